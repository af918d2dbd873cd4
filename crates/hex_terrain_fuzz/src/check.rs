//! The properties every target asserts on what it got: finite buffers in range, and errors
//! that explain themselves.

use hex_terrain::{ChunkMesh, ConfigError, LoadError, Terrain};

/// Panics unless every buffer of `mesh` is finite and consistent, and the queries answer with
/// finite values on its tiles.
pub fn check_terrain(terrain: &Terrain, mesh: &ChunkMesh) {
    let b = &mesh.buffers;
    let n = b.positions.len();
    assert_eq!(b.normals.len(), n, "one normal a vertex");
    assert_eq!(b.uvs.len(), n, "one uv a vertex");
    assert_eq!(b.tile_kinds.len(), n, "one tile kind a vertex");
    assert_eq!(b.center_distances.len(), n, "one center distance a vertex");
    assert_eq!(b.indices.len() % 3, 0, "whole triangles");
    assert!(b.indices.iter().all(|&i| (i as usize) < n), "an index past the {n} vertices");
    assert!(b.positions.iter().flatten().all(|v| v.is_finite()), "a position is not finite");
    assert!(b.uvs.iter().flatten().all(|v| v.is_finite()), "a uv is not finite");
    for normal in &b.normals {
        let len = normal.iter().map(|v| v * v).sum::<f32>().sqrt();
        assert!((len - 1.0).abs() < 1e-3, "normal {normal:?} is not unit length");
    }
    assert!(b.center_distances.iter().all(|d| (0.0..=1.0 + 1e-4).contains(d)), "a center distance outside [0, 1]");
    let top = terrain.config().terrain.max_elevation;
    for info in &mesh.tiles {
        assert!(info.elevation.is_finite() && (0.0..=top * 1.0001 + 1e-3).contains(&info.elevation));
        let top = f64::from(top);
        let [x, y, z] = terrain.tile_center(info.hex).expect("a generated tile is in the world");
        assert!(x.is_finite() && y.is_finite() && z.is_finite(), "tile center of {:?}", info.hex);
        assert!(terrain.surface_height(x, z).is_some_and(f64::is_finite), "surface height at {x}, {z}");
        if let Some(hit) = terrain.raycast([x, top + 10.0, z], [0.3, -1.0, 0.2], f64::MAX) {
            assert!(hit.point.iter().all(|v| v.is_finite()) && hit.distance.is_finite(), "{hit:?}");
        }
        assert!(terrain.tile_at(x, z).is_some(), "no tile under the center of {:?}", info.hex);
    }
}

/// Panics unless a refused config names the field, the value and the allowed range.
pub fn check_config_error(error: &ConfigError) {
    assert!(!error.field.is_empty() && !error.value.is_empty() && !error.allowed.is_empty(), "{error:?}");
    let text = error.to_string();
    assert!(text.contains(&error.field) && text.contains("allowed"), "{text}");
}

/// Panics unless a load error says where or what: malformed RON with its line and column, an
/// invalid field as [`check_config_error`].
pub fn check_load_error(error: &LoadError) {
    match error {
        LoadError::Ron(spanned) => {
            assert!(spanned.span.start.line >= 1 && spanned.span.start.col >= 1, "{error}");
            let at = format!("{}:{}", spanned.span.start.line, spanned.span.start.col);
            assert!(error.to_string().contains(&at), "{error} does not say {at}");
        }
        LoadError::Invalid(e) => check_config_error(e),
        other => assert!(!other.to_string().is_empty()),
    }
}
