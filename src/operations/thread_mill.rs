//! Thread milling of internal threads with a single-form thread mill: the tool goes down the
//! hole's axis, leads in on a half circle tangent to the thread, climbs (right hand) or
//! descends (left hand) one pitch per turn counter-clockwise (climb milling), leads out on a
//! half circle, in one or more radial passes to the major diameter. Threads are named (ISO
//! metric coarse and fine, Unified coarse and fine: [`crate::machining::threads`]) or given by
//! their major diameter and pitch.

use serde::{Deserialize, Serialize};

use crate::drawing::Loop;
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::machining::holes::{entry_height, helix, hole_path, point, HolePick};
use crate::machining::report::Groove;
use crate::machining::{named_operation, positive, threads, Context, FieldError, Operate, Planned};
use crate::toolpath::Move;

/// Which way the thread turns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Hand {
    #[default]
    Right,
    Left,
}

/// Milling internal threads.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct ThreadMill {
    /// Default value: "thread".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// A thread mill. Default value: 1.
    pub tool: u32,
    /// The holes to thread (drilled to the thread's minor diameter).
    #[serde(flatten)]
    #[ts(flatten)]
    pub pick: HolePick,
    /// The thread's name: M8, M8x1, 1/4-20, #10-32, 1/4 UNC. Default value: M6.
    pub thread: String,
    /// The major diameter (mm), instead of the name's. Default value: none.
    pub major_diameter: Option<f64>,
    /// The pitch (mm), instead of the name's. Default value: none.
    pub pitch: Option<f64>,
    /// Default value: right.
    pub hand: Hand,
    /// Radial passes to the full depth. Default value: 1.
    pub passes: u32,
    /// How deep the thread goes below the hole's top (mm). Default value: the hole's depth.
    pub length: Option<f64>,
    /// Height above the material over the hole the tool enters from (mm). Default value: 1.
    pub retract: f64,
    /// An external thread, on a part's round boss (a stud turned or milled to the major
    /// diameter, cleared round), picked as `swarf holes --bosses` lists them: the tool comes
    /// down beside it and goes round it clockwise (climb: down for a right-hand thread, up for a
    /// left-hand one). Default value: false (internal, in holes).
    pub external: bool,
    /// Its own clearance in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Clearance,
}

impl Default for ThreadMill {
    fn default() -> Self {
        ThreadMill {
            name: "thread".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            pick: HolePick::default(),
            thread: "M6".into(),
            major_diameter: None,
            pitch: None,
            hand: Hand::Right,
            passes: 1,
            length: None,
            retract: 1.0,
            external: false,
        }
    }
}

impl ThreadMill {
    /// The thread's major diameter and pitch (mm).
    pub fn size(&self) -> std::result::Result<(f64, f64), FieldError> {
        let named = if self.major_diameter.is_some() && self.pitch.is_some() { None } else { Some(threads::lookup(&self.thread).map_err(|message| FieldError { field: "thread", message })?) };
        let major = self.major_diameter.or(named.map(|n| n.0)).unwrap_or(0.0);
        let pitch = self.pitch.or(named.map(|n| n.1)).unwrap_or(0.0);
        Ok((major, pitch))
    }
}

impl Operate for ThreadMill {
    named_operation!(Either);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm, Picks};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend(F::which_holes());
        fields.extend([
            F::text("thread", "Thread").note("M8, M8x1, 1/4-20, #10-32, 1/4 UNC"),
            F::check("external", "external: round a boss of the part (a stud), not in a hole"),
            F::choice("hand", "Hand", &[("right", "right"), ("left", "left")]),
            F::int("passes", "Radial passes", 1.0, Some(20.0)),
            F::length("length", "Thread length below the top", 0.01).empty("the hole's depth"),
            F::length("majorDiameter", "Major diameter", 0.01).empty("the thread's"),
            F::length("pitch", "Pitch", 0.01).empty("the thread's"),
            F::start_above(),
            F::marks(),
        ]);
        fields.extend(crate::machining::settings::Clearance::fields());
        OperationForm::new("mill threads (in holes, or round studs)", fields).picks(Picks::Holes)
    }

    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        if cutter.shape == crate::cutter::Shape::ThreadMill {
            Ok(())
        } else {
            Err("thread mills")
        }
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        self.pick.validate()?;
        for (field, v) in [("majorDiameter", self.major_diameter), ("pitch", self.pitch), ("length", self.length)] {
            if let Some(v) = v {
                positive(field, v)?;
            }
        }
        if !(1..=20).contains(&self.passes) {
            return Err(FieldError { field: "passes", message: format!("must be 1 to 20 (got {})", self.passes) });
        }
        let (major, pitch) = self.size()?;
        if pitch >= major / 2.0 {
            return Err(FieldError { field: "pitch", message: format!("must be less than half the major diameter (got {pitch} for φ{major})") });
        }
        positive("retract", self.retract)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        if self.external {
            return self.plan_external(ctx);
        }
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let (major, pitch) = self.size().map_err(|e| Error::operation(&self.name, format!("{}: {}", e.field, e.message)))?;
        let minor = threads::minor_diameter(major, pitch);
        let depth = threads::internal_depth(pitch);
        let r_tool = tool.cutter.radius();
        // The tool's centre when its form reaches the major diameter.
        let outer = major / 2.0 - r_tool;
        if r_tool >= minor / 2.0 - 1e-6 {
            return Err(Error::operation(
                &self.name,
                format!("T{} (φ{}) does not fit the thread's minor diameter φ{minor:.3}: use a thread mill smaller than that", tool.number, tool.cutter.diameter),
            ));
        }
        let holes = self.pick.sized(ctx, &self.name)?;
        let clearance = ctx.heights.clearance;
        let profile = tool.cutter.profile();
        let feed = tool.feed_rate;
        let mut moves = Vec::new();
        let mut grooves = Vec::new();
        let mut small = 0;
        for h in &holes {
            if h.diameter > major + 1e-6 {
                return Err(Error::operation(&self.name, format!("the φ{:.3} hole at X{:.3} Y{:.3} is wider than the thread's major diameter φ{major}", h.diameter, h.center.x, h.center.y)));
            }
            if h.diameter < minor - 0.05 {
                small += 1;
            }
            let (low, high) = self.span(&tool, h, pitch, "hole", "deep")?;
            let (from, to) = if self.hand == Hand::Right { (low, high) } else { (high, low) };
            let c = h.center;
            let start = entry_height(ctx, h, &profile, self.retract);
            moves.push(Move::Rapid { to: c.extend(clearance) });
            moves.push(Move::Rapid { to: c.extend(start) });
            let n = self.passes;
            for k in 1..=n {
                let rho = outer - depth * (n - k) as f64 / n as f64;
                // Down the axis (the drilled hole), a half circle out tangent to the thread,
                // the helix counter-clockwise, a half circle back to the axis.
                moves.push(Move::Line { to: c.extend(from), feed: tool.plunge_rate });
                let mid = c + DVec2::new(rho / 2.0, 0.0);
                moves.push(Move::Arc { to: point(c, rho, 0.0, from), center: mid, clockwise: false, feed });
                helix(c, rho, 0.0, from, to, pitch, true, feed, &mut moves);
                moves.push(Move::Arc { to: c.extend(to), center: mid, clockwise: false, feed });
            }
            moves.push(Move::Rapid { to: c.extend(clearance) });
            grooves.push(Groove { path: Loop::circle(c, outer).segments().collect(), radius: r_tool, depth: ctx.stock.max.z - low.min(high) });
        }
        if small > 0 {
            ctx.warn(&self.name, format!("{small} holes are narrower than the thread's minor diameter φ{minor:.3}: drill them to that first"));
        }
        Ok(Planned { paths: vec![hole_path(&self.name, &tool, moves, Vec::new(), clearance)], grooves, ..Planned::default() })
    }
}

impl ThreadMill {
    /// The heights the thread's helix runs between on `h` (a hole, or a boss: `what`, its
    /// height said as `tall`): from its foot, the thread's length below the top (the whole
    /// hole or boss by default), whole turns up until the form has passed the top; refused where
    /// the thread is longer than the hole or boss, or than the tool's neck.
    fn span(&self, tool: &crate::tool::Tool, h: &crate::holes::Hole, pitch: f64, what: &str, tall: &str) -> Result<(f64, f64)> {
        let length = self.length.unwrap_or(h.top - h.bottom);
        let low = h.top - length;
        if !h.through && low < h.bottom - 1e-9 {
            return Err(Error::operation(&self.name, format!("the thread is {length} mm long; the {what} at X{:.3} Y{:.3} is {:.3} mm {tall}", h.center.x, h.center.y, h.top - h.bottom)));
        }
        if length > tool.cutter.flute_length + 1e-9 {
            return Err(Error::operation(&self.name, format!("the thread is {length} mm long, longer than T{}'s neck ({} mm)", tool.number, tool.cutter.flute_length)));
        }
        crate::machining::too_many(&self.name, "turns", length / pitch, crate::limits::MAX_TURNS, "a pitch of", pitch, length)?;
        let turns = ((h.top + pitch / 2.0 - low) / pitch).ceil().max(1.0);
        Ok((low, low + turns * pitch))
    }

    /// External threads on a part's bosses: per boss, down beside it (outside the major
    /// diameter by the tool's radius and a millimetre), a half circle in tangent to the thread,
    /// the helix clockwise one pitch a turn (down for a right-hand thread, up for a left-hand),
    /// a half circle out, in radial passes from the major diameter to the thread's depth.
    fn plan_external(&self, ctx: &mut Context) -> Result<Planned> {
        if ctx.sheet.is_some() {
            return Err(Error::operation(&self.name, "external threads are milled on a part's round bosses, not on a drawing"));
        }
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let (major, pitch) = self.size().map_err(|e| Error::operation(&self.name, format!("{}: {}", e.field, e.message)))?;
        let depth = threads::external_depth(pitch);
        let bosses = crate::holes::mesh::bosses(&ctx.part);
        if bosses.is_empty() {
            return Err(Error::operation(&self.name, "the part has no round boss to thread (a vertical cylinder standing up, cleared round)"));
        }
        let bosses = self.pick.pick_from(bosses, ctx, &self.name)?;
        let r_tool = tool.cutter.radius();
        let clearance = ctx.heights.clearance;
        let profile = tool.cutter.profile();
        let feed = tool.feed_rate;
        let mut moves = Vec::new();
        let mut grooves = Vec::new();
        for b in &bosses {
            if b.diameter > major + 1e-3 {
                return Err(Error::operation(
                    &self.name,
                    format!("the φ{:.3} boss at X{:.3} Y{:.3} is wider than the thread's major diameter φ{major}: turn it to that first", b.diameter, b.center.x, b.center.y),
                ));
            }
            if b.diameter < major - 2.0 * depth {
                return Err(Error::operation(
                    &self.name,
                    format!("the φ{:.3} boss at X{:.3} Y{:.3} is narrower than the thread's minor diameter φ{:.3}", b.diameter, b.center.x, b.center.y, major - 2.0 * depth),
                ));
            }
            let (low, high) = self.span(&tool, b, pitch, "boss", "high")?;
            let (from, to) = if self.hand == Hand::Right { (high, low) } else { (low, high) };
            let c = b.center;
            // Beside the boss, clear of it.
            let out = major / 2.0 + r_tool + 1.0;
            let beside = point(c, out, 0.0, 0.0).truncate();
            let start = ctx.material_estimate(beside, &profile).max(b.top) + self.retract;
            moves.push(Move::Rapid { to: beside.extend(clearance) });
            moves.push(Move::Rapid { to: beside.extend(start) });
            let n = self.passes;
            for k in 1..=n {
                let rho = major / 2.0 + r_tool - depth * k as f64 / n as f64;
                let mid = c + DVec2::new((out + rho) / 2.0, 0.0);
                // Down (or up) beside the boss, a half circle in, tangent to the helix.
                moves.push(Move::Line { to: beside.extend(from), feed: tool.plunge_rate });
                moves.push(Move::Arc { to: point(c, rho, 0.0, from), center: mid, clockwise: false, feed });
                helix(c, rho, 0.0, from, to, pitch, false, feed, &mut moves);
                moves.push(Move::Arc { to: beside.extend(to), center: mid, clockwise: false, feed });
            }
            moves.push(Move::Rapid { to: beside.extend(clearance) });
            let rho = major / 2.0 + r_tool - depth;
            grooves.push(Groove { path: Loop::circle(c, rho).segments().collect(), radius: r_tool, depth: ctx.stock.max.z - low.min(high) });
        }
        Ok(Planned { paths: vec![hole_path(&self.name, &tool, moves, Vec::new(), clearance)], grooves, ..Planned::default() })
    }
}
