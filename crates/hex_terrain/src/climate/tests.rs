use super::*;
use crate::Terrain;
use crate::config::{BiomeRule, MapConfig};

#[test]
fn the_default_table_covers_both_kinds_once() {
    let mut c = MapConfig::default();
    c.climate.enabled = true;
    c.validate().unwrap();
    let land: Vec<&BiomeRule> = c.climate.biomes.iter().filter(|r| r.relief == TileKind::Land).collect();
    for t in 0..=20 {
        for m in 0..=20 {
            let (t, m) = (t as f32 / 20.0, m as f32 / 20.0);
            assert_eq!(land.iter().filter(|r| r.covers(t, m)).count(), 1, "t {t} m {m}");
        }
    }
}

#[test]
fn gaps_and_overlaps_in_the_table_name_the_rule() {
    let mut c = MapConfig::default();
    c.climate.enabled = true;
    c.climate.biomes.remove(1); // tundra: a gap in temperature
    let e = c.validate().unwrap_err();
    assert_eq!(e.field, "climate.biomes");
    assert!(e.value.contains("no Land rule"), "{e}");

    let mut c = MapConfig::default();
    c.climate.enabled = true;
    c.climate.biomes[1].temperature.1 = 0.5; // tundra over plains
    let e = c.validate().unwrap_err();
    assert!(e.field.starts_with("climate.biomes["), "{e}");
    assert!(e.value.contains("overlaps"), "{e}");
}

#[test]
fn climate_is_off_by_default_and_biomes_follow_the_kind() {
    let t = Terrain::new(MapConfig::default()).unwrap();
    for tile in t.tiles().take(50) {
        let info = t.tile_info(tile).unwrap();
        assert_eq!(t.ruleset().biome(info.terrain.terrain), Some(Biome::of_kind(info.kind)));
        assert!(t.tile_climate(tile).is_none());
    }
}

#[test]
fn poles_are_colder_than_the_equator() {
    let mut c = MapConfig { size: crate::MapSize::Bounded { x: 40, z: 60 }, ..MapConfig::default() };
    c.climate.enabled = true;
    c.climate.lapse_rate = 0.0;
    let t = Terrain::new(c).unwrap();
    let mean = |row: i32| {
        (0..40).map(|col| t.tile_climate(t.tile_from_offset([col, row])).unwrap().temperature).sum::<f32>() / 40.0
    };
    assert!(mean(0) + 0.5 < mean(30), "pole {} equator {}", mean(0), mean(30));
    assert!(mean(59) + 0.5 < mean(30));
}
