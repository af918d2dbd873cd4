//! Checking a game setup's fields against their allowed ranges, by name.

use super::{
    MAX_PER_PLAYER, MAX_PLAYERS, MAX_SETUP_DISTANCE, MAX_SETUP_RINGS, MAX_SETUP_RULES, MAX_SETUP_TILES, MAX_YIELD,
    Place, SetupConfig, Yields,
};
use crate::config::check::{check, finite_in};
use crate::error::ConfigError;

impl SetupConfig {
    /// Checks every field against its allowed range; `bounds` is the map's size (`None` for an
    /// unbounded world, where `area` is required).
    ///
    /// # Errors
    /// The first invalid field (`setup.…`), with its value and the allowed range.
    pub fn validate(&self, bounds: Option<(u32, u32)>) -> Result<(), ConfigError> {
        check((1..=MAX_PLAYERS).contains(&self.players), "setup.players", self.players, format!("1..={MAX_PLAYERS}"))?;
        check(
            (1..=MAX_SETUP_RINGS).contains(&self.rings),
            "setup.rings",
            self.rings,
            format!("1..={MAX_SETUP_RINGS}"),
        )?;
        check(
            (1..=MAX_SETUP_DISTANCE).contains(&self.min_distance),
            "setup.min_distance",
            self.min_distance,
            format!("1..={MAX_SETUP_DISTANCE}"),
        )?;
        let y = &self.yields;
        for (biome, v) in &y.biomes {
            check_yields(&format!("setup.yields.biomes.{}", biome.name()), *v)?;
        }
        for (kind, v) in &y.kinds {
            check_yields(&format!("setup.yields.kinds.{}", kind.name()), *v)?;
        }
        check_yields("setup.yields.river", y.river)?;
        check_yields("setup.yields.coast", y.coast)?;
        let w = &self.value;
        for (name, v) in [("food", w.food), ("production", w.production), ("gold", w.gold), ("reach", w.reach)] {
            check(finite_in(f64::from(v), 0.0, 100.0), &format!("setup.value.{name}"), v, "[0, 100]")?;
        }
        check(finite_in(f64::from(self.fairness), 0.0, 10.0), "setup.fairness", self.fairness, "[0, 10]")?;
        check(
            self.resources.len() <= MAX_SETUP_RULES,
            "setup.resources",
            format!("{} rules", self.resources.len()),
            format!("at most {MAX_SETUP_RULES}"),
        )?;
        for (i, r) in self.resources.iter().enumerate() {
            let field = |name: &str| format!("setup.resources[{i}].{name}");
            let earlier = self.resources[..i].iter().map(|o| o.name.as_str());
            check_named(&field, &r.name, earlier, &r.on, "resource")?;
            check(finite_in(f64::from(r.density), 0.0, 1.0), &field("density"), r.density, "[0, 1]")?;
            check(
                (1..=MAX_SETUP_DISTANCE).contains(&r.spacing),
                &field("spacing"),
                r.spacing,
                format!("1..={MAX_SETUP_DISTANCE}"),
            )?;
            check(r.per_player <= MAX_PER_PLAYER, &field("per_player"), r.per_player, format!("0..={MAX_PER_PLAYER}"))?;
            check_yields(&field("yields"), r.yields)?;
        }
        let wonders = &self.wonders;
        check(
            wonders.count <= MAX_SETUP_RULES as u32,
            "setup.wonders.count",
            wonders.count,
            format!("0..={MAX_SETUP_RULES}"),
        )?;
        check(
            wonders.spacing <= MAX_SETUP_DISTANCE,
            "setup.wonders.spacing",
            wonders.spacing,
            format!("0..={MAX_SETUP_DISTANCE}"),
        )?;
        check(
            wonders.from_starts <= MAX_SETUP_DISTANCE,
            "setup.wonders.from_starts",
            wonders.from_starts,
            format!("0..={MAX_SETUP_DISTANCE}"),
        )?;
        check(
            wonders.list.len() <= MAX_SETUP_RULES,
            "setup.wonders.list",
            format!("{} wonders", wonders.list.len()),
            format!("at most {MAX_SETUP_RULES}"),
        )?;
        for (i, r) in wonders.list.iter().enumerate() {
            let field = |name: &str| format!("setup.wonders.list[{i}].{name}");
            let earlier = wonders.list[..i].iter().map(|o| o.name.as_str());
            check_named(&field, &r.name, earlier, &r.on, "wonder")?;
            check_yields(&field("yields"), r.yields)?;
        }
        match (self.area, bounds) {
            (None, None) => Err(ConfigError::new(
                "setup.area",
                "None".into(),
                "a rectangle of tiles, e.g. Some((min: (0, 0), max: (80, 50))), on an unbounded map".into(),
            )),
            (None, Some((x, z))) => check(
                u64::from(x) * u64::from(z) <= MAX_SETUP_TILES,
                "setup.area",
                format!("None (the whole map: {} tiles)", u64::from(x) * u64::from(z)),
                format!("a rectangle of at most {MAX_SETUP_TILES} tiles on a map larger than that"),
            ),
            (Some(a), b) => {
                let value = format!("(min: {:?}, max: {:?})", a.min, a.max);
                check(!a.is_empty(), "setup.area", &value, "a rectangle with max above min in both columns and rows")?;
                check(
                    a.len() as u64 <= MAX_SETUP_TILES,
                    "setup.area",
                    &value,
                    format!("at most {MAX_SETUP_TILES} tiles"),
                )?;
                if let Some((x, z)) = b {
                    check(
                        a.min[0] >= 0 && a.min[1] >= 0 && a.max[0] <= x as i32 && a.max[1] <= z as i32,
                        "setup.area",
                        &value,
                        format!("inside the map: columns 0..{x}, rows 0..{z}"),
                    )?;
                } else {
                    let m = crate::config::MAX_WORLD_TILE;
                    check(
                        a.min.iter().chain(&a.max).all(|v| (-m..=m).contains(v)),
                        "setup.area",
                        &value,
                        format!("inside the world: -{m}..={m}"),
                    )?;
                }
                Ok(())
            }
        }
    }
}

/// Checks a resource's or wonder's name (given, not taken by an `earlier` one of its `kind`)
/// and that it may lie somewhere.
fn check_named<'a>(
    field: &dyn Fn(&str) -> String,
    name: &str,
    mut earlier: impl Iterator<Item = &'a str>,
    on: &[Place],
    kind: &str,
) -> Result<(), ConfigError> {
    check(!name.trim().is_empty(), &field("name"), format!("{name:?}"), "a name")?;
    check(!earlier.any(|o| o == name), &field("name"), format!("{name:?}"), format!("a name no other {kind} has"))?;
    check(!on.is_empty(), &field("on"), "[]", "at least one biome or tile type")
}

/// Checks one entry of yields.
fn check_yields(field: &str, y: Yields) -> Result<(), ConfigError> {
    for (name, v) in [("food", y.food), ("production", y.production), ("gold", y.gold)] {
        check(finite_in(f64::from(v), 0.0, f64::from(MAX_YIELD)), &format!("{field}.{name}"), v, "[0, 100]")?;
    }
    Ok(())
}
