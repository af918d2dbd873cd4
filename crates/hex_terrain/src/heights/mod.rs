//! Heights: where every vertex's raw (unmanipulated) height comes from.
//!
//! The source is Perlin fBm ([`Fbm`], thesis Algorithm 2) or a greyscale heightmap
//! ([`HeightImage`], the thesis' filter use), then a shaping filter of thesis section 7.1
//! ([`shape`]: island, mediterranean, inland, gradient) for bounded maps. Each is a pure function
//! of the lattice point, so any chunk samples the same heights as the whole map.

pub mod fbm;
pub mod image;
pub mod shape;

pub use fbm::{FastPerlin, Fbm};
pub use image::{HeightImage, ImageError, MAX_IMAGE_PIXELS, MAX_PNG_BYTES, remap_sea_level};
pub use shape::ShapeBounds;

use hexx::Hex;

use crate::terrain::Terrain;

impl Terrain {
    /// Normalised height after shaping, before manipulation, at a lattice point.
    #[must_use]
    #[inline]
    pub fn raw_height(&self, p: Hex) -> f32 {
        self.shaped(self.noise_height(p), p)
    }

    /// Applies the shaping filter to a bare source height at lattice point `p`.
    #[inline]
    pub(crate) fn shaped(&self, noise: f64, p: Hex) -> f32 {
        if self.shaping {
            let [x, z] = self.lattice.world(self.wrap_point(p));
            shape::apply(&self.config.shape, self.shape_bounds.as_ref(), noise, x, z) as f32
        } else {
            noise as f32
        }
    }

    /// Bare source height (fBm or heightmap, no shaping) at a lattice point.
    #[must_use]
    #[inline]
    pub fn noise_height(&self, p: Hex) -> f64 {
        if let Some((image, sea_level)) = &self.image {
            return self.image_height(image, *sea_level, p);
        }
        let [ux, uz] = self.noise_position(p);
        self.fbm.sample(ux, uz)
    }

    /// Whether heights come from fBm (rather than a heightmap image).
    pub(crate) fn samples_noise(&self) -> bool {
        self.image.is_none()
    }

    /// Source heights of many lattice points (batched for the noise).
    pub(crate) fn base_heights(&self, points: &[Hex], out: &mut [f64]) {
        if let Some((image, sea_level)) = &self.image {
            for (p, o) in points.iter().zip(out) {
                *o = self.image_height(image, *sea_level, *p);
            }
        } else {
            const STEP: usize = 256;
            let mut positions = [[0.0; 2]; STEP];
            for (points, out) in points.chunks(STEP).zip(out.chunks_mut(STEP)) {
                for (position, &p) in positions.iter_mut().zip(points) {
                    *position = self.noise_position(p);
                }
                self.fbm.sample_many(&positions[..points.len()], out);
            }
        }
    }

    fn image_height(&self, image: &HeightImage, sea_level: f64, p: Hex) -> f64 {
        let [x, z] = self.lattice.world(self.wrap_point(p));
        let (u, v) = self.shape_bounds.map_or((0.5, 0.5), |b| b.normalise(x, z));
        remap_sea_level(image.sample(u, v), sea_level, f64::from(self.config.terrain.sea_threshold))
    }

    /// Where a lattice point samples the noise: its world position in hex radii, shifted by the
    /// map's offset (on a wrapping map, the position of its canonical point).
    #[must_use]
    #[inline]
    pub fn noise_position(&self, p: Hex) -> [f64; 2] {
        self.lattice.unit(self.wrap_point(p) + self.origin_lattice)
    }
}
