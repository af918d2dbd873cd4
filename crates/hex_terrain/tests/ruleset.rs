//! Terrain rulesets: random rulesets choose every tile's terrain and feature by the rules, as a
//! brute force written here recomputes them; bad rulesets are refused by entry and field.

use std::collections::BTreeMap;

use hex_terrain::{
    FeatureDef, FeaturePatches, Landform, LoadError, Occurs, TerrainDef, TerrainRuleset, TileFacts, Traits, Yields,
};
use proptest::prelude::*;
#[path = "common/biome.rs"]
mod biome;

/// A range `[lo, hi)` of `[0, 1]`, either whole or drawn.
fn range() -> impl Strategy<Value = (f32, f32)> {
    prop_oneof![Just((0.0, 1.0)), (0.0f32..0.9, 0.05f32..1.0).prop_map(|(lo, len)| (lo, (lo + len).min(1.0)))]
}

fn rule() -> impl Strategy<Value = Occurs> {
    (
        prop::sample::subsequence(Landform::ALL.to_vec(), 1..=6),
        range(),
        range(),
        range(),
        range(),
        prop::option::of(any::<bool>()),
        prop::option::of(any::<bool>()),
    )
        .prop_map(|(landform, temperature, moisture, elevation, latitude, near_water, near_river)| Occurs {
            landform,
            temperature,
            moisture,
            elevation,
            latitude,
            near_water,
            near_river,
            priority: 0,
        })
}

/// A random valid ruleset: 1-32 terrains of 0-3 rules, 0-16 features of 1-3 rules on 1-4
/// terrains; every rule its own priority (so no two overlap at one), every landform a fallback.
fn ruleset() -> impl Strategy<Value = TerrainRuleset> {
    (1usize..=32, 0usize..=16)
        .prop_flat_map(|(terrains, features)| {
            (
                prop::collection::vec(prop::collection::vec(rule(), 0..=3), terrains),
                prop::collection::vec(
                    (prop::collection::vec(rule(), 1..=3), prop::collection::vec(0..terrains, 1..=4), 0.05f32..=1.0),
                    features,
                ),
                prop::collection::vec(0..terrains, 6),
                Just(()).prop_perturb(|_, mut rng| {
                    let mut p: Vec<u8> = (0..=255).collect();
                    for i in (1..p.len()).rev() {
                        p.swap(i, rng.random_range(0..=i));
                    }
                    p
                }),
            )
        })
        .prop_map(|(terrain_rules, feature_rules, fallback, priorities)| {
            let mut next = priorities.into_iter();
            let terrains: Vec<TerrainDef> = terrain_rules
                .into_iter()
                .enumerate()
                .map(|(i, mut occurs)| {
                    for r in &mut occurs {
                        r.priority = next.next().unwrap();
                    }
                    TerrainDef {
                        id: format!("t{i}"),
                        name: format!("Terrain {i}"),
                        occurs,
                        traits: Traits {
                            movement: (i % 4) as u32,
                            tall: i % 3 == 0,
                            yields: Yields::new(i as f32, 1.0, 0.0),
                        },
                        hills: (i % 2 == 0).then_some(Traits {
                            movement: 3,
                            tall: true,
                            yields: Yields::new(0.0, 2.0, 0.0),
                        }),
                        look: Default::default(),
                    }
                })
                .collect();
            let features = feature_rules
                .into_iter()
                .enumerate()
                .map(|(i, (mut occurs, on, density))| {
                    for r in &mut occurs {
                        r.priority = next.next().unwrap();
                    }
                    let mut on: Vec<String> = on.into_iter().map(|t| format!("t{t}")).collect();
                    on.dedup();
                    FeatureDef {
                        id: format!("f{i}"),
                        name: format!("Feature {i}"),
                        on,
                        occurs,
                        density,
                        patch: 1.0 + i as f32,
                        traits: Traits { movement: 2, tall: i % 2 == 0, yields: Yields::new(1.0, 0.0, 1.0) },
                        replace: i % 3 == 0,
                        look: Default::default(),
                    }
                })
                .collect();
            let fallback: BTreeMap<Landform, String> =
                Landform::ALL.into_iter().zip(fallback).map(|(l, t)| (l, format!("t{t}"))).collect();
            TerrainRuleset { name: "random".to_owned(), fallback, terrains, features }
        })
}

fn facts() -> impl Strategy<Value = TileFacts> {
    (
        prop::sample::select(Landform::ALL.to_vec()),
        0.0f32..=1.0,
        0.0f32..=1.0,
        0.0f32..=1.0,
        0.0f32..=1.0,
        any::<bool>(),
        any::<bool>(),
        prop_oneof![4 => Just(true), 1 => Just(false)],
    )
        .prop_map(|(landform, temperature, moisture, elevation, latitude, near_water, near_river, climate)| {
            TileFacts { landform, temperature, moisture, elevation, latitude, near_water, near_river, climate }
        })
}

/// The test's own rule: every range half-open with 1 inside one ending at 1, every condition.
fn holds(r: &Occurs, f: &TileFacts) -> bool {
    let inside = |v: f32, (lo, hi): (f32, f32)| lo <= v && (v < hi || (hi == 1.0 && v == 1.0));
    r.landform.contains(&f.landform)
        && inside(f.temperature, r.temperature)
        && inside(f.moisture, r.moisture)
        && inside(f.elevation, r.elevation)
        && inside(f.latitude, r.latitude)
        && r.near_water.is_none_or(|w| w == f.near_water)
        && r.near_river.is_none_or(|w| w == f.near_river)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every tile's terrain is the one whose covering rule has the highest priority (every
    /// rule of every terrain tried here), else its landform's fallback; its feature sits on a
    /// terrain it lists, under a rule of its own that covers the tile, and no covering feature
    /// of a higher priority whose patches reach the tile was passed over.
    #[test]
    fn a_tile_gets_the_highest_priority_rule(ruleset in ruleset(), tiles in prop::collection::vec((facts(), -50.0f64..50.0, -50.0f64..50.0), 1..40), seed in any::<u32>()) {
        prop_assert!(ruleset.validate().is_ok(), "{:?}", ruleset.validate());
        let patches = FeaturePatches::new(&ruleset, seed, None);
        for (f, x, z) in tiles {
            let got = ruleset.terrain_for(&f);
            let best = ruleset
                .terrains
                .iter()
                .enumerate()
                .flat_map(|(i, t)| t.occurs.iter().filter(|r| f.climate && holds(r, &f)).map(move |r| (r.priority, i)))
                .max();
            let want = match best {
                Some((_, i)) => format!("t{i}"),
                None => ruleset.fallback[&f.landform].clone(),
            };
            prop_assert_eq!(&ruleset.terrain(got).id, &want);

            let feature = patches.feature_for(&ruleset, got, &f, (x, z));
            let admits = |d: &FeatureDef| {
                f.climate && d.on.contains(&want) && d.occurs.iter().any(|r| holds(r, &f))
            };
            let priority = |d: &FeatureDef| d.occurs.iter().filter(|r| holds(r, &f)).map(|r| r.priority).max();
            if let Some(id) = feature {
                let d = ruleset.feature(id);
                prop_assert!(admits(d), "{} on {want}", d.id);
                for (k, other) in ruleset.features.iter().enumerate() {
                    if admits(other) && priority(other) > priority(d) {
                        prop_assert!(!patches.reaches(hex_terrain::FeatureId(k as u8), x, z), "{} passed over", other.id);
                    }
                }
            } else {
                for (k, d) in ruleset.features.iter().enumerate() {
                    prop_assert!(!(admits(d) && patches.reaches(hex_terrain::FeatureId(k as u8), x, z)), "{} left out", d.id);
                }
            }
        }
    }

    /// A tile's traits: the terrain's (its hills traits on hills), then the feature's, which
    /// replace them or add to them.
    #[test]
    fn traits_follow_terrain_and_feature(ruleset in ruleset(), landform in prop::sample::select(Landform::ALL.to_vec()), t in 0usize..32, f in prop::option::of(0usize..16)) {
        let t = hex_terrain::TerrainId((t % ruleset.terrains.len()) as u8);
        let f = f.filter(|_| !ruleset.features.is_empty()).map(|f| hex_terrain::FeatureId((f % ruleset.features.len()) as u8));
        let def = ruleset.terrain(t);
        let base = if landform == Landform::Hills { def.hills.unwrap_or(def.traits) } else { def.traits };
        let got = ruleset.traits(t, landform, f);
        match f.map(|f| ruleset.feature(f)) {
            None => prop_assert_eq!(got, base),
            Some(d) if d.replace => prop_assert_eq!(got, d.traits),
            Some(d) => {
                let movement = if base.movement == 0 || d.traits.movement == 0 { 0 } else { base.movement.max(d.traits.movement) };
                prop_assert_eq!(got.movement, movement);
                prop_assert_eq!(got.tall, base.tall || d.traits.tall);
                prop_assert_eq!(got.yields.food, base.yields.food + d.traits.yields.food);
                prop_assert_eq!(got.yields.gold, base.yields.gold + d.traits.yields.gold);
            }
        }
    }
}

/// A feature's patches cover about its density of the tiles it may sit on, in patches: over a
/// wide area, the share within 0.1 of the density, and a tile's neighbors agree with it far more
/// often than chance.
#[test]
fn patches_cover_about_their_density_in_patches() {
    for (density, patch) in [(0.2f32, 2.0f32), (0.45, 3.0), (0.7, 5.0)] {
        let ruleset = TerrainRuleset {
            name: String::new(),
            fallback: Landform::ALL.into_iter().map(|l| (l, "t".to_owned())).collect(),
            terrains: vec![TerrainDef {
                id: "t".into(),
                name: "T".into(),
                occurs: Vec::new(),
                traits: Traits::default(),
                hills: None,
                look: Default::default(),
            }],
            features: vec![FeatureDef {
                id: "f".into(),
                name: "F".into(),
                on: vec!["t".into()],
                occurs: vec![Occurs { landform: Landform::ALL.to_vec(), ..Occurs::default() }],
                density,
                patch,
                traits: Traits::default(),
                replace: false,
                look: Default::default(),
            }],
        };
        ruleset.validate().unwrap();
        let patches = FeaturePatches::new(&ruleset, 7, None);
        let f = hex_terrain::FeatureId(0);
        let (mut on, mut same, mut pairs, n) = (0, 0, 0, 200);
        for i in 0..n {
            for j in 0..n {
                let (x, z) = (f64::from(i) * 1.732, f64::from(j) * 1.5);
                let here = patches.reaches(f, x, z);
                on += usize::from(here);
                same += usize::from(here == patches.reaches(f, x + 1.732, z));
                pairs += 1;
            }
        }
        let share = on as f64 / f64::from(n * n);
        println!(
            "density {density} patch {patch}: covers {share:.3}, neighbors agree {:.3}",
            same as f64 / f64::from(pairs)
        );
        assert!((share - f64::from(density)).abs() < 0.1, "density {density}: {share}");
        let chance = share * share + (1.0 - share) * (1.0 - share);
        assert!(same as f64 / f64::from(pairs) > chance + 0.1, "patches, not salt and pepper");
    }
}

/// Bad rulesets are refused, naming the entry, the field, the value and what is allowed.
#[test]
fn bad_rulesets_name_the_entry_and_the_field() {
    let base = include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron");
    let cases = [
        (
            base.replace(r#"on: ["desert"],"#, r#"on: ["dessert"],"#),
            "ruleset.features[3] \"floodplains\".on[0]",
            "\"dessert\"",
        ),
        (
            base.replace("temperature: (0.2, 0.36), priority: 2", "temperature: (0.36, 0.2), priority: 2"),
            "ruleset.terrains[6] \"tundra\".occurs[0].temperature",
            "(0.36, 0.2)",
        ),
        (
            base.replace(
                "temperature: (0.6, 1.0), moisture: (0.0, 0.18), priority: 1",
                "temperature: (0.6, 1.0), moisture: (0.0, 0.18), priority: 0",
            ),
            "ruleset.terrains[5] \"desert\".occurs[0].priority",
            "0",
        ),
        (base.replace("density: 0.55", "density: 1.5"), "ruleset.features[0] \"forest\".density", "1.5"),
        (base.replace("Mountain: \"mountain\"", "Mountain: \"peak\""), "ruleset.fallback.Mountain", "\"peak\""),
        (base.replace("(id: \"lake\"", "(id: \"coast\""), "ruleset.terrains[2] \"coast\".id", "\"coast\""),
    ];
    for (text, field, value) in cases {
        match TerrainRuleset::from_ron(&text) {
            Err(LoadError::Invalid(e)) => {
                assert_eq!(e.field, field, "{e}");
                assert_eq!(e.value, value, "{e}");
                assert!(!e.allowed.is_empty());
            }
            other => panic!("{field}: {other:?}"),
        }
    }
    // More terrains than the material holds.
    let mut many = TerrainRuleset::from_ron(base).unwrap();
    let extra = many.terrains[0].clone();
    many.terrains.extend((0..40).map(|i| TerrainDef { id: format!("x{i}"), occurs: Vec::new(), ..extra.clone() }));
    let e = many.validate().unwrap_err();
    assert_eq!(e.field, "ruleset.terrains", "{e}");
    // Malformed text: the line and column.
    let e = TerrainRuleset::from_ron("(\n  fallback: {},\n  terrains: [(id: 3)],\n)").unwrap_err();
    assert!(e.to_string().contains("3:"), "{e}");
}

/// A ruleset survives a trip through RON.
#[test]
fn a_ruleset_round_trips_through_ron() {
    for name in ["default", "civ5", "fantasy"] {
        let path = format!("{}/../bevy_hex_terrain/assets/rulesets/{name}.terrain.ron", env!("CARGO_MANIFEST_DIR"));
        let ruleset = TerrainRuleset::load(path).unwrap();
        assert_eq!(TerrainRuleset::from_ron(&ruleset.to_ron()).unwrap(), ruleset, "{name}");
    }
}

fn maps() -> impl Strategy<Value = hex_terrain::MapConfig> {
    (any::<u32>(), 8i32..24, 6i32..16, any::<bool>(), any::<bool>(), 0u8..3, any::<bool>(), any::<bool>()).prop_map(
        |(seed, x, z, wrap, climate, rivers, winds, bounded)| {
            let mut text = format!(
                "(seed: {seed}, size: {}, wrap: {}, chunk_size: (8, 8), climate: (enabled: {climate}{}), rivers: {})",
                if bounded { format!("Bounded(x: {}, z: {z})", x + x % 2) } else { "Unbounded".to_owned() },
                wrap && bounded && climate,
                if winds && bounded && climate { ", winds: Some((pattern: Bands([45, 225, 45])))" } else { "" },
                match rivers {
                    _ if !(climate && bounded) => "(enabled: false)",
                    0 => "(enabled: false)",
                    1 => "(enabled: true, threshold: 3.0)",
                    _ => "(enabled: true, model: Edges, sources: Relief(tiles_per_edge: 8.0))",
                },
            );
            text = text.replace("wrap: false, ", "");
            hex_terrain::MapConfig::from_ron(&text).unwrap()
        },
    )
}

fn tiles(t: &hex_terrain::Terrain) -> Vec<hex_terrain::hexx::Hex> {
    match t.bounds() {
        Some(_) => t.tiles().collect(),
        None => hex_terrain::TileRect::new([-6, -6], [12, 10]).iter().map(|oc| t.tile_from_offset(oc)).collect(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// On random maps (bounded or not, wrapping, with climate, winds and either river model),
    /// the default ruleset's rules (its terrain for the tile's facts, computed here) give every
    /// tile the terrain and landform its info has (its biome); under the
    /// Civilization V ruleset every feature sits on a terrain it lists, a tile's answer is the
    /// same for its copy across a wrapping map's seam and on another thread.
    #[test]
    fn maps_read_through_a_ruleset(config in maps()) {
        let t = hex_terrain::Terrain::new(config.clone()).unwrap();
        prop_assert_eq!(t.ruleset(), &TerrainRuleset::biomes(&config));
        for h in tiles(&t) {
            let info = t.tile_info(h).unwrap();
            let sample = t.pipeline().tile_sample(h);
            let lake = t.lake(h).is_some();
            let climate = t.tile_climate(h).filter(|_| !lake && sample.kind != hex_terrain::TileKind::Sea);
            let facts = t.climate().facts(t.geometry(), h, &sample, lake, climate, (false, false));
            prop_assert_eq!(t.ruleset().terrain_for(&facts), info.terrain.terrain, "{:?} {:?}", h, facts);
            prop_assert_eq!(facts.landform, info.terrain.landform, "{:?}", h);
            prop_assert_eq!(t.ruleset().biome(info.terrain.terrain).map(|b| b as u8), Some(info.terrain.terrain.0));
        }
        let civ = std::sync::Arc::new(
            TerrainRuleset::from_ron(include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap(),
        );
        let with_civ = hex_terrain::MapConfig { ruleset: Some("civ5.terrain.ron".to_owned()), ..config };
        let t = hex_terrain::Terrain::with_sources(with_civ.clone(), None, Some(civ.clone())).unwrap();
        let elsewhere = std::thread::spawn({
            let (config, civ) = (with_civ, civ.clone());
            move || {
                let t = hex_terrain::Terrain::with_sources(config, None, Some(civ)).unwrap();
                tiles(&t).into_iter().map(|h| t.tile_info(h).map(|i| i.terrain).unwrap()).collect::<Vec<_>>()
            }
        })
        .join()
        .unwrap();
        // The meshes take the ruleset's colors (a tile's center: its feature's, else its
        // terrain's), and a map meshed chunk by chunk has the colors of the whole.
        if t.has_vertex_colors() {
            for h in tiles(&t).into_iter().take(60) {
                let got = t.tile_info(h).map(|i| i.terrain).unwrap();
                let look = got.feature.map_or(&civ.terrain(got.terrain).look, |f| &civ.feature(f).look);
                let color = t.point_color(t.lattice().tile_center(h)).unwrap();
                prop_assert_eq!([color[0], color[1], color[2]], look.color);
            }
            // The minimap paints a tile's center pixel in its look's minimap color.
            let rect = t.bounds().unwrap_or(hex_terrain::TileRect::new([0, 0], [16, 12]));
            let style = hex_terrain::minimap::MinimapStyle::default();
            if let Some(map) = hex_terrain::minimap::Minimap::new(&t, rect, [240, 240], style.clone()) {
                let visible = map.paint(|_| hex_terrain::minimap::TileLook::VISIBLE);
                let w = map.size()[0];
                for h in rect.iter().map(|oc| t.tile_from_offset(oc)).take(80) {
                    let [x, _, z] = t.tile_center(h).unwrap();
                    let [px, py] = map.world_to_pixel(x, z);
                    let (px, py) = (px as u32, py as u32);
                    if map.tile_at_pixel(px, py) != Some(h) || t.river(h).is_some() {
                        continue;
                    }
                    let got = t.tile_info(h).map(|i| i.terrain).unwrap();
                    let look = got.feature.map_or(&civ.terrain(got.terrain).look, |f| &civ.feature(f).look);
                    let want = if t.lake(h).is_some() { style.water_color } else { look.minimap.unwrap_or(look.color) };
                    let i = ((py * w + px) * 4) as usize;
                    prop_assert_eq!(&visible[i..i + 3], &want[..], "tile {:?}", h);
                }
            }
            // Props: what the tile's feature (else terrain) grows, of its kind and size.
            let whole = t.generate_rect(t.bounds().unwrap_or(hex_terrain::TileRect::new([0, 0], [16, 12])));
            for prop in t.props(&whole, 100_000, 1.0) {
                let got = t.tile_info(prop.tile).map(|i| i.terrain).unwrap();
                let look = got.feature.map_or(&civ.terrain(got.terrain).look, |f| &civ.feature(f).look);
                let grows = look.props.unwrap();
                prop_assert!(prop.kind == grows.kind || matches!(prop.kind, hex_terrain::PropKind::Resource | hex_terrain::PropKind::Wonder));
                prop_assert!(prop.kind != grows.kind || (prop.scale - grows.size).abs() < 1.0, "{:?}", prop);
            }
            if t.bounds().is_some() {
                let key = |o: [f64; 3], p: [f32; 3]| {
                    [0, 2].map(|k| ((o[k] + f64::from(p[k])) * 100.0).round() as i64)
                };
                let whole = t.generate_map().unwrap();
                let colors: std::collections::HashMap<[i64; 2], [u8; 4]> = whole
                    .buffers
                    .positions
                    .iter()
                    .zip(&whole.buffers.colors)
                    .map(|(&p, &c)| (key(whole.origin, p), c))
                    .collect();
                for coord in t.chunks() {
                    let m = t.generate_chunk(coord).unwrap();
                    for (&p, c) in m.buffers.positions.iter().zip(&m.buffers.colors) {
                        prop_assert_eq!(colors.get(&key(m.origin, p)), Some(c));
                    }
                }
            }
        }
        // MapStats counts the ruleset's terrains (and those on hills) and features.
        if let Some(stats) = hex_terrain::MapStats::measure(&t) {
            let all: Vec<_> = t.tiles().map(|h| t.tile_info(h).map(|i| i.terrain).unwrap()).collect();
            for (i, _) in civ.terrains.iter().enumerate() {
                let n = all.iter().filter(|x| usize::from(x.terrain.0) == i).count() as u32;
                let hills = all.iter().filter(|x| usize::from(x.terrain.0) == i && x.landform == Landform::Hills).count() as u32;
                let got = stats.terrains.iter().find(|e| usize::from(e.0.0) == i).map_or((0, 0), |e| (e.1, e.2));
                prop_assert_eq!(got, (n, hills), "terrain {}", i);
            }
            for (i, _) in civ.features.iter().enumerate() {
                let n = all.iter().filter(|x| x.feature.is_some_and(|f| usize::from(f.0) == i)).count() as u32;
                prop_assert_eq!(stats.features[i].1, n, "feature {}", i);
            }
        }
        for (h, there) in tiles(&t).into_iter().zip(elsewhere) {
            let here = t.tile_info(h).map(|i| i.terrain).unwrap();
            prop_assert_eq!(here, there);
            if let Some(f) = here.feature {
                prop_assert!(civ.feature(f).on.contains(&civ.terrain(here.terrain).id));
            }
            if let Some(w) = t.wrap() {
                let copy = h + w.tile_shift;
                prop_assert_eq!(t.tile_info(copy).map(|i| i.terrain), Some(here));
            }
        }
    }
}

/// Every triangle of every chunk of `t` (a bounded map's, or those around the origin) lies in
/// one tile (the one under its centroid), and each of its three vertices holds that tile's
/// texture layer (its feature's, else its terrain's, in `ruleset`) in the entry of the tile's
/// class.
fn triangles_hold_their_tiles_layers(t: &hex_terrain::Terrain, ruleset: &TerrainRuleset) -> Result<(), TestCaseError> {
    let chunks = match t.bounds() {
        Some(_) => t.chunks(),
        None => [(-1, -1), (0, 0), (1, 0), (0, 1)].map(|(x, z)| hex_terrain::ChunkCoord::new(x, z)).to_vec(),
    };
    for coord in chunks {
        let Some(m) = t.generate_chunk(coord) else { continue };
        let b = &m.buffers;
        prop_assert_eq!(b.texture_layers.len(), b.positions.len());
        for tri in b.indices.chunks(3) {
            let world = |k: usize| {
                let p = b.positions[tri[k] as usize];
                [m.origin[0] + f64::from(p[0]), m.origin[2] + f64::from(p[2])]
            };
            let [a, c, d] = [world(0), world(1), world(2)];
            let tile = t.tile_at((a[0] + c[0] + d[0]) / 3.0, (a[1] + c[1] + d[1]) / 3.0).unwrap();
            prop_assert!(
                m.tiles.iter().any(|i| i.hex == tile),
                "a triangle of {:?} outside its chunk {:?}",
                tile,
                coord
            );
            let got = t.tile_info(tile).map(|i| i.terrain).unwrap();
            let look = got.feature.map_or(&ruleset.terrain(got.terrain).look, |f| &ruleset.feature(f).look);
            let class = hex_terrain::texture_class(tile);
            for &v in tri {
                prop_assert_eq!(
                    b.texture_layers[v as usize][class],
                    look.texture,
                    "tile {:?} of chunk {:?}",
                    tile,
                    coord
                );
            }
        }
    }
    Ok(())
}

/// Texture layers across a wrapping map's seam where one chunk holds both sides of it (the
/// map no wider than a chunk) and where two chunks meet there, flat and pointy, at widths whose
/// tiles' classes repeat across the seam and at widths whose classes do not (pointy tiles in
/// rows of a width not a multiple of 3: there the tiles on either side of the seam may be of one
/// class).
#[test]
fn texture_layers_hold_across_a_wrapping_seam() {
    let maps = [(8, 8, "Flat"), (10, 8, "Pointy"), (7, 8, "Pointy"), (14, 4, "Pointy"), (16, 16, "Flat")];
    for (seed, (x, chunk, orientation)) in maps.into_iter().enumerate() {
        let text = format!(
            "(seed: {seed}, size: Bounded(x: {x}, z: 8), wrap: true, chunk_size: ({chunk}, 8), climate: (enabled: true), \
             layout: (orientation: {orientation}), terrain: (sea_threshold: 0.3, mountain_threshold: 0.7))"
        );
        let config = hex_terrain::MapConfig::from_ron(&text).unwrap();
        let t = hex_terrain::Terrain::new(config.clone()).unwrap();
        assert!(t.has_vertex_colors());
        triangles_hold_their_tiles_layers(&t, t.ruleset()).unwrap();
        let civ = civ_with_layers();
        let with_civ = hex_terrain::MapConfig { ruleset: Some("civ5.terrain.ron".to_owned()), ..config };
        let t = hex_terrain::Terrain::with_sources(with_civ, None, Some(civ.clone())).unwrap();
        triangles_hold_their_tiles_layers(&t, &civ).unwrap();
    }
}

/// The Civilization V ruleset with a texture layer of its own for each terrain and feature.
fn civ_with_layers() -> std::sync::Arc<TerrainRuleset> {
    let mut civ =
        TerrainRuleset::from_ron(include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap();
    for (i, terrain) in civ.terrains.iter_mut().enumerate() {
        terrain.look.texture = (3 * i as u8 + 1) % 32;
    }
    for (i, feature) in civ.features.iter_mut().enumerate() {
        feature.look.texture = (5 * i as u8 + 17) % 32;
    }
    std::sync::Arc::new(civ)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    /// The meshes' texture layers: on random maps with vertex colors (bounded or not, wrapping
    /// across seams of any width), under the default ruleset and under the Civilization V one
    /// with a layer of its own for every terrain and feature, every vertex of a triangle holds
    /// the layer of the triangle's tile in the entry of its class; a map without colors has
    /// none.
    #[test]
    fn every_triangle_is_drawn_with_its_tiles_texture_layer(config in maps()) {
        let t = hex_terrain::Terrain::new(config.clone()).unwrap();
        if !t.has_vertex_colors() {
            let rect = t.bounds().unwrap_or(hex_terrain::TileRect::new([0, 0], [8, 8]));
            prop_assert!(t.generate_rect(rect).buffers.texture_layers.is_empty());
            return Ok(());
        }
        triangles_hold_their_tiles_layers(&t, t.ruleset())?;
        let civ = civ_with_layers();
        let with_civ = hex_terrain::MapConfig { ruleset: Some("civ5.terrain.ron".to_owned()), ..config };
        let t = hex_terrain::Terrain::with_sources(with_civ, None, Some(civ.clone())).unwrap();
        triangles_hold_their_tiles_layers(&t, &civ)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    /// Under a map's own ruleset the rules read the tiles' traits: entering a tile costs its
    /// traits' movement (the sea `movement.embark` when set, a river `movement.river` more),
    /// mountains stand 2 for sight and tall traits 1; paths cost what a Dijkstra written here
    /// over those costs (and the river crossings) finds; the game setup's yields are the
    /// traits'.
    #[test]
    fn the_rules_read_the_traits(seed in any::<u32>(), embark in prop::option::of(1u32..4), pairs in prop::collection::vec((0usize..400, 0usize..400), 4)) {
        let civ = std::sync::Arc::new(
            TerrainRuleset::from_ron(include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap(),
        );
        let mut config = hex_terrain::MapConfig::from_ron(&format!(
            "(seed: {seed}, size: Bounded(x: 24, z: 16), chunk_size: (8, 8), climate: (enabled: true), \
             rivers: (enabled: true, model: Edges, sources: Relief(tiles_per_edge: 6.0)), ruleset: Some(\"civ5.terrain.ron\"), \
             setup: Some((players: 2, min_distance: 4)))"
        ))
        .unwrap();
        config.movement.embark = embark;
        let Ok(t) = hex_terrain::Terrain::with_sources(config.clone(), None, Some(civ.clone())) else {
            // Two starts that do not fit a small map are refused by name: nothing to check.
            return Ok(());
        };
        let tiles: Vec<_> = t.tiles().collect();
        let index = |h: hex_terrain::hexx::Hex| tiles.iter().position(|&x| x == h);
        let cost: Vec<Option<u32>> = tiles
            .iter()
            .map(|&h| {
                let tt = t.tile_info(h).map(|i| i.terrain).unwrap();
                let sea = matches!(tt.landform, Landform::OpenSea | Landform::Shore);
                let base = if sea { embark.unwrap_or(tt.traits.movement) } else { tt.traits.movement };
                let river = t.river_flow(h).unwrap_or(0.0) > 0.0;
                (base > 0).then_some(base + if river { config.movement.river } else { 0 })
            })
            .collect();
        for (i, &h) in tiles.iter().enumerate() {
            prop_assert_eq!(t.move_cost(h), cost[i], "{:?}", h);
            let tt = t.tile_info(h).map(|i| i.terrain).unwrap();
            let height = if t.tile_kind(h) == Some(hex_terrain::TileKind::Mountain) && t.lake(h).is_none() {
                2
            } else {
                u8::from(tt.traits.tall)
            };
            prop_assert_eq!(t.sight_height(h), Some(height));
        }
        // A Dijkstra over those costs, a river on the edge crossed costing more.
        for (a, b) in pairs {
            let (a, b) = (a % tiles.len(), b % tiles.len());
            let mut best = vec![u32::MAX; tiles.len()];
            let mut queue = std::collections::BinaryHeap::new();
            best[a] = 0;
            queue.push(std::cmp::Reverse((0u32, a)));
            while let Some(std::cmp::Reverse((d, i))) = queue.pop() {
                if d > best[i] {
                    continue;
                }
                for n in tiles[i].all_neighbors() {
                    let Some(j) = t.wrap_tile(n).and_then(index) else { continue };
                    let Some(c) = cost[j] else { continue };
                    let across = if t.crosses_river(tiles[i], tiles[j]) { config.movement.river } else { 0 };
                    if d + c + across < best[j] {
                        best[j] = d + c + across;
                        queue.push(std::cmp::Reverse((best[j], j)));
                    }
                }
            }
            let want = (best[b] != u32::MAX).then_some(best[b]);
            prop_assert_eq!(t.path(tiles[a], tiles[b]).map(|p| p.cost), want);
        }
        // The setup's report: each start's yields, the traits' of the tiles in its rings plus
        // the river and coast bonuses and what the resources and wonders add.
        let setup = t.setup().unwrap();
        let cfg = config.setup.as_ref().unwrap();
        for row in &setup.report().starts {
            let mut sum = Yields::default();
            for &h in tiles.iter().filter(|&&h| t.distance(row.tile, h).is_some_and(|d| d <= cfg.rings)) {
                let tt = t.tile_info(h).map(|i| i.terrain).unwrap();
                let river = t.river_flow(h).unwrap_or(0.0) > 0.0 || !t.river_edges(h).is_empty();
                let sea = |n: hex_terrain::hexx::Hex| {
                    t.wrap_tile(n).is_some_and(|n| t.tile_kind(n) == Some(hex_terrain::TileKind::Sea) && t.lake(n).is_none())
                };
                let coast = t.tile_kind(h) != Some(hex_terrain::TileKind::Sea) && h.all_neighbors().into_iter().any(sea);
                sum += tt.traits.yields;
                if river {
                    sum += cfg.yields.river;
                }
                if coast {
                    sum += cfg.yields.coast;
                }
                if let Some(r) = t.resource(h) {
                    sum += cfg.resources[r.rule as usize].yields;
                }
                if let Some(w) = t.wonder(h) {
                    sum += cfg.wonders.list[w.rule as usize].yields;
                }
            }
            for (got, want) in row.yields.values().iter().zip(sum.values()) {
                prop_assert!((got - want).abs() < 1e-3, "start {:?}: {:?} against {:?}", row.tile, row.yields, sum);
            }
        }
    }
}

/// A map with its own ruleset refuses biome-keyed costs, sight and yields, by field.
#[test]
fn a_ruleset_map_refuses_biome_keyed_rules() {
    let base = "size: Bounded(x: 12, z: 10), climate: (enabled: true), ruleset: Some(\"civ5.terrain.ron\")";
    for (extra, field) in [
        ("movement: (costs: {Forest: 3})", "movement.costs"),
        ("sight: (tall: [Hills])", "sight.tall"),
        ("setup: Some((yields: (biomes: {Forest: (food: 3.0)})))", "setup.yields.biomes"),
        ("", ""),
    ] {
        let text = format!("({base}, {extra})").replace(", )", ")");
        match hex_terrain::MapConfig::from_ron(&text) {
            Err(LoadError::Invalid(e)) => assert_eq!(e.field, field, "{e}"),
            Ok(_) => assert!(field.is_empty(), "{text}"),
            Err(e) => panic!("{e}"),
        }
    }
}

/// Resources and wonders placed by terrain and feature: every placed one lies on a tile of a
/// terrain or with a feature its rule names (the map's own ruleset, or the biome table's
/// ids); an id the ruleset lacks is refused by field, naming the ruleset's ids.
#[test]
fn resources_lie_on_the_terrains_and_features_they_name() {
    let civ = std::sync::Arc::new(
        TerrainRuleset::from_ron(include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap(),
    );
    let setup = |ruleset: &str, on: &str| {
        format!(
            "(seed: 5, size: Bounded(x: 48, z: 30), climate: (enabled: true), {ruleset} \
             setup: Some((players: 2, min_distance: 6, resources: [\
               (name: \"deer\", on: [{on}], density: 0.08, spacing: 2, yields: (food: 1.0)),\
               (name: \"gold\", class: Luxury, on: [Terrain(\"desert\"), Kind(Mountain)], density: 0.05, spacing: 2, yields: (gold: 2.0)),\
             ])))"
        )
    };
    let ruled = "ruleset: Some(\"civ5.terrain.ron\"),";
    let config = hex_terrain::MapConfig::from_ron(&setup(ruled, "Feature(\"forest\"), Terrain(\"tundra\")")).unwrap();
    let t = hex_terrain::Terrain::with_sources(config, None, Some(civ.clone())).unwrap();
    let placed = t.setup().unwrap().resources();
    assert!(placed.iter().any(|r| r.name == "deer") && placed.iter().any(|r| r.name == "gold"), "{placed:?}");
    for r in placed {
        let tt = t.tile_info(r.tile).map(|i| i.terrain).unwrap();
        let terrain = &civ.terrain(tt.terrain).id;
        let feature = tt.feature.map(|f| civ.feature(f).id.as_str());
        match r.name.as_str() {
            "deer" => assert!(feature == Some("forest") || terrain == "tundra", "deer on {terrain} {feature:?}"),
            _ => assert!(
                terrain == "desert" || t.tile_kind(r.tile) == Some(hex_terrain::TileKind::Mountain),
                "gold on {terrain}"
            ),
        }
    }
    // The biome table's ids without a ruleset of the map's own.
    let config = hex_terrain::MapConfig::from_ron(&setup("", "Terrain(\"forest\"), Terrain(\"snow_peak\")")).unwrap();
    let t = hex_terrain::Terrain::new(config).unwrap();
    for r in t.setup().unwrap().resources().iter().filter(|r| r.name == "deer") {
        let biome = biome::at(&t, r.tile).unwrap();
        assert!(matches!(biome, hex_terrain::Biome::Forest | hex_terrain::Biome::SnowPeak), "{biome:?}");
    }
    // An id the ruleset lacks.
    let config = hex_terrain::MapConfig::from_ron(&setup(ruled, "Feature(\"taiga\")")).unwrap();
    let e = hex_terrain::Terrain::with_sources(config, None, Some(civ)).unwrap_err();
    assert_eq!(e.field, "setup.resources[0].on[0]", "{e}");
    assert!(e.allowed.contains("forest") && e.allowed.contains("jungle"), "{e}");
}

/// The world builder paints terrains and features of the map's own ruleset: the tiles the brush
/// covers take them (and their traits), undo brings the generated ones back, the edits travel
/// as ids in the map file (a ruleset that lost one refuses the file, naming the edit and the
/// ids it has); biomes are painted only on maps of biomes, terrains only on maps with their own
/// ruleset.
#[test]
fn the_world_builder_paints_terrains_and_features() {
    use hex_terrain::{Brush, Editor, FeatureEdit, RuleId, Stroke, Tool};
    let civ = std::sync::Arc::new(
        TerrainRuleset::from_ron(include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap(),
    );
    let config = hex_terrain::MapConfig::from_ron(
        "(seed: 8, size: Bounded(x: 24, z: 16), climate: (enabled: true), ruleset: Some(\"civ5.terrain.ron\"))",
    )
    .unwrap();
    let terrain = hex_terrain::Terrain::with_sources(config.clone(), None, Some(civ.clone())).unwrap();
    let land = terrain.tiles().find(|&t| terrain.tile_kind(t) == Some(hex_terrain::TileKind::Land)).unwrap();
    let before = terrain.tile_info(land).map(|i| i.terrain).unwrap();
    let mut editor = Editor::from_terrain(terrain);
    let desert = RuleId::new("desert").unwrap();
    let oasis = RuleId::new("oasis").unwrap();
    editor.apply(Stroke { tool: Tool::SetTerrain(desert), brush: Brush::Range(0), tile: land }).unwrap();
    editor
        .apply(Stroke { tool: Tool::SetFeature(FeatureEdit::Grow(oasis)), brush: Brush::Range(0), tile: land })
        .unwrap();
    let t = editor.terrain().tile_info(land).map(|i| i.terrain).unwrap();
    assert_eq!(civ.terrain(t.terrain).id, "desert");
    assert_eq!(t.feature.map(|f| civ.feature(f).id.as_str()), Some("oasis"));
    assert_eq!(t.traits, civ.traits(t.terrain, t.landform, t.feature));
    // The map file holds the ids and loads back to the same tiles.
    let saved = editor.config();
    let text = saved.to_ron();
    assert!(text.contains("terrain: Some(\"desert\")") && text.contains("Grow(\"oasis\")"), "{text}");
    let again =
        hex_terrain::Terrain::with_sources(hex_terrain::MapConfig::from_ron(&text).unwrap(), None, Some(civ.clone()))
            .unwrap();
    assert_eq!(again.tile_info(land).map(|i| i.terrain), editor.terrain().tile_info(land).map(|i| i.terrain));
    // Clearing the feature, then undoing everything: the generated tile.
    editor.apply(Stroke { tool: Tool::SetFeature(FeatureEdit::Clear), brush: Brush::Range(0), tile: land }).unwrap();
    assert_eq!(editor.terrain().tile_info(land).map(|i| i.terrain).unwrap().feature, None);
    while editor.undo().is_some() {}
    assert_eq!(editor.terrain().tile_info(land).map(|i| i.terrain), Some(before));
    // A ruleset without oasis refuses the saved file by the edit's field.
    let mut no_oasis = (*civ).clone();
    no_oasis.features.retain(|f| f.id != "oasis");
    let e = hex_terrain::Terrain::with_sources(saved.clone(), None, Some(std::sync::Arc::new(no_oasis))).unwrap_err();
    assert!(e.field.ends_with(".feature") && e.allowed.contains("forest"), "{e}");
    // An unknown terrain painted: refused, the map as it was.
    let mut editor = Editor::from_terrain(hex_terrain::Terrain::with_sources(config, None, Some(civ)).unwrap());
    let err = editor.apply(Stroke {
        tool: Tool::SetTerrain(RuleId::new("lava").unwrap()),
        brush: Brush::Range(0),
        tile: land,
    });
    assert!(err.is_err() && editor.edited_tiles() == 0, "{err:?}");
    // Biomes on maps of biomes, terrains on maps with their own ruleset.
    let biomes = hex_terrain::MapConfig::from_ron("(size: Bounded(x: 12, z: 10), climate: (enabled: true))").unwrap();
    let mut editor = Editor::new(biomes).unwrap();
    let tile = editor.terrain().tile_from_offset([3, 3]);
    assert!(editor.apply(Stroke { tool: Tool::SetTerrain(desert), brush: Brush::Range(0), tile }).is_err());
    assert!(
        hex_terrain::MapConfig::from_ron(
            "(size: Bounded(x: 12, z: 10), ruleset: Some(\"civ5.terrain.ron\"), edits: [(at: (3, 3), biome: Some(Desert))])"
        )
        .is_err()
    );
}

/// The world builder puts land tiles on hills and takes them off: each land tile the brush
/// covers lands on the landform asked (by the rule written here: its center's raw height
/// against the hills line), keeps its type, and takes the ruleset's traits for that landform
/// (Civilization V's grassland hills cost 2); sea and mountains stay; a map without a hills line
/// refuses the tool by name; undo gives the generated tiles back. On maps of biomes, hills are
/// the Hills biome's.
#[test]
fn the_world_builder_puts_tiles_on_hills_and_off() {
    use hex_terrain::{Brush, EditError, Editor, Landform, Stroke, TileKind, Tool};
    let civ = std::sync::Arc::new(
        TerrainRuleset::from_ron(include_str!("../../bevy_hex_terrain/assets/rulesets/civ5.terrain.ron")).unwrap(),
    );
    for (seed, own) in [(8, true), (9, true), (8, false), (11, false)] {
        let ruled = if own { "ruleset: Some(\"civ5.terrain.ron\")," } else { "" };
        let config = hex_terrain::MapConfig::from_ron(&format!(
            "(seed: {seed}, size: Bounded(x: 24, z: 16), climate: (enabled: true, hills: 0.55), {ruled})"
        ))
        .unwrap();
        let ruleset = own.then(|| civ.clone());
        let terrain = hex_terrain::Terrain::with_sources(config.clone(), None, ruleset).unwrap();
        let t = terrain.thresholds();
        let line = t.sea + config.climate.hills * (t.mountain - t.sea);
        let generated: Vec<_> = terrain.tiles().map(|h| terrain.tile_info(h).unwrap()).collect();
        let mut editor = Editor::from_terrain(terrain.clone());
        for on in [true, false] {
            for tile in terrain.tiles().step_by(5) {
                editor.apply(Stroke { tool: Tool::SetHills(on), brush: Brush::Range(1), tile }).unwrap();
            }
            let now = editor.terrain();
            for (tile, before) in terrain.tiles().zip(&generated) {
                let info = now.tile_info(tile).unwrap();
                let raw = now.pipeline().tile_sample(tile).raw;
                // Every land tile the strokes covered is on the landform asked; the rest as before.
                let covered = terrain.tiles().step_by(5).any(|s| terrain.distance(s, tile) <= Some(1));
                if before.kind != TileKind::Land || !covered {
                    continue;
                }
                assert_eq!(info.kind, TileKind::Land, "{tile:?}");
                assert_eq!(raw >= line, on, "{tile:?}: raw {raw} against the line {line}");
                let want = if on { Landform::Hills } else { Landform::Flat };
                if info.lake.is_none() {
                    assert_eq!(info.terrain.landform, want, "{tile:?}");
                }
                let r = now.ruleset();
                assert_eq!(
                    info.terrain.traits,
                    r.traits(info.terrain.terrain, info.terrain.landform, info.terrain.feature)
                );
                if own && on && r.terrain(info.terrain.terrain).id == "grassland" && info.terrain.feature.is_none() {
                    assert_eq!(info.terrain.traits.movement, 2, "grassland hills");
                }
                if !own && on && info.lake.is_none() {
                    let biome = r.biome(info.terrain.terrain).unwrap();
                    assert!(
                        matches!(
                            biome,
                            hex_terrain::Biome::Hills | hex_terrain::Biome::Snow | hex_terrain::Biome::Tundra
                        ),
                        "{tile:?}: {biome:?} on hills"
                    );
                }
            }
            // Sea and mountains stay as they were.
            for (tile, before) in terrain.tiles().zip(&generated) {
                if before.kind != TileKind::Land {
                    assert_eq!(now.tile_info(tile).unwrap().kind, before.kind, "{tile:?}");
                }
            }
        }
        while editor.undo().is_some() {}
        let back: Vec<_> = terrain.tiles().map(|h| editor.terrain().tile_info(h).unwrap()).collect();
        assert_eq!(back, generated);
        // Without a hills line: refused by name.
        let flat = hex_terrain::MapConfig {
            climate: hex_terrain::ClimateConfig { hills: 1.0, ..config.climate.clone() },
            ..config
        };
        let mut editor =
            Editor::from_terrain(hex_terrain::Terrain::with_sources(flat, None, Some(civ.clone())).unwrap());
        let tile = terrain.tiles().next().unwrap();
        let e = editor.apply(Stroke { tool: Tool::SetHills(true), brush: Brush::Range(0), tile }).unwrap_err();
        assert!(matches!(e, EditError::Unsupported { tool: "SetHills", .. }), "{e}");
        assert!(e.to_string().contains("climate.hills"), "{e}");
    }
}
