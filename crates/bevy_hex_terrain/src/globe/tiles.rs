//! [`GlobeTileStates`]: the game's per-tile state on a globe (fog of war, owners, a lens overlay,
//! highlights), kept for every tile by id in the texel layout the flat map's
//! [`TileStates`](crate::TileStates) has, and drawn by the globe's material without touching a
//! mesh.

#[cfg(feature = "render")]
use std::collections::BTreeSet;

use bevy::platform::collections::HashSet;
use bevy::prelude::*;
use hex_terrain::{GlobeFog, GlobeTile};

#[cfg(feature = "render")]
use super::GLOBE_ROW;
use super::HexGlobe;
use crate::tiles::texel;
use crate::tiles::{FogState, Highlight, Texel, TileStateError};

/// Per-tile game state of the globe shown ([`HexGlobe`]), by tile: what the player knows of it
/// ([`FogState`]), its owner, an overlay color (the lens) and any number of highlights, drawn by
/// the globe's material with the flat map's [`HexTileStateStyle`](crate::HexTileStateStyle)
/// (fog blended across tile borders, owners' borders inside their tiles' edges, pentagons as
/// any tile).
///
/// It follows the globe at the end of [`HexTerrainSystems::Map`](crate::HexTerrainSystems::Map):
/// another config of the same frequency (a hot reload) keeps every tile's state, a globe of
/// another frequency starts afresh. Before the globe has loaded it has no tiles, and writes are
/// refused. A write to a tile not of the globe, an owner beyond
/// [`MAX_OWNERS`](crate::MAX_OWNERS) or a non-finite overlay color is refused with a
/// [`TileStateError`] and changes nothing.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_hex_terrain::hex_terrain::GlobeTile;
/// use bevy_hex_terrain::prelude::*;
///
/// fn claim(mut states: ResMut<GlobeTileStates>) {
///     // Player 0 owns the north pole's pentagon and sees it; its neighbors are explored.
///     let pole = GlobeTile(0);
///     if states.set_owner(pole, Some(0)).is_ok() {
///         states.set_visibility(pole, FogState::Visible).unwrap();
///     }
/// }
/// # App::new().add_systems(Update, claim.after(HexTerrainSystems::Map));
/// ```
#[derive(Resource, Debug, Clone, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct GlobeTileStates {
    /// Every tile's texel, by id.
    #[reflect(ignore)]
    texels: Vec<Texel>,
    #[reflect(ignore)]
    highlighted: [HashSet<GlobeTile>; 3],
    /// The tiles in sight, so [`GlobeTileStates::hide_visible`] touches only them.
    #[reflect(ignore)]
    visible: HashSet<GlobeTile>,
    /// The tiles written since the journal was last cleared; `None` once every tile may have
    /// changed.
    #[reflect(ignore)]
    journal: Option<Vec<GlobeTile>>,
    /// The texture rows (`GLOBE_ROW` tiles each) the GPU's copy has behind.
    #[cfg(feature = "render")]
    #[reflect(ignore)]
    dirty: BTreeSet<u32>,
    writes: u64,
}

/// Most tiles [`GlobeTileStates::changed_tiles`] lists in a frame; past it, it answers "every tile".
const JOURNAL_LIMIT: usize = 1 << 16;

impl GlobeTileStates {
    /// How many tiles it holds: the globe's, 0 before the globe has loaded.
    #[must_use]
    pub fn tile_count(&self) -> u32 {
        self.texels.len() as u32
    }

    /// What the player knows of a tile (unexplored for a tile not of the globe).
    #[must_use]
    pub fn visibility(&self, tile: GlobeTile) -> FogState {
        texel::fog(self.texel(tile))
    }

    /// The owner of a tile, a player `0..MAX_OWNERS`, if any.
    #[must_use]
    pub fn owner(&self, tile: GlobeTile) -> Option<u32> {
        texel::owner(self.texel(tile))
    }

    /// The overlay color of a tile, if any (drawn while the lens is on).
    #[must_use]
    pub fn overlay(&self, tile: GlobeTile) -> Option<Color> {
        texel::overlay(self.texel(tile))
    }

    /// Whether a tile carries a highlight.
    #[must_use]
    pub fn is_highlighted(&self, tile: GlobeTile, highlight: Highlight) -> bool {
        texel::is_highlighted(self.texel(tile), highlight)
    }

    /// The tiles carrying a highlight.
    pub fn highlighted(&self, highlight: Highlight) -> impl Iterator<Item = GlobeTile> + '_ {
        self.highlighted[highlight as usize].iter().copied()
    }

    /// Sets what the player knows of a tile.
    ///
    /// # Errors
    /// [`TileStateError::NotOnGlobe`]; nothing changes.
    pub fn set_visibility(&mut self, tile: GlobeTile, fog: FogState) -> Result<(), TileStateError> {
        self.check(tile)?;
        self.update(tile, |t| texel::with_fog(t, fog));
        Ok(())
    }

    /// Makes every visible tile explored (the start of a sight update: the game then marks what
    /// its units see now as visible). Its cost is the number of visible tiles.
    pub fn hide_visible(&mut self) {
        for tile in std::mem::take(&mut self.visible) {
            self.update(tile, |t| texel::with_fog(t, FogState::Explored));
        }
    }

    /// Gives a tile to a player (`0..MAX_OWNERS`, numbered as a game setup numbers its starts),
    /// or to nobody.
    ///
    /// # Errors
    /// [`TileStateError::NotOnGlobe`], [`TileStateError::OwnerOutOfRange`]; nothing changes.
    pub fn set_owner(&mut self, tile: GlobeTile, owner: Option<u32>) -> Result<(), TileStateError> {
        self.check(tile)?;
        let word = texel::owner_word(owner)?;
        self.update(tile, |mut t| {
            t[1] = word;
            t
        });
        Ok(())
    }

    /// Sets a tile's overlay color (its alpha is the strength; 8 bits a channel, sRGB), or
    /// removes it.
    ///
    /// # Errors
    /// [`TileStateError::NotOnGlobe`], [`TileStateError::OverlayNotFinite`]; nothing changes.
    pub fn set_overlay(&mut self, tile: GlobeTile, color: Option<Color>) -> Result<(), TileStateError> {
        self.check(tile)?;
        let [rg, ba] = texel::overlay_words(color)?;
        self.update(tile, |t| [t[0], t[1], rg, ba]);
        Ok(())
    }

    /// Puts a highlight on a tile or takes it off.
    ///
    /// # Errors
    /// [`TileStateError::NotOnGlobe`]; nothing changes.
    pub fn set_highlight(&mut self, tile: GlobeTile, highlight: Highlight, on: bool) -> Result<(), TileStateError> {
        self.check(tile)?;
        let set = &mut self.highlighted[highlight as usize];
        if if on { set.insert(tile) } else { set.remove(&tile) } {
            self.update(tile, |t| texel::with_highlight(t, highlight, on));
        }
        Ok(())
    }

    /// Makes `tiles` the only ones carrying `highlight`; tiles not of the globe are skipped.
    /// Returns how many were skipped.
    pub fn replace_highlight(&mut self, highlight: Highlight, tiles: impl IntoIterator<Item = GlobeTile>) -> usize {
        let mut skipped = 0;
        let mut new = HashSet::default();
        for tile in tiles {
            if self.check(tile).is_ok() {
                new.insert(tile);
            } else {
                skipped += 1;
            }
        }
        let old = std::mem::take(&mut self.highlighted[highlight as usize]);
        for &tile in old.difference(&new) {
            self.update(tile, |t| texel::with_highlight(t, highlight, false));
        }
        for &tile in new.difference(&old) {
            self.update(tile, |t| texel::with_highlight(t, highlight, true));
        }
        self.highlighted[highlight as usize] = new;
        skipped
    }

    /// Takes a highlight off every tile.
    pub fn clear_highlight(&mut self, highlight: Highlight) {
        self.replace_highlight(highlight, []);
    }

    /// Forgets every tile's state: unexplored, nobody's, no overlay, no highlight.
    pub fn clear(&mut self) {
        self.texels.fill([0; 4]);
        self.highlighted = Default::default();
        self.visible.clear();
        self.changed_everything();
    }

    /// Shows `player`'s fog: each tile's visibility becomes what the fog says `player` knows of
    /// it, the other states (owners, overlays, highlights) untouched.
    ///
    /// # Errors
    /// [`TileStateError::NoSuchPlayer`] for a player the fog does not have,
    /// [`TileStateError::NotOnGlobe`] for the fog of a globe of another size; nothing changes
    /// then.
    pub fn show_fog(&mut self, fog: &GlobeFog, player: u32) -> Result<(), TileStateError> {
        if player >= fog.players() {
            return Err(TileStateError::NoSuchPlayer { player, players: fog.players() });
        }
        let tiles = self.tile_count();
        // A fog of another globe has no state for one of these tiles, or one past them.
        if let Some(tile) = [tiles.checked_sub(1), Some(tiles)]
            .into_iter()
            .flatten()
            .find(|&t| fog.state(player, GlobeTile(t)).is_some() != (t < tiles))
        {
            return Err(TileStateError::NotOnGlobe { tile, tiles });
        }
        for t in 0..tiles {
            let state = fog.state(player, GlobeTile(t)).unwrap_or(FogState::Unexplored);
            self.update(GlobeTile(t), |texel| texel::with_fog(texel, state));
        }
        Ok(())
    }

    /// Writes made so far (a write that changes nothing is not counted).
    #[must_use]
    pub fn writes(&self) -> u64 {
        self.writes
    }

    /// The tiles whose state was written this frame (each at least once), for a system that
    /// follows the state without reading every tile (the minimap); `None` when every tile may
    /// have changed (another globe, a clear, or more writes than it keeps). Read it before
    /// `PostUpdate`'s [`HexTileStateSystems::Pack`](crate::HexTileStateSystems::Pack), which
    /// starts the next frame's list.
    #[must_use]
    pub fn changed_tiles(&self) -> Option<&[GlobeTile]> {
        self.journal.as_deref()
    }

    /// Every tile's texel, by id, as the GPU reads them.
    #[cfg(feature = "render")]
    pub(crate) fn texels(&self) -> &[Texel] {
        &self.texels
    }

    /// The texture rows the GPU's copy has behind, in order; clears the marks.
    #[cfg(feature = "render")]
    pub(crate) fn take_dirty_rows(&mut self) -> BTreeSet<u32> {
        std::mem::take(&mut self.dirty)
    }

    /// Starts a new list of written tiles.
    pub(crate) fn clear_journal(&mut self) {
        match &mut self.journal {
            Some(journal) => journal.clear(),
            None => self.journal = Some(Vec::new()),
        }
    }

    /// Follows a globe of `tiles` tiles: the same count (a hot reload) keeps every state,
    /// another starts afresh.
    pub(crate) fn follow(&mut self, tiles: u32) {
        if self.tile_count() == tiles {
            return;
        }
        *self = Self { texels: vec![[0; 4]; tiles as usize], writes: self.writes, ..Self::default() };
        self.changed_everything();
    }

    fn changed_everything(&mut self) {
        self.journal = None;
        #[cfg(feature = "render")]
        {
            self.dirty = (0..self.tile_count().div_ceil(GLOBE_ROW)).collect();
        }
    }

    fn check(&self, tile: GlobeTile) -> Result<(), TileStateError> {
        if tile.0 < self.tile_count() {
            Ok(())
        } else {
            Err(TileStateError::NotOnGlobe { tile: tile.0, tiles: self.tile_count() })
        }
    }

    fn texel(&self, tile: GlobeTile) -> Texel {
        self.texels.get(tile.0 as usize).copied().unwrap_or([0; 4])
    }

    /// Changes the texel of a tile of the globe (checked by the caller).
    fn update(&mut self, tile: GlobeTile, f: impl FnOnce(Texel) -> Texel) {
        let old = self.texels[tile.0 as usize];
        let new = f(old);
        if old == new {
            return;
        }
        self.writes += 1;
        #[cfg(feature = "render")]
        self.dirty.insert(tile.0 / GLOBE_ROW);
        if texel::is_visible(new) {
            self.visible.insert(tile);
        } else if texel::is_visible(old) {
            self.visible.remove(&tile);
        }
        self.texels[tile.0 as usize] = new;
        if let Some(journal) = &mut self.journal {
            if journal.len() < JOURNAL_LIMIT {
                journal.push(tile);
            } else {
                self.journal = None;
            }
        }
    }
}

/// Follows the globe shown: runs at the end of [`HexTerrainSystems::Map`](crate::HexTerrainSystems::Map).
pub(super) fn follow_globe(globe: Res<HexGlobe>, mut states: ResMut<GlobeTileStates>) {
    if globe.is_changed()
        && let Some(terrain) = globe.globe()
    {
        states.follow(terrain.grid().tile_count());
    }
}

/// Starts the next frame's list of changed tiles (after `Update`, with the flat map's packing).
pub(super) fn clear_journal(mut states: ResMut<GlobeTileStates>) {
    states.bypass_change_detection().clear_journal();
}
