//! STL: binary through the `stl_io` crate, after size checks that turn a truncated or
//! mislabelled file into a clear message; ASCII by a small line reader with line numbers.

use std::io::Cursor;

use super::ImportError;
use crate::geom::DVec3;

const HEADER: usize = 80;
const RECORD: u64 = 50;

pub(super) fn read(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    let binary_size = |n: u32| HEADER as u64 + 4 + RECORD * n as u64;
    let announced = (bytes.len() >= HEADER + 4)
        .then(|| u32::from_le_bytes(bytes[HEADER..HEADER + 4].try_into().unwrap()));
    let looks_ascii = bytes.trim_ascii_start().starts_with(b"solid")
        && announced.map_or(true, |n| binary_size(n) != bytes.len() as u64);
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

/// ASCII STL: `facet ... outer loop, vertex x y z (three times), endloop, endfacet`. Only the
/// vertex lines carry geometry; the rest is checked loosely, as real files vary (names after
/// `solid`, missing `endsolid`, several solids in one file).
fn read_ascii(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    let text = std::str::from_utf8(bytes).map_err(|_| ImportError::Stl("the ASCII STL contains bytes that are not text".into()))?;
    let mut triangles = Vec::new();
    let mut corners: Vec<DVec3> = Vec::with_capacity(3);
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vertex") => {
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    let word = words.next().ok_or_else(|| ImportError::Stl(format!("line {}: a vertex needs three numbers", number + 1)))?;
                    *c = word.parse::<f64>().map_err(|_| ImportError::Stl(format!("line {}: '{word}' is not a number", number + 1)))?;
                }
                if corners.len() == 3 {
                    return Err(ImportError::Stl(format!("line {}: a facet has more than three vertices", number + 1)));
                }
                corners.push(DVec3::from_array(xyz));
            }
            Some("endloop") | Some("endfacet") if !corners.is_empty() => {
                if corners.len() != 3 {
                    return Err(ImportError::Stl(format!("line {}: a facet has {} vertices instead of three", number + 1, corners.len())));
                }
                triangles.push([corners[0], corners[1], corners[2]]);
                corners.clear();
            }
            _ => {}
        }
    }
    if !corners.is_empty() {
        return Err(ImportError::Stl("the file ends inside a facet (truncated?)".into()));
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
