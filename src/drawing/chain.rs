//! Entities chained into closed loops: end points within the chaining tolerance are one
//! point. A chain that does not close is reported by layer and location, never closed or
//! dropped silently.

use std::collections::BTreeMap;

use super::{DrawnLoop, Loop, OpenChain};
use crate::geom::segment::Segment;

/// Loops and open chains made of `pieces` (segment, layer); chains never mix layers.
pub fn chain(pieces: Vec<(Segment, String)>, tol: f64) -> (Vec<DrawnLoop>, Vec<OpenChain>) {
    let mut by_layer: BTreeMap<String, Vec<Segment>> = BTreeMap::new();
    for (s, layer) in pieces {
        if s.length() > 0.0 && s.a.is_finite() && s.b.is_finite() && s.bulge.is_finite() {
            by_layer.entry(layer).or_default().push(s);
        }
    }
    let (mut loops, mut open) = (Vec::new(), Vec::new());
    for (layer, segs) in by_layer {
        chain_layer(&segs, tol, &layer, &mut loops, &mut open);
    }
    (loops, open)
}

/// `pieces` with every duplicate dropped: a segment whose ends lie within `tol` of another's on
/// the same layer (either way round) and whose bulge matches it (its middle within `tol`).
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
        for &j in order[n + 1..].iter().take_while(|&&j| keys[j].a.x <= si.a.x + tol) {
            let sj = &keys[j];
            if !dropped[j] && pieces[j].1 == *li && sj.a.distance(si.a) <= tol && sj.b.distance(si.b) <= tol && sj.point_at(0.5).distance(si.point_at(0.5)) <= tol {
                dropped[j] = true;
            }
        }
    }
    pieces.into_iter().zip(dropped).filter(|(_, d)| !d).map(|(p, _)| p).collect()
}

fn chain_layer(segs: &[Segment], tol: f64, layer: &str, loops: &mut Vec<DrawnLoop>, open: &mut Vec<OpenChain>) {
    // End points sorted by x, to find the ends within `tol` of a point.
    let mut ends: Vec<(f64, usize, bool)> = Vec::with_capacity(segs.len() * 2);
    for (i, s) in segs.iter().enumerate() {
        ends.push((s.a.x, i, false));
        ends.push((s.b.x, i, true));
    }
    ends.sort_by(|a, b| a.0.total_cmp(&b.0));
    let point = |i: usize, at_b: bool| if at_b { segs[i].b } else { segs[i].a };
    let mut used = vec![false; segs.len()];
    // The unused segment with an end within tol of p, and whether that end is its b.
    let find = |p: glam::DVec2, used: &[bool]| -> Option<(usize, bool)> {
        let lo = ends.partition_point(|e| e.0 < p.x - tol);
        ends[lo..]
            .iter()
            .take_while(|e| e.0 <= p.x + tol)
            .filter(|e| !used[e.1] && point(e.1, e.2).distance(p) <= tol)
            .min_by(|a, b| point(a.1, a.2).distance(p).total_cmp(&point(b.1, b.2).distance(p)))
            .map(|e| (e.1, e.2))
    };
    for first in 0..segs.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut chain = vec![segs[first]];
        // Forward from the end, then backward from the start.
        loop {
            let end = chain[chain.len() - 1].b;
            if chain.len() > 1 && end.distance(chain[0].a) <= tol {
                break;
            }
            let Some((i, at_b)) = find(end, &used) else { break };
            used[i] = true;
            chain.push(if at_b { segs[i].reversed() } else { segs[i] });
        }
        let closed = chain[chain.len() - 1].b.distance(chain[0].a) <= tol && (chain.len() > 1 || chain[0].bulge != 0.0);
        if !closed {
            loop {
                let start = chain[0].a;
                let Some((i, at_b)) = find(start, &used) else { break };
                used[i] = true;
                chain.insert(0, if at_b { segs[i] } else { segs[i].reversed() });
            }
        }
        let closed = chain[chain.len() - 1].b.distance(chain[0].a) <= tol && (chain.len() > 1 || chain[0].bulge != 0.0);
        if closed {
            // Each segment starts exactly where the one before ends.
            for k in 1..chain.len() {
                chain[k].a = chain[k - 1].b;
            }
            let n = chain.len();
            chain[n - 1].b = chain[0].a;
            loops.push(DrawnLoop { layer: layer.to_string(), path: Loop::from_segments(&chain) });
        } else {
            open.push(OpenChain { layer: layer.to_string(), start: chain[0].a, end: chain[chain.len() - 1].b, segments: chain.len(), path: chain.clone() });
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
        let (loops, open) = chain(kept, 0.01);
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
        let (loops, open) = chain(pieces, 0.01);
        assert_eq!(loops.len(), 1);
        assert!((loops[0].path.area().abs() - 100.0).abs() < 0.01);
        assert_eq!(open.len(), 1);
        assert_eq!(open[0].layer, "cut");
        assert_eq!(open[0].segments, 2);
        assert!(open[0].start.distance(p(20.0, 0.0)) < 1e-12 && open[0].end.distance(p(30.0, 5.0)) < 1e-12);
    }
}
