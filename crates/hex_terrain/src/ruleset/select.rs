//! A tile's terrain and feature from what the stages know of it ([`TileFacts`]): a pure function
//! of the ruleset, the facts and (for a feature's patches) the tile's position, so chunks agree
//! at their seams and a chunk agrees with the whole map.

use serde::{Deserialize, Serialize};

use super::{Landform, Occurs, TerrainRuleset, Traits};
use crate::config::NoiseConfig;
use crate::heights::Fbm;

/// A terrain of a ruleset: its index in [`TerrainRuleset::terrains`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(transparent)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct TerrainId(pub u8);

/// A feature of a ruleset: its index in [`TerrainRuleset::features`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(transparent)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct FeatureId(pub u8);

/// What a tile is under a ruleset ([`TileInfo::terrain`](crate::TileInfo::terrain)); its
/// names are the ruleset's ([`TerrainRuleset::terrain`], [`TerrainRuleset::feature`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct TileTerrain {
    /// Its base terrain.
    pub terrain: TerrainId,
    /// Where it lies (hills are a landform of a land terrain).
    pub landform: Landform,
    /// The feature on it, if any.
    pub feature: Option<FeatureId>,
    /// Its traits: the terrain's (on hills, its hills traits), then the feature's.
    pub traits: Traits,
}

/// Whatever answers what each tile of a map is under its own terrain ruleset (the compiled
/// pipeline): what the game setup's survey reads its traits from.
pub(crate) trait TileTerrains: Sync {
    /// What a tile of the map is.
    fn tile_terrain(&self, tile: hexx::Hex) -> TileTerrain;
}

/// What a tile's terrain and feature are decided from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TileFacts {
    /// Where it lies.
    pub landform: Landform,
    /// Its temperature, in `[0, 1]`.
    pub temperature: f32,
    /// Its moisture, in `[0, 1]`.
    pub moisture: f32,
    /// Its center's height within its landform's band, in `[0, 1]`.
    pub elevation: f32,
    /// Its latitude, 0 at the equator, 1 at a pole.
    pub latitude: f32,
    /// Whether a neighbor is sea or lake.
    pub near_water: bool,
    /// Whether a river runs through it or on one of its edges.
    pub near_river: bool,
    /// Whether the map has a climate (without one, every tile's terrain is its landform's
    /// fallback and no feature grows).
    pub climate: bool,
}

impl TileFacts {
    /// A tile of `landform` on a map with a climate, at mid temperature, moisture, elevation
    /// and latitude, away from water and rivers.
    #[must_use]
    pub fn new(landform: Landform) -> Self {
        Self {
            landform,
            temperature: 0.5,
            moisture: 0.5,
            elevation: 0.5,
            latitude: 0.5,
            near_water: false,
            near_river: false,
            climate: true,
        }
    }
}

/// `[lo, hi)`, with 1 itself inside a range ending at 1.
#[inline]
fn within(v: f32, (lo, hi): (f32, f32)) -> bool {
    v >= lo && (v < hi || (hi >= 1.0 && v <= 1.0))
}

impl Occurs {
    /// Whether the rule covers a tile with these facts.
    #[must_use]
    pub fn covers(&self, f: &TileFacts) -> bool {
        self.landform.contains(&f.landform)
            && within(f.temperature, self.temperature)
            && within(f.moisture, self.moisture)
            && within(f.elevation, self.elevation)
            && within(f.latitude, self.latitude)
            && self.near_water.is_none_or(|w| w == f.near_water)
            && self.near_river.is_none_or(|r| r == f.near_river)
    }
}

impl TerrainRuleset {
    /// A tile's terrain: the terrain of the highest-priority rule covering its facts, or its
    /// landform's fallback when none does (always, without a climate).
    #[must_use]
    pub fn terrain_for(&self, facts: &TileFacts) -> TerrainId {
        let mut best: Option<(u8, usize)> = None;
        if facts.climate {
            for (i, t) in self.terrains.iter().enumerate() {
                for rule in t.occurs.iter().filter(|r| r.covers(facts)) {
                    if best.is_none_or(|(p, _)| rule.priority > p) {
                        best = Some((rule.priority, i));
                    }
                }
            }
        }
        match best {
            Some((_, i)) => TerrainId(i as u8),
            None => self.terrain_id(&self.fallback[&facts.landform]).expect("a validated ruleset's fallback"),
        }
    }

    /// The features that may sit on a tile of `terrain` with these facts, highest priority
    /// first (then in the ruleset's order), with the priority of the rule that admits each.
    pub fn feature_candidates(&self, terrain: TerrainId, facts: &TileFacts) -> Vec<(super::FeatureId, u8)> {
        if !facts.climate {
            return Vec::new();
        }
        let id = &self.terrain(terrain).id;
        let mut found: Vec<(FeatureId, u8)> = self
            .features
            .iter()
            .enumerate()
            .filter(|(_, f)| f.on.contains(id))
            .filter_map(|(i, f)| {
                f.occurs.iter().filter(|r| r.covers(facts)).map(|r| r.priority).max().map(|p| (FeatureId(i as u8), p))
            })
            .collect();
        found.sort_by_key(|&(f, p)| (std::cmp::Reverse(p), f));
        found
    }

    /// A tile's traits: its terrain's (on hills, the terrain's hills traits when it has them),
    /// then its feature's, which replace them or add to them ([`super::FeatureDef::replace`]).
    #[must_use]
    pub fn traits(&self, terrain: TerrainId, landform: Landform, feature: Option<FeatureId>) -> Traits {
        let t = self.terrain(terrain);
        let base = match (landform, t.hills) {
            (Landform::Hills, Some(hills)) => hills,
            _ => t.traits,
        };
        let Some(f) = feature.map(|f| self.feature(f)) else { return base };
        if f.replace {
            return f.traits;
        }
        let movement =
            if base.movement == 0 || f.traits.movement == 0 { 0 } else { base.movement.max(f.traits.movement) };
        let (a, b) = (base.yields, f.traits.yields);
        Traits {
            movement,
            tall: base.tall || f.traits.tall,
            yields: crate::config::Yields::new(a.food + b.food, a.production + b.production, a.gold + b.gold),
        }
    }
}

/// A map's feature patches: one noise field a feature, from the map's seed and the feature's
/// id, periodic across a wrapping map's seam. A tile has a candidate feature when the noise at
/// its center lies in the lowest `density` of its spread.
#[derive(Debug, Clone)]
pub struct FeaturePatches {
    fields: Vec<Fbm>,
    densities: Vec<f32>,
}

/// The spread of a patch field's values about 0.5 (three octaves of Perlin noise), measured:
/// a density `d` covers the tiles whose value lies under the normal quantile of `d`.
pub const PATCH_SPREAD: f64 = 0.143;

/// Hex radii of a patch field's noise scale per tile of [`super::FeatureDef::patch`].
const PATCH_SCALE: f64 = 14.0;

impl FeaturePatches {
    /// The patches of a validated ruleset's features on a map of `seed`; `wrap_width`, a
    /// wrapping map's width in hex radii.
    #[must_use]
    pub fn new(ruleset: &TerrainRuleset, seed: u32, wrap_width: Option<f64>) -> Self {
        let fields = ruleset
            .features
            .iter()
            .map(|f| {
                let name: Vec<i64> = f.id.bytes().map(i64::from).collect();
                let seed = crate::hash::hash(seed, &name) as u32;
                let noise = NoiseConfig {
                    octaves: 3,
                    persistence: 0.5,
                    lacunarity: 2.0,
                    scale: PATCH_SCALE * f64::from(f.patch),
                };
                match wrap_width {
                    Some(width) => Fbm::wrapped(seed, &noise, width),
                    None => Fbm::new(seed, &noise),
                }
            })
            .collect();
        Self { fields, densities: ruleset.features.iter().map(|f| f.density).collect() }
    }

    /// Whether feature `feature`'s patches reach the point `(x, z)` (hex radii, the tile's
    /// center).
    #[must_use]
    pub fn reaches(&self, feature: FeatureId, x: f64, z: f64) -> bool {
        let i = usize::from(feature.0);
        let density = f64::from(self.densities[i]);
        if density >= 1.0 {
            return true;
        }
        let v = self.fields[i].sample(x, z);
        // The normal distribution's CDF at the value's distance from the middle.
        let below = 0.5 * (1.0 + libm::erf((v - 0.5) / (PATCH_SPREAD * std::f64::consts::SQRT_2)));
        below < density
    }

    /// A tile's feature: the first candidate ([`TerrainRuleset::feature_candidates`]) whose
    /// patches reach the tile's center `(x, z)`.
    #[must_use]
    pub fn feature_for(
        &self,
        ruleset: &TerrainRuleset,
        terrain: TerrainId,
        facts: &TileFacts,
        (x, z): (f64, f64),
    ) -> Option<FeatureId> {
        ruleset.feature_candidates(terrain, facts).into_iter().map(|(f, _)| f).find(|&f| self.reaches(f, x, z))
    }
}
