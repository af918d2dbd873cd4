//! A [`bevy_picking`](bevy::picking) backend for the terrain (the `picking` cargo feature):
//! every pointer's ray from Bevy's [`RayMap`] is cast on the real surface with the core's exact
//! ray cast (the answer [`HexMap::raycast`] gives, in f64, so it holds far from the origin and
//! with `big_space`), and the hit is reported as [`PointerHits`] on the chunk entity showing it,
//! with the depth, the position, the surface normal and, as the hit's extra data, a [`HexPick`]:
//! the tile. Bevy's hover and pointer events do the rest: an observer on chunks (or a global
//! one) receives `Pointer<Over>`, `Pointer<Move>`, `Pointer<Click>`, `Pointer<Drag>` and the
//! others, and reads the tile from the event's hit:
//!
//! ```no_run
//! use bevy::picking::events::{Click, Pointer};
//! use bevy::prelude::*;
//! use bevy_hex_terrain::HexPick;
//!
//! fn on_click(click: On<Pointer<Click>>) {
//!     if let Some(pick) = click.hit.extra_as::<HexPick>() {
//!         info!("clicked tile {:?}", pick.tile);
//!     }
//! }
//! # App::new().add_observer(on_click);
//! ```
//!
//! A chunk with [`Pickable::IGNORE`] is not hit; an entity in front of the terrain that another
//! backend reports (a unit, with `MeshPickingPlugin`) comes first by Bevy's depth order and
//! blocks the terrain behind it unless its `Pickable` says otherwise. Only loaded chunks are hit:
//! a ray to a chunk not streamed in reports nothing.

use bevy::ecs::system::SystemParam;
use bevy::math::DVec3;
use bevy::picking::Pickable;
use bevy::picking::PickingSystems;
use bevy::picking::backend::ray::RayMap;
use bevy::picking::backend::{HitData, PointerHits};
use bevy::prelude::*;
use hex_terrain::ChunkCoord;
use hex_terrain::hexx::Hex;

use crate::map::HexMap;
use crate::streaming::ChunkStreamer;

/// The extra data of every terrain hit ([`HitData::extra_as`]): the tile under the pointer.
#[derive(Debug, Clone, Copy, PartialEq, Reflect)]
pub struct HexPick {
    /// The tile hit (the map's own tile on a wrapping map): ask [`HexMap::tile_info`] about it.
    pub tile: Hex,
    /// The chunk whose entity was hit (on a wrapping map, the copy under the pointer).
    pub chunk: ChunkCoord,
    /// World position of the hit, in f64 (with `big_space`, in the grid's frame rather than the
    /// floating origin's).
    pub world: DVec3,
}

/// The picking backend's settings.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource)]
pub struct HexPickingSettings {
    /// Cast pointer rays on the terrain.
    pub enabled: bool,
    /// Only cameras with [`HexPickingCamera`] pick the terrain (otherwise every active camera).
    pub require_markers: bool,
    /// Longest ray, in world units.
    pub max_distance: f32,
}

impl Default for HexPickingSettings {
    fn default() -> Self {
        Self { enabled: true, require_markers: false, max_distance: 1e5 }
    }
}

/// Marks a camera that picks the terrain when [`HexPickingSettings::require_markers`] is on.
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexPickingCamera;

/// The terrain picking backend: [`HexPickingSettings`] and a system in
/// [`PickingSystems::Backend`]. Part of [`HexTerrainPlugins`](crate::HexTerrainPlugins); Bevy's
/// picking plugins (in `DefaultPlugins`) turn its hits into pointer events.
#[derive(Debug, Clone, Default)]
pub struct HexPickingPlugin {
    /// The backend's settings (the [`HexPickingSettings`] resource).
    pub settings: HexPickingSettings,
}

impl Plugin for HexPickingPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexMapPlugin>() {
            panic!("HexPickingPlugin needs HexMapPlugin: add HexTerrainPlugins (or HexMapPlugin before it)");
        }
        app.insert_resource(self.settings.clone())
            .init_resource::<RayMap>()
            .add_message::<PointerHits>()
            .register_type::<HexPickingSettings>()
            .register_type::<HexPickingCamera>()
            .add_systems(PreUpdate, pick_terrain.in_set(PickingSystems::Backend));
    }
}

/// Where the render frame's origin lies in the world: zero, or with `big_space` the floating
/// origin's cell.
#[derive(SystemParam)]
pub struct FrameOrigin<'w, 's> {
    #[cfg(feature = "big_space")]
    origins: Query<
        'w,
        's,
        (&'static big_space::prelude::CellCoord, &'static ChildOf),
        With<big_space::prelude::FloatingOrigin>,
    >,
    #[cfg(feature = "big_space")]
    grids: Query<'w, 's, &'static big_space::prelude::Grid>,
    #[cfg(not(feature = "big_space"))]
    _unused: std::marker::PhantomData<(&'w (), &'s ())>,
}

impl FrameOrigin<'_, '_> {
    /// The world position (f64) of the render frame's origin.
    #[must_use]
    pub fn world(&self) -> DVec3 {
        #[cfg(feature = "big_space")]
        if let Ok((cell, parent)) = self.origins.single()
            && let Ok(grid) = self.grids.get(parent.parent())
        {
            return grid.cell_to_float(cell);
        }
        DVec3::ZERO
    }
}

/// What a ray can hit: the map, the loaded chunks and their `Pickable`s, in the render frame.
#[derive(SystemParam)]
struct Targets<'w, 's> {
    map: Res<'w, HexMap>,
    streamer: Res<'w, ChunkStreamer>,
    pickables: Query<'w, 's, &'static Pickable>,
    frame: FrameOrigin<'w, 's>,
}

/// Casts every pointer's ray on the terrain and reports the hit on the chunk showing it.
fn pick_terrain(
    settings: Res<HexPickingSettings>,
    rays: Res<RayMap>,
    cameras: Query<(&Camera, Has<HexPickingCamera>)>,
    targets: Targets,
    mut hits: MessageWriter<PointerHits>,
) {
    if !settings.enabled {
        return;
    }
    let (map, streamer, pickables) = (&targets.map, &targets.streamer, &targets.pickables);
    let offset = targets.frame.world();
    for (&id, ray) in rays.iter() {
        let Ok((camera, marked)) = cameras.get(id.camera) else { continue };
        if !camera.is_active || (settings.require_markers && !marked) {
            continue;
        }
        let (origin, direction) = (ray.origin.as_dvec3() + offset, ray.direction.as_dvec3());
        let Some(pick) = pick(map, streamer, origin, direction, settings.max_distance) else { continue };
        if pickables.get(pick.0).is_ok_and(|p| !p.is_hoverable) {
            continue;
        }
        let (entity, depth, normal, data) = pick;
        let hit = HitData::new_with_extra(id.camera, depth, Some((data.world - offset).as_vec3()), Some(normal), data);
        hits.write(PointerHits::new(id.pointer, vec![(entity, hit)], camera.order as f32));
    }
}

/// The loaded chunk entity a ray hits, with the depth, the normal and the pick.
fn pick(
    map: &HexMap,
    streamer: &ChunkStreamer,
    origin: DVec3,
    direction: DVec3,
    max_distance: f32,
) -> Option<(Entity, f32, Vec3, HexPick)> {
    let hit = map.raycast_f64(origin, direction, f64::from(max_distance))?;
    // The chunk under the hit, not wrapped: east of a wrapping map's edge it is the copy there.
    let chunk = map.chunk_of(map.terrain().unwrapped_tile_at(hit.point.x, hit.point.z)?);
    let entity = streamer.entity(chunk).filter(|_| streamer.is_chunk_loaded(chunk))?;
    let normal = map.surface_normal_f64(hit.point)?.as_vec3();
    Some((entity, hit.distance as f32, normal, HexPick { tile: hit.tile, chunk, world: hit.point }))
}
