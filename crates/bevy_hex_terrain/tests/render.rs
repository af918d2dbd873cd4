//! The terrain material in a real renderer: a known small map from a fixed top-down camera,
//! rendered (Mesa's software Vulkan under Xvfb in CI) and saved with Bevy's screenshot API, then
//! checked pixel by pixel. Each scenario opens its own window, so each runs in a process of its
//! own (`support::in_own_process`, under `xvfb-run` when there is no display): the `#[test]`s
//! here start the `#[ignore]`d scenarios.

#[macro_use]
mod support;

use bevy::math::DVec3;
use bevy::prelude::*;
use bevy_hex_terrain::hex_terrain::{MapConfig, Terrain};
use bevy_hex_terrain::prelude::*;
use support::scene::*;

in_own_process! {
    tiles_show_their_type_color_without_outlines => scenario_outlines_off,
    outlines_darken_tile_borders => scenario_outlines_on,
    textures_and_highlights => scenario_textures_and_highlights,
    a_missing_texture_falls_back_to_flat_colors => scenario_missing_texture,
    a_deferred_camera_draws_the_terrain_colors => scenario_deferred,
    biomes_rivers_and_lakes_show_their_colors => scenario_biomes,
    biomes_rivers_and_lakes_show_their_colors_on_coarse_chunks => scenario_biomes_coarse,
    each_tile_is_drawn_with_its_terrains_texture_layer => scenario_terrain_textures,
    edited_tiles_show_their_new_type => scenario_edited,
    levels_of_detail_meet_without_a_crack => scenario_levels,
    levels_of_detail_meet_without_a_crack_past_a_wrapping_edge => scenario_levels_wrapping,
}

/// Streaming settings whose levels split a top-down view from 50 units up: the chunks under the
/// camera (47 units above the 3-unit mountains) full, those more than about 10 units aside coarse.
fn split_levels() -> HexStreamingSettings {
    HexStreamingSettings { coarse_distance: Some(48.0), ..default() }
}

/// Pixels of the clear color ([`HOLE`]) where the map covers the ground: inside the rectangle
/// of the outermost tile centers (`z` only when `rows_only`, for a wrapping map whose copies
/// cover every `x`).
fn holes_inside(img: &image::RgbImage, terrain: &Terrain, (center, size): (Vec2, Vec2), rows_only: bool) -> usize {
    let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
    for t in terrain.tiles() {
        let [x, _, z] = terrain.tile_center(t).unwrap().map(|v| v as f32);
        lo = lo.min(Vec2::new(x, z));
        hi = hi.max(Vec2::new(x, z));
    }
    let mut holes = 0;
    for (px, py, p) in img.enumerate_pixels() {
        let world = center
            + (Vec2::new(px as f32 + 0.5, py as f32 + 0.5) / Vec2::new(WIDTH as f32, HEIGHT as f32) - 0.5) * size;
        let inside_x = rows_only || (lo.x..=hi.x).contains(&world.x);
        if inside_x && (lo.y..=hi.y).contains(&world.y) && p.0 == HOLE {
            holes += 1;
        }
    }
    holes
}

/// Full and coarse chunks side by side: no crack or hole where they meet, and every clear tile,
/// at either level, shows its type's color at its center.
#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_levels() {
    let config = MapConfig { chunk_size: (4, 4), ..map() };
    let terrain = Terrain::new(config.clone()).unwrap();
    let view = view(&terrain);
    let scene = Scene { config: Some(config), streaming: Some(split_levels()), look_at: Some(view.0), ..default() };
    let (img, counts) = render_scene(scene, "levels");
    let [full, coarse] = counts.levels;
    assert!(full > 0 && coarse > 0, "{full} full and {coarse} coarse chunks: both levels must be in view");
    let holes = holes_inside(&img, &terrain, view, false);
    assert_eq!(holes, 0, "{holes} pixels of the clear color inside the map: cracks where levels meet");
    assert_type_colors(&img, &terrain, &[]);
}

/// The same past a wrapping map's east edge: the copies east of it, full near the camera, meet
/// the map's own chunks, coarse farther west, without a crack.
#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_levels_wrapping() {
    let config = MapConfig { chunk_size: (4, 4), wrap: true, size: MapSize::Bounded { x: 24, z: 14 }, ..map() };
    let terrain = Terrain::new(config.clone()).unwrap();
    // The east edge: the map's last column, and the first copy's first.
    let (center, size) = view(&terrain);
    let edge = Vec2::new(24.0 * 1.5 - 0.75, center.y);
    let scene = Scene { config: Some(config), streaming: Some(split_levels()), look_at: Some(edge), ..default() };
    let (img, counts) = render_scene(scene, "levels_wrapping");
    let [full, coarse] = counts.levels;
    assert!(full > 0 && coarse > 0, "{full} full and {coarse} coarse chunks: both levels must be in view");
    let holes = holes_inside(&img, &terrain, (edge, size), true);
    assert_eq!(holes, 0, "{holes} pixels of the clear color inside the map's rows: cracks where levels meet");
}

/// The world builder's edits on [`map`]: a land tile made deep sea, a sea tile made a high
/// mountain, a mountain tile (or, without one, a second land tile) made mid land; tiles away
/// from the map's edge. Returns the config and each edited tile with its new type.
fn edited_map() -> (MapConfig, Vec<(Hex, TileKind)>) {
    use bevy_hex_terrain::hex_terrain::TileEdit;
    let generated = Terrain::new(map()).unwrap();
    let inner = |k: TileKind, skip: &[Hex]| {
        generated
            .tiles()
            .find(|&t| {
                generated.tile_kind(t) == Some(k) && !skip.contains(&t) && t.range(2).all(|n| generated.contains(n))
            })
            .unwrap_or_else(|| panic!("an inner {k:?} tile"))
    };
    let land = inner(TileKind::Land, &[]);
    let sea = inner(TileKind::Sea, &[]);
    let third = generated
        .tiles()
        .find(|&t| generated.tile_kind(t) == Some(TileKind::Mountain) && t.range(2).all(|n| generated.contains(n)))
        .unwrap_or_else(|| inner(TileKind::Land, &[land]));
    let t = &generated.config().terrain;
    let mid = (t.sea_threshold + t.mountain_threshold) / 2.0;
    let wanted = [(land, TileKind::Sea, 0.05), (sea, TileKind::Mountain, 0.97), (third, TileKind::Land, mid)];
    let mut config = map();
    for (tile, kind, height) in wanted {
        let [col, row] = generated.offset_of(tile);
        config.edits.push(TileEdit { height: Some(height), kind: Some(kind), ..TileEdit::at((col, row)) });
    }
    (config, wanted.iter().map(|&(t, k, _)| (t, k)).collect())
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_edited() {
    let (config, edited) = edited_map();
    let terrain = Terrain::new(config.clone()).unwrap();
    let (center, size) = view(&terrain);
    let (img, _) = render_scene(Scene { config: Some(config), ..default() }, "edited");
    for &(tile, kind) in &edited {
        assert_eq!(terrain.tile_kind(tile), Some(kind), "{tile:?} edited to {kind:?}");
        let at = DVec3::from_array(terrain.tile_center(tile).unwrap()).as_vec3();
        assert_kind_color(tile, kind, rgb(&img, pixel(center, size, at)));
    }
    // Every other clear tile keeps its type's color.
    let checked = check_type_colors(&img, &terrain, &[]);
    assert!(checked.iter().sum::<usize>() > 20, "tiles checked: {checked:?}");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_biomes() {
    biomes(false);
}

/// Every chunk drawn coarse: biomes, rivers and lakes read the same.
#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_biomes_coarse() {
    biomes(true);
}

/// Textures on a map with a climate: each tile is drawn with its terrain's layer of the texture
/// array. The wet map under Civilization V's ruleset (forests on layer 5, deserts 3, snow and
/// tundra 4: not the layers the relief's heights would pick) rendered twice, the second time
/// with the forest layer swapped for the bright snow texture: every tile of layer 5 (dark
/// forest, far from white) brightens, every other tile stays as it was, at its center and near
/// each of its six edges (where a triangle's corners are shared with the neighbors, so the
/// layer must be the one of the tile's own class).
#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_terrain_textures() {
    let config = MapConfig { ruleset: Some("assets/rulesets/civ5.terrain.ron".into()), ..wet_map() };
    let terrain = Terrain::new(config.clone()).unwrap();
    let (center, size) = view(&terrain);
    let material = HexTerrainMaterialSettings { textures: true, ..default() };
    let (forest, snow) = render_pair(
        Scene {
            config: Some(config),
            material,
            then: Some(|_, _, material| material.texture_paths[5] = "textures/snow.png".into()),
            ..default()
        },
        "terrain_textures",
    );
    let ruleset = terrain.ruleset();
    let luma = |img: &image::RgbImage, at: DVec3| {
        let [r, g, b] = rgb(img, pixel(center, size, at.as_vec3()));
        0.3 * r + 0.6 * g + 0.1 * b
    };
    let (mut swapped, mut kept) = (0, 0);
    for h in terrain.tiles().filter(|&h| terrain.river(h).is_none() && terrain.lake(h).is_none()) {
        let t = terrain.tile_info(h).unwrap().terrain;
        let layer = t.feature.map_or(ruleset.terrain(t.terrain).look.texture, |f| ruleset.feature(f).look.texture);
        // The center, and 0.42 of the way to each dry neighbor's center: in the tile's outer
        // ring of triangles, short of its edge (at 0.5; water beside a river or a lake covers
        // the texture).
        let middle = DVec3::from_array(terrain.tile_center(h).unwrap());
        let near_edges = h.all_neighbors().map(|nb| {
            let dry = terrain.river(nb).is_none() && terrain.lake(nb).is_none();
            terrain.tile_center(nb).filter(|_| dry).map(|c| middle + (DVec3::from_array(c) - middle) * 0.42)
        });
        for (k, at) in std::iter::once(Some(middle)).chain(near_edges).enumerate() {
            let Some(at) = at else { continue };
            let (before, after) = (luma(&forest, at), luma(&snow, at));
            if layer == 5 {
                assert!(after > before * 1.1, "tile {h:?} of layer 5 at {k}: {before} with forest, {after} with snow");
            } else {
                assert!((after - before).abs() < 0.02, "tile {h:?} of layer {layer} at {k}: {before}, then {after}");
            }
        }
        if layer == 5 {
            swapped += 1;
        } else {
            kept += 1;
        }
    }
    assert!(swapped >= 5 && kept > 20, "{swapped} tiles of layer 5, {kept} of others");
}

/// Renders the wet map, every chunk coarse if `coarse`, and checks each tile's center shows its
/// biome and each river tile's center water.
fn biomes(coarse: bool) {
    let terrain = Terrain::new(wet_map()).unwrap();
    let (center, size) = view(&terrain);
    let streaming = coarse.then(|| HexStreamingSettings { coarse_distance: Some(0.0), ..default() });
    let name = if coarse { "biomes_coarse" } else { "biomes" };
    let (img, counts) = render_scene(Scene { config: Some(wet_map()), streaming, ..default() }, name);
    if coarse {
        assert_eq!(counts.levels[0], 0, "{:?} chunks full, coarse", counts.levels);
    }
    let at = |h: Hex| rgb(&img, pixel(center, size, DVec3::from_array(terrain.tile_center(h).unwrap()).as_vec3()));
    let mut classes = std::collections::BTreeSet::new();
    // With two inner rings the center and the first ring take the tile's own color, so a
    // center pixel shows its biome unblended.
    for (hex, biome) in
        terrain.tiles().map(|t| (t, terrain.ruleset().biome(terrain.tile_info(t).unwrap().terrain.terrain).unwrap()))
    {
        if terrain.river(hex).is_some() {
            continue;
        }
        let [r, g, b] = at(hex);
        let c = [r, g, b];
        let spread = r.max(g).max(b) - r.min(g).min(b);
        let class = match biome {
            Biome::Ocean | Biome::Coast | Biome::Lake => {
                assert!(b > r + 0.1 && b > g, "{biome:?} tile {hex:?} drawn {c:?}");
                "water"
            }
            Biome::Desert | Biome::Plains | Biome::Hills => {
                assert!(r > b + 0.1, "{biome:?} tile {hex:?} drawn {c:?}");
                "dry"
            }
            Biome::Grassland | Biome::Forest | Biome::Rainforest => {
                assert!(g > r && g > b, "{biome:?} tile {hex:?} drawn {c:?}");
                "green"
            }
            Biome::Snow | Biome::SnowPeak => {
                assert!(brightness(c) > 0.6 && spread < 0.15, "{biome:?} tile {hex:?} drawn {c:?}");
                "snow"
            }
            Biome::Tundra | Biome::Rock => {
                assert!(spread < 0.2, "{biome:?} tile {hex:?} drawn {c:?}");
                "grey"
            }
        };
        classes.insert(class);
    }
    assert!(classes.len() >= 4, "the test map shows several biome classes: {classes:?}");
    // A river tile's center shows water; a point of it away from the channel shows its biome.
    let rivers = terrain.rivers();
    assert!(!rivers.is_empty(), "the test map has rivers");
    for river in &rivers {
        let [r, g, b] = at(river.hex);
        assert!(b > r && b > g, "river tile {:?} center drawn {:?}", river.hex, [r, g, b]);
    }
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_outlines_off() {
    let terrain = Terrain::new(map()).unwrap();
    let material = HexTerrainMaterialSettings { outlines: false, outline_width: 0.1, ..default() };
    let (img, counts) = render_scene(Scene { material, ..default() }, "outlines_off");
    assert_type_colors(&img, &terrain, &[]);
    let ratio = border_to_center(&img, &terrain);
    assert!(ratio > 0.85, "without outlines, borders look like centers: {ratio}");
    // Streaming chunks in changes neither the map nor the material.
    assert!(counts.frames > 20, "{} frames", counts.frames);
    assert_eq!(counts.map_changed, 1, "HexMap changed only when inserted");
    assert_eq!(counts.material_modified, 0, "the material was rewritten with unchanged parameters");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_deferred() {
    let terrain = Terrain::new(map()).unwrap();
    let (img, _) = render_scene(Scene { deferred: true, ..default() }, "deferred");
    assert_type_colors(&img, &terrain, &[]);
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_outlines_on() {
    let terrain = Terrain::new(map()).unwrap();
    let img = render(true, "outlines_on");
    let ratio = border_to_center(&img, &terrain);
    assert!(ratio < 0.6, "with outlines, borders are darker than centers: {ratio}");
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_textures_and_highlights() {
    let terrain = Terrain::new(map()).unwrap();
    let (center, size) = view(&terrain);
    let (hovered, selected) = highlighted(&terrain);
    let (img, _) = render_scene(
        Scene {
            material: HexTerrainMaterialSettings { textures: true, ..default() },
            tiles: Some(|terrain, states| {
                let (hovered, selected) = highlighted(terrain);
                states.set_highlight(hovered, Highlight::Hovered, true).unwrap();
                states.replace_highlight(Highlight::Reachable, selected);
            }),
            ..default()
        },
        "textures_highlights",
    );
    let mut tinted = selected.clone();
    tinted.push(hovered);
    assert_type_colors(&img, &terrain, &tinted);
    let at = |h: Hex| rgb(&img, pixel(center, size, DVec3::from_array(terrain.tile_center(h).unwrap()).as_vec3()));
    let [r, g, _] = at(hovered);
    assert!(r > g * 0.8, "the hovered land tile is tinted warm: {:?}", at(hovered));
    for h in selected {
        let [r, _, b] = at(h);
        assert!(b > r, "a reachable land tile is tinted blue: {:?}", at(h));
    }
}

/// The hovered and the reachable tiles of the highlight scenario: clear land tiles.
fn highlighted(terrain: &Terrain) -> (Hex, Vec<Hex>) {
    let land: Vec<Hex> =
        clear_tiles(terrain).into_iter().filter(|(_, k, _)| *k == TileKind::Land).map(|(h, _, _)| h).collect();
    (land[0], land[1..4].to_vec())
}

#[test]
#[ignore = "a scenario: run by its #[test] in a process of its own"]
fn scenario_missing_texture() {
    let terrain = Terrain::new(map()).unwrap();
    let mut material = HexTerrainMaterialSettings { textures: true, ..default() };
    material.texture_paths[1] = "textures/no_such_grass.png".into();
    let (img, _) = render_scene(Scene { material, ..default() }, "missing_texture");
    let magenta = img.pixels().filter(|p| p[0] > 150 && p[2] > 150 && p[1] < 80).count();
    assert_eq!(magenta, 0, "no magenta error color");
    assert_type_colors(&img, &terrain, &[]);
}
