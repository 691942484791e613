//! Seed 001 §3.1, the inverse offset: the inverted cutter is stood on every node of the CC
//! z-map and raises the nodes around it, `CL(q) = max over p of CC(p) - height(|p - q|)`.
//! It sees the part only at the nodes, so its error grows as the ratio of cutter diameter to
//! grid spacing falls (the paper's δ, Fig. 4-b).
//!
//! The loops run offset by offset over whole rows, so the inner loop is a plain
//! `max(out, src - h)` over contiguous memory that the compiler vectorises.

use super::HeightField;
use crate::cutter::Profile;
use crate::error::{Error, Result};
use crate::progress::Progress;

/// Builds the CL z-map from a CC z-map by inverse offset.
pub fn cl_inverse_offset(cc: &HeightField, profile: &Profile, progress: &mut Progress) -> Result<HeightField> {
    let (nx, ny, spacing) = (cc.nx, cc.ny, cc.spacing);
    let reach = (profile.radius / spacing).floor() as isize;
    // Offsets (dx, dy) inside the cutter with the cutter's height there, grouped by dy.
    let rows: Vec<(isize, Vec<(isize, f64)>)> = (-reach..=reach)
        .map(|dy| {
            let row = (-reach..=reach)
                .filter_map(|dx| {
                    let r = ((dx * dx + dy * dy) as f64).sqrt() * spacing;
                    (r <= profile.radius).then(|| (dx, profile.height(r)))
                })
                .collect();
            (dy, row)
        })
        .collect();
    let mut out = cc.clone();
    for j in 0..ny {
        if j % 64 == 0 && !progress.report(j as f64 / ny as f64) {
            return Err(Error::Cancelled);
        }
        let target = j * nx;
        for (dy, offsets) in &rows {
            let js = j as isize + dy;
            if js < 0 || js >= ny as isize {
                continue;
            }
            let source = &cc.z[js as usize * nx..(js as usize + 1) * nx];
            let out_row = &mut out.z[target..target + nx];
            for &(dx, h) in offsets {
                // out[i] = max(out[i], source[i - dx] - h) for every i with i - dx on the grid.
                let (o_lo, s_lo, len) = if dx >= 0 { (dx as usize, 0, nx.saturating_sub(dx as usize)) } else { (0, (-dx) as usize, nx.saturating_sub((-dx) as usize)) };
                for (o, s) in out_row[o_lo..o_lo + len].iter_mut().zip(&source[s_lo..s_lo + len]) {
                    // A compare-and-select (not f64::max, whose NaN rule has no vector form in
                    // wasm) so that it vectorises to f64x2.pmax / maxpd.
                    let v = s - h;
                    *o = if *o < v { v } else { *o };
                }
            }
        }
    }
    Ok(out)
}
