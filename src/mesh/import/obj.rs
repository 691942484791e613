//! Wavefront OBJ through the `tobj` crate, triangulated; material libraries are never loaded.

use super::ImportError;
use crate::geom::DVec3;

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    let options = tobj::LoadOptions { triangulate: true, single_index: false, ignore_points: true, ignore_lines: true };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| Err(tobj::LoadError::OpenFileFailed))
        .map_err(|e| ImportError::Obj(e.to_string()))?;
    let mut triangles = Vec::new();
    for model in models {
        let m = model.mesh;
        let vertex = |i: u32| -> Result<DVec3, ImportError> {
            let i = i as usize * 3;
            m.positions
                .get(i..i + 3)
                .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
                .ok_or_else(|| ImportError::Obj(format!("face refers to vertex {} of {}", i / 3 + 1, m.positions.len() / 3)))
        };
        for c in m.indices.chunks_exact(3) {
            triangles.push([vertex(c[0])?, vertex(c[1])?, vertex(c[2])?]);
        }
    }
    Ok(triangles)
}
