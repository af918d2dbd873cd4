//! Start positions: in each region of equal fertility the best tile a start may stand on (the
//! value of the tiles within its rings, a little less the farther it is from the region's
//! fertile middle, so neighbors do not crowd a shared border) that keeps its distance from the
//! starts already chosen (when regions leave gaps, the starts spread as far apart as they go, and
//! when that is not far enough, an exact search within [`MAX_START_SEARCH_CHECKS`]); then moves that narrow the spread of the starts' values, each kept
//! only if it does, a bounded number of times.

use std::collections::BTreeSet;

use super::board::Board;
use super::paths;
use super::regions::Division;
use super::survey::Survey;
use crate::config::SetupConfig;
use crate::error::ConfigError;

/// How much a start's rank falls from a region's fertile middle to its farthest corner.
const CENTER_BIAS: f32 = 0.3;
/// How much a start's rank falls for each guaranteed resource its rings have no tile for.
const MISSING_PENALTY: f32 = 0.15;

/// The most distance checks the exact search for starts makes (over all the distances it
/// tries for one setup) when the greedy spread does not fit them: about 0.15 s on one core.
/// Past it a refusal says the search stopped instead of claiming a bound.
pub const MAX_START_SEARCH_CHECKS: u64 = 1 << 22;

/// What the exact search for starts found.
enum Search {
    /// Starts, in the candidates' order.
    Found(Vec<usize>),
    /// Proven: no such starts.
    None,
    /// The budget ran out first.
    Stopped,
}

/// What choosing starts reads.
pub(crate) struct Chooser<'a> {
    pub survey: &'a Survey<'a>,
    pub config: &'a SetupConfig,
    /// Each tile's ring value (the value of the tiles within the rings), for eligible tiles.
    pub scores: &'a [f32],
    pub division: &'a Division,
    /// For each tile, how many guaranteed resources (rules with `per_player > 0`) have fewer
    /// tiles they may lie on within its rings than a player is guaranteed.
    pub missing: &'a [u32],
}

impl Chooser<'_> {
    /// Whether tile `i` is at least the minimum distance from every start but `skip`.
    fn far_enough(&self, i: usize, starts: &[usize], skip: Option<usize>) -> bool {
        starts
            .iter()
            .enumerate()
            .filter(|&(k, _)| Some(k) != skip)
            .all(|(_, &s)| self.survey.distance(s, i).is_some_and(|d| d >= self.config.min_distance))
    }

    /// The starts, one a region where the region has room, in region order.
    ///
    /// # Errors
    /// `setup.players` when the area has fewer tiles a start may stand on than players,
    /// `setup.min_distance` when the starts do not fit that far apart.
    pub fn place(&self) -> Result<Vec<usize>, ConfigError> {
        let survey = self.survey;
        let n = self.config.players as usize;
        let eligible: Vec<usize> = (0..survey.len()).filter(|&i| survey.eligible[i]).collect();
        if eligible.len() < n {
            return Err(ConfigError::new(
                "setup.players",
                n.to_string(),
                format!(
                    "at most {} on this map: the tiles a start may stand on (land, not mountain, not lake, {:?})",
                    eligible.len(),
                    self.config.start_on
                ),
            ));
        }
        let ranks = self.ranks();
        let by_region = self.by_region();
        let mut starts = Vec::with_capacity(n);
        let mut missing = 0;
        for tiles in &by_region {
            let mut order = tiles.clone();
            order.sort_by(|&a, &b| ranks[b].total_cmp(&ranks[a]).then(a.cmp(&b)));
            match order.into_iter().find(|&i| self.far_enough(i, &starts, None)) {
                Some(i) => starts.push(i),
                None => missing += 1,
            }
        }
        for _ in 0..missing {
            if let Some(i) = best(eligible.iter().copied().filter(|&i| self.far_enough(i, &starts, None)), self.scores)
            {
                starts.push(i);
            }
        }
        if starts.len() == n {
            return Ok(starts);
        }
        // Regions leave gaps: spread the starts as far apart as they go (each next start the
        // tile farthest from those chosen, the best on a tie).
        let mut spread = vec![best(eligible.iter().copied(), self.scores).unwrap_or(eligible[0])];
        let mut nearest: Vec<u32> = vec![u32::MAX; survey.len()];
        while spread.len() < n {
            let last = spread[spread.len() - 1];
            for &i in &eligible {
                let d = survey.distance(last, i).unwrap_or(0);
                nearest[i] = nearest[i].min(d);
            }
            let next = eligible.iter().copied().max_by(|&a, &b| {
                nearest[a].cmp(&nearest[b]).then(self.scores[a].total_cmp(&self.scores[b])).then(b.cmp(&a))
            });
            spread.push(next.unwrap_or(eligible[0]));
        }
        let apart = (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .map(|(a, b)| survey.distance(spread[a], spread[b]).unwrap_or(0))
            .min()
            .unwrap_or(u32::MAX);
        let min = self.config.min_distance;
        if apart >= min {
            return Ok(spread);
        }
        // The greedy spread is short: search exactly, within a bound of work.
        let mut budget = MAX_START_SEARCH_CHECKS;
        let stopped = match self.search(&eligible, n, min, &mut budget) {
            Search::Found(starts) => return Ok(starts),
            Search::None => None,
            Search::Stopped => Some(min),
        };
        // Refused: the largest distance the starts fit at, proven when the search ends.
        let mut fits = apart;
        let mut stopped = stopped;
        if stopped.is_none() {
            for d in (apart + 1..min).rev() {
                match self.search(&eligible, n, d, &mut budget) {
                    Search::Found(_) => {
                        fits = d;
                        break;
                    }
                    Search::None => {}
                    Search::Stopped => {
                        stopped = Some(d);
                        break;
                    }
                }
            }
        }
        let tiles = eligible.len();
        let allowed = match stopped {
            None => format!(
                "at most {fits} for {n} starts on this map (no {n} of its {tiles} tiles a start may stand on are {} \
                 apart), or fewer players",
                fits + 1
            ),
            Some(d) => format!(
                "a distance {n} starts fit at: {fits} fits on this map, {d} was not found within the search's bound \
                 ({MAX_START_SEARCH_CHECKS} distance checks among its {tiles} tiles a start may stand on), or fewer \
                 players"
            ),
        };
        Err(ConfigError::new("setup.min_distance", min.to_string(), allowed))
    }

    /// `n` of the `candidates` pairwise at least `d` apart: a depth-first search over them in
    /// order (each start chosen keeps only the candidates far enough from it), exact unless it
    /// spends `budget` distance checks first.
    fn search(&self, candidates: &[usize], n: usize, d: u32, budget: &mut u64) -> Search {
        let mut chosen = Vec::with_capacity(n);
        match self.extend(candidates, n, d, &mut chosen, budget) {
            Some(true) => Search::Found(chosen),
            Some(false) => Search::None,
            None => Search::Stopped,
        }
    }

    /// Adds starts from `candidates` (each at least `d` from every start in `chosen`) until
    /// there are `n`: `Some(true)` when it did, `Some(false)` when no choice can, `None` when
    /// the budget ran out.
    fn extend(
        &self,
        candidates: &[usize],
        n: usize,
        d: u32,
        chosen: &mut Vec<usize>,
        budget: &mut u64,
    ) -> Option<bool> {
        let need = n - chosen.len();
        if need == 0 {
            return Some(true);
        }
        if candidates.len() < need {
            return Some(false);
        }
        if need == 1 {
            chosen.push(candidates[0]);
            return Some(true);
        }
        for (k, &c) in candidates.iter().enumerate() {
            if candidates.len() - k < need {
                break;
            }
            let rest = &candidates[k + 1..];
            *budget = budget.checked_sub(rest.len() as u64)?;
            let next: Vec<usize> =
                rest.iter().copied().filter(|&o| self.survey.distance(c, o).is_some_and(|e| e >= d)).collect();
            chosen.push(c);
            match self.extend(&next, n, d, chosen, budget) {
                Some(false) => {
                    chosen.pop();
                }
                found_or_stopped => return found_or_stopped,
            }
        }
        Some(false)
    }

    /// The tiles a start may stand on, region by region.
    fn by_region(&self) -> Vec<Vec<usize>> {
        let mut by_region: Vec<Vec<usize>> = vec![Vec::new(); self.division.regions.len()];
        for i in (0..self.survey.len()).filter(|&i| self.survey.eligible[i]) {
            by_region[self.division.region_of[i] as usize].push(i);
        }
        by_region
    }

    /// Each eligible tile's rank: its score, less up to [`CENTER_BIAS`] of it by its distance
    /// from its region's fertility-weighted middle (on a flat map in columns and rows over the
    /// region's longer side; on a globe the angle over the region's widest angle from it).
    fn ranks(&self) -> Vec<f32> {
        let off = match &self.survey.board {
            Board::Flat(flat) => self.flat_offsets(flat.cols),
            Board::Globe(sphere) => self.globe_offsets(&sphere.centers),
        };
        (0..self.survey.len())
            .map(|i| {
                let missing = 1.0 - MISSING_PENALTY * self.missing[i] as f32;
                self.scores[i] * (1.0 - CENTER_BIAS * off[i].min(1.0) as f32) * missing.max(0.0)
            })
            .collect()
    }

    /// Each tile's distance from its region's middle over half the region's longer side.
    fn flat_offsets(&self, cols: usize) -> Vec<f64> {
        let survey = self.survey;
        let d = self.division;
        let local = |i: usize| ((i % cols + cols - d.cut) % cols, i / cols);
        let mut middle = vec![[0.0f64; 3]; d.regions.len()];
        for i in 0..survey.len() {
            let (c, r) = local(i);
            let w = f64::from(self.scores[i].max(0.0));
            let m = &mut middle[d.region_of[i] as usize];
            m[0] += w * c as f64;
            m[1] += w * r as f64;
            m[2] += w;
        }
        (0..survey.len())
            .map(|i| {
                let k = d.region_of[i] as usize;
                let region = &d.regions[k];
                let m = middle[k];
                let (c, r) = local(i);
                let (mc, mr) = if m[2] > 0.0 {
                    (m[0] / m[2], m[1] / m[2])
                } else {
                    ((region.cols[0] + region.cols[1]) as f64 / 2.0, (region.rows[0] + region.rows[1]) as f64 / 2.0)
                };
                let half =
                    ((region.cols[1] - region.cols[0]).max(region.rows[1] - region.rows[0]) as f64 / 2.0).max(1.0);
                ((c as f64 - mc).powi(2) + (r as f64 - mr).powi(2)).sqrt() / half
            })
            .collect()
    }

    /// Each tile's angle from its region's middle (the fertility-weighted mean direction, the
    /// plain mean where the region has no fertility) over the widest such angle of the region.
    fn globe_offsets(&self, centers: &[[f64; 3]]) -> Vec<f64> {
        let d = self.division;
        let mut weighted = vec![[0.0f64; 3]; d.regions.len()];
        let mut plain = vec![[0.0f64; 3]; d.regions.len()];
        for (i, c) in centers.iter().enumerate() {
            let k = d.region_of[i] as usize;
            let w = f64::from(self.scores[i].max(0.0));
            for a in 0..3 {
                weighted[k][a] += w * c[a];
                plain[k][a] += c[a];
            }
        }
        let middle: Vec<[f64; 3]> = weighted
            .iter()
            .zip(&plain)
            .map(|(w, p)| {
                let m = if w.iter().any(|&x| x != 0.0) { w } else { p };
                let len = m.iter().map(|x| x * x).sum::<f64>().sqrt();
                if len > 0.0 { m.map(|x| x / len) } else { [0.0, 1.0, 0.0] }
            })
            .collect();
        let angle = |a: [f64; 3], b: [f64; 3]| (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0).acos();
        let angles: Vec<f64> =
            centers.iter().enumerate().map(|(i, &c)| angle(c, middle[d.region_of[i] as usize])).collect();
        let mut widest = vec![0.0f64; d.regions.len()];
        for (i, &a) in angles.iter().enumerate() {
            let w = &mut widest[d.region_of[i] as usize];
            *w = w.max(a);
        }
        angles.iter().enumerate().map(|(i, &a)| a / widest[d.region_of[i] as usize].max(1e-9)).collect()
    }

    /// The starts' values from their ring scores and the land each reaches first.
    pub fn values(&self, starts: &[usize]) -> Vec<f32> {
        let reach = paths::reach(self.survey, starts);
        starts.iter().zip(reach).map(|(&s, r)| self.scores[s] + self.config.value.reach * r as f32).collect()
    }

    /// Moves starts inside their regions while that narrows the spread of their values, at
    /// most `2 * players + 8` tries.
    pub fn refine(&self, starts: &mut [usize]) {
        let n = starts.len();
        let bound = self.config.fairness;
        let mut values = self.values(starts);
        let mut tried = BTreeSet::new();
        let mut exhausted = vec![false; n];
        let by_region = self.by_region();
        for _ in 0..2 * n + 8 {
            let now = spread(&values);
            if now <= bound {
                return;
            }
            let mut sorted = values.clone();
            sorted.sort_by(f32::total_cmp);
            let target = sorted[n / 2];
            let Some(p) = (0..n)
                .filter(|&p| !exhausted[p])
                .max_by(|&a, &b| (values[a] - target).abs().total_cmp(&(values[b] - target).abs()).then(b.cmp(&a)))
            else {
                return;
            };
            let reach_part = values[p] - self.scores[starts[p]];
            let region = self.division.region_of[starts[p]] as usize;
            // Nearest the target first; the distance to the other starts is asked only of
            // those in turn, as it is the dearer test.
            let miss = |i: usize| (self.scores[i] + reach_part - target).abs();
            let mut options: Vec<usize> = by_region[region]
                .iter()
                .copied()
                .filter(|&i| i != starts[p] && self.missing[i] <= self.missing[starts[p]] && !tried.contains(&(p, i)))
                .collect();
            options.sort_by(|&a, &b| miss(a).total_cmp(&miss(b)).then(a.cmp(&b)));
            let candidate = options.into_iter().find(|&i| self.far_enough(i, starts, Some(p)));
            let Some(c) = candidate else {
                exhausted[p] = true;
                continue;
            };
            tried.insert((p, c));
            let old = starts[p];
            starts[p] = c;
            let moved = self.values(starts);
            if spread(&moved) < now {
                values = moved;
            } else {
                starts[p] = old;
            }
        }
    }
}

/// `max / min - 1` of some values (infinite when the least is not above 0, 0 for none).
pub(crate) fn spread(values: &[f32]) -> f32 {
    let max = values.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let min = values.iter().copied().fold(f32::INFINITY, f32::min);
    if values.is_empty() {
        0.0
    } else if min <= 0.0 {
        if max <= 0.0 { 0.0 } else { f32::INFINITY }
    } else {
        max / min - 1.0
    }
}

/// The tile of `tiles` with the highest `key`, the first on a tie.
fn best(tiles: impl Iterator<Item = usize>, key: &[f32]) -> Option<usize> {
    tiles.fold(None, |best: Option<usize>, i| match best {
        Some(b) if key[b] >= key[i] => Some(b),
        _ => Some(i),
    })
}
