//! Deserts in rain shadows, as [`MapStats`](super::MapStats) counts them on a map with winds:
//! how often a desert has a mountain a few tiles upwind, beside how often land in general has.

use hexx::Hex;

use crate::climate::winds::{neighbor_steps, row_winds};
use crate::info::TileInfo;
use crate::terrain::Terrain;
use crate::vocab::{Biome, TileKind};

/// How far upwind (in tiles) a mountain casts its rain shadow, as [`RainShadow`] counts it.
pub const SHADOW_REACH: u32 = 6;

/// Deserts and land in the lee of mountains, on a map with winds ([`MapStats::rain_shadow`](super::MapStats::rain_shadow)).
/// A tile is in a mountain's shadow when a mountain lies within [`SHADOW_REACH`] steps upwind of
/// it: each step to the neighbor most directly against the wind of the row the walk is in.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct RainShadow {
    /// Desert tiles.
    pub deserts: u32,
    /// Desert tiles in a mountain's shadow.
    pub deserts_in_shadow: u32,
    /// Land tiles other than mountains (lakes aside).
    pub land: u32,
    /// Of those, the ones in a mountain's shadow.
    pub land_in_shadow: u32,
}

impl RainShadow {
    /// How much more often a desert lies in a mountain's shadow than land in general does (1:
    /// no more often; 0 without a desert or without land in a shadow).
    #[must_use]
    pub fn ratio(&self) -> f64 {
        let deserts = f64::from(self.deserts_in_shadow) / f64::from(self.deserts.max(1));
        let land = f64::from(self.land_in_shadow) / f64::from(self.land.max(1));
        if land == 0.0 { 0.0 } else { deserts / land }
    }
}

/// The rain shadow's counts of a bounded map with winds (`None` without).
pub(super) fn rain_shadow(
    terrain: &Terrain,
    tiles: &[Hex],
    neighbors: &[[Option<u32>; 6]],
    infos: &[TileInfo],
    biomes: &[Biome],
) -> Option<RainShadow> {
    let winds = terrain.climate().winds()?;
    let rect = terrain.bounds()?;
    let rows = row_winds(winds, rect, terrain.climate().latitudes());
    let steps = neighbor_steps(terrain.geometry());
    let mountain = |i: usize| infos[i].kind == TileKind::Mountain && infos[i].lake.is_none();
    // The neighbor most directly upwind of tile `i` (the first of equals), if on the map.
    let upwind = |i: usize| {
        let wind = rows[(terrain.offset_of(tiles[i])[1] - rect.min[1]) as usize];
        let against = |d: usize| -(steps[d][0] * wind[0] + steps[d][1] * wind[1]);
        let d = (0..6).fold(0, |best, d| if against(d) > against(best) { d } else { best });
        neighbors[i][d].map(|j| j as usize)
    };
    let shadowed = |i: usize| {
        let mut at = i;
        for _ in 0..SHADOW_REACH {
            match upwind(at) {
                Some(j) if mountain(j) => return true,
                Some(j) => at = j,
                None => return false,
            }
        }
        false
    };
    let mut out = RainShadow::default();
    for (i, info) in infos.iter().enumerate() {
        if info.kind != TileKind::Land || info.lake.is_some() {
            continue;
        }
        let shadow = shadowed(i);
        out.land += 1;
        out.land_in_shadow += u32::from(shadow);
        if biomes[i] == Biome::Desert {
            out.deserts += 1;
            out.deserts_in_shadow += u32::from(shadow);
        }
    }
    Some(out)
}
