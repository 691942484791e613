//! Step 2 of seed 003 (§2-2, Figs. 4–7): neighbouring raw entities are joined into one loop.

use super::raw::RawEntity;
use crate::drawing::Loop;
use crate::geom::segment::Segment;
use crate::geom::DVec2;

/// How the raw entity `i` meets entity `i + 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Join {
    /// Their ends already meet (tangent entities, or a collapsed arc between them).
    Meet,
    /// They cross at `p`, at position `t` along the first and `u` along the second (keys of
    /// `Segment::position_with`): both are cut there and what lies past the crossing is
    /// trimmed at once (Fig. 7).
    Cross { t: f64, u: f64, p: DVec2 },
    /// They do not meet: an arc of the distance's radius about the original corner joins them.
    Arc,
}

/// The raw offset of `l` joined into one closed chain of segments: at every corner the
/// neighbours are cut at their crossing when the corner turns away from the offset side and
/// they cross, and joined by an arc about the corner otherwise (a corner turning away whose
/// entities are too short to cross gets an arc that runs backwards: a twisted part that
/// [`super::trim`] removes).
pub fn join_neighbours(l: &Loop, raw: &[RawEntity], distance: f64, eps: f64) -> Vec<Segment> {
    let n = raw.len();
    if n == 0 {
        return Vec::new();
    }
    let mut joins: Vec<Join> = (0..n).map(|i| classify(l, raw, i, distance, eps)).collect();
    // Range kept of each entity; an entity that both its crossings would consume entirely
    // gets arcs at both ends instead (the global trim then sorts it out).
    let range = |joins: &[Join], i: usize| {
        let (t1, p1) = match joins[i] {
            Join::Cross { t, p, .. } => (t, Some(p)),
            _ => (1.0, None),
        };
        let (t0, p0) = match joins[(i + n - 1) % n] {
            Join::Cross { u, p, .. } => (u, Some(p)),
            _ => (0.0, None),
        };
        (t0, t1, p0, p1)
    };
    loop {
        let mut changed = false;
        for i in 0..n {
            let (t0, t1, ..) = range(&joins, i);
            if !raw[i].collapsed && t1 - t0 <= 0.0 {
                joins[i] = Join::Arc;
                joins[(i + n - 1) % n] = Join::Arc;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let mut out: Vec<Segment> = Vec::with_capacity(2 * n);
    for i in 0..n {
        let (_, _, p0, p1) = range(&joins, i);
        if !raw[i].collapsed {
            let seg = raw[i].seg;
            let s = if p0.is_some() || p1.is_some() { seg.between(seg.arc_geom().as_ref(), p0.unwrap_or(seg.a), p1.unwrap_or(seg.b)) } else { seg };
            if s.a != s.b {
                out.push(s);
            }
        }
        if joins[i] == Join::Arc {
            let next = &raw[(i + 1) % n];
            let corner = l.vertices[(i + 1) % n].p;
            let (from, to) = (raw[i].seg.b, next.seg.a);
            let arc = Segment::arc(from, to, corner, corner_turn(from - corner, to - corner, distance) > 0.0);
            if arc.a != arc.b {
                out.push(arc);
            }
        }
    }
    // Each segment starts exactly where the one before it ends.
    for k in 0..out.len() {
        let prev_end = out[(k + out.len() - 1) % out.len()].b;
        out[k].a = prev_end;
    }
    out.retain(|s| s.a != s.b);
    out
}

fn classify(l: &Loop, raw: &[RawEntity], i: usize, distance: f64, eps: f64) -> Join {
    let n = raw.len();
    let (a, b) = (&raw[i], &raw[(i + 1) % n]);
    if a.seg.b.distance(b.seg.a) <= eps {
        return Join::Meet;
    }
    let corner = l.vertices[(i + 1) % n].p;
    let turns_away = corner_turn(a.seg.b - corner, b.seg.a - corner, distance) * distance < 0.0;
    if !turns_away || a.collapsed || b.collapsed || n < 2 {
        return Join::Arc;
    }
    let crossings = a.seg.crossings(&b.seg, eps);
    let last = crossings.iter().max_by(|p, q| p.t.total_cmp(&q.t));
    let first = crossings.iter().min_by(|p, q| p.u.total_cmp(&q.u));
    match (last, first) {
        (Some(x), Some(y)) if x == y => Join::Cross { t: x.t, u: x.u, p: x.p },
        _ => Join::Arc,
    }
}

/// Which way the join arc about the corner turns from `from` to `to` (both at the distance
/// from it): the sign of the corner's turning angle, positive counter-clockwise; a full
/// reversal goes round the corner's outside.
fn corner_turn(from: DVec2, to: DVec2, distance: f64) -> f64 {
    let (sin, cos) = (from.perp_dot(to), from.dot(to));
    if cos < 0.0 && sin.abs() < 1e-12 * from.length() * to.length() {
        distance.signum()
    } else {
        sin
    }
}
