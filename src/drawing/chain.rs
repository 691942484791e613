//! Entities chained into closed loops: end points within the chaining tolerance are one
//! point. A chain that does not close is reported by layer and location, never closed or
//! dropped silently. A curve drawn finely divided (a hole as 100,000 lines of 0.6 µm, a fillet
//! as 2,000) chains like any other, whatever its pieces' length: a chain closes where its end
//! meets its start and nothing nearer continues it, and [`tidy`] then fits its runs of short
//! lines with the arcs (or lines) they trace.

use std::collections::{BTreeMap, VecDeque};

use super::{DrawnLoop, Loop, OpenChain};
use crate::drawing::arcfit::through;
use crate::geom::segment::Segment;
use crate::geom::tolerance::FINE_PIECE;
use crate::geom::DVec2;

/// Loops and open chains made of `pieces` (segment, layer); chains never mix layers. `tol` is
/// the chaining tolerance; the chains are tidied ([`tidy`]) within `fit` (the arc-fit
/// tolerance).
pub fn chain(pieces: Vec<(Segment, String)>, tol: f64, fit: f64) -> (Vec<DrawnLoop>, Vec<OpenChain>) {
    let mut by_layer: BTreeMap<String, Vec<Segment>> = BTreeMap::new();
    for (s, layer) in pieces {
        if s.length() > 0.0 && s.a.is_finite() && s.b.is_finite() && s.bulge.is_finite() {
            by_layer.entry(layer).or_default().push(s);
        }
    }
    let (mut loops, mut open) = (Vec::new(), Vec::new());
    for (layer, segs) in by_layer {
        chain_layer(&segs, tol, fit, &layer, &mut loops, &mut open);
    }
    (loops, open)
}

/// A chain with its runs of short lines (three or more, each shorter than [`FINE_PIECE`]: a
/// curve drawn finely divided) replaced by the arcs and lines they trace, each within `fit` of
/// every point and chord of its run; then each piece still shorter than `tiny` merged into the
/// next (the chaining tolerance bridges it: its neighbour starts where it started). A closed
/// chain's runs may wrap past its start.
pub fn tidy(chain: Vec<Segment>, closed: bool, fit: f64, tiny: f64) -> Vec<Segment> {
    let short = |s: &Segment| s.is_line() && s.length() < FINE_PIECE;
    let n = chain.len();
    // A closed chain whose run wraps past its start starts after a piece that is no part of a
    // run (if it has one).
    let wraps = closed && n > 1 && short(&chain[0]) && short(&chain[n - 1]);
    let start = if wraps { (0..n).find(|&k| !short(&chain[k])).map_or(0, |k| (k + 1) % n) } else { 0 };
    let chain: Vec<Segment> = chain[start..].iter().chain(&chain[..start]).copied().collect();
    let mut out: Vec<Segment> = Vec::with_capacity(n);
    let mut k = 0;
    while k < n {
        let run = chain[k..].iter().take_while(|s| short(s)).count();
        if run >= 3 {
            let points: Vec<DVec2> = std::iter::once(chain[k].a).chain(chain[k..k + run].iter().map(|s| s.b)).collect();
            fit_run(&points, fit, &mut out);
            k += run;
        } else {
            out.push(chain[k]);
            k += 1;
        }
    }
    // Pieces shorter than `tiny`: their neighbour takes their start.
    if out.len() > 1 && out.iter().any(|s| s.length() < tiny) && out.iter().any(|s| s.length() >= tiny) {
        let end = out[out.len() - 1].b;
        let mut kept: Vec<Segment> = Vec::with_capacity(out.len());
        let mut from: Option<DVec2> = None;
        for s in &out {
            if s.length() < tiny {
                from.get_or_insert(s.a);
                continue;
            }
            kept.push(Segment { a: from.take().unwrap_or(s.a), ..*s });
        }
        if from.is_some() {
            // The chain ended in short pieces: the last kept piece reaches its end.
            let end = if closed { kept[0].a } else { end };
            let last = kept.len() - 1;
            kept[last].b = end;
        }
        return kept;
    }
    out
}

/// Appends to `out` the arcs (or lines) through the polyline `p`, each as long as it can be
/// while every point of its stretch and every chord's middle lies within `fit` of it and it
/// turns through at most half a circle: grown by doubling, then by halving back (a run of n
/// points costs n log n).
fn fit_run(p: &[DVec2], fit: f64, out: &mut Vec<Segment>) {
    let piece = |i: usize, j: usize| if j == i + 1 { Segment::line(p[i], p[j]) } else { through(p[i], p[(i + j) / 2], p[j]) };
    let fits = |i: usize, j: usize| {
        let s = piece(i, j);
        s.bulge.abs() <= 1.0 && (i..j).all(|k| s.distance_to(p[k + 1]) <= fit && s.distance_to((p[k] + p[k + 1]) * 0.5) <= fit)
    };
    let last = p.len() - 1;
    let mut i = 0;
    while i < last {
        let (mut good, mut step) = (i + 1, 1);
        while good + step <= last && fits(i, good + step) {
            good += step;
            step *= 2;
        }
        let mut bad = (good + step).min(last + 1);
        while bad - good > 1 {
            let mid = (good + bad) / 2;
            if fits(i, mid) {
                good = mid;
            } else {
                bad = mid;
            }
        }
        out.push(piece(i, good));
        i = good;
    }
}

/// `pieces` with every duplicate dropped: a segment whose ends lie within `tol` of another's on
/// the same layer (either way round) and whose bulge matches it (its middle within `tol`); for
/// a piece shorter than four times `tol`, within a quarter of its length (the next piece of a
/// finely divided curve is no copy of it).
pub fn without_duplicates(pieces: Vec<(Segment, String)>, tol: f64) -> Vec<(Segment, String)> {
    // Each piece with its ends in order (lower x first), so a reversed copy has the same start.
    let canonical = |s: &Segment| if (s.a.x, s.a.y) <= (s.b.x, s.b.y) { *s } else { s.reversed() };
    let keys: Vec<Segment> = pieces.iter().map(|(s, _)| canonical(s)).collect();
    let starts = PointGrid::new(keys.iter().map(|s| s.a), tol);
    let mut dropped = vec![false; pieces.len()];
    for i in 0..keys.len() {
        if dropped[i] {
            continue;
        }
        let (si, li) = (&keys[i], &pieces[i].1);
        let near = tol.min(si.length() * 0.25);
        starts.near(si.a, near, |j| {
            let sj = &keys[j];
            if j > i && !dropped[j] && pieces[j].1 == *li && sj.b.distance(si.b) <= near && sj.point_at(0.5).distance(si.point_at(0.5)) <= near {
                dropped[j] = true;
            }
        });
    }
    pieces.into_iter().zip(dropped).filter(|(_, d)| !d).map(|(p, _)| p).collect()
}

/// Points in square cells as wide as the tolerance they are looked up within: the points near
/// one are those of its cell and the eight around it, however the drawing lines its entities up
/// (a panel's 100,000 holes share their ends' x by the hundred; sorted by x, each lookup read
/// them all).
struct PointGrid {
    cell: f64,
    cells: std::collections::HashMap<(i64, i64), Vec<usize>>,
    points: Vec<DVec2>,
}

impl PointGrid {
    fn new(points: impl Iterator<Item = DVec2>, tol: f64) -> PointGrid {
        let points: Vec<DVec2> = points.collect();
        let cell = tol.max(crate::geom::tolerance::FLOAT_SLACK);
        let mut cells: std::collections::HashMap<(i64, i64), Vec<usize>> = std::collections::HashMap::with_capacity(points.len());
        for (k, p) in points.iter().enumerate() {
            cells.entry(Self::key(*p, cell)).or_default().push(k);
        }
        PointGrid { cell, cells, points }
    }

    fn key(p: DVec2, cell: f64) -> (i64, i64) {
        ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64)
    }

    /// Calls `f` with each point within `within` (at most the grid's tolerance) of `p`.
    fn near(&self, p: DVec2, within: f64, mut f: impl FnMut(usize)) {
        let (i, j) = Self::key(p, self.cell);
        for di in -1..=1 {
            for dj in -1..=1 {
                if let Some(ks) = self.cells.get(&(i + di, j + dj)) {
                    for &k in ks {
                        if self.points[k].distance(p) <= within {
                            f(k);
                        }
                    }
                }
            }
        }
    }
}

fn chain_layer(segs: &[Segment], tol: f64, fit: f64, layer: &str, loops: &mut Vec<DrawnLoop>, open: &mut Vec<OpenChain>) {
    // The end points in a grid, to find the ends within `tol` of a point: a, then b, of each
    // segment (point 2i is segment i's a, 2i + 1 its b).
    let ends = PointGrid::new(segs.iter().flat_map(|s| [s.a, s.b]), tol);
    let mut used = vec![false; segs.len()];
    // The unused segment with an end within tol of p, whether that end is its b, and how far
    // (the nearest; of two as near, the first drawn).
    let find = |p: DVec2, used: &[bool]| -> Option<(usize, bool, f64)> {
        let mut best: Option<(usize, bool, f64)> = None;
        ends.near(p, tol, |k| {
            let (i, at_b) = (k / 2, k % 2 == 1);
            if used[i] {
                return;
            }
            let d = ends.points[k].distance(p);
            if best.is_none_or(|b| (d, k) < (b.2, 2 * b.0 + b.1 as usize)) {
                best = Some((i, at_b, d));
            }
        });
        best
    };
    for first in 0..segs.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut chain = VecDeque::from([segs[first]]);
        // Forward from the end, then backward from the start; a chain closes where its end
        // meets its start and no piece lies nearer (a finely divided curve's next piece does).
        let mut closed = false;
        loop {
            let end = chain[chain.len() - 1].b;
            let next = find(end, &used);
            let home = end.distance(chain[0].a);
            if (chain.len() > 1 || chain[0].bulge != 0.0) && home <= tol && next.is_none_or(|n| home <= n.2) {
                closed = true;
                break;
            }
            let Some((i, at_b, _)) = next else { break };
            used[i] = true;
            chain.push_back(if at_b { segs[i].reversed() } else { segs[i] });
        }
        if !closed {
            while let Some((i, at_b, _)) = find(chain[0].a, &used) {
                used[i] = true;
                chain.push_front(if at_b { segs[i] } else { segs[i].reversed() });
            }
            closed = chain[chain.len() - 1].b.distance(chain[0].a) <= tol && (chain.len() > 1 || chain[0].bulge != 0.0);
        }
        let mut chain = Vec::from(chain);
        if closed {
            // Each segment starts exactly where the one before ends.
            for k in 1..chain.len() {
                chain[k].a = chain[k - 1].b;
            }
            let n = chain.len();
            chain[n - 1].b = chain[0].a;
            let chain = tidy(chain, true, fit, tol * 0.5);
            loops.push(DrawnLoop { layer: layer.to_string(), path: Loop::from_segments(&chain) });
        } else {
            let chain = tidy(chain, false, fit, tol * 0.5);
            open.push(OpenChain { layer: layer.to_string(), start: chain[0].a, end: chain[chain.len() - 1].b, segments: chain.len(), path: chain });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn a_square_with_a_line_drawn_twice_still_closes() {
        let p = |x, y| DVec2::new(x, y);
        let l = |a, b| (Segment::line(a, b), "0".to_string());
        let mut pieces = vec![l(p(0.0, 0.0), p(10.0, 0.0)), l(p(10.0, 0.0), p(10.0, 10.0)), l(p(10.0, 10.0), p(0.0, 10.0)), l(p(0.0, 10.0), p(0.0, 0.0))];
        // The bottom drawn again, reversed and 0.004 off; an arc over the top twice; a line on
        // another layer where the left side is (kept: layers are apart).
        pieces.push(l(p(10.0, 0.004), p(0.0, 0.0)));
        pieces.push((Segment { a: p(0.0, 20.0), b: p(10.0, 20.0), bulge: 0.5 }, "0".into()));
        pieces.push((Segment { a: p(10.0, 20.0), b: p(0.0, 20.0), bulge: -0.5 }, "0".into()));
        pieces.push((Segment::line(p(0.0, 10.0), p(0.0, 0.0)), "other".into()));
        let kept = without_duplicates(pieces, 0.01);
        assert_eq!(kept.len(), 6);
        let (loops, open) = chain(kept, 0.01, 0.002);
        assert_eq!(loops.len(), 1, "{open:?}");
        assert_eq!(open.len(), 2, "the arc and the other layer's line stay open");
        // An arc bulging the other way is another entity.
        let two = vec![(Segment { a: p(0.0, 0.0), b: p(10.0, 0.0), bulge: 0.5 }, "0".to_string()), (Segment { a: p(0.0, 0.0), b: p(10.0, 0.0), bulge: -0.5 }, "0".to_string())];
        assert_eq!(without_duplicates(two, 0.01).len(), 2);
    }

    #[test]
    fn shuffled_and_reversed_pieces_close_and_gaps_are_reported() {
        let p = |x, y| DVec2::new(x, y);
        let pieces = vec![
            (Segment::line(p(10.0, 0.0), p(10.0, 10.0)), "0".to_string()),
            (Segment::line(p(0.0, 0.0), p(10.0, 0.0 + 0.001)), "0".to_string()),
            (Segment::line(p(0.0, 10.0), p(10.0, 10.0)), "0".to_string()), // reversed
            (Segment::line(p(0.0, 10.0), p(0.0, 0.0)), "0".to_string()),
            (Segment::line(p(20.0, 0.0), p(30.0, 0.0)), "cut".to_string()),
            (Segment::line(p(30.0, 0.0), p(30.0, 5.0)), "cut".to_string()),
        ];
        let (loops, open) = chain(pieces, 0.01, 0.002);
        assert_eq!(loops.len(), 1);
        assert!((loops[0].path.area().abs() - 100.0).abs() < 0.01);
        assert_eq!(open.len(), 1);
        assert_eq!(open[0].layer, "cut");
        assert_eq!(open[0].segments, 2);
        assert!(open[0].start.distance(p(20.0, 0.0)) < 1e-12 && open[0].end.distance(p(30.0, 5.0)) < 1e-12);
    }
}
