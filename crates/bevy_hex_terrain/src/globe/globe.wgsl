// The globe's material: StandardMaterial's lighting over the mesh's vertex colors, the sea drawn
// as water where the ground lies below the sea's sphere (depth colors over the sea floor, foam
// along the shore, moving waves that catch the sun), with the per-tile game state of
// GlobeTileStates drawn per fragment. Each vertex carries its tile's id in
// its first UV (id mod row, id / row: every corner of a triangle the same tile, so the value is
// exact); the tile state texture holds each tile's texel, the topology texture its center and
// neighbors. Fog and borders measure the fragment's distance to each edge as the distance to the
// plane halfway between the two tiles' centers, so the three tiles at a corner (a pentagon's
// five neighbors too) agree.

#import bevy_pbr::{
    pbr_fragment::pbr_input_from_standard_material,
    pbr_functions::{alpha_discard, apply_pbr_lighting, main_pass_post_lighting_processing},
    forward_io::{VertexOutput, FragmentOutput},
    mesh_view_bindings::{globals, view},
}
#import hex_terrain::triplanar::triplanar_layer
#import hex_terrain::texel::{
    FOG_MASK, FOG_EXPLORED, FOG_VISIBLE, overlay_of, srgb_to_linear, tint, tint_highlights,
}

struct GlobeParams {
    hover_color: vec4<f32>,
    selected_color: vec4<f32>,
    reachable_color: vec4<f32>,
    unexplored_color: vec4<f32>,
    // Fractions of a tile's radius (center to corner).
    border_width: f32,
    border_inset: f32,
    fog_softness: f32,
    tint_strength: f32,
    // Bits HEX_FLAG_* (material/params.rs's `flags`).
    flags: u32,
    // The water (HexWaterSettings; linear colors, depths in world units).
    shallow_water_color: vec4<f32>,
    deep_water_color: vec4<f32>,
    foam_color: vec4<f32>,
    sea_floor_color: vec4<f32>,
    sea_radius: f32,
    deep_water: f32,
    foam_width: f32,
    waves: f32,
    hex_size: f32,
    // The texture array's repeats per world unit, and its layers (0: none).
    texture_scale: f32,
    texture_layers: u32,
}

struct OwnerColors {
    colors: array<vec4<f32>, #{HEX_MAX_OWNERS}>,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> params: GlobeParams;
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var tile_state: texture_2d<u32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(102) var topology: texture_2d<u32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var<uniform> owners: OwnerColors;
@group(#{MATERIAL_BIND_GROUP}) @binding(104) var layer_textures: texture_2d_array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(105) var layer_sampler: sampler;

// Tiles a texture row holds.
const ROW: u32 = #{HEX_GLOBE_ROW}u;
const FLAG_FOG: u32 = #{HEX_FLAG_FOG}u;
const FLAG_BORDERS: u32 = #{HEX_FLAG_BORDERS}u;
const FLAG_TERRITORY_TINT: u32 = #{HEX_FLAG_TERRITORY_TINT}u;
const FLAG_LENS: u32 = #{HEX_FLAG_LENS}u;
const FLAG_SEA_FLOOR: u32 = #{HEX_FLAG_SEA_FLOOR}u;
const FLAG_WATER: u32 = #{HEX_FLAG_WATER}u;
const FLAG_TEXTURES: u32 = #{HEX_FLAG_TEXTURES}u;
// A hexagon's inner radius over its outer one: the distance from an edge to the center.
const INNER: f32 = 0.8660254;
// The tiles' outline: the color's share at a tile's edge, and how far in (in the measure of
// `INNER` at the center) it fades out.
const OUTLINE_SHADE: f32 = 0.78;
const OUTLINE_WIDTH: f32 = 0.25;

fn has_flag(flag: u32) -> bool {
    return (params.flags & flag) != 0u;
}

fn texel_of(tile: u32) -> vec4<u32> {
    return textureLoad(tile_state, vec2<u32>(tile % ROW, tile / ROW), 0);
}

// Texel `k` of a tile's three in the topology texture: its center (x, y, z as bits) and neighbor
// count, then its neighbors, four and two.
fn topology_of(tile: u32, k: u32) -> vec4<u32> {
    return textureLoad(topology, vec2<u32>(3u * (tile % ROW) + k, tile / ROW), 0);
}

fn center_of(tile: u32) -> vec3<f32> {
    return bitcast<vec3<f32>>(topology_of(tile, 0u).xyz);
}

// The water over `depth` (world units) of sea at `p` at time `t`, seen over the ground's color
// `ground`: shallow to deep colors and opacity, the sea floor through the shallows (sand
// darkening with depth, with the sea floor flag; else the ground's own color), and foam in a
// band along the shore broken by ripples running in.
fn water_over(ground: vec3<f32>, depth: f32, p: vec3<f32>, t: f32) -> vec3<f32> {
    let deep = smoothstep(0.0, max(params.deep_water, 1e-3), depth);
    var floor = ground;
    if has_flag(FLAG_SEA_FLOOR) {
        floor = params.sea_floor_color.rgb * mix(1.0, 0.45, deep);
    }
    let water = mix(params.shallow_water_color.rgb, params.deep_water_color.rgb, deep);
    var color = mix(floor, water, mix(0.62, 0.97, deep));
    // The globe's shallows slope gently: the band is half the flat map's depth, and the foam
    // lighter, so the coast reads as surf, not snow.
    let width = max(0.5 * params.foam_width, 1e-4);
    let shore = 1.0 - smoothstep(0.0, width, depth);
    let ripple = 0.5 + 0.5 * sin(depth / width * 5.0 - t * 1.8 + 2.0 * sin(p.x * 2.3 + p.y * 1.7 + p.z * 1.9));
    return mix(color, params.foam_color.rgb, shore * (0.35 + 0.3 * ripple));
}

// The moving waves' normal at `p` on the sea's sphere (`up` its outward direction): three
// trains of waves a hex wide and less, their slopes laid in the sphere's tangent plane, so the
// waves have no pole and no seam. They calm with the distance from the camera (from 10 to 40
// hexes), where a pixel would hold many of them.
fn wave_normal(p: vec3<f32>, up: vec3<f32>, t: f32) -> vec3<f32> {
    let far = smoothstep(10.0, 40.0, length(view.world_position - p) / max(params.hex_size, 1e-3));
    let k = 6.2831853 / max(params.hex_size, 1e-3);
    let d1 = vec3<f32>(0.8, 0.36, 0.48);
    let d2 = vec3<f32>(-0.45, 0.62, 0.64);
    let d3 = vec3<f32>(0.57, -0.51, 0.64);
    let g = d1 * cos(dot(p, d1) * k * 0.9 + t * 1.1) * 0.5
        + d2 * cos(dot(p, d2) * k * 1.7 + t * 1.7) * 0.3
        + d3 * cos(dot(p, d3) * k * 3.1 + t * 2.3) * 0.2;
    return normalize(up - params.waves * (1.0 - far) * (g - up * dot(g, up)));
}

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
    var color = pbr_input.material.base_color;
#ifdef VERTEX_UVS_B
    // Textures: the tile's layer (the second UV) modulates its color, as on a flat map. Sampled
    // in uniform control flow, so the derivatives hold.
    let layer = u32(round(in.uv_b.x));
    let detail = triplanar_layer(
        layer_textures, layer_sampler, params.texture_layers, layer, params.texture_scale,
        in.world_position.xyz, normalize(in.world_normal),
    ).rgb;
    if has_flag(FLAG_TEXTURES) {
        color = vec4<f32>(color.rgb * (0.6 + 0.8 * detail), color.a);
    }
#endif
    // The sea: the ground below the sea's sphere is seen through water, smooth and glinting.
    let up = normalize(in.world_position.xyz);
    let depth = params.sea_radius - length(in.world_position.xyz);
    if has_flag(FLAG_WATER) && depth > 0.0 {
        let t = globals.time;
        color = vec4<f32>(water_over(color.rgb, depth, in.world_position.xyz, t), color.a);
        pbr_input.N = wave_normal(in.world_position.xyz, up, t);
        pbr_input.material.perceptual_roughness = 0.12;
        pbr_input.material.reflectance = vec3<f32>(0.5);
    }
    var explored = 1.0;
    var visible = 1.0;
    var border = vec4<f32>(0.0);
#ifdef VERTEX_UVS_A
    let tile = u32(round(in.uv.x)) + u32(round(in.uv.y)) * ROW;
    let texel = texel_of(tile);
    let owner = texel.y;
    if owner != 0u && has_flag(FLAG_TERRITORY_TINT) {
        color = tint(color, vec4<f32>(owners.colors[owner - 1u].rgb, params.tint_strength));
    }
    let overlay = overlay_of(texel);
    if has_flag(FLAG_LENS) && overlay.a > 0.0 {
        color = tint(color, vec4<f32>(srgb_to_linear(overlay.rgb), overlay.a));
    }
    color = tint_highlights(color, texel, params.reachable_color, params.selected_color, params.hover_color);

    // Fog weights: own tile 1, each neighbor from 1 at the shared edge to 0 at `fog_softness`
    // inside; the owner's border where the neighbor across is not the owner's.
    let fog = texel.x & FOG_MASK;
    explored = f32(fog >= FOG_EXPLORED);
    visible = f32(fog == FOG_VISIBLE);
    var total = 1.0;
    let p = normalize(in.world_position.xyz);
    let c = center_of(tile);
    let head = topology_of(tile, 0u);
    let first = topology_of(tile, 1u);
    let rest = topology_of(tile, 2u);
    let neighbors = array<u32, 6>(first.x, first.y, first.z, first.w, rest.x, rest.y);
    let soft = max(params.fog_softness, 1e-4);
    let band = vec2<f32>(params.border_inset, params.border_inset + params.border_width);
    // The nearest edge toward another owner (a fragment of the mesh's tile past the halfway
    // plane, where the mesh's border zigzags, is nearer than 0 and draws no line).
    var nearest_other = 2.0;
    var nearest = 2.0;
    for (var i = 0u; i < head.w; i++) {
        let n = neighbors[i];
        let across = c - center_of(n);
        // 0 on the plane halfway between the centers, INNER at this tile's center.
        let d = dot(p, across) / (0.5 * dot(across, across)) * INNER;
        nearest = min(nearest, d);
        let near_fog = d < soft;
        let near_border = owner != 0u && d < band.y;
        if !(near_fog || near_border) {
            continue;
        }
        let other = texel_of(n);
        if near_fog {
            let k = 1.0 - smoothstep(0.0, soft, max(d, 0.0));
            let nf = other.x & FOG_MASK;
            explored += k * f32(nf >= FOG_EXPLORED);
            visible += k * f32(nf == FOG_VISIBLE);
            total += k;
        }
        if near_border && other.y != owner {
            nearest_other = min(nearest_other, d);
        }
    }
    // Antialiased edges of the band, a hundredth of the radius wide.
    let aa = 0.01;
    let line = smoothstep(band.x - aa, band.x + aa, nearest_other) * (1.0 - smoothstep(band.y - aa, band.y + aa, nearest_other));
    // Every tile's outline, darker toward its edges: drawn here, so a coarse chunk (a fan a
    // tile) shows it as a full one does.
    color = vec4<f32>(color.rgb * mix(OUTLINE_SHADE, 1.0, clamp(nearest / OUTLINE_WIDTH, 0.0, 1.0)), color.a);
    explored /= total;
    visible /= total;
    if !has_flag(FLAG_FOG) {
        explored = 1.0;
        visible = 1.0;
    }
    if has_flag(FLAG_BORDERS) && owner != 0u {
        border = vec4<f32>(owners.colors[owner - 1u].rgb, 0.95 * line);
    }
#endif
    pbr_input.material.base_color = alpha_discard(pbr_input.material, color);
    var out: FragmentOutput;
    out.color = apply_pbr_lighting(pbr_input);
    // The border over the lit color, so lighting never washes it out; the fog over everything:
    // desaturated and darker where explored, the unexplored color (faintly mottled) where never seen.
    var lit = mix(out.color.rgb, border.rgb, border.a);
    let grey = vec3<f32>(dot(lit, vec3<f32>(0.2126, 0.7152, 0.0722)));
    let remembered = mix(grey, lit, 0.2) * 0.6;
    let seen = mix(remembered, lit, visible);
    let q = in.world_position.xyz;
    let mottle = 0.85 + 0.15 * sin(q.x * 0.37 + sin(q.z * 0.23)) * sin(q.y * 0.31 + sin(q.x * 0.19));
    lit = mix(params.unexplored_color.rgb * mottle, seen, explored);
    out.color = main_pass_post_lighting_processing(pbr_input, vec4<f32>(lit, out.color.a));
    return out;
}
