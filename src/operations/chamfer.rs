//! Chamfering (countersinking) holes' top edges, or a drawing's loops (outside its outlines,
//! inside its holes), with a V-bit, chamfer mill or spot drill: the user gives the chamfer's
//! width at the top; the tool's angle gives its depth. The cone's side, not its tip, cuts the
//! edge: the tip goes `extraDepth` below the chamfer's foot, the cone's axis at the distance
//! from the edge where its side lies on the chamfer. A hole: one circle (climb), in from the
//! hole's axis and back to it. A drawing's loops: the sheet's parts grown by that distance (so
//! the axis keeps it from every edge, and the cone's reach into the material is the chamfer's
//! width and no more, corners included), each loop entered along a ramp.

use serde::{Deserialize, Serialize};

use crate::drawing::Loop;
use crate::error::{Error, Result};
use crate::geom::segment::Segment;
use crate::machining::holes::{circle, entry_height, hole_path, point, HolePick};
use crate::machining::path2d::{cut_line, start_nearest};
use crate::machining::report::Groove;
use crate::machining::settings::Direction;
use crate::machining::sheet;
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::offset::offset;
use crate::tool::Tool;
use crate::toolpath::Move;

/// Chamfering holes' edges.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Chamfer {
    /// Default value: "chamfer".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// A V-bit, chamfer mill or spot drill. Default value: 1.
    pub tool: u32,
    /// The holes whose edges to chamfer.
    #[serde(flatten)]
    #[ts(flatten)]
    pub pick: HolePick,
    /// The chamfer's width at the top (mm, measured out from the hole's edge). Default value: 0.5.
    pub width: f64,
    /// How far below the chamfer's foot the tip goes, so the cone's side cuts the edge (mm).
    /// Default value: 0.2.
    pub extra_depth: f64,
    /// Height above the material over the hole where feeding starts (mm). Default value: 1.
    pub retract: f64,
    /// Default value: climb.
    pub direction: Direction,
    /// Which edges: the holes' (picked as above), or a drawing's loops (on `layers`, or those
    /// named in `loops`). Default value: holes.
    pub edges: ChamferEdges,
    /// A drawing's layers whose loops to chamfer (edges: loops). Default value: all.
    pub layers: Vec<String>,
    /// The drawing's loops to chamfer, by index as `swarf drawing` lists them (edges: loops).
    /// Default value: all on the layers.
    pub loops: Vec<usize>,
    /// The angle a loop's chamfer is entered at, along the loop (degrees). Default value: 10.
    pub ramp_angle: f64,
}

/// The edges a chamfer breaks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ChamferEdges {
    /// The top edges of holes.
    #[default]
    Holes,
    /// A drawing's loops: outside its outlines, inside its holes.
    Loops,
}

impl Default for Chamfer {
    fn default() -> Self {
        Chamfer {
            name: "chamfer".into(),
            enabled: true,
            tool: 1,
            pick: HolePick::default(),
            width: 0.5,
            extra_depth: 0.2,
            retract: 1.0,
            direction: Direction::Climb,
            edges: ChamferEdges::Holes,
            layers: Vec::new(),
            loops: Vec::new(),
            ramp_angle: 10.0,
        }
    }
}

impl Operate for Chamfer {
    named_operation!(Either);

    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_all_but_thread_mills(cutter)
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.pick.validate()?;
        positive("width", self.width)?;
        not_negative("extraDepth", self.extra_depth)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)?;
        positive("retract", self.retract)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cutter = &tool.cutter;
        if !cutter.is_cone() {
            return Err(Error::operation(&self.name, format!("a chamfer needs a V-bit, chamfer mill or spot drill; T{} is a {}", tool.number, cutter.describe())));
        }
        let half = cutter.point_angle().to_radians() / 2.0;
        // The chamfer's depth at the cone's angle, and the cone's radius where it meets the top.
        let depth = self.width / half.tan();
        let at_top = cutter.tip_radius() + (depth + self.extra_depth) * half.tan();
        if at_top > cutter.radius() + 1e-9 {
            return Err(Error::operation(
                &self.name,
                format!(
                    "a {} mm chamfer with the tip {} mm below it needs a cone {:.3} mm across at the top; T{} is {} mm across",
                    self.width,
                    self.extra_depth,
                    2.0 * at_top,
                    tool.number,
                    cutter.diameter
                ),
            ));
        }
        if self.edges == ChamferEdges::Loops {
            return self.plan_loops(ctx, &tool, depth, at_top);
        }
        let holes = self.pick.sized(ctx, &self.name)?;
        let clearance = ctx.heights.clearance;
        let ccw = self.direction == Direction::Climb;
        let profile = cutter.profile();
        let mut moves = Vec::new();
        let mut grooves = Vec::new();
        let mut below = 0;
        for h in &holes {
            let r_hole = h.diameter / 2.0;
            let rho = r_hole + self.width - at_top;
            if rho < 0.0 {
                return Err(Error::operation(
                    &self.name,
                    format!(
                        "the φ{} hole at X{:.3} Y{:.3} is too small for this chamfer with T{}: its cone is {:.3} mm across at the top",
                        crate::limits::shown((h.diameter * 1000.0).round() / 1000.0),
                        h.center.x,
                        h.center.y,
                        tool.number,
                        2.0 * at_top
                    ),
                ));
            }
            let tip = h.top - depth - self.extra_depth;
            if !h.through && h.bottom > tip {
                return Err(Error::operation(
                    &self.name,
                    format!("the hole at X{:.3} Y{:.3} is {:.3} mm deep: the tip would reach its floor ({:.3} mm needed)", h.center.x, h.center.y, h.depth(), depth + self.extra_depth),
                ));
            }
            let c = h.center;
            // On a part, nothing within the tool's reach may stand above the hole's rim (a hole
            // in a counterbore's floor): the tool's full width stands there.
            if ctx.sheet.is_none() {
                let reach = rho + cutter.radius();
                let highest = crate::zmap::drop::PointDrop::new(&ctx.part, &crate::cutter::Profile::new(reach, 0.0), &ctx.tolerances).at(c, f64::NEG_INFINITY);
                if highest > h.top + ctx.tolerances.gouge {
                    below += 1;
                    continue;
                }
            }
            let start = entry_height(ctx, h, &profile, self.retract);
            moves.push(Move::Rapid { to: c.extend(clearance) });
            moves.push(Move::Rapid { to: c.extend(start) });
            moves.push(Move::Line { to: c.extend(tip), feed: tool.plunge_rate });
            moves.push(Move::Line { to: point(c, rho, 0.0, tip), feed: tool.feed_rate });
            if rho > 1e-6 {
                circle(c, rho, 0.0, tip, ccw, tool.feed_rate, &mut moves);
            }
            moves.push(Move::Line { to: c.extend(tip), feed: tool.feed_rate });
            moves.push(Move::Rapid { to: c.extend(clearance) });
            // What the chamfer takes: within the cone's reach at the top of its circle.
            let path: Vec<Segment> = if rho > 1e-6 { Loop::circle(c, rho).segments().collect() } else { vec![Segment::line(c, c)] };
            grooves.push(Groove { path, radius: at_top, depth: ctx.stock.max.z - tip });
        }
        if below > 0 {
            ctx.warn(
                &self.name,
                format!("{below} holes lie below the part around them (in a counterbore's floor, a pocket's): not chamfered, T{}'s full width would meet the walls above", tool.number),
            );
        }
        if moves.is_empty() {
            return Err(Error::operation(&self.name, "no hole's edge is clear for the tool to chamfer"));
        }
        Ok(Planned { paths: vec![hole_path(&self.name, &tool, moves, Vec::new(), clearance)], grooves, ..Planned::default() })
    }
}

impl Chamfer {
    /// A drawing's loops chamfered: the sheet's parts (the loops on the layers) grown by the
    /// axis's distance from the edge, `at_top - width`; each grown loop that keeps that distance
    /// from a chosen loop is cut at the tip's depth, entered along the loop at the ramp angle.
    fn plan_loops(&self, ctx: &mut Context, tool: &Tool, depth: f64, at_top: f64) -> Result<Planned> {
        let (drawing, _) = sheet::sheet(ctx, &self.name)?;
        let shape = drawing.shape(&self.layers).map_err(|e| Error::operation(&self.name, e.to_string()))?;
        if let Some(&k) = self.loops.iter().find(|&&k| k >= drawing.loops.len()) {
            return Err(Error::operation(&self.name, format!("the drawing has no loop {k} (it has {})", drawing.loops.len())));
        }
        let chosen: Vec<&Loop> = drawing
            .loops
            .iter()
            .enumerate()
            .filter(|(i, l)| (self.layers.is_empty() || self.layers.contains(&l.layer)) && (self.loops.is_empty() || self.loops.contains(i)))
            .map(|(_, l)| &l.path)
            .collect();
        if chosen.is_empty() {
            return Err(Error::operation(&self.name, "none of the chosen loops is on the chosen layers"));
        }
        let away = at_top - self.width;
        let grown = offset(&shape, away, &ctx.tolerances);
        // A grown loop follows a chosen one where it keeps the axis's distance from it.
        let near = away + ctx.tolerances.chain.max(1e-6);
        let follows = |l: &Loop, c: &Loop| l.vertices.iter().any(|v| c.distance_to(v.p) <= near);
        let rings: Vec<&Loop> = grown.loops.iter().filter(|l| chosen.iter().any(|c| follows(l, c))).collect();
        let lost = chosen.iter().filter(|c| !grown.loops.iter().any(|l| follows(l, c))).count();
        if lost > 0 {
            ctx.warn(&self.name, format!("{lost} loops are too small inside for T{}'s cone at this chamfer: not chamfered", tool.number));
        }
        if rings.is_empty() {
            return Err(Error::operation(&self.name, format!("no chosen loop leaves room for T{}'s cone at this chamfer", tool.number)));
        }
        let top = ctx.stock.max.z;
        let tip = top - depth - self.extra_depth;
        let angle = self.ramp_angle.to_radians();
        let mut cursor = sheet::cursor(ctx, tool);
        let mut out: Vec<Move> = Vec::new();
        let mut grooves = Vec::new();
        let mut left = rings;
        while !left.is_empty() {
            // The nearest loop next, from its point nearest the tool.
            let here = cursor.at.truncate();
            let k = (0..left.len()).min_by(|&a, &b| left[a].distance_to(here).total_cmp(&left[b].distance_to(here))).expect("loops left");
            let ring = left.swap_remove(k);
            // Grown outlines run counter-clockwise and holes clockwise: the material on the
            // left, a conventional cut; climb runs them the other way.
            let ring = if self.direction == Direction::Climb { ring.reversed() } else { ring.clone() };
            let path = start_nearest(&ring, here);
            grooves.push(Groove { path: path.clone(), radius: at_top, depth: top - tip });
            let start_z = cursor.material_top(path.iter().copied(), top, tip, ctx.tolerances.gouge).unwrap_or(tip);
            cursor.safe = start_z.max(tip) + cursor.gap;
            cursor.reposition(path[0].a.extend(start_z), &mut out);
            cut_line(&path, true, start_z, tip, depth + self.extra_depth, angle, tool.feed_rate, &mut out);
            cursor.moved(&out);
        }
        Ok(Planned { paths: vec![sheet::toolpath(&self.name, tool, out, ctx.heights.clearance)], grooves, ..Planned::default() })
    }
}
