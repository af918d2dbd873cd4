//! Every player's fog over random maps (bounded, wrapping, unbounded, edited) and random turns,
//! against a model kept here: after a player's turn its visible tiles are the union of its
//! units' fields of view, its explored tiles every tile seen before and not now, and the other
//! players' fog is unchanged. Saves round-trip and refuse damaged, foreign and impossible
//! files; the fog is the same whatever thread or order the players' turns run in.

use std::collections::{BTreeMap, BTreeSet};

use hex_terrain::hexx::Hex;
use hex_terrain::{
    FogError, FogOfWar, FogState, MAX_OWNERS, MapConfig, MapSize, NoiseConfig, SaveError, Terrain, TileEdit, TileKind,
};
use proptest::prelude::*;

mod common;

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        (x, z) in (6u32..28, 6u32..18),
        unbounded in prop::bool::weighted(0.2),
        scale in 3.0f64..15.0,
        climate in any::<bool>(),
        wrap in any::<bool>(),
        edits in prop::collection::btree_map((0i32..6, 0i32..6), 0usize..3, 0..6),
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: if unbounded { MapSize::Unbounded } else { MapSize::Bounded { x, z } },
            noise: NoiseConfig { scale, ..NoiseConfig::default() },
            chunk_size: (8, 8),
            ..MapConfig::default()
        };
        c.terrain.mountain_threshold = 0.55;
        c.climate.enabled = climate;
        if !unbounded {
            c.edits = edits
                .into_iter()
                .map(|((col, row), k)| TileEdit { kind: Some(TileKind::ALL[k]), ..TileEdit::at((col, row)) })
                .collect();
        }
        common::wrapping(c, wrap && !unbounded)
    }
}

/// A turn: each player's units as `(column, row, sight)`.
type Turn = Vec<Vec<(i32, i32, u32)>>;

fn turns() -> impl Strategy<Value = (u32, Vec<Turn>)> {
    (1u32..4).prop_flat_map(|players| {
        let units = prop::collection::vec((-2i32..32, -2i32..22, 0u32..4), 0..4);
        let turn = prop::collection::vec(units, players as usize);
        (Just(players), prop::collection::vec(turn, 1..5))
    })
}

/// The tiles `player` has seen with their states, as the model has them.
type Model = Vec<BTreeMap<(i32, i32), FogState>>;

fn key(t: &Terrain, tile: Hex) -> (i32, i32) {
    let [col, row] = t.offset_of(t.wrap_tile(tile).expect("a map tile"));
    (col, row)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn each_players_fog_is_its_units_view_and_explored_never_shrinks(config in config(), (players, turns) in turns()) {
        let t = Terrain::new(config).unwrap();
        let mut fog = FogOfWar::new(&t, players).unwrap();
        let mut model: Model = vec![BTreeMap::new(); players as usize];
        for turn in &turns {
            for (player, units) in turn.iter().enumerate() {
                let before: Vec<Vec<(Hex, FogState)>> = (0..players).map(|p| fog.seen(p).collect()).collect();
                let units: Vec<(Hex, u32)> =
                    units.iter().map(|&(c, r, s)| (t.tile_from_offset([c, r]), s)).collect();
                fog.update(&t, player as u32, units.iter().copied()).unwrap();
                // The model: what was visible is explored, then the union of the views.
                let view = &mut model[player];
                for state in view.values_mut() {
                    *state = FogState::Explored;
                }
                let visible: BTreeSet<(i32, i32)> =
                    units.iter().flat_map(|&(u, s)| t.field_of_view(u, s).unwrap()).map(|h| key(&t, h)).collect();
                for &at in &visible {
                    view.insert(at, FogState::Visible);
                }
                let seen: BTreeMap<(i32, i32), FogState> =
                    fog.seen(player as u32).map(|(h, s)| (key(&t, h), s)).collect();
                prop_assert_eq!(&seen, &*view);
                let now: BTreeSet<(i32, i32)> = fog.visible(player as u32).map(|h| key(&t, h)).collect();
                prop_assert_eq!(&now, &visible);
                for (&(c, r), &state) in view.iter() {
                    prop_assert_eq!(fog.state(player as u32, t.tile_from_offset([c, r])), Some(state));
                }
                // Explored never shrinks, and the other players' fog did not move.
                for (tile, _) in &before[player] {
                    prop_assert_ne!(fog.state(player as u32, *tile), Some(FogState::Unexplored));
                }
                for p in (0..players).filter(|&p| p as usize != player) {
                    prop_assert_eq!(&fog.seen(p).collect::<Vec<_>>(), &before[p as usize]);
                }
            }
        }
        // A copy of a tile a period east answers for it on a wrapping map.
        if let Some(w) = t.wrap() {
            for (tile, state) in fog.seen(0).collect::<Vec<_>>() {
                prop_assert_eq!(fog.state(0, tile + w.tile_shift), Some(state));
            }
        }
        // Saves round-trip in both encodings.
        let read = FogOfWar::from_bytes(&fog.to_bytes(), &t);
        prop_assert_eq!(read.as_ref(), Ok(&fog));
        let read = FogOfWar::from_ron(&fog.to_ron(), &t);
        prop_assert_eq!(read.as_ref(), Ok(&fog));
    }

    #[test]
    fn the_fog_is_the_same_on_any_thread_and_in_any_order_of_players(config in config(), (players, turns) in turns()) {
        let t = Terrain::new(config).unwrap();
        let run = |order: &[usize]| {
            let mut fog = FogOfWar::new(&t, players).unwrap();
            for turn in &turns {
                for &player in order {
                    let units = turn[player].iter().map(|&(c, r, s)| (t.tile_from_offset([c, r]), s));
                    fog.update(&t, player as u32, units).unwrap();
                }
            }
            fog
        };
        let forward: Vec<usize> = (0..players as usize).collect();
        let backward: Vec<usize> = forward.iter().rev().copied().collect();
        let here = run(&forward);
        prop_assert_eq!(&run(&backward), &here);
        let threaded = std::thread::scope(|s| {
            let handle = s.spawn(|| run(&backward));
            handle.join().unwrap()
        });
        prop_assert_eq!(&threaded, &here);
    }
}

fn small(seed: u32, wrap: bool) -> Terrain {
    let c = MapConfig { seed, size: MapSize::Bounded { x: 12, z: 9 }, chunk_size: (8, 8), ..MapConfig::default() };
    Terrain::new(common::wrapping(c, wrap)).unwrap()
}

#[test]
fn a_fog_refuses_players_it_does_not_have_and_another_maps_terrain() {
    let t = small(1, false);
    assert_eq!(FogOfWar::new(&t, 0), Err(FogError::Players { count: 0 }));
    assert_eq!(FogOfWar::new(&t, MAX_OWNERS + 1), Err(FogError::Players { count: MAX_OWNERS + 1 }));
    let mut fog = FogOfWar::new(&t, 2).unwrap();
    let tile = t.tile_from_offset([3, 3]);
    assert_eq!(fog.update(&t, 2, [(tile, 2)]), Err(FogError::Player { player: 2, players: 2 }));
    let other = small(2, false);
    let refused = fog.update(&other, 0, [(tile, 2)]).unwrap_err();
    assert!(refused.to_string().contains("seed is 2"), "{refused}");
    assert_eq!(fog, FogOfWar::new(&t, 2).unwrap(), "a refused update changes nothing");
    assert_eq!(fog.state(5, tile), None);
    assert_eq!(fog.state(0, t.tile_from_offset([30, 30])), None);
}

#[test]
fn damaged_foreign_and_impossible_saves_are_refused_naming_why() {
    let t = small(7, true);
    let mut fog = FogOfWar::new(&t, 3).unwrap();
    fog.update(&t, 1, [(t.tile_from_offset([4, 4]), 2), (t.tile_from_offset([0, 2]), 1)]).unwrap();
    fog.update(&t, 1, [(t.tile_from_offset([8, 6]), 1)]).unwrap();
    let bytes = fog.to_bytes();
    // A flipped bit anywhere is caught by the checksum, or the header.
    for i in [0, 5, 9, bytes.len() / 2, bytes.len() - 1] {
        let mut bad = bytes.clone();
        bad[i] ^= 0x10;
        assert!(FogOfWar::from_bytes(&bad, &t).is_err(), "byte {i}");
    }
    assert!(matches!(FogOfWar::from_bytes(&bytes[..bytes.len() - 3], &t), Err(SaveError::Corrupt(_))));
    // A tile state save is not a fog save.
    let states = hex_terrain::TileStateSave {
        version: hex_terrain::SAVE_VERSION,
        map: hex_terrain::save::SavedMap::of(t.config()),
        tiles: Vec::new(),
    };
    assert!(matches!(FogOfWar::from_bytes(&states.to_bytes(), &t), Err(SaveError::Corrupt(_))));
    // Another map's fog.
    let refused = FogOfWar::from_bytes(&bytes, &small(8, true)).unwrap_err();
    assert!(matches!(refused, SaveError::OtherMap { field: "seed", .. }), "{refused}");
    let refused = FogOfWar::from_ron(&fog.to_ron(), &small(7, false)).unwrap_err();
    assert!(matches!(refused, SaveError::OtherMap { field: "wrap", .. }), "{refused}");
    // Impossible contents, each named.
    let ron = fog.to_ron();
    let map = &ron[ron.find("map:").unwrap()..ron.find("players:").unwrap()];
    let with = |players: &str| format!("(version: 1, {map} players: {players})");
    let refuse = |text: String, says: &str| {
        let error = FogOfWar::from_ron(&text, &t).expect_err(&text);
        assert!(error.to_string().contains(says), "{error} should say {says:?}");
    };
    refuse(with("[]"), "fog for 0 players");
    refuse(with(&format!("[{}]", vec!["[]"; 65].join(","))), "fog for 65 players");
    refuse(with("[[(0, 0, 3, 3)]]"), "fog state 3");
    refuse(with("[[(0, 0, 3, 0)]]"), "fog state 0");
    refuse(with("[[(10, 0, 3, 1)]]"), "within columns 0..12 and rows 0..9");
    refuse(with("[[(0, 9, 1, 1)]]"), "within columns 0..12 and rows 0..9");
    refuse(with("[[(0, 0, 0, 1)]]"), "a run of 0 tiles");
    refuse(with("[[(0, 0, 3, 1), (2, 0, 2, 2)]]"), "column 2 is listed twice");
    refuse(with("[[], [(-1, 0, 1, 1)]]"), "player 1");
    refuse(format!("(version: 2, {map} players: [[]])"), "format version 2");
    refuse("(version: 1, map: (".into(), "not valid RON");
    // A good hand-written one reads.
    let read = FogOfWar::from_ron(&with("[[(0, 0, 3, 1), (3, 0, 1, 2)], []]"), &t).unwrap();
    assert_eq!(read.state(0, t.tile_from_offset([3, 0])), Some(FogState::Visible));
    assert_eq!(read.visible(0).count(), 1);
    assert_eq!(read.seen(0).count(), 4);
}
