//! The minimap of a globe: an equirectangular picture (longitude east across, latitude north at
//! the top, every pixel the tile under its center's direction), the tiles' terrain colors, a
//! game's per-tile state painted over them as on a flat map's picture (fog of war, owners' tint,
//! their borders where a pixel's tile and the next pixel's differ in owner), and the outline of
//! a camera's view: the circle around the direction it looks along.

use super::{MinimapStyle, TileLook, shade};
use crate::globe::{GlobeTerrain, GlobeTile};
use crate::save::FogState;

/// The widest picture, in pixels (its height is half its width).
pub const MAX_GLOBE_MINIMAP_WIDTH: u32 = 4096;

/// The picture of a globe (see the module docs): the pixels' tiles and base colors, computed
/// once; painting applies the tiles' [`TileLook`]s.
#[derive(Debug, Clone)]
pub struct GlobeMinimap {
    style: MinimapStyle,
    size: [u32; 2],
    /// Per pixel, row by row from the north: its tile's id.
    pixel_tile: Vec<u32>,
    /// Per pixel: its color before any tile state.
    base: Vec<[u8; 4]>,
    /// Per tile: its color.
    colors: Vec<[u8; 4]>,
    /// Per tile: where its pixels start in `tile_pixels` (one more entry at the end).
    tile_start: Vec<u32>,
    /// The pixels of every tile, tile after tile.
    tile_pixels: Vec<u32>,
}

impl GlobeMinimap {
    /// The picture of `globe`, `width` pixels wide and half as tall; `None` for a width of 0,
    /// an odd one, or one above [`MAX_GLOBE_MINIMAP_WIDTH`]. A tile's color is its terrain's
    /// minimap color (else its color) on a globe with a climate, else its type's in `style`.
    #[must_use]
    pub fn new(globe: &GlobeTerrain, width: u32, style: MinimapStyle) -> Option<Self> {
        if width == 0 || width % 2 == 1 || width > MAX_GLOBE_MINIMAP_WIDTH {
            return None;
        }
        let size = [width, width / 2];
        let colors = tile_colors(globe, &style);
        let mut picture = Self {
            style,
            size,
            pixel_tile: Vec::with_capacity((size[0] * size[1]) as usize),
            base: Vec::new(),
            colors: Vec::new(),
            tile_start: Vec::new(),
            tile_pixels: Vec::new(),
        };
        for py in 0..size[1] {
            for px in 0..size[0] {
                let direction = picture.direction_at(f64::from(px) + 0.5, f64::from(py) + 0.5);
                picture.pixel_tile.push(globe.tile_at(direction).expect("a unit direction").0);
            }
        }
        picture.base = picture.pixel_tile.iter().map(|&t| colors[t as usize]).collect();
        picture.colors = colors;
        // Each tile's pixels, by a counting sort of the pixels by tile.
        let tiles = globe.grid().tile_count() as usize;
        let mut start = vec![0u32; tiles + 1];
        for &t in &picture.pixel_tile {
            start[t as usize + 1] += 1;
        }
        for t in 0..tiles {
            start[t + 1] += start[t];
        }
        let mut next = start.clone();
        picture.tile_pixels = vec![0; picture.pixel_tile.len()];
        for (i, &t) in picture.pixel_tile.iter().enumerate() {
            picture.tile_pixels[next[t as usize] as usize] = i as u32;
            next[t as usize] += 1;
        }
        picture.tile_start = start;
        Some(picture)
    }

    /// Takes the colors of `globe`, an edit or a reload of the globe pictured (the same
    /// frequency): the tiles whose color changed get it, and are returned (by id) for a
    /// [`repaint`](Self::repaint); `None`, and nothing changed, for a globe of another size.
    /// Reads the globe's tables only, so it is cheap enough for a frame.
    pub fn recolor(&mut self, globe: &GlobeTerrain) -> Option<Vec<GlobeTile>> {
        if globe.grid().tile_count() as usize != self.colors.len() {
            return None;
        }
        let colors = tile_colors(globe, &self.style);
        let mut changed = Vec::new();
        for (t, (&new, old)) in colors.iter().zip(&mut self.colors).enumerate() {
            if new == *old {
                continue;
            }
            *old = new;
            changed.push(GlobeTile(t as u32));
            let (start, end) = (self.tile_start[t] as usize, self.tile_start[t + 1] as usize);
            for &i in &self.tile_pixels[start..end] {
                self.base[i as usize] = new;
            }
        }
        Some(changed)
    }

    /// The picture's size in pixels, `[width, width / 2]`.
    #[must_use]
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// The style it is drawn with.
    #[must_use]
    pub fn style(&self) -> &MinimapStyle {
        &self.style
    }

    /// The unit direction at a point of the picture, in pixels from its north-west corner
    /// (`x` east, `y` south; a pixel's center is at `+0.5`): longitude `-180` degrees at `x = 0`
    /// to `180` at the east edge, latitude `90` at `y = 0` to `-90` at the south edge, as
    /// [`GlobeTileInfo`](crate::GlobeTileInfo)'s longitude and latitude.
    #[must_use]
    pub fn direction_at(&self, x: f64, y: f64) -> [f64; 3] {
        let [w, h] = self.size.map(f64::from);
        let longitude = (x / w * 2.0 - 1.0) * std::f64::consts::PI;
        let latitude = (0.5 - y / h) * std::f64::consts::PI;
        let (sl, cl) = latitude.sin_cos();
        [cl * longitude.cos(), sl, -cl * longitude.sin()]
    }

    /// The point of the picture (pixels from its north-west corner) a direction falls on.
    #[must_use]
    pub fn point_of(&self, direction: [f64; 3]) -> [f64; 2] {
        let [w, h] = self.size.map(f64::from);
        let [x, y, z] = direction;
        let longitude = (-z).atan2(x);
        let latitude = y.atan2(x.hypot(z));
        [(longitude / std::f64::consts::PI + 1.0) * 0.5 * w, (0.5 - latitude / std::f64::consts::PI) * h]
    }

    /// The tile a pixel shows; `None` past the picture.
    #[must_use]
    pub fn tile_at_pixel(&self, px: u32, py: u32) -> Option<GlobeTile> {
        (px < self.size[0] && py < self.size[1]).then(|| GlobeTile(self.pixel_tile[(py * self.size[0] + px) as usize]))
    }

    /// The pixels (row-major indices) that show a tile; none for a tile too small to hold a
    /// pixel's center, or not of the globe.
    #[must_use]
    pub fn pixels_of(&self, tile: GlobeTile) -> &[u32] {
        let t = tile.0 as usize;
        if t + 1 >= self.tile_start.len() {
            return &[];
        }
        &self.tile_pixels[self.tile_start[t] as usize..self.tile_start[t + 1] as usize]
    }

    /// The whole picture, RGBA8 sRGB rows north to south, with each tile's look.
    #[must_use]
    pub fn paint(&self, look: impl Fn(GlobeTile) -> TileLook) -> Vec<u8> {
        let looks: Vec<TileLook> = (0..self.tile_start.len() as u32 - 1).map(|t| look(GlobeTile(t))).collect();
        let mut rgba = vec![0u8; self.base.len() * 4];
        for (i, px) in rgba.chunks_exact_mut(4).enumerate() {
            px.copy_from_slice(&self.pixel(i, |t| looks[t as usize]));
        }
        rgba
    }

    /// Repaints in `rgba` (a picture from [`paint`](Self::paint)) the pixels whose color may
    /// depend on `tiles`: their pixels and the pixels beside them (east, west, north, south: a
    /// border reads them), each with its tile's look; returns how many pixels changed color.
    /// The result equals a full [`paint`](Self::paint) with the same looks when only the looks
    /// of `tiles` changed since `rgba` was painted. Tiles not of the globe are skipped.
    ///
    /// # Panics
    /// If `rgba` is not the picture's size (width × height × 4 bytes).
    pub fn repaint(
        &self,
        tiles: impl IntoIterator<Item = GlobeTile>,
        look: impl Fn(GlobeTile) -> TileLook,
        rgba: &mut [u8],
    ) -> usize {
        assert_eq!(rgba.len(), self.base.len() * 4, "the picture is {}x{} RGBA8", self.size[0], self.size[1]);
        let mut dirty: Vec<u32> = Vec::new();
        for tile in tiles {
            for &i in self.pixels_of(tile) {
                dirty.push(i);
                dirty.extend(self.around(i));
            }
        }
        dirty.sort_unstable();
        dirty.dedup();
        let mut changed = 0;
        for i in dirty {
            let i = i as usize;
            let color = self.pixel(i, |t| look(GlobeTile(t)));
            if rgba[i * 4..i * 4 + 4] != color {
                rgba[i * 4..i * 4 + 4].copy_from_slice(&color);
                changed += 1;
            }
        }
        changed
    }

    /// The pixels (row-major indices) of the circle `angle` radians around `direction`: the
    /// outline of what a camera looking down along `direction` sees of the globe. Each pixel
    /// once; none for an angle not in `(0, pi)`.
    #[must_use]
    pub fn view_outline(&self, direction: [f64; 3], angle: f64) -> Vec<u32> {
        if !(angle > 0.0 && angle < std::f64::consts::PI) {
            return Vec::new();
        }
        let d = normalize(direction);
        // Two unit vectors across `d`, then points of the circle, a step under a pixel apart.
        let helper = if d[1].abs() < 0.9 { [0.0, 1.0, 0.0] } else { [1.0, 0.0, 0.0] };
        let u = normalize(cross(d, helper));
        let v = cross(d, u);
        let (sa, ca) = angle.sin_cos();
        let steps = (8.0 * f64::from(self.size[0]) * sa).ceil().max(16.0) as u32;
        let mut out = Vec::new();
        for k in 0..steps {
            let t = f64::from(k) / f64::from(steps) * std::f64::consts::TAU;
            let (st, ct) = t.sin_cos();
            let p = [0, 1, 2].map(|i| d[i] * ca + (u[i] * ct + v[i] * st) * sa);
            out.push(self.pixel_index(p));
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The pixels (row-major indices) of a closed polygon on the sphere: its corners are unit
    /// directions (any length is normalized), each edge the shorter great-circle arc from a
    /// corner to the next (the last back to the first). The outline of a camera's view when the
    /// corners are where the rays along its view's border meet the globe. Each pixel once; none
    /// for fewer than two corners.
    #[must_use]
    pub fn polygon_outline(&self, corners: &[[f64; 3]]) -> Vec<u32> {
        if corners.len() < 2 {
            return Vec::new();
        }
        let pixel = std::f64::consts::TAU / f64::from(self.size[0]);
        let mut out = Vec::new();
        for (k, &a) in corners.iter().enumerate() {
            let (a, b) = (normalize(a), normalize(corners[(k + 1) % corners.len()]));
            let dot = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0);
            let angle = dot.acos();
            let steps = (4.0 * angle / pixel).ceil().max(1.0) as u32;
            let sin = angle.sin();
            for s in 0..steps {
                let t = f64::from(s) / f64::from(steps);
                // Spherical interpolation; a degenerate edge (its corners equal or opposite)
                // is drawn as its first corner.
                let p = if sin < 1e-9 {
                    a
                } else {
                    let (wa, wb) = (((1.0 - t) * angle).sin() / sin, (t * angle).sin() / sin);
                    [0, 1, 2].map(|i| a[i] * wa + b[i] * wb)
                };
                out.push(self.pixel_index(p));
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The row-major index of the pixel a direction falls in.
    fn pixel_index(&self, direction: [f64; 3]) -> u32 {
        let [x, y] = self.point_of(direction);
        let px = (x.floor() as i64).rem_euclid(i64::from(self.size[0])) as u32;
        let py = (y.floor() as i64).clamp(0, i64::from(self.size[1]) - 1) as u32;
        py * self.size[0] + px
    }

    /// The color of pixel `i`: its tile's look; an owned pixel beside one of another owner (or
    /// none), east, west, north or south, is its border.
    fn pixel(&self, i: usize, look_of: impl Fn(u32) -> TileLook) -> [u8; 4] {
        let look = look_of(self.pixel_tile[i]);
        let style = &self.style;
        if style.fog_of_war && look.fog == FogState::Unexplored {
            return style.unexplored;
        }
        let border = look.owner.is_some_and(|owner| {
            self.around(i as u32).iter().any(|&j| look_of(self.pixel_tile[j as usize]).owner != Some(owner))
        });
        shade(style, self.base[i], look, border)
    }

    /// The pixels east, west, north and south of pixel `i` (across the date line east and west;
    /// at the top and bottom rows, the pixel itself north or south).
    fn around(&self, i: u32) -> [u32; 4] {
        let [w, h] = self.size;
        let (x, y) = (i % w, i / w);
        [y * w + (x + 1) % w, y * w + (x + w - 1) % w, y.saturating_sub(1) * w + x, (y + 1).min(h - 1) * w + x]
    }
}

/// Each tile's color: its terrain's minimap color (else its color) on a globe with a climate,
/// else its type's in `style`.
fn tile_colors(globe: &GlobeTerrain, style: &MinimapStyle) -> Vec<[u8; 4]> {
    let ruleset = globe.ruleset();
    globe
        .grid()
        .tiles()
        .map(|t| {
            let [r, g, b] = if globe.config().climate.enabled {
                let look = &ruleset.terrain(globe.tile_terrain(t).expect("a tile of the globe").terrain).look;
                look.minimap.unwrap_or(look.color)
            } else {
                style.kind_colors[globe.tile_kind(t).expect("a tile of the globe") as usize]
            };
            [r, g, b, 255]
        })
        .collect()
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(f64::MIN_POSITIVE);
    a.map(|c| c / l)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
