//! Facing: the stock's top cleared down to a height (the part's top by default, or a given
//! depth below the stock's top) in step-downs, by zigzag passes or an inward rectangular
//! spiral, the tool overlapping the stock's outline by a share of its diameter (half by
//! default) so no ridge stands at the edge, each level entered from outside the stock. The
//! step-over never exceeds the tool's flat width, so no ridge stands between passes.
//!
//! On a drawing, facing takes the whole sheet, or the insides of chosen loops (`loops`): a
//! region cleared to the depth by the pocket's rings or passes ([`clear_down`]), the tool past
//! the loops by the same overlap, entered by a helix or a ramp where the region lies inside
//! the sheet. What it takes is the part's to lose (a [`SheetCut`] for the verification).

use serde::{Deserialize, Serialize};

use crate::drawing::{Loop, Shape};
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::machining::report::SheetCut;
use crate::machining::rings::{clear_down, Clearing, RingSetup};
use crate::machining::settings::PocketPattern;
use crate::machining::{named_operation, not_negative, positive, sheet, Context, FieldError, Operate, Planned};
use crate::tool::Tool;
use crate::toolpath::{Move, Toolpath};

/// How a level is cleared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum FacePattern {
    /// Passes along X, back and forth.
    #[default]
    Zigzag,
    /// Rectangular rings from the outside in.
    Spiral,
}

/// Facing the stock's top.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Face {
    /// Default value: "face".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// A flat end mill or face mill. Default value: 1.
    pub tool: u32,
    /// How much to take off the stock's top (mm). Default value: down to the part's top.
    pub depth: Option<f64>,
    /// Largest depth cut in one level (mm). Default value: 1.
    pub stepdown: f64,
    /// Distance between passes (fraction of the tool's diameter, at most its flat). Default value: 0.7.
    pub stepover_fraction: f64,
    /// How far the tool reaches past the stock's outline (fraction of its diameter). Default value: 0.5.
    pub overlap: f64,
    /// Default value: zigzag.
    pub pattern: FacePattern,
    /// A drawing's loops whose insides to face, as `swarf drawing` numbers them (the holes
    /// inside them faced over); empty: the whole stock. Default value: empty.
    pub loops: Vec<usize>,
    /// Its own clearance (and retract) in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Moves,
}

impl Default for Face {
    fn default() -> Self {
        Face {
            name: "face".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            depth: None,
            stepdown: 1.0,
            stepover_fraction: 0.7,
            overlap: 0.5,
            pattern: FacePattern::Zigzag,
            loops: Vec::new(),
        }
    }
}

impl Operate for Face {
    named_operation!(Either);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{Applies, FieldUnit as U, FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::length("depth", "Depth off the stock's top", 0.01).empty("down to the part's top"),
            F::length("stepdown", "Step-down", 0.01),
            F::fraction("stepoverFraction", "Step-over", "fraction of the tool's diameter, at most its flat", 1.0),
            F::number("overlap", "Past the stock's edge, or the region's loops", U::None).note("fraction of the tool's diameter").range(0.0, Some(1.0)),
            F::choice("pattern", "Pattern", &[("zigzag", "zigzag"), ("spiral", "spiral inwards")]),
            F::loops("Region", "a drawing's loops to face inside: numbers with commas, or click them in the view", "the whole sheet").applies(Applies::Drawing),
        ]);
        fields.extend(crate::machining::settings::Moves::fields());
        OperationForm::new("face the stock's top", fields)
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.stepdown)
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        if let Some(d) = self.depth {
            positive("depth", d)?;
        }
        positive("stepdown", self.stepdown)?;
        crate::machining::fraction("stepoverFraction", self.stepover_fraction)?;
        not_negative("overlap", self.overlap)?;
        if self.overlap > 1.0 {
            return Err(FieldError { field: "overlap", message: format!("must be at most 1 (the tool's whole diameter past the edge; got {})", self.overlap) });
        }
        Ok(())
    }

    fn check_scale(&self, ctx: &Context) -> Result<()> {
        let depth = match self.depth {
            Some(d) => d,
            None if ctx.sheet.is_some() => return Ok(()), // planning says what is missing
            None => ctx.stock.max.z - ctx.part.bounds().max.z,
        };
        crate::machining::too_many(&self.name, "levels", (depth / self.stepdown).ceil(), crate::machining::MAX_LEVELS, "stepdown", self.stepdown, depth)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cutter = &tool.cutter;
        if cutter.is_cone() || cutter.shape == crate::cutter::Shape::Ball {
            return Err(Error::operation(&self.name, format!("facing needs a flat end mill, face mill or bull nose; T{} is a {}", tool.number, cutter.describe())));
        }
        let top = ctx.stock.max.z;
        let target = match self.depth {
            Some(d) => top - d,
            None if ctx.sheet.is_some() => return Err(Error::operation(&self.name, "a sheet's top is the drawing's: give the depth to face off")),
            None => ctx.part.bounds().max.z,
        };
        if target >= top - 1e-9 {
            return Err(Error::operation(&self.name, format!("nothing to face: the part's top ({target:.3}) is the stock's top; give a depth, or more stock over the face that is up (Stock: 'Stock above the part's top', or for a setup that turns the part over, 'Stock below the part')")));
        }
        let r = cutter.radius();
        let flat = 2.0 * (r - cutter.corner());
        let step = (self.stepover_fraction * cutter.diameter).min(flat);
        if step <= 1e-6 {
            return Err(Error::operation(&self.name, "the tool has no flat to face with"));
        }
        if !self.loops.is_empty() {
            return self.plan_region(ctx, &tool, top - target, step);
        }
        // The rectangle the tool's centre covers: the stock's outline, out by the overlap less
        // the radius (half a diameter of overlap: the centre on the edge).
        let out = self.overlap * cutter.diameter - r;
        let (lo, hi) = (ctx.stock.min.truncate() - DVec2::splat(out), ctx.stock.max.truncate() + DVec2::splat(out));
        if hi.x < lo.x || hi.y < lo.y {
            return Err(Error::operation(&self.name, "the stock is narrower than the tool's overlap leaves room for"));
        }
        let levels = ((top - target) / self.stepdown - 1e-9).ceil().max(1.0) as usize;
        let clearance = ctx.heights.clearance;
        // Entered from outside the stock, clear of it by the radius and a millimetre.
        let outside = ctx.stock.min.x - r - 1.0;
        let feed = tool.feed_rate;
        let mut moves: Vec<Move> = Vec::new();
        for k in 1..=levels {
            let z = top + (target - top) * k as f64 / levels as f64;
            let pass = match self.pattern {
                FacePattern::Zigzag => zigzag(lo, hi, step, z),
                FacePattern::Spiral => spiral(lo, hi, step, z),
            };
            let first = pass[0];
            let entry = DVec3::new(outside.min(first.x - r - 1.0), first.y, z);
            moves.push(Move::Rapid { to: entry.truncate().extend(clearance) });
            moves.push(Move::Rapid { to: entry });
            for p in pass {
                moves.push(Move::Line { to: p, feed });
            }
            let last = moves.last().map_or(entry, |m| m.to());
            moves.push(Move::Rapid { to: last.truncate().extend(clearance) });
        }
        let start = moves[0].to();
        let path = Toolpath { name: self.name.clone(), tool: tool.number, spindle_rpm: tool.spindle_rpm, start, moves, cycles: Vec::new() };
        // On a sheet the faced top is the part's to lose: the stock's outline, as far past it as
        // the tool reaches.
        let cuts = match ctx.sheet {
            Some(_) => vec![SheetCut { region: Shape::new(vec![Loop::rect(ctx.stock.min.truncate(), ctx.stock.max.truncate())]), inside: true, depth: top - target, leave: -(out + r), scrap: false }],
            None => Vec::new(),
        };
        Ok(Planned { paths: vec![path], cuts, ..Planned::default() })
    }
}

impl Face {
    /// Faces the insides of a drawing's chosen loops `depth` down from the sheet's top.
    fn plan_region(&self, ctx: &mut Context, tool: &Tool, depth: f64, step: f64) -> Result<Planned> {
        let (drawing, _) = sheet::sheet(ctx, &self.name).map_err(|_| Error::operation(&self.name, "faces a drawing's loops; a 3D part's top is faced whole (leave loops empty)"))?;
        let (walls, picked) = sheet::selected(drawing, &self.name, &[], &self.loops)?;
        // Each picked loop's inside, once: a loop inside another picked one is faced with it.
        let chosen: Vec<Loop> = picked.iter().map(|&k| walls.shape.loops[k].counter_clockwise()).collect();
        let outer: Vec<Loop> = chosen
            .iter()
            .enumerate()
            .filter(|&(i, l)| !chosen.iter().enumerate().any(|(j, m)| j != i && m.contains(l.probe_point()) && !l.contains(m.probe_point())))
            .map(|(_, l)| l.clone())
            .collect();
        let region = Shape::new(outer);
        let r = tool.cutter.radius();
        let past = self.overlap * tool.cutter.diameter;
        let pattern = match self.pattern {
            FacePattern::Zigzag => PocketPattern::Zigzag,
            FacePattern::Spiral => PocketPattern::Offset,
        };
        let clearing = Clearing::plain(step, r, pattern);
        let mut cursor = sheet::cursor(ctx, tool);
        let mut setup = RingSetup { tool_radius: r, top: ctx.stock.max.z, feed: tool.feed_rate, cursor: &mut cursor, tol: &ctx.tolerances, unfinished: false };
        let moves = clear_down(&region, r - past, &clearing, depth, self.stepdown, &mut setup).ok_or_else(|| Error::operation(&self.name, "the loops are too small for the tool"))?;
        let cuts = vec![SheetCut { region, inside: true, depth, leave: -past, scrap: false }];
        if moves.is_empty() {
            ctx.note(&self.name, "nothing left to face in the loops (earlier operations cut it away)");
            return Ok(Planned { cuts, ..Planned::default() });
        }
        Ok(Planned { paths: vec![sheet::toolpath(&self.name, tool, moves, ctx.heights.clearance)], cuts, ..Planned::default() })
    }
}

/// Passes along X over `[lo, hi]`, `step` apart in Y (the last on `hi.y`), back and forth.
fn zigzag(lo: DVec2, hi: DVec2, step: f64, z: f64) -> Vec<DVec3> {
    let n = ((hi.y - lo.y) / step - 1e-9).ceil().max(0.0) as usize;
    let mut out = Vec::with_capacity(2 * n + 2);
    for k in 0..=n {
        let y = if n == 0 { lo.y } else { lo.y + (hi.y - lo.y) * k as f64 / n as f64 };
        let (a, b) = if k % 2 == 0 { (lo.x, hi.x) } else { (hi.x, lo.x) };
        out.push(DVec3::new(a, y, z));
        out.push(DVec3::new(b, y, z));
    }
    out
}

/// Rectangular rings over `[lo, hi]` from the outside in, `step` apart, each joined to the
/// next by a step inwards; the last a line or a point where the rectangle closes.
fn spiral(lo: DVec2, hi: DVec2, step: f64, z: f64) -> Vec<DVec3> {
    let (mut a, mut b) = (lo, hi);
    let mut out = Vec::new();
    loop {
        out.push(DVec3::new(a.x, a.y, z));
        if b.x - a.x <= 1e-9 || b.y - a.y <= 1e-9 {
            out.push(DVec3::new(b.x, b.y, z));
            break;
        }
        out.extend([DVec3::new(b.x, a.y, z), DVec3::new(b.x, b.y, z), DVec3::new(a.x, b.y, z), DVec3::new(a.x, a.y + step.min((b.y - a.y) / 2.0), z)]);
        // The next ring in by a step (or to the middle where less is left).
        let s = step.min((b.x - a.x) / 2.0).min((b.y - a.y) / 2.0);
        a += DVec2::splat(s);
        b -= DVec2::splat(s);
        if s < step - 1e-9 {
            out.push(DVec3::new(a.x, a.y, z));
            out.push(DVec3::new(b.x, b.y, z));
            break;
        }
    }
    out
}
