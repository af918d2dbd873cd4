//! The water surface's entities: each chunk with water ([`ChunkContent::water`](crate::ChunkContent::water)) gets a
//! [`HexWater`] child showing it, despawned with the chunk. With Bevy's renderer the terrain
//! material gives it the water look (its water instance: depth colors, shore foam, moving
//! waves, transparent over the shallows), and it neither casts nor receives shadows. How deep
//! rivers run and how the water looks is the plugin's [`HexWaterSettings`].

mod settings;

use bevy::prelude::*;

pub use settings::HexWaterSettings;

use crate::HexTerrainSystems;
use crate::streaming::ContentRequest;
use crate::streaming::content::{ContentQuery, stale_chunks};

/// A chunk's water surface entity (a child of its chunk).
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
#[require(Transform)]
#[cfg_attr(feature = "render", require(Visibility))]
pub struct HexWater;

/// Spawns and despawns the water surfaces of loaded chunks (in
/// [`HexTerrainSystems::Children`]), owns [`HexWaterSettings`]; without it, chunk tasks build no
/// water surface. Part of [`HexTerrainPlugins`](crate::HexTerrainPlugins); works headless.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexWaterPlugin;

impl Plugin for HexWaterPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<HexWaterSettings>()
            .init_resource::<ContentRequest>()
            .register_type::<HexWaterSettings>()
            .register_type::<HexWater>()
            .add_systems(
                Update,
                (
                    // Before tasks start: they build the surface as the settings ask.
                    request_water.run_if(resource_changed::<HexWaterSettings>).before(HexTerrainSystems::Stream),
                    sync_water.in_set(HexTerrainSystems::Children),
                ),
            );
    }
}

/// Asks chunk tasks for the water surface at the settings' river depth.
fn request_water(settings: Res<HexWaterSettings>, mut request: ResMut<ContentRequest>) {
    request.river_depth = Some(settings.river_depth);
}

/// Keeps each chunk's water child in step with its [`ChunkContent`](crate::ChunkContent) and
/// the settings.
fn sync_water(
    mut commands: Commands,
    settings: Res<HexWaterSettings>,
    chunks: ContentQuery,
    waters: Query<(), With<HexWater>>,
    mut was_enabled: Local<Option<bool>>,
) {
    let enabled = settings.enabled;
    for (chunk, content, old) in stale_chunks(&chunks, |e| waters.contains(e), enabled, &mut was_enabled) {
        // One surface a chunk: replaced at once.
        for water in old {
            commands.entity(water).despawn();
        }
        let Some(mesh) = content.water.clone().filter(|_| enabled) else { continue };
        commands.entity(chunk).with_children(|c| {
            let mut water = c.spawn((HexWater, Mesh3d(mesh)));
            #[cfg(feature = "render")]
            // Neither casts nor receives shadows: the sun's shadows lie on the floor beneath, and
            // the water's fragments skip the shadow lookups (they cover much of the screen).
            water.insert((bevy::light::NotShadowCaster, bevy::light::NotShadowReceiver));
            #[cfg(not(feature = "render"))]
            let _ = &mut water;
        });
    }
}
