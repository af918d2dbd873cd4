//! The panels: the hovered tile and the selected unit, the End Turn button, and the fairness
//! report of the map's game setup.

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::pieces::{MOVES, Unit};
use crate::{Game, vision};

#[derive(Component)]
pub(crate) struct Panel;

/// The fairness report of the map's game setup (F).
#[derive(Component)]
pub(crate) struct ReportPanel;

#[derive(Component)]
pub(crate) struct EndTurnButton;

pub(crate) fn panel(
    game: Res<Game>,
    map: Res<HexMap>,
    states: Res<TileStates>,
    style: Res<HexTileStateStyle>,
    units: Query<&Unit>,
    mut text: Query<&mut Text, With<Panel>>,
) {
    let mut s = format!("Turn {}", game.turn);
    if style.lens {
        s += "   Lens: movement cost (green 1, yellow 2, orange more; water and peaks impassable)";
    }
    if let Some(tile) = game.hovered.filter(|&t| !style.fog_of_war || states.visibility(t) != FogState::Unexplored) {
        let owner = match states.owner(tile) {
            Some(vision::HUMAN) => "yours",
            Some(_) => "rival's",
            None => "nobody's",
        };
        s += &format!("\nTerritory: {owner}");
        match map.move_cost(tile) {
            Some(cost) => s += &format!("   Move cost: {cost}"),
            None => s += "   Impassable",
        }
        let Some(info) = map.tile_info(tile) else { return };
        // Offset coordinates (column, row), as the fairness report gives them.
        let [col, row] = map.terrain().offset_of(tile);
        // What the tile is: its terrain (under the default ruleset its biome; under the map's
        // own, on hills or not), with its feature.
        let (t, ruleset) = (info.terrain, map.terrain().ruleset());
        let hills = if map.terrain().has_own_ruleset() && t.landform == Landform::Hills { " hills" } else { "" };
        let feature = t.feature.map_or(String::new(), |f| format!(", {}", ruleset.feature(f).name));
        let what = format!("{}{hills}{feature}", ruleset.terrain(t.terrain).name);
        s += &format!("\nTile ({col}, {row})  {what} ({})  elevation {:.2}", info.kind.name(), info.elevation);
        if let Some(river) = map.river(tile) {
            let extra = map.terrain().config().movement.river;
            s += &format!("\nRiver: flow {:.1} (entering costs {extra} more)", river.flow);
        }
        if let Some(lake) = info.lake {
            s += &format!("\nLake {lake} (impassable)");
        }
        if let Some(r) = map.resource(tile) {
            s += &format!("\nResource: {} ({})", r.name, r.class.name());
        }
        if let Some(w) = map.wonder(tile) {
            s += &format!("\nNatural wonder: {}", w.name);
        }
        if let Some(p) = map.start(tile) {
            let yours = if p == vision::HUMAN { " (yours)" } else { "" };
            s += &format!("\nStart of player {p}{yours}");
        }
    }
    if let Some(unit) = game.selected.and_then(|e| units.get(e).ok()) {
        s += &format!("\nSelected unit: {} of {MOVES} moves left", unit.moves_left);
    }
    for mut t in &mut text {
        t.0.clone_from(&s);
    }
}

/// Writes the setup's fairness report and the map's statistics into their panel when the map
/// changes.
pub(crate) fn report_panel(map: Res<HexMap>, mut text: Query<&mut Text, With<ReportPanel>>) {
    if !map.is_changed() {
        return;
    }
    let mut report = match map.setup() {
        Some(setup) => format!("Fairness report ({} players)\n{}", setup.starts().len(), setup.report()),
        None => "This map has no game setup (the World preset has one).".to_owned(),
    };
    // The map's statistics, measured again after every change (an edit, another map).
    if let Some(stats) = map.stats() {
        report += &format!("\n\nMap statistics\n{stats}");
    }
    // A map type's targets, as the generator measured them.
    if let Some(map_type) = map.terrain().map_type() {
        report += &format!("\n\nMap type {map_type}");
    }
    for mut t in &mut text {
        t.0.clone_from(&report);
    }
}
