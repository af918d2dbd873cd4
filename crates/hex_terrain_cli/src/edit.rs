//! `hexterrain edit`: the world builder without a window. Strokes from a RON file, in offset
//! coordinates, applied one operation each by the core's `Editor`; the edited map written as a
//! map file whose `edits` section is the delta over the seed.

use std::path::Path;

use hex_terrain::{Brush, Editor, MapConfig, Stroke, Tool};
use serde::Deserialize;

use crate::CliResult;

/// One stroke of the file: a tool, a brush, and the tile in offset coordinates.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileStroke {
    tool: Tool,
    brush: Brush,
    /// `(column, row)`, like the map's size and the edits.
    at: (i32, i32),
}

/// Applies the strokes of `strokes` to `config` and writes the edited map to `output`.
pub(crate) fn run(config: &MapConfig, strokes: &Path, output: &Path) -> CliResult<()> {
    let text = std::fs::read_to_string(strokes).map_err(|e| format!("{}: {e}", strokes.display()))?;
    let list: Vec<FileStroke> = ron::from_str(&text)
        .map_err(|e| format!("{}:{}:{}: {}", strokes.display(), e.span.start.line, e.span.start.col, e.code))?;
    let mut editor = Editor::new(config.clone()).map_err(|e| e.to_string())?;
    for (i, s) in list.iter().enumerate() {
        let tile = editor.terrain().tile_from_offset([s.at.0, s.at.1]);
        let change = editor
            .apply(Stroke { tool: s.tool, brush: s.brush, tile })
            .map_err(|e| format!("{}: stroke {i} ({:?} at {:?}): {e}", strokes.display(), s.tool, s.at))?;
        println!(
            "stroke {i}: {:?} {:?} at {:?}: {} tiles, {} chunks changed",
            s.tool,
            s.brush,
            s.at,
            change.tiles.len(),
            change.chunks.len()
        );
    }
    let edited = editor.config();
    std::fs::write(output, edited.to_ron()).map_err(|e| format!("{}: {e}", output.display()))?;
    println!("{} edited tiles written to {}", edited.edits.len(), output.display());
    Ok(())
}
