//! Props on a globe, property-based over random globes and checked by computations written here:
//! each prop stands where a ray from outside the globe (the core's `raycast`, over the whole
//! shell) meets the surface, on the tile it names, upright along the globe's up; chunk by chunk
//! gives the props of the whole mesh; what a tile grows follows its biome (a table of the test's
//! own), or the density set by hand; a lower density keeps a part of the props of a higher one;
//! the cap keeps that many.

use std::collections::HashMap;

use hex_terrain::{
    Biome, GlobeMesh, GlobeProp, GlobeTerrain, GlobeTile, MapConfig, MapSize, MapType, MapTypeConfig, PropKind,
    TileKind,
};
use proptest::prelude::*;

fn config(frequency: u32, inner_rings: u32, seed: u32, climate: bool, map_type: bool) -> MapConfig {
    let mut config = MapConfig { seed, size: MapSize::Globe { frequency }, chunk_size: (2, 2), ..Default::default() };
    config.terrain.inner_rings = inner_rings;
    config.climate.enabled = climate;
    if map_type && frequency >= 4 {
        config.map_type = Some(MapTypeConfig { kind: MapType::Continents, ..MapTypeConfig::default() });
    }
    config
}

/// A prop's foot from the globe's center.
fn foot(mesh: &GlobeMesh, p: &GlobeProp) -> [f64; 3] {
    [0, 1, 2].map(|k| mesh.origin[k] + f64::from(p.position[k]))
}

fn length(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Every chunk's props, with their feet from the globe's center.
fn chunked(globe: &GlobeTerrain, max: usize, density: f32) -> Vec<(GlobeProp, [f64; 3])> {
    globe
        .chunks()
        .into_iter()
        .flat_map(|c| {
            let mesh = globe.generate(c);
            globe.props(&mesh, max, density).into_iter().map(move |p| (p, foot(&mesh, &p))).collect::<Vec<_>>()
        })
        .collect()
}

/// What a tile of `biome` and `kind` may grow, written out from the module's rule: rocks on
/// mountains, rock and snow peaks; trees in forests and rainforests, on hills and tundra, and on
/// grassland without a climate; reeds on any other land tile by the sea (and on hills, tundra
/// and such grassland the hash gave no trees); nothing at sea.
fn may_grow(kind: TileKind, biome: Biome, climate: bool, coastal: bool) -> Vec<PropKind> {
    use PropKind::{Broadleaf, Pine, Reed, Rock};
    let mut kinds = match (kind, biome) {
        (TileKind::Sea, _) => return Vec::new(),
        (_, Biome::Ocean | Biome::Lake) => Vec::new(),
        (TileKind::Mountain, _) | (_, Biome::Rock | Biome::SnowPeak) => return vec![Rock],
        (_, Biome::Forest) => return vec![Pine, Broadleaf],
        (_, Biome::Rainforest) => return vec![Broadleaf],
        (_, Biome::Hills) => vec![Pine, Broadleaf],
        (_, Biome::Tundra) => vec![Pine],
        (_, Biome::Grassland) if !climate => vec![Pine, Broadleaf],
        _ => Vec::new(),
    };
    if kind == TileKind::Land && coastal && !matches!(biome, Biome::Ocean | Biome::Lake) {
        kinds.push(Reed);
    }
    kinds
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn props_stand_on_their_tiles_surface_by_their_biomes_rule(
        frequency in 2u32..9,
        inner_rings in 1u32..3,
        seed in any::<u32>(),
        climate in any::<bool>(),
        map_type in any::<bool>(),
    ) {
        let globe = GlobeTerrain::new(config(frequency, inner_rings, seed, climate, map_type)).unwrap();
        let grid = globe.grid();
        let all = chunked(&globe, usize::MAX, 1.0);
        let radius = globe.radius();
        let sea = radius + f64::from(globe.config().terrain.sea_threshold * globe.config().terrain.max_elevation);
        let mut per_tile: HashMap<GlobeTile, usize> = HashMap::new();
        for (p, at) in &all {
            let r = length(*at);
            let up = at.map(|c| c / r);
            // Upright along the globe's up, on its tile, above the sea.
            for k in 0..3 {
                prop_assert!((f64::from(p.up[k]) - up[k]).abs() < 1e-5, "{:?} up {:?} at {:?}", p.tile, p.up, up);
            }
            prop_assert_eq!(globe.tile_at(*at), Some(p.tile));
            prop_assert!(r > sea, "{:?} under the sea: {} <= {}", p.tile, r, sea);
            // On the surface: a ray from outside down the prop's up meets it there, on its tile.
            let above = radius + 2.0 * f64::from(globe.config().terrain.max_elevation) + 1.0;
            let hit = globe.raycast(up.map(|c| c * above), up.map(|c| -c), f64::MAX).unwrap();
            prop_assert_eq!(hit.tile, p.tile);
            let off = length([0, 1, 2].map(|k| hit.point[k] - at[k]));
            prop_assert!(off < 1e-4 * radius, "{:?} stands {} off the surface", p.tile, off);
            // What it is follows the tile's biome.
            let info = globe.tile_info(p.tile).unwrap();
            let biome = globe.ruleset().biome(info.terrain.terrain).unwrap();
            let coastal = grid.neighbors(p.tile).unwrap().as_slice().iter().any(|&n| globe.tile_kind(n) == Some(TileKind::Sea));
            prop_assert!(
                may_grow(info.kind, biome, climate, coastal).contains(&p.kind),
                "{:?} ({:?}, {:?}) grows {:?}", p.tile, info.kind, biome, p.kind
            );
            prop_assert!(p.variant < hex_terrain::PROP_VARIANTS);
            *per_tile.entry(p.tile).or_default() += 1;
        }
        // At most ten on a tile (seven to nine in a rainforest).
        prop_assert!(per_tile.values().all(|&n| n <= 9), "{:?}", per_tile.values().max());
        // Chunk by chunk is the whole mesh.
        let whole_mesh = globe.generate_whole();
        let whole = globe.props(&whole_mesh, usize::MAX, 1.0);
        prop_assert_eq!(whole.len(), all.len());
        let key = |p: &GlobeProp| (p.tile, p.kind, p.variant, p.yaw.to_bits(), p.scale.to_bits());
        let mut by_key: HashMap<_, [f64; 3]> = all.iter().map(|(p, at)| (key(p), *at)).collect();
        for p in &whole {
            let at = by_key.remove(&key(p));
            prop_assert!(at.is_some(), "{:?} of the whole mesh not in its chunk", p.tile);
            let off = length([0, 1, 2].map(|k| at.unwrap()[k] - foot(&whole_mesh, p)[k]));
            prop_assert!(off < 1e-4 * radius, "{:?}: chunk and whole {} apart", p.tile, off);
        }
        // Densities nest; the cap keeps its count from the chunk's props; the same twice.
        let half = chunked(&globe, usize::MAX, 0.5);
        prop_assert!(half.len() <= all.len());
        let full: std::collections::HashSet<_> = all.iter().map(|(p, _)| key(p)).collect();
        prop_assert!(half.iter().all(|(p, _)| full.contains(&key(p))), "a prop of density 0.5 not at 1");
        prop_assert!(chunked(&globe, usize::MAX, 0.0).is_empty() && chunked(&globe, 0, 1.0).is_empty());
        for chunk in globe.chunks().into_iter().take(4) {
            let mesh = globe.generate(chunk);
            let every = globe.props(&mesh, usize::MAX, 1.0);
            let capped = globe.props(&mesh, 3, 1.0);
            prop_assert_eq!(capped.len(), every.len().min(3));
            prop_assert!(capped.iter().all(|p| every.contains(p)));
            prop_assert_eq!(globe.props(&mesh, usize::MAX, 1.0), every);
            prop_assert!(globe.props(&mesh, usize::MAX, f32::NAN).is_empty());
        }
    }
}

/// A globe with a climate grows forests, rocks and reeds.
#[test]
fn a_globe_with_a_climate_grows_every_kind() {
    let globe = GlobeTerrain::new(config(8, 1, 7, true, true)).unwrap();
    let all = chunked(&globe, usize::MAX, 1.0);
    for kind in [PropKind::Pine, PropKind::Broadleaf, PropKind::Rock, PropKind::Reed] {
        assert!(all.iter().any(|(p, _)| p.kind == kind), "no {kind:?} among {} props", all.len());
    }
}

/// A density set by hand replaces the biome's rule: a wood (seven to nine trees) or a few trees
/// on land, a few rocks or one on a mountain, nothing at sea or with `None`.
#[test]
fn densities_set_by_hand_replace_the_rule() {
    use hex_terrain::{PropDensity, TileEdit};
    let base = config(8, 2, 3, true, true);
    let globe = GlobeTerrain::new(base.clone()).unwrap();
    let of_kind = |kind: TileKind| -> Vec<GlobeTile> {
        globe.grid().tiles().filter(|&t| globe.tile_kind(t) == Some(kind)).step_by(7).take(6).collect()
    };
    let (land, mountains, sea) = (of_kind(TileKind::Land), of_kind(TileKind::Mountain), of_kind(TileKind::Sea));
    assert!(land.len() == 6 && !mountains.is_empty() && sea.len() == 6);
    let mut edits = Vec::new();
    let set = |edits: &mut Vec<TileEdit>, tiles: &[GlobeTile], density| {
        edits.extend(tiles.iter().map(|t| TileEdit { props: Some(density), ..TileEdit::at((t.0 as i32, 0)) }));
    };
    set(&mut edits, &land[..3], PropDensity::Dense);
    set(&mut edits, &land[3..], PropDensity::None);
    set(&mut edits, &mountains, PropDensity::Sparse);
    set(&mut edits, &sea, PropDensity::Dense);
    let edited = GlobeTerrain::new(MapConfig { edits, ..base }).unwrap();
    let props = chunked(&edited, usize::MAX, 1.0);
    let on = |t: GlobeTile| props.iter().filter(|(p, _)| p.tile == t).map(|(p, _)| p.kind).collect::<Vec<_>>();
    for &t in &land[..3] {
        let kinds = on(t);
        assert!((7..=9).contains(&kinds.len()), "{t:?}: {kinds:?}");
        assert!(kinds.iter().all(|k| matches!(k, PropKind::Pine | PropKind::Broadleaf)), "{t:?}: {kinds:?}");
    }
    for &t in land[3..].iter().chain(&sea) {
        assert!(on(t).is_empty(), "{t:?}: {:?}", on(t));
    }
    for &t in &mountains {
        assert!(on(t).len() <= 1 && on(t).iter().all(|&k| k == PropKind::Rock), "{t:?}: {:?}", on(t));
    }
}
