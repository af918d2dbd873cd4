//! Entities on tiles: [`OnTile`] keeps a unit, a city or a marker standing on the surface of its
//! tile, [`TileWalk`] walks it along a path over frames, and the fog of war the
//! [`TileStates`](crate::TileStates) show hides it.
//!
//! Where an entity stands is a pure function of the map and its tile: the tile's center on the
//! surface ([`HexMap::tile_center`]) plus the entity's offset, lifted by its `lift`. The center
//! is a vertex of the chunk's mesh at every level of detail, so an entity at the center stands
//! on what is drawn whether its chunk is near or far; an edit under it moves it with the new
//! surface. On a wrapping map it is drawn at the copy of its tile nearest the first
//! [`HexTerrainAgent`] (the camera), and on a `big_space` grid (the feature of that name) in the
//! grid cell of its exact position.

use bevy::math::DVec3;
use bevy::prelude::*;
use hex_terrain::hexx::Hex;

use crate::HexTerrainSystems;
use crate::map::HexMap;
use crate::streaming::{HexTerrainAgent, HexWorldPosition};
use crate::tiles::FogState;
#[cfg(feature = "render")]
use crate::tiles::TileStates;

/// Puts an entity on a tile of the map: its `Transform` is kept on the surface at the tile's
/// center (plus [`offset`](Self::offset), lifted by [`lift`](Self::lift)) through edits,
/// hot reloads and level-of-detail changes, and its `Visibility` follows the fog of war the
/// [`TileStates`](crate::TileStates) show (see [`shown_from`](Self::shown_from)). Change `tile` to move it at
/// once; add [`TileWalk`] to walk it there.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_hex_terrain::prelude::*;
///
/// fn spawn_settler(mut commands: Commands, map: Res<HexMap>) {
///     let tile = map.tile_from_offset([10, 6]);
///     // A unit: shown while its tile is in sight.
///     commands.spawn((OnTile::new(tile), Name::new("Settler")));
///     // A city: shown once its tile has been explored.
///     commands.spawn(OnTile { shown_from: FogState::Explored, ..OnTile::new(tile) });
/// }
/// # App::new().add_systems(Update, spawn_settler);
/// ```
#[derive(Component, Debug, Clone, Copy, PartialEq, Reflect)]
#[reflect(Component)]
#[cfg_attr(feature = "render", require(Transform, Visibility))]
#[cfg_attr(not(feature = "render"), require(Transform))]
pub struct OnTile {
    /// The tile (any copy of it on a wrapping map).
    pub tile: Hex,
    /// Where on the tile, from its center in world `x` and `z` (keep it inside the tile: past
    /// its edge the entity stands on its neighbor's surface). Off the center, the entity stands
    /// on the full-detail surface, which a far chunk's coarse mesh approximates.
    pub offset: Vec2,
    /// How far above the surface the entity's origin stands.
    pub lift: f32,
    /// The least the viewer must know of the tile for the entity to show: `Visible` (a unit:
    /// hidden unless its tile is in sight), `Explored` (a city: shown once seen), `Unexplored`
    /// (always shown). The plugin sets its `Visibility` to `Hidden` under the fog and back to
    /// `Inherited` when it shows, only when that changes (with the `render` feature: a
    /// headless build draws nothing).
    pub shown_from: FogState,
}

impl OnTile {
    /// An entity on a tile's center, on the surface, shown while the tile is in sight.
    #[must_use]
    pub fn new(tile: Hex) -> Self {
        Self { tile, offset: Vec2::ZERO, lift: 0.0, shown_from: FogState::Visible }
    }
}

/// Walks an [`OnTile`] entity along a path over frames: from tile to tile at `speed` world units
/// a second on the surface, [`OnTile::tile`] becoming each tile as it is reached; when the last
/// is reached the component is removed and [`WalkEnded`] is triggered on the entity. A path of
/// [`HexMap::path`] is the usual one (its first tile, the entity's own, is skipped).
#[derive(Component, Debug, Clone, PartialEq, Reflect)]
#[reflect(Component)]
pub struct TileWalk {
    /// The tiles still to walk to, in order (neighbors of each other; a tile equal to where the
    /// entity stands is skipped).
    pub path: Vec<Hex>,
    /// World units a second.
    pub speed: f32,
}

impl TileWalk {
    /// A walk along a path's tiles at `speed` world units a second.
    #[must_use]
    pub fn new(path: impl IntoIterator<Item = Hex>, speed: f32) -> Self {
        Self { path: path.into_iter().collect(), speed }
    }
}

/// An [`OnTile`] entity's [`TileWalk`] reached its last tile.
#[derive(EntityEvent, Debug, Clone, Copy, PartialEq, Reflect)]
pub struct WalkEnded {
    /// The entity.
    pub entity: Entity,
    /// The tile it stands on.
    pub tile: Hex,
}

/// Keeps [`OnTile`] entities on the surface, walks [`TileWalk`]s in
/// [`HexTerrainSystems::Place`], and hides entities under the fog in `PostUpdate`. Part of
/// `HexTerrainPlugins`.
#[derive(Debug, Clone, Copy, Default)]
pub struct HexPlacementPlugin;

impl Plugin for HexPlacementPlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<OnTile>()
            .register_type::<TileWalk>()
            .add_systems(Update, (walk, place).chain().in_set(HexTerrainSystems::Place));
        #[cfg(feature = "render")]
        app.add_systems(PostUpdate, hide_under_fog.before(bevy::transform::TransformSystems::Propagate));
    }
}

/// Where a tile's entity stands: the tile's copy nearest `focus`, on the surface under its
/// offset, lifted.
fn stand(map: &HexMap, on: &OnTile, focus: DVec3) -> Option<DVec3> {
    let center = map.tile_center_f64(on.tile)?;
    let mut at = map.wrap_near_f64(center, focus) + DVec3::new(f64::from(on.offset.x), 0.0, f64::from(on.offset.y));
    if on.offset != Vec2::ZERO {
        at.y = map.surface_height_f64(at)?;
    }
    at.y += f64::from(on.lift);
    Some(at)
}

/// The first agent's position: where the copies of a wrapping map's tiles are drawn near.
fn focus(agents: &Query<(&GlobalTransform, Option<&HexWorldPosition>), With<HexTerrainAgent>>) -> DVec3 {
    agents.iter().next().map_or(DVec3::ZERO, |(t, world)| world.map_or_else(|| t.translation().as_dvec3(), |w| w.0))
}

/// Which copy of the map a position is drawn in (0 unless the map wraps): the placements are
/// redone when the focus moves to another.
fn period(map: &HexMap, focus: DVec3) -> i64 {
    map.terrain().wrap().map_or(0, |w| (focus.x / w.width).round() as i64)
}

#[cfg(feature = "big_space")]
type Cells<'w, 's> = Query<'w, 's, &'static big_space::prelude::Grid, With<crate::HexTerrainGrid>>;
#[cfg(feature = "big_space")]
type CellOf = Option<&'static mut big_space::prelude::CellCoord>;
#[cfg(feature = "big_space")]
type CellItem<'a> = Option<Mut<'a, big_space::prelude::CellCoord>>;
#[cfg(not(feature = "big_space"))]
type Cells<'w, 's> = ();
#[cfg(not(feature = "big_space"))]
type CellOf = ();
#[cfg(not(feature = "big_space"))]
type CellItem<'a> = ();

/// Moves a transform to an f64 world position: in the terrain grid's cell of it when the
/// entity has a `big_space` cell (the feature of that name), else as an f32 translation.
#[cfg_attr(not(feature = "big_space"), expect(unused_variables))]
fn put(transform: &mut Transform, cell: &mut CellItem, grids: &Cells, at: DVec3) {
    #[cfg(feature = "big_space")]
    if let Some(cell) = cell
        && let Ok(grid) = grids.single()
    {
        let (c, offset) = grid.translation_to_grid(at);
        **cell = c;
        transform.translation = offset;
        return;
    }
    transform.translation = at.as_vec3();
}

/// Puts every [`OnTile`] entity on its tile: those whose tile changed, and all of them when the
/// map changed (an edit, a reload, another map) or the focus moved to another copy of a
/// wrapping map. Walking entities are the walk's.
#[allow(clippy::type_complexity)]
fn place(
    map: Res<HexMap>,
    agents: Query<(&GlobalTransform, Option<&HexWorldPosition>), With<HexTerrainAgent>>,
    mut entities: Query<(Ref<OnTile>, &mut Transform, CellOf), Without<TileWalk>>,
    grids: Cells,
    mut last: Local<Option<(u64, u64, i64)>>,
) {
    let focus = focus(&agents);
    let now = (map.map_id(), map.generation(), period(&map, focus));
    let all = *last != Some(now);
    *last = Some(now);
    for (on, mut transform, mut cell) in &mut entities {
        if (all || on.is_changed())
            && let Some(at) = stand(&map, &on, focus)
        {
            put(&mut transform, &mut cell, &grids, at);
        }
    }
}

/// Walks [`TileWalk`]s: toward the next tile's center (its copy nearest the entity's tile, so a
/// walk across a wrapping map's seam goes the short way), on the surface.
fn walk(
    mut commands: Commands,
    time: Res<Time>,
    map: Res<HexMap>,
    agents: Query<(&GlobalTransform, Option<&HexWorldPosition>), With<HexTerrainAgent>>,
    mut entities: Query<(Entity, &mut OnTile, &mut TileWalk, &mut Transform, CellOf)>,
    grids: Cells,
    mut positions: Local<bevy::platform::collections::HashMap<Entity, DVec3>>,
) {
    let focus = focus(&agents);
    positions.retain(|e, _| entities.contains(*e));
    for (entity, mut on, mut walk, mut transform, mut cell) in &mut entities {
        let Some(start) = stand(&map, &on, focus) else { continue };
        // The walk's own f64 position, so a long walk far from the origin keeps its precision.
        let here = *positions.entry(entity).or_insert(start);
        let mut budget = f64::from(walk.speed.max(0.0)) * time.delta_secs_f64();
        let mut at = here;
        while let Some(&next) = walk.path.first() {
            if map.wrap_tile(next) == map.wrap_tile(on.tile) || map.wrap_tile(next).is_none() {
                walk.path.remove(0);
                continue;
            }
            let near = map.tile_near(next, on.tile);
            let Some(goal) = stand(&map, &OnTile { tile: near, ..*on }, at) else {
                walk.path.clear();
                break;
            };
            let to = goal - at;
            let flat = DVec3::new(to.x, 0.0, to.z).length();
            if flat <= budget {
                budget -= flat;
                at = goal;
                on.tile = map.wrap_tile(next).unwrap_or(next);
                walk.path.remove(0);
                continue;
            }
            at += DVec3::new(to.x, 0.0, to.z) / flat.max(f64::EPSILON) * budget;
            at.y = map.surface_height_f64(at).map_or(at.y, |y| y + f64::from(on.lift));
            break;
        }
        positions.insert(entity, at);
        put(&mut transform, &mut cell, &grids, at);
        if walk.path.is_empty() {
            positions.remove(&entity);
            commands.entity(entity).remove::<TileWalk>();
            commands.trigger(WalkEnded { entity, tile: on.tile });
        }
    }
}

#[cfg(feature = "render")]
/// Hides [`OnTile`] entities whose tile the viewer knows less of than their
/// [`shown_from`](OnTile::shown_from), and shows them again, writing `Visibility` only when
/// that changes.
fn hide_under_fog(states: Res<TileStates>, mut entities: Query<(&OnTile, &mut Visibility)>) {
    for (on, mut visibility) in &mut entities {
        let shown = states.visibility(on.tile) >= on.shown_from;
        let wanted = if shown { Visibility::Inherited } else { Visibility::Hidden };
        let showing = *visibility != Visibility::Hidden;
        if showing != shown {
            *visibility = wanted;
        }
    }
}
