//! Scallop finishing (issue 60): passes at a constant step across the surface, so the cusp
//! between them is the one asked for on steep ground and shallow alike — what a raster finish
//! (a constant step in plan) leaves too high on the steep and cuts too fine on the flat.
//!
//! Steps, in order ([`crate::machining::scallop`]):
//! 1. the exact CL z-map over the stock (seed 001 §3.3), and the area: the part's silhouette
//!    grown by the margin, or the stock;
//! 2. the step from the cusp: 2√(2ah − h²) for the ball's (or the bull-nose's corner's) radius
//!    a, with h the cusp less the chordal tolerance the passes are reduced within;
//! 3. every node's distance from the area's edge over the CL surface, and its level lines half
//!    a step from the edge and a step apart; a pass along each ridge the fronts leave between
//!    them;
//! 4. the tip follows the exact CL surface along every pass, as raster finishing's does
//!    ([`crate::zmap::surface::ClSurface::along`]); the passes are cut nearest-first and linked
//!    by the shared linker.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::machining::context::SurfaceRequest;
use crate::machining::raster::{follow_line, rest_only, shallow_only, Boundary};
use crate::machining::scallop::{cusp_step, passes};
use crate::machining::{finite, named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::progress::Progress;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::zmap::ClBuilder;

/// Scallop finishing: passes a step apart over the surface for a given cusp height.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FinishScallop {
    /// Shown in the program's comments. Default value: "scallop finish".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Number of the tool to use (a ball or bull-nose end mill). Default value: 1.
    pub tool: u32,
    /// Height of the ridge left between two passes (mm): the step between them follows from
    /// it and the tool's radius, measured across the surface. Default value: 0.01.
    pub cusp: f64,
    /// Default value: silhouette.
    pub boundary: Boundary,
    /// Growth of the silhouette boundary (mm). Default value: the tool's radius.
    pub margin: Option<f64>,
    /// Material left on the part (mm). Default value: 0.
    pub allowance: f64,
    /// Spacing of the CL z-map (mm). Default value: 0.2.
    pub grid: f64,
    /// Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
    pub floor: Option<f64>,
    /// Longest link that may stay down (mm). Default value: twice the step.
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
    /// Only where the surface is no steeper than this (degrees from horizontal). Default
    /// value: none (everywhere).
    pub slope_max: Option<f64>,
}

impl Default for FinishScallop {
    fn default() -> Self {
        FinishScallop {
            name: "scallop finish".into(),
            enabled: true,
            tool: 1,
            cusp: 0.01,
            boundary: Boundary::Silhouette,
            margin: None,
            allowance: 0.0,
            grid: 0.2,
            floor: None,
            stay_down_max: None,
            entry: Entry::default(),
            rest_only: false,
            heights: Default::default(),
            slope_max: None,
        }
    }
}

impl Operate for FinishScallop {
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
            F::length("cusp", "Cusp height (scallop) left", 0.0001).help("The height of the ridge between two passes: the step between them follows from it and the tool's corner radius, measured across the surface, so steep ground gets the same finish as flat."),
            F::area(),
            F::outline_growth(),
            F::length("allowance", "Leave on the part", 0.0),
            F::grid().help("How finely the part's surface is sampled under the tool: the passes are laid out on it and follow the exact surface between its points."),
            F::degrees("slopeMax", "Only where no steeper than", 0.0, 90.0).empty("everywhere"),
            F::check("restOnly", "only what earlier operations left (rest machining)"),
            F::number("floor", "Lowest the tip goes beside the part", U::Length).empty("the stock's bottom"),
            F::length("stayDownMax", "Longest link that stays down", 0.0).empty("twice the step"),
        ]);
        fields.extend(F::entry());
        fields.extend(crate::machining::settings::Heights::fields());
        OperationForm::new("scallop: a constant cusp over the surface", fields).hint(
            "Passes offset from the area's edge across the surface, a step apart for the cusp height you ask: the same finish on steep and flat ground, in fewer passes than a raster finish fine enough for the steep.",
        )
    }

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.heights.validate()?;
        positive("cusp", self.cusp)?;
        positive("grid", self.grid)?;
        not_negative("allowance", self.allowance)?;
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
        let profile = ctx.tool(&self.name, self.tool)?.cutter.profile();
        let step = cusp_step(&self.name, self.cusp, profile.corner, ctx.tolerances.chordal)?;
        crate::machining::raster::check_points(ctx, &self.name, step, self.grid)
    }

    fn surfaces(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        Ok(vec![self.request(ctx)?])
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let profile = tool.cutter.profile();
        let tol = ctx.tolerances;
        let step = cusp_step(&self.name, self.cusp, profile.corner, tol.chordal)?;
        if !progress.stage("CL z-map", 0.0, 0.4) {
            return Err(Error::Cancelled);
        }
        let request = self.request(ctx)?;
        let cl = ctx.cl_surface(request, progress)?;
        if !progress.stage("passes", 0.4, 0.6) {
            return Err(Error::Cancelled);
        }
        let f = &cl.field;
        let g = f.grid();
        let margin = self.margin.unwrap_or(profile.radius);
        let region = self.boundary.region(ctx, request, margin);
        let inside: Vec<bool> = (0..f.z.len()).map(|n| region.contains(g.node(n % f.nx, n / f.nx))).collect();
        let lines = passes(f, &inside, step, self.grid).ok_or_else(|| {
            Error::operation(&self.name, format!("a cusp of {} mm makes more than {} passes: ask for a larger cusp, or check the part's units", self.cusp, crate::machining::MAX_PASSES))
        })?;
        if !progress.report(0.6) {
            return Err(Error::Cancelled);
        }
        let skip_floor = (self.boundary == Boundary::Silhouette && margin <= profile.radius).then_some(request.floor);
        let mut runs: Vec<Vec<DVec3>> = Vec::new();
        for line in lines {
            runs.extend(follow_line(&cl, &line, self.allowance, skip_floor, tol.chordal));
        }
        if let Some(limit) = self.slope_max {
            runs = shallow_only(runs, f, limit.to_radians().tan());
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
        Ok(vec![ctx.link(&self.name, &tool, &runs, &floor_surface, self.entry, self.stay_down_max.unwrap_or(2.0 * step))].into())
    }
}

impl FinishScallop {
    /// The CL surface it cuts on.
    pub fn request(&self, ctx: &Context) -> Result<SurfaceRequest> {
        ctx.stock_surface(&self.name, self.tool, self.grid, self.floor, ClBuilder::Exact)
    }
}
