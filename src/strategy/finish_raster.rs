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

use super::context::SurfaceRequest;
use super::{Context, FieldError, Operate};
use crate::error::{Error, Result};
use crate::geom::segment::Rect;
use crate::geom::{DVec2, DVec3};
use crate::progress::Progress;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::toolpath::reduce::reduce;
use crate::toolpath::Toolpath;
use crate::zmap::region::Region;
use crate::zmap::surface::{point_at, ClSurface};
use crate::zmap::{ClBuilder, Grid};

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

/// Raster finishing over the CL z-map (seed 001).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FinishRaster {
    /// Shown in the program's comments. Default value: "raster finish".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Number of the tool to use. Default value: 1.
    pub tool: u32,
    /// Direction of the passes (degrees from +X). Default value: 0.
    pub angle: f64,
    /// Distance between passes (mm). Default value: 0.5.
    pub stepover: f64,
    /// Default value: zigzag.
    pub pattern: Pattern,
    /// Default value: silhouette.
    pub boundary: Boundary,
    /// Growth of the silhouette boundary (mm). Default value: the tool's radius.
    pub margin: Option<f64>,
    /// Material left on the part (mm). Default value: 0.
    pub allowance: f64,
    /// Spacing of the CL z-map (mm). Default value: 0.25.
    pub grid: f64,
    /// Default value: exact.
    pub builder: ClBuilder,
    /// Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
    pub floor: Option<f64>,
    /// Longest link that may stay down (mm). Default value: twice the stepover.
    pub stay_down_max: Option<f64>,
    /// How the cutter enters material (helix, else ramp along the pass).
    pub entry: Entry,
    /// Cut only where the stock the earlier operations left stands above what this one
    /// leaves (by more than the job's gouge tolerance). Default value: false.
    pub rest_only: bool,
    /// Only where the surface is no steeper than this (degrees from horizontal; waterline
    /// finishing takes the steeper areas). Default value: none (everywhere).
    pub slope_max: Option<f64>,
}

impl Default for FinishRaster {
    fn default() -> Self {
        FinishRaster {
            name: "raster finish".into(),
            enabled: true,
            tool: 1,
            angle: 0.0,
            stepover: 0.5,
            pattern: Pattern::Zigzag,
            boundary: Boundary::Silhouette,
            margin: None,
            allowance: 0.0,
            grid: 0.25,
            builder: ClBuilder::Exact,
            floor: None,
            stay_down_max: None,
            entry: Entry::default(),
            rest_only: false,
            slope_max: None,
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

impl Operate for FinishRaster {
    super::named_operation!(OnPart);

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        super::positive("stepover", self.stepover)?;
        super::positive("grid", self.grid)?;
        super::not_negative("allowance", self.allowance)?;
        super::finite("angle", self.angle)?;
        super::positive("entry.rampAngle", self.entry.ramp_angle)?;
        super::not_negative("entry.helixMin", self.entry.helix_min)?;
        super::not_negative("entry.helixMax", self.entry.helix_max)?;
        if let Some(m) = self.margin {
            super::finite("margin", m)?;
        }
        if let Some(f) = self.floor {
            super::finite("floor", f)?;
        }
        if let Some(d) = self.stay_down_max {
            super::not_negative("stayDownMax", d)?;
        }
        if let Some(s) = self.slope_max {
            super::finite("slopeMax", s)?;
        }
        Ok(())
    }

    fn surfaces(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        Ok(vec![self.request(ctx)?])
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Vec<Toolpath>> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let profile = tool.cutter.profile();
        if !progress.stage("CL z-map", 0.0, 0.2) {
            return Err(Error::Cancelled);
        }
        let request = self.request(ctx)?;
        let cl = ctx.cl_surface(request, progress)?;
        if !progress.stage("passes", 0.2, 0.8) {
            return Err(Error::Cancelled);
        }
        let (region, passes) = self.layout(ctx)?;
        let tol = ctx.tolerances;
        let mut runs = match ctx.given_passes.remove(&ctx.operation) {
            Some(given) => join_passes(given, passes.pattern),
            None => raster_runs(&cl, &region, &passes, progress).ok_or(Error::Cancelled)?,
        };
        if let Some(limit) = self.slope_max {
            runs = shallow_only(runs, &cl.field, limit.to_radians().tan());
        }
        if self.rest_only {
            runs = rest_only(runs, &|p: DVec2| ctx.material_estimate(p, &profile), profile.radius / 4.0, tol.gouge);
            if runs.is_empty() {
                ctx.note(&self.name, "the earlier operations left nothing for it to cut (rest only)");
                return Ok(Vec::new());
            }
        }
        let bounds = ctx.node_bounds(request);
        let floor_surface = Floor { cl: &cl, allowance: self.allowance, region: &region, bounds: Some(bounds.as_ref()) };
        Ok(vec![ctx.link(&self.name, &tool, &runs, &floor_surface, self.entry, self.stay_down_max.unwrap_or(2.0 * self.stepover))])
    }
}

impl FinishRaster {
    /// The CL surface it cuts on.
    pub fn request(&self, ctx: &Context) -> Result<SurfaceRequest> {
        let tool = ctx.tool(&self.name, self.tool)?;
        let stock = ctx.stock;
        let grid = Grid::checked(stock.min.truncate(), stock.max.truncate(), self.grid).map_err(|e| Error::operation(&self.name, e))?;
        Ok(SurfaceRequest { profile: tool.cutter.profile(), grid, floor: self.floor.unwrap_or(stock.min.z), builder: self.builder })
    }

    /// Where its passes run and how: the region (the stock, or the part's silhouette grown by
    /// the margin) and the passes' settings.
    pub fn layout(&self, ctx: &mut Context) -> Result<(Region, RasterPasses)> {
        let SurfaceRequest { profile, grid, floor, .. } = self.request(ctx)?;
        let stock = ctx.stock;
        let margin = self.margin.unwrap_or(profile.radius);
        let region = match self.boundary {
            Boundary::Stock => Region::Rect { min: stock.min.truncate(), max: stock.max.truncate() },
            Boundary::Silhouette => Region::silhouette(&ctx.cc_zmap(grid, floor), floor, margin),
        };
        let skip_floor = (self.boundary == Boundary::Silhouette && margin <= profile.radius).then_some(floor);
        let passes = RasterPasses { angle_deg: self.angle, stepover: self.stepover, pattern: self.pattern, allowance: self.allowance, tolerance: ctx.tolerances.chordal, skip_floor };
        Ok((region, passes))
    }
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
pub fn shallow_only(runs: Vec<Vec<DVec3>>, field: &crate::zmap::HeightField, steep: f64) -> Vec<Vec<DVec3>> {
    keep_segments(runs, |a, b| {
        let flat = a.truncate().distance(b.truncate());
        let own = if flat > 0.0 { (b.z - a.z).abs() / flat } else if (b.z - a.z).abs() > 0.0 { f64::INFINITY } else { 0.0 };
        own <= steep && super::finish_waterline::gradient(field, (a.truncate() + b.truncate()) * 0.5) <= steep
    })
}

/// The segments of `runs` that `keep` accepts, consecutive ones joined into runs.
fn keep_segments(runs: Vec<Vec<DVec3>>, keep: impl Fn(DVec3, DVec3) -> bool) -> Vec<Vec<DVec3>> {
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
