//! 2.5D pocketing of drawn regions, islands respected: rings inside-out or zigzag passes and a
//! finishing ring, pass by pass down to the depth (the clearing is [`crate::machining::rings`],
//! shared with z-level roughing).

use serde::{Deserialize, Serialize};

use crate::drawing::{Loop, Shape};
use crate::geom::tolerance::LEAST_STEP;
use crate::machining::path2d::does_not_fit;
use crate::machining::report::SheetCut;
use crate::machining::rings::{clear_down, Clearing, RingSetup};
use crate::machining::settings::{Direction, EntryKind, LoadControl, PocketPattern};
use crate::machining::{named_operation, not_negative, positive, sheet, Context, FieldError, Operate, Planned};
use crate::toolpath::Move;

/// Pocket operation on a drawing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Pocket2d {
    /// Default value: "pocket".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Default value: 1.
    pub tool: u32,
    /// Depth below the stock top (mm). Default value: 3.
    pub depth: f64,
    /// Largest depth cut in one pass (mm). Default value: 1.
    pub stepdown: f64,
    /// Distance between rings or passes as a fraction of the tool diameter. Default value: 0.4.
    pub stepover_fraction: f64,
    /// Material left on walls and islands (mm). Default value: 0.
    pub leave_stock: f64,
    /// Default value: offset.
    pub pattern: PocketPattern,
    /// Direction of zigzag passes (degrees from +X). Default value: 0.
    pub angle: f64,
    /// How the zigzag pattern holds the tool's load at the step-over's (seed 004 §3). Default
    /// value: path.
    pub load: LoadControl,
    /// How far over the reference load a zigzag step may go (0.1: 10 %). Default value: 0.1.
    pub load_tolerance: f64,
    /// Default value: helix.
    pub entry: EntryKind,
    /// Helix radius (mm). Default value: 0.4 × the tool diameter.
    pub helix_radius: Option<f64>,
    /// Steepest descent of helices and ramps (degrees). Default value: 3.
    pub ramp_angle: f64,
    /// Default value: climb.
    pub direction: Direction,
    /// Layers to pocket (empty: all). Default value: empty.
    pub layers: Vec<String>,
    /// Indices of the drawing's loops bounding the pocket, with the holes inside them as
    /// islands (empty: all). Default value: empty.
    pub loops: Vec<usize>,
    /// Its own clearance (and retract) in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Moves,
}

impl Default for Pocket2d {
    fn default() -> Self {
        Pocket2d {
            name: "pocket".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            depth: 3.0,
            stepdown: 1.0,
            stepover_fraction: 0.4,
            leave_stock: 0.0,
            pattern: PocketPattern::Offset,
            angle: 0.0,
            load: LoadControl::Path,
            load_tolerance: 0.1,
            entry: EntryKind::Helix,
            helix_radius: None,
            ramp_angle: 3.0,
            direction: Direction::Climb,
            layers: Vec::new(),
            loops: Vec::new(),
        }
    }
}

/// The moves of a pocket over `region` (outer loops counter-clockwise, islands clockwise).
pub fn pocket_moves(region: &Shape, op: &Pocket2d, s: &mut RingSetup) -> Result<Vec<Move>, String> {
    let r = s.tool_radius;
    let clearing = clearing(op, r);
    clear_down(region, r + op.leave_stock, &clearing, op.depth, op.stepdown, s).ok_or_else(|| does_not_fit(r, op.leave_stock, "the pocket", &region.bounds()))
}

/// How `op` clears with a tool of radius `r`: its rings or passes, and its entry.
fn clearing(op: &Pocket2d, r: f64) -> Clearing {
    Clearing {
        step: (op.stepover_fraction.clamp(0.01, 1.0) * 2.0 * r).max(LEAST_STEP),
        climb: op.direction == Direction::Climb,
        pattern: op.pattern,
        angle: op.angle.to_radians(),
        load: op.load,
        load_tolerance: op.load_tolerance,
        entry: op.entry,
        ramp_angle: op.ramp_angle.clamp(0.1, 90.0).to_radians(),
        helix_r: op.helix_radius.unwrap_or(0.8 * r),
        depth: None,
        adaptive_steps: Default::default(),
    }
}

impl Operate for Pocket2d {
    named_operation!(OnDrawing);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm};
        let mut fields = F::sheet_cut();
        fields.extend([
            F::length("leaveStock", "Leave on walls", 0.0),
            F::direction(),
            F::choice("pattern", "Pattern", &[("offset", "rings (offset)"), ("zigzag", "zigzag"), ("adaptive", "adaptive (constant engagement)")]),
            F::number("angle", "Zigzag pass angle", U::Degrees),
            F::load(
                "Zigzag: keep the load even by",
                "Where a zigzag pass would take a heavier cut than a full step-over (into a corner), the path adds a short detour to keep the chip load even, or the feed drops there.",
            ),
            F::number("loadTolerance", "Zigzag: load allowed over the even one", U::None).note("fraction").range(0.0, None),
            F::fraction("stepoverFraction", "Step-over", "fraction of the tool's diameter", 1.0),
            F::choice("entry", "Entry", &[("helix", "helix"), ("ramp", "ramp")]),
            F::length("helixRadius", "Helix radius", 0.01).empty("0.4 × the tool's diameter"),
            F::loops("Loops", "numbers with commas, or click them in the view", "every loop on the layers"),
            F::ramp_angle(),
        ]);
        fields.extend(crate::machining::settings::Moves::fields());
        OperationForm::new("pocket (2D)", fields)
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.stepdown)
    }

    fn check_scale(&self, ctx: &Context) -> crate::error::Result<()> {
        sheet::check_levels(ctx, &self.name, Some(self.depth), self.stepdown)
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.moves.validate()?;
        positive("depth", self.depth)?;
        positive("stepdown", self.stepdown)?;
        crate::machining::fraction("stepoverFraction", self.stepover_fraction)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)?;
        not_negative("leaveStock", self.leave_stock)?;
        crate::machining::angle("angle", self.angle, -360.0, 360.0)?;
        not_negative("loadTolerance", self.load_tolerance)?;
        if let Some(r) = self.helix_radius {
            positive("helixRadius", r)?;
        }
        if self.pattern == PocketPattern::Adaptive {
            crate::machining::adaptive::check_load(self.stepover_fraction)?;
        }
        Ok(())
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> crate::error::Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let (drawing, _) = sheet::sheet(ctx, &self.name)?;
        let (walls, picked) = sheet::selected(drawing, &self.name, &self.layers, &self.loops)?;
        let open = drawing.open_note(&self.layers);
        let picked: Vec<Loop> = picked.iter().map(|&k| walls.shape.loops[k].clone()).collect();
        let region = sheet::pocket_region(&walls.shape, &picked, self.loops.is_empty());
        let mut cursor = sheet::cursor(ctx, &tool);
        let mut setup = RingSetup { tool_radius: tool.cutter.radius(), top: ctx.stock.max.z, feed: tool.feed_rate, cursor: &mut cursor, tol: &ctx.tolerances, unfinished: false };
        clearing(self, tool.cutter.radius()).check_helix(&self.name, self.stepdown.min(self.depth))?;
        let moves = pocket_moves(&region, self, &mut setup).map_err(|e| crate::error::Error::operation(&self.name, e))?;
        if setup.unfinished {
            ctx.warn(&self.name, crate::machining::adaptive::unfinished(&[]));
        }
        let cuts = vec![SheetCut { region, inside: true, depth: self.depth, leave: self.leave_stock, scrap: false }];
        if let Some(note) = open {
            ctx.warn(&self.name, note);
        }
        if moves.is_empty() {
            ctx.note(&self.name, "the pocket has no material left to its depth (earlier operations cut it away)");
            return Ok(Planned { cuts, ..Planned::default() });
        }
        let r = tool.cutter.radius();
        let engagement = (self.pattern == PocketPattern::Adaptive).then(|| crate::machining::report::EngagementTarget {
            angle: crate::machining::adaptive::Adaptive::angle_of((2.0 * r * self.stepover_fraction).min(2.0 * r), r),
            climb: self.direction == Direction::Climb,
            levels: Vec::new(),
        });
        Ok(Planned { paths: vec![sheet::toolpath(&self.name, &tool, moves, ctx.heights.clearance)], cuts, engagement, ..Planned::default() })
    }
}
