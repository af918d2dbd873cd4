//! Prevailing winds, a step of the per-map tile table on maps whose climate has `winds`: the
//! rain each tile gets from the air that blows over it.
//!
//! Every tile has the wind of its latitude band ([`WindPattern`]). Its air comes from its
//! upwind neighbors (the neighbors lying against its wind whose own wind blows toward it),
//! weighted by how squarely they lie upwind; air from past a map's edge is sea air. Over the sea
//! the air picks up humidity; over land a share of its humidity rains out (`raininess`), the air
//! dries a little (`drying`), and where the land is higher than the air's humidity allows (it
//! holds 1 at sea level, falling with the square of the height to 0 at the top of the relief,
//! so a quarter halfway up) a share of the excess rains out on the
//! slope (`rain_shadow`), so the land behind a range gets drier air. The rain is then raised
//! where the bands' winds meet and lowered where they part (`uplift`).
//!
//! Tiles are taken in order along their own wind (each band's tiles after those upwind of them),
//! twice over: the second lap carries the air that crossed a wrapping map's seam, or a band's
//! edge, in the first. A fixed order and a fixed number of laps over the whole map's tiles make
//! the rain a pure function of the tiles' heights and kinds: every chunk, thread and order reads
//! the same table.

use hexx::Hex;

use crate::chunk::TileRect;
use crate::config::{WindConfig, WindPattern};
use crate::geometry::Geometry;
use crate::hash::order_key;
use crate::vocab::TileKind;

/// Laps over the map: the first carries air along each band, the second across the seam of a
/// wrapping map and the bands' edges.
const LAPS: usize = 2;

/// A neighbor lies upwind when the cosine between the wind and the step to it is below minus
/// this (a neighbor square to the wind is neither upwind nor downwind).
const ACROSS: f32 = 1e-3;

/// An upwind slot with no neighbor in it.
const NONE: u32 = u32::MAX;

/// An upwind neighbor past the map's edge: sea air.
const SEA: u32 = u32::MAX - 1;

/// The humidity of air that has crossed open sea (and of air blowing in past a map's edge).
const SEA_AIR: f32 = 1.0;

/// The tiles of a map with what the rain needs of them, row by row.
pub(crate) struct RainInput<'a> {
    /// The map's tiles: their rectangle, and each tile row by row.
    pub rect: TileRect,
    pub tiles: &'a [Hex],
    /// Each tile's center height, raw (normalised).
    pub raw: &'a [f32],
    /// Each tile's kind.
    pub kinds: &'a [TileKind],
    /// The sea threshold: land at it is at sea level, 1 is the top of the relief.
    pub sea: f32,
    /// The latitudes of the map's first and last rows.
    pub latitudes: (f32, f32),
}

/// A tile's latitude on a map of `rect` whose first and last rows' outer edges lie at
/// `latitudes` ([`ClimateConfig::latitudes`](crate::ClimateConfig::latitudes): 1 the north
/// pole, 0 the equator, -1 the south pole): how far from the equator (0) toward a pole (1), and
/// whether it lies in the northern half.
#[must_use]
pub(crate) fn latitude(rect: TileRect, row: i32, latitudes: (f32, f32)) -> (f32, bool) {
    let rows = (rect.max[1] - rect.min[1]).max(1) as f32;
    let t = ((row - rect.min[1]) as f32 + 0.5) / rows;
    if latitudes == POLE_TO_POLE {
        let v = t - 0.5;
        return (v.abs() * 2.0, v < 0.0);
    }
    let l = latitudes.0 + (latitudes.1 - latitudes.0) * t;
    (l.abs(), l > 0.0)
}

/// The default [`ClimateConfig::latitudes`](crate::ClimateConfig::latitudes): the first row at
/// the north pole, the last at the south pole.
pub(crate) const POLE_TO_POLE: (f32, f32) = (1.0, -1.0);

/// The unit vector (world `x`, `z`) the air moves along under a wind blowing from `bearing`
/// degrees clockwise from north (`-z`).
fn moving(bearing: f32) -> [f32; 2] {
    let b = bearing.to_radians();
    [-b.sin(), b.cos()]
}

/// The winds of a map: the direction of each band's air in each half.
struct Bands {
    /// The air's direction in band `i` of the northern half, equator first.
    north: Vec<[f32; 2]>,
    /// Whether it is one wind over the whole map (not mirrored, no band edges).
    one: bool,
}

impl Bands {
    fn new(pattern: &WindPattern) -> Self {
        let (bearings, one) = match pattern {
            WindPattern::Bands(b) => (b.clone(), false),
            WindPattern::One(b) => (vec![*b], true),
        };
        Self { north: bearings.into_iter().map(moving).collect(), one }
    }

    /// The band of a latitude.
    fn band(&self, latitude: f32) -> usize {
        ((latitude * self.north.len() as f32) as usize).min(self.north.len() - 1)
    }

    /// The air's direction at a latitude; the southern half mirrors the northern north to
    /// south.
    fn wind(&self, latitude: f32, north: bool) -> [f32; 2] {
        let [x, z] = self.north[self.band(latitude)];
        if self.one || north { [x, z] } else { [x, -z] }
    }

    /// The air's speed toward the pole in band `i` (the same in both halves).
    fn poleward(&self, i: usize) -> f32 {
        -self.north[i][1]
    }

    /// How much the rain is raised (above 1) or lowered at a latitude: at each band's edge, by
    /// how squarely the winds on its two sides blow toward it (meeting, rising air) or away
    /// from it (parting, sinking air), fading to nothing half a band away.
    fn uplift(&self, uplift: f32, latitude: f32) -> f32 {
        if self.one {
            return 1.0;
        }
        let n = self.north.len();
        let half = 0.5 / n as f32;
        let mut sum = 0.0;
        for k in 0..n {
            // Edge k: the equator (both halves' first band) or between bands k - 1 and k.
            let meet = if k == 0 { -self.poleward(0) } else { 0.5 * (self.poleward(k - 1) - self.poleward(k)) };
            let d = ((latitude - k as f32 / n as f32).abs() / half).min(1.0);
            let fade = 0.5 + 0.5 * (d * std::f32::consts::PI).cos();
            sum += meet * fade;
        }
        (1.0 + uplift * sum).max(0.0)
    }
}

/// The unit step (world `x`, `z`) toward each neighbor, in `Hex::all_neighbors` order: the same
/// from every tile.
#[must_use]
pub(crate) fn neighbor_steps(geometry: &Geometry) -> [[f32; 2]; 6] {
    let lattice = geometry.lattice();
    let position = |t: Hex| lattice.world(lattice.tile_center(t)).map(|v| v as f32);
    let origin = position(Hex::ZERO);
    Hex::ZERO.all_neighbors().map(|nb| {
        let [x, z] = position(nb);
        let (dx, dz) = (x - origin[0], z - origin[1]);
        let len = dx.hypot(dz);
        [dx / len, dz / len]
    })
}

/// The unit vector (world `x`, `z`) the air moves along in each row of a map of `rect`, first
/// row first, under `config`'s winds with the rows at `latitudes`.
#[must_use]
pub(crate) fn row_winds(config: &WindConfig, rect: TileRect, latitudes: (f32, f32)) -> Vec<[f32; 2]> {
    let bands = Bands::new(&config.pattern);
    (rect.min[1]..rect.max[1])
        .map(|r| {
            let (lat, north) = latitude(rect, r, latitudes);
            bands.wind(lat, north)
        })
        .collect()
}

/// Each tile's rain (row by row over `input.rect`, `0` and above, about 1 on a windward coast),
/// with `neighbor(i, d)` giving the row-major index of tile `i`'s neighbor in direction `d`
/// (`Hex::all_neighbors` order; any copy of it on a wrapping map), `None` past the map's edge.
#[must_use]
pub(crate) fn rainfall(
    config: &WindConfig,
    geometry: &Geometry,
    input: &RainInput<'_>,
    neighbor: impl Fn(usize, usize) -> Option<usize>,
) -> Vec<f32> {
    let rect = input.rect;
    let bands = Bands::new(&config.pattern);
    let lattice = geometry.lattice();
    let position = |t: Hex| lattice.world(lattice.tile_center(t)).map(|v| v as f32);
    let steps = neighbor_steps(geometry);
    let dot = |a: [f32; 2], b: [f32; 2]| a[0] * b[0] + a[1] * b[1];
    let tiles = input.tiles;
    let cols = (rect.max[0] - rect.min[0]).max(0) as usize;
    // Each row's latitude, wind and uplift.
    let rows: Vec<(f32, [f32; 2], f32)> = (rect.min[1]..rect.max[1])
        .map(|r| {
            let (lat, north) = latitude(rect, r, input.latitudes);
            (lat, bands.wind(lat, north), bands.uplift(config.uplift, lat))
        })
        .collect();
    let wind = |i: usize| rows[i / cols.max(1)].1;
    // Each tile's upwind neighbors and their weights (`SEA`: sea air from past the edge).
    let mut upwind: Vec<[(u32, f32); 6]> = vec![[(NONE, 0.0); 6]; tiles.len()];
    for (i, slots) in upwind.iter_mut().enumerate() {
        let mut n = 0;
        for (d, &step) in steps.iter().enumerate() {
            let toward = dot(step, wind(i));
            if toward >= -ACROSS {
                continue;
            }
            let from = match neighbor(i, d) {
                Some(j) if dot(step, wind(j)) < -ACROSS => j as u32,
                Some(_) => continue,
                None => SEA,
            };
            slots[n] = (from, -toward);
            n += 1;
        }
    }
    // Upwind tiles first: by position along the tile's own wind, then row-major.
    let mut keys: Vec<u64> =
        tiles.iter().enumerate().map(|(i, &t)| order_key(dot(position(t), wind(i)), i as u32)).collect();
    keys.sort_unstable();
    let order: Vec<usize> = keys.iter().map(|&k| (k & u64::from(u32::MAX)) as usize).collect();

    let land_range = (1.0 - input.sea).max(f32::EPSILON);
    let mut humidity = vec![SEA_AIR; tiles.len()];
    let mut rain = vec![0.0; tiles.len()];
    for _ in 0..LAPS {
        for &i in &order {
            let (mut sum, mut weight) = (0.0, 0.0);
            for &(j, w) in upwind[i].iter().take_while(|(j, _)| *j != NONE) {
                sum += w * if j == SEA { SEA_AIR } else { humidity[j as usize] };
                weight += w;
            }
            // No air from upwind: sinking, dry air.
            let arriving = if weight > 0.0 { sum / weight } else { 0.0 };
            if input.kinds[i] == TileKind::Sea {
                humidity[i] = (arriving + config.evaporation).min(SEA_AIR);
                rain[i] = config.raininess * arriving;
                continue;
            }
            let height = ((input.raw[i] - input.sea) / land_range).clamp(0.0, 1.0);
            let mut air = arriving * (1.0 - config.drying);
            let holds = (1.0 - height) * (1.0 - height);
            let shadow = if air > holds { config.rain_shadow * (air - holds) } else { 0.0 };
            air -= shadow;
            humidity[i] = air;
            rain[i] = config.raininess * arriving + shadow;
        }
    }
    for (i, r) in rain.iter_mut().enumerate() {
        *r *= rows[i / cols.max(1)].2;
    }
    rain
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn earth_bands_part_at_the_horse_latitudes_and_meet_at_the_equator() {
        let pattern = WindPattern::default();
        let bands = Bands::new(&pattern);
        let at = |lat: f32| bands.uplift(0.5, lat);
        assert!(at(0.0) > 1.3, "equator {}", at(0.0));
        assert!(at(1.0 / 3.0) < 0.7, "horse latitudes {}", at(1.0 / 3.0));
        assert!(at(2.0 / 3.0) > 1.3, "polar front {}", at(2.0 / 3.0));
        assert!((at(1.0 / 6.0) - 1.0).abs() < 1e-6, "mid-band {}", at(1.0 / 6.0));
        // The trade winds blow toward the equator and west in the north, toward it and west in
        // the south.
        let [x, z] = bands.wind(0.1, true);
        assert!(x < 0.0 && z > 0.0, "north trades move south-west: {x} {z}");
        let [x, z] = bands.wind(0.1, false);
        assert!(x < 0.0 && z < 0.0, "south trades move north-west: {x} {z}");
        assert_eq!(Bands::new(&WindPattern::One(90.0)).uplift(1.0, 0.33), 1.0);
    }
}
