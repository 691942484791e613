//! Raster finishing on the CL z-map: the CL-Cartesian method of seed 001 §1 — parallel vertical
//! planes cut the CL surface, and the tool tip follows the cut.
//!
//! Steps, in order:
//! 1. lay parallel passes at `angle` and `stepover` across the region's bounds;
//! 2. follow the exact CL surface along each pass ([`crate::zmap::surface::ClSurface::along`]: even pieces no longer
//!    than the grid spacing (half for cutters other than balls), probed at midpoints and quarters and subdivided until the surface
//!    between two samples stays within the tolerance of the chord), and split it where it
//!    leaves the region; passes are independent, so they run on every core;
//! 3. lift every point by the allowance and reduce within the chordal tolerance, never below;
//! 4. order the runs (zigzag or one way); linking is left to [`crate::toolpath::link`].

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::machining::context::SurfaceRequest;
pub use crate::machining::raster::Boundary;
use crate::machining::raster::{check_points, join_passes, raster_runs, rest_only, shallow_only, Pattern, RasterPasses};
use crate::machining::{finite, named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::progress::Progress;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::zmap::region::Region;
use crate::zmap::ClBuilder;

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
    /// The heights it cuts between (what lies above its top or below its bottom is left),
    /// its clearance and retract.
    #[serde(flatten)]
    #[ts(flatten)]
    pub heights: crate::machining::settings::Heights,
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
            heights: Default::default(),
            slope_max: None,
        }
    }
}

impl Operate for FinishRaster {
    fn plans_round_fixtures(&self) -> bool {
        true
    }
    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_end_mills_and_v_bits(cutter)
    }

    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::length("stepover", "Step-over", 0.01),
            F::number("angle", "Pass angle", U::Degrees),
            F::choice("pattern", "Passes", &[("zigzag", "back and forth"), ("oneWay", "one way")]),
            F::area(),
            F::outline_growth(),
            F::length("allowance", "Leave on the part", 0.0),
            F::grid().help("How finely the part's surface is sampled under the tool: the tool's lowest safe height is worked out at points this far apart, and the passes follow the exact surface between them. Finer: slower to compute, closer into narrow places."),
            F::choice("builder", "Surface", &[("exact", "exact (safe everywhere)"), ("inverseOffset", "fast estimate (leaves some at walls)")]).help("Exact: the tool's lowest safe height at every point, from every facet, edge and corner of the part. Fast estimate: from the part's heights alone: quicker, but it can leave material at steep walls. (The methods: seed 001 §3.3 and §3.1.)"),
            F::degrees("slopeMax", "Only where no steeper than", 0.0, 90.0).empty("everywhere"),
            F::check("restOnly", "only what earlier operations left (rest machining)"),
            F::number("floor", "Lowest the tip goes beside the part", U::Length).empty("the stock's bottom"),
            F::length("stayDownMax", "Longest link that stays down", 0.0).empty("twice the step-over"),
        ]);
        fields.extend(F::entry());
        fields.extend(crate::machining::settings::Heights::fields());
        OperationForm::new("finish by parallel passes", fields)
    }

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.heights.validate()?;
        positive("stepover", self.stepover)?;
        positive("grid", self.grid)?;
        not_negative("allowance", self.allowance)?;
        crate::machining::angle("angle", self.angle, -360.0, 360.0)?;
        self.entry.validate()?;
        if let Some(m) = self.margin {
            finite("margin", m)?;
        }
        if let Some(f) = self.floor {
            finite("floor", f)?;
        }
        if let Some(d) = self.stay_down_max {
            not_negative("stayDownMax", d)?;
        }
        if let Some(s) = self.slope_max {
            crate::machining::angle("slopeMax", s, 0.0, 90.0)?;
        }
        Ok(())
    }

    fn check_scale(&self, ctx: &Context) -> Result<()> {
        check_points(ctx, &self.name, self.stepover, self.grid)
    }

    fn surfaces(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        Ok(vec![self.request(ctx)?])
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
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
                return Ok(Planned::default());
            }
        }
        let Some(runs) = self.heights.keep(&self.name, ctx, runs)? else {
            return Ok(Planned::default());
        };
        let bounds = ctx.node_bounds(request);
        let floor_surface = Floor { cl: &cl, allowance: self.allowance, region: &region, bounds: Some(bounds.as_ref()) };
        Ok(vec![ctx.link(&self.name, &tool, &runs, &floor_surface, self.entry, self.stay_down_max.unwrap_or(2.0 * self.stepover))].into())
    }
}

impl FinishRaster {
    /// The CL surface it cuts on.
    pub fn request(&self, ctx: &Context) -> Result<SurfaceRequest> {
        ctx.stock_surface(&self.name, self.tool, self.grid, self.floor, self.builder)
    }

    /// Where its passes run and how: the region (the stock, or the part's silhouette grown by
    /// the margin) and the passes' settings.
    pub fn layout(&self, ctx: &mut Context) -> Result<(Region, RasterPasses)> {
        let request = self.request(ctx)?;
        let (profile, floor) = (request.profile, request.floor);
        let margin = self.margin.unwrap_or(profile.radius);
        let region = self.boundary.region(ctx, request, margin);
        let skip_floor = (self.boundary == Boundary::Silhouette && margin <= profile.radius).then_some(floor);
        let passes = RasterPasses { angle_deg: self.angle, stepover: self.stepover, pattern: self.pattern, allowance: self.allowance, tolerance: ctx.tolerances.chordal, skip_floor };
        Ok((region, passes))
    }
}
