//! Raster passes on a CL surface (seed 001 §1's CL-Cartesian method): parallel passes laid
//! across a region, each following the exact surface, cut apart where it leaves the region, and
//! joined in a pattern; and the filters finishing applies to them (rest only, shallow only).
//! Raster finishing plans with them, and a pool of workers makes the passes in ranges.

use serde::{Deserialize, Serialize};

use crate::geom::segment::Rect;
use crate::geom::{DVec2, DVec3};
use crate::progress::Progress;
use crate::toolpath::reduce::reduce;
use crate::zmap::region::Region;
use crate::zmap::surface::{point_at, ClSurface};
use crate::zmap::HeightField;

/// Where the tool's centre may go.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Boundary {
    /// The stock's rectangle.
    Stock,
    /// The part's outline seen from above, grown by the operation's margin.
    #[default]
    Silhouette,
}

impl Boundary {
    /// The region it stands for on `request`'s grid: the stock's rectangle, or the part's
    /// silhouette above the floor grown by `margin`.
    pub fn region(self, ctx: &mut crate::machining::Context, request: crate::machining::context::SurfaceRequest, margin: f64) -> Region {
        match self {
            Boundary::Stock => Region::Rect { min: ctx.stock.min.truncate(), max: ctx.stock.max.truncate() },
            Boundary::Silhouette => Region::silhouette(&ctx.cc_zmap(request.grid, request.floor), request.floor, margin),
        }
    }
}

/// How consecutive passes run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
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
    let layout = PassLayout::new(region, passes);
    // The passes are independent: each core takes a share of a batch (in wasm, one after
    // another; the page's pool splits them over its workers with [`PassLayout::pass`]).
    let batch = 4 * crate::parallel::threads();
    let mut cut = Vec::with_capacity(layout.count);
    for first in (0..layout.count).step_by(batch) {
        if !progress.report(first as f64 / layout.count.max(1) as f64) {
            return None;
        }
        let n = batch.min(layout.count - first);
        cut.extend(crate::parallel::map_heavy(n, |i| layout.pass(cl, first + i)));
    }
    Some(join_passes(cut, passes.pattern))
}

/// The raster passes over a region: how many, and each one's runs.
pub struct PassLayout<'a> {
    region: &'a Region,
    passes: &'a RasterPasses,
    /// How many passes (some may cut nothing).
    pub count: usize,
    along: DVec2,
    across: DVec2,
    v0: f64,
    step: f64,
    s0: f64,
    s1: f64,
}

impl<'a> PassLayout<'a> {
    pub fn new(region: &'a Region, passes: &'a RasterPasses) -> PassLayout<'a> {
        let angle = passes.angle_deg.to_radians();
        let along = DVec2::new(angle.cos(), angle.sin());
        let across = along.perp();
        let (min, max) = region.bounds();
        let corners = [min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)];
        let (v0, v1) = extent(&corners, across);
        let (s0, s1) = extent(&corners, along);
        let count = (((v1 - v0) / passes.stepover).ceil().max(0.0) as usize) + 1;
        let step = if count > 1 { (v1 - v0) / (count - 1) as f64 } else { 0.0 };
        PassLayout { region, passes, count, along, across, v0, step, s0, s1 }
    }

    /// The runs of pass `k` (all in the pass's own direction), on `cl`.
    pub fn pass(&self, cl: &ClSurface, k: usize) -> Vec<Vec<DVec3>> {
        let (min, max) = self.region.bounds();
        let base = self.across * (self.v0 + self.step * k as f64);
        Rect { min, max }.clip(base + self.along * self.s0, base + self.along * self.s1).map(|(a, b)| cut_pass(cl, self.region, a, b, self.passes)).unwrap_or_default()
    }
}

/// The runs of every pass, in machining order: with the zigzag pattern every other pass turned
/// round.
pub fn join_passes(cut: Vec<Vec<Vec<DVec3>>>, pattern: Pattern) -> Vec<Vec<DVec3>> {
    let mut runs = Vec::new();
    for (k, mut pass_runs) in cut.into_iter().enumerate() {
        if pattern == Pattern::Zigzag && k % 2 == 1 {
            pass_runs.reverse();
            for run in &mut pass_runs {
                run.reverse();
            }
        }
        runs.extend(pass_runs);
    }
    runs
}

fn extent(points: &[DVec2], dir: DVec2) -> (f64, f64) {
    points.iter().map(|p| p.dot(dir)).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)))
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

/// The tip's runs along the plan polyline `line` on the exact surface `cl`, lifted by the
/// allowance, cut where the tool stands on the floor beside the part (`skip_floor`, as
/// [`RasterPasses::skip_floor`]), reduced within `tolerance`: a raster pass's, along any line.
pub fn follow_line(cl: &ClSurface, line: &[DVec2], allowance: f64, skip_floor: Option<f64>, tolerance: f64) -> Vec<Vec<DVec3>> {
    let mut runs = Vec::new();
    let mut run: Vec<DVec3> = Vec::new();
    for w in line.windows(2) {
        for (k, (t, z)) in cl.along(w[0], w[1]).into_iter().enumerate() {
            if k == 0 && !run.is_empty() {
                continue;
            }
            if skip_floor == Some(z) {
                if run.len() > 1 {
                    runs.push(reduce(&run, tolerance));
                }
                run.clear();
            } else {
                run.push(point_at(w[0], w[1], t).extend(z + allowance));
            }
        }
    }
    if run.len() > 1 {
        runs.push(reduce(&run, tolerance));
    }
    runs
}

/// The parts of `runs` where the cutter would remove material from the in-process stock:
/// `material` (the highest tip height touching it) stands more than `threshold` above the run
/// at some point of a segment (sampled every `spacing` at most). Consecutive such segments stay
/// one run; the rest is left out.
pub fn rest_only(runs: Vec<Vec<DVec3>>, material: &dyn Fn(DVec2) -> f64, spacing: f64, threshold: f64) -> Vec<Vec<DVec3>> {
    let cuts = |p: DVec3| material(p.truncate()) > p.z + threshold;
    keep_segments(runs, |a, b| {
        let n = ((a.truncate().distance(b.truncate()) / spacing).ceil() as usize).max(1);
        (0..=n).any(|k| cuts(point_at(a, b, k as f64 / n as f64)))
    })
}

/// The parts of `runs` on shallow ground: segments whose own slope and the CL surface's slope
/// at their middle are both no steeper than `steep` (rise over run); a vertical step is steep.
pub fn shallow_only(runs: Vec<Vec<DVec3>>, field: &HeightField, steep: f64) -> Vec<Vec<DVec3>> {
    keep_segments(runs, |a, b| {
        let flat = a.truncate().distance(b.truncate());
        let own = if flat > 0.0 {
            (b.z - a.z).abs() / flat
        } else if (b.z - a.z).abs() > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        own <= steep && gradient(field, (a.truncate() + b.truncate()) * 0.5) <= steep
    })
}

/// The segments of `runs` that `keep` accepts, consecutive ones joined into runs.
pub fn keep_segments(runs: Vec<Vec<DVec3>>, keep: impl Fn(DVec3, DVec3) -> bool) -> Vec<Vec<DVec3>> {
    let mut out = Vec::new();
    for run in runs {
        let mut current: Vec<DVec3> = Vec::new();
        for w in run.windows(2) {
            if keep(w[0], w[1]) {
                if current.is_empty() {
                    current.push(w[0]);
                }
                current.push(w[1]);
            } else if !current.is_empty() {
                out.push(std::mem::take(&mut current));
            }
        }
        if !current.is_empty() {
            out.push(current);
        }
    }
    out
}

/// The slope of the CL surface at `p` (rise over run), from the nodes around it.
pub fn gradient(f: &HeightField, p: DVec2) -> f64 {
    let u = (p - f.origin) / f.spacing;
    let (i, j) = (u.x.floor().clamp(0.0, (f.nx - 1) as f64) as usize, u.y.floor().clamp(0.0, (f.ny - 1) as f64) as usize);
    let (i1, j1) = ((i + 1).min(f.nx - 1), (j + 1).min(f.ny - 1));
    let dx = ((f.at(i1, j) - f.at(i, j)).abs()).max((f.at(i1, j1) - f.at(i, j1)).abs());
    let dy = ((f.at(i, j1) - f.at(i, j)).abs()).max((f.at(i1, j1) - f.at(i1, j)).abs());
    (dx * dx + dy * dy).sqrt() / f.spacing
}

/// Refuses, before any work, passes `stepover` apart across the stock past
/// [`crate::machining::MAX_PASSES`], or more points than [`crate::limits::MAX_PATH_POINTS`]
/// where they follow the surface a `grid` apart.
pub fn check_points(ctx: &crate::machining::Context, op: &str, stepover: f64, grid: f64) -> crate::error::Result<()> {
    let size = (ctx.stock.max - ctx.stock.min).truncate();
    let span = size.length();
    crate::machining::too_many(op, "passes", span / stepover, crate::machining::MAX_PASSES, "a step-over of", stepover, span)?;
    let points = size.x * size.y / (stepover * grid);
    if points > crate::limits::MAX_PATH_POINTS {
        return Err(crate::error::Error::operation(
            op,
            format!(
                "a step-over of {} mm at a grid of {} mm makes about {:.1} million points over the {:.0} × {:.0} mm stock (at most {:.0} million): choose a coarser grid or step-over, or check the part's unit",
                stepover,
                grid,
                points / 1e6,
                size.x,
                size.y,
                crate::limits::MAX_PATH_POINTS / 1e6
            ),
        ));
    }
    Ok(())
}
