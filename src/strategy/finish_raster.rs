//! Raster finishing on the CL z-map: the CL-Cartesian method of seed 001 §1 — parallel vertical
//! planes cut the CL surface, and the tool tip follows the cut.
//!
//! Steps, in order:
//! 1. lay parallel passes at `angle` and `stepover` across the region's bounds;
//! 2. follow the exact CL surface along each pass ([`ClSurface::along`]: even pieces no longer
//!    than the grid spacing (half for cutters other than balls), probed at midpoints and quarters and subdivided until the surface
//!    between two samples stays within the tolerance of the chord), and split it where it
//!    leaves the region; passes are independent, so they run on every core;
//! 3. lift every point by the allowance and reduce within the chordal tolerance, never below;
//! 4. order the runs (zigzag or one way); linking is left to [`crate::toolpath::link`].

use serde::{Deserialize, Serialize};

use super::region::Region;
use crate::geom::{DVec2, DVec3};
use crate::progress::Progress;
use crate::toolpath::reduce::reduce;
use crate::zmap::surface::{point_at, ClSurface};

/// How consecutive passes run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Pattern {
    /// Every other pass reversed: no return moves.
    #[default]
    Zigzag,
    /// All passes in the same direction (constant climb or conventional cut).
    OneWay,
}

/// Parameters of the raster passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterPasses {
    /// Direction of the passes, degrees counter-clockwise from +X.
    pub angle_deg: f64,
    /// Distance between passes (mm).
    pub stepover: f64,
    pub pattern: Pattern,
    /// Material left above the part (mm).
    pub allowance: f64,
    /// Chordal tolerance of point reduction (mm).
    pub tolerance: f64,
    /// Leave out the points where the cutter stands at this height, reaching no part: with the
    /// silhouette grown by no more than the cutter radius, those lie outside the grown
    /// silhouette (which the grid's mask only approximates), and a finishing pass must not
    /// drop to the floor beside the part.
    pub skip_floor: Option<f64>,
}

/// The cutting runs, in machining order, each a polyline of tip positions; `None` when the
/// user cancelled (checked, with a progress report, between batches of passes).
pub fn raster_runs(cl: &ClSurface, region: &Region, passes: &RasterPasses, progress: &mut Progress) -> Option<Vec<Vec<DVec3>>> {
    let angle = passes.angle_deg.to_radians();
    let along = DVec2::new(angle.cos(), angle.sin());
    let across = along.perp();
    let (min, max) = region.bounds();
    let corners = [min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)];
    let (v0, v1) = extent(&corners, across);
    let (s0, s1) = extent(&corners, along);
    let count = (((v1 - v0) / passes.stepover).ceil().max(0.0) as usize) + 1;
    let step = if count > 1 { (v1 - v0) / (count - 1) as f64 } else { 0.0 };

    // The passes are independent: each core takes a share of a batch (in wasm, one after
    // another).
    let batch = 4 * crate::parallel::threads();
    let mut cut = Vec::with_capacity(count);
    for first in (0..count).step_by(batch) {
        if !progress.report(first as f64 / count.max(1) as f64) {
            return None;
        }
        let n = batch.min(count - first);
        cut.extend(crate::parallel::map_heavy(n, |i| {
            let base = across * (v0 + step * (first + i) as f64);
            clip_to_rect(base + along * s0, base + along * s1, min, max).map(|(a, b)| cut_pass(cl, region, a, b, passes)).unwrap_or_default()
        }));
    }
    let mut runs = Vec::new();
    for (k, mut pass_runs) in cut.into_iter().enumerate() {
        if passes.pattern == Pattern::Zigzag && k % 2 == 1 {
            pass_runs.reverse();
            for run in &mut pass_runs {
                run.reverse();
            }
        }
        runs.extend(pass_runs);
    }
    Some(runs)
}

fn extent(points: &[DVec2], dir: DVec2) -> (f64, f64) {
    points.iter().map(|p| p.dot(dir)).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)))
}

/// Clips the segment to the rectangle (Liang–Barsky); the ends are clamped into it.
fn clip_to_rect(a: DVec2, b: DVec2, min: DVec2, max: DVec2) -> Option<(DVec2, DVec2)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d.x, a.x - min.x), (d.x, max.x - a.x), (-d.y, a.y - min.y), (d.y, max.y - a.y)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| ((a + d * t0).clamp(min, max), (a + d * t1).clamp(min, max)))
}

/// One pass from `a` to `b`: the CL polyline, split where it leaves the region, each run
/// lifted by the allowance and reduced.
fn cut_pass(cl: &ClSurface, region: &Region, a: DVec2, b: DVec2, passes: &RasterPasses) -> Vec<Vec<DVec3>> {
    let mut runs = Vec::new();
    let mut run: Vec<DVec3> = Vec::new();
    for (t, z) in cl.along(a, b) {
        let p = point_at(a, b, t);
        if region.contains(p) && passes.skip_floor != Some(z) {
            run.push(p.extend(z + passes.allowance));
        } else if !run.is_empty() {
            runs.push(reduce(&std::mem::take(&mut run), passes.tolerance));
        }
    }
    if !run.is_empty() {
        runs.push(reduce(&run, passes.tolerance));
    }
    runs
}
