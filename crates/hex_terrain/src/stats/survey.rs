//! What a map type's maps keep over many seeds, judged as a Civilization player judges a map
//! (ranges, poles, lakes, rivers, shapes, deserts): [`SurveyTarget`], the figures
//! [`MapStats`] measures with their bounds, and [`SurveyTarget::judge`], which `hexterrain
//! survey` prints.
//!
//! A target bounds a figure's median over the seeds and its tail (the 95th percentile on the
//! bad side: the 5th for a lower bound), and for a few figures every seed. The sources of the
//! bounds are on [`survey_targets`].

use crate::config::{MapType, RIVER_MIN_LANDMASS};

use super::MapStats;

/// A figure of a map the survey bounds, read from its [`MapStats`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum SurveyFigure {
    /// The most mountains in a row along a hex axis ([`MapStats::straight_ridge`]).
    StraightRidge,
    /// Mountains with 5 or 6 mountain neighbors, of the mountains ([`MapStats::blob_share`]).
    BlobShare,
    /// Snow, tundra and snow peaks, of the land ([`MapStats::cold_share`]).
    ColdShare,
    /// Land in the first and last tenth of the rows, of the land
    /// ([`MapStats::polar_land_share`]).
    PolarLandShare,
    /// Lake tiles, of the land ([`MapStats::lake_share`]).
    LakeShare,
    /// Lakes per 1,000 land tiles ([`MapStats::lakes_per_thousand`]).
    LakesPerThousand,
    /// Land on a river ([`MapStats::river_share`]).
    RiverShare,
    /// Landmasses of [`RIVER_MIN_LANDMASS`] tiles or more without a river
    /// ([`MapStats::landmasses_without_river`]).
    LandmassesWithoutRiver,
    /// The median river's length from its source to its mouth, in edges on edges and tiles
    /// through tile centers ([`RiverStats::median`](super::RiverStats::median)).
    RiverLength,
    /// The longest river, in edges or tiles ([`RiverStats::longest`](super::RiverStats::longest)).
    LongestRiver,
    /// Sources within 2 tiles of hills or mountains, of the sources
    /// ([`MapStats::sources_near_relief_share`]).
    SourcesNearRelief,
    /// Rivers ending at the map's edge ([`RiverStats::mouths_at_edge`](super::RiverStats::mouths_at_edge)).
    MouthsAtEdge,
    /// The rows the continent spanning the fewest spans, of the map's rows (0 without one).
    ContinentHeight,
    /// The columns the largest landmass spans, of the map's columns.
    LargestLandmassWidth,
    /// Pairs of continents whose centers lie in line, of the pairs
    /// ([`MapStats::continents_in_line`]): continents on a grid are mostly in line.
    ContinentsInLine,
    /// The third largest landmass' tiles (0 with fewer than three).
    ThirdLandmassTiles,
    /// Landmasses of 1 to 3 tiles, of the landmasses.
    TinyLandmassShare,
    /// How much more often a desert lies in a mountain's rain shadow than land in general does
    /// ([`RainShadow::ratio`](super::RainShadow::ratio); 0 without winds).
    RainShadow,
}

impl SurveyFigure {
    /// The figure's name, as the survey prints it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::StraightRidge => "straightest ridge (mountains in a row)",
            Self::BlobShare => "mountains in blobs",
            Self::ColdShare => "snow, tundra, snow peaks of the land",
            Self::PolarLandShare => "polar rows' land",
            Self::LakeShare => "lake tiles of the land",
            Self::LakesPerThousand => "lakes per 1,000 land tiles",
            Self::RiverShare => "land on a river",
            Self::LandmassesWithoutRiver => "landmasses of 20+ tiles without a river",
            Self::RiverLength => "river length, median of the map",
            Self::LongestRiver => "longest river",
            Self::SourcesNearRelief => "sources near hills or mountains",
            Self::MouthsAtEdge => "rivers ending at the map's edge",
            Self::ContinentHeight => "least continent's height of the rows",
            Self::LargestLandmassWidth => "largest landmass' width of the columns",
            Self::ContinentsInLine => "continents in line, of their pairs",
            Self::ThirdLandmassTiles => "third largest landmass (tiles)",
            Self::TinyLandmassShare => "landmasses of 1-3 tiles",
            Self::RainShadow => "deserts in rain shadow (x land's rate)",
        }
    }

    /// Whether it is a share (printed in percent).
    #[must_use]
    pub fn is_share(self) -> bool {
        matches!(
            self,
            Self::BlobShare
                | Self::ColdShare
                | Self::PolarLandShare
                | Self::LakeShare
                | Self::RiverShare
                | Self::SourcesNearRelief
                | Self::ContinentHeight
                | Self::LargestLandmassWidth
                | Self::TinyLandmassShare
                | Self::ContinentsInLine
        )
    }

    /// The figure of one map (its statistics, and its size in columns and rows).
    #[must_use]
    pub fn of(self, stats: &MapStats, (columns, rows): (u32, u32)) -> f64 {
        let r = &stats.rivers;
        match self {
            Self::StraightRidge => f64::from(stats.straight_ridge),
            Self::BlobShare => stats.blob_share(),
            Self::ColdShare => stats.cold_share(),
            Self::PolarLandShare => stats.polar_land_share(),
            Self::LakeShare => stats.lake_share(),
            Self::LakesPerThousand => stats.lakes_per_thousand(),
            Self::RiverShare => stats.river_share(),
            Self::LandmassesWithoutRiver => stats.landmasses_without_river(RIVER_MIN_LANDMASS) as f64,
            Self::RiverLength => f64::from(r.median),
            Self::LongestRiver => f64::from(r.longest),
            Self::SourcesNearRelief => stats.sources_near_relief_share(),
            Self::MouthsAtEdge => f64::from(r.mouths_at_edge),
            Self::ContinentHeight => {
                stats.continents().map(|c| f64::from(c.rows) / f64::from(rows.max(1))).reduce(f64::min).unwrap_or(0.0)
            }
            Self::LargestLandmassWidth => {
                stats.landmasses.first().map_or(0.0, |l| f64::from(l.columns) / f64::from(columns.max(1)))
            }
            Self::ContinentsInLine => stats.continents_in_line(),
            Self::ThirdLandmassTiles => stats.landmasses.get(2).map_or(0.0, |l| f64::from(l.tiles)),
            Self::TinyLandmassShare => {
                let tiny = stats.landmasses.iter().filter(|l| l.tiles <= 3).count();
                tiny as f64 / stats.landmasses.len().max(1) as f64
            }
            Self::RainShadow => stats.rain_shadow.map_or(0.0, |s| s.ratio()),
        }
    }
}

/// A bound on a figure over many seeds: its median and its tail (the 95th percentile on the
/// bad side) within `median` and `tail`, and every seed within `every` when given; `at_most`
/// says which side is bad.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct SurveyTarget {
    /// The figure bounded.
    pub figure: SurveyFigure,
    /// An upper bound (`true`) or a lower one.
    pub at_most: bool,
    /// The bound of the median.
    pub median: f64,
    /// The bound of the 95th percentile on the bad side.
    pub tail: f64,
    /// The bound every seed keeps, when there is one.
    pub every: Option<f64>,
}

/// One target judged over the seeds ([`SurveyTarget::judge`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SurveyVerdict {
    /// The median over the seeds.
    pub median: f64,
    /// The 95th percentile on the bad side.
    pub tail: f64,
    /// The worst seed and its figure.
    pub worst: (u32, f64),
    /// Whether the median, the tail and every seed keep their bounds.
    pub met: bool,
    /// The seeds whose own figure lies past the tail's bound (past `every`'s when given), in
    /// the order given.
    pub missed: Vec<u32>,
}

impl SurveyTarget {
    const fn new(figure: SurveyFigure, at_most: bool, median: f64, tail: f64, every: Option<f64>) -> Self {
        Self { figure, at_most, median, tail, every }
    }

    /// Whether `value` lies within `bound` on this target's side.
    fn within(&self, value: f64, bound: f64) -> bool {
        if self.at_most { value <= bound } else { value >= bound }
    }

    /// Judges the figure over seeds: `values` are each seed with its figure (at least one).
    #[must_use]
    pub fn judge(&self, values: &[(u32, f64)]) -> SurveyVerdict {
        let mut sorted: Vec<f64> = values.iter().map(|v| v.1).collect();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = sorted[(n - 1) / 2];
        // The 95th percentile on the bad side, by the nearest rank.
        let rank = ((0.95 * n as f64).ceil() as usize).clamp(1, n);
        let tail = if self.at_most { sorted[rank - 1] } else { sorted[n - rank] };
        let worse = |a: f64, b: f64| if self.at_most { a > b } else { a < b };
        let worst = values.iter().copied().fold(values[0], |w, v| if worse(v.1, w.1) { v } else { w });
        let limit = self.every.unwrap_or(self.tail);
        let missed = values.iter().filter(|v| !self.within(v.1, limit)).map(|v| v.0).collect();
        let met = self.within(median, self.median)
            && self.within(tail, self.tail)
            && self.every.is_none_or(|e| self.within(worst.1, e));
        SurveyVerdict { median, tail, worst, met, missed }
    }
}

/// The survey's targets of a map type (at normal water and temperature, on the presets' size),
/// with rivers on tile edges (`on_edges`, lengths in edges) or through tile centers (in tiles):
///
/// | figure | median | 95th percentile | every seed | types |
/// |---|---|---|---|---|
/// | straightest ridge | | at most 6 | at most 8 | all |
/// | mountains in blobs | at most 5 % | at most 5 % | | all |
/// | snow, tundra and snow peaks | at most 12 % of the land | at most 18 % | | all |
/// | polar rows' land | at most 3 % of the land | at most 3 % | | all but Inland Sea |
/// | lake tiles | at most 2.5 % of the land | at most 2.5 % | | all |
/// | lakes | at most 6 per 1,000 land tiles | at most 6 | | all |
/// | land on a river | at least 15 % | | | all |
/// | landmasses of 20 tiles or more without a river | | | 0 | all |
/// | river length, the map's median | at least 6 edges (4 tiles) | at least 6 (4) | | all |
/// | longest river | at least 18 edges (12 tiles) | at least 18 (12) | | Pangaea, Continents, Small Continents, Inland Sea |
/// | sources near hills or mountains | at least 70 % | at least 70 % | | all |
/// | rivers ending at the map's edge | | | 0 | all |
/// | least continent's height | at least 55 % of the rows | at least 55 % | | Continents |
/// | largest landmass' width | at least 70 % of the columns | at least 70 % | | Pangaea |
/// | continents in line (pairs of continents whose centers share a row or a column) | at most 25 % | at most 40 % | | Small Continents |
/// | third largest landmass | at least 30 tiles | at least 30 | | Archipelago |
/// | landmasses of 1-3 tiles | at most 50 % | at most 50 % | | Archipelago |
/// | deserts in rain shadow | at least 1.5 times land's rate | | | all but Inland Sea, with winds |
///
/// The sources: Civilization V keeps its polar rows sea or ice (`FractalWorld.lua`), gives every
/// landmass a river edge for every 12 of its tiles and one more (`MapGenerator.lua`,
/// `AddRivers`), starts rivers on hills and mountains away from the coast, places few lakes
/// (`AddLakes`), breaks its ridge lines with gaps; snow and tundra keep to high latitudes
/// (`TerrainGenerator.lua`), deserts lie in the subtropics and in the lee of mountains (the
/// `PerfectWorld3` script's winds). The numbers are ours, from renders of many seeds beside
/// Civilization V's maps. Inland Sea, a temperate region, keeps land in its first and last rows;
/// its air crosses land all round the world but for its sea, so its deserts lie where the air
/// has come farthest from the sea, behind a range or not (measured: 1.1 to 1.3 times land's
/// rate), and the rain shadow is not its target.
#[must_use]
pub fn survey_targets(kind: MapType, on_edges: bool, winds: bool) -> Vec<SurveyTarget> {
    use SurveyFigure::*;
    let length = if on_edges { 6.0 } else { 4.0 };
    let longest = if on_edges { 18.0 } else { 12.0 };
    let mut targets = vec![
        SurveyTarget::new(StraightRidge, true, f64::INFINITY, 6.0, Some(8.0)),
        SurveyTarget::new(BlobShare, true, 0.05, 0.05, None),
        SurveyTarget::new(ColdShare, true, 0.12, 0.18, None),
    ];
    if kind != MapType::InlandSea {
        targets.push(SurveyTarget::new(PolarLandShare, true, 0.03, 0.03, None));
    }
    targets.extend([
        SurveyTarget::new(LakeShare, true, 0.025, 0.025, None),
        SurveyTarget::new(LakesPerThousand, true, 6.0, 6.0, None),
        SurveyTarget::new(RiverShare, false, 0.15, 0.0, None),
        SurveyTarget::new(LandmassesWithoutRiver, true, 0.0, 0.0, Some(0.0)),
        SurveyTarget::new(RiverLength, false, length, length, None),
    ]);
    if matches!(kind, MapType::Pangaea | MapType::Continents | MapType::SmallContinents | MapType::InlandSea) {
        targets.push(SurveyTarget::new(LongestRiver, false, longest, longest, None));
    }
    targets.extend([
        SurveyTarget::new(SourcesNearRelief, false, 0.7, 0.7, None),
        SurveyTarget::new(MouthsAtEdge, true, 0.0, 0.0, Some(0.0)),
    ]);
    match kind {
        MapType::Continents => targets.push(SurveyTarget::new(ContinentHeight, false, 0.55, 0.55, None)),
        MapType::Pangaea => targets.push(SurveyTarget::new(LargestLandmassWidth, false, 0.7, 0.7, None)),
        MapType::SmallContinents => targets.push(SurveyTarget::new(ContinentsInLine, true, 0.25, 0.4, None)),
        MapType::Archipelago => targets.extend([
            SurveyTarget::new(ThirdLandmassTiles, false, 30.0, 30.0, None),
            SurveyTarget::new(TinyLandmassShare, true, 0.5, 0.5, None),
        ]),
        _ => {}
    }
    if winds && kind != MapType::InlandSea {
        targets.push(SurveyTarget::new(RainShadow, false, 1.5, 0.0, None));
    }
    targets
}
