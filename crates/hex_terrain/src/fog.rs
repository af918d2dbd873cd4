//! Every player's fog of war on one map, kept without Bevy so a server keeps it for all players
//! at once: for each player and tile, [`FogState`] (never seen, seen before, in sight now).
//!
//! The rule, written once (tested in `tests/fog.rs` against the units' fields of view computed
//! there): a player's turn ([`FogOfWar::update`]) makes every tile it saw explored, then every
//! tile its units see now ([`Terrain::field_of_view`]) visible. So after a turn a player's
//! visible tiles are the union of its units' fields of view, and what was once seen is never
//! unexplored again. A pure function of the terrain, the units and the fog before: the same on
//! any thread, in any order of players.
//!
//! A fog saves as a file ([`FogOfWar::to_bytes`], [`FogOfWar::to_ron`]) read back only into
//! the map it belongs to, in the envelope of the tile state saves (`crate::save`): versioned,
//! with a checksum, every value checked and a refusal naming what is wrong.

use std::collections::BTreeMap;

use hexx::Hex;
use serde::{Deserialize, Serialize};

use crate::chunk::TileRect;
use crate::config::MAX_WORLD_TILE;
use crate::geometry::Geometry;
use crate::save::{self, FogState, MAX_OWNERS, MAX_SAVED_TILES, SaveError, SavedMap};
use crate::sight::SightError;
use crate::terrain::Terrain;

/// The fog format version this crate writes; it reads every version up to it.
pub const FOG_VERSION: u32 = 1;

/// First bytes of a binary fog save.
pub const FOG_MAGIC: [u8; 4] = *b"HXFG";

/// A fog asked of a player it does not have, or used with another map's terrain.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FogError {
    /// A fog for no players, or for more than [`MAX_OWNERS`].
    #[error("a fog for {count} players: 1..={MAX_OWNERS} are allowed")]
    Players {
        /// The players asked for.
        count: u32,
    },
    /// A player the fog does not have.
    #[error("player {player}: this fog has players 0..{players}")]
    Player {
        /// The player asked for.
        player: u32,
        /// How many players it has.
        players: u32,
    },
    /// A unit whose sight an unbounded world refuses ([`Terrain::field_of_view`]).
    #[error("the unit on {tile:?}: {error}")]
    Sight {
        /// The unit's tile.
        tile: Hex,
        /// What is refused.
        error: SightError,
    },
    /// A terrain of another map than the fog's.
    #[error("the terrain is of another map: its {field} is {terrain}, the fog's map's is {fog}")]
    OtherMap {
        /// The config field that differs.
        field: &'static str,
        /// The terrain's value.
        terrain: String,
        /// The fog's map's value.
        fog: String,
    },
}

/// Every player's fog of war on one map (see the module's rule): players are numbered from 0,
/// as a game setup numbers its starts and [`TileStates`]-like stores number owners.
///
/// [`TileStates`]: https://docs.rs/bevy_hex_terrain/latest/bevy_hex_terrain/struct.TileStates.html
///
/// ```
/// use hex_terrain::{FogOfWar, FogState, MapConfig, MapSize, Terrain};
///
/// let terrain = Terrain::new(MapConfig { size: MapSize::Bounded { x: 20, z: 12 }, ..MapConfig::default() })?;
/// let mut fog = FogOfWar::new(&terrain, 2)?;
/// let scout = terrain.tile_from_offset([5, 5]);
/// // Player 0's turn: one unit with sight 2 on (5, 5).
/// fog.update(&terrain, 0, [(scout, 2)])?;
/// assert_eq!(fog.state(0, scout), Some(FogState::Visible));
/// assert_eq!(fog.state(1, scout), Some(FogState::Unexplored));
/// // The unit left: what it saw stays explored.
/// fog.update(&terrain, 0, [])?;
/// assert_eq!(fog.state(0, scout), Some(FogState::Explored));
/// let saved = fog.to_bytes();
/// assert_eq!(FogOfWar::from_bytes(&saved, &terrain)?, fog);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct FogOfWar {
    map: SavedMap,
    geometry: Geometry,
    views: Vec<View>,
}

impl PartialEq for FogOfWar {
    fn eq(&self, other: &Self) -> bool {
        self.map == other.map && self.views == other.views
    }
}

/// One player's fog.
#[derive(Debug, Clone, PartialEq, Eq)]
struct View {
    cells: Cells,
    /// The tiles visible now, as `(row, column)`.
    visible: Vec<(i32, i32)>,
}

/// Each tile's state: a state per tile, row by row, on a bounded map; the tiles seen, on an
/// unbounded world (which has no end to store densely).
#[derive(Debug, Clone, PartialEq, Eq)]
enum Cells {
    Dense { rect: TileRect, states: Vec<FogState> },
    Sparse(BTreeMap<(i32, i32), FogState>),
}

impl Cells {
    fn new(bounds: Option<TileRect>) -> Self {
        match bounds {
            Some(rect) => {
                let tiles = rect.iter().count();
                Self::Dense { rect, states: vec![FogState::Unexplored; tiles] }
            }
            None => Self::Sparse(BTreeMap::new()),
        }
    }

    /// Index of a tile's `(row, column)` in a dense store.
    fn index(rect: TileRect, (row, col): (i32, i32)) -> Option<usize> {
        rect.index([col, row])
    }

    fn get(&self, at: (i32, i32)) -> FogState {
        match self {
            Self::Dense { rect, states } => Self::index(*rect, at).map_or(FogState::Unexplored, |i| states[i]),
            Self::Sparse(tiles) => tiles.get(&at).copied().unwrap_or_default(),
        }
    }

    fn set(&mut self, at: (i32, i32), state: FogState) {
        match self {
            Self::Dense { rect, states } => {
                if let Some(i) = Self::index(*rect, at) {
                    states[i] = state;
                }
            }
            Self::Sparse(tiles) => {
                if state == FogState::Unexplored {
                    tiles.remove(&at);
                } else {
                    tiles.insert(at, state);
                }
            }
        }
    }

    /// Every tile not unexplored, as `((row, column), state)`, row by row.
    fn seen(&self) -> Box<dyn Iterator<Item = ((i32, i32), FogState)> + '_> {
        match self {
            Self::Dense { rect, states } => Box::new(
                rect.iter()
                    .zip(states)
                    .filter(|&(_, &s)| s != FogState::Unexplored)
                    .map(|([col, row], &s)| ((row, col), s)),
            ),
            Self::Sparse(tiles) => Box::new(tiles.iter().map(|(&at, &s)| (at, s))),
        }
    }
}

impl FogOfWar {
    /// A fog of the terrain's map for `players` players, every tile unexplored to each.
    ///
    /// # Errors
    /// [`FogError::Players`] for 0 players or more than [`MAX_OWNERS`].
    pub fn new(terrain: &Terrain, players: u32) -> Result<Self, FogError> {
        if !(1..=MAX_OWNERS).contains(&players) {
            return Err(FogError::Players { count: players });
        }
        let geometry = terrain.geometry().clone();
        let view = View { cells: Cells::new(geometry.bounds()), visible: Vec::new() };
        Ok(Self { map: SavedMap::of(terrain.config()), views: vec![view; players as usize], geometry })
    }

    /// How many players it keeps (players `0..players()`).
    #[must_use]
    pub fn players(&self) -> u32 {
        self.views.len() as u32
    }

    /// What `player` knows of a tile; `None` for a player it does not have or a tile not on the
    /// map (on a wrapping map, any copy of a tile answers for it).
    #[must_use]
    pub fn state(&self, player: u32, tile: Hex) -> Option<FogState> {
        let view = self.views.get(player as usize)?;
        Some(view.cells.get(self.key(tile)?))
    }

    /// The tiles `player` sees now, row by row (the map's own tiles); empty for a player it
    /// does not have.
    pub fn visible(&self, player: u32) -> impl Iterator<Item = Hex> + '_ {
        let visible = self.views.get(player as usize).map_or(&[][..], |v| &v.visible[..]);
        visible.iter().map(|&(row, col)| self.geometry.tile_from_offset([col, row]))
    }

    /// Every tile `player` has seen (explored or visible now) with its state, row by row; empty
    /// for a player it does not have.
    pub fn seen(&self, player: u32) -> impl Iterator<Item = (Hex, FogState)> + '_ {
        let view = self.views.get(player as usize);
        view.into_iter()
            .flat_map(|v| v.cells.seen())
            .map(|((row, col), s)| (self.geometry.tile_from_offset([col, row]), s))
    }

    /// `player`'s turn: every tile it saw becomes explored, then every tile its units see now
    /// becomes visible. `units` gives each unit's tile and sight radius (the field of view of
    /// [`Terrain::field_of_view`], with the sight rule's bonus); a unit off the map sees
    /// nothing.
    ///
    /// # Errors
    /// [`FogError::Player`] for a player it does not have, [`FogError::OtherMap`] for a terrain
    /// of another map, [`FogError::Sight`] for a unit whose sight an unbounded world refuses
    /// (past [`MAX_UNBOUNDED_SIGHT`](crate::MAX_UNBOUNDED_SIGHT)); the fog is unchanged then.
    pub fn update(
        &mut self,
        terrain: &Terrain,
        player: u32,
        units: impl IntoIterator<Item = (Hex, u32)>,
    ) -> Result<(), FogError> {
        if let Some((field, terrain, fog)) = SavedMap::of(terrain.config()).difference(&self.map) {
            return Err(FogError::OtherMap { field, terrain, fog });
        }
        let players = self.players();
        let Some(view) = self.views.get_mut(player as usize) else {
            return Err(FogError::Player { player, players });
        };
        let viewers = units
            .into_iter()
            .map(|(tile, radius)| terrain.viewer(tile, radius).map_err(|error| FogError::Sight { tile, error }))
            .collect::<Result<Vec<_>, _>>()?;
        for &at in &view.visible {
            view.cells.set(at, FogState::Explored);
        }
        view.visible.clear();
        for viewer in viewers.into_iter().flatten() {
            terrain.each_seen(viewer, |tile| {
                let [col, row] = terrain.offset_of(tile);
                if view.cells.get((row, col)) != FogState::Visible {
                    view.cells.set((row, col), FogState::Visible);
                    view.visible.push((row, col));
                }
            });
        }
        view.visible.sort_unstable();
        Ok(())
    }

    /// A tile's `(row, column)` on the map (its own tile on a wrapping map).
    fn key(&self, tile: Hex) -> Option<(i32, i32)> {
        if !self.geometry.contains(tile) {
            return None;
        }
        let [col, row] = self.geometry.offset_of(self.geometry.wrap_tile(tile));
        Some((row, col))
    }

    /// The fog as compact binary: [`FOG_MAGIC`], the version, the payload's length, the payload
    /// (CBOR: the map, then each player's runs of tiles in one state along a row), and a CRC-32
    /// of all of it, so a damaged file is refused rather than read as another fog.
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        save::seal_cbor(FOG_MAGIC, FOG_VERSION, &self.file())
    }

    /// Reads a binary fog save into the terrain's map.
    ///
    /// # Errors
    /// [`SaveError::Corrupt`] (magic, length, checksum or payload), [`SaveError::Version`] for
    /// a newer format, and what [`FogOfWar::from_ron`] refuses.
    pub fn from_bytes(bytes: &[u8], terrain: &Terrain) -> Result<Self, SaveError> {
        let (version, file): (u32, FogFile) = save::open_cbor(bytes, FOG_MAGIC, FOG_VERSION)?;
        if file.version != version {
            return Err(SaveError::Corrupt(format!("the header says version {version}, the payload {}", file.version)));
        }
        Self::from_file(file, terrain)
    }

    /// The fog as RON text, for people and tools: the map, then each player's runs
    /// `(column, row, length, state)` of tiles along a row in one state (1 explored, 2 visible).
    #[must_use]
    pub fn to_ron(&self) -> String {
        let config = ron::ser::PrettyConfig::new().depth_limit(2).struct_names(false);
        ron::ser::to_string_pretty(&self.file(), config).expect("a fog always serialises")
    }

    /// Reads a RON fog save into the terrain's map.
    ///
    /// # Errors
    /// [`SaveError::Syntax`] with the line and column; [`SaveError::Version`],
    /// [`SaveError::OtherMap`], [`SaveError::Players`], [`SaveError::TooManyTiles`], and
    /// [`SaveError::Tile`] naming the run that is off the map, overlaps another or holds a
    /// state other than explored or visible. Nothing is read then.
    pub fn from_ron(text: &str, terrain: &Terrain) -> Result<Self, SaveError> {
        let file: FogFile = ron::from_str(text).map_err(|e| SaveError::Syntax {
            line: e.span.start.line,
            column: e.span.start.col,
            message: e.code.to_string(),
        })?;
        Self::from_file(file, terrain)
    }

    /// The file form: each player's runs, row by row.
    fn file(&self) -> FogFile {
        let players = self
            .views
            .iter()
            .map(|view| {
                let mut runs: Vec<Run> = Vec::new();
                for ((row, col), state) in view.cells.seen() {
                    match runs.last_mut() {
                        Some(run) if run.1 == row && run.0 + run.2 as i32 == col && run.3 == state as u8 => run.2 += 1,
                        _ => runs.push((col, row, 1, state as u8)),
                    }
                }
                runs
            })
            .collect();
        FogFile { version: FOG_VERSION, map: self.map.clone(), players }
    }

    /// A fog from its file form, every value checked against the terrain's map.
    fn from_file(file: FogFile, terrain: &Terrain) -> Result<Self, SaveError> {
        if file.version == 0 || file.version > FOG_VERSION {
            return Err(SaveError::Version { found: file.version, newest: FOG_VERSION });
        }
        if let Some((field, saved, current)) = file.map.difference(&SavedMap::of(terrain.config())) {
            return Err(SaveError::OtherMap { field, saved, current });
        }
        let count = u32::try_from(file.players.len()).unwrap_or(u32::MAX);
        if !(1..=MAX_OWNERS).contains(&count) {
            return Err(SaveError::Players { count: file.players.len() });
        }
        let runs: usize = file.players.iter().map(Vec::len).sum();
        if runs > MAX_SAVED_TILES {
            return Err(SaveError::TooManyTiles { count: runs });
        }
        let mut fog = Self::new(terrain, count).expect("the player count is checked");
        let (columns, rows) = match fog.geometry.bounds() {
            Some(b) => (b.min[0]..b.max[0], b.min[1]..b.max[1]),
            None => (-MAX_WORLD_TILE..MAX_WORLD_TILE, -MAX_WORLD_TILE..MAX_WORLD_TILE),
        };
        let mut index = 0;
        for (player, runs) in file.players.into_iter().enumerate() {
            let view = &mut fog.views[player];
            let mut tiles = 0usize;
            for (col, row, length, state) in runs {
                let bad = |problem: String| SaveError::Tile {
                    index,
                    at: (col, row),
                    problem: format!("player {player}: {problem}"),
                };
                let state = match FogState::from_bits(state) {
                    Some(s @ (FogState::Explored | FogState::Visible)) => s,
                    _ => return Err(bad(format!("fog state {state}: 1 (explored) or 2 (visible) are allowed"))),
                };
                let end = i64::from(col) + i64::from(length);
                if length == 0 || !rows.contains(&row) || !columns.contains(&col) || end > i64::from(columns.end) {
                    return Err(bad(format!(
                        "a run of {length} tiles: runs of 1 or more tiles within columns {}..{} and rows {}..{} are \
                         allowed",
                        columns.start, columns.end, rows.start, rows.end
                    )));
                }
                tiles += length as usize;
                if tiles > MAX_SAVED_TILES {
                    return Err(SaveError::TooManyTiles { count: tiles });
                }
                for c in col..col + length as i32 {
                    if view.cells.get((row, c)) != FogState::Unexplored {
                        return Err(bad(format!("column {c} is listed twice: each tile at most once")));
                    }
                    view.cells.set((row, c), state);
                    if state == FogState::Visible {
                        view.visible.push((row, c));
                    }
                }
                index += 1;
            }
            view.visible.sort_unstable();
        }
        Ok(fog)
    }
}

/// A run of tiles of one row in one state: `(column, row, length, state)`.
type Run = (i32, i32, u32, u8);

/// A fog save's contents.
#[derive(Serialize, Deserialize)]
struct FogFile {
    version: u32,
    map: SavedMap,
    /// Each player's runs, row by row.
    players: Vec<Vec<Run>>,
}
