//! Pencil finishing (issue 60): one pass along each concave corner and fillet where the ball
//! touches the part at two places, found as the creases of the exact CL z-map
//! ([`crate::machining::pencil`]); the tip follows the exact surface along each pass
//! ([`crate::zmap::surface::ClSurface::along`]), so a pencil pass is as gouge-free as a raster pass. After a larger
//! ball it takes what that one left in the corners; with `restOnly`, only where the stock the
//! earlier operations left stands above what this one leaves.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::machining::context::SurfaceRequest;
use crate::machining::pencil::{chains, crease_nodes};
use crate::machining::raster::rest_only;
use crate::machining::scallop::{distance_from_lines, iso_lines, order};
use crate::machining::{finite, named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::progress::Progress;
use crate::toolpath::entry::Entry;
use crate::toolpath::link::Floor;
use crate::toolpath::reduce::reduce;
use crate::zmap::region::Region;
use crate::zmap::surface::point_at;
use crate::zmap::ClBuilder;

/// Pencil finishing along the part's concave corners.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FinishPencil {
    /// Shown in the program's comments. Default value: "pencil finish".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Number of the tool to use (a ball end mill). Default value: 1.
    pub tool: u32,
    /// The least bend of the tool's path across a corner that makes it a pencil line (degrees):
    /// where the ball touches two faces at once, its path turns by their angle. Default value:
    /// 20.
    pub bend: f64,
    /// Passes either side of each corner's, each a step-over farther from it across the
    /// surface (closing round its ends): a wider band cleaned where a larger tool left a
    /// fillet's width. Default value: 0 (the corner's pass alone).
    pub passes: u32,
    /// Distance between the parallel passes, measured across the surface (mm). Default value:
    /// a fifth of the tool's diameter.
    pub stepover: Option<f64>,
    /// Material left on the part (mm). Default value: 0.
    pub allowance: f64,
    /// Spacing of the CL z-map (mm): the corners are found to about half of it. Default value:
    /// 0.1.
    pub grid: f64,
    /// Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
    pub floor: Option<f64>,
    /// Longest link that may stay down (mm). Default value: the tool's diameter.
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
}

/// The most parallel passes either side of a corner.
const MOST_PASSES: u32 = 50;

impl Default for FinishPencil {
    fn default() -> Self {
        FinishPencil {
            name: "pencil finish".into(),
            enabled: true,
            tool: 1,
            bend: 20.0,
            passes: 0,
            stepover: None,
            allowance: 0.0,
            grid: 0.1,
            floor: None,
            stay_down_max: None,
            entry: Entry::default(),
            rest_only: false,
            heights: Default::default(),
        }
    }
}

impl Operate for FinishPencil {
    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::degrees("bend", "Corners that turn the tool by at least", 1.0, 90.0),
            F::int("passes", "Parallel passes either side", 0.0, Some(MOST_PASSES as f64)).note("0: the corner's pass alone"),
            F::length("stepover", "Step-over of the parallel passes", 0.001).empty("a fifth of the tool's diameter"),
            F::length("allowance", "Leave on the part", 0.0),
            F::grid().help("How finely the part's surface is sampled under the tool: the corners are found to about half of it."),
            F::check("restOnly", "only what earlier operations left (rest machining)"),
            F::number("floor", "Lowest the tip goes beside the part", U::Length).empty("the stock's bottom"),
            F::length("stayDownMax", "Longest link that stays down", 0.0).empty("the tool's diameter"),
        ]);
        fields.extend(F::entry());
        fields.extend(crate::machining::settings::Heights::fields());
        OperationForm::new("pencil: along the inside corners", fields).hint(
            "One pass along every inside corner and fillet tighter than the ball, where it touches two faces at once: what a raster or waterline finish leaves there. After a larger ball, with a smaller one.",
        )
    }

    fn allowance(&self) -> f64 {
        self.allowance
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.heights.validate()?;
        crate::machining::angle("bend", self.bend, 1.0, 90.0)?;
        not_negative("allowance", self.allowance)?;
        positive("grid", self.grid)?;
        if self.passes > MOST_PASSES {
            return Err(FieldError { field: "passes", message: format!("is at most {MOST_PASSES} either side (got {})", self.passes) });
        }
        if let Some(s) = self.stepover {
            positive("stepover", s)?;
        }
        self.entry.validate()?;
        if let Some(f) = self.floor {
            finite("floor", f)?;
        }
        if let Some(d) = self.stay_down_max {
            not_negative("stayDownMax", d)?;
        }
        Ok(())
    }

    fn surfaces(&self, ctx: &Context) -> Result<Vec<SurfaceRequest>> {
        Ok(vec![self.request(ctx)?])
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let profile = tool.cutter.profile();
        if !progress.stage("CL z-map", 0.0, 0.5) {
            return Err(Error::Cancelled);
        }
        let request = self.request(ctx)?;
        let cl = ctx.cl_surface(request, progress)?;
        if !progress.stage("corners", 0.5, 0.5) {
            return Err(Error::Cancelled);
        }
        let tol = ctx.tolerances;
        let floor = request.floor;
        let marked = crease_nodes(&cl.field, self.bend.to_radians(), floor);
        // Corners shorter than the tool's radius are a node's noise; the lines kept within a
        // quarter of the grid of the nodes they join.
        let mut lines = chains(&cl.field, &marked, profile.radius, 0.25 * self.grid);
        if self.passes > 0 && !lines.is_empty() {
            // The parallel passes: level lines of the distance from the corners' lines across
            // the surface, outermost first, each round its corner (scallop finishing's).
            let step = self.stepover.unwrap_or(0.4 * profile.radius);
            let inside = vec![true; cl.field.z.len()];
            let d = distance_from_lines(&cl.field, &inside, &lines);
            let levels: Vec<f64> = (1..=self.passes).rev().map(|k| k as f64 * step).collect();
            let around: Vec<Vec<DVec2>> = iso_lines(&cl.field, &d, &levels).into_iter().flat_map(order).filter(|l| l.len() > 1).collect();
            lines = around.into_iter().chain(order(lines)).collect();
        }
        let mut runs: Vec<Vec<DVec3>> = lines
            .iter()
            .map(|line| {
                let mut run: Vec<DVec3> = Vec::new();
                for w in line.windows(2) {
                    let along = cl.along(w[0], w[1]);
                    let skip = usize::from(!run.is_empty());
                    run.extend(along.into_iter().skip(skip).map(|(t, z)| point_at(w[0], w[1], t).extend(z + self.allowance)));
                }
                reduce(&run, tol.chordal)
            })
            .filter(|run| run.len() > 1)
            .collect();
        if self.rest_only {
            runs = rest_only(runs, &|p: DVec2| ctx.material_estimate(p, &profile), profile.radius / 4.0, tol.gouge);
        }
        if runs.is_empty() {
            ctx.note(&self.name, if self.rest_only { "no inside corner left for it to cut (rest only)" } else { "the part has no inside corner tighter than the tool" });
            return Ok(Planned::default());
        }
        let stock = ctx.stock;
        let region = Region::Rect { min: stock.min.truncate(), max: stock.max.truncate() };
        let Some(runs) = self.heights.keep(&self.name, ctx, runs)? else {
            return Ok(Planned::default());
        };
        let bounds = ctx.node_bounds(request);
        let floor_surface = Floor { cl: &cl, allowance: self.allowance, region: &region, bounds: Some(bounds.as_ref()) };
        Ok(vec![ctx.link(&self.name, &tool, &runs, &floor_surface, self.entry, self.stay_down_max.unwrap_or(2.0 * profile.radius))].into())
    }
}

impl FinishPencil {
    /// The CL surface it cuts on.
    pub fn request(&self, ctx: &Context) -> Result<SurfaceRequest> {
        ctx.stock_surface(&self.name, self.tool, self.grid, self.floor, ClBuilder::Exact)
    }
}
