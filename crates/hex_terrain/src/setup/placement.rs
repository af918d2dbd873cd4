//! Natural wonders and resources, and the normalisation of weak starts. Every choice among
//! allowed tiles goes by a hash of the seed and the tile, so placement is a pure function of the
//! config: the same on every machine, thread count and chunk order.
//!
//! - **Wonders** first (as Unciv does), rarest first: the wonder with the fewest tiles it may
//!   stand on picks first, away from starts and from other wonders.
//! - **Resources**, rule by rule in table order: first each player's guaranteed ones within its
//!   start's rings, then the rest up to the rule's density, never closer than its spacing to
//!   another of the same resource, one thing a tile.
//! - **Normalisation** (Unciv's start normalisation): while the spread of the starts' values is
//!   above the bound, the weakest start gets the bonus resource that adds the most value on a
//!   free tile of its rings; it stops when the spread is within the bound or the weakest start
//!   has no room left, so it always ends.

use super::survey::{NONE, Survey};
use crate::config::{Place, ResourceClass, SetupConfig, Yields};
use crate::hash;

/// Something the setup could not do as asked, with the field of the config it concerns.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct SetupNote {
    /// The field, e.g. `setup.resources[3]`.
    pub field: String,
    /// What happened.
    pub why: String,
}

/// A player that did not find all its guaranteed resources.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Shortfall {
    /// The player (0 is the first).
    pub player: u32,
    /// The resource's name.
    pub resource: String,
    /// How many lie within its rings.
    pub found: u32,
    /// How many it is guaranteed.
    pub wanted: u32,
}

/// What lies on the area's tiles.
#[derive(Debug, Clone)]
pub(crate) struct Placement {
    /// The resource rule on each tile, [`NONE`] for none.
    pub resource: Vec<u32>,
    /// Whether the tile's resource was added by normalisation.
    pub added: Vec<bool>,
    /// The wonder on each tile, [`NONE`] for none.
    pub wonder: Vec<u32>,
    pub shortfalls: Vec<Shortfall>,
    pub notes: Vec<SetupNote>,
    /// For each resource rule, the tiles its spacing closes to another of it.
    blocked: Vec<Vec<bool>>,
}

/// Whether tile `i` is of any of the places.
pub(crate) fn allowed(survey: &Survey, i: usize, on: &[Place]) -> bool {
    on.iter().any(|p| match p {
        Place::Biome(b) => survey.biomes[i] == *b,
        Place::Kind(k) => survey.kinds[i] == *k,
        Place::Terrain(id) => survey.terrain_is(i, id),
        Place::Feature(id) => survey.feature_is(i, id),
    })
}

/// What chooses and places.
pub(crate) struct Placer<'a> {
    pub survey: &'a Survey<'a>,
    pub config: &'a SetupConfig,
    pub seed: u32,
    pub starts: &'a [usize],
    /// Each start's tiles within its rings.
    pub rings: &'a [Vec<u32>],
}

impl Placer<'_> {
    /// A tile's draw for `salt`: lower picks first.
    fn draw(&self, i: usize, salt: i64) -> u64 {
        let [x, y] = self.survey.board.key(i);
        hash::hash(self.seed, &[x, y, salt])
    }

    /// Marks the tiles within `radius` of `i`.
    fn mark(&self, marks: &mut [bool], i: usize, radius: u32, scratch: &mut Vec<u32>) {
        self.survey.range(i, radius, scratch);
        for &j in scratch.iter() {
            marks[j as usize] = true;
        }
    }

    /// Places wonders and resources.
    pub fn place(&self) -> Placement {
        let n = self.survey.len();
        let mut p = Placement {
            resource: vec![NONE; n],
            added: vec![false; n],
            wonder: vec![NONE; n],
            shortfalls: Vec::new(),
            notes: Vec::new(),
            blocked: vec![vec![false; n]; self.config.resources.len()],
        };
        self.wonders(&mut p);
        self.resources(&mut p);
        p
    }

    fn wonders(&self, p: &mut Placement) {
        let survey = self.survey;
        let w = &self.config.wonders;
        let mut scratch = Vec::new();
        let mut near_start = vec![false; survey.len()];
        for &s in self.starts {
            self.mark(&mut near_start, s, w.from_starts.saturating_sub(1), &mut scratch);
        }
        let candidates: Vec<Vec<usize>> = w
            .list
            .iter()
            .enumerate()
            .map(|(k, rule)| {
                let mut tiles: Vec<usize> =
                    (0..survey.len()).filter(|&i| !near_start[i] && allowed(survey, i, &rule.on)).collect();
                tiles.sort_by_key(|&i| (self.draw(i, 0x3011 + k as i64), i));
                tiles
            })
            .collect();
        let mut order: Vec<usize> = (0..w.list.len()).collect();
        order.sort_by_key(|&k| (candidates[k].len(), k));
        let mut closed = vec![false; survey.len()];
        let mut placed = 0;
        for k in order {
            if placed == w.count {
                break;
            }
            if let Some(&i) = candidates[k].iter().find(|&&i| !closed[i]) {
                p.wonder[i] = k as u32;
                self.mark(&mut closed, i, w.spacing.saturating_sub(1), &mut scratch);
                closed[i] = true;
                placed += 1;
            }
        }
        if placed < w.count {
            p.notes.push(SetupNote {
                field: "setup.wonders.count".into(),
                why: format!(
                    "{placed} of {} wonders placed: no more room for the listed wonders at spacing {} and {} tiles from \
                     starts",
                    w.count, w.spacing, w.from_starts
                ),
            });
        }
    }

    /// Whether rule `r` may go on tile `i` now.
    fn free(&self, p: &Placement, r: usize, i: usize) -> bool {
        p.resource[i] == NONE
            && p.wonder[i] == NONE
            && !p.blocked[r][i]
            && !self.starts.contains(&i)
            && allowed(self.survey, i, &self.config.resources[r].on)
    }

    fn put(&self, p: &mut Placement, r: usize, i: usize, added: bool, scratch: &mut Vec<u32>) {
        p.resource[i] = r as u32;
        p.added[i] = added;
        let spacing = self.config.resources[r].spacing;
        let mut blocked = std::mem::take(&mut p.blocked[r]);
        self.mark(&mut blocked, i, spacing.saturating_sub(1), scratch);
        p.blocked[r] = blocked;
    }

    fn resources(&self, p: &mut Placement) {
        let survey = self.survey;
        let mut scratch = Vec::new();
        let rules = &self.config.resources;
        let salt = |r: usize| 0x5e50 + r as i64;
        let tiles: Vec<Vec<usize>> =
            rules.iter().map(|rule| (0..survey.len()).filter(|&i| allowed(survey, i, &rule.on)).collect()).collect();
        for (r, rule) in rules.iter().enumerate() {
            if tiles[r].is_empty() && (rule.density > 0.0 || rule.per_player > 0) {
                p.notes.push(SetupNote {
                    field: format!("setup.resources[{r}].on"),
                    why: format!("no tile of this map may hold {} ({:?})", rule.name, rule.on),
                });
            }
        }
        // Every player's guaranteed ones first, before any resource is spread by density, so
        // the common ones do not take the tiles a guarantee needs.
        for (player, ring) in self.rings.iter().enumerate() {
            // The rule with the fewest tiles it may take in the rings first.
            let room = |r: usize| ring.iter().filter(|&&j| self.free(p, r, j as usize)).count();
            let mut order: Vec<(usize, usize)> =
                (0..rules.len()).filter(|&r| rules[r].per_player > 0).map(|r| (room(r), r)).collect();
            order.sort_unstable();
            for (_, r) in order {
                let rule = &rules[r];
                let mut found = ring.iter().filter(|&&j| p.resource[j as usize] == r as u32).count() as u32;
                while found < rule.per_player {
                    let pick = ring
                        .iter()
                        .map(|&j| j as usize)
                        .filter(|&j| self.free(p, r, j))
                        .min_by_key(|&j| (self.draw(j, salt(r)), j));
                    let Some(j) = pick else { break };
                    self.put(p, r, j, false, &mut scratch);
                    found += 1;
                }
                if found < rule.per_player {
                    p.shortfalls.push(Shortfall {
                        player: player as u32,
                        resource: rule.name.clone(),
                        found,
                        wanted: rule.per_player,
                    });
                }
            }
        }
        // The rest, up to each rule's density, in draw order.
        for (r, rule) in rules.iter().enumerate() {
            let mut count = p.resource.iter().filter(|&&k| k == r as u32).count();
            let target = (rule.density * tiles[r].len() as f32).round() as usize;
            let mut order = tiles[r].clone();
            order.sort_by_key(|&i| (self.draw(i, salt(r)), i));
            for i in order {
                if count >= target {
                    break;
                }
                if self.free(p, r, i) {
                    self.put(p, r, i, false, &mut scratch);
                    count += 1;
                }
            }
        }
    }

    /// The yields of tile `i` with what lies on it.
    pub fn yields(&self, p: &Placement, i: usize) -> Yields {
        let mut y = self.survey.yields[i];
        if p.resource[i] != NONE {
            y += self.config.resources[p.resource[i] as usize].yields;
        }
        if p.wonder[i] != NONE {
            y += self.config.wonders.list[p.wonder[i] as usize].yields;
        }
        y
    }

    /// Each start's ring value with what lies on its tiles, plus `extra` (the reach part).
    pub fn values(&self, p: &Placement, extra: &[f32]) -> Vec<f32> {
        let w = &self.config.value;
        self.rings
            .iter()
            .zip(extra)
            .map(|(ring, e)| ring.iter().map(|&j| w.of(self.yields(p, j as usize))).sum::<f32>() + e)
            .collect()
    }

    /// Adds bonus resources near the weakest start while the spread is above the bound (see
    /// the module docs); `extra` is each start's reach part of its value.
    pub fn normalize(&self, p: &mut Placement, extra: &[f32]) {
        let rules = &self.config.resources;
        // Bonus resources first (a bonus sorts before the other classes), then any.
        let rank = |r: usize| u8::from(rules[r].class != ResourceClass::Bonus);
        let worth = |r: usize| self.config.value.of(rules[r].yields);
        let mut scratch = Vec::new();
        let limit: usize = self.rings.iter().map(Vec::len).sum();
        for _ in 0..limit {
            let values = self.values(p, extra);
            if super::starts::spread(&values) <= self.config.fairness {
                return;
            }
            let weakest = (0..values.len()).min_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
            let Some(weakest) = weakest else { return };
            let pick = self.rings[weakest]
                .iter()
                .flat_map(|&j| (0..rules.len()).map(move |r| (r, j as usize)))
                .filter(|&(r, j)| worth(r) > 0.0 && self.free(p, r, j))
                .min_by(|&(ra, ja), &(rb, jb)| {
                    rank(ra)
                        .cmp(&rank(rb))
                        .then(worth(rb).total_cmp(&worth(ra)))
                        .then(self.draw(ja, 0x40a1).cmp(&self.draw(jb, 0x40a1)))
                        .then(ja.cmp(&jb))
                });
            let Some((r, j)) = pick else { return };
            self.put(p, r, j, true, &mut scratch);
        }
    }
}
