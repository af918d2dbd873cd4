//! What each fuzz target does with its input, and the properties it asserts. The cargo-fuzz
//! targets in `fuzz/` call these functions; `tests/corpus.rs` replays the kept corpus and every
//! input that once failed through them, so CI checks them in seconds on the stable toolchain.
//!
//! A property violation panics, which is what a fuzzer reports:
//! - no panic anywhere on the way from bytes to buffers (the fuzzer catches those itself);
//! - no hang: validation refuses every size that would take long, and each target generates a
//!   bounded amount of terrain (at most [`MAX_TILES`] tiles);
//! - every buffer finite, every index in range;
//! - every error names what was wrong (the field and the allowed range, the line and column of
//!   malformed RON, the size of an oversized image).

use std::sync::Arc;

use hex_terrain::save::{SaveError, TileStateSave};
use hex_terrain::{
    Biome, Brush, Editor, GenerateOptions, HeightImage, HeightSourceConfig, Landform, MapConfig, MapFile, MapSize,
    PropDensity, Stroke, Terrain, TerrainRuleset, TileFacts, TileKind, TileRect, Tool,
};
use hex_terrain::{FogOfWar, FogState, GlobeChunk, GlobeEditor, GlobeFog, GlobeStroke, GlobeTerrain, GlobeTile};

mod check;

pub use check::{check_config_error, check_load_error, check_terrain};

/// Most tiles a target generates from one input (a 4x4 rectangle).
pub const MAX_TILES: u32 = 16;

/// The heightmap the map-text target gives an `Image` source (it reads no file named by
/// fuzzed text): a 5x4 ramp.
fn ramp() -> Arc<HeightImage> {
    let data = (0..20).map(|i| i as f32 / 19.0).collect();
    Arc::new(HeightImage::from_samples(5, 4, data).expect("a 5x4 ramp is a valid heightmap"))
}

/// Map text: RON → [`MapConfig::from_ron`] → [`Terrain`] → a small rectangle of tiles, as the
/// CLI reads a map file.
pub fn map_text(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match MapConfig::from_ron(text) {
        Ok(config) => build(config, Some(ramp())),
        Err(error) => check_load_error(&error),
    }
}

/// Terrain ruleset: RON → [`TerrainRuleset::from_ron`](hex_terrain::TerrainRuleset::from_ron)
/// (refused by name, or the line and column), then every landform at corners of the climate
/// and in between gives a terrain of the ruleset (a feature only on a terrain it lists, traits
/// within their ranges), and a 4x4 map with a climate under the ruleset answers every tile.
pub fn ruleset(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let ruleset = match TerrainRuleset::from_ron(text) {
        Ok(ruleset) => Arc::new(ruleset),
        Err(error) => return check_load_error(&error),
    };
    let patches = hex_terrain::FeaturePatches::new(&ruleset, 7, None);
    for landform in Landform::ALL {
        for (i, v) in [0.0_f32, 0.25, 0.5, 0.999, 1.0].into_iter().enumerate() {
            let facts = TileFacts {
                temperature: v,
                moisture: 1.0 - v,
                elevation: v,
                latitude: v,
                near_water: i % 2 == 0,
                near_river: i % 3 == 0,
                ..TileFacts::new(landform)
            };
            let terrain = ruleset.terrain_for(&facts);
            assert!(usize::from(terrain.0) < ruleset.terrains.len());
            let feature = patches.feature_for(&ruleset, terrain, &facts, (f64::from(v) * 9.0, 3.0));
            if let Some(f) = feature {
                assert!(ruleset.feature(f).on.contains(&ruleset.terrain(terrain).id));
            }
            let traits = ruleset.traits(terrain, landform, feature);
            assert!(traits.movement <= hex_terrain::MAX_MOVE_COST);
            let y = traits.yields;
            assert!([y.food, y.production, y.gold].iter().all(|v| v.is_finite() && *v >= 0.0));
        }
    }
    let config = MapConfig::from_ron(
        "(size: Bounded(x: 4, z: 4), chunk_size: (4, 4), climate: (enabled: true), ruleset: Some(\"fuzz.terrain.ron\"))",
    )
    .expect("a valid config");
    let terrain = Terrain::with_sources(config, None, Some(ruleset.clone())).expect("a valid ruleset is taken");
    for tile in terrain.tiles() {
        let t = terrain.tile_info(tile).expect("a tile of the map").terrain;
        assert!(usize::from(t.terrain.0) < ruleset.terrains.len());
    }
}

/// Edit file: a map file with an `edits` section, as the world builder saves it. The text must
/// load or be refused by name (the line and column, or `edits[i]` and the allowed range); a map
/// that loads is edited with strokes the bytes pick (tools, brushes, tiles), undone to its start
/// bit for bit, and saved: the saved text loads back to the same edits.
pub fn edits(data: &[u8]) {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (text, script) = (&data[..split], data.get(split + 1..).unwrap_or_default());
    let file = match MapFile::from_bytes(text) {
        Ok(file) => file,
        Err(error) => return check_load_error(&error),
    };
    let mut config = file.config;
    if matches!(config.source, HeightSourceConfig::Image { .. }) {
        config.source = HeightSourceConfig::Noise;
    }
    if let Some(frequency) = config.size.globe() {
        return globe_edits(config, frequency, script);
    }
    // Each stroke compiles the map again and compares every tile: keep maps small.
    if config.size.bounds().is_some_and(|(x, z)| u64::from(x) * u64::from(z) > 64 * 64) {
        return;
    }
    // A small corner of the map: at most MAX_TILES tiles are generated for the comparisons.
    let Ok(mut editor) = Editor::new(config.clone()) else { return };
    let rect = TileRect::new([0, 0], [4, 4]);
    let start = editor.terrain().generate(rect, GenerateOptions::CURRENT_THREAD);
    check_terrain(editor.terrain(), &start);
    let mut applied = 0;
    for step in script.chunks(4).take(8) {
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| step.get(i).copied().unwrap_or(0));
        // A flood on an unbounded map fills thousands of tiles: too slow an input to fuzz.
        let bounded = editor.terrain().bounds().is_some();
        let brush = match c % 6 {
            4 if bounded => Brush::Flood,
            5 if bounded => Brush::FloodTerrain,
            _ => Brush::Range(u32::from(c % 4)),
        };
        let tile = editor.terrain().tile_from_offset([i32::from(d % 8), i32::from(d / 8 % 8)]);
        let tool = fuzzed_tool(a, b, c, d);
        match editor.apply(Stroke { tool, brush, tile }) {
            Ok(change) => applied += usize::from(!change.is_empty()),
            Err(error) => assert!(!error.to_string().is_empty()),
        }
    }
    assert_eq!(editor.undo_len(), applied);
    let saved = editor.config();
    let reloaded = MapConfig::from_ron(&saved.to_ron()).expect("a saved edited map loads");
    assert_eq!(reloaded.edits, saved.edits, "the saved edits load back the same");
    let edited = editor.terrain().generate(rect, GenerateOptions::CURRENT_THREAD);
    check_terrain(editor.terrain(), &edited);
    while editor.undo().is_some() {}
    let undone = editor.terrain().generate(rect, GenerateOptions::CURRENT_THREAD);
    assert!(undone.buffers == start.buffers, "undoing every stroke gives back the map as loaded");
    let mut loaded = config.edits;
    loaded.sort_by_key(|e| (e.at.1, e.at.0));
    assert_eq!(editor.edits(), loaded, "undoing every stroke gives back the edits as loaded");
}

/// A stroke's tool from four bytes of a script.
fn fuzzed_tool(a: u8, b: u8, c: u8, d: u8) -> Tool {
    let amount = f32::from(b) / 255.0;
    match a % 14 {
        0 => Tool::Raise(amount),
        1 => Tool::Lower(amount),
        2 => Tool::SetHeight(amount),
        3 => Tool::Smooth,
        4 => Tool::SetKind([TileKind::Sea, TileKind::Land, TileKind::Mountain][usize::from(b % 3)]),
        5 => Tool::Erase,
        6 => Tool::SetBiome([Biome::Desert, Biome::Grassland, Biome::Snow][usize::from(b % 3)]),
        7 => Tool::AddRiver,
        8 => Tool::RemoveRiver,
        9 => Tool::FillLake,
        10 => Tool::DrainLake,
        11 => Tool::SetProps([PropDensity::None, PropDensity::Sparse, PropDensity::Dense][usize::from(b % 3)]),
        12 => Tool::SetHills(b.is_multiple_of(2)),
        _ => Tool::Raise(f32::from_bits(u32::from_le_bytes([a, b, c, d]))),
    }
}

/// The edits target on a globe (at most [`MAX_GLOBE_FREQUENCY`]): up to eight strokes by a
/// [`GlobeEditor`] on tiles the script names, refusals said in words; the edited globe's map
/// file loads as the same edits, its north pole's chunk meshes finite, and undoing every stroke
/// gives back the globe as loaded, bit for bit.
fn globe_edits(config: MapConfig, frequency: u32, script: &[u8]) {
    if frequency > MAX_GLOBE_FREQUENCY || 5 * config.subdivisions().pow(2) > MAX_GLOBE_POINTS {
        return;
    }
    let mut editor = match GlobeEditor::new(config) {
        Ok(editor) => editor,
        Err(error) => return check_config_error(&error),
    };
    let start = editor.globe().generate(GlobeChunk::North);
    let tiles = editor.globe().grid().tile_count();
    let mut applied = 0;
    for step in script.chunks(4).take(8) {
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| step.get(i).copied().unwrap_or(0));
        let brush = match c % 6 {
            4 => Brush::Flood,
            5 => Brush::FloodTerrain,
            _ => Brush::Range(u32::from(c % 4)),
        };
        // A tile past the globe one stroke in 64.
        let tile = GlobeTile((u32::from(d) * 7 + u32::from(b)) % (tiles + tiles / 64 + 1));
        match editor.apply(GlobeStroke { tool: fuzzed_tool(a, b, c, d), brush, tile }) {
            Ok(change) => applied += usize::from(!change.is_empty()),
            Err(error) => assert!(!error.to_string().is_empty()),
        }
    }
    assert_eq!(editor.undo_len(), applied);
    let saved = editor.config();
    let reloaded = MapConfig::from_ron(&saved.to_ron()).expect("a saved edited globe loads");
    assert_eq!(reloaded.edits, saved.edits, "the saved edits load back the same");
    let edited = editor.globe().generate(GlobeChunk::North);
    assert!(edited.buffers.positions.iter().flatten().all(|v| v.is_finite()), "a position is not finite");
    assert!(edited.heights.iter().all(|h| (0.0..=1.0).contains(h)), "a height outside [0, 1]");
    while editor.undo().is_some() {}
    assert!(editor.globe().generate(GlobeChunk::North) == start, "undoing every stroke gives back the globe");
}

/// Heightmap: PNG bytes → [`HeightImage`] → a 12x8 map tiled from it.
pub fn heightmap(data: &[u8]) {
    match HeightImage::from_png_bytes(data) {
        Ok(image) => {
            let (w, h) = image.size();
            assert!(w > 0 && h > 0 && (w as u64) * (h as u64) <= hex_terrain::MAX_IMAGE_PIXELS);
            for (u, v) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.25), (-3.0, 7.0)] {
                let s = image.sample(u, v);
                assert!((0.0..=1.0).contains(&s), "sample ({u}, {v}) = {s}");
            }
            let sea_level = data.len() as f32 % 97.0 / 96.0;
            let config = MapConfig {
                source: HeightSourceConfig::Image { path: "fuzzed.png".into(), sea_level },
                size: MapSize::Bounded { x: 12, z: 8 },
                ..MapConfig::default()
            };
            let terrain = Terrain::with_sources(config, Some(Arc::new(image)), None).expect("a valid config");
            let map = terrain.generate_map().expect("a bounded map");
            check_terrain(&terrain, &map);
        }
        Err(error) => assert!(!error.to_string().is_empty()),
    }
}

/// Map asset, as the Bevy plugin's loader reads it: the bytes up to the first NUL are the map
/// file ([`MapFile::from_bytes`]); the rest are the bytes of its heightmap when its source is
/// `Image`. Then the terrain the plugin builds from the asset, and a small chunk of it.
pub fn map_asset(data: &[u8]) {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (file, png) = (&data[..split], data.get(split + 1..).unwrap_or_default());
    let file = match MapFile::from_bytes(file) {
        Ok(file) => file,
        Err(error) => return check_load_error(&error),
    };
    if let Some(blend) = file.clamped_blend {
        assert!(!(0.0..=1.0).contains(&blend) && (0.0..=1.0).contains(&file.config.appearance.blend));
    }
    let image = match &file.config.source {
        HeightSourceConfig::Noise => None,
        HeightSourceConfig::Image { .. } => match HeightImage::from_png_bytes(png) {
            Ok(image) => Some(Arc::new(image)),
            Err(error) => return assert!(!error.to_string().is_empty()),
        },
    };
    build(file.config, image);
}

/// Tile state save: the bytes as a binary save, as the same bytes with their length and
/// checksum made right (so the fuzzer reaches the CBOR decoder behind the CRC), and as RON text;
/// each save read is checked against a 12x9 map (wrapping when the first byte is odd). A save
/// read from binary must encode back to the same save, and one that passes the check must in
/// both encodings; a refused one must say why.
pub fn tile_save(data: &[u8]) {
    let config = MapConfig {
        size: MapSize::Bounded { x: 12, z: 9 },
        wrap: data.first().is_some_and(|b| b & 1 == 1),
        ..MapConfig::default()
    };
    read_save(TileStateSave::from_bytes(data), &config, true);
    if data.len() >= 20 {
        let mut sealed = data.to_vec();
        let payload = (data.len() - 20) as u64;
        sealed[..4].copy_from_slice(&hex_terrain::save::SAVE_MAGIC);
        sealed[8..16].copy_from_slice(&payload.to_le_bytes());
        let n = sealed.len();
        let crc = hex_terrain::save::crc32(&sealed[..n - 4]);
        sealed[n - 4..].copy_from_slice(&crc.to_le_bytes());
        read_save(TileStateSave::from_bytes(&sealed), &config, true);
    }
    if let Ok(text) = std::str::from_utf8(data) {
        read_save(TileStateSave::from_ron(text), &config, false);
    }
}

fn read_save(read: Result<TileStateSave, SaveError>, config: &MapConfig, binary: bool) {
    let save = match read {
        Ok(save) => save,
        Err(error) => return check_save_error(&error),
    };
    let round_trip = |save: &TileStateSave| {
        assert_eq!(TileStateSave::from_bytes(&save.to_bytes()).as_ref(), Ok(save), "binary round trip");
        assert_eq!(TileStateSave::from_ron(&save.to_ron()).as_ref(), Ok(save), "RON round trip");
    };
    if binary {
        round_trip(&save);
    }
    match save.check(config) {
        Ok(()) => {
            round_trip(&save);
            let bounds = config.size.bounds().expect("a bounded map");
            for tile in &save.tiles {
                assert!((0..bounds.0 as i32).contains(&tile.at.0) && (0..bounds.1 as i32).contains(&tile.at.1));
                assert!(tile.owner.is_none_or(|o| u32::from(o) < hex_terrain::save::MAX_OWNERS));
            }
        }
        Err(error) => check_save_error(&error),
    }
}

/// A fog save: bytes → [`FogOfWar::from_bytes`] (and, when the bytes are text,
/// [`FogOfWar::from_ron`]) into a 12x9 map (wrapping when the first byte is odd), as a game
/// loads a player's fog. The bytes are also sealed with a good header and checksum, so the
/// fuzzer reaches the payload's checks. A fog read must encode back to the same fog in both
/// encodings, with every seen tile on the map and visible tiles listed as visible; a refused one
/// must say why.
pub fn fog_save(data: &[u8]) {
    // The two maps are made once: the fuzzer spends its time on the fog, not the terrain.
    static MAPS: std::sync::OnceLock<[Terrain; 2]> = std::sync::OnceLock::new();
    let maps = MAPS.get_or_init(|| {
        [false, true].map(|wrap| {
            let config = MapConfig { size: MapSize::Bounded { x: 12, z: 9 }, wrap, ..MapConfig::default() };
            Terrain::new(config).expect("a 12x9 map is valid")
        })
    });
    let terrain = &maps[usize::from(data.first().is_some_and(|b| b & 1 == 1))];
    read_fog(FogOfWar::from_bytes(data, terrain), terrain);
    if data.len() >= 20 {
        let mut sealed = data.to_vec();
        let payload = (data.len() - 20) as u64;
        sealed[..4].copy_from_slice(&hex_terrain::FOG_MAGIC);
        sealed[4..8].copy_from_slice(&hex_terrain::FOG_VERSION.to_le_bytes());
        sealed[8..16].copy_from_slice(&payload.to_le_bytes());
        let n = sealed.len();
        let crc = hex_terrain::save::crc32(&sealed[..n - 4]);
        sealed[n - 4..].copy_from_slice(&crc.to_le_bytes());
        read_fog(FogOfWar::from_bytes(&sealed, terrain), terrain);
    }
    if let Ok(text) = std::str::from_utf8(data) {
        read_fog(FogOfWar::from_ron(text, terrain), terrain);
    }
    // A globe's fog, from the same bytes, and sealed as a globe fog save.
    static GLOBE: std::sync::OnceLock<GlobeTerrain> = std::sync::OnceLock::new();
    let globe = GLOBE.get_or_init(|| {
        let config = MapConfig { size: MapSize::Globe { frequency: 3 }, ..MapConfig::default() };
        GlobeTerrain::new(config).expect("a globe of frequency 3 is valid")
    });
    read_globe_fog(GlobeFog::from_bytes(data, globe), globe);
    if data.len() >= 20 {
        let mut sealed = data.to_vec();
        let payload = (data.len() - 20) as u64;
        sealed[..4].copy_from_slice(&hex_terrain::GLOBE_FOG_MAGIC);
        sealed[4..8].copy_from_slice(&hex_terrain::GLOBE_FOG_VERSION.to_le_bytes());
        sealed[8..16].copy_from_slice(&payload.to_le_bytes());
        let n = sealed.len();
        let crc = hex_terrain::save::crc32(&sealed[..n - 4]);
        sealed[n - 4..].copy_from_slice(&crc.to_le_bytes());
        read_globe_fog(GlobeFog::from_bytes(&sealed, globe), globe);
    }
}

fn read_globe_fog(read: Result<GlobeFog, SaveError>, globe: &GlobeTerrain) {
    let fog = match read {
        Ok(fog) => fog,
        Err(error) => return check_save_error(&error),
    };
    assert_eq!(GlobeFog::from_bytes(&fog.to_bytes(), globe).as_ref(), Ok(&fog), "binary round trip");
    for player in 0..fog.players() {
        assert!(fog.visible(player).all(|tile| fog.state(player, tile) == Some(FogState::Visible)));
    }
}

fn read_fog(read: Result<FogOfWar, SaveError>, terrain: &Terrain) {
    let fog = match read {
        Ok(fog) => fog,
        Err(error) => {
            let text = error.to_string();
            if let SaveError::Tile { index, .. } = &error {
                assert!(text.contains(&format!("tile {index}")) && text.contains("player"), "{text}");
            }
            return check_save_error(&error);
        }
    };
    assert_eq!(FogOfWar::from_bytes(&fog.to_bytes(), terrain).as_ref(), Ok(&fog), "binary round trip");
    assert_eq!(FogOfWar::from_ron(&fog.to_ron(), terrain).as_ref(), Ok(&fog), "RON round trip");
    for player in 0..fog.players() {
        for (tile, state) in fog.seen(player) {
            assert!(terrain.contains(tile) && state != FogState::Unexplored);
        }
        assert!(fog.visible(player).all(|tile| fog.state(player, tile) == Some(FogState::Visible)));
    }
}

/// Most globe frequency a target compiles (642 tiles); a larger globe is only validated.
pub const MAX_GLOBE_FREQUENCY: u32 = 8;

/// Most fine points of the one chunk a target meshes from a globe.
pub const MAX_GLOBE_POINTS: u32 = 20_000;

/// A globe config: validated, compiled when small ([`MAX_GLOBE_FREQUENCY`]), its north pole's
/// chunk meshed when small ([`MAX_GLOBE_POINTS`]); every buffer finite and in range, and the
/// rules (tile info, a path, a view, a ray) answer without panicking.
fn build_globe(config: MapConfig, frequency: u32) {
    if let Err(error) = config.validate() {
        return check_config_error(&error);
    }
    if frequency > MAX_GLOBE_FREQUENCY {
        return;
    }
    let globe = match GlobeTerrain::new(config) {
        Ok(globe) => globe,
        Err(error) => return check_config_error(&error),
    };
    let n = globe.config().subdivisions();
    if 5 * n * n <= MAX_GLOBE_POINTS {
        let mesh = globe.generate(GlobeChunk::North);
        let b = &mesh.buffers;
        let count = b.positions.len();
        assert_eq!((b.normals.len(), b.tile_kinds.len(), mesh.heights.len()), (count, count, count));
        assert!(b.indices.len() == 15 * (n * n) as usize && b.indices.iter().all(|&i| (i as usize) < count));
        assert!(b.positions.iter().flatten().all(|v| v.is_finite()), "a position is not finite");
        assert!(b.normals.iter().all(|v| (v.iter().map(|c| c * c).sum::<f32>() - 1.0).abs() < 1e-3));
        assert!(mesh.heights.iter().all(|h| (0.0..=1.0).contains(h)), "a height outside [0, 1]");
    }
    let last = GlobeTile(globe.grid().tile_count() - 1);
    for tile in [GlobeTile(0), last] {
        let info = globe.tile_info(tile).expect("a tile of the globe");
        assert!(info.elevation.is_finite() && info.latitude.is_finite() && info.longitude.is_finite());
    }
    if let Some(path) = globe.path(GlobeTile(0), last) {
        assert_eq!(path.tiles.first(), Some(&GlobeTile(0)));
    }
    assert!(globe.field_of_view(GlobeTile(0), 3).contains(&GlobeTile(0)));
    let r = globe.radius() * 3.0;
    if let Some(hit) = globe.raycast([r, r, 0.0], [-1.0, -1.0, 0.0], f64::MAX) {
        assert!(hit.point.iter().all(|v| v.is_finite()) && hit.distance.is_finite(), "{hit:?}");
    }
}

/// Panics unless a refused save says why: malformed RON with its line and column, the tile and
/// the allowed range, the field of another map.
pub fn check_save_error(error: &SaveError) {
    let text = error.to_string();
    match error {
        SaveError::Syntax { line, column, .. } => {
            assert!(*line >= 1 && *column >= 1 && text.contains(&format!("line {line}, column {column}")), "{text}");
        }
        SaveError::Tile { index, .. } => assert!(text.contains(&format!("tile {index}")), "{text}"),
        SaveError::OtherMap { field, .. } => assert!(text.contains(field), "{text}"),
        _ => assert!(!text.is_empty()),
    }
}

/// Builds the terrain of a valid config and generates at most [`MAX_TILES`] tiles of it: the
/// first tiles of a bounded map, or tiles around the first chunk of an unbounded one.
fn build(config: MapConfig, image: Option<Arc<HeightImage>>) {
    if let Some(frequency) = config.size.globe() {
        return build_globe(config, frequency);
    }
    let terrain = match Terrain::with_sources(config, image, None) {
        Ok(terrain) => terrain,
        Err(error) => return check_config_error(&error),
    };
    let (cx, cz) = terrain.chunk_size();
    let side = [cx.min(4), cz.min(4)];
    let min = [terrain.config().offset.0 % 1000, terrain.config().offset.1 % 1000];
    let rect = match terrain.bounds() {
        Some(bounds) => TileRect::new(bounds.min, side).intersect(&bounds),
        None => TileRect::new(min, side),
    };
    assert!(rect.len() as u32 <= MAX_TILES);
    let mesh = terrain.generate(rect, GenerateOptions::default());
    check_terrain(&terrain, &mesh);
}
