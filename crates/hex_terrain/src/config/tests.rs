use super::*;

fn rejects(mutate: impl FnOnce(&mut MapConfig), field: &str) {
    let mut config = MapConfig::default();
    mutate(&mut config);
    let err = config.validate().expect_err(field);
    assert_eq!(err.field, field, "{err}");
    let text = err.to_string();
    assert!(text.contains(field) && text.contains("allowed"), "{text}");
}

#[test]
fn defaults_are_map0_and_valid() {
    let c = MapConfig::default();
    c.validate().unwrap();
    assert_eq!((c.seed, c.noise.octaves, c.noise.scale), (1000, 10, 40.0));
    assert_eq!((c.terrain.sea_threshold, c.terrain.mountain_threshold), (0.3, 0.7));
    assert_eq!(c.terrain.inner_rings, 1);
}

#[test]
fn every_bad_value_names_its_field() {
    rejects(|c| c.noise.octaves = 0, "noise.octaves");
    rejects(|c| c.noise.octaves = 33, "noise.octaves");
    rejects(|c| c.noise.persistence = 0.0, "noise.persistence");
    rejects(|c| c.noise.persistence = 1.5, "noise.persistence");
    rejects(|c| c.noise.persistence = f64::NAN, "noise.persistence");
    rejects(|c| c.noise.lacunarity = 0.5, "noise.lacunarity");
    rejects(|c| c.noise.lacunarity = f64::INFINITY, "noise.lacunarity");
    rejects(|c| c.noise.scale = 0.0, "noise.scale");
    rejects(|c| c.noise.scale = f64::NAN, "noise.scale");
    rejects(|c| c.terrain.max_elevation = -1.0, "terrain.max_elevation");
    rejects(|c| c.terrain.max_elevation = f32::INFINITY, "terrain.max_elevation");
    rejects(|c| c.terrain.sea_threshold = f32::NAN, "terrain.sea_threshold");
    rejects(|c| c.terrain.sea_threshold = 0.8, "terrain.sea_threshold");
    rejects(|c| c.terrain.mountain_threshold = 1.2, "terrain.mountain_threshold");
    rejects(|c| c.terrain.interpolation_tolerance = 0.2, "terrain.interpolation_tolerance");
    rejects(|c| c.terrain.interpolation_tolerance = -0.01, "terrain.interpolation_tolerance");
    rejects(|c| c.terrain.inner_rings = 0, "terrain.inner_rings");
    rejects(|c| c.terrain.inner_rings = 99, "terrain.inner_rings");
    rejects(|c| c.layout.hex_size = 0.0, "layout.hex_size");
    rejects(|c| c.layout.hex_size = f32::NAN, "layout.hex_size");
    rejects(|c| c.chunk_size = (0, 8), "chunk_size");
    rejects(
        |c| {
            c.chunk_size = (512, 512);
            c.terrain.inner_rings = 16;
        },
        "chunk_size",
    );
    rejects(|c| c.offset = (0, i32::MIN), "offset");
    rejects(|c| c.appearance.blend = 1.5, "appearance.blend");
    rejects(|c| c.size = MapSize::Bounded { x: 0, z: 10 }, "size");
    rejects(|c| c.size = MapSize::Bounded { x: 1_000_000, z: 1_000_000 }, "size");
    rejects(|c| c.shape = Shape::Island { a: 0.0, b: 6.0 }, "shape.a");
    rejects(|c| c.shape = Shape::Mediterranean { a: 1.0, b: f32::NAN }, "shape.b");
    rejects(|c| c.shape = Shape::Inland { min: 0.5, max: 0.4 }, "shape.max");
    rejects(|c| c.shape = Shape::Inland { min: -0.5, max: 0.4 }, "shape.min");
    rejects(
        |c| {
            c.size = MapSize::Unbounded;
            c.shape = Shape::Island { a: 3.0, b: 6.0 };
        },
        "shape",
    );
}

#[test]
fn malformed_ron_reports_line_and_column() {
    let err = MapConfig::from_ron("(\n  seed: 1,\n  noise: (octaves: \"ten\"),\n)").unwrap_err();
    let LoadError::Ron(spanned) = &err else { panic!("{err}") };
    assert_eq!(spanned.span.start.line, 3);
    assert!(err.to_string().contains("3:"), "{err}");
    let err = MapConfig::from_ron("(seed: 1, color: 3)").unwrap_err();
    assert!(matches!(err, LoadError::Ron(_)), "unknown fields are refused: {err}");
    let err = MapConfig::from_ron("(noise: (octaves: 0))").unwrap_err();
    assert!(matches!(&err, LoadError::Invalid(e) if e.field == "noise.octaves"), "{err}");
}

#[test]
fn ron_round_trips() {
    let mut c = MapConfig { shape: Shape::Island { a: 3.0, b: 6.0 }, ..MapConfig::default() };
    c.manipulation.pull = PullMode::Thesis;
    c.layout.orientation = Orientation::Pointy;
    let back = MapConfig::from_ron(&c.to_ron()).unwrap();
    assert_eq!(back, c);
}

#[test]
fn a_map_file_clamps_its_blend_and_refuses_the_rest() {
    let file = MapFile::from_bytes(b"(seed: 3, appearance: (blend: 1.5))").unwrap();
    assert_eq!((file.config.seed, file.config.appearance.blend, file.clamped_blend), (3, 1.0, Some(1.5)));
    let file = MapFile::from_bytes(b"(appearance: (blend: NaN))").unwrap();
    assert_eq!(file.config.appearance.blend, AppearanceConfig::default().blend);
    assert!(file.clamped_blend.is_some_and(f32::is_nan));
    assert_eq!(MapFile::from_bytes(b"(seed: 3)").unwrap().clamped_blend, None);
    let err = MapFile::from_bytes(b"(seed: 3, name: \"\xff\")").unwrap_err();
    assert!(matches!(err, LoadError::Utf8(_)), "{err}");
    let err = MapFile::from_bytes(b"(noise: (octaves: 40))").unwrap_err();
    assert!(err.to_string().contains("noise.octaves") && err.to_string().contains("1..=32"), "{err}");
}
