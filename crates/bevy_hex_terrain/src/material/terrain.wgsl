// Hex terrain material: thesis Algorithm 5 (three layers split by the thresholds, blended over
// the blend distance), flat colors or world-space triplanar textures, tile outlines computed from
// the world position (no per-vertex data needed, so they are exact on every chunk), a gently
// animated sea (or, under a water surface, a sea floor), the water surface itself (the HEX_WATER
// instance: depth colors, shore foam, waves), and the per-tile game state read from the tile state texture: highlights, the
// lens, territory tint and borders, and fog of war blended across tile borders. Lighting and
// shadows are StandardMaterial's.

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
    selected_color: vec4<f32>,
    reachable_color: vec4<f32>,
    unexplored_color: vec4<f32>,
    outline_color: vec4<f32>,
    water_color: vec4<f32>,
    shallow_water_color: vec4<f32>,
    deep_water_color: vec4<f32>,
    foam_color: vec4<f32>,
    sea_floor_color: vec4<f32>,
    // Water surface: depth of full deep color, foam width (world units), wave strength.
    deep_water: f32,
    foam_width: f32,
    waves: f32,
    // World heights of the thresholds and the blend distance.
    sea_level: f32,
    mountain_level: f32,
    blend: f32,
    hex_size: f32,
    outline_width: f32,
    texture_scale: f32,
    // Fractions of the hex radius.
    border_width: f32,
    border_inset: f32,
    fog_softness: f32,
    tint_strength: f32,
    // Bits FLAG_*, defined in Rust (material/mod.rs, `flags`) and passed as shader defs.
    flags: u32,
    // The tiles the tile state texture holds: first offset column and row, width, height.
    tile_window: vec4<i32>,
    // x: a wrapping map's width in columns (0: no wrap); yz: the axial tile nearest the render
    // frame's origin (a floating origin renders relative to a far-away cell).
    map_wrap: vec4<i32>,
    // xy: the render frame's origin relative to that tile's center.
    origin_offset: vec4<f32>,
}

struct OwnerColors {
    colors: array<vec4<f32>, #{HEX_MAX_OWNERS}>,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> params: TerrainParams;
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var sea_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(102) var sea_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var land_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(104) var land_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(105) var mountain_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(106) var mountain_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(107) var tile_state: texture_2d<u32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(108) var<uniform> owners: OwnerColors;

const SQRT3: f32 = 1.7320508;
const FLAG_OUTLINES: u32 = #{HEX_FLAG_OUTLINES}u;
const FLAG_TEXTURES: u32 = #{HEX_FLAG_TEXTURES}u;
const FLAG_POINTY: u32 = #{HEX_FLAG_POINTY}u;
const FLAG_FOG: u32 = #{HEX_FLAG_FOG}u;
const FLAG_BORDERS: u32 = #{HEX_FLAG_BORDERS}u;
const FLAG_TERRITORY_TINT: u32 = #{HEX_FLAG_TERRITORY_TINT}u;
const FLAG_LENS: u32 = #{HEX_FLAG_LENS}u;
const FLAG_SEA_FLOOR: u32 = #{HEX_FLAG_SEA_FLOOR}u;
// Bits of a tile state texel's first channel (tiles/window.rs): fog in bits 0-1, then the
// highlights.
const FOG_MASK: u32 = 3u;
const HOVERED: u32 = 4u;
const SELECTED: u32 = 8u;
const REACHABLE: u32 = 16u;

fn triplanar(t: texture_2d<f32>, s: sampler, p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    var w = abs(n);
    w = w / (w.x + w.y + w.z);
    let k = params.texture_scale;
    return textureSample(t, s, p.zx * k) * w.y + textureSample(t, s, p.zy * k) * w.x + textureSample(t, s, p.xy * k) * w.z;
}

// Under a water surface the sea layer is the sea floor: sand at the coast, darker with depth.
fn sea_floor(h: f32) -> vec4<f32> {
    let depth = max(params.sea_level - h, 0.0);
    let dark = smoothstep(0.0, max(params.deep_water, 1e-3) * 1.5, depth);
    return vec4<f32>(params.sea_floor_color.rgb * mix(1.0, 0.3, dark), 1.0);
}

fn has_sea_floor() -> bool {
    return (params.flags & FLAG_SEA_FLOOR) != 0u;
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

fn pointy() -> bool {
    return (params.flags & FLAG_POINTY) != 0u;
}

// Axial coordinates of the hex under a world position.
fn hex_at(p: vec2<f32>) -> vec2<i32> {
    let s = params.hex_size;
    var q: f32;
    var r: f32;
    if pointy() {
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
    return vec2<i32>(i32(rc.x), i32(rc.y));
}

// World (x, z) center of a hex.
fn hex_center(h: vec2<i32>) -> vec2<f32> {
    let f = vec2<f32>(h);
    if pointy() {
        return params.hex_size * vec2<f32>(SQRT3 * f.x + SQRT3 / 2.0 * f.y, 1.5 * f.y);
    }
    return params.hex_size * vec2<f32>(1.5 * f.x, SQRT3 / 2.0 * f.x + SQRT3 * f.y);
}

// The six axial neighbor steps.
const NEIGHBORS = array<vec2<i32>, 6>(
    vec2<i32>(1, 0), vec2<i32>(1, -1), vec2<i32>(0, -1), vec2<i32>(-1, 0), vec2<i32>(-1, 1), vec2<i32>(0, 1),
);

// Distance to the edge facing neighbor step `d` of a point `offset` from its hex's center (the
// center of a step is the direction to that neighbor: centers are linear in the coordinates).
fn edge_distance(offset: vec2<f32>, d: vec2<i32>) -> f32 {
    return params.hex_size * SQRT3 / 2.0 - dot(offset, normalize(hex_center(d)));
}

// The tile state texel of a hex (zero, the default state, outside the texture's window). Offset
// coordinates are hexx's odd mode, as the core's.
fn tile_texel(h: vec2<i32>) -> vec4<u32> {
    var oc: vec2<i32>;
    if pointy() {
        oc = vec2<i32>(h.x + (h.y - (h.y & 1)) / 2, h.y);
    } else {
        oc = vec2<i32>(h.x, h.y + (h.x - (h.x & 1)) / 2);
    }
    // A wrapping map's tiles east or west of it are its own.
    let columns = params.map_wrap.x;
    if columns > 0 {
        oc.x = ((oc.x % columns) + columns) % columns;
    }
    let w = params.tile_window;
    let local = oc - w.xy;
    if any(local < vec2<i32>(0)) || any(local >= w.zw) {
        return vec4<u32>(0u);
    }
    let t = ((oc % w.zw) + w.zw) % w.zw;
    return textureLoad(tile_state, t, 0);
}

fn overlay_of(texel: vec4<u32>) -> vec4<f32> {
    return vec4<f32>(
        f32(texel.z & 255u), f32(texel.z >> 8u), f32(texel.w & 255u), f32(texel.w >> 8u),
    ) / 255.0;
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
}

fn tint(color: vec4<f32>, t: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(mix(color.rgb, t.rgb, t.a), color.a);
}

// What the per-tile state does to a fragment: albedo tints before lighting, and after lighting
// the border (color, strength) and the fog (explored and visible weights, blended across
// borders).
struct TileLook {
    albedo: vec4<f32>,
    border: vec4<f32>,
    explored: f32,
    visible: f32,
    outline: f32,
}

// `tint`: tint owned tiles in their owner's color (the ground; the water keeps its own color and
// shows territory by the border line alone).
fn tile_look(render_p: vec2<f32>, albedo: vec4<f32>, tint_owned: bool) -> TileLook {
    var look: TileLook;
    // Hexes relative to the tile nearest the render origin (small numbers, exact), and `base`
    // to make them absolute for the tile state.
    let p = render_p + params.origin_offset.xy;
    let base = params.map_wrap.yz;
    let h = hex_at(p);
    let texel = tile_texel(h + base);
    let owner = texel.y;
    var color = albedo;
    if owner != 0u && tint_owned && (params.flags & FLAG_TERRITORY_TINT) != 0u {
        color = tint(color, vec4<f32>(owners.colors[owner - 1u].rgb, params.tint_strength));
    }
    let overlay = overlay_of(texel);
    if (params.flags & FLAG_LENS) != 0u && overlay.a > 0.0 {
        color = tint(color, vec4<f32>(srgb_to_linear(overlay.rgb), overlay.a));
    }
    if (texel.x & REACHABLE) != 0u { color = tint(color, params.reachable_color); }
    if (texel.x & SELECTED) != 0u { color = tint(color, params.selected_color); }
    if (texel.x & HOVERED) != 0u { color = tint(color, params.hover_color); }
    look.albedo = color;

    // Fog weights: own tile 1, each neighbor from 1 at the shared edge to 0 at `fog_softness`
    // inside, so both sides of an edge (and the three tiles at a corner) agree.
    let fog = texel.x & FOG_MASK;
    var explored = f32(fog >= 1u);
    var visible = f32(fog == 2u);
    var total = 1.0;
    let radius = params.hex_size;
    let soft = max(params.fog_softness * radius, 1e-4);
    let band = vec2<f32>(params.border_inset, params.border_inset + params.border_width) * radius;
    var border = 0.0;
    var nearest = radius;
    let offset = p - hex_center(h);
    for (var i = 0; i < 6; i++) {
        let d = edge_distance(offset, NEIGHBORS[i]);
        nearest = min(nearest, d);
        let near_fog = d < soft;
        let near_border = owner != 0u && d < band.y;
        if !(near_fog || near_border) {
            continue;
        }
        let n = tile_texel(h + base + NEIGHBORS[i]);
        if near_fog {
            let k = 1.0 - smoothstep(0.0, soft, d);
            let nf = n.x & FOG_MASK;
            explored += k * f32(nf >= 1u);
            visible += k * f32(nf == 2u);
            total += k;
        }
        if near_border && n.y != owner {
            // Antialiased edges of the band, a hundredth of the radius wide.
            let aa = 0.01 * radius;
            border = max(border, smoothstep(band.x - aa, band.x + aa, d) * (1.0 - smoothstep(band.y - aa, band.y + aa, d)));
        }
    }
    look.explored = explored / total;
    look.visible = visible / total;
    if (params.flags & FLAG_FOG) == 0u {
        look.explored = 1.0;
        look.visible = 1.0;
    }
    if (params.flags & FLAG_BORDERS) != 0u && owner != 0u {
        look.border = vec4<f32>(owners.colors[owner - 1u].rgb, 0.95 * border);
    }
    if (params.flags & FLAG_OUTLINES) != 0u && nearest < params.outline_width {
        look.outline = params.outline_color.a;
    }
    return look;
}

// Fog of war over a finished color: desaturated and darker where explored, the unexplored color
// (with a faint low-frequency mottle, no terrain detail) where never seen.
fn apply_fog(color: vec3<f32>, look: TileLook, p: vec2<f32>) -> vec3<f32> {
    let grey = vec3<f32>(dot(color, vec3<f32>(0.2126, 0.7152, 0.0722)));
    let remembered = mix(grey, color, 0.2) * 0.6;
    let seen = mix(remembered, color, look.visible);
    let mottle = 0.85 + 0.15 * sin(p.x * 0.37 + sin(p.y * 0.23)) * sin(p.y * 0.31 + sin(p.x * 0.19));
    return mix(params.unexplored_color.rgb * mottle, seen, look.explored);
}

#ifdef HEX_WATER
#ifndef PREPASS_PIPELINE
// The water surface's normal: three travelling waves, their slopes tilting the normal.
fn wave_normal(p: vec2<f32>, t: f32) -> vec3<f32> {
    let k = 6.2831853 / params.hex_size;
    let d1 = vec2<f32>(0.8, 0.6);
    let d2 = vec2<f32>(-0.45, 0.89);
    let d3 = vec2<f32>(0.96, -0.28);
    let g = d1 * cos(dot(p, d1) * k * 0.9 + t * 1.1) * 0.5
        + d2 * cos(dot(p, d2) * k * 1.7 + t * 1.7) * 0.3
        + d3 * cos(dot(p, d3) * k * 3.1 + t * 2.3) * 0.2;
    return normalize(vec3<f32>(-g.x * params.waves, 1.0, -g.y * params.waves));
}

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
    let deep = smoothstep(0.0, max(params.deep_water, 1e-3), depth);
    var color = mix(params.shallow_water_color.rgb, params.deep_water_color.rgb, deep);
    var alpha = mix(0.62, 0.97, deep);
    // Foam: a band along the shore, broken by ripples running in.
    let width = max(params.foam_width, 1e-4);
    let shore = 1.0 - smoothstep(0.0, width, depth);
    let q = p.xz + params.origin_offset.xy;
    let ripple = 0.5 + 0.5 * sin(depth / width * 5.0 - t * 1.8 + 2.0 * sin(q.x * 2.3 + q.y * 1.7));
    let foam = shore * (0.6 + 0.4 * ripple);
    color = mix(color, params.foam_color.rgb, foam);
    alpha = max(alpha, 0.9 * foam);
    let look = tile_look(p.xz, vec4<f32>(color, alpha), false);
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
    // interpolation between vertices); its alpha is river or lake water. With textures on, the
    // relief texture's detail modulates the biome color.
    var biome = in.color.rgb;
    if (params.flags & FLAG_TEXTURES) != 0u {
        biome = biome * (0.6 + 0.8 * color.rgb);
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
