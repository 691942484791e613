//! Waterline finishing (z-level finishing) on the CL z-map: at each level the cutter follows the
//! boundary of the region its centre may occupy there ([`crate::zmap::contour`]), where it
//! touches the part at that height. Limited to steep areas (where the CL surface is steeper
//! than `slopeMin`); raster finishing's `slopeMax` takes the rest, so the two together finish a
//! part "steep and shallow". Levels are spaced by the step-down, or by the scallop height: on a
//! slope θ a ball of radius r leaves a scallop h between paths s = sqrt(8 r h) apart along the
//! surface, so the next level lies s · sin θ lower, θ the shallowest slope of the steep grid
//! cells across the level (those its steep contours pass through). Either way the levels are
//! known before any is contoured, so their regions are made side by side (on threads, or by a
//! pool of workers in the page). The contours are linked and entered by the shared linker
//! ([`crate::toolpath::link`]).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::machining::context::SurfaceRequest;
use crate::machining::levels::{pack, RegionWork};
use crate::machining::raster::{gradient, rest_only};
use crate::machining::settings::Direction;
use crate::machining::{named_operation, not_negative, positive, too_many, Context, FieldError, Operate, Planned, MAX_LEVELS};
use crate::progress::Progress;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::zmap::region::Region;
use crate::zmap::{ClBuilder, HeightField};

/// Waterline finishing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FinishWaterline {
    /// Default value: "waterline finish".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Default value: 1.
    pub tool: u32,
    /// Height between levels (mm); used when `scallop` is not set. Default value: 0.5.
    pub stepdown: f64,
    /// Largest scallop height between levels (mm, at least 0.001): levels closer where the surface is
    /// shallower. Default value: none (the step-down).
    pub scallop: Option<f64>,
    /// Material left on the part (mm). Default value: 0.
    pub allowance: f64,
    /// Only where the surface is steeper than this (degrees from horizontal). Default value: 30.
    pub slope_min: f64,
    /// Default value: climb.
    pub direction: Direction,
    /// Spacing of the CL z-map (mm). Default value: 0.25.
    pub grid: f64,
    pub entry: Entry,
    /// Cut only where the stock the earlier operations left stands above what this one
    /// leaves (by more than the job's gouge tolerance): after a larger ball, a smaller one
    /// takes only the corners it left. Default value: false.
    pub rest_only: bool,
}

impl Default for FinishWaterline {
    fn default() -> Self {
        FinishWaterline {
            name: "waterline finish".into(),
            enabled: true,
            tool: 1,
            stepdown: 0.5,
            scallop: None,
            allowance: 0.0,
            slope_min: 30.0,
            direction: Direction::Climb,
            grid: 0.25,
            entry: Entry::default(),
            rest_only: false,
        }
    }
}

/// Contour pieces shorter than this are left out (mm).
const SHORTEST: f64 = 0.5;
/// Smallest step between levels (mm), however shallow the slope.
const LEAST_STEP: f64 = 0.02;
/// Smallest scallop height (mm): a micron, finer than any machine holds; a scallop of 1e-9 mm
/// would put every level [`LEAST_STEP`] apart, 1,300 levels on the 26 mm sample.
const LEAST_SCALLOP: f64 = 0.001;

impl Operate for FinishWaterline {
    fn plans_round_fixtures(&self) -> bool {
        true
    }
    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_end_mills_and_v_bits(cutter)
    }

    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::length("stepdown", "Step-down", 0.01),
            F::length("scallop", "Scallop height", 0.001).empty("by the step-down"),
            F::length("allowance", "Leave on the part", 0.0),
            F::degrees("slopeMin", "Only where steeper than", 0.0, 90.0),
            F::direction(),
            F::grid(),
            F::check("restOnly", "only what earlier operations left (rest machining)"),
        ]);
        fields.extend(F::entry());
        OperationForm::new("finish steep walls in levels", fields)
    }

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("stepdown", self.stepdown)?;
        if let Some(h) = self.scallop {
            positive("scallop", h)?;
            if h < LEAST_SCALLOP {
                return Err(FieldError { field: "scallop", message: format!("is at least {LEAST_SCALLOP} mm, a micron: finer than any machine holds (got {})", crate::limits::shown(h)) });
            }
        }
        not_negative("allowance", self.allowance)?;
        crate::machining::angle("slopeMin", self.slope_min, 0.0, 90.0)?;
        positive("grid", self.grid)?;
        self.entry.validate()?;
        Ok(())
    }

    fn check_scale(&self, ctx: &Context) -> Result<()> {
        // Levels by the scallop are at least LEAST_STEP apart (`heights`); by the step-down, as set.
        match self.scallop {
            Some(_) => Ok(()),
            None => crate::machining::check_levels(&self.name, ctx.stock, self.stepdown, self.grid),
        }
    }

    fn level_maps(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        self.surfaces(ctx)
    }

    fn surfaces(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        Ok(vec![ctx.stock_surface(&self.name, self.tool, self.grid, None, ClBuilder::Exact)?])
    }

    fn region_work(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Option<RegionWork>> {
        let request = self.surfaces(ctx)?[0];
        let cl = ctx.cl_surface(request, progress)?;
        let profile = ctx.tool(&self.name, self.tool)?.cutter.profile();
        let all = pack(&vec![true; request.grid.nodes()]);
        let levels = self.heights(&cl.field, request.floor, profile.radius)?.into_iter().map(|z| (z - self.allowance, all.clone())).collect();
        Ok(Some(RegionWork { request, levels }))
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let profile = tool.cutter.profile();
        if !progress.stage("CL z-map", 0.0, 0.3) {
            return Err(Error::Cancelled);
        }
        let request = self.surfaces(ctx)?[0];
        let (grid, floor) = (request.grid, request.floor);
        let cl = ctx.cl_surface(request, progress)?;
        if !progress.stage("levels", 0.3, 0.7) {
            return Err(Error::Cancelled);
        }
        let tol = ctx.tolerances;
        let map = ctx.level_map(request, &cl);
        let steep = self.slope_min.to_radians().tan();
        let slope = |p: DVec2| gradient(&cl.field, p);
        let heights = self.heights(&cl.field, floor, profile.radius)?;
        // Every level's region on whichever core is free (the levels are known beforehand),
        // unless a pool made it already.
        let given = &ctx.given_regions;
        let all = (!given.is_empty()).then(|| pack(&vec![true; grid.nodes()]));
        let made = crate::parallel::map_uneven(heights.len(), |k| {
            let level = heights[k] - self.allowance;
            let kept = all.as_ref().and_then(|all| given.iter().find(|g| g.request == request && g.level == level && g.keep == *all));
            kept.map_or_else(|| map.region(&cl, level, &|_, _| true, &tol), |g| g.region.clone())
        });
        let mut runs: Vec<Vec<DVec3>> = Vec::new();
        for (k, (&z, region)) in heights.iter().zip(made).enumerate() {
            if !progress.report(k as f64 / heights.len() as f64) {
                return Err(Error::Cancelled);
            }
            for l in &region.loops {
                // The region's loops keep it on their left, the part on their right: climb with
                // a clockwise spindle.
                let l = if self.direction == Direction::Climb { l.clone() } else { l.reversed() };
                let pts: Vec<DVec2> = l.vertices.iter().map(|v| v.p).chain(l.vertices.first().map(|v| v.p)).collect();
                for piece in split_steep(&pts, &slope, steep) {
                    let length: f64 = piece.windows(2).map(|w| w[0].distance(w[1])).sum();
                    if length < SHORTEST.max(crate::toolpath::entry::shortest_ramp(profile.radius)) {
                        continue;
                    }
                    runs.push(piece.into_iter().map(|p| p.extend(z)).collect());
                }
            }
        }
        if runs.is_empty() {
            ctx.note(&self.name, format!("no area of the part is steeper than {}°", self.slope_min));
            return Ok(Planned::default());
        }
        if self.rest_only {
            runs = rest_only(runs, &|p: DVec2| ctx.material_estimate(p, &profile), profile.radius / 4.0, tol.gouge);
            if runs.is_empty() {
                ctx.note(&self.name, "the earlier operations left nothing for it to cut (rest only)");
                return Ok(Planned::default());
            }
        }
        let region = Region::Rect { min: grid.origin, max: grid.node(grid.nx - 1, grid.ny - 1) };
        let bounds = ctx.node_bounds(request);
        let floor_surface = Floor { cl: &cl, allowance: self.allowance, region: &region, bounds: Some(bounds.as_ref()) };
        Ok(vec![ctx.link(&self.name, &tool, &runs, &floor_surface, self.entry, 2.0 * profile.radius)].into())
    }
}

impl FinishWaterline {
    /// The heights of the levels, from the top down, known before any is contoured: a step-down
    /// apart, or by the scallop: the next level s · sin θ lower, s = sqrt(8 r h) and θ the
    /// shallowest slope of the steep cells (those the level's steep contours pass through) that
    /// reach across its height. More than [`MAX_LEVELS`] (levels [`LEAST_STEP`] apart on a tall
    /// part), or more than the level map allows, are refused as soon as they are counted.
    fn heights(&self, cl: &HeightField, floor: f64, radius: f64) -> Result<Vec<f64>> {
        let top = cl.max();
        let bottom = floor + self.allowance;
        let steep = self.slope_min.to_radians().tan();
        // Per steep cell: the lowest and highest of its nodes, and its slope.
        let mut cells = Vec::new();
        if self.scallop.is_some() {
            for j in 0..cl.ny.saturating_sub(1) {
                for i in 0..cl.nx.saturating_sub(1) {
                    let slope = gradient(cl, cl.origin + (DVec2::new(i as f64, j as f64) + 0.5) * cl.spacing);
                    if slope >= steep {
                        let z = [cl.at(i, j), cl.at(i + 1, j), cl.at(i, j + 1), cl.at(i + 1, j + 1)];
                        cells.push((z.iter().copied().fold(f64::INFINITY, f64::min), z.iter().copied().fold(f64::NEG_INFINITY, f64::max), slope));
                    }
                }
            }
        }
        // Shallowest first: at most levels one of the first cells reaches across.
        crate::geom::sort::sort_by_float(&mut cells, |a| a.2);
        let mut out = Vec::new();
        let mut z = top - 0.5 * self.stepdown.min(top - floor);
        let nodes = (cl.nx * cl.ny) as f64;
        let cap = MAX_LEVELS.min(crate::limits::MAX_LEVEL_NODES / nodes);
        while z > bottom {
            if out.len() as f64 >= cap {
                // More levels than a limit allows: at least these and the one below.
                let more = (out.len() as f64 * (top - bottom) / (top - z)).max(out.len() as f64 + 1.0);
                let (what, h) = self.scallop.map_or(("a step-down of", self.stepdown), |h| ("a scallop of", h));
                too_many(&self.name, "levels", more, MAX_LEVELS, what, h, top - bottom)?;
                let size = DVec3::new(cl.spacing * (cl.nx - 1) as f64, cl.spacing * (cl.ny - 1) as f64, top - floor);
                crate::machining::level_work(&self.name, more, &format!("{what} {} mm", crate::limits::shown(h)), cl.spacing, size)?;
            }
            out.push(z);
            let level = z - self.allowance;
            let shallowest = cells.iter().find(|&&(lo, hi, _)| lo <= level && level <= hi).map_or(f64::INFINITY, |c| c.2);
            z -= match self.scallop {
                Some(h) if shallowest.is_finite() => {
                    let s = (8.0 * radius * h).sqrt();
                    (s * shallowest.atan().sin()).clamp(LEAST_STEP, self.stepdown.max(LEAST_STEP))
                }
                _ => self.stepdown,
            };
        }
        Ok(out)
    }
}

/// The stretches of the closed polyline `pts` (its last point its first) where the slope is at
/// least `steep`, as open polylines (one closed one when it is steep all round).
fn split_steep(pts: &[DVec2], slope: &dyn Fn(DVec2) -> f64, steep: f64) -> Vec<Vec<DVec2>> {
    let keep: Vec<bool> = pts.windows(2).map(|w| slope((w[0] + w[1]) * 0.5) >= steep).collect();
    if keep.iter().all(|&k| k) {
        return vec![pts.to_vec()];
    }
    // Start at a segment that is left out, so stretches do not wrap.
    let n = keep.len();
    let Some(first_out) = keep.iter().position(|&k| !k) else { return Vec::new() };
    let mut out = Vec::new();
    let mut current: Vec<DVec2> = Vec::new();
    for s in 0..n {
        let k = (first_out + s) % n;
        if keep[k] {
            if current.is_empty() {
                current.push(pts[k]);
            }
            current.push(pts[k + 1]);
        } else if !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}
