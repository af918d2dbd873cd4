//! Input: the pointer over the terrain (through the picking backend: its events carry the tile)
//! and the keys that switch what is drawn and which map is shown.

use bevy::picking::backend::HitData;
use bevy::picking::events::{Move, Out, Over, Pointer};
use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::panel::ReportPanel;
use crate::{DIGITS, Game, MAP_TYPES, PRESETS, RULESETS};

/// A pointer event that carries the terrain hit it is about.
pub(crate) trait TerrainHit {
    fn terrain_hit(&self) -> &HitData;
}

impl TerrainHit for Over {
    fn terrain_hit(&self) -> &HitData {
        &self.hit
    }
}

impl TerrainHit for Move {
    fn terrain_hit(&self) -> &HitData {
        &self.hit
    }
}

/// The hovered tile: the tile the terrain picking backend reports under the pointer.
pub(crate) fn hover<E: TerrainHit + std::fmt::Debug + Clone + Reflect>(
    pointer: On<Pointer<E>>,
    map: Res<HexMap>,
    mut game: ResMut<Game>,
) {
    // A hit on a prop bubbles up to its chunk: act on the first.
    if pointer.entity != pointer.original_event_target() {
        return;
    }
    if let Some(pick) = pointer.event.terrain_hit().extra_as::<HexPick>() {
        game.hovered = Some(pick.tile).filter(|&t| map.contains(t));
    }
}

/// The pointer left the terrain (a chunk it was over).
pub(crate) fn leave(pointer: On<Pointer<Out>>, mut game: ResMut<Game>) {
    if pointer.entity == pointer.original_event_target() && pointer.hit.extra_as::<HexPick>().is_some() {
        game.hovered = None;
    }
}

pub(crate) fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut material: ResMut<HexTerrainMaterialSettings>,
    mut style: ResMut<HexTileStateStyle>,
    map: Res<HexMap>,
    mut load: MessageWriter<LoadHexMap>,
    mut game: ResMut<Game>,
    mut report: Query<&mut Visibility, With<ReportPanel>>,
) {
    if keys.just_pressed(KeyCode::KeyG) {
        material.outlines = !material.outlines;
    }
    if keys.just_pressed(KeyCode::KeyL) {
        style.lens = !style.lens;
    }
    if keys.just_pressed(KeyCode::KeyT) {
        style.territory_tint = !style.territory_tint;
    }
    if keys.just_pressed(KeyCode::KeyV) {
        style.fog_of_war = !style.fog_of_war;
    }
    if keys.just_pressed(KeyCode::F3) {
        game.show_chunks = !game.show_chunks;
    }
    // The world builder takes the digits, F and R (and Ctrl+S) while it is open.
    if game.editing {
        return;
    }
    if keys.just_pressed(KeyCode::KeyF) {
        for mut v in &mut report {
            v.toggle_inherited_hidden();
        }
    }
    if keys.just_pressed(KeyCode::KeyP) {
        game.auto_pan = !game.auto_pan;
    }
    if keys.just_pressed(KeyCode::KeyR) {
        let mut config = map.config().clone();
        config.seed = config.seed.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        load.write(LoadHexMap(config.into()));
    }
    // The map types in turn: Pangaea, Continents, Small Continents, Archipelago, Fractal, Inland
    // Sea (the report panel, F, says what each met).
    // The World preset's terrain rulesets in turn: biomes, Civilization V, The Shattered Realms.
    if keys.just_pressed(KeyCode::KeyU) {
        game.rulesets += 1;
        load.write(LoadHexMap(RULESETS[game.rulesets % RULESETS.len()].into()));
    }
    if keys.just_pressed(KeyCode::KeyM) {
        load.write(LoadHexMap(MAP_TYPES[game.map_types % MAP_TYPES.len()].into()));
        game.map_types += 1;
    }
    for (i, key) in DIGITS.into_iter().take(PRESETS.len()).enumerate() {
        if keys.just_pressed(key) {
            load.write(LoadHexMap(PRESETS[i].into()));
        }
    }
}
