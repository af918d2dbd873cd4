//! A ruleset's validation: every error names the entry (its index and id), the field, the value
//! found and what is allowed, under `ruleset.` (`ruleset.terrains[3] "grassland".occurs[0].temperature`).

use std::collections::BTreeSet;

use super::{FeatureDef, Landform, Look, MAX_PROPS_ON_TILE, Occurs, TerrainRuleset, Traits};
use crate::config::{MAX_MOVE_COST, MAX_YIELD};
use crate::error::ConfigError;

/// Most terrains in a ruleset (the material's texture array and its per-terrain colors hold
/// this many).
pub const MAX_TERRAINS: usize = 32;

/// Most features in a ruleset.
pub const MAX_FEATURES: usize = 16;

/// Most rules one terrain or feature has.
pub const MAX_RULES: usize = 16;

/// The largest patch of a feature, in tiles.
pub const MAX_PATCH: f32 = 64.0;

fn fail(field: String, value: impl std::fmt::Display, allowed: impl Into<String>) -> ConfigError {
    ConfigError { field, value: value.to_string(), allowed: allowed.into() }
}

fn ensure(
    ok: bool,
    field: impl FnOnce() -> String,
    value: impl std::fmt::Display,
    allowed: &str,
) -> Result<(), ConfigError> {
    if ok { Ok(()) } else { Err(fail(field(), value, allowed)) }
}

/// Whether `range` is a finite `[lo, hi)` with `0 <= lo < hi <= 1`.
fn unit_range((lo, hi): (f32, f32)) -> bool {
    lo.is_finite() && hi.is_finite() && lo >= 0.0 && lo < hi && hi <= 1.0
}

/// Whether two half-open ranges (1 inside those ending at 1) share a value.
fn meet((a, b): (f32, f32), (c, d): (f32, f32)) -> bool {
    a < d && c < b
}

/// Whether two conditions can both hold.
fn agree(a: Option<bool>, b: Option<bool>) -> bool {
    a.is_none() || b.is_none() || a == b
}

/// Whether some tile could meet both rules.
pub(crate) fn overlap(a: &Occurs, b: &Occurs) -> bool {
    a.landform.iter().any(|l| b.landform.contains(l))
        && meet(a.temperature, b.temperature)
        && meet(a.moisture, b.moisture)
        && meet(a.elevation, b.elevation)
        && meet(a.latitude, b.latitude)
        && agree(a.near_water, b.near_water)
        && agree(a.near_river, b.near_river)
}

fn id_ok(id: &str) -> bool {
    !id.is_empty()
        && id.len() <= crate::vocab::MAX_ID_LEN
        && id.bytes().all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_')
}

fn check_occurs(at: &str, occurs: &[Occurs]) -> Result<(), ConfigError> {
    ensure(
        occurs.len() <= MAX_RULES,
        || format!("{at}.occurs"),
        format!("{} rules", occurs.len()),
        "at most 16 rules",
    )?;
    for (k, rule) in occurs.iter().enumerate() {
        let field = |name: &str| format!("{at}.occurs[{k}].{name}");
        ensure(!rule.landform.is_empty(), || field("landform"), "[]", "at least one landform")?;
        for (name, range) in [
            ("temperature", rule.temperature),
            ("moisture", rule.moisture),
            ("elevation", rule.elevation),
            ("latitude", rule.latitude),
        ] {
            ensure(unit_range(range), || field(name), format!("{range:?}"), "a range (lo, hi) with 0 <= lo < hi <= 1")?;
        }
    }
    Ok(())
}

fn check_traits(at: &str, traits: &Traits) -> Result<(), ConfigError> {
    ensure(traits.movement <= MAX_MOVE_COST, || format!("{at}.movement"), traits.movement, "0 (impassable) to 100")?;
    let y = traits.yields;
    for (name, v) in [("food", y.food), ("production", y.production), ("gold", y.gold)] {
        ensure(v.is_finite() && (0.0..=MAX_YIELD).contains(&v), || format!("{at}.yields.{name}"), v, "0 to 100")?;
    }
    Ok(())
}

fn check_look(at: &str, look: &Look) -> Result<(), ConfigError> {
    ensure(
        usize::from(look.texture) < MAX_TERRAINS,
        || format!("{at}.look.texture"),
        look.texture,
        "a texture layer, 0 to 31",
    )?;
    if let Some(p) = look.props {
        ensure((1..=MAX_PROPS_ON_TILE).contains(&p.count), || format!("{at}.look.props.count"), p.count, "1 to 12")?;
        ensure(
            p.size.is_finite() && p.size > 0.0 && p.size <= 1.0,
            || format!("{at}.look.props.size"),
            p.size,
            "(0, 1]",
        )?;
        ensure(
            p.chance.is_finite() && p.chance > 0.0 && p.chance <= 1.0,
            || format!("{at}.look.props.chance"),
            p.chance,
            "(0, 1]",
        )?;
    }
    Ok(())
}

/// The first pair of rules of different entries (of `entries`) that share a priority and could
/// both cover a tile; `shares` says whether two entries can meet on one tile at all.
fn clash<'a, T>(
    entries: &'a [T],
    rules: impl Fn(&'a T) -> &'a [Occurs],
    shares: impl Fn(usize, usize) -> bool,
) -> Option<(usize, usize, usize, usize)> {
    for (i, a) in entries.iter().enumerate() {
        for (j, b) in entries.iter().enumerate().skip(i + 1) {
            if !shares(i, j) {
                continue;
            }
            for (ka, ra) in rules(a).iter().enumerate() {
                for (kb, rb) in rules(b).iter().enumerate() {
                    if ra.priority == rb.priority && overlap(ra, rb) {
                        return Some((i, ka, j, kb));
                    }
                }
            }
        }
    }
    None
}

impl TerrainRuleset {
    /// Checks every entry, then that no two rules of different terrains (or of features that
    /// may sit on a common terrain) share a priority where both could cover a tile.
    ///
    /// # Errors
    /// The first value out of range, naming the entry and the field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let terrains = &self.terrains;
        ensure(
            !terrains.is_empty() && terrains.len() <= MAX_TERRAINS,
            || "ruleset.terrains".to_owned(),
            format!("{} terrains", terrains.len()),
            "1 to 32 terrains",
        )?;
        ensure(
            self.features.len() <= MAX_FEATURES,
            || "ruleset.features".to_owned(),
            format!("{} features", self.features.len()),
            "at most 16 features",
        )?;
        let mut seen = BTreeSet::new();
        for (i, t) in terrains.iter().enumerate() {
            let at = format!("ruleset.terrains[{i}] {:?}", t.id);
            ensure(id_ok(&t.id), || format!("{at}.id"), format!("{:?}", t.id), "lower-case letters, digits and _")?;
            ensure(
                seen.insert(t.id.as_str()),
                || format!("{at}.id"),
                format!("{:?}", t.id),
                "an id no other terrain has",
            )?;
            ensure(!t.name.is_empty(), || format!("{at}.name"), "\"\"", "a name")?;
            check_occurs(&at, &t.occurs)?;
            check_traits(&format!("{at}.traits"), &t.traits)?;
            if let Some(hills) = &t.hills {
                check_traits(&format!("{at}.hills"), hills)?;
            }
            check_look(&at, &t.look)?;
        }
        for landform in Landform::ALL {
            let field = || format!("ruleset.fallback.{landform:?}");
            match self.fallback.get(&landform) {
                None => return Err(fail(field(), "none", "a terrain for every landform")),
                Some(id) => ensure(self.terrain_id(id).is_some(), field, format!("{id:?}"), "the id of a terrain")?,
            }
        }
        let mut seen = BTreeSet::new();
        for (i, f) in self.features.iter().enumerate() {
            let at = format!("ruleset.features[{i}] {:?}", f.id);
            ensure(id_ok(&f.id), || format!("{at}.id"), format!("{:?}", f.id), "lower-case letters, digits and _")?;
            ensure(
                seen.insert(f.id.as_str()),
                || format!("{at}.id"),
                format!("{:?}", f.id),
                "an id no other feature has",
            )?;
            ensure(!f.name.is_empty(), || format!("{at}.name"), "\"\"", "a name")?;
            ensure(!f.on.is_empty(), || format!("{at}.on"), "[]", "at least one terrain id")?;
            for (k, id) in f.on.iter().enumerate() {
                ensure(
                    self.terrain_id(id).is_some(),
                    || format!("{at}.on[{k}]"),
                    format!("{id:?}"),
                    "the id of a terrain",
                )?;
            }
            ensure(!f.occurs.is_empty(), || format!("{at}.occurs"), "[]", "at least one rule")?;
            check_occurs(&at, &f.occurs)?;
            ensure(
                f.density.is_finite() && f.density > 0.0 && f.density <= 1.0,
                || format!("{at}.density"),
                f.density,
                "(0, 1]",
            )?;
            ensure(
                f.patch.is_finite() && (1.0..=MAX_PATCH).contains(&f.patch),
                || format!("{at}.patch"),
                f.patch,
                "1 to 64 tiles",
            )?;
            check_traits(&format!("{at}.traits"), &f.traits)?;
            check_look(&at, &f.look)?;
        }
        if let Some((i, ka, j, kb)) = clash(terrains, |t| &t.occurs, |_, _| true) {
            let (a, b) = (&terrains[i], &terrains[j]);
            return Err(fail(
                format!("ruleset.terrains[{j}] {:?}.occurs[{kb}].priority", b.id),
                b.occurs[kb].priority,
                format!(
                    "not {} where terrains[{i}] {:?}.occurs[{ka}] covers the same tiles",
                    a.occurs[ka].priority, a.id
                ),
            ));
        }
        let features = &self.features;
        let share = |i: usize, j: usize| features[i].on.iter().any(|t| features[j].on.contains(t));
        if let Some((i, ka, j, kb)) = clash(features, |f: &FeatureDef| &f.occurs, share) {
            let (a, b) = (&features[i], &features[j]);
            return Err(fail(
                format!("ruleset.features[{j}] {:?}.occurs[{kb}].priority", b.id),
                b.occurs[kb].priority,
                format!(
                    "not {} where features[{i}] {:?}.occurs[{ka}] covers the same tiles",
                    a.occurs[ka].priority, a.id
                ),
            ));
        }
        Ok(())
    }
}
