//! Rendering a million units from the origin with `big_space`'s floating origin (Mesa's software
//! Vulkan under Xvfb in CI): the picture is not blank, has no hole (no clear-color pixel: no
//! crack between chunks, full or coarse, no NaN vertex), every clear tile shows its type's color
//! at its center, at either level of detail, and the tile state (a lens overlay) lands on the
//! right tile.

#[macro_use]
mod support;

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::Terrain;
use bevy_hex_terrain::prelude::*;
use support::scene::*;

/// Where the camera looks: a million units east and south of the origin, off the lattice.
const FAR: DVec3 = DVec3::new(1.0e6 + 0.37, 0.0, 1.0e6 - 0.21);

fn far_map() -> MapConfig {
    MapConfig { size: MapSize::Unbounded, ..map() }
}

/// The tile under the camera gets a blue lens overlay.
fn lens_tile(terrain: &Terrain) -> Hex {
    terrain.tile_at(FAR.x, FAR.z).unwrap()
}

fn write_lens(terrain: &Terrain, states: &mut TileStates) {
    states.set_overlay(lens_tile(terrain), Some(Color::srgba(0.0, 0.1, 1.0, 0.9))).unwrap();
}

in_own_process! {
    far_from_the_origin_the_terrain_renders_whole_and_exact => scenario_far,
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_far() {
    let style = HexTileStateStyle { lens: true, ..default() };
    // Levels of detail split the view: full chunks under the camera (47 units above the 3-unit
    // mountains), coarse ones more than about 10 units aside.
    let streaming = HexStreamingSettings { coarse_distance: Some(48.0), ..default() };
    let scene = Scene {
        config: Some(far_map()),
        style,
        tiles: Some(write_lens),
        far: Some(FAR),
        streaming: Some(streaming),
        ..default()
    };
    let (img, counts) = render_scene(scene, "far");
    let [full, coarse] = counts.levels;
    assert!(full > 0 && coarse > 0, "{full} full and {coarse} coarse chunks: both levels must be in view");

    let holes = img.pixels().filter(|p| p.0 == HOLE).count();
    assert_eq!(holes, 0, "{holes} pixels of the clear color: holes or cracks in the terrain");
    let black = img.pixels().filter(|p| p.0.iter().all(|&c| c < 8)).count();
    assert_eq!(black, 0, "{black} black pixels (NaN vertices render black)");

    // Tile centers, measured from the camera in f64 so the pixel is exact out there.
    let terrain = Terrain::new(far_map()).unwrap();
    let c = terrain.config().clone();
    let (s, m, b) = (c.terrain.sea_threshold, c.terrain.mountain_threshold, c.appearance.blend);
    let center = terrain.unwrapped_tile_at(FAR.x, FAR.z).unwrap();
    let lens = lens_tile(&terrain);
    let mut seen = [0; 3];
    for tile in center.range(20) {
        let [x, y, z] = terrain.tile_center(tile).unwrap();
        let local = Vec3::new((x - FAR.x) as f32, y as f32, (z - FAR.z) as f32);
        if local.x.abs() > FAR_VIEW.x / 2.0 - 1.0 || local.z.abs() > FAR_VIEW.y / 2.0 - 1.0 {
            continue;
        }
        let at = rgb(&img, pixel(Vec2::ZERO, FAR_VIEW, local));
        if tile == lens {
            assert!(at[2] > at[0] + 0.3 && at[2] > at[1] + 0.2, "the lensed tile under the camera is {at:?}");
            continue;
        }
        let info = terrain.tile_info(tile).unwrap();
        let h = info.elevation / c.terrain.max_elevation;
        if (h - s).abs() > b && (h - m).abs() > b {
            assert_kind_color(tile, info.kind, at);
            seen[info.kind as usize] += 1;
        }
    }
    assert!(seen.iter().sum::<usize>() > 100, "tiles checked by kind: {seen:?}");
}
