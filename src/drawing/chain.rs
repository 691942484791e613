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
    // Each piece with its ends in order (lower x first), so a reversed copy sorts beside it.
    let canonical = |s: &Segment| if (s.a.x, s.a.y) <= (s.b.x, s.b.y) { *s } else { s.reversed() };
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    let keys: Vec<Segment> = pieces.iter().map(|(s, _)| canonical(s)).collect();
    order.sort_by(|&i, &j| keys[i].a.x.total_cmp(&keys[j].a.x));
    let mut dropped = vec![false; pieces.len()];
    for (n, &i) in order.iter().enumerate() {
        if dropped[i] {
            continue;
        }
        let (si, li) = (&keys[i], &pieces[i].1);
        let near = tol.min(si.length() * 0.25);
        for &j in order[n + 1..].iter().take_while(|&&j| keys[j].a.x <= si.a.x + near) {
            let sj = &keys[j];
            if !dropped[j] && pieces[j].1 == *li && sj.a.distance(si.a) <= near && sj.b.distance(si.b) <= near && sj.point_at(0.5).distance(si.point_at(0.5)) <= near {
                dropped[j] = true;
            }
        }
    }
    pieces.into_iter().zip(dropped).filter(|(_, d)| !d).map(|(p, _)| p).collect()
}

fn chain_layer(segs: &[Segment], tol: f64, fit: f64, layer: &str, loops: &mut Vec<DrawnLoop>, open: &mut Vec<OpenChain>) {
    // End points sorted by x, to find the ends within `tol` of a point.
    let mut ends: Vec<(f64, usize, bool)> = Vec::with_capacity(segs.len() * 2);
    for (i, s) in segs.iter().enumerate() {
        ends.push((s.a.x, i, false));
        ends.push((s.b.x, i, true));
    }
    ends.sort_by(|a, b| a.0.total_cmp(&b.0));
    let point = |i: usize, at_b: bool| if at_b { segs[i].b } else { segs[i].a };
    let mut used = vec![false; segs.len()];
    // The unused segment with an end within tol of p, whether that end is its b, and how far.
    let find = |p: DVec2, used: &[bool]| -> Option<(usize, bool, f64)> {
        let lo = ends.partition_point(|e| e.0 < p.x - tol);
        ends[lo..].iter().take_while(|e| e.0 <= p.x + tol).filter(|e| !used[e.1]).map(|e| (e.1, e.2, point(e.1, e.2).distance(p))).filter(|e| e.2 <= tol).min_by(|a, b| a.2.total_cmp(&b.2))
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
