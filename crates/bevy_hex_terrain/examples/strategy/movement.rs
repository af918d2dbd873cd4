//! Movement rules: what entering a tile costs, a path's cost, where a unit can go this turn, and
//! units walking their paths on the surface.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::rig::Rig;
use crate::units::Unit;

/// Moves a unit has each turn.
pub(crate) const MOVES: u32 = 4;

/// Movement cost of entering a tile: land 1, mountain 3; sea, lakes and outside the map
/// impassable.
pub(crate) fn cost(map: &HexMap, tile: Hex) -> Option<u32> {
    if !map.contains(tile) || map.lake(tile).is_some() {
        return None;
    }
    match map.tile_kind(tile)? {
        TileKind::Sea => None,
        TileKind::Land => Some(1),
        TileKind::Mountain => Some(3),
    }
}

/// Cost of the step from `a` to its neighbor `b`: entering `b`, plus 1 for fording a river, that
/// is entering a river tile from a tile its river does not come from or go to (walking along a
/// river costs nothing more).
pub(crate) fn step_cost(map: &HexMap, a: Hex, b: Hex) -> Option<u32> {
    let enter = cost(map, b)?;
    // Rivers name the map's own tiles; `a` may be a copy past a wrapping map's edge.
    let a = map.wrap_tile(a)?;
    let ford = map.river(b).is_some_and(|r| r.downstream != Some(a) && !r.upstream.contains(&a));
    Some(enter + u32::from(ford))
}

/// What a path costs, step by step.
pub(crate) fn path_cost(map: &HexMap, path: &[Hex]) -> u32 {
    path.windows(2).filter_map(|w| step_cost(map, w[0], w[1])).sum()
}

/// Every tile reachable from `start` with `budget` moves (Dijkstra over [`step_cost`]), tiles
/// in `blocked` excluded. The search runs on the plane, so on a wrapping map it crosses the
/// seam; the tiles returned are the map's own.
pub(crate) fn reachable(map: &HexMap, start: Hex, budget: u32, blocked: &HashSet<Hex>) -> HashSet<Hex> {
    let mut best: HashMap<Hex, u32> = HashMap::from([(start, 0)]);
    let mut queue = BinaryHeap::from([(Reverse(0), start.x, start.y)]);
    while let Some((Reverse(spent), x, y)) = queue.pop() {
        let here = Hex::new(x, y);
        if best.get(&here).is_some_and(|&b| b < spent) {
            continue;
        }
        for next in here.all_neighbors() {
            if map.wrap_tile(next).is_some_and(|own| blocked.contains(&own)) {
                continue;
            }
            let Some(c) = step_cost(map, here, next) else { continue };
            let total = spent + c;
            if total <= budget && best.get(&next).is_none_or(|&b| total < b) {
                best.insert(next, total);
                queue.push((Reverse(total), next.x, next.y));
            }
        }
    }
    best.into_keys().filter_map(|t| map.wrap_tile(t)).filter(|&t| t != start).collect()
}

/// Moves units along their paths, on the surface. On a wrapping map a unit is drawn at its copy
/// nearest the camera, and walks the short way to the next point of its path, whichever copy of
/// it that is.
pub(crate) fn walk(
    time: Res<Time>,
    map: Res<HexMap>,
    rigs: Query<&Rig>,
    mut units: Query<(&mut Unit, &mut Transform)>,
) {
    let focus = rigs.iter().next().map_or(Vec3::ZERO, |r| r.focus);
    for (mut unit, mut t) in &mut units {
        t.translation = map.wrap_near(t.translation, focus);
        let Some(&next) = unit.path.first() else { continue };
        let next = map.wrap_near(next, t.translation);
        let to = next - t.translation;
        let step = 6.0 * time.delta_secs();
        if to.length() <= step {
            t.translation = next;
            unit.path.remove(0);
        } else {
            t.translation += to.normalize() * step;
            if let Some(y) = map.surface_height(t.translation) {
                t.translation.y = y + 0.6;
            }
        }
    }
}
