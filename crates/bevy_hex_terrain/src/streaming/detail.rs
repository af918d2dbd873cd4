//! Level of detail: which level ([`Detail`]) a chunk is drawn at, from its distance to the
//! nearest viewer (the cameras, or the agents without a camera). A pure function of the terrain,
//! the settings, the viewers and the level a chunk shows now, tested without an `App`.

use std::sync::Arc;

use bevy::ecs::system::SystemParam;
use bevy::math::DVec3;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use hex_terrain::{ChunkCoord, Detail, Terrain};

use super::HexStreamingSettings;

/// A chunk showing one level keeps it while its distance is within this share of
/// [`HexStreamingSettings::coarse_distance`] of the threshold on the other side: it turns coarse
/// beyond the threshold and full again only nearer than `(1 - DETAIL_HYSTERESIS)` of it, so a
/// camera resting near the threshold does not make chunks switch back and forth.
pub const DETAIL_HYSTERESIS: f64 = 0.1;

/// The box a chunk's mesh lies in, in world coordinates: `(min, max)`, its height from zero to
/// the map's highest elevation. `None` for a chunk outside the map.
#[must_use]
pub fn chunk_box(terrain: &Terrain, chunk: ChunkCoord) -> Option<(DVec3, DVec3)> {
    let rect = terrain.chunk_rect(chunk)?;
    let [ox, _, oz] = terrain.chunk_origin(chunk)?;
    let lattice = terrain.lattice();
    let origin = terrain.rect_origin(rect);
    let size = f64::from(terrain.config().layout.hex_size);
    let (mut min, mut max) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    // The corner tiles' centers, both parities of the shoved rows and columns: every tile center
    // lies within their box, every vertex within a hex radius of its center.
    let [c0, r0] = rect.min;
    let [c1, r1] = [rect.max[0] - 1, rect.max[1] - 1];
    for col in [c0, (c0 + 1).min(c1), (c1 - 1).max(c0), c1] {
        for row in [r0, (r0 + 1).min(r1), (r1 - 1).max(r0), r1] {
            let [x, z] = lattice.world(lattice.tile_center(terrain.tile_from_offset([col, row])) - origin);
            let p = DVec3::new(ox + x, 0.0, oz + z);
            min = min.min(p);
            max = max.max(p);
        }
    }
    let top = f64::from(terrain.config().terrain.max_elevation.max(0.0));
    Some((min - DVec3::new(size, 0.0, size), max + DVec3::new(size, top, size)))
}

/// The distance from `viewer` to the nearest point of the box `(min, max)`: zero inside it.
#[must_use]
pub fn box_distance(viewer: DVec3, (min, max): (DVec3, DVec3)) -> f64 {
    (min - viewer).max(viewer - max).max(DVec3::ZERO).length()
}

/// The level a chunk whose box ([`chunk_box`]) is `bounds` is drawn at: [`Detail::Coarse`] when
/// it is farther than [`HexStreamingSettings::coarse_distance`] hex sizes from every viewer,
/// [`Detail::Full`] when nearer than `1 - DETAIL_HYSTERESIS` of that, and in between the level it
/// shows (`shown`, `None` for a chunk without a mesh, which takes the level of its side of the
/// threshold). Without viewers, a threshold or a box (a chunk outside the map) it is full.
#[must_use]
pub fn chunk_detail(
    terrain: &Terrain,
    settings: &HexStreamingSettings,
    viewers: &[DVec3],
    bounds: Option<(DVec3, DVec3)>,
    shown: Option<Detail>,
) -> Detail {
    let Some(threshold) = settings.coarse_distance else { return Detail::Full };
    let Some(bounds) = bounds else { return Detail::Full };
    if viewers.is_empty() || !threshold.is_finite() {
        return Detail::Full;
    }
    let far = f64::from(threshold.max(0.0)) * f64::from(terrain.config().layout.hex_size);
    let d = viewers.iter().map(|&v| box_distance(v, bounds)).fold(f64::INFINITY, f64::min);
    match shown {
        Some(Detail::Coarse) if d >= far * (1.0 - DETAIL_HYSTERESIS) => Detail::Coarse,
        _ if d > far => Detail::Coarse,
        _ => Detail::Full,
    }
}

/// The boxes of one terrain's chunks ([`chunk_box`]), each computed once: the planner measures
/// every wanted chunk's distance every frame a viewer moves. Emptied when asked about another
/// terrain (another `Arc`: a reload, an edit), and of the chunks no longer wanted by
/// [`ChunkBoxes::keep`].
#[derive(Default)]
pub struct ChunkBoxes {
    terrain: Option<Arc<Terrain>>,
    boxes: HashMap<ChunkCoord, Option<(DVec3, DVec3)>>,
}

impl ChunkBoxes {
    /// [`chunk_detail`] of `chunk`, its box computed once per terrain.
    pub fn detail(
        &mut self,
        terrain: &Arc<Terrain>,
        settings: &HexStreamingSettings,
        viewers: &[DVec3],
        chunk: ChunkCoord,
        shown: Option<Detail>,
    ) -> Detail {
        if !self.terrain.as_ref().is_some_and(|t| Arc::ptr_eq(t, terrain)) {
            self.boxes.clear();
            self.terrain = Some(terrain.clone());
        }
        let bounds = *self.boxes.entry(chunk).or_insert_with(|| chunk_box(terrain, chunk));
        chunk_detail(terrain, settings, viewers, bounds, shown)
    }

    /// Boxes held (what the tests check the cache forgets).
    #[cfg(test)]
    #[must_use]
    pub fn held(&self) -> usize {
        self.boxes.len()
    }

    /// Forgets the boxes of chunks `wanted` does not hold, so an agent walking on does not pile
    /// them up.
    pub fn keep<V>(&mut self, wanted: &HashMap<ChunkCoord, V>) {
        if self.boxes.len() > wanted.len() {
            self.boxes.retain(|c, _| wanted.contains_key(c));
        }
    }
}

impl std::fmt::Debug for ChunkBoxes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ChunkBoxes").field("boxes", &self.boxes.len()).finish_non_exhaustive()
    }
}

/// The cameras levels of detail are measured from: every active `Camera`, at its
/// [`HexWorldPosition`](super::HexWorldPosition) when it has one, else its `GlobalTransform`.
/// Without the `render` feature there are none.
#[derive(SystemParam)]
pub(crate) struct Cameras<'w, 's> {
    #[cfg(feature = "render")]
    cameras: Query<
        'w,
        's,
        (&'static bevy::camera::Camera, &'static GlobalTransform, Option<&'static super::HexWorldPosition>),
    >,
    #[cfg(not(feature = "render"))]
    none: std::marker::PhantomData<(&'w (), &'s ())>,
}

impl Cameras<'_, '_> {
    /// The active cameras' world positions, `None` when there is none.
    pub(crate) fn positions(&self) -> Option<Vec<DVec3>> {
        #[cfg(feature = "render")]
        {
            let all: Vec<DVec3> = self
                .cameras
                .iter()
                .filter(|(camera, ..)| camera.is_active)
                .map(|(_, t, world)| world.map_or_else(|| t.translation().as_dvec3(), |w| w.0))
                .collect();
            (!all.is_empty()).then_some(all)
        }
        #[cfg(not(feature = "render"))]
        {
            let _ = self.none;
            None
        }
    }
}
