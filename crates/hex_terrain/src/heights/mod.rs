//! Heights, the second stage: where every vertex's raw (unmanipulated) height comes from.
//!
//! The source is Perlin fBm ([`Fbm`], thesis Algorithm 2) or a greyscale heightmap
//! ([`HeightImage`], the thesis' filter use), then, for bounded maps, a shaping filter of
//! thesis section 7.1 ([`shape`]: island, mediterranean, inland, gradient) or a map type
//! ([`map_type`]: Pangaea, Continents, Archipelago... with their [`targets`]). Each is a pure function
//! of the lattice point, so any chunk samples the same heights as the whole map.

pub mod fbm;
pub(crate) mod graph;
pub mod image;
mod knots;
pub(crate) mod layout;
pub mod map_type;
pub mod ranges;
pub mod shape;
pub mod targets;

pub use fbm::{FastPerlin, Fbm, Kernel};
pub use image::{HeightImage, ImageError, MAX_IMAGE_PIXELS, MAX_PNG_BYTES, remap_sea_level};
pub use knots::{MAX_BLOB_SHARE, MAX_STRAIGHT_RIDGE};
pub use map_type::{MAX_LAYOUTS, MAX_TRIES, MapTypeField, SEA_STEPS};
pub use shape::ShapeBounds;
pub use targets::{MapTypeReport, MapTypeTarget, TargetCheck};

use std::sync::Arc;

use hexx::Hex;

use crate::config::{HeightSourceConfig, MapConfig, Shape};
use crate::edits::Edits;
use crate::error::ConfigError;
use crate::geometry::Geometry;

/// The height field of a map: its source (fBm or a decoded heightmap) and its shaping filter.
/// Every method takes the map's [`Geometry`], which says where a lattice point is.
#[derive(Debug, Clone)]
pub struct HeightField {
    fbm: Fbm,
    /// The decoded heightmap and the image's sea level, for an `Image` source.
    image: Option<(Arc<HeightImage>, f64)>,
    shape: Shape,
    shape_bounds: Option<ShapeBounds>,
    /// The map type of a bounded map whose config has one (in place of the shape).
    map_type: Option<Arc<MapTypeField>>,
    /// Whether a shaping filter changes heights (a bounded map with a shape other than `None`,
    /// or a map type).
    shaping: bool,
    sea_threshold: f64,
    /// A designer's edits, applied after shaping (`None`: the generated heights).
    edits: Option<Arc<Edits>>,
}

impl HeightField {
    /// The height field of a validated config over `geometry`; `image` is the decoded
    /// heightmap of an `Image` source (ignored for a `Noise` source).
    ///
    /// # Errors
    /// `source.path` when an `Image` source has no image.
    pub fn new(config: &MapConfig, geometry: &Geometry, image: Option<Arc<HeightImage>>) -> Result<Self, ConfigError> {
        let image = match &config.source {
            HeightSourceConfig::Noise => None,
            HeightSourceConfig::Image { path, sea_level } => Some((
                image.ok_or_else(|| {
                    ConfigError::new("source.path", format!("{path:?}"), "a decoded heightmap image".into())
                })?,
                f64::from(*sea_level),
            )),
        };
        let fbm = match geometry.wrap() {
            Some(w) => Fbm::wrapped(config.seed, &config.noise, w.width / geometry.hex_size()),
            None => Fbm::new(config.seed, &config.noise),
        };
        let shape_bounds = geometry.bounds().map(|rect| {
            let (mut min_x, mut max_x, mut min_z, mut max_z) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            let corners = [
                rect.min,
                [rect.max[0] - 1, rect.min[1]],
                [rect.min[0], rect.max[1] - 1],
                [rect.max[0] - 1, rect.max[1] - 1],
            ];
            let lattice = geometry.lattice();
            // Both parities of the first and last columns/rows, so the zig-zag is covered.
            for [c, r] in corners {
                for (dc, dr) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
                    let oc = [c + dc, r + dr];
                    if rect.contains(oc) {
                        let [x, z] = lattice.world(lattice.tile_center(geometry.tile_from_offset(oc)));
                        min_x = min_x.min(x);
                        max_x = max_x.max(x);
                        min_z = min_z.min(z);
                        max_z = max_z.max(z);
                    }
                }
            }
            let step = lattice.steps().0[0].abs().max(lattice.steps().1[0].abs());
            let min_u = if max_x > min_x { step / (max_x - min_x) } else { 1.0 };
            ShapeBounds { min_x, max_x, min_z, max_z, min_u }
        });
        let mut field = Self {
            fbm,
            image,
            shape: config.shape.clone(),
            shaping: shape_bounds.is_some() && config.shape != Shape::None,
            shape_bounds,
            map_type: None,
            sea_threshold: f64::from(config.terrain.sea_threshold),
            edits: None,
        };
        if let (Some(map_type), Some(bounds)) = (&config.map_type, shape_bounds) {
            let thresholds = (config.terrain.sea_threshold, config.terrain.mountain_threshold);
            let built = MapTypeField::build(map_type, config.seed, geometry, &field, &bounds, thresholds);
            field.map_type = Some(Arc::new(built));
            field.shaping = true;
        }
        Ok(field)
    }

    /// What came of the map's type (its targets measured, the tries it took); `None` without
    /// one.
    #[must_use]
    pub fn map_type(&self) -> Option<&MapTypeReport> {
        self.map_type.as_deref().map(MapTypeField::report)
    }

    /// The same field with `edits` applied after shaping (none when they are empty).
    #[must_use]
    pub fn with_edits(mut self, edits: Edits) -> Self {
        self.edits = (!edits.is_empty()).then(|| Arc::new(edits));
        self
    }

    /// The same field without edits: the generated heights.
    #[must_use]
    pub fn without_edits(&self) -> Self {
        Self { edits: None, ..self.clone() }
    }

    /// The edits applied, if any.
    #[must_use]
    pub fn edits(&self) -> Option<&Edits> {
        self.edits.as_deref()
    }

    /// The fBm height source.
    #[must_use]
    pub fn fbm(&self) -> &Fbm {
        &self.fbm
    }

    /// The same field with its fBm on another kernel ([`Fbm::with_kernel`]), or `None` if this
    /// CPU does not run it. The heights are the same bits.
    #[must_use]
    pub fn with_kernel(&self, kernel: Kernel) -> Option<Self> {
        let fbm = self.fbm.clone().with_kernel(kernel)?;
        Some(Self { fbm, ..self.clone() })
    }

    /// Normalised height after shaping and the edits, before manipulation, at a lattice point.
    #[must_use]
    #[inline]
    pub fn raw_height(&self, geometry: &Geometry, p: Hex) -> f32 {
        self.shaped(geometry, self.source_height(geometry, p), p)
    }

    /// Applies the shaping filter, then the edits, to a bare source height at lattice point `p`:
    /// the raw height every later stage reads.
    #[must_use]
    #[inline]
    pub fn shaped(&self, geometry: &Geometry, source: f64, p: Hex) -> f32 {
        let raw = if self.shaping {
            let [x, z] = geometry.lattice().world(geometry.wrap_point(p));
            match &self.map_type {
                Some(map_type) => map_type.apply(source, x, z) as f32,
                None => shape::apply(&self.shape, self.shape_bounds.as_ref(), source, x, z) as f32,
            }
        } else {
            source as f32
        };
        match &self.edits {
            Some(edits) => edits.apply(geometry, p, raw),
            None => raw,
        }
    }

    /// [`HeightField::shaped`] of many points: `out[i]` from `sources[i]` at `points[i]` (a
    /// plain conversion, which vectorises, when no filter and no edit applies).
    #[inline]
    pub fn shaped_many(&self, geometry: &Geometry, sources: &[f64], points: &[Hex], out: &mut [f32]) {
        if self.shaping || self.edits.is_some() {
            for ((o, &source), &p) in out.iter_mut().zip(sources).zip(points) {
                *o = self.shaped(geometry, source, p);
            }
        } else {
            for (o, &source) in out.iter_mut().zip(sources) {
                *o = source as f32;
            }
        }
    }

    /// Bare source height (fBm or heightmap, no shaping) at a lattice point.
    #[must_use]
    #[inline]
    pub fn source_height(&self, geometry: &Geometry, p: Hex) -> f64 {
        if let Some((image, sea_level)) = &self.image {
            return self.image_height(geometry, image, *sea_level, p);
        }
        let [ux, uz] = self.noise_position(geometry, p);
        self.fbm.sample(ux, uz)
    }

    /// Source heights of many lattice points (batched for the noise).
    pub fn source_heights(&self, geometry: &Geometry, points: &[Hex], out: &mut [f64]) {
        if let Some((image, sea_level)) = &self.image {
            for (p, o) in points.iter().zip(out) {
                *o = self.image_height(geometry, image, *sea_level, *p);
            }
        } else {
            const STEP: usize = 256;
            let mut positions = [[0.0; 2]; STEP];
            for (points, out) in points.chunks(STEP).zip(out.chunks_mut(STEP)) {
                for (position, &p) in positions.iter_mut().zip(points) {
                    *position = self.noise_position(geometry, p);
                }
                self.fbm.sample_many(&positions[..points.len()], out);
            }
        }
    }

    fn image_height(&self, geometry: &Geometry, image: &HeightImage, sea_level: f64, p: Hex) -> f64 {
        let [x, z] = geometry.lattice().world(geometry.wrap_point(p));
        let (u, v) = self.shape_bounds.map_or((0.5, 0.5), |b| b.normalise(x, z));
        remap_sea_level(image.sample(u, v), sea_level, self.sea_threshold)
    }

    /// Where a lattice point samples the noise: its world position in hex radii, shifted by the
    /// map's offset (on a wrapping map, the position of its canonical point).
    #[must_use]
    #[inline]
    pub fn noise_position(&self, geometry: &Geometry, p: Hex) -> [f64; 2] {
        let (p, o) = (geometry.wrap_point(p), geometry.origin_lattice());
        match (p.x.checked_add(o.x), p.y.checked_add(o.y)) {
            (Some(x), Some(y)) => geometry.lattice().unit(Hex::new(x, y)),
            // A point past the world (whose sum overflows `i32`): the same position in f64.
            _ => {
                let ([px, pz], [ox, oz]) = (geometry.lattice().unit(p), geometry.lattice().unit(o));
                [px + ox, pz + oz]
            }
        }
    }
}
