//! How [`MapStats`] prints: the lines `hexterrain stats` shows (and the demo).

use super::{Landmass, MapStats, SHADOW_REACH};

/// The statistics as `hexterrain stats` prints them (and the demo shows them): a line each for
/// water and land, mountains, landmasses, coast and strait, rivers and lakes, and the starts'
/// land.
impl std::fmt::Display for MapStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let percent = |x: f64| x * 100.0;
        writeln!(
            f,
            "water: {:.1} % ({} sea, {} lake tiles); land {:.1} % ({} tiles)",
            percent(self.water_share()),
            self.sea_tiles,
            self.lake_tiles,
            percent(self.land_share()),
            self.land_tiles
        )?;
        writeln!(
            f,
            "mountains: {:.1} % of the land, {:.1} % of them in ranges, the longest {} tiles end to end; {:.1} \
             mountain neighbors a mountain",
            percent(self.mountain_share()),
            percent(self.range_share()),
            self.longest_range,
            self.mountain_neighbors()
        )?;
        writeln!(
            f,
            "shape: the straightest ridge {} mountains in a row, {:.1} % of mountains in blobs; the polar rows hold \
             {:.1} % of the land; snow, tundra and snow peaks {:.1} % of it",
            self.straight_ridge,
            percent(self.blob_share()),
            percent(self.polar_land_share()),
            percent(self.cold_share())
        )?;
        let list = |masses: Vec<&Landmass>| match masses.len() {
            0 => "none".to_owned(),
            n => {
                let shown: Vec<String> = masses.iter().take(8).map(|m| m.tiles.to_string()).collect();
                let more = if n > 8 { format!(" and {} more", n - 8) } else { String::new() };
                format!("{n} ({}{more} tiles)", shown.join(", "))
            }
        };
        writeln!(
            f,
            "landmasses: continents {}; islands {}; the largest holds {:.1} % of the land",
            list(self.continents().collect()),
            list(self.islands().collect()),
            percent(self.largest_landmass_share())
        )?;
        match self.narrowest_strait {
            Some(n) => {
                writeln!(f, "coast: {} tile edges; narrowest strait between continents: {n} tiles", self.coast_edges)?;
            }
            None => writeln!(f, "coast: {} tile edges; one continent or none: no strait", self.coast_edges)?,
        }
        let r = &self.rivers;
        writeln!(
            f,
            "rivers reach {:.1} % of the land; {} sources ({:.0} % near hills or mountains), a river {} long on median",
            percent(self.river_share()),
            r.sources,
            percent(self.sources_near_relief_share()),
            r.median
        )?;
        writeln!(
            f,
            "rivers ending at the map's edge: {}; landmasses of {} tiles or more without a river: {}",
            r.mouths_at_edge,
            crate::RIVER_MIN_LANDMASS,
            self.landmasses_without_river(crate::RIVER_MIN_LANDMASS)
        )?;
        if let Some(shadow) = &self.rain_shadow {
            writeln!(
                f,
                "rain shadow: {} of {} deserts and {} of {} land tiles have a mountain within {SHADOW_REACH} tiles \
                 upwind: deserts {:.2} times as often",
                shadow.deserts_in_shadow,
                shadow.deserts,
                shadow.land_in_shadow,
                shadow.land,
                shadow.ratio()
            )?;
        }
        if r.edges > 0 {
            write!(
                f,
                "rivers: {} systems on {} edges, {} tiles on a river, the longest {} edges; {} lakes",
                r.systems, r.edges, r.tiles, r.longest, self.lakes
            )?;
        } else {
            write!(
                f,
                "rivers: {} systems, {} tiles, the longest {} tiles; {} lakes",
                r.systems, r.tiles, r.longest, self.lakes
            )?;
        }
        if !self.start_landmass_tiles.is_empty() {
            let starts: Vec<String> =
                self.start_landmass_tiles.iter().enumerate().map(|(p, n)| format!("player {p} {n}")).collect();
            write!(f, "\nland each start stands on (tiles): {}", starts.join(", "))?;
        }
        Ok(())
    }
}
