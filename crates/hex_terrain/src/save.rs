//! Saved tile state: what a game writes on the map's tiles (fog of war, owners, lens overlays,
//! highlights) as a file a later version of the crate reads back. Two encodings of one
//! [`TileStateSave`]: RON for people and tools, and a compact binary for games (a header, CBOR,
//! and a CRC-32 that catches a corrupted file). Bevy-free, so it is fuzzed with the core; the
//! plugin's `TileStates` converts to and from it.
//!
//! A save names the map it belongs to ([`SavedMap`]: seed, size, wrap, orientation, offset), and
//! [`TileStateSave::check`] refuses one of another map, of a newer format, or with a tile that
//! is not on the map, naming what is wrong, before anything is changed.

use serde::{Deserialize, Serialize};

use crate::config::{MAX_WORLD_TILE, MapConfig, MapSize, Orientation};

/// The format version this crate writes; it reads every version up to it. Version 2 numbers
/// owners as players from 0 (version 1 numbered them from 1: read, they become players from 0).
pub const SAVE_VERSION: u32 = 2;

/// How many players may own tiles: owners are players `0..MAX_OWNERS`, numbered as a game
/// setup numbers its starts (Civilization VI's largest map has 12 civilizations and 16
/// city-states).
pub const MAX_OWNERS: u32 = 64;

/// First bytes of a binary save.
pub const SAVE_MAGIC: [u8; 4] = *b"HXTS";

/// Most tiles a save may hold: every tile of the largest bounded map the stores keep densely
/// (a hostile file cannot make a load allocate more).
pub const MAX_SAVED_TILES: usize = 1 << 22;

/// What a player knows of a tile, ordered from least (unexplored) to most (visible).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum FogState {
    /// Never seen: drawn dark, without terrain detail.
    #[default]
    Unexplored = 0,
    /// Seen before, not now: drawn desaturated.
    Explored = 1,
    /// In sight: drawn in full color.
    Visible = 2,
}

impl FogState {
    /// The state a fog value stands for (`0` unexplored, `1` explored, `2` visible), `None` for
    /// any other value: the one decoding of fog bits for saves, texels and tools.
    #[must_use]
    pub fn from_bits(bits: u8) -> Option<Self> {
        match bits {
            0 => Some(Self::Unexplored),
            1 => Some(Self::Explored),
            2 => Some(Self::Visible),
            _ => None,
        }
    }
}

/// A tile tint; a tile may carry several.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
#[repr(u8)]
pub enum Highlight {
    /// The tile under the cursor.
    Hovered = 0,
    /// Selected tiles (a unit's tile, a city's).
    Selected = 1,
    /// Tiles a unit can reach, or any other set the game shows.
    Reachable = 2,
}

impl Highlight {
    /// Every highlight.
    pub const ALL: [Self; 3] = [Self::Hovered, Self::Selected, Self::Reachable];
}

/// The map a save belongs to: what decides which tile an offset coordinate is and what lies
/// there. A save of a map whose seed, size, wrap, orientation or offset differ is refused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SavedMap {
    /// The map's seed.
    pub seed: u32,
    /// Its size.
    pub size: MapSize,
    /// Whether it wraps east to west.
    pub wrap: bool,
    /// Its tiles' orientation.
    pub orientation: Orientation,
    /// Its offset in the world, in tiles.
    pub offset: (i32, i32),
}

impl SavedMap {
    /// The identity of a config's map.
    #[must_use]
    pub fn of(config: &MapConfig) -> Self {
        Self {
            seed: config.seed,
            size: config.size,
            wrap: config.wrap,
            orientation: config.layout.orientation,
            offset: config.offset,
        }
    }

    /// The first field that differs from another map's, with both values.
    pub(crate) fn difference(&self, other: &Self) -> Option<(&'static str, String, String)> {
        let d =
            |field, a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug| Some((field, format!("{a:?}"), format!("{b:?}")));
        if self.seed != other.seed {
            return d("seed", &self.seed, &other.seed);
        }
        if self.size != other.size {
            return d("size", &self.size, &other.size);
        }
        if self.wrap != other.wrap {
            return d("wrap", &self.wrap, &other.wrap);
        }
        if self.orientation != other.orientation {
            return d("layout.orientation", &self.orientation, &other.orientation);
        }
        if self.offset != other.offset {
            return d("offset", &self.offset, &other.offset);
        }
        None
    }
}

/// One tile's saved state; fields left out of a RON save take their defaults (unexplored,
/// nobody's, no overlay, no highlight).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SavedTile {
    /// Offset coordinate `(column, row)` of the tile (the map's own tile on a wrapping map); on
    /// a globe `(id, 0)` ([`GlobeTile::at`](crate::GlobeTile::at)).
    pub at: (i32, i32),
    /// What the player knows of it.
    #[serde(default)]
    pub fog: FogState,
    /// Its owner, a player `0..MAX_OWNERS` (`None`: nobody).
    #[serde(default)]
    pub owner: Option<u8>,
    /// Its overlay color, sRGB bytes `[r, g, b, a]` (the alpha is the strength).
    #[serde(default)]
    pub overlay: Option<[u8; 4]>,
    /// The highlights it carries, each at most once.
    #[serde(default)]
    pub highlights: Vec<Highlight>,
}

/// Every tile's state the game wrote, for one map: the tiles in another state than the default,
/// row by row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TileStateSave {
    /// Format version ([`SAVE_VERSION`] when written by this crate).
    pub version: u32,
    /// The map it belongs to.
    pub map: SavedMap,
    /// The tiles not in the default state.
    pub tiles: Vec<SavedTile>,
}

/// A save (of tile states, [`TileStateSave`], or of fog, [`FogOfWar`](crate::FogOfWar)) that
/// cannot be read, or does not fit the map; nothing was changed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SaveError {
    /// Malformed RON, with where.
    #[error("the save is not valid RON: line {line}, column {column}: {message}")]
    Syntax {
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
        /// What the parser expected.
        message: String,
    },
    /// A binary save that is damaged: wrong magic, truncated, a checksum that does not match, or
    /// a payload that does not decode.
    #[error("the save is corrupted: {0}")]
    Corrupt(String),
    /// A format this version cannot read.
    #[error("the save is format version {found}: this version reads versions 1..={newest}")]
    Version {
        /// The save's version.
        found: u32,
        /// The newest version this crate reads.
        newest: u32,
    },
    /// A save of another map.
    #[error("the save is of another map: its {field} is {saved}, this map's is {current}")]
    OtherMap {
        /// The config field that differs.
        field: &'static str,
        /// The saved value.
        saved: String,
        /// This map's value.
        current: String,
    },
    /// A saved tile that cannot be on the map or holds an impossible state.
    #[error("tile {index} of the save, at column {} row {}: {problem}", .at.0, .at.1)]
    Tile {
        /// Its index in the save's tile list.
        index: usize,
        /// Its offset coordinate.
        at: (i32, i32),
        /// What is wrong, with the allowed range.
        problem: String,
    },
    /// A fog save for no players or more than [`MAX_OWNERS`].
    #[error("the save holds fog for {count} players: 1..={MAX_OWNERS} are allowed")]
    Players {
        /// The players it holds.
        count: usize,
    },
    /// More tiles than any map holds.
    #[error("the save holds {count} tiles: at most {MAX_SAVED_TILES} are allowed")]
    TooManyTiles {
        /// The tiles it holds.
        count: usize,
    },
}

/// The CRC-32 (IEEE) binary saves end with, of the bytes before it.
#[must_use]
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}

/// A tile as the binary payload stores it: `(column, row, fog, owner, highlight bits,
/// overlay)`, an array in CBOR rather than a map with field names.
type PackedTile = (i32, i32, u8, u8, u8, Option<[u8; 4]>);

/// The binary payload.
#[derive(Serialize, Deserialize)]
struct Packed {
    map: SavedMap,
    tiles: Vec<PackedTile>,
}

/// Header: magic, version (u32 LE), payload length (u64 LE); then the payload and a CRC-32
/// (u32 LE) of everything before it.
const HEADER: usize = 4 + 4 + 8;

/// A binary file: `magic`, `version` (u32 LE), the payload's length (u64 LE), the payload, and
/// a CRC-32 (u32 LE) of everything before it. The envelope of every binary save of the crate.
pub(crate) fn seal(magic: [u8; 4], version: u32, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + payload.len() + 4);
    out.extend_from_slice(&magic);
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(payload);
    let crc = crc32fast::hash(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    out
}

/// The version and payload of a file [`seal`] made with `magic`, of a version up to `newest`.
///
/// # Errors
/// [`SaveError::Corrupt`] for a wrong magic, a length that does not match or a checksum that
/// does not; [`SaveError::Version`] for version 0 or one newer than `newest`.
pub(crate) fn open(bytes: &[u8], magic: [u8; 4], newest: u32) -> Result<(u32, &[u8]), SaveError> {
    let corrupt = |why: String| Err(SaveError::Corrupt(why));
    if bytes.len() < HEADER + 4 {
        return corrupt(format!("{} bytes, shorter than the {}-byte header and checksum", bytes.len(), HEADER + 4));
    }
    if bytes[..4] != magic {
        return corrupt(format!("it starts with {:?}, not {:?}", &bytes[..4], magic));
    }
    let version = u32::from_le_bytes(bytes[4..8].try_into().expect("4 bytes"));
    let length = u64::from_le_bytes(bytes[8..16].try_into().expect("8 bytes"));
    let expected = bytes.len() - HEADER - 4;
    if length != expected as u64 {
        return corrupt(format!("the header gives a {length}-byte payload, the file holds {expected} bytes"));
    }
    let (body, crc) = bytes.split_at(bytes.len() - 4);
    let (stored, computed) = (u32::from_le_bytes(crc.try_into().expect("4 bytes")), crc32fast::hash(body));
    if stored != computed {
        return corrupt(format!("checksum {stored:#010x}, the contents give {computed:#010x}"));
    }
    if version == 0 || version > newest {
        return Err(SaveError::Version { found: version, newest });
    }
    Ok((version, &body[HEADER..]))
}

/// `value` as CBOR, sealed ([`seal`]).
pub(crate) fn seal_cbor(magic: [u8; 4], version: u32, value: &impl Serialize) -> Vec<u8> {
    let mut payload = Vec::new();
    ciborium::into_writer(value, &mut payload).expect("writing to a Vec cannot fail");
    seal(magic, version, &payload)
}

/// The version and the CBOR value of a file [`seal_cbor`] made with `magic`, of a version up to
/// `newest`.
///
/// # Errors
/// What [`open`] refuses, and [`SaveError::Corrupt`] for a payload that does not decode.
pub(crate) fn open_cbor<T: serde::de::DeserializeOwned>(
    bytes: &[u8],
    magic: [u8; 4],
    newest: u32,
) -> Result<(u32, T), SaveError> {
    let (version, payload) = open(bytes, magic, newest)?;
    let value =
        ciborium::from_reader(payload).map_err(|e| SaveError::Corrupt(format!("the payload does not decode: {e}")))?;
    Ok((version, value))
}

impl TileStateSave {
    /// The save as RON text.
    #[must_use]
    pub fn to_ron(&self) -> String {
        let config = ron::ser::PrettyConfig::new().depth_limit(3).struct_names(false);
        ron::ser::to_string_pretty(self, config).expect("a tile state save always serialises")
    }

    /// Reads a RON save (it is not checked against a map: see [`TileStateSave::check`]); each
    /// tile's highlights come back in [`Highlight::ALL`]'s order.
    ///
    /// # Errors
    /// [`SaveError::Syntax`] with the line and column, [`SaveError::TooManyTiles`].
    pub fn from_ron(text: &str) -> Result<Self, SaveError> {
        let mut save: Self = ron::from_str(text).map_err(|e| SaveError::Syntax {
            line: e.span.start.line,
            column: e.span.start.col,
            message: e.code.to_string(),
        })?;
        if save.tiles.len() > MAX_SAVED_TILES {
            return Err(SaveError::TooManyTiles { count: save.tiles.len() });
        }
        // Highlights in one order (the binary form keeps a set of bits).
        for tile in &mut save.tiles {
            tile.highlights.sort_by_key(|&h| h as u8);
        }
        if save.version == 1 {
            // Version 1 numbered owners from 1.
            for (index, tile) in save.tiles.iter_mut().enumerate() {
                if let Some(owner) = tile.owner {
                    let Some(player) = owner.checked_sub(1) else {
                        let problem = "owner 0: version 1 saves number owners 1..=64 (None for nobody)".into();
                        return Err(SaveError::Tile { index, at: tile.at, problem });
                    };
                    tile.owner = Some(player);
                }
            }
            save.version = SAVE_VERSION;
        }
        Ok(save)
    }

    /// The save as compact binary: [`SAVE_MAGIC`], the version, the payload's length, the
    /// payload (CBOR, RFC 8949: a tile is an array of six small numbers), and a CRC-32 of all of
    /// it, so a damaged file is refused rather than read as other state.
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        let packed = Packed {
            map: self.map.clone(),
            tiles: self
                .tiles
                .iter()
                .map(|t| {
                    let bits = t.highlights.iter().fold(0u8, |b, &h| b | 1 << h as u8);
                    // 0 is nobody, player p is p + 1 (as version 1 stored its owners 1..=64).
                    (t.at.0, t.at.1, t.fog as u8, t.owner.map_or(0, |o| o.saturating_add(1)), bits, t.overlay)
                })
                .collect(),
        };
        seal_cbor(SAVE_MAGIC, self.version, &packed)
    }

    /// Reads a binary save (not checked against a map: see [`TileStateSave::check`]).
    ///
    /// # Errors
    /// [`SaveError::Corrupt`] (magic, length, checksum or payload), [`SaveError::Version`] for
    /// a newer format, [`SaveError::TooManyTiles`].
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, SaveError> {
        let (_, packed): (u32, Packed) = open_cbor(bytes, SAVE_MAGIC, SAVE_VERSION)?;
        if packed.tiles.len() > MAX_SAVED_TILES {
            return Err(SaveError::TooManyTiles { count: packed.tiles.len() });
        }
        let mut tiles = Vec::with_capacity(packed.tiles.len());
        for (index, (col, row, fog, owner, bits, overlay)) in packed.tiles.into_iter().enumerate() {
            let bad = |problem: String| SaveError::Tile { index, at: (col, row), problem };
            let Some(fog) = FogState::from_bits(fog) else {
                return Err(bad(format!("fog state {fog}: 0 (unexplored), 1 (explored) or 2 (visible) are allowed")));
            };
            if bits >> Highlight::ALL.len() != 0 {
                return Err(bad(format!(
                    "highlight bits {bits:#b}: only the lowest {} are allowed",
                    Highlight::ALL.len()
                )));
            }
            let highlights = Highlight::ALL.into_iter().filter(|&h| bits & (1 << h as u8) != 0).collect();
            let owner = owner.checked_sub(1);
            tiles.push(SavedTile { at: (col, row), fog, owner, overlay, highlights });
        }
        // Every version stores owners the same way in binary: read, the save is this version's.
        Ok(Self { version: SAVE_VERSION, map: packed.map, tiles })
    }

    /// Checks the save against the map it is to be loaded into (a flat map or a globe): its
    /// version, that it is of this map ([`SavedMap`]), and that every tile is on the map, listed once, with an owner in
    /// `0..MAX_OWNERS` and each highlight at most once.
    ///
    /// # Errors
    /// The first problem found, naming the field or the tile.
    pub fn check(&self, config: &MapConfig) -> Result<(), SaveError> {
        if self.version == 0 || self.version > SAVE_VERSION {
            return Err(SaveError::Version { found: self.version, newest: SAVE_VERSION });
        }
        if let Some((field, saved, current)) = self.map.difference(&SavedMap::of(config)) {
            return Err(SaveError::OtherMap { field, saved, current });
        }
        if self.tiles.len() > MAX_SAVED_TILES {
            return Err(SaveError::TooManyTiles { count: self.tiles.len() });
        }
        let (columns, rows) = match (config.size, config.size.bounds()) {
            // A globe's tiles are one row of ids (`GlobeTile::at`).
            (MapSize::Globe { frequency }, _) => (0..(10 * frequency * frequency + 2) as i32, 0..1),
            (_, Some((x, z))) => (0..x as i32, 0..z as i32),
            (_, None) => (-MAX_WORLD_TILE..MAX_WORLD_TILE, -MAX_WORLD_TILE..MAX_WORLD_TILE),
        };
        let mut seen = std::collections::HashSet::with_capacity(self.tiles.len());
        for (index, tile) in self.tiles.iter().enumerate() {
            let bad = |problem: String| Err(SaveError::Tile { index, at: tile.at, problem });
            let (col, row) = tile.at;
            if !columns.contains(&col) || !rows.contains(&row) {
                return bad(format!(
                    "not on the map: columns {}..{} and rows {}..{} are allowed",
                    columns.start, columns.end, rows.start, rows.end
                ));
            }
            if !seen.insert(tile.at) {
                return bad("listed twice: each tile at most once".into());
            }
            if let Some(owner) = tile.owner.filter(|&o| u32::from(o) >= MAX_OWNERS) {
                return bad(format!("owner {owner}: owners are players 0..{MAX_OWNERS} (None for nobody)"));
            }
            if let Some(h) = Highlight::ALL.iter().find(|h| tile.highlights.iter().filter(|x| x == h).count() > 1) {
                return bad(format!("highlight {h:?} listed twice: each at most once"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
