//! Props on a globe: each chunk's trees, rocks and reeds ([`GlobeTerrain::props`], placed in
//! the chunk's mesh task at [`HexPropSettings`]' cap and density) become [`HexGlobeProp`]
//! children of the chunk, upright along the globe's up, a budget a frame
//! ([`HexPropSettings::max_spawns_per_frame`]), made again when the chunk's mesh is (an edit, a
//! hot reload) and despawned with it. With Bevy's renderer they share the flat map's prop meshes
//! and material ([`PropAssets`]), and under fog of war those on unexplored tiles are hidden. The
//! game setup's resources and natural wonders ([`GlobeTerrain::marker_props`]) are props too
//! ([`PropKind::Resource`], [`PropKind::Wonder`]), never thinned by the cap: drawn and hidden by
//! fog the same way.
//!
//! [`GlobeTerrain::props`]: hex_terrain::GlobeTerrain::props
//! [`GlobeTerrain::marker_props`]: hex_terrain::GlobeTerrain::marker_props

use bevy::prelude::*;
use hex_terrain::{GlobeProp, GlobeTile, PropKind};

use super::HexGlobe;
use crate::props::{HexPropSettings, PropAssets, spawn_batch};

/// A prop on a globe (a child of its chunk's entity).
#[derive(Component, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Component)]
#[require(Transform)]
#[cfg_attr(feature = "render", require(Visibility))]
pub struct HexGlobeProp {
    /// What it is.
    pub kind: PropKind,
    /// Which of the kind's meshes.
    pub variant: u8,
    /// The tile it stands on.
    pub tile: GlobeTile,
}

/// A chunk's props from its last mesh, and how many of them are spawned.
#[derive(Component, Debug, Default)]
pub(super) struct GlobeChunkProps {
    props: Vec<GlobeProp>,
    /// The props spawned so far (the first `next`).
    next: usize,
    /// Whether the props came with a new mesh and the old ones are still to go.
    fresh: bool,
}

impl GlobeChunkProps {
    pub(super) fn new(props: Vec<GlobeProp>) -> Self {
        Self { props, next: 0, fresh: true }
    }
}

/// A prop's transform in its chunk: at its foot, its `y` along the globe's up, turned by its
/// yaw about it, `scale` hex radii tall.
fn placed(p: &GlobeProp, size: f32) -> Transform {
    let up = Vec3::from_array(p.up);
    Transform::from_translation(Vec3::from_array(p.position))
        .with_rotation(Quat::from_rotation_arc(Vec3::Y, up) * Quat::from_rotation_y(p.yaw))
        .with_scale(Vec3::splat(p.scale * size))
}

/// Keeps each chunk's prop children in step with its props: a chunk with a new mesh loses its
/// old props and gets the new ones; turning props off despawns them all, on spawns them again.
/// At most [`HexPropSettings::max_spawns_per_frame`] props are spawned a frame.
pub(super) fn sync_props(
    mut commands: Commands,
    settings: Res<HexPropSettings>,
    globe: Res<HexGlobe>,
    assets: Option<Res<PropAssets>>,
    mut chunks: Query<(Entity, &mut GlobeChunkProps, Option<&Children>)>,
    props: Query<(), With<HexGlobeProp>>,
    mut was_enabled: Local<Option<bool>>,
) {
    let Some(terrain) = globe.globe() else { return };
    let size = terrain.config().layout.hex_size;
    let enabled = settings.enabled;
    let toggled = *was_enabled != Some(enabled);
    *was_enabled = Some(enabled);
    let mut budget = settings.max_spawns_per_frame.max(1);
    for (chunk, mut state, children) in &mut chunks {
        if state.fresh || toggled {
            for &child in children.into_iter().flatten().filter(|&&c| props.contains(c)) {
                commands.entity(child).despawn();
            }
            state.fresh = false;
            state.next = if enabled { 0 } else { state.props.len() };
        }
        if budget == 0 || state.next >= state.props.len() {
            continue;
        }
        let take = (state.props.len() - state.next).min(budget);
        let batch = state.props[state.next..state.next + take]
            .iter()
            .map(|p| {
                (HexGlobeProp { kind: p.kind, variant: p.variant, tile: p.tile }, placed(p, size), p.kind, p.variant)
            })
            .collect();
        spawn_batch(&mut commands, chunk, batch, assets.as_deref(), false);
        state.next += take;
        budget -= take;
    }
}

/// Hides props on unexplored tiles while the tile states' style draws fog of war: the new props,
/// and those of tiles written this frame whose fog changed.
#[cfg(feature = "render")]
pub(super) fn hide_unexplored(
    states: Res<super::GlobeTileStates>,
    style: Res<crate::HexTileStateStyle>,
    added: Query<(Entity, &HexGlobeProp), Added<HexGlobeProp>>,
    mut removed: RemovedComponents<HexGlobeProp>,
    mut visibilities: Query<&mut Visibility, With<HexGlobeProp>>,
    mut index: Local<crate::props::PropsByTile<GlobeTile>>,
) {
    use crate::props::{fog_change, show};
    let fog = style.fog_of_war;
    let change = fog_change(style.is_changed(), states.is_changed(), states.changed_tiles().map(|t| t.iter().copied()));
    index.hide(
        added.iter().map(|(e, prop)| (e, prop.tile)),
        removed.read(),
        change,
        |tile| fog && states.visibility(tile) == crate::FogState::Unexplored,
        |e, hidden| show(&mut visibilities, e, hidden),
    );
}
