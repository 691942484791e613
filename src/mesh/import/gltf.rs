//! glTF 2.0 (`.gltf` JSON with embedded `data:` URIs, and binary `.glb`). The document is read
//! into the `gltf` crate's JSON schema types (`gltf::json::Root`) with serde, and walked here
//! with a checked look-up at every reference: the crate's own loader validates with unchecked
//! indexing (a primitive naming a missing accessor panics, and in wasm a panic ends the page's
//! worker), so it is not used. Buffers come only from the GLB chunk or data URIs; an external
//! URI is refused and never fetched. Node transforms of the default scene are applied.

use base64::Engine;
use glam::{DMat4, DQuat, DVec3 as V3, Mat4};
use gltf::json::{self, accessor::ComponentType, accessor::Type, mesh::Mode, mesh::Semantic, validation::Checked};

use super::face::{fan_polygon, triangulate, FAN_MOST};
use super::ImportError;
use crate::geom::DVec3;

fn broken<T>(what: impl Into<String>) -> Result<T, ImportError> {
    Err(ImportError::Gltf(what.into()))
}

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    let (json_bytes, blob) = if bytes.starts_with(b"glTF") { split_glb(bytes)? } else { (bytes, None) };
    let root: json::Root = serde_json::from_slice(json_bytes).map_err(|e| {
        if e.is_eof() {
            ImportError::Truncated(format!("the glTF's JSON ends at line {}, column {}, before it is closed", e.line(), e.column()))
        } else {
            ImportError::Gltf(e.to_string())
        }
    })?;
    let buffers = load_buffers(&root, blob)?;
    let document = Document { root: &root, buffers, placed: std::cell::Cell::new(0) };
    let mut triangles = Vec::new();
    let scene = root.scene.map(|s| s.value()).or((!root.scenes.is_empty()).then_some(0));
    match scene {
        Some(index) => {
            let Some(scene) = root.scenes.get(index) else { return broken(format!("scene {index} does not exist")) };
            for node in &scene.nodes {
                document.visit(node.value(), DMat4::IDENTITY, &mut triangles, 0)?;
            }
        }
        // No scene: every mesh, untransformed.
        None => {
            for mesh in 0..root.meshes.len() {
                document.mesh(mesh, DMat4::IDENTITY, &mut triangles)?;
            }
        }
    }
    Ok(triangles)
}

/// Splits a GLB into its JSON chunk and its binary chunk, checking every length first.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), ImportError> {
    let word = |at: usize| bytes.get(at..at + 4).map(|w| u32::from_le_bytes(w.try_into().unwrap()) as usize);
    let (Some(version), Some(total)) = (word(4), word(8)) else { return broken("the GLB's header is cut short") };
    if version != 2 {
        return broken(format!("the GLB is version {version}, expected 2"));
    }
    if total > bytes.len() {
        return Err(ImportError::Truncated(format!("the GLB's header says {total} bytes, the file has {}", bytes.len())));
    }
    if total != bytes.len() {
        return broken(format!("the GLB's header says {total} bytes, the file has {}", bytes.len()));
    }
    let mut chunks = Vec::new();
    let mut at = 12;
    while at < total {
        let (Some(length), Some(kind)) = (word(at), bytes.get(at + 4..at + 8)) else { return broken("a GLB chunk header is cut short") };
        let Some(end) = (at + 8).checked_add(length).filter(|&end| end <= total) else { return broken("a GLB chunk runs past the end of the file") };
        chunks.push((kind, &bytes[at + 8..end]));
        at = end;
    }
    match chunks.as_slice() {
        [(b"JSON", json), rest @ ..] => Ok((json, rest.iter().find(|(kind, _)| *kind == b"BIN\0").map(|(_, b)| *b))),
        _ => broken("the GLB does not start with a JSON chunk"),
    }
}

fn load_buffers(root: &json::Root, blob: Option<&[u8]>) -> Result<Vec<Vec<u8>>, ImportError> {
    root.buffers
        .iter()
        .enumerate()
        .map(|(k, buffer)| {
            let data = match (&buffer.uri, blob) {
                (Some(uri), _) => decode_data_uri(uri)?,
                (None, Some(blob)) if k == 0 => blob.to_vec(),
                (None, _) => return broken(format!("buffer {k} has no data (no URI and no GLB binary chunk)")),
            };
            if (data.len() as u64) < buffer.byte_length.0 {
                return Err(ImportError::Truncated(format!("the glTF's buffer {k} should hold {} bytes but has {}", buffer.byte_length.0, data.len())));
            }
            Ok(data)
        })
        .collect()
}

fn decode_data_uri(uri: &str) -> Result<Vec<u8>, ImportError> {
    let Some(rest) = uri.strip_prefix("data:") else {
        return Err(ImportError::ExternalUri(uri.chars().take(200).collect()));
    };
    let Some((_, payload)) = rest.split_once(";base64,") else { return broken("a data URI is not base64-encoded") };
    base64::engine::general_purpose::STANDARD.decode(payload.trim()).map_err(|e| ImportError::Gltf(format!("a data URI is not valid base64: {e}")))
}

const MAX_DEPTH: usize = 64;

/// The most node instances a scene may place: a node listed as a child of several others is
/// placed once for each path to it, and 20 nodes each listing the next twice place 2^20 (the
/// read once asked 5.4 GB). A real assembly places a few thousand.
const MAX_INSTANCES: usize = 100_000;

struct Document<'a> {
    root: &'a json::Root,
    buffers: Vec<Vec<u8>>,
    /// Node instances placed so far.
    placed: std::cell::Cell<usize>,
}

impl Document<'_> {
    fn visit(&self, index: usize, parent: DMat4, out: &mut Vec<[DVec3; 3]>, depth: usize) -> Result<(), ImportError> {
        if depth > MAX_DEPTH {
            return broken("the node hierarchy is deeper than 64 levels (a cycle?)");
        }
        self.placed.set(self.placed.get() + 1);
        if self.placed.get() > MAX_INSTANCES {
            return broken(format!("the scene places its nodes more than {MAX_INSTANCES} times (nodes listed as children of several others, over and over)"));
        }
        let Some(node) = self.root.nodes.get(index) else { return broken(format!("node {index} does not exist")) };
        let local = match node.matrix {
            Some(m) => Mat4::from_cols_array(&m).as_dmat4(),
            None => {
                let t = node.translation.map_or(V3::ZERO, |t| V3::new(t[0] as f64, t[1] as f64, t[2] as f64));
                let r = node.rotation.map_or(DQuat::IDENTITY, |q| DQuat::from_xyzw(q.0[0] as f64, q.0[1] as f64, q.0[2] as f64, q.0[3] as f64).normalize());
                let s = node.scale.map_or(V3::ONE, |s| V3::new(s[0] as f64, s[1] as f64, s[2] as f64));
                DMat4::from_scale_rotation_translation(s, r, t)
            }
        };
        let world = parent * local;
        if let Some(mesh) = node.mesh {
            self.mesh(mesh.value(), world, out)?;
        }
        for child in node.children.iter().flatten() {
            self.visit(child.value(), world, out, depth + 1)?;
        }
        Ok(())
    }

    fn mesh(&self, index: usize, transform: DMat4, out: &mut Vec<[DVec3; 3]>) -> Result<(), ImportError> {
        let Some(mesh) = self.root.meshes.get(index) else { return broken(format!("mesh {index} does not exist")) };
        for primitive in &mesh.primitives {
            let mode = match primitive.mode {
                Checked::Valid(m) => m,
                Checked::Invalid => return broken("a primitive has an unknown mode"),
            };
            if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
                continue; // points and lines carry no surface
            }
            let Some(position) = primitive.attributes.get(&Checked::Valid(Semantic::Positions)) else { continue };
            let positions: Vec<DVec3> = self.read_accessor(position.value(), Type::Vec3)?.chunks_exact(3).map(|p| transform.transform_point3(V3::new(p[0], p[1], p[2]))).collect();
            let indices: Vec<usize> = match primitive.indices {
                Some(i) => self.read_accessor(i.value(), Type::Scalar)?.into_iter().map(|v| v as usize).collect(),
                None => (0..positions.len()).collect(),
            };
            if let Some(bad) = indices.iter().find(|&&i| i >= positions.len()) {
                return broken(format!("index {bad} points past the {} vertices", positions.len()));
            }
            let corner = |i: usize| positions[i];
            match mode {
                Mode::Triangles => out.extend(indices.chunks_exact(3).map(|c| [corner(c[0]), corner(c[1]), corner(c[2])])),
                Mode::TriangleStrip => {
                    out.extend(indices.windows(3).enumerate().map(|(k, w)| if k % 2 == 0 { [corner(w[0]), corner(w[1]), corner(w[2])] } else { [corner(w[1]), corner(w[0]), corner(w[2])] }))
                }
                _ => {
                    // A large fan over a flat convex polygon is that polygon: cut as a strip
                    // (see `face`); any other fan is kept as the file gives it. A small one is
                    // kept without looking.
                    let ring: Vec<DVec3> = indices.iter().map(|&i| corner(i)).collect();
                    let polygon = if ring.len() > FAN_MOST { fan_polygon(&ring).filter(|p| p.len() > FAN_MOST) } else { None };
                    if let Some(polygon) = polygon {
                        out.extend(triangulate(polygon.len()).into_iter().map(|[a, b, c]| [polygon[a], polygon[b], polygon[c]]));
                    } else if let Some((&first, rest)) = ring.split_first() {
                        out.extend(rest.windows(2).map(|w| [first, w[0], w[1]]));
                    }
                }
            }
        }
        Ok(())
    }

    /// An accessor's values as f64 (components flattened), after checking its type and that its
    /// bytes lie inside its view and buffer.
    fn read_accessor(&self, index: usize, expected: Type) -> Result<Vec<f64>, ImportError> {
        let Some(accessor) = self.root.accessors.get(index) else { return broken(format!("accessor {index} does not exist")) };
        if accessor.sparse.is_some() {
            return broken("sparse accessors are not supported");
        }
        let (Checked::Valid(kind), Checked::Valid(component)) = (accessor.type_, accessor.component_type) else {
            return broken(format!("accessor {index} has an unknown type"));
        };
        let component = component.0;
        let fits = match expected {
            Type::Vec3 => kind == Type::Vec3 && component == ComponentType::F32,
            _ => kind == Type::Scalar && matches!(component, ComponentType::U8 | ComponentType::U16 | ComponentType::U32),
        };
        if !fits {
            return broken(format!("accessor {index} is {kind:?} of {component:?}, which swarf does not read there"));
        }
        let Some(view_index) = accessor.buffer_view else { return broken(format!("accessor {index} has no buffer view")) };
        let Some(view) = self.root.buffer_views.get(view_index.value()) else { return broken(format!("buffer view {} does not exist", view_index.value())) };
        let Some(buffer) = self.buffers.get(view.buffer.value()) else { return broken(format!("buffer {} does not exist", view.buffer.value())) };
        let view_start = view.byte_offset.map_or(0, |o| o.0) as usize;
        let view_len = view.byte_length.0 as usize;
        let Some(view_bytes) = view_start.checked_add(view_len).and_then(|end| buffer.get(view_start..end)) else {
            return broken(format!("buffer view {} runs past the end of its buffer", view_index.value()));
        };
        let components = if kind == Type::Vec3 { 3 } else { 1 };
        let size = match component {
            ComponentType::U8 | ComponentType::I8 => 1,
            ComponentType::U16 | ComponentType::I16 => 2,
            _ => 4,
        };
        let element = components * size;
        let stride = view.byte_stride.map_or(element, |s| s.0);
        let count = accessor.count.0 as usize;
        let offset = accessor.byte_offset.map_or(0, |o| o.0) as usize;
        let needed = match count {
            0 => Some(0),
            n => (n - 1).checked_mul(stride).and_then(|s| s.checked_add(element)).and_then(|s| s.checked_add(offset)),
        };
        if stride < element || needed.is_none_or(|n| n > view_bytes.len()) {
            return broken(format!("accessor {index} runs past the end of its buffer view"));
        }
        let mut values = Vec::with_capacity(count * components);
        for k in 0..count {
            let base = offset + k * stride;
            for c in 0..components {
                let b = &view_bytes[base + c * size..base + (c + 1) * size];
                values.push(match component {
                    ComponentType::F32 => f32::from_le_bytes(b.try_into().unwrap()) as f64,
                    ComponentType::U32 => u32::from_le_bytes(b.try_into().unwrap()) as f64,
                    ComponentType::U16 => u16::from_le_bytes(b.try_into().unwrap()) as f64,
                    _ => b[0] as f64,
                });
            }
        }
        Ok(values)
    }
}
