//! Prevailing winds (`climate.winds`): rain shadows behind ridges, deserts in the lee of ranges
//! and in the horse latitudes, the same rain on every thread, and bad winds refused by name.
//! What is upwind of a tile is worked out here from the bearings, not read from the crate.

use std::sync::Arc;

use hex_terrain::hexx::Hex;
use hex_terrain::{
    Biome, ClimateConfig, HeightImage, HeightSourceConfig, MapConfig, MapSize, Orientation, Terrain, TileKind,
    WindConfig, WindPattern,
};
use proptest::prelude::*;
#[path = "common/biome.rs"]
mod biome;

fn maps_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../bevy_hex_terrain/assets/maps")
}

/// An image of land rising from a sea strip on the west (`u` below 0.12) with a ridge across
/// the map at `u = at`, `peak` high (image values; the sea level is 0.3, the plain 0.45).
fn ridge(at: f32, peak: f32) -> HeightImage {
    let (w, h) = (240, 8);
    let data = (0..w * h)
        .map(|i| {
            let u = (i % w) as f32 / (w - 1) as f32;
            if u < 0.12 {
                return 0.1;
            }
            let tent = (1.0 - (u - at).abs() / RIDGE_HALF_WIDTH).max(0.0);
            0.45 + tent * (peak - 0.45)
        })
        .collect();
    HeightImage::from_samples(w, h, data).unwrap()
}

/// Half the ridge's width, in image `u`.
const RIDGE_HALF_WIDTH: f32 = 0.06;

/// A map of the ridge image under a west wind, with the moisture the rain's alone.
fn ridge_map(cols: u32, rows: u32, pointy: bool, wrap: bool, at: f32, peak: f32) -> Terrain {
    let mut config = MapConfig {
        size: MapSize::Bounded { x: cols, z: rows },
        wrap,
        source: HeightSourceConfig::Image { path: "ridge.png".into(), sea_level: 0.3 },
        climate: ClimateConfig {
            enabled: true,
            winds: Some(WindConfig { pattern: WindPattern::One(270.0), variety: 0.0, ..WindConfig::default() }),
            ..ClimateConfig::default()
        },
        ..MapConfig::default()
    };
    config.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
    Terrain::with_sources(config, Some(Arc::new(ridge(at, peak))), None).unwrap()
}

/// The mean moisture of the land tiles whose centers lie, in image `u`, within `band`.
fn mean_moisture(t: &Terrain, band: (f32, f32)) -> f32 {
    let centers: Vec<(Hex, f64)> = t.tiles().map(|h| (h, t.tile_center(h).unwrap()[0])).collect();
    let lo = centers.iter().map(|c| c.1).fold(f64::MAX, f64::min);
    let hi = centers.iter().map(|c| c.1).fold(f64::MIN, f64::max);
    let (mut sum, mut n) = (0.0, 0.0);
    for &(h, x) in &centers {
        let u = ((x - lo) / (hi - lo)) as f32;
        if u >= band.0 && u < band.1 && t.tile_kind(h).unwrap() != TileKind::Sea {
            sum += t.tile_climate(h).unwrap().moisture;
            n += 1.0;
        }
    }
    assert!(n > 0.0, "no land tile in {band:?}");
    sum / n
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Behind a ridge across the wind the land is drier than before it, drier than the same
    /// land without the ridge, and drier the higher the ridge; the ridge's windward slope gets
    /// more rain than the same tiles without it.
    #[test]
    fn a_ridge_across_the_wind_casts_a_rain_shadow(
        cols in 36u32..64,
        rows in 8u32..16,
        pointy in any::<bool>(),
        wrap in any::<bool>(),
        at in 0.4f32..0.6,
        low in 0.75f32..0.85,
        rise in 0.08f32..0.15,
    ) {
        let cols = if wrap && !pointy { cols + cols % 2 } else { cols };
        let map = |peak| ridge_map(cols, rows, pointy, wrap, at, peak);
        let (flat, lower, higher) = (map(0.45), map(low), map(low + rise));
        let w = RIDGE_HALF_WIDTH;
        let (windward, lee, slope) = ((at - w - 0.12, at - w), (at + w, at + w + 0.12), (at - w, at - 0.01));
        let m = |t: &Terrain, band| mean_moisture(t, band);
        prop_assert!(m(&lower, lee) < m(&lower, windward), "lee {} windward {}", m(&lower, lee), m(&lower, windward));
        prop_assert!(m(&lower, lee) < m(&flat, lee) - 0.05, "lee {} without the ridge {}", m(&lower, lee), m(&flat, lee));
        prop_assert!(m(&higher, lee) < m(&lower, lee), "higher ridge's lee {} lower's {}", m(&higher, lee), m(&lower, lee));
        prop_assert!(m(&lower, slope) > m(&flat, slope), "slope {} without the ridge {}", m(&lower, slope), m(&flat, slope));
    }

    /// Two compilations of one map with winds, one on another thread, give every tile the same
    /// climate and biome, bit for bit (the rain is one table for the whole map).
    #[test]
    fn the_rain_is_the_same_on_every_thread(seed in any::<u32>(), wrap in any::<bool>(), one in prop::option::of(0.0f32..360.0)) {
        let mut config = MapConfig::load(maps_dir().join("world.map.ron")).unwrap();
        config.seed = seed;
        config.size = MapSize::Bounded { x: 32, z: 20 };
        config.setup = None;
        config.wrap = wrap;
        if let (Some(bearing), Some(winds)) = (one, config.climate.winds.as_mut()) {
            winds.pattern = WindPattern::One(bearing);
        }
        let here = Terrain::new(config.clone()).unwrap();
        let there = std::thread::spawn(move || Terrain::new(config).unwrap()).join().unwrap();
        for tile in here.tiles() {
            let (a, b) = (here.tile_climate(tile).unwrap(), there.tile_climate(tile).unwrap());
            prop_assert_eq!(a.moisture.to_bits(), b.moisture.to_bits());
            prop_assert_eq!(a.temperature.to_bits(), b.temperature.to_bits());
            prop_assert_eq!(biome::at(&here, tile), biome::at(&there, tile));
        }
    }
}

/// The bearing (degrees clockwise from north, `-z`) the wind of a row blows from under Earth's
/// bands (north-east trades, westerlies, polar easterlies), mirrored in the southern half.
fn earth_bearing(row: i32, rows: i32) -> f32 {
    let v = (row as f32 + 0.5) / rows as f32 - 0.5;
    let band = ((v.abs() * 2.0 * 3.0) as usize).min(2);
    let north = [45.0, 225.0, 45.0][band];
    if v < 0.0 { north } else { 180.0 - north }
}

/// Whether a mountain lies within [`REACH`] steps of `tile`, stepping each time to the neighbor
/// lying most squarely toward `bearing` (or away from it, `against`).
fn mountain_within(t: &Terrain, tile: Hex, bearing: f32, against: bool) -> bool {
    let b = bearing.to_radians();
    let sign = if against { -1.0 } else { 1.0 };
    let toward = [sign * b.sin() as f64, -sign * b.cos() as f64];
    let mut at = tile;
    for _ in 0..REACH {
        let [x, _, z] = t.tile_center(at).unwrap();
        // The step's direction from the neighbor as it lies (not its copy across a seam).
        let along = |h: Hex| {
            let [hx, _, hz] = t.tile_center(h).unwrap();
            let (dx, dz) = (hx - x, hz - z);
            (dx * toward[0] + dz * toward[1]) / dx.hypot(dz)
        };
        let in_map = t.neighbors(at).unwrap();
        let Some((_, next)) = at
            .all_neighbors()
            .into_iter()
            .zip(in_map)
            .filter_map(|(nb, copy)| copy.map(|copy| (nb, copy)))
            .max_by(|a, b| along(a.0).total_cmp(&along(b.0)))
        else {
            return false;
        };
        if t.tile_kind(next) == Some(TileKind::Mountain) {
            return true;
        }
        at = next;
    }
    false
}

/// How far behind (or before) a range a tile counts as in its lee (or on its windward side).
const REACH: usize = 5;

/// Desert shares of a map's plain land tiles (land, not hills): in the lee of mountains, on their windward side,
/// in the horse latitudes (a sixth of the way from the equator to the poles either side of a
/// third), and elsewhere.
fn desert_shares(t: &Terrain) -> [f64; 4] {
    let rows = t.bounds().unwrap().max[1];
    let mut counts = [(0.0, 0.0); 4];
    for tile in t.tiles() {
        if t.tile_kind(tile) != Some(TileKind::Land) || matches!(biome::at(t, tile), Some(Biome::Hills | Biome::Lake)) {
            continue;
        }
        let row = t.offset_of(tile)[1];
        let bearing = earth_bearing(row, rows);
        let desert = f64::from(u8::from(biome::at(t, tile) == Some(Biome::Desert)));
        let lee = mountain_within(t, tile, bearing, false);
        let windward = mountain_within(t, tile, bearing, true);
        let latitude = ((row as f32 + 0.5) / rows as f32 - 0.5).abs() * 2.0;
        let horse = (latitude - 1.0 / 3.0).abs() < 1.0 / 12.0;
        for (i, on) in [lee && !windward, windward && !lee, horse, !horse].into_iter().enumerate() {
            if on {
                counts[i].0 += desert;
                counts[i].1 += 1.0;
            }
        }
    }
    counts.map(|(d, n)| d / f64::max(n, 1.0))
}

/// The World preset's winds put deserts in the lee of its ranges and in the horse latitudes,
/// where the moisture fBm's climate (the same map without winds) puts them anywhere warm.
#[test]
fn deserts_lie_behind_ranges_and_in_the_horse_latitudes_of_the_world_preset() {
    let config = MapConfig::load(maps_dir().join("world.map.ron")).unwrap();
    assert!(config.climate.winds.is_some(), "the World preset blows Earth's winds");
    let winds = Terrain::new(config.clone()).unwrap();
    let fields =
        Terrain::new(MapConfig { climate: ClimateConfig { winds: None, ..config.climate.clone() }, ..config }).unwrap();
    let [lee, windward, horse, rest] = desert_shares(&winds);
    let [old_lee, old_windward, old_horse, old_rest] = desert_shares(&fields);
    println!(
        "desert share of plain land, winds / moisture fBm: lee of mountains {:.1}% / {:.1}%, windward {:.1}% / {:.1}%, \
         horse latitudes {:.1}% / {:.1}%, other latitudes {:.1}% / {:.1}%",
        lee * 100.0,
        old_lee * 100.0,
        windward * 100.0,
        old_windward * 100.0,
        horse * 100.0,
        old_horse * 100.0,
        rest * 100.0,
        old_rest * 100.0
    );
    assert!(lee > windward + 0.05, "lee {lee} windward {windward}");
    assert!(lee > old_lee, "lee {lee} without winds {old_lee}");
    assert!(horse > rest, "horse latitudes {horse} elsewhere {rest}");
}

/// Bad winds are refused by the field's name, with the value and what is allowed.
#[test]
fn bad_winds_are_refused_by_name() {
    let with = |f: &dyn Fn(&mut MapConfig)| {
        let mut c = MapConfig { size: MapSize::Bounded { x: 20, z: 12 }, ..MapConfig::default() };
        c.climate.enabled = true;
        c.climate.winds = Some(WindConfig::default());
        f(&mut c);
        c.validate().err().map(|e| e.to_string())
    };
    assert_eq!(with(&|_| {}), None);
    let refused = |f: &dyn Fn(&mut MapConfig), field: &str| {
        let e = with(f).unwrap_or_else(|| panic!("{field} accepted"));
        assert!(e.contains(field), "{e}");
    };
    refused(&|c| c.size = MapSize::Unbounded, "climate.winds");
    refused(&|c| c.climate.enabled = false, "climate.winds");
    refused(&|c| c.size = MapSize::Bounded { x: 1024, z: 1024 }, "climate.winds");
    refused(&|c| c.climate.winds.as_mut().unwrap().pattern = WindPattern::One(360.0), "climate.winds.pattern.One");
    refused(&|c| c.climate.winds.as_mut().unwrap().pattern = WindPattern::Bands(vec![]), "climate.winds.pattern");
    refused(
        &|c| c.climate.winds.as_mut().unwrap().pattern = WindPattern::Bands(vec![45.0, f32::NAN]),
        "climate.winds.pattern.Bands[1]",
    );
    refused(&|c| c.climate.winds.as_mut().unwrap().pattern = WindPattern::Bands(vec![0.0; 9]), "climate.winds.pattern");
    refused(&|c| c.climate.winds.as_mut().unwrap().evaporation = -0.1, "climate.winds.evaporation");
    refused(&|c| c.climate.winds.as_mut().unwrap().raininess = 1.5, "climate.winds.raininess");
    refused(&|c| c.climate.winds.as_mut().unwrap().rain_shadow = f32::INFINITY, "climate.winds.rain_shadow");
    refused(&|c| c.climate.winds.as_mut().unwrap().drying = 2.0, "climate.winds.drying");
    refused(&|c| c.climate.winds.as_mut().unwrap().uplift = -1.0, "climate.winds.uplift");
    refused(&|c| c.climate.winds.as_mut().unwrap().variety = 1.01, "climate.winds.variety");
    // In RON too, at the line and column.
    let e = MapConfig::from_ron("(size: Bounded(x: 9, z: 9), climate: (enabled: true, winds: Some((pattern: Two))))");
    assert!(e.is_err());
}

/// The winds change the moisture of most tiles and warm the middle latitudes (the temperature
/// follows halfway to the sun's height, never below the latitude's line); without winds the
/// climate is the moisture fBm's, bit for bit (the presets' fingerprints, in `assets.rs`).
#[test]
fn winds_change_the_moisture_and_warm_the_middle_latitudes() {
    let mut config = MapConfig::load(maps_dir().join("world.map.ron")).unwrap();
    config.setup = None;
    let winds = Terrain::new(config.clone()).unwrap();
    config.climate.winds = None;
    let fields = Terrain::new(config).unwrap();
    let differ = fields
        .tiles()
        .filter(|&h| fields.tile_climate(h).unwrap().moisture != winds.tile_climate(h).unwrap().moisture)
        .count();
    assert!(differ > fields.tiles().count() / 2, "{differ} tiles differ");
    for h in fields.tiles() {
        let (a, b) = (fields.tile_climate(h).unwrap(), winds.tile_climate(h).unwrap());
        assert!(b.temperature >= a.temperature, "{h:?}: {} with winds, {} without", b.temperature, a.temperature);
    }
}
