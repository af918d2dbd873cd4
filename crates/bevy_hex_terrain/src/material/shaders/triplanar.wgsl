// World-space triplanar sampling of a texture array's layer, shared by the flat map's material
// and the globe's (each passes its own binding of the array and the sampler).
#define_import_path hex_terrain::triplanar

// Layer `layer` of `layers` (the last of `count` layers for a layer past it), `k` repeats per
// world unit, projected on the three world planes and weighted by the normal `n`.
fn triplanar_layer(
    layers: texture_2d_array<f32>,
    s: sampler,
    count: u32,
    layer: u32,
    k: f32,
    p: vec3<f32>,
    n: vec3<f32>,
) -> vec4<f32> {
    var w = abs(n);
    w = w / (w.x + w.y + w.z);
    let l = i32(min(layer, max(count, 1u) - 1u));
    return textureSample(layers, s, p.zx * k, l) * w.y
        + textureSample(layers, s, p.zy * k, l) * w.x
        + textureSample(layers, s, p.xy * k, l) * w.z;
}
