//! The fairness report: every start's value and what it is made of, the spread of the values
//! against the bound, which starts cannot reach each other by land, and what the setup could
//! not do as asked.

use hexx::Hex;

use super::placement::{SetupNote, Shortfall};
use crate::config::Yields;

/// One start in the report (`T`: a flat map's [`Hex`], a globe's
/// [`GlobeTile`](crate::GlobeTile)).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct StartReport<T = Hex> {
    /// The player (0 is the first; the printed table counts from 1).
    pub player: u32,
    /// Its start tile (map-local axial on a flat map).
    pub tile: T,
    /// Where the start tile is, as the printed table shows it: on a flat map its offset
    /// coordinate `[col, row]`, on a globe its longitude and latitude in whole degrees (east
    /// and north positive).
    pub coords: [i32; 2],
    /// Its region.
    pub region: u32,
    /// Its value: the value of the yields within its rings (resources and wonders included)
    /// plus the reach weight times `reach`. The spread is of these.
    pub value: f32,
    /// The yields of the tiles within its rings.
    pub yields: Yields,
    /// Resources within its rings.
    pub resources: u32,
    /// Of those, how many normalisation added.
    pub added: u32,
    /// Passable tiles it reaches at a lower path cost than any rival.
    pub reach: u32,
    /// Tiles of its land mass (the passable tiles connected to it).
    pub land_area: u32,
    /// The nearest rival by path cost over land and that cost; `None` when no rival is reachable.
    pub nearest_rival: Option<(u32, u32)>,
}

/// The whole report (`T`: a flat map's [`Hex`], a globe's [`GlobeTile`](crate::GlobeTile)).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct SetupReport<T = Hex> {
    /// One row a start, in player order.
    pub starts: Vec<StartReport<T>>,
    /// `max / min - 1` of the starts' values: 0 for one start or equal values (and when no
    /// value is above 0), infinite when the smallest value is at most 0 and another is above
    /// it (no ratio bounds them: such a setup is never within a bound).
    pub spread: f32,
    /// The bound asked (`setup.fairness`).
    pub bound: f32,
    /// Whether `spread <= bound`.
    pub within_bound: bool,
    /// Path cost between every two starts (`costs[a][b]`) by the map's movement model: the
    /// cost of `Terrain::path` between them, kept inside the setup's area when it has one;
    /// `None` when one cannot reach the other.
    pub costs: Vec<Vec<Option<u32>>>,
    /// Pairs of players (lower first) that cannot reach each other by land.
    pub unreachable: Vec<(u32, u32)>,
    /// Players that did not find all their guaranteed resources.
    pub shortfalls: Vec<Shortfall>,
    /// What the setup could not do as asked.
    pub notes: Vec<SetupNote>,
    /// Resources placed on the map (normalisation's included).
    pub resources: u32,
    /// Natural wonders placed.
    pub wonders: u32,
}

impl<T> std::fmt::Display for SetupReport<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{:>6}  {:>10}  {:>7}  {:>5}  {:>5}  {:>5}  {:>9}  {:>5}  {:>5}  {:>13}",
            "player", "tile", "value", "food", "prod", "gold", "resources", "reach", "land", "nearest rival"
        )?;
        for s in &self.starts {
            let rival = match s.nearest_rival {
                Some((p, cost)) => format!("{p} (cost {cost})"),
                None => "unreachable".into(),
            };
            let resources =
                if s.added > 0 { format!("{} (+{})", s.resources - s.added, s.added) } else { s.resources.to_string() };
            writeln!(
                f,
                "{:>6}  {:>10}  {:>7.1}  {:>5.0}  {:>5.0}  {:>5.0}  {:>9}  {:>5}  {:>5}  {:>13}",
                s.player,
                format!("({}, {})", s.coords[0], s.coords[1]),
                s.value,
                s.yields.food,
                s.yields.production,
                s.yields.gold,
                resources,
                s.reach,
                s.land_area,
                rival
            )?;
        }
        let verdict = if self.within_bound { "within the bound" } else { "ABOVE the bound: the best found" };
        writeln!(
            f,
            "spread {:.1} % (max / min - 1; bound {:.1} %): {verdict}; {} resources, {} wonders",
            self.spread * 100.0,
            self.bound * 100.0,
            self.resources,
            self.wonders
        )?;
        if !self.unreachable.is_empty() {
            let pairs: Vec<String> = self.unreachable.iter().map(|(a, b)| format!("{a}-{b}")).collect();
            writeln!(f, "cannot reach each other by land: {}", pairs.join(", "))?;
        }
        for s in &self.shortfalls {
            writeln!(f, "player {} finds {} of {} {} near its start", s.player, s.found, s.wanted, s.resource)?;
        }
        for n in &self.notes {
            writeln!(f, "{}: {}", n.field, n.why)?;
        }
        Ok(())
    }
}
