//! The water surface's entities: each chunk with water ([`ChunkContent::water`]) gets a
//! [`HexWater`] child showing it, despawned with the chunk. With Bevy's renderer the terrain
//! material gives it the water look (its water instance: depth colors, shore foam, moving
//! waves, transparent over the shallows), and it casts no shadow.

use bevy::prelude::*;

use crate::streaming::ChunkContent;
use crate::{HexChunk, HexTerrainSettings, HexTerrainSystems};

/// A chunk's water surface entity (a child of its chunk).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexWater;

/// Spawns and despawns the water surfaces of loaded chunks, in [`HexTerrainSystems::Insert`].
/// Part of [`HexTerrainPlugins`](crate::HexTerrainPlugins); works headless.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexWaterPlugin;

impl Plugin for HexWaterPlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<HexWater>().add_systems(
            Update,
            sync_water.in_set(HexTerrainSystems::Insert).after(crate::streaming::insert::insert_ready),
        );
    }
}

/// Keeps each chunk's water child in step with its [`ChunkContent`] and the settings.
fn sync_water(
    mut commands: Commands,
    settings: Res<HexTerrainSettings>,
    chunks: Query<(Entity, Ref<ChunkContent>, Option<&Children>), With<HexChunk>>,
    waters: Query<(), With<HexWater>>,
    mut was_enabled: Local<Option<bool>>,
) {
    let enabled = settings.water.enabled;
    let toggled = *was_enabled != Some(enabled);
    *was_enabled = Some(enabled);
    for (chunk, content, children) in &chunks {
        if !(toggled || content.is_changed()) {
            continue;
        }
        for child in children.into_iter().flatten() {
            if waters.contains(*child) {
                commands.entity(*child).despawn();
            }
        }
        let Some(mesh) = content.water.clone().filter(|_| enabled) else { continue };
        commands.entity(chunk).with_children(|c| {
            let mut water = c.spawn((HexWater, Mesh3d(mesh), Transform::IDENTITY, Visibility::default()));
            #[cfg(feature = "render")]
            water.insert(bevy::light::NotShadowCaster);
            #[cfg(not(feature = "render"))]
            let _ = &mut water;
        });
    }
}
