//! A top-down picture of a map, for a minimap: which tile every pixel shows, the tiles' biome or
//! type colors with rivers and lakes, and a game's per-tile state painted over them (fog of war,
//! owners' tint and borders). A change of state repaints only the pixels of the tiles it touches
//! (and of their neighbors, whose borders depend on it), so a game that writes a few tiles a
//! turn never redraws the picture. [`Minimap::outline`] gives the pixels of a polygon's edges (a
//! camera's view on the ground).
//!
//! A bounded map is shown whole; a wrapping map's picture spans exactly one period east-west, so
//! it wraps as the map does (a pixel past its east edge is the pixel at its west edge); an
//! unbounded world is shown in a rectangle of tiles the caller chooses (around the camera).
//! Pixels are square: row 0 is the north edge (smallest world z), column 0 the west edge.
//!
//! ```
//! use hex_terrain::minimap::{Minimap, MinimapStyle, TileLook};
//! use hex_terrain::{MapConfig, MapSize, Terrain};
//!
//! let terrain = Terrain::new(MapConfig { size: MapSize::Bounded { x: 40, z: 24 }, ..MapConfig::default() }).unwrap();
//! let minimap = Minimap::new(&terrain, terrain.bounds().unwrap(), [160, 160], MinimapStyle::default()).unwrap();
//! let rgba = minimap.paint(|_| TileLook::VISIBLE);
//! assert_eq!(rgba.len(), (minimap.size()[0] * minimap.size()[1] * 4) as usize);
//! ```

mod build;
mod globe;
mod outline;

use hexx::Hex;

use crate::chunk::TileRect;
use crate::save::FogState;
use crate::terrain::Terrain;

pub use globe::{GlobeMinimap, MAX_GLOBE_MINIMAP_WIDTH};

/// No tile: a pixel off the map.
const NONE: u32 = u32::MAX;

/// The state of a tile the picture shows: what the player knows of it and who owns it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TileLook {
    /// Fog of war: unexplored tiles are drawn in [`MinimapStyle::unexplored`], explored ones
    /// dimmed.
    pub fog: FogState,
    /// The owner, a player from 0 (as a setup numbers its starts), tinting the tile and drawing
    /// a border along its edges with other owners or nobody.
    pub owner: Option<u32>,
}

impl TileLook {
    /// A visible tile nobody owns: the map as generated.
    pub const VISIBLE: Self = Self { fog: FogState::Visible, owner: None };
}

/// How the picture is drawn. Colors are sRGB bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct MinimapStyle {
    /// Colors of sea, land and mountain tiles on maps without climate (on maps with it, each
    /// biome's [`Biome::color`](crate::Biome::color)).
    pub kind_colors: [[u8; 3]; 3],
    /// Color of rivers and lakes.
    pub water_color: [u8; 3],
    /// Width of a river line, a fraction of the hex radius (at least about a pixel is drawn).
    pub river_width: f64,
    /// Pixels off the map.
    pub background: [u8; 4],
    /// Draw fog of war (off: every tile as visible).
    pub fog_of_war: bool,
    /// Unexplored tiles.
    pub unexplored: [u8; 4],
    /// Brightness of explored tiles not in sight, `0..=1` (they are also half desaturated).
    pub explored_brightness: f32,
    /// Owner colors: player `n` takes entry `n` (entries repeat past the list's end).
    pub owner_colors: Vec<[u8; 3]>,
    /// How much an owned tile takes its owner's color, `0..=1`.
    pub territory_tint: f32,
    /// Width of the border line inside an owned tile's edges with another owner or nobody, a
    /// fraction of the hex radius (0: none).
    pub border_width: f64,
}

impl Default for MinimapStyle {
    fn default() -> Self {
        Self {
            kind_colors: [[28, 87, 184], [77, 153, 51], [158, 153, 148]],
            water_color: [52, 118, 176],
            river_width: 0.22,
            background: [12, 14, 18, 255],
            fog_of_war: true,
            unexplored: [0, 0, 0, 255],
            explored_brightness: 0.55,
            owner_colors: vec![
                [220, 50, 47],
                [38, 139, 210],
                [240, 200, 40],
                [133, 153, 0],
                [211, 54, 130],
                [42, 161, 152],
                [203, 75, 22],
                [108, 113, 196],
            ],
            territory_tint: 0.35,
            border_width: 0.28,
        }
    }
}

/// The picture of a rectangle of tiles: the pixels' tiles, edges and base colors, computed once;
/// painting applies the tiles' [`TileLook`]s.
#[derive(Debug, Clone)]
pub struct Minimap {
    terrain: Terrain,
    style: MinimapStyle,
    region: TileRect,
    size: [u32; 2],
    /// World `(x, z)` of the north-west corner of pixel `(0, 0)`.
    origin: [f64; 2],
    /// World units a pixel.
    step: f64,
    /// Whether the picture spans one period of a wrapping map.
    wraps: bool,
    /// Per pixel: the index of its tile in the region, or [`NONE`].
    pixel_tile: Vec<u32>,
    /// Per pixel: the neighbor slot (`0..6`, in [`Hex::all_neighbors`] order) of the tile edge
    /// nearest to it, and its distance to that edge in hex radii.
    pixel_edge: Vec<(u8, f32)>,
    /// Per pixel: its color before any tile state.
    base: Vec<[u8; 4]>,
    /// Per region tile: the indices of its six neighbors in the region (wrapped), or [`NONE`].
    neighbors: Vec<[u32; 6]>,
    /// Per region tile: where its pixels start in `tile_pixels` (one more entry at the end).
    tile_start: Vec<u32>,
    /// The pixels of every tile, tile after tile.
    tile_pixels: Vec<u32>,
}

impl Minimap {
    /// The picture's size in pixels.
    #[must_use]
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// The tiles shown (offset coordinates).
    #[must_use]
    pub fn region(&self) -> TileRect {
        self.region
    }

    /// World units a pixel.
    #[must_use]
    pub fn step(&self) -> f64 {
        self.step
    }

    /// Whether the picture wraps east-west (it spans one period of a wrapping map).
    #[must_use]
    pub fn wraps(&self) -> bool {
        self.wraps
    }

    /// The style it is drawn with.
    #[must_use]
    pub fn style(&self) -> &MinimapStyle {
        &self.style
    }

    /// World `(x, z)` at fractional pixel coordinates (`(0, 0)` is the north-west corner of the
    /// first pixel, `(0.5, 0.5)` its center).
    #[must_use]
    pub fn pixel_to_world(&self, px: f64, py: f64) -> [f64; 2] {
        [self.origin[0] + px * self.step, self.origin[1] + py * self.step]
    }

    /// Fractional pixel coordinates of world `(x, z)`; on a wrapping picture, `x` of any copy of
    /// the map lands in `0..width`.
    #[must_use]
    pub fn world_to_pixel(&self, x: f64, z: f64) -> [f64; 2] {
        let mut px = (x - self.origin[0]) / self.step;
        if self.wraps {
            px = px.rem_euclid(f64::from(self.size[0]));
        }
        [px, (z - self.origin[1]) / self.step]
    }

    /// The tile a pixel shows (the map's own tile), `None` off the map or the picture.
    #[must_use]
    pub fn tile_at_pixel(&self, px: u32, py: u32) -> Option<Hex> {
        if px >= self.size[0] || py >= self.size[1] {
            return None;
        }
        let t = self.pixel_tile[(py * self.size[0] + px) as usize];
        (t != NONE).then(|| self.tile(t))
    }

    /// The pixels showing a tile (indices `y * width + x`; the map's own tile on a wrapping map;
    /// empty for a tile not in the picture or smaller than a pixel).
    #[must_use]
    pub fn pixels_of(&self, tile: Hex) -> &[u32] {
        self.index(tile).map_or(&[], |t| {
            &self.tile_pixels[self.tile_start[t as usize] as usize..self.tile_start[t as usize + 1] as usize]
        })
    }

    /// The whole picture, RGBA8 sRGB rows north to south, with each tile's look.
    #[must_use]
    pub fn paint(&self, look: impl Fn(Hex) -> TileLook) -> Vec<u8> {
        let looks: Vec<TileLook> = (0..self.neighbors.len() as u32).map(|t| look(self.tile(t))).collect();
        let mut rgba = vec![0u8; self.base.len() * 4];
        for (i, px) in rgba.chunks_exact_mut(4).enumerate() {
            px.copy_from_slice(&self.pixel(i, |t| looks[t as usize]));
        }
        rgba
    }

    /// Repaints in `rgba` (a picture from [`paint`](Self::paint)) the pixels of `tiles` and of
    /// their neighbors (whose borders depend on them) with each tile's look; returns how many
    /// pixels were written. The result equals a full [`paint`](Self::paint) with the same looks.
    ///
    /// # Panics
    /// If `rgba` is not the picture's size (width × height × 4 bytes).
    pub fn repaint(
        &self,
        tiles: impl IntoIterator<Item = Hex>,
        look: impl Fn(Hex) -> TileLook,
        rgba: &mut [u8],
    ) -> usize {
        assert_eq!(rgba.len(), self.base.len() * 4, "the picture is {}x{} RGBA8", self.size[0], self.size[1]);
        let mut dirty: Vec<u32> = Vec::new();
        for tile in tiles {
            if let Some(t) = self.index(tile) {
                dirty.push(t);
                dirty.extend(self.neighbors[t as usize].iter().copied().filter(|&n| n != NONE));
            }
        }
        dirty.sort_unstable();
        dirty.dedup();
        // The looks needed: the dirty tiles' and their neighbors'.
        let mut needed: Vec<u32> = dirty.clone();
        for &t in &dirty {
            needed.extend(self.neighbors[t as usize].iter().copied().filter(|&n| n != NONE));
        }
        needed.sort_unstable();
        needed.dedup();
        let looks: Vec<TileLook> = needed.iter().map(|&t| look(self.tile(t))).collect();
        let look_of = |t: u32| looks[needed.binary_search(&t).unwrap_or_default()];
        let mut written = 0;
        for &t in &dirty {
            for &i in &self.tile_pixels[self.tile_start[t as usize] as usize..self.tile_start[t as usize + 1] as usize]
            {
                let i = i as usize;
                rgba[i * 4..i * 4 + 4].copy_from_slice(&self.pixel(i, look_of));
                written += 1;
            }
        }
        written
    }

    /// The color of pixel `i`.
    fn pixel(&self, i: usize, look_of: impl Fn(u32) -> TileLook) -> [u8; 4] {
        let t = self.pixel_tile[i];
        if t == NONE {
            return self.style.background;
        }
        let style = &self.style;
        let look = look_of(t);
        if style.fog_of_war && look.fog == FogState::Unexplored {
            return style.unexplored;
        }
        let border = look.owner.is_some_and(|owner| {
            let (slot, distance) = self.pixel_edge[i];
            let across = self.neighbors[t as usize][slot as usize];
            f64::from(distance) < style.border_width && (across == NONE || look_of(across).owner != Some(owner))
        });
        shade(style, self.base[i], look, border)
    }
}

/// A tile pixel's color (`base`, before any state) with its tile's look: its owner's tint (the
/// full color on its border), dimmed and half desaturated when explored but not in sight. A
/// flat map's picture and a globe's alike.
fn shade(style: &MinimapStyle, base: [u8; 4], look: TileLook, border: bool) -> [u8; 4] {
    let mut c = base.map(f32::from);
    if let Some(owner) = look.owner {
        let colors = &style.owner_colors;
        let color = if colors.is_empty() { [255, 255, 255] } else { colors[owner as usize % colors.len()] };
        let tint = if border { 1.0 } else { style.territory_tint.clamp(0.0, 1.0) };
        for k in 0..3 {
            c[k] += (f32::from(color[k]) - c[k]) * tint;
        }
    }
    if style.fog_of_war && look.fog == FogState::Explored {
        let luma = 0.3 * c[0] + 0.59 * c[1] + 0.11 * c[2];
        let b = style.explored_brightness.clamp(0.0, 1.0);
        for v in &mut c[..3] {
            *v = (0.5 * (*v + luma)) * b;
        }
    }
    [c[0].round() as u8, c[1].round() as u8, c[2].round() as u8, 255]
}

impl Minimap {
    fn tile(&self, t: u32) -> Hex {
        let w = self.region.max[0] - self.region.min[0];
        let t = t as i32;
        self.terrain.tile_from_offset([self.region.min[0] + t % w, self.region.min[1] + t / w])
    }

    fn index(&self, tile: Hex) -> Option<u32> {
        index_in(&self.terrain, self.region, self.terrain.wrap_tile(tile)?)
    }
}

/// The index of a tile of the map (its own tile on a wrapping map) in `region`, row after row,
/// if it is in it.
fn index_in(terrain: &Terrain, region: TileRect, tile: Hex) -> Option<u32> {
    let [col, row] = terrain.offset_of(tile);
    let w = region.max[0] - region.min[0];
    region.contains([col, row]).then(|| ((row - region.min[1]) * w + (col - region.min[0])) as u32)
}
