// The water surface's look: depth colors and opacity, shore foam broken by ripples, and three
// travelling waves tilting its normal.
#define_import_path hex_terrain::water

#import hex_terrain::bindings::params

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

// The water's color and opacity over `depth` of water at `q` (world (x, z) from the render
// origin's tile) and time `t`.
fn water_color(depth: f32, q: vec2<f32>, t: f32) -> vec4<f32> {
    let deep = smoothstep(0.0, max(params.deep_water, 1e-3), depth);
    var color = mix(params.shallow_water_color.rgb, params.deep_water_color.rgb, deep);
    var alpha = mix(0.62, 0.97, deep);
    // Foam: a band along the shore, broken by ripples running in.
    let width = max(params.foam_width, 1e-4);
    let shore = 1.0 - smoothstep(0.0, width, depth);
    let ripple = 0.5 + 0.5 * sin(depth / width * 5.0 - t * 1.8 + 2.0 * sin(q.x * 2.3 + q.y * 1.7));
    let foam = shore * (0.6 + 0.4 * ripple);
    color = mix(color, params.foam_color.rgb, foam);
    alpha = max(alpha, 0.9 * foam);
    return vec4<f32>(color, alpha);
}
