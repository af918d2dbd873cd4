//! Editing a globe, checked by computations written here: a stroke moves every point of an
//! edited tile by the tile's shift and every shared point by the mean of its tiles' shifts (the
//! tiles holding a point found from one-tile chunks' meshes); after random strokes the edited
//! globe is what its map file gives, every inner vertex stays in its type's range, the reported
//! change holds every tile and chunk that changed (both compared in full), undoing everything
//! gives back the generated globe bit for bit; bad strokes, edits and saves are refused by name.

use std::collections::{HashMap, HashSet};

use hex_terrain::save::SavedTile;
use hex_terrain::{
    Biome, Brush, EditError, GlobeEditor, GlobeMesh, GlobePoint, GlobeStroke, GlobeTerrain, GlobeTile, Landform,
    ManipulationConfig, MapConfig, MapSize, MapType, MapTypeConfig, SaveError, TileEdit, TileKind, TileStateSave, Tool,
};

fn config(frequency: u32, inner_rings: u32, seed: u32, chunk: u32) -> MapConfig {
    let mut config =
        MapConfig { seed, size: MapSize::Globe { frequency }, chunk_size: (chunk, chunk), ..Default::default() };
    config.terrain.inner_rings = inner_rings;
    config.terrain.max_elevation = 1.0;
    config.terrain.sea_threshold = 0.45;
    config.terrain.mountain_threshold = 0.58;
    config
}

/// Every point's height in a mesh, by point.
fn heights(mesh: &GlobeMesh) -> HashMap<GlobePoint, f32> {
    mesh.points.iter().zip(&mesh.heights).map(|(&p, &h)| (p, h)).collect()
}

/// A vertex as comparable bits: point, height, normal, kind, color.
type VertexBits = (u64, u32, [u32; 3], u32, Option<[u8; 4]>);

/// A mesh's vertices as comparable bits, by point.
fn bits(mesh: &GlobeMesh) -> Vec<VertexBits> {
    let b = &mesh.buffers;
    let mut out: Vec<_> = (0..mesh.points.len())
        .map(|v| {
            (
                mesh.points[v].0,
                mesh.heights[v].to_bits(),
                b.normals[v].map(f32::to_bits),
                b.tile_kinds[v],
                b.colors.get(v).copied(),
            )
        })
        .collect();
    out.sort_unstable_by_key(|v| v.0);
    out
}

/// The raw heights a tile of kind `kind` keeps its inner points in, from the thresholds (the
/// largest height below an open end).
fn range(kind: TileKind, sea: f32, mountain: f32) -> (f32, f32) {
    match kind {
        TileKind::Sea => (0.0, sea.next_down()),
        TileKind::Land => (sea, mountain.next_down()),
        TileKind::Mountain => (mountain, 1.0),
    }
}

#[test]
fn a_stroke_moves_each_point_by_the_mean_of_its_tiles_shifts() {
    // Raw heights (no manipulation), one tile a chunk: a one-tile chunk's mesh is the tile's
    // points, so the tiles holding a point are the chunks whose meshes hold it.
    let mut base = config(5, 2, 7, 1);
    base.manipulation = ManipulationConfig::raw();
    let mut editor = GlobeEditor::new(base).unwrap();
    let before = editor.globe().clone();
    let mut holders: HashMap<GlobePoint, Vec<GlobeTile>> = HashMap::new();
    for tile in before.grid().tiles() {
        let mesh = before.generate(before.chunk_of(tile).unwrap());
        assert_eq!(before.chunk_tiles(before.chunk_of(tile).unwrap()), vec![tile]);
        for &p in &mesh.points {
            holders.entry(p).or_default().push(tile);
        }
    }
    // A land tile no other stroke reaches.
    let grid = before.grid();
    let apart = |t: GlobeTile| [0, 40, 200].iter().all(|&o| grid.distance(t, GlobeTile(o)).unwrap() > 2);
    let land = grid.tiles().find(|&t| before.tile_kind(t) == Some(TileKind::Land) && apart(t)).unwrap();
    let strokes = [
        GlobeStroke { tool: Tool::SetHeight(0.9), brush: Brush::Range(0), tile: GlobeTile(0) },
        GlobeStroke { tool: Tool::Raise(0.08), brush: Brush::Range(1), tile: GlobeTile(40) },
        GlobeStroke { tool: Tool::SetKind(TileKind::Sea), brush: Brush::Range(0), tile: land },
        GlobeStroke { tool: Tool::Lower(0.3), brush: Brush::Range(2), tile: GlobeTile(200) },
    ];
    for stroke in strokes {
        editor.apply(stroke).unwrap();
    }
    let after = editor.globe();
    let t = before.thresholds();
    // The pentagon at the north pole is a mountain at 0.9; the land tile is sea now.
    assert_eq!(after.tile_height(GlobeTile(0)), Some(0.9));
    assert_eq!(after.tile_kind(GlobeTile(0)), Some(TileKind::Mountain));
    assert_eq!(after.tile_kind(land), Some(TileKind::Sea));
    let edited: HashSet<GlobeTile> = editor.edits().iter().map(|e| GlobeTile::from_at(e.at).unwrap()).collect();
    assert!(edited.len() > 20, "{} tiles edited", edited.len());
    let shift = |tile: GlobeTile| {
        if edited.contains(&tile) { after.tile_height(tile).unwrap() - before.tile_height(tile).unwrap() } else { 0.0 }
    };
    for tile in before.grid().tiles().filter(|t| !edited.contains(t)) {
        assert_eq!(before.tile_height(tile).map(f32::to_bits), after.tile_height(tile).map(f32::to_bits));
    }
    let (old, new) = (heights(&before.generate_whole()), heights(&after.generate_whole()));
    let mut shared_moved = 0;
    for (p, tiles) in &holders {
        let expected = match tiles.as_slice() {
            [tile] if edited.contains(tile) => {
                let (lo, hi) = range(after.tile_kind(*tile).unwrap(), t.sea, t.mountain);
                (old[p] + shift(*tile)).clamp(lo, hi)
            }
            [_] => old[p],
            _ => {
                let moved = tiles.iter().map(|&t| shift(t)).sum::<f32>() / tiles.len() as f32;
                if moved != 0.0 {
                    shared_moved += 1;
                }
                (old[p] + moved).clamp(0.0, 1.0)
            }
        };
        assert!((new[p] - expected).abs() <= 2e-6, "{p:?} held by {tiles:?}: {} for {expected}", new[p]);
    }
    assert!(shared_moved > 50, "{shared_moved} shared points moved");
}

/// A small random number generator of the test's own (`SplitMix64`).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

fn random_stroke(rng: &mut Rng, tiles: u32) -> GlobeStroke {
    let tool = match rng.below(8) {
        0 => Tool::Raise(rng.unit() * 0.2),
        1 => Tool::Lower(rng.unit() * 0.2),
        2 => Tool::SetHeight(rng.unit()),
        3 => Tool::Smooth,
        4 => Tool::SetKind([TileKind::Sea, TileKind::Land, TileKind::Mountain][rng.below(3) as usize]),
        5 => Tool::SetBiome(Biome::ALL[rng.below(Biome::ALL.len() as u64) as usize]),
        6 => Tool::Erase,
        _ => Tool::Raise(0.05),
    };
    let brush = match rng.below(6) {
        0 => Brush::Flood,
        1 => Brush::FloodTerrain,
        r => Brush::Range(r as u32 - 2),
    };
    // A pentagon one stroke in four.
    let tile = if rng.below(4) == 0 { GlobeTile(0) } else { GlobeTile(rng.below(u64::from(tiles)) as u32) };
    GlobeStroke { tool, brush, tile }
}

#[test]
fn random_strokes_keep_the_globe_its_map_file_and_undo_gives_back_the_generated_one() {
    let cases = [(4, 1, None, false), (6, 2, Some(MapType::Continents), true), (7, 1, Some(MapType::Pangaea), true)];
    for (case, (f, rings, kind, climate)) in cases.into_iter().enumerate() {
        let mut base = config(f, rings, 30 + case as u32, 3);
        base.map_type = kind.map(|kind| MapTypeConfig { kind, ..Default::default() });
        base.climate.enabled = climate;
        let mut editor = GlobeEditor::new(base.clone()).unwrap();
        let generated = editor.globe().clone();
        let generated_bits = bits(&generated.generate_whole());
        let mut rng = Rng(case as u64);
        let mut applied = 0;
        for _ in 0..10 {
            let stroke = random_stroke(&mut rng, generated.grid().tile_count());
            let old = editor.globe().clone();
            let change = editor.apply(stroke).unwrap();
            if change.is_empty() {
                continue;
            }
            applied += 1;
            let new = editor.globe();
            // Every tile whose data changed, and every chunk whose mesh changed, is reported.
            for tile in new.grid().tiles() {
                let same = old.tile_height(tile).map(f32::to_bits) == new.tile_height(tile).map(f32::to_bits)
                    && old.tile_kind(tile) == new.tile_kind(tile)
                    && old.tile_info(tile).map(|i| i.terrain) == new.tile_info(tile).map(|i| i.terrain)
                    && old.tile_climate(tile) == new.tile_climate(tile);
                assert!(same || change.tiles.contains(&tile), "case {case}: {tile:?} changed, not reported");
            }
            for chunk in new.chunks() {
                let moved = bits(&old.generate(chunk)) != bits(&new.generate(chunk));
                assert!(!moved || change.chunks.contains(&chunk), "case {case}: {chunk:?} changed, not reported");
            }
            assert!(change.edited.iter().all(|t| change.tiles.contains(t)));
            // Every inner vertex stays in its type's range.
            let mesh = new.generate_whole();
            for (v, &h) in mesh.heights.iter().enumerate() {
                if mesh.buffers.center_distances[v] < 1.0 {
                    let kind = [TileKind::Sea, TileKind::Land, TileKind::Mountain][mesh.buffers.tile_kinds[v] as usize];
                    let (lo, hi) = new.thresholds().range(kind);
                    assert!((lo..=hi).contains(&h), "case {case}: {kind:?} vertex at {h}");
                }
            }
            // The map file of the edited globe is the edited globe.
            let text = editor.config().to_ron();
            let reloaded = GlobeTerrain::new(MapConfig::from_ron(&text).unwrap()).unwrap();
            assert_eq!(bits(&reloaded.generate_whole()), bits(&mesh), "case {case}: the map file differs");
            for tile in new.grid().tiles() {
                assert_eq!(reloaded.tile_info(tile), new.tile_info(tile));
            }
        }
        assert!(applied >= 5, "case {case}: {applied} strokes changed the globe");
        let edited_bits = bits(&editor.globe().generate_whole());
        while editor.undo().is_some() {}
        assert!(editor.edits().is_empty());
        assert_eq!(bits(&editor.globe().generate_whole()), generated_bits, "case {case}: undo");
        while editor.redo().is_some() {}
        assert_eq!(bits(&editor.globe().generate_whole()), edited_bits, "case {case}: redo");
    }
}

#[test]
fn bad_globe_strokes_edits_and_saves_are_refused_by_name() {
    let base = config(4, 1, 3, 2);
    let mut editor = GlobeEditor::new(base.clone()).unwrap();
    let tiles = editor.globe().grid().tile_count();
    let stroke = |tool, tile| GlobeStroke { tool, brush: Brush::Range(1), tile: GlobeTile(tile) };
    assert!(matches!(editor.apply(stroke(Tool::AddRiver, 3)), Err(EditError::Unsupported { tool: "AddRiver", .. })));
    assert!(matches!(editor.apply(stroke(Tool::FillLake, 3)), Err(EditError::Unsupported { .. })));
    assert_eq!(editor.apply(stroke(Tool::Raise(0.1), tiles)), Err(EditError::OffGlobe { tile: tiles, tiles }));
    assert!(matches!(editor.apply(stroke(Tool::Raise(f32::NAN), 3)), Err(EditError::Amount { .. })));
    let far = GlobeStroke { tool: Tool::Smooth, brush: Brush::Range(17), tile: GlobeTile(3) };
    assert_eq!(editor.apply(far), Err(EditError::Range { radius: 17 }));
    assert_eq!(editor.undo_len(), 0, "nothing was applied");
    // Props by hand are a stroke like any other on a globe: the tiles' edits hold the density.
    let change = editor.apply(stroke(Tool::SetProps(hex_terrain::PropDensity::Dense), 3)).unwrap();
    assert_eq!(change.edited.len(), editor.brush_tiles(Brush::Range(1), GlobeTile(3)).len());
    assert!(editor.edits().iter().all(|e| e.props == Some(hex_terrain::PropDensity::Dense)));
    editor.undo().unwrap();

    let refused = |edit: TileEdit, field: &str| {
        let e = GlobeTerrain::new(MapConfig { edits: vec![edit], ..base.clone() }).unwrap_err();
        assert_eq!(e.field, field, "{e}");
    };
    refused(TileEdit { height: Some(0.5), ..TileEdit::at((tiles as i32, 0)) }, "edits[0].at");
    refused(TileEdit { height: Some(0.5), ..TileEdit::at((3, 1)) }, "edits[0].at");
    refused(TileEdit { height: Some(1.5), ..TileEdit::at((3, 0)) }, "edits[0].height");
    refused(TileEdit { river: Some(hex_terrain::RiverEdit::Source), ..TileEdit::at((3, 0)) }, "edits[0].river");
    assert!(GlobeTerrain::new(MapConfig { edits: vec![TileEdit::at((tiles as i32 - 1, 0))], ..base.clone() }).is_ok());

    // A tile state save names a globe's tiles (id, 0).
    let tile =
        |at| SavedTile { at, fog: hex_terrain::FogState::Visible, owner: Some(1), overlay: None, highlights: vec![] };
    let save = |tiles: Vec<SavedTile>| TileStateSave {
        version: hex_terrain::SAVE_VERSION,
        map: hex_terrain::save::SavedMap::of(&base),
        tiles,
    };
    let good = save(vec![tile((0, 0)), tile((tiles as i32 - 1, 0))]);
    good.check(&base).unwrap();
    assert_eq!(TileStateSave::from_bytes(&good.to_bytes()).unwrap(), good);
    for at in [(tiles as i32, 0), (3, 1), (-1, 0)] {
        assert!(matches!(save(vec![tile(at)]).check(&base), Err(SaveError::Tile { .. })), "{at:?}");
    }
    // A save of another globe (another frequency) is refused by `size`.
    let other = MapConfig { size: MapSize::Globe { frequency: 5 }, ..base.clone() };
    assert!(matches!(good.check(&other), Err(SaveError::OtherMap { field: "size", .. })));
}

/// A globe's land tiles go on hills and off as a flat map's do: the landform asked, by the
/// center's height against the hills line (computed here), the type kept; a globe without a
/// hills line refuses the tool by name.
#[test]
fn globe_tiles_go_on_hills_and_off() {
    let mut config = config(8, 2, 4, 4);
    config.climate.enabled = true;
    config.climate.hills = 0.5;
    let globe = GlobeTerrain::new(config.clone()).unwrap();
    let t = globe.thresholds();
    let line = t.sea + 0.5 * (t.mountain - t.sea);
    let land: Vec<GlobeTile> = globe.grid().tiles().filter(|&g| globe.tile_kind(g) == Some(TileKind::Land)).collect();
    assert!(land.len() > 20);
    let mut editor = GlobeEditor::new(config.clone()).unwrap();
    for on in [true, false] {
        for &tile in land.iter().step_by(7) {
            editor.apply(GlobeStroke { tool: Tool::SetHills(on), brush: Brush::Range(0), tile }).unwrap();
            let info = editor.globe().tile_info(tile).unwrap();
            assert_eq!(info.kind, TileKind::Land, "{tile:?}");
            assert_eq!(editor.globe().tile_height(tile).unwrap() >= line, on, "{tile:?}");
            assert_eq!(info.terrain.landform, if on { Landform::Hills } else { Landform::Flat }, "{tile:?}");
        }
    }
    config.climate.hills = 1.0;
    let mut editor = GlobeEditor::new(config).unwrap();
    let e =
        editor.apply(GlobeStroke { tool: Tool::SetHills(true), brush: Brush::Range(0), tile: land[0] }).unwrap_err();
    assert!(matches!(e, EditError::Unsupported { tool: "SetHills", .. }), "{e}");
}
