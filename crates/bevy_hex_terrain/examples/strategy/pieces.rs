//! A player's unit as the other modules read it: the component, its moves a turn and how high it
//! stands; `units` places, selects and moves them, `vision` fogs by them, `panel` shows them.

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

/// Moves a unit has each turn.
pub(crate) const MOVES: u32 = 4;

/// How high a unit's origin stands over the surface (half its capsule).
pub(crate) const LIFT: f32 = 0.6;

/// A player's unit; where it stands is its `OnTile`.
#[derive(Component)]
#[require(OnTile = OnTile::new(Hex::ZERO))]
pub(crate) struct Unit {
    /// [`crate::vision::HUMAN`] or [`crate::vision::RIVAL`].
    pub(crate) player: u32,
    pub(crate) moves_left: u32,
}
