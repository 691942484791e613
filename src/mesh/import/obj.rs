//! Wavefront OBJ through the `tobj` crate, triangulated; material libraries are never loaded.

use super::ImportError;
use crate::geom::DVec3;

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    check_last_line(bytes)?;
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

/// A file cut short usually ends inside a statement: a vertex with fewer than three numbers, a
/// face with fewer than three corners, or a corner cut after its slash. tobj reads such a line
/// as best it can (or skips it), so the part would load with faces missing, silently.
fn check_last_line(bytes: &[u8]) -> Result<(), ImportError> {
    let text = String::from_utf8_lossy(bytes);
    let trimmed = text.trim_end_matches(['\r', '\n', ' ', '\t']);
    if trimmed.len() < text.len() && text.ends_with('\n') {
        return Ok(()); // a complete last line
    }
    let number = trimmed.lines().count();
    let last = trimmed.lines().last().unwrap_or("").trim();
    let mut words = last.split_whitespace();
    let incomplete = match words.next() {
        Some("v") => {
            let numbers: Vec<&str> = words.collect();
            numbers.len() < 3 || numbers.iter().any(|w| w.parse::<f64>().is_err())
        }
        Some("f") => {
            let corners: Vec<&str> = words.collect();
            corners.len() < 3 || corners.iter().any(|c| c.ends_with('/') || c.split('/').next().is_none_or(|i| i.parse::<i64>().is_err()))
        }
        _ => false,
    };
    if incomplete {
        return Err(ImportError::Obj(format!("the file ends early, inside line {number} ('{last}'): it was cut short")));
    }
    Ok(())
}
