//! The minimap picture on Civ6 Huge (128x80, climate and rivers) at the plugin's default size
//! (280x200): building it (once a map), a full paint, and the repaint of one tile and of a
//! hundred tiles (a turn's writes), in one run so the ratios compare like with like.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use hex_terrain::minimap::{Minimap, MinimapStyle, TileLook};
use hex_terrain::save::FogState;
use hex_terrain::{MapConfig, Terrain};

fn huge() -> Terrain {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/maps/civ6/huge.map.ron");
    Terrain::new(MapConfig::load(path).expect("the Huge preset")).expect("a valid config")
}

fn minimap(c: &mut Criterion) {
    let terrain = huge();
    let bounds = terrain.bounds().expect("a bounded map");
    let picture = Minimap::new(&terrain, bounds, [280, 200], MinimapStyle::default()).expect("a picture");
    let tiles: Vec<_> = terrain.tiles().collect();
    // Half the map explored, a tenth owned: borders and fog everywhere.
    let look = |t: hex_terrain::hexx::Hex| {
        let k = (t.x * 7 + t.y * 13).rem_euclid(20);
        TileLook {
            fog: if k < 10 {
                FogState::Visible
            } else if k < 15 {
                FogState::Explored
            } else {
                FogState::Unexplored
            },
            owner: (k < 2).then_some(t.x.rem_euclid(4) as u32),
        }
    };
    let mut rgba = picture.paint(look);
    let mut group = c.benchmark_group("minimap, Civ6 Huge, 280x200");
    group.sample_size(10);
    group.bench_function("build the picture", |b| {
        b.iter(|| Minimap::new(&terrain, bounds, [280, 200], MinimapStyle::default()).map(|m| m.size()));
    });
    group.bench_function("full paint", |b| b.iter(|| picture.paint(look).len()));
    group.bench_function("repaint 1 tile", |b| b.iter(|| picture.repaint([black_box(tiles[4321])], look, &mut rgba)));
    group.bench_function("repaint 100 tiles", |b| {
        b.iter(|| picture.repaint(tiles.iter().step_by(101).take(100).copied(), look, &mut rgba));
    });
    group.finish();
}

criterion_group!(benches, minimap);
criterion_main!(benches);
