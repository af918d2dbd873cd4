//! Props: where trees, rocks and reeds stand on a chunk (and the game setup's markers:
//! starts, resources, wonders), decided tile by tile from a hash of
//! the tile, so the same map always has the same props, whichever chunk, thread or order
//! generates them, and a tile's props never depend on its neighbors' chunks.
//!
//! - **Trees** on wooded tiles: the forest and rainforest biomes (dense), hills and tundra
//!   (sparse); on a map without a climate, on a band of land elevation (the middle of the land
//!   range) on about half its tiles. Pines on high or cold ground, broadleaf trees elsewhere.
//! - **Rocks** on mountain tiles (and rock and snow peak biomes), a few each.
//! - **Reeds** on about half the open land tiles (no trees) next to the sea, near the tile's
//!   edge.
//!
//! - On a map with its own terrain ruleset ([`MapConfig::ruleset`](crate::MapConfig::ruleset)):
//!   what the look of the tile's feature (else its terrain) grows (`Look::props`: the kind, a
//!   count, a size, the share of its tiles that have them), nothing at sea or on a lake.
//!
//! A density set by hand on a tile ([`TileEdit::props`](crate::TileEdit::props)) replaces its
//! biome's rule: none, a few or a wood of trees on land, rocks on a mountain, nothing at sea.
//!
//! Each prop stands on the meshed surface (its chunk's vertices, interpolated like
//! [`surface_height`]) at a point drawn inside
//! its tile; points under the sea, in a river channel or on a lake are skipped. A chunk keeps at
//! most `max_per_chunk` props: over the cap, those with the lowest hash priority stay, so the
//! thinning is as deterministic as the placement.

use hexx::Hex;

use crate::config::{PropDensity, ResourceClass};
use crate::hash;
use crate::info::TileInfo;
use crate::kind::Thresholds;
use crate::mesh::coarse::fan_border;
use crate::mesh::{ChunkMesh, Detail};
use crate::pipeline::Pipeline;
use crate::query::surface_height;
use crate::vocab::{Biome, TileKind};
pub use crate::vocab::{PROP_VARIANTS, PropKind};

/// One prop of a chunk.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Prop {
    /// What it is.
    pub kind: PropKind,
    /// Which of the kind's meshes, below [`PROP_VARIANTS`].
    pub variant: u8,
    /// Position of its foot, relative to the chunk's origin ([`ChunkMesh::origin`]) like the
    /// chunk's mesh: on the surface.
    pub position: [f32; 3],
    /// Rotation about the vertical axis, radians.
    pub yaw: f32,
    /// Size, in hex radii (a mesh of unit size is scaled by this times the hex size).
    pub scale: f32,
    /// The tile it stands on (map-local axial coordinate).
    pub tile: Hex,
}

/// What a tile grows: the kind, how many, and their size in hex radii (a density set by hand
/// first).
fn rule(pipeline: &Pipeline, info: &TileInfo, h: u64) -> Option<(PropKind, u32, f32)> {
    let land = land_share(info.elevation, pipeline.max_elevation(), pipeline.thresholds());
    let pick = hash::unit(h);
    let extra = (h >> 8) as u32 % 3;
    let geometry = pipeline.geometry();
    if let Some(density) = pipeline.heights().edits().and_then(|e| e.props(geometry, info.hex)) {
        return hand_rule(density, info.kind, land, h);
    }
    // Under the map's own terrain ruleset: what its feature (else its terrain) grows, on the
    // share of tiles its `chance` says, a variety of one to three more.
    if pipeline.has_own_ruleset() {
        if info.kind == TileKind::Sea || info.lake.is_some() {
            return None;
        }
        let t = info.terrain;
        let ruleset = pipeline.ruleset();
        let look = t.feature.map_or(&ruleset.terrain(t.terrain).look, |f| &ruleset.feature(f).look);
        return look.props.filter(|p| pick < p.chance).map(|p| (p.kind, u32::from(p.count) + extra % 2, p.size));
    }
    // The default ruleset's terrain `i` is biome `i`.
    let biome = Biome::ALL[usize::from(info.terrain.terrain.0)];
    let coastal =
        || geometry.wrapped_neighbors(info.hex).iter().any(|&n| pipeline.map_tile_kind(n) == Some(TileKind::Sea));
    biome_rule(info.kind, biome, land, h, pipeline.climate().is_enabled(), coastal)
}

/// What a tile whose prop density is set by hand grows (a flat map's or a globe's): none, a few
/// or a wood of trees on land (pines on high ground), rocks on a mountain, nothing at sea.
pub(crate) fn hand_rule(density: PropDensity, kind: TileKind, land: f32, h: u64) -> Option<(PropKind, u32, f32)> {
    let extra = (h >> 8) as u32 % 3;
    let tree = if land > 0.62 { PropKind::Pine } else { PropKind::Broadleaf };
    match (density, kind) {
        (PropDensity::None, _) | (_, TileKind::Sea) => None,
        (PropDensity::Sparse, TileKind::Mountain) => Some((PropKind::Rock, 1, 0.2)),
        (PropDensity::Dense, TileKind::Mountain) => Some((PropKind::Rock, 4 + extra, 0.2)),
        (PropDensity::Sparse, TileKind::Land) => Some((tree, 2 + extra % 2, 0.28)),
        (PropDensity::Dense, TileKind::Land) => Some((tree, 7 + extra, 0.3)),
    }
}

/// Where a tile's center elevation lies in the land range: 0 at the sea threshold, 1 at the
/// mountains'.
pub(crate) fn land_share(elevation: f32, max_elevation: f32, t: &Thresholds) -> f32 {
    let max = max_elevation.max(f32::MIN_POSITIVE);
    ((elevation / max - t.sea) / (t.mountain - t.sea).max(f32::EPSILON)).clamp(0.0, 1.0)
}

/// What a tile of the 13 biomes grows (a flat map's or a globe's): rocks on mountains, trees by
/// biome (pines on high ground, at `land` past 0.62 of the land range), on a map without a
/// climate a band of trees in the middle of the land range, and reeds on half the open land
/// tiles by the sea (`coastal`, asked only then). `h` is the tile's hash.
pub(crate) fn biome_rule(
    kind: TileKind,
    biome: Biome,
    land: f32,
    h: u64,
    climate: bool,
    coastal: impl FnOnce() -> bool,
) -> Option<(PropKind, u32, f32)> {
    let pick = hash::unit(h);
    let extra = (h >> 8) as u32 % 3;
    let tree = if land > 0.62 { PropKind::Pine } else { PropKind::Broadleaf };
    let grows = match (kind, biome) {
        (TileKind::Sea, _) | (_, Biome::Ocean | Biome::Lake | Biome::Desert | Biome::Snow) => None,
        (TileKind::Mountain, _) | (_, Biome::Rock | Biome::SnowPeak) => Some((PropKind::Rock, 1 + extra, 0.2)),
        (_, Biome::Forest) => Some((tree, 5 + extra, 0.3)),
        (_, Biome::Rainforest) => Some((PropKind::Broadleaf, 7 + extra, 0.32)),
        (_, Biome::Tundra) => (pick < 0.5).then_some((PropKind::Pine, 1 + extra, 0.24)),
        (_, Biome::Hills) => (pick < 0.6).then_some((tree, 2 + extra, 0.27)),
        (_, Biome::Grassland) if !climate => {
            ((0.25..0.75).contains(&land) && pick < 0.5).then_some((tree, 4 + extra, 0.3))
        }
        _ => None,
    };
    if grows.is_some() || kind != TileKind::Land || pick < 0.5 {
        return grows;
    }
    coastal().then_some((PropKind::Reed, 2 + extra, 0.16))
}

/// Keeps the `max` items of the lowest priority (ties by index), in their order.
pub(crate) fn keep_first<T>(items: &mut Vec<T>, priority: &[f32], max: usize) {
    if items.len() <= max {
        return;
    }
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| priority[a].total_cmp(&priority[b]).then(a.cmp(&b)));
    let mut keep = vec![false; items.len()];
    for &i in &order[..max] {
        keep[i] = true;
    }
    let mut k = keep.iter();
    items.retain(|_| k.next().copied().unwrap_or(false));
}

/// The props of a generated chunk (see the module docs), at most `max_per_chunk`, with
/// `density` (in `[0, 1]`, clamped) the share of each tile's props that stand, on the surface
/// drawn at `detail` (`chunk` is the full mesh whatever the detail).
#[must_use]
pub fn props(pipeline: &Pipeline, chunk: &ChunkMesh, max_per_chunk: usize, density: f32, detail: Detail) -> Vec<Prop> {
    let density = if density.is_finite() { density.clamp(0.0, 1.0) } else { 0.0 };
    let mut props = Vec::new();
    let mut priority = Vec::new();
    if max_per_chunk == 0 || density == 0.0 {
        return props;
    }
    let geometry = pipeline.geometry();
    let origin = geometry.rect_origin(chunk.rect);
    let lattice = geometry.lattice();
    let size = geometry.hex_size();
    let sea = f64::from(pipeline.sea_level());
    let seed = pipeline.config().seed;
    let surface = ChunkSurface::new(chunk);
    for (info, offset) in chunk.tiles.iter().zip(chunk.rect.iter()) {
        if !info.in_map || info.lake.is_some() {
            continue;
        }
        let tile = geometry.tile_from_offset(offset);
        let key = geometry.wrap_tile(tile);
        let h = hash::hash(seed, &[i64::from(key.x), i64::from(key.y), 0x9e0]);
        let Some((kind, count, scale)) = rule(pipeline, info, h) else { continue };
        let center = lattice.tile_center(tile);
        let [cx, cz] = lattice.world(center);
        let [lx, lz] = lattice.world(center - origin);
        // Whether any water runs on the tile: asked once a tile, not once a prop.
        let wet = pipeline.tile_is_wet(tile);
        // The tile's coarse fan, once a tile.
        let fan = if detail == Detail::Coarse { fan_border(geometry, chunk.rect, tile) } else { Vec::new() };
        for i in 0..count {
            let r = hash::hash(seed, &[i64::from(key.x), i64::from(key.y), i64::from(i)]);
            let u = |k: u32| f64::from(hash::unit(hash::hash(seed, &[r as i64, i64::from(k)])));
            if u(0) >= f64::from(density) {
                continue;
            }
            // Inside the tile's inscribed circle (reeds in its outer band, near the shore).
            let (inner, outer) = if kind == PropKind::Reed { (0.55, 0.82) } else { (0.0, 0.78) };
            let radius = size * 0.866 * (inner + (outer - inner) * u(1).sqrt());
            let angle = std::f64::consts::TAU * u(2);
            let (dx, dz) = (radius * angle.cos(), radius * angle.sin());
            let (x, z) = (cx + dx, cz + dz);
            if wet && is_wet_at(pipeline, tile, x, z) {
                continue;
            }
            // Which props stand is decided on the full surface, whatever the detail.
            let Some(y) = surface.height(pipeline, origin, x, z) else { continue };
            if y <= sea + 0.02 * size {
                continue;
            }
            let y = match detail {
                Detail::Full => y,
                Detail::Coarse => surface.fan_height(pipeline, origin, tile, &fan, x, z).unwrap_or(y),
            };
            props.push(Prop {
                kind,
                variant: (u(3) * f64::from(PROP_VARIANTS)) as u8 % PROP_VARIANTS,
                position: [(lx + dx) as f32, y as f32, (lz + dz) as f32],
                yaw: (std::f64::consts::TAU * u(4)) as f32,
                scale: scale * (0.75 + 0.5 * u(5) as f32),
                tile: key,
            });
            priority.push(hash::unit(r));
        }
    }
    keep_first(&mut props, &priority, max_per_chunk);
    props
}

/// A chunk's meshed surface: the height of each vertex by its position in the chunk, so a prop's
/// height comes from the chunk's own buffers instead of the vertex chain run again for the
/// corners of its lattice triangle.
struct ChunkSurface {
    /// `(position key, height)` of every vertex, by key.
    vertices: Vec<(u64, f32)>,
}

impl ChunkSurface {
    fn new(chunk: &ChunkMesh) -> Self {
        let mut vertices: Vec<(u64, f32)> =
            chunk.buffers.positions.iter().map(|&[x, y, z]| (Self::key(x, z), y)).collect();
        vertices.sort_unstable_by_key(|v| v.0);
        Self { vertices }
    }

    /// A vertex's key: its position's bits, as the mesh computes it (`x` and `z` of the lattice
    /// point less the chunk's origin, in f32).
    fn key(x: f32, z: f32) -> u64 {
        (u64::from(x.to_bits()) << 32) | u64::from(z.to_bits())
    }

    /// The height of the chunk's vertex at lattice point `p`, if the chunk has it.
    fn vertex(&self, pipeline: &Pipeline, origin: Hex, p: Hex) -> Option<f32> {
        let [lx, lz] = pipeline.geometry().lattice().world(p - origin);
        let key = Self::key(lx as f32, lz as f32);
        self.vertices.binary_search_by_key(&key, |v| v.0).ok().map(|i| self.vertices[i].1)
    }

    /// The surface height at world `(x, z)` inside the chunk: the lattice triangle's corners'
    /// heights from the buffers, interpolated (the vertex chain for a corner the chunk lacks).
    fn height(&self, pipeline: &Pipeline, origin: Hex, x: f64, z: f64) -> Option<f64> {
        let (tri, w) = pipeline.geometry().lattice().triangle_at(x, z);
        let mut y = 0.0;
        for (&p, w) in tri.iter().zip(w) {
            let Some(h) = self.vertex(pipeline, origin, p) else { return surface_height(pipeline, x, z) };
            y += w * f64::from(h);
        }
        Some(y)
    }

    /// The height at world `(x, z)` of `tile`'s coarse fan ([`Detail::Coarse`]): the fan
    /// triangle under the point, its corners' heights from the buffers (the coarse mesh's
    /// vertices are the full mesh's), interpolated. `None` off the fan.
    /// `border` is the tile's [`fan_border`].
    fn fan_height(&self, pipeline: &Pipeline, origin: Hex, tile: Hex, border: &[Hex], x: f64, z: f64) -> Option<f64> {
        let lattice = pipeline.geometry().lattice();
        let center = lattice.tile_center(tile);
        let at = |p: Hex| lattice.world(p);
        let [cx, cz] = at(center);
        for k in 0..border.len() {
            let (a, b) = (border[k], border[(k + 1) % border.len()]);
            let ([ax, az], [bx, bz]) = (at(a), at(b));
            // Barycentric weights of (x, z) in the triangle (center, a, b).
            let det = (ax - cx) * (bz - cz) - (bx - cx) * (az - cz);
            if det == 0.0 {
                continue;
            }
            let wa = ((x - cx) * (bz - cz) - (bx - cx) * (z - cz)) / det;
            let wb = ((ax - cx) * (z - cz) - (x - cx) * (az - cz)) / det;
            let wc = 1.0 - wa - wb;
            let eps = -1e-9;
            if wa < eps || wb < eps || wc < eps {
                continue;
            }
            let h = |p: Hex| self.vertex(pipeline, origin, p).map(f64::from);
            return Some(wc * h(center)? + wa * h(a)? + wb * h(b)?);
        }
        None
    }
}

/// Whether river or lake water covers world `(x, z)` of a wet `tile` (the lattice triangle's
/// corners' water cover).
fn is_wet_at(pipeline: &Pipeline, tile: Hex, x: f64, z: f64) -> bool {
    let (tri, _) = pipeline.geometry().lattice().triangle_at(x, z);
    tri.iter().any(|&p| pipeline.water_cover(tile, p) > 0.05)
}

/// What a setup marker shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub enum MarkerKind {
    /// A player's start (0 is the first player).
    Start(u32),
    /// A resource: its class and its rule's index in `setup.resources`.
    Resource(ResourceClass, u32),
    /// A natural wonder: its rule's index in `setup.wonders.list`.
    Wonder(u32),
}

/// A marker of the game setup on a chunk: a start, a resource or a natural wonder, at its
/// tile's center.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct Marker {
    /// What it shows.
    pub kind: MarkerKind,
    /// The tile (map-local axial, the map's own copy on a wrapping map).
    pub tile: Hex,
    /// Its foot, relative to the chunk's origin like the chunk's mesh: on the surface at the
    /// tile's center, or on the water of a sea or lake tile.
    pub position: [f32; 3],
}

/// The setup's markers on a generated chunk, in tile order; none without a setup. They come
/// from the setup placed once for the whole map, so every chunk, whichever order they are
/// generated in, shows the same markers as the whole map.
#[must_use]
pub fn markers(pipeline: &Pipeline, chunk: &ChunkMesh) -> Vec<Marker> {
    let Some(setup) = pipeline.setup() else { return Vec::new() };
    let geometry = pipeline.geometry();
    let lattice = geometry.lattice();
    let origin = geometry.rect_origin(chunk.rect);
    let sea = f64::from(pipeline.sea_level());
    let mut out = Vec::new();
    for (info, offset) in chunk.tiles.iter().zip(chunk.rect.iter()) {
        if !info.in_map {
            continue;
        }
        let tile = geometry.tile_from_offset(offset);
        let Some(at) = setup.at(geometry, tile) else { continue };
        let kind = match (at.start, at.resource, at.wonder) {
            (Some(p), _, _) => MarkerKind::Start(p),
            (_, _, Some(w)) => MarkerKind::Wonder(w.rule),
            (_, Some(r), _) => MarkerKind::Resource(r.class, r.rule),
            _ => continue,
        };
        let center = lattice.tile_center(tile);
        let [x, z] = lattice.world(center);
        let [lx, lz] = lattice.world(center - origin);
        let ground = surface_height(pipeline, x, z).unwrap_or(sea);
        let y = if info.terrain.landform.is_water() { ground.max(sea) } else { ground };
        out.push(Marker { kind, tile: geometry.wrap_tile(tile), position: [lx as f32, y as f32, lz as f32] });
    }
    out
}

/// The resource and wonder markers of a chunk as props ([`PropKind::Resource`], whose variant is
/// the resource's class, and [`PropKind::Wonder`]), so a renderer draws and fogs them as it
/// does trees; starts are left to the game (it puts its units there). The yaw comes from a hash
/// of the tile, like every prop's.
#[must_use]
pub fn marker_props(pipeline: &Pipeline, markers: &[Marker]) -> Vec<Prop> {
    let seed = pipeline.config().seed;
    markers
        .iter()
        .filter_map(|m| {
            let (kind, variant, scale) = match m.kind {
                MarkerKind::Start(_) => return None,
                MarkerKind::Resource(class, _) => (PropKind::Resource, class as u8, 0.4),
                MarkerKind::Wonder(_) => (PropKind::Wonder, 0, 0.7),
            };
            let h = hash::hash(seed, &[i64::from(m.tile.x), i64::from(m.tile.y), 0x3a4]);
            let yaw = (std::f64::consts::TAU * f64::from(hash::unit(h))) as f32;
            Some(Prop { kind, variant, position: m.position, yaw, scale, tile: m.tile })
        })
        .collect()
}
