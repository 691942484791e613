//! A job on a drawing: the sheet (stock top at Z0, its thickness below), the 2.5D operations
//! (profile, pocket), and the part the drawing means for verification: full height inside the
//! kept region, cut to each operation's depth where it cuts.

use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec2, DVec3};
use crate::job::{Finish, Job, JobOutput, Operation};
use crate::mesh::Mesh;
use crate::offset::offset;
use crate::profile::{Drawing, Loop, Shape};
use crate::progress::Progress;
use crate::sim::verify::verify_against;
use crate::strategy::path2d::Cursor;
use crate::strategy::pocket2d::{self, pocket_moves};
use crate::strategy::profile2d::{self, profile_moves, Profile2d};
use crate::strategy::walls::Walls;
use crate::toolpath::{Move, Toolpath};
use crate::zmap::{Grid, HeightField};

/// Rapids stop this far above the sheet (mm).
const RAPID_GAP: f64 = 1.0;
/// Depth below the sheet a through cut goes (mm).
const BREAKTHROUGH: f64 = 0.2;

/// The loops an operation works on: every loop on its layers (all when none) by nesting, with
/// their drawing indices (the walls), and the positions among them of those it cuts (named by
/// drawing index when it names some, else all).
fn selected(drawing: &Drawing, layers: &[String], indices: &[usize]) -> Result<(Walls, Vec<usize>)> {
    let shape = drawing.shape(layers).map_err(|e| Error::Job(e.to_string()))?;
    let on: Vec<usize> = (0..drawing.loops.len()).filter(|&i| layers.is_empty() || layers.contains(&drawing.loops[i].layer)).collect();
    let picked: Vec<usize> = (0..on.len()).filter(|&k| indices.is_empty() || indices.contains(&on[k])).collect();
    if picked.is_empty() {
        return Err(Error::Job(format!("none of the loops {indices:?} is on the chosen layers")));
    }
    Ok((Walls::new(shape, on), picked))
}

/// The region a pocket clears: each picked loop as an outer boundary with the loops inside it
/// (islands, and pockets in islands again).
fn pocket_region(shape: &Shape, picked: &[Loop], all: bool) -> Shape {
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

/// Runs a job's 2.5D operations on a drawing.
pub fn run_drawing(job: &Job, mut drawing: Drawing, progress: &mut Progress) -> Result<JobOutput> {
    if let Some(op) = job.operations.iter().find(|op| !op.is_2d()) {
        return Err(Error::Job(format!("'{}' works on 3D parts, not on drawings", op.name())));
    }
    job.drawing.apply(&mut drawing);
    let thickness = job.drawing.thickness;
    if !(thickness > 0.0 && thickness.is_finite()) {
        return Err(Error::Job(format!("the sheet thickness must be a positive number (got {thickness})")));
    }
    let b = drawing.bounds();
    if b.is_empty() {
        return Err(Error::Job("the drawing is empty".into()));
    }
    let m = job.stock.margin_xy;
    let stock = Aabb { min: (b.min - DVec2::splat(m)).extend(-thickness), max: (b.max + DVec2::splat(m)).extend(0.0) };
    let clearance_z = job.stock.clearance;
    let mut paths = Vec::new();
    let mut warnings = Vec::new();
    // Where each operation cuts and how deep, for the verification's part.
    let mut cuts: Vec<Cut> = Vec::new();
    let count = job.operations.len().max(1) as f64;
    let share = if job.simulation.verify { 0.85 } else { 1.0 };
    for (k, op) in job.operations.iter().enumerate() {
        if !progress.stage(op.name(), share * k as f64 / count, share / count) {
            return Err(Error::Cancelled);
        }
        let tool = job.tool(op.tool())?;
        let r = tool.cutter.radius();
        let mut cursor = Cursor { at: DVec3::new(0.0, 0.0, clearance_z), clearance: clearance_z, safe: RAPID_GAP, plunge: tool.plunge_rate };
        let moves = match op {
            Operation::Profile2d(p) => {
                let (walls, picked) = selected(&drawing, &p.layers, &p.loops)?;
                let depth = p.depth.unwrap_or(thickness + BREAKTHROUGH);
                cuts.extend(profile_cuts(&walls, &picked, p, depth));
                let setup = profile2d::Setup { tool_radius: r, top: 0.0, depth, feed: tool.feed_rate, cursor: &mut cursor, tol: &job.tolerances };
                let (moves, notes) = profile_moves(&walls, &picked, p, setup).map_err(|e| Error::Job(format!("{}: {e}", p.name)))?;
                warnings.extend(notes.into_iter().map(|w| format!("{}: {w}", p.name)));
                moves
            }
            Operation::Pocket2d(p) => {
                let (walls, picked) = selected(&drawing, &p.layers, &p.loops)?;
                let picked: Vec<Loop> = picked.iter().map(|&k| walls.shape.loops[k].clone()).collect();
                let region = pocket_region(&walls.shape, &picked, p.loops.is_empty());
                cuts.push(Cut { region: region.clone(), inside: true, depth: p.depth, leave: p.leave_stock });
                let setup = pocket2d::Setup { tool_radius: r, top: 0.0, feed: tool.feed_rate, cursor: &mut cursor, tol: &job.tolerances };
                pocket_moves(&region, p, setup).map_err(|e| Error::Job(format!("{}: {e}", p.name)))?
            }
            Operation::FinishRaster(_) => return Err(Error::Job("3D operations need a part".into())),
        };
        paths.push(toolpath(op, tool, moves, clearance_z));
    }
    let finish = Finish { job, stock, clearance_z, share };
    let gouge = job.tolerances.gouge;
    let tol = job.tolerances;
    let surface = move |grid: Grid| drawing_surface(&cuts, grid, gouge, &tol);
    finish.run(paths, Mesh::default(), Some(drawing), warnings, progress, |_, moves, settings, progress| {
        verify_against(surface, &stock, moves, settings, &job.tolerances, progress)
    })
}

fn toolpath(op: &Operation, tool: &crate::job::Tool, mut moves: Vec<Move>, clearance_z: f64) -> Toolpath {
    let start = moves.iter().find(|m| m.is_rapid()).map(|m| m.to().truncate()).unwrap_or(DVec2::ZERO).extend(clearance_z);
    if moves.first().is_some_and(|m| m.to() == start) {
        moves.remove(0);
    }
    if let Some(last) = moves.last().map(|m| m.to()) {
        if last.z < clearance_z {
            moves.push(Move::Rapid { to: last.truncate().extend(clearance_z) });
        }
    }
    Toolpath { name: op.name().to_string(), tool: tool.number, spindle_rpm: tool.spindle_rpm, start, moves }
}

/// Where an operation may cut, to what depth, leaving how much on the walls.
struct Cut {
    region: Shape,
    /// Cuts inside the region (else everywhere outside it).
    inside: bool,
    depth: f64,
    leave: f64,
}

/// Where a profile cuts: outside the material of every loop on its layers (the walls), and
/// for a loop cut on the side its nesting does not give, outside or inside that loop alone.
fn profile_cuts(walls: &Walls, picked: &[usize], p: &Profile2d, depth: f64) -> Vec<Cut> {
    let leave = p.leave_stock;
    let mut cuts = vec![Cut { region: walls.shape.clone(), inside: false, depth, leave }];
    for &k in picked {
        let l = &walls.shape.loops[k];
        let outside = p.side.cuts_outside(l.is_ccw());
        if outside != l.is_ccw() {
            cuts.push(Cut { region: Shape::from_oriented(vec![l.counter_clockwise()]), inside: !outside, depth, leave });
        }
    }
    cuts
}

/// The part's heights on the simulation grid: the sheet's top, lowered to each cut's depth
/// where it cuts (inside its region, or outside it). Regions are narrowed by the leave-stock
/// and widened by the gouge tolerance where they cut, so cells on a wall are not judged by a
/// hair.
fn drawing_surface(cuts: &[Cut], grid: Grid, gouge: f64, tol: &crate::geom::Tolerances) -> HeightField {
    let mut field = grid.filled(0.0);
    for Cut { region, inside, depth, leave } in cuts {
        let widen = gouge - leave;
        let region = offset(region, if *inside { widen } else { -widen }, tol);
        for j in 0..grid.ny {
            let y = grid.node(0, j).y;
            let spans = region.spans_at(y);
            for i in 0..grid.nx {
                let x = grid.node(i, 0).x;
                let within = spans.iter().any(|&(a, b)| x > a && x < b);
                // A profile cutting outside a loop cuts everything but the loop's inside.
                let cut = if *inside { within } else { !within };
                if cut {
                    let c = j * grid.nx + i;
                    field.z[c] = field.z[c].min(-depth);
                }
            }
        }
    }
    field
}
