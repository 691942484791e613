//! Keeping a tool's holder out of the part (issue 58): the holder's rings
//! ([`crate::tool::Holder::rings`], each a flat cylinder from its rise above the tip up) are
//! cutters too, dropped onto the part (with the fixtures), and a ring of radius `r` rising `h`
//! above the tip keeps the tip at least its drop less `h`: the holder's bound on how deep the
//! tool may go at each place. A path is held to it after it is planned: each move below it is
//! raised onto it (never lowered, so no path comes nearer the part than it was planned), and
//! the places raised are given back, for the operation to say what was left there for a longer
//! stick-out.
//!
//! The bound is made on a grid of cells [`HOLDER_CELL`] wide, each cell's value the rings
//! dropped at its centre widened by half its diagonal (so it bounds every point of the cell);
//! a point of a path is held to the highest cell round it (the 3 × 3 block), and a path is
//! sampled at half a cell, so every straight piece between two samples, lying in the block of
//! its first end, stands on or above the bound all along. Only places deep enough for the
//! lowest ring to reach the part's top are looked at: most jobs' tools stand out farther than
//! their parts are deep, and pay nothing.
//!
//! The holder meets the stock as well as the part: the margin round the part, the top an
//! operation does not face, what a roughing left on the walls. So each operation's paths are
//! also held to the rings dropped on the stock that operation leaves ([`stock_left`]): the
//! in-process stock before it, on cells about half of [`HOLDER_CELL`], each as high as the
//! highest it holds, cut by the operation's own moves with its tools narrowed by a cell's
//! diagonal and lifted to the height their rim reaches there, so that a cell is lowered only
//! where the whole of it is cut at least that deep. It never stands lower than the stock the
//! operation leaves. The holder of a roughing that goes down level by level meets only what the
//! levels above it left; an operation that goes deep in one place before the top of a place
//! beside it is cleared may still bring its holder to that top, which the verification finds.

use crate::cutter::Profile;
use crate::geom::{Aabb, DVec2, DVec3, Tolerances};
use crate::mesh::Mesh;
use crate::sim::{DexelStock, StockModel, Sweep};
use crate::toolpath::{Move, Toolpath};
use crate::zmap::drop::PointDrop;

/// The width of the cells the holder's bound is made on (mm).
pub const HOLDER_CELL: f64 = 1.0;

/// How far the holder keeps from the part (mm), besides the cells' widening.
pub const HOLDER_CLEARANCE: f64 = 0.5;

/// A tool's holder's bound over a part, and over the stock an operation leaves, made cell by
/// cell as paths ask for it.
pub struct HolderBound {
    rings: Vec<(PointDrop, f64)>,
    /// The part's top, and the lowest ring's rise: a tip higher than the top less that rise is
    /// never held.
    top: f64,
    lowest: f64,
    /// The cells over the part's and the stock's boxes grown by the widest ring's reach
    /// (beyond it no ring meets either), row by row from `origin`: NaN until asked for.
    origin: (i64, i64),
    size: (usize, usize),
    cells: Vec<f64>,
    /// The stock the operation being held leaves ([`HolderBound::against`]), its highest top,
    /// and its cells like `cells`.
    stock: Option<(DexelStock, f64, Vec<f64>)>,
}

impl HolderBound {
    /// The bound of a holder with `rings` (`(radius, rise)`) over `solid` (the part with the
    /// fixtures) in a stock within `stock`; none without rings or without a part.
    pub fn new(solid: &Mesh, stock: &Aabb, rings: &[(f64, f64)], tolerances: &Tolerances) -> Option<HolderBound> {
        if rings.is_empty() || solid.faces.is_empty() {
            return None;
        }
        let widen = HOLDER_CELL * std::f64::consts::FRAC_1_SQRT_2 + HOLDER_CLEARANCE;
        let rings: Vec<(PointDrop, f64)> = rings.iter().map(|&(r, rise)| (PointDrop::new(solid, &Profile::new(r + widen, 0.0), tolerances), rise - HOLDER_CLEARANCE)).collect();
        let lowest = rings_lowest(&rings);
        let reach = rings.iter().map(|(d, _)| d.profile().radius).fold(0.0, f64::max) + 2.0 * HOLDER_CELL;
        let part = solid.bounds();
        let (min, max) = (part.min.min(stock.min), part.max.max(stock.max));
        let origin = (((min.x - reach) / HOLDER_CELL).floor() as i64, ((min.y - reach) / HOLDER_CELL).floor() as i64);
        let size = ((((max.x + reach) / HOLDER_CELL).ceil() as i64 - origin.0).max(1) as usize, (((max.y + reach) / HOLDER_CELL).ceil() as i64 - origin.1).max(1) as usize);
        Some(HolderBound { rings, top: part.max.z, lowest, origin, size, cells: vec![f64::NAN; size.0 * size.1], stock: None })
    }

    /// Holds paths from now on to the stock `left` ([`stock_left`]) as well as the part, or
    /// to the part only.
    pub fn against(&mut self, left: Option<DexelStock>) {
        self.stock = left.map(|left| {
            let top = left.tops().iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (left, top, vec![f64::NAN; self.cells.len()])
        });
    }

    fn cell(&mut self, i: i64, j: i64) -> f64 {
        let (u, v) = (i - self.origin.0, j - self.origin.1);
        if u < 0 || v < 0 || u as usize >= self.size.0 || v as usize >= self.size.1 {
            return f64::NEG_INFINITY;
        }
        let k = v as usize * self.size.0 + u as usize;
        let c = DVec2::new((i as f64 + 0.5) * HOLDER_CELL, (j as f64 + 0.5) * HOLDER_CELL);
        if self.cells[k].is_nan() {
            self.cells[k] = self.rings.iter().map(|(drop, rise)| drop.at(c, f64::NEG_INFINITY) - rise).fold(f64::NEG_INFINITY, f64::max);
        }
        let Some((left, _, cells)) = self.stock.as_mut() else { return self.cells[k] };
        if cells[k].is_nan() {
            // The rings as the part's drops have them (widened alike), on the stock's columns.
            cells[k] = self.rings.iter().map(|(drop, rise)| left.touch(c, drop.profile(), true) - rise).fold(f64::NEG_INFINITY, f64::max);
        }
        self.cells[k].max(cells[k])
    }

    /// The bound over the 3 × 3 block of cells round `p`.
    fn block(&mut self, p: DVec2) -> f64 {
        let (i, j) = ((p.x / HOLDER_CELL).floor() as i64, (p.y / HOLDER_CELL).floor() as i64);
        let mut most = f64::NEG_INFINITY;
        for dj in -1..=1 {
            for di in -1..=1 {
                most = most.max(self.cell(i + di, j + dj));
            }
        }
        most
    }

    /// Whether a tip at `z` is too high for any ring to reach the part or the stock.
    fn above(&self, z: f64) -> bool {
        let top = self.stock.as_ref().map_or(self.top, |s| self.top.max(s.1));
        z + self.lowest > top + HOLDER_CLEARANCE
    }

    /// The lowest ring's rise above the tip, less the clearance: a tip `lowest` under the
    /// stock's top may bring the holder to it.
    pub fn lowest(&self) -> f64 {
        self.lowest
    }
}

/// The stock `paths` leave of `stock` as the holder bound takes it: on cells about half of
/// [`HOLDER_CELL`] (whole multiples of the stock's; on whole ones a φ6 tool's own levels,
/// narrowed by their diagonal, no longer clear the way down for its holder), each as high as
/// the highest material it holds, lowered by each cutting move of a tool `profile_of` gives
/// (rapids cut nothing here), narrowed by a cell's diagonal and lifted to the height its rim
/// reaches one half-diagonal in, so a cell is lowered only as far as every point of it is cut.
/// No cell stands lower than the material the paths leave over it.
pub fn stock_left(stock: &DexelStock, paths: &[Toolpath], profile_of: impl Fn(u32) -> Option<Profile>, chordal: f64) -> DexelStock {
    let factor = (HOLDER_CELL / 2.0 / stock.grid().spacing).floor().max(1.0) as usize;
    let mut left = stock.coarsened(factor);
    let half_diagonal = left.grid().spacing * std::f64::consts::FRAC_1_SQRT_2;
    for path in paths.iter().filter(|p| p.cycles.is_empty()) {
        let Some(profile) = profile_of(path.tool) else { continue };
        let reach = profile.radius - 2.0 * half_diagonal;
        if reach <= 0.0 {
            continue;
        }
        let lift = DVec3::Z * profile.height(profile.radius - half_diagonal);
        let narrow = Profile::new(reach, 0.0);
        let mut at = path.start;
        for m in &path.moves {
            let from = std::mem::replace(&mut at, m.to());
            let lifted = match *m {
                Move::Rapid { .. } => continue,
                Move::Line { to, feed } => Move::Line { to: to + lift, feed },
                Move::Arc { to, center, clockwise, feed } => Move::Arc { to: to + lift, center, clockwise, feed },
            };
            for sweep in Sweep::of_move(narrow, from + lift, &lifted, chordal) {
                left.apply(&sweep);
            }
        }
    }
    left
}

fn rings_lowest(rings: &[(PointDrop, f64)]) -> f64 {
    rings.iter().map(|(_, rise)| *rise).fold(f64::INFINITY, f64::min)
}

/// Holds `path` to `bound`: each move (a drilling cycle's are left as they are) that dips
/// below it is raised onto it, as straight pieces half a cell long; the places raised by more
/// than `tolerance` are given back, each with the height the tip was planned at there. A
/// rapid or a move faster than the tool's `cut_feed` (a link at the air feed) was planned
/// through space known to be clear; raised, it may meet what the raised cuts left, so its
/// raised pieces run at `cut_feed`.
pub fn keep_holder_out(path: &mut Toolpath, bound: &mut HolderBound, tolerance: f64, cut_feed: f64) -> Vec<(DVec3, f64)> {
    let mut raised = Vec::new();
    if !path.cycles.is_empty() {
        return raised;
    }
    let moves = std::mem::take(&mut path.moves);
    let mut out = Vec::with_capacity(moves.len());
    // Where the tool stands as written, and as made.
    let (mut at, mut pos) = (path.start, path.start);
    for m in moves {
        let to = m.to();
        let low = at.z.min(to.z);
        if bound.above(low) {
            out.push(m);
            (at, pos) = (to, to);
            continue;
        }
        let n = (m.length(at) / (HOLDER_CELL / 2.0)).ceil().max(1.0) as usize;
        let points: Vec<DVec3> = (0..=n).map(|k| crate::sim::fixtures::along(at, &m, k as f64 / n as f64)).collect();
        let blocks: Vec<f64> = points.iter().map(|p| bound.block(p.truncate())).collect();
        let held: Vec<f64> = (0..=n).map(|k| points[k].z.max(blocks[k]).max(if k > 0 { blocks[k - 1] } else { f64::NEG_INFINITY })).collect();
        if held.iter().zip(&points).all(|(h, p)| *h <= p.z) && pos == at {
            out.push(m);
            (at, pos) = (to, to);
            continue;
        }
        let air = m.feed().is_none_or(|feed| feed > cut_feed * (1.0 + 1e-9));
        let piece = |to: DVec3, raised: bool| match m.feed() {
            _ if air && raised => Move::Line { to, feed: cut_feed },
            Some(feed) => Move::Line { to, feed },
            None => Move::Rapid { to },
        };
        // The start raised where the move before left it lower (up, at its feed).
        if held[0] > pos.z + 1e-12 {
            pos = pos.truncate().extend(held[0]);
            out.push(piece(pos, true));
        }
        for k in 1..=n {
            let p = points[k].truncate().extend(held[k]);
            let lifted = held[k] > points[k].z + 1e-12 || held[k - 1] > points[k - 1].z + 1e-12;
            if held[k] > points[k].z + tolerance {
                raised.push((p, points[k].z));
            }
            if p.distance(pos) > 1e-9 {
                out.push(piece(p, lifted));
                pos = p;
            }
        }
        at = to;
    }
    path.moves = out;
    raised
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat tool with a φ30 nut 10 mm up, over a 20 × 20 pocket 20 deep in a plate: the
    /// bound keeps the tip 10 mm (and the clearance) under the plate's top in the pocket, and
    /// lets it down to the floor far out from the plate; a pass across the pocket at its floor
    /// is raised there and nowhere lower than it was.
    #[test]
    fn a_pass_too_deep_for_the_holder_is_raised_onto_its_bound() {
        let part = crate::mesh::sample::height_field_solid(DVec2::new(-20.0, -20.0), DVec2::new(20.0, 20.0), 80, 80, -30.0, |x, y| if x.abs() < 10.0 && y.abs() < 10.0 { -20.0 } else { 0.0 });
        let mut bound = HolderBound::new(&part, &part.bounds(), &[(15.0, 10.0)], &Tolerances::default()).unwrap();
        let start = DVec3::new(-15.0, 0.0, 5.0);
        let moves = vec![
            Move::Rapid { to: DVec3::new(-5.0, 0.0, 5.0) },
            Move::Line { to: DVec3::new(-5.0, 0.0, -19.5), feed: 300.0 },
            Move::Line { to: DVec3::new(5.0, 0.0, -19.5), feed: 1000.0 },
            Move::Rapid { to: DVec3::new(5.0, 0.0, 5.0) },
        ];
        let mut path = Toolpath { name: "rough".into(), tool: 1, spindle_rpm: 10000.0, start, moves: moves.clone(), cycles: Vec::new() };
        let raised = keep_holder_out(&mut path, &mut bound, 1e-6, 1000.0);
        assert!(!raised.is_empty());
        let lowest = path.moves.iter().map(|m| m.to().z).fold(f64::INFINITY, f64::min);
        // 10 mm up less the clearance, and the cells' widening cannot lift it past the plate.
        assert!(lowest <= -10.0 + HOLDER_CLEARANCE + 1e-9 && lowest > -10.0 - 1e-9, "{lowest}");
        assert_eq!(path.moves.last().unwrap().to(), DVec3::new(5.0, 0.0, 5.0));
        // Never lower than planned: every point raised lies above the pass's.
        assert!(raised.iter().all(|(p, planned)| p.z > -19.5 && *planned < p.z));
    }
}
