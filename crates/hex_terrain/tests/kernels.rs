//! Every kernel gives the same map: generation's vector loops (the noise, the owned points'
//! chain, the normals, the indices) are compiled for the instruction set of the map's kernel
//! ([`Kernel`]), and every kernel this CPU runs must give the same bits in every buffer, for
//! maps that take every branch of the chain (shaping, manipulation modes, relief, river and lake
//! carving, vertex colors, edge rivers, wrapping, an unbounded map's chunks), with and without
//! diagnostics, on the pool and on the calling thread.

use std::path::{Path, PathBuf};

use hex_terrain::{ChunkCoord, ChunkMesh, GenerateOptions, Kernel, MapConfig, Terrain, TileRect};

fn maps_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/maps")
}

/// Every buffer of a mesh as bits, so that `-0.0` and `0.0` (or two NaNs) are told apart.
fn bits(mesh: &ChunkMesh) -> Vec<u32> {
    let b = &mesh.buffers;
    let mut out: Vec<u32> = b.positions.iter().chain(&b.normals).flatten().map(|v| v.to_bits()).collect();
    out.extend(b.uvs.iter().flatten().map(|v| v.to_bits()));
    out.extend(&b.tile_kinds);
    out.extend(b.center_distances.iter().map(|v| v.to_bits()));
    out.extend(b.colors.iter().map(|c| u32::from_le_bytes(*c)));
    out.extend(&b.indices);
    for t in &mesh.tiles {
        out.extend([t.kind as u32, t.elevation.to_bits(), t.river_flow.to_bits()]);
    }
    if let Some(d) = &mesh.diagnostics {
        out.extend(d.raw_heights.iter().map(|v| v.to_bits()));
        out.extend(d.moved.iter().map(|&m| u32::from(m)));
        out.extend(d.rings.iter().map(|&r| u32::from(r)));
    }
    out
}

/// The meshes a terrain gives: the whole map (or two chunks of an unbounded one) on the pool,
/// with diagnostics, and a rectangle inside it on the calling thread.
fn meshes(t: &Terrain) -> Vec<Vec<u32>> {
    match t.bounds() {
        Some(rect) => {
            let inner = TileRect { min: [rect.min[0] + 1, rect.min[1] + 2], max: [rect.max[0] - 2, rect.max[1] - 1] };
            vec![
                bits(&t.generate(rect, GenerateOptions::DIAGNOSTICS)),
                bits(&t.generate(inner, GenerateOptions::CURRENT_THREAD)),
            ]
        }
        None => [ChunkCoord::new(3, -2), ChunkCoord::new(-1, 0)]
            .into_iter()
            .map(|c| bits(&t.generate_chunk(c).expect("unbounded maps have every chunk")))
            .collect(),
    }
}

#[test]
fn every_kernel_generates_the_same_bits() {
    let files = [
        "world.map.ron",
        "island.map.ron",
        "mediterranean.map.ron",
        "continent.map.ron",
        "civ6/duel.map.ron",
        "thesis/map03.map.ron",
        "thesis/map09.map.ron",
        "types/archipelago.map.ron",
    ];
    let supported: Vec<Kernel> = Kernel::ALL.into_iter().filter(|k| k.is_supported()).collect();
    for file in files {
        let mut configs = vec![MapConfig::load(maps_dir().join(file)).unwrap()];
        // The same map with its rivers on tile edges, when it has rivers.
        if configs[0].rivers.enabled {
            let mut edges = configs[0].clone();
            edges.rivers.model = hex_terrain::RiverModel::Edges;
            configs.push(edges);
        }
        for config in configs {
            let base = Terrain::new(config).unwrap();
            let portable = meshes(&base.with_kernel(Kernel::Portable).expect("the portable kernel runs anywhere"));
            for &kernel in &supported {
                let got = meshes(&base.with_kernel(kernel).unwrap());
                assert!(got == portable, "{file}: {kernel:?} differs from the portable loops");
            }
        }
    }
}
