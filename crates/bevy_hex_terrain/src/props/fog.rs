//! Fog of war over props: props on unexplored tiles are hidden while the terrain draws fog of
//! war (with Bevy's renderer; headless there is no fog to draw).

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::hexx::Hex;

use super::{HexProp, HexPropStats};
use crate::TileStates;

/// The props standing on each tile (the map's own tile), for the fog to find them.
#[derive(Default)]
pub(super) struct PropsByTile {
    tiles: HashMap<Hex, Vec<Entity>>,
    of: HashMap<Entity, Hex>,
}

/// Hides props on unexplored tiles while the terrain draws fog of war, so the fog does not show
/// the forests it hides. Only new props and the props of tiles written this frame
/// ([`TileStates::changed_tiles`]) are looked at: a hover moving the highlight every frame
/// touches a few props, not every prop of the map.
pub(super) fn hide_unexplored(
    states: Res<TileStates>,
    style: Res<crate::tiles::TileStateStyle>,
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
