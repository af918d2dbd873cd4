//! The terrain's `bevy_picking` backend (the `picking` feature): see [`HexPickingPlugin`].

use bevy::camera::primitives::MeshAabb;
use bevy::ecs::system::SystemParam;
use bevy::math::DVec3;
use bevy::picking::Pickable;
use bevy::picking::PickingSystems;
use bevy::picking::backend::ray::RayMap;
use bevy::picking::backend::{HitData, PointerHits};
use bevy::picking::hover::HoverMap;
use bevy::picking::pointer::PointerId;
use bevy::prelude::*;
use hex_terrain::ChunkCoord;
use hex_terrain::hexx::Hex;

use crate::map::HexMap;
use crate::props::HexProp;
use crate::streaming::ChunkStreamer;
use crate::water::HexWater;

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
#[derive(Resource, Debug, Clone, PartialEq, Reflect)]
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

/// Figures of the picking backend: how many pointer rays it cast and the time it took (what a
/// pick costs in a game, props and water surfaces included).
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource)]
pub struct HexPickingStats {
    /// Pointer rays cast since the start.
    pub picks: u64,
    /// Time spent casting them.
    pub time: std::time::Duration,
}

/// The tile under the mouse pointer, for systems (observers read the tile from their event's
/// hit): the tile of the nearest terrain hit Bevy's hover map holds for the mouse (the ground, a
/// prop or the water surface). `None` when no terrain is under the pointer: the sky, a UI node,
/// a chunk not loaded, or an entity in front that blocks what is behind it (a unit with
/// `MeshPickingPlugin`). Updated in `PreUpdate` after [`PickingSystems::Hover`], and written only
/// when the tile changes, so `resource_changed::<HoveredTile>` means "the pointer moved to
/// another tile".
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq, Reflect)]
#[reflect(Resource, Default)]
pub struct HoveredTile {
    tile: Option<Hex>,
}

impl HoveredTile {
    /// The tile under the mouse pointer (the map's own tile on a wrapping map), if any.
    #[must_use]
    pub fn tile(&self) -> Option<Hex> {
        self.tile
    }
}

/// Marks a camera that picks the terrain when [`HexPickingSettings::require_markers`] is on.
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexPickingCamera;

/// The terrain picking backend: [`HexPickingSettings`] and a system in
/// [`PickingSystems::Backend`]. Part of [`HexTerrainPlugins`](crate::HexTerrainPlugins); Bevy's
/// picking plugins (in `DefaultPlugins`) turn its hits into pointer events.
///
/// A [`bevy_picking`](bevy::picking) backend for the terrain (the `picking` cargo feature):
/// every pointer's ray from Bevy's [`RayMap`] is cast on the real surface with the core's exact
/// ray cast (the answer [`HexMap::raycast`] gives, in f64, so it holds far from the origin and
/// with `big_space`), and the hit is reported as [`PointerHits`] on the chunk entity showing it,
/// with the depth, the position, the surface normal and, as the hit's extra data, a [`HexPick`]:
/// the tile. Bevy's hover and pointer events do the rest: an observer on chunks (or a global
/// one) receives `Pointer<Over>`, `Pointer<Move>`, `Pointer<Click>`, `Pointer<Drag>` and the
/// others, and reads the tile from the event's hit:
///
/// ```no_run
/// use bevy::picking::events::{Click, Pointer};
/// use bevy::prelude::*;
/// use bevy_hex_terrain::HexPick;
///
/// fn on_click(click: On<Pointer<Click>>) {
///     if let Some(pick) = click.hit.extra_as::<HexPick>() {
///         info!("clicked tile {:?}", pick.tile);
///     }
/// }
/// # App::new().add_observer(on_click);
/// ```
///
/// What stands on the terrain is hit too, before the ground behind it: a prop ([`HexProp`]: a
/// tree, a rock, reeds; its mesh's bounding box, or a unit box when it has no mesh) is reported
/// on the prop entity with the tile it stands on, and the sea's water surface ([`HexWater`]) on
/// the water entity with the tile under the surface point. Both are children of their chunk, so
/// Bevy's event bubbling brings their events to observers on the chunk too (a global observer
/// sees each step: compare `event_target()` with `original_event_target()` to act once). A
/// hidden prop (under fog of war) is not hit; a chunk, prop or water surface with
/// [`Pickable::IGNORE`] is not hit (the ray goes on to what is behind it); an entity in front of
/// the terrain that another backend reports (a unit, with `MeshPickingPlugin`) comes first by
/// Bevy's depth order and blocks the terrain behind it unless its `Pickable` says otherwise.
/// Only loaded chunks are hit: a ray to a chunk not streamed in reports nothing.
///
/// A system that wants the tile under the mouse reads [`HoveredTile`].
///
/// Its settings are the [`HexPickingSettings`] resource: a value inserted before the plugin is
/// added is kept.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexPickingPlugin;

impl Plugin for HexPickingPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<crate::HexMapPlugin>() {
            panic!("HexPickingPlugin needs HexMapPlugin: add HexTerrainPlugins (or HexMapPlugin before it)");
        }
        app.init_resource::<HexPickingSettings>()
            .init_resource::<RayMap>()
            .add_message::<PointerHits>()
            .init_resource::<HexPickingStats>()
            .register_type::<HexPickingSettings>()
            .register_type::<HexPickingStats>()
            .register_type::<HexPickingCamera>()
            .init_resource::<HoveredTile>()
            .register_type::<HoveredTile>()
            .add_systems(PreUpdate, pick_terrain.in_set(PickingSystems::Backend))
            .add_systems(PreUpdate, follow_hover.after(PickingSystems::Hover));
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

/// What a ray can hit: the map, the loaded chunks, what stands on them and their `Pickable`s, in
/// the render frame.
#[derive(SystemParam)]
struct Targets<'w, 's> {
    map: Res<'w, HexMap>,
    streamer: Res<'w, ChunkStreamer>,
    pickables: Query<'w, 's, &'static Pickable>,
    frame: FrameOrigin<'w, 's>,
    children: Query<'w, 's, &'static Children>,
    props: Query<'w, 's, (&'static HexProp, &'static GlobalTransform, &'static Visibility, Option<&'static Mesh3d>)>,
    water: Query<'w, 's, &'static Visibility, With<HexWater>>,
    meshes: Option<Res<'w, Assets<Mesh>>>,
}

impl Targets<'_, '_> {
    /// Whether an entity takes hits (no `Pickable`, or a hoverable one).
    fn hoverable(&self, entity: Entity) -> bool {
        !self.pickables.get(entity).is_ok_and(|p| !p.is_hoverable)
    }

    /// The nearest prop or sea surface the render-frame ray meets before `limit`: its entity,
    /// depth, normal and pick.
    fn standing(
        &self,
        origin: Vec3,
        direction: Vec3,
        offset: DVec3,
        limit: f32,
        boxes: &mut MeshBoxes,
    ) -> Option<(Entity, f32, Vec3, HexPick)> {
        let map = &self.map;
        let terrain = map.terrain();
        let mut best: Option<(Entity, f32, Vec3, HexPick)> = None;
        // The sea's surface, where the ground lies under it.
        let sea = f64::from(terrain.sea_level()) - offset.y;
        if direction.y < 0.0 {
            let t = ((sea - f64::from(origin.y)) / f64::from(direction.y)) as f32;
            let at = (origin + direction * t).as_dvec3() + DVec3::new(offset.x, 0.0, offset.z);
            let world = DVec3::new(at.x, terrain.sea_level().into(), at.z);
            if t >= 0.0
                && t < limit
                && let Some(tile) =
                    map.tile_at_f64(world).filter(|&t| map.tile_kind(t) == Some(hex_terrain::TileKind::Sea))
                && let Some(water) =
                    self.chunk_child(world, |e| self.water.get(e).is_ok_and(|v| v != Visibility::Hidden))
            {
                let chunk = map.chunk_of(map.terrain().unwrapped_tile_at(world.x, world.z)?)?;
                best = Some((water, t, Vec3::Y, HexPick { tile, chunk, world }));
            }
        }
        // Props of the chunks the ray crosses below the top of the relief and its props.
        let max = terrain.config().terrain.max_elevation * 2.0 + 4.0 * terrain.config().layout.hex_size;
        let (low, high) = (-offset.y as f32 - 1.0, max - offset.y as f32);
        let span = |y: f32| if direction.y.abs() < 1e-9 { 0.0 } else { (y - origin.y) / direction.y };
        let (mut t0, mut t1) = (span(high).min(span(low)).max(0.0), span(high).max(span(low)));
        if direction.y.abs() < 1e-9 {
            (t0, t1) = (0.0, limit);
        }
        let t1 = t1.min(limit.min(best.map_or(f32::MAX, |b| b.1)));
        let step = terrain.config().layout.hex_size.max(1e-3);
        let mut chunks: Vec<ChunkCoord> = Vec::new();
        let samples = (((t1 - t0) / step).ceil() as u32).min(4096);
        for k in 0..=samples {
            let p = (origin + direction * (t0 + (t1 - t0) * k as f32 / samples.max(1) as f32)).as_dvec3() + offset;
            if let Some(tile) = terrain.unwrapped_tile_at(p.x, p.z) {
                for c in std::iter::once(tile).chain(tile.all_neighbors()).filter_map(|t| map.chunk_of(t)) {
                    if !chunks.contains(&c) {
                        chunks.push(c);
                    }
                }
            }
        }
        for chunk in chunks {
            let Some(entity) = self.streamer.entity(chunk).filter(|_| self.streamer.is_chunk_loaded(chunk)) else {
                continue;
            };
            let Ok(children) = self.children.get(entity) else { continue };
            for &child in children {
                let Ok((prop, transform, visibility, mesh)) = self.props.get(child) else { continue };
                if *visibility == Visibility::Hidden || !self.hoverable(child) {
                    continue;
                }
                let (min, max) = mesh.and_then(|m| self.mesh_box(&m.0, boxes)).unwrap_or(UNIT_BOX);
                let inverse = transform.affine().inverse();
                let (o, d) = (inverse.transform_point3(origin), inverse.transform_vector3(direction));
                let Some(t) = slab(o, d, min, max).filter(|&t| t < best.map_or(limit, |b| b.1)) else { continue };
                let world = (origin + direction * t).as_dvec3() + offset;
                best = Some((child, t, (-direction).normalize_or_zero(), HexPick { tile: prop.tile, chunk, world }));
            }
        }
        best
    }

    /// The bounding box of a prop mesh, computed once a mesh.
    fn mesh_box(&self, mesh: &Handle<Mesh>, boxes: &mut MeshBoxes) -> Option<(Vec3, Vec3)> {
        if let Some(&b) = boxes.get(&mesh.id()) {
            return Some(b);
        }
        let aabb = self.meshes.as_ref()?.get(mesh)?.compute_aabb()?;
        let b = (Vec3::from(aabb.min()), Vec3::from(aabb.max()));
        boxes.insert(mesh.id(), b);
        Some(b)
    }

    /// The child of the loaded chunk under `world` that `wanted` accepts and takes hits.
    fn chunk_child(&self, world: DVec3, wanted: impl Fn(Entity) -> bool) -> Option<Entity> {
        let chunk = self.map.chunk_of(self.map.terrain().unwrapped_tile_at(world.x, world.z)?)?;
        let entity = self.streamer.entity(chunk).filter(|_| self.streamer.is_chunk_loaded(chunk))?;
        self.children.get(entity).ok()?.iter().find(|&e| wanted(e) && self.hoverable(e))
    }
}

/// The bounding boxes of the prop meshes seen so far (props share a few meshes).
type MeshBoxes = bevy::platform::collections::HashMap<AssetId<Mesh>, (Vec3, Vec3)>;

/// A prop without a mesh (headless): a unit box standing on its position, in its scale.
const UNIT_BOX: (Vec3, Vec3) = (Vec3::new(-0.5, 0.0, -0.5), Vec3::new(0.5, 1.0, 0.5));

/// The entry depth of a ray into a box (0 when it starts inside), if it meets it.
fn slab(origin: Vec3, direction: Vec3, min: Vec3, max: Vec3) -> Option<f32> {
    let inv = direction.recip();
    let (a, b) = ((min - origin) * inv, (max - origin) * inv);
    let (near, far) = (a.min(b).max_element().max(0.0), a.max(b).min_element());
    (near <= far && far.is_finite() && near.is_finite()).then_some(near)
}

/// Casts every pointer's ray on the terrain and reports the hit on the chunk showing it.
fn pick_terrain(
    settings: Res<HexPickingSettings>,
    rays: Res<RayMap>,
    cameras: Query<(&Camera, Has<HexPickingCamera>)>,
    targets: Targets,
    mut hits: MessageWriter<PointerHits>,
    mut boxes: Local<MeshBoxes>,
    mut stats: ResMut<HexPickingStats>,
) {
    if !settings.enabled || rays.map.is_empty() {
        return;
    }
    let start = std::time::Instant::now();
    let mut picks = 0;
    let (map, streamer, pickables) = (&targets.map, &targets.streamer, &targets.pickables);
    let offset = targets.frame.world();
    for (&id, ray) in rays.iter() {
        let Ok((camera, marked)) = cameras.get(id.camera) else { continue };
        if !camera.is_active || (settings.require_markers && !marked) {
            continue;
        }
        picks += 1;
        let (origin, direction) = (ray.origin.as_dvec3() + offset, ray.direction.as_dvec3());
        let ground = pick(map, streamer, origin, direction, settings.max_distance)
            .filter(|p| !pickables.get(p.0).is_ok_and(|p| !p.is_hoverable));
        let limit = ground.map_or(settings.max_distance, |g| g.1);
        let standing = targets.standing(ray.origin, *ray.direction, offset, limit, &mut boxes);
        let Some((entity, depth, normal, data)) = standing.or(ground) else { continue };
        let hit = HitData::new_with_extra(id.camera, depth, Some((data.world - offset).as_vec3()), Some(normal), data);
        hits.write(PointerHits::new(id.pointer, vec![(entity, hit)], camera.order as f32));
    }
    if picks > 0 {
        stats.picks += picks;
        stats.time += start.elapsed();
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
    let chunk = map.chunk_of(map.terrain().unwrapped_tile_at(hit.point.x, hit.point.z)?)?;
    let entity = streamer.entity(chunk).filter(|_| streamer.is_chunk_loaded(chunk))?;
    let normal = map.surface_normal_f64(hit.point)?.as_vec3();
    Some((entity, hit.distance as f32, normal, HexPick { tile: hit.tile, chunk, world: hit.point }))
}

/// Sets [`HoveredTile`] from the mouse's hovered entities: the nearest hit that carries a tile.
fn follow_hover(hover: Option<Res<HoverMap>>, mut hovered: ResMut<HoveredTile>) {
    let tile = mouse_pick(hover.as_deref(), |pick: &HexPick| pick.tile);
    hovered.set_if_neq(HoveredTile { tile });
}

/// What `read` reads of the nearest of the mouse's hovered hits whose extra data is a `P` (the
/// flat map's and the globe's picks).
pub(crate) fn mouse_pick<P: std::any::Any, T>(hover: Option<&HoverMap>, read: impl Fn(&P) -> T) -> Option<T> {
    let hits = hover?.get(&PointerId::Mouse)?;
    hits.values()
        .filter_map(|hit| hit.extra_as::<P>().map(|pick| (hit.depth, read(pick))))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, value)| value)
}
