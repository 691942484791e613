//! STL: binary through the `stl_io` crate, after size checks that turn a truncated or
//! mislabelled file into a clear message; ASCII by a small line reader with line numbers.

use std::io::Cursor;

use super::ImportError;
use crate::geom::DVec3;

const HEADER: usize = 80;
const RECORD: u64 = 50;

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    let binary_size = |n: u32| HEADER as u64 + 4 + RECORD * n as u64;
    let announced = (bytes.len() >= HEADER + 4).then(|| u32::from_le_bytes(bytes[HEADER..HEADER + 4].try_into().unwrap()));
    let looks_ascii = bytes.trim_ascii_start().starts_with(b"solid") && announced.is_none_or(|n| binary_size(n) != bytes.len() as u64);
    if looks_ascii {
        return read_ascii(bytes);
    }
    let Some(announced) = announced else {
        return Err(ImportError::StlSizeMismatch { announced: 0, expected: HEADER as u64 + 4, actual: bytes.len() as u64 });
    };
    let expected = binary_size(announced);
    if expected != bytes.len() as u64 {
        return Err(ImportError::StlSizeMismatch { announced, expected, actual: bytes.len() as u64 });
    }
    let mut cursor = Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| ImportError::Stl(e.to_string()))?;
    collect(reader)
}

/// ASCII STL: `solid`, then `facet ... outer loop, vertex x y z (three times), endloop,
/// endfacet` per triangle, then `endsolid`. Only the vertex lines carry geometry; names after
/// `solid` and several solids in one file are read. A file that ends inside a facet, or after
/// its last facet without `endsolid`, was cut short (a download or a copy that stopped): it is
/// refused with the line where it ends, never machined as half a part.
fn read_ascii(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    let text = std::str::from_utf8(bytes).map_err(|_| ImportError::Stl("the ASCII STL contains bytes that are not text".into()))?;
    // A last line without its line end, other than the closing `endsolid`, was cut.
    let last = text.trim_end_matches([' ', '\t']);
    if !last.ends_with(['\n', '\r']) {
        let line = last.lines().last().unwrap_or_default().trim();
        if !line.starts_with("endsolid") {
            let number = last.lines().count();
            return Err(ImportError::Truncated(format!("the ASCII STL ends inside line {number} ('{}'), which has no line end", line.chars().take(60).collect::<String>())));
        }
    }
    let mut triangles = Vec::new();
    let mut corners: Vec<DVec3> = Vec::with_capacity(3);
    // The line of the open facet, and of the open solid.
    let (mut facet, mut solid) = (None, None);
    let mut lines = 0;
    for (number, line) in text.lines().enumerate() {
        let number = number + 1;
        lines = number;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("solid") if facet.is_none() => solid = Some(number),
            Some("endsolid") => {
                if let Some(open) = facet {
                    return Err(ImportError::Stl(format!("line {number}: the solid ends inside the facet opened at line {open}")));
                }
                solid = None;
            }
            Some("facet") => {
                if let Some(open) = facet {
                    return Err(ImportError::Stl(format!("line {number}: a facet begins inside the facet opened at line {open}")));
                }
                facet = Some(number);
            }
            Some("vertex") => {
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    let word = words.next().ok_or_else(|| ImportError::Stl(format!("line {number}: a vertex needs three numbers")))?;
                    *c = word.parse::<f64>().map_err(|_| ImportError::Stl(format!("line {number}: '{word}' is not a number")))?;
                }
                // A fourth number is a damaged line (two run together, a point from elsewhere),
                // not one to read as its first three.
                if let Some(extra) = words.next() {
                    return Err(ImportError::Stl(format!("line {number}: a vertex has three numbers, and this one goes on with '{extra}'")));
                }
                if corners.len() == 3 {
                    return Err(ImportError::Stl(format!("line {number}: a facet has more than three vertices")));
                }
                corners.push(DVec3::from_array(xyz));
            }
            Some("endfacet") => {
                if corners.len() != 3 {
                    return Err(ImportError::Stl(format!("line {number}: a facet has {} vertices instead of three", corners.len())));
                }
                triangles.push([corners[0], corners[1], corners[2]]);
                corners.clear();
                facet = None;
            }
            _ => {}
        }
    }
    if let Some(open) = facet {
        return Err(ImportError::Truncated(format!("the ASCII STL ends at line {lines} inside the facet opened at line {open}")));
    }
    if let Some(open) = solid {
        return Err(ImportError::Truncated(format!("the ASCII STL ends at line {lines} without the endsolid that closes the solid opened at line {open}")));
    }
    Ok(triangles)
}

fn collect<'a>(reader: Box<dyn stl_io::TriangleIterator<Item = std::io::Result<stl_io::Triangle>> + 'a>) -> Result<Vec<[DVec3; 3]>, ImportError> {
    reader
        .map(|t| {
            let t = t.map_err(|e| ImportError::Stl(e.to_string()))?;
            Ok(t.vertices.map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)))
        })
        .collect()
}
