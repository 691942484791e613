//! Steep-and-shallow finishing (issue 60): one operation for the whole surface at one cusp
//! height: waterlines where the surface is steeper than `slope` (levels spaced by the scallop
//! the slope leaves, [`crate::machining::waterline`]), scallop passes or raster passes on the
//! shallow ground (seed 001's CL-Cartesian method, [`crate::machining::raster`];
//! [`crate::machining::scallop`]), the two zones overlapping by `overlap` so no seam is left
//! between them.
//!
//! Steps, in order:
//! 1. the exact CL z-map over the stock (seed 001 §3.3), and the area (the silhouette grown by
//!    the margin, or the stock);
//! 2. the zones: each node steep or shallow by the CL surface's slope there, each zone grown by
//!    `overlap` (a distance map of the other, [`crate::zmap::distance`]);
//! 3. the shallow zone's passes: scallop passes a step apart across the surface, or raster
//!    passes whose plan step leaves the cusp at the steepest shallow slope, the tip on the exact
//!    drop;
//! 4. the steep zone's waterlines, kept where they run in it; the steep first (top down), then
//!    the shallow, linked by the shared linker.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::machining::context::SurfaceRequest;
use crate::machining::raster::{follow_line, gradient, keep_segments, raster_runs, rest_only, Boundary, Pattern, RasterPasses};
use crate::machining::scallop::{cusp_step, passes};
use crate::machining::settings::Direction;
use crate::machining::waterline::{contours, heights, Spacing, SHORTEST};
use crate::machining::{finite, named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::progress::Progress;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::zmap::ClBuilder;

/// What finishes the shallow ground.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Shallow {
    /// Passes offset across the surface from the zone's edge, a step apart.
    #[default]
    Scallop,
    /// Parallel passes at `angle`.
    Raster,
}

/// Steep-and-shallow finishing: waterline on the steep, scallop or raster on the shallow.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FinishSteepShallow {
    /// Shown in the program's comments. Default value: "steep and shallow finish".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Number of the tool to use (a ball or bull-nose end mill). Default value: 1.
    pub tool: u32,
    /// Height of the ridge left between passes and between levels (mm). Default value: 0.01.
    pub cusp: f64,
    /// Where steep begins (degrees from horizontal): waterline above it, the shallow passes
    /// below. Default value: 40.
    pub slope: f64,
    /// How far each zone reaches into the other (mm), so no seam is left. Default value: 0.5.
    pub overlap: f64,
    /// Default value: scallop.
    pub shallow: Shallow,
    /// Direction of the raster passes (degrees from +X). Default value: 0.
    pub angle: f64,
    /// The waterlines' direction. Default value: climb.
    pub direction: Direction,
    /// Default value: silhouette.
    pub boundary: Boundary,
    /// Growth of the silhouette boundary (mm). Default value: the tool's radius.
    pub margin: Option<f64>,
    /// Material left on the part (mm). Default value: 0.
    pub allowance: f64,
    /// Spacing of the CL z-map (mm). Default value: 0.2.
    pub grid: f64,
    /// How the cutter enters material (helix, else ramp along the pass).
    pub entry: Entry,
    /// Cut only where the stock the earlier operations left stands above what this one
    /// leaves (by more than the job's gouge tolerance). Default value: false.
    pub rest_only: bool,
    /// The heights it cuts between (what lies above its top or below its bottom is left),
    /// its clearance and retract.
    #[serde(flatten)]
    #[ts(flatten)]
    pub heights: crate::machining::settings::Heights,
}

impl Default for FinishSteepShallow {
    fn default() -> Self {
        FinishSteepShallow {
            name: "steep and shallow finish".into(),
            enabled: true,
            tool: 1,
            cusp: 0.01,
            slope: 40.0,
            overlap: 0.5,
            shallow: Shallow::Scallop,
            angle: 0.0,
            direction: Direction::Climb,
            boundary: Boundary::Silhouette,
            margin: None,
            allowance: 0.0,
            grid: 0.2,
            entry: Entry::default(),
            rest_only: false,
            heights: Default::default(),
        }
    }
}

impl Operate for FinishSteepShallow {
    fn plans_round_fixtures(&self) -> bool {
        true
    }

    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_rounded_corners(cutter)
    }

    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::length("cusp", "Cusp height (scallop) left", 0.0001).help("The height of the ridge left between passes on the shallow ground and between levels on the steep."),
            F::degrees("slope", "Steep from", 1.0, 89.0).help("Steeper than this: waterlines; shallower: the passes below."),
            F::length("overlap", "Overlap of steep and shallow", 0.0),
            F::choice("shallow", "Shallow ground", &[("scallop", "scallop: offsets across the surface"), ("raster", "parallel passes")]),
            F::number("angle", "Parallel passes' angle", U::Degrees),
            F::direction(),
            F::area(),
            F::outline_growth(),
            F::length("allowance", "Leave on the part", 0.0),
            F::grid(),
            F::check("restOnly", "only what earlier operations left (rest machining)"),
        ]);
        fields.extend(F::entry());
        fields.extend(crate::machining::settings::Heights::fields());
        OperationForm::new("steep and shallow at one cusp", fields)
            .hint("Waterlines on the steep walls, scallop or parallel passes on the shallow ground, overlapping: the whole surface finished to one cusp height in one operation.")
    }

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.heights.validate()?;
        positive("cusp", self.cusp)?;
        crate::machining::angle("slope", self.slope, 1.0, 89.0)?;
        not_negative("overlap", self.overlap)?;
        crate::machining::angle("angle", self.angle, -360.0, 360.0)?;
        not_negative("allowance", self.allowance)?;
        positive("grid", self.grid)?;
        self.entry.validate()?;
        if let Some(m) = self.margin {
            finite("margin", m)?;
        }
        Ok(())
    }

    fn check_scale(&self, ctx: &Context) -> Result<()> {
        let profile = ctx.tool(&self.name, self.tool)?.cutter.profile();
        let step = cusp_step(&self.name, self.cusp, profile.corner, ctx.tolerances.chordal)?;
        crate::machining::raster::check_points(ctx, &self.name, step, self.grid)?;
        crate::machining::check_levels(&self.name, ctx.stock, step.max(crate::machining::waterline::LEAST_STEP), self.grid)
    }

    fn surfaces(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        Ok(vec![self.request(ctx)?])
    }

    fn level_maps(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        self.surfaces(ctx)
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let profile = tool.cutter.profile();
        let tol = ctx.tolerances;
        let step = cusp_step(&self.name, self.cusp, profile.corner, tol.chordal)?;
        if !progress.stage("CL z-map", 0.0, 0.3) {
            return Err(Error::Cancelled);
        }
        let request = self.request(ctx)?;
        let cl = ctx.cl_surface(request, progress)?;
        let f = &cl.field;
        let g = f.grid();
        let margin = self.margin.unwrap_or(profile.radius);
        let region = self.boundary.region(ctx, request, margin);
        // The zones: steep nodes by the CL surface's slope, each zone grown by the overlap.
        let steep_slope = self.slope.to_radians().tan();
        let steep: Vec<bool> = (0..f.z.len()).map(|n| gradient(f, g.node(n % f.nx, n / f.nx)) >= steep_slope).collect();
        let shallow: Vec<bool> = steep.iter().map(|&s| !s).collect();
        let reach = self.overlap + 1e-9;
        let near_steep = crate::zmap::distance::distance_within(&steep, f.nx, f.ny, f.spacing, reach);
        let near_shallow = crate::zmap::distance::distance_within(&shallow, f.nx, f.ny, f.spacing, reach);
        let at = |p: DVec2| g.nearest(p);
        let in_steep = |p: DVec2| at(p).is_some_and(|n| near_steep[n] <= reach);
        let in_shallow = |p: DVec2| at(p).is_some_and(|n| near_shallow[n] <= reach);

        if !progress.stage("waterlines", 0.3, 0.3) {
            return Err(Error::Cancelled);
        }
        // Levels by the cusp on the steep, never farther apart than the step across it: the
        // waterlines' scallop s = sqrt(8 a h) made the same step as the shallow passes'.
        let scallop = step * step / (8.0 * profile.corner);
        let spacing = Spacing { stepdown: step, scallop: Some(scallop), allowance: self.allowance, steep: steep_slope };
        let levels = heights(&self.name, f, request.floor, profile.corner, spacing)?;
        let shortest = SHORTEST.max(crate::toolpath::entry::shortest_ramp(profile.radius));
        let in_region_steep = |p: DVec2| in_steep(p) && region.contains(p);
        let mut runs = contours(ctx, request, &cl, &levels, self.allowance, self.direction, &in_region_steep, shortest, progress).ok_or(Error::Cancelled)?;

        if !progress.stage("shallow passes", 0.6, 0.4) {
            return Err(Error::Cancelled);
        }
        let skip_floor = (self.boundary == Boundary::Silhouette && margin <= profile.radius).then_some(request.floor);
        let shallow_runs: Vec<Vec<DVec3>> = match self.shallow {
            Shallow::Scallop => {
                let inside: Vec<bool> = (0..f.z.len()).map(|n| near_shallow[n] <= reach && region.contains(g.node(n % f.nx, n / f.nx))).collect();
                let lines = passes(f, &inside, step, self.grid).ok_or_else(|| {
                    Error::operation(&self.name, format!("a cusp of {} mm makes more than {} passes: ask for a larger cusp, or check the part's units", self.cusp, crate::machining::MAX_PASSES))
                })?;
                lines.iter().flat_map(|line| follow_line(&cl, line, self.allowance, skip_floor, tol.chordal)).collect()
            }
            Shallow::Raster => {
                // The plan step that leaves the cusp on the steepest shallow ground.
                let stepover = step * self.slope.to_radians().cos();
                let raster = RasterPasses { angle_deg: self.angle, stepover, pattern: Pattern::Zigzag, allowance: self.allowance, tolerance: tol.chordal, skip_floor };
                let all = raster_runs(&cl, &region, &raster, progress).ok_or(Error::Cancelled)?;
                keep_segments(all, |a, b| in_shallow((a.truncate() + b.truncate()) * 0.5))
            }
        };
        runs.extend(shallow_runs);
        if self.rest_only {
            runs = rest_only(runs, &|p: DVec2| ctx.material_estimate(p, &profile), profile.radius / 4.0, tol.gouge);
        }
        if runs.is_empty() {
            ctx.note(&self.name, if self.rest_only { "the earlier operations left nothing for it to cut (rest only)" } else { "nothing to cut in its area" });
            return Ok(Planned::default());
        }
        let Some(runs) = self.heights.keep(&self.name, ctx, runs)? else {
            return Ok(Planned::default());
        };
        let bounds = ctx.node_bounds(request);
        let floor_surface = Floor { cl: &cl, allowance: self.allowance, region: &region, bounds: Some(bounds.as_ref()) };
        Ok(vec![ctx.link(&self.name, &tool, &runs, &floor_surface, self.entry, 2.0 * profile.radius)].into())
    }
}

impl FinishSteepShallow {
    /// The CL surface it cuts on.
    pub fn request(&self, ctx: &Context) -> Result<SurfaceRequest> {
        ctx.stock_surface(&self.name, self.tool, self.grid, None, ClBuilder::Exact)
    }
}
