//! The minimap picture, property-based over random maps: every pixel shows the tile under its
//! center, colors follow the tiles and their state, a repaint equals a full paint and touches
//! only the changed tiles and their neighbors, a wrapping picture wraps, outlines stay on the
//! picture.

use std::collections::HashMap;

use hex_terrain::hexx::Hex;
use hex_terrain::minimap::{Minimap, MinimapStyle, TileLook};
use hex_terrain::save::FogState;
use hex_terrain::{MapConfig, MapSize, Orientation, RiverConfig, Terrain, TileKind, TileRect};
use proptest::prelude::*;

#[path = "common/biome.rs"]
mod biome;
mod common;

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        columns in 4u32..40,
        rows in 2u32..30,
        pointy in any::<bool>(),
        wrap in any::<bool>(),
        unbounded in prop::bool::weighted(0.2),
        hex_size in 0.5f32..3.0,
        climate in any::<bool>(),
        rivers in any::<bool>(),
    ) -> MapConfig {
        let mut c = MapConfig { seed, ..MapConfig::default() };
        c.size = if unbounded { MapSize::Unbounded } else { MapSize::Bounded { x: columns, z: rows } };
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        c.layout.hex_size = hex_size;
        c.climate.enabled = climate;
        if rivers && !unbounded {
            c.rivers = RiverConfig { enabled: true, threshold: 2.0, ..RiverConfig::default() };
        }
        common::wrapping(c, wrap && !unbounded)
    }
}

/// The region shown: a bounded map's tiles, or a rectangle of an unbounded world.
fn region(terrain: &Terrain, at: [i32; 2]) -> TileRect {
    terrain.bounds().unwrap_or(TileRect::new(at, [24, 18]))
}

fn minimap(terrain: &Terrain, at: [i32; 2], size: [u32; 2]) -> Minimap {
    Minimap::new(terrain, region(terrain, at), size, MinimapStyle::default()).expect("a region on the map")
}

/// A deterministic look per tile from a table, visible and unowned elsewhere.
fn look_of(table: &HashMap<Hex, TileLook>) -> impl Fn(Hex) -> TileLook + '_ {
    |t| table.get(&t).copied().unwrap_or(TileLook::VISIBLE)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Every pixel shows the tile the map has under the pixel's center (none off the map), and
    /// a tile's pixels are exactly the pixels showing it.
    #[test]
    fn pixels_show_the_tile_under_them(config in config(), at in (-1000i32..1000, -1000i32..1000), size in (8u32..200, 8u32..200)) {
        let terrain = Terrain::new(config).unwrap();
        let map = minimap(&terrain, [at.0, at.1], [size.0, size.1]);
        let [w, h] = map.size();
        prop_assert!(w >= 1 && h >= 1 && w <= size.0 && h <= size.1);
        // The picture fills its size along one axis at least (square pixels, fitted).
        prop_assert!(w == size.0 || h == size.1 || map.wraps(), "{w}x{h} in {size:?}");
        let region = map.region();
        let mut counts: HashMap<Hex, usize> = HashMap::new();
        for py in 0..h {
            for px in 0..w {
                let [x, z] = map.pixel_to_world(f64::from(px) + 0.5, f64::from(py) + 0.5);
                let want = terrain.tile_at(x, z).filter(|&t| terrain.contains(t) && region.contains(terrain.offset_of(t)));
                let got = map.tile_at_pixel(px, py);
                prop_assert_eq!(got, want, "pixel ({}, {})", px, py);
                if let Some(t) = got {
                    *counts.entry(t).or_default() += 1;
                    prop_assert!(map.pixels_of(t).contains(&(py * w + px)));
                }
            }
        }
        for (t, n) in counts {
            prop_assert_eq!(map.pixels_of(t).len(), n);
        }
        prop_assert_eq!(map.tile_at_pixel(w, 0), None);
    }

    /// With every tile visible and unowned, a tile's center pixel has its biome's color (maps
    /// with climate or rivers) or its type's; unexplored tiles are the unexplored color, explored
    /// ones darker than visible ones.
    #[test]
    fn colors_follow_the_tiles(config in config()) {
        let terrain = Terrain::new(config).unwrap();
        let map = minimap(&terrain, [0, 0], [300, 300]);
        let style = MinimapStyle::default();
        let visible = map.paint(|_| TileLook::VISIBLE);
        let unexplored = map.paint(|_| TileLook { fog: FogState::Unexplored, owner: None });
        let explored = map.paint(|_| TileLook { fog: FogState::Explored, owner: None });
        let w = map.size()[0];
        for tile in region(&terrain, [0, 0]).iter().map(|oc| terrain.tile_from_offset(oc)).take(400) {
            let [x, _, z] = terrain.tile_center(tile).unwrap();
            let [px, py] = map.world_to_pixel(x, z);
            let (px, py) = (px as u32, py as u32);
            let Some(shown) = map.tile_at_pixel(px, py) else { continue };
            prop_assert_eq!(Some(shown), terrain.wrap_tile(tile));
            let i = ((py * w + px) * 4) as usize;
            let river = terrain.river(tile).is_some();
            if !river {
                let want = if terrain.lake(tile).is_some() {
                    style.water_color
                } else if terrain.has_vertex_colors() {
                    biome::at(&terrain, tile).unwrap().color()
                } else {
                    style.kind_colors[terrain.tile_kind(tile).unwrap_or(TileKind::Sea) as usize]
                };
                prop_assert_eq!(&visible[i..i + 3], &want[..], "tile {:?}", tile);
            }
            prop_assert_eq!(&unexplored[i..i + 4], &style.unexplored[..]);
            let luma = |p: &[u8]| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]);
            prop_assert!(luma(&explored[i..]) < luma(&visible[i..]) || luma(&visible[i..]) == 0);
        }
    }

    /// A sequence of state writes, each repainted: the picture equals a full paint after every
    /// write, and the pixels that changed belong to the written tiles or their neighbors.
    #[test]
    fn a_repaint_equals_a_full_paint_and_stays_local(
        config in config(),
        writes in prop::collection::vec((0u32..10_000, 0u8..3, prop::option::of(0u32..5)), 1..24),
    ) {
        let terrain = Terrain::new(config).unwrap();
        let map = minimap(&terrain, [0, 0], [160, 120]);
        let tiles: Vec<Hex> = region(&terrain, [0, 0]).iter().map(|oc| terrain.tile_from_offset(oc)).collect();
        let mut table: HashMap<Hex, TileLook> = HashMap::new();
        let mut rgba = map.paint(look_of(&table));
        for (pick, fog, owner) in writes {
            let tile = tiles[pick as usize % tiles.len()];
            let fog = [FogState::Unexplored, FogState::Explored, FogState::Visible][fog as usize];
            table.insert(tile, TileLook { fog, owner });
            let before = rgba.clone();
            map.repaint([tile], look_of(&table), &mut rgba);
            prop_assert_eq!(&rgba, &map.paint(look_of(&table)));
            let mut near: Vec<u32> = map.pixels_of(tile).to_vec();
            for n in tile.all_neighbors() {
                near.extend_from_slice(map.pixels_of(n));
            }
            for (i, (a, b)) in before.chunks_exact(4).zip(rgba.chunks_exact(4)).enumerate() {
                if a != b {
                    prop_assert!(near.contains(&(i as u32)), "pixel {} changed, far from {:?}", i, tile);
                }
            }
        }
    }

    /// A globe's picture the same: after each write a repaint of the written tile equals a full
    /// paint, the pixels that changed are the tile's or touch one (east, west, north, south),
    /// and the count it returns is the pixels that changed.
    #[test]
    fn a_globes_repaint_equals_a_full_paint_and_stays_local(
        frequency in 2u32..12,
        half_width in 4u32..200,
        fog_drawn in any::<bool>(),
        writes in prop::collection::vec((0u32..10_000, 0u8..3, prop::option::of(0u32..5)), 1..16),
    ) {
        use hex_terrain::minimap::GlobeMinimap;
        use hex_terrain::{GlobeTerrain, GlobeTile};
        let config = MapConfig::from_ron(&format!("(seed: {frequency}, size: Globe(frequency: {frequency}))")).unwrap();
        let globe = GlobeTerrain::new(config).unwrap();
        let style = MinimapStyle { fog_of_war: fog_drawn, ..MinimapStyle::default() };
        let map = GlobeMinimap::new(&globe, half_width * 2, style).unwrap();
        let [w, h] = map.size();
        let tiles = globe.grid().tile_count();
        let mut table: HashMap<GlobeTile, TileLook> = HashMap::new();
        let look = |table: &HashMap<GlobeTile, TileLook>| {
            let table = table.clone();
            move |t: GlobeTile| table.get(&t).copied().unwrap_or(TileLook::VISIBLE)
        };
        let mut rgba = map.paint(look(&table));
        for (pick, fog, owner) in writes {
            let tile = GlobeTile(pick % tiles);
            let fog = [FogState::Unexplored, FogState::Explored, FogState::Visible][fog as usize];
            table.insert(tile, TileLook { fog, owner });
            let before = rgba.clone();
            let changed = map.repaint([tile, GlobeTile(tiles + pick)], look(&table), &mut rgba);
            prop_assert_eq!(&rgba, &map.paint(look(&table)));
            let mut count = 0;
            for (i, (a, b)) in before.chunks_exact(4).zip(rgba.chunks_exact(4)).enumerate() {
                if a == b {
                    continue;
                }
                count += 1;
                let (x, y) = (i as u32 % w, i as u32 / w);
                let touching = [(x, y), ((x + 1) % w, y), ((x + w - 1) % w, y), (x, y.saturating_sub(1)), (x, (y + 1).min(h - 1))]
                    .iter()
                    .any(|&(x, y)| map.tile_at_pixel(x, y) == Some(tile));
                prop_assert!(touching, "pixel {} changed, away from {:?}", i, tile);
            }
            prop_assert_eq!(changed, count);
        }
    }

    /// An owned tile's pixels next to an edge with nobody are the owner's color; its inner
    /// pixels are tinted, not replaced.
    #[test]
    fn owners_draw_borders(config in config(), pick in 0u32..10_000) {
        let terrain = Terrain::new(config).unwrap();
        let map = minimap(&terrain, [0, 0], [400, 400]);
        let tiles: Vec<Hex> = region(&terrain, [0, 0]).iter().map(|oc| terrain.tile_from_offset(oc)).collect();
        let tile = tiles[pick as usize % tiles.len()];
        let style = MinimapStyle::default();
        let owned = map.paint(|t| TileLook { fog: FogState::Visible, owner: (t == tile).then_some(0) });
        let plain = map.paint(|_| TileLook::VISIBLE);
        let [cx, _, cz] = terrain.tile_center(tile).unwrap();
        let [px, py] = map.world_to_pixel(cx, cz);
        let w = map.size()[0];
        let center = ((py as u32 * w + px as u32) * 4) as usize;
        if map.tile_at_pixel(px as u32, py as u32) == terrain.wrap_tile(tile) && map.pixels_of(tile).len() > 30 {
            prop_assert!(owned[center..center + 3] != style.owner_colors[0] || plain[center..center + 3] == style.owner_colors[0]);
            let borders = map.pixels_of(tile).iter().filter(|&&i| owned[i as usize * 4..i as usize * 4 + 3] == style.owner_colors[0]).count();
            prop_assert!(borders > 0, "no border pixel on {:?}", tile);
        }
    }

    /// A wrapping picture spans one period: a position and its copies a period away land on the
    /// same pixel, and the pixels at the east and west edges of a row show neighboring tiles.
    #[test]
    fn a_wrapping_picture_wraps(config in config(), k in -50i32..50, fx in 0.0f64..1.0, fz in 0.0f64..1.0) {
        let terrain = Terrain::new(config).unwrap();
        let Some(wrap) = terrain.wrap().copied() else { return Ok(()) };
        let map = minimap(&terrain, [0, 0], [256, 256]);
        prop_assert!(map.wraps());
        let [w, h] = map.size();
        prop_assert!((f64::from(w) * map.step() - wrap.width).abs() < 1e-9 * wrap.width);
        let [x, z] = map.pixel_to_world(fx * f64::from(w), fz * f64::from(h));
        let a = map.world_to_pixel(x, z);
        let b = map.world_to_pixel(x + f64::from(k) * wrap.width, z);
        prop_assert!((a[0] - b[0]).abs() < 1e-6 || (a[0] - b[0]).abs() > f64::from(w) - 1e-6, "{a:?} {b:?}");
        for py in 0..h {
            if let (Some(west), Some(east)) = (map.tile_at_pixel(0, py), map.tile_at_pixel(w - 1, py)) {
                let d = terrain.distance(west, east).unwrap();
                prop_assert!(d <= 1 + u32::from(map.step() > terrain.geometry().hex_size()), "row {py}: {west:?} {east:?} {d}");
            }
        }
    }

    /// Outlines: a rectangle's outline lies on the rectangle's edges, inside the picture, each
    /// pixel once; a wrapping picture draws a polygon across the seam on both sides; a polygon
    /// far larger than the picture or with non-finite points ends quickly with what is on it.
    #[test]
    fn outlines_stay_on_the_picture(config in config(), a in (0.1f64..0.45, 0.1f64..0.45), b in (0.55f64..0.9, 0.55f64..0.9)) {
        let terrain = Terrain::new(config).unwrap();
        let map = minimap(&terrain, [0, 0], [200, 150]);
        let [w, h] = map.size().map(f64::from);
        let corner = |fx: f64, fy: f64| map.pixel_to_world(fx * w, fy * h);
        let rect = [corner(a.0, a.1), corner(b.0, a.1), corner(b.0, b.1), corner(a.0, b.1)];
        let pixels = map.outline(&rect);
        let mut sorted = pixels.clone();
        sorted.dedup();
        prop_assert_eq!(sorted.len(), pixels.len());
        prop_assert!(!pixels.is_empty());
        for &i in &pixels {
            let (px, py) = (f64::from(i % map.size()[0]), f64::from(i / map.size()[0]));
            let on_x = (px - (a.0 * w).floor()).abs() <= 1.0 || (px - (b.0 * w).floor()).abs() <= 1.0;
            let on_y = (py - (a.1 * h).floor()).abs() <= 1.0 || (py - (b.1 * h).floor()).abs() <= 1.0;
            prop_assert!(on_x || on_y, "pixel ({px}, {py}) is off the rectangle's edges");
        }
        let huge = [[-1e12, -1e12], [1e12, -1e12], [1e12, 1e12], [-1e12, 1e12]];
        prop_assert!(map.outline(&huge).len() <= (map.size()[0] * map.size()[1]) as usize);
        prop_assert!(map.outline(&[[f64::NAN, 0.0], [1.0, 1.0], [2.0, 0.0]]).is_empty());
        if map.wraps() {
            // A rectangle straddling the seam: pixels near both the east and the west edge.
            let seam = [corner(-0.1, 0.3), corner(0.1, 0.3), corner(0.1, 0.7), corner(-0.1, 0.7)];
            let px: Vec<u32> = map.outline(&seam).iter().map(|i| i % map.size()[0]).collect();
            prop_assert!(px.iter().any(|&x| f64::from(x) < 0.2 * w) && px.iter().any(|&x| f64::from(x) > 0.8 * w));
        }
    }
}

/// Regions that miss a bounded map give no picture; sizes are clamped, never zero.
#[test]
fn regions_off_the_map_and_tiny_sizes() {
    let config = MapConfig { size: MapSize::Bounded { x: 10, z: 8 }, ..MapConfig::default() };
    let terrain = Terrain::new(config).unwrap();
    assert!(Minimap::new(&terrain, TileRect::new([20, 20], [5, 5]), [64, 64], MinimapStyle::default()).is_none());
    assert!(Minimap::new(&terrain, TileRect::new([0, 0], [0, 5]), [64, 64], MinimapStyle::default()).is_none());
    let one = Minimap::new(&terrain, terrain.bounds().unwrap(), [0, 0], MinimapStyle::default()).unwrap();
    assert_eq!(one.size(), [1, 1]);
    assert_eq!(one.paint(|_| TileLook::VISIBLE).len(), 4);
    // A region partly off the map is clipped to it.
    let clipped = Minimap::new(&terrain, TileRect::new([-5, -5], [8, 8]), [64, 64], MinimapStyle::default()).unwrap();
    assert_eq!(clipped.region(), TileRect { min: [0, 0], max: [3, 3] });
}

/// A globe's picture: equirectangular (a point and its direction round-trip; each tile's center
/// falls on a pixel of it or of a neighbor, at its info's longitude and latitude); every tile
/// has pixels and every pixel one tile; colors are the tiles' terrains' (a climate) or kinds';
/// fog and owners paint as on a flat map, owners' borders where the owner changes; the view's
/// outline lies on its circle.
#[test]
fn a_globes_picture() {
    use hex_terrain::minimap::GlobeMinimap;
    use hex_terrain::{GlobeTerrain, GlobeTile};
    for (frequency, climate, width) in [(4u32, false, 256u32), (8, true, 512), (11, true, 640)] {
        let config = MapConfig::from_ron(&format!(
            "(seed: {frequency}, size: Globe(frequency: {frequency}), climate: (enabled: {climate}))"
        ))
        .unwrap();
        let globe = GlobeTerrain::new(config).unwrap();
        let style = MinimapStyle::default();
        let map = GlobeMinimap::new(&globe, width, style.clone()).unwrap();
        let [w, h] = map.size();
        assert_eq!([w, h], [width, width / 2]);
        // Round trips.
        for (x, y) in [(0.5, 0.5), (10.25, 7.75), (f64::from(w) - 0.5, f64::from(h) - 0.5), (f64::from(w) / 3.0, 40.0)]
        {
            let [px, py] = map.point_of(map.direction_at(x, y));
            assert!((px - x).abs() < 1e-6 && (py - y).abs() < 1e-6, "{x} {y}: {px} {py}");
        }
        let mut seen = 0;
        for t in globe.grid().tiles() {
            let info = globe.tile_info(t).unwrap();
            let [x, y] = map.point_of(globe.grid().center(t).unwrap());
            let longitude = x / f64::from(w) * 360.0 - 180.0;
            let polar = info.latitude.abs() > 89.999;
            let apart = (longitude - info.longitude + 540.0).rem_euclid(360.0) - 180.0;
            assert!(polar || apart.abs() < 1e-6, "{t:?}: {longitude} {}", info.longitude);
            assert!((90.0 - y / f64::from(h) * 180.0 - info.latitude).abs() < 1e-6);
            let shown = map.tile_at_pixel((x as u32).min(w - 1), (y as u32).min(h - 1)).unwrap();
            let near = shown == t || globe.grid().neighbors(t).unwrap().as_slice().contains(&shown);
            assert!(near, "f {frequency}: the center of {t:?} shows {shown:?}");
            let pixels = map.pixels_of(t);
            assert!(!pixels.is_empty(), "f {frequency}: {t:?} has no pixel");
            for &i in pixels {
                assert_eq!(map.tile_at_pixel(i % w, i / w), Some(t));
            }
            seen += pixels.len();
        }
        assert_eq!(seen, (w * h) as usize);
        // Colors: the terrain's (or the kind's); unexplored; an owner's tint and border.
        let owned = GlobeTile(1);
        let rgba = map.paint(|t| TileLook {
            fog: if t.0 % 7 == 3 { FogState::Unexplored } else { FogState::Visible },
            owner: (t == owned).then_some(0),
        });
        for i in (0..(w * h)).step_by(97) {
            let t = map.tile_at_pixel(i % w, i / w).unwrap();
            let px = &rgba[i as usize * 4..i as usize * 4 + 4];
            let info = globe.tile_info(t).unwrap();
            let [r, g, b] = if climate {
                globe.ruleset().terrain(info.terrain.terrain).look.color
            } else {
                style.kind_colors[info.kind as usize]
            };
            if t.0 % 7 == 3 {
                assert_eq!(px, style.unexplored, "{t:?}");
            } else if t != owned {
                assert_eq!(px, [r, g, b, 255], "{t:?}");
            }
        }
        let pixels = map.pixels_of(owned);
        let edge = pixels.iter().find(|&&i| {
            let (x, y) = (i % w, i / w);
            [(x + 1) % w + y * w, (x + w - 1) % w + y * w, (y + 1).min(h - 1) * w + x]
                .iter()
                .any(|&j| map.tile_at_pixel(j % w, j / w) != Some(owned))
        });
        let i = *edge.expect("a tile has an edge") as usize;
        assert_eq!(&rgba[i * 4..i * 4 + 3], &style.owner_colors[0]);
        // The outline: every pixel's center within a pixel's angle of the circle.
        let d = [0.3, 0.8, -0.52];
        let l = (0.09f64 + 0.64 + 0.2704).sqrt();
        let d = d.map(|c| c / l);
        for angle in [0.3, 1.0, 2.0] {
            let outline = map.view_outline(d, angle);
            assert!(outline.len() > 10);
            for &i in &outline {
                let p = map.direction_at(f64::from(i % w) + 0.5, f64::from(i / w) + 0.5);
                let off = (p[0] * d[0] + p[1] * d[1] + p[2] * d[2]).clamp(-1.0, 1.0).acos() - angle;
                assert!(off.abs() <= 2.0 * std::f64::consts::PI / f64::from(w), "{angle}: {off}");
            }
        }
        assert!(map.view_outline(d, 0.0).is_empty() && map.view_outline(d, 4.0).is_empty());
        // A polygon: every pixel within a pixel's angle of one of its great-circle edges, and
        // each corner's pixel on it.
        let corners = [[0.9, 0.3, 0.1], [0.5, 0.6, -0.5], [-0.2, 0.4, -0.9], [0.3, -0.5, -0.6]];
        let unit = |a: [f64; 3]| {
            let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            a.map(|c| c / l)
        };
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let polygon = map.polygon_outline(&corners);
        let pixel = std::f64::consts::TAU / f64::from(w);
        for &i in &polygon {
            let p = map.direction_at(f64::from(i % w) + 0.5, f64::from(i / w) + 0.5);
            // The angle from p to the arc a-b: to the great circle through them when p projects
            // between them, else to the nearer corner.
            let near = (0..corners.len()).any(|k| {
                let (a, b) = (unit(corners[k]), unit(corners[(k + 1) % corners.len()]));
                let n = unit([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]);
                let off_plane = dot(p, n).asin().abs();
                let ends = dot(p, a).clamp(-1.0, 1.0).acos().min(dot(p, b).clamp(-1.0, 1.0).acos());
                let between = dot(p, a) >= dot(a, b) - 1e-9 && dot(p, b) >= dot(a, b) - 1e-9;
                (if between { off_plane } else { ends }) <= 1.5 * pixel
            });
            assert!(near, "pixel {i} off the polygon");
        }
        for c in corners {
            let [x, y] = map.point_of(unit(c));
            let i = (y as u32).min(h - 1) * w + (x as u32).min(w - 1);
            assert!(polygon.contains(&i), "corner {c:?}");
        }
        assert!(map.polygon_outline(&corners[..1]).is_empty());
    }
    let globe = GlobeTerrain::new(MapConfig::from_ron("(size: Globe(frequency: 3))").unwrap()).unwrap();
    for bad in [0, 3, 8192] {
        assert!(GlobeMinimap::new(&globe, bad, MinimapStyle::default()).is_none(), "{bad}");
    }
}

/// A globe's picture takes an edited globe of its size in place: the tiles it recolors are
/// exactly those whose color differs between the two globes (compared here from their tile
/// infos), and repainting them gives the picture built afresh from the edited globe; a globe of
/// another size is refused.
#[test]
fn a_globes_picture_recolors_an_edited_globe() {
    use hex_terrain::minimap::GlobeMinimap;
    use hex_terrain::{Brush, GlobeEditor, GlobeStroke, GlobeTerrain, GlobeTile, Tool};
    for climate in [false, true] {
        let config =
            MapConfig::from_ron(&format!("(seed: 4, size: Globe(frequency: 9), climate: (enabled: {climate}))"))
                .unwrap();
        let mut editor = GlobeEditor::new(config).unwrap();
        let before = editor.globe().clone();
        let style = MinimapStyle::default();
        let mut map = GlobeMinimap::new(&before, 360, style.clone()).unwrap();
        let look = |t: GlobeTile| TileLook { fog: FogState::Visible, owner: t.0.is_multiple_of(11).then_some(1) };
        let mut rgba = map.paint(look);
        for (tool, tile) in
            [(Tool::SetKind(TileKind::Mountain), 40), (Tool::SetKind(TileKind::Sea), 300), (Tool::Raise(0.2), 500)]
        {
            editor.apply(GlobeStroke { tool, brush: Brush::Range(2), tile: GlobeTile(tile) }).unwrap();
        }
        let after = editor.globe();
        let color = |g: &GlobeTerrain, t: GlobeTile| {
            let info = g.tile_info(t).unwrap();
            if climate {
                let l = &g.ruleset().terrain(info.terrain.terrain).look;
                l.minimap.unwrap_or(l.color)
            } else {
                style.kind_colors[info.kind as usize]
            }
        };
        let differ: Vec<GlobeTile> = after.grid().tiles().filter(|&t| color(&before, t) != color(after, t)).collect();
        assert!(!differ.is_empty(), "climate {climate}: the strokes changed no tile's color");
        let changed = map.recolor(after).unwrap();
        assert_eq!(changed, differ, "climate {climate}");
        map.repaint(changed, look, &mut rgba);
        assert!(rgba == GlobeMinimap::new(after, 360, style.clone()).unwrap().paint(look), "climate {climate}");
        assert_eq!(map.recolor(after), Some(Vec::new()), "nothing more to recolor");
        let other = GlobeTerrain::new(MapConfig::from_ron("(size: Globe(frequency: 8))").unwrap()).unwrap();
        assert!(map.recolor(&other).is_none());
    }
}
