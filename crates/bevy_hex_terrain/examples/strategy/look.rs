//! The look's switches, for weak GPUs and for comparing: J shadows, K distance fog, B props,
//! N the water surface, O ambient occlusion, X the terrain textures (each tile its terrain's
//! layer of the texture array). `HEXTERRAIN_LOOK=off` starts with all of them off (the look
//! before water, light and props: the frame-cost baseline), `HEXTERRAIN_SHADOWS=off`,
//! `HEXTERRAIN_PROPS=off` and `HEXTERRAIN_WATER=off` one each; `HEXTERRAIN_TEXTURES=on` starts
//! with the textures.

use bevy::pbr::ScreenSpaceAmbientOcclusion;
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

fn off(var: &str) -> bool {
    std::env::var(var).is_ok_and(|v| v == "off")
}

/// Applies the environment's switches at start.
pub(crate) fn from_env(
    mut lighting: ResMut<HexLightSettings>,
    mut props: ResMut<HexPropSettings>,
    mut water: ResMut<HexWaterSettings>,
    mut material: ResMut<HexTerrainMaterialSettings>,
) {
    material.textures = std::env::var("HEXTERRAIN_TEXTURES").is_ok_and(|v| v == "on");
    let all = off("HEXTERRAIN_LOOK");
    if all || off("HEXTERRAIN_SHADOWS") {
        lighting.shadows = false;
    }
    if all {
        lighting.fog = false;
    }
    if all || off("HEXTERRAIN_PROPS") {
        props.enabled = false;
    }
    if all || off("HEXTERRAIN_WATER") {
        water.enabled = false;
    }
}

/// The keys.
pub(crate) fn keys(
    mut commands: Commands,
    keys: Res<ButtonInput<KeyCode>>,
    mut lighting: ResMut<HexLightSettings>,
    mut props: ResMut<HexPropSettings>,
    mut water: ResMut<HexWaterSettings>,
    mut material: ResMut<HexTerrainMaterialSettings>,
    cameras: Query<(Entity, Has<ScreenSpaceAmbientOcclusion>), With<HexTerrainCamera>>,
) {
    if keys.just_pressed(KeyCode::KeyJ) {
        lighting.shadows = !lighting.shadows;
    }
    if keys.just_pressed(KeyCode::KeyK) {
        lighting.fog = !lighting.fog;
    }
    if keys.just_pressed(KeyCode::KeyO) {
        // Ambient occlusion is the camera's: it needs MSAA off (and brings its prepasses).
        for (camera, on) in &cameras {
            if on {
                commands.entity(camera).remove::<ScreenSpaceAmbientOcclusion>().insert(Msaa::default());
            } else {
                commands.entity(camera).insert((ScreenSpaceAmbientOcclusion::default(), Msaa::Off));
            }
        }
    }
    if keys.just_pressed(KeyCode::KeyB) {
        props.enabled = !props.enabled;
    }
    if keys.just_pressed(KeyCode::KeyN) {
        water.enabled = !water.enabled;
    }
    if keys.just_pressed(KeyCode::KeyX) {
        material.textures = !material.textures;
    }
}
