//! Error types.

use thiserror::Error;

/// A configuration value outside its allowed range.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("invalid map config: `{field}` = {value}; allowed: {allowed}")]
pub struct ConfigError {
    /// Dotted path of the field, e.g. `noise.octaves`.
    pub field: String,
    /// The value found.
    pub value: String,
    /// The allowed range, in words.
    pub allowed: String,
}

impl ConfigError {
    /// Builds an error for `field`.
    #[must_use]
    pub fn new(field: &str, value: String, allowed: String) -> Self {
        Self { field: field.to_owned(), value, allowed }
    }
}

/// Why a map config could not be loaded.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The path tried.
        path: String,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not UTF-8 text.
    #[error("the map config is not UTF-8: {0}")]
    Utf8(#[from] std::str::Utf8Error),
    /// Malformed RON; the message carries line and column.
    #[error("malformed map config at {0}")]
    Ron(#[from] ron::error::SpannedError),
    /// Well-formed but out of range.
    #[error(transparent)]
    Invalid(#[from] ConfigError),
}
