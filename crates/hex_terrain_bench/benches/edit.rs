//! The world builder on Civ6 Huge (106x66, climate and rivers): one radius-3 stroke, by part
//! (compiling the edited map with its rivers, lakes and biomes; finding what changed; building
//! the reported chunks' meshes, one after the other and on all cores), the median of strokes on
//! land all over the map; then undo of the last of 1,000 operations beside applying one.
//!
//! `cargo bench -p hex_terrain_bench --bench edit`

use std::time::Instant;

use hex_terrain::{Brush, Editor, MapConfig, Stroke, TileKind, Tool};
use hex_terrain_bench::{median, ms};
use rayon::prelude::*;

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    let config = MapConfig::load(path).expect("the Huge preset");
    let mut editor = Editor::new(config.clone()).expect("a valid config");
    // Land tiles spread over the map, every 7th column and 5th row.
    let land: Vec<_> = editor
        .terrain()
        .tiles()
        .filter(|&t| {
            let [c, r] = editor.terrain().offset_of(t);
            c % 7 == 3 && r % 5 == 2 && editor.terrain().tile_kind(t) == Some(TileKind::Land)
        })
        .take(21)
        .collect();
    let (mut compile, mut compare, mut serial, mut parallel, mut whole) = (vec![], vec![], vec![], vec![], vec![]);
    let (mut chunks, mut tiles) = (vec![], vec![]);
    for (i, &tile) in land.iter().enumerate() {
        let tool = if i % 2 == 0 { Tool::Raise(0.08) } else { Tool::Lower(0.08) };
        let start = Instant::now();
        let change = editor.apply(Stroke { tool, brush: Brush::Range(3), tile }).expect("a stroke on land");
        let applied = start.elapsed();
        let t = editor.terrain();
        let s = Instant::now();
        for &c in &change.chunks {
            std::hint::black_box(t.generate_chunk(c));
        }
        serial.push(s.elapsed());
        let p = Instant::now();
        change.chunks.par_iter().for_each(|&c| {
            std::hint::black_box(t.generate_chunk(c));
        });
        parallel.push(p.elapsed());
        let timings = editor.last_timings();
        compile.push(timings.compile);
        compare.push(timings.compare);
        whole.push(applied + *parallel.last().unwrap());
        chunks.push(change.chunks.len());
        tiles.push(change.tiles.len());
    }
    chunks.sort_unstable();
    tiles.sort_unstable();
    let all_chunks = editor.terrain().chunks().len();
    println!("one radius-3 stroke on {} (106x66, climate and rivers): median of {} strokes", config.name, land.len());
    println!("  compile the edited map (edits, rivers, lakes, biomes)   {}", ms(median(compile)));
    println!("  find the changed tiles and chunks                        {}", ms(median(compare)));
    println!("  build the reported chunks, one after the other           {}", ms(median(serial)));
    println!("  build the reported chunks, on all cores                  {}", ms(median(parallel)));
    println!("  the whole operation (apply + chunks on all cores)        {}", ms(median(whole)));
    println!(
        "  chunks rebuilt: median {} of {all_chunks} (min {}, max {}); tiles changed: median {}",
        chunks[chunks.len() / 2],
        chunks[0],
        chunks[chunks.len() - 1],
        tiles[tiles.len() / 2]
    );

    // Undo of the last of 1,000 operations beside applying one (small strokes, radius 0).
    let mut editor = Editor::new(config).expect("a valid config");
    let tile = land[0];
    let mut apply = Vec::new();
    for i in 0..1000 {
        let s = Instant::now();
        let amount = 0.001 * f32::from(u16::try_from(i % 50).unwrap_or(0));
        editor.apply(Stroke { tool: Tool::SetHeight(0.4 + amount), brush: Brush::Range(0), tile }).ok();
        apply.push(s.elapsed());
    }
    let ops = editor.undo_len();
    let s = Instant::now();
    editor.undo();
    let undo = s.elapsed();
    println!("after {ops} operations: apply one (median) {}, undo the last {}", ms(median(apply)), ms(undo));
}
