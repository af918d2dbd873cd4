//! The thesis' filter use: an existing heightmap tiled with the same classification.

use std::sync::Arc;

use hex_terrain::{HeightImage, HeightSourceConfig, ImageError, MapConfig, MapSize, Terrain, TileKind};

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
    let t = Terrain::with_sources(config, Some(image.clone()), None).unwrap();
    let b = t.bounds().unwrap();
    // The image spans the tile centers' extent.
    let centers: Vec<[f64; 3]> = t.tiles().map(|h| t.tile_center(h).unwrap()).collect();
    let extent = |axis: usize| {
        let lo = centers.iter().map(|c| c[axis]).fold(f64::MAX, f64::min);
        let hi = centers.iter().map(|c| c[axis]).fold(f64::MIN, f64::max);
        (lo, hi)
    };
    let ((min_x, max_x), (min_z, max_z)) = (extent(0), extent(2));
    let (mut sea, mut dry) = (0, 0);
    for oc in b.iter() {
        let tile = t.tile_from_offset(oc);
        // Where the tile center falls on the image.
        let [x, _, z] = t.tile_center(tile).unwrap();
        let kind = t.tile_kind(tile).unwrap();
        // Sample the image as the source does (u over x extent, v over z extent).
        let u = (x - min_x) / (max_x - min_x);
        let v = (z - min_z) / (max_z - min_z);
        let value = image.sample(u, v) as f32;
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
    // A device named as the heightmap is refused, not read forever.
    let err = HeightImage::load(std::path::Path::new("/dev/zero")).unwrap_err();
    assert!(err.to_string().contains("not a regular file"), "{err}");
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

/// CRC-32 of a PNG chunk (type and data).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// A PNG whose header claims `width x height` 8-bit grey pixels, with an empty image stream.
fn png_header_only(width: u32, height: u32) -> Vec<u8> {
    let mut png = vec![0x89, b'P', b'N', b'G', 13, 10, 26, 10];
    let mut chunk = |kind: &[u8], data: &[u8]| {
        png.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let body: Vec<u8> = kind.iter().chain(data).copied().collect();
        png.extend_from_slice(&body);
        png.extend_from_slice(&crc32(&body).to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&width.to_be_bytes());
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    png
}

#[test]
fn oversized_heightmaps_are_refused_from_their_header() {
    let err = HeightImage::from_png_bytes(&png_header_only(100_000, 90_000)).unwrap_err();
    assert!(matches!(err, ImageError::TooLarge(100_000, 90_000)), "{err}");
    assert!(err.to_string().contains("100000x90000") && err.to_string().contains("8192x8192"), "{err}");
    // Within the limit, the same (truncated) stream is a decode error, not a size error.
    let err = HeightImage::from_png_bytes(&png_header_only(64, 64)).unwrap_err();
    assert!(matches!(err, ImageError::Decode(_)), "{err}");
}
