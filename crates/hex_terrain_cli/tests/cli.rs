//! Runs the `hexterrain` binary on small maps: every subcommand on good input, a clear error and
//! a non-zero exit (never a panic) on each bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use hex_terrain::hexx::Hex;
use hex_terrain::{MapConfig, MapSize, Terrain, TileKind};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_hexterrain"))
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hexterrain-cli-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().unwrap()
}

fn ok(args: &[&str]) -> String {
    let out = run(args);
    assert!(out.status.success(), "{args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Fails with a message containing every `needle`, without panicking.
fn fails(args: &[&str], needles: &[&str]) {
    let out = run(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} should fail");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {n:?} not in {err:?}");
    }
}

/// The pixel of `render`'s top-down picture, `width` pixels wide, under each tile's center.
fn center_pixels(terrain: &Terrain, mesh: &hex_terrain::ChunkMesh, width: u32) -> impl Fn(Hex) -> (u32, u32) {
    let (mut min_x, mut max_x, mut min_z) = (f32::MAX, f32::MIN, f32::MAX);
    for p in &mesh.buffers.positions {
        min_x = min_x.min(p[0]);
        max_x = max_x.max(p[0]);
        min_z = min_z.min(p[2]);
    }
    let scale = (width - 1) as f32 / (max_x - min_x);
    move |hex| {
        let [x, _, z] = terrain.tile_center(hex).unwrap().map(|v| v as f32);
        (((x - min_x) * scale).round() as u32, ((z - min_z) * scale).round() as u32)
    }
}

fn small_map(name: &str, extra: &str) -> PathBuf {
    let path = tmp(name);
    std::fs::write(&path, format!("(name: \"small\", size: Bounded(x: 14, z: 12), {extra})")).unwrap();
    path
}

#[test]
fn render_shows_each_tile_type_in_its_color() {
    // Blend 0 so a pixel's color is its layer's; tiles well inside their range only.
    let map = small_map("render.ron", "appearance: (blend: 0.0)");
    let out = tmp("render.png");
    ok(&["render", map.to_str().unwrap(), "-o", out.to_str().unwrap(), "--width", "300"]);
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.width(), 300);

    let config = MapConfig::load(&map).unwrap();
    let terrain = Terrain::new(config).unwrap();
    let mesh = terrain.generate_map().unwrap();
    let at = center_pixels(&terrain, &mesh, 300);
    let mut seen = [0; 3];
    for info in &mesh.tiles {
        let (px, py) = at(info.hex);
        let px = image::Rgb::<u8>::to_owned(img.get_pixel(px, py));
        let [r, g, b] = px.0.map(i32::from);
        match info.kind {
            TileKind::Sea => assert!(b > r + 40 && b > g + 20, "sea tile {:?} drawn {:?}", info.hex, px),
            TileKind::Land => assert!(g > r + 30 && g > b + 30, "land tile {:?} drawn {:?}", info.hex, px),
            TileKind::Mountain => {
                assert!((r - g).abs() < 30 && (g - b).abs() < 30 && r > 90, "mountain {:?} drawn {:?}", info.hex, px);
            }
        }
        seen[info.kind as usize] += 1;
    }
    assert!(seen.iter().all(|&n| n > 0), "the test map has every tile type: {seen:?}");

    // Outlines darken tile borders; raw renders too.
    let outlined = tmp("render_outlines.png");
    ok(&["render", map.to_str().unwrap(), "-o", outlined.to_str().unwrap(), "--width", "300", "--outlines"]);
    let lined = image::open(&outlined).unwrap().to_rgb8();
    let darker = img.pixels().zip(lined.pixels()).filter(|(a, b)| b.0[1] < a.0[1]).count();
    assert!(darker > 1000, "outlines drew {darker} darker pixels");
    let raw = tmp("render_raw.png");
    ok(&["render", map.to_str().unwrap(), "-o", raw.to_str().unwrap(), "--width", "200", "--raw"]);
    assert_eq!(image::open(&raw).unwrap().width(), 200);
}

#[test]
fn bad_input_gives_clear_errors() {
    let out = tmp("bad.png");
    let o = out.to_str().unwrap();
    fails(&["render", "/no/such/map.ron", "-o", o], &["/no/such/map.ron", "cannot read"]);
    let malformed = tmp("malformed.ron");
    std::fs::write(&malformed, "(\n  seed: 1,\n  noise: (octaves: \"ten\"),\n)").unwrap();
    fails(&["render", malformed.to_str().unwrap(), "-o", o], &["3:"]);
    let invalid = small_map("invalid.ron", "noise: (octaves: 0)");
    fails(&["stats", invalid.to_str().unwrap()], &["noise.octaves", "allowed"]);
    let unbounded = tmp("unbounded.ron");
    std::fs::write(&unbounded, "(size: Unbounded)").unwrap();
    fails(&["render", unbounded.to_str().unwrap(), "-o", o], &["bounded"]);
    let map = small_map("ok.ron", "");
    fails(&["render", map.to_str().unwrap(), "-o", o, "--width", "0"], &["--width"]);
    fails(&["render", map.to_str().unwrap(), "-o", "/no/such/dir/x.png"], &["/no/such/dir/x.png"]);
    fails(&["export", map.to_str().unwrap(), "-o", tmp("x.stl").to_str().unwrap()], &[".glb or .obj"]);
    fails(&["render", map.to_str().unwrap(), "-o", o, "--blend", "2"], &["appearance.blend"]);
}

/// Writes a radial hill heightmap (1 in the middle, 0 at the corners) as a PNG.
fn hill_png(path: &Path, size: u32, sixteen_bit: bool) {
    let c = (size - 1) as f32 / 2.0;
    let value = |x: u32, y: u32| {
        let (dx, dy) = (x as f32 - c, y as f32 - c);
        (1.0 - (dx * dx + dy * dy).sqrt() / (c * 1.2)).max(0.0)
    };
    if sixteen_bit {
        let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(size, size, |x, y| {
            image::Luma([(value(x, y) * 65535.0) as u16])
        });
        img.save(path).unwrap();
    } else {
        let img = image::GrayImage::from_fn(size, size, |x, y| image::Luma([(value(x, y) * 255.0) as u8]));
        img.save(path).unwrap();
    }
}

#[test]
fn tile_image_puts_sea_where_the_image_is_below_sea_level() {
    for sixteen in [false, true] {
        let png = tmp(&format!("hill{sixteen}.png"));
        hill_png(&png, 121, sixteen);
        let ron = tmp(&format!("hill{sixteen}.ron"));
        ok(&[
            "tile-image",
            png.to_str().unwrap(),
            "--sea-level",
            "0.4",
            "-o",
            ron.to_str().unwrap(),
            "--size",
            "20x18",
        ]);
        let config = MapConfig::load(&ron).unwrap();
        let terrain = Terrain::new(config).unwrap();
        let mesh = terrain.generate_map().unwrap();
        let (mut min_x, mut max_x, mut min_z, mut max_z) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for t in &mesh.tiles {
            let [x, _, z] = terrain.tile_center(t.hex).unwrap();
            min_x = min_x.min(x);
            max_x = max_x.max(x);
            min_z = min_z.min(z);
            max_z = max_z.max(z);
        }
        let (mut sea, mut dry) = (0, 0);
        for t in &mesh.tiles {
            let [x, _, z] = terrain.tile_center(t.hex).unwrap();
            // The hill's value under the tile center, from the geometry of the picture.
            let (u, v) = ((x - min_x) / (max_x - min_x) * 2.0 - 1.0, (z - min_z) / (max_z - min_z) * 2.0 - 1.0);
            let value = (1.0 - (u * u + v * v).sqrt() / 1.2).max(0.0);
            if value < 0.37 {
                assert_eq!(t.kind, TileKind::Sea, "{:?} under {value}", t.hex);
                sea += 1;
            } else if value > 0.43 {
                assert_ne!(t.kind, TileKind::Sea, "{:?} under {value}", t.hex);
                dry += 1;
            }
        }
        assert!(sea > 30 && dry > 30, "{sea} sea, {dry} dry");
        let preview = tmp(&format!("hill{sixteen}_preview.png"));
        ok(&[
            "tile-image",
            png.to_str().unwrap(),
            "--sea-level",
            "0.4",
            "-o",
            preview.to_str().unwrap(),
            "--width",
            "160",
        ]);
        assert_eq!(image::open(&preview).unwrap().width(), 160);
    }
}

/// A PNG signature and IHDR chunk declaring `w`x`h`, with a valid CRC, and no image data.
fn header_only_png(w: u32, h: u32) -> Vec<u8> {
    fn crc(bytes: &[u8]) -> u32 {
        let mut c = 0xFFFF_FFFF_u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    let mut out = vec![0x89, b'P', b'N', b'G', 13, 10, 26, 10];
    out.extend_from_slice(&13_u32.to_be_bytes());
    out.extend_from_slice(&ihdr);
    out.extend_from_slice(&crc(&ihdr).to_be_bytes());
    out
}

#[test]
fn tile_image_rejects_bad_heightmaps() {
    let out = tmp("never.ron");
    let o = out.to_str().unwrap();
    let text = tmp("text.png");
    std::fs::write(&text, "this is not a png").unwrap();
    fails(&["tile-image", text.to_str().unwrap(), "--sea-level", "0.3", "-o", o], &["text.png", "PNG"]);
    let good = tmp("good.png");
    hill_png(&good, 64, false);
    let bytes = std::fs::read(&good).unwrap();
    let truncated = tmp("truncated.png");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    fails(&["tile-image", truncated.to_str().unwrap(), "--sea-level", "0.3", "-o", o], &["truncated.png"]);
    let empty = tmp("empty.png");
    std::fs::write(&empty, header_only_png(0, 0)).unwrap();
    fails(&["tile-image", empty.to_str().unwrap(), "--sea-level", "0.3", "-o", o], &["empty.png"]);
    fails(&["tile-image", good.to_str().unwrap(), "--sea-level", "1.5", "-o", o], &["--sea-level", "[0, 1]"]);
    fails(&["tile-image", "/no/such.png", "--sea-level", "0.3", "-o", o], &["/no/such.png"]);
    fails(&["tile-image", good.to_str().unwrap(), "--sea-level", "0.3", "-o", o, "--size", "0x5"], &["size"]);
    assert!(!out.exists());
}

#[test]
fn export_reads_back_in_a_gltf_loader_with_the_same_vertices() {
    let map = small_map("export.ron", "");
    let stats = ok(&["stats", map.to_str().unwrap()]);
    let vertices: usize = stats
        .lines()
        .find_map(|l| l.strip_prefix("mesh: "))
        .and_then(|l| l.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    let glb = tmp("map.glb");
    ok(&["export", map.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    let bytes = std::fs::read(&glb).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).expect("a valid glTF binary");
    let mesh = gltf.meshes().next().unwrap();
    let prim = mesh.primitives().next().unwrap();
    let positions = prim.get(&gltf::Semantic::Positions).unwrap();
    assert_eq!(positions.count(), vertices);
    assert_eq!(prim.get(&gltf::Semantic::Normals).unwrap().count(), vertices);
    assert_eq!(prim.get(&gltf::Semantic::TexCoords(0)).unwrap().count(), vertices);
    assert_eq!(prim.get(&gltf::Semantic::Extras("TILE".into())).unwrap().count(), vertices);
    let indices = prim.indices().unwrap();
    assert_eq!(indices.count(), 14 * 12 * 24 * 3);
    // Read the index buffer back and check every index is in range.
    let blob = gltf.blob.as_ref().unwrap();
    let view = indices.view().unwrap();
    let start = view.offset() + indices.offset();
    let max = blob[start..start + indices.count() * 4]
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .max()
        .unwrap();
    assert_eq!(max as usize, vertices - 1);

    let obj = tmp("map.obj");
    ok(&["export", map.to_str().unwrap(), "-o", obj.to_str().unwrap()]);
    let text = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), vertices);
    assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), vertices);
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 14 * 12 * 24);
}

#[test]
fn stats_prints_counts_and_sharpness() {
    let out = ok(&["stats", repo().join("assets/maps/thesis/map00.map.ron").to_str().unwrap()]);
    for needle in ["sea", "land", "mountain", "total     900", "vertices", "triangles", "max", "average", "eq. 7.3"] {
        assert!(out.contains(needle), "{needle:?} missing from {out}");
    }
}

/// `stats` prints the map statistics of the library (`MapStats`): the strait preset's two
/// continents and its three-tile strait.
#[test]
fn stats_prints_the_map_statistics() {
    let strait = repo().join("assets/maps/strait.map.ron");
    let out = ok(&["stats", strait.to_str().unwrap()]);
    let terrain = Terrain::new(MapConfig::load(&strait).unwrap()).unwrap();
    let stats = hex_terrain::MapStats::measure(&terrain).unwrap();
    let sizes: Vec<String> = stats.continents().map(|m| m.tiles.to_string()).collect();
    for needle in [
        format!("continents 2 ({} tiles)", sizes.join(", ")),
        format!("narrowest strait between continents: {} tiles", stats.narrowest_strait.unwrap()),
        format!("coast: {} tile edges", stats.coast_edges),
        format!("rivers: {} systems", stats.rivers.systems),
    ] {
        assert!(out.contains(&needle), "{needle:?} missing from {out}");
    }
}

/// `stats` on a map whose rivers run on tile edges counts them (it printed none): the Jacksboro
/// map's river edges, systems and tiles, as `MapStats` measures them.
#[test]
fn stats_counts_rivers_on_edges() {
    let path = repo().join("assets/maps/jacksboro.map.ron");
    let out = ok(&["stats", path.to_str().unwrap()]);
    let terrain = Terrain::new(MapConfig::load(&path).unwrap()).unwrap();
    let r = hex_terrain::MapStats::measure(&terrain).unwrap().rivers;
    assert!(r.edges > 0 && r.systems > 0, "{r:?}");
    let needle =
        format!("water: rivers on {} tile edges ({} systems, {} tiles on a river", r.edges, r.systems, r.tiles);
    assert!(out.contains(&needle), "{needle:?} missing from {out}");
    assert!(out.contains(&format!("rivers: {} systems on {} edges", r.systems, r.edges)), "{out}");
}

/// `survey` runs seeds in a row and prints each statistic's min, median and max, which are
/// those of the maps it made; bad arguments are refused by name.
#[test]
fn survey_prints_each_statistic_over_the_seeds() {
    let map = small_map("survey.map.ron", "seed: 40");
    let out = ok(&["survey", map.to_str().unwrap(), "--seeds", "5", "--size", "20x14"]);
    assert!(out.contains("20x14") && out.contains("5 seeds from 40"), "{out}");
    let mut land: Vec<u32> = (40..45)
        .map(|seed| {
            let config = MapConfig { seed, size: MapSize::Bounded { x: 20, z: 14 }, ..MapConfig::load(&map).unwrap() };
            hex_terrain::MapStats::measure(&Terrain::new(config).unwrap()).unwrap().land_tiles
        })
        .collect();
    land.sort_unstable();
    let row = out.lines().find(|l| l.starts_with("land tiles")).unwrap_or_else(|| panic!("{out}"));
    let numbers: Vec<f64> = row.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    assert_eq!(numbers, [f64::from(land[0]), f64::from(land[2]), f64::from(land[4])], "{row}");
    fails(&["survey", map.to_str().unwrap(), "--seeds", "0"], &["--seeds 0", "1..=100000"]);
    let continent = repo().join("assets/maps/continent.map.ron");
    fails(&["survey", continent.to_str().unwrap(), "--seeds", "2"], &["unbounded", "--size"]);
}

/// `survey` takes a map type's name for its preset: it prints how many maps met every target
/// and each target's spread, as the library measured them; `--water` sets the level, and needs a
/// map type; `stats` prints a typed map's report.
#[test]
fn survey_and_stats_report_a_map_types_targets() {
    let out = ok(&["survey", "small-continents", "--seeds", "4", "--size", "44x26", "--water", "high"]);
    let preset = MapConfig::load(repo().join("assets/maps/types/small_continents.map.ron")).unwrap();
    let reports: Vec<_> = (0..4)
        .map(|i| {
            let mut config =
                MapConfig { seed: preset.seed + i, size: MapSize::Bounded { x: 44, z: 26 }, ..preset.clone() };
            config.map_type.as_mut().unwrap().water = hex_terrain::WaterLevel::High;
            Terrain::new(config).unwrap().map_type().unwrap().clone()
        })
        .collect();
    let met = reports.iter().filter(|r| r.met()).count();
    assert!(out.contains(&format!("map type Small Continents: {met} of 4 maps met every target")), "{out}");
    let mut sea: Vec<f64> =
        reports.iter().map(|r| r.check(hex_terrain::MapTypeTarget::SeaShare).unwrap().measured * 100.0).collect();
    sea.sort_by(f64::total_cmp);
    let row = out.lines().find(|l| l.starts_with("sea share (%)")).unwrap_or_else(|| panic!("{out}"));
    assert!(row.contains(&format!("{:.1}", sea[0])) && row.contains(&format!("{:.1}", sea[3])), "{row} vs {sea:?}");
    let plain = small_map("untyped.map.ron", "seed: 3");
    fails(&["survey", plain.to_str().unwrap(), "--water", "low"], &["--water", "map_type"]);
    fails(&["survey", "continents", "--water", "deep"], &["low, normal or high"]);

    let stats = ok(&["stats", repo().join("assets/maps/types/archipelago.map.ron").to_str().unwrap()]);
    assert!(stats.contains("map type Archipelago: every target met") && stats.contains("landmasses: "), "{stats}");
}

/// A map file with an `edits` section: `stats` counts the edited tiles and the edits show in
/// the counts (a tile set to mountain in a sea of Map0's), a bad edit is refused by name.
#[test]
fn stats_applies_the_edits_of_a_map_file() {
    let plain = tmp("plain.map.ron");
    std::fs::write(&plain, "(size: Bounded(x: 12, z: 10), terrain: (sea_threshold: 0.99, mountain_threshold: 0.995, interpolation_tolerance: 0.0))")
        .unwrap();
    let out = ok(&["stats", plain.to_str().unwrap()]);
    assert!(out.contains("edits: none") && out.contains("mountain  0"), "{out}");
    let edited = tmp("edited.map.ron");
    std::fs::write(
        &edited,
        "(size: Bounded(x: 12, z: 10), terrain: (sea_threshold: 0.99, mountain_threshold: 0.995, interpolation_tolerance: 0.0),\n \
         edits: [(at: (3, 3), kind: Some(Mountain)), (at: (4, 3), kind: Some(Mountain))])",
    )
    .unwrap();
    let out = ok(&["stats", edited.to_str().unwrap()]);
    assert!(out.contains("edits: 2 tiles edited") && out.contains("mountain  2"), "{out}");
    let bad = tmp("bad_edit.map.ron");
    std::fs::write(&bad, "(size: Bounded(x: 12, z: 10), edits: [(at: (30, 3), kind: Some(Land))])").unwrap();
    fails(&["stats", bad.to_str().unwrap()], &["edits[0].at", "columns 0..12"]);
}

#[test]
fn experiments_write_every_table_and_picture() {
    let dir = tmp("experiments");
    let maps = repo().join("assets/maps/thesis");
    ok(&[
        "experiments",
        "--out",
        dir.to_str().unwrap(),
        "--maps",
        maps.to_str().unwrap(),
        "--runs",
        "1",
        "--max-hexes",
        "200",
        "--width",
        "48",
        "--rings",
        "1",
    ]);
    let md = std::fs::read_to_string(dir.join("README.md")).unwrap();
    for table in ["Table 5", "Table 6", "Table 7", "Table 8", "Table 9", "Map13", "Map4'"] {
        assert!(md.contains(table), "{table} missing");
    }
    for i in 0..16 {
        assert!(dir.join(format!("images/map{i:02}_raw.png")).exists());
        assert!(dir.join(format!("images/map{i:02}_tiled.png")).exists());
    }
}

#[test]
fn textures_are_tileable_and_distinct() {
    let dir = tmp("textures");
    ok(&["textures", "--out", dir.to_str().unwrap(), "--size", "64"]);
    let mut means = Vec::new();
    for name in ["sea", "grass", "mountain"] {
        let img = image::open(dir.join(format!("{name}.png"))).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (64, 64));
        // Tileable: the last column continues into the first as smoothly as neighbors do.
        let step = |a: &image::Rgb<u8>, b: &image::Rgb<u8>| {
            a.0.iter().zip(b.0).map(|(x, y)| (i32::from(*x) - i32::from(y)).abs()).sum::<i32>()
        };
        let wrap: i32 = (0..64).map(|y| step(img.get_pixel(63, y), img.get_pixel(0, y))).sum();
        let inner: i32 = (0..64).map(|y| step(img.get_pixel(31, y), img.get_pixel(32, y))).sum();
        assert!(wrap < inner * 3 + 64 * 12, "{name} seam {wrap} vs inner {inner}");
        let mean = img
            .pixels()
            .fold([0.0_f32; 3], |m, p| [m[0] + f32::from(p[0]), m[1] + f32::from(p[1]), m[2] + f32::from(p[2])]);
        means.push(mean.map(|c| c / 4096.0));
    }
    assert!(means[0][2] > means[0][0] && means[0][2] > means[0][1], "sea is blue: {:?}", means[0]);
    assert!(means[1][1] > means[1][0] && means[1][1] > means[1][2], "grass is green: {:?}", means[1]);
    assert!((means[2][0] - means[2][2]).abs() < 30.0, "rock is grey: {:?}", means[2]);
    fails(&["textures", "--out", dir.to_str().unwrap(), "--size", "100"], &["power of two"]);
}

#[test]
fn stats_and_render_show_biomes_rivers_and_lakes() {
    let world = repo().join("assets/maps/world.map.ron");
    let out = ok(&["stats", world.to_str().unwrap()]);
    for needle in [
        "biomes:",
        "ocean",
        "coast",
        "lake",
        "desert",
        "forest",
        "tundra",
        "snow peak",
        "rivers on",
        "tile edges",
        "lakes (",
    ] {
        assert!(out.contains(needle), "{needle:?} missing from {out}");
    }
    // Per-biome counts add up to the tiles.
    let biomes: usize = out
        .lines()
        .skip_while(|l| !l.starts_with("biomes:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .map(|l| l.split_whitespace().last().unwrap().parse::<usize>().unwrap())
        .sum();
    assert_eq!(biomes, 80 * 52);

    // Each tile center of the render shows its biome's color (hill shading scales it), and a
    // lake tile's center shows water (the preset's rivers run on tile edges, between centers).
    let png = tmp("world.png");
    ok(&["render", world.to_str().unwrap(), "-o", png.to_str().unwrap(), "--width", "640"]);
    let img = image::open(&png).unwrap().to_rgb8();
    let terrain = Terrain::new(MapConfig::load(&world).unwrap()).unwrap();
    let mesh = terrain.generate_map().unwrap();
    let at = center_pixels(&terrain, &mesh, 640);
    let (mut matched, mut total) = (0, 0);
    for info in &mesh.tiles {
        let (x, y) = at(info.hex);
        let px = img.get_pixel(x, y).0;
        let [r, g, b] = px.map(f32::from);
        if info.river_flow > 0.0 || info.lake.is_some() {
            assert!(b > r && b > g, "river or lake tile {:?} drawn {px:?}", info.hex);
            continue;
        }
        // Same hue as the biome color: the channels in the same proportions.
        let [br, bg, bb] = terrain.ruleset().biome(info.terrain.terrain).unwrap().color().map(f32::from);
        let (s, t) = (r + g + b, br + bg + bb);
        let close = (r / s - br / t).abs() < 0.05 && (g / s - bg / t).abs() < 0.05;
        matched += usize::from(close);
        total += 1;
    }
    assert!(matched * 10 >= total * 9, "{matched} of {total} tiles drawn in their biome's color");
}

#[test]
fn setup_prints_a_row_a_player_and_marks_the_starts() {
    let duel = repo().join("assets/maps/civ6/duel.map.ron");
    let duel = duel.to_str().unwrap();
    let out = ok(&["setup", duel, "--players", "4"]);
    let rows: Vec<&str> =
        out.lines().filter(|l| l.trim_start().chars().next().is_some_and(|c| c.is_ascii_digit())).collect();
    assert_eq!(rows.len(), 4, "{out}");
    for (i, row) in rows.iter().enumerate() {
        assert!(row.trim_start().starts_with(&i.to_string()), "players from 0: {row}");
    }
    assert!(out.contains("spread") && out.contains("bound"), "{out}");
    // The same starts as the library's, with the same config.
    let mut config = MapConfig::load(duel).unwrap();
    config.setup = Some(hex_terrain::SetupConfig { players: 4, ..Default::default() });
    let terrain = Terrain::new(config).unwrap();
    let setup = terrain.setup().unwrap();
    for (row, &start) in rows.iter().zip(setup.starts()) {
        let [c, r] = terrain.offset_of(start);
        assert!(row.contains(&format!("({c}, {r})")), "{row} is not at ({c}, {r})");
    }
    // The picture has a white start marker at each start's center.
    let png = tmp("setup.png");
    ok(&["setup", duel, "--players", "4", "-o", png.to_str().unwrap(), "--width", "800"]);
    let img = image::open(&png).unwrap().to_rgb8();
    let mesh = terrain.generate_map().unwrap();
    let at = center_pixels(&terrain, &mesh, 800);
    for &s in setup.starts() {
        let (x, y) = at(s);
        assert_eq!(img.get_pixel(x, y).0, [250, 250, 250], "no start marker at {s:?}");
    }
    // `stats` mentions the setup; a setup that cannot fit is an error naming the field.
    assert!(ok(&["stats", duel]).contains("setup: none"));
    let crowded = small_map("crowded.map.ron", "setup: Some((players: 12, min_distance: 20))");
    fails(&["setup", crowded.to_str().unwrap()], &["setup.min_distance"]);
    fails(&["setup", duel, "--players", "99"], &["setup.players", "1..=32"]);
}

#[test]
fn edit_applies_strokes_from_a_file_and_refuses_bad_ones_by_line_or_stroke() {
    let map = tmp("to_edit.map.ron");
    std::fs::write(&map, "(size: Bounded(x: 12, z: 10), terrain: (sea_threshold: 0.99, mountain_threshold: 0.995, interpolation_tolerance: 0.0))").unwrap();
    let strokes = tmp("strokes.ron");
    std::fs::write(
        &strokes,
        "[(tool: SetKind(Mountain), brush: Range(1), at: (5, 5)), (tool: Erase, brush: Range(0), at: (5, 5))]",
    )
    .unwrap();
    let out_file = tmp("edited_by_cli.map.ron");
    let out =
        ok(&["edit", map.to_str().unwrap(), "--strokes", strokes.to_str().unwrap(), "-o", out_file.to_str().unwrap()]);
    assert!(out.contains("stroke 0") && out.contains("6 edited tiles written"), "{out}");
    let stats = ok(&["stats", out_file.to_str().unwrap()]);
    assert!(stats.contains("edits: 6 tiles edited") && stats.contains("mountain  6"), "{stats}");
    // A malformed stroke file: its line and column; a stroke off the map: which one.
    std::fs::write(&strokes, "[\n (tool: Raise(0.1), brush: Range(1), at: (5, 5), typo: 1)]").unwrap();
    fails(
        &["edit", map.to_str().unwrap(), "--strokes", strokes.to_str().unwrap(), "-o", out_file.to_str().unwrap()],
        &["strokes.ron:2:"],
    );
    std::fs::write(&strokes, "[(tool: AddRiver, brush: Range(0), at: (5, 5))]").unwrap();
    fails(
        &["edit", map.to_str().unwrap(), "--strokes", strokes.to_str().unwrap(), "-o", out_file.to_str().unwrap()],
        &["stroke 0", "rivers.enabled"],
    );
}

#[test]
fn edit_applies_strokes_to_a_globe_by_tile_id() {
    let map = tmp("globe_to_edit.map.ron");
    std::fs::write(&map, "(size: Globe(frequency: 5), terrain: (inner_rings: 1))").unwrap();
    let strokes = tmp("globe_strokes.ron");
    // A mountain over the north pole's pentagon and its five neighbors, then a sea tile.
    std::fs::write(
        &strokes,
        "[(tool: SetKind(Mountain), brush: Range(1), at: (0, 0)), (tool: SetKind(Sea), brush: Range(0), at: (100, 0))]",
    )
    .unwrap();
    let out_file = tmp("globe_edited_by_cli.map.ron");
    let args =
        ["edit", map.to_str().unwrap(), "--strokes", strokes.to_str().unwrap(), "-o", out_file.to_str().unwrap()];
    let out = ok(&args);
    assert!(out.contains("stroke 1"), "{out}");
    let edited = hex_terrain::GlobeTerrain::new(hex_terrain::MapConfig::load(&out_file).unwrap()).unwrap();
    let pole = hex_terrain::GlobeTile(0);
    for &t in std::iter::once(&pole).chain(edited.grid().neighbors(pole).unwrap().as_slice()) {
        assert_eq!(edited.tile_kind(t), Some(hex_terrain::TileKind::Mountain), "{t:?}");
    }
    assert_eq!(edited.tile_kind(hex_terrain::GlobeTile(100)), Some(hex_terrain::TileKind::Sea));
    // A tile off the globe: which stroke, and the globe's ids.
    std::fs::write(&strokes, "[(tool: Raise(0.1), brush: Range(0), at: (252, 0))]").unwrap();
    fails(&args, &["stroke 0", "0..252"]);
}

/// The shipped scenario is what the editor makes of the World map with the shipped strokes.
#[test]
fn the_strait_scenario_is_the_world_map_edited_by_its_strokes() {
    let out_file = tmp("strait_again.map.ron");
    let world = repo().join("assets/maps/world.map.ron");
    let strokes = repo().join("assets/strokes/strait.strokes.ron");
    ok(&["edit", world.to_str().unwrap(), "--strokes", strokes.to_str().unwrap(), "-o", out_file.to_str().unwrap()]);
    let made = hex_terrain::MapConfig::load(&out_file).unwrap();
    let shipped = hex_terrain::MapConfig::load(repo().join("assets/maps/strait.map.ron")).unwrap();
    assert_eq!(hex_terrain::MapConfig { name: shipped.name.clone(), ..made }, shipped);
}

/// `survey` on a map type prints its survey targets, each with the median and the tail it
/// measured and its verdict, which agree with the targets judged here over the same maps.
#[test]
fn survey_prints_the_survey_targets() {
    let out = ok(&["survey", "pangaea", "--seeds", "6"]);
    let preset = MapConfig::load(repo().join("assets/maps/types/pangaea.map.ron")).unwrap();
    let size = preset.size.bounds().unwrap();
    let stats: Vec<(u32, hex_terrain::MapStats)> = (0..6)
        .map(|i| {
            let t = Terrain::new(MapConfig { seed: preset.seed + i, ..preset.clone() }).unwrap();
            (preset.seed + i, hex_terrain::MapStats::measure(&t).unwrap())
        })
        .collect();
    let targets = hex_terrain::survey_targets(hex_terrain::MapType::Pangaea, true, true);
    let met = targets
        .iter()
        .filter(|t| t.judge(&stats.iter().map(|(s, m)| (*s, t.figure.of(m, size))).collect::<Vec<_>>()).met)
        .count();
    assert!(out.contains(&format!("survey targets: {met} of {} met", targets.len())), "{out}");
    for target in &targets {
        let line = out
            .lines()
            .skip_while(|l| !l.starts_with("survey targets"))
            .find(|l| l.starts_with(target.figure.name()))
            .unwrap_or_else(|| panic!("{out}"));
        let verdict = target.judge(&stats.iter().map(|(s, m)| (*s, target.figure.of(m, size))).collect::<Vec<_>>());
        assert_eq!(line.contains(" met"), verdict.met, "{line}");
    }
}

/// `gallery` draws one sheet: the maps in a grid of the columns asked, labelled; bad arguments
/// are refused by name.
#[test]
fn gallery_draws_a_contact_sheet() {
    let map = small_map("gallery.map.ron", "seed: 5, map_type: Some((kind: Continents))");
    let sheet = tmp("gallery.png");
    let out = ok(&[
        "gallery",
        map.to_str().unwrap(),
        "--seeds",
        "5",
        "--columns",
        "2",
        "--width",
        "120",
        "--size",
        "24x16",
        "-o",
        sheet.to_str().unwrap(),
    ]);
    assert!(out.contains("5 maps of small"), "{out}");
    let img = image::open(&sheet).unwrap().to_rgb8();
    // Two columns of 120 pixels and their gaps; three rows, each a map and its labels.
    assert_eq!(img.width(), 2 * (120 + 6) + 6);
    let one = hex_terrain::Terrain::new(MapConfig {
        size: MapSize::Bounded { x: 24, z: 16 },
        ..MapConfig::load(&map).unwrap()
    })
    .unwrap();
    assert!(one.map_type().is_some());
    assert!(img.height() > 3 * 80, "{}", img.height());
    // The labels are drawn: the strip above the bottom gap (the last row's labels) is not all
    // background.
    let background = *img.get_pixel(0, img.height() - 1);
    let written = (0..img.width())
        .flat_map(|x| (img.height() - 36..img.height() - 6).map(move |y| (x, y)))
        .filter(|&(x, y)| *img.get_pixel(x, y) != background)
        .count();
    assert!(written > 50, "{written} pixels written in the labels");
    fails(&["gallery", map.to_str().unwrap(), "--seeds", "0"], &["--seeds 0", "1..=64"]);
    fails(&["gallery", map.to_str().unwrap(), "--seeds", "4", "--columns", "5"], &["--columns 5"]);
    fails(&["gallery", map.to_str().unwrap(), "--width", "10"], &["--width 10", "64..=2048"]);
    let continent = repo().join("assets/maps/continent.map.ron");
    fails(&["gallery", continent.to_str().unwrap(), "--seeds", "2", "--columns", "2"], &["bounded", "--size"]);
}

/// `gallery` of a globe: equirectangular maps (twice as wide as high), labelled with their
/// landmasses on the sphere.
#[test]
fn gallery_draws_globes_equirectangular() {
    let map = tmp("gallery_globe.map.ron");
    std::fs::write(&map, "(name: \"tiny globe\", size: Globe(frequency: 6), map_type: Some((kind: Pangaea)))").unwrap();
    let sheet = tmp("gallery_globe.png");
    let out = ok(&[
        "gallery",
        map.to_str().unwrap(),
        "--seeds",
        "2",
        "--columns",
        "2",
        "--width",
        "160",
        "-o",
        sheet.to_str().unwrap(),
    ]);
    assert!(out.contains("2 maps of tiny globe"), "{out}");
    let img = image::open(&sheet).unwrap().to_rgb8();
    assert_eq!(img.width(), 2 * (160 + 6) + 6);
    // Each picture is 160 x 80 under the title line: the sea's blue and some land in it.
    let (mut sea, mut land) = (0, 0);
    for y in 40..100 {
        for x in 6..166 {
            let [r, g, b] = img.get_pixel(x, y).0;
            if b > r + 40 && b > g {
                sea += 1;
            } else if g >= b {
                land += 1;
            }
        }
    }
    assert!(sea > 1000 && land > 300, "sea {sea}, land {land} pixels");
}

/// `stats --ruleset` counts the tiles by the ruleset's terrains (every tile once) and features,
/// as `Terrain::tile_terrain` reads them; a broken ruleset names its file and line.
#[test]
fn stats_counts_a_rulesets_terrains_and_features() {
    let map = repo().join("assets/maps/types/continents.map.ron");
    let civ = repo().join("assets/rulesets/civ5.terrain.ron");
    let out = ok(&["stats", map.to_str().unwrap(), "--ruleset", civ.to_str().unwrap()]);
    let mut config = MapConfig::load(&map).unwrap();
    config.ruleset = Some(civ.display().to_string());
    let t = Terrain::new(config).unwrap();
    let ruleset = hex_terrain::TerrainRuleset::load(&civ).unwrap();
    assert_eq!(t.ruleset(), &ruleset);
    let section: Vec<&str> = out.lines().skip_while(|l| !l.starts_with("terrains (Civilization V):")).skip(1).collect();
    let count = |id: &str| {
        section
            .iter()
            .find(|l| l.split_whitespace().next() == Some(id))
            .map(|l| l.split_whitespace().nth(1).unwrap().parse::<usize>().unwrap())
    };
    let mut total = 0;
    for (i, def) in ruleset.terrains.iter().enumerate() {
        let n = t.tiles().filter(|&h| t.tile_info(h).unwrap().terrain.terrain.0 as usize == i).count();
        assert_eq!(count(&def.id).unwrap_or(0), n, "{}: {out}", def.id);
        total += n;
    }
    assert_eq!(total, t.tiles().count());
    for (i, def) in ruleset.features.iter().enumerate() {
        let n =
            t.tiles().filter(|&h| t.tile_info(h).unwrap().terrain.feature.is_some_and(|f| f.0 as usize == i)).count();
        assert_eq!(count(&def.id), Some(n), "{}: {out}", def.id);
    }
    // `survey` of a map with its own ruleset spreads each terrain's and feature's share.
    let world = repo().join("assets/maps/world_civ5.map.ron");
    let out = ok(&["survey", world.to_str().unwrap(), "--seeds", "2"]);
    for line in ["terrain grassland (% of tiles)", "terrain snow (% of tiles)", "feature forest (% of tiles)"] {
        assert!(out.contains(line), "{line}: {out}");
    }
    let bad = tmp("bad.terrain.ron");
    std::fs::write(&bad, "(\n  fallback: {},\n  terrains: [(id: 3)],\n)").unwrap();
    fails(&["stats", map.to_str().unwrap(), "--ruleset", bad.to_str().unwrap()], &["ruleset", "bad.terrain.ron", "3:"]);
}

/// The layer a pixel of the render's colors shows: blue sea, green land, grey rock.
fn layer_of(p: [u8; 3]) -> TileKind {
    let [r, g, b] = p;
    if b > r && b > g {
        TileKind::Sea
    } else if g > r && g > b.saturating_add(20) {
        TileKind::Land
    } else {
        TileKind::Mountain
    }
}

#[test]
fn setup_prints_a_globes_report_and_marks_its_starts() {
    let map = repo().join("assets/maps/globe/continents.map.ron");
    let map = map.to_str().unwrap();
    let out = ok(&["setup", map, "--players", "3"]);
    let rows: Vec<&str> =
        out.lines().filter(|l| l.trim_start().chars().next().is_some_and(|c| c.is_ascii_digit())).collect();
    assert_eq!(rows.len(), 3, "{out}");
    assert!(out.contains("on a globe") && out.contains("spread"), "{out}");
    // The same starts as the library's, at their longitude and latitude.
    let mut config = MapConfig::load(map).unwrap();
    config.setup = Some(hex_terrain::SetupConfig { players: 3, ..Default::default() });
    let globe = hex_terrain::GlobeTerrain::new(config).unwrap();
    let setup = globe.setup().unwrap();
    let width = 720;
    let png = tmp("globe_setup.png");
    ok(&["setup", map, "--players", "3", "-o", png.to_str().unwrap(), "--width", &width.to_string()]);
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!((img.width(), img.height()), (width, width / 2));
    for (row, &start) in rows.iter().zip(setup.starts()) {
        let info = globe.tile_info(start).unwrap();
        let (lon, lat) = (info.longitude.round() as i32, info.latitude.round() as i32);
        assert!(row.contains(&format!("({lon}, {lat})")), "{row} is not at ({lon}, {lat})");
        // A white start marker at the start's place on the equirectangular picture.
        let x = (((info.longitude + 180.0) / 360.0 * f64::from(width)) as u32).min(width - 1);
        let y = (((90.0 - info.latitude) / 180.0 * f64::from(width / 2)) as u32).min(width / 2 - 1);
        assert_eq!(img.get_pixel(x, y).0, [250, 250, 250], "no start marker at {start:?}");
    }
}

#[test]
fn stats_and_survey_measure_a_globe() {
    let map = repo().join("assets/maps/globe/continents.map.ron");
    let map = map.to_str().unwrap();
    let globe = hex_terrain::GlobeTerrain::new(MapConfig::load(map).unwrap()).unwrap();
    let stats = hex_terrain::GlobeStats::measure(&globe);
    let out = ok(&["stats", map]);
    for kind in [TileKind::Sea, TileKind::Land, TileKind::Mountain] {
        let count = globe.grid().tiles().filter(|&t| globe.tile_kind(t) == Some(kind)).count();
        assert!(out.contains(&format!("  {:<9} {count}", kind.name())), "{kind:?} in {out}");
    }
    assert!(out.contains(&format!("{} continents", stats.continents().count())), "{out}");
    assert!(out.contains("map type Continents: every target met"), "{out}");
    let out = ok(&["survey", map, "--seeds", "3"]);
    assert!(out.contains("its targets met on 3 of 3 seeds"), "{out}");
    assert!(out.lines().any(|l| l.starts_with("water share (%)")), "{out}");
    fails(&["survey", map, "--seeds", "3", "--size", "20x10"], &["--size", "frequency"]);
    fails(&["stats", map, "--ruleset", "x.terrain.ron"], &["--ruleset", "globes"]);
}

#[test]
fn render_draws_a_globe_equirectangular_and_from_above_a_tile() {
    let map = repo().join("assets/maps/globe/standard.map.ron");
    let map = map.to_str().unwrap();
    let globe = hex_terrain::GlobeTerrain::new(MapConfig::load(map).unwrap()).unwrap();
    let flat = tmp("globe_flat.png");
    ok(&["render", map, "-o", flat.to_str().unwrap(), "--width", "400"]);
    let img = image::open(&flat).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (400, 200));
    // The sea's share of the sphere's area, from the picture's rows weighted by their circles,
    // is the globe's share of sea tiles (the tiles' areas are within 5 % of each other).
    let (mut sea, mut all) = (0.0, 0.0);
    for (_, y, p) in img.enumerate_pixels() {
        let w = ((f64::from(y) + 0.5) / 200.0 * std::f64::consts::PI - std::f64::consts::FRAC_PI_2).cos();
        all += w;
        if layer_of(p.0) == TileKind::Sea {
            sea += w;
        }
    }
    let share = sea / all;
    assert!((share - globe.sea_share()).abs() < 0.04, "picture {share}, tiles {}", globe.sea_share());
    // Seen from above a tile's center, the picture's middle is that tile's kind.
    let grid = globe.grid();
    for kind in [TileKind::Sea, TileKind::Land, TileKind::Mountain] {
        let tile = grid.tiles().find(|&t| globe.tile_kind(t) == Some(kind) && !grid.is_pentagon(t)).unwrap();
        let [x, y, z] = grid.center(tile).unwrap();
        let (lat, lon) = (y.asin().to_degrees(), (-z).atan2(x).to_degrees());
        let out = tmp("globe_view.png");
        ok(&["render", map, "-o", out.to_str().unwrap(), "--width", "301", "--from", &format!("{lon},{lat}")]);
        let img = image::open(&out).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (301, 301));
        assert_eq!(layer_of(img.get_pixel(150, 150).0), kind, "{tile:?} seen from {lon}, {lat}");
        assert_eq!(img.get_pixel(0, 0).0, [5, 5, 13], "the corner is space");
    }
    fails(&["render", map, "-o", "x.png", "--from", "200,0"], &["--from 200,0", "[-180, 180]"]);
    let thesis = repo().join("assets/maps/thesis/map00.map.ron");
    fails(&["render", thesis.to_str().unwrap(), "-o", "x.png", "--from", "0,0"], &["--from", "globe"]);
}
