//! A drawing as walls: every loop on an operation's layers bounds material that every cut of
//! that operation keeps its distance from, not only the loop being cut. Parts nested closer
//! than the tool on one sheet, an island part in a neighbour's cut-out, a lead arc swinging
//! towards the next part: all are judged against the drawing as one shape.
//!
//! The tool-centre paths of a profile are the boundary of that shape grown by the tool radius
//! plus leave-stock, offset as one shape by the seed 003 offsetter (its trimming step removes
//! whatever comes closer to *any* loop than the distance, §2-3). Where two parts stand closer
//! than the tool's width their grown regions merge, so one path runs around both and the gap
//! between them is left uncut; [`Walls::paths`] says which drawn loops each path runs along,
//! so that merge can be named.

use crate::drawing::{Loop, Shape};
use crate::geom::index::RectIndex;
use crate::geom::segment::{Rect, Segment};
use crate::geom::tolerance::HAIR;
use crate::geom::{DVec2, Tolerances};
use crate::offset::offset;
use crate::offset::trim::Original;

/// The material of a drawing: its loops by nesting (outer loops counter-clockwise around
/// material, holes clockwise), each with its index in the drawing, indexed for distance
/// queries (the offsetter's [`Original`]).
/// The finest first sampling of [`Walls::closest_approach`] (mm).
const COARSEST_SAMPLE: f64 = 0.01;

pub struct Walls {
    pub shape: Shape,
    /// The drawing's index of each loop of `shape`.
    pub index: Vec<usize>,
    original: Original,
    /// The loop (position in `shape`) of each of the shape's segments, in order.
    owner: Vec<usize>,
    /// The loops' bounds, indexed: a point's loops are found without a look at every loop
    /// (a sheet of 30,000 holes).
    bounds: RectIndex,
    /// Each loop's bounds, by position.
    rects: Vec<Rect>,
}

/// A tool-centre path around the material and the loops (positions in [`Walls::shape`]) it
/// runs along.
pub struct WallPath {
    pub path: Loop,
    pub along: Vec<usize>,
}

/// The finest spacing the closest approach of two parts is sampled at (mm): a tenth of a micron,
/// finer than any gap a tool could pass.
const FINEST_SAMPLE: f64 = 1e-4;

impl Walls {
    pub fn new(shape: Shape, index: Vec<usize>) -> Walls {
        let owner = shape.loops.iter().enumerate().flat_map(|(k, l)| std::iter::repeat_n(k, l.len())).collect();
        let rects: Vec<Rect> = shape.loops.iter().map(Loop::bounds).collect();
        let bounds = RectIndex::new(&rects);
        Walls { original: Original::new(&shape), shape, index, owner, bounds, rects }
    }

    /// The loop nearest `q` among those closer than `reach`, and its distance.
    pub fn nearest(&self, q: DVec2, reach: f64) -> Option<(usize, f64)> {
        self.original.nearest(q, reach).map(|(i, d)| (self.owner[i], d))
    }

    /// Whether a point lies in material (even-odd over the loops around it).
    pub fn in_material(&self, q: DVec2) -> bool {
        let mut around = 0;
        self.bounds.query(&Rect { min: q, max: q }, |k| {
            if self.shape.loops[k].contains(q) {
                around += 1;
            }
        });
        around % 2 == 1
    }

    /// For points within `radius` of `p` (the walls near them looked up once): whether one
    /// keeps at least `distance` (less a thousandth of a micrometre) from every loop.
    pub fn keeps_off_around(&self, p: DVec2, radius: f64, distance: f64) -> impl Fn(DVec2) -> bool + '_ {
        let reach = distance - HAIR;
        let ids = self.original.near(p, radius + reach);
        move |q| self.original.distance_among(&ids, q, reach) >= reach
    }

    /// The boundary of the material grown by `distance`, each loop with the drawn loops it runs
    /// along (every piece of an offset is at the distance from the entity it came from, so a
    /// piece's midpoint names its loop).
    pub fn paths(&self, distance: f64, tol: &Tolerances) -> Vec<WallPath> {
        let grown = offset(&self.shape, distance, tol);
        let reach = distance.abs() * (1.0 + HAIR) + HAIR;
        grown
            .loops
            .into_iter()
            .map(|path| {
                let mut along: Vec<usize> = path.segments().filter_map(|s| self.nearest(s.midpoint(), reach).map(|n| n.0)).collect();
                along.sort_unstable();
                along.dedup();
                WallPath { path, along }
            })
            .collect()
    }

    /// Where loops `a` and `b` come closest: the gap and a point midway across it (sampled
    /// along `a` at a fiftieth of the gap, at most 20,000 points).
    /// The pairs of `loops` (positions in [`Walls::shape`]) whose bounds come within `gap` of
    /// each other: the only ones that can be closer than `gap`, found without a look at every
    /// pair (one path round a sheet of 30,000 holes runs along all of them).
    pub fn near_pairs(&self, loops: &[usize], gap: f64) -> Vec<(usize, usize)> {
        let grown: Vec<Rect> = loops.iter().map(|&k| self.rects[k].expand(0.5 * gap)).collect();
        let mut out = Vec::new();
        RectIndex::new(&grown).pairs(|i, j| out.push((loops[i], loops[j])));
        out
    }

    pub fn closest_approach(&self, a: usize, b: usize) -> (f64, DVec2) {
        let (la, lb) = (&self.shape.loops[a], &self.shape.loops[b]);
        // At most 20,000 samples, and no closer than a hundredth of a millimetre (a small
        // loop's): the search is refined near the best of them.
        let coarse = (la.length() / 20_000.0).max(COARSEST_SAMPLE);
        let mut best = (f64::INFINITY, DVec2::ZERO);
        closest_on(la.segments(), lb, coarse, &mut best);
        // Finer on the segments of `a` near the best point found.
        let (gap, at) = best;
        closest_on(la.segments().filter(|s| s.distance_to(at) <= gap + 2.0 * coarse), lb, (gap / 50.0).max(FINEST_SAMPLE), &mut best);
        best
    }
}

/// The closest approach of points `step` apart along `segs` to the loop `to`, if closer than
/// `best`.
fn closest_on(segs: impl Iterator<Item = Segment>, to: &Loop, step: f64, best: &mut (f64, DVec2)) {
    for s in segs {
        let n = (s.length() / step).ceil().clamp(1.0, 20_000.0) as usize;
        for i in 0..=n {
            let p = s.point_at(i as f64 / n as f64);
            for t in to.segments() {
                let q = t.closest(p).0;
                let d = p.distance(q);
                if d < best.0 {
                    *best = (d, (p + q) * 0.5);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_squares(gap: f64) -> Walls {
        let a = Loop::rect(DVec2::ZERO, DVec2::splat(20.0));
        let b = Loop::rect(DVec2::new(20.0 + gap, 0.0), DVec2::new(40.0 + gap, 20.0));
        Walls::new(Shape::new(vec![a, b]), vec![0, 1])
    }

    #[test]
    fn parts_closer_than_the_tool_share_one_path() {
        let w = two_squares(4.04);
        let apart = w.paths(1.5, &Tolerances::default());
        assert_eq!(apart.len(), 2);
        assert!(apart.iter().all(|p| p.along.len() == 1));
        let merged = w.paths(3.0, &Tolerances::default());
        assert_eq!(merged.len(), 1);
        assert_eq!(merged[0].along, vec![0, 1]);
        let (gap, at) = w.closest_approach(0, 1);
        assert!((gap - 4.04).abs() < 1e-9 && (at.x - 22.02).abs() < 1e-9, "{gap} at {at}");
    }

    #[test]
    fn clear_means_out_of_material_by_the_distance() {
        let w = two_squares(10.0);
        let clear = |q: DVec2, d: f64| !w.in_material(q) && w.keeps_off_around(q, 0.0, d)(q);
        assert!(!clear(DVec2::new(10.0, 10.0), 1.0));
        assert!(clear(DVec2::new(25.0, 10.0), 4.9));
        assert!(!clear(DVec2::new(25.0, 10.0), 5.1));
        assert!(clear(DVec2::new(-3.0, -4.0), 4.9));
        assert!(!w.in_material(DVec2::new(25.0, 10.0)) && w.in_material(DVec2::new(35.0, 10.0)));
    }
}
