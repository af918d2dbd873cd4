//! Height source from a greyscale heightmap image: the thesis' filter use (abstract, chapter
//! 8), where an existing map (a real-world elevation raster, say) is tiled with the same
//! classification and manipulation as the noise.

use std::io::Cursor;
use std::path::Path;

use image::ImageDecoder;

/// Largest heightmap file read from disk, in bytes.
pub const MAX_PNG_BYTES: u64 = 512 << 20;

/// Most pixels a heightmap may have (8192 x 8192): decoding it takes about a second, and its
/// samples 256 MiB. Larger images are refused before their pixels are decoded.
pub const MAX_IMAGE_PIXELS: u64 = 8192 * 8192;

/// A heightmap resampled bilinearly, with values in `[0, 1]`.
#[derive(Clone, PartialEq)]
pub struct HeightImage {
    width: usize,
    height: usize,
    data: Vec<f32>,
}

impl std::fmt::Debug for HeightImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "HeightImage({}x{})", self.width, self.height)
    }
}

/// Why a heightmap could not be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ImageError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path tried.
        path: String,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Not a decodable PNG.
    #[error("not a readable PNG heightmap: {0}")]
    Decode(#[from] image::ImageError),
    /// No pixels.
    #[error("the heightmap is empty ({0}x{1} pixels)")]
    Empty(u32, u32),
    /// More pixels than [`MAX_IMAGE_PIXELS`].
    #[error("the heightmap is {0}x{1} pixels; allowed: at most {MAX_IMAGE_PIXELS} pixels (8192x8192)")]
    TooLarge(u32, u32),
}

impl HeightImage {
    /// Builds a heightmap from row-major samples in `[0, 1]` (clamped; NaN becomes 0).
    ///
    /// # Errors
    /// [`ImageError::Empty`] when there are no samples or `data` does not hold `width * height`.
    pub fn from_samples(width: usize, height: usize, data: Vec<f32>) -> Result<Self, ImageError> {
        if width == 0 || height == 0 || data.len() != width * height {
            return Err(ImageError::Empty(width as u32, height as u32));
        }
        let data = data.into_iter().map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) }).collect();
        Ok(Self { width, height, data })
    }

    /// Decodes an 8 or 16 bit PNG (grey, grey-alpha, RGB or RGBA; color is reduced to luma).
    ///
    /// # Errors
    /// [`ImageError::Decode`] for anything that is not a valid PNG, [`ImageError::Empty`] for
    /// a 0x0 image, [`ImageError::TooLarge`] for more than [`MAX_IMAGE_PIXELS`] (read from the
    /// header, before any pixel is decoded).
    pub fn from_png_bytes(bytes: &[u8]) -> Result<Self, ImageError> {
        let decoder = image::ImageReader::with_format(Cursor::new(bytes), image::ImageFormat::Png).into_decoder()?;
        let (w, h) = decoder.dimensions();
        if w == 0 || h == 0 {
            return Err(ImageError::Empty(w, h));
        }
        if u64::from(w) * u64::from(h) > MAX_IMAGE_PIXELS {
            return Err(ImageError::TooLarge(w, h));
        }
        let img = image::DynamicImage::from_decoder(decoder)?;
        let luma = img.into_luma16();
        let data = luma.pixels().map(|p| f32::from(p.0[0]) / 65535.0).collect();
        Self::from_samples(w as usize, h as usize, data)
    }

    /// Reads a PNG file (a regular file of at most [`MAX_PNG_BYTES`]: a device or a pipe
    /// named as a heightmap is refused, not read forever).
    ///
    /// # Errors
    /// As [`HeightImage::from_png_bytes`], plus [`ImageError::Io`].
    pub fn load(path: &Path) -> Result<Self, ImageError> {
        use std::io::Read;
        let io = |source| ImageError::Io { path: path.display().to_string(), source };
        let file = std::fs::File::open(path).map_err(io)?;
        let meta = file.metadata().map_err(io)?;
        if !meta.is_file() || meta.len() > MAX_PNG_BYTES {
            let what = if meta.is_file() { "a file larger than 512 MiB" } else { "not a regular file" };
            return Err(io(std::io::Error::new(std::io::ErrorKind::InvalidInput, what)));
        }
        let mut bytes = Vec::new();
        file.take(MAX_PNG_BYTES).read_to_end(&mut bytes).map_err(io)?;
        Self::from_png_bytes(&bytes)
    }

    /// Width and height in pixels.
    #[must_use]
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Bilinear sample at `(u, v)` in `[0, 1]²` (clamped): `u` across columns, `v` down rows.
    #[must_use]
    pub fn sample(&self, u: f64, v: f64) -> f64 {
        let x = u.clamp(0.0, 1.0) * (self.width - 1) as f64;
        let y = v.clamp(0.0, 1.0) * (self.height - 1) as f64;
        let (x0, y0) = (x.floor() as usize, y.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (fx, fy) = (x - x0 as f64, y - y0 as f64);
        let at = |x: usize, y: usize| f64::from(self.data[y * self.width + x]);
        let top = at(x0, y0) * (1.0 - fx) + at(x1, y0) * fx;
        let bottom = at(x0, y1) * (1.0 - fx) + at(x1, y1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

/// Remaps an image height so that `sea_level` lands on the sea threshold: `[0, sea_level]`
/// onto `[0, sea_threshold]` and `[sea_level, 1]` onto `[sea_threshold, 1]`, so exactly the
/// pixels below the sea level become sea.
#[must_use]
pub fn remap_sea_level(h: f64, sea_level: f64, sea_threshold: f64) -> f64 {
    if h < sea_level {
        if sea_level > 0.0 { h / sea_level * sea_threshold } else { 0.0 }
    } else if sea_level < 1.0 {
        sea_threshold + (h - sea_level) / (1.0 - sea_level) * (1.0 - sea_threshold)
    } else {
        1.0
    }
}
