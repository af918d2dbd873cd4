//! Top-down software rendering of a map: colors blended by height (thesis Algorithm 5), or the
//! mesh's biome colors with rivers and lakes when the map has a climate or rivers; hill shading
//! from the mesh normals, optional tile outlines.

use std::path::Path;

use hex_terrain::{ChunkMesh, Terrain, TileKind};
use image::{Rgb, RgbImage};
use rayon::prelude::*;

use crate::CliResult;

/// Layer colors: sea, land (grass), mountain (rock).
pub const SEA: [f32; 3] = [0.11, 0.34, 0.72];
/// Land color.
pub const LAND: [f32; 3] = [0.30, 0.60, 0.20];
/// Mountain color.
pub const MOUNTAIN: [f32; 3] = [0.62, 0.60, 0.58];
/// River and lake color (sRGB, as the plugin's default water color).
pub const WATER: [f32; 3] = [0.16, 0.42, 0.72];
const BACKGROUND: Rgb<u8> = Rgb([24, 24, 28]);

/// What to draw.
pub struct Options {
    /// Image width in pixels.
    pub width: u32,
    /// Whether to darken tile borders.
    pub outlines: bool,
    /// Markers drawn over the map (starts, resources, wonders).
    pub marks: Vec<Mark>,
}

/// A marker over the map: a disc at a world position, with a dark rim.
pub struct Mark {
    /// World `x` and `z` of its center.
    pub at: [f64; 2],
    /// Radius in hex radii.
    pub radius: f32,
    /// Fill color (sRGB).
    pub color: [u8; 3],
}

fn layer(kind: TileKind) -> [f32; 3] {
    match kind {
        TileKind::Sea => SEA,
        TileKind::Land => LAND,
        TileKind::Mountain => MOUNTAIN,
    }
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t]
}

/// Algorithm 5 with linear blending on both sides of each threshold: at the threshold the two
/// layers mix half and half, fading to the pixel's own layer over `blend` (normalised height).
#[must_use]
pub fn albedo(h: f32, sea: f32, mountain: f32, blend: f32) -> [f32; 3] {
    let own = if h < sea {
        SEA
    } else if h < mountain {
        LAND
    } else {
        MOUNTAIN
    };
    if blend <= 0.0 {
        return own;
    }
    for (t, below, above) in [(sea, SEA, LAND), (mountain, LAND, MOUNTAIN)] {
        let d = h - t;
        if d.abs() < blend {
            let other = if d < 0.0 { above } else { below };
            return mix(own, other, 0.5 * (1.0 - d.abs() / blend));
        }
    }
    own
}

/// Renders the mesh seen from straight above, north (lowest z) at the top.
///
/// # Errors
/// When the image would be larger than 16384 pixels in either direction.
pub fn render(terrain: &Terrain, mesh: &ChunkMesh, options: &Options) -> CliResult<RgbImage> {
    let b = &mesh.buffers;
    let (mut min_x, mut max_x, mut min_z, mut max_z) = (f32::MAX, f32::MIN, f32::MAX, f32::MIN);
    for p in &b.positions {
        min_x = min_x.min(p[0]);
        max_x = max_x.max(p[0]);
        min_z = min_z.min(p[2]);
        max_z = max_z.max(p[2]);
    }
    let scale = (options.width as f32 - 1.0).max(1.0) / (max_x - min_x).max(1e-6);
    let height = ((max_z - min_z) * scale).ceil() as u32 + 1;
    if height > 16384 {
        return Err(format!("the picture would be {}x{height} pixels; use a smaller --width", options.width));
    }
    let config = terrain.config();
    let max_e = config.terrain.max_elevation;
    let (sea, mountain) = (config.terrain.sea_threshold, config.terrain.mountain_threshold);
    let blend = config.appearance.blend.clamp(0.0, 1.0);
    let light = {
        let l = [-0.5_f32, 1.0, -0.6];
        let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        l.map(|c| c / n)
    };
    // Outline half-width in center-distance units, about 1.2 pixels wide.
    let n = terrain.lattice().subdivisions() as f32;
    let edge = (1.2 / (scale * config.layout.hex_size / n)).clamp(0.02, 0.5) / n;

    // Rasterise per row band so bands fill in parallel; each band scans the triangles
    // overlapping it (triangles are bucketed by their first row).
    let w = options.width as usize;
    let mut pixels = vec![BACKGROUND; w * height as usize];
    let project = |p: [f32; 3]| [(p[0] - min_x) * scale, (p[2] - min_z) * scale];
    let band = 32_usize;
    let bands = (height as usize).div_ceil(band);
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (t, tri) in b.indices.chunks_exact(3).enumerate() {
        let ys = [0, 1, 2].map(|j| project(b.positions[tri[j] as usize])[1]);
        let lo = ys.iter().copied().fold(f32::MAX, f32::min).floor().max(0.0) as usize / band;
        let hi = (ys.iter().copied().fold(f32::MIN, f32::max).ceil().max(0.0) as usize / band).min(bands - 1);
        for bucket in &mut buckets[lo..=hi] {
            bucket.push(t as u32);
        }
    }
    pixels.par_chunks_mut(w * band).enumerate().for_each(|(k, rows)| {
        let y0 = k * band;
        for &t in &buckets[k] {
            let idx = [0, 1, 2].map(|j| b.indices[t as usize * 3 + j] as usize);
            let p = idx.map(|i| project(b.positions[i]));
            let det = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
            if det.abs() < 1e-12 {
                continue;
            }
            let (x_lo, x_hi) = (
                p.iter().map(|q| q[0]).fold(f32::MAX, f32::min).floor().max(0.0) as usize,
                (p.iter().map(|q| q[0]).fold(f32::MIN, f32::max).ceil() as usize).min(w - 1),
            );
            let (yl, yh) = (
                p.iter().map(|q| q[1]).fold(f32::MAX, f32::min).floor().max(y0 as f32) as usize,
                (p.iter().map(|q| q[1]).fold(f32::MIN, f32::max).ceil() as usize).min(y0 + rows.len() / w - 1),
            );
            for py in yl..=yh {
                for px in x_lo..=x_hi {
                    let (fx, fy) = (px as f32, py as f32);
                    let l1 = ((fx - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (fy - p[0][1])) / det;
                    let l2 = ((p[1][0] - p[0][0]) * (fy - p[0][1]) - (fx - p[0][0]) * (p[1][1] - p[0][1])) / det;
                    let l0 = 1.0 - l1 - l2;
                    if l0 < -1e-4 || l1 < -1e-4 || l2 < -1e-4 {
                        continue;
                    }
                    let lerp = |v: [f32; 3]| v[0] * l0 + v[1] * l1 + v[2] * l2;
                    let y = lerp(idx.map(|i| b.positions[i][1]));
                    let color = if !b.colors.is_empty() {
                        let c = [0, 1, 2, 3].map(|k| lerp(idx.map(|i| f32::from(b.colors[i][k]) / 255.0)));
                        let t = ((c[3] - 0.2) / 0.35).clamp(0.0, 1.0);
                        mix([c[0], c[1], c[2]], WATER, t * t * (3.0 - 2.0 * t))
                    } else if max_e > 0.0 {
                        albedo(y / max_e, sea, mountain, blend)
                    } else {
                        layer(match b.tile_kinds[idx[0]] {
                            0 => TileKind::Sea,
                            1 => TileKind::Land,
                            _ => TileKind::Mountain,
                        })
                    };
                    let normal = [0, 1, 2].map(|c| lerp(idx.map(|i| b.normals[i][c])));
                    let len = (normal[0].powi(2) + normal[1].powi(2) + normal[2].powi(2)).sqrt().max(1e-6);
                    let lambert = (normal[0] * light[0] + normal[1] * light[1] + normal[2] * light[2]) / len;
                    // Flat ground gets 0.92; slopes facing the light brighter, away darker.
                    let mut shade = 0.45 + 0.47 * lambert.max(0.0) / light[1];
                    if options.outlines && lerp(idx.map(|i| b.center_distances[i])) > 1.0 - edge {
                        shade *= 0.3;
                    }
                    let rgb = color.map(|c| ((c * shade).clamp(0.0, 1.0) * 255.0).round() as u8);
                    rows[(py - y0) * w + px] = Rgb(rgb);
                }
            }
        }
    });
    let mut img = RgbImage::new(options.width, height);
    for (dst, src) in img.pixels_mut().zip(pixels) {
        *dst = src;
    }
    let origin = mesh.origin;
    for mark in &options.marks {
        let [cx, cy] = project([(mark.at[0] - origin[0]) as f32, 0.0, (mark.at[1] - origin[2]) as f32]);
        disc(&mut img, [cx, cy], (mark.radius * config.layout.hex_size * scale).max(2.0), mark.color);
    }
    Ok(img)
}

/// Draws a disc of radius `r` pixels centered at `[cx, cy]` with a dark rim.
pub fn disc(img: &mut RgbImage, [cx, cy]: [f32; 2], r: f32, color: [u8; 3]) {
    let (x0, x1) =
        ((cx - r - 1.0).floor().max(0.0) as u32, ((cx + r + 1.0).ceil().max(0.0) as u32).min(img.width() - 1));
    let (y0, y1) =
        ((cy - r - 1.0).floor().max(0.0) as u32, ((cy + r + 1.0).ceil().max(0.0) as u32).min(img.height() - 1));
    for py in y0..=y1 {
        for px in x0..=x1 {
            let d = ((px as f32 - cx).powi(2) + (py as f32 - cy).powi(2)).sqrt();
            if d <= r {
                let rim = d > r - (r * 0.3).max(1.0);
                img.put_pixel(px, py, Rgb(if rim { [16, 16, 16] } else { color }));
            }
        }
    }
}

/// Writes a PNG.
///
/// # Errors
/// When the file cannot be written.
pub fn save(img: &RgbImage, path: &Path) -> CliResult<()> {
    img.save_with_format(path, image::ImageFormat::Png).map_err(|e| format!("{}: {e}", path.display()))
}
