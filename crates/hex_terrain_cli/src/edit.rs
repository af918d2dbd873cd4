//! `hexterrain edit`: the world builder without a window. Strokes from a RON file, in offset
//! coordinates (on a globe `(id, 0)`), applied one operation each by the core's `Editor` (a
//! globe's by its `GlobeEditor`); the edited map written as a map file whose `edits` section is
//! the delta over the seed.

use std::path::Path;

use hex_terrain::{Brush, Editor, GlobeEditor, GlobeStroke, GlobeTile, MapConfig, MapSize, Stroke, Tool};
use serde::Deserialize;

use crate::CliResult;

/// One stroke of the file: a tool, a brush, and the tile in offset coordinates.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileStroke {
    tool: Tool,
    brush: Brush,
    /// `(column, row)`, like the map's size and the edits; on a globe `(id, 0)`.
    at: (i32, i32),
}

/// Applies the strokes of `strokes` to `config` and writes the edited map to `output`.
pub(crate) fn run(config: &MapConfig, strokes: &Path, output: &Path) -> CliResult<()> {
    let text = std::fs::read_to_string(strokes).map_err(|e| format!("{}: {e}", strokes.display()))?;
    let list: Vec<FileStroke> = ron::from_str(&text)
        .map_err(|e| format!("{}:{}:{}: {}", strokes.display(), e.span.start.line, e.span.start.col, e.code))?;
    let failed = |i: usize, s: &FileStroke, e: String| {
        format!("{}: stroke {i} ({:?} at {:?}): {e}", strokes.display(), s.tool, s.at)
    };
    let changed = |i: usize, s: &FileStroke, tiles: usize, chunks: usize| {
        println!("stroke {i}: {:?} {:?} at {:?}: {tiles} tiles, {chunks} chunks changed", s.tool, s.brush, s.at);
    };
    let edited = if let MapSize::Globe { .. } = config.size {
        let mut editor = GlobeEditor::new(config.clone()).map_err(|e| e.to_string())?;
        for (i, s) in list.iter().enumerate() {
            let tile = GlobeTile::from_at(s.at).ok_or_else(|| failed(i, s, "a globe's tiles are (id, 0)".into()))?;
            let change = editor
                .apply(GlobeStroke { tool: s.tool, brush: s.brush, tile })
                .map_err(|e| failed(i, s, e.to_string()))?;
            changed(i, s, change.tiles.len(), change.chunks.len());
        }
        editor.config()
    } else {
        let mut editor = Editor::new(config.clone()).map_err(|e| e.to_string())?;
        for (i, s) in list.iter().enumerate() {
            let tile = editor.terrain().tile_from_offset([s.at.0, s.at.1]);
            let change =
                editor.apply(Stroke { tool: s.tool, brush: s.brush, tile }).map_err(|e| failed(i, s, e.to_string()))?;
            changed(i, s, change.tiles.len(), change.chunks.len());
        }
        editor.config()
    };
    std::fs::write(output, edited.to_ron()).map_err(|e| format!("{}: {e}", output.display()))?;
    println!("{} edited tiles written to {}", edited.edits.len(), output.display());
    Ok(())
}
