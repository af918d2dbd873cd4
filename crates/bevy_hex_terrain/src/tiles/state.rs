//! [`TileStates`]: per-tile game state (fog of war, owner, lens overlay, highlights) written by
//! the game, kept for every tile on the CPU and mirrored into the window the GPU texture holds.

use bevy::platform::collections::HashSet;
use bevy::prelude::*;
use hex_terrain::hexx::{Hex, HexOrientation};
use hex_terrain::{Geometry, MapConfig, MapSize, TileRect};

mod fog;
mod save;

use super::store::TileStore;
use super::texel::{self, FOG_MASK, bit};
use super::window::{Texel, TexelWindow, TileStateUpload};

pub use super::error::TileStateError;
pub use hex_terrain::save::{FogState, Highlight, MAX_OWNERS};

/// Per-tile game state the terrain material draws without rebuilding a mesh: fog of war
/// ([`FogState`]), territory ([`set_owner`](Self::set_owner)), a lens overlay color and any
/// number of highlighted tiles.
///
/// Every tile's state is kept here, loaded or not (a chunk streamed out and back keeps it); the
/// GPU holds a window of tiles around the loaded chunks (the whole map when it fits in
/// [`HexTileStateSettings::max_window`](super::HexTileStateSettings::max_window)) and receives only the rows that changed, once a frame,
/// after `Update`. The state is kept when the map file is hot-reloaded (tiles that fall off a
/// resized map are dropped) and cleared when another map is loaded. What is written while the
/// plugin's map file loads (from `Startup` on, any tile: the placeholder is not the map) is kept
/// on the tiles of the map once it applies.
///
/// It follows [`HexMap`](crate::HexMap) at the end of
/// [`HexTerrainSystems::Map`](crate::HexTerrainSystems::Map): write it from a system after that
/// set (`.after(HexTerrainSystems::Map)`) when the tiles you write come from the map you read,
/// so that on the frame another map applies you write on the new map's bounds, not the old.
///
/// A write to a tile outside a bounded map, an owner beyond [`MAX_OWNERS`] or a non-finite
/// overlay color is refused with a [`TileStateError`] and changes nothing.
#[derive(Resource, Debug, Clone, Reflect)]
#[reflect(Resource)]
pub struct TileStates {
    #[reflect(ignore)]
    tiles: TileStore,
    #[reflect(ignore)]
    highlighted: [HashSet<Hex>; 3],
    /// The map's geometry (the core's): its bounds, orientation, offset coordinates and
    /// east-west wrap.
    #[reflect(ignore)]
    geometry: MapGeometry,
    #[reflect(ignore)]
    window: TexelWindow,
    /// The tiles in sight, so [`TileStates::hide_visible`] touches only them (a game's explored
    /// tiles grow all game long; its visible ones do not).
    #[reflect(ignore)]
    visible: HashSet<IVec2>,
    /// The tiles written since the journal was last cleared (after `PostUpdate`), for systems
    /// following the state incrementally; `None` once everything may have changed.
    #[reflect(ignore)]
    journal: Option<Vec<IVec2>>,
    writes: u64,
    /// The map followed: its id, whether it was the placeholder waiting for its file, and its
    /// config generation.
    #[reflect(ignore)]
    followed: Option<(u64, bool, u64)>,
}

/// The core's geometry of the map the states follow (an unbounded map before any): one place for
/// offsets and the east-west wrap.
#[derive(Debug, Clone)]
struct MapGeometry(Geometry);

impl Default for MapGeometry {
    fn default() -> Self {
        Self(Geometry::new(&MapConfig { size: MapSize::Unbounded, ..MapConfig::default() }))
    }
}

impl std::ops::Deref for MapGeometry {
    type Target = Geometry;

    fn deref(&self) -> &Geometry {
        &self.0
    }
}

/// Most tiles [`TileStates::changed_tiles`] lists in a frame; past it, it answers "everything".
const JOURNAL_LIMIT: usize = 1 << 16;

impl Default for TileStates {
    fn default() -> Self {
        Self {
            tiles: TileStore::default(),
            highlighted: Default::default(),
            geometry: MapGeometry::default(),
            window: TexelWindow::new(IVec2::ZERO, UVec2::ONE),
            visible: HashSet::default(),
            journal: None,
            writes: 0,
            followed: None,
        }
    }
}

impl TileStates {
    /// What the player knows of a tile.
    #[must_use]
    pub fn visibility(&self, tile: Hex) -> FogState {
        texel::fog(self.texel(tile))
    }

    /// The owner of a tile, a player `0..MAX_OWNERS` numbered as a game setup numbers its starts
    /// ([`HexMap::start`](crate::HexMap::start)), if any.
    #[must_use]
    pub fn owner(&self, tile: Hex) -> Option<u32> {
        texel::owner(self.texel(tile))
    }

    /// The overlay color of a tile, if any (drawn while the lens is on).
    #[must_use]
    pub fn overlay(&self, tile: Hex) -> Option<Color> {
        texel::overlay(self.texel(tile))
    }

    /// Whether a tile carries a highlight.
    #[must_use]
    pub fn is_highlighted(&self, tile: Hex, highlight: Highlight) -> bool {
        texel::is_highlighted(self.texel(tile), highlight)
    }

    /// The tiles carrying a highlight.
    pub fn highlighted(&self, highlight: Highlight) -> impl Iterator<Item = Hex> + '_ {
        self.highlighted[highlight as usize].iter().copied()
    }

    /// Sets what the player knows of a tile.
    ///
    /// # Errors
    /// [`TileStateError::OutsideMap`]; nothing changes.
    pub fn set_visibility(&mut self, tile: Hex, fog: FogState) -> Result<(), TileStateError> {
        let oc = self.check(tile)?;
        self.update(oc, |t| *t = texel::with_fog(*t, fog));
        Ok(())
    }

    /// Makes every visible tile explored (the start of a sight update: the game then marks what
    /// its units see now as visible). Its cost is the number of visible tiles, however many have
    /// been explored.
    pub fn hide_visible(&mut self) {
        for oc in std::mem::take(&mut self.visible) {
            let old = self.tiles.get(oc);
            self.store(oc, old, texel::with_fog(old, FogState::Explored));
        }
    }

    /// Gives a tile to a player (`0..MAX_OWNERS`, numbered as a game setup numbers its starts),
    /// or to nobody.
    ///
    /// # Errors
    /// [`TileStateError::OutsideMap`], [`TileStateError::OwnerOutOfRange`]; nothing changes.
    pub fn set_owner(&mut self, tile: Hex, owner: Option<u32>) -> Result<(), TileStateError> {
        let oc = self.check(tile)?;
        let word = texel::owner_word(owner)?;
        self.update(oc, |t| t[1] = word);
        Ok(())
    }

    /// Sets a tile's overlay color (its alpha is the strength; 8 bits a channel, sRGB), or
    /// removes it.
    ///
    /// # Errors
    /// [`TileStateError::OutsideMap`], [`TileStateError::OverlayNotFinite`]; nothing changes.
    pub fn set_overlay(&mut self, tile: Hex, color: Option<Color>) -> Result<(), TileStateError> {
        let oc = self.check(tile)?;
        let [rg, ba] = texel::overlay_words(color)?;
        self.update(oc, |t| [t[2], t[3]] = [rg, ba]);
        Ok(())
    }

    /// Puts a highlight on a tile or takes it off.
    ///
    /// # Errors
    /// [`TileStateError::OutsideMap`]; nothing changes.
    pub fn set_highlight(&mut self, tile: Hex, highlight: Highlight, on: bool) -> Result<(), TileStateError> {
        let tile = self.wrap_tile(tile);
        let oc = self.check(tile)?;
        let set = &mut self.highlighted[highlight as usize];
        let changed = if on { set.insert(tile) } else { set.remove(&tile) };
        if changed {
            self.update(oc, |t| *t = texel::with_highlight(*t, highlight, on));
        }
        Ok(())
    }

    /// Makes `tiles` the only ones carrying `highlight` (however many); tiles outside the map
    /// are skipped. Returns how many were skipped.
    pub fn replace_highlight(&mut self, highlight: Highlight, tiles: impl IntoIterator<Item = Hex>) -> usize {
        let mut skipped = 0;
        let mut new = HashSet::default();
        for tile in tiles {
            let tile = self.wrap_tile(tile);
            if self.check(tile).is_ok() {
                new.insert(tile);
            } else {
                skipped += 1;
            }
        }
        let old = std::mem::take(&mut self.highlighted[highlight as usize]);
        for &tile in old.difference(&new) {
            self.update(self.offset_of(tile), |t| *t = texel::with_highlight(*t, highlight, false));
        }
        for &tile in new.difference(&old) {
            self.update(self.offset_of(tile), |t| *t = texel::with_highlight(*t, highlight, true));
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
        self.tiles = TileStore::new(self.geometry.bounds());
        self.highlighted = Default::default();
        self.visible.clear();
        self.window.clear();
        self.journal = None;
    }

    /// Writes made so far (a write that changes nothing is not counted).
    #[must_use]
    pub fn writes(&self) -> u64 {
        self.writes
    }

    /// Tiles with a state other than the default (unexplored, nobody's, no overlay, no
    /// highlight): the memory the store holds.
    #[must_use]
    pub fn stored_tiles(&self) -> usize {
        self.tiles.len()
    }

    /// The window of tiles the GPU texture holds: first offset coordinate `[col, row]` and
    /// size in tiles.
    #[must_use]
    pub fn window(&self) -> (IVec2, UVec2) {
        (self.window.origin(), self.window.size())
    }

    /// Offset coordinate of a tile, in the map's orientation ([`Geometry::offset_of`]).
    #[must_use]
    pub fn offset_of(&self, tile: Hex) -> IVec2 {
        IVec2::from(self.geometry.offset_of(tile))
    }

    /// The map's hex orientation (which offset coordinates mean).
    #[must_use]
    pub fn orientation(&self) -> HexOrientation {
        self.geometry.layout().orientation
    }

    /// The tile of the map a tile stands for: on a wrapping map, past its east or west edge,
    /// the tile of the same row whose column is the tile's column modulo the map's width; the
    /// tile itself otherwise. Every method takes such tiles.
    #[must_use]
    pub fn wrap_tile(&self, tile: Hex) -> Hex {
        self.geometry.wrap_tile(tile)
    }

    /// The tile's offset coordinate (of the map's own tile on a wrapping map), if it is on the
    /// map.
    fn check(&self, tile: Hex) -> Result<IVec2, TileStateError> {
        let oc = self.offset_of(self.wrap_tile(tile));
        match self.geometry.bounds() {
            Some(bounds) if !bounds.contains(oc.to_array()) => {
                Err(TileStateError::OutsideMap { tile, offset: oc.to_array(), bounds })
            }
            _ => Ok(oc),
        }
    }

    fn texel(&self, tile: Hex) -> Texel {
        self.tiles.get(self.offset_of(self.wrap_tile(tile)))
    }

    /// Changes the texel of a tile on the map (checked by the caller).
    fn update(&mut self, oc: IVec2, f: impl FnOnce(&mut Texel)) {
        let old = self.tiles.get(oc);
        let mut texel = old;
        f(&mut texel);
        self.store(oc, old, texel);
    }

    fn store(&mut self, oc: IVec2, old: Texel, texel: Texel) {
        if old == texel {
            return;
        }
        self.writes += 1;
        if texel::is_visible(texel) {
            self.visible.insert(oc);
        } else if texel::is_visible(old) {
            self.visible.remove(&oc);
        }
        self.tiles.set(oc, texel);
        self.window.write(oc, texel);
        if let Some(journal) = &mut self.journal {
            if journal.len() < JOURNAL_LIMIT {
                journal.push(oc);
            } else {
                self.journal = None;
            }
        }
    }

    /// The tiles whose state was written this frame (each at least once, maybe more), for a
    /// system that follows the state without reading every tile (the minimap); `None` when every
    /// tile may have changed (another map, a load, a clear, or more writes than it keeps). Read it
    /// in `PostUpdate` before [`HexTileStateSystems::Pack`](super::HexTileStateSystems::Pack),
    /// which starts the next frame's list.
    #[must_use]
    pub fn changed_tiles(&self) -> Option<impl Iterator<Item = Hex> + '_> {
        let geometry = &self.geometry;
        self.journal.as_ref().map(move |j| j.iter().map(move |oc| geometry.tile_from_offset(oc.to_array())))
    }

    /// Starts a new list of written tiles.
    pub(crate) fn clear_journal(&mut self) {
        match &mut self.journal {
            Some(journal) => journal.clear(),
            None => self.journal = Some(Vec::new()),
        }
    }

    /// Follows the map: its id, whether it is the placeholder waiting for its file, its config
    /// generation and its geometry. Another config of the same map (a hot reload) keeps the
    /// states of tiles still on it; another map clears them, except after the placeholder: what
    /// was written while the map file loaded (anywhere: the placeholder's tiles are not the
    /// map's) is kept on the tiles of the map.
    pub(crate) fn follow(&mut self, geometry: &Geometry, map_id: u64, waiting: bool, config: u64) {
        let now = (map_id, waiting, config);
        if self.followed == Some(now) {
            return;
        }
        let keep = self.followed.is_none_or(|(id, was_waiting, _)| was_waiting || id == map_id);
        self.followed = Some(now);
        if waiting {
            self.set_map(&MapGeometry::default(), keep);
        } else {
            self.set_map(geometry, keep);
        }
    }

    /// Follows a new map's geometry (bounds, orientation, east-west wrap). With `keep`, tiles
    /// still on the map keep their state; otherwise everything is forgotten.
    pub(crate) fn set_map(&mut self, geometry: &Geometry, keep: bool) {
        let old_geometry = std::mem::replace(&mut self.geometry, MapGeometry(geometry.clone()));
        let old = std::mem::take(&mut self.tiles);
        self.tiles = TileStore::new(geometry.bounds());
        self.visible.clear();
        self.journal = None;
        if !keep {
            self.highlighted = Default::default();
            self.window.clear();
            return;
        }
        // Offset coordinates may change meaning (another orientation): through the hexes.
        for (oc, texel) in old.stored() {
            let tile = old_geometry.tile_from_offset(oc.to_array());
            if let Ok(oc) = self.check(tile) {
                self.tiles.set(oc, texel);
                if texel::is_visible(texel) {
                    self.visible.insert(oc);
                }
            }
        }
        let bounds: Option<TileRect> = geometry.bounds();
        for set in &mut self.highlighted {
            set.retain(|&h| bounds.is_none_or(|b| b.contains(geometry.offset_of(h))));
        }
        self.window.refill_all(&self.tiles);
    }

    /// Places the window (a new size makes a new texture).
    pub(crate) fn refill_window(&mut self, origin: IVec2, size: UVec2) {
        self.window.reposition(origin, size, &self.tiles);
    }

    /// Whether the texture has changes to upload.
    #[must_use]
    pub fn has_upload(&self) -> bool {
        self.window.is_dirty()
    }

    /// The rows changed since the last call, ready for the texture; the plugin calls this once
    /// a frame (a caller taking them would steal the frame's upload, so it is the crate's).
    pub(crate) fn take_upload(&mut self) -> TileStateUpload {
        self.window.take_upload()
    }

    /// Generation of the texture (a new one each time the window size changes).
    #[must_use]
    pub fn texture_generation(&self) -> u64 {
        self.window.texture()
    }
}
