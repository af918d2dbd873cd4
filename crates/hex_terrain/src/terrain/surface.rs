//! The surface methods of [`Terrain`]: the tile under a position, a tile's center on the
//! surface, the surface height and ray casts (see [`crate::query`]).

use hexx::Hex;

use super::Terrain;
use crate::query::{self, RayHit};

impl Terrain {
    /// The tile under world `(x, z)` (the map's own tile on a wrapping map, for any finite
    /// `x`); `None` past the world.
    #[must_use]
    pub fn tile_at(&self, x: f64, z: f64) -> Option<Hex> {
        self.geometry().tile_at(x, z)
    }

    /// The tile under world `(x, z)` of the plane, not wrapped: on a wrapping map, a position
    /// one map width east gives the tile one map width east. `None` past the world.
    #[must_use]
    pub fn unwrapped_tile_at(&self, x: f64, z: f64) -> Option<Hex> {
        self.geometry().unwrapped_tile_at(x, z)
    }

    /// World position of a tile's center on the surface (for a tile past a wrapping map's
    /// edge, where it is drawn there); `None` past the world.
    #[must_use]
    pub fn tile_center(&self, tile: Hex) -> Option<[f64; 3]> {
        query::tile_center(&self.pipeline, tile)
    }

    /// World height of the surface (as meshed) at world `(x, z)`; `None` past the world (see
    /// `query::surface_height`).
    #[must_use]
    pub fn surface_height(&self, x: f64, z: f64) -> Option<f64> {
        query::surface_height(&self.pipeline, x, z)
    }

    /// Upward unit normal of the surface as meshed at world `(x, z)` (see
    /// `query::surface_normal`); `None` past the world.
    #[must_use]
    pub fn surface_normal(&self, x: f64, z: f64) -> Option<[f64; 3]> {
        query::surface_normal(&self.pipeline, x, z)
    }

    /// First hit of a ray on the surface within `max_distance` (see `query::raycast`).
    #[must_use]
    pub fn raycast(&self, origin: [f64; 3], direction: [f64; 3], max_distance: f64) -> Option<RayHit> {
        query::raycast(&self.pipeline, origin, direction, max_distance)
    }
}
