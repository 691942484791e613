//! Reading parts from bytes: binary and ASCII STL, glTF 2.0 (`.gltf` with embedded data URIs,
//! and `.glb`), Wavefront OBJ. Nothing is ever fetched: a glTF that points at an external URI
//! is refused.

mod face;
mod gltf;
mod obj;
mod stl;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::Mesh;
use crate::geom::Tolerances;

/// What can be wrong with a part file. Messages are written for the person who dropped it.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ImportError {
    #[error("the file is empty")]
    Empty,
    #[error("the file is not a part swarf can read (expected STL, glTF/GLB or OBJ)")]
    UnknownFormat,
    /// A file of another kind, known by its first bytes ([`crate::file_kind::Foreign`]).
    #[error("the file is {}, not a part swarf reads (STL, glTF/GLB or OBJ): {}", .0.describe(), .0.for_a_part())]
    Foreign(crate::file_kind::Foreign),
    /// A drawing given where a part is asked for.
    #[error("the file is {0} drawing, not a 3D part: open it as a drawing (its loops are cut by the 2D operations), or give a part as STL, glTF/GLB or OBJ")]
    Drawing(&'static str),
    #[error("the binary STL is truncated: it announces {announced} triangles ({expected} bytes) but has {actual} bytes")]
    StlSizeMismatch { announced: u32, expected: u64, actual: u64 },
    #[error("the STL file is broken: {0}")]
    Stl(String),
    /// The file stops before its format says it ends: a download or a copy cut short.
    #[error("{0}: the file was cut short (a download or a copy that stopped?); open the whole file")]
    Truncated(String),
    #[error("the glTF file is broken: {0}")]
    Gltf(String),
    #[error("the glTF file refers to an external file '{0}'; swarf never fetches anything: embed the data (data URI) or use a .glb")]
    ExternalUri(String),
    #[error("the OBJ file is broken: {0}")]
    Obj(String),
    #[error("triangle {triangle} has a coordinate that is not a finite number ({value})")]
    NonFinite { triangle: usize, value: String },
    #[error("triangle {triangle} has a coordinate of {value}, out of range for any part (more than 10 km from the origin): a number damaged in the file?")]
    OutOfRange { triangle: usize, value: String },
    #[error("the file has no triangles")]
    NoTriangles,
    #[error("all {count} triangles of the file are degenerate (zero area)")]
    AllDegenerate { count: usize },
}

/// File formats swarf reads parts from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum MeshFormat {
    Stl,
    Gltf,
    Glb,
    Obj,
}

impl MeshFormat {
    /// Guesses the format from the file name's extension, then from the content.
    pub fn detect(name: Option<&str>, bytes: &[u8]) -> Option<MeshFormat> {
        let ext = crate::file_kind::extension(name);
        match ext.as_deref() {
            Some("stl") => return Some(MeshFormat::Stl),
            Some("gltf") => return Some(MeshFormat::Gltf),
            Some("glb") => return Some(MeshFormat::Glb),
            Some("obj") => return Some(MeshFormat::Obj),
            _ => {}
        }
        if bytes.starts_with(b"glTF") {
            return Some(MeshFormat::Glb);
        }
        let head = String::from_utf8_lossy(&bytes[..bytes.len().min(512)]);
        let trimmed = head.trim_start();
        if trimmed.starts_with('{') {
            Some(MeshFormat::Gltf)
        } else if trimmed.starts_with("solid") || bytes.len() >= 84 {
            if trimmed.starts_with("v ") || trimmed.starts_with('#') && head.contains("\nv ") {
                Some(MeshFormat::Obj)
            } else {
                Some(MeshFormat::Stl)
            }
        } else if head.lines().any(|l| l.starts_with("v ") || l.starts_with("f ")) {
            Some(MeshFormat::Obj)
        } else {
            None
        }
    }
}

/// Reads a mesh in the file's own units and axes (see [`super::placement`] for those).
pub fn read_mesh(bytes: &[u8], format: MeshFormat, tolerances: &Tolerances) -> Result<Mesh, ImportError> {
    if bytes.is_empty() {
        return Err(ImportError::Empty);
    }
    let triangles = match format {
        MeshFormat::Stl => stl::read(bytes)?,
        MeshFormat::Gltf | MeshFormat::Glb => gltf::read(bytes)?,
        MeshFormat::Obj => obj::read(bytes)?,
    };
    let mut mesh = Mesh::from_triangles(triangles, tolerances)?;
    mesh.in_metres = matches!(format, MeshFormat::Gltf | MeshFormat::Glb);
    Ok(mesh)
}

/// Reads a mesh, detecting its format from `name` and the bytes.
pub fn read_mesh_auto(bytes: &[u8], name: Option<&str>, tolerances: &Tolerances) -> Result<Mesh, ImportError> {
    if bytes.is_empty() {
        return Err(ImportError::Empty);
    }
    if let Some(kind) = crate::file_kind::Foreign::of(name, bytes) {
        return Err(ImportError::Foreign(kind));
    }
    let ext = crate::file_kind::extension(name);
    match ext.as_deref() {
        Some("dxf") => return Err(ImportError::Drawing("a DXF")),
        Some("svg") => return Err(ImportError::Drawing("an SVG")),
        _ => {}
    }
    let format = MeshFormat::detect(name, bytes).ok_or(ImportError::UnknownFormat)?;
    read_mesh(bytes, format, tolerances)
}
