//! What the 2.5D strategies share: heights that vary along a closed chain of lines and arcs
//! (ramps, tabs), moves that follow such a chain, helices and ramps for entering material, and
//! the retract-and-reposition link. DESIGN.md idea 6: entries and links are passes over data,
//! not parts of one strategy.

use crate::cutter::Profile;
use crate::drawing::Loop;
use crate::geom::segment::Segment;
pub use crate::geom::segment::{arc_lengths, pieces};
use crate::geom::tolerance::{FLOAT_SLACK, LEAST_STEP};
use crate::geom::{DVec2, DVec3};
use crate::sim::dexel::DexelStock;
use crate::toolpath::link::retract;
use crate::toolpath::Move;

/// A height that varies linearly along arc length between breakpoints `(s, z)`, constant
/// beyond the first and last.
#[derive(Clone, Debug, PartialEq)]
pub struct Heights(pub Vec<(f64, f64)>);

impl Heights {
    pub fn constant(z: f64) -> Heights {
        Heights(vec![(0.0, z)])
    }

    /// Descends from `from` at `s0` to `to` at slope `tan(angle)`, then stays at `to`.
    pub fn ramp(s0: f64, from: f64, to: f64, angle: f64) -> Heights {
        let run = (from - to).max(0.0) / angle.tan();
        Heights(vec![(s0, from), (s0 + run, to)])
    }

    pub fn at(&self, s: f64) -> f64 {
        let p = &self.0;
        if s <= p[0].0 {
            return p[0].1;
        }
        for w in p.windows(2) {
            if s <= w[1].0 {
                let span = w[1].0 - w[0].0;
                return if span <= 0.0 { w[1].1 } else { w[0].1 + (w[1].1 - w[0].1) * (s - w[0].0) / span };
            }
        }
        p[p.len() - 1].1
    }

    /// The higher of two height functions, with breakpoints where they cross.
    pub fn max(&self, other: &Heights) -> Heights {
        let mut s: Vec<f64> = self.0.iter().chain(&other.0).map(|p| p.0).collect();
        crate::geom::sort::sort_floats(&mut s);
        s.dedup();
        let mut out = Vec::with_capacity(s.len() * 2);
        for (k, &x) in s.iter().enumerate() {
            if k > 0 {
                // A crossing strictly between two breakpoints.
                let (x0, d0, d1) = (s[k - 1], self.at(s[k - 1]) - other.at(s[k - 1]), self.at(x) - other.at(x));
                if d0 * d1 < 0.0 {
                    let xc = x0 + (x - x0) * d0 / (d0 - d1);
                    out.push((xc, self.at(xc)));
                }
            }
            out.push((x, self.at(x).max(other.at(x))));
        }
        Heights(out)
    }

    pub fn breakpoints(&self) -> impl Iterator<Item = f64> + '_ {
        self.0.iter().map(|p| p.0)
    }
}

/// The point of a closed chain at arc length `s` (wrapping).
pub fn point_at(segs: &[Segment], starts: &[f64], total: f64, s: f64) -> DVec2 {
    let s = s.rem_euclid(total);
    let i = starts.partition_point(|&x| x <= s).saturating_sub(1);
    let len = segs[i].length();
    segs[i].point_at(if len > 0.0 { (s - starts[i]) / len } else { 0.0 })
}

/// Arcs with ends closer than this (mm) go as lines.
const ARC_CHORD_MIN: f64 = 1e-6;

/// Moves that follow the closed chain `segs` from arc length `s0` to `s1` (`s1` may pass the
/// end: the chain repeats), at the heights `z` gives along the way (arcs with changing height
/// are helices).
pub fn follow(segs: &[Segment], s0: f64, s1: f64, z: &Heights, feed: f64, out: &mut Vec<Move>) {
    for (_, to, piece) in pieces(segs, s0, s1, z.breakpoints()) {
        let end = piece.b.extend(z.at(to));
        match piece.arc_geom() {
            // A sliver of an arc (a loop split a hair from a joint) goes as a line: an arc move
            // whose ends nearly meet reads as a full circle the other way round when rounding
            // turns its direction (seen on ocl_wheel_in_box: a φ3's ring swept a whole circle
            // into the hub in the simulation, 13 mm deep).
            Some(g) if piece.a.distance(piece.b) > ARC_CHORD_MIN => out.push(Move::Arc { to: end, center: g.center, clockwise: g.bulge < 0.0, feed }),
            _ => out.push(Move::Line { to: end, feed }),
        }
    }
}

/// A loop's segments starting at the point of it nearest to `q` (the segment there is split).
pub fn start_nearest(l: &Loop, q: DVec2) -> Vec<Segment> {
    let segs: Vec<Segment> = l.segments().collect();
    let (mut best, mut best_d, mut best_t) = (0, f64::INFINITY, 0.0);
    for (i, s) in segs.iter().enumerate() {
        let (p, t) = s.closest(q);
        let d = p.distance(q);
        if d < best_d {
            (best, best_d, best_t) = (i, d, t);
        }
    }
    let n = segs.len();
    let s = segs[best];
    let mut out = Vec::with_capacity(n + 1);
    if best_t > FLOAT_SLACK && best_t < 1.0 - FLOAT_SLACK {
        out.push(s.sub(best_t, 1.0));
        out.extend((1..n).map(|k| segs[(best + k) % n]));
        out.push(s.sub(0.0, best_t));
    } else {
        let first = if best_t >= 1.0 - FLOAT_SLACK { best + 1 } else { best };
        out.extend((0..n).map(|k| segs[(first + k) % n]));
    }
    out
}

/// "the φD tool (plus L leave-stock) does not fit in `what` at (x, y)–(x, y)".
pub fn does_not_fit(tool_radius: f64, leave_stock: f64, what: &str, b: &crate::geom::segment::Rect) -> String {
    format!("the φ{:.3} tool (plus {:.3} leave-stock) does not fit in {what} at ({:.3}, {:.3})–({:.3}, {:.3})", 2.0 * tool_radius, leave_stock, b.min.x, b.min.y, b.max.x, b.max.y)
}

/// A height at which the straight traverse from one point to another is safe, if there is one
/// lower than the clearance height.
pub type Traverse = Box<dyn Fn(DVec2, DVec2) -> Option<f64>>;

/// The in-process stock as a 2.5D strategy's cutter meets it: the material the earlier
/// operations of the job left.
#[derive(Clone, Copy)]
pub struct InStock<'m> {
    stock: &'m DexelStock,
    profile: Profile,
    /// The cutter `shy` smaller, for the estimate.
    smaller: Profile,
}

impl<'m> InStock<'m> {
    /// The stock as `profile` meets it; the estimate's footprint `shy` smaller (mm), so that
    /// the walls an earlier cut left at exactly this cutter's reach do not count as material
    /// in its way.
    pub fn new(stock: &'m DexelStock, profile: Profile, shy: f64) -> InStock<'m> {
        let r = (profile.radius - shy).max(0.0);
        InStock { stock, profile, smaller: Profile::new(r, profile.corner.min(r)) }
    }

    /// The stock model itself.
    pub fn model(&self) -> &'m DexelStock {
        self.stock
    }

    /// The cutter as it meets the stock.
    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// Whether there is material at height `z` over `p` (the stock's top above it).
    pub fn material_at(&self, p: DVec2, z: f64) -> bool {
        crate::zigzag::load::material_at(self.stock, p, z)
    }

    /// The highest tip height at which the cutter at `p` touches material as the stock model
    /// samples it (`-inf` where there is none): as the program's verification sees the
    /// material, for rapids. Not the bound the 3D linker takes (each cell as a column over its
    /// whole square): beside a wall an earlier cut left at exactly this cutter's reach, that
    /// bound stands at the wall's top.
    pub fn reach(&self, p: DVec2) -> f64 {
        self.stock.touch(p, &self.profile, false)
    }

    /// The highest tip height at which the cutter touches the material anywhere along the
    /// straight way from `a` to `b`, each cell as a column over its whole square (`-inf` where
    /// there is none): a level traverse above it meets no material.
    pub fn along(&self, a: DVec2, b: DVec2) -> f64 {
        self.stock.touch_along(a, b, &self.profile, true)
    }

    /// The same as the stock model samples it, at its cells' centres, with the footprint
    /// `shy` smaller: for deciding where material is left to cut.
    pub fn estimate(&self, p: DVec2) -> f64 {
        self.stock.touch(p, &self.smaller, false)
    }

    /// The highest [`InStock::estimate`] over points along `segments`, at most `spacing` apart,
    /// or the first at or above `enough` (where a higher one would not matter).
    pub fn highest_along(&self, segments: impl IntoIterator<Item = Segment>, spacing: f64, enough: f64) -> f64 {
        let mut top = f64::NEG_INFINITY;
        for seg in segments {
            let n = (seg.length() / spacing.max(LEAST_STEP)).ceil().max(1.0) as usize;
            for k in 0..=n {
                top = top.max(self.estimate(seg.point_at(k as f64 / n as f64)));
                if top >= enough {
                    return top;
                }
            }
        }
        top
    }
}

/// Where the tool is and how it moves between cuts.
pub struct Cursor<'m> {
    pub at: DVec3,
    pub clearance: f64,
    /// Height above which rapids are safe near the next cut: the stock top plus a gap.
    pub safe: f64,
    /// How far above the material a rapid descent stops (mm).
    pub gap: f64,
    /// Retracts across material go to the clearance height (or the strategy's traverse), not
    /// the gap above the material on the way.
    pub full_retract: bool,
    pub plunge: f64,
    /// A lower traverse than the clearance height where the strategy knows one (the short
    /// retract); `None`: always the clearance height.
    pub traverse: Option<Traverse>,
    /// Where `safe` holds, when only somewhere (the region the level before cleared); past it
    /// a rapid descent stops the gap above the in-process stock. `None`: everywhere.
    pub safe_at: Option<Box<dyn Fn(DVec2) -> bool>>,
    /// Past `safe_at`, the height down to which the operation has cleared the material about
    /// a point already (an earlier level's region), if it has: a rapid descent stops the gap
    /// above it, and a ramp starts on it.
    pub cleared_to: Option<Box<dyn Fn(DVec2) -> Option<f64>>>,
    /// The in-process stock: rapid descents stop the gap above the material under the cutter
    /// at that spot (no lower than `safe` allows otherwise).
    pub stock: InStock<'m>,
    /// Feed of level moves that cut nothing ([`super::air`]); no faster than the tool's feed:
    /// none.
    pub air_feed: f64,
}

impl Cursor<'_> {
    /// Up to the clearance (or the strategy's lower traverse, or the gap above the in-process
    /// stock on the way, whichever is lower), over to above `to`, rapid down to the safe height
    /// (or the gap above the in-process stock there, when lower), then feed down to `to`: the
    /// linker's retract ([`retract`]).
    pub fn reposition(&mut self, to: DVec3, out: &mut Vec<Move>) {
        let feed = self.plunge;
        self.reposition_at(to, feed, out);
    }

    /// [`Cursor::reposition`] down into a hole the operation has just cleared about `to` (the
    /// tool's whole circle, from the material's top down to `to`): the descent runs in air, at
    /// the air feed (no slower than the plunge) instead of the plunge.
    pub fn reposition_into_cleared(&mut self, to: DVec3, out: &mut Vec<Move>) {
        let feed = self.air_feed.max(self.plunge);
        self.reposition_at(to, feed, out);
    }

    fn reposition_at(&mut self, to: DVec3, feed: f64, out: &mut Vec<Move>) {
        let low = self.traverse.as_ref().and_then(|f| f(self.at.truncate(), to.truncate()));
        let travel = low.map_or(self.clearance, |h| h.max(self.safe.min(self.clearance)).min(self.clearance));
        let travel = if self.full_retract { travel } else { travel.min((self.stock.along(self.at.truncate(), to.truncate()) + self.gap).max(to.z)) };
        let safe = if self.safe_at.as_ref().is_none_or(|f| f(to.truncate())) { self.safe } else { self.cleared(to.truncate()).map_or(self.clearance, |h| (h + self.gap).min(self.clearance)) };
        let stop = safe.min(travel).min(self.stock.reach(to.truncate()).max(to.z) + self.gap);
        retract(self.at, to.truncate(), travel, stop.max(to.z), out);
        if stop > to.z {
            out.push(Move::Line { to, feed });
        }
        self.at = to;
    }

    /// [`Cursor::cleared_to`] at `p`.
    pub fn cleared(&self, p: DVec2) -> Option<f64> {
        self.cleared_to.as_ref().and_then(|f| f(p))
    }

    /// Where material starts for a cut from `from` down to `to` whose tool runs along `segments`:
    /// the highest estimate of the in-process stock at points along them (the stock's cell or
    /// half the cutter's radius apart, whichever is larger), no higher than `from`; `None` when
    /// it stands no higher than `to` plus `threshold` (the cut would be in the air).
    pub fn material_top(&self, segments: impl IntoIterator<Item = Segment>, from: f64, to: f64, threshold: f64) -> Option<f64> {
        let spacing = self.stock.stock.grid().spacing.max(0.5 * self.stock.profile.radius);
        let top = self.stock.highest_along(segments, spacing, from);
        (top > to + threshold).then(|| top.clamp(to, from))
    }

    /// Tracks the end of moves appended since.
    pub fn moved(&mut self, out: &[Move]) {
        if let Some(m) = out.last() {
            self.at = m.to();
        }
    }
}

/// A path run the other way.
pub fn reversed(path: &[Segment]) -> Vec<Segment> {
    path.iter().rev().map(Segment::reversed).collect()
}

/// The passes along one line from `top` to `z_final`: each descends along the line at the ramp
/// angle by at most `stepdown`; an open line is cut back and forth, a closed one in laps; the
/// last pass follows the whole line at the final depth.
#[allow(clippy::too_many_arguments)]
pub fn cut_line(path: &[Segment], closed: bool, top: f64, z_final: f64, stepdown: f64, angle: f64, feed: f64, out: &mut Vec<Move>) {
    let (_, total) = arc_lengths(path);
    let back = reversed(path);
    let mut current = top;
    let mut forward = true;
    loop {
        let finishing = current <= z_final + FLOAT_SLACK;
        let target = (current - stepdown).max(z_final);
        let heights = if finishing { Heights::constant(z_final) } else { Heights::ramp(0.0, current, target, angle) };
        let segs = if forward || closed { path } else { &back[..] };
        follow(segs, 0.0, total, &heights, feed, out);
        if finishing {
            break;
        }
        current = heights.at(total);
        if !closed {
            forward = !forward;
        }
    }
}

/// Which of `left` to cut next from `here`, and whether from its far end: the nearest of their
/// starts and, where they may be run backwards, their ends (`ends` gives both; `None`: forwards
/// only, as a closed loop).
pub fn nearest_end<T>(left: &[T], here: DVec2, ends: impl Fn(&T) -> (DVec2, Option<DVec2>)) -> (usize, bool) {
    let mut best = (0, false, f64::INFINITY);
    for (k, item) in left.iter().enumerate() {
        let (start, end) = ends(item);
        for (flip, p) in [(false, Some(start)), (true, end)] {
            if let Some(d) = p.map(|p| p.distance(here)) {
                if d < best.2 {
                    best = (k, flip, d);
                }
            }
        }
    }
    (best.0, best.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heights_max_crosses_between_breakpoints() {
        let ramp = Heights::ramp(0.0, 0.0, -2.0, (1.0f64).atan()); // slope 1: 0 at 0, -2 at 2
        let tab = Heights(vec![(0.0, -3.0), (1.0, -3.0), (1.5, -1.0), (3.0, -1.0)]);
        let m = ramp.max(&tab);
        for k in 0..=30 {
            let s = k as f64 * 0.1;
            assert!((m.at(s) - ramp.at(s).max(tab.at(s))).abs() < 1e-12, "{s}");
        }
    }

    #[test]
    fn a_sliver_of_an_arc_goes_as_a_line_never_as_a_full_circle() {
        let arc = Segment::arc(DVec2::new(0.0, 20.0), DVec2::new(3.0, 17.0), DVec2::new(0.0, 17.0), false);
        // A loop split 4e-8 mm from a joint: the sliver's ends nearly meet.
        let segs = [arc.sub(0.0, 1.0 - 1e-8), arc.sub(1.0 - 1e-8, 1.0)];
        let mut out = Vec::new();
        let total = segs[0].length() + segs[1].length();
        follow(&segs, 0.0, total, &Heights::constant(0.0), 100.0, &mut out);
        assert_eq!(out.len(), 2);
        assert!(matches!(out[0], Move::Arc { .. }) && matches!(out[1], Move::Line { .. }), "{out:?}");
        let mut at = segs[0].a.extend(0.0);
        let length: f64 = out
            .iter()
            .map(|m| {
                let l = m.length(at);
                at = m.to();
                l
            })
            .sum();
        assert!((length - total).abs() < 1e-9, "{length} against {total}");
    }

    #[test]
    fn follow_walks_a_square_twice_with_a_ramp() {
        let l = Loop::rect(DVec2::ZERO, DVec2::splat(10.0));
        let segs: Vec<Segment> = l.segments().collect();
        let mut out = Vec::new();
        let z = Heights::ramp(0.0, 0.0, -1.0, (0.1f64).atan()); // reaches -1 after 10 mm
        follow(&segs, 0.0, 50.0, &z, 100.0, &mut out);
        assert_eq!(out.len(), 5);
        assert!((out[0].to().z + 1.0).abs() < 1e-12);
        assert!(out[4].to().distance(DVec3::new(10.0, 0.0, -1.0)) < 1e-12);
    }
}
