//! The thesis' filter use: an existing heightmap tiled with the same classification.

use std::sync::Arc;

use hex_terrain::{HeightImage, HeightSourceConfig, MapConfig, MapSize, Terrain, TileKind};

/// A radial hill: 1 in the middle, 0 at the corners.
fn hill(size: usize) -> HeightImage {
    let c = (size - 1) as f32 / 2.0;
    let data = (0..size * size)
        .map(|i| {
            let (x, y) = ((i % size) as f32 - c, (i / size) as f32 - c);
            (1.0 - (x * x + y * y).sqrt() / (c * 1.2)).max(0.0)
        })
        .collect();
    HeightImage::from_samples(size, size, data).unwrap()
}

#[test]
fn pixels_below_sea_level_become_sea_tiles() {
    let image = Arc::new(hill(101));
    let sea_level = 0.4;
    let config = MapConfig {
        source: HeightSourceConfig::Image { path: "hill.png".into(), sea_level },
        size: MapSize::Bounded { x: 24, z: 20 },
        ..MapConfig::default()
    };
    let t = Terrain::with_image(config, Some(image.clone())).unwrap();
    let b = t.bounds().unwrap();
    // The image spans the tile centers' extent.
    let centers: Vec<[f32; 3]> = t.tiles().map(|h| t.tile_center(h)).collect();
    let extent = |axis: usize| {
        let lo = centers.iter().map(|c| c[axis]).fold(f32::MAX, f32::min);
        let hi = centers.iter().map(|c| c[axis]).fold(f32::MIN, f32::max);
        (lo, hi)
    };
    let ((min_x, max_x), (min_z, max_z)) = (extent(0), extent(2));
    let (mut sea, mut dry) = (0, 0);
    for oc in b.iter() {
        let tile = t.tile_from_offset(oc);
        // Where the tile center falls on the image.
        let [x, _, z] = t.tile_center(tile);
        let kind = t.tile_kind(tile);
        // Sample the image as the source does (u over x extent, v over z extent).
        let u = (x - min_x) / (max_x - min_x);
        let v = (z - min_z) / (max_z - min_z);
        let value = image.sample(f64::from(u), f64::from(v)) as f32;
        if value < sea_level - 0.02 {
            assert_eq!(kind, TileKind::Sea, "{oc:?} image {value}");
            sea += 1;
        } else if value > sea_level + 0.02 {
            assert_ne!(kind, TileKind::Sea, "{oc:?} image {value}");
            dry += 1;
        }
    }
    assert!(sea > 20 && dry > 20, "both sides are exercised: {sea} sea, {dry} dry");
}

#[test]
fn bad_images_are_errors_not_panics() {
    assert!(HeightImage::from_png_bytes(b"not a png").is_err());
    assert!(HeightImage::from_png_bytes(&[0x89, b'P', b'N', b'G', 13, 10, 26, 10, 0, 0]).is_err());
    assert!(HeightImage::from_samples(0, 0, vec![]).is_err());
    let missing = MapConfig {
        source: HeightSourceConfig::Image { path: "/nonexistent/height.png".into(), sea_level: 0.3 },
        ..MapConfig::default()
    };
    let err = Terrain::new(missing).unwrap_err();
    assert_eq!(err.field, "source.path");
    let bad_level = MapConfig {
        source: HeightSourceConfig::Image { path: "x.png".into(), sea_level: 1.5 },
        ..MapConfig::default()
    };
    assert_eq!(Terrain::new(bad_level).unwrap_err().field, "source.sea_level");
    let unbounded = MapConfig {
        source: HeightSourceConfig::Image { path: "x.png".into(), sea_level: 0.5 },
        size: MapSize::Unbounded,
        ..MapConfig::default()
    };
    assert_eq!(Terrain::new(unbounded).unwrap_err().field, "source");
}
