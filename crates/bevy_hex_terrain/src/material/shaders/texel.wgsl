// A tile's state texel in the shaders (the layout of tiles/texel.rs, its bits as shader defs from
// Rust), shared by the flat map's material and the globe's: the fog and highlight bits, the
// overlay's color, and tints.
#define_import_path hex_terrain::texel

// Bits of a texel's first channel: the fog state, then the highlights.
const FOG_MASK: u32 = #{HEX_TEXEL_FOG_MASK}u;
const HOVERED: u32 = #{HEX_TEXEL_HOVERED}u;
const SELECTED: u32 = #{HEX_TEXEL_SELECTED}u;
const REACHABLE: u32 = #{HEX_TEXEL_REACHABLE}u;
// The fog states (`FogState` in Rust).
const FOG_EXPLORED: u32 = #{HEX_FOG_EXPLORED}u;
const FOG_VISIBLE: u32 = #{HEX_FOG_VISIBLE}u;

// The overlay color of a texel (sRGB, alpha the strength).
fn overlay_of(texel: vec4<u32>) -> vec4<f32> {
    return vec4<f32>(
        f32(texel.z & 255u), f32(texel.z >> 8u), f32(texel.w & 255u), f32(texel.w >> 8u),
    ) / 255.0;
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
}

// A color mixed toward `t.rgb` by `t.a`.
fn tint(color: vec4<f32>, t: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(mix(color.rgb, t.rgb, t.a), color.a);
}

// A color with the texel's highlights' tints over it (reachable, then selected, then hovered),
// each tint's alpha its strength.
fn tint_highlights(color: vec4<f32>, texel: vec4<u32>, reachable: vec4<f32>, selected: vec4<f32>, hovered: vec4<f32>) -> vec4<f32> {
    var c = color;
    if (texel.x & REACHABLE) != 0u { c = tint(c, reachable); }
    if (texel.x & SELECTED) != 0u { c = tint(c, selected); }
    if (texel.x & HOVERED) != 0u { c = tint(c, hovered); }
    return c;
}
