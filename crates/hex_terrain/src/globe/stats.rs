//! A globe's statistics ([`GlobeStats::measure`]): the flat map's [`MapStats`](crate::MapStats)
//! rules on the sphere's tile graph, so a globe is judged by the numbers a flat map is.
//!
//! - **Water** is sea tiles (a globe has no lakes yet); **land** every other tile.
//! - A **landmass** is a set of land tiles joined through their neighbors; a **continent** holds
//!   at least [`CONTINENT_MIN_SHARE`] of the land and [`CONTINENT_MIN_TILES`] tiles, an
//!   **island** less.
//! - The **coast** is counted in tile edges between a land tile and a sea tile.
//! - The **narrowest strait** is the fewest tiles between two continents: the fewest steps over
//!   the tile graph between tiles of two continents, less one.
//! - The **polar land** is the land beyond [`POLAR_LATITUDE`] degrees north or south (the
//!   latitudes of a flat map's first and last tenth of its rows, from pole to pole).

use crate::heights::targets::{components, nearest_between};
use crate::stats::{CONTINENT_MIN_SHARE, CONTINENT_MIN_TILES, LandmassKind};
use crate::vocab::{Biome, TileKind};

use super::GlobeTile;
use super::terrain::GlobeTerrain;

/// Latitude (degrees, north or south) beyond which land counts as polar.
pub const POLAR_LATITUDE: f64 = 72.0;

/// One landmass of a globe ([`GlobeStats::landmasses`]).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeLandmass {
    /// Its tile of the smallest id: a name that does not depend on the order tiles are visited.
    pub first: GlobeTile,
    /// Its tiles.
    pub tiles: u32,
    /// Its mountain tiles.
    pub mountains: u32,
    /// Its coast, in tile edges to the sea.
    pub coast_edges: u32,
    /// The latitudes of its southernmost and northernmost tile centers, in degrees.
    pub latitudes: [f64; 2],
    /// Continent or island.
    pub kind: LandmassKind,
}

/// The statistics of a globe.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeStats {
    /// Tiles of the globe.
    pub tiles: u32,
    /// Sea tiles.
    pub sea_tiles: u32,
    /// Land tiles (mountains included).
    pub land_tiles: u32,
    /// Mountain tiles.
    pub mountain_tiles: u32,
    /// Neighbor pairs of mountains, each counted from both sides.
    pub mountain_adjacencies: u32,
    /// Land tiles beyond [`POLAR_LATITUDE`].
    pub polar_land_tiles: u32,
    /// The landmasses, largest first (ties: the smaller first tile).
    pub landmasses: Vec<GlobeLandmass>,
    /// Coast length, in tile edges between land and sea.
    pub coast_edges: u32,
    /// The fewest tiles between two continents; `None` with fewer than two.
    pub narrowest_strait: Option<u32>,
    /// Tiles of each biome present, in [`Biome::ALL`]'s order.
    pub biomes: Vec<(Biome, u32)>,
}

impl GlobeStats {
    /// Measures a globe.
    #[must_use]
    pub fn measure(globe: &GlobeTerrain) -> Self {
        let grid = globe.grid();
        let n = grid.tile_count() as usize;
        let kinds: Vec<TileKind> = grid.tiles().map(|t| globe.tile_kind(t).expect("a tile of the globe")).collect();
        let neighbors: Vec<[Option<u32>; 6]> = grid
            .tiles()
            .map(|t| {
                let mut six = [None; 6];
                for (slot, m) in six.iter_mut().zip(grid.neighbors(t).expect("a tile of the globe").as_slice()) {
                    *slot = Some(m.0);
                }
                six
            })
            .collect();
        let around = |i: usize| neighbors[i].iter().flatten().map(|&m| m as usize);
        let sea = |i: usize| kinds[i] == TileKind::Sea;
        let land_tiles = (0..n).filter(|&i| !sea(i)).count() as u32;
        let mountain = |i: usize| kinds[i] == TileKind::Mountain;
        // From the tile's center alone (a tile's info would finish its center point too).
        let latitude = |i: usize| {
            let center = grid.center(GlobeTile(i as u32)).expect("a tile of the globe");
            center[1].clamp(-1.0, 1.0).asin().to_degrees()
        };
        let masses = components(&neighbors, |i| !sea(i));
        let mut landmasses: Vec<GlobeLandmass> = masses
            .first
            .iter()
            .zip(&masses.sizes)
            .map(|(&first, &tiles)| GlobeLandmass {
                first: GlobeTile(first as u32),
                tiles,
                mountains: 0,
                coast_edges: 0,
                latitudes: [f64::INFINITY, f64::NEG_INFINITY],
                kind: if tiles >= CONTINENT_MIN_TILES
                    && f64::from(tiles) / f64::from(land_tiles.max(1)) >= CONTINENT_MIN_SHARE
                {
                    LandmassKind::Continent
                } else {
                    LandmassKind::Island
                },
            })
            .collect();
        let (mut coast_edges, mut mountain_adjacencies, mut polar_land_tiles) = (0, 0, 0);
        for i in (0..n).filter(|&i| !sea(i)) {
            let mass = &mut landmasses[masses.of[i] as usize];
            let shore = around(i).filter(|&m| sea(m)).count() as u32;
            mass.coast_edges += shore;
            coast_edges += shore;
            let lat = latitude(i);
            mass.latitudes = [mass.latitudes[0].min(lat), mass.latitudes[1].max(lat)];
            if mountain(i) {
                mass.mountains += 1;
                mountain_adjacencies += around(i).filter(|&m| mountain(m)).count() as u32;
            }
            polar_land_tiles += u32::from(lat.abs() >= POLAR_LATITUDE);
        }
        let continent: Vec<u32> = masses
            .of
            .iter()
            .map(
                |&m| if m != u32::MAX && landmasses[m as usize].kind == LandmassKind::Continent { m } else { u32::MAX },
            )
            .collect();
        let narrowest_strait = nearest_between(&neighbors, &continent);
        landmasses.sort_by(|a, b| b.tiles.cmp(&a.tiles).then(a.first.cmp(&b.first)));
        let biomes = Biome::ALL
            .iter()
            .map(|&b| (b, grid.tiles().filter(|&t| globe.tile_biome(t) == Some(b)).count() as u32))
            .filter(|&(_, count)| count > 0)
            .collect();
        Self {
            tiles: n as u32,
            sea_tiles: n as u32 - land_tiles,
            land_tiles,
            mountain_tiles: (0..n).filter(|&i| mountain(i)).count() as u32,
            mountain_adjacencies,
            polar_land_tiles,
            landmasses,
            coast_edges,
            narrowest_strait,
            biomes,
        }
    }

    /// Water's share of the tiles.
    #[must_use]
    pub fn water_share(&self) -> f64 {
        f64::from(self.sea_tiles) / f64::from(self.tiles.max(1))
    }

    /// The continents, largest first.
    pub fn continents(&self) -> impl Iterator<Item = &GlobeLandmass> {
        self.landmasses.iter().filter(|m| m.kind == LandmassKind::Continent)
    }

    /// The islands, largest first.
    pub fn islands(&self) -> impl Iterator<Item = &GlobeLandmass> {
        self.landmasses.iter().filter(|m| m.kind == LandmassKind::Island)
    }

    /// The largest landmass' share of the land (0 without land).
    #[must_use]
    pub fn largest_landmass_share(&self) -> f64 {
        self.landmasses.first().map_or(0.0, |m| f64::from(m.tiles) / f64::from(self.land_tiles.max(1)))
    }

    /// Mountains' share of the land.
    #[must_use]
    pub fn mountain_share(&self) -> f64 {
        f64::from(self.mountain_tiles) / f64::from(self.land_tiles.max(1))
    }

    /// How many mountain neighbors a mountain has on average (0 without mountains).
    #[must_use]
    pub fn mountain_neighbors(&self) -> f64 {
        f64::from(self.mountain_adjacencies) / f64::from(self.mountain_tiles.max(1))
    }

    /// Snow, tundra and snow peaks' share of the land.
    #[must_use]
    pub fn cold_share(&self) -> f64 {
        let cold: u32 = self
            .biomes
            .iter()
            .filter(|(b, _)| matches!(b, Biome::Snow | Biome::Tundra | Biome::SnowPeak))
            .map(|&(_, n)| n)
            .sum();
        f64::from(cold) / f64::from(self.land_tiles.max(1))
    }

    /// The polar land's share of the land.
    #[must_use]
    pub fn polar_land_share(&self) -> f64 {
        f64::from(self.polar_land_tiles) / f64::from(self.land_tiles.max(1))
    }
}

impl std::fmt::Display for GlobeStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let percent = |x: f64| x * 100.0;
        writeln!(
            f,
            "water: {:.1} % ({} sea tiles); land {} tiles; mountains {:.1} % of the land, {:.1} mountain neighbors a \
             mountain",
            percent(self.water_share()),
            self.sea_tiles,
            self.land_tiles,
            percent(self.mountain_share()),
            self.mountain_neighbors()
        )?;
        writeln!(
            f,
            "landmasses: {} ({} continents, {} islands), the largest {:.1} % of the land; coast {} edges; narrowest \
             strait {}",
            self.landmasses.len(),
            self.continents().count(),
            self.islands().count(),
            percent(self.largest_landmass_share()),
            self.coast_edges,
            self.narrowest_strait.map_or("none".to_owned(), |s| format!("{s} tiles"))
        )?;
        for (k, c) in self.continents().enumerate() {
            writeln!(
                f,
                "  continent {}: {} tiles ({} mountains), from {:.0} to {:.0} degrees of latitude",
                k + 1,
                c.tiles,
                c.mountains,
                c.latitudes[0],
                c.latitudes[1]
            )?;
        }
        write!(
            f,
            "poles: {:.1} % of the land beyond {POLAR_LATITUDE} degrees; snow, tundra and snow peaks {:.1} % of it",
            percent(self.polar_land_share()),
            percent(self.cold_share())
        )
    }
}
