//! What a correct offset is, checked point by point: the properties the tests, the fuzz target
//! and the benchmark's random corpus demand of every result. Also the random shapes they use.

use crate::drawing::{Loop, Shape, Vertex};
use crate::geom::index::RectIndex;
use crate::geom::segment::{Rect, Segment};
use crate::geom::DVec2;

use super::trim::Original;

/// Points where two segments of the shape cross or touch (within `eps`), other than the vertex
/// two neighbours share (their meeting points within `near` of it).
pub fn self_crossings(shape: &Shape, eps: f64, near: f64) -> Vec<DVec2> {
    meeting_points(shape, eps, near, false)
}

/// [`self_crossings`] less the points where two entities only touch: they meet at one point (or
/// at two within `near` of each other) and are tangent there. An offset whose region is pinched
/// to a point (two offset circles exactly tangent: the distance is exactly half the gap) must
/// touch itself there, since both sides of the pinch pass through it.
pub fn crossings_not_touching(shape: &Shape, eps: f64, near: f64) -> Vec<DVec2> {
    meeting_points(shape, eps, near, true)
}

fn meeting_points(shape: &Shape, eps: f64, near: f64, allow_touching: bool) -> Vec<DVec2> {
    /// Directions closer than this (sine of the angle) are tangent.
    const TANGENT: f64 = 1e-6;
    let mut segs: Vec<(usize, usize, usize, Segment)> = Vec::new();
    for (k, l) in shape.loops.iter().enumerate() {
        for (i, s) in l.segments().enumerate() {
            segs.push((k, i, l.len(), s));
        }
    }
    let rects: Vec<Rect> = segs.iter().map(|s| s.3.bounds().expand(eps)).collect();
    let index = RectIndex::new(&rects);
    let mut found = Vec::new();
    for g in 0..segs.len() {
        let (k, i, m, s) = segs[g];
        index.query(&rects[g], |h| {
            if h <= g {
                return;
            }
            let (kh, j, _, o) = segs[h];
            let points: Vec<DVec2> = s
                .crossings(&o, eps)
                .iter()
                .map(|c| c.p)
                .filter(|p| {
                    let shared_next = kh == k && j == (i + 1) % m && p.distance(s.b) <= near;
                    let shared_prev = kh == k && i == (j + 1) % m && p.distance(s.a) <= near;
                    !(shared_next || shared_prev)
                })
                .collect();
            let touching = allow_touching
                && !points.is_empty()
                && points.iter().all(|p| p.distance(points[0]) <= near)
                && s.direction_at(s.arc_geom().as_ref(), points[0]).perp_dot(o.direction_at(o.arc_geom().as_ref(), points[0])).abs() < TANGENT;
            if !touching {
                found.extend(points);
            }
        });
    }
    found
}

/// Everything wrong with `result` as the offset of `input` by `distance`, each as a sentence;
/// empty when it is right. `tol` bounds distances (mm); `samples` is the number of test points
/// per segment and the square root of the number of area probes.
pub fn problems(input: &Shape, distance: f64, result: &Shape, tol: f64, samples: usize) -> Vec<String> {
    let mut out = Vec::new();
    for (k, l) in result.loops.iter().enumerate() {
        if l.len() < 2 {
            out.push(format!("loop {k} has {} entities", l.len()));
        }
        if l.segments().any(|s| !(s.length() > 0.0) || !s.a.is_finite() || !s.bulge.is_finite()) {
            out.push(format!("loop {k} has a null or non-finite entity"));
        }
    }
    if !out.is_empty() {
        return out;
    }
    // Neighbours may meet again within `tol` of their vertex: nearly tangent entities whose two
    // crossings lie closer than the offsetter's cut snapping are cut once. Tangent touches are
    // where the region is pinched to a point.
    let crossings = crossings_not_touching(result, tol * 1e-3, tol);
    if let Some(p) = crossings.first() {
        out.push(format!("{} self-crossings, first at ({:.6}, {:.6})", crossings.len(), p.x, p.y));
    }
    let renormalised = Shape::new(result.loops.clone());
    if renormalised.loops.iter().zip(&result.loops).any(|(a, b)| a.is_ccw() != b.is_ccw()) {
        out.push("a loop runs the wrong way for its nesting".into());
    }
    let original = Original::new(input);
    let d = distance.abs();
    let mut worst: f64 = 0.0;
    for s in result.segments() {
        for j in 0..=samples {
            let p = s.point_at(j as f64 / samples as f64);
            worst = worst.max((original.distance(p, d * 2.0 + 1.0) - d).abs());
        }
    }
    if worst > tol {
        out.push(format!("a point of the result is {worst:.3e} mm off the offset distance"));
    }
    // The region: probes on a grid must be inside the result exactly when they are in the
    // offset region (probes within tol of the boundary are skipped).
    let b = input.bounds().expand(d.max(0.0) + 1.0);
    let mut wrong = 0;
    for i in 0..samples * 4 {
        for j in 0..samples * 4 {
            let f = |k: usize, n: usize| (k as f64 + 0.5) / n as f64;
            let q = b.min + b.size() * DVec2::new(f(i, samples * 4), f(j, samples * 4));
            if (original.distance(q, d * 2.0 + 1.0) - d).abs() <= tol * 10.0 || result.distance_to(q) <= tol * 10.0 {
                continue;
            }
            if original.in_offset_region(q, distance) != result.contains(q) {
                wrong += 1;
            }
        }
    }
    if wrong > 0 {
        out.push(format!("{wrong} probes disagree about being inside the offset region"));
    }
    out
}

/// A star-shaped loop about `center`: vertex k at angle 2πk/n + `phase` and radius `radii[k]`,
/// the edge leaving it with `bulges[k]` (shorter slices repeat).
pub fn star(center: DVec2, radii: &[f64], bulges: &[f64], phase: f64) -> Loop {
    let n = radii.len();
    let vertices = (0..n)
        .map(|k| {
            let th = phase + std::f64::consts::TAU * k as f64 / n as f64;
            let bulge = if bulges.is_empty() { 0.0 } else { bulges[k % bulges.len()] };
            Vertex { p: center + DVec2::from_angle(th) * radii[k], bulge }
        })
        .collect();
    Loop { vertices }
}

/// A small deterministic random source (xorshift), for corpora that must be the same on
/// every run and every target.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_f64() * n as f64) as usize).min(n - 1)
    }
}

/// A random simple shape: a star of lines and arcs with up to three islands (stars or
/// circles) inside it, none touching. `None` when the draw is not simple.
pub fn random_shape(rng: &mut Rng) -> Option<Shape> {
    let n = 3 + rng.below(30);
    let radii: Vec<f64> = (0..n).map(|_| rng.range(6.0, 20.0)).collect();
    let bulges: Vec<f64> = (0..n).map(|_| if rng.next_f64() < 0.4 { rng.range(-0.4, 0.4) } else { 0.0 }).collect();
    let mut loops = vec![star(DVec2::ZERO, &radii, &bulges, rng.range(0.0, 1.0))];
    for _ in 0..rng.below(4) {
        let c = DVec2::from_angle(rng.range(0.0, 6.3)) * rng.range(0.0, 4.0);
        let hole = if rng.next_f64() < 0.5 {
            Loop::circle(c, rng.range(0.3, 2.0))
        } else {
            let m = 3 + rng.below(6);
            let r: Vec<f64> = (0..m).map(|_| rng.range(0.5, 2.5)).collect();
            star(c, &r, &[], rng.range(0.0, 1.0))
        };
        let mut candidate = loops.clone();
        candidate.push(hole);
        let shape = Shape::new(candidate.clone());
        if self_crossings(&shape, 1e-9, 1e-8).is_empty() && shape.loops.iter().skip(1).all(|l| !l.is_ccw()) {
            loops = candidate;
        }
    }
    let shape = Shape::new(loops);
    self_crossings(&shape, 1e-9, 1e-8).is_empty().then_some(shape)
}

/// A shape and an offset distance decoded from arbitrary bytes (the fuzz target's input): a
/// star of 3 to 42 lines and arcs, up to two round islands, and a distance in ±10 mm. `None`
/// when the bytes are too few or the shape is not simple.
pub fn shape_from_bytes(data: &[u8]) -> Option<(Shape, f64)> {
    let (&first, rest) = data.split_first()?;
    let n = 3 + first as usize % 40;
    if rest.len() < 2 * n + 1 {
        return None;
    }
    let unit = |b: u8| b as f64 / 255.0;
    let radii: Vec<f64> = (0..n).map(|k| 2.0 + 18.0 * unit(rest[2 * k])).collect();
    let bulges: Vec<f64> = (0..n).map(|k| if rest[2 * k + 1] < 128 { 0.0 } else { (unit(rest[2 * k + 1]) - 0.75) * 3.2 }).collect();
    let d = (unit(rest[2 * n]) - 0.5) * 20.0;
    let mut loops = vec![star(DVec2::ZERO, &radii, &bulges, 0.0)];
    for hole in rest[2 * n + 1..].chunks_exact(3).take(2) {
        let c = DVec2::new(unit(hole[0]) - 0.5, unit(hole[1]) - 0.5) * 8.0;
        loops.push(Loop::circle(c, 0.2 + 1.8 * unit(hole[2])));
    }
    let shape = Shape::new(loops);
    let simple = self_crossings(&shape, 1e-9, 1e-8).is_empty() && shape.loops.iter().skip(1).all(|l| !l.is_ccw());
    (simple && d.abs() > 1e-3).then_some((shape, d))
}
