//! Fog of war over props: props on unexplored tiles are hidden while the terrain draws fog of
//! war (with Bevy's renderer; headless there is no fog to draw).

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::hexx::Hex;

use super::{HexProp, HexPropStats};
use crate::TileStates;

/// The props standing on each tile (the map's own tile), for the fog to find them, and whether
/// the fog last hid that tile's props.
#[derive(Default)]
pub(super) struct PropsByTile {
    tiles: HashMap<Hex, Vec<Entity>>,
    of: HashMap<Entity, Hex>,
    hidden: HashMap<Hex, bool>,
}

/// Hides props on unexplored tiles while the terrain draws fog of war, so the fog does not show
/// the forests it hides. Only new props, and the props of tiles written this frame
/// ([`TileStates::changed_tiles`]) whose fog changed, are looked at: a hover moving the
/// highlight every frame touches no prop at all.
pub(super) fn hide_unexplored(
    states: Res<TileStates>,
    style: Res<crate::tiles::HexTileStateStyle>,
    added: Query<(Entity, &HexProp), Added<HexProp>>,
    mut removed: RemovedComponents<HexProp>,
    mut visibilities: Query<(&HexProp, &mut Visibility)>,
    mut index: Local<PropsByTile>,
    mut stats: ResMut<HexPropStats>,
) {
    let (fog, fog_changed) = (style.fog_of_war, style.is_changed());
    let index = &mut *index;
    for e in removed.read() {
        if let Some(tile) = index.of.remove(&e)
            && let Some(list) = index.tiles.get_mut(&tile)
        {
            list.retain(|&p| p != e);
            if list.is_empty() {
                index.tiles.remove(&tile);
                index.hidden.remove(&tile);
            }
        }
    }
    let hidden_on = |tile: Hex| fog && states.visibility(tile) == crate::FogState::Unexplored;
    let mut checks = 0u64;
    let mut show = |e: Entity, hidden: bool, visibilities: &mut Query<(&HexProp, &mut Visibility)>| {
        let Ok((_, mut visibility)) = visibilities.get_mut(e) else { return };
        checks += 1;
        visibility.set_if_neq(if hidden { Visibility::Hidden } else { Visibility::Inherited });
    };
    for (e, prop) in &added {
        let tile = states.wrap_tile(prop.tile);
        index.tiles.entry(tile).or_default().push(e);
        index.of.insert(e, tile);
        let hidden = hidden_on(tile);
        index.hidden.insert(tile, hidden);
        show(e, hidden, &mut visibilities);
    }
    let changed = if fog_changed { None } else { states.changed_tiles() };
    match changed {
        None if fog_changed || states.is_changed() => {
            let PropsByTile { tiles, hidden, .. } = index;
            for (&tile, props) in tiles.iter() {
                let now = hidden_on(tile);
                hidden.insert(tile, now);
                for &e in props {
                    show(e, now, &mut visibilities);
                }
            }
        }
        None => {}
        Some(changed) => {
            for tile in changed {
                let Some(props) = index.tiles.get(&tile) else { continue };
                // A write that left the tile's fog as it was (a highlight, an owner) changes
                // nothing here.
                let now = hidden_on(tile);
                if index.hidden.insert(tile, now) == Some(now) {
                    continue;
                }
                for &e in props {
                    show(e, now, &mut visibilities);
                }
            }
        }
    }
    stats.fog_checks += checks;
}
