//! The generator's invariants 1-6 (docs/ARCHITECTURE.md), property-based over random valid
//! configs.

use std::collections::HashMap;

use hex_terrain::hexx::Hex;
use hex_terrain::{
    ChunkCoord, ChunkMesh, Detail, GenerateOptions, ManipulationConfig, MapConfig, MapSize, MapType, MapTypeConfig,
    NoiseConfig, Orientation, PullMode, ReliefConfig, RiverConfig, RiverModel, Shape, Terrain, TerrainConfig, Threads,
    TileKind, TileRect, WaterLevel, WindConfig, WindPattern,
};
use proptest::prelude::*;

mod common;

fn terrain_config() -> impl Strategy<Value = TerrainConfig> {
    (0.05f32..0.45, 0.1f32..0.5, 0.0f32..1.0, 1u32..4, prop_oneof![Just(0.0f32), 0.1f32..50.0]).prop_map(
        |(sea, gap, tol_frac, inner_rings, max_elevation)| {
            let mountain = (sea + gap).min(0.95);
            let max_tol = sea.min(1.0 - mountain).min((mountain - sea) / 2.0);
            TerrainConfig {
                max_elevation,
                sea_threshold: sea,
                mountain_threshold: mountain,
                interpolation_tolerance: max_tol * tol_frac * 0.99,
                inner_rings,
            }
        },
    )
}

fn noise_config() -> impl Strategy<Value = NoiseConfig> {
    (1u32..7, 0.1f64..=1.0, 1.0f64..4.0, 2.0f64..120.0)
        .prop_map(|(octaves, persistence, lacunarity, scale)| NoiseConfig { octaves, persistence, lacunarity, scale })
}

fn shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        Just(Shape::None),
        (0.5f32..5.0, 0.5f32..8.0).prop_map(|(a, b)| Shape::Island { a, b }),
        (0.5f32..5.0, 0.5f32..8.0).prop_map(|(a, b)| Shape::Mediterranean { a, b }),
        (0.0f32..0.5, 0.6f32..1.0).prop_map(|(min, max)| Shape::Inland { min, max }),
        Just(Shape::Gradient),
    ]
}

fn manipulation() -> impl Strategy<Value = ManipulationConfig> {
    (any::<bool>(), any::<bool>(), any::<bool>(), prop_oneof![Just(PullMode::Clamp), Just(PullMode::Thesis)]).prop_map(
        |(hex_unity, interpolation, edge_correction, pull)| ManipulationConfig {
            hex_unity,
            interpolation,
            edge_correction,
            pull,
        },
    )
}

prop_compose! {
    fn config()(
        seed in any::<u32>(),
        bounded in prop::option::weighted(0.8, (1u32..13, 1u32..13)),
        offset in (-50i32..50, -50i32..50),
        noise in noise_config(),
        terrain in terrain_config(),
        shape in shape(),
        manipulation in manipulation(),
        pointy in any::<bool>(),
        hex_size in 0.25f32..4.0,
        chunk_size in (1u32..7, 1u32..7),
        climate in any::<bool>(),
        wrap in any::<bool>(),
        rivers in prop::option::of((1.0f32..12.0, 0.0f32..0.05, 0.0f32..=1.0, 0.5f32..=4.0)),
        on_edges in any::<bool>(),
        relief in prop::option::of((0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0)),
        map_type in prop::option::weighted(0.25, (0usize..6, 0usize..3, 0.0f32..0.3, any::<bool>())),
        winds in prop::option::weighted(0.3, (prop::collection::vec(0.0f32..360.0, 1..4), any::<bool>(), 0.0f32..=1.0)),
    ) -> MapConfig {
        let mut c = MapConfig {
            seed,
            size: bounded.map_or(MapSize::Unbounded, |(x, z)| MapSize::Bounded { x, z }),
            offset,
            noise,
            terrain,
            shape,
            manipulation,
            chunk_size,
            ..MapConfig::default()
        };
        if c.size == MapSize::Unbounded {
            c.shape = Shape::None;
        }
        c.climate.enabled = climate;
        if let (true, Some((bands, one, shadow)), MapSize::Bounded { .. }) = (climate, winds, c.size) {
            let pattern = if one { WindPattern::One(bands[0]) } else { WindPattern::Bands(bands) };
            c.climate.winds = Some(WindConfig { pattern, rain_shadow: shadow, ..WindConfig::default() });
        }
        if let (Some((threshold, min_lake_depth, carve, width)), MapSize::Bounded { .. }) = (rivers, c.size) {
            let model = if on_edges { RiverModel::Edges } else { RiverModel::Centers };
            c.rivers = RiverConfig { enabled: true, threshold, lakes: true, min_lake_depth, carve, width, model, ..RiverConfig::default() };
        }
        if let Some((peaks, ridges, hills)) = relief {
            c.relief = ReliefConfig { peaks, ridges, hills };
        }
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        c.layout.hex_size = hex_size;
        let map_type = map_type.map(|(kind, water, mountains, ranges)| MapTypeConfig {
            kind: MapType::ALL[kind],
            water: WaterLevel::ALL[water],
            mountains,
            ranges,
        });
        typed(common::wrapping(c, wrap), map_type)
    }
}

/// `c` with a map type, made valid for it: left as it is when unbounded (map types need the
/// map's bounds), else at least [`MIN_MAP_TYPE_SIDE`](hex_terrain::MIN_MAP_TYPE_SIDE) tiles a
/// side and no shape (the type shapes the land in its place). Call it after `common::wrapping`.
#[must_use]
pub fn typed(mut c: MapConfig, map_type: Option<hex_terrain::MapTypeConfig>) -> MapConfig {
    let (Some(map_type), Some((x, z))) = (map_type, c.size.bounds()) else { return c };
    let side = hex_terrain::MIN_MAP_TYPE_SIDE;
    // The side is even: a wrapping map of flat tiles keeps an even width.
    c.size = MapSize::Bounded { x: x.max(side), z: z.max(side) };
    c.shape = Shape::None;
    c.map_type = Some(map_type);
    c
}

/// The area compared: the whole bounded map, or a 3x3-chunk window of an unbounded world.
fn area(t: &Terrain) -> TileRect {
    t.bounds().unwrap_or_else(|| {
        let (w, h) = t.chunk_size();
        TileRect::new([-(w as i32), -(h as i32)], [3 * w, 3 * h])
    })
}

fn chunks_of(t: &Terrain, rect: TileRect) -> Vec<ChunkCoord> {
    let first = ChunkCoord::of(rect.min, t.chunk_size());
    let last = ChunkCoord::of([rect.max[0] - 1, rect.max[1] - 1], t.chunk_size());
    (first.z..=last.z).flat_map(|z| (first.x..=last.x).map(move |x| ChunkCoord::new(x, z))).collect()
}

fn lattice(m: &ChunkMesh) -> &[Hex] {
    &m.diagnostics.as_ref().expect("generated with diagnostics").lattice
}

fn index(m: &ChunkMesh) -> HashMap<Hex, usize> {
    lattice(m).iter().enumerate().map(|(i, &p)| (p, i)).collect()
}

/// What a renderer receives for one vertex that does not depend on the mesh's frame, as bits:
/// height, normal, kind, center distance, color.
type VertexBits = (u32, [u32; 3], u32, u32, Option<[u8; 4]>);

fn vertex_bits(m: &ChunkMesh, i: usize) -> VertexBits {
    let b = &m.buffers;
    (
        b.positions[i][1].to_bits(),
        b.normals[i].map(f32::to_bits),
        b.tile_kinds[i],
        b.center_distances[i].to_bits(),
        b.colors.get(i).copied(),
    )
}

/// A vertex's world `(x, z)`, brought out of its mesh's frame in f64.
fn world_xz(m: &ChunkMesh, i: usize) -> [f64; 2] {
    let p = m.buffers.positions[i];
    [m.origin[0] + f64::from(p[0]), m.origin[2] + f64::from(p[2])]
}

/// The edges of a mesh that belong to one triangle only (its outline), as lattice pairs.
fn outline(m: &ChunkMesh) -> std::collections::BTreeSet<((i32, i32), (i32, i32))> {
    let l = lattice(m);
    let mut count: HashMap<(Hex, Hex), usize> = HashMap::new();
    for t in m.buffers.indices.chunks_exact(3) {
        for k in 0..3 {
            let (a, b) = (l[t[k] as usize], l[t[(k + 1) % 3] as usize]);
            let key = if (a.x, a.y) < (b.x, b.y) { (a, b) } else { (b, a) };
            *count.entry(key).or_default() += 1;
        }
    }
    count.into_iter().filter(|&(_, c)| c == 1).map(|((a, b), _)| ((a.x, a.y), (b.x, b.y))).collect()
}

/// The area of a mesh's faces seen from above.
fn ground(m: &ChunkMesh) -> f64 {
    m.buffers
        .indices
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.buffers.positions[i as usize].map(f64::from));
            ((b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2])).abs() / 2.0
        })
        .sum()
}

/// For each face of a mesh, whether it is wound counter-clockwise seen from above.
fn windings(m: &ChunkMesh) -> Vec<bool> {
    m.buffers
        .indices
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.buffers.positions[i as usize].map(f64::from));
            (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]) > 0.0
        })
        .collect()
}

/// Distance between two UVs modulo whole texture repeats.
fn uv_gap(a: [f32; 2], b: [f32; 2]) -> f64 {
    let d = |x: f32, y: f32| {
        let f = (f64::from(x) - f64::from(y)).rem_euclid(1.0);
        f.min(1.0 - f)
    };
    d(a[0], b[0]).max(d(a[1], b[1]))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Invariants 1-3: same bytes whatever the thread count and chunk order; chunks generated
    /// alone equal the whole; neighbors share bit-identical border vertices and normals.
    #[test]
    fn chunks_are_deterministic_seamless_and_equal_the_whole(config in config(), order_seed in any::<u64>()) {
        let t = Terrain::new(config).unwrap();
        let rect = area(&t);
        let whole = t.generate(rect, GenerateOptions::DIAGNOSTICS);
        let single = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let again = single.install(|| t.generate(rect, GenerateOptions::DIAGNOSTICS));
        prop_assert_eq!(&whole, &again);
        // Options change where the work runs and what is kept, never the buffers.
        let here = t.generate(rect, GenerateOptions { diagnostics: false, threads: Threads::Current });
        prop_assert_eq!(&here.buffers, &whole.buffers);
        prop_assert_eq!(&here.tiles, &whole.tiles);
        prop_assert!(here.diagnostics.is_none());

        let whole_index = index(&whole);
        let mut chunks = chunks_of(&t, rect);
        // A pseudo-random order.
        let mut s = order_seed | 1;
        for i in (1..chunks.len()).rev() {
            s ^= s << 13; s ^= s >> 7; s ^= s << 17;
            chunks.swap(i, (s % (i as u64 + 1)) as usize);
        }
        let mut seen: HashMap<Hex, VertexBits> = HashMap::new();
        let mut tiles = 0;
        // Positions are relative to each mesh's origin: in one frame, within the two meshes'
        // position errors.
        let whole_error = t.geometry().position_error(rect);
        for chunk in chunks {
            let Some(rect_c) = t.chunk_rect(chunk) else { continue };
            let m = t.generate(rect_c.intersect(&rect), GenerateOptions::DIAGNOSTICS);
            let tolerance = t.geometry().position_error(rect_c.intersect(&rect)) + whole_error;
            tiles += m.tiles.len();
            for (i, p) in lattice(&m).iter().enumerate() {
                let bits = vertex_bits(&m, i);
                let w = whole_index[p];
                prop_assert_eq!(bits, vertex_bits(&whole, w), "chunk {:?} vertex {:?} differs from the whole", chunk, p);
                let ([x, z], [wx, wz]) = (world_xz(&m, i), world_xz(&whole, w));
                prop_assert!((x - wx).hypot(z - wz) <= tolerance, "vertex {:?} at {:?} vs {:?}", p, (x, z), (wx, wz));
                prop_assert!(uv_gap(m.buffers.uvs[i], whole.buffers.uvs[w]) < 1e-4, "uv of {:?}", p);
                if let Some(prev) = seen.insert(*p, bits) {
                    prop_assert_eq!(prev, bits, "seam vertex {:?} differs between chunks", p);
                }
            }
            for info in &m.tiles {
                let w = whole.tiles.iter().find(|x| x.hex == info.hex).unwrap();
                prop_assert_eq!(w, info);
            }
        }
        prop_assert_eq!(tiles, whole.tiles.len());
        prop_assert_eq!(seen.len(), lattice(&whole).len());
    }

    /// Invariants 4-6: every non-border vertex lies in its tile type's range; counts follow the
    /// formula; nothing is NaN or infinite.
    /// Level of detail: a coarse chunk is vertices of the full chunk (every attribute the same
    /// bits, so invariants 1-4 carry over), with the full chunk's outline edge for edge (so a
    /// coarse chunk meets a full or coarse neighbor without a crack), covering the same ground
    /// (no hole, no overlap: the same area seen from above, every face up), a fan of six
    /// triangles a tile inside.
    #[test]
    fn coarse_chunks_keep_the_full_vertices_and_outline(config in config()) {
        let t = Terrain::new(config).unwrap();
        let rect = area(&t);
        for chunk in chunks_of(&t, rect).into_iter().take(4) {
            let Some(rect_c) = t.chunk_rect(chunk) else { continue };
            let full = t.generate_detail(rect_c, GenerateOptions::DIAGNOSTICS, Detail::Full);
            let coarse = t.generate_detail(rect_c, GenerateOptions::DIAGNOSTICS, Detail::Coarse);
            prop_assert_eq!(&coarse.tiles, &full.tiles);
            let full_index = index(&full);
            // Every attribute as the full mesh's, but the color: a fan's vertices have its
            // tile's own biome color (the fan's first vertex, the tile's center) and their
            // point's own water.
            let points = lattice(&coarse);
            for t in coarse.buffers.indices.chunks_exact(3) {
                for &v in &t[1..] {
                    if let (Some(own), Some(c)) = (coarse.buffers.colors.get(t[0] as usize), coarse.buffers.colors.get(v as usize)) {
                        prop_assert_eq!(&c[..3], &own[..3], "a fan vertex not in its tile's color");
                        prop_assert_eq!(c[3], full.buffers.colors[full_index[&points[v as usize]]][3]);
                    }
                }
            }
            for (i, p) in points.iter().enumerate() {
                let f = full_index[p];
                let without_color = |m: &ChunkMesh, i: usize| { let b = vertex_bits(m, i); (b.0, b.1, b.2, b.3) };
                prop_assert_eq!(without_color(&coarse, i), without_color(&full, f), "vertex {:?}", p);
                prop_assert_eq!(coarse.buffers.positions[i].map(f32::to_bits), full.buffers.positions[f].map(f32::to_bits));
                prop_assert_eq!(coarse.buffers.uvs[i].map(f32::to_bits), full.buffers.uvs[f].map(f32::to_bits));
            }
            prop_assert_eq!(outline(&coarse), outline(&full), "chunk {:?}: the outline differs", chunk);
            let (area_full, area_coarse) = (ground(&full), ground(&coarse));
            prop_assert!((area_full - area_coarse).abs() <= 1e-4 * area_full.max(1e-6), "area {} vs {}", area_coarse, area_full);
            // Every face wound as the full mesh's are (up).
            let up = windings(&full);
            prop_assert!(up.iter().all(|&w| w == up[0]));
            prop_assert!(windings(&coarse).iter().all(|&w| w == up[0]), "a coarse face points down");
            let tiles = full.tiles.len();
            let n = t.lattice().subdivisions() as usize;
            prop_assert_eq!(full.buffers.triangle_count(), 6 * n * n * tiles);
            // Six a tile, plus n - 1 more for each tile edge on the outline.
            prop_assert_eq!(coarse.buffers.triangle_count(), 6 * tiles + (n - 1) * outline(&full).len() / n);
        }
    }

    #[test]
    fn tiles_are_recognisable_counts_match_and_buffers_are_finite(config in config()) {
        let t = Terrain::new(config.clone()).unwrap();
        let rect = area(&t);
        let m = t.generate(rect, GenerateOptions::DIAGNOSTICS);
        let b = &m.buffers;
        let d = m.diagnostics.as_ref().unwrap();
        let n = t.lattice().subdivisions();

        let finite = b.positions.iter().flatten().chain(b.normals.iter().flatten()).chain(b.uvs.iter().flatten())
            .chain(b.center_distances.iter()).all(|v| v.is_finite());
        prop_assert!(finite);
        prop_assert_eq!(b.triangle_count(), rect.len() * t.lattice().triangles_per_tile());
        let tiles: std::collections::HashSet<Hex> = m.tiles.iter().map(|i| i.hex).collect();
        let boundary: usize = tiles.iter().map(|h| h.all_neighbors().iter().filter(|x| !tiles.contains(x)).count()).sum();
        prop_assert_eq!(b.vertex_count(), t.lattice().mesh_vertex_count(tiles.len(), boundary));
        // Tile by tile, each triangle is the template's about the tile's center, in order.
        let template = t.lattice().template_triangles();
        for (info, tris) in m.tiles.iter().zip(b.indices.chunks_exact(3 * template.len())) {
            let center = t.lattice().tile_center(info.hex);
            for (tri, want) in tris.chunks_exact(3).zip(template) {
                let got = [tri[0], tri[1], tri[2]].map(|i| d.lattice[i as usize]);
                prop_assert_eq!(got, want.map(|o| center + o), "a triangle of tile {:?}", info.hex);
            }
        }

        let unity = config.manipulation.hex_unity && config.manipulation.pull == PullMode::Clamp;
        let max = config.terrain.max_elevation;
        let eps = 1e-4 * max.max(1.0);
        let th = t.thresholds();
        let kinds: HashMap<Hex, TileKind> = m.tiles.iter().map(|i| (i.hex, i.kind)).collect();
        for (i, &p) in d.lattice.iter().enumerate() {
            let y = b.positions[i][1];
            let ring = u32::from(d.rings[i]);
            let set = t.lattice().tiles_at(p);
            let owners: Vec<TileKind> = set.tiles().iter().filter_map(|h| kinds.get(h).copied()).collect();
            let check = if ring < n {
                unity || ring == 0
            } else {
                // Border vertices shared only by tiles of one type are corrected into its range.
                config.manipulation.edge_correction
                    && owners.len() == set.tiles().len()
                    && owners.iter().all(|&k| k == owners[0])
            };
            if check {
                let (lo, hi) = th.range(owners[0]);
                prop_assert!(y >= lo * max - eps && y <= hi * max + eps,
                    "vertex {:?} ring {} of a {:?} tile at {} outside [{}, {}]", p, ring, owners[0], y, lo * max, hi * max);
            }
        }
    }

    /// Invariant 6: every invalid value is refused with the field named, never a panic.
    #[test]
    fn invalid_configs_are_refused_with_the_field(config in config(), which in 0usize..11, bad in prop_oneof![
        Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY), Just(-1.0), Just(0.0), Just(1e12)]) {
        let mut c = config;
        let field = match which {
            0 => { c.noise.persistence = if bad > 0.0 && bad <= 1.0 { 2.0 } else { bad }; "noise.persistence" }
            1 => { c.noise.lacunarity = if (1.0..=64.0).contains(&bad) { 0.5 } else { bad }; "noise.lacunarity" }
            2 => { c.noise.scale = if bad > 0.0 && bad <= 1e9 { -bad } else { bad }; "noise.scale" }
            3 => { c.terrain.max_elevation = if (0.0..=1e6).contains(&bad) { -1.0 } else { bad as f32 }; "terrain.max_elevation" }
            4 => { c.terrain.sea_threshold = if (0.0..=1.0).contains(&bad) { 2.0 } else { bad as f32 }; "terrain.sea_threshold" }
            5 => { c.layout.hex_size = if bad > 0.0 && bad <= 1e4 { -1.0 } else { bad as f32 }; "layout.hex_size" }
            6 => { c.noise.octaves = 0; "noise.octaves" }
            7 => { c.terrain.inner_rings = 0; "terrain.inner_rings" }
            8 => { c.relief.ridges = if (0.0..=1.0).contains(&bad) { -0.5 } else { bad as f32 }; "relief.ridges" }
            9 => match &mut c.map_type {
                Some(m) => { m.mountains = if (0.0..=0.5).contains(&bad) { 0.75 } else { bad as f32 }; "map_type.mountains" }
                None => { c.noise.octaves = 0; "noise.octaves" }
            },
            _ => { c.appearance.blend = if (0.0..=1.0).contains(&bad) { 1.5 } else { bad as f32 }; "appearance.blend" }
        };
        let err = Terrain::new(c).expect_err("invalid config accepted");
        prop_assert_eq!(err.field.as_str(), field);
    }
}
