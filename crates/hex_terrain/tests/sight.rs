//! Field of view over random maps (bounded, wrapping, unbounded) and sight rules, against the
//! rule computed here from the tiles' types and biomes and hexx's lines, tile by tile.

use std::collections::BTreeSet;

use hex_terrain::hexx::Hex;
use hex_terrain::{Biome, MapConfig, MapSize, NoiseConfig, SightConfig, Terrain, TileKind};
use proptest::prelude::*;

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
        u8::from(t.config().sight.tall.contains(&info.biome))
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn the_field_of_view_follows_the_rule(config in config(), (col, row) in (0i32..30, 0i32..20), radius in 0u32..5) {
        let t = Terrain::new(config).unwrap();
        let from = t.tile_from_offset([col, row]);
        let seen = t.field_of_view(from, radius);
        let Some(from) = t.wrap_tile(from) else {
            prop_assert!(seen.is_empty());
            return Ok(());
        };
        let own = height(&t, from).unwrap();
        let sight = &t.config().sight;
        let reach = radius + [0, sight.tall_bonus, sight.mountain_bonus][own as usize];
        // Every candidate: the map's tiles (a disc around the viewer on an unbounded world).
        let candidates: Vec<Hex> = match t.bounds() {
            Some(_) => t.tiles().collect(),
            None => from.range(reach + 2).collect(),
        };
        let mut expected = BTreeSet::new();
        for tile in candidates {
            let near = t.tile_near(tile, from);
            if from.unsigned_distance_to(near) > reach {
                continue;
            }
            // hexx's line, drawn with the viewer at the origin (where it lies on the map does not
            // change what it sees).
            let line: Vec<Hex> = Hex::ZERO.line_to(near - from).map(|h| from + h).collect();
            let inner = &line[1..line.len().saturating_sub(1).max(1)];
            let blocked = inner.iter().any(|&h| height(&t, h).is_some_and(|hh| hh > own || hh == 2));
            if !blocked {
                expected.insert(t.offset_of(tile));
            }
        }
        let got: BTreeSet<[i32; 2]> = seen.iter().map(|&h| t.offset_of(h)).collect();
        prop_assert_eq!(got.len(), seen.len(), "each tile once");
        prop_assert_eq!(&got, &expected);
        prop_assert!(seen.contains(&from), "the viewer's tile");
        prop_assert!(seen.iter().all(|&h| t.contains(h)), "tiles of the map");
        prop_assert_eq!(t.field_of_view(from, radius), seen, "the same view again");
    }
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
    let sees = |from: Hex, to: Hex| t.field_of_view(from, 4).contains(&to);
    assert!(!sees(hill + east, hill + east * 3), "a forest hides what is behind it from flat land");
    assert!(sees(hill, hill + east * 3), "a hill sees over a forest");
    assert!(!sees(hill + south, hill + south * 3), "a mountain hides what is behind it");
    assert!(!sees(hill, hill + south * 3), "from a hill too");
    assert!(sees(hill + south, hill + south * 2), "the mountain itself is seen");
}
