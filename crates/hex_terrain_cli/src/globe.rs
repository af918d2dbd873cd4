//! Pictures of a globe: its whole mesh rasterised as an equirectangular map (longitude across,
//! latitude up) or as an orthographic view from above a longitude and latitude, in the flat
//! render's colors by height (Algorithm 5) with hill shading from a light in the north-west of
//! every place, and tile outlines where the rings reach the border.

use hex_terrain::{GlobeMesh, GlobeTerrain};
use image::{Rgb, RgbImage};

use crate::render::albedo;

type V = [f64; 3];

/// How to look at the globe.
#[derive(Debug, Clone, Copy)]
pub enum View {
    /// The whole surface, longitude -180..180 across, latitude 90..-90 down; twice as wide as
    /// high.
    Equirectangular,
    /// The half seen from far above the point at this longitude and latitude (degrees).
    Orthographic {
        /// Longitude, east positive.
        lon: f64,
        /// Latitude, north positive.
        lat: f64,
    },
}

impl View {
    /// `LON,LAT` in degrees: longitude in [-180, 180], latitude in [-90, 90].
    pub fn from_lon_lat(text: &str) -> Result<Self, String> {
        let bad = || format!("--from {text}: allowed LON,LAT in degrees, LON in [-180, 180], LAT in [-90, 90]");
        let (lon, lat) = text.split_once(',').ok_or_else(bad)?;
        let (lon, lat): (f64, f64) = (lon.trim().parse().map_err(|_| bad())?, lat.trim().parse().map_err(|_| bad())?);
        if !((-180.0..=180.0).contains(&lon) && (-90.0..=90.0).contains(&lat)) {
            return Err(bad());
        }
        Ok(Self::Orthographic { lon, lat })
    }
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn normalize(a: V) -> V {
    let l = dot(a, a).sqrt();
    if l > 0.0 { a.map(|c| c / l) } else { a }
}

/// The direction at a latitude and longitude in radians (the core's convention: `y` north,
/// longitude east, counterclockwise seen from above the north pole).
fn from_lat_lon(lat: f64, lon: f64) -> V {
    [lat.cos() * lon.cos(), lat.sin(), -lat.cos() * lon.sin()]
}

/// A vertex's color: its tile's biome color on a globe with a climate, else its height's layer
/// color; shaded by its normal against a light from the north-west of its place.
fn shade(globe: &GlobeTerrain, mesh: &GlobeMesh, v: usize, p: V) -> [f32; 3] {
    let t = &globe.config().terrain;
    let biome = globe
        .config()
        .climate
        .enabled
        .then(|| globe.tile_at(p).and_then(|tile| globe.tile_info(tile)))
        .flatten()
        .and_then(|info| globe.ruleset().biome(info.terrain.terrain));
    let color = match biome {
        Some(biome) => biome.color().map(|c| f32::from(c) / 255.0),
        None => albedo(mesh.heights[v], t.sea_threshold, t.mountain_threshold, globe.config().appearance.blend),
    };
    let up = normalize(p);
    // At a pole every way is south: take the prime meridian's north there.
    let north = normalize([-up[1] * up[0], 1.0 - up[1] * up[1], -up[1] * up[2]]);
    let north = if dot(north, north) > 0.5 { north } else { [-up[1], 0.0, 0.0] };
    let east = cross(north, up);
    let light = normalize([
        up[0] + 0.7 * (north[0] - east[0]),
        up[1] + 0.7 * (north[1] - east[1]),
        up[2] + 0.7 * (north[2] - east[2]),
    ]);
    let n = mesh.buffers.normals[v].map(f64::from);
    let lit = (0.35 + 0.75 * dot(n, light).max(0.0)) as f32;
    color.map(|c| (c * lit).min(1.0))
}

/// Fills the triangle `xy` (pixels) with colors interpolated from `colors`, keeping the nearest
/// by `depth` (larger is nearer) and the border value `rim` (tile outlines past 1).
fn fill(image: &mut Raster, xy: [[f64; 2]; 3], depth: [f64; 3], colors: [[f32; 3]; 3], rim: [f32; 3]) {
    let (w, h) = (image.width as f64, image.height as f64);
    let min_x = xy.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min).floor().max(0.0);
    let max_x = xy.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max).ceil().min(w - 1.0);
    let min_y = xy.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min).floor().max(0.0);
    let max_y = xy.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max).ceil().min(h - 1.0);
    let area = (xy[1][0] - xy[0][0]) * (xy[2][1] - xy[0][1]) - (xy[2][0] - xy[0][0]) * (xy[1][1] - xy[0][1]);
    if area.abs() < 1e-12 || min_x > max_x || min_y > max_y {
        return;
    }
    for y in min_y as u32..=max_y as u32 {
        for x in min_x as u32..=max_x as u32 {
            let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            let edge = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1]);
            let w0 = edge(xy[1], xy[2]) / area;
            let w1 = edge(xy[2], xy[0]) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9 {
                continue;
            }
            let z = w0 * depth[0] + w1 * depth[1] + w2 * depth[2];
            let i = (y * image.width + x) as usize;
            if z <= image.depth[i] {
                continue;
            }
            image.depth[i] = z;
            let ws = [w0 as f32, w1 as f32, w2 as f32];
            let mut c = [0.0f32; 3];
            for k in 0..3 {
                for (ch, col) in c.iter_mut().zip(colors[k]) {
                    *ch += ws[k] * col;
                }
            }
            let r = ws[0] * rim[0] + ws[1] * rim[1] + ws[2] * rim[2];
            if r > 1.0 {
                c = c.map(|ch| ch * 0.45);
            }
            image.color[i] = c;
        }
    }
}

struct Raster {
    width: u32,
    height: u32,
    depth: Vec<f64>,
    color: Vec<[f32; 3]>,
}

/// Draws the globe's whole mesh seen as `view`, `width` pixels wide.
#[must_use]
pub fn render(globe: &GlobeTerrain, view: View, width: u32, outlines: bool) -> RgbImage {
    let mesh = globe.generate_whole();
    let height = match view {
        View::Equirectangular => (width / 2).max(1),
        View::Orthographic { .. } => width,
    };
    let mut raster = Raster {
        width,
        height,
        depth: vec![f64::NEG_INFINITY; (width * height) as usize],
        color: vec![[0.02, 0.02, 0.05]; (width * height) as usize],
    };
    let points: Vec<V> = mesh.buffers.positions.iter().map(|p| p.map(f64::from)).collect();
    let colors: Vec<[f32; 3]> = (0..points.len()).map(|v| shade(globe, &mesh, v, points[v])).collect();
    let n = globe.config().subdivisions() as f32;
    // Outlines: past 1 near a tile's border (the rings over n reach 1 exactly on it).
    let rims: Vec<f32> =
        mesh.buffers.center_distances.iter().map(|&d| if outlines { d * (1.0 + 0.3 / n) } else { 0.0 }).collect();
    let reach = globe.radius() + f64::from(globe.config().terrain.max_elevation);
    for t in mesh.buffers.indices.chunks(3) {
        let v = [t[0] as usize, t[1] as usize, t[2] as usize];
        let c = v.map(|k| colors[k]);
        let r = v.map(|k| rims[k]);
        match view {
            View::Equirectangular => {
                let lat = v.map(|k| (points[k][1] / dot(points[k], points[k]).sqrt()).asin());
                let mut lon = v.map(|k| (-points[k][2]).atan2(points[k][0]));
                // A pole's longitude is its neighbors'; a triangle across the date line is
                // drawn on both sides.
                for k in 0..3 {
                    if lat[k].abs() > std::f64::consts::FRAC_PI_2 - 1e-9 {
                        lon[k] = (lon[(k + 1) % 3] + lon[(k + 2) % 3]) / 2.0;
                    }
                }
                let base = lon[0];
                let lon = lon.map(|l| {
                    let mut l = l;
                    while l - base > std::f64::consts::PI {
                        l -= std::f64::consts::TAU;
                    }
                    while base - l > std::f64::consts::PI {
                        l += std::f64::consts::TAU;
                    }
                    l
                });
                let (w, h) = (f64::from(width), f64::from(height));
                for shift in [-std::f64::consts::TAU, 0.0, std::f64::consts::TAU] {
                    let xy = [0, 1, 2].map(|k| {
                        [
                            (lon[k] + shift + std::f64::consts::PI) / std::f64::consts::TAU * w,
                            (std::f64::consts::FRAC_PI_2 - lat[k]) / std::f64::consts::PI * h,
                        ]
                    });
                    fill(&mut raster, xy, [0.0; 3], c, r);
                }
            }
            View::Orthographic { lon, lat } => {
                let eye = from_lat_lon(lat.to_radians(), lon.to_radians());
                let right = normalize(cross([0.0, 1.0, 0.0], eye));
                let right = if dot(right, right) > 0.5 { right } else { [1.0, 0.0, 0.0] };
                let up = cross(eye, right);
                let p = v.map(|k| points[k]);
                let face = cross(
                    [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]],
                    [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]],
                );
                if dot(face, eye) <= 0.0 {
                    continue;
                }
                let s = f64::from(width) / (2.0 * reach * 1.02);
                let xy =
                    p.map(|q| [f64::from(width) / 2.0 + dot(q, right) * s, f64::from(width) / 2.0 - dot(q, up) * s]);
                fill(&mut raster, xy, p.map(|q| dot(q, eye)), c, r);
            }
        }
    }
    RgbImage::from_fn(width, height, |x, y| {
        let c = raster.color[(y * width + x) as usize];
        Rgb(c.map(|ch| (ch.clamp(0.0, 1.0) * 255.0).round() as u8))
    })
}
