//! Entities on a globe's tiles: [`OnGlobeTile`] keeps a unit, a city or a marker standing on the
//! surface at its tile's center, its up the globe's up there (the center's direction from the
//! globe's center), and [`GlobeTileWalk`] walks it from tile to tile over frames along great
//! circles, on the surface as meshed (the core's ray cast down each step), across pentagons as
//! across any tile. Where an entity stands is a pure function of the globe and its tile: an edit
//! or a hot reload moves it with the new surface.

use bevy::math::{DQuat, DVec3};
use bevy::prelude::*;
use hex_terrain::{GlobeTerrain, GlobeTile};

use super::HexGlobe;

/// Puts an entity on a tile of the globe: its `Transform` is kept on the surface at the tile's
/// center (lifted by [`lift`](Self::lift)), its `y` axis along the globe's up there, through
/// edits and hot reloads. Change `tile` to move it at once; add [`GlobeTileWalk`] to walk it
/// there.
#[derive(Component, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Component)]
#[require(Transform)]
pub struct OnGlobeTile {
    /// The tile.
    pub tile: GlobeTile,
    /// How far above the surface the entity's origin stands.
    pub lift: f32,
}

impl OnGlobeTile {
    /// An entity on a tile's center, on the surface.
    #[must_use]
    pub fn new(tile: GlobeTile) -> Self {
        Self { tile, lift: 0.0 }
    }
}

/// Walks an [`OnGlobeTile`] entity along a path over frames: from tile to tile at `speed` world
/// units a second, [`OnGlobeTile::tile`] becoming each tile as it is reached; when the last is
/// reached the component is removed and [`GlobeWalkEnded`] is triggered on the entity. A path of
/// [`GlobeTerrain::path`] is the usual one (its first tile, the entity's own, is skipped).
#[derive(Component, Debug, Clone, PartialEq, Reflect)]
#[reflect(Component)]
pub struct GlobeTileWalk {
    /// The tiles still to walk to, in order (neighbors of each other; a tile equal to where the
    /// entity stands is skipped).
    pub path: Vec<GlobeTile>,
    /// World units a second.
    pub speed: f32,
}

impl GlobeTileWalk {
    /// A walk along a path's tiles at `speed` world units a second.
    #[must_use]
    pub fn new(path: impl IntoIterator<Item = GlobeTile>, speed: f32) -> Self {
        Self { path: path.into_iter().collect(), speed }
    }
}

/// An [`OnGlobeTile`] entity's [`GlobeTileWalk`] reached its last tile.
#[derive(EntityEvent, Debug, Clone, Copy, PartialEq, Reflect)]
pub struct GlobeWalkEnded {
    /// The entity.
    pub entity: Entity,
    /// The tile it stands on.
    pub tile: GlobeTile,
}

/// Where the surface as meshed lies along a direction from the globe's center (a unit vector):
/// a ray cast down from above the highest surface. `None` off the globe (a zero direction).
fn surface(globe: &GlobeTerrain, up: DVec3) -> Option<DVec3> {
    let above = globe.radius() + 2.0 * f64::from(globe.config().terrain.max_elevation) + 1.0;
    let hit = globe.raycast((up * above).to_array(), (-up).to_array(), f64::MAX)?;
    Some(DVec3::from_array(hit.point))
}

/// Where a tile's entity stands: the tile's center on the surface, lifted.
fn stand(globe: &GlobeTerrain, tile: GlobeTile, lift: f32) -> Option<DVec3> {
    let up = DVec3::from_array(globe.grid().center(tile)?);
    let info = globe.tile_info(tile)?;
    Some(up * (globe.radius() + f64::from(info.elevation) + f64::from(lift)))
}

/// Puts a transform at `at`, its `y` axis along the globe's up there.
fn put(transform: &mut Transform, at: DVec3) {
    let up = at.normalize().as_vec3();
    transform.translation = at.as_vec3();
    transform.rotation = Quat::from_rotation_arc(Vec3::Y, up);
}

/// Keeps [`OnGlobeTile`] entities on their tiles: all of them when the globe changed, else the
/// ones whose tile changed.
pub(super) fn place(
    globe: Res<HexGlobe>,
    mut entities: Query<(Ref<OnGlobeTile>, &mut Transform), Without<GlobeTileWalk>>,
    mut last: Local<Option<u64>>,
) {
    let Some(terrain) = globe.globe() else { return };
    let all = *last != Some(globe.generation());
    *last = Some(globe.generation());
    for (on, mut transform) in &mut entities {
        if (all || on.is_changed())
            && let Some(at) = stand(terrain, on.tile, on.lift)
        {
            put(&mut transform, at);
        }
    }
}

/// Walks [`GlobeTileWalk`]s: toward the next tile's center along the great circle, on the
/// surface as meshed.
pub(super) fn walk(
    mut commands: Commands,
    time: Res<Time>,
    globe: Res<HexGlobe>,
    mut entities: Query<(Entity, &mut OnGlobeTile, &mut GlobeTileWalk, &mut Transform)>,
    mut positions: Local<bevy::platform::collections::HashMap<Entity, DVec3>>,
) {
    let Some(terrain) = globe.globe() else { return };
    positions.retain(|e, _| entities.contains(*e));
    for (entity, mut on, mut walk, mut transform) in &mut entities {
        // Where the walk stands: kept between frames (the tile's center, which costs a noise
        // sample, is asked only when the walk starts).
        let here = match positions.get(&entity) {
            Some(&here) => here,
            None => {
                let Some(start) = stand(terrain, on.tile, on.lift) else { continue };
                start
            }
        };
        let mut budget = f64::from(walk.speed.max(0.0)) * time.delta_secs_f64();
        let mut at = here;
        while let Some(&next) = walk.path.first() {
            if next == on.tile {
                walk.path.remove(0);
                continue;
            }
            let Some(goal) = stand(terrain, next, on.lift) else {
                walk.path.clear();
                break;
            };
            // Along the great circle from here to the goal's direction, at the surface's radius.
            let (from, to) = (at.normalize(), goal.normalize());
            let angle = from.dot(to).clamp(-1.0, 1.0).acos();
            let arc = angle * terrain.radius();
            if arc <= budget {
                budget -= arc;
                at = goal;
                on.tile = next;
                walk.path.remove(0);
                continue;
            }
            // Neighbors' centers are never opposite: the axis is well defined.
            let axis = from.cross(to).normalize();
            let dir = DQuat::from_axis_angle(axis, budget / terrain.radius()) * from;
            at = surface(terrain, dir).map_or(dir * at.length(), |s| s + dir * f64::from(on.lift));
            break;
        }
        positions.insert(entity, at);
        put(&mut transform, at);
        if walk.path.is_empty() {
            positions.remove(&entity);
            commands.entity(entity).remove::<GlobeTileWalk>();
            commands.trigger(GlobeWalkEnded { entity, tile: on.tile });
        }
    }
}
