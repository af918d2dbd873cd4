use bevy::prelude::*;
use hex_terrain::hexx::{Hex, HexOrientation};
use hex_terrain::{Geometry, MapConfig, MapSize, Orientation};

use super::window::{TEXEL_BYTES, TexelWindow};
use super::*;

/// A small deterministic generator (xorshift), so the random walks below replay exactly.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo) as u64) as i32
    }
}

/// The core's geometry of a map: `size` columns and rows (`None`: unbounded), its orientation,
/// wrapping east to west or not.
fn geometry(size: Option<(u32, u32)>, orientation: HexOrientation, wrap: bool) -> Geometry {
    let mut config = MapConfig {
        size: size.map_or(MapSize::Unbounded, |(x, z)| MapSize::Bounded { x, z }),
        wrap,
        ..MapConfig::default()
    };
    config.layout.orientation =
        if orientation == HexOrientation::Flat { Orientation::Flat } else { Orientation::Pointy };
    Geometry::new(&config)
}

fn bounded(x: i32, z: i32) -> TileStates {
    let mut s = TileStates::default();
    s.set_map(&geometry(Some((x as u32, z as u32)), HexOrientation::Flat, false), true);
    s.refill_window(IVec2::ZERO, UVec2::new(x as u32, z as u32));
    s
}

/// The tile at an offset coordinate of a flat-topped map (the maps here).
fn hex(_: &TileStates, col: i32, row: i32) -> Hex {
    Hex::from_offset_coordinates([col, row], hex_terrain::terrain::OFFSET_MODE, HexOrientation::Flat)
}

/// Applies an upload to a CPU copy of the texture, as the render world does.
fn apply(texture: &mut Vec<Texel>, upload: &TileStateUpload) {
    let width = upload.size.x as usize;
    texture.resize(width * upload.size.y as usize, [0; 4]);
    let mut at = 0;
    for span in &upload.spans {
        let start = span.y as usize * width + span.x as usize;
        texture[start..start + span.z as usize].copy_from_slice(&upload.data[at..at + span.z as usize]);
        at += span.z as usize;
    }
}

#[test]
fn writes_read_back_and_defaults_hold() {
    let mut s = bounded(20, 10);
    let a = hex(&s, 3, 4);
    assert_eq!(s.visibility(a), FogState::Unexplored);
    assert_eq!(s.owner(a), None);
    assert_eq!(s.overlay(a), None);
    s.set_visibility(a, FogState::Visible).unwrap();
    s.set_owner(a, Some(7)).unwrap();
    s.set_overlay(a, Some(Color::srgba(1.0, 0.5, 0.0, 0.5))).unwrap();
    s.set_highlight(a, Highlight::Selected, true).unwrap();
    assert_eq!(s.visibility(a), FogState::Visible);
    assert_eq!(s.owner(a), Some(7));
    assert_eq!(s.overlay(a).unwrap().to_srgba().to_u8_array(), [255, 128, 0, 128]);
    assert!(s.is_highlighted(a, Highlight::Selected));
    assert!(!s.is_highlighted(a, Highlight::Hovered));
    s.hide_visible();
    assert_eq!(s.visibility(a), FogState::Explored);
    // Back to the default state, the tile is no longer stored.
    s.set_visibility(a, FogState::Unexplored).unwrap();
    s.set_owner(a, None).unwrap();
    s.set_overlay(a, None).unwrap();
    s.set_highlight(a, Highlight::Selected, false).unwrap();
    assert_eq!(s.stored_tiles(), 0);
}

#[test]
fn bad_writes_are_refused_by_name_and_change_nothing() {
    let mut s = bounded(20, 10);
    s.take_upload();
    let writes = s.writes();
    let outside = hex(&s, 20, 3);
    let e = s.set_visibility(outside, FogState::Visible).unwrap_err();
    assert!(matches!(e, TileStateError::OutsideMap { offset: [20, 3], .. }), "{e}");
    assert!(e.to_string().contains("columns 0..20"), "{e}");
    assert!(s.set_owner(hex(&s, -1, 0), Some(1)).is_err());
    assert!(s.set_highlight(hex(&s, 0, 10), Highlight::Reachable, true).is_err());
    let inside = hex(&s, 1, 1);
    let e = s.set_owner(inside, Some(MAX_OWNERS)).unwrap_err();
    assert!(e.to_string().contains(&format!("players 0..{MAX_OWNERS}")), "{e}");
    let e = s.set_overlay(inside, Some(Color::srgba(f32::NAN, 0.0, 0.0, 1.0))).unwrap_err();
    assert!(e.to_string().contains("not finite"), "{e}");
    assert_eq!(s.writes(), writes);
    assert_eq!(s.stored_tiles(), 0);
    assert!(!s.has_upload());
    // A bulk highlight skips what is outside.
    assert_eq!(s.replace_highlight(Highlight::Reachable, [inside, outside, hex(&s, 5, 99)]), 2);
    assert_eq!(s.highlighted(Highlight::Reachable).collect::<Vec<_>>(), vec![inside]);
    // Player 0 owns: players are numbered from 0, as a setup numbers its starts.
    s.set_owner(inside, Some(0)).unwrap();
    assert_eq!(s.owner(inside), Some(0));
}

#[test]
fn only_changed_rows_are_uploaded_and_a_quiet_frame_uploads_nothing() {
    let mut s = bounded(106, 66);
    let first = s.take_upload();
    assert_eq!(first.spans.len(), 66, "a new texture is filled whole");
    assert!(!s.has_upload());
    // Writing the same state again is no change.
    s.set_visibility(hex(&s, 5, 5), FogState::Unexplored).unwrap();
    assert!(!s.has_upload());
    s.set_visibility(hex(&s, 5, 5), FogState::Visible).unwrap();
    s.set_visibility(hex(&s, 9, 5), FogState::Explored).unwrap();
    s.set_owner(hex(&s, 2, 40), Some(2)).unwrap();
    let up = s.take_upload();
    assert_eq!(up.spans, vec![UVec3::new(5, 5, 5), UVec3::new(2, 40, 1)]);
    assert_eq!(up.bytes(), 6 * TEXEL_BYTES);
    assert!(s.take_upload().spans.is_empty());
}

#[test]
fn many_highlights_are_all_kept() {
    let mut s = bounded(106, 66);
    let tiles: Vec<Hex> = (0..106).flat_map(|c| (0..66).map(move |r| (c, r))).map(|(c, r)| hex(&s, c, r)).collect();
    assert_eq!(s.replace_highlight(Highlight::Reachable, tiles.iter().copied()), 0);
    assert!(tiles.iter().all(|&t| s.is_highlighted(t, Highlight::Reachable)));
    s.replace_highlight(Highlight::Reachable, tiles[..500].iter().copied());
    assert_eq!(s.highlighted(Highlight::Reachable).count(), 500);
    assert!(!s.is_highlighted(tiles[500], Highlight::Reachable));
    s.clear_highlight(Highlight::Reachable);
    assert_eq!(s.stored_tiles(), 0);
}

/// Random writes and window moves (unbounded): after every upload, the CPU copy of the texture
/// holds exactly the stored state of every tile inside the window, so a moved window never
/// shows a stale tile and tiles outside keep their state.
#[test]
fn a_moving_window_always_mirrors_the_store() {
    for seed in 1..=20u64 {
        let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let mut s = TileStates::default();
        let orientation = if seed % 2 == 0 { HexOrientation::Flat } else { HexOrientation::Pointy };
        s.set_map(&geometry(None, orientation, false), true);
        let size = UVec2::new(rng.range(3, 12) as u32, rng.range(3, 12) as u32);
        let mut origin = IVec2::new(rng.range(-20, 20), rng.range(-20, 20));
        s.refill_window(origin, size);
        let mut texture = Vec::new();
        for _ in 0..60 {
            for _ in 0..rng.range(0, 12) {
                let oc = origin + IVec2::new(rng.range(-6, size.x as i32 + 6), rng.range(-6, size.y as i32 + 6));
                let h = Hex::from_offset_coordinates(oc.to_array(), hex_terrain::terrain::OFFSET_MODE, s.orientation());
                match rng.range(0, 3) {
                    0 => s
                        .set_visibility(
                            h,
                            [FogState::Unexplored, FogState::Explored, FogState::Visible][rng.range(0, 3) as usize],
                        )
                        .unwrap(),
                    1 => s.set_owner(h, Some(rng.range(0, 5) as u32).filter(|&o| o < 4)).unwrap(),
                    _ => s.set_highlight(h, Highlight::Reachable, rng.range(0, 2) == 1).unwrap(),
                }
            }
            if rng.range(0, 3) == 0 {
                origin += IVec2::new(rng.range(-14, 15), rng.range(-14, 15));
                s.refill_window(origin, size);
            }
            apply(&mut texture, &s.take_upload());
            for y in 0..size.y as i32 {
                for x in 0..size.x as i32 {
                    let oc = origin + IVec2::new(x, y);
                    let h =
                        Hex::from_offset_coordinates(oc.to_array(), hex_terrain::terrain::OFFSET_MODE, s.orientation());
                    let t = UVec2::new(oc.x.rem_euclid(size.x as i32) as u32, oc.y.rem_euclid(size.y as i32) as u32);
                    let texel = texture[(t.y * size.x + t.x) as usize];
                    assert_eq!(texel[0] & 3, s.visibility(h) as u16, "seed {seed} tile {oc}");
                    assert_eq!(texel[1], s.owner(h).map_or(0, |o| o as u16 + 1), "seed {seed} tile {oc}");
                    assert_eq!(texel[0] & 16 != 0, s.is_highlighted(h, Highlight::Reachable), "seed {seed} tile {oc}");
                }
            }
        }
    }
}

#[test]
fn window_texels_are_unique_inside_the_window() {
    let w = TexelWindow::new(IVec2::new(-7, 13), UVec2::new(5, 4));
    let mut seen = std::collections::HashSet::new();
    for y in 13..17 {
        for x in -7..-2 {
            assert!(w.contains(IVec2::new(x, y)));
            assert!(seen.insert(w.texel_of(IVec2::new(x, y))));
            assert_eq!(w.texel(IVec2::new(x, y)), Some([0; 4]));
        }
    }
    assert!(!w.contains(IVec2::new(-2, 13)) && !w.contains(IVec2::new(-7, 17)));
}

#[test]
fn a_new_map_clears_and_a_reload_keeps_what_is_still_on_the_map() {
    let mut s = bounded(20, 10);
    let (a, b) = (hex(&s, 2, 2), hex(&s, 15, 8));
    s.set_owner(a, Some(1)).unwrap();
    s.set_owner(b, Some(2)).unwrap();
    // Hot reload to a smaller map: `b` falls off.
    s.set_map(&geometry(Some((10, 10)), HexOrientation::Flat, false), true);
    assert_eq!(s.owner(a), Some(1));
    assert_eq!(s.owner(b), None);
    // Another map: nothing kept.
    s.set_map(&geometry(Some((10, 10)), HexOrientation::Flat, false), false);
    assert_eq!(s.owner(a), None);
    assert_eq!(s.stored_tiles(), 0);
}

#[test]
fn a_wrapping_map_takes_tiles_past_its_east_and_west_edges_as_its_own() {
    for orientation in [HexOrientation::Flat, HexOrientation::Pointy] {
        let mut s = TileStates::default();
        s.set_map(&geometry(Some((20, 10)), orientation, true), true);
        s.refill_window(IVec2::ZERO, UVec2::new(20, 10));
        let at = |col: i32, row: i32| {
            Hex::from_offset_coordinates([col, row], hex_terrain::terrain::OFFSET_MODE, orientation)
        };
        // Column 23 is column 3, column -1 is column 19, in the same row.
        s.set_owner(at(23, 4), Some(5)).unwrap();
        assert_eq!(s.owner(at(3, 4)), Some(5));
        assert_eq!(s.wrap_tile(at(-1, 7)), at(19, 7));
        s.set_highlight(at(-1, 7), Highlight::Selected, true).unwrap();
        assert!(s.is_highlighted(at(19, 7), Highlight::Selected));
        assert_eq!(s.highlighted(Highlight::Selected).collect::<Vec<_>>(), vec![at(19, 7)]);
        assert_eq!(s.replace_highlight(Highlight::Reachable, [at(40, 1), at(0, 1), at(5, 10)]), 1, "row 10 is off");
        assert_eq!(s.highlighted(Highlight::Reachable).count(), 1, "columns 40 and 0 are one tile");
        assert!(s.set_visibility(at(3, -1), FogState::Visible).is_err(), "rows do not wrap");
    }
}

#[test]
fn a_players_fog_is_shown_and_another_players_replaces_it() {
    use hex_terrain::{FogOfWar, Terrain};
    let config = MapConfig { size: MapSize::Bounded { x: 12, z: 8 }, ..MapConfig::default() };
    let terrain = Terrain::new(config.clone()).unwrap();
    let mut s = bounded(12, 8);
    let mut fog = FogOfWar::new(&terrain, 2).unwrap();
    let (a, b) = (hex(&s, 2, 2), hex(&s, 9, 5));
    fog.update(&terrain, 0, [(a, 1)]).unwrap();
    fog.update(&terrain, 0, [(a + Hex::new(1, 0), 1)]).unwrap();
    fog.update(&terrain, 1, [(b, 1)]).unwrap();
    s.set_owner(a, Some(0)).unwrap();
    for player in [0, 1, 0] {
        s.show_fog(&fog, player).unwrap();
        for tile in terrain.tiles() {
            assert_eq!(Some(s.visibility(tile)), fog.state(player, tile), "player {player}, {tile:?}");
        }
    }
    assert_eq!(s.owner(a), Some(0), "the other states stay");
    assert_eq!(s.show_fog(&fog, 2), Err(TileStateError::NoSuchPlayer { player: 2, players: 2 }));
    // A fog of a larger map does not fit.
    let larger = Terrain::new(MapConfig { size: MapSize::Bounded { x: 20, z: 8 }, ..config }).unwrap();
    let mut wide = FogOfWar::new(&larger, 1).unwrap();
    wide.update(&larger, 0, [(hex(&s, 18, 3), 1)]).unwrap();
    let before = s.visibility(a);
    assert!(matches!(s.show_fog(&wide, 0), Err(TileStateError::OutsideMap { .. })));
    assert_eq!(s.visibility(a), before, "a refused fog changes nothing");
}
