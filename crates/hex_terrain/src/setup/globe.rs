//! A game setup on a whole globe: the flat map's steps (ring values, regions of equal
//! fertility, starts, wonders and resources, normalisation, the report) over the globe's tile
//! graph, pentagons included. Regions are cut on a grid of longitude and latitude cells about a
//! tile wide, wrapping east to west, so a region is a box of longitudes and latitudes as on a
//! wrapping flat map.

use std::time::Instant;

use super::board::{Board, lon_lat};
use super::regions::{self, Division};
use super::survey::{GlobeStages, Survey};
use super::{Placed, PlacedResource, PlacedWonder, SetupReport, SetupTimings, TileSetup, check_places, place};
use crate::config::SetupConfig;
use crate::error::ConfigError;
use crate::globe::grid::GlobeTile;

/// A region of equal fertility on a globe: a box of longitudes and latitudes.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeRegion {
    /// Its western and eastern longitude in degrees, east positive; the eastern one may pass
    /// 180 when the region runs across the antimeridian (subtract 360 for the longitude).
    pub longitudes: [f64; 2],
    /// Its southern and northern latitude in degrees, north positive.
    pub latitudes: [f64; 2],
    /// Its tiles' fertility (their value, open ocean not counted).
    pub fertility: f32,
}

/// The setup of a game on a globe ([`GlobeTerrain::setup`](crate::GlobeTerrain::setup)): the
/// players' starts, resources, natural wonders, regions and the fairness report, as
/// [`Setup`](crate::Setup) places them on a flat map.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobeSetup {
    regions: Vec<GlobeRegion>,
    placed: Placed<GlobeTile>,
}

impl GlobeSetup {
    /// Places the setup on a globe's tiles, drawing with `seed` (the map's).
    ///
    /// # Errors
    /// A terrain or feature its rules name that is not of the ruleset, `setup.players` or
    /// `setup.min_distance` when the starts do not fit.
    pub(crate) fn build(stages: GlobeStages, config: &SetupConfig, seed: u32) -> Result<Self, ConfigError> {
        let clock = Instant::now();
        check_places(stages.ruleset, config)?;
        let survey = Survey::globe(stages, config);
        let Board::Globe(sphere) = &survey.board else { unreachable!("a globe's survey") };
        // Cells about a tile wide: a tile's angle is about the square root of its share of the
        // sphere's 4 pi steradians.
        let tile_angle = (4.0 * std::f64::consts::PI / sphere.centers.len() as f64).sqrt();
        let rows = ((std::f64::consts::PI / tile_angle).round() as usize).max(2);
        let cols = 2 * rows;
        let cell_of: Vec<usize> = sphere
            .centers
            .iter()
            .map(|&dir| {
                let [lon, lat] = lon_lat(dir);
                let c = (((lon + 180.0) / 360.0 * cols as f64) as usize).min(cols - 1);
                let r = (((90.0 - lat) / 180.0 * rows as f64) as usize).min(rows - 1);
                r * cols + c
            })
            .collect();
        let divide = |fertility: &[f32]| {
            let mut cells = vec![0.0f32; rows * cols];
            for (i, &f) in fertility.iter().enumerate() {
                cells[cell_of[i]] += f;
            }
            let by_cell = regions::divide(cols, true, &cells, config.players as usize);
            let region_of = cell_of.iter().map(|&c| by_cell.region_of[c]).collect();
            Division { region_of, ..by_cell }
        };
        let mut timings = SetupTimings::default();
        let (placed, division) = place(&survey, config, seed, |i| GlobeTile(i as u32), divide, clock, &mut timings)?;
        let (lon_step, lat_step) = (360.0 / cols as f64, 180.0 / rows as f64);
        let regions = division
            .regions
            .iter()
            .map(|r| {
                let west = -180.0 + ((r.cols[0] + division.cut) % cols) as f64 * lon_step;
                GlobeRegion {
                    longitudes: [west, west + (r.cols[1] - r.cols[0]) as f64 * lon_step],
                    latitudes: [90.0 - r.rows[1] as f64 * lat_step, 90.0 - r.rows[0] as f64 * lat_step],
                    fertility: r.fertility,
                }
            })
            .collect();
        Ok(Self { regions, placed })
    }

    /// The start tiles, in player order.
    #[must_use]
    pub fn starts(&self) -> &[GlobeTile] {
        &self.placed.starts
    }

    /// The regions, in order (region `k` is where player `k` was first placed).
    #[must_use]
    pub fn regions(&self) -> &[GlobeRegion] {
        &self.regions
    }

    /// Every resource, in tile order (by id).
    #[must_use]
    pub fn resources(&self) -> &[PlacedResource<GlobeTile>] {
        &self.placed.resources
    }

    /// Every natural wonder, in tile order.
    #[must_use]
    pub fn wonders(&self) -> &[PlacedWonder<GlobeTile>] {
        &self.placed.wonders
    }

    /// The fairness report.
    #[must_use]
    pub fn report(&self) -> &SetupReport<GlobeTile> {
        &self.placed.report
    }

    /// What lies on a tile; `None` for a tile not of the globe.
    #[must_use]
    pub fn at(&self, tile: GlobeTile) -> Option<TileSetup<'_, GlobeTile>> {
        ((tile.0 as usize) < self.placed.region_of.len()).then(|| self.placed.at(tile.0 as usize))
    }
}
