//! Wavefront OBJ through the `tobj` crate; material libraries are never loaded. Faces are
//! triangulated here ([`super::face::triangulate`]): small ones as a fan from the first corner
//! (as tobj does), large ones (a cylinder's cap of 100,000 corners) as a strip across them.

use super::face::triangulate;
use super::ImportError;
use crate::geom::DVec3;

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    check_last_line(bytes)?;
    let options = tobj::LoadOptions { triangulate: false, single_index: false, ignore_points: true, ignore_lines: true };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| Err(tobj::LoadError::OpenFileFailed)).map_err(|e| ImportError::Obj(e.to_string()))?;
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
        // Without arities every face is a triangle.
        let arities: Vec<u32> = if m.face_arities.is_empty() { vec![3; m.indices.len() / 3] } else { m.face_arities.clone() };
        let mut first = 0;
        for &n in &arities {
            let n = n as usize;
            let Some(face) = m.indices.get(first..first + n) else { return Err(ImportError::Obj(format!("a face of {n} corners runs past the file's indices"))) };
            first += n;
            for [a, b, c] in triangulate(n) {
                triangles.push([vertex(face[a])?, vertex(face[b])?, vertex(face[c])?]);
            }
        }
    }
    Ok(triangles)
}

/// A file cut short ends inside a statement, and tobj reads such a line as best it can (or
/// skips it), so the part would load with faces missing, silently. Refused here, with the line:
/// a last statement without its line end (a vertex or face cut mid-number still parses, so
/// every unterminated statement is taken as cut: a whole file ends its last line), and a face
/// naming a vertex no line before it gave (a file cut and joined, or written out of order).
fn check_last_line(bytes: &[u8]) -> Result<(), ImportError> {
    let text = String::from_utf8_lossy(bytes);
    let (mut vertices, mut textures, mut normals) = (0i64, 0i64, 0i64);
    let mut number = 0;
    for (k, line) in text.lines().enumerate() {
        number = k + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => vertices += 1,
            Some("vt") => textures += 1,
            Some("vn") => normals += 1,
            Some("f") => {
                for corner in words {
                    let mut parts = corner.split('/');
                    let Some(Ok(i)) = parts.next().map(str::parse::<i64>) else { continue };
                    if i > vertices || i == 0 || -i > vertices {
                        return Err(ImportError::Truncated(format!("the OBJ's line {number} names vertex {i}, but the {vertices} lines before it give {vertices} vertices")));
                    }
                    // A texture or normal index out of range (a relative −12 of 2) would overflow
                    // the reader's arithmetic: refused here, with the line.
                    for (what, count) in [("texture coordinate", textures), ("normal", normals)] {
                        if let Some(Ok(k)) = parts.next().filter(|p| !p.is_empty()).map(str::parse::<i64>) {
                            if k > count || k == 0 || -k > count {
                                return Err(ImportError::Obj(format!("line {number} names {what} {k}, but the lines before it give {count}")));
                            }
                        }
                    }
                }
            }
            _ => {}
        }
    }
    let trimmed = text.trim_end_matches([' ', '\t']);
    if trimmed.ends_with(['\n', '\r']) || trimmed.is_empty() {
        return Ok(()); // a complete last line
    }
    let last = trimmed.lines().last().unwrap_or("").trim();
    if matches!(last.split_whitespace().next(), Some("v" | "f" | "vn" | "vt" | "l" | "p")) {
        return Err(ImportError::Truncated(format!("the OBJ ends inside line {number} ('{}'), which has no line end", last.chars().take(60).collect::<String>())));
    }
    Ok(())
}
