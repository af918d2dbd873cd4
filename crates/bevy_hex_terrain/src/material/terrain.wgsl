// Hex terrain material: thesis Algorithm 5 (three layers split by the thresholds, blended over
// the blend distance), flat colors or world-space triplanar textures, tile outlines computed from
// the world position (no per-vertex data needed, so they are exact on every chunk), hovered and
// selected tile tints, and a gently animated sea. Lighting and shadows are StandardMaterial's.

#import bevy_pbr::{
    pbr_fragment::pbr_input_from_standard_material,
    pbr_functions::alpha_discard,
}

#ifdef PREPASS_PIPELINE
#import bevy_pbr::{
    prepass_io::{VertexOutput, FragmentOutput},
    pbr_deferred_functions::deferred_output,
}
#else
#import bevy_pbr::{
    forward_io::{VertexOutput, FragmentOutput},
    pbr_functions::{apply_pbr_lighting, main_pass_post_lighting_processing},
    mesh_view_bindings::globals,
}
#endif

struct TerrainParams {
    sea_color: vec4<f32>,
    land_color: vec4<f32>,
    mountain_color: vec4<f32>,
    hover_color: vec4<f32>,
    highlight_color: vec4<f32>,
    outline_color: vec4<f32>,
    water_color: vec4<f32>,
    // World heights of the thresholds and the blend distance.
    sea_level: f32,
    mountain_level: f32,
    blend: f32,
    hex_size: f32,
    outline_width: f32,
    texture_scale: f32,
    // Bits FLAG_*, defined in Rust (material/mod.rs, `flags`) and passed as shader defs.
    flags: u32,
    highlight_count: u32,
    hovered: vec4<i32>,
}

struct Highlights {
    tiles: array<vec4<i32>, #{HEX_MAX_HIGHLIGHTS}>,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> params: TerrainParams;
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var sea_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(102) var sea_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var land_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(104) var land_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(105) var mountain_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(106) var mountain_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(107) var<uniform> highlights: Highlights;

const SQRT3: f32 = 1.7320508;
const FLAG_OUTLINES: u32 = #{HEX_FLAG_OUTLINES}u;
const FLAG_TEXTURES: u32 = #{HEX_FLAG_TEXTURES}u;
const FLAG_POINTY: u32 = #{HEX_FLAG_POINTY}u;
const FLAG_HOVERED: u32 = #{HEX_FLAG_HOVERED}u;

fn triplanar(t: texture_2d<f32>, s: sampler, p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    var w = abs(n);
    w = w / (w.x + w.y + w.z);
    let k = params.texture_scale;
    return textureSample(t, s, p.zx * k) * w.y + textureSample(t, s, p.zy * k) * w.x + textureSample(t, s, p.xy * k) * w.z;
}

// Algorithm 5 with linear blending on both sides of each threshold. Textures are sampled in
// uniform control flow (every fragment samples all three) so their derivatives stay valid.
fn albedo(p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    var layers = array<vec4<f32>, 3>(params.sea_color, params.land_color, params.mountain_color);
    let sea = triplanar(sea_texture, sea_sampler, p, n);
    let land = triplanar(land_texture, land_sampler, p, n);
    let rock = triplanar(mountain_texture, mountain_sampler, p, n);
    if (params.flags & FLAG_TEXTURES) != 0u {
        layers = array<vec4<f32>, 3>(sea, land, rock);
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

// Axial coordinates of the hex under a world position, and the distance to its border.
fn hex_at(p: vec2<f32>) -> vec3<f32> {
    let s = params.hex_size;
    var q: f32;
    var r: f32;
    if (params.flags & FLAG_POINTY) != 0u {
        q = (SQRT3 / 3.0 * p.x - p.y / 3.0) / s;
        r = (2.0 / 3.0 * p.y) / s;
    } else {
        q = (2.0 / 3.0 * p.x) / s;
        r = (-p.x / 3.0 + SQRT3 / 3.0 * p.y) / s;
    }
    let c = vec3<f32>(q, r, -q - r);
    var rc = round(c);
    let diff = abs(rc - c);
    if diff.x > diff.y && diff.x > diff.z {
        rc.x = -rc.y - rc.z;
    } else if diff.y > diff.z {
        rc.y = -rc.x - rc.z;
    }
    // Center of that hex and the distance from it along the three edge normals.
    var center: vec2<f32>;
    var normals: array<vec2<f32>, 3>;
    if (params.flags & FLAG_POINTY) != 0u {
        center = s * vec2<f32>(SQRT3 * rc.x + SQRT3 / 2.0 * rc.y, 1.5 * rc.y);
        normals = array<vec2<f32>, 3>(vec2<f32>(1.0, 0.0), vec2<f32>(0.5, SQRT3 / 2.0), vec2<f32>(-0.5, SQRT3 / 2.0));
    } else {
        center = s * vec2<f32>(1.5 * rc.x, SQRT3 / 2.0 * rc.x + SQRT3 * rc.y);
        normals = array<vec2<f32>, 3>(vec2<f32>(0.0, 1.0), vec2<f32>(SQRT3 / 2.0, 0.5), vec2<f32>(SQRT3 / 2.0, -0.5));
    }
    let d = p - center;
    let reach = max(max(abs(dot(d, normals[0])), abs(dot(d, normals[1]))), abs(dot(d, normals[2])));
    return vec3<f32>(rc.x, rc.y, s * SQRT3 / 2.0 - reach);
}

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
    let p = in.world_position.xyz;
    let n = normalize(in.world_normal);
    var color = albedo(p, n);
#ifdef VERTEX_COLORS
    // Biomes: the vertex color is the tiles' biome colors (blended across tile borders by the
    // interpolation between vertices); its alpha is river or lake water. With textures on, the
    // relief texture's detail modulates the biome color.
    var biome = in.color.rgb;
    if (params.flags & FLAG_TEXTURES) != 0u {
        biome = biome * (0.6 + 0.8 * color.rgb);
    }
    let water = smoothstep(0.2, 0.55, in.color.a);
    color = vec4<f32>(mix(biome, params.water_color.rgb, water), 1.0);
#endif

    // A gently moving sea surface: a slow shimmer below sea level. (The deferred prepass has no
    // time uniform bound: there the sea is still.)
#ifndef PREPASS_PIPELINE
    var wet = p.y < params.sea_level;
#ifdef VERTEX_COLORS
    wet = wet || in.color.a > 0.3;
#endif
    if wet {
        let wave = 0.5 + 0.5 * sin(globals.time * 1.3 + p.x * 1.7 + p.z * 1.1) * sin(globals.time * 0.9 - p.z * 1.3);
        color = vec4<f32>(color.rgb * (0.92 + 0.12 * wave), color.a);
    }
#endif

    let hex = hex_at(p.xz);
    let tile = vec2<i32>(i32(hex.x), i32(hex.y));
    for (var i = 0u; i < params.highlight_count; i++) {
        if all(highlights.tiles[i].xy == tile) {
            color = vec4<f32>(mix(color.rgb, params.highlight_color.rgb, params.highlight_color.a), color.a);
        }
    }
    if (params.flags & FLAG_HOVERED) != 0u && all(params.hovered.xy == tile) {
        color = vec4<f32>(mix(color.rgb, params.hover_color.rgb, params.hover_color.a), color.a);
    }
    // Outlines go over the lit color, so lighting and specular never wash them out.
    var outline = 0.0;
    if (params.flags & FLAG_OUTLINES) != 0u && hex.z < params.outline_width {
        outline = params.outline_color.a;
    }

#ifdef VERTEX_COLORS
    // The standard path put the vertex color (water in alpha) in the base color: replace it.
    pbr_input.material.base_color = color;
#else
    pbr_input.material.base_color = pbr_input.material.base_color * color;
#endif
    pbr_input.material.base_color = alpha_discard(pbr_input.material, pbr_input.material.base_color);

#ifdef PREPASS_PIPELINE
    // Deferred: the outline goes into the albedo (lighting comes later, in the deferred pass).
    pbr_input.material.base_color = vec4<f32>(
        mix(pbr_input.material.base_color.rgb, params.outline_color.rgb, outline),
        pbr_input.material.base_color.a,
    );
    let out = deferred_output(in, pbr_input);
#else
    var out: FragmentOutput;
    out.color = apply_pbr_lighting(pbr_input);
    out.color = vec4<f32>(mix(out.color.rgb, params.outline_color.rgb, outline), out.color.a);
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);
#endif
    return out;
}
