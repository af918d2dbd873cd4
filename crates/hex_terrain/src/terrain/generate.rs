//! The generation methods of [`Terrain`]: every way to turn tiles into a [`ChunkMesh`], and the
//! props of a generated chunk.

use super::Terrain;
use crate::chunk::{ChunkCoord, TileRect};
use crate::mesh::{self, ChunkMesh, Detail, GenerateOptions};
use crate::props::{self, Prop};

impl Terrain {
    /// Generates a chunk on the calling thread (a chunk is the unit of parallel work of a
    /// streaming caller), `None` when it lies outside a bounded map. Its
    /// [`ChunkMesh::origin`] is [`Terrain::chunk_origin`]: on a wrapping map, a chunk placed
    /// periods east of the map is the map's chunk's mesh with its origin there.
    #[must_use]
    pub fn generate_chunk(&self, chunk: ChunkCoord) -> Option<ChunkMesh> {
        let rect = self.chunk_rect(chunk)?;
        let mut mesh = self.generate(rect, GenerateOptions::CURRENT_THREAD);
        mesh.origin = self.chunk_origin(chunk)?;
        Some(mesh)
    }

    /// [`Terrain::generate_chunk`] at a level of detail: [`Detail::Full`] is `generate_chunk`.
    #[must_use]
    pub fn generate_chunk_detail(&self, chunk: ChunkCoord, detail: Detail) -> Option<ChunkMesh> {
        let rect = self.chunk_rect(chunk)?;
        let mut mesh = self.generate_detail(rect, GenerateOptions::CURRENT_THREAD, detail);
        mesh.origin = self.chunk_origin(chunk)?;
        Some(mesh)
    }

    /// [`Terrain::generate`] at a level of detail: [`Detail::Full`] is `generate`; a
    /// [`Detail::Coarse`] mesh is the full mesh's vertices (the same bits, each tile's in its own
    /// biome color) drawn as a fan a tile, its outline kept whole, so it meets a neighbor of
    /// either level without a crack.
    #[must_use]
    pub fn generate_detail(&self, rect: TileRect, options: GenerateOptions, detail: Detail) -> ChunkMesh {
        match detail {
            Detail::Full => self.generate(rect, options),
            Detail::Coarse => {
                let full = self.generate(rect, GenerateOptions { diagnostics: true, ..options });
                // Generated with diagnostics, so never the fallback.
                mesh::coarse::coarsen(self.geometry(), &full, options.diagnostics).unwrap_or(full)
            }
        }
    }

    /// The [`Detail::Coarse`] mesh of a full mesh generated with diagnostics
    /// ([`GenerateOptions::diagnostics`]), keeping them if `keep_diagnostics`: what
    /// [`Terrain::generate_detail`] returns, for a caller that also needs the full mesh (for
    /// [`Terrain::props_on`], the water surface). `None` when `full` has no diagnostics.
    #[must_use]
    pub fn coarsen(&self, full: &ChunkMesh, keep_diagnostics: bool) -> Option<ChunkMesh> {
        mesh::coarse::coarsen(self.geometry(), full, keep_diagnostics)
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
        mesh::generate(&self.pipeline, rect, options)
    }

    /// The lattice points generation evaluates for `rect`, enumerated as generation does: its
    /// vertices, then the one-step halo that normals need. For benchmarks (the noise floor).
    #[cfg(feature = "bench")]
    #[must_use]
    pub fn mesh_points(&self, rect: TileRect) -> Vec<hexx::Hex> {
        mesh::mesh_points(&self.pipeline, rect)
    }

    /// The props of a generated chunk (see `crate::props`), at most `max_per_chunk`, with
    /// `density` (in `[0, 1]`, clamped) the share of each tile's props that stand.
    #[must_use]
    pub fn props(&self, chunk: &ChunkMesh, max_per_chunk: usize, density: f32) -> Vec<Prop> {
        props::props(&self.pipeline, chunk, max_per_chunk, density, Detail::Full)
    }

    /// [`Terrain::props`] standing on the surface drawn at `detail`: `chunk` is the full mesh,
    /// and each prop's height is that of the mesh [`Terrain::generate_detail`] makes at `detail`
    /// under its foot (a coarse tile is flatter than the full one, so a prop at the full
    /// surface's height would float or sink). Same props, same places, same order as
    /// [`Terrain::props`] (which stand is decided on the full surface); only the heights differ.
    #[must_use]
    pub fn props_on(&self, chunk: &ChunkMesh, max_per_chunk: usize, density: f32, detail: Detail) -> Vec<Prop> {
        props::props(&self.pipeline, chunk, max_per_chunk, density, detail)
    }

    /// The game setup's markers (starts, resources, wonders) on a generated chunk (see
    /// `props::markers`); none without a setup.
    #[must_use]
    pub fn markers(&self, chunk: &ChunkMesh) -> Vec<props::Marker> {
        props::markers(&self.pipeline, chunk)
    }

    /// The setup's resource and wonder markers of a chunk as props (see
    /// `props::marker_props`); none without a setup.
    #[must_use]
    pub fn marker_props(&self, chunk: &ChunkMesh) -> Vec<Prop> {
        props::marker_props(&self.pipeline, &props::markers(&self.pipeline, chunk))
    }
}
