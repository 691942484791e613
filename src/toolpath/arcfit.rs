//! Runs of short lines at one height and one feed replaced by fewer lines and arcs (G1, G2,
//! G3) within a tolerance, so that a controller does not crawl through thousands of tiny
//! moves: seed 004 §3.3 fits arcs to the segments its load correction inserts; the same pass
//! serves any strategy that makes dense points.

use super::Move;
use crate::geom::tolerance::FLOAT_ZERO;
use crate::geom::{DVec2, DVec3};

/// The most points one fitted piece spans (a bound on the work per piece).
const MOST: usize = 400;
/// Circles larger than this are lines (mm).
const LARGEST_RADIUS: f64 = 1e4;

/// `moves`, starting from `from`, with each run of lines at one height and feed replaced by
/// lines and arcs that stay within `tol` of its points, and whose points between them are
/// accepted by `ok` (the region the tool's centre may occupy).
pub fn fit(moves: &[Move], from: DVec3, tol: f64, ok: &dyn Fn(DVec2) -> bool) -> Vec<Move> {
    let mut out = Vec::with_capacity(moves.len());
    let mut at = from;
    let mut k = 0;
    while k < moves.len() {
        let Move::Line { feed, .. } = moves[k] else {
            out.push(moves[k]);
            at = moves[k].to();
            k += 1;
            continue;
        };
        // The run: lines at the height `at` stands at, with this feed.
        let mut pts = vec![at.truncate()];
        let z = at.z;
        let mut e = k;
        while let Some(Move::Line { to, feed: f }) = moves.get(e) {
            if to.z != z || *f != feed {
                break;
            }
            pts.push(to.truncate());
            e += 1;
        }
        if e == k {
            // A line changing height: as it is.
            out.push(moves[k]);
            at = moves[k].to();
            k += 1;
            continue;
        }
        let mut i = 0;
        while i + 1 < pts.len() {
            let (j, arc) = longest_piece(&pts, i, tol, ok);
            let to = pts[j].extend(z);
            match arc {
                Some((center, clockwise)) => out.push(Move::Arc { to, center, clockwise, feed }),
                None => out.push(Move::Line { to, feed }),
            }
            i = j;
        }
        at = pts[pts.len() - 1].extend(z);
        k = e;
    }
    out
}

/// The farthest point from `i` that one line or one arc reaches within `tol`, and the arc's
/// centre and turn (clockwise) when an arc reaches farther than a line. The reach grows by
/// doubling, then is bisected (a piece that fits is assumed to fit when shortened); an arc is
/// checked against `ok` only once chosen, and shortened until it passes.
fn longest_piece(pts: &[DVec2], i: usize, tol: f64, ok: &dyn Fn(DVec2) -> bool) -> (usize, Option<(DVec2, bool)>) {
    let last = (pts.len() - 1).min(i + MOST);
    let line = farthest(i + 1, last, &|j| fits_line(&pts[i..=j], tol));
    let arc_end = if i + 2 <= last && fits_arc(&pts[i..=i + 2], tol).is_some() { farthest(i + 2, last, &|j| fits_arc(&pts[i..=j], tol).is_some()) } else { i };
    let mut j = arc_end;
    while j > line.max(i + 1) {
        if let Some(a) = fits_arc(&pts[i..=j], tol).filter(|&(c, _)| arc_clear(&pts[i..=j], c, ok)) {
            return (j, Some(a));
        }
        j -= 1.max((j - line) / 2);
    }
    (line, None)
}

/// The largest `j` in `[from, last]` for which `fits(j)` holds, given that it holds at `from`
/// and keeps holding below any `j` where it holds.
fn farthest(from: usize, last: usize, fits: &dyn Fn(usize) -> bool) -> usize {
    let (mut good, mut step) = (from, 1);
    let mut bad = last + 1;
    while good + step <= last {
        if fits(good + step) {
            good += step;
            step *= 2;
        } else {
            bad = good + step;
            break;
        }
    }
    if bad == last + 1 && good < last {
        if fits(last) {
            return last;
        }
        bad = last;
    }
    while bad - good > 1 {
        let mid = (good + bad) / 2;
        if fits(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}

/// Whether the middle of the arc between each two points is accepted by `ok`.
fn arc_clear(p: &[DVec2], c: DVec2, ok: &dyn Fn(DVec2) -> bool) -> bool {
    let r = c.distance(p[0]);
    p.windows(2).all(|w| ok(c + ((w[0] - c) + (w[1] - c)).normalize_or_zero() * r))
}

/// Whether the points lie within `tol` of the line from the first to the last, in order along it.
fn fits_line(p: &[DVec2], tol: f64) -> bool {
    let (a, b) = (p[0], p[p.len() - 1]);
    let d = b - a;
    let len = d.length();
    if len < FLOAT_ZERO {
        return false;
    }
    let u = d / len;
    let mut along = 0.0;
    p.iter().all(|&q| {
        let t = (q - a).dot(u);
        let ok = (q - a).perp_dot(u).abs() <= tol && t >= along - FLOAT_ZERO && t <= len + FLOAT_ZERO;
        along = t;
        ok
    })
}

/// The centre and turn of the arc through the first, middle and last point, when every point
/// lies within `tol` of it, in order, turning less than a full circle, and the arc between
/// each two points stays within `tol` of their chord.
fn fits_arc(p: &[DVec2], tol: f64) -> Option<(DVec2, bool)> {
    let (a, m, b) = (p[0], p[p.len() / 2], p[p.len() - 1]);
    let d = 2.0 * ((m - a).perp_dot(b - a));
    if d.abs() < FLOAT_ZERO {
        return None;
    }
    // The circumcentre.
    let (am, ab) = (m - a, b - a);
    let c = a + DVec2::new(ab.y * am.length_squared() - am.y * ab.length_squared(), am.x * ab.length_squared() - ab.x * am.length_squared()) / d;
    let r = c.distance(a);
    if r > LARGEST_RADIUS {
        return None;
    }
    let clockwise = d < 0.0;
    let sign = if clockwise { -1.0 } else { 1.0 };
    let mut swept = 0.0;
    for w in p.windows(2) {
        let (u, v) = (w[0] - c, w[1] - c);
        let turn = sign * u.perp_dot(v).atan2(u.dot(v));
        if turn < 0.0 || (w[1].distance(c) - r).abs() > tol {
            return None;
        }
        swept += turn;
        let half = w[0].distance(w[1]) * 0.5;
        if r - (r * r - half * half).max(0.0).sqrt() > tol {
            return None;
        }
    }
    (swept < 1.9 * std::f64::consts::PI).then_some((c, clockwise))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dense_points_on_a_circle_and_a_line_become_one_arc_and_one_line() {
        let c = DVec2::new(10.0, 0.0);
        let mut moves: Vec<Move> = (1..=90)
            .map(|k| {
                let a = std::f64::consts::PI - std::f64::consts::PI * k as f64 / 180.0;
                Move::Line { to: (c + DVec2::from_angle(a) * 10.0).extend(-1.0), feed: 500.0 }
            })
            .collect();
        moves.extend((1..=20).map(|k| Move::Line { to: DVec3::new(10.0 + k as f64, 10.0, -1.0), feed: 500.0 }));
        let out = fit(&moves, DVec3::new(0.0, 0.0, -1.0), 0.001, &|_| true);
        assert_eq!(out.len(), 2, "{out:?}");
        match out[0] {
            Move::Arc { to, center, clockwise, .. } => {
                assert!(to.distance(DVec3::new(10.0, 10.0, -1.0)) < 1e-9 && center.distance(c) < 1e-6 && clockwise);
            }
            m => panic!("{m:?}"),
        }
        assert!(matches!(out[1], Move::Line { to, .. } if to == DVec3::new(30.0, 10.0, -1.0)));
    }

    #[test]
    fn a_change_of_feed_or_height_and_a_turn_back_stay() {
        let moves = vec![
            Move::Line { to: DVec3::new(1.0, 0.0, 0.0), feed: 100.0 },
            Move::Line { to: DVec3::new(2.0, 0.0, 0.0), feed: 50.0 },
            Move::Line { to: DVec3::new(0.0, 0.0, 0.0), feed: 50.0 },
            Move::Line { to: DVec3::new(0.0, 0.0, -1.0), feed: 50.0 },
        ];
        let out = fit(&moves, DVec3::ZERO, 0.01, &|_| true);
        assert_eq!(out, moves);
    }
}
