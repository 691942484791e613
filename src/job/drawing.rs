//! A job on a drawing: the drawing scaled and placed as a sheet (its top at Z0, its thickness
//! below), and the part the drawing means for verification: full height inside the kept
//! region, cut to each operation's depth where it cuts.

use super::schema::Job;
use crate::drawing::Drawing;
use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec2};
use crate::machining::report::{Groove, SheetCut};
use crate::offset::offset;
use crate::zmap::{Grid, HeightField};

/// Scales and places `drawing` as the job says; returns the sheet's stock (its top at Z0) and
/// thickness.
pub fn place(job: &Job, drawing: &mut Drawing) -> Result<(Aabb, f64)> {
    job.drawing.apply(drawing);
    let thickness = job.drawing.thickness;
    if !(thickness > 0.0 && thickness.is_finite()) {
        return Err(Error::Input(format!("drawing.thickness: the sheet thickness must be a positive number (got {thickness})")));
    }
    let b = drawing.bounds();
    if b.is_empty() {
        return Err(Error::Nothing("the drawing is empty".into()));
    }
    let m = job.stock.margin_xy;
    Ok((Aabb { min: (b.min - DVec2::splat(m)).extend(-thickness), max: (b.max + DVec2::splat(m)).extend(0.0) }, thickness))
}

/// The part's heights on the simulation grid: the sheet's top, lowered to each cut's depth
/// where it cuts (inside its region, or outside it). Regions are narrowed by the leave-stock
/// and widened by the gouge tolerance where they cut, so cells on a wall are not judged by a
/// hair.
pub fn surface(cuts: &[SheetCut], grooves: &[Groove], grid: Grid, gouge: f64, tol: &crate::geom::Tolerances) -> HeightField {
    let mut field = grid.filled(0.0);
    lower_in_grooves(&mut field, grooves, grid, gouge, 0.0);
    // Cells a cut that leaves scrap beyond its kerf (a profile) reaches, and cells another
    // cut clears (a pocket, a facing): the first are no part unless the second.
    let mut scrap = vec![false; field.z.len()];
    let mut cleared = vec![false; field.z.len()];
    for SheetCut { region, inside, depth, leave, scrap: parts_off } in cuts {
        let widen = gouge - leave;
        let region = offset(region, if *inside { widen } else { -widen }, tol);
        let ys: Vec<f64> = (0..grid.ny).map(|j| grid.node(0, j).y).collect();
        for (j, spans) in region.spans_on_rows(&ys).into_iter().enumerate() {
            // The spans are in order and apart: the first not wholly left of a node is the
            // only one that may hold it.
            let mut k = 0;
            for i in 0..grid.nx {
                let x = grid.node(i, 0).x;
                while k < spans.len() && spans[k].1 <= x {
                    k += 1;
                }
                let within = spans.get(k).is_some_and(|&(a, b)| x > a && x < b);
                // A profile cutting outside a loop cuts everything but the loop's inside.
                let cut = if *inside { within } else { !within };
                if cut {
                    let c = j * grid.nx + i;
                    field.z[c] = field.z[c].min(-depth);
                    if *parts_off {
                        scrap[c] = true;
                    } else {
                        cleared[c] = true;
                    }
                }
            }
        }
    }
    // Scrap is not the part: no height to judge (as where a mesh has no part).
    for c in 0..field.z.len() {
        if scrap[c] && !cleared[c] {
            field.z[c] = f64::NEG_INFINITY;
        }
    }
    field
}

/// Lowers `field` (on `grid`) within each groove's reach (its radius and `gouge`) of its line
/// to the groove's depth below `top`: where an engraving, a drilled hole or a chamfer may
/// take material the part keeps elsewhere.
pub fn lower_in_grooves(field: &mut HeightField, grooves: &[Groove], grid: Grid, gouge: f64, top: f64) {
    for g in grooves {
        let reach = g.radius + gouge;
        for seg in &g.path {
            let b = seg.bounds().expand(reach);
            let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(b.min.x, b.max.x), grid.rows(b.min.y, b.max.y)) else { continue };
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let q = grid.node(i, j);
                    if seg.distance_to(q) < reach {
                        let c = j * grid.nx + i;
                        field.z[c] = field.z[c].min(top - g.depth);
                    }
                }
            }
        }
    }
}
