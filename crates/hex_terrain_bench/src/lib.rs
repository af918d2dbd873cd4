//! Workloads shared by the `hexterrain-bench` binary and the criterion benchmarks.
//!
//! Each function does one whole piece of work on all cores and returns a count that depends on
//! all of it, so nothing can be optimised away.

use std::collections::HashMap;

use hex_terrain::hexx::{HeightMapMeshBuilder, Hex};
use hex_terrain::{GenerateOptions, ManipulationConfig, MapConfig, MapSize, Terrain, TileRect};
use rayon::prelude::*;

/// The sizes of thesis table 7 (small maps).
pub const TABLE_7: [(u32, u32); 11] =
    [(2, 2), (6, 6), (10, 6), (16, 8), (20, 10), (24, 12), (30, 16), (36, 20), (40, 20), (48, 24), (60, 30)];
/// The sizes of thesis table 8 (larger maps).
pub const TABLE_8: [(u32, u32); 8] =
    [(80, 40), (100, 50), (200, 100), (400, 200), (500, 250), (600, 300), (800, 400), (1000, 500)];
/// Civilization 6 map sizes (thesis table 9).
pub const TABLE_9: [(&str, u32, u32); 6] =
    [("Duel", 44, 26), ("Tiny", 60, 38), ("Small", 74, 46), ("Standard", 84, 54), ("Large", 96, 60), ("Huge", 106, 66)];

/// Map0's parameters at a size and ring count: the full pipeline and the basic PTG baseline
/// (same noise, same lattice, no manipulation).
#[must_use]
pub fn terrains(x: u32, z: u32, inner_rings: u32) -> (Terrain, Terrain) {
    let mut config = MapConfig { size: MapSize::Bounded { x, z }, ..MapConfig::default() };
    config.terrain.inner_rings = inner_rings;
    let full = Terrain::new(config.clone()).expect("benchmark config is valid");
    config.manipulation = ManipulationConfig::raw();
    let basic = Terrain::new(config).expect("benchmark config is valid");
    (full, basic)
}

/// Map0's parameters at a size and ring count without and with climate (biomes), rivers and
/// lakes: the same heights, plus the tile-level water network and a colored, carved mesh.
#[must_use]
pub fn water_terrains(x: u32, z: u32, inner_rings: u32) -> (MapConfig, MapConfig) {
    let mut plain = MapConfig { size: MapSize::Bounded { x, z }, ..MapConfig::default() };
    plain.terrain.inner_rings = inner_rings;
    let mut water = plain.clone();
    water.climate.enabled = true;
    water.rivers.enabled = true;
    (plain, water)
}

/// Generates the whole map; returns its vertex count.
#[must_use]
pub fn generate(terrain: &Terrain) -> usize {
    terrain.generate_map().map_or(0, |m| m.buffers.vertex_count())
}

/// Generates the whole map keeping the per-vertex diagnostics (lattice coordinates, raw
/// heights, moved flags, rings); returns its vertex count.
#[must_use]
pub fn generate_with_diagnostics(terrain: &Terrain) -> usize {
    terrain.bounds().map_or(0, |rect| terrain.generate(rect, GenerateOptions::DIAGNOSTICS).buffers.vertex_count())
}

/// Points sampled together, as generation batches them.
const BATCH: usize = 1024;

/// Bare fBm (our Perlin) at exactly the points generation evaluates, enumerated the same way
/// and sampled the way generation samples them (the same call, on the same batches, on all
/// cores): the noise floor of generation. Returns the sum of the samples so the work cannot be
/// elided.
#[must_use]
pub fn noise_floor(terrain: &Terrain) -> f64 {
    let Some(rect) = terrain.bounds() else { return 0.0 };
    let points = terrain.mesh_points(rect);
    let mut out = vec![0.0; points.len()];
    out.par_chunks_mut(BATCH).enumerate().for_each(|(k, chunk)| {
        let points = &points[k * BATCH..k * BATCH + chunk.len()];
        terrain.heights().source_heights(terrain.geometry(), points, chunk);
    });
    out.iter().sum()
}

/// Bare fBm with `noise::Perlin` at the same points; returns their sum.
#[must_use]
pub fn noise_floor_reference(terrain: &Terrain, reference: &noise::Perlin) -> f64 {
    let Some(rect) = terrain.bounds() else { return 0.0 };
    let points = terrain.mesh_points(rect);
    points
        .par_iter()
        .with_min_len(256)
        .map(|&p| {
            let [x, z] = terrain.heights().noise_position(terrain.geometry(), p);
            terrain.fbm().sample_reference(reference, x, z)
        })
        .sum()
}

/// hexx's `HeightMapMeshBuilder` (flat-topped hexagonal columns) fed by the same fBm, one
/// sample per hex, built in row bands small enough for its u16 indices; returns the vertices.
#[must_use]
pub fn hexx_columns(terrain: &Terrain) -> usize {
    let Some(rect) = terrain.bounds() else { return 0 };
    let width = (rect.max[0] - rect.min[0]).max(1) as usize;
    // A column has at most 7 top and 24 side vertices.
    let rows_per_band = (65_535 / 31 / width).max(1) as i32;
    let mut bands = Vec::new();
    let mut row = rect.min[1];
    while row < rect.max[1] {
        let end = (row + rows_per_band).min(rect.max[1]);
        for col in (rect.min[0]..rect.max[0]).step_by(2000) {
            bands.push(TileRect { min: [col, row], max: [(col + 2000).min(rect.max[0]), end] });
        }
        row = end;
    }
    let max_elevation = terrain.config().terrain.max_elevation;
    bands
        .par_iter()
        .map(|band| {
            let heights: HashMap<Hex, f32> = band
                .iter()
                .map(|oc| {
                    let hex = terrain.tile_from_offset(oc);
                    let center = terrain.lattice().tile_center(hex);
                    (hex, terrain.heights().source_height(terrain.geometry(), center) as f32 * max_elevation)
                })
                .collect();
            let mesh = HeightMapMeshBuilder::new(terrain.layout(), &heights).build();
            assert!(mesh.vertices.len() <= 65_536, "band too large for u16 indices");
            mesh.vertices.len()
        })
        .sum()
}

/// The median of some timings (the upper one of an even count).
#[must_use]
pub fn median(mut v: Vec<std::time::Duration>) -> std::time::Duration {
    v.sort_unstable();
    v.get(v.len() / 2).copied().unwrap_or_default()
}

/// A timing in milliseconds, right-aligned for a table.
#[must_use]
pub fn ms(d: std::time::Duration) -> String {
    format!("{:8.2} ms", d.as_secs_f64() * 1e3)
}
