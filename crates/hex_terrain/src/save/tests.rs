use proptest::prelude::*;

use super::*;

fn config(bounded: Option<(u32, u32)>, wrap: bool) -> MapConfig {
    MapConfig {
        seed: 9,
        size: bounded.map_or(MapSize::Unbounded, |(x, z)| MapSize::Bounded { x, z }),
        wrap: wrap && bounded.is_some(),
        ..MapConfig::default()
    }
}

prop_compose! {
    fn tile(columns: i32, rows: i32)(
        col in 0..columns,
        row in 0..rows,
        fog in 0u8..3,
        owner in prop::option::of(0..MAX_OWNERS as u8),
        overlay in prop::option::of(any::<[u8; 4]>()),
        bits in 0u8..8,
    ) -> SavedTile {
        let fog = [FogState::Unexplored, FogState::Explored, FogState::Visible][fog as usize];
        let highlights = Highlight::ALL.into_iter().filter(|&h| bits & (1 << h as u8) != 0).collect();
        SavedTile { at: (col, row), fog, owner, overlay, highlights }
    }
}

prop_compose! {
    /// A valid save of `config(Some((12, 9)), wrap)`: distinct tiles.
    fn save()(wrap in any::<bool>(), tiles in prop::collection::vec(tile(12, 9), 0..60)) -> (TileStateSave, MapConfig) {
        let config = config(Some((12, 9)), wrap);
        let mut seen = std::collections::HashSet::new();
        let tiles = tiles.into_iter().filter(|t| seen.insert(t.at)).collect();
        (TileStateSave { version: SAVE_VERSION, map: SavedMap::of(&config), tiles }, config)
    }
}

proptest! {
    /// Both encodings read back to the same save, which checks against its map.
    #[test]
    fn saves_round_trip_in_ron_and_binary((save, config) in save()) {
        prop_assert_eq!(save.check(&config), Ok(()));
        prop_assert_eq!(&TileStateSave::from_ron(&save.to_ron()).unwrap(), &save);
        let bytes = save.to_bytes();
        prop_assert_eq!(&TileStateSave::from_bytes(&bytes).unwrap(), &save);
        // Deterministic: the same save, the same bytes.
        prop_assert_eq!(bytes, save.to_bytes());
    }

    /// Any damage to a binary save is refused: a changed byte, a cut, extra bytes.
    #[test]
    fn damaged_binary_saves_are_refused((save, _) in save(), at in any::<prop::sample::Index>(), flip in 1u8..=255, cut in any::<prop::sample::Index>()) {
        let bytes = save.to_bytes();
        let mut damaged = bytes.clone();
        let i = at.index(bytes.len());
        damaged[i] ^= flip;
        prop_assert!(TileStateSave::from_bytes(&damaged).is_err(), "byte {} changed", i);
        let n = cut.index(bytes.len());
        prop_assert!(matches!(TileStateSave::from_bytes(&bytes[..n]), Err(SaveError::Corrupt(_))), "cut at {}", n);
        let mut longer = bytes;
        longer.push(0);
        prop_assert!(matches!(TileStateSave::from_bytes(&longer), Err(SaveError::Corrupt(_))));
    }

    /// A save of another map is refused, naming the field that differs.
    #[test]
    fn saves_of_another_map_are_refused((save, config) in save(), which in 0usize..5) {
        let mut other = config.clone();
        let field = match which {
            0 => { other.seed ^= 1; "seed" }
            1 => { other.size = MapSize::Bounded { x: 14, z: 9 }; "size" }
            2 => { other.wrap = !other.wrap; "wrap" }
            3 => { other.layout.orientation = Orientation::Pointy; "layout.orientation" }
            _ => { other.offset = (3, 0); "offset" }
        };
        match save.check(&other) {
            Err(SaveError::OtherMap { field: f, .. }) => prop_assert_eq!(f, field),
            r => prop_assert!(false, "{:?}", r),
        }
    }
}

#[test]
fn impossible_tiles_and_versions_are_refused_with_the_reason() {
    let config = config(Some((12, 9)), false);
    let ok = SavedTile { at: (1, 1), fog: FogState::Visible, owner: None, overlay: None, highlights: vec![] };
    let with = |tiles: Vec<SavedTile>| TileStateSave { version: SAVE_VERSION, map: SavedMap::of(&config), tiles };
    let cases = [
        (SavedTile { at: (12, 0), ..ok.clone() }, "not on the map: columns 0..12 and rows 0..9"),
        (SavedTile { at: (0, -1), ..ok.clone() }, "not on the map"),
        (SavedTile { owner: Some(64), ..ok.clone() }, "owners are players 0..64"),
        (SavedTile { owner: Some(65), ..ok.clone() }, "owner 65"),
        (SavedTile { highlights: vec![Highlight::Hovered, Highlight::Hovered], ..ok.clone() }, "listed twice"),
    ];
    for (tile, reason) in cases {
        let e = with(vec![tile]).check(&config).unwrap_err();
        assert!(e.to_string().contains(reason) && e.to_string().contains("tile 0"), "{e}");
    }
    let e = with(vec![ok.clone(), ok.clone()]).check(&config).unwrap_err();
    assert!(e.to_string().contains("tile 1") && e.to_string().contains("listed twice"), "{e}");
    let newer = TileStateSave { version: SAVE_VERSION + 1, ..with(vec![]) };
    assert_eq!(newer.check(&config), Err(SaveError::Version { found: SAVE_VERSION + 1, newest: SAVE_VERSION }));
    assert_eq!(
        TileStateSave::from_bytes(&newer.to_bytes()),
        Err(SaveError::Version { found: SAVE_VERSION + 1, newest: SAVE_VERSION })
    );
    // Unbounded maps take any tile of the world.
    let world = config_unbounded();
    let far = TileStateSave {
        version: SAVE_VERSION,
        map: SavedMap::of(&world),
        tiles: vec![SavedTile { at: (-900_000, 5_000_000), ..ok }],
    };
    assert_eq!(far.check(&world), Ok(()));
}

fn config_unbounded() -> MapConfig {
    config(None, false)
}

#[test]
fn malformed_ron_names_the_line_and_column() {
    let text = "(\n  version: 1,\n  map: (seed: 9, size: Bounded(x: 12, z: 9), wrap: false, orientation: Flat, offset: (0, 0)),\n  tiles: [(at: (1, 1), fog: Foggy)],\n)";
    let e = TileStateSave::from_ron(text).unwrap_err();
    assert!(matches!(e, SaveError::Syntax { line: 4, .. }), "{e:?}");
    assert!(e.to_string().contains("line 4, column"), "{e}");
    // A hand-written save leaves the defaults out.
    let text = "(version: 2, map: (seed: 9, size: Bounded(x: 12, z: 9), wrap: false, orientation: Flat, offset: (0, 0)), tiles: [(at: (2, 3), owner: Some(0))])";
    let save = TileStateSave::from_ron(text).unwrap();
    assert_eq!(
        save.tiles[0],
        SavedTile { at: (2, 3), fog: FogState::Unexplored, owner: Some(0), overlay: None, highlights: vec![] }
    );
    assert_eq!(save.check(&config(Some((12, 9)), false)), Ok(()));
}

/// Version 1 numbered owners from 1: its saves read as players from 0, in both encodings.
#[test]
fn version_1_saves_read_with_players_from_0() {
    let map = "map: (seed: 9, size: Bounded(x: 12, z: 9), wrap: false, orientation: Flat, offset: (0, 0))";
    let v1 = format!("(version: 1, {map}, tiles: [(at: (2, 3), owner: Some(4)), (at: (3, 3), owner: Some(1))])");
    let save = TileStateSave::from_ron(&v1).unwrap();
    assert_eq!(save.version, SAVE_VERSION);
    assert_eq!(save.tiles.iter().map(|t| t.owner).collect::<Vec<_>>(), [Some(3), Some(0)]);
    let v1_zero = format!("(version: 1, {map}, tiles: [(at: (0, 0)), (at: (2, 3), owner: Some(0))])");
    let e = TileStateSave::from_ron(&v1_zero).unwrap_err();
    assert!(e.to_string().contains("tile 1") && e.to_string().contains("owners 1..=64"), "{e}");
    // A version 1 binary file stored owner 4 as 4: player 3, as version 2 stores player 3.
    let config = config(Some((12, 9)), false);
    let tile = SavedTile { at: (2, 3), fog: FogState::Visible, owner: Some(3), overlay: None, highlights: vec![] };
    let mut bytes =
        TileStateSave { version: SAVE_VERSION, map: SavedMap::of(&config), tiles: vec![tile.clone()] }.to_bytes();
    bytes[4..8].copy_from_slice(&1u32.to_le_bytes());
    let body = bytes.len() - 4;
    let crc = crc32(&bytes[..body]);
    bytes[body..].copy_from_slice(&crc.to_le_bytes());
    let read = TileStateSave::from_bytes(&bytes).unwrap();
    assert_eq!((read.version, read.tiles), (SAVE_VERSION, vec![tile]));
}

#[test]
fn the_binary_format_is_compact_and_starts_with_its_magic() {
    let config = config(Some((12, 9)), false);
    let tiles = (0..100)
        .map(|i| SavedTile {
            at: (i % 12, i / 12),
            fog: FogState::Explored,
            owner: Some(3),
            overlay: None,
            highlights: vec![],
        })
        .collect();
    let save = TileStateSave { version: SAVE_VERSION, map: SavedMap::of(&config), tiles };
    let bytes = save.to_bytes();
    assert_eq!(bytes[..4], SAVE_MAGIC);
    assert!(bytes.len() < 100 * 10 + 120, "{} bytes for 100 tiles", bytes.len());
    assert!(bytes.len() * 4 < save.to_ron().len(), "binary {} vs RON {}", bytes.len(), save.to_ron().len());
}
