//! Props on the terrain: each chunk's trees, rocks and reeds ([`hex_terrain::Terrain::props`],
//! placed in the chunk's task) become child entities of the chunk, spawned a budget a frame
//! (nearest chunks first) and despawned with it (a budget a frame too, see
//! [`HexStreamingSettings::max_despawns_per_frame`](crate::HexStreamingSettings::max_despawns_per_frame)).
//! Each prop is spawned whole, into a table given room before the first prop for every prop
//! the chunks streaming keeps can hold, so the table does not grow (copying every prop in one
//! frame) while the world fills.
//! With Bevy's renderer, every prop of a kind and variant shares one mesh and all share one
//! vertex-colored material: Bevy batches them into instanced draws (a handful of draws for
//! thousands of props). Headless, the entities exist without meshes (games and tests can read
//! them). The game setup's resources and natural wonders ([`hex_terrain::Terrain::marker_props`])
//! are props too ([`PropKind::Resource`], [`PropKind::Wonder`]): drawn, picked and hidden by fog
//! the same way. Under fog of war, props on unexplored tiles are hidden. How many stand is the
//! plugin's [`HexPropSettings`].

#[cfg(feature = "render")]
mod fog;
#[cfg(feature = "render")]
mod meshes;
mod settings;

use std::collections::{HashMap, VecDeque};
use std::marker::PhantomData;

use bevy::ecs::bundle::NoBundleEffect;
use bevy::prelude::*;
#[cfg(feature = "render")]
use hex_terrain::PROP_VARIANTS;
use hex_terrain::{Detail, Prop, PropKind};

#[cfg(feature = "render")]
pub(crate) use fog::{PropsByTile, fog_change, show};
pub use settings::HexPropSettings;

use crate::HexTerrainSystems;
use crate::streaming::ContentRequest;
use crate::streaming::content::{ContentQuery, stale_chunks};

/// A prop entity (a child of its chunk).
#[derive(Component, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Component)]
#[require(Transform)]
#[cfg_attr(feature = "render", require(Visibility))]
pub struct HexProp {
    /// What it is.
    pub kind: PropKind,
    /// Which of the kind's meshes.
    pub variant: u8,
    /// The tile it stands on (map-local axial coordinate).
    pub tile: hex_terrain::hexx::Hex,
}

/// The shared meshes (by kind and variant) and material of the props, with Bevy's renderer.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource, Debug)]
pub struct PropAssets {
    /// `meshes[kind as usize][variant]`.
    pub meshes: Vec<Vec<Handle<Mesh>>>,
    /// The far meshes, for props on chunks drawn coarse (far from every camera): the same shapes
    /// with a third of the faces or fewer, `far_meshes[kind as usize][variant]`.
    pub far_meshes: Vec<Vec<Handle<Mesh>>>,
    /// The one material every prop uses (white base, vertex colors).
    #[cfg(feature = "render")]
    pub material: Handle<StandardMaterial>,
    /// The bounding box of each of `meshes`, `aabbs[kind as usize][variant]`: a prop is spawned
    /// with it, so Bevy does not add one later (which would move every prop to another table).
    #[cfg(feature = "render")]
    pub aabbs: Vec<Vec<bevy::camera::primitives::Aabb>>,
}

/// Spawns and despawns the props of loaded chunks ([`HexProp`] children, in
/// [`HexTerrainSystems::Children`]), owns [`HexPropSettings`] (without this plugin, chunk tasks
/// place no props) and hides props on unexplored tiles while the
/// [`HexTileStateStyle`](crate::HexTileStateStyle) draws fog of war. Part of
/// [`HexTerrainPlugins`](crate::HexTerrainPlugins); works headless.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexPropsPlugin;

impl Plugin for HexPropsPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<HexPropSettings>()
            .init_resource::<ContentRequest>()
            .init_resource::<HexPropStats>()
            .register_type::<HexPropSettings>()
            .register_type::<HexProp>()
            .register_type::<HexPropStats>()
            .register_type::<PropAssets>()
            .add_systems(
                Update,
                (
                    // Before tasks start: they place props as the settings ask.
                    request_props.run_if(resource_changed::<HexPropSettings>).before(HexTerrainSystems::Stream),
                    sync_props.in_set(HexTerrainSystems::Children),
                ),
            );
        // After every game system's writes of the frame, before their list starts again.
        #[cfg(feature = "render")]
        app.add_systems(PostUpdate, fog::hide_unexplored.before(crate::tiles::HexTileStateSystems::Pack));
        #[cfg(feature = "render")]
        app.configure_sets(
            PostUpdate,
            crate::tiles::HexTileStateSystems::Pack
                .before(bevy::camera::visibility::VisibilitySystems::VisibilityPropagate),
        );
        #[cfg(feature = "render")]
        if app.is_plugin_added::<bevy::pbr::PbrPlugin>() {
            app.add_systems(Startup, create_assets);
        }
    }
}

/// Makes the [`PropAssets`] once (the flat map's props plugin and the globe's plugin both ask).
#[cfg(feature = "render")]
pub(crate) fn create_assets(mut commands: Commands) {
    commands.queue(|world: &mut World| {
        if !world.contains_resource::<PropAssets>() {
            world.run_system_cached(make_assets).expect("the prop assets' system runs");
        }
    });
}

#[cfg(feature = "render")]
fn make_assets(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    use bevy::camera::primitives::MeshAabb;
    let build = |make: fn(PropKind, u8) -> Mesh| -> Vec<Vec<Mesh>> {
        PropKind::ALL.iter().map(|&kind| (0..PROP_VARIANTS).map(|v| make(kind, v)).collect()).collect()
    };
    let (near, far) = (build(meshes::prop_mesh), build(meshes::prop_mesh_far));
    let aabbs = near.iter().map(|row| row.iter().map(|m| m.compute_aabb().unwrap_or_default()).collect()).collect();
    let mut add = |all: Vec<Vec<Mesh>>| -> Vec<Vec<Handle<Mesh>>> {
        all.into_iter().map(|row| row.into_iter().map(|m| meshes.add(m)).collect()).collect()
    };
    let (near, far_meshes) = (add(near), add(far));
    let material = materials.add(StandardMaterial { perceptual_roughness: 0.9, reflectance: 0.15, ..default() });
    commands.insert_resource(PropAssets { meshes: near, far_meshes, material, aabbs });
}

/// Asks chunk tasks for props at the settings' cap and density.
fn request_props(settings: Res<HexPropSettings>, mut request: ResMut<ContentRequest>) {
    request.props = Some((settings.max_per_chunk, settings.density));
}

/// A prop entity as spawned with Bevy's renderer and the prop assets: its mesh, material and
/// box, and its chunk.
#[cfg(feature = "render")]
type DrawnProp =
    (HexProp, Transform, Mesh3d, MeshMaterial3d<StandardMaterial>, bevy::camera::primitives::Aabb, ChildOf);
/// A prop entity as spawned headless: what it is, where, and its chunk.
type BareProp = (HexProp, Transform, ChildOf);

/// The props' entities of one chunk (children of it, in `props`' order), with the far meshes on
/// a chunk drawn coarse: one batch, every prop spawned whole (one table row each, no move).
fn spawn_props(
    commands: &mut Commands,
    chunk: Entity,
    props: &[Prop],
    size: f32,
    assets: Option<&PropAssets>,
    far: bool,
) {
    let bare = |p: &Prop| {
        let transform = Transform::from_translation(Vec3::from_array(p.position))
            .with_rotation(Quat::from_rotation_y(p.yaw))
            .with_scale(Vec3::splat(p.scale * size));
        (HexProp { kind: p.kind, variant: p.variant, tile: p.tile }, transform, p.kind, p.variant)
    };
    spawn_batch(commands, chunk, props.iter().map(bare).collect(), assets, far);
}

/// Spawns props as children of `chunk`, each its component, transform, kind and variant: with
/// Bevy's renderer and the prop assets, with its kind's mesh (the far one when `far`), the one
/// material and its box; headless, bare. One batch, every prop spawned whole. A flat map's props
/// and a globe's alike.
pub(crate) fn spawn_batch<C: Component>(
    commands: &mut Commands,
    chunk: Entity,
    props: Vec<(C, Transform, PropKind, u8)>,
    assets: Option<&PropAssets>,
    far: bool,
) {
    #[cfg(feature = "render")]
    if let Some(assets) = assets {
        let meshes = if far { &assets.far_meshes } else { &assets.meshes };
        let drawn: Vec<_> = props
            .into_iter()
            .map(|(prop, transform, kind, variant)| {
                let (kind, variant) = (kind as usize, usize::from(variant % PROP_VARIANTS));
                let mesh = Mesh3d(meshes[kind][variant].clone());
                let material = MeshMaterial3d(assets.material.clone());
                (prop, transform, mesh, material, assets.aabbs[kind][variant], ChildOf(chunk))
            })
            .collect();
        commands.spawn_batch(drawn);
        return;
    }
    #[cfg(not(feature = "render"))]
    let _ = (assets, far);
    commands.spawn_batch(
        props.into_iter().map(|(prop, transform, ..)| (prop, transform, ChildOf(chunk))).collect::<Vec<_>>(),
    );
}

/// The most props [`sync_props`] makes room for ahead (a few hundred bytes of address space a
/// prop, which the system backs with memory only as props are written); beyond it the table
/// grows as Bevy grows it.
const MAX_ROOM: usize = 1 << 18;

/// Makes room for at least `additional` more props in the table their entities are spawned
/// into (and as many entity slots), in one allocation: without it, Bevy doubles the table as
/// props come, and the doubling that copies some 16,000 props costs one frame milliseconds.
fn make_room(commands: &mut Commands, additional: usize, assets: Option<&PropAssets>) {
    #[cfg(feature = "render")]
    if assets.is_some() {
        commands.queue(move |world: &mut World| room_for::<DrawnProp>(world, additional));
        return;
    }
    #[cfg(not(feature = "render"))]
    let _ = assets;
    commands.queue(move |world: &mut World| room_for::<BareProp>(world, additional));
}

/// Room for `additional` more entities of bundle `B`: `World::spawn_batch` reserves its table
/// (and entity slots) for the most its iterator says it may yield, and [`Room`] yields none.
/// Bevy 0.19 has no other public way to reserve a table.
fn room_for<B: Bundle<Effect: NoBundleEffect>>(world: &mut World, additional: usize) {
    world.spawn_batch(Room::<B>(additional, PhantomData));
}

/// An iterator of no bundles that says it may yield `.0` of them (see [`room_for`]).
struct Room<B>(usize, PhantomData<fn() -> B>);

impl<B> Iterator for Room<B> {
    type Item = B;

    fn next(&mut self) -> Option<B> {
        None
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (0, Some(self.0))
    }
}

/// What [`sync_props`] remembers between frames: whether props were shown, the chunks whose
/// props wait to be spawned (with the index of the next), the map generation and level of
/// each chunk's props, and the props the table was last given room for.
#[derive(Default)]
struct Spawning {
    was_enabled: Option<bool>,
    queue: VecDeque<(Entity, usize)>,
    shown: HashMap<Entity, (Option<u64>, Detail)>,
    room: usize,
}

/// The prop entities, as [`sync_props`] reads and moves them.
type PropQuery<'w, 's> = Query<'w, 's, (&'static HexProp, &'static mut Transform, PropMesh)>;

/// A prop's mesh, with Bevy's renderer (none headless).
#[cfg(feature = "render")]
type PropMesh = Option<&'static mut Mesh3d>;
/// A prop's mesh, with Bevy's renderer (none headless).
#[cfg(not(feature = "render"))]
type PropMesh = ();

/// Keeps each chunk's prop children in step with its [`ChunkContent`](crate::ChunkContent) and the settings: a chunk
/// whose content changed (a new mesh, a hot reload) gets its props anew; turning props off or on
/// despawns or spawns them everywhere. Spawning is queued, chunk by chunk, the chunks nearest an
/// agent first, at most [`HexPropSettings::max_spawns_per_frame`] props a frame. A chunk that only
/// changed level of detail keeps its prop entities: they move to the new surface and take the
/// level's meshes, in place.
fn sync_props(
    mut commands: Commands,
    (settings, map, assets): (Res<HexPropSettings>, Res<crate::HexMap>, Option<Res<PropAssets>>),
    (streamer, streaming, agents): (
        Option<Res<crate::ChunkStreamer>>,
        Option<Res<crate::HexStreamingSettings>>,
        Query<&crate::HexTerrainAgent>,
    ),
    (chunks, coords): (ContentQuery, Query<&crate::HexChunk>),
    mut props: PropQuery,
    mut spawning: Local<Spawning>,
    mut stats: ResMut<HexPropStats>,
) {
    let Spawning { was_enabled, queue, shown, room } = &mut *spawning;
    let enabled = settings.enabled;
    let size = map.config().layout.hex_size;
    // Whether a chunk's props were queued this frame (the room is looked at only then).
    let mut queued = false;
    for (chunk, content, old) in stale_chunks(&chunks, |e| props.contains(e), enabled, was_enabled) {
        let now = coords.get(chunk).ok().map(|c| (c.generation, c.detail));
        // Only the level changed (same map generation, another detail): the same props on
        // another surface (see `Terrain::props_on`), moved in place.
        let level_change = enabled && now.is_some_and(|(g, d)| shown.get(&chunk).is_some_and(|s| s.0 == g && s.1 != d));
        let far = now.is_some_and(|(_, d)| d == Detail::Coarse);
        if level_change && relevel(&mut props, &old, &content.props, far, assets.as_deref()) {
            shown.insert(chunk, now.unwrap_or_default());
            continue;
        }
        queue.retain(|&(e, _)| e != chunk);
        for prop in old {
            commands.entity(prop).despawn();
        }
        match now {
            Some(now) if enabled => {
                shown.insert(chunk, now);
                queue.push_back((chunk, 0));
                queued = true;
            }
            _ => {
                shown.remove(&chunk);
            }
        }
    }
    if !enabled {
        queue.clear();
    }
    shown.retain(|&chunk, _| coords.contains(chunk));
    // The chunks nearest an agent first (those in view), the order they came in among equals.
    if let Some(streamer) = &streamer
        && queue.len() > 1
    {
        let distance =
            |e: Entity| coords.get(e).ok().and_then(|c| streamer.wanted_distance(c.coord)).unwrap_or(u32::MAX);
        queue.make_contiguous().sort_by_key(|&(e, _)| distance(e));
    }
    // Room in the props' table for every prop the chunks kept can hold (with the last props of
    // the chunks retiring), made at once while the table is small instead of doubled as props
    // come; again when the settings or the agents ask for more. Looked at when a chunk's props
    // are queued, not every frame they wait.
    if let (Some(streaming), true) = (&streaming, queued) {
        let radii = agents.iter().map(|a| a.radius.unwrap_or(streaming.load_radius));
        let kept = crate::streaming::kept_at_most(map.terrain(), streaming, radii) + crate::MAX_RETIRED_CHUNKS;
        let target = kept.saturating_mul(settings.max_per_chunk).min(MAX_ROOM);
        if target > *room {
            make_room(&mut commands, target.saturating_sub(props.iter().count()), assets.as_deref());
            *room = target;
        }
    }
    let mut budget = settings.max_spawns_per_frame.max(1);
    while budget > 0 {
        let Some(&mut (chunk, ref mut next)) = queue.front_mut() else { break };
        // A chunk dropped (or retired) before its turn has nothing to show.
        let all = chunks.get(chunk).map_or(&[][..], |(_, content, _)| &content.into_inner().props[..]);
        let rest = &all[(*next).min(all.len())..];
        let take = rest.len().min(budget);
        if take > 0 {
            let far = coords.get(chunk).is_ok_and(|c| c.detail == hex_terrain::Detail::Coarse);
            spawn_props(&mut commands, chunk, &rest[..take], size, assets.as_deref(), far);
        }
        budget -= take;
        *next += take;
        if take == rest.len() {
            queue.pop_front();
        }
    }
    let pending = queue
        .iter()
        .map(|&(chunk, next)| chunks.get(chunk).map_or(0, |(_, c, _)| c.props.len().saturating_sub(next)))
        .sum();
    // Written only when it changes, so the figures are not "changed" every frame.
    if stats.pending != pending {
        stats.pending = pending;
    }
}

/// Moves a chunk's spawned props (`old`, in spawn order, the first of `props`) onto the surface
/// of the chunk's new level and gives them its meshes (`far` on a coarse chunk). `false`, and
/// nothing moved, if they are not the first of `props` (then the chunk's props are made anew).
fn relevel(props: &mut PropQuery, old: &[Entity], new: &[Prop], far: bool, assets: Option<&PropAssets>) -> bool {
    let same = old.len() <= new.len()
        && old.iter().zip(new).all(|(&e, p)| {
            props.get(e).is_ok_and(|(prop, t, _)| {
                (prop.kind, prop.variant, prop.tile) == (p.kind, p.variant, p.tile)
                    && t.translation.x == p.position[0]
                    && t.translation.z == p.position[2]
            })
        });
    if !same {
        return false;
    }
    for (&e, p) in old.iter().zip(new) {
        let Ok((_, mut transform, mesh)) = props.get_mut(e) else { continue };
        transform.translation.y = p.position[1];
        #[cfg(feature = "render")]
        if let (Some(mut mesh), Some(assets)) = (mesh, assets) {
            let meshes = if far { &assets.far_meshes } else { &assets.meshes };
            mesh.0 = meshes[p.kind as usize][usize::from(p.variant % PROP_VARIANTS)].clone();
        }
        #[cfg(not(feature = "render"))]
        let _ = (mesh, far, assets);
    }
    true
}

/// Figures of the props.
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource)]
pub struct HexPropStats {
    /// Props whose visibility the fog set since the start: a frame adds only the props new in
    /// it and those on tiles whose fog changed in it (every prop when the fog is switched or
    /// another map is loaded); a highlight or an owner written on a tile adds none.
    pub fog_checks: u64,
    /// Props of loaded chunks waiting for their turn to be spawned (see
    /// [`HexPropSettings::max_spawns_per_frame`]).
    pub pending: usize,
}
