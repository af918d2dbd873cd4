//! Game setup, a stage after the terrain: the players' start positions, resources and natural
//! wonders, and a fairness report, from the map's [`SetupConfig`], computed once for the whole
//! map (or the `area` of an unbounded one; a whole globe, [`GlobeSetup`]) when the map is
//! compiled, so every chunk and every query reads the same placement whatever the chunk order
//! or thread count.
//!
//! In the order data flows through it:
//!
//! | module | step |
//! | --- | --- |
//! | [`survey`] | every tile's type, biome, river, coast, yields, movement cost, neighbors |
//! | `board` | where the tiles lie: steps between them, the tiles within a radius (flat or globe) |
//! | `regions` | regions of equal fertility, one a player (Civilization V's and Unciv's division) |
//! | `starts` | the best start of each region at the minimum distance, then moves that narrow the spread |
//! | `paths` | path costs over land, the land each start reaches first, land masses |
//! | `placement` | wonders (rarest first), resources (guaranteed ones, then by density), normalisation of weak starts |
//! | [`report`] | the fairness report |
//!
//! The terrain is not changed: what the setup places lies on the tiles the generator made, so
//! every invariant of the terrain holds with a setup as without.

use std::time::{Duration, Instant};

use hexx::Hex;

use crate::chunk::TileRect;
use crate::config::{Place, ResourceClass, SetupConfig};
use crate::error::ConfigError;
use crate::geometry::Geometry;

mod board;
mod globe;
mod paths;
mod placement;
mod regions;
pub mod report;
mod starts;
pub mod survey;

pub use globe::{GlobeRegion, GlobeSetup};
pub use placement::{SetupNote, Shortfall};
pub use report::{SetupReport, StartReport};
pub use starts::MAX_START_SEARCH_CHECKS;
pub use survey::Stages;

use board::Board;
use regions::Division;
use survey::{NONE, Survey};

/// A resource on the map (`T`: a flat map's [`Hex`], a globe's
/// [`GlobeTile`](crate::GlobeTile)).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct PlacedResource<T = Hex> {
    /// Its tile (map-local axial on a flat map).
    pub tile: T,
    /// Its rule's index in `setup.resources`.
    pub rule: u32,
    /// Its rule's name.
    pub name: String,
    /// Bonus, strategic or luxury.
    pub class: ResourceClass,
    /// Whether normalisation added it near a weak start.
    pub added: bool,
}

/// A natural wonder on the map (`T`: a flat map's [`Hex`], a globe's
/// [`GlobeTile`](crate::GlobeTile)).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct PlacedWonder<T = Hex> {
    /// Its tile (map-local axial on a flat map).
    pub tile: T,
    /// Its rule's index in `setup.wonders.list`.
    pub rule: u32,
    /// Its name.
    pub name: String,
}

/// A region of equal fertility: a rectangle of offset coordinates (on a wrapping map its
/// columns may run across the seam: `columns[1]` is then past the map's width, and columns are
/// taken modulo the width).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct SetupRegion {
    /// First column and one past the last.
    pub columns: [i32; 2],
    /// First row and one past the last.
    pub rows: [i32; 2],
    /// Its tiles' fertility (their value, open ocean not counted).
    pub fertility: f32,
}

/// What the setup placed on one tile (`T`: a flat map's [`Hex`], a globe's
/// [`GlobeTile`](crate::GlobeTile)).
#[derive(Debug, PartialEq)]
pub struct TileSetup<'a, T = Hex> {
    /// The player starting here.
    pub start: Option<u32>,
    /// The resource on it.
    pub resource: Option<&'a PlacedResource<T>>,
    /// The natural wonder on it.
    pub wonder: Option<&'a PlacedWonder<T>>,
    /// Its region.
    pub region: u32,
}

impl<T> Clone for TileSetup<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for TileSetup<'_, T> {}

/// How long each part of the setup took.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SetupTimings {
    /// Reading every tile.
    pub survey: Duration,
    /// Ring values and regions.
    pub regions: Duration,
    /// Choosing and refining the starts.
    pub starts: Duration,
    /// Wonders and resources.
    pub placement: Duration,
    /// Normalising weak starts.
    pub normalize: Duration,
    /// The report (path costs between starts, land masses).
    pub report: Duration,
}

impl SetupTimings {
    /// The whole setup.
    #[must_use]
    pub fn total(&self) -> Duration {
        self.survey + self.regions + self.starts + self.placement + self.normalize + self.report
    }
}

/// The setup of a game on a map (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    rect: TileRect,
    regions: Vec<SetupRegion>,
    placed: Placed<Hex>,
}

/// What a setup placed, by the survey's tile order: the part a flat map's and a globe's setup
/// share.
#[derive(Debug, Clone, PartialEq)]
struct Placed<T> {
    starts: Vec<T>,
    region_of: Vec<u32>,
    resources: Vec<PlacedResource<T>>,
    wonders: Vec<PlacedWonder<T>>,
    resource_at: Vec<u32>,
    wonder_at: Vec<u32>,
    start_at: Vec<u32>,
    report: SetupReport<T>,
}

impl<T> Placed<T> {
    /// What lies on tile `i` of the survey.
    fn at(&self, i: usize) -> TileSetup<'_, T> {
        let get = |at: &[u32]| (at[i] != NONE).then_some(at[i] as usize);
        TileSetup {
            start: get(&self.start_at).map(|p| p as u32),
            resource: get(&self.resource_at).map(|k| &self.resources[k]),
            wonder: get(&self.wonder_at).map(|k| &self.wonders[k]),
            region: self.region_of[i],
        }
    }
}

impl Setup {
    /// Places the setup on the terrain's `stages`, drawing with `seed` (the map's).
    ///
    /// # Errors
    /// `setup.players` or `setup.min_distance` when the starts do not fit, `setup.area` when an
    /// unbounded map has none.
    pub fn build(stages: Stages, config: &SetupConfig, seed: u32) -> Result<Self, ConfigError> {
        Self::build_timed(stages, config, seed).map(|(setup, _)| setup)
    }

    /// As [`Setup::build`], with the time each part took.
    ///
    /// # Errors
    /// As [`Setup::build`].
    pub fn build_timed(stages: Stages, config: &SetupConfig, seed: u32) -> Result<(Self, SetupTimings), ConfigError> {
        let geometry = stages.geometry;
        let mut timings = SetupTimings::default();
        let clock = Instant::now();
        let rect = config.area.or(geometry.bounds()).ok_or_else(|| {
            ConfigError::new("setup.area", "None".into(), "a rectangle of tiles on an unbounded map".into())
        })?;
        check_places(stages.ruleset, config)?;
        let survey = Survey::new(stages, config, rect);
        let Board::Flat(flat) = &survey.board else { unreachable!("a flat map's survey") };
        let (cols, wraps) = (flat.cols, flat.wraps);
        let divide = |fertility: &[f32]| regions::divide(cols, wraps, fertility, config.players as usize);
        let tile = |i: usize| match &survey.board {
            Board::Flat(flat) => flat.tiles[i],
            Board::Globe(_) => unreachable!("a flat map's survey"),
        };
        let (placed, division) = place(&survey, config, seed, tile, divide, clock, &mut timings)?;
        let cols = cols as i32;
        let regions = division
            .regions
            .iter()
            .map(|r| {
                let first = rect.min[0] + ((r.cols[0] + division.cut) as i32 % cols.max(1));
                SetupRegion {
                    columns: [first, first + (r.cols[1] - r.cols[0]) as i32],
                    rows: [rect.min[1] + r.rows[0] as i32, rect.min[1] + r.rows[1] as i32],
                    fertility: r.fertility,
                }
            })
            .collect();
        Ok((Self { rect, regions, placed }, timings))
    }

    /// Index of a tile of the area (any copy of it on a wrapping map).
    #[inline]
    fn index(&self, geometry: &Geometry, tile: Hex) -> Option<usize> {
        board::area_index(self.rect, geometry, tile)
    }

    /// The tiles the setup placed on.
    #[must_use]
    pub fn area(&self) -> TileRect {
        self.rect
    }

    /// The start tiles, in player order.
    #[must_use]
    pub fn starts(&self) -> &[Hex] {
        &self.placed.starts
    }

    /// The regions, in order (region `k` is where player `k` was first placed).
    #[must_use]
    pub fn regions(&self) -> &[SetupRegion] {
        &self.regions
    }

    /// Every resource, in tile order (row by row).
    #[must_use]
    pub fn resources(&self) -> &[PlacedResource] {
        &self.placed.resources
    }

    /// Every natural wonder, in tile order.
    #[must_use]
    pub fn wonders(&self) -> &[PlacedWonder] {
        &self.placed.wonders
    }

    /// The fairness report.
    #[must_use]
    pub fn report(&self) -> &SetupReport {
        &self.placed.report
    }

    /// What lies on a tile (any copy of it on a wrapping map); `None` outside the area.
    #[must_use]
    pub fn at(&self, geometry: &Geometry, tile: Hex) -> Option<TileSetup<'_>> {
        Some(self.placed.at(self.index(geometry, tile)?))
    }

    /// The resource on a tile.
    #[must_use]
    pub fn resource(&self, geometry: &Geometry, tile: Hex) -> Option<&PlacedResource> {
        self.at(geometry, tile)?.resource
    }

    /// The natural wonder on a tile.
    #[must_use]
    pub fn wonder(&self, geometry: &Geometry, tile: Hex) -> Option<&PlacedWonder> {
        self.at(geometry, tile)?.wonder
    }

    /// The player starting on a tile.
    #[must_use]
    pub fn start(&self, geometry: &Geometry, tile: Hex) -> Option<u32> {
        self.at(geometry, tile)?.start
    }

    /// The region of a tile.
    #[must_use]
    pub fn region(&self, geometry: &Geometry, tile: Hex) -> Option<u32> {
        self.at(geometry, tile).map(|t| t.region)
    }
}

/// The setup's steps after the survey, the same on a flat map and a globe: ring values, the
/// regions (`divide` cuts them by each tile's fertility), the starts, wonders and resources,
/// normalisation and the report, each tile named by `tile`. Laps into `timings` from `clock`
/// (the survey's start).
fn place<T: Copy>(
    survey: &Survey,
    config: &SetupConfig,
    seed: u32,
    tile: impl Fn(usize) -> T,
    divide: impl FnOnce(&[f32]) -> Division,
    mut clock: Instant,
    timings: &mut SetupTimings,
) -> Result<(Placed<T>, Division), ConfigError> {
    let mut lap = |slot: &mut Duration| {
        let now = Instant::now();
        *slot = now - clock;
        clock = now;
    };
    lap(&mut timings.survey);
    let weights = config.value;
    let value: Vec<f32> = survey.yields.iter().map(|&y| weights.of(y)).collect();
    let mut ring = Vec::new();
    let scores: Vec<f32> = (0..survey.len())
        .map(|i| {
            survey.range(i, config.rings, &mut ring);
            ring.iter().map(|&j| value[j as usize]).sum()
        })
        .collect();
    let fertility: Vec<f32> = (0..survey.len())
        .map(|i| if survey.biomes[i] == crate::vocab::Biome::Ocean { 0.0 } else { value[i] })
        .collect();
    let division = divide(&fertility);
    lap(&mut timings.regions);

    let guaranteed: Vec<&crate::config::ResourceRule> =
        config.resources.iter().filter(|r| r.per_player > 0).take(64).collect();
    // Which guaranteed rules each tile may hold, one bit a rule (at most 64 rules).
    let fits: Vec<u64> = (0..survey.len())
        .map(|i| {
            guaranteed
                .iter()
                .enumerate()
                .fold(0, |m, (k, r)| if placement::allowed(survey, i, &r.on) { m | 1 << k } else { m })
        })
        .collect();
    let missing: Vec<u32> = (0..survey.len())
        .map(|i| {
            if !survey.eligible[i] || guaranteed.is_empty() {
                return 0;
            }
            survey.range(i, config.rings, &mut ring);
            ring.retain(|&j| j as usize != i && fits[j as usize] != 0);
            unmet(&ring, &fits, &guaranteed)
        })
        .collect();
    let chooser = starts::Chooser { survey, config, scores: &scores, division: &division, missing: &missing };
    let mut starts = chooser.place()?;
    chooser.refine(&mut starts);
    lap(&mut timings.starts);

    let rings: Vec<Vec<u32>> = starts
        .iter()
        .map(|&s| {
            let mut r = Vec::new();
            survey.range(s, config.rings, &mut r);
            r
        })
        .collect();
    let reach = paths::reach(survey, &starts);
    let extra: Vec<f32> = reach.iter().map(|&r| weights.reach * r as f32).collect();
    let placer = placement::Placer { survey, config, seed, starts: &starts, rings: &rings };
    let mut placed = placer.place();
    lap(&mut timings.placement);
    if config.normalize {
        placer.normalize(&mut placed, &extra);
    }
    lap(&mut timings.normalize);

    let values = placer.values(&placed, &extra);
    let (mass, sizes) = paths::land_masses(survey);
    let costs: Vec<Vec<Option<u32>>> = starts
        .iter()
        .map(|&s| {
            let c = paths::costs(survey, &[s]);
            starts.iter().map(|&t| (c.dist[t] != paths::FAR).then_some(c.dist[t])).collect()
        })
        .collect();
    let n = starts.len();
    let mut reports = Vec::with_capacity(n);
    for (p, &s) in starts.iter().enumerate() {
        let mut yields = crate::config::Yields::default();
        for &j in &rings[p] {
            yields += placer.yields(&placed, j as usize);
        }
        let near = |j: &&u32| placed.resource[**j as usize] != NONE;
        let nearest_rival =
            (0..n).filter(|&q| q != p).filter_map(|q| costs[p][q].map(|c| (q as u32, c))).min_by_key(|&(q, c)| (c, q));
        reports.push(StartReport {
            player: p as u32,
            tile: tile(s),
            coords: survey.board.coords(s),
            region: division.region_of[s],
            value: values[p],
            yields,
            resources: rings[p].iter().filter(near).count() as u32,
            added: rings[p].iter().filter(near).filter(|&&j| placed.added[j as usize]).count() as u32,
            reach: reach[p],
            land_area: if mass[s] == NONE { 0 } else { sizes[mass[s] as usize] },
            nearest_rival,
        });
    }
    let unreachable = (0..n)
        .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
        .filter(|&(a, b)| costs[a][b].is_none())
        .map(|(a, b)| (a as u32, b as u32))
        .collect();
    let spread = starts::spread(&values);

    let mut resources = Vec::new();
    let mut resource_at = vec![NONE; survey.len()];
    let mut wonders = Vec::new();
    let mut wonder_at = vec![NONE; survey.len()];
    for i in 0..survey.len() {
        if placed.resource[i] != NONE {
            let rule = placed.resource[i];
            let r = &config.resources[rule as usize];
            resource_at[i] = resources.len() as u32;
            resources.push(PlacedResource {
                tile: tile(i),
                rule,
                name: r.name.clone(),
                class: r.class,
                added: placed.added[i],
            });
        }
        if placed.wonder[i] != NONE {
            let rule = placed.wonder[i];
            wonder_at[i] = wonders.len() as u32;
            wonders.push(PlacedWonder { tile: tile(i), rule, name: config.wonders.list[rule as usize].name.clone() });
        }
    }
    let mut start_at = vec![NONE; survey.len()];
    for (p, &s) in starts.iter().enumerate() {
        start_at[s] = p as u32;
    }
    let report = SetupReport {
        starts: reports,
        spread,
        bound: config.fairness,
        within_bound: spread <= config.fairness,
        costs,
        unreachable,
        shortfalls: placed.shortfalls,
        notes: placed.notes,
        resources: resources.len() as u32,
        wonders: wonders.len() as u32,
    };
    let placed = Placed {
        starts: starts.iter().map(|&s| tile(s)).collect(),
        region_of: division.region_of.clone(),
        resources,
        wonders,
        resource_at,
        wonder_at,
        start_at,
        report,
    };
    lap(&mut timings.report);
    Ok((placed, division))
}

/// How many of the guaranteed resources could not be given tiles of `ring`, one a tile: the
/// rules with the fewest tiles they may lie on choose first, each the tiles fewest other rules
/// want (a greedy matching, exact for the few rules a table guarantees in all but rare cases).
/// `fits[j]` has bit `k` set when tile `j` may hold `rules[k]`.
fn unmet(ring: &[u32], fits: &[u64], rules: &[&crate::config::ResourceRule]) -> u32 {
    let mask = |x: usize| fits[ring[x] as usize];
    let mut order: Vec<usize> = (0..rules.len()).collect();
    order.sort_by_key(|&k| ((0..ring.len()).filter(|&x| mask(x) >> k & 1 == 1).count(), k));
    let mut used = vec![false; ring.len()];
    let mut unmet = 0;
    let mut options = Vec::new();
    for k in order {
        options.clear();
        options.extend((0..ring.len()).filter(|&x| !used[x] && mask(x) >> k & 1 == 1));
        options.sort_by_key(|&x| (mask(x).count_ones(), x));
        let take = options.len().min(rules[k].per_player as usize);
        for &x in &options[..take] {
            used[x] = true;
        }
        unmet += rules[k].per_player - take as u32;
    }
    unmet
}

/// Every terrain and feature a resource or a wonder names is one of the map's ruleset.
fn check_places(ruleset: &crate::ruleset::TerrainRuleset, config: &SetupConfig) -> Result<(), ConfigError> {
    let resources = config.resources.iter().enumerate().map(|(i, r)| (format!("setup.resources[{i}]"), &r.on));
    let wonders = config.wonders.list.iter().enumerate().map(|(i, w)| (format!("setup.wonders.list[{i}]"), &w.on));
    for (field, on) in resources.chain(wonders) {
        for (j, place) in on.iter().enumerate() {
            let (known, id, what, ids): (bool, &String, &str, Vec<&str>) = match place {
                Place::Terrain(id) => (
                    ruleset.terrain_id(id).is_some(),
                    id,
                    "terrain",
                    ruleset.terrains.iter().map(|t| t.id.as_str()).collect(),
                ),
                Place::Feature(id) => (
                    ruleset.feature_id(id).is_some(),
                    id,
                    "feature",
                    ruleset.features.iter().map(|f| f.id.as_str()).collect(),
                ),
                Place::Biome(_) | Place::Kind(_) => continue,
            };
            if !known {
                return Err(ConfigError::new(
                    &format!("{field}.on[{j}]"),
                    format!("{id:?}"),
                    format!("a {what} of the map's ruleset {:?}: {}", ruleset.name, ids.join(", ")),
                ));
            }
        }
    }
    Ok(())
}
