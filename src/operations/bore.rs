//! Helical boring: a hole wider than the tool milled on a helix (the tool's centre circling
//! the hole's axis while it descends a pitch per turn), a full circle at the bottom to level
//! the floor, in rings from the axis out where the hole is more than twice the tool (no core
//! left standing), and an optional finishing pass climbing the wall at a small step. Climb by
//! default (counter-clockwise for a clockwise spindle); the tool never comes nearer the hole's
//! wall than its radius plus the leave-stock.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::segment::Segment;
use crate::holes::Hole;
use crate::machining::holes::{circle, entry_height, helix, hole_path, point, HolePick};
use crate::machining::report::Groove;
use crate::machining::settings::Direction;
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::tool::Tool;
use crate::toolpath::Move;

/// Helical boring of holes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Bore {
    /// Default value: "bore".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// Default value: 1.
    pub tool: u32,
    /// The holes to bore.
    #[serde(flatten)]
    #[ts(flatten)]
    pub pick: HolePick,
    /// Descent per turn of the helix (mm). Default value: 1.
    pub pitch: f64,
    /// Step between rings where the hole is more than twice the tool (fraction of the tool's
    /// diameter). Default value: 0.4.
    pub stepover_fraction: f64,
    /// Material left on the wall (mm). Default value: 0.
    pub leave_stock: f64,
    /// The finishing pass's radial step (mm; 0: none): the wall is roughed this much short,
    /// then finished climbing from the bottom. Default value: 0.
    pub finish_step: f64,
    /// Depth below each hole's top (mm). Default value: the hole's own (through: past its
    /// bottom by the breakthrough).
    pub depth: Option<f64>,
    /// How far past a through hole's bottom (mm). Default value: 0.5.
    pub breakthrough: f64,
    /// Height above the material over the hole where the helix starts (mm). Default value: 1.
    pub retract: f64,
    /// Default value: climb.
    pub direction: Direction,
    /// Its own clearance in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Clearance,
}

impl Default for Bore {
    fn default() -> Self {
        Bore {
            name: "bore".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            pick: HolePick::default(),
            pitch: 1.0,
            stepover_fraction: 0.4,
            leave_stock: 0.0,
            finish_step: 0.0,
            depth: None,
            breakthrough: 0.5,
            retract: 1.0,
            direction: Direction::Climb,
        }
    }
}

impl Bore {
    /// How deep it bores `h`: to its depth where one is set, else the hole's own (a through
    /// hole past its bottom by the breakthrough).
    fn bottom(&self, h: &Hole) -> f64 {
        match self.depth {
            Some(d) => h.top - d,
            None if h.through => h.bottom - self.breakthrough,
            None => h.bottom,
        }
    }

    /// The setting that does not fit boring `h` to `bottom` with `tool`, with its field: a tool
    /// too wide for the hole, a hole deeper than the flutes.
    fn misfit(&self, h: &Hole, bottom: f64, tool: &Tool) -> Option<(&'static str, String)> {
        if h.diameter / 2.0 - self.leave_stock - tool.cutter.radius() <= 1e-3 {
            return Some((
                "tool",
                format!(
                    "T{} (φ{}) does not fit the φ{} hole at X{:.3} Y{:.3} with {} mm left on its wall: bore with a smaller tool, or drill it",
                    tool.number,
                    tool.cutter.diameter,
                    crate::limits::shown((h.diameter * 1000.0).round() / 1000.0),
                    h.center.x,
                    h.center.y,
                    self.leave_stock
                ),
            ));
        }
        (h.top - bottom > tool.cutter.flute_length + 1e-9).then(|| {
            (
                if self.depth.is_some() { "depth" } else { "tool" },
                format!("the hole at X{:.3} Y{:.3} is {:.2} mm deep, deeper than T{}'s flutes ({} mm)", h.center.x, h.center.y, h.top - bottom, tool.number, tool.cutter.flute_length),
            )
        })
    }
}

impl Operate for Bore {
    named_operation!(Either);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm, Picks};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend(F::which_holes());
        fields.extend([
            F::length("pitch", "Descent per turn", 0.01),
            F::fraction("stepoverFraction", "Step between rings", "fraction of the tool's diameter", 1.0),
            F::length("leaveStock", "Leave on the wall", 0.0),
            F::length("finishStep", "Finishing step", 0.0).note("0: none"),
            F::length("depth", "Depth below the hole's top", 0.01).empty("the hole's"),
            F::length("breakthrough", "Past a through hole's bottom", 0.0),
            F::start_above(),
            F::direction(),
            F::marks(),
        ]);
        fields.extend(crate::machining::settings::Clearance::fields());
        OperationForm::new("bore holes on a helix", fields).picks(Picks::Holes)
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        self.pick.validate()?;
        positive("pitch", self.pitch)?;
        crate::machining::fraction("stepoverFraction", self.stepover_fraction)?;
        not_negative("leaveStock", self.leave_stock)?;
        not_negative("finishStep", self.finish_step)?;
        if let Some(d) = self.depth {
            positive("depth", d)?;
        }
        not_negative("breakthrough", self.breakthrough)?;
        positive("retract", self.retract)
    }

    fn hole_problems(&self, holes: &[Hole], tool: &Tool) -> Vec<(&'static str, String)> {
        // Drill marks have no size to bore to (the plan refuses them by name).
        self.pick.chosen(holes).into_iter().filter(|h| !h.mark).find_map(|h| self.misfit(&h, self.bottom(&h), tool)).into_iter().collect()
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let r_tool = tool.cutter.radius();
        let holes = self.pick.sized(ctx, &self.name)?;
        let profile = tool.cutter.profile();
        let clearance = ctx.heights.clearance;
        let ccw = self.direction == Direction::Climb;
        let (feed, plunge) = (tool.feed_rate, tool.plunge_rate);
        let step = self.stepover_fraction * tool.cutter.diameter;
        let mut moves = Vec::new();
        let mut grooves = Vec::new();
        for h in &holes {
            let outer = h.diameter / 2.0 - self.leave_stock - r_tool;
            let bottom = self.bottom(h);
            if let Some((_, message)) = self.misfit(h, bottom, &tool) {
                return Err(Error::operation(&self.name, message));
            }
            let start = entry_height(ctx, h, &profile, self.retract);
            crate::machining::too_many(&self.name, "turns", (start - bottom) / self.pitch, crate::limits::MAX_TURNS, "a pitch of", self.pitch, start - bottom)?;
            crate::machining::too_many(&self.name, "rings", outer / step, crate::limits::MAX_PASSES, "a step-over of", step, outer)?;
            if start > clearance {
                return Err(Error::operation(
                    &self.name,
                    format!("the helix would start ({start:.3}) above the clearance height ({clearance:.3}): raise its 'Clearance height' (Heights), or 'Safe height above the stock' (Stock tab; stock.clearance)"),
                ));
            }
            // Rings from the axis out: the first within the tool's radius of the axis, so no
            // core stands; the last the wall's, or short of it by the finishing step.
            let rough = (outer - self.finish_step).max(outer.min(step));
            let mut radii = vec![rough.min(step).min(r_tool * 0.9).max(1e-3)];
            while radii.last().is_some_and(|&r| r < rough - 1e-9) {
                let next = (radii.last().copied().unwrap_or(0.0) + step).min(rough);
                radii.push(next);
            }
            let c = h.center;
            moves.push(Move::Rapid { to: c.extend(clearance) });
            moves.push(Move::Rapid { to: c.extend(start) });
            for &r in &radii {
                moves.push(Move::Line { to: point(c, r, 0.0, start), feed });
                let end = helix(c, r, 0.0, start, bottom, self.pitch, ccw, feed, &mut moves);
                circle(c, r, end, bottom, ccw, feed, &mut moves);
                if r < rough - 1e-9 || self.finish_step <= 0.0 {
                    moves.push(Move::Line { to: c.extend(bottom), feed });
                    moves.push(Move::Rapid { to: c.extend(start) });
                }
            }
            if self.finish_step > 0.0 {
                // Out to the wall at the bottom, once round, and up it on the helix.
                let at = moves.last().map_or(0.0, |m: &Move| {
                    let v = m.to().truncate() - c;
                    v.y.atan2(v.x)
                });
                moves.push(Move::Line { to: point(c, outer, at, bottom), feed: plunge.min(feed) });
                circle(c, outer, at, bottom, ccw, feed, &mut moves);
                let end = helix(c, outer, at, bottom, h.top, self.pitch, ccw, feed, &mut moves);
                moves.push(Move::Line { to: point(c, 0.0, end, h.top), feed });
                moves.push(Move::Rapid { to: c.extend(start) });
            }
            moves.push(Move::Rapid { to: c.extend(clearance) });
            if ctx.sheet.is_some() {
                grooves.push(Groove { path: vec![Segment::line(c, c)], radius: h.diameter / 2.0, depth: ctx.stock.max.z - bottom });
            }
        }
        Ok(Planned { paths: vec![hole_path(&self.name, &tool, moves, Vec::new(), clearance)], grooves, ..Planned::default() })
    }
}
