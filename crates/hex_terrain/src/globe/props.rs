//! Props on a globe: the flat map's trees, rocks and reeds by the same rule (a density set by
//! hand on the tile first, [`TileEdit::props`](crate::TileEdit::props); else the tile's kind,
//! biome and place in the land range; reeds on half the open land tiles by the sea), each at a
//! point drawn inside its tile from a hash of the seed and the tile's id, standing on the
//! chunk's meshed surface (the ray from the globe's center through the point, met on the tile's
//! own triangles), upright along the globe's up there. A tile's props depend on nothing but the
//! globe and the tile, so every chunk, thread and order gives the same; a chunk keeps at most
//! its cap, those of lowest hash priority, as on a flat map.
//!
//! The game setup's resources and natural wonders stand on their tiles as props too
//! ([`GlobeTerrain::marker_props`]: [`PropKind::Resource`], [`PropKind::Wonder`]), at the
//! tile's center, as on a flat map.

use super::project::{self, Dir, hit};
use super::{GlobeMesh, GlobeTerrain, GlobeTile};
use crate::hash;
use crate::props::{biome_rule, hand_rule, keep_first, land_share};
use crate::vocab::{PROP_VARIANTS, PropKind};

/// One prop on a globe chunk ([`GlobeTerrain::props`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "bevy_reflect", derive(bevy_reflect::Reflect))]
pub struct GlobeProp {
    /// What it is.
    pub kind: PropKind,
    /// Which of the kind's meshes, below [`PROP_VARIANTS`].
    pub variant: u8,
    /// Its foot, relative to the mesh's [`GlobeMesh::origin`] like the mesh's positions: on
    /// the surface as meshed.
    pub position: [f32; 3],
    /// The globe's up at its foot (the unit direction from the globe's center): its mesh's `y`.
    pub up: [f32; 3],
    /// Rotation about `up`, radians.
    pub yaw: f32,
    /// Size, in hex radii (a mesh of unit size is scaled by this times `layout.hex_size`).
    pub scale: f32,
    /// The tile it stands on.
    pub tile: GlobeTile,
}

impl GlobeTerrain {
    /// The props of a chunk's mesh (from [`GlobeTerrain::generate`]; see the module docs), at
    /// most `max_per_chunk`, with `density` (in `[0, 1]`, clamped; 0 for NaN) the share of each
    /// tile's props that stand. Points under the sea's surface are skipped.
    #[must_use]
    pub fn props(&self, mesh: &GlobeMesh, max_per_chunk: usize, density: f32) -> Vec<GlobeProp> {
        let density = if density.is_finite() { density.clamp(0.0, 1.0) } else { 0.0 };
        let mut props = Vec::new();
        let mut priority = Vec::new();
        if max_per_chunk == 0 || density == 0.0 {
            return props;
        }
        let b = &mesh.buffers;
        let config = self.config();
        let (seed, max_elevation) = (config.seed, config.terrain.max_elevation);
        let sea = self.radius() + f64::from(self.thresholds().sea * max_elevation);
        let origin = mesh.origin;
        // The ray's start, the globe's center, from the mesh's origin.
        let from = origin.map(|c| -c);
        let corner = |v: u32| b.positions[v as usize].map(f64::from);
        for (tile, triangles) in tile_triangles(mesh) {
            let Some(info) = self.tile_info(tile) else { continue };
            let h = hash::hash(seed, &[i64::from(tile.0), 0, 0x9e0]);
            let land = land_share(info.elevation, max_elevation, self.thresholds());
            let biome = self.tile_biome(tile).expect("a tile of the globe");
            let coastal = || {
                let neighbors = self.grid().neighbors(tile).expect("a tile of the globe");
                neighbors.as_slice().iter().any(|&n| self.tile_kind(n) == Some(crate::TileKind::Sea))
            };
            let grows = match self.tile_props(tile) {
                Some(density) => hand_rule(density, info.kind, land, h),
                None => biome_rule(info.kind, biome, land, h, config.climate.enabled, coastal),
            };
            let Some((kind, count, scale)) = grows else { continue };
            let (center, reach) = self.tile_disk(tile);
            // Two unit vectors across the center, from its longitude's east and north.
            let east = project::normalize(project::cross([0.0, 1.0, 0.0], center));
            let east = if east.iter().all(|c| c.is_finite()) { east } else { [1.0, 0.0, 0.0] };
            let north = project::cross(center, east);
            for i in 0..count {
                let r = hash::hash(seed, &[i64::from(tile.0), 0, i64::from(i)]);
                let u = |k: u32| f64::from(hash::unit(hash::hash(seed, &[r as i64, i64::from(k)])));
                if u(0) >= f64::from(density) {
                    continue;
                }
                let (inner, outer) = if kind == PropKind::Reed { (0.55, 0.82) } else { (0.0, 0.78) };
                let angle = (reach * (inner + (outer - inner) * u(1).sqrt())).tan();
                let (s, c) = (std::f64::consts::TAU * u(2)).sin_cos();
                let d = project::normalize([0, 1, 2].map(|k| center[k] + angle * (c * east[k] + s * north[k])));
                let Some(t) = triangles
                    .chunks_exact(3)
                    .find_map(|t| hit(from, d, corner(t[0]), corner(t[1]), corner(t[2])).filter(|&t| t > 0.0))
                else {
                    continue;
                };
                if t <= sea + 0.02 * f64::from(config.layout.hex_size) {
                    continue;
                }
                props.push(GlobeProp {
                    kind,
                    variant: (u(3) * f64::from(PROP_VARIANTS)) as u8 % PROP_VARIANTS,
                    position: [0, 1, 2].map(|k| (from[k] + d[k] * t) as f32),
                    up: d.map(|c| c as f32),
                    yaw: (std::f64::consts::TAU * u(4)) as f32,
                    scale: scale * (0.75 + 0.5 * u(5) as f32),
                    tile,
                });
                priority.push(hash::unit(r));
            }
        }
        keep_first(&mut props, &priority, max_per_chunk);
        props
    }

    /// The game setup's resources and natural wonders on a chunk's mesh (from
    /// [`GlobeTerrain::generate`] or [`GlobeMesh::coarse`]) as props, in tile order: each at its
    /// tile's center on the surface as meshed (on the sea's surface over water), upright, a
    /// resource as [`PropKind::Resource`] of its class's variant, a wonder as
    /// [`PropKind::Wonder`], their yaw from a hash of the tile. None without a setup; starts are
    /// left to the game. Never thinned by a cap: a player reads them at every zoom.
    #[must_use]
    pub fn marker_props(&self, mesh: &GlobeMesh) -> Vec<GlobeProp> {
        let Some(setup) = self.setup() else { return Vec::new() };
        let config = self.config();
        let sea = self.radius() + f64::from(self.thresholds().sea * config.terrain.max_elevation);
        let b = &mesh.buffers;
        let from = mesh.origin.map(|c| -c);
        let corner = |v: u32| b.positions[v as usize].map(f64::from);
        let mut out = Vec::new();
        for (tile, triangles) in tile_triangles(mesh) {
            let Some(at) = setup.at(tile).filter(|at| at.start.is_none()) else { continue };
            let (kind, variant, scale) = match (at.wonder, at.resource) {
                (Some(_), _) => (PropKind::Wonder, 0, 0.7),
                (None, Some(r)) => (PropKind::Resource, r.class as u8, 0.4),
                (None, None) => continue,
            };
            let d = self.grid().center(tile).expect("a tile of the globe");
            // The center is a vertex of the tile's triangles at both levels: the ray through it
            // may graze their edges, so the vertex nearest its direction answers when no
            // triangle does.
            let ground = triangles
                .chunks_exact(3)
                .find_map(|t| hit(from, d, corner(t[0]), corner(t[1]), corner(t[2])).filter(|&t| t > 0.0))
                .or_else(|| {
                    let radius = |v: u32| {
                        let p = corner(v);
                        let r = [0, 1, 2].map(|k| p[k] - from[k]);
                        project::dot(r, r).sqrt()
                    };
                    let toward =
                        |v: u32| project::dot(project::normalize([0, 1, 2].map(|k| corner(v)[k] - from[k])), d);
                    triangles.iter().copied().max_by(|&a, &b| toward(a).total_cmp(&toward(b))).map(radius)
                });
            let Some(ground) = ground else { continue };
            let t = ground.max(sea);
            let h = hash::hash(config.seed, &[i64::from(tile.0), 0, 0x3a4]);
            out.push(GlobeProp {
                kind,
                variant,
                position: [0, 1, 2].map(|k| (from[k] + d[k] * t) as f32),
                up: d.map(|c| c as f32),
                yaw: (std::f64::consts::TAU * f64::from(hash::unit(h))) as f32,
                scale,
                tile,
            });
        }
        out
    }

    /// A tile's center direction and the angle, radians, of the disk about it inside the tile:
    /// half the angle to its nearest neighbor's center.
    fn tile_disk(&self, tile: GlobeTile) -> (Dir, f64) {
        let grid = self.grid();
        let center = grid.center(tile).expect("a tile of the globe");
        let nearest = grid
            .neighbors(tile)
            .expect("a tile of the globe")
            .as_slice()
            .iter()
            .map(|&n| project::dot(center, grid.center(n).expect("a neighbor")).clamp(-1.0, 1.0).acos())
            .fold(f64::INFINITY, f64::min);
        (center, nearest / 2.0)
    }
}

/// Each tile of a mesh with its triangles' indices (a tile's triangles come one after the other).
fn tile_triangles(mesh: &GlobeMesh) -> impl Iterator<Item = (GlobeTile, &[u32])> {
    mesh.triangle_tiles.chunk_by(|a, b| a == b).scan(0, |start, run| {
        let triangles = &mesh.buffers.indices[3 * *start..3 * (*start + run.len())];
        *start += run.len();
        Some((run[0], triangles))
    })
}
