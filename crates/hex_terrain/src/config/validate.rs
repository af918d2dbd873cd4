//! Validation: every field of a [`MapConfig`] against its allowed range, and the limits that
//! keep any accepted config from taking minutes or gigabytes.

use super::check::{check, finite_in};
use super::{
    HeightSourceConfig, MAX_MOUNTAIN_SHARE, MAX_MOVE_COST, MAX_SIGHT_BONUS, MapConfig, MapSize, NoiseConfig,
    Orientation, Shape, SightConfig,
};
use crate::error::ConfigError;

/// Largest number of octaves accepted.
pub const MAX_OCTAVES: u32 = 32;
/// Largest number of inner rings accepted.
pub const MAX_INNER_RINGS: u32 = 16;
/// Largest absolute tile offset accepted.
pub const MAX_OFFSET: i32 = 1_000_000;
/// Fewest columns of a wrapping map.
pub const MIN_WRAP_COLUMNS: u32 = 4;
/// Largest absolute tile column or row of an unbounded world: lattice coordinates stay within
/// `i32` for every ring count. Chunks beyond it do not exist.
pub const MAX_WORLD_TILE: i32 = 1 << 24;
/// Fewest columns and rows of a map with a map type.
pub const MIN_MAP_TYPE_SIDE: u32 = 8;

/// Smallest globe frequency a map type arranges (162 tiles).
pub const MIN_MAP_TYPE_FREQUENCY: u32 = 4;
/// Largest chunk side, in tiles.
pub const MAX_CHUNK_SIDE: u32 = 512;
/// Largest estimated size of one chunk's mesh, in bytes: a chunk is generated on one thread
/// while a game runs, so this keeps one chunk well under a second.
pub const MAX_CHUNK_BYTES: u64 = 256 << 20;
/// Largest estimated size of a whole bounded map's mesh, in bytes.
pub const MAX_MAP_BYTES: u64 = 12 << 30;
/// Bytes a mesh vertex and its share of the index buffer take, about.
const BYTES_PER_VERTEX: u64 = 3 * 4 + 3 * 4 + 2 * 4 + 4 + 4 + 2 * 3 * 4;

impl MapConfig {
    /// Checks every field against its allowed range (a game setup's fit to the generated map is
    /// checked when it is compiled, by [`Terrain::new`](crate::Terrain::new)).
    ///
    /// # Errors
    /// The first invalid field, with its value and the allowed range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_noise("noise", &self.noise)?;
        if let Some(path) = &self.ruleset {
            check(path.ends_with(".terrain.ron"), "ruleset", format!("{path:?}"), "the path of a *.terrain.ron file")?;
            // One way to say what a tile costs, hides and yields: the ruleset's traits.
            let ruled = "none: a map with its own terrain ruleset takes it from the ruleset's traits";
            check(self.movement.costs.is_empty(), "movement.costs", format!("{:?}", self.movement.costs), ruled)?;
            check(
                self.sight.tall == SightConfig::default().tall,
                "sight.tall",
                format!("{:?}", self.sight.tall),
                "the default: a map with its own terrain ruleset takes it from the ruleset's traits",
            )?;
            if let Some(setup) = &self.setup {
                check(
                    setup.yields.biomes.is_empty(),
                    "setup.yields.biomes",
                    format!("{:?}", setup.yields.biomes),
                    ruled,
                )?;
            }
        }

        let t = &self.terrain;
        check(finite_in(f64::from(t.max_elevation), 0.0, 1e6), "terrain.max_elevation", t.max_elevation, "[0, 1e6]")?;
        check(finite_in(f64::from(t.sea_threshold), 0.0, 1.0), "terrain.sea_threshold", t.sea_threshold, "[0, 1]")?;
        check(
            finite_in(f64::from(t.mountain_threshold), 0.0, 1.0),
            "terrain.mountain_threshold",
            t.mountain_threshold,
            "[0, 1]",
        )?;
        check(
            t.sea_threshold < t.mountain_threshold,
            "terrain.sea_threshold",
            t.sea_threshold,
            format!("below terrain.mountain_threshold ({})", t.mountain_threshold),
        )?;
        let max_tol =
            t.sea_threshold.min(1.0 - t.mountain_threshold).min((t.mountain_threshold - t.sea_threshold) / 2.0);
        check(
            t.interpolation_tolerance.is_finite()
                && t.interpolation_tolerance >= 0.0
                && (t.interpolation_tolerance < max_tol || t.interpolation_tolerance == 0.0),
            "terrain.interpolation_tolerance",
            t.interpolation_tolerance,
            format!("[0, {max_tol}) (below the sea threshold, 1 - the mountain threshold and half the land range)"),
        )?;
        check(
            (1..=MAX_INNER_RINGS).contains(&t.inner_rings),
            "terrain.inner_rings",
            t.inner_rings,
            format!("1..={MAX_INNER_RINGS}"),
        )?;

        let l = &self.layout;
        check(
            l.hex_size.is_finite() && l.hex_size > 0.0 && l.hex_size <= 1e4,
            "layout.hex_size",
            l.hex_size,
            "(0, 1e4]",
        )?;
        check(
            (1..=MAX_CHUNK_SIDE).contains(&self.chunk_size.0) && (1..=MAX_CHUNK_SIDE).contains(&self.chunk_size.1),
            "chunk_size",
            format!("{:?}", self.chunk_size),
            format!("each side in 1..={MAX_CHUNK_SIDE}"),
        )?;
        let per_hex = 3 * u64::from(self.subdivisions()).pow(2);
        let chunk_bytes = u64::from(self.chunk_size.0) * u64::from(self.chunk_size.1) * per_hex * BYTES_PER_VERTEX;
        check(
            chunk_bytes <= MAX_CHUNK_BYTES,
            "chunk_size",
            format!(
                "{:?} ({} MiB of mesh a chunk with {} inner rings)",
                self.chunk_size,
                chunk_bytes >> 20,
                t.inner_rings
            ),
            format!("a chunk mesh of at most {} MiB: fewer tiles a chunk or fewer inner rings", MAX_CHUNK_BYTES >> 20),
        )?;
        check(
            self.offset.0.unsigned_abs() <= MAX_OFFSET as u32 && self.offset.1.unsigned_abs() <= MAX_OFFSET as u32,
            "offset",
            format!("{:?}", self.offset),
            format!("each in -{MAX_OFFSET}..={MAX_OFFSET}"),
        )?;
        let r = &self.relief;
        for (value, field) in [(r.peaks, "relief.peaks"), (r.ridges, "relief.ridges"), (r.hills, "relief.hills")] {
            check(finite_in(f64::from(value), 0.0, 1.0), field, value, "[0, 1]")?;
        }
        check(
            finite_in(f64::from(self.appearance.blend), 0.0, 1.0),
            "appearance.blend",
            self.appearance.blend,
            "[0, 1]",
        )?;

        if let HeightSourceConfig::Image { sea_level, path } = &self.source {
            check(finite_in(f64::from(*sea_level), 0.0, 1.0), "source.sea_level", sea_level, "[0, 1]")?;
            check(!path.is_empty(), "source.path", "\"\"", "the path of a PNG heightmap")?;
            check(
                self.size != MapSize::Unbounded,
                "source",
                "Image on an Unbounded map",
                "Noise for an Unbounded map (an image covers a bounded map)",
            )?;
        }

        match self.size {
            MapSize::Bounded { x, z } => {
                check(x >= 1 && z >= 1, "size", format!("{x}x{z}"), "at least 1x1 hexes")?;
                check(
                    x <= 2 * MAX_OFFSET as u32 && z <= 2 * MAX_OFFSET as u32,
                    "size",
                    format!("{x}x{z}"),
                    format!("at most {0}x{0} hexes", 2 * MAX_OFFSET),
                )?;
                let bytes = u64::from(x) * u64::from(z) * per_hex * BYTES_PER_VERTEX;
                check(
                    bytes <= MAX_MAP_BYTES,
                    "size",
                    format!("{x}x{z} ({} GiB of mesh with {} inner rings)", bytes >> 30, t.inner_rings),
                    format!(
                        "a mesh of at most {} GiB; use Unbounded and chunks for larger worlds",
                        MAX_MAP_BYTES >> 30
                    ),
                )?;
            }
            MapSize::Globe { frequency } => self.validate_globe(frequency, per_hex)?,
            MapSize::Unbounded => {
                check(
                    !self.wrap,
                    "wrap",
                    "true on an Unbounded map",
                    "false for an Unbounded map (only a bounded map wraps: an unbounded one has no edge)",
                )?;
                check(
                    self.shape == Shape::None,
                    "shape",
                    format!("{:?}", self.shape),
                    "None for an Unbounded map (shapes need the map's bounds)",
                )?;
            }
        }

        if let (true, MapSize::Bounded { x, .. }) = (self.wrap, self.size) {
            check(
                x >= MIN_WRAP_COLUMNS,
                "size.x",
                x,
                format!("at least {MIN_WRAP_COLUMNS} columns on a wrapping map"),
            )?;
            check(
                self.layout.orientation == Orientation::Pointy || x % 2 == 0,
                "size.x",
                x,
                "an even number of columns on a wrapping map of flat tiles (odd columns are shoved half a \
                 tile: an odd width would not join its first column)",
            )?;
            check(
                self.shape != Shape::Gradient,
                "shape",
                "Gradient on a wrapping map",
                "None, Island, Mediterranean or Inland on a wrapping map (the gradient rises from the west \
                 edge, which a wrapping map does not have)",
            )?;
        }

        if let Some(map_type) = &self.map_type {
            match (self.size, self.size.bounds()) {
                (MapSize::Globe { frequency }, _) => check(
                    frequency >= MIN_MAP_TYPE_FREQUENCY,
                    "size.Globe.frequency",
                    frequency,
                    format!("at least {MIN_MAP_TYPE_FREQUENCY} with a map type"),
                )?,
                (_, Some((x, z))) => check(
                    x >= MIN_MAP_TYPE_SIDE && z >= MIN_MAP_TYPE_SIDE,
                    "size",
                    format!("{x}x{z}"),
                    format!("at least {MIN_MAP_TYPE_SIDE}x{MIN_MAP_TYPE_SIDE} hexes with a map type"),
                )?,
                (_, None) => {
                    return Err(ConfigError::new(
                        "map_type",
                        format!("{:?} on an Unbounded map", map_type.kind),
                        "None for an Unbounded map (a map type arranges a bounded map's land and sea; an \
                         unbounded world keeps the thesis' shapes)"
                            .into(),
                    ));
                }
            }
            check(
                self.shape == Shape::None,
                "shape",
                format!("{:?} with a map type", self.shape),
                "None with a map type (the type shapes the land in its place)",
            )?;
            check(
                self.source == HeightSourceConfig::Noise,
                "source",
                "Image with a map type",
                "Noise with a map type (a heightmap has its land and sea already)",
            )?;
            check(
                finite_in(f64::from(map_type.mountains), 0.0, f64::from(MAX_MOUNTAIN_SHARE)),
                "map_type.mountains",
                map_type.mountains,
                format!("[0, {MAX_MOUNTAIN_SHARE}]"),
            )?;
        }

        match self.shape {
            Shape::None | Shape::Gradient => {}
            Shape::Island { a, b } | Shape::Mediterranean { a, b } => {
                check(finite_in(f64::from(a), 1e-3, 100.0), "shape.a", a, "[0.001, 100]")?;
                check(finite_in(f64::from(b), 1e-3, 100.0), "shape.b", b, "[0.001, 100]")?;
            }
            Shape::Inland { min, max } => {
                check(finite_in(f64::from(min), 0.0, 1.0), "shape.min", min, "[0, 1]")?;
                check(finite_in(f64::from(max), 0.0, 1.0) && max > min, "shape.max", max, format!("({min}, 1]"))?;
            }
        }
        self.validate_climate()?;
        let m = &self.movement;
        for (biome, &c) in &m.costs {
            let range = format!("0..={MAX_MOVE_COST} (0: impassable)");
            check(c <= MAX_MOVE_COST, &format!("movement.costs.{}", biome.name()), c, range)?;
        }
        check(m.river <= MAX_MOVE_COST, "movement.river", m.river, format!("0..={MAX_MOVE_COST}"))?;
        if let Some(embark) = m.embark {
            check((1..=MAX_MOVE_COST).contains(&embark), "movement.embark", embark, format!("1..={MAX_MOVE_COST}"))?;
        }
        let s = &self.sight;
        for (field, bonus) in [("sight.tall_bonus", s.tall_bonus), ("sight.mountain_bonus", s.mountain_bonus)] {
            check(bonus <= MAX_SIGHT_BONUS, field, bonus, format!("0..={MAX_SIGHT_BONUS}"))?;
        }
        if let Some(setup) = &self.setup {
            // A globe's setup covers it whole (its `area` is refused above): its tiles count as
            // one row for the setup's limit on tiles.
            let bounds = match self.size {
                MapSize::Globe { frequency } => Some((10 * frequency * frequency + 2, 1)),
                _ => self.size.bounds(),
            };
            setup.validate(bounds)?;
        }
        super::edits::validate(&self.edits, self.size, self.terrain.sea_threshold, &self.rivers, self.ruleset.is_some())
    }
}

impl MapConfig {
    /// A globe's own checks: its frequency and mesh size, and the parts of a flat map a globe
    /// does not have (an edge to wrap, a shape or map type drawn on the map's rectangle, a
    /// heightmap, a setup's area) or has not yet (winds, rivers, ranges, a ruleset).
    fn validate_globe(&self, frequency: u32, per_hex: u64) -> Result<(), ConfigError> {
        let max = crate::MAX_GLOBE_FREQUENCY;
        check((1..=max).contains(&frequency), "size.Globe.frequency", frequency, format!("1..={max}"))?;
        let tiles = 10 * u64::from(frequency).pow(2);
        let bytes = tiles * per_hex * BYTES_PER_VERTEX;
        check(
            bytes <= MAX_MAP_BYTES,
            "size.Globe.frequency",
            format!("{frequency} ({} GiB of mesh with {} inner rings)", bytes >> 30, self.terrain.inner_rings),
            format!("a globe mesh of at most {} GiB: a lower frequency or fewer inner rings", MAX_MAP_BYTES >> 30),
        )?;
        check(!self.wrap, "wrap", "true on a globe", "false on a globe (a globe has no edge to wrap)")?;
        check(self.offset == (0, 0), "offset", format!("{:?} on a globe", self.offset), "(0, 0) on a globe")?;
        check(
            self.source == HeightSourceConfig::Noise,
            "source",
            "Image on a globe",
            "Noise on a globe (its heights are 3D noise at each point's direction)",
        )?;
        check(
            self.shape == Shape::None,
            "shape",
            format!("{:?} on a globe", self.shape),
            "None on a globe (shapes are drawn on a flat map's rectangle)",
        )?;
        let not_yet = |part: &str| format!("none on a globe: {part} are not on globes yet");
        check(
            self.map_type.as_ref().is_none_or(|t| !t.ranges),
            "map_type.ranges",
            true,
            "false on a globe: mountain ranges are not on globes yet",
        )?;
        check(
            self.climate.winds.is_none(),
            "climate.winds",
            "winds on a globe",
            "None on a globe: winds are not on globes yet",
        )?;
        check(
            self.climate.latitudes == (1.0, -1.0),
            "climate.latitudes",
            format!("{:?} on a globe", self.climate.latitudes),
            "(1, -1) on a globe (its latitudes come from its axis)",
        )?;
        check(!self.rivers.enabled, "rivers.enabled", true, "false on a globe: rivers are not on globes yet")?;
        check(self.ruleset.is_none(), "ruleset", format!("{:?}", self.ruleset), not_yet("terrain rulesets"))?;
        let area = self.setup.as_ref().and_then(|s| s.area);
        check(
            area.is_none(),
            "setup.area",
            format!("{area:?} on a globe"),
            "None on a globe (its setup covers the whole globe)",
        )
    }
}

/// Checks fBm parameters; `prefix` names the field (`noise`, `climate.moisture`).
pub(super) fn check_noise(prefix: &str, n: &NoiseConfig) -> Result<(), ConfigError> {
    let field = |name: &str| format!("{prefix}.{name}");
    check((1..=MAX_OCTAVES).contains(&n.octaves), &field("octaves"), n.octaves, format!("1..={MAX_OCTAVES}"))?;
    check(
        n.persistence.is_finite() && n.persistence > 0.0 && n.persistence <= 1.0,
        &field("persistence"),
        n.persistence,
        "(0, 1]",
    )?;
    check(finite_in(n.lacunarity, 1.0, 64.0), &field("lacunarity"), n.lacunarity, "[1, 64]")?;
    check(n.scale.is_finite() && n.scale > 0.0 && n.scale <= 1e9, &field("scale"), n.scale, "(0, 1e9]")
}
