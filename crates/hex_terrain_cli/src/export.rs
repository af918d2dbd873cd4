//! Mesh export: glTF binary (through `gltf-json`) and Wavefront OBJ.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

use gltf_json as json;
use hex_terrain::ChunkMesh;
use json::validation::Checked::Valid;
use json::validation::USize64;

use crate::CliResult;

/// Name of the custom vertex attribute: `[tile kind, distance to the tile center]`.
pub const TILE_ATTRIBUTE: &str = "TILE";

fn push_f32s(bin: &mut Vec<u8>, values: impl Iterator<Item = f32>) -> (usize, usize) {
    let start = bin.len();
    for v in values {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    (start, bin.len() - start)
}

/// The glTF document and binary buffer of a mesh.
fn document(mesh: &ChunkMesh) -> CliResult<(json::Root, Vec<u8>)> {
    let b = &mesh.buffers;
    let count = b.vertex_count();
    let mut bin = Vec::new();
    let views = [
        push_f32s(&mut bin, b.positions.iter().flatten().copied()),
        push_f32s(&mut bin, b.normals.iter().flatten().copied()),
        push_f32s(&mut bin, b.uvs.iter().flatten().copied()),
        push_f32s(&mut bin, b.tile_kinds.iter().zip(&b.center_distances).flat_map(|(&k, &d)| [k as f32, d])),
    ];
    let index_start = bin.len();
    for i in &b.indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let index_len = bin.len() - index_start;

    let mut root = json::Root::default();
    root.asset.generator = Some(format!("hexterrain {}", env!("CARGO_PKG_VERSION")));
    let buffer = root.push(json::Buffer {
        byte_length: USize64::from(bin.len()),
        extensions: None,
        extras: Default::default(),
        name: None,
        uri: None,
    });
    let view = |root: &mut json::Root, (offset, len): (usize, usize), stride: Option<usize>, target| {
        root.push(json::buffer::View {
            buffer,
            byte_length: USize64::from(len),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: stride.map(json::buffer::Stride),
            extensions: None,
            extras: Default::default(),
            name: None,
            target: Some(Valid(target)),
        })
    };
    let (mut min, mut max) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in &b.positions {
        for c in 0..3 {
            min[c] = min[c].min(p[c]);
            max[c] = max[c].max(p[c]);
        }
    }
    let kinds = [
        (3, json::accessor::Type::Vec3),
        (3, json::accessor::Type::Vec3),
        (2, json::accessor::Type::Vec2),
        (2, json::accessor::Type::Vec2),
    ];
    let mut accessors = Vec::new();
    for (k, (&range, (width, ty))) in views.iter().zip(kinds).enumerate() {
        let v = view(&mut root, range, Some(width * 4), json::buffer::Target::ArrayBuffer);
        let bounds = k == 0 && count > 0;
        accessors.push(root.push(json::Accessor {
            buffer_view: Some(v),
            byte_offset: Some(USize64(0)),
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(json::accessor::ComponentType::F32)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(ty),
            min: bounds.then(|| json::Value::from(min.to_vec())),
            max: bounds.then(|| json::Value::from(max.to_vec())),
            name: None,
            normalized: false,
            sparse: None,
        }));
    }
    let iv = view(&mut root, (index_start, index_len), None, json::buffer::Target::ElementArrayBuffer);
    let indices = root.push(json::Accessor {
        buffer_view: Some(iv),
        byte_offset: Some(USize64(0)),
        count: USize64::from(b.indices.len()),
        component_type: Valid(json::accessor::GenericComponentType(json::accessor::ComponentType::U32)),
        extensions: None,
        extras: Default::default(),
        type_: Valid(json::accessor::Type::Scalar),
        min: None,
        max: None,
        name: None,
        normalized: false,
        sparse: None,
    });
    let attributes = BTreeMap::from([
        (Valid(json::mesh::Semantic::Positions), accessors[0]),
        (Valid(json::mesh::Semantic::Normals), accessors[1]),
        (Valid(json::mesh::Semantic::TexCoords(0)), accessors[2]),
        (Valid(json::mesh::Semantic::Extras(TILE_ATTRIBUTE.into())), accessors[3]),
    ]);
    let primitive = json::mesh::Primitive {
        attributes,
        extensions: None,
        extras: Default::default(),
        indices: Some(indices),
        material: None,
        mode: Valid(json::mesh::Mode::Triangles),
        targets: None,
    };
    let mesh_index = root.push(json::Mesh {
        extensions: None,
        extras: Default::default(),
        name: Some("hex terrain".into()),
        primitives: vec![primitive],
        weights: None,
    });
    let node = root.push(json::Node { mesh: Some(mesh_index), ..Default::default() });
    let scene = root.push(json::Scene { extensions: None, extras: Default::default(), name: None, nodes: vec![node] });
    root.scene = Some(scene);
    Ok((root, bin))
}

/// Writes a glTF binary (GLB) file.
///
/// # Errors
/// When the file cannot be written or the mesh is too large for one GLB (4 GiB).
pub fn write_glb(mesh: &ChunkMesh, path: &Path) -> CliResult<()> {
    let (root, mut bin) = document(mesh)?;
    let mut json = root.to_vec().map_err(|e| format!("glTF serialisation: {e}"))?;
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let total = u32::try_from(total).map_err(|_| "the mesh is too large for one GLB file (4 GiB)".to_string())?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2_u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    std::fs::write(path, out).map_err(|e| format!("{}: {e}", path.display()))
}

/// Writes a Wavefront OBJ file (positions, UVs, normals, faces).
///
/// # Errors
/// When the file cannot be written.
pub fn write_obj(mesh: &ChunkMesh, path: &Path) -> CliResult<()> {
    let b = &mesh.buffers;
    let file = std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut w = std::io::BufWriter::new(file);
    let io = |e: std::io::Error| format!("{}: {e}", path.display());
    writeln!(
        w,
        "# hexterrain {}: {} vertices, {} triangles",
        env!("CARGO_PKG_VERSION"),
        b.vertex_count(),
        b.triangle_count()
    )
    .map_err(io)?;
    for p in &b.positions {
        writeln!(w, "v {} {} {}", p[0], p[1], p[2]).map_err(io)?;
    }
    for t in &b.uvs {
        writeln!(w, "vt {} {}", t[0], t[1]).map_err(io)?;
    }
    for n in &b.normals {
        writeln!(w, "vn {} {} {}", n[0], n[1], n[2]).map_err(io)?;
    }
    for f in b.indices.chunks_exact(3) {
        let [a, b2, c] = [f[0] + 1, f[1] + 1, f[2] + 1];
        writeln!(w, "f {a}/{a}/{a} {b2}/{b2}/{b2} {c}/{c}/{c}").map_err(io)?;
    }
    w.flush().map_err(io)
}
