//! The generation methods of [`Terrain`]: every way to turn tiles into a [`ChunkMesh`].

use super::job::Job;
use super::{ChunkMesh, GenerateOptions};
use crate::chunk::{ChunkCoord, TileRect};
use crate::terrain::Terrain;

impl Terrain {
    /// Generates a chunk on the calling thread (a chunk is the unit of parallel work of a
    /// streaming caller), `None` when it lies outside a bounded map.
    #[must_use]
    pub fn generate_chunk(&self, chunk: ChunkCoord) -> Option<ChunkMesh> {
        self.chunk_rect(chunk).map(|rect| self.generate(rect, GenerateOptions::CURRENT_THREAD))
    }

    /// Generates a bounded map in one mesh on all cores, `None` for an unbounded world.
    #[must_use]
    pub fn generate_map(&self) -> Option<ChunkMesh> {
        self.bounds().map(|rect| self.generate_rect(rect))
    }

    /// Generates the mesh of any rectangle of tiles (clipped to the map) on all cores, with the
    /// halo it needs: the result for a tile does not depend on which rectangle it was generated
    /// in.
    #[must_use]
    pub fn generate_rect(&self, rect: TileRect) -> ChunkMesh {
        self.generate(rect, GenerateOptions::default())
    }

    /// [`Terrain::generate_rect`] with options: diagnostics, and where the work runs. The
    /// buffers are the same bits whatever the options.
    #[must_use]
    pub fn generate(&self, rect: TileRect, options: GenerateOptions) -> ChunkMesh {
        Job::new(self, rect, options).run()
    }

    /// The lattice points generation evaluates for `rect`, enumerated as generation does: its
    /// vertices, then the one-step halo that normals need. For benchmarks (the noise floor).
    #[cfg(feature = "bench")]
    #[must_use]
    pub fn mesh_points(&self, rect: TileRect) -> Vec<hexx::Hex> {
        Job::new(self, rect, GenerateOptions::default()).points()
    }
}
