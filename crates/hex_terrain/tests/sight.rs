//! Field of view over random maps (bounded, wrapping, unbounded) and sight rules, against the
//! rule computed here from the tiles' types and biomes and hexx's lines, tile by tile.

use std::collections::BTreeSet;

use hex_terrain::hexx::Hex;
use hex_terrain::{
    Biome, FogError, FogOfWar, MAX_UNBOUNDED_SIGHT, MapConfig, MapSize, NoiseConfig, SightConfig, SightError, Terrain,
    TileKind,
};
use proptest::prelude::*;

#[path = "common/biome.rs"]
mod biome;
mod common;

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        (x, z) in (6u32..30, 6u32..20),
        unbounded in prop::bool::weighted(0.2),
        scale in 3.0f64..15.0,
        climate in any::<bool>(),
        wrap in any::<bool>(),
        tall in prop::collection::btree_set(0usize..13, 0..5),
        (tall_bonus, mountain_bonus) in (0u32..3, 0u32..4),
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: if unbounded { MapSize::Unbounded } else { MapSize::Bounded { x, z } },
            noise: NoiseConfig { scale, ..NoiseConfig::default() },
            chunk_size: (8, 8),
            sight: SightConfig { tall: tall.into_iter().map(|b| Biome::ALL[b]).collect(), tall_bonus, mountain_bonus },
            ..MapConfig::default()
        };
        c.terrain.mountain_threshold = 0.55;
        c.climate.enabled = climate;
        common::wrapping(c, wrap && !unbounded)
    }
}

/// A tile's height for sight, from its type and biome and the config's tall biomes.
fn height(t: &Terrain, tile: Hex) -> Option<u8> {
    let own = t.wrap_tile(tile)?;
    let info = t.tile_info(own)?;
    Some(if info.kind == TileKind::Mountain && info.lake.is_none() {
        2
    } else {
        u8::from(t.config().sight.tall.contains(&biome::of(t, &info)))
    })
}

/// The copy of `tile` a viewer on `from` looks at: the nearest, the western one (the lower
/// column) of two equally near; the tile itself on a map that does not wrap.
fn nearest_copy(t: &Terrain, tile: Hex, from: Hex) -> Hex {
    let Some(wrap) = t.wrap() else { return tile };
    (-2..=2)
        .map(|k| tile + wrap.tile_shift * k)
        .min_by_key(|&c| (from.unsigned_distance_to(c), t.offset_of(c)[0]))
        .unwrap()
}

/// The field of view by the rule, tile by tile; `reach` is the radius plus the viewer's bonus.
fn expected_view(t: &Terrain, from: Hex, reach: u32) -> BTreeSet<[i32; 2]> {
    let own = height(t, from).unwrap();
    let mut heights = std::collections::HashMap::new();
    let mut height_at = |h: Hex| *heights.entry(h).or_insert_with(|| height(t, h));
    // Every candidate: the map's tiles (a disc around the viewer on an unbounded world).
    let candidates: Vec<Hex> = match t.bounds() {
        Some(_) => t.tiles().collect(),
        None => from.range(reach + 2).collect(),
    };
    let mut expected = BTreeSet::new();
    for tile in candidates {
        let near = nearest_copy(t, tile, from);
        if from.unsigned_distance_to(near) > reach {
            continue;
        }
        // hexx's line, drawn with the viewer at the origin (where it lies on the map does not
        // change what it sees); a tile off the map blocks nothing.
        let line: Vec<Hex> = Hex::ZERO.line_to(near - from).map(|h| from + h).collect();
        let inner = &line[1..line.len().saturating_sub(1).max(1)];
        let blocked = inner.iter().any(|&h| height_at(h).is_some_and(|hh| hh > own || hh == 2));
        if !blocked {
            expected.insert(t.offset_of(tile));
        }
    }
    expected
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Any radius: small ones, ones past the map, and the largest numbers (no overflow, in the
    /// overflow-checked build too); an unbounded world refuses a reach past its limit by name.
    #[test]
    fn the_field_of_view_follows_the_rule(
        config in config(),
        (col, row) in (0i32..30, 0i32..20),
        radius in prop_oneof![4 => 0u32..5, 1 => 5u32..70, 1 => Just(u32::MAX), 1 => u32::MAX - 9..=u32::MAX],
    ) {
        let t = Terrain::new(config).unwrap();
        let from = t.tile_from_offset([col, row]);
        let seen = t.field_of_view(from, radius);
        let Some(from) = t.wrap_tile(from) else {
            prop_assert_eq!(seen, Ok(Vec::new()));
            return Ok(());
        };
        let own = height(&t, from).unwrap();
        let sight = &t.config().sight;
        let bonus = [0, sight.tall_bonus, sight.mountain_bonus][own as usize];
        let reach = radius.saturating_add(bonus);
        if t.bounds().is_none() && reach > MAX_UNBOUNDED_SIGHT {
            prop_assert_eq!(seen, Err(SightError { radius, reach }));
            let error = t.field_of_view(from, radius).unwrap_err().to_string();
            prop_assert!(error.contains(&radius.to_string()) && error.contains("64"), "{}", error);
            return Ok(());
        }
        let seen = seen.unwrap();
        let expected = expected_view(&t, from, reach);
        let got: BTreeSet<[i32; 2]> = seen.iter().map(|&h| t.offset_of(h)).collect();
        prop_assert_eq!(got.len(), seen.len(), "each tile once");
        prop_assert_eq!(&got, &expected);
        prop_assert!(seen.contains(&from), "the viewer's tile");
        prop_assert!(seen.iter().all(|&h| t.contains(h)), "tiles of the map");
        prop_assert_eq!(t.field_of_view(from, radius), Ok(seen.clone()), "the same view again");
        if t.bounds().is_some() {
            // The limit is the largest radius that can matter: past it, every tile the rule sees.
            let all = t.field_of_view(from, u32::MAX).unwrap();
            prop_assert_eq!(&t.field_of_view(from, t.sight_limit()).unwrap(), &all);
            let all: BTreeSet<[i32; 2]> = all.iter().map(|&h| t.offset_of(h)).collect();
            prop_assert_eq!(all, expected_view(&t, from, u32::MAX));
            // Radii past the lines drawn once and short of the limit.
            for mid in [13, t.sight_limit() / 3, t.sight_limit() / 2] {
                let seen: BTreeSet<[i32; 2]> = t.field_of_view(from, mid).unwrap().iter().map(|&h| t.offset_of(h)).collect();
                prop_assert_eq!(seen, expected_view(&t, from, mid.saturating_add(bonus)), "radius {}", mid);
            }
        }
    }
}

/// A line of sight that leaves a bounded map past its ragged edge: the tiles off the map on it
/// block nothing. On a map of mountains, where every tile on a line blocks, a tile two steps
/// away is seen exactly when the tile between is off the map.
#[test]
fn tiles_off_the_map_block_no_view() {
    for orientation in ["Pointy", "Flat"] {
        let config = MapConfig::from_ron(&format!(
            "(size: Bounded(x: 9, z: 9), layout: (orientation: {orientation}), \
             terrain: (sea_threshold: 0.0001, mountain_threshold: 0.0002, interpolation_tolerance: 0.0))"
        ))
        .unwrap();
        let t = Terrain::new(config).unwrap();
        assert!(t.tiles().all(|h| t.sight_height(h) == Some(2)), "a map of mountains");
        let mut off_map_lines = 0;
        for from in t.tiles() {
            let seen = t.field_of_view(from, 2).unwrap();
            for to in t.tiles().filter(|&to| from.unsigned_distance_to(to) == 2) {
                let between = Hex::ZERO.line_to(to - from).nth(1).map(|h| from + h).unwrap();
                off_map_lines += usize::from(!t.contains(between));
                assert_eq!(seen.contains(&to), !t.contains(between), "{orientation}: {from:?} -> {to:?}");
            }
        }
        assert!(off_map_lines > 0, "{orientation}: no line leaves the map");
    }
}

/// A lake on a mountain tile is water for sight, not a mountain: it neither blocks as one nor
/// lifts a viewer as one.
#[test]
fn a_lake_on_a_mountain_is_no_mountain_for_sight() {
    let mut found = 0;
    for seed in 0..40 {
        let config = MapConfig::from_ron(&format!(
            "(seed: {seed}, size: Bounded(x: 40, z: 24), terrain: (mountain_threshold: 0.5), \
             rivers: (enabled: true, min_lake_depth: 0.0))"
        ))
        .unwrap();
        let t = Terrain::new(config).unwrap();
        for tile in t.tiles() {
            let info = t.tile_info(tile).unwrap();
            if info.kind == TileKind::Mountain && info.lake.is_some() {
                found += 1;
                assert_eq!(t.sight_height(tile), Some(u8::from(t.config().sight.tall.contains(&biome::of(&t, &info)))));
                assert_ne!(t.sight_height(tile), Some(2));
            }
        }
        if found >= 3 {
            break;
        }
    }
    assert!(found > 0, "no lake on a mountain tile in 40 seeds");
}

/// On a wrapping map of even width a tile half way round is as near to the east as to the west:
/// the viewer looks at it through its western copy (the lower column), once.
#[test]
fn of_two_copies_equally_near_the_western_one_is_looked_at() {
    let config = MapConfig::from_ron(
        "(size: Bounded(x: 8, z: 5), wrap: true, \
         terrain: (sea_threshold: 0.0001, mountain_threshold: 0.9999, interpolation_tolerance: 0.0), \
         sight: (tall: []))",
    )
    .unwrap();
    let t = Terrain::new(config).unwrap();
    let from = t.tile_from_offset([0, 2]);
    let across = t.tile_from_offset([4, 2]);
    let wrap = t.wrap().unwrap();
    let (west, east) = (across - wrap.tile_shift, across);
    assert_eq!(from.unsigned_distance_to(west), from.unsigned_distance_to(east), "equally near");
    assert_eq!(t.tile_near(across, from), west);
    let seen = t.field_of_view(from, 4).unwrap();
    assert_eq!(seen.iter().filter(|&&h| h == across).count(), 1, "seen once");
}

/// The largest radius that matters: the map's columns plus rows on a bounded map, and a larger
/// one sees the same tiles; an unbounded world's limit is `MAX_UNBOUNDED_SIGHT`, past which the
/// fog refuses the unit by name and stays as it was.
#[test]
fn the_sight_limit() {
    let bounded = Terrain::new(MapConfig::from_ron("(size: Bounded(x: 20, z: 12))").unwrap()).unwrap();
    assert_eq!(bounded.sight_limit(), 32);
    let from = bounded.tile_from_offset([3, 4]);
    let whole = bounded.field_of_view(from, 32).unwrap();
    for radius in [33, 1_000, 40_000, 1 << 31, u32::MAX] {
        assert_eq!(bounded.field_of_view(from, radius).unwrap(), whole, "radius {radius}");
    }
    let mut fog = FogOfWar::new(&bounded, 1).unwrap();
    fog.update(&bounded, 0, [(from, u32::MAX)]).unwrap();
    assert_eq!(fog.visible(0).collect::<Vec<_>>(), whole);

    let world = Terrain::new(MapConfig::from_ron("(size: Unbounded)").unwrap()).unwrap();
    assert_eq!(world.sight_limit(), MAX_UNBOUNDED_SIGHT);
    let here = world.tile_from_offset([0, 0]);
    assert!(world.field_of_view(here, MAX_UNBOUNDED_SIGHT - 8).is_ok());
    let mut fog = FogOfWar::new(&world, 1).unwrap();
    fog.update(&world, 0, [(here, 2)]).unwrap();
    let before = fog.clone();
    let e = fog.update(&world, 0, [(here, 3), (here, 40_000)]).unwrap_err();
    assert!(matches!(e, FogError::Sight { error: SightError { radius: 40_000, .. }, .. }), "{e}");
    assert!(e.to_string().contains("40000"), "{e}");
    assert_eq!(fog, before, "the fog is unchanged");
}

#[test]
fn a_mountain_blocks_and_a_hill_sees_over_a_forest() {
    // A flat map of plains; along two hex directions from a hill: plains, a forest, plains; and
    // plains, a mountain, plains.
    let plain = "size: Bounded(x: 14, z: 14), climate: (enabled: true), \
                 terrain: (sea_threshold: 0.0001, mountain_threshold: 0.9999, interpolation_tolerance: 0.0)";
    let base = Terrain::new(MapConfig::from_ron(&format!("({plain})")).unwrap()).unwrap();
    let hill = base.tile_from_offset([6, 6]);
    let (east, south) = (Hex::new(1, 0), Hex::new(0, 1));
    let at = |h: Hex| {
        let [c, r] = base.offset_of(h);
        format!("({c}, {r})")
    };
    let mut edits = vec![format!("(at: {}, biome: Some(Hills))", at(hill))];
    for k in [1, 3] {
        edits.push(format!("(at: {}, biome: Some(Plains))", at(hill + east * k)));
        edits.push(format!("(at: {}, biome: Some(Plains))", at(hill + south * k)));
    }
    edits.push(format!("(at: {}, biome: Some(Forest))", at(hill + east * 2)));
    edits.push(format!("(at: {}, kind: Some(Mountain))", at(hill + south * 2)));
    let config =
        MapConfig::from_ron(&format!("({plain}, sight: (tall_bonus: 0), edits: [{}])", edits.join(", "))).unwrap();
    let t = Terrain::new(config).unwrap();
    assert_eq!(t.sight_height(hill), Some(1));
    assert_eq!(t.sight_height(hill + east), Some(0));
    assert_eq!(t.sight_height(hill + east * 2), Some(1));
    assert_eq!(t.sight_height(hill + south * 2), Some(2));
    let sees = |from: Hex, to: Hex| t.field_of_view(from, 4).unwrap().contains(&to);
    assert!(!sees(hill + east, hill + east * 3), "a forest hides what is behind it from flat land");
    assert!(sees(hill, hill + east * 3), "a hill sees over a forest");
    assert!(!sees(hill + south, hill + south * 3), "a mountain hides what is behind it");
    assert!(!sees(hill, hill + south * 3), "from a hill too");
    assert!(sees(hill + south, hill + south * 2), "the mountain itself is seen");
}
