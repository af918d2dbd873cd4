//! East-west wrapping and far geometry, property-based over random wrapping configs.

use std::collections::HashMap;

use hex_terrain::hexx::Hex;
use hex_terrain::{
    ChunkCoord, GenerateOptions, MapConfig, MapSize, NoiseConfig, Orientation, RiverConfig, Shape, Terrain,
};
use proptest::prelude::*;

mod common;

prop_compose! {
    fn wrapping_config()(
        seed in any::<u32>(),
        half_columns in 2u32..14,
        rows in 2u32..12,
        pointy in any::<bool>(),
        odd in any::<bool>(),
        inner_rings in 1u32..4,
        octaves in 1u32..8,
        lacunarity in 1.5f64..3.0,
        scale in 3.0f64..80.0,
        hex_size in 0.5f32..3.0,
        chunk in (1u32..9, 1u32..9),
        shape in 0usize..4,
        climate in any::<bool>(),
        rivers in any::<bool>(),
    ) -> MapConfig {
        // Pointy maps may be any width; flat ones even.
        let columns = 2 * half_columns + u32::from(pointy && odd);
        let mut c = MapConfig {
            seed,
            size: MapSize::Bounded { x: columns, z: rows },
            wrap: true,
            noise: NoiseConfig { octaves, persistence: 0.5, lacunarity, scale },
            chunk_size: chunk,
            shape: [Shape::None, Shape::Island { a: 2.0, b: 3.0 }, Shape::Mediterranean { a: 2.0, b: 3.0 },
                Shape::Inland { min: 0.2, max: 0.9 }][shape].clone(),
            ..MapConfig::default()
        };
        c.terrain.inner_rings = inner_rings;
        c.layout.orientation = if pointy { Orientation::Pointy } else { Orientation::Flat };
        c.layout.hex_size = hex_size;
        c.climate.enabled = climate;
        if rivers {
            c.rivers = RiverConfig { enabled: true, threshold: 2.0, ..RiverConfig::default() };
        }
        // Already a valid width; the shared rules keep it so if they change.
        common::wrapping(c, true)
    }
}

/// What a renderer receives for one vertex apart from its position: height, normal, kind,
/// center distance, color.
type VertexBits = (u32, [u32; 3], u32, u32, Option<[u8; 4]>);

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]

    /// The last and first columns meet like two neighbouring chunks: every vertex of the map
    /// that is also in the map one period east or west (the seam's vertices, generated once as
    /// the east edge of the last column and once as the west edge of the first) has the same
    /// bits there; chunks placed a period east are the map's chunks one width further east.
    #[test]
    fn the_seam_is_bit_identical(config in wrapping_config()) {
        let t = Terrain::new(config).unwrap();
        let wrap = *t.wrap().expect("a wrapping map");
        let m = t.generate(t.bounds().unwrap(), GenerateOptions::DIAGNOSTICS);
        let lattice = &m.diagnostics.as_ref().unwrap().lattice;
        let index: HashMap<Hex, usize> = lattice.iter().enumerate().map(|(i, &p)| (p, i)).collect();
        let b = &m.buffers;
        let bits = |i: usize| -> VertexBits {
            (b.positions[i][1].to_bits(), b.normals[i].map(f32::to_bits), b.tile_kinds[i],
                b.center_distances[i].to_bits(), b.colors.get(i).copied())
        };
        let mut pairs = 0;
        for (i, &p) in lattice.iter().enumerate() {
            if let Some(&j) = index.get(&(p + wrap.lattice_shift)) {
                prop_assert_eq!(bits(i), bits(j), "seam vertex {:?} and {:?}", p, p + wrap.lattice_shift);
                prop_assert_eq!(t.wrap_point(p), t.wrap_point(p + wrap.lattice_shift));
                pairs += 1;
            }
        }
        // Every row of tiles meets itself across the seam.
        let rows = t.bounds().unwrap().max[1] as usize;
        prop_assert!(pairs >= rows, "{} seam vertices for {} rows", pairs, rows);

        let columns = wrap.chunk_columns();
        for chunk in t.chunks() {
            for k in [-2, -1, 1, 3] {
                let placed = ChunkCoord::new(chunk.x + k * columns, chunk.z);
                prop_assert_eq!(t.wrap_chunk(placed), (chunk, k));
                prop_assert_eq!(t.chunk_rect(placed), t.chunk_rect(chunk));
                let (a, b) = (t.chunk_origin(chunk).unwrap(), t.chunk_origin(placed).unwrap());
                prop_assert!((b[0] - a[0] - f64::from(k) * wrap.width).abs() < 1e-9 * wrap.width.abs().max(1.0));
                prop_assert_eq!(a[2], b[2]);
            }
        }
    }

    /// Every query wraps: a position one map width east is the same tile and the same surface;
    /// a ray hitting just east of the seam returns the tile on the west side; neighbors and
    /// distances cross the seam; rivers drain across it and leave the map only north or south.
    #[test]
    fn queries_and_rivers_wrap(config in wrapping_config(), fx in 0.0f64..1.0, fz in 0.0f64..1.0) {
        let t = Terrain::new(config).unwrap();
        let wrap = *t.wrap().unwrap();
        let bounds = t.bounds().unwrap();
        let (columns, rows) = (bounds.max[0], bounds.max[1]);
        let [x0, _, z0] = t.tile_center(t.tile_from_offset([0, 0])).unwrap();
        let [_, _, z1] = t.tile_center(t.tile_from_offset([0, rows - 1])).unwrap();
        let (x, z) = (x0 + fx * wrap.width, z0 + fz * (z1 - z0));
        for k in [-3.0, -1.0, 1.0, 2.0] {
            prop_assert_eq!(t.tile_at(x + k * wrap.width, z).unwrap(), t.tile_at(x, z).unwrap());
            let (h, hk) = (t.surface_height(x, z).unwrap(), t.surface_height(x + k * wrap.width, z).unwrap());
            prop_assert!((h - hk).abs() <= 1e-9 * h.abs().max(1.0), "height {} vs {}", h, hk);
        }
        let sample = t.fbm().sample(fx * 7.0, fz * 5.0);
        let unit = wrap.width / f64::from(t.config().layout.hex_size);
        prop_assert!((t.fbm().sample(fx * 7.0 + unit, fz * 5.0) - sample).abs() < 1e-9, "the noise is periodic");

        for row in 0..rows {
            let west = t.tile_from_offset([0, row]);
            let east = t.tile_from_offset([columns - 1, row]);
            let past = t.tile_from_offset([columns, row]);
            let [px, _, pz] = t.tile_center(past).unwrap();
            let top = f64::from(t.config().terrain.max_elevation) + 5.0;
            let hit = t.raycast([px, top, pz], [0.0, -1.0, 0.0], f64::MAX).expect("a ray down hits");
            prop_assert_eq!(hit.tile, west, "row {}", row);
            prop_assert_eq!(t.wrap_tile(past), Some(west));
            prop_assert!(t.contains(past));
            prop_assert!(t.neighbors(east).unwrap().contains(&Some(west)));
            prop_assert_eq!(t.distance(east, west), Some(1));
            prop_assert_eq!(t.tile_info(past).unwrap().kind, t.tile_info(west).unwrap().kind);
            prop_assert_eq!(t.tile_info(past).unwrap().terrain, t.tile_info(west).unwrap().terrain);
        }
        for river in t.rivers() {
            let in_map = |h: Hex| bounds.contains(t.offset_of(h));
            prop_assert!(in_map(river.hex));
            prop_assert!(river.upstream.iter().all(|&h| in_map(h)));
            match river.downstream {
                Some(d) => {
                    prop_assert!(in_map(d));
                    prop_assert_eq!(t.distance(river.hex, d), Some(1));
                }
                None => {
                    let row = t.offset_of(river.hex)[1];
                    prop_assert!(row == 0 || row == rows - 1, "a river leaves at row {} of {}", row, rows);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]

    /// No seam in the noise: walking east along a lattice line over two periods, the height step
    /// across the seam is no larger than the steps elsewhere (planar noise read at the canonical
    /// point would jump there).
    #[test]
    fn the_noise_joins_across_the_seam(config in wrapping_config(), row in 0i32..2) {
        let t = Terrain::new(config).unwrap();
        let wrap = *t.wrap().unwrap();
        let start = t.lattice().tile_center(t.tile_from_offset([0, row]));
        let steps = 2 * (wrap.lattice_shift.x.abs() + wrap.lattice_shift.y.abs());
        let (mut seam, mut elsewhere) = (0.0_f64, 0.0_f64);
        for k in 0..steps {
            let (p, q) = (start + Hex::new(k, 0), start + Hex::new(k + 1, 0));
            let d = (t.source_height(q).unwrap() - t.source_height(p).unwrap()).abs();
            if wrap.point_period(p) == wrap.point_period(q) { elsewhere = elsewhere.max(d) } else { seam = seam.max(d) }
        }
        prop_assert!(seam <= 2.0 * elsewhere + 1e-12, "step {} across the seam, at most {} elsewhere", seam, elsewhere);
    }
}

#[test]
fn periodic_noise_equals_planar_noise_inside_one_period_and_joins() {
    let perlin = hex_terrain::FastPerlin::new(42);
    for cells in [1_i64, 2, 7, 300] {
        for i in 0..400 {
            let x = (i as f64) * 0.173 % (cells as f64);
            let y = i as f64 * 0.37 - 20.0;
            if x < (cells - 1) as f64 {
                assert_eq!(perlin.get_periodic(x, y, cells), perlin.get(x, y), "inside the period");
            }
            let p = perlin.get_periodic(x, y, cells);
            for k in [-2.0, 1.0, 5.0] {
                assert!((perlin.get_periodic(x + k * cells as f64, y, cells) - p).abs() < 1e-9, "periodic");
            }
        }
        // Continuous across the end of the period.
        let end = cells as f64;
        let (a, b) = (perlin.get_periodic(end - 1e-7, 3.3, cells), perlin.get_periodic(0.0, 3.3, cells));
        assert!((a - b).abs() < 1e-5, "{cells} cells: {a} vs {b}");
    }
}

#[test]
fn wrapped_fbm_keeps_the_octaves_within_half_a_cell_of_the_config() {
    let config = NoiseConfig::default();
    let planar = hex_terrain::Fbm::new(1, &config);
    let width = 1.5 * 106.0;
    let wrapped = hex_terrain::Fbm::wrapped(1, &config, width);
    let cells = width * 4.0 / config.scale;
    for ((f, a), ((g, b), p)) in planar.octaves().iter().zip(wrapped.octaves().iter().zip(wrapped.periods().unwrap())) {
        assert_eq!(a, b);
        assert!((g * cells - p as f64).abs() < 1e-9, "a whole number of cells");
        assert!(((g - f) * cells).abs() <= 0.5 + 1e-9, "rounded by at most half a cell");
    }
}

#[test]
fn wrapping_configs_that_cannot_wrap_are_refused_with_the_field() {
    let base = MapConfig { size: MapSize::Bounded { x: 20, z: 10 }, wrap: true, ..MapConfig::default() };
    assert!(Terrain::new(base.clone()).is_ok());
    let cases = [
        (MapConfig { size: MapSize::Unbounded, ..base.clone() }, "wrap"),
        (MapConfig { size: MapSize::Bounded { x: 21, z: 10 }, ..base.clone() }, "size.x"),
        (MapConfig { size: MapSize::Bounded { x: 2, z: 10 }, ..base.clone() }, "size.x"),
        (MapConfig { shape: Shape::Gradient, ..base.clone() }, "shape"),
    ];
    for (config, field) in cases {
        let err = Terrain::new(config).expect_err("refused");
        assert_eq!(err.field, field, "{err}");
        assert!(!err.allowed.is_empty() && !err.value.is_empty());
    }
    let mut pointy = MapConfig { size: MapSize::Bounded { x: 21, z: 10 }, ..base };
    pointy.layout.orientation = Orientation::Pointy;
    assert!(Terrain::new(pointy).is_ok(), "pointy rows are shoved, not columns: any width wraps");
}

#[test]
fn the_civ6_presets_wrap() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/maps/civ6");
    for name in ["duel", "tiny", "small", "standard", "large", "huge"] {
        let config = MapConfig::load(dir.join(format!("{name}.map.ron"))).unwrap();
        assert!(config.wrap, "{name} wraps, as in the game");
        let t = Terrain::new(config).unwrap();
        let columns = t.bounds().unwrap().max[0];
        let a = t.tile_from_offset([columns - 1, 3]);
        assert_eq!(t.distance(a, t.tile_from_offset([0, 3])), Some(1), "{name}");
    }
}

/// Chunk-local positions: every vertex within the geometry's stated bound
/// ([`Geometry::chunk_position_error`](hex_terrain::Geometry::chunk_position_error)) of
/// its exact position, far out and at the largest chunk coordinates the config allows: the
/// bound does not grow with the distance.
#[test]
fn far_chunks_keep_exact_positions() {
    let mut config = MapConfig { size: MapSize::Unbounded, ..MapConfig::default() };
    config.terrain.inner_rings = 3;
    let t = Terrain::new(config).unwrap();
    let lattice = t.lattice();
    let step = f64::from(t.config().layout.hex_size) / f64::from(lattice.subdivisions());
    let (w, h) = t.chunk_size();
    let last = hex_terrain::config::MAX_WORLD_TILE / w.max(h) as i32 - 1;
    for chunk in [ChunkCoord::new(60_000, -60_000), ChunkCoord::new(last, -last), ChunkCoord::new(-last, last)] {
        let rect = t.chunk_rect(chunk).expect("inside the world");
        let m = t.generate(rect, GenerateOptions::DIAGNOSTICS);
        let origin = t.rect_origin(rect);
        let [ox, _, oz] = t.chunk_origin(chunk).unwrap();
        assert_eq!([ox, oz], lattice.world(origin));
        let mut worst = 0.0_f64;
        for (pos, &p) in m.buffers.positions.iter().zip(&m.diagnostics.as_ref().unwrap().lattice) {
            // Exact: the integer lattice offset in f64 (small numbers, no cancellation).
            let [x, z] = lattice.world(p - origin);
            worst = worst.max((f64::from(pos[0]) - x).hypot(f64::from(pos[2]) - z));
            assert!(pos[1].is_finite());
        }
        let bound = t.geometry().chunk_position_error();
        println!(
            "chunk {chunk:?}: worst vertex {:.2e} lattice steps from exact (bound {:.2e})",
            worst / step,
            bound / step
        );
        assert!(worst <= bound, "chunk {chunk:?}: {} lattice steps off", worst / step);
        assert!(bound <= 1e-5 * step, "the default chunks keep the 1e-5 steps README states");
        // The f64 queries find the chunk's tiles out there.
        let first = t.tile_from_offset(rect.min);
        let [x, _, z] = t.tile_center(first).unwrap();
        assert_eq!(t.tile_at(x, z).unwrap(), first);
    }
    // Past the largest chunk there is nothing (and nothing overflows).
    assert!(t.chunk_rect(ChunkCoord::new(last + 2, 0)).is_none());
    assert!(t.chunk_rect(ChunkCoord::new(i32::MAX, i32::MIN)).is_none());
}

/// Map0's parameters give thesis-like maps when wrapping: on every Civ6 size, the share of sea,
/// land and mountain tiles and the sharpness figures of eq. 7.3 stay close to the planar map's
/// (the periodic noise changes each octave's frequency by at most half a cell over the map).
#[test]
fn map0_stays_thesis_like_when_wrapping() {
    use hex_terrain::{ManipulationConfig, Sharpness, TileKind};
    for (x, z) in [(44, 26), (84, 54), (106, 66)] {
        let planar = MapConfig { size: MapSize::Bounded { x, z }, ..MapConfig::default() };
        let wrapping = MapConfig { wrap: true, ..planar.clone() };
        let measure = |config: &MapConfig| {
            let t = Terrain::new(config.clone()).unwrap();
            let raw = Terrain::new(MapConfig { manipulation: ManipulationConfig::raw(), ..config.clone() }).unwrap();
            let rect = t.bounds().unwrap();
            let m = t.generate(rect, GenerateOptions::DIAGNOSTICS);
            let r = raw.generate(rect, GenerateOptions::DIAGNOSTICS);
            let mut shares = [0.0_f64; 3];
            for info in &m.tiles {
                shares[info.kind as usize] += 1.0 / m.tiles.len() as f64;
            }
            (shares, Sharpness::measure(&r, &m, config.terrain.max_elevation))
        };
        let ((a, sa), (b, sb)) = (measure(&planar), measure(&wrapping));
        for kind in [TileKind::Sea, TileKind::Land, TileKind::Mountain] {
            let (p, w) = (a[kind as usize], b[kind as usize]);
            assert!((p - w).abs() < 0.12, "{x}x{z} {kind:?}: {p:.3} planar, {w:.3} wrapping");
        }
        let close = |p: f32, w: f32| (p - w).abs() <= 0.25 * p.abs().max(1e-6);
        assert!(
            close(sa.weighted_mesh, sb.weighted_mesh),
            "{x}x{z} eq. 7.3: {} vs {}",
            sa.weighted_mesh,
            sb.weighted_mesh
        );
        assert!(close(sa.raw_average, sb.raw_average), "{x}x{z} raw: {} vs {}", sa.raw_average, sb.raw_average);
    }
}
