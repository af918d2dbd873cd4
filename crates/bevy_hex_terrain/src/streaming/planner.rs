//! The streaming planner: from the agents' chunks and the chunks that exist, which chunks are
//! wanted, which are dropped and which get a task, in what order. A pure function of its
//! inputs, tested on [`ChunkCoord`]s without an `App`.

use std::sync::Arc;

use bevy::math::DVec3;
use bevy::platform::collections::HashMap;
use hex_terrain::{ChunkCoord, Detail, Terrain};

use super::HexStreamingSettings;
use super::detail::ChunkBoxes;

/// What an existing chunk shows and does, as the planner sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ChunkState {
    /// It shows a mesh of the current map generation.
    pub current: bool,
    /// A task for the current map generation is building its mesh.
    pub building: bool,
    /// The level of the mesh its task builds, if building, else of the mesh it shows.
    pub detail: Detail,
}

/// What one frame of streaming does.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plan {
    /// Chunks that must exist, with their distance (in chunks) to the nearest agent.
    pub wanted: HashMap<ChunkCoord, u32>,
    /// The level each wanted chunk is to be drawn at ([`chunk_detail`](super::detail::chunk_detail)).
    pub detail: HashMap<ChunkCoord, Detail>,
    /// Existing chunks to despawn: beyond every agent's keep distance, or outside the map.
    pub drop: Vec<ChunkCoord>,
    /// Wanted chunks to start a task for, with the level to build: missing, showing an older
    /// generation, or current at another level than wanted, and not being rebuilt; nearest
    /// first, at most the free task budget.
    pub start: Vec<(ChunkCoord, Detail)>,
}

/// Plans a frame. `agents` holds each agent's chunk and radius; `viewers` the world positions
/// levels of detail are measured from; `existing` every chunk entity's state; `boxes` the chunk
/// boxes computed so far (a cache: the plan is the same with an empty one).
#[must_use]
pub fn plan(
    terrain: &Arc<Terrain>,
    settings: &HexStreamingSettings,
    agents: &[(ChunkCoord, u32)],
    viewers: &[DVec3],
    existing: &HashMap<ChunkCoord, ChunkState>,
    boxes: &mut ChunkBoxes,
) -> Plan {
    let ahead = settings.prefetch;
    let mut centers = agents.to_vec();
    let mut wanted: HashMap<ChunkCoord, u32> = HashMap::default();
    if centers.is_empty() {
        if terrain.bounds().is_some() {
            wanted.extend(terrain.chunks().into_iter().map(|c| (c, 0)));
        } else {
            centers.push((ChunkCoord::default(), settings.load_radius));
        }
    }
    for &(center, radius) in &centers {
        let r = (radius + ahead) as i32;
        for dz in -r..=r {
            for dx in -r..=r {
                let c = ChunkCoord::new(center.x + dx, center.z + dz);
                if terrain.chunk_rect(c).is_none() {
                    continue;
                }
                let d = c.distance(center);
                wanted.entry(c).and_modify(|e| *e = (*e).min(d)).or_insert(d);
            }
        }
    }

    // Kept: inside the map and within some agent's radius + prefetch + hysteresis (every chunk
    // of a bounded map when there is no agent).
    let keep = |c: ChunkCoord| {
        terrain.chunk_rect(c).is_some()
            && (centers.is_empty()
                || centers
                    .iter()
                    .any(|&(center, radius)| c.distance(center) <= radius + ahead + settings.unload_hysteresis))
    };
    let mut drop: Vec<ChunkCoord> = existing.keys().copied().filter(|c| !wanted.contains_key(c) && !keep(*c)).collect();
    drop.sort_unstable();

    let in_flight = existing.iter().filter(|(c, s)| s.building && !drop.contains(c)).count();
    let budget = settings.max_tasks_in_flight.saturating_sub(in_flight);
    let detail: HashMap<ChunkCoord, Detail> = wanted
        .keys()
        .map(|&c| (c, boxes.detail(terrain, settings, viewers, c, existing.get(&c).map(|s| s.detail))))
        .collect();
    boxes.keep(&wanted);
    // Missing or outdated chunks first, then level changes, each nearest first.
    let mut todo: Vec<(bool, u32, ChunkCoord)> = wanted
        .iter()
        .filter_map(|(&c, &d)| match existing.get(&c) {
            None => Some((false, d, c)),
            Some(s) if s.building => None,
            Some(s) if !s.current => Some((false, d, c)),
            Some(s) => (s.detail != detail[&c]).then_some((true, d, c)),
        })
        .collect();
    todo.sort_unstable();
    let start = todo.into_iter().take(budget).map(|(_, _, c)| (c, detail[&c])).collect();
    Plan { wanted, detail, drop, start }
}

/// The most chunks [`plan`] keeps at once, for agents of these radii: every chunk within an
/// agent's radius + prefetch + hysteresis (a square of chunks each), at most the map's chunks on a
/// bounded map that does not wrap (a wrapping map's copies past its edges are chunks of their
/// own); without agents, every chunk of a bounded map, or those around the origin of an unbounded
/// one. An upper bound, to size what grows with the chunks ahead of time.
#[must_use]
pub fn kept_at_most(terrain: &Terrain, settings: &HexStreamingSettings, radii: impl IntoIterator<Item = u32>) -> usize {
    let square = |r: u32| {
        let side = 2 * (r as usize + settings.prefetch as usize + settings.unload_hysteresis as usize) + 1;
        side * side
    };
    let mut radii = radii.into_iter().peekable();
    let bounded = terrain.bounds().is_some();
    if radii.peek().is_none() {
        return if bounded { terrain.chunks().len() } else { square(settings.load_radius) };
    }
    let squares = radii.map(square).fold(0usize, usize::saturating_add);
    if bounded && terrain.wrap().is_none() { squares.min(terrain.chunks().len()) } else { squares }
}

#[cfg(test)]
mod tests;
