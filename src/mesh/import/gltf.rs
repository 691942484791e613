//! glTF 2.0 (`.gltf` JSON with embedded `data:` URIs, and binary `.glb`) through the `gltf`
//! crate's document model. Buffers come only from the GLB chunk or data URIs; an external URI
//! is refused and never fetched. Node transforms of the default scene are applied. Accessor
//! ranges are checked here before reading so that a lying file gives an error, not a panic.

use base64::Engine;
use glam::{DMat4, Mat4};

use super::ImportError;
use crate::geom::DVec3;

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    if bytes.starts_with(b"glTF") {
        check_glb(bytes)?;
    }
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| ImportError::Gltf(e.to_string()))?;
    let buffers = load_buffers(&gltf)?;
    let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
    let mut triangles = Vec::new();
    match scene {
        Some(scene) => {
            for node in scene.nodes() {
                visit(&node, DMat4::IDENTITY, &buffers, &mut triangles, 0)?;
            }
        }
        // No scene: take every mesh untransformed.
        None => {
            for mesh in gltf.meshes() {
                read_mesh(&mesh, DMat4::IDENTITY, &buffers, &mut triangles)?;
            }
        }
    }
    Ok(triangles)
}

/// Checks a GLB container's header and chunk lengths against the bytes (the `gltf` crate trusts
/// them, and a lying length makes it fail badly).
fn check_glb(bytes: &[u8]) -> Result<(), ImportError> {
    let word = |at: usize| bytes.get(at..at + 4).map(|w| u32::from_le_bytes(w.try_into().unwrap()) as usize);
    let broken = |what: &str| Err(ImportError::Gltf(format!("the GLB is broken: {what}")));
    let (Some(version), Some(total)) = (word(4), word(8)) else { return broken("its header is cut short") };
    if version != 2 {
        return broken(&format!("version {version}, expected 2"));
    }
    if total != bytes.len() {
        return broken(&format!("its header says {total} bytes, the file has {}", bytes.len()));
    }
    let mut at = 12;
    let mut chunks = 0;
    while at < total {
        let Some(length) = word(at) else { return broken("a chunk header is cut short") };
        let end = at.checked_add(8).and_then(|a| a.checked_add(length));
        if end.map_or(true, |end| end > total) {
            return broken("a chunk runs past the end of the file");
        }
        at = end.unwrap();
        chunks += 1;
    }
    if chunks == 0 {
        return broken("it has no JSON chunk");
    }
    Ok(())
}

fn load_buffers(gltf: &gltf::Gltf) -> Result<Vec<Vec<u8>>, ImportError> {
    gltf.buffers()
        .map(|buffer| {
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => gltf
                    .blob
                    .clone()
                    .ok_or_else(|| ImportError::Gltf("the GLB has no binary chunk for buffer 0".into()))?,
                gltf::buffer::Source::Uri(uri) => decode_data_uri(uri)?,
            };
            if data.len() < buffer.length() {
                return Err(ImportError::Gltf(format!(
                    "buffer {} should hold {} bytes but has {}",
                    buffer.index(),
                    buffer.length(),
                    data.len()
                )));
            }
            Ok(data)
        })
        .collect()
}

fn decode_data_uri(uri: &str) -> Result<Vec<u8>, ImportError> {
    let Some(rest) = uri.strip_prefix("data:") else {
        return Err(ImportError::ExternalUri(uri.chars().take(200).collect()));
    };
    let Some((_, payload)) = rest.split_once(";base64,") else {
        return Err(ImportError::Gltf("a data URI is not base64-encoded".into()));
    };
    base64::engine::general_purpose::STANDARD
        .decode(payload.trim())
        .map_err(|e| ImportError::Gltf(format!("a data URI is not valid base64: {e}")))
}

const MAX_DEPTH: usize = 64;

fn visit(node: &gltf::Node, parent: DMat4, buffers: &[Vec<u8>], out: &mut Vec<[DVec3; 3]>, depth: usize) -> Result<(), ImportError> {
    if depth > MAX_DEPTH {
        return Err(ImportError::Gltf("the node hierarchy is deeper than 64 levels (a cycle?)".into()));
    }
    let local = Mat4::from_cols_array_2d(&node.transform().matrix()).as_dmat4();
    let world = parent * local;
    if let Some(mesh) = node.mesh() {
        read_mesh(&mesh, world, buffers, out)?;
    }
    for child in node.children() {
        visit(&child, world, buffers, out, depth + 1)?;
    }
    Ok(())
}

fn read_mesh(mesh: &gltf::Mesh, transform: DMat4, buffers: &[Vec<u8>], out: &mut Vec<[DVec3; 3]>) -> Result<(), ImportError> {
    use gltf::mesh::Mode;
    for primitive in mesh.primitives() {
        let mode = primitive.mode();
        if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            continue; // points and lines carry no surface
        }
        let Some(position) = primitive.get(&gltf::Semantic::Positions) else { continue };
        check_accessor(&position, buffers)?;
        if let Some(indices) = primitive.indices() {
            check_accessor(&indices, buffers)?;
        }
        let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
        let positions: Vec<DVec3> = reader
            .read_positions()
            .ok_or_else(|| ImportError::Gltf("a primitive's positions cannot be read".into()))?
            .map(|p| transform.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)))
            .collect();
        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        if let Some(bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(ImportError::Gltf(format!("index {bad} points past the {} vertices", positions.len())));
        }
        let corner = |i: u32| positions[i as usize];
        match mode {
            Mode::Triangles => {
                out.extend(indices.chunks_exact(3).map(|c| [corner(c[0]), corner(c[1]), corner(c[2])]));
            }
            Mode::TriangleStrip => out.extend(indices.windows(3).enumerate().map(|(k, w)| {
                if k % 2 == 0 { [corner(w[0]), corner(w[1]), corner(w[2])] } else { [corner(w[1]), corner(w[0]), corner(w[2])] }
            })),
            _ => {
                if let Some((&first, rest)) = indices.split_first() {
                    out.extend(rest.windows(2).map(|w| [corner(first), corner(w[0]), corner(w[1])]));
                }
            }
        }
    }
    Ok(())
}

/// Checks that an accessor's bytes lie inside its buffer view and the view inside its buffer.
fn check_accessor(accessor: &gltf::Accessor, buffers: &[Vec<u8>]) -> Result<(), ImportError> {
    if accessor.sparse().is_some() {
        return Err(ImportError::Gltf("sparse accessors are not supported".into()));
    }
    let Some(view) = accessor.view() else {
        return Err(ImportError::Gltf(format!("accessor {} has no buffer view", accessor.index())));
    };
    let buffer_len = buffers.get(view.buffer().index()).map_or(0, |b| b.len());
    let view_end = view.offset().checked_add(view.length());
    if view_end.map_or(true, |end| end > buffer_len) {
        return Err(ImportError::Gltf(format!("buffer view {} runs past the end of its buffer", view.index())));
    }
    let element = accessor.size();
    let stride = view.stride().unwrap_or(element);
    let needed = match accessor.count() {
        0 => Some(0),
        n => (n - 1).checked_mul(stride).and_then(|s| s.checked_add(element)).and_then(|s| s.checked_add(accessor.offset())),
    };
    if needed.map_or(true, |n| n > view.length()) || stride < element {
        return Err(ImportError::Gltf(format!("accessor {} runs past the end of its buffer view", accessor.index())));
    }
    Ok(())
}
