//! Waterlines on the CL z-map, shared by waterline finishing and steep-and-shallow finishing:
//! the levels' heights (a step-down apart, or by the scallop the slope leaves between levels),
//! and at each level the boundary of the region the cutter's centre may occupy there
//! ([`crate::zmap::contour`]), kept where the operation asks (on steep ground).

use crate::error::Result;
use crate::geom::{DVec2, DVec3};
use crate::machining::context::SurfaceRequest;
use crate::machining::levels::pack;
use crate::machining::raster::gradient;
use crate::machining::settings::Direction;
use crate::machining::{too_many, Context, MAX_LEVELS};
use crate::progress::Progress;
use crate::zmap::surface::ClSurface;
use crate::zmap::HeightField;

/// Contour pieces shorter than this are left out (mm).
pub const SHORTEST: f64 = 0.5;
/// Smallest step between levels (mm), however shallow the slope.
pub const LEAST_STEP: f64 = 0.02;
/// Smallest scallop height (mm): a micron, finer than any machine holds; a scallop of 1e-9 mm
/// would put every level [`LEAST_STEP`] apart, 1,300 levels on the 26 mm sample.
pub const LEAST_SCALLOP: f64 = 0.001;

/// How far apart the levels are.
#[derive(Clone, Copy, Debug)]
pub struct Spacing {
    /// Height between levels (mm), and the most between them by the scallop.
    pub stepdown: f64,
    /// Largest scallop height between levels (mm): closer where the surface is shallower.
    pub scallop: Option<f64>,
    /// Material left on the part (mm): the levels stop this far above the floor.
    pub allowance: f64,
    /// The least slope (rise over run) counted steep.
    pub steep: f64,
}

/// The heights of the levels, from the top down, known before any is contoured: a step-down
/// apart, or by the scallop: the next level s · sin θ lower, s = sqrt(8 r h) and θ the
/// shallowest slope of the steep cells (those the level's steep contours pass through) that
/// reach across its height. More than [`MAX_LEVELS`] (levels [`LEAST_STEP`] apart on a tall
/// part), or more than the level map allows, are refused for the operation `op` as soon as
/// they are counted.
pub fn heights(op: &str, cl: &HeightField, floor: f64, radius: f64, spacing: Spacing) -> Result<Vec<f64>> {
    let Spacing { stepdown, scallop, allowance, steep } = spacing;
    let top = cl.max();
    let bottom = floor + allowance;
    // Per steep cell: the lowest and highest of its nodes, and its slope.
    let mut cells = Vec::new();
    if scallop.is_some() {
        for j in 0..cl.ny.saturating_sub(1) {
            for i in 0..cl.nx.saturating_sub(1) {
                let slope = gradient(cl, cl.origin + (DVec2::new(i as f64, j as f64) + 0.5) * cl.spacing);
                if slope >= steep {
                    let z = [cl.at(i, j), cl.at(i + 1, j), cl.at(i, j + 1), cl.at(i + 1, j + 1)];
                    cells.push((z.iter().copied().fold(f64::INFINITY, f64::min), z.iter().copied().fold(f64::NEG_INFINITY, f64::max), slope));
                }
            }
        }
    }
    // Shallowest first: at most levels one of the first cells reaches across.
    crate::geom::sort::sort_by_float(&mut cells, |a| a.2);
    let mut out = Vec::new();
    let mut z = top - 0.5 * stepdown.min(top - floor);
    let nodes = (cl.nx * cl.ny) as f64;
    let cap = MAX_LEVELS.min(crate::limits::MAX_LEVEL_NODES / nodes);
    while z > bottom {
        if out.len() as f64 >= cap {
            // More levels than a limit allows: at least these and the one below.
            let more = (out.len() as f64 * (top - bottom) / (top - z)).max(out.len() as f64 + 1.0);
            let (what, h) = scallop.map_or(("a step-down of", stepdown), |h| ("a scallop of", h));
            too_many(op, "levels", more, MAX_LEVELS, what, h, top - bottom)?;
            let size = DVec3::new(cl.spacing * (cl.nx - 1) as f64, cl.spacing * (cl.ny - 1) as f64, top - floor);
            crate::machining::level_work(op, more, &format!("{what} {} mm", crate::limits::shown(h)), cl.spacing, size)?;
        }
        out.push(z);
        let level = z - allowance;
        let shallowest = cells.iter().find(|&&(lo, hi, _)| lo <= level && level <= hi).map_or(f64::INFINITY, |c| c.2);
        z -= match scallop {
            Some(h) if shallowest.is_finite() => {
                let s = (8.0 * radius * h).sqrt();
                (s * shallowest.atan().sin()).clamp(LEAST_STEP, stepdown.max(LEAST_STEP))
            }
            _ => stepdown,
        };
    }
    Ok(out)
}

/// The levels' contours at `heights` (each lowered by `allowance` to contour at), in `direction`,
/// kept where `keep` holds at a segment's middle, pieces shorter than `shortest` left out; made
/// side by side, or taken from a pool's regions ([`Context::given_regions`]). `None` when the
/// user cancelled.
pub fn contours(
    ctx: &mut Context,
    request: SurfaceRequest,
    cl: &ClSurface,
    heights: &[f64],
    allowance: f64,
    direction: Direction,
    keep: &(dyn Fn(DVec2) -> bool + Sync),
    shortest: f64,
    progress: &mut Progress,
) -> Option<Vec<Vec<DVec3>>> {
    let tol = ctx.tolerances;
    let map = ctx.level_map(request, cl);
    // Every level's region on whichever core is free (the levels are known beforehand),
    // unless a pool made it already.
    let given = &ctx.given_regions;
    let all = (!given.is_empty()).then(|| pack(&vec![true; request.grid.nodes()]));
    let made = crate::parallel::map_uneven(heights.len(), |k| {
        let level = heights[k] - allowance;
        let kept = all.as_ref().and_then(|all| given.iter().find(|g| g.request == request && g.level == level && g.keep == *all));
        kept.map_or_else(|| map.region(cl, level, &|_, _| true, &tol), |g| g.region.clone())
    });
    let mut runs: Vec<Vec<DVec3>> = Vec::new();
    for (k, (&z, region)) in heights.iter().zip(made).enumerate() {
        if !progress.report(k as f64 / heights.len() as f64) {
            return None;
        }
        for l in &region.loops {
            // The region's loops keep it on their left, the part on their right: climb with
            // a clockwise spindle.
            let l = if direction == Direction::Climb { l.clone() } else { l.reversed() };
            let pts: Vec<DVec2> = l.vertices.iter().map(|v| v.p).chain(l.vertices.first().map(|v| v.p)).collect();
            for piece in split_where(&pts, keep) {
                let length: f64 = piece.windows(2).map(|w| w[0].distance(w[1])).sum();
                if length >= shortest {
                    runs.push(piece.into_iter().map(|p| p.extend(z)).collect());
                }
            }
        }
    }
    Some(runs)
}

/// The stretches of the closed polyline `pts` (its last point its first) where `keep` holds at
/// a segment's middle, as open polylines (one closed one when it holds all round).
pub fn split_where(pts: &[DVec2], keep: &dyn Fn(DVec2) -> bool) -> Vec<Vec<DVec2>> {
    let kept: Vec<bool> = pts.windows(2).map(|w| keep((w[0] + w[1]) * 0.5)).collect();
    if kept.iter().all(|&k| k) {
        return vec![pts.to_vec()];
    }
    // Start at a segment that is left out, so stretches do not wrap.
    let n = kept.len();
    let Some(first_out) = kept.iter().position(|&k| !k) else { return Vec::new() };
    let mut out = Vec::new();
    let mut current: Vec<DVec2> = Vec::new();
    for s in 0..n {
        let k = (first_out + s) % n;
        if kept[k] {
            if current.is_empty() {
                current.push(pts[k]);
            }
            current.push(pts[k + 1]);
        } else if !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}
