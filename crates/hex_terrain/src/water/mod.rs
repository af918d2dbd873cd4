//! Water: the network of rivers and lakes of a bounded map ([`hydrology`], built once with the
//! per-map tile table; rivers on tile edges in [`edges`]), the cover of river channels and lakes on each lattice point
//! ([`channels`], which the vertex chain carves by), and the water surface over a generated
//! chunk ([`surface`]).

pub mod channels;
mod corners;
mod descent;
pub mod edges;
pub mod hydrology;
mod sources;
pub mod surface;

pub use edges::{EdgeRivers, RiverEdge};
pub use hydrology::{Hydrology, RiverTile};
pub use surface::{WaterBuffers, water_surface};

/// Steps from each member of a river network to its mouth, itself counted (0 for the others):
/// walked down from each member until one already measured or the mouth (`next` is `None`). A
/// course coming back on itself (rivers never rise, so none does) stops where it closes.
pub(crate) fn steps_to_mouth(
    len: usize,
    members: impl Iterator<Item = usize>,
    next: impl Fn(usize) -> Option<usize>,
) -> Vec<u32> {
    let mut to_mouth = vec![0u32; len];
    let mut on_walk = vec![false; len];
    let mut walk = Vec::new();
    for start in members {
        let mut at = Some(start);
        while let Some(c) = at.filter(|&c| to_mouth[c] == 0 && !on_walk[c]) {
            on_walk[c] = true;
            walk.push(c);
            at = next(c);
        }
        let mut length = at.map_or(0, |c| to_mouth[c]);
        while let Some(c) = walk.pop() {
            on_walk[c] = false;
            length += 1;
            to_mouth[c] = length;
        }
    }
    to_mouth
}
