//! STL, binary and ASCII, through the `stl_io` crate; the size checks that turn a truncated or
//! mislabelled file into a clear message are swarf's.

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

fn read_ascii(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, ImportError> {
    if std::str::from_utf8(bytes).is_err() {
        return Err(ImportError::Stl("the ASCII STL contains bytes that are not text".into()));
    }
    let mut cursor = Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| ImportError::Stl(e.to_string()))?;
    collect(reader)
}

fn collect<'a>(reader: Box<dyn stl_io::TriangleIterator<Item = std::io::Result<stl_io::Triangle>> + 'a>) -> Result<Vec<[DVec3; 3]>, ImportError> {
    reader
        .map(|t| {
            let t = t.map_err(|e| ImportError::Stl(e.to_string()))?;
            Ok(t.vertices.map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)))
        })
        .collect()
}
