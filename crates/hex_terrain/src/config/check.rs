//! The field checks every part of the config's validation shares: a field against its allowed
//! range, named in the error.

use crate::error::ConfigError;

/// `Ok` when `ok`, else the error naming the field, its value and what is allowed.
pub(super) fn check(
    ok: bool,
    field: &str,
    value: impl std::fmt::Display,
    allowed: impl Into<String>,
) -> Result<(), ConfigError> {
    if ok { Ok(()) } else { Err(ConfigError::new(field, value.to_string(), allowed.into())) }
}

/// Whether `v` is a finite number in `lo..=hi`.
pub(super) fn finite_in(v: f64, lo: f64, hi: f64) -> bool {
    v.is_finite() && v >= lo && v <= hi
}
