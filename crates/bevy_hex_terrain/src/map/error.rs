//! [`HexMapError`]: a map, an edit or a save that could not be applied, typed, with the file,
//! field or line it is about.

use bevy::prelude::*;

/// A map that could not be applied: the terrain stays as it was. `map` says which (`map config`
/// for one given in code, `map maps/x.map.ron` for a file); its `Display` is the whole sentence.
#[derive(Message, Debug, Clone, PartialEq, Eq, Reflect, thiserror::Error)]
pub enum HexMapError {
    /// A value outside its allowed range.
    #[error(
        "{map} not applied, keeping the current terrain: invalid map config: `{field}` = {value}; allowed: {allowed}"
    )]
    Invalid {
        /// The map.
        map: String,
        /// Dotted path of the field, e.g. `noise.octaves` or `setup.min_distance`.
        field: String,
        /// The value found.
        value: String,
        /// The allowed range, in words.
        allowed: String,
    },
    /// A map file that is not valid RON, at a line and column (from 1).
    #[error("{map} not applied, keeping the current terrain: malformed map config at {line}:{column}: {message}")]
    Malformed {
        /// The map.
        map: String,
        /// Line of the error.
        line: usize,
        /// Column of the error.
        column: usize,
        /// What the parser expected.
        message: String,
    },
    /// A map file or its heightmap that could not be read.
    #[error("{map} not applied, keeping the current terrain: {message}")]
    Unreadable {
        /// The map.
        map: String,
        /// Why.
        message: String,
    },
    /// An edit ([`HexMapEdit`](crate::HexMapEdit)) that could not be applied.
    #[error("{map}: edit not applied, keeping the current terrain: {message}")]
    Edit {
        /// The map.
        map: String,
        /// Why (the tool's amount out of range, a water tool on a map without rivers...).
        message: String,
    },
    /// An edited map's file that could not be written; the edits stay in memory.
    #[error("{path} not saved, the edits are kept in memory: {message}")]
    Unwritable {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
}

impl HexMapError {
    /// An error of a config that does not validate.
    #[must_use]
    pub fn invalid(map: &str, e: &hex_terrain::ConfigError) -> Self {
        Self::Invalid { map: map.into(), field: e.field.clone(), value: e.value.clone(), allowed: e.allowed.clone() }
    }

    /// An error of a map file that does not load.
    #[must_use]
    pub fn load(map: &str, e: &hex_terrain::LoadError) -> Self {
        match e {
            hex_terrain::LoadError::Invalid(e) => Self::invalid(map, e),
            hex_terrain::LoadError::Ron(e) => Self::Malformed {
                map: map.into(),
                line: e.span.start.line,
                column: e.span.start.col,
                message: e.code.to_string(),
            },
            other => Self::Unreadable { map: map.into(), message: other.to_string() },
        }
    }

    /// Which map it was.
    #[must_use]
    pub fn map(&self) -> &str {
        match self {
            Self::Invalid { map, .. }
            | Self::Malformed { map, .. }
            | Self::Unreadable { map, .. }
            | Self::Edit { map, .. }
            | Self::Unwritable { path: map, .. } => map,
        }
    }

    /// The field, for a value out of range.
    #[must_use]
    pub fn field(&self) -> Option<&str> {
        match self {
            Self::Invalid { field, .. } => Some(field),
            _ => None,
        }
    }
}
