//! Fog of war over props: props on unexplored tiles are hidden while the terrain draws fog of
//! war (with Bevy's renderer; headless there is no fog to draw). A flat map's props and a
//! globe's alike ([`PropsByTile::hide`]).

use std::hash::Hash;

use bevy::ecs::query::QueryFilter;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::hexx::Hex;

use super::{HexProp, HexPropStats};
use crate::TileStates;

/// The props standing on each tile (`K`: a flat map's own tile or a globe's), for the fog to
/// find them, and whether the fog last hid that tile's props.
pub(crate) struct PropsByTile<K> {
    tiles: HashMap<K, Vec<Entity>>,
    of: HashMap<Entity, K>,
    hidden: HashMap<K, bool>,
}

impl<K> Default for PropsByTile<K> {
    fn default() -> Self {
        Self { tiles: HashMap::default(), of: HashMap::default(), hidden: HashMap::default() }
    }
}

/// What changed for the fog this frame.
pub(crate) enum FogChange<I> {
    /// Nothing.
    None,
    /// The fog of these tiles may have changed (written this frame).
    Tiles(I),
    /// Any tile's (the fog switched, the states reset, more writes than listed).
    All,
}

impl<K: Copy + Eq + Hash> PropsByTile<K> {
    /// Indexes the props `added`, forgets the `removed`, and sets the visibility of the new props
    /// and of those on tiles whose fog changed (`hidden_on` says whether a tile's props are
    /// hidden now) with `show`; returns how many props it set.
    pub(crate) fn hide(
        &mut self,
        added: impl IntoIterator<Item = (Entity, K)>,
        removed: impl IntoIterator<Item = Entity>,
        change: FogChange<impl IntoIterator<Item = K>>,
        hidden_on: impl Fn(K) -> bool,
        mut show: impl FnMut(Entity, bool) -> bool,
    ) -> u64 {
        for e in removed {
            if let Some(tile) = self.of.remove(&e)
                && let Some(list) = self.tiles.get_mut(&tile)
            {
                list.retain(|&p| p != e);
                if list.is_empty() {
                    self.tiles.remove(&tile);
                    self.hidden.remove(&tile);
                }
            }
        }
        let mut checks = 0u64;
        let mut set = |e: Entity, hidden: bool| checks += u64::from(show(e, hidden));
        for (e, tile) in added {
            self.tiles.entry(tile).or_default().push(e);
            self.of.insert(e, tile);
            let hidden = hidden_on(tile);
            self.hidden.insert(tile, hidden);
            set(e, hidden);
        }
        match change {
            FogChange::None => {}
            FogChange::All => {
                for (&tile, props) in &self.tiles {
                    let now = hidden_on(tile);
                    self.hidden.insert(tile, now);
                    for &e in props {
                        set(e, now);
                    }
                }
            }
            FogChange::Tiles(changed) => {
                for tile in changed {
                    let Some(props) = self.tiles.get(&tile) else { continue };
                    // A write that left the tile's fog as it was (a highlight, an owner) changes
                    // nothing here.
                    let now = hidden_on(tile);
                    if self.hidden.insert(tile, now) == Some(now) {
                        continue;
                    }
                    for &e in props {
                        set(e, now);
                    }
                }
            }
        }
        checks
    }
}

/// What changed for the fog: the tiles written this frame, every tile when the fog was switched
/// or the states list no tiles, nothing when the states did not change.
pub(crate) fn fog_change<I>(fog_switched: bool, states_changed: bool, changed_tiles: Option<I>) -> FogChange<I> {
    match (fog_switched, changed_tiles) {
        (true, _) => FogChange::All,
        (false, Some(tiles)) => FogChange::Tiles(tiles),
        (false, None) if states_changed => FogChange::All,
        (false, None) => FogChange::None,
    }
}

/// Sets a prop's visibility: hidden, or inherited from its chunk; whether it was found.
pub(crate) fn show<F: QueryFilter>(visibilities: &mut Query<&mut Visibility, F>, e: Entity, hidden: bool) -> bool {
    let Ok(mut visibility) = visibilities.get_mut(e) else { return false };
    visibility.set_if_neq(if hidden { Visibility::Hidden } else { Visibility::Inherited });
    true
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
    mut visibilities: Query<&mut Visibility, With<HexProp>>,
    mut index: Local<PropsByTile<Hex>>,
    mut stats: ResMut<HexPropStats>,
) {
    let fog = style.fog_of_war;
    let change = fog_change(style.is_changed(), states.is_changed(), states.changed_tiles());
    let checks = index.hide(
        added.iter().map(|(e, prop)| (e, states.wrap_tile(prop.tile))),
        removed.read(),
        change,
        |tile| fog && states.visibility(tile) == crate::FogState::Unexplored,
        |e, hidden| show(&mut visibilities, e, hidden),
    );
    stats.fog_checks += checks;
}
