//! Props on the terrain: each chunk's trees, rocks and reeds ([`hex_terrain::Terrain::props`],
//! placed in the chunk's task) become child entities of the chunk, so they despawn with it.
//! With Bevy's renderer, every prop of a kind and variant shares one mesh and all share one
//! vertex-colored material: Bevy batches them into instanced draws (a handful of draws for
//! thousands of props). Headless, the entities exist without meshes (games and tests can read
//! them). The game setup's resources and natural wonders ([`hex_terrain::Terrain::marker_props`])
//! are props too ([`PropKind::Resource`], [`PropKind::Wonder`]): drawn, picked and hidden by fog
//! the same way. Under fog of war, props on unexplored tiles are hidden.

#[cfg(feature = "render")]
pub mod meshes;

use bevy::prelude::*;
use hex_terrain::{PROP_VARIANTS, Prop, PropKind};

use bevy::platform::collections::HashMap;
use hex_terrain::hexx::Hex;

use crate::streaming::content::{ContentQuery, stale_chunks};
use crate::tiles::HexTileStateSystems;
use crate::{HexTerrainSettings, HexTerrainSystems, TileStates};

/// A prop entity (a child of its chunk).
#[derive(Component, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Component)]
pub struct HexProp {
    /// What it is.
    pub kind: PropKind,
    /// Which of the kind's meshes.
    pub variant: u8,
    /// The tile it stands on (map-local axial coordinate).
    pub tile: hex_terrain::hexx::Hex,
}

/// The shared meshes (by kind and variant) and material of the props, with Bevy's renderer.
#[derive(Resource, Debug, Clone)]
pub struct PropAssets {
    /// `meshes[kind as usize][variant]`.
    pub meshes: Vec<Vec<Handle<Mesh>>>,
    /// The one material every prop uses (white base, vertex colors).
    #[cfg(feature = "render")]
    pub material: Handle<StandardMaterial>,
}

/// Spawns and despawns the props of loaded chunks ([`HexProp`] children, in
/// [`HexTerrainSystems::Insert`]) and hides those on unexplored tiles when the appearance draws
/// fog of war. Part of [`HexTerrainPlugins`](crate::HexTerrainPlugins); works headless.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexPropsPlugin;

impl Plugin for HexPropsPlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<HexProp>()
            .register_type::<HexPropStats>()
            .init_resource::<HexPropStats>()
            .add_systems(
                Update,
                sync_props.in_set(HexTerrainSystems::Insert).after(crate::streaming::insert::insert_ready),
            )
            // After every game system's writes of the frame, before their list starts again.
            .add_systems(PostUpdate, hide_unexplored.before(HexTileStateSystems::Pack));
        #[cfg(feature = "render")]
        app.configure_sets(
            PostUpdate,
            HexTileStateSystems::Pack.before(bevy::camera::visibility::VisibilitySystems::VisibilityPropagate),
        );
        #[cfg(feature = "render")]
        if app.is_plugin_added::<bevy::pbr::PbrPlugin>() {
            app.add_systems(Startup, create_assets);
        }
    }
}

#[cfg(feature = "render")]
fn create_assets(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let meshes = PropKind::ALL
        .iter()
        .map(|&kind| (0..PROP_VARIANTS).map(|v| meshes.add(meshes::prop_mesh(kind, v))).collect())
        .collect();
    let material = materials.add(StandardMaterial { perceptual_roughness: 0.9, reflectance: 0.15, ..default() });
    commands.insert_resource(PropAssets { meshes, material });
}

/// The props' entities of one chunk.
fn spawn_props(commands: &mut Commands, chunk: Entity, props: &[Prop], size: f32, assets: Option<&PropAssets>) {
    commands.entity(chunk).with_children(|children| {
        for p in props {
            let transform = Transform::from_translation(Vec3::from_array(p.position))
                .with_rotation(Quat::from_rotation_y(p.yaw))
                .with_scale(Vec3::splat(p.scale * size));
            let prop = HexProp { kind: p.kind, variant: p.variant, tile: p.tile };
            let mut e = children.spawn((prop, transform, Visibility::default()));
            #[cfg(feature = "render")]
            if let Some(assets) = assets {
                let mesh = assets.meshes[p.kind as usize][usize::from(p.variant % PROP_VARIANTS)].clone();
                e.insert((Mesh3d(mesh), MeshMaterial3d(assets.material.clone())));
            }
            #[cfg(not(feature = "render"))]
            let _ = (&mut e, assets);
        }
    });
}

/// Keeps each chunk's prop children in step with its [`ChunkContent`](crate::ChunkContent) and the settings: a chunk
/// whose content changed (a new mesh, a hot reload) gets its props anew; turning props off or on
/// despawns or spawns them everywhere.
fn sync_props(
    mut commands: Commands,
    settings: Res<HexTerrainSettings>,
    map: Res<crate::HexMap>,
    assets: Option<Res<PropAssets>>,
    chunks: ContentQuery,
    props: Query<(), With<HexProp>>,
    mut was_enabled: Local<Option<bool>>,
) {
    let enabled = settings.props.enabled;
    let size = map.config().layout.hex_size;
    for (chunk, content) in stale_chunks(&mut commands, &chunks, &props, enabled, &mut was_enabled) {
        if enabled {
            spawn_props(&mut commands, chunk, &content.props, size, assets.as_deref());
        }
    }
}

/// Figures of the props.
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource)]
pub struct HexPropStats {
    /// Props whose tile's fog was looked at since the start: a frame adds only the props new in
    /// it and those on tiles whose state was written in it (every prop when the fog is switched
    /// or another map is loaded).
    pub fog_checks: u64,
}

/// The props standing on each tile (the map's own tile), for the fog to find them.
#[derive(Default)]
struct PropsByTile {
    tiles: HashMap<Hex, Vec<Entity>>,
    of: HashMap<Entity, Hex>,
}

/// Hides props on unexplored tiles while the terrain draws fog of war, so the fog does not show
/// the forests it hides. Only new props and the props of tiles written this frame
/// ([`TileStates::changed_tiles`]) are looked at: a hover moving the highlight every frame
/// touches a few props, not every prop of the map.
fn hide_unexplored(
    states: Res<TileStates>,
    #[cfg(feature = "render")] appearance: Option<Res<crate::TerrainAppearance>>,
    added: Query<(Entity, &HexProp), Added<HexProp>>,
    mut removed: RemovedComponents<HexProp>,
    mut visibilities: Query<(&HexProp, &mut Visibility)>,
    mut index: Local<PropsByTile>,
    mut stats: ResMut<HexPropStats>,
) {
    #[cfg(feature = "render")]
    let (fog, fog_changed) = appearance.map_or((false, false), |a| (a.fog_of_war, a.is_changed()));
    #[cfg(not(feature = "render"))]
    let (fog, fog_changed) = (false, false);
    let index = &mut *index;
    for e in removed.read() {
        if let Some(tile) = index.of.remove(&e)
            && let Some(list) = index.tiles.get_mut(&tile)
        {
            list.retain(|&p| p != e);
            if list.is_empty() {
                index.tiles.remove(&tile);
            }
        }
    }
    let mut checks = 0u64;
    let mut check = |e: Entity, visibilities: &mut Query<(&HexProp, &mut Visibility)>| {
        let Ok((prop, mut visibility)) = visibilities.get_mut(e) else { return };
        checks += 1;
        let hidden = fog && states.visibility(prop.tile) == crate::FogState::Unexplored;
        visibility.set_if_neq(if hidden { Visibility::Hidden } else { Visibility::Inherited });
    };
    for (e, prop) in &added {
        let tile = states.wrap_tile(prop.tile);
        index.tiles.entry(tile).or_default().push(e);
        index.of.insert(e, tile);
        check(e, &mut visibilities);
    }
    let changed = if fog_changed { None } else { states.changed_tiles() };
    match changed {
        None if fog_changed || states.is_changed() => {
            for &e in index.of.keys() {
                check(e, &mut visibilities);
            }
        }
        None => {}
        Some(tiles) => {
            for tile in tiles {
                for &e in index.tiles.get(&tile).into_iter().flatten() {
                    check(e, &mut visibilities);
                }
            }
        }
    }
    stats.fog_checks += checks;
}
