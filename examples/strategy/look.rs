//! The look's switches, for weak GPUs and for comparing: J shadows, K distance fog, B props,
//! N the water surface, O ambient occlusion. `HEXTERRAIN_LOOK=off` starts with all of them off
//! (the look before water, light and props: the frame-cost baseline), `HEXTERRAIN_SHADOWS=off`,
//! `HEXTERRAIN_PROPS=off` and `HEXTERRAIN_WATER=off` one each.

use bevy::prelude::*;
use hex_terrain_game::prelude::*;

fn off(var: &str) -> bool {
    std::env::var(var).is_ok_and(|v| v == "off")
}

/// Applies the environment's switches at start.
pub(crate) fn from_env(mut lighting: ResMut<TerrainLighting>, mut settings: ResMut<HexTerrainSettings>) {
    let all = off("HEXTERRAIN_LOOK");
    if all || off("HEXTERRAIN_SHADOWS") {
        lighting.shadows = false;
    }
    if all {
        lighting.fog = false;
    }
    if all || off("HEXTERRAIN_PROPS") {
        settings.props.enabled = false;
    }
    if all || off("HEXTERRAIN_WATER") {
        settings.water.enabled = false;
    }
}

/// The keys.
pub(crate) fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut lighting: ResMut<TerrainLighting>,
    mut settings: ResMut<HexTerrainSettings>,
) {
    if keys.just_pressed(KeyCode::KeyJ) {
        lighting.shadows = !lighting.shadows;
    }
    if keys.just_pressed(KeyCode::KeyK) {
        lighting.fog = !lighting.fog;
    }
    if keys.just_pressed(KeyCode::KeyO) {
        lighting.ambient_occlusion = !lighting.ambient_occlusion;
    }
    if keys.just_pressed(KeyCode::KeyB) {
        settings.props.enabled = !settings.props.enabled;
    }
    if keys.just_pressed(KeyCode::KeyN) {
        settings.water.enabled = !settings.water.enabled;
    }
}
