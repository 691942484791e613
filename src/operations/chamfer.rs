//! Chamfering (countersinking) holes' top edges with a V-bit, chamfer mill or spot drill: the
//! user gives the chamfer's width at the top; the tool's angle gives its depth. The cone's
//! side, not its tip, cuts the edge: the tip goes `extraDepth` below the chamfer's foot, the
//! cone's axis circling the hole at the radius where its side lies on the chamfer (one
//! circle, climb), in from the hole's axis and back to it.

use serde::{Deserialize, Serialize};

use crate::drawing::Loop;
use crate::error::{Error, Result};
use crate::geom::segment::Segment;
use crate::machining::holes::{circle, entry_height, hole_path, point, HolePick};
use crate::machining::report::Groove;
use crate::machining::settings::Direction;
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
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
}

impl Default for Chamfer {
    fn default() -> Self {
        Chamfer { name: "chamfer".into(), enabled: true, tool: 1, pick: HolePick::default(), width: 0.5, extra_depth: 0.2, retract: 1.0, direction: Direction::Climb }
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
        positive("retract", self.retract)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cutter = &tool.cutter;
        if !cutter.is_cone() {
            return Err(Error::operation(&self.name, format!("a chamfer needs a V-bit, chamfer mill or spot drill; T{} is a {}", tool.number, cutter.describe())));
        }
        let holes = self.pick.pick(ctx, &self.name)?;
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
