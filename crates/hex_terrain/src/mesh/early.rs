//! The noise a side thread samples at the first tiles' points while the points are enumerated
//! (the job's prelude), for the owned pass to read rather than sample again.

/// The noise at the points of the first tiles, sampled by a side thread while the points are
/// enumerated: a tile's template points in order, the first `tiles` tiles' worth (each tile's
/// own points; the others are left at zero and never read). A pure function of the points, so
/// the mesh is the same bits however many tiles it holds.
#[derive(Default)]
pub(super) struct Early {
    pub tiles: usize,
    pub noise: Vec<f64>,
    /// The last grid slot of the points sampled: a batch starting past it reads none.
    pub last_slot: usize,
}
