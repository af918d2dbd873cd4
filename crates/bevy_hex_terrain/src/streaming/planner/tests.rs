use hex_terrain::{MapConfig, MapSize};

use super::*;

fn terrain(size: MapSize) -> Arc<Terrain> {
    Arc::new(Terrain::new(MapConfig { size, chunk_size: (8, 8), ..MapConfig::default() }).unwrap())
}

fn settings(tasks: usize) -> HexStreamingSettings {
    HexStreamingSettings { load_radius: 1, prefetch: 1, unload_hysteresis: 1, max_tasks_in_flight: tasks, ..default() }
}

fn default<T: Default>() -> T {
    T::default()
}

fn square(center: ChunkCoord, r: i32) -> Vec<ChunkCoord> {
    (-r..=r).flat_map(|dz| (-r..=r).map(move |dx| ChunkCoord::new(center.x + dx, center.z + dz))).collect()
}

#[test]
fn an_agent_wants_its_radius_plus_prefetch_nearest_first() {
    let t = terrain(MapSize::Unbounded);
    let agent = ChunkCoord::new(5, -3);
    let p = plan(&t, &settings(100), &[(agent, 1)], &[], &HashMap::default(), &mut ChunkBoxes::default());
    let mut wanted: Vec<ChunkCoord> = p.wanted.keys().copied().collect();
    wanted.sort_unstable();
    let mut expected = square(agent, 2);
    expected.sort_unstable();
    assert_eq!(wanted, expected);
    assert_eq!(p.start.len(), 25);
    assert_eq!(p.start[0].0, agent, "the agent's own chunk first");
    let distances: Vec<u32> = p.start.iter().map(|(c, _)| c.distance(agent)).collect();
    assert!(distances.windows(2).all(|w| w[0] <= w[1]), "nearest first: {distances:?}");
    assert!(p.drop.is_empty());
}

#[test]
fn the_task_budget_counts_running_tasks() {
    let t = terrain(MapSize::Unbounded);
    let agent = ChunkCoord::default();
    let mut existing = HashMap::default();
    existing.insert(agent, ChunkState { current: false, building: true, ..default() });
    existing.insert(ChunkCoord::new(1, 0), ChunkState { current: true, building: false, ..default() });
    let p = plan(&t, &settings(4), &[(agent, 1)], &[], &existing, &mut ChunkBoxes::default());
    assert_eq!(p.start.len(), 3, "4 slots, one taken");
    assert!(!p.start.iter().any(|s| s.0 == agent), "a chunk being built is not started again");
    assert!(!p.start.iter().any(|s| s.0 == ChunkCoord::new(1, 0)), "a current chunk is not rebuilt");
    // An outdated chunk (older generation, no task) is rebuilt.
    existing.insert(ChunkCoord::new(1, 0), ChunkState::default());
    let p = plan(&t, &settings(100), &[(agent, 1)], &[], &existing, &mut ChunkBoxes::default());
    assert!(p.start.iter().any(|s| s.0 == ChunkCoord::new(1, 0)));
}

#[test]
fn chunks_drop_only_beyond_the_hysteresis() {
    let t = terrain(MapSize::Unbounded);
    let agent = ChunkCoord::new(10, 0);
    let existing: HashMap<ChunkCoord, ChunkState> = [0, 7, 8, 13, 14]
        .into_iter()
        .map(|x| (ChunkCoord::new(x, 0), ChunkState { current: true, building: false, ..default() }))
        .collect();
    // radius 1 + prefetch 1 + hysteresis 1: kept within 3 chunks.
    let p = plan(&t, &settings(8), &[(agent, 1)], &[], &existing, &mut ChunkBoxes::default());
    assert_eq!(p.drop, vec![ChunkCoord::new(0, 0), ChunkCoord::new(14, 0)]);
    assert!(!p.wanted.contains_key(&ChunkCoord::new(7, 0)), "kept, not wanted");
}

#[test]
fn several_agents_keep_the_union_at_the_nearest_distance() {
    let t = terrain(MapSize::Unbounded);
    let (a, b) = (ChunkCoord::new(0, 0), ChunkCoord::new(3, 0));
    let p = plan(&t, &settings(100), &[(a, 1), (b, 1)], &[], &HashMap::default(), &mut ChunkBoxes::default());
    assert_eq!(p.wanted[&ChunkCoord::new(2, 0)], 1, "nearer to b");
    assert_eq!(p.wanted[&ChunkCoord::new(1, 0)], 1, "nearer to a");
    assert_eq!(p.wanted.len(), 5 * 8);
}

#[test]
fn bounded_maps_clip_and_without_agents_want_every_chunk() {
    let t = terrain(MapSize::Bounded { x: 20, z: 12 });
    let p = plan(&t, &settings(100), &[], &[], &HashMap::default(), &mut ChunkBoxes::default());
    let mut all = t.chunks();
    all.sort_unstable();
    let mut wanted: Vec<ChunkCoord> = p.wanted.keys().copied().collect();
    wanted.sort_unstable();
    assert_eq!(wanted, all);
    // An agent in a corner wants only chunks inside the map.
    let p =
        plan(&t, &settings(100), &[(ChunkCoord::new(0, 0), 1)], &[], &HashMap::default(), &mut ChunkBoxes::default());
    assert!(p.wanted.keys().all(|c| t.chunk_rect(*c).is_some()));
    assert_eq!(p.wanted.len(), 3 * 2);
    // A chunk outside the map (after a reload to a smaller map) is dropped.
    let existing: HashMap<ChunkCoord, ChunkState> =
        [(ChunkCoord::new(9, 9), ChunkState::default())].into_iter().collect();
    assert_eq!(
        plan(&t, &settings(100), &[], &[], &existing, &mut ChunkBoxes::default()).drop,
        vec![ChunkCoord::new(9, 9)]
    );
}

#[test]
fn without_agents_an_unbounded_world_streams_around_the_origin() {
    let t = terrain(MapSize::Unbounded);
    let p = plan(&t, &settings(100), &[], &[], &HashMap::default(), &mut ChunkBoxes::default());
    assert_eq!(p.wanted.len(), 25);
    assert!(p.wanted.keys().all(|c| c.distance(ChunkCoord::default()) <= 2));
}

fn lod(coarse_distance: f32) -> HexStreamingSettings {
    HexStreamingSettings { coarse_distance: Some(coarse_distance), ..settings(100) }
}

/// A viewer above the middle of chunk (0, 0), `height` units up.
fn viewer_over(t: &Terrain, height: f64) -> DVec3 {
    let (min, max) = super::super::detail::chunk_box(t, ChunkCoord::default()).unwrap();
    DVec3::new((min.x + max.x) / 2.0, height, (min.z + max.z) / 2.0)
}

#[test]
fn chunks_far_from_every_viewer_are_coarse_with_hysteresis() {
    use super::super::detail::{DETAIL_HYSTERESIS, box_distance, chunk_box, chunk_detail};
    let t = terrain(MapSize::Unbounded);
    let viewer = viewer_over(&t, 0.0);
    let s = lod(20.0);
    assert_eq!(chunk_detail(&t, &s, &[viewer], chunk_box(&t, ChunkCoord::default()), None), Detail::Full);
    assert_eq!(chunk_detail(&t, &s, &[viewer], chunk_box(&t, ChunkCoord::new(6, 0)), None), Detail::Coarse);
    // Every chunk's level against its distance, for each level it may show.
    let size = f64::from(t.config().layout.hex_size);
    for x in -6..=6 {
        for z in -6..=6 {
            let c = ChunkCoord::new(x, z);
            let d = box_distance(viewer, chunk_box(&t, c).unwrap()) / size;
            let (near, far) = (d < 20.0 * (1.0 - DETAIL_HYSTERESIS), d > 20.0);
            for shown in [None, Some(Detail::Full), Some(Detail::Coarse)] {
                let got = chunk_detail(&t, &s, &[viewer], chunk_box(&t, c), shown);
                let expected = if far {
                    Detail::Coarse
                } else if near {
                    Detail::Full
                } else {
                    shown.unwrap_or(Detail::Full)
                };
                assert_eq!(got, expected, "chunk {c:?} at {d:.1} hex sizes showing {shown:?}");
            }
        }
    }
    // The nearest viewer counts; height counts (a camera zoomed out sees every chunk coarse).
    let (min, max) = chunk_box(&t, ChunkCoord::new(6, 0)).unwrap();
    let other = (min + max) / 2.0;
    assert_eq!(chunk_detail(&t, &s, &[viewer, other], chunk_box(&t, ChunkCoord::new(6, 0)), None), Detail::Full);
    assert_eq!(
        chunk_detail(&t, &s, &[viewer_over(&t, 40.0 * size)], chunk_box(&t, ChunkCoord::default()), None),
        Detail::Coarse
    );
    // No viewer, no threshold, or a threshold that is not a number: everything full.
    assert_eq!(chunk_detail(&t, &s, &[], chunk_box(&t, ChunkCoord::new(6, 0)), None), Detail::Full);
    let off = HexStreamingSettings { coarse_distance: None, ..settings(100) };
    assert_eq!(chunk_detail(&t, &off, &[viewer], chunk_box(&t, ChunkCoord::new(6, 0)), None), Detail::Full);
    assert_eq!(chunk_detail(&t, &lod(f32::NAN), &[viewer], chunk_box(&t, ChunkCoord::new(6, 0)), None), Detail::Full);
}

#[test]
fn a_level_change_is_a_task_after_the_missing_chunks_and_keeps_the_mesh() {
    let t = terrain(MapSize::Unbounded);
    let agent = ChunkCoord::default();
    let viewer = viewer_over(&t, 0.0);
    let near = ChunkCoord::new(1, 0);
    let far = ChunkCoord::new(2, 2);
    let s = HexStreamingSettings { load_radius: 2, ..lod(10.0) };
    let p = plan(&t, &s, &[(agent, 2)], &[viewer], &HashMap::default(), &mut ChunkBoxes::default());
    assert_eq!(p.detail[&agent], Detail::Full);
    assert_eq!(p.detail[&far], Detail::Coarse);
    assert!(p.start.contains(&(far, Detail::Coarse)), "a new far chunk is built coarse at once");
    // Every chunk current at full detail: the far ones get a coarse task, the near ones none.
    let mut existing: HashMap<ChunkCoord, ChunkState> =
        p.wanted.keys().map(|&c| (c, ChunkState { current: true, building: false, detail: Detail::Full })).collect();
    let p = plan(&t, &s, &[(agent, 2)], &[viewer], &existing, &mut ChunkBoxes::default());
    assert!(p.start.contains(&(far, Detail::Coarse)));
    assert!(p.start.iter().all(|&(c, d)| d == Detail::Coarse && p.detail[&c] == Detail::Coarse));
    assert!(!p.start.iter().any(|s| s.0 == near || s.0 == agent));
    assert!(p.drop.is_empty(), "a level change drops nothing: the old mesh stays until the new one");
    // A missing chunk goes before a level change even when farther; a chunk being rebuilt is left.
    let missing = ChunkCoord::new(3, 3);
    existing.remove(&missing);
    existing.insert(far, ChunkState { current: true, building: true, detail: Detail::Coarse });
    // Two task slots, one taken by the chunk being rebuilt.
    let one = HexStreamingSettings { max_tasks_in_flight: 2, ..s.clone() };
    let p = plan(&t, &one, &[(agent, 2)], &[viewer], &existing, &mut ChunkBoxes::default());
    assert_eq!(p.start, vec![(missing, Detail::Coarse)]);
    let p = plan(&t, &s, &[(agent, 2)], &[viewer], &existing, &mut ChunkBoxes::default());
    assert!(!p.start.iter().any(|s| s.0 == far));
}

#[test]
fn a_chunks_box_holds_its_mesh_wherever_it_stands() {
    use hex_terrain::Orientation;
    for pointy in [false, true] {
        for wrap in [false, true] {
            let mut c =
                MapConfig { size: MapSize::Bounded { x: 32, z: 20 }, chunk_size: (8, 8), ..MapConfig::default() };
            c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
            c.terrain.inner_rings = 2;
            c.wrap = wrap;
            let t = Terrain::new(c).unwrap();
            // The map's chunks, and on a wrapping map copies a period east and west.
            let chunks = t.chunks().into_iter().chain(if wrap {
                vec![ChunkCoord::new(-1, 1), ChunkCoord::new(5, 0)]
            } else {
                vec![]
            });
            for chunk in chunks {
                let (min, max) = super::super::detail::chunk_box(&t, chunk).unwrap();
                let mesh = t.generate_chunk(chunk).unwrap();
                for p in &mesh.buffers.positions {
                    let w = DVec3::new(mesh.origin[0], mesh.origin[1], mesh.origin[2])
                        + bevy::math::Vec3::from_array(*p).as_dvec3();
                    let inside = w.cmpge(min - 1e-3).all() && w.cmple(max + 1e-3).all();
                    assert!(inside, "pointy {pointy}, wrap {wrap}, chunk {chunk:?}: vertex {w} outside {min}..{max}");
                }
            }
        }
    }
}

#[test]
fn one_box_cache_over_frames_and_terrains_plans_as_an_empty_one() {
    use hex_terrain::Orientation;
    // Two terrains of other geometry (a reload), the cache asked about each in turn, and a viewer
    // walking on past many chunks (the cache forgets those no longer wanted).
    let flat = terrain(MapSize::Unbounded);
    let mut c = MapConfig { size: MapSize::Bounded { x: 64, z: 40 }, chunk_size: (8, 8), ..MapConfig::default() };
    c.layout.orientation = Orientation::Pointy;
    c.layout.hex_size = 2.5;
    let pointy = Arc::new(Terrain::new(c).unwrap());
    let s = HexStreamingSettings { load_radius: 2, ..lod(12.0) };
    let mut boxes = ChunkBoxes::default();
    let mut existing: HashMap<ChunkCoord, ChunkState> = HashMap::default();
    for step in 0..40 {
        let t = if step % 7 < 4 { &flat } else { &pointy };
        let size = f64::from(t.config().layout.hex_size);
        let viewer = DVec3::new(f64::from(step) * 9.0 * size, f64::from(step % 5) * 4.0 * size, 3.0 * size);
        let agent = t.tile_at(viewer.x, viewer.z).and_then(|tile| t.chunk_of(tile)).unwrap_or_default();
        let cached = plan(t, &s, &[(agent, 2)], &[viewer], &existing, &mut boxes);
        let fresh = plan(t, &s, &[(agent, 2)], &[viewer], &existing, &mut ChunkBoxes::default());
        assert_eq!(cached, fresh, "step {step}");
        assert!(boxes.held() <= cached.wanted.len(), "step {step}: {} boxes kept", boxes.held());
        // The chunks now show what the plan wanted, so hysteresis comes into play.
        existing = cached
            .detail
            .iter()
            .map(|(&c, &d)| (c, ChunkState { current: true, building: false, detail: d }))
            .collect();
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]

    /// However agents of any radius walk (unbounded, bounded and wrapping maps; with or without
    /// agents; any prefetch and hysteresis), the chunks that exist, once every planned task
    /// has started and every drop is done, never number more than `kept_at_most`.
    #[test]
    fn the_kept_chunks_never_outnumber_their_bound(
        size in 0u8..3,
        (load, prefetch, hysteresis) in (0u32..3, 0u32..3, 0u32..3),
        agents in proptest::collection::vec((0u32..4, -6i32..6, -6i32..6), 0..4),
        steps in proptest::collection::vec(proptest::collection::vec((-2i32..3, -2i32..3), 4), 1..12),
    ) {
        let mut c = MapConfig { chunk_size: (8, 8), ..MapConfig::default() };
        c.size = if size == 0 { MapSize::Unbounded } else { MapSize::Bounded { x: 40, z: 24 } };
        c.wrap = size == 2;
        let t = Arc::new(Terrain::new(c).unwrap());
        let s = HexStreamingSettings {
            load_radius: load,
            prefetch,
            unload_hysteresis: hysteresis,
            max_tasks_in_flight: usize::MAX,
            coarse_distance: None,
            ..default()
        };
        let bound = kept_at_most(&t, &s, agents.iter().map(|a| a.0));
        let mut at: Vec<(ChunkCoord, u32)> =
            agents.iter().map(|&(r, x, z)| (ChunkCoord::new(x, z), r)).collect();
        let mut existing: HashMap<ChunkCoord, ChunkState> = HashMap::default();
        for step in &steps {
            for (agent, &(dx, dz)) in at.iter_mut().zip(step) {
                agent.0 = ChunkCoord::new(agent.0.x + dx, agent.0.z + dz);
            }
            let p = plan(&t, &s, &at, &[], &existing, &mut ChunkBoxes::default());
            for c in &p.drop {
                existing.remove(c);
            }
            for &(c, detail) in &p.start {
                existing.insert(c, ChunkState { current: true, building: false, detail });
            }
            proptest::prop_assert!(existing.len() <= bound, "{} chunks kept, bound {bound}", existing.len());
        }
    }
}
