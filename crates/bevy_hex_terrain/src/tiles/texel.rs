//! A tile's state in its texel, the one layout the flat map's [`TileStates`](super::TileStates),
//! the globe's [`GlobeTileStates`](crate::GlobeTileStates) and the shaders share: reading each
//! state and the checked writes of owners and overlays.

use bevy::prelude::*;

use hex_terrain::save::{FogState, Highlight, MAX_OWNERS};

use super::error::TileStateError;
use super::window::Texel;

/// The fog state's bits in a texel's first word (the shader takes it as a shader def).
pub(crate) const FOG_MASK: u16 = 0b11;

/// A highlight's bit in a texel's first word (the shader takes these as shader defs).
pub(crate) const fn bit(highlight: Highlight) -> u16 {
    1 << (2 + highlight as u16)
}

/// What the player knows of the tile.
pub(crate) fn fog(texel: Texel) -> FogState {
    // The two fog bits hold 0, 1 or 2: any other value is never written.
    FogState::from_bits((texel[0] & FOG_MASK) as u8).unwrap_or(FogState::Visible)
}

/// Whether the tile is in sight.
pub(crate) fn is_visible(texel: Texel) -> bool {
    texel[0] & FOG_MASK == FogState::Visible as u16
}

/// The texel with another fog state.
pub(crate) fn with_fog(mut texel: Texel, fog: FogState) -> Texel {
    texel[0] = (texel[0] & !FOG_MASK) | fog as u16;
    texel
}

/// The tile's owner.
pub(crate) fn owner(texel: Texel) -> Option<u32> {
    // The texel holds the player + 1; 0 is nobody.
    u32::from(texel[1]).checked_sub(1)
}

/// An owner's word: the player + 1 (below 65), 0 for nobody.
pub(crate) fn owner_word(owner: Option<u32>) -> Result<u16, TileStateError> {
    match owner {
        Some(owner) if owner >= MAX_OWNERS => Err(TileStateError::OwnerOutOfRange { owner }),
        Some(owner) => Ok(owner as u16 + 1),
        None => Ok(0),
    }
}

/// The tile's overlay color.
pub(crate) fn overlay(texel: Texel) -> Option<Color> {
    let [_, _, rg, ba] = texel;
    (ba >> 8 != 0).then(|| Color::srgba_u8(rg as u8, (rg >> 8) as u8, ba as u8, (ba >> 8) as u8))
}

/// An overlay color's two words (8 bits a channel, sRGB), `[0, 0]` for none.
pub(crate) fn overlay_words(color: Option<Color>) -> Result<[u16; 2], TileStateError> {
    let [r, g, b, a] = match color {
        None => [0; 4],
        Some(c) => {
            let s = c.to_srgba();
            let f = [s.red, s.green, s.blue, s.alpha];
            if f.iter().any(|v| !v.is_finite()) {
                return Err(TileStateError::OverlayNotFinite { color: f });
            }
            s.to_u8_array()
        }
    };
    Ok([u16::from(r) | u16::from(g) << 8, u16::from(b) | u16::from(a) << 8])
}

/// Whether the tile carries a highlight.
pub(crate) fn is_highlighted(texel: Texel, highlight: Highlight) -> bool {
    texel[0] & bit(highlight) != 0
}

/// The texel with a highlight on or off.
pub(crate) fn with_highlight(mut texel: Texel, highlight: Highlight, on: bool) -> Texel {
    let bit = bit(highlight);
    texel[0] = if on { texel[0] | bit } else { texel[0] & !bit };
    texel
}
