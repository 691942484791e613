//! Writing height fields so other tools can compare them point by point.
//!
//! * CSV: a header line `x,y,z`, then one line per node, row by row (j outer, i inner), in mm.
//! * Raw (little-endian): the 8 bytes `SWZMAP\0\0`, `u32 nx`, `u32 ny`, `f64 origin_x`,
//!   `f64 origin_y`, `f64 spacing`, then `nx * ny` f64 heights row-major (`z[j * nx + i]`).
//!   Node (i, j) stands at `(origin_x + i * spacing, origin_y + j * spacing)`.

use std::fmt::Write as _;

use super::HeightField;

pub const RAW_MAGIC: &[u8; 8] = b"SWZMAP\0\0";

pub fn to_csv(field: &HeightField) -> String {
    let mut out = String::with_capacity(field.z.len() * 28 + 8);
    out.push_str("x,y,z\n");
    let grid = field.grid();
    for j in 0..field.ny {
        for i in 0..field.nx {
            let p = grid.node(i, j);
            let _ = writeln!(out, "{:.6},{:.6},{:.6}", p.x, p.y, field.at(i, j));
        }
    }
    out
}

pub fn to_raw(field: &HeightField) -> Vec<u8> {
    let mut out = Vec::with_capacity(40 + field.z.len() * 8);
    out.extend_from_slice(RAW_MAGIC);
    out.extend_from_slice(&(field.nx as u32).to_le_bytes());
    out.extend_from_slice(&(field.ny as u32).to_le_bytes());
    for v in [field.origin.x, field.origin.y, field.spacing] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for z in &field.z {
        out.extend_from_slice(&z.to_le_bytes());
    }
    out
}

/// Reads the raw format back; `None` when the bytes are not one.
pub fn from_raw(bytes: &[u8]) -> Option<HeightField> {
    let rest = bytes.strip_prefix(RAW_MAGIC)?;
    let u32_at = |o: usize| Some(u32::from_le_bytes(rest.get(o..o + 4)?.try_into().ok()?) as usize);
    let f64_at = |o: usize| Some(f64::from_le_bytes(rest.get(o..o + 8)?.try_into().ok()?));
    let (nx, ny) = (u32_at(0)?, u32_at(4)?);
    let origin = crate::geom::DVec2::new(f64_at(8)?, f64_at(16)?);
    let spacing = f64_at(24)?;
    let body = rest.get(32..)?;
    if body.len() != nx.checked_mul(ny)?.checked_mul(8)? {
        return None;
    }
    let z = body.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
    Some(HeightField { origin, spacing, nx, ny, z })
}
