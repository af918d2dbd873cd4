//! Golden fingerprints: games send a seed, not a map, so the bytes a config generates are part of
//! the public contract. Each fingerprint hashes the positions, normals and indices of a map (in
//! buffer order) and its tiles' kinds. A change to any of them is a deliberate, reviewed change:
//! update the table below in the same commit and say why. `docs/ARCHITECTURE.md` lists the float
//! operations generation relies on being the same on every platform.

use std::path::{Path, PathBuf};

use hex_terrain::{ChunkCoord, ChunkMesh, MapConfig, Terrain};

fn maps_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/maps")
}

/// FNV-1a, 64 bits: small, fixed, and the same on every platform.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
}

fn fingerprint(mesh: &ChunkMesh) -> u64 {
    let mut h = Fnv::new();
    let b = &mesh.buffers;
    for v in b.positions.iter().chain(&b.normals).flatten() {
        h.write(&v.to_bits().to_le_bytes());
    }
    for i in &b.indices {
        h.write(&i.to_le_bytes());
    }
    for t in &mesh.tiles {
        h.write(&[t.kind as u8]);
    }
    h.0
}

/// Map0 ... Map15 of the thesis, whole, then chunk (3, -2) of the unbounded continent.
const GOLDEN: [u64; 17] = [
    0x4cdf380b2120e2db,
    0x447546621bfbb82e,
    0x7b1435cb57e52582,
    0x478e19c3a5d7fe0b,
    0xe23e89ea4a782f19,
    0x1e0aa460c46a4576,
    0xef378e8f4352d7ca,
    0x380bbb2fc920395a,
    0x00046dc7aabd09bf,
    0xcc6f95555436d42e,
    0xd6fecdf26f8b0987,
    0x2ec79c0078947793,
    0x1a1c157de701a2ad,
    0xac69b73afec11a81,
    0x4821823f88f21983,
    0xcbaecc5bd08f0ebd,
    // Chunk-local positions (relative to the chunk's first tile center) since wrapping and far
    // geometry: the chunk's heights, normals and indices are the bits they were.
    0xef90c47208d2451a,
];

#[test]
fn generated_bytes_match_the_pinned_fingerprints() {
    let mut got = Vec::new();
    for i in 0..16 {
        let config = MapConfig::load(maps_dir().join(format!("thesis/map{i:02}.map.ron"))).unwrap();
        let terrain = Terrain::new(config).unwrap();
        got.push(fingerprint(&terrain.generate_map().unwrap()));
    }
    let continent = Terrain::new(MapConfig::load(maps_dir().join("continent.map.ron")).unwrap()).unwrap();
    got.push(fingerprint(&continent.generate_chunk(ChunkCoord::new(3, -2)).unwrap()));
    let table: Vec<String> = got.iter().map(|f| format!("    0x{f:016x},")).collect();
    assert_eq!(got, GOLDEN, "generated output changed; if deliberate, the new table is:\n{}", table.join("\n"));
}
