//! What the 2.5D operations share when they plan on a drawing laid as a sheet (its top at Z0):
//! the loops an operation works on and the walls it must respect, the cursor that moves
//! between cuts, and the tool path around an operation's moves.

use super::context::Context;
use super::path2d::{Cursor, InStock};
use super::walls::Walls;
use crate::drawing::{Drawing, Loop, Shape};
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3};
use crate::tool::Tool;
use crate::toolpath::{Move, Toolpath};

/// Depth below the sheet a through cut goes (mm).
pub const BREAKTHROUGH: f64 = 0.2;

/// Refuses a 2.5D operation whose `stepdown` makes more than [`super::MAX_LEVELS`] passes
/// down to `depth` (the sheet's thickness and the breakthrough when `None`), before any work.
pub fn check_levels(ctx: &Context, op: &str, depth: Option<f64>, stepdown: f64) -> Result<()> {
    let depth = depth.unwrap_or(ctx.stock.max.z - ctx.stock.min.z + BREAKTHROUGH);
    super::too_many(op, "levels", depth / stepdown, super::MAX_LEVELS, "a step-down of", stepdown, depth)
}

/// The drawing and sheet thickness of the context, or the error for a 2.5D operation on a part.
pub fn sheet<'a>(ctx: &'a Context, op: &str) -> Result<(&'a Drawing, f64)> {
    ctx.sheet.as_ref().map(|s| (&s.drawing, s.thickness)).ok_or_else(|| Error::operation(op, "works on DXF or SVG drawings, not on a 3D part"))
}

/// The loops an operation works on: every loop on its layers (all when none) by nesting, with
/// their drawing indices (the walls), and the positions among them of those it cuts (named by
/// drawing index when it names some, else all).
pub fn selected(drawing: &Drawing, op: &str, layers: &[String], indices: &[usize]) -> Result<(Walls, Vec<usize>)> {
    let shape = drawing.shape(layers).map_err(|e| Error::operation(op, e.to_string()))?;
    let on: Vec<usize> = (0..drawing.loops.len()).filter(|&i| layers.is_empty() || layers.contains(&drawing.loops[i].layer)).collect();
    let picked: Vec<usize> = (0..on.len()).filter(|&k| indices.is_empty() || indices.contains(&on[k])).collect();
    if picked.is_empty() {
        return Err(Error::operation(op, format!("none of the loops {indices:?} is on the chosen layers")));
    }
    Ok((Walls::new(shape, on), picked))
}

/// The region a pocket clears: each picked loop as an outer boundary with the loops inside it
/// (islands, and pockets in islands again).
pub fn pocket_region(shape: &Shape, picked: &[Loop], all: bool) -> Shape {
    if all {
        return shape.clone();
    }
    let mut loops = Vec::new();
    for p in picked {
        let outer = p.counter_clockwise();
        loops.push(outer.clone());
        for l in &shape.loops {
            if l != p && outer.contains(l.probe_point()) {
                loops.push(l.clone());
            }
        }
    }
    Shape::new(loops)
}

/// The cursor of a 2.5D operation with `tool`, at the clearance height: rapids stop the job's
/// gap above the in-process stock under the cutter (never above the stock's top plus the gap).
pub fn cursor<'m>(ctx: &'m Context, tool: &Tool) -> Cursor<'m> {
    let clearance = ctx.heights.clearance;
    let stock = InStock::new(ctx.sim.stock(), tool.cutter.profile(), ctx.tolerances.gouge);
    Cursor {
        at: DVec3::new(0.0, 0.0, clearance),
        clearance,
        safe: ctx.stock.max.z + ctx.heights.gap,
        gap: ctx.heights.gap,
        full_retract: ctx.heights.full,
        plunge: tool.plunge_rate,
        traverse: None,
        safe_at: None,
        cleared_to: None,
        stock,
        air_feed: ctx.air_feed,
    }
}

/// An operation's moves as a tool path: it starts above its first rapid's end at the
/// clearance height and ends there.
pub fn toolpath(name: &str, tool: &Tool, mut moves: Vec<Move>, clearance_z: f64) -> Toolpath {
    let start = moves.iter().find(|m| m.is_rapid()).map(|m| m.to().truncate()).unwrap_or(DVec2::ZERO).extend(clearance_z);
    if moves.first().is_some_and(|m| m.to() == start) {
        moves.remove(0);
    }
    if let Some(last) = moves.last().map(|m| m.to()) {
        if last.z < clearance_z {
            moves.push(Move::Rapid { to: last.truncate().extend(clearance_z) });
        }
    }
    Toolpath { name: name.to_string(), tool: tool.number, spindle_rpm: tool.spindle_rpm, start, moves, cycles: Vec::new() }
}
