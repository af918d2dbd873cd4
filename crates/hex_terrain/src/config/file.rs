//! A map file as a game reads it from its assets: bytes in, a validated config or an error out.
//! The Bevy asset loader is this plus reading the heightmap; the fuzz targets drive it directly.

use super::MapConfig;
use crate::error::LoadError;

/// A map config read from the bytes of a map file, with what was repaired on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct MapFile {
    /// The validated config.
    pub config: MapConfig,
    /// The file's `appearance.blend` when it was outside `[0, 1]` (or NaN): it only affects
    /// looks, so it was clamped (NaN: the default) instead of refusing the map, and renderers
    /// should fall back to flat colors.
    pub clamped_blend: Option<f32>,
}

impl MapFile {
    /// Parses and validates the bytes of a RON map file.
    ///
    /// # Errors
    /// [`LoadError::Utf8`] when the bytes are not UTF-8, [`LoadError::Ron`] with line and column
    /// for malformed RON, [`LoadError::Invalid`] naming the first out-of-range field.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, LoadError> {
        let mut config: MapConfig = ron::de::from_str(std::str::from_utf8(bytes)?)?;
        let blend = config.appearance.blend;
        let clamped_blend = (!(0.0..=1.0).contains(&blend)).then_some(blend);
        if clamped_blend.is_some() {
            config.appearance.blend =
                if blend.is_nan() { super::AppearanceConfig::default().blend } else { blend.clamp(0.0, 1.0) };
        }
        config.validate()?;
        Ok(Self { config, clamped_blend })
    }
}
