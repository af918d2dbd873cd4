//! The world builder's core over random maps and random strokes: edited tiles are recognisable
//! (every inner vertex in its type's range), chunks still meet bit for bit and equal the whole,
//! undoing everything gives back the generated map bit for bit and redoing it the edited one, a
//! saved map file replays to the same bytes, only the reported chunks change, and rivers on an
//! edited map still flow down to the sea, a lake or the edge. Rivers added and removed, lakes dug
//! and drained and props set by hand do what they say. Bad edits are refused by name.

mod common;

use std::collections::{HashMap, HashSet};

use hex_terrain::hexx::Hex;
use hex_terrain::{
    Biome, Brush, ChunkCoord, EditError, Editor, GenerateOptions, MapConfig, MapSize, NoiseConfig, Orientation,
    PropDensity, PropKind, ReliefConfig, RiverEdit, Stroke, Terrain, TileEdit, TileKind, TileRect, Tool,
};
use proptest::prelude::*;
#[path = "common/biome.rs"]
mod biome;

prop_compose! {
    /// Small maps (bounded, wrapping or unbounded), with and without climate, rivers and relief.
    fn map()(
        seed in any::<u32>(),
        bounded in prop::option::weighted(0.8, (6u32..18, 6u32..14)),
        scale in 8.0f64..60.0,
        octaves in 1u32..6,
        sea in 0.2f32..0.45,
        rings in 1u32..4,
        chunk in (2u32..7, 2u32..7),
        pointy in any::<bool>(),
        climate in any::<bool>(),
        rivers in any::<bool>(),
        relief in any::<bool>(),
        unity in any::<bool>(),
        wrap in any::<bool>(),
        winds in any::<bool>(),
        on_edges in any::<bool>(),
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: bounded.map_or(MapSize::Unbounded, |(x, z)| MapSize::Bounded { x, z }),
            noise: NoiseConfig { octaves, persistence: 0.5, lacunarity: 2.0, scale },
            chunk_size: chunk,
            ..MapConfig::default()
        };
        c.terrain.sea_threshold = sea;
        c.terrain.inner_rings = rings;
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        c.climate.enabled = climate;
        if climate && winds && bounded.is_some() {
            c.climate.winds = Some(hex_terrain::WindConfig::default());
        }
        c.rivers.enabled = rivers && bounded.is_some();
        c.rivers.threshold = 3.0;
        if on_edges {
            c.rivers.model = hex_terrain::RiverModel::Edges;
        }
        c.manipulation.hex_unity = unity;
        if relief {
            c.relief = ReliefConfig::MOUNTAINS;
        }
        common::wrapping(c, wrap)
    }
}

/// A random stroke around a tile near the map's middle, in offset coordinates `0..12`.
fn stroke() -> impl Strategy<Value = ((i32, i32), Tool, Brush)> {
    let tool = prop_oneof![
        (0.01f32..0.5).prop_map(Tool::Raise),
        (0.01f32..0.5).prop_map(Tool::Lower),
        (0.0f32..=1.0).prop_map(Tool::SetHeight),
        Just(Tool::Smooth),
        prop_oneof![Just(TileKind::Sea), Just(TileKind::Land), Just(TileKind::Mountain)].prop_map(Tool::SetKind),
        prop_oneof![Just(Biome::Desert), Just(Biome::Tundra), Just(Biome::Forest)].prop_map(Tool::SetBiome),
        Just(Tool::AddRiver),
        Just(Tool::RemoveRiver),
        Just(Tool::FillLake),
        Just(Tool::DrainLake),
        prop_oneof![Just(PropDensity::None), Just(PropDensity::Sparse), Just(PropDensity::Dense)]
            .prop_map(Tool::SetProps),
        Just(Tool::Erase),
    ];
    let brush =
        prop_oneof![4 => (0u32..4).prop_map(Brush::Range), 1 => Just(Brush::Flood), 1 => Just(Brush::FloodTerrain)];
    ((0i32..12, 0i32..12), tool, brush)
}

/// The tiles a test generates: the bounded map, or nine chunks around the origin.
fn area(t: &Terrain) -> TileRect {
    t.bounds().unwrap_or_else(|| {
        let (w, h) = t.chunk_size();
        TileRect::new([-(w as i32), -(h as i32)], [3 * w, 3 * h])
    })
}

/// The chunks covering `rect`.
fn chunks_of(t: &Terrain, rect: TileRect) -> Vec<ChunkCoord> {
    let mut out: Vec<ChunkCoord> = rect.iter().filter_map(|oc| t.chunk_of(t.tile_from_offset(oc))).collect();
    out.sort_unstable_by_key(|c| (c.z, c.x));
    out.dedup();
    out
}

/// Every byte a chunk's mesh holds that a renderer draws.
fn chunk_bytes(t: &Terrain, c: ChunkCoord) -> Vec<u32> {
    let Some(m) = t.generate_chunk(c) else { return Vec::new() };
    let b = &m.buffers;
    let mut out: Vec<u32> =
        b.positions.iter().flatten().chain(b.normals.iter().flatten()).map(|v| v.to_bits()).collect();
    out.extend(b.colors.iter().map(|c| u32::from_le_bytes(*c)));
    out.extend(b.tile_kinds.iter().copied());
    out.extend(&b.indices);
    out
}

/// The whole area's bytes, chunk by chunk.
fn map_bytes(t: &Terrain) -> Vec<Vec<u32>> {
    chunks_of(t, area(t)).into_iter().map(|c| chunk_bytes(t, c)).collect()
}

/// Applies the strokes that apply (those on the map), returning how many did.
fn apply_all(editor: &mut Editor, strokes: &[((i32, i32), Tool, Brush)]) -> usize {
    let mut applied = 0;
    for &((col, row), tool, brush) in strokes {
        let tile = editor.terrain().tile_from_offset([col, row]);
        match editor.apply(Stroke { tool, brush, tile }) {
            Ok(change) if !change.is_empty() => applied += 1,
            // Water tools on a map without rivers, or a lake dug too close to the sea.
            Ok(_) | Err(EditError::OffMap(_) | EditError::Unsupported { .. } | EditError::NoLake { .. }) => {}
            Err(e) => panic!("a stroke on the map failed: {e}"),
        }
    }
    applied
}

/// Rivers on edges run down (their level never rises) without coming back to an edge, and end
/// at a corner beside the sea, a lake or the map's edge.
fn assert_edge_rivers_flow_down(t: &Terrain) -> Result<(), TestCaseError> {
    let edges: usize = t.tiles().map(|h| t.river_edges(h).len()).sum();
    for tile in t.tiles() {
        for r in t.river_edges(tile) {
            let course = t.river_course(r.edge);
            prop_assert!(!course.is_empty() && course.len() <= edges, "a course of {} edges", course.len());
            let mut level = f32::INFINITY;
            let mut mouth = None;
            for edge in course {
                let origin = t.wrap_tile(edge.origin).unwrap();
                let here = t.river_edges(origin).into_iter().find(|e| e.edge.direction == edge.direction);
                prop_assert!(here.is_some(), "{:?} on a course carries no river", edge);
                let here = here.unwrap();
                prop_assert!(here.level <= level, "a river rises at {:?}", edge);
                level = here.level;
                mouth = Some(here.downstream);
            }
            let ends = mouth.unwrap().coordinates().into_iter().any(|c| {
                t.wrap_tile(c)
                    .filter(|&c| t.contains(c))
                    .is_none_or(|c| t.tile_kind(c) == Some(TileKind::Sea) || t.lake(c).is_some())
            });
            prop_assert!(ends, "a river on edges ends inland at {:?}", mouth);
        }
    }
    Ok(())
}

/// Rivers flow to tiles whose water level is not higher and end in the sea, a lake or off the
/// map's edge, without coming back to a tile.
fn assert_rivers_flow_down(t: &Terrain) -> Result<(), TestCaseError> {
    let tiles = t.tiles().count();
    for r in t.rivers() {
        let mut seen = HashSet::new();
        let mut here = r.clone();
        loop {
            prop_assert!(seen.insert(here.hex) && seen.len() <= tiles, "a river comes back to {:?}", here.hex);
            let Some(next) = here.downstream else {
                let edge = here.hex.all_neighbors().iter().any(|&n| !t.contains(n));
                prop_assert!(edge, "{:?} ends inland without an outlet", here.hex);
                break;
            };
            prop_assert!(t.water_level(next).unwrap() <= here.level, "{:?} flows up to {:?}", here.hex, next);
            if t.tile_kind(next).unwrap() == TileKind::Sea || t.lake(next).is_some() {
                break;
            }
            let down = t.river(next);
            prop_assert!(down.is_some(), "{:?} flows into {:?}, neither river, lake nor sea", here.hex, next);
            here = down.unwrap();
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Every inner vertex of an edited tile lies in its type's range (whatever the manipulation
    /// settings), chunks share their border vertices bit for bit and equal the whole map, and
    /// rivers still flow down.
    #[test]
    fn edited_maps_keep_every_invariant(config in map(), strokes in prop::collection::vec(stroke(), 1..5)) {
        let mut editor = Editor::new(config).unwrap();
        apply_all(&mut editor, &strokes);
        let t = editor.terrain();
        let rect = area(t);
        let whole = t.generate(rect, GenerateOptions::DIAGNOSTICS);
        let d = whole.diagnostics.as_ref().unwrap();
        let n = t.lattice().subdivisions();
        let max = t.config().terrain.max_elevation;
        let eps = 1e-4 * max.max(1.0);
        // Tiles whose height or type is edited (a biome alone moves no height: such a tile has
        // the generated heights, whose invariants are `invariants.rs`'s).
        let edited: HashSet<Hex> = editor
            .edits()
            .iter()
            .filter(|e| e.height.is_some() || e.kind.is_some())
            .filter_map(|e| t.wrap_tile(t.tile_from_offset([e.at.0, e.at.1])))
            .collect();
        let kinds: HashMap<Hex, TileKind> = whole.tiles.iter().map(|i| (i.hex, i.kind)).collect();
        let mut heights: HashMap<Hex, u32> = HashMap::new();
        for (i, &p) in d.lattice.iter().enumerate() {
            let y = whole.buffers.positions[i][1];
            heights.insert(p, y.to_bits());
            let set = t.lattice().tiles_at(p);
            let [tile] = set.tiles() else { continue };
            if u32::from(d.rings[i]) < n && t.wrap_tile(*tile).is_some_and(|own| edited.contains(&own)) {
                let kind = kinds[tile];
                let (lo, hi) = t.thresholds().range(kind);
                prop_assert!(y >= lo * max - eps && y <= hi * max + eps,
                    "inner vertex {:?} of an edited {:?} tile at {} outside [{}, {}]", p, kind, y, lo * max, hi * max);
            }
        }
        // On a wrapping map the last and first columns meet bit for bit: every vertex that is
        // also in the map one period east has the same height and normal there.
        if let Some(wrap) = t.wrap() {
            let index: HashMap<Hex, usize> = d.lattice.iter().enumerate().map(|(i, &p)| (p, i)).collect();
            let b = &whole.buffers;
            for (i, &p) in d.lattice.iter().enumerate() {
                if let Some(&j) = index.get(&(p + wrap.lattice_shift)) {
                    prop_assert_eq!(b.positions[i][1].to_bits(), b.positions[j][1].to_bits(),
                        "seam vertex {:?} and its copy {:?}", p, p + wrap.lattice_shift);
                    prop_assert_eq!(b.normals[i].map(f32::to_bits), b.normals[j].map(f32::to_bits),
                        "seam normal {:?}", p);
                }
            }
        }
        // Every tile of the whole map's mesh is the tile `tile_info` describes (its biome set
        // by hand too, with or without climate).
        for info in &whole.tiles {
            prop_assert_eq!(Some(*info), t.tile_info(info.hex), "tile {:?}", info.hex);
        }
        // Chunked = whole, so neighbors meet bit for bit.
        for c in chunks_of(t, rect) {
            let Some(rect) = t.chunk_rect(c) else { continue };
            let m = t.generate(rect, GenerateOptions::DIAGNOSTICS);
            for (i, p) in m.diagnostics.as_ref().unwrap().lattice.iter().enumerate() {
                if let Some(&bits) = heights.get(p) {
                    prop_assert_eq!(m.buffers.positions[i][1].to_bits(), bits, "chunk {:?} at {:?}", c, p);
                }
            }
        }
        assert_rivers_flow_down(t)?;
        assert_edge_rivers_flow_down(t)?;
    }

    /// Undoing every operation gives back the generated map bit for bit; redoing every one the
    /// edited map; the saved map file (the seed's config plus the edits) replays to the same
    /// bytes.
    #[test]
    fn undo_redo_and_replay_are_bit_exact(config in map(), strokes in prop::collection::vec(stroke(), 1..6)) {
        let generated = map_bytes(&Terrain::new(config.clone()).unwrap());
        let mut editor = Editor::new(config).unwrap();
        let applied = apply_all(&mut editor, &strokes);
        prop_assert_eq!(editor.undo_len(), applied);
        let edited = map_bytes(editor.terrain());
        let file = editor.config().to_ron();
        let replayed = Terrain::new(MapConfig::from_ron(&file).unwrap()).unwrap();
        prop_assert!(map_bytes(&replayed) == edited, "the saved file does not replay to the edited map");
        while editor.undo().is_some() {}
        prop_assert!(editor.edits().is_empty());
        prop_assert!(map_bytes(editor.terrain()) == generated, "undoing everything is not the generated map");
        prop_assert_eq!(editor.redo_len(), applied);
        while editor.redo().is_some() {}
        prop_assert!(map_bytes(editor.terrain()) == edited, "redoing everything is not the edited map");
    }

    /// An operation changes the meshes of the chunks it reports and of no other.
    #[test]
    fn only_the_reported_chunks_change(config in map(), strokes in prop::collection::vec(stroke(), 1..4)) {
        let mut editor = Editor::new(config).unwrap();
        for &((col, row), tool, brush) in &strokes {
            let before = editor.terrain().clone();
            let tile = before.tile_from_offset([col, row]);
            let Ok(change) = editor.apply(Stroke { tool, brush, tile }) else { continue };
            let after = editor.terrain();
            let reported: HashSet<ChunkCoord> = change.chunks.iter().copied().collect();
            for c in chunks_of(after, area(after)) {
                if !reported.contains(&after.wrap_chunk(c).0) {
                    prop_assert!(chunk_bytes(&before, c) == chunk_bytes(after, c),
                        "chunk {:?} changed but was not reported ({:?})", c, change.chunks);
                }
            }
        }
    }
}

fn bounded(edits: Vec<TileEdit>) -> MapConfig {
    MapConfig { size: MapSize::Bounded { x: 20, z: 10 }, edits, ..MapConfig::default() }
}

#[test]
fn a_kind_edit_makes_the_tile_that_kind_and_its_neighbors_keep_theirs() {
    let base = Terrain::new(bounded(Vec::new())).unwrap();
    for kind in [TileKind::Sea, TileKind::Land, TileKind::Mountain] {
        let t = Terrain::new(bounded(vec![TileEdit { kind: Some(kind), ..TileEdit::at((7, 4)) }])).unwrap();
        let tile = t.tile_from_offset([7, 4]);
        assert_eq!(t.tile_kind(tile), Some(kind));
        for n in tile.all_neighbors() {
            // Neighbors' centers are their own (a neighbor changes only where it meets the tile).
            assert_eq!(t.tile_kind(n), base.tile_kind(n), "neighbor {n:?} of a new {kind:?}");
        }
    }
}

/// A biome set by hand shows in the tile's info and its chunk's colors, stays when the tile is
/// raised, and goes when erased; it moves no height.
#[test]
fn a_biome_set_by_hand_stays_until_erased() {
    let mut config = bounded(Vec::new());
    config.climate.enabled = true;
    let mut editor = Editor::new(config).unwrap();
    let t = editor.terrain().clone();
    let tile = t.tiles().find(|&x| t.tile_info(x).unwrap().kind == TileKind::Land).unwrap();
    let generated = t.tile_info(tile).unwrap();
    let biome = if biome::of(&t, &generated) == Biome::Desert { Biome::Tundra } else { Biome::Desert };
    let change = editor.apply(Stroke { tool: Tool::SetBiome(biome), brush: Brush::Range(0), tile }).unwrap();
    let info = editor.terrain().tile_info(tile).unwrap();
    assert_eq!((biome::of(editor.terrain(), &info), info.elevation), (biome, generated.elevation));
    let chunk = t.chunk_of(tile).unwrap();
    assert!(change.chunks.contains(&chunk));
    assert_eq!(change.edited, vec![tile]);
    let colors = |t: &Terrain| t.generate_chunk(chunk).unwrap().buffers.colors;
    assert_ne!(colors(&t), colors(editor.terrain()));
    editor.apply(Stroke { tool: Tool::Raise(0.05), brush: Brush::Range(0), tile }).unwrap();
    assert_eq!(biome::at(editor.terrain(), tile), Some(biome));
    editor.apply(Stroke { tool: Tool::Erase, brush: Brush::Range(0), tile }).unwrap();
    assert_eq!(editor.terrain().tile_info(tile).unwrap(), generated);
}

#[test]
fn setting_a_tiles_own_type_changes_nothing() {
    let mut editor = Editor::new(bounded(Vec::new())).unwrap();
    let terrain = editor.terrain().clone();
    let tiles: Vec<Hex> =
        (0..16).flat_map(|x| (0..12).map(move |z| [x, z])).map(|o| terrain.tile_from_offset(o)).collect();
    for kind in [TileKind::Sea, TileKind::Land, TileKind::Mountain] {
        // A tile of that type: the stroke has nothing to set.
        if let Some(&own) = tiles.iter().find(|&&t| editor.terrain().tile_kind(t) == Some(kind)) {
            let change = editor.apply(Stroke { tool: Tool::SetKind(kind), brush: Brush::Range(0), tile: own }).unwrap();
            assert!(change.edited.is_empty() && change.tiles.is_empty(), "{kind:?} on a {kind:?} tile: {change:?}");
        }
        // A tile made that type: a second stroke has nothing to set either.
        let other = *tiles.iter().find(|&&t| editor.terrain().tile_kind(t) != Some(kind)).unwrap();
        let first = editor.apply(Stroke { tool: Tool::SetKind(kind), brush: Brush::Range(0), tile: other }).unwrap();
        assert!(first.edited.contains(&other));
        assert_eq!(editor.terrain().tile_kind(other), Some(kind));
        let edits = editor.edits();
        let again = editor.apply(Stroke { tool: Tool::SetKind(kind), brush: Brush::Range(0), tile: other }).unwrap();
        assert!(again.edited.is_empty() && again.tiles.is_empty(), "{kind:?} twice: {again:?}");
        assert_eq!(editor.edits(), edits);
    }
}

#[test]
fn a_raise_moves_the_whole_tile_and_a_second_undo_is_none() {
    let mut editor = Editor::new(bounded(Vec::new())).unwrap();
    let tile = editor.terrain().tile_from_offset([5, 5]);
    let before = editor.terrain().tile_info(tile).unwrap().elevation;
    let change = editor.apply(Stroke { tool: Tool::Raise(0.2), brush: Brush::Range(0), tile }).unwrap();
    assert!(change.tiles.contains(&tile) && !change.chunks.is_empty());
    let after = editor.terrain().tile_info(tile).unwrap().elevation;
    assert!(after > before, "{after} not above {before}");
    assert_eq!(editor.edits().len(), 1);
    assert!(editor.undo().is_some());
    assert!(editor.undo().is_none());
    assert_eq!(editor.terrain().tile_info(tile).unwrap().elevation, before);
}

#[test]
fn a_brush_across_a_wrapping_maps_seam_edits_the_maps_own_tiles() {
    let config = MapConfig { size: MapSize::Bounded { x: 20, z: 10 }, wrap: true, ..MapConfig::default() };
    let mut editor = Editor::new(config).unwrap();
    // Column 20 is column 0 again; a radius-1 brush there reaches columns 19, 0 and 1.
    let tile = editor.terrain().tile_from_offset([20, 5]);
    editor.apply(Stroke { tool: Tool::SetKind(TileKind::Mountain), brush: Brush::Range(1), tile }).unwrap();
    let columns: HashSet<i32> = editor.edits().iter().map(|e| e.at.0).collect();
    assert_eq!(columns, HashSet::from([19, 0, 1]));
    assert!(editor.edits().iter().all(|e| (0..20).contains(&e.at.0)));
}

#[test]
fn bad_edits_are_refused_by_name_and_strokes_off_the_map_change_nothing() {
    let refused = |edits: Vec<TileEdit>| Terrain::new(bounded(edits)).unwrap_err().to_string();
    let e = refused(vec![TileEdit::at((20, 3))]);
    assert!(e.contains("edits[0].at") && e.contains("columns 0..20"), "{e}");
    let e = refused(vec![TileEdit::at((1, 1)), TileEdit { height: Some(0.5), ..TileEdit::at((1, 1)) }]);
    assert!(e.contains("edits[1].at") && e.contains("no other edit"), "{e}");
    for bad in [f32::NAN, f32::INFINITY, -0.5, 1.5] {
        let e = refused(vec![TileEdit { height: Some(bad), ..TileEdit::at((2, 2)) }]);
        assert!(e.contains("edits[0].height") && e.contains("[0, 1]"), "{e}");
    }
    let mut sealess = bounded(vec![TileEdit { kind: Some(TileKind::Sea), ..TileEdit::at((2, 2)) }]);
    sealess.terrain.sea_threshold = 0.0;
    sealess.terrain.interpolation_tolerance = 0.0;
    let e = Terrain::new(sealess).unwrap_err().to_string();
    assert!(e.contains("edits[0].kind"), "{e}");
    // A malformed edit in a map file: its line and column.
    let e = MapConfig::from_ron("(size: Bounded(x: 20, z: 10),\n edits: [(at: (1, 1), biome_typo: 3)])").unwrap_err();
    assert!(e.to_string().contains("2:"), "{e}");

    let mut editor = Editor::new(bounded(Vec::new())).unwrap();
    let off = editor.terrain().tile_from_offset([40, 40]);
    let stroke = Stroke { tool: Tool::Raise(0.1), brush: Brush::Range(2), tile: off };
    assert_eq!(editor.apply(stroke), Err(EditError::OffMap(off)));
    let tile = editor.terrain().tile_from_offset([3, 3]);
    let bad = Stroke { tool: Tool::Raise(f32::NAN), brush: Brush::Range(0), tile };
    assert!(matches!(editor.apply(bad), Err(EditError::Amount { .. })));
    assert_eq!((editor.undo_len(), editor.edits().len()), (0, 0));
}

#[test]
fn a_map_without_edits_writes_no_edits_section() {
    let text = bounded(Vec::new()).to_ron();
    assert!(!text.contains("edits"), "{text}");
    let edited = bounded(vec![TileEdit { kind: Some(TileKind::Mountain), ..TileEdit::at((3, 4)) }]).to_ron();
    assert!(edited.contains("edits") && edited.contains("Mountain"), "{edited}");
    assert_eq!(MapConfig::from_ron(&edited).unwrap().edits.len(), 1);
}

/// A map with climate and rivers, 30x20.
fn watered() -> MapConfig {
    let mut config = MapConfig { size: MapSize::Bounded { x: 30, z: 20 }, seed: 7, ..MapConfig::default() };
    config.climate.enabled = true;
    config.rivers.enabled = true;
    config
}

/// A river added on a dry inland tile runs from it to the sea, a lake or the edge; removing it
/// there takes it off the tile and everything upstream, and undo brings the map back.
#[test]
fn an_added_river_runs_to_an_outlet_and_a_removed_one_is_gone_upstream() {
    let mut editor = Editor::new(watered()).unwrap();
    let t = editor.terrain().clone();
    let tile = t
        .tiles()
        .find(|&x| {
            t.tile_kind(x) == Some(TileKind::Land)
                && t.river(x).is_none()
                && t.lake(x).is_none()
                && x.all_neighbors().iter().all(|&n| t.contains(n) && t.tile_kind(n) == Some(TileKind::Land))
        })
        .expect("an inland tile without a river");
    let change = editor.apply(Stroke { tool: Tool::AddRiver, brush: Brush::Range(0), tile }).unwrap();
    assert_eq!(editor.edits()[0].river, Some(RiverEdit::Source));
    let added = editor.terrain().river(tile).expect("a river rises on the tile");
    let next = added.downstream.expect("it runs on from its source");
    assert!(change.tiles.contains(&tile) && change.tiles.contains(&next), "the river's tiles are reported");
    // Follow it down: every tile on its way carries it until the sea, a lake or the edge.
    let after = editor.terrain().clone();
    let mut here = added;
    for _ in 0..after.tiles().count() {
        let Some(next) = here.downstream else { break };
        if after.tile_kind(next) == Some(TileKind::Sea) || after.lake(next).is_some() {
            break;
        }
        here = after.river(next).expect("the river goes on to the next tile");
        assert!(change.tiles.contains(&here.hex), "{:?} on the new river is not reported", here.hex);
    }
    assert_rivers_flow_down(&after).unwrap();

    // Remove it where it rises: no river on the tile.
    editor.apply(Stroke { tool: Tool::RemoveRiver, brush: Brush::Range(0), tile }).unwrap();
    assert!(editor.terrain().river(tile).is_none());
    // Remove a generated river mid-way: the tile and every tile draining through it go dry.
    let mut editor = Editor::new(watered()).unwrap();
    let t = editor.terrain().clone();
    let river = t.rivers().into_iter().find(|r| !r.upstream.is_empty()).expect("a river with a tributary");
    editor.apply(Stroke { tool: Tool::RemoveRiver, brush: Brush::Range(0), tile: river.hex }).unwrap();
    let dry = editor.terrain();
    assert!(dry.river(river.hex).is_none());
    for up in &river.upstream {
        assert!(dry.river(*up).is_none(), "{up:?} upstream of a removed river still carries one");
    }
    assert_rivers_flow_down(dry).unwrap();
    while editor.undo().is_some() {}
    assert_eq!(editor.terrain().rivers(), t.rivers());
}

/// On a map whose rivers run on edges, a river added on an inland tile rises at one of its
/// corners and runs to the sea, a lake or the edge; a tile made dry has no river along or ending
/// on its edges; undo brings the network back; the map file keeps the rivers set by hand.
#[test]
fn an_edge_river_added_rises_at_the_tile_and_a_dry_tile_has_none() {
    let mut config = watered();
    config.rivers.model = hex_terrain::RiverModel::Edges;
    config.rivers.threshold = 4.0;
    let mut editor = Editor::new(config).unwrap();
    let t = editor.terrain().clone();
    let corners = |tile: Hex| tile.all_vertices();
    let touches = |t: &Terrain, tile: Hex| {
        tile.all_neighbors().into_iter().chain([tile]).any(|h| {
            t.river_edges(h)
                .iter()
                .any(|r| r.edge.vertices().iter().any(|v| corners(tile).iter().any(|c| c.equivalent(v))))
        })
    };
    let tile = t
        .tiles()
        .find(|&x| {
            x.range(2).all(|n| t.contains(n) && t.tile_kind(n) == Some(TileKind::Land) && t.lake(n).is_none())
                && !touches(&t, x)
        })
        .expect("an inland tile away from rivers");
    let change = editor.apply(Stroke { tool: Tool::AddRiver, brush: Brush::Range(0), tile }).unwrap();
    let after = editor.terrain().clone();
    assert!(touches(&after, tile), "no river rises at a corner of {tile:?}");
    assert!(change.tiles.contains(&tile), "the source's tile is reported");
    assert_edge_rivers_flow_down(&after).unwrap();
    let saved = MapConfig::from_ron(&editor.config().to_ron()).unwrap();
    let again = Terrain::new(saved).unwrap();
    for h in after.tiles() {
        assert_eq!(again.river_edges(h), after.river_edges(h), "the saved map replays to other rivers at {h:?}");
    }
    // A tile beside a river made dry: nothing runs along or ends on the
    // dry tile's edges.
    let crossing = after.tiles().find(|&h| after.river_edges(h).len() >= 2).expect("a tile beside a river");
    editor.apply(Stroke { tool: Tool::RemoveRiver, brush: Brush::Range(0), tile: crossing }).unwrap();
    let dry = editor.terrain().clone();
    assert!(!touches(&dry, crossing), "a river still touches {crossing:?}");
    assert_edge_rivers_flow_down(&dry).unwrap();
    while editor.undo().is_some() {}
    for h in t.tiles() {
        assert_eq!(editor.terrain().river_edges(h), t.river_edges(h));
    }
}

/// A lake dug into land fills with water; draining it gives land at its surface and no lake.
#[test]
fn a_dug_lake_holds_water_and_a_drained_one_is_land() {
    let mut editor = Editor::new(watered()).unwrap();
    let t = editor.terrain().clone();
    // The inland tile whose surroundings stand highest above the sea.
    let rim =
        |x: Hex| x.range(2).filter_map(|n| t.raw_height(t.lattice().tile_center(n))).fold(f32::INFINITY, f32::min);
    let tile = t
        .tiles()
        .filter(|&x| t.tile_kind(x) == Some(TileKind::Land) && t.lake(x).is_none() && x.range(2).all(|n| t.contains(n)))
        .max_by(|&a, &b| rim(a).total_cmp(&rim(b)))
        .expect("an inland tile two tiles from the edge");
    let change = editor.apply(Stroke { tool: Tool::FillLake, brush: Brush::Range(1), tile }).unwrap();
    let dug = editor.terrain().clone();
    assert!(dug.lake(tile).is_some(), "no lake where one was dug");
    for n in tile.range(1) {
        assert!(dug.lake(n).is_some(), "{n:?} under the brush holds no water");
        assert!(change.tiles.contains(&n));
    }
    assert_rivers_flow_down(&dug).unwrap();
    // Drain the whole lake (a flood of its biome, or every tile of it).
    let lake = dug.lake(tile).unwrap();
    let lake_tiles: Vec<Hex> = dug.tiles().filter(|&x| dug.lake(x) == Some(lake)).collect();
    editor.apply(Stroke { tool: Tool::DrainLake, brush: Brush::Range(2), tile }).unwrap();
    let drained = editor.terrain();
    for x in lake_tiles.iter().filter(|x| x.unsigned_distance_to(tile) <= 2) {
        assert!(drained.lake(*x).is_none(), "{x:?} still holds water after draining");
        assert_ne!(drained.tile_kind(*x), Some(TileKind::Sea));
    }
    assert_rivers_flow_down(drained).unwrap();

    // Water tools on a map without rivers are refused by what they need.
    let mut dry = Editor::new(bounded(Vec::new())).unwrap();
    let tile = dry.terrain().tile_from_offset([5, 5]);
    for tool in [Tool::AddRiver, Tool::RemoveRiver, Tool::FillLake, Tool::DrainLake] {
        let e = dry.apply(Stroke { tool, brush: Brush::Range(0), tile }).unwrap_err();
        assert!(matches!(e, EditError::Unsupported { needs: "rivers.enabled", .. }), "{e}");
    }
    let mut no_lakes = watered();
    no_lakes.rivers.lakes = false;
    let mut editor = Editor::new(no_lakes).unwrap();
    let e = editor.apply(Stroke { tool: Tool::FillLake, brush: Brush::Range(0), tile }).unwrap_err();
    assert!(e.to_string().contains("rivers.lakes"), "{e}");
    // A river edit in a file of a map without rivers is refused by name.
    let e = Terrain::new(bounded(vec![TileEdit { river: Some(RiverEdit::Source), ..TileEdit::at((3, 3)) }]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("edits[0].river") && e.contains("rivers.enabled"), "{e}");
}

/// Props set by hand: none leaves the tile bare, dense grows a wood, on any land tile.
#[test]
fn prop_density_set_by_hand_replaces_the_biomes() {
    let mut editor = Editor::new(watered()).unwrap();
    let t = editor.terrain().clone();
    let props_on = |t: &Terrain, tile: Hex| {
        let chunk = t.generate_chunk(t.chunk_of(tile).unwrap()).unwrap();
        t.props(&chunk, usize::MAX, 1.0).into_iter().filter(|p| p.tile == tile).collect::<Vec<_>>()
    };
    let wooded = t.tiles().find(|&x| props_on(&t, x).len() >= 3).expect("a tile with props");
    editor.apply(Stroke { tool: Tool::SetProps(PropDensity::None), brush: Brush::Range(0), tile: wooded }).unwrap();
    assert!(props_on(editor.terrain(), wooded).is_empty(), "props stand on a tile set to none");
    let bare = t
        .tiles()
        .find(|&x| {
            t.tile_kind(x) == Some(TileKind::Land)
                && t.river(x).is_none()
                && t.lake(x).is_none()
                && props_on(&t, x).is_empty()
        })
        .expect("a bare dry land tile");
    editor.apply(Stroke { tool: Tool::SetProps(PropDensity::Dense), brush: Brush::Range(0), tile: bare }).unwrap();
    let wood = props_on(editor.terrain(), bare);
    assert!(wood.len() >= 5, "a dense tile grows {} props", wood.len());
    assert!(wood.iter().all(|p| matches!(p.kind, PropKind::Pine | PropKind::Broadleaf)));
    // The heights did not move: a prop edit is no height edit.
    assert_eq!(editor.terrain().tile_info(bare), t.tile_info(bare));
}

/// A biome set by hand on a map without climate is the biome of the mesh's tile, of
/// `tile_info` and of every query (the mesh used to give the kind's biome).
#[test]
fn a_biome_set_by_hand_shows_in_the_mesh_on_a_map_without_climate() {
    let config =
        MapConfig::from_ron("(size: Bounded(x: 4, z: 4), edits: [(at: (1, 1), biome: Some(Desert))])").unwrap();
    assert!(!config.climate.enabled);
    let t = Terrain::new(config).unwrap();
    let tile = t.tile_from_offset([1, 1]);
    let mesh = t.generate_map().unwrap();
    let info = mesh.tiles.iter().find(|i| i.hex == tile).unwrap();
    assert_eq!(biome::of(&t, info), Biome::Desert);
    assert_eq!(info, &t.tile_info(tile).unwrap());
    assert_eq!(biome::at(&t, tile), Some(Biome::Desert));
}

/// Three edited tiles around a seam corner of a wrapping map: the corner and its copy one
/// period east have the same bits (the deltas were summed in the order the point's cube
/// rounding listed the tiles, which differed between the copies).
#[test]
fn an_edited_corner_on_the_wrap_seam_is_bit_exact() {
    let config = MapConfig::from_ron(
        "(size: Bounded(x: 8, z: 22), wrap: true, terrain: (max_elevation: 43.983936, sea_threshold: 0.3724436, \
         mountain_threshold: 0.686497, interpolation_tolerance: 0.047680397, inner_rings: 2), \
         shape: Island(a: 4.2091084, b: 5.2374687), chunk_size: (10, 5), edits: [(at: (7, 10), height: \
         Some(0.15201788)), (at: (0, 11), height: Some(0.109587856)), (at: (7, 11), height: Some(0.13849555))])",
    )
    .unwrap();
    let t = Terrain::new(config).unwrap();
    let shift = t.wrap().unwrap().lattice_shift;
    let m = t.generate(t.bounds().unwrap(), GenerateOptions::DIAGNOSTICS);
    let lattice = &m.diagnostics.as_ref().unwrap().lattice;
    let index: HashMap<Hex, usize> = lattice.iter().enumerate().map(|(i, &p)| (p, i)).collect();
    let mut pairs = 0;
    for (i, &p) in lattice.iter().enumerate() {
        if let Some(&j) = index.get(&(p + shift)) {
            assert_eq!(m.buffers.positions[i][1].to_bits(), m.buffers.positions[j][1].to_bits(), "{p:?}");
            assert_eq!(m.buffers.normals[i].map(f32::to_bits), m.buffers.normals[j].map(f32::to_bits), "{p:?}");
            pairs += 1;
        }
    }
    assert!(pairs > 22, "{pairs} seam pairs");
    let corner = Hex::new(-36, 66);
    assert_eq!(t.vertex(corner).unwrap().height.to_bits(), t.vertex(corner + shift).unwrap().height.to_bits());
}
