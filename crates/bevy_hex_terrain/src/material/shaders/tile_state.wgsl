// The per-tile game state in the flat map's shader: a hex's texel in the tile state texture (the window
// and the map's wrap come in the parameters), and what it does to a fragment: highlights, the
// lens, territory tint and borders, fog of war blended across tile borders, outlines. The
// texel's bit layout (tiles/window.rs) comes from Rust as shader defs.
#define_import_path hex_terrain::tile_state

#import hex_terrain::bindings::{
    params, owners, tile_state, has_flag, FLAG_TERRITORY_TINT, FLAG_LENS, FLAG_FOG, FLAG_BORDERS, FLAG_OUTLINES,
}
#import hex_terrain::hex::{pointy, hex_at, hex_center, NEIGHBORS, edge_distance}
#import hex_terrain::texel::{
    FOG_MASK, FOG_EXPLORED, FOG_VISIBLE, overlay_of, srgb_to_linear, tint, tint_highlights,
}

// The offset coordinate of a hex on the map (hexx's odd mode, as the core's): a wrapping map's
// tiles east or west of it are its own.
fn map_offset(h: vec2<i32>) -> vec2<i32> {
    var oc: vec2<i32>;
    if pointy() {
        oc = vec2<i32>(h.x + (h.y - (h.y & 1)) / 2, h.y);
    } else {
        oc = vec2<i32>(h.x, h.y + (h.x - (h.x & 1)) / 2);
    }
    let columns = params.map_wrap.x;
    if columns > 0 {
        oc.x = ((oc.x % columns) + columns) % columns;
    }
    return oc;
}

// The texture class of the map's own tile under a render position (`hex_terrain::texture_class`:
// `(q - r) mod 3` of its axial coordinate): which entry of the mesh's texture layers holds that
// tile's layer.
fn tile_class(render_p: vec2<f32>) -> u32 {
    let oc = map_offset(hex_at(render_p + params.origin_offset.xy) + params.map_wrap.yz);
    var a: vec2<i32>;
    if pointy() {
        a = vec2<i32>(oc.x - (oc.y - (oc.y & 1)) / 2, oc.y);
    } else {
        a = vec2<i32>(oc.x, oc.y - (oc.x - (oc.x & 1)) / 2);
    }
    return u32((((a.x - a.y) % 3) + 3) % 3);
}

// The tile state texel of a hex (zero, the default state, outside the texture's window).
fn tile_texel(h: vec2<i32>) -> vec4<u32> {
    let oc = map_offset(h);
    let w = params.tile_window;
    let local = oc - w.xy;
    if any(local < vec2<i32>(0)) || any(local >= w.zw) {
        return vec4<u32>(0u);
    }
    let t = ((oc % w.zw) + w.zw) % w.zw;
    return textureLoad(tile_state, t, 0);
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
    if owner != 0u && tint_owned && has_flag(FLAG_TERRITORY_TINT) {
        color = tint(color, vec4<f32>(owners.colors[owner - 1u].rgb, params.tint_strength));
    }
    let overlay = overlay_of(texel);
    if has_flag(FLAG_LENS) && overlay.a > 0.0 {
        color = tint(color, vec4<f32>(srgb_to_linear(overlay.rgb), overlay.a));
    }
    color = tint_highlights(color, texel, params.reachable_color, params.selected_color, params.hover_color);
    look.albedo = color;

    // Fog weights: own tile 1, each neighbor from 1 at the shared edge to 0 at `fog_softness`
    // inside, so both sides of an edge (and the three tiles at a corner) agree.
    let fog = texel.x & FOG_MASK;
    var explored = f32(fog >= FOG_EXPLORED);
    var visible = f32(fog == FOG_VISIBLE);
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
            explored += k * f32(nf >= FOG_EXPLORED);
            visible += k * f32(nf == FOG_VISIBLE);
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
    if !has_flag(FLAG_FOG) {
        look.explored = 1.0;
        look.visible = 1.0;
    }
    if has_flag(FLAG_BORDERS) && owner != 0u {
        look.border = vec4<f32>(owners.colors[owner - 1u].rgb, 0.95 * border);
    }
    if has_flag(FLAG_OUTLINES) && nearest < params.outline_width {
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

