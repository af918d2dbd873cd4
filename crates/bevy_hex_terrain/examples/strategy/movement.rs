//! Moves a turn, and units walking their paths on the surface. What a move costs, paths and
//! where a unit can go are the map's rules (`HexMap::move_cost`, `path_avoiding`,
//! `reachable_avoiding`: the map file's movement model, which the fairness report measures too).

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::rig::Rig;
use crate::units::Unit;

/// Moves a unit has each turn.
pub(crate) const MOVES: u32 = 4;

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
