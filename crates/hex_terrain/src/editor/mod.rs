//! The world builder's core, Bevy-free so a server or a tool can edit too: an [`Editor`] holds a
//! map and its [`TileEdit`]s, applies strokes ([`Stroke`]: a [`Tool`] with a [`Brush`] around a
//! tile) as one operation each, undoes and redoes them, and reports what each one changed
//! ([`Change`]: the tiles and the chunks to rebuild).
//!
//! An operation only changes the config's `edits`; the map is compiled again from the config, so
//! an edited map is exactly what loading its map file gives (the edits are saved as a delta over
//! the seed: [`Editor::config`], [`MapConfig::to_ron`]). Undoing every operation gives back the
//! generated map bit for bit, redoing them the edited one.

mod brush;
mod change;
mod error;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use hexx::Hex;

pub(crate) use brush::flood;
pub use brush::{Brush, MAX_BRUSH_RADIUS, MAX_FLOOD_TILES};
pub use change::Change;
pub use error::EditError;

use crate::config::{FeatureEdit, MapConfig, PropDensity, RiverEdit, TileEdit};
use crate::error::ConfigError;
use crate::terrain::Terrain;
use crate::vocab::{Biome, RuleId, TileKind};

/// What a stroke does to each tile its brush covers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum Tool {
    /// Raises the tile's center height by this much (a fraction of the maximum elevation),
    /// whatever type that makes it.
    Raise(f32),
    /// Lowers it by this much.
    Lower(f32),
    /// Sets the center height (a fraction of the maximum elevation, `[0, 1]`).
    SetHeight(f32),
    /// Sets the center height to the mean of the tile's and its neighbors' (on the map).
    Smooth,
    /// Sets the type (sea, land, mountain): the height is brought into the type's range.
    SetKind(TileKind),
    /// Sets the biome by hand: it stays whatever the elevation becomes.
    SetBiome(Biome),
    /// Puts a land tile on hills (`true`) or on flat land (`false`): its center height is
    /// brought a quarter of the way into that part of the land range, above or below the hills
    /// line ([`ClimateConfig::hills`](crate::ClimateConfig::hills)), so its type stays land and
    /// its terrain is the ruleset's for that landform ([`Landform`](crate::Landform)). A sea or
    /// mountain tile, or a tile on that landform already, stays as it is. Needs a map with a
    /// climate and a hills line (`climate.hills` below 1).
    SetHills(bool),
    /// Starts a river on the tile ([`RiverEdit::Source`]): it runs down the drainage to the sea,
    /// a lake or the map's edge. Needs a map with rivers.
    AddRiver,
    /// Takes the river off the tile and everything that drains through it ([`RiverEdit::Dry`]).
    /// Needs a map with rivers.
    RemoveRiver,
    /// Digs a lake: the land and mountain tiles the brush covers (not on the map's edge, where water runs off
    /// the map) sink below the lowest tile around them by more than `rivers.min_lake_depth`, so
    /// water fills them up to that rim. Needs a map with rivers and lakes.
    FillLake,
    /// Drains the lake tiles the brush covers: each is raised to its lake's surface, dry land
    /// where the water stood. Needs a map with rivers and lakes.
    DrainLake,
    /// Sets how many props (trees, rocks, reeds) the tile grows.
    SetProps(PropDensity),
    /// Sets the tile's terrain (an id of the map's own terrain ruleset), whatever its climate.
    SetTerrain(RuleId),
    /// Sets the tile's feature (an id of the map's own ruleset), or takes it off.
    SetFeature(FeatureEdit),
    /// Takes the tile's edits away: it is the generated tile again.
    Erase,
}

/// One stroke: a tool applied with a brush around a tile. One stroke is one operation for undo.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Stroke {
    /// What it does.
    pub tool: Tool,
    /// Which tiles around `tile` it covers.
    pub brush: Brush,
    /// The tile under the cursor (any copy of it on a wrapping map).
    pub tile: Hex,
}

/// How far above its lake's surface a drained tile rises (raw height), so no water stands on it
/// whatever `rivers.min_lake_depth` is.
const DRAIN_MARGIN: f32 = 1e-4;

/// How much deeper than `rivers.min_lake_depth` a dug lake is (raw height), so it is a lake
/// whatever the rounding.
const LAKE_MARGIN: f32 = 0.01;

/// One tile of an operation: its offset coordinate, its edit before and after.
type TileStep = ((i32, i32), Option<TileEdit>, Option<TileEdit>);

/// One operation: each tile it touched, with its edit before and after.
#[derive(Debug, Clone, PartialEq)]
struct Operation {
    tiles: Vec<TileStep>,
}

// Raising, lowering, setting or smoothing a height clears a type set by hand (the new height
// decides the type) and keeps a biome set by hand.

/// A map being edited: its terrain, its edits, and the operations to undo and redo.
#[derive(Debug, Clone)]
pub struct Editor {
    terrain: Terrain,
    /// The config without edits (they are in `edits`).
    base: MapConfig,
    /// The edits by `(row, column)` (see `row_major`), in the file's order.
    edits: BTreeMap<(i32, i32), TileEdit>,
    undo: Vec<Operation>,
    redo: Vec<Operation>,
    timings: EditTimings,
}

/// How long an operation took, by part (for benchmarks; the chunks' meshes are built after it,
/// by whoever shows them).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EditTimings {
    /// Compiling the edited map: the edits, the tile table (rivers, lakes, biomes), the setup.
    pub compile: Duration,
    /// Finding the tiles and chunks that changed.
    pub compare: Duration,
}

impl Editor {
    /// Starts editing a map (its config's edits are where editing starts; undo goes back to
    /// them, not past them).
    ///
    /// # Errors
    /// The config's first invalid field.
    pub fn new(config: MapConfig) -> Result<Self, ConfigError> {
        Ok(Self::from_terrain(Terrain::new(config)?))
    }

    /// Starts editing a compiled map (a heightmap it was compiled with stays: edits reuse its
    /// height field), without compiling it again: undo goes back to its edits, not past them.
    #[must_use]
    pub fn from_terrain(terrain: Terrain) -> Self {
        let config = terrain.config();
        let edits = config.edits.iter().map(|e| (row_major(e.at), *e)).collect();
        let base = MapConfig { edits: Vec::new(), ..config.clone() };
        Self { terrain, base, edits, undo: Vec::new(), redo: Vec::new(), timings: EditTimings::default() }
    }

    /// The map as edited so far.
    #[must_use]
    pub fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    /// The edits, row by row: what the map file's `edits` section holds.
    #[must_use]
    pub fn edits(&self) -> Vec<TileEdit> {
        sorted(&self.edits)
    }

    /// The config of the edited map: the seed's config plus [`Editor::edits`]. Written with
    /// [`MapConfig::to_ron`], it is the map file of the edited map.
    #[must_use]
    pub fn config(&self) -> MapConfig {
        MapConfig { edits: self.edits(), ..self.base.clone() }
    }

    /// How many tiles are edited (the length of [`Editor::edits`], without building it).
    #[must_use]
    pub fn edited_tiles(&self) -> usize {
        self.edits.len()
    }

    /// Operations that [`Editor::undo`] can take back.
    #[must_use]
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// Operations that [`Editor::redo`] can apply again.
    #[must_use]
    pub fn redo_len(&self) -> usize {
        self.redo.len()
    }

    /// Applies a stroke as one operation (clearing what could be redone) and reports what
    /// changed ([`Change::edited`]: the tiles whose edits it changed). A stroke that changes no
    /// edit is no operation: it answers an empty [`Change`] and nothing can be undone for it.
    ///
    /// # Errors
    /// Checked in this order, the first that fails is answered and nothing changes:
    /// [`EditError::Amount`] (the tool's amount not finite or out of range),
    /// [`EditError::Range`] (a brush range above [`MAX_BRUSH_RADIUS`]),
    /// [`EditError::Unsupported`] (a water tool on a map without rivers or lakes, hills on a
    /// map without a hills line),
    /// [`EditError::OffMap`] (the stroke's tile not on the map), [`EditError::NoLake`] (a lake
    /// dug where it would be sea), [`EditError::Invalid`] (the edited map would not be valid).
    pub fn apply(&mut self, stroke: Stroke) -> Result<Change, EditError> {
        check_amount(stroke.tool)?;
        if let Brush::Range(radius) = stroke.brush
            && radius > MAX_BRUSH_RADIUS
        {
            return Err(EditError::Range { radius });
        }
        self.check_water(stroke.tool)?;
        if let Tool::SetHills(_) = stroke.tool {
            hills_line(self.terrain.config(), self.terrain.thresholds())?;
        }
        let tiles = stroke.brush.tiles(&self.terrain, stroke.tile);
        if tiles.is_empty() {
            return Err(EditError::OffMap(stroke.tile));
        }
        let lake = match stroke.tool {
            Tool::FillLake => Some(self.lake_level(&tiles)?),
            _ => None,
        };
        let mut operation = Operation { tiles: Vec::with_capacity(tiles.len()) };
        for &tile in &tiles {
            let [col, row] = self.terrain.offset_of(tile);
            let at = (col, row);
            let before = self.edits.get(&row_major(at)).copied();
            let after = match (stroke.tool, lake) {
                (Tool::FillLake, Some(level)) => self.dug(tile, level, before),
                _ => self.edited(stroke.tool, tile, before),
            };
            if after != before {
                operation.tiles.push((at, before, after));
            }
        }
        if operation.tiles.is_empty() {
            return Ok(Change::default());
        }
        let change = self.run(&operation)?;
        self.undo.push(operation);
        self.redo.clear();
        Ok(change)
    }

    /// Takes the last operation back; `None` when there is none.
    pub fn undo(&mut self) -> Option<Change> {
        let operation = self.undo.pop()?;
        let reversed =
            Operation { tiles: operation.tiles.iter().map(|&(at, before, after)| (at, after, before)).collect() };
        // The map was valid before the operation, so going back compiles.
        let change = self.run(&reversed).ok()?;
        self.redo.push(operation);
        Some(change)
    }

    /// Applies the last undone operation again; `None` when there is none.
    pub fn redo(&mut self) -> Option<Change> {
        let operation = self.redo.pop()?;
        let change = self.run(&operation).ok()?;
        self.undo.push(operation);
        Some(change)
    }

    /// Sets each tile of `operation` to its edit after, compiles the map and reports the
    /// change; on an invalid map nothing changes.
    fn run(&mut self, operation: &Operation) -> Result<Change, EditError> {
        let mut edits = self.edits.clone();
        for &(at, _, after) in &operation.tiles {
            match after {
                Some(edit) => edits.insert(row_major(at), edit),
                None => edits.remove(&row_major(at)),
            };
        }
        let start = Instant::now();
        let terrain = self.terrain.with_edits(sorted(&edits))?;
        let compiled = Instant::now();
        let touched: Vec<Hex> =
            operation.tiles.iter().map(|&(at, ..)| terrain.tile_from_offset([at.0, at.1])).collect();
        let change = Change::between(&self.terrain, &terrain, &touched);
        self.timings = EditTimings { compile: compiled - start, compare: compiled.elapsed() };
        self.terrain = terrain;
        self.edits = edits;
        Ok(change)
    }

    /// How long the last operation (or undo, or redo) took, by part.
    #[must_use]
    pub fn last_timings(&self) -> EditTimings {
        self.timings
    }

    /// A tile's edit after `tool` (`None`: no edit left).
    fn edited(&self, tool: Tool, tile: Hex, before: Option<TileEdit>) -> Option<TileEdit> {
        match tool {
            Tool::DrainLake => {
                // A lake tile rises to just above its lake's surface: no water stands on it.
                let (Some(_), Some(level)) = (self.terrain.lake(tile), self.terrain.water_level(tile)) else {
                    return before;
                };
                let [col, row] = self.terrain.offset_of(tile);
                let mut edit = before.unwrap_or_else(|| TileEdit::at((col, row)));
                edit.height = Some((level + DRAIN_MARGIN).min(1.0));
                edit.kind = None;
                Some(edit)
            }
            // Planned for the whole stroke in `apply`.
            Tool::FillLake => before,
            _ => {
                let [col, row] = self.terrain.offset_of(tile);
                edited((col, row), tool, before, |neighbors| TileNow {
                    height: self.center_height(tile),
                    kind: self.terrain.tile_kind(tile),
                    hills: hills_line(self.terrain.config(), self.terrain.thresholds()).ok(),
                    neighbors: if neighbors {
                        self.terrain
                            .neighbors(tile)
                            .into_iter()
                            .flatten()
                            .flatten()
                            .map(|n| self.center_height(n))
                            .collect()
                    } else {
                        Vec::new()
                    },
                })
            }
        }
    }

    /// Refuses a water tool on a map without rivers (or lakes).
    fn check_water(&self, tool: Tool) -> Result<(), EditError> {
        let rivers = &self.base.rivers;
        let (name, needs_lakes) = match tool {
            Tool::AddRiver => ("AddRiver", false),
            Tool::RemoveRiver => ("RemoveRiver", false),
            Tool::FillLake => ("FillLake", true),
            Tool::DrainLake => ("DrainLake", true),
            _ => return Ok(()),
        };
        match (rivers.enabled, rivers.lakes || !needs_lakes) {
            (true, true) => Ok(()),
            (false, _) => Err(EditError::Unsupported { tool: name, needs: "rivers.enabled" }),
            (true, false) => Err(EditError::Unsupported { tool: name, needs: "rivers.lakes" }),
        }
    }

    /// The raw height the tiles of a lake dug under `tiles` sink to: below the lowest tile
    /// around them (the rim water spills over) by more than the minimum lake depth.
    fn lake_level(&self, tiles: &[Hex]) -> Result<f32, EditError> {
        let inside: std::collections::HashSet<Hex> = tiles.iter().copied().collect();
        let mut rim = f32::INFINITY;
        for &t in tiles {
            for n in self.terrain.neighbors(t).into_iter().flatten().flatten() {
                if !inside.contains(&n) {
                    rim = rim.min(self.center_height(n));
                }
            }
        }
        let sea = self.terrain.thresholds().sea;
        let depth = self.base.rivers.min_lake_depth + LAKE_MARGIN;
        let floor = rim - depth;
        if !(floor.is_finite() && floor >= sea) {
            return Err(EditError::NoLake { rim, sea });
        }
        Ok(floor)
    }

    /// A tile's edit after a lake is dug to `floor`: a land or mountain tile off the map's edge sinks to it
    /// (one already lower keeps its height); others keep their edit.
    fn dug(&self, tile: Hex, floor: f32, before: Option<TileEdit>) -> Option<TileEdit> {
        let on_edge = self.terrain.neighbors(tile).is_none_or(|around| around.contains(&None));
        if on_edge || self.terrain.tile_kind(tile) == Some(TileKind::Sea) {
            return before;
        }
        let [col, row] = self.terrain.offset_of(tile);
        let mut edit = before.unwrap_or_else(|| TileEdit::at((col, row)));
        edit.height = Some(self.center_height(tile).min(floor));
        edit.kind = None;
        Some(edit)
    }

    /// A tile's center height as the map has it now (edited), before the type rules.
    fn center_height(&self, tile: Hex) -> f32 {
        let geometry = self.terrain.geometry();
        self.terrain.pipeline().heights().raw_height(geometry, geometry.lattice().tile_center(tile))
    }
}

/// The edits in the order the map file lists them: row by row (the map's key order).
fn sorted(edits: &BTreeMap<(i32, i32), TileEdit>) -> Vec<TileEdit> {
    edits.values().copied().collect()
}

/// The key of the edit of the tile at `(column, row)`: `(row, column)`, so the map keeps the
/// edits in the file's order.
fn row_major((col, row): (i32, i32)) -> (i32, i32) {
    (row, col)
}

/// Refuses a tool amount that is not finite or out of range.
pub(crate) fn check_amount(tool: Tool) -> Result<(), EditError> {
    let (value, ok, allowed) = match tool {
        Tool::Raise(v) | Tool::Lower(v) => (v, v.is_finite() && (0.0..=1.0).contains(&v), "[0, 1]"),
        Tool::SetHeight(v) => (v, v.is_finite() && (0.0..=1.0).contains(&v), "[0, 1]"),
        _ => return Ok(()),
    };
    if ok { Ok(()) } else { Err(EditError::Amount { value, allowed }) }
}

/// What the height and type tools read of one tile: its center height (raw, edited) and type,
/// the map's land range split by its hills line (`[sea, line, mountain]`, raw heights, on a map
/// with one), and its neighbors' center heights (for [`Tool::Smooth`] only). A flat map's and
/// a globe's editors alike.
pub(crate) struct TileNow {
    pub(crate) height: f32,
    pub(crate) kind: Option<TileKind>,
    pub(crate) hills: Option<[f32; 3]>,
    pub(crate) neighbors: Vec<f32>,
}

/// The land range of a map split by its hills line, `[sea, line, mountain]` in raw heights (the
/// landform rule's); [`EditError::Unsupported`] for [`Tool::SetHills`] on a map without one.
pub(crate) fn hills_line(config: &crate::MapConfig, t: &crate::Thresholds) -> Result<[f32; 3], EditError> {
    let climate = &config.climate;
    if !(climate.enabled && climate.hills < 1.0) {
        return Err(EditError::Unsupported {
            tool: "SetHills",
            needs: "a climate (climate.enabled) with a hills line (climate.hills below 1)",
        });
    }
    Ok([t.sea, t.sea + climate.hills * (t.mountain - t.sea), t.mountain])
}

/// A tile's edit after `tool` for the tools every map has (heights, types, biomes, props,
/// terrains and features, rivers set by hand, erasing); `None`: no edit left. `read` gives what
/// the tile is now, asked only by the tools that read it (raise, lower, smooth, set a type),
/// and told whether to read the neighbors too. A lake tool (planned by the map's editor) leaves
/// the tile as it was.
pub(crate) fn edited(
    at: (i32, i32),
    tool: Tool,
    before: Option<TileEdit>,
    read: impl FnOnce(bool) -> TileNow,
) -> Option<TileEdit> {
    let mut edit = before.unwrap_or_else(|| TileEdit::at(at));
    let mut height = |h: f32| {
        edit.height = Some(h.clamp(0.0, 1.0));
        edit.kind = None;
    };
    match tool {
        Tool::Raise(by) => height(read(false).height + by),
        Tool::Lower(by) => height(read(false).height - by),
        Tool::SetHeight(h) => height(h),
        Tool::Smooth => {
            let now = read(true);
            let sum = now.neighbors.iter().fold(now.height, |sum, &h| sum + h);
            height(sum / (1 + now.neighbors.len()) as f32);
        }
        Tool::SetKind(kind) => {
            let now = read(false);
            // A tile of that type already: nothing to set (its height stays its own).
            if now.kind == Some(kind) {
                return before;
            }
            edit.height = Some(now.height);
            edit.kind = Some(kind);
        }
        Tool::SetBiome(biome) => edit.biome = Some(biome),
        Tool::SetHills(on) => {
            let now = read(false);
            let (Some(TileKind::Land), Some([sea, line, mountain])) = (now.kind, now.hills) else { return before };
            if (now.height >= line) == on {
                return before;
            }
            height(if on { line + 0.25 * (mountain - line) } else { line - 0.25 * (line - sea) });
        }
        Tool::AddRiver => edit.river = Some(RiverEdit::Source),
        Tool::RemoveRiver => edit.river = Some(RiverEdit::Dry),
        Tool::FillLake | Tool::DrainLake => return before,
        Tool::SetProps(density) => edit.props = Some(density),
        Tool::SetTerrain(id) => edit.terrain = Some(id),
        Tool::SetFeature(feature) => edit.feature = Some(feature),
        Tool::Erase => return None,
    }
    (!edit.is_empty()).then_some(edit)
}
