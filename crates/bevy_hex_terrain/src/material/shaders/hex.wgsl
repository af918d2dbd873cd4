// Hex geometry in the shader, the core's layout: the hex under a world position, a hex's center,
// the neighbor steps and the distance to a hex's edges. Positions are world (x, z) relative to
// the render frame's origin tile (small numbers, exact far from the world's origin).
#define_import_path hex_terrain::hex

#import hex_terrain::bindings::{params, has_flag, FLAG_POINTY}

const SQRT3: f32 = 1.7320508;

fn pointy() -> bool {
    return has_flag(FLAG_POINTY);
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

