// The ground's color before the tile state: thesis Algorithm 5 (three layers split by the
// thresholds, blended over the blend distance) in flat colors or world-space triplanar textures
// (the texture array's layers 0, 1 and 2), and under a water surface the sea floor instead of
// the sea.
#define_import_path hex_terrain::ground

#import hex_terrain::bindings::{params, layer_textures, layer_sampler, has_flag, FLAG_TEXTURES, FLAG_SEA_FLOOR}
#import hex_terrain::triplanar::triplanar_layer

// A layer of the texture array (the last one for a layer past it), projected on the three world
// planes and weighted by the normal.
fn triplanar(layer: u32, p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    return triplanar_layer(layer_textures, layer_sampler, params.texture_layers, layer, params.texture_scale, p, n);
}

// Under a water surface the sea layer is the sea floor: sand at the coast, darker with depth.
fn sea_floor(h: f32) -> vec4<f32> {
    let depth = max(params.sea_level - h, 0.0);
    let dark = smoothstep(0.0, max(params.deep_water, 1e-3) * 1.5, depth);
    return vec4<f32>(params.sea_floor_color.rgb * mix(1.0, 0.3, dark), 1.0);
}

fn has_sea_floor() -> bool {
    return has_flag(FLAG_SEA_FLOOR);
}

// Algorithm 5 with linear blending on both sides of each threshold. Textures are sampled in
// uniform control flow (every fragment samples all three) so their derivatives stay valid.
fn albedo(p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    var layers = array<vec4<f32>, 3>(params.sea_color, params.land_color, params.mountain_color);
    let sea = triplanar(0u, p, n);
    let land = triplanar(1u, p, n);
    let rock = triplanar(2u, p, n);
    if has_flag(FLAG_TEXTURES) {
        layers = array<vec4<f32>, 3>(sea, land, rock);
    }
    if has_sea_floor() {
        layers[0] = sea_floor(p.y);
    }
    let h = p.y;
    var own = 2;
    if h < params.sea_level { own = 0; } else if h < params.mountain_level { own = 1; }
    var color = layers[own];
    let thresholds = array<f32, 2>(params.sea_level, params.mountain_level);
    for (var t = 0; t < 2; t++) {
        let d = h - thresholds[t];
        if params.blend > 0.0 && abs(d) < params.blend {
            var other = t;
            if d < 0.0 { other = t + 1; }
            color = mix(color, layers[other], 0.5 * (1.0 - abs(d) / params.blend));
        }
    }
    return color;
}
