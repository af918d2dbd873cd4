use hex_terrain::{MapConfig, MapSize};

use super::*;

fn terrain(size: MapSize) -> Terrain {
    Terrain::new(MapConfig { size, chunk_size: (8, 8), ..MapConfig::default() }).unwrap()
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
    let p = plan(&t, &settings(100), &[(agent, 1)], &HashMap::default());
    let mut wanted: Vec<ChunkCoord> = p.wanted.keys().copied().collect();
    wanted.sort_unstable();
    let mut expected = square(agent, 2);
    expected.sort_unstable();
    assert_eq!(wanted, expected);
    assert_eq!(p.start.len(), 25);
    assert_eq!(p.start[0], agent, "the agent's own chunk first");
    let distances: Vec<u32> = p.start.iter().map(|c| c.distance(agent)).collect();
    assert!(distances.windows(2).all(|w| w[0] <= w[1]), "nearest first: {distances:?}");
    assert!(p.drop.is_empty());
}

#[test]
fn the_task_budget_counts_running_tasks() {
    let t = terrain(MapSize::Unbounded);
    let agent = ChunkCoord::default();
    let mut existing = HashMap::default();
    existing.insert(agent, ChunkState { current: false, building: true });
    existing.insert(ChunkCoord::new(1, 0), ChunkState { current: true, building: false });
    let p = plan(&t, &settings(4), &[(agent, 1)], &existing);
    assert_eq!(p.start.len(), 3, "4 slots, one taken");
    assert!(!p.start.contains(&agent), "a chunk being built is not started again");
    assert!(!p.start.contains(&ChunkCoord::new(1, 0)), "a current chunk is not rebuilt");
    // An outdated chunk (older generation, no task) is rebuilt.
    existing.insert(ChunkCoord::new(1, 0), ChunkState::default());
    let p = plan(&t, &settings(100), &[(agent, 1)], &existing);
    assert!(p.start.contains(&ChunkCoord::new(1, 0)));
}

#[test]
fn chunks_drop_only_beyond_the_hysteresis() {
    let t = terrain(MapSize::Unbounded);
    let agent = ChunkCoord::new(10, 0);
    let existing: HashMap<ChunkCoord, ChunkState> = [0, 7, 8, 13, 14]
        .into_iter()
        .map(|x| (ChunkCoord::new(x, 0), ChunkState { current: true, building: false }))
        .collect();
    // radius 1 + prefetch 1 + hysteresis 1: kept within 3 chunks.
    let p = plan(&t, &settings(8), &[(agent, 1)], &existing);
    assert_eq!(p.drop, vec![ChunkCoord::new(0, 0), ChunkCoord::new(14, 0)]);
    assert!(!p.wanted.contains_key(&ChunkCoord::new(7, 0)), "kept, not wanted");
}

#[test]
fn several_agents_keep_the_union_at_the_nearest_distance() {
    let t = terrain(MapSize::Unbounded);
    let (a, b) = (ChunkCoord::new(0, 0), ChunkCoord::new(3, 0));
    let p = plan(&t, &settings(100), &[(a, 1), (b, 1)], &HashMap::default());
    assert_eq!(p.wanted[&ChunkCoord::new(2, 0)], 1, "nearer to b");
    assert_eq!(p.wanted[&ChunkCoord::new(1, 0)], 1, "nearer to a");
    assert_eq!(p.wanted.len(), 5 * 8);
}

#[test]
fn bounded_maps_clip_and_without_agents_want_every_chunk() {
    let t = terrain(MapSize::Bounded { x: 20, z: 12 });
    let p = plan(&t, &settings(100), &[], &HashMap::default());
    let mut all = t.chunks();
    all.sort_unstable();
    let mut wanted: Vec<ChunkCoord> = p.wanted.keys().copied().collect();
    wanted.sort_unstable();
    assert_eq!(wanted, all);
    // An agent in a corner wants only chunks inside the map.
    let p = plan(&t, &settings(100), &[(ChunkCoord::new(0, 0), 1)], &HashMap::default());
    assert!(p.wanted.keys().all(|c| t.chunk_rect(*c).is_some()));
    assert_eq!(p.wanted.len(), 3 * 2);
    // A chunk outside the map (after a reload to a smaller map) is dropped.
    let existing: HashMap<ChunkCoord, ChunkState> =
        [(ChunkCoord::new(9, 9), ChunkState::default())].into_iter().collect();
    assert_eq!(plan(&t, &settings(100), &[], &existing).drop, vec![ChunkCoord::new(9, 9)]);
}

#[test]
fn without_agents_an_unbounded_world_streams_around_the_origin() {
    let t = terrain(MapSize::Unbounded);
    let p = plan(&t, &settings(100), &[], &HashMap::default());
    assert_eq!(p.wanted.len(), 25);
    assert!(p.wanted.keys().all(|c| c.distance(ChunkCoord::default()) <= 2));
}
