//! Editing a globe: the world builder's [`Editor`](crate::Editor) on a sphere. A
//! [`GlobeEditor`] holds a globe and its [`TileEdit`]s, applies [`GlobeStroke`]s (the flat
//! map's [`Tool`]s and [`Brush`]es around a globe tile) as one operation each, undoes and redoes
//! them, and reports what each one changed ([`GlobeChange`]: the tiles and the chunks to
//! rebuild). An operation only changes the config's `edits` (each naming its tile `(id, 0)`), so
//! the edited globe is exactly what loading its map file gives, and undoing every operation
//! gives back the generated globe bit for bit.

use std::collections::{BTreeMap, BTreeSet};

use super::{GlobeChunk, GlobeTerrain, GlobeTile};
use crate::config::{MapConfig, TileEdit};
use crate::editor::{Brush, EditError, MAX_BRUSH_RADIUS, TileNow, Tool, check_amount, edited, flood, hills_line};
use crate::error::ConfigError;

/// One stroke on a globe: a tool applied with a brush around a tile; one operation for undo.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeStroke {
    /// What it does: every [`Tool`] but the water tools (rivers and lakes are not on globes
    /// yet) and a ruleset's terrains and features.
    pub tool: Tool,
    /// Which tiles around `tile` it covers: a range in steps over the tile graph (pentagons
    /// included), or a flood fill of the tile's type or biome.
    pub brush: Brush,
    /// The tile under the cursor.
    pub tile: GlobeTile,
}

/// What one operation on a globe (or its undo) changed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeChange {
    /// The tiles that changed: the edited tiles and their neighbors (whose shared border points
    /// moved), and every tile whose center height, type, climate or biome changed as a
    /// consequence (a coast's moisture follows its neighbors' types), or on which the game
    /// setup (placed again on the edited globe) starts a player or puts another resource or
    /// wonder, with their neighbors. By id, each once.
    pub tiles: Vec<GlobeTile>,
    /// The tiles whose edits the operation changed, a part of `tiles`. By id, each once.
    pub edited: Vec<GlobeTile>,
    /// The chunks holding `tiles` (a changed tile's neighbors are among them, so a chunk whose
    /// border points' normals read faces beyond it is too): the meshes to build again. In
    /// [`GlobeTerrain::chunks`]' order, each once.
    pub chunks: Vec<GlobeChunk>,
}

impl GlobeChange {
    /// Whether nothing changed.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.tiles.is_empty()
    }

    /// The change from `old` to `new`, two compilations of one globe whose edits differ on the
    /// `touched` tiles.
    fn between(old: &GlobeTerrain, new: &GlobeTerrain, touched: &[GlobeTile]) -> Self {
        let grid = new.grid();
        let around = |t: GlobeTile| grid.neighbors(t).expect("a tile of the globe");
        // What the setup placed on a tile, its region aside (a region's bounds move no marker).
        fn placed(g: &GlobeTerrain, t: GlobeTile) -> Option<SetupMarks<'_>> {
            g.tile_setup(t).map(|s| (s.start, s.resource, s.wonder))
        }
        let mut tiles = BTreeSet::new();
        for t in grid.tiles() {
            let changed = old.tile_height(t).map(f32::to_bits) != new.tile_height(t).map(f32::to_bits)
                || old.tile_kind(t) != new.tile_kind(t)
                || old.tile_biome(t) != new.tile_biome(t)
                || old.tile_climate(t) != new.tile_climate(t)
                || placed(old, t) != placed(new, t);
            if changed {
                tiles.insert(t);
                tiles.extend(around(t).as_slice());
            }
        }
        for &t in touched {
            tiles.insert(t);
            tiles.extend(around(t).as_slice());
        }
        // A moved point lies on a changed tile, so the faces round it lie on that tile and its
        // neighbors, all in `tiles`: their chunks are every mesh with a point or normal moved.
        let chunks: BTreeSet<GlobeChunk> =
            tiles.iter().map(|&t| new.chunk_of(t).expect("a tile of the globe")).collect();
        let edited: BTreeSet<GlobeTile> = touched.iter().copied().collect();
        Self {
            tiles: tiles.into_iter().collect(),
            edited: edited.into_iter().collect(),
            chunks: new.chunks().into_iter().filter(|c| chunks.contains(c)).collect(),
        }
    }
}

/// What the setup put on a tile: the player starting there, its resource and its wonder.
type SetupMarks<'a> =
    (Option<u32>, Option<&'a crate::PlacedResource<GlobeTile>>, Option<&'a crate::PlacedWonder<GlobeTile>>);

/// One operation: each tile it touched, with its edit before and after.
type Operation = Vec<(GlobeTile, Option<TileEdit>, Option<TileEdit>)>;

/// A globe being edited: its terrain, its edits, and the operations to undo and redo.
#[derive(Debug, Clone)]
pub struct GlobeEditor {
    globe: GlobeTerrain,
    /// The edits by tile id.
    edits: BTreeMap<GlobeTile, TileEdit>,
    undo: Vec<Operation>,
    redo: Vec<Operation>,
}

impl GlobeEditor {
    /// Starts editing a globe (its config's edits are where editing starts; undo goes back to
    /// them, not past them).
    ///
    /// # Errors
    /// The config's first invalid field (`size` for a flat map's config).
    pub fn new(config: MapConfig) -> Result<Self, ConfigError> {
        Ok(Self::from_globe(GlobeTerrain::new(config)?))
    }

    /// Starts editing a compiled globe.
    #[must_use]
    pub fn from_globe(globe: GlobeTerrain) -> Self {
        let edits =
            globe.config().edits.iter().map(|e| (GlobeTile::from_at(e.at).expect("validated: (id, 0)"), *e)).collect();
        Self { globe, edits, undo: Vec::new(), redo: Vec::new() }
    }

    /// The globe as edited so far.
    #[must_use]
    pub fn globe(&self) -> &GlobeTerrain {
        &self.globe
    }

    /// The edits, by tile id: what the map file's `edits` section holds.
    #[must_use]
    pub fn edits(&self) -> Vec<TileEdit> {
        self.edits.values().copied().collect()
    }

    /// The config of the edited globe: the seed's config plus [`GlobeEditor::edits`]. Written
    /// with [`MapConfig::to_ron`], it is the map file of the edited globe.
    #[must_use]
    pub fn config(&self) -> MapConfig {
        MapConfig { edits: self.edits(), ..self.globe.config().clone() }
    }

    /// How many tiles carry an edit.
    #[must_use]
    pub fn edited_tiles(&self) -> usize {
        self.edits.len()
    }

    /// Operations that [`GlobeEditor::undo`] can take back.
    #[must_use]
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// Operations that [`GlobeEditor::redo`] can apply again.
    #[must_use]
    pub fn redo_len(&self) -> usize {
        self.redo.len()
    }

    /// The globe's tiles a brush covers around `tile`, each once: a range nearest first, then by
    /// id; a flood breadth first. None when `tile` is not the globe's or a range is above
    /// [`MAX_BRUSH_RADIUS`].
    #[must_use]
    pub fn brush_tiles(&self, brush: Brush, tile: GlobeTile) -> Vec<GlobeTile> {
        let (globe, grid) = (&self.globe, self.globe.grid());
        if !grid.contains(tile) {
            return Vec::new();
        }
        let neighbors = |t: GlobeTile| grid.neighbors(t).expect("a tile of the globe").as_slice().to_vec();
        match brush {
            Brush::Range(radius) if radius > MAX_BRUSH_RADIUS => Vec::new(),
            Brush::Range(radius) => grid.within(tile, radius).into_iter().map(|(t, _)| t).collect(),
            Brush::Flood => flood(tile, |t| globe.tile_kind(t), neighbors),
            Brush::FloodTerrain => flood(tile, |t| globe.tile_biome(t), neighbors),
        }
    }

    /// Applies a stroke as one operation (clearing what could be redone) and reports what
    /// changed. A stroke that changes no edit is no operation: it answers an empty
    /// [`GlobeChange`] and nothing can be undone for it.
    ///
    /// # Errors
    /// Checked in this order, the first that fails is answered and nothing changes:
    /// [`EditError::Amount`], [`EditError::Range`], [`EditError::Unsupported`] (a water tool or
    /// a ruleset's terrain or feature: not on globes yet), [`EditError::OffGlobe`],
    /// [`EditError::Invalid`] (the edited globe would not be valid).
    pub fn apply(&mut self, stroke: GlobeStroke) -> Result<GlobeChange, EditError> {
        check_amount(stroke.tool)?;
        if let Brush::Range(radius) = stroke.brush
            && radius > MAX_BRUSH_RADIUS
        {
            return Err(EditError::Range { radius });
        }
        let unsupported = |tool, needs| Err(EditError::Unsupported { tool, needs });
        const RIVERS: &str = "a flat map with rivers (rivers and lakes are not on globes yet)";
        match stroke.tool {
            Tool::AddRiver => return unsupported("AddRiver", RIVERS),
            Tool::RemoveRiver => return unsupported("RemoveRiver", RIVERS),
            Tool::FillLake => return unsupported("FillLake", RIVERS),
            Tool::DrainLake => return unsupported("DrainLake", RIVERS),
            Tool::SetTerrain(_) | Tool::SetFeature(_) => {
                return unsupported(
                    "SetTerrain and SetFeature",
                    "a map with its own terrain ruleset (flat maps only yet)",
                );
            }
            Tool::SetHills(_) => {
                hills_line(self.globe.config(), self.globe.thresholds())?;
            }
            _ => {}
        }
        let tiles = self.brush_tiles(stroke.brush, stroke.tile);
        if tiles.is_empty() {
            return Err(EditError::OffGlobe { tile: stroke.tile.0, tiles: self.globe.grid().tile_count() });
        }
        let mut operation = Operation::with_capacity(tiles.len());
        for tile in tiles {
            let before = self.edits.get(&tile).copied();
            let after = edited(tile.at(), stroke.tool, before, |neighbors| self.now(tile, neighbors));
            if after != before {
                operation.push((tile, before, after));
            }
        }
        if operation.is_empty() {
            return Ok(GlobeChange::default());
        }
        let change = self.run(&operation)?;
        self.undo.push(operation);
        self.redo.clear();
        Ok(change)
    }

    /// Takes the last operation back; `None` when there is none.
    pub fn undo(&mut self) -> Option<GlobeChange> {
        let operation = self.undo.pop()?;
        let reversed: Operation = operation.iter().map(|&(t, before, after)| (t, after, before)).collect();
        // The globe was valid before the operation, so going back compiles.
        let change = self.run(&reversed).ok()?;
        self.redo.push(operation);
        Some(change)
    }

    /// Applies the last undone operation again; `None` when there is none.
    pub fn redo(&mut self) -> Option<GlobeChange> {
        let operation = self.redo.pop()?;
        let change = self.run(&operation).ok()?;
        self.undo.push(operation);
        Some(change)
    }

    /// Sets each tile of `operation` to its edit after, compiles the globe and reports the
    /// change; on an invalid globe nothing changes.
    fn run(&mut self, operation: &Operation) -> Result<GlobeChange, EditError> {
        let mut edits = self.edits.clone();
        for &(tile, _, after) in operation {
            match after {
                Some(edit) => edits.insert(tile, edit),
                None => edits.remove(&tile),
            };
        }
        let globe = self.globe.with_edits(edits.values().copied().collect())?;
        let touched: Vec<GlobeTile> = operation.iter().map(|&(t, ..)| t).collect();
        let change = GlobeChange::between(&self.globe, &globe, &touched);
        self.globe = globe;
        self.edits = edits;
        Ok(change)
    }

    /// What the height and type tools read of a tile (its neighbors too when `neighbors`).
    fn now(&self, tile: GlobeTile, neighbors: bool) -> TileNow {
        let height = |t: GlobeTile| self.globe.tile_height(t).expect("a tile of the globe");
        let neighbors = if neighbors {
            self.globe
                .grid()
                .neighbors(tile)
                .expect("a tile of the globe")
                .as_slice()
                .iter()
                .map(|&n| height(n))
                .collect()
        } else {
            Vec::new()
        };
        let hills = hills_line(self.globe.config(), self.globe.thresholds()).ok();
        TileNow { height: height(tile), kind: self.globe.tile_kind(tile), hills, neighbors }
    }
}
