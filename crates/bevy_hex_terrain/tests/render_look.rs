//! The strategy look in a real renderer (Mesa's software Vulkan under Xvfb in CI): water colored
//! by depth with a shore between land and sea, props standing where the core places them, the
//! sun's shadows on the lee side of mountains, and outlines, textures and highlights kept over all
//! of it.
//! Each scenario runs in a process of its own (see `render.rs`).

#[macro_use]
mod support;

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{ReliefConfig, Terrain};
use bevy_hex_terrain::prelude::*;
use support::scene::*;

in_own_process! {
    deep_water_is_darker_than_the_coast_and_the_shore_is_neither => scenario_water,
    props_stand_where_the_core_places_them => scenario_props,
    shadows_darken_the_lee_side_of_mountains => scenario_shadows,
}

/// The render map with relief, as high as the demo's.
fn relief_map() -> MapConfig {
    let mut c = MapConfig { relief: ReliefConfig::MOUNTAINS, ..map() };
    c.terrain.max_elevation = 5.0;
    c
}

fn center_of(terrain: &Terrain, h: Hex) -> Vec3 {
    DVec3::from_array(terrain.tile_center(h).unwrap()).as_vec3()
}

fn distance(a: [f32; 3], b: [f32; 3]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f32::max)
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_water() {
    let config = relief_map();
    let terrain = Terrain::new(config.clone()).unwrap();
    let (center, size) = view(&terrain);
    // Textures on: the relief textures keep working beside the water (which does not use them).
    let material = HexTerrainMaterialSettings { outlines: true, outline_width: 0.1, textures: true, ..default() };
    let (img, _) = render_scene(
        Scene {
            config: Some(config),
            material,
            water: true,
            tiles: Some(|terrain, states| {
                states.set_highlight(hovered(terrain), Highlight::Hovered, true).unwrap();
            }),
            ..default()
        },
        "water",
    );
    let at = |p: Vec3| rgb(&img, pixel(center, size, p));
    let sea = terrain.sea_level();
    let depth = |h: Hex| sea - terrain.tile_info(h).unwrap().elevation;
    let coastal = |h: &Hex| h.all_neighbors().iter().any(|n| terrain.map_tile_kind(*n) == Some(TileKind::Land));
    let seas: Vec<Hex> = terrain.tiles().filter(|&t| terrain.tile_kind(t).unwrap() == TileKind::Sea).collect();
    let deep = *seas.iter().max_by(|a, b| depth(**a).total_cmp(&depth(**b))).unwrap();
    let coast = *seas.iter().filter(|h| coastal(h)).min_by(|a, b| depth(**a).total_cmp(&depth(**b))).unwrap();
    assert!(depth(deep) > 2.0 * depth(coast), "the test map has deep and shallow sea");
    // Patches, not single pixels: the sun glints on the moving waves.
    let patch_at = |p: Vec3| patch(&img, pixel(center, size, p));
    let (d, c) = (patch_at(center_of(&terrain, deep)), patch_at(center_of(&terrain, coast)));
    assert!(brightness(d) < 0.8 * brightness(c), "deep sea {d:?} is darker than the coast {c:?}");
    assert!(c[0] > d[0] + 0.04, "the sandy floor shows through the shallows: coast {c:?}, deep {d:?}");
    // The shore: halfway between a coastal sea tile's center and its land neighbor's, the
    // border vertex at sea level. It is neither the water nor the land.
    let land = *coast.all_neighbors().iter().find(|n| terrain.map_tile_kind(**n) == Some(TileKind::Land)).unwrap();
    let shore_point = (center_of(&terrain, coast) + center_of(&terrain, land)) / 2.0;
    let inland = center_of(&terrain, land);
    let (shore, ground) = (at(shore_point), at(inland));
    assert!(distance(shore, c) > 0.08, "the shore {shore:?} differs from the coast's water {c:?}");
    assert!(distance(shore, ground) > 0.08, "the shore {shore:?} differs from the land {ground:?}");
    // Outlines, textures and highlights still show over land and water.
    let ratio = border_to_center(&img, &terrain);
    assert!(ratio < 0.7, "with outlines, borders are darker than centers over land and water: {ratio}");
    let [r, g, _] = at(center_of(&terrain, hovered(&terrain)));
    assert!(r > g * 0.8, "the hovered land tile is tinted warm: {:?}", [r, g]);
}

/// A clear land tile to hover.
fn hovered(terrain: &Terrain) -> Hex {
    clear_tiles(terrain).into_iter().find(|(_, k, _)| *k == TileKind::Land).unwrap().0
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_props() {
    let config = relief_map();
    let terrain = Terrain::new(config.clone()).unwrap();
    let (center, size) = view(&terrain);
    let cap = HexPropSettings::default().max_per_chunk;
    let props: Vec<Vec3> = terrain
        .chunks()
        .into_iter()
        .filter_map(|c| terrain.generate_chunk(c))
        .flat_map(|m| {
            let origin = DVec3::from_array(m.origin);
            terrain
                .props(&m, cap, 1.0)
                .into_iter()
                .map(move |p| (origin + DVec3::from_array(p.position.map(f64::from))).as_vec3())
        })
        .collect();
    assert!(props.len() > 30, "the test map grows props: {}", props.len());
    let (with, without) = render_pair(
        Scene { config: Some(config), props: true, then: Some(|s, _, _| s.enabled = false), ..default() },
        "props",
    );
    let changed = |p: Vec3| {
        let px = pixel(center, size, p);
        distance(rgb(&with, px), rgb(&without, px)) > 0.05
    };
    let shown = props.iter().filter(|p| changed(**p)).count();
    assert!(shown * 10 >= props.len() * 7, "{shown} of {} props show pixels", props.len());
    // Away from every prop, nothing changed.
    let far_from_props = terrain
        .tiles()
        .map(|t| center_of(&terrain, t))
        .filter(|c| props.iter().all(|p| Vec2::new(p.x - c.x, p.z - c.z).length() > 0.9))
        .collect::<Vec<_>>();
    assert!(far_from_props.len() > 10);
    let moved = far_from_props.iter().filter(|p| changed(**p)).count();
    assert!(moved * 20 <= far_from_props.len(), "{moved} of {} prop-free points changed", far_from_props.len());
}

/// A low sun from the west, with sharp (2048²) shadow maps.
fn lighting() -> HexLightSettings {
    HexLightSettings { sun_elevation: 22.0, sun_azimuth: 270.0, fog: false, shadow_map_size: 2048, ..default() }
}

fn lighting_direction() -> Vec3 {
    lighting().sun_direction()
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_shadows() {
    let config = relief_map();
    let terrain = Terrain::new(config.clone()).unwrap();
    let (center, size) = view(&terrain);
    let lighting = lighting();
    // The direction the light travels, on the ground.
    let travel = lighting.sun_direction();
    let travel = Vec3::new(travel.x, 0.0, travel.z).normalize();
    let (lit, unlit) = render_pair(
        Scene { config: Some(config), lighting: Some(lighting), then: Some(|_, l, _| l.shadows = false), ..default() },
        "shadows",
    );
    let mountains: Vec<Vec3> = terrain
        .tiles()
        .filter(|&t| terrain.tile_kind(t).unwrap() == TileKind::Mountain)
        .map(|t| center_of(&terrain, t))
        .collect();
    assert!(mountains.len() > 5, "the test map has mountains");
    let hex = terrain.config().layout.hex_size;
    // Pixels the shadows darken are pixels whose ground the terrain hides from the sun (a ray
    // from the ground towards the sun hits the terrain), and most pixels so hidden darken.
    let toward_sun = (-lighting_direction()).to_array().map(f64::from);
    let hidden = |x: u32, y: u32| {
        let (wx, wz) = (
            f64::from(center.x) + (f64::from(x) / f64::from(WIDTH) - 0.5) * f64::from(size.x),
            f64::from(center.y) + (f64::from(y) / f64::from(HEIGHT) - 0.5) * f64::from(size.y),
        );
        let ground = terrain.surface_height(wx, wz).unwrap() + 0.05 * f64::from(hex);
        terrain.raycast([wx, ground, wz], toward_sun, 50.0).is_some()
    };
    let b = |p: &image::Rgb<u8>| p.0.iter().map(|&c| f32::from(c)).sum::<f32>() / (3.0 * 255.0);
    // (darkened, hidden, brightness without shadows) of every sampled pixel on the map.
    let mut samples = Vec::new();
    for (x, y, on) in lit.enumerate_pixels().filter(|(x, y, _)| x % 3 == 0 && y % 3 == 0) {
        let world = Vec2::new(
            center.x + (x as f32 / WIDTH as f32 - 0.5) * size.x,
            center.y + (y as f32 / HEIGHT as f32 - 0.5) * size.y,
        );
        if !terrain.contains(terrain.tile_at(f64::from(world.x), f64::from(world.y)).unwrap()) {
            continue;
        }
        let off = b(unlit.get_pixel(x, y));
        samples.push((off - b(on) > 0.04, hidden(x, y), off));
    }
    let darkened = samples.iter().filter(|s| s.0).count();
    let darkened_hidden = samples.iter().filter(|s| s.0 && s.1).count();
    assert!(darkened > 300, "shadows darken {darkened} sampled pixels");
    assert!(
        darkened_hidden * 10 >= darkened * 7,
        "{darkened_hidden} of {darkened} darkened pixels are hidden from the sun"
    );
    // Ground facing the sun (brighter than the median without shadows) that the terrain hides
    // from it darkens: slopes facing away are dark either way.
    let mut lights: Vec<f32> = samples.iter().map(|s| s.2).collect();
    lights.sort_by(f32::total_cmp);
    let median = lights[lights.len() / 2];
    let sunny_hidden = samples.iter().filter(|s| s.1 && s.2 > median).count();
    let sunny_hidden_dark = samples.iter().filter(|s| s.1 && s.2 > median && s.0).count();
    // The shadow map's bias spares grazing occlusion by low bumps: a share of them darkens, many
    // times the share of the ground the sun sees.
    let sunny_seen = samples.iter().filter(|s| !s.1 && s.2 > median).count();
    let sunny_seen_dark = samples.iter().filter(|s| !s.1 && s.2 > median && s.0).count();
    let (hidden_share, seen_share) =
        (sunny_hidden_dark as f32 / sunny_hidden.max(1) as f32, sunny_seen_dark as f32 / sunny_seen.max(1) as f32);
    assert!(
        hidden_share > 0.3 && hidden_share > 5.0 * seen_share,
        "{sunny_hidden_dark} of {sunny_hidden} sunward pixels hidden from the sun darken, \
         {sunny_seen_dark} of {sunny_seen} seen by it"
    );
    let mean = |img: &image::RgbImage, offset: f32| {
        let points: Vec<f32> =
            mountains.iter().map(|c| brightness(rgb(img, pixel(center, size, *c + travel * offset * hex)))).collect();
        points.iter().sum::<f32>() / points.len() as f32
    };
    let (lee_on, lee_off) = (mean(&lit, 1.1), mean(&unlit, 1.1));
    assert!(
        lee_on < 0.95 * lee_off,
        "the lee side of mountains is darker with shadows: {lee_on} with, {lee_off} without"
    );
    let (sun_on, sun_off) = (mean(&lit, -0.5), mean(&unlit, -0.5));
    assert!(sun_on > 0.93 * sun_off, "the sunny side stays lit: {sun_on} with, {sun_off} without");
}
