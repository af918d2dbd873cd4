//! The globe's `bevy_picking` backend (the `picking` feature): every pointer's ray cast on the
//! globe's surface as meshed with the core's exact ray cast ([`GlobeTerrain::raycast`], in f64,
//! pentagons as any tile), reported as [`PointerHits`] on the chunk entity showing the hit, with
//! a [`HexGlobePick`] (the tile) as the hit's extra data; and [`HoveredGlobeTile`], the tile
//! under the mouse. The flat map's [`HexPickingSettings`] and [`HexPickingCamera`] say which
//! cameras pick and how far.

use bevy::math::DVec3;
use bevy::picking::Pickable;
use bevy::picking::PickingSystems;
use bevy::picking::backend::ray::RayMap;
use bevy::picking::backend::{HitData, PointerHits};
use bevy::picking::hover::HoverMap;
use bevy::prelude::*;
use hex_terrain::{GlobeChunk, GlobeTerrain, GlobeTile};

use super::{GlobeStreamer, HexGlobe, HexGlobeChunk};
use crate::picking::{HexPickingCamera, HexPickingSettings, mouse_pick};

/// The extra data of every globe hit ([`HitData::extra_as`]): the tile under the pointer.
#[derive(Debug, Clone, Copy, PartialEq, Reflect)]
pub struct HexGlobePick {
    /// The tile hit (a pentagon as any other): ask [`GlobeTerrain::tile_info`] about it.
    pub tile: GlobeTile,
    /// The chunk whose entity was hit.
    pub chunk: GlobeChunk,
    /// World position of the hit, in f64 (the globe's center is the world's origin).
    pub world: DVec3,
}

/// The globe tile under the mouse pointer, for systems (observers read it from their event's
/// hit): the tile of the nearest globe hit Bevy's hover map holds for the mouse; `None` over the
/// sky, a UI node or a chunk not shown. Written only when the tile changes, so
/// `resource_changed::<HoveredGlobeTile>` means "the pointer moved to another tile".
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq, Reflect)]
#[reflect(Resource, Default)]
pub struct HoveredGlobeTile {
    tile: Option<GlobeTile>,
}

impl HoveredGlobeTile {
    /// The tile under the mouse pointer, if any.
    #[must_use]
    pub fn tile(&self) -> Option<GlobeTile> {
        self.tile
    }
}

/// Adds the backend to the globe plugin.
pub(super) fn build(app: &mut App) {
    app.init_resource::<HexPickingSettings>()
        .init_resource::<RayMap>()
        .add_message::<PointerHits>()
        .init_resource::<HoveredGlobeTile>()
        .register_type::<HexPickingSettings>()
        .register_type::<HexPickingCamera>()
        .register_type::<HoveredGlobeTile>()
        .add_systems(PreUpdate, pick_globe.in_set(PickingSystems::Backend))
        .add_systems(PreUpdate, follow_hover.after(PickingSystems::Hover));
}

/// Casts every pointer's ray on the globe and reports the hit on the chunk showing it.
fn pick_globe(
    settings: Res<HexPickingSettings>,
    rays: Res<RayMap>,
    cameras: Query<(&Camera, Has<HexPickingCamera>)>,
    globe: Res<HexGlobe>,
    streamer: Res<GlobeStreamer>,
    chunks: Query<(&HexGlobeChunk, Option<&Pickable>)>,
    mut hits: MessageWriter<PointerHits>,
) {
    let Some(globe) = globe.globe().filter(|_| settings.enabled && !rays.map.is_empty()) else { return };
    for (&id, ray) in rays.iter() {
        let Ok((camera, marked)) = cameras.get(id.camera) else { continue };
        if !camera.is_active || (settings.require_markers && !marked) {
            continue;
        }
        let Some((entity, depth, pick)) = pick(globe, &streamer, &chunks, *ray, settings.max_distance) else {
            continue;
        };
        let normal = pick.world.normalize().as_vec3();
        let hit = HitData::new_with_extra(id.camera, depth, Some(pick.world.as_vec3()), Some(normal), pick);
        hits.write(PointerHits::new(id.pointer, vec![(entity, hit)], camera.order as f32));
    }
}

/// The shown chunk entity a ray hits, with the depth and the pick. A chunk not shown (not
/// streamed in, its mesh not built) or not hoverable reports nothing.
fn pick(
    globe: &GlobeTerrain,
    streamer: &GlobeStreamer,
    chunks: &Query<(&HexGlobeChunk, Option<&Pickable>)>,
    ray: Ray3d,
    max_distance: f32,
) -> Option<(Entity, f32, HexGlobePick)> {
    let (origin, direction) = (ray.origin.as_dvec3(), ray.direction.as_dvec3());
    let hit = globe.raycast(origin.to_array(), direction.to_array(), f64::from(max_distance))?;
    let chunk = globe.chunk_of(hit.tile)?;
    let entity = streamer.chunk(chunk)?;
    let (shown, pickable) = chunks.get(entity).ok()?;
    if shown.generation.is_none() || pickable.is_some_and(|p| !p.is_hoverable) {
        return None;
    }
    Some((entity, hit.distance as f32, HexGlobePick { tile: hit.tile, chunk, world: DVec3::from_array(hit.point) }))
}

/// Sets [`HoveredGlobeTile`] from the mouse's hovered entities: the nearest hit with a tile.
fn follow_hover(hover: Option<Res<HoverMap>>, mut hovered: ResMut<HoveredGlobeTile>) {
    let tile = mouse_pick(hover.as_deref(), |pick: &HexGlobePick| pick.tile);
    hovered.set_if_neq(HoveredGlobeTile { tile });
}
