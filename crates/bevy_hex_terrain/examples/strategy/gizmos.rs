//! Debug drawing: the loaded chunks' outlines (F3).

use bevy::prelude::*;
use bevy_hex_terrain::prelude::*;

use crate::Game;

/// F3: outlines of the loaded chunks.
pub(crate) fn chunk_boundaries(game: Res<Game>, map: Res<HexMap>, streamer: Res<ChunkStreamer>, mut gizmos: Gizmos) {
    if !game.show_chunks {
        return;
    }
    let terrain = map.terrain();
    let top = map.config().terrain.max_elevation + 0.2;
    for chunk in streamer.loaded_chunks() {
        let Some(rect) = terrain.chunk_rect(chunk) else { continue };
        // A chunk past a wrapping map's edge shows its map chunk's tiles, whole map widths on.
        let shift = terrain.wrap().map_or(0.0, |w| w.width * f64::from(terrain.wrap_chunk(chunk).1));
        let corners = [
            rect.min,
            [rect.max[0] - 1, rect.min[1]],
            [rect.max[0] - 1, rect.max[1] - 1],
            [rect.min[0], rect.max[1] - 1],
        ]
        .map(|oc| {
            let [x, _, z] = terrain.tile_center(terrain.tile_from_offset(oc)).unwrap_or_default();
            Vec3::new((x + shift) as f32, top, z as f32)
        });
        for k in 0..4 {
            gizmos.line(corners[k], corners[(k + 1) % 4], Color::srgb(1.0, 0.3, 0.1));
        }
    }
}
