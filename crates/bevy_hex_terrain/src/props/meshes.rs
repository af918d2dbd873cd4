//! The props' meshes, made in code: a few low-poly, flat-shaded variants of each kind, colored
//! by vertex so that every prop shares one material (and Bevy batches each variant's props into
//! instanced draws). A mesh's unit is the prop's scale (see [`hex_terrain::Prop::scale`]): its
//! foot is at the origin, trees are about 2.2 units tall.

use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use hex_terrain::{PROP_VARIANTS, PropKind};

/// A flat-shaded part in one color, placed by `transform`, without its faces that look straight
/// down (the base of a cone, the bottom of a box): from any camera above a face's plane, and a
/// strategy game's camera is above the ground, such a face is a back face, culled unseen.
fn part(mesh: Mesh, color: Color, transform: Transform) -> Mesh {
    let mut mesh = mesh.with_duplicated_vertices().transformed_by(transform);
    mesh.remove_attribute(Mesh::ATTRIBUTE_UV_0);
    mesh.remove_attribute(Mesh::ATTRIBUTE_TANGENT);
    mesh.compute_flat_normals();
    if let (Some(VertexAttributeValues::Float32x3(p)), Some(VertexAttributeValues::Float32x3(n))) =
        (mesh.attribute(Mesh::ATTRIBUTE_POSITION), mesh.attribute(Mesh::ATTRIBUTE_NORMAL))
    {
        // Flat normals: each triangle's three vertices share its normal.
        let keep: Vec<bool> = n.chunks_exact(3).map(|t| t[0][1] > -0.99).collect();
        let kept = |v: &[[f32; 3]]| -> Vec<[f32; 3]> {
            v.chunks_exact(3).zip(&keep).filter(|(_, k)| **k).flat_map(|(t, _)| t.iter().copied()).collect()
        };
        let (p, n) = (kept(p), kept(n));
        mesh.insert_attribute(Mesh::ATTRIBUTE_POSITION, p);
        mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, n);
    }
    let n = mesh.count_vertices();
    let c = color.to_linear().to_f32_array();
    mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, vec![c; n]);
    mesh
}

/// Merges flat parts into one mesh.
fn merged(parts: Vec<Mesh>) -> Mesh {
    let mut parts = parts.into_iter();
    let mut mesh = parts.next().unwrap_or_else(|| Mesh::from(Cuboid::from_length(0.0)));
    for p in parts {
        // Every part comes from `part`: same attributes, same topology.
        if let Err(e) = mesh.merge(&p) {
            warn!("prop mesh part not merged: {e}");
        }
    }
    mesh
}

/// A small deterministic wobble in `[-1, 1]` for vertex `i` of variant `v`.
fn wobble(v: u8, i: usize, salt: u32) -> f32 {
    hex_terrain::unit(hex_terrain::hash(salt, &[i64::from(v), i as i64])) * 2.0 - 1.0
}

/// Moves each vertex of a sphere-like mesh in and out by up to `amount` of its radius.
fn lumpy(mut mesh: Mesh, v: u8, amount: f32, salt: u32) -> Mesh {
    if let Some(bevy::mesh::VertexAttributeValues::Float32x3(positions)) = mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION)
    {
        for (i, p) in positions.iter_mut().enumerate() {
            let k = 1.0 + amount * wobble(v, i, salt);
            *p = [p[0] * k, p[1] * k, p[2] * k];
        }
    }
    mesh
}

fn ico(radius: f32, subdivisions: u32) -> Mesh {
    Sphere::new(radius).mesh().ico(subdivisions).unwrap_or_else(|_| Sphere::new(radius).mesh().uv(6, 4))
}

/// A trunk: an open tube (its top is inside the crown, its foot in the ground).
fn trunk(height: f32, radius: f32) -> Mesh {
    part(
        Cylinder::new(radius, height).mesh().resolution(4).without_caps().build(),
        Color::srgb(0.36, 0.25, 0.16),
        Transform::from_xyz(0.0, height * 0.5, 0.0),
    )
}

/// A round-crowned tree: a trunk and one or two lumpy crowns.
fn broadleaf(v: u8) -> Mesh {
    let greens = [Color::srgb(0.20, 0.42, 0.13), Color::srgb(0.26, 0.47, 0.15), Color::srgb(0.17, 0.36, 0.12)];
    let green = greens[usize::from(v) % greens.len()];
    let crown = lumpy(ico(0.72, 0), v, 0.15, 11);
    let mut parts = vec![trunk(0.9, 0.12), part(crown, green, Transform::from_xyz(0.0, 1.45, 0.0))];
    if v != 0 {
        let side = lumpy(ico(0.48, 0), v, 0.15, 12);
        let x = if v == 1 { 0.4 } else { -0.35 };
        parts.push(part(side, green.darker(0.04), Transform::from_xyz(x, 1.05, 0.2)));
    }
    merged(parts)
}

/// A conifer: a trunk and stacked cones.
fn pine(v: u8) -> Mesh {
    let green = [Color::srgb(0.10, 0.30, 0.17), Color::srgb(0.13, 0.34, 0.19), Color::srgb(0.09, 0.27, 0.15)]
        [usize::from(v) % 3];
    let tiers = 2 + u32::from(v % 2);
    let mut parts = vec![trunk(0.5, 0.09)];
    for t in 0..tiers {
        let f = t as f32 / tiers as f32;
        let radius = 0.62 * (1.0 - 0.55 * f) * (1.0 + 0.08 * wobble(v, t as usize, 13));
        let height = 1.0 - 0.25 * f;
        let y = 0.4 + 0.55 * t as f32 + height * 0.5;
        parts.push(part(
            Cone::new(radius, height).mesh().resolution(6).build(),
            green,
            Transform::from_xyz(0.0, y, 0.0),
        ));
    }
    merged(parts)
}

/// A boulder: a squashed, lumpy icosahedron, half sunk.
fn rock(v: u8) -> Mesh {
    let grey = [Color::srgb(0.45, 0.43, 0.40), Color::srgb(0.52, 0.50, 0.47), Color::srgb(0.40, 0.38, 0.37)]
        [usize::from(v) % 3];
    let body = lumpy(ico(0.8, 0), v, 0.3, 21);
    let squash = Transform::from_xyz(0.0, 0.3, 0.0).with_scale(Vec3::new(1.0, 0.7 + 0.15 * f32::from(v), 0.85));
    let mut parts = vec![part(body, grey, squash)];
    if v == 2 {
        let small = lumpy(ico(0.45, 0), v, 0.3, 22);
        parts.push(part(small, grey.lighter(0.05), Transform::from_xyz(0.75, 0.15, 0.3)));
    }
    merged(parts)
}

/// A clump of reeds: thin three-sided blades leaning out.
fn reed(v: u8) -> Mesh {
    let color = Color::srgb(0.45, 0.55, 0.25);
    let blades = 5 + usize::from(v) * 2;
    let parts = (0..blades)
        .map(|i| {
            let a = std::f32::consts::TAU * i as f32 / blades as f32 + wobble(v, i, 31);
            let (x, z) = (0.25 * a.cos(), 0.25 * a.sin());
            let height = 1.4 + 0.4 * wobble(v, i, 32);
            let lean = Quat::from_rotation_z(0.2 * a.cos()) * Quat::from_rotation_x(0.2 * a.sin());
            let t = Transform::from_xyz(x, height * 0.5, z).with_rotation(lean);
            part(Cone::new(0.05, height).mesh().resolution(3).build(), color, t)
        })
        .collect();
    merged(parts)
}

/// A resource marker: a cut gem on a short stand, in its class's color (bonus green, strategic
/// rust red, luxury violet), big enough to read at a strategic zoom.
fn resource(v: u8) -> Mesh {
    let color = [Color::srgb(0.45, 0.78, 0.22), Color::srgb(0.78, 0.30, 0.18), Color::srgb(0.62, 0.32, 0.86)]
        [usize::from(v) % 3];
    let stand = part(
        Cylinder::new(0.35, 0.25).mesh().resolution(6).build(),
        Color::srgb(0.85, 0.80, 0.66),
        Transform::from_xyz(0.0, 0.12, 0.0),
    );
    let gem = part(ico(0.55, 0), color, Transform::from_xyz(0.0, 0.95, 0.0).with_scale(Vec3::new(1.0, 1.35, 1.0)));
    merged(vec![stand, gem])
}

/// A natural wonder marker: a golden obelisk on a stepped white plinth.
fn wonder() -> Mesh {
    let stone = Color::srgb(0.92, 0.90, 0.84);
    let gold = Color::srgb(0.95, 0.74, 0.22);
    merged(vec![
        part(Cuboid::new(1.3, 0.2, 1.3).mesh().build(), stone, Transform::from_xyz(0.0, 0.1, 0.0)),
        part(Cuboid::new(0.9, 0.2, 0.9).mesh().build(), stone, Transform::from_xyz(0.0, 0.3, 0.0)),
        part(Cuboid::new(0.38, 1.9, 0.38).mesh().build(), gold, Transform::from_xyz(0.0, 1.35, 0.0)),
        part(
            Cone::new(0.27, 0.45).mesh().resolution(4).build(),
            gold.lighter(0.1),
            Transform::from_xyz(0.0, 2.52, 0.0).with_rotation(Quat::from_rotation_y(std::f32::consts::FRAC_PI_4)),
        ),
    ])
}

/// The far mesh of a tree: one crown of three to six faces standing on the ground (`cone`: a
/// three-sided pyramid, else a squat double one), in the full mesh's colors.
fn far_tree(v: u8, cone: bool) -> Mesh {
    let greens = if cone {
        [Color::srgb(0.10, 0.30, 0.17), Color::srgb(0.13, 0.34, 0.19), Color::srgb(0.09, 0.27, 0.15)]
    } else {
        [Color::srgb(0.20, 0.42, 0.13), Color::srgb(0.26, 0.47, 0.15), Color::srgb(0.17, 0.36, 0.12)]
    };
    let green = greens[usize::from(v) % 3];
    if cone {
        part(Cone::new(0.6, 2.0).mesh().resolution(3).build(), green, Transform::from_xyz(0.0, 1.0, 0.0))
    } else {
        let crown = Transform::from_xyz(0.0, 1.3, 0.0).with_scale(Vec3::new(1.0, 1.1, 1.0));
        part(Sphere::new(0.8).mesh().uv(3, 2), green, crown)
    }
}

/// The far mesh of variant `v` of a prop kind, for props on chunks drawn coarse (far from every
/// camera, a few pixels tall): the same size, colors and foot as [`prop_mesh`], three to six
/// faces. Markers (resources, wonders) keep their full mesh: they must read at a strategic zoom.
#[must_use]
pub fn prop_mesh_far(kind: PropKind, v: u8) -> Mesh {
    let v = v % PROP_VARIANTS;
    match kind {
        PropKind::Broadleaf => far_tree(v, false),
        PropKind::Pine => far_tree(v, true),
        PropKind::Rock => {
            let grey = [Color::srgb(0.45, 0.43, 0.40), Color::srgb(0.52, 0.50, 0.47), Color::srgb(0.40, 0.38, 0.37)]
                [usize::from(v) % 3];
            let squash = Transform::from_xyz(0.0, 0.3, 0.0).with_scale(Vec3::new(1.0, 0.7 + 0.15 * f32::from(v), 0.85));
            part(Sphere::new(0.8).mesh().uv(3, 2), grey, squash)
        }
        PropKind::Reed => part(
            Cone::new(0.2, 1.5).mesh().resolution(3).build(),
            Color::srgb(0.45, 0.55, 0.25),
            Transform::from_xyz(0.0, 0.75, 0.0),
        ),
        PropKind::Resource | PropKind::Wonder => prop_mesh(kind, v),
    }
}

/// The mesh of variant `v` (below [`PROP_VARIANTS`]) of a prop kind.
#[must_use]
pub fn prop_mesh(kind: PropKind, v: u8) -> Mesh {
    let v = v % PROP_VARIANTS;
    match kind {
        PropKind::Broadleaf => broadleaf(v),
        PropKind::Pine => pine(v),
        PropKind::Rock => rock(v),
        PropKind::Reed => reed(v),
        PropKind::Resource => resource(v),
        PropKind::Wonder => wonder(),
    }
}
