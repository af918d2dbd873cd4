// The terrain material's bindings and flags: the uniform parameters (material/params.rs's
// `TerrainParams`), the texture array of the layers, the tile state texture and the owner colors. The
// flag bits and the owner palette's size are shader defs from Rust, so both sides share them.
#define_import_path hex_terrain::bindings

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
    // Bits FLAG_*, defined in Rust (material/params.rs, `flags`) and passed as shader defs.
    flags: u32,
    // Layers in the texture array.
    texture_layers: u32,
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
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var layer_textures: texture_2d_array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(102) var layer_sampler: sampler;
@group(#{MATERIAL_BIND_GROUP}) @binding(107) var tile_state: texture_2d<u32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(108) var<uniform> owners: OwnerColors;

const FLAG_OUTLINES: u32 = #{HEX_FLAG_OUTLINES}u;
const FLAG_TEXTURES: u32 = #{HEX_FLAG_TEXTURES}u;
const FLAG_POINTY: u32 = #{HEX_FLAG_POINTY}u;
const FLAG_FOG: u32 = #{HEX_FLAG_FOG}u;
const FLAG_BORDERS: u32 = #{HEX_FLAG_BORDERS}u;
const FLAG_TERRITORY_TINT: u32 = #{HEX_FLAG_TERRITORY_TINT}u;
const FLAG_LENS: u32 = #{HEX_FLAG_LENS}u;
const FLAG_SEA_FLOOR: u32 = #{HEX_FLAG_SEA_FLOOR}u;

fn has_flag(flag: u32) -> bool {
    return (params.flags & flag) != 0u;
}
