//! Map configs as Bevy assets: `*.map.ron` files loaded into [`HexMapAsset`] (the loader claims
//! no other `.ron` file of a game).

use std::sync::Arc;

use bevy::asset::io::Reader;
use bevy::asset::{AssetLoader, LoadContext};
use bevy::prelude::*;
use hex_terrain::{HeightImage, HeightSourceConfig, ImageError, LoadError, MapConfig, MapFile, TerrainRuleset};
use thiserror::Error;

/// A loaded map config, with the heightmap of an `Image` source already decoded.
#[derive(Asset, TypePath, Debug, Clone)]
pub struct HexMapAsset {
    /// The validated config.
    pub config: MapConfig,
    /// The decoded heightmap when the config's source is `Image`.
    pub image: Option<Arc<HeightImage>>,
    /// The terrain ruleset the config names ([`MapConfig::ruleset`], relative to the map
    /// file), else the game's ([`HexMapPlugin::ruleset`](crate::HexMapPlugin::ruleset), then
    /// named in `config.ruleset` relative to the map file, so a saved map keeps it), loaded and
    /// validated with it: editing the ruleset file reloads the map.
    pub ruleset: Option<Arc<TerrainRuleset>>,
    /// The file's blend value was outside `[0, 1]`: it was clamped and the material falls back
    /// to flat colors (with a logged warning) instead of refusing the map.
    pub appearance_fallback: bool,
}

/// Loads [`HexMapAsset`]s from RON.
#[derive(Debug, Default, Clone, TypePath)]
pub struct HexMapLoader {
    /// The asset path of the game's terrain ruleset (`*.terrain.ron`), taken by every map file
    /// that names none ([`HexMapPlugin::ruleset`](crate::HexMapPlugin::ruleset)).
    pub ruleset: Option<String>,
}

/// Why a map config asset failed to load. A failed (re)load leaves the terrain as it was.
#[non_exhaustive]
#[derive(Debug, Error)]
pub enum HexMapLoaderError {
    /// The file could not be read.
    #[error("could not read the map config: {0}")]
    Io(#[from] std::io::Error),
    /// Not UTF-8, malformed RON (with line and column) or a value out of range (naming the
    /// field and the allowed range).
    #[error(transparent)]
    Map(#[from] LoadError),
    /// The heightmap of an `Image` source could not be read.
    #[error("heightmap {path}: {source}")]
    Image {
        /// Asset path of the heightmap.
        path: String,
        /// The underlying error.
        #[source]
        source: ImageError,
    },
    /// The heightmap of an `Image` source could not be read from the asset source.
    #[error("heightmap {path}: {message}")]
    ImageRead {
        /// Asset path of the heightmap.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// The terrain ruleset the config names could not be read, or is malformed (with its line
    /// and column) or invalid (naming the entry and the field).
    #[error("terrain ruleset {path}: {message}")]
    Ruleset {
        /// Asset path of the ruleset.
        path: String,
        /// What went wrong.
        message: String,
    },
}

impl AssetLoader for HexMapLoader {
    type Asset = HexMapAsset;
    type Settings = ();
    type Error = HexMapLoaderError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        load_context: &mut LoadContext<'_>,
    ) -> Result<HexMapAsset, HexMapLoaderError> {
        let mut bytes = Vec::new();
        reader.read_to_end(&mut bytes).await?;
        // Parsing and validation are the core's, so the fuzz targets exercise this very path.
        let MapFile { mut config, clamped_blend } = MapFile::from_bytes(&bytes)?;
        // A map file that names no ruleset takes the game's, named relative to the map file.
        if let (None, Some(game)) = (&config.ruleset, &self.ruleset) {
            config.ruleset = Some(relative_to(&load_context.path().path().to_string_lossy(), game));
        }
        // An out-of-range blend only affects looks: it was clamped; warn, and fall back to flat
        // colors rather than refusing the whole map.
        if let Some(blend) = clamped_blend {
            warn!(
                "{}: appearance.blend = {blend} is outside [0, 1]; using {} and flat colors",
                load_context.path(),
                config.appearance.blend
            );
        }
        let image = match &config.source {
            HeightSourceConfig::Noise => None,
            HeightSourceConfig::Image { path, .. } => {
                // Relative to the map file, like any asset dependency.
                let asset_path = load_context
                    .path()
                    .resolve_embed_str(path)
                    .map_err(|e| HexMapLoaderError::ImageRead { path: path.clone(), message: e.to_string() })?;
                let bytes = load_context
                    .read_asset_bytes(asset_path.clone())
                    .await
                    .map_err(|e| HexMapLoaderError::ImageRead { path: path.clone(), message: e.to_string() })?;
                Some(Arc::new(
                    HeightImage::from_png_bytes(&bytes)
                        .map_err(|source| HexMapLoaderError::Image { path: path.clone(), source })?,
                ))
            }
        };
        let ruleset = match &config.ruleset {
            None => None,
            Some(path) => {
                let failed = |message: String| HexMapLoaderError::Ruleset { path: path.clone(), message };
                let asset_path = load_context.path().resolve_embed_str(path).map_err(|e| failed(e.to_string()))?;
                let bytes = load_context.read_asset_bytes(asset_path).await.map_err(|e| failed(e.to_string()))?;
                let text = std::str::from_utf8(&bytes).map_err(|e| failed(e.to_string()))?;
                Some(Arc::new(TerrainRuleset::from_ron(text).map_err(|e| failed(e.to_string()))?))
            }
        };
        Ok(HexMapAsset { config, image, ruleset, appearance_fallback: clamped_blend.is_some() })
    }

    fn extensions(&self) -> &[&str] {
        &["map.ron"]
    }
}

/// The path of asset `target` relative to the folder of asset `from` (both from the asset
/// root): `maps/world.map.ron` to `rulesets/civ5.terrain.ron` is `../rulesets/civ5.terrain.ron`.
fn relative_to(from: &str, target: &str) -> String {
    let folder: Vec<&str> = from.split('/').filter(|c| !c.is_empty()).collect();
    let folder = &folder[..folder.len().saturating_sub(1)];
    let target: Vec<&str> = target.split('/').filter(|c| !c.is_empty()).collect();
    let common = folder.iter().zip(&target).take_while(|(a, b)| a == b).count();
    let up = std::iter::repeat_n("..", folder.len() - common);
    up.chain(target[common..].iter().copied()).collect::<Vec<_>>().join("/")
}

#[cfg(test)]
mod tests {
    use super::relative_to;

    #[test]
    fn a_path_relative_to_a_map_file() {
        assert_eq!(relative_to("maps/world.map.ron", "rulesets/civ5.terrain.ron"), "../rulesets/civ5.terrain.ron");
        assert_eq!(relative_to("world.map.ron", "rulesets/civ5.terrain.ron"), "rulesets/civ5.terrain.ron");
        assert_eq!(relative_to("maps/types/a.map.ron", "maps/own.terrain.ron"), "../own.terrain.ron");
        assert_eq!(relative_to("maps/a.map.ron", "maps/rules/own.terrain.ron"), "rules/own.terrain.ron");
    }
}
