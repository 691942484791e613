//! What the hole operations (drill, bore, thread mill, chamfer) share: which holes they work
//! on ([`HolePick`]: by index as `swarf holes` lists them, or by a diameter range), taken in a
//! short order (nearest neighbour, then 2-opt, [`crate::holes::order`]); and the helix they
//! descend and climb on ([`helix`]).

use serde::{Deserialize, Serialize};

use crate::cutter::Profile;
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::holes::{self, Hole};
use crate::machining::{positive, Context, FieldError};
use crate::tool::Tool;
use crate::toolpath::cycle::Cycle;
use crate::toolpath::{Move, Toolpath};

/// Which holes an operation works on.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct HolePick {
    /// The holes, by their index as `swarf holes` (a part) or `swarf drawing` (a drawing's
    /// loops) numbers them. Default value: all (within the diameters).
    pub holes: Vec<usize>,
    /// Only holes at least this wide (mm). Default value: none.
    pub min_diameter: Option<f64>,
    /// Only holes at most this wide (mm). Default value: none.
    pub max_diameter: Option<f64>,
    /// A drawing's drill marks (its POINTs) too, which "all the holes" leaves out: a DXF's points
    /// are as often its dimensions' anchors as places to drill (a mark picked by number is
    /// taken anyway). Default value: false.
    pub marks: bool,
}

/// The holes of the workpiece: a drawing's circles through the sheet, else the part's.
pub fn holes_of(ctx: &Context) -> Vec<Hole> {
    match &ctx.sheet {
        Some(sheet) => holes::in_drawing(&sheet.drawing, ctx.stock.max.z, ctx.stock.max.z - sheet.thickness),
        None => holes::mesh::find(&ctx.part),
    }
}

impl HolePick {
    pub fn validate(&self) -> std::result::Result<(), FieldError> {
        for (field, v) in [("minDiameter", self.min_diameter), ("maxDiameter", self.max_diameter)] {
            if let Some(v) = v {
                positive(field, v)?;
            }
        }
        Ok(())
    }

    /// The picked holes of the workpiece, in the order to visit them from the stock's corner.
    pub fn pick(&self, ctx: &Context, op: &str) -> Result<Vec<Hole>> {
        self.pick_from(holes_of(ctx), ctx, op)
    }

    /// The picked ones of `all` (holes, or a part's bosses), in the order to visit them.
    pub fn pick_from(&self, all: Vec<Hole>, ctx: &Context, op: &str) -> Result<Vec<Hole>> {
        if let Some(&k) = self.holes.iter().find(|&&k| k >= all.len() && !all.iter().any(|h| h.loop_index == Some(k))) {
            return Err(Error::operation(op, format!("there is no hole {k} (the {} has {})", if ctx.sheet.is_some() { "drawing" } else { "part" }, all.len())));
        }
        let picked = self.chosen(&all);
        if picked.is_empty() {
            return Err(Error::operation(
                op,
                if all.is_empty() {
                    "no holes found: a drawing's holes are its circles, a part's its vertical round holes".to_string()
                } else {
                    let marks = if all.iter().any(|h| h.mark) { "; drill marks (POINTs) are taken by number, or all of them with marks: true" } else { "" };
                    format!("none of the holes fits the choice (there are {}{marks})", sizes(&all).join(", "))
                },
            ));
        }
        let points: Vec<DVec2> = picked.iter().map(|h| h.center).collect();
        let order = holes::order(&points, DVec2::new(ctx.stock.min.x, ctx.stock.min.y));
        Ok(order.into_iter().map(|k| picked[k].clone()).collect())
    }

    /// The holes of `all` the choice takes, in their order there (no error where it takes none,
    /// nor for a number past the last: [`HolePick::pick_from`] says those).
    pub fn chosen(&self, all: &[Hole]) -> Vec<Hole> {
        all.iter()
            .enumerate()
            .filter(|(k, h)| {
                // A drawing's holes go by their loop's number, a part's by their own.
                let index = h.loop_index.unwrap_or(*k);
                if h.mark {
                    // A drill mark has no diameter for a range to take it by.
                    return self.holes.contains(&index) || self.marks && self.holes.is_empty() && self.min_diameter.is_none() && self.max_diameter.is_none();
                }
                (self.holes.is_empty() || self.holes.contains(&index)) && self.min_diameter.is_none_or(|d| h.diameter >= d - 1e-9) && self.max_diameter.is_none_or(|d| h.diameter <= d + 1e-9)
            })
            .map(|(_, h)| h.clone())
            .collect()
    }

    /// The picked holes for an operation that works to a hole's size (boring, chamfering,
    /// threading): refused where one is a drill mark (a drawing's POINT), which has none.
    pub fn sized(&self, ctx: &Context, op: &str) -> Result<Vec<Hole>> {
        let holes = self.pick(ctx, op)?;
        let marks: Vec<String> = holes.iter().filter(|h| h.mark).map(|h| h.loop_index.unwrap_or(0).to_string()).collect();
        if marks.is_empty() {
            return Ok(holes);
        }
        Err(Error::operation(op, format!("holes {} are drill marks (the drawing's POINTs), with no diameter to work to: drill them", marks.join(", "))))
    }
}

/// The holes by diameter, for messages: "3 × φ6, 2 × φ8.5".
pub fn sizes(holes: &[Hole]) -> Vec<String> {
    let mut by: Vec<(f64, usize)> = Vec::new();
    for h in holes {
        let d = (h.diameter * 1000.0).round() / 1000.0;
        match by.iter_mut().find(|(x, _)| (*x - d).abs() < 1e-9) {
            Some((_, n)) => *n += 1,
            None => by.push((d, 1)),
        }
    }
    crate::geom::sort::sort_by_float(&mut by, |a| a.0);
    // A drill mark's diameter is 0: it has none.
    by.into_iter().map(|(d, n)| if d == 0.0 { format!("{n} drill marks") } else { format!("{n} × φ{}", crate::limits::shown(d)) }).collect()
}

/// Where a hole operation starts feeding over `hole`: `retract` above what stands over it now
/// under a cutter of `profile` (the hole's top, or stock not yet cut above it).
pub fn entry_height(ctx: &Context, hole: &Hole, profile: &Profile, retract: f64) -> f64 {
    ctx.material_estimate(hole.center, profile).max(hole.top) + retract
}

/// A hole operation's moves (and drilling cycles) as its tool path with `tool`, starting where
/// its first move goes (above the first hole at the clearance height, a move of no length).
pub fn hole_path(name: &str, tool: &Tool, moves: Vec<Move>, cycles: Vec<Cycle>, clearance: f64) -> Toolpath {
    let start = moves.first().map_or(DVec3::new(0.0, 0.0, clearance), Move::to);
    Toolpath { name: name.to_string(), tool: tool.number, spindle_rpm: tool.spindle_rpm, start, moves, cycles }
}

/// A helix about `center` at `radius` from the height `from` to `to`, rising or falling
/// `pitch` per turn (the last turn shortened to end at `to`), in half turns (posts that split
/// arcs at the quadrants get whole ones); `ccw`: counter-clockwise seen from above (climb for
/// a hole's wall with the spindle turning clockwise). Starts where the tool stands, at angle
/// `start` (radians) on the circle; returns the angle it ends at (the same: whole half turns).
#[allow(clippy::too_many_arguments)]
pub fn helix(center: DVec2, radius: f64, start: f64, from: f64, to: f64, pitch: f64, ccw: bool, feed: f64, out: &mut Vec<Move>) -> f64 {
    let halves = ((from - to).abs() / pitch * 2.0).ceil().max(1.0) as usize;
    let mut angle = start;
    for k in 1..=halves {
        angle += if ccw { std::f64::consts::PI } else { -std::f64::consts::PI };
        let z = from + (to - from) * k as f64 / halves as f64;
        out.push(Move::Arc { to: point(center, radius, angle, z), center, clockwise: !ccw, feed });
    }
    angle
}

/// A full circle at the height the tool stands at, in two half turns.
pub fn circle(center: DVec2, radius: f64, start: f64, z: f64, ccw: bool, feed: f64, out: &mut Vec<Move>) {
    for k in 1..=2 {
        let angle = start + if ccw { 1.0 } else { -1.0 } * std::f64::consts::PI * k as f64;
        out.push(Move::Arc { to: point(center, radius, angle, z), center, clockwise: !ccw, feed });
    }
}

/// The point at `angle` on the circle about `center` of `radius`, at `z`.
pub fn point(center: DVec2, radius: f64, angle: f64, z: f64) -> DVec3 {
    (center + DVec2::from_angle(angle) * radius).extend(z)
}
