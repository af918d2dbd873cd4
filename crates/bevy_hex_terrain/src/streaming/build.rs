//! A chunk's build on the async compute pool: the task a chunk carries while its mesh is built,
//! and what the task returns. Streaming starts it (`tasks`), insertion reads it (`insert`) and
//! retiring a chunk cancels it (`retire`).

use bevy::platform::time::Instant;
use bevy::prelude::*;
use bevy::tasks::Task;
use hex_terrain::Detail;

use super::content::BuiltContent;

/// What a chunk task returns.
pub struct ChunkBuild {
    pub(super) generation: u64,
    pub(super) mesh: Mesh,
    pub(super) vertices: usize,
    pub(super) mesh_bytes: usize,
    pub(super) content: BuiltContent,
    pub(super) detail: Detail,
}

/// A chunk mesh being built on the async compute pool.
///
/// Dropping it (the chunk was despawned, or a newer task replaced it) cancels the work if the
/// pool has not started it yet. A chunk's generation has no await point, so once started it
/// runs to its end (about a millisecond for a 16x16-tile chunk) and its result is discarded.
///
/// Hidden from the docs: streaming's internal; public so the tests and the screenshot harness
/// can wait until no chunk is being built (a game waits for [`TerrainReady`](crate::TerrainReady)).
#[doc(hidden)]
#[derive(Component)]
pub struct ChunkTask {
    pub(super) task: Task<ChunkBuild>,
    pub(super) generation: u64,
    pub(super) requested: Instant,
    pub(super) detail: Detail,
}

impl ChunkTask {
    /// The level of detail of the mesh it builds.
    #[must_use]
    pub fn detail(&self) -> Detail {
        self.detail
    }
}
