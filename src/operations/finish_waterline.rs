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
use crate::geom::DVec2;
use crate::machining::context::SurfaceRequest;
use crate::machining::levels::{pack, RegionWork};
use crate::machining::raster::{gradient, rest_only};
use crate::machining::settings::{Direction, Heights};
use crate::machining::waterline::{contours, heights, Spacing, LEAST_SCALLOP, SHORTEST};
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::progress::Progress;

/// Holes narrower than this many tool diameters are left to the hole operations: a helix of
/// the least radius an entry takes does not fit in them.
const NARROW_HOLE: f64 = 1.5;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::zmap::region::Region;
use crate::zmap::ClBuilder;

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
    /// The heights it cuts between (no level above its top or below its bottom), its
    /// clearance and retract.
    #[serde(flatten)]
    #[ts(flatten)]
    pub heights: Heights,
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
            heights: Heights::default(),
        }
    }
}

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
        fields.extend(Heights::fields());
        OperationForm::new("finish steep walls in levels", fields)
    }

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("stepdown", self.stepdown)?;
        self.heights.validate()?;
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
        let levels = heights(&self.name, &cl.field, request.floor, profile.radius, self.spacing())?.into_iter().map(|z| (z - self.allowance, all.clone())).collect();
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
        let steep = self.slope_min.to_radians().tan();
        let field = &cl.field;
        let slope = |p: DVec2| gradient(field, p) >= steep;
        let mut heights = heights(&self.name, field, floor, profile.radius, self.spacing())?;
        let (lowest, highest) = self.heights.window(&self.name, &ctx.stock, &ctx.part)?;
        if lowest.is_some() || highest.is_some() {
            heights.retain(|&z| z >= lowest.unwrap_or(f64::NEG_INFINITY) - 1e-9 && z <= highest.unwrap_or(f64::INFINITY) + 1e-9);
            if heights.is_empty() {
                ctx.note(&self.name, format!("no level between its bottom and top heights (Z{:.3} to Z{:.3})", lowest.unwrap_or(ctx.stock.min.z), highest.unwrap_or(ctx.stock.max.z)));
                return Ok(Planned::default());
            }
        }
        let shortest = SHORTEST.max(crate::toolpath::entry::shortest_ramp(profile.radius));
        let mut runs = contours(ctx, request, &cl, &heights, self.allowance, self.direction, &slope, shortest, progress).ok_or(Error::Cancelled)?;
        if runs.is_empty() {
            ctx.note(&self.name, format!("no area of the part is steeper than {}°", self.slope_min));
            return Ok(Planned::default());
        }
        // Holes too narrow to helix into are the hole operations' (drill, bore): a level's
        // ring inside one has no room to enter but straight down.
        let holes: Vec<crate::holes::Hole> = crate::holes::mesh::find(&ctx.part).into_iter().filter(|h| h.diameter < NARROW_HOLE * tool.cutter.diameter).collect();
        let before = runs.len();
        runs.retain(|run| !holes.iter().any(|h| run.iter().all(|p| p.truncate().distance(h.center) < h.diameter / 2.0 && p.z < h.top)));
        if runs.len() < before {
            let places: Vec<String> = holes.iter().take(5).map(|h| format!("φ{:.3} at X{:.3} Y{:.3}", h.diameter, h.center.x, h.center.y)).collect();
            ctx.note(
                &self.name,
                format!(
                    "{} of its level rings lie in holes narrower than {NARROW_HOLE} × the tool's diameter ({}{}): left to the hole operations (drill, bore), which enter them as a hole is entered",
                    before - runs.len(),
                    places.join(", "),
                    if holes.len() > 5 { ", …" } else { "" }
                ),
            );
            if runs.is_empty() {
                return Ok(Planned::default());
            }
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
    /// How far apart its levels are.
    fn spacing(&self) -> Spacing {
        Spacing { stepdown: self.stepdown, scallop: self.scallop, allowance: self.allowance, steep: self.slope_min.to_radians().tan() }
    }
}
