//! Per-tile game state in a real renderer (Mesa's software Vulkan under Xvfb in CI): fog of war,
//! territory borders, highlights without a cap and the lens, checked pixel by pixel on
//! screenshots. Each scenario renders in a process of its own; tests comparing two pictures run
//! two scenarios and read their files.

#[macro_use]
mod support;

use std::path::Path;

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::Terrain;
use bevy_hex_terrain::prelude::*;
use support::scene::*;

/// Offset column of a tile.
fn col(terrain: &Terrain, h: Hex) -> i32 {
    terrain.offset_of(h)[0]
}

fn row(terrain: &Terrain, h: Hex) -> i32 {
    terrain.offset_of(h)[1]
}

/// Fog by column: unexplored up to 6, explored 7 to 13, visible from 14.
fn fog_of(terrain: &Terrain, h: Hex) -> FogState {
    match col(terrain, h) {
        ..=6 => FogState::Unexplored,
        7..=13 => FogState::Explored,
        _ => FogState::Visible,
    }
}

fn write_fog(terrain: &Terrain, states: &mut TileStates) {
    for t in terrain.tiles() {
        states.set_visibility(t, fog_of(terrain, t)).unwrap();
    }
}

/// Clear tiles whose neighbors on the map all share `f`'s value with them.
fn interior<T: PartialEq>(terrain: &Terrain, f: impl Fn(Hex) -> T) -> Vec<(Hex, TileKind, Vec3)> {
    clear_tiles(terrain)
        .into_iter()
        .filter(|(h, ..)| h.all_neighbors().iter().all(|&n| !terrain.contains(n) || f(n) == f(*h)))
        .collect()
}

fn spread(c: [f32; 3]) -> f32 {
    c[0].max(c[1]).max(c[2]) - c[0].min(c[1]).min(c[2])
}

in_own_process! {
    fog_shows_unexplored_dark_explored_grey_and_visible_in_color => scenario_fog,
    borders_carry_the_owner_color_inside_the_owned_tile => scenario_borders,
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_fog() {
    let terrain = Terrain::new(map()).unwrap();
    let (center, size) = view(&terrain);
    let style = HexTileStateStyle { fog_of_war: true, ..default() };
    let (img, _) = render_scene(Scene { style, tiles: Some(write_fog), ..default() }, "fog");
    let at = |p: Vec3| rgb(&img, pixel(center, size, p));
    let tiles = interior(&terrain, |h| fog_of(&terrain, h));
    let mut seen = [0; 3];
    for &(h, kind, p) in &tiles {
        let c = at(p);
        match fog_of(&terrain, h) {
            FogState::Unexplored => assert!(brightness(c) < 0.16 && spread(c) < 0.08, "unexplored {h:?} drawn {c:?}"),
            FogState::Explored => {
                assert!(spread(c) < 0.2 && brightness(c) > 0.12, "explored {kind:?} {h:?} drawn {c:?}");
            }
            FogState::Visible => {}
        }
        seen[fog_of(&terrain, h) as usize] += 1;
    }
    assert!(seen.iter().all(|&n| n > 3), "every fog state has interior tiles: {seen:?}");
    let visible: Vec<Hex> = tiles.iter().filter(|t| fog_of(&terrain, t.0) == FogState::Visible).map(|t| t.0).collect();
    let not_visible: Vec<Hex> = terrain.tiles().filter(|h| !visible.contains(h)).collect();
    let checked = check_type_colors(&img, &terrain, &not_visible);
    assert!(checked.iter().sum::<usize>() > 3, "visible tiles checked: {checked:?}");
    // Soft transitions: from an unexplored tile's center to its explored neighbor's, the
    // brightness passes through intermediate values over several pixels, not in one step.
    let pairs: Vec<(Hex, Hex)> = terrain
        .tiles()
        .filter(|&h| col(&terrain, h) == 6)
        .flat_map(|h| h.all_neighbors().into_iter().map(move |n| (h, n)))
        .filter(|&(_, n)| terrain.contains(n) && col(&terrain, n) == 7)
        .collect();
    let mut soft = 0;
    for &(a, b) in &pairs {
        let (pa, pb) = (
            DVec3::from_array(terrain.tile_center(a).unwrap()).as_vec3(),
            DVec3::from_array(terrain.tile_center(b).unwrap()).as_vec3(),
        );
        let samples: Vec<f32> = (0..=40).map(|k| brightness(at(pa.lerp(pb, k as f32 / 40.0)))).collect();
        let (lo, hi) =
            (samples[..10].iter().copied().fold(f32::MAX, f32::min), samples[30..].iter().copied().fold(0.0, f32::max));
        let between = samples.iter().filter(|&&v| v > lo + 0.25 * (hi - lo) && v < hi - 0.25 * (hi - lo)).count();
        soft += usize::from(hi - lo > 0.05 && between >= 4);
    }
    assert!(soft * 2 > pairs.len(), "{soft} of {} unexplored-explored borders blend softly", pairs.len());
}

/// Owners: nobody in the first two rows, player 1 left of column 10, player 2 from it.
fn owner_of(terrain: &Terrain, h: Hex) -> Option<u32> {
    (row(terrain, h) >= 2).then_some(if col(terrain, h) < 10 { 0 } else { 1 })
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_borders() {
    let terrain = Terrain::new(map()).unwrap();
    let (center, size) = view(&terrain);
    let style = HexTileStateStyle { territory_tint: false, border_width: 0.25, border_inset: 0.05, ..default() };
    let tiles = |terrain: &Terrain, states: &mut TileStates| {
        for t in terrain.tiles() {
            states.set_owner(t, owner_of(terrain, t)).unwrap();
        }
    };
    let (img, _) = render_scene(Scene { style, tiles: Some(tiles), ..default() }, "borders");
    let at = |p: Vec3| rgb(&img, pixel(center, size, p));
    // Tile centers keep their type colors (no tint).
    assert_type_colors(&img, &terrain, &[]);
    let (mut red, mut blue, mut plain) = (0, 0, 0);
    for a in terrain.tiles() {
        for b in a.all_neighbors().into_iter().filter(|&b| terrain.contains(b)) {
            let (oa, ob) = (owner_of(&terrain, a), owner_of(&terrain, b));
            if oa == ob {
                continue;
            }
            // The middle of the border band, inside `a`, 0.175 radii from the shared edge.
            let (pa, pb) = (
                DVec3::from_array(terrain.tile_center(a).unwrap()).as_vec3(),
                DVec3::from_array(terrain.tile_center(b).unwrap()).as_vec3(),
            );
            let mid = (pa + pb) / 2.0;
            let c = at(mid + (pa - mid).normalize() * 0.175);
            match oa {
                Some(0) => {
                    assert!(
                        c[0] > c[1] + 0.25 && c[0] > c[2] + 0.25,
                        "player 0's border in {a:?} towards {b:?}: {c:?}"
                    );
                    red += 1;
                }
                Some(_) => {
                    assert!(c[2] > c[0] + 0.25 && c[2] > c[1] + 0.1, "player 1's border in {a:?} towards {b:?}: {c:?}");
                    blue += 1;
                }
                None => {
                    // Nobody's tile: no border on its side.
                    let redish = c[0] > c[1] + 0.25 && c[0] > c[2] + 0.25;
                    assert!(!redish, "nobody's tile {a:?} shows a border: {c:?}");
                    plain += 1;
                }
            }
        }
    }
    assert!(red > 10 && blue > 10 && plain > 10, "borders checked: {red} red, {blue} blue, {plain} nobody's");
}

/// A map big enough for 500 highlighted tiles (40x28).
fn big_map() -> MapConfig {
    MapConfig { size: MapSize::Bounded { x: 40, z: 28 }, ..map() }
}

/// 500 tiles of [`big_map`], spread over it (every other tile).
fn five_hundred(terrain: &Terrain) -> Vec<Hex> {
    terrain.tiles().filter(|&h| (col(terrain, h) + row(terrain, h)) % 2 == 0).take(500).collect()
}

fn image(name: &str) -> image::RgbImage {
    image::open(Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.png"))).unwrap().to_rgb8()
}

fn distance(a: [f32; 3], b: [f32; 3]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f32>().sqrt()
}

#[test]
fn five_hundred_highlighted_tiles_are_all_tinted() {
    support::in_own_process("scenario_big_plain");
    support::in_own_process("scenario_big_highlighted");
    let terrain = Terrain::new(big_map()).unwrap();
    let (center, size) = view(&terrain);
    let (plain, lit) = (image("big_plain"), image("big_highlighted"));
    let tinted = five_hundred(&terrain);
    assert_eq!(tinted.len(), 500);
    // The tint's color as the screen shows it (sRGB).
    let tint = HexTileStateStyle::default().reachable_color.to_srgba();
    let tint = [tint.red, tint.green, tint.blue];
    for t in terrain.tiles() {
        let p = pixel(center, size, DVec3::from_array(terrain.tile_center(t).unwrap()).as_vec3());
        let (before, after) = (rgb(&plain, p), rgb(&lit, p));
        if tinted.contains(&t) {
            assert!(
                distance(after, tint) < distance(before, tint) - 0.05,
                "highlighted tile {t:?}: {before:?} -> {after:?}, not towards {tint:?}"
            );
        } else {
            // The sea's shimmer moves with time: a little change is allowed.
            assert!(
                distance(after, before) < 0.1,
                "tile {t:?} is not highlighted but changed: {before:?} -> {after:?}"
            );
        }
    }
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_big_plain() {
    render_scene(Scene { config: Some(big_map()), ..default() }, "big_plain");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_big_highlighted() {
    let tiles = |terrain: &Terrain, states: &mut TileStates| {
        assert_eq!(states.replace_highlight(Highlight::Reachable, five_hundred(terrain)), 0);
    };
    render_scene(Scene { config: Some(big_map()), tiles: Some(tiles), ..default() }, "big_highlighted");
}

/// The lens colors a third of the tiles magenta.
fn lensed(terrain: &Terrain, h: Hex) -> bool {
    (col(terrain, h) + 2 * row(terrain, h)) % 3 == 0
}

fn write_lens(terrain: &Terrain, states: &mut TileStates) {
    for t in terrain.tiles().filter(|&t| lensed(terrain, t)) {
        states.set_overlay(t, Some(Color::srgba(1.0, 0.0, 1.0, 0.8))).unwrap();
    }
}

#[test]
fn toggling_the_lens_changes_only_the_tiles_it_colors() {
    support::in_own_process("scenario_lens_off");
    support::in_own_process("scenario_lens_on");
    let terrain = Terrain::new(map()).unwrap();
    let (center, size) = view(&terrain);
    let (off, on) = (image("lens_off"), image("lens_on"));
    let (mut changed, mut kept) = (0, 0);
    for (t, kind, p) in clear_tiles(&terrain) {
        let p = pixel(center, size, p);
        let (before, after) = (rgb(&off, p), rgb(&on, p));
        if lensed(&terrain, t) {
            let magenta = [1.0, 0.0, 1.0];
            assert!(
                distance(after, magenta) < distance(before, magenta) - 0.1,
                "lensed {kind:?} tile {t:?}: {before:?} -> {after:?}, not towards magenta"
            );
            changed += 1;
        } else {
            let allowed = if kind == TileKind::Sea { 0.1 } else { 0.02 };
            assert!(
                distance(after, before) < allowed,
                "{kind:?} tile {t:?} has no lens color but changed: {before:?} -> {after:?}"
            );
            kept += 1;
        }
    }
    assert!(changed > 20 && kept > 40, "{changed} lensed and {kept} other tiles checked");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_lens_off() {
    render_scene(Scene { tiles: Some(write_lens), ..default() }, "lens_off");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_lens_on() {
    let style = HexTileStateStyle { lens: true, ..default() };
    render_scene(Scene { style, tiles: Some(write_lens), ..default() }, "lens_on");
}
