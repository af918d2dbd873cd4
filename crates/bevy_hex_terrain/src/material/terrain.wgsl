// Hex terrain material's fragment shader: the ground pass and, in the material's water instance
// (HEX_WATER), the water surface's pass. What they draw comes from the modules in shaders/: the
// bindings and flags (hex_terrain::bindings), hex geometry (hex_terrain::hex), the ground's
// layers (hex_terrain::ground), the water's look (hex_terrain::water) and the per-tile game
// state (hex_terrain::tile_state). Lighting and shadows are StandardMaterial's; the same shader
// serves forward and deferred cameras.

#import bevy_pbr::{
    pbr_fragment::pbr_input_from_standard_material,
    pbr_functions::alpha_discard,
}
#import hex_terrain::bindings::{params, has_flag, FLAG_TEXTURES}
#import hex_terrain::ground::{albedo, has_sea_floor, sea_floor, triplanar}
#import hex_terrain::tile_state::{tile_look, apply_fog, tile_class}

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
#import hex_terrain::water::{water_color, wave_normal}
#endif

#ifdef HEX_WATER
#ifndef PREPASS_PIPELINE
// The water pass: color and opacity by the depth of water below (the mesh's second UV), foam at
// the shore, moving waves, the tile state (fog, borders, highlights, outlines) as on the ground.
fn water_fragment(in: VertexOutput, is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
    let p = in.world_position.xyz;
    let depth = in.uv_b.x;
    if depth <= 0.0 {
        discard;
    }
    let t = globals.time;
    let q = p.xz + params.origin_offset.xy;
    let water = water_color(depth, q, t);
    let alpha = water.a;
    let look = tile_look(p.xz, water, false);
    pbr_input.material.base_color = vec4<f32>(look.albedo.rgb, alpha);
    pbr_input.N = wave_normal(q, t);
    var out: FragmentOutput;
    out.color = apply_pbr_lighting(pbr_input);
    var lit = mix(out.color.rgb, look.border.rgb, look.border.a);
    lit = mix(lit, params.outline_color.rgb, look.outline);
    // Unexplored water is as opaque as the unexplored ground.
    out.color = vec4<f32>(apply_fog(lit, look, p.xz), mix(1.0, alpha, look.explored));
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);
    return out;
}
#endif
#endif

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
#ifdef HEX_WATER
#ifndef PREPASS_PIPELINE
    return water_fragment(in, is_front);
#else
    return ground_fragment(in, is_front);
#endif
#else
    return ground_fragment(in, is_front);
#endif
}

// The ground pass.
fn ground_fragment(in: VertexOutput, is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
    let p = in.world_position.xyz;
    let n = normalize(in.world_normal);
    var color = albedo(p, n);
#ifdef VERTEX_COLORS
    // Biomes: the vertex color is the tiles' biome colors (blended across tile borders by the
    // interpolation between vertices); its alpha is river or lake water. With textures on, a
    // texture's detail modulates the biome color: the tile's own layer (its terrain's) where the
    // mesh carries the layers (UV_0 and UV_1: the entry of each texture class, the same at the
    // three corners of each of the tile's triangles), else the relief's layer.
    var biome = in.color.rgb;
    if has_flag(FLAG_TEXTURES) {
        var detail = color.rgb;
#ifdef VERTEX_UVS_B
#ifndef HEX_WATER
        let entries = vec3<f32>(in.uv.x, in.uv.y, in.uv_b.x);
        detail = triplanar(u32(round(entries[tile_class(p.xz)])), p, n).rgb;
#endif
#endif
        biome = biome * (0.6 + 0.8 * detail);
    }
    let water = smoothstep(0.2, 0.55, in.color.a);
    color = vec4<f32>(mix(biome, params.water_color.rgb, water), 1.0);
    if has_sea_floor() {
        // The sea's biome colors belong to the water surface above; here lies its floor.
        let under = smoothstep(params.sea_level + 0.5 * params.blend, params.sea_level - 0.5 * params.blend, p.y);
        color = vec4<f32>(mix(color.rgb, sea_floor(p.y).rgb, under), 1.0);
    }
#endif

    // A gently moving sea surface: a slow shimmer below sea level. (The deferred prepass has no
    // time uniform bound: there the sea is still.)
#ifndef PREPASS_PIPELINE
    var wet = p.y < params.sea_level && !has_sea_floor();
#ifdef VERTEX_COLORS
    wet = wet || (in.color.a > 0.3 && !has_sea_floor());
#endif
    if wet {
        let wave = 0.5 + 0.5 * sin(globals.time * 1.3 + p.x * 1.7 + p.z * 1.1) * sin(globals.time * 0.9 - p.z * 1.3);
        color = vec4<f32>(color.rgb * (0.92 + 0.12 * wave), color.a);
    }
#endif

    let look = tile_look(p.xz, color, true);
    color = look.albedo;

#ifdef VERTEX_COLORS
    // The standard path put the vertex color (water in alpha) in the base color: replace it.
    pbr_input.material.base_color = color;
#else
    pbr_input.material.base_color = pbr_input.material.base_color * color;
#endif
    pbr_input.material.base_color = alpha_discard(pbr_input.material, pbr_input.material.base_color);

    // Borders and outlines go over the lit color, so lighting and specular never wash them out;
    // fog goes over everything.
#ifdef PREPASS_PIPELINE
    // Deferred: everything goes into the albedo (lighting comes later, in the deferred pass).
    var base = pbr_input.material.base_color.rgb;
    base = mix(base, look.border.rgb, look.border.a);
    base = mix(base, params.outline_color.rgb, look.outline);
    pbr_input.material.base_color = vec4<f32>(apply_fog(base, look, p.xz), pbr_input.material.base_color.a);
    let out = deferred_output(in, pbr_input);
#else
    var out: FragmentOutput;
    out.color = apply_pbr_lighting(pbr_input);
    var lit = mix(out.color.rgb, look.border.rgb, look.border.a);
    lit = mix(lit, params.outline_color.rgb, look.outline);
    out.color = vec4<f32>(apply_fog(lit, look, p.xz), out.color.a);
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);
#endif
    return out;
}
