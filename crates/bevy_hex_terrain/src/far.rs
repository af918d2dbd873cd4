//! Far from the origin with [`big_space`] (the `big_space` cargo feature): chunks placed in the
//! cells of a floating-origin grid, agents streamed from their f64 position, and the shader's
//! tiles measured from the floating origin's cell, so a camera a million units out renders
//! without jitter.
//!
//! Put [`HexTerrainGrid`] on the [`Grid`] entity that holds the terrain (usually the
//! [`BigSpace`](big_space::prelude::BigSpace) root), add [`HexBigSpacePlugin`] beside
//! `BigSpaceDefaultPlugins`, and give the camera `FloatingOrigin`. Agents that are children of
//! that grid with a [`CellCoord`] stream terrain from their exact position; the queries take it
//! as [`HexMap::tile_at_f64`](crate::HexMap::tile_at_f64) and friends, from
//! [`Grid::grid_position_double`].
//!
//! Without the feature, chunk entities carry their origin in a plain `Transform`: exact while an
//! f32 holds the origin to a fraction of a lattice step. At 10⁵ world units an f32 is good to
//! 0.008 units (3% of a lattice step of the default 1-unit hexes with one inner ring); at 10⁶,
//! to 0.06 units (a quarter of a step): use the feature beyond a few hundred thousand units.

use bevy::math::DVec3;
use bevy::prelude::*;
use big_space::prelude::{CellCoord, FloatingOrigin, Grid};
use hex_terrain::hexx::Hex;

use crate::HexTerrainSystems;
use crate::map::HexMap;
use crate::streaming::{HexChunk, HexTerrainAgent, HexWorldPosition};

/// Marks the [`Grid`] entity the terrain's chunks are placed in.
#[derive(Component, Debug, Clone, Copy, Default, Reflect)]
#[reflect(Component, Default)]
pub struct HexTerrainGrid;

/// Places chunks in the [`HexTerrainGrid`]'s cells, feeds agents' f64 positions to streaming,
/// and keeps the shader's render origin on the floating origin's cell. Add it after
/// `HexTerrainPlugins` and `BigSpaceDefaultPlugins`.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexBigSpacePlugin;

impl Plugin for HexBigSpacePlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<HexTerrainGrid>()
            .add_systems(Update, track_agents.before(HexTerrainSystems::Stream).after(HexTerrainSystems::Map))
            .add_systems(Update, place_chunks.after(HexTerrainSystems::Insert).before(HexTerrainSystems::Tiles));
        #[cfg(feature = "render")]
        app.add_systems(Update, follow_floating_origin.before(HexTerrainSystems::Render));
    }
}

/// The grid's f64 position of an entity in it.
fn position(grid: &Grid, cell: &CellCoord, transform: &Transform) -> DVec3 {
    grid.grid_position_double(cell, transform)
}

/// Queries in `big_space`'s convention: positions as a cell of a grid and a small offset in it.
impl HexMap {
    /// The tile under a position given as a cell of `grid` and an offset from its center;
    /// `None` past the world's edge.
    #[must_use]
    pub fn tile_at_cell(&self, grid: &Grid, cell: &CellCoord, offset: Vec3) -> Option<Hex> {
        self.tile_at_f64(position(grid, cell, &Transform::from_translation(offset)))
    }

    /// Height of the surface under a position given as a cell of `grid` and an offset; `None`
    /// past the world's edge.
    #[must_use]
    pub fn surface_height_at_cell(&self, grid: &Grid, cell: &CellCoord, offset: Vec3) -> Option<f64> {
        self.surface_height_f64(position(grid, cell, &Transform::from_translation(offset)))
    }

    /// The first tile a ray from a cell of `grid` (and an offset in it) hits on the surface.
    #[must_use]
    pub fn raycast_from_cell(
        &self,
        grid: &Grid,
        cell: &CellCoord,
        offset: Vec3,
        direction: Dir3,
        max_distance: f64,
    ) -> Option<crate::TileHitF64> {
        let origin = position(grid, cell, &Transform::from_translation(offset));
        self.raycast_f64(origin, direction.as_vec3().as_dvec3(), max_distance)
    }

    /// Where a tile's center on the surface lies in `grid`: its cell and the offset in it (where
    /// a unit standing on the tile goes); `None` for a tile past the world's edge.
    #[must_use]
    pub fn tile_center_in_grid(&self, grid: &Grid, tile: Hex) -> Option<(CellCoord, Vec3)> {
        self.tile_center_f64(tile).map(|center| grid.translation_to_grid(center))
    }
}

/// What streaming reads the f64 position of: agents (where terrain streams) and, with a
/// renderer, cameras (what levels of detail are measured from).
#[cfg(feature = "render")]
type Tracked = Or<(With<HexTerrainAgent>, With<bevy::camera::Camera>)>;
/// What streaming reads the f64 position of: agents (where terrain streams).
#[cfg(not(feature = "render"))]
type Tracked = With<HexTerrainAgent>;

/// Agents and cameras in a grid: where they are, and the f64 position streaming last read.
type GridAgents<'w, 's> = Query<
    'w,
    's,
    (Entity, &'static ChildOf, &'static CellCoord, &'static Transform, Option<&'static HexWorldPosition>),
    Tracked,
>;

/// Chunks that changed, with their cell and parent if placed.
type ChangedChunks<'w, 's> =
    Query<'w, 's, (Entity, &'static HexChunk, Option<&'static CellCoord>, Option<&'static ChildOf>), Changed<HexChunk>>;

/// Agents in a grid stream from their f64 position; cameras in it measure levels of detail from
/// theirs.
fn track_agents(mut commands: Commands, grids: Query<&Grid>, agents: GridAgents) {
    for (entity, parent, cell, transform, known) in &agents {
        let Ok(grid) = grids.get(parent.parent()) else { continue };
        let world = HexWorldPosition(position(grid, cell, transform));
        if known != Some(&world) {
            commands.entity(entity).insert(world);
        }
    }
}

/// Chunks that changed (new, or a new mesh, whose origin a hot reload may have moved) go into the
/// grid's cell holding their origin, with a small transform inside it.
fn place_chunks(mut commands: Commands, grids: Query<(Entity, &Grid), With<HexTerrainGrid>>, chunks: ChangedChunks) {
    let Ok((grid_entity, grid)) = grids.single() else { return };
    for (entity, chunk, cell, parent) in &chunks {
        let (new_cell, local) = grid.translation_to_grid(chunk.origin);
        let mut e = commands.entity(entity);
        e.insert(Transform::from_translation(local));
        if cell != Some(&new_cell) {
            e.insert(new_cell);
        }
        if parent.is_none_or(|p| p.parent() != grid_entity) {
            e.insert(ChildOf(grid_entity));
        }
    }
}

/// The shader measures tiles from the floating origin's cell, where positions are rendered from.
#[cfg(feature = "render")]
fn follow_floating_origin(
    map: Res<HexMap>,
    grids: Query<&Grid>,
    origins: Query<(&CellCoord, &ChildOf), With<FloatingOrigin>>,
    render: Option<ResMut<crate::material::RenderOrigin>>,
) {
    // Headless (the material plugin off) there is no shader to tell.
    let Some(mut render) = render else { return };
    let Ok((cell, parent)) = origins.single() else { return };
    let Ok(grid) = grids.get(parent.parent()) else { return };
    let at = grid.cell_to_float(cell);
    // Past the world's edge there is no terrain to measure: keep the last origin.
    let Some(origin) = crate::material::RenderOrigin::at(map.terrain(), at.x, at.z) else { return };
    if *render != origin {
        *render = origin;
    }
}
