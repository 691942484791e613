//! Curves (ellipses, splines, Béziers) replaced by arcs that stay within a tolerance of them,
//! so that everything reaching the offsetter is lines and arcs.

use crate::geom::segment::Segment;
use crate::geom::DVec2;

/// Deepest halving of a piece before it is accepted as it is: 65,536 arcs to an eighth of a
/// turn, more than any curve within 10 m needs at a micrometre (24 let a degenerate curve ask
/// for 16 million).
const MAX_DEPTH: u32 = 16;

/// Appends arcs (or lines, where the curve is straight) approximating `f` over `[t0, t1]` to
/// `out`, each within `tol` of the curve at nine points along its piece. The curve starts in
/// `pieces` equal pieces (enough that none turns through half a circle).
pub fn fit_arcs(f: &dyn Fn(f64) -> DVec2, t0: f64, t1: f64, pieces: usize, tol: f64, out: &mut Vec<Segment>) {
    let n = pieces.max(1);
    for k in 0..n {
        let a = t0 + (t1 - t0) * k as f64 / n as f64;
        let b = t0 + (t1 - t0) * (k + 1) as f64 / n as f64;
        fit_piece(f, a, b, tol, 0, out);
    }
}

fn fit_piece(f: &dyn Fn(f64) -> DVec2, a: f64, b: f64, tol: f64, depth: u32, out: &mut Vec<Segment>) {
    let (p0, pm, p1) = (f(a), f((a + b) * 0.5), f(b));
    if p0.distance(p1) <= tol * 1e-3 && p0.distance(pm) <= tol {
        return; // a point: nothing to draw
    }
    let seg = through(p0, pm, p1);
    let fits = (1..8).all(|k| seg.distance_to(f(a + (b - a) * k as f64 / 8.0)) <= tol);
    if fits || depth >= MAX_DEPTH {
        out.push(seg);
    } else {
        let m = (a + b) * 0.5;
        fit_piece(f, a, m, tol, depth + 1, out);
        fit_piece(f, m, b, tol, depth + 1, out);
    }
}

/// The arc from `p0` through `pm` to `p1`, or the line when they are (nearly) collinear.
pub fn through(p0: DVec2, pm: DVec2, p1: DVec2) -> Segment {
    let cross = (pm - p0).perp_dot(p1 - p0);
    let chord = p0.distance(p1);
    if cross.abs() <= 1e-12 * chord * chord.max(1.0) || chord == 0.0 {
        return Segment::line(p0, p1);
    }
    // The bulge is tan of a quarter of the sweep; the inscribed angle at pm is half the
    // sweep's complement: bulge = tan((π − ∠p0 pm p1)/2) with the turn's sign.
    let (u, v) = (p0 - pm, p1 - pm);
    let angle = u.perp_dot(v).abs().atan2(u.dot(v)); // ∠p0 pm p1 in (0, π)
    let bulge = ((std::f64::consts::PI - angle) / 2.0).tan() * -cross.signum();
    Segment { a: p0, b: p1, bulge: -bulge }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_is_fitted_exactly_and_ellipse_within_tolerance() {
        let circle = |t: f64| DVec2::new(3.0 + 2.0 * t.cos(), -1.0 + 2.0 * t.sin());
        let mut out = Vec::new();
        fit_arcs(&circle, 0.0, std::f64::consts::TAU, 4, 1e-3, &mut out);
        assert_eq!(out.len(), 4);
        for s in &out {
            let g = s.arc_geom().unwrap();
            assert!((g.radius - 2.0).abs() < 1e-9 && g.center.distance(DVec2::new(3.0, -1.0)) < 1e-9);
            assert!(g.bulge > 0.0);
        }
        let ellipse = |t: f64| DVec2::new(10.0 * t.cos(), 4.0 * t.sin());
        let mut out = Vec::new();
        fit_arcs(&ellipse, 0.0, std::f64::consts::TAU, 4, 1e-3, &mut out);
        for k in 0..1000 {
            let p = ellipse(k as f64 / 1000.0 * std::f64::consts::TAU);
            let d = out.iter().map(|s| s.distance_to(p)).fold(f64::INFINITY, f64::min);
            assert!(d < 1.1e-3, "{d}");
        }
        let area: f64 = crate::drawing::Loop::from_segments(&out).area();
        assert!((area - std::f64::consts::PI * 40.0).abs() < 0.05, "{area}");
    }
}
