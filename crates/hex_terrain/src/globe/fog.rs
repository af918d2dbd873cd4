//! Every player's fog of war on a globe: the rule of the flat map's [`FogOfWar`](crate::FogOfWar)
//! on the globe's tiles. A player's turn ([`GlobeFog::update`]) makes every tile it saw explored,
//! then every tile its units see now ([`GlobeTerrain::field_of_view`]) visible; what was once
//! seen is never unexplored again. Saved in the envelope of the tile state saves (versioned,
//! with a checksum, every value checked): each player's runs of tile ids in one state.

use serde::{Deserialize, Serialize};

use super::GlobeTile;
use super::terrain::GlobeTerrain;
use crate::fog::FogError;
use crate::save::{self, FogState, MAX_OWNERS, MAX_SAVED_TILES, SaveError, SavedMap};

/// The globe fog format version this crate writes; it reads every version up to it.
pub const GLOBE_FOG_VERSION: u32 = 1;

/// First bytes of a binary globe fog save.
pub const GLOBE_FOG_MAGIC: [u8; 4] = *b"HXGF";

/// Every player's fog of war on one globe, players numbered from 0.
///
/// ```
/// use hex_terrain::{FogState, GlobeFog, GlobeTerrain, GlobeTile, MapConfig, MapSize};
///
/// let globe = GlobeTerrain::new(MapConfig { size: MapSize::Globe { frequency: 4 }, ..MapConfig::default() })?;
/// let mut fog = GlobeFog::new(&globe, 2)?;
/// let scout = GlobeTile(0); // the north pole's pentagon
/// fog.update(&globe, 0, [(scout, 2)])?;
/// assert_eq!(fog.state(0, scout), Some(FogState::Visible));
/// assert_eq!(fog.state(1, scout), Some(FogState::Unexplored));
/// fog.update(&globe, 0, [])?;
/// assert_eq!(fog.state(0, scout), Some(FogState::Explored));
/// assert_eq!(GlobeFog::from_bytes(&fog.to_bytes(), &globe)?, fog);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GlobeFog {
    map: SavedMap,
    /// Each player's state of every tile, by id, and the tiles visible now.
    views: Vec<(Vec<FogState>, Vec<GlobeTile>)>,
}

impl GlobeFog {
    /// A fog for `players` players, every tile unexplored.
    ///
    /// # Errors
    /// [`FogError::Players`] for no players or more than [`MAX_OWNERS`].
    pub fn new(globe: &GlobeTerrain, players: u32) -> Result<Self, FogError> {
        if !(1..=MAX_OWNERS).contains(&players) {
            return Err(FogError::Players { count: players });
        }
        let tiles = globe.grid().tile_count() as usize;
        Ok(Self {
            map: SavedMap::of(globe.config()),
            views: (0..players).map(|_| (vec![FogState::Unexplored; tiles], Vec::new())).collect(),
        })
    }

    /// How many players it has.
    #[must_use]
    pub fn players(&self) -> u32 {
        self.views.len() as u32
    }

    /// A player's state of a tile; `None` for a player or tile it does not have.
    #[must_use]
    pub fn state(&self, player: u32, tile: GlobeTile) -> Option<FogState> {
        self.views.get(player as usize)?.0.get(tile.0 as usize).copied()
    }

    /// The tiles a player sees now, by id.
    pub fn visible(&self, player: u32) -> impl Iterator<Item = GlobeTile> + '_ {
        self.views.get(player as usize).into_iter().flat_map(|v| v.1.iter().copied())
    }

    /// A player's turn: what it saw becomes explored, then what `units` (each unit's tile and
    /// sight radius) see becomes visible. A unit on a tile not of the globe sees nothing.
    ///
    /// # Errors
    /// [`FogError::Player`] for a player it does not have, [`FogError::OtherMap`] for another
    /// globe's terrain; the fog is unchanged then.
    pub fn update(
        &mut self,
        globe: &GlobeTerrain,
        player: u32,
        units: impl IntoIterator<Item = (GlobeTile, u32)>,
    ) -> Result<(), FogError> {
        if let Some((field, terrain, fog)) = SavedMap::of(globe.config()).difference(&self.map) {
            return Err(FogError::OtherMap { field, terrain, fog });
        }
        let players = self.players();
        let Some((states, visible)) = self.views.get_mut(player as usize) else {
            return Err(FogError::Player { player, players });
        };
        for t in visible.drain(..) {
            states[t.0 as usize] = FogState::Explored;
        }
        for (unit, radius) in units {
            for t in globe.field_of_view(unit, radius) {
                if states[t.0 as usize] != FogState::Visible {
                    states[t.0 as usize] = FogState::Visible;
                    visible.push(t);
                }
            }
        }
        visible.sort_unstable();
        Ok(())
    }

    /// The fog as compact binary: [`GLOBE_FOG_MAGIC`], the version, the payload's length, the
    /// payload (CBOR: the map, then each player's runs of tile ids in one state) and a CRC-32.
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        save::seal_cbor(GLOBE_FOG_MAGIC, GLOBE_FOG_VERSION, &self.file())
    }

    /// Reads a binary globe fog save into the globe's map.
    ///
    /// # Errors
    /// [`SaveError::Corrupt`] (magic, length, checksum or payload), [`SaveError::Version`] for a
    /// newer format, [`SaveError::OtherMap`], [`SaveError::Players`], [`SaveError::TooManyTiles`],
    /// and [`SaveError::Tile`] naming a run past the globe's tiles, overlapping another or
    /// holding a state other than explored or visible. Nothing is read then.
    pub fn from_bytes(bytes: &[u8], globe: &GlobeTerrain) -> Result<Self, SaveError> {
        let (version, file): (u32, FogFile) = save::open_cbor(bytes, GLOBE_FOG_MAGIC, GLOBE_FOG_VERSION)?;
        if file.version != version {
            return Err(SaveError::Corrupt(format!("the header says version {version}, the payload {}", file.version)));
        }
        Self::from_file(file, globe)
    }

    fn file(&self) -> FogFile {
        let players = self
            .views
            .iter()
            .map(|(states, _)| {
                let mut runs: Vec<Run> = Vec::new();
                for (id, &state) in states.iter().enumerate().filter(|(_, s)| **s != FogState::Unexplored) {
                    match runs.last_mut() {
                        Some(run) if run.0 + run.1 == id as u32 && run.2 == state as u8 => run.1 += 1,
                        _ => runs.push((id as u32, 1, state as u8)),
                    }
                }
                runs
            })
            .collect();
        FogFile { version: GLOBE_FOG_VERSION, map: self.map.clone(), players }
    }

    fn from_file(file: FogFile, globe: &GlobeTerrain) -> Result<Self, SaveError> {
        if file.version == 0 || file.version > GLOBE_FOG_VERSION {
            return Err(SaveError::Version { found: file.version, newest: GLOBE_FOG_VERSION });
        }
        if let Some((field, saved, current)) = file.map.difference(&SavedMap::of(globe.config())) {
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
        let mut fog = Self::new(globe, count).expect("the player count is checked");
        let tiles = globe.grid().tile_count();
        let mut index = 0;
        for (player, runs) in file.players.into_iter().enumerate() {
            let (states, visible) = &mut fog.views[player];
            for (first, length, state) in runs {
                let bad = |problem: String| SaveError::Tile {
                    index,
                    at: (first as i32, 0),
                    problem: format!("player {player}: {problem}"),
                };
                let state = match FogState::from_bits(state) {
                    Some(s @ (FogState::Explored | FogState::Visible)) => s,
                    _ => return Err(bad(format!("fog state {state}: 1 (explored) or 2 (visible) are allowed"))),
                };
                if length == 0 || u64::from(first) + u64::from(length) > u64::from(tiles) {
                    return Err(bad(format!(
                        "a run of {length} tiles from tile {first}: runs of 1 or more of the globe's tiles 0..{tiles} \
                         are allowed"
                    )));
                }
                for id in first..first + length {
                    if states[id as usize] != FogState::Unexplored {
                        return Err(bad(format!("tile {id} is listed twice: each tile at most once")));
                    }
                    states[id as usize] = state;
                    if state == FogState::Visible {
                        visible.push(GlobeTile(id));
                    }
                }
                index += 1;
            }
            visible.sort_unstable();
        }
        Ok(fog)
    }
}

/// A run of tiles in one state: `(first id, length, state)`.
type Run = (u32, u32, u8);

/// A globe fog save's contents.
#[derive(Serialize, Deserialize)]
struct FogFile {
    version: u32,
    map: SavedMap,
    /// Each player's runs, by id.
    players: Vec<Vec<Run>>,
}
