//! A globe's climate: each tile's temperature from its latitude on the globe's axis (1 at the
//! equator, 0 at the poles, bent by a low-frequency field and cooler the higher the tile), its
//! moisture from a second fBm (wetter next to the sea), and the biome both give by the config's
//! biome table, as on a flat map from pole to pole; sea tiles are coast next to land and ocean
//! elsewhere. Both fields are 3D fBm at the tile center's direction, so the climate has no seam
//! and no pinch at the poles. A pure function of the config and the tile.

use rayon::prelude::*;

use super::project::Dir;
use super::{GlobeGrid, GlobeTile};
use crate::climate::{Climate, TEMPERATURE_SHIFT, TileSample, biome_by_table, stretch};
use crate::config::MapConfig;
use crate::heights::fbm::{LANES, SolidFbm};
use crate::kind::Thresholds;
use crate::vocab::{Biome, TileKind};

/// The climate's fields: the moisture fBm, read far away and zoomed out for the temperature
/// field (as a flat map reads its moisture fBm).
#[derive(Debug, Clone)]
struct GlobeClimate {
    moisture: SolidFbm,
    zoom: f64,
}

impl GlobeClimate {
    /// The fields of a config with a climate; `None` without one.
    fn new(config: &MapConfig) -> Option<Self> {
        let c = &config.climate;
        c.enabled.then(|| Self {
            moisture: SolidFbm::new(config.seed.wrapping_add(c.moisture_seed), &c.moisture, 4.0 / c.moisture.scale),
            zoom: c.moisture.scale / c.temperature_scale,
        })
    }
}

/// The latitude of a unit direction, in `[-1, 1]` (1 the north pole, 0 the equator).
pub(super) fn latitude(dir: Dir) -> f64 {
    dir[1].clamp(-1.0, 1.0).asin() / std::f64::consts::FRAC_PI_2
}

/// What the climate reads of a globe: its config, thresholds, grid, each tile's center height
/// and kind by id, and its radius in hex radii.
pub(super) struct Ground<'a> {
    pub(super) config: &'a MapConfig,
    pub(super) thresholds: &'a Thresholds,
    pub(super) grid: &'a GlobeGrid,
    pub(super) heights: &'a [f32],
    pub(super) kinds: &'a [TileKind],
    pub(super) radius: f64,
}

impl Ground<'_> {
    /// Every tile's climate (`None` without a climate) and biome, by id.
    pub(super) fn climates(&self) -> (Vec<Option<Climate>>, Vec<Biome>) {
        let fields = GlobeClimate::new(self.config);
        let fields = fields.as_ref();
        let tiles: Vec<GlobeTile> = self.grid.tiles().collect();
        tiles
            .par_chunks(LANES)
            .flat_map_iter(|batch| {
                let samples: Vec<(TileSample, Dir)> = batch
                    .iter()
                    .map(|&t| (self.sample(t), self.grid.center(t).expect("a tile of the globe")))
                    .collect();
                let climates = fields.map(|fields| self.batch_climate(fields, &samples));
                samples
                    .into_iter()
                    .enumerate()
                    .map(move |(k, (s, _))| {
                        let climate = climates.as_ref().map(|c| c[k]);
                        let biome = match (climate, s.kind) {
                            (Some(_), TileKind::Sea) if s.next_to_land => Biome::Coast,
                            (Some(climate), TileKind::Land | TileKind::Mountain) => {
                                biome_by_table(&self.config.climate, self.thresholds, &s, climate)
                            }
                            _ => Biome::of_kind(s.kind),
                        };
                        (climate, biome)
                    })
                    .collect::<Vec<_>>()
            })
            .unzip()
    }

    /// A tile's center height and kind and whether a neighbor is sea or land.
    pub(super) fn sample(&self, tile: GlobeTile) -> TileSample {
        let kind = |t: GlobeTile| self.kinds[t.0 as usize];
        let neighbors = self.grid.neighbors(tile).expect("a tile of the globe");
        TileSample::new(self.heights[tile.0 as usize], kind(tile), neighbors.as_slice().iter().map(|&n| Some(kind(n))))
    }

    /// Up to `LANES` tiles' climates from their samples and center directions.
    fn batch_climate(&self, fields: &GlobeClimate, samples: &[(TileSample, Dir)]) -> Vec<Climate> {
        let c = &self.config.climate;
        let mut wet_at = [[0.0; 3]; LANES];
        let mut warm_at = [[0.0; 3]; LANES];
        for ((wet, warm), (_, dir)) in wet_at.iter_mut().zip(&mut warm_at).zip(samples.iter().cycle()) {
            *wet = dir.map(|x| x * self.radius);
            let k = fields.zoom;
            *warm = [wet[0] * k + TEMPERATURE_SHIFT, wet[1] * k - TEMPERATURE_SHIFT, wet[2] * k + TEMPERATURE_SHIFT];
        }
        let (mut wet, mut warm) = ([0.0; LANES], [0.0; LANES]);
        fields.moisture.sample_batch(&wet_at, &mut wet);
        fields.moisture.sample_batch(&warm_at, &mut warm);
        let sea = self.thresholds.sea;
        samples
            .iter()
            .zip(wet.iter().zip(&warm))
            .map(|((s, dir), (&wet, &field))| {
                let base = 1.0 - latitude(*dir).abs() as f32 + c.temperature_jitter * (2.0 * field as f32 - 1.0);
                let above = ((s.raw - sea) / (1.0 - sea).max(f32::EPSILON)).max(0.0);
                let mut moisture = stretch(wet, 2.4);
                if s.next_to_sea {
                    moisture = (moisture + c.coast_moisture).min(1.0);
                }
                Climate { temperature: (base - c.lapse_rate * above).clamp(0.0, 1.0), moisture }
            })
            .collect()
    }
}
