//! Plane segments: a line or a circular arc from `a` to `b`, the arc given by its bulge
//! (tan of a quarter of its signed sweep, counter-clockwise positive), as in DXF polylines.
//! Everything the offsetter (seed 003) asks of a segment lives here: points along it, lengths,
//! bounds, the closest point to a point, and intersections with another segment.

use std::f64::consts::TAU;

use super::DVec2;

/// Bulges smaller than this make a segment a line (an arc with a sagitta of 1e-12 of its chord).
pub const LINE_BULGE: f64 = 1e-12;

/// A line (`bulge` 0) or an arc of less than a full turn from `a` to `b`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Segment {
    pub a: DVec2,
    pub b: DVec2,
    pub bulge: f64,
}

/// A rectangle in the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub min: DVec2,
    pub max: DVec2,
}

impl Rect {
    pub const EMPTY: Rect = Rect { min: DVec2::splat(f64::INFINITY), max: DVec2::splat(f64::NEG_INFINITY) };

    pub fn grow(self, p: DVec2) -> Rect {
        Rect { min: self.min.min(p), max: self.max.max(p) }
    }
    pub fn union(self, o: Rect) -> Rect {
        Rect { min: self.min.min(o.min), max: self.max.max(o.max) }
    }
    pub fn expand(self, by: f64) -> Rect {
        Rect { min: self.min - DVec2::splat(by), max: self.max + DVec2::splat(by) }
    }
    pub fn overlaps(&self, o: &Rect) -> bool {
        // `&`, not `&&`: four compares without branches are faster than guessing at them.
        (self.min.x <= o.max.x) & (o.min.x <= self.max.x) & (self.min.y <= o.max.y) & (o.min.y <= self.max.y)
    }
    pub fn center(&self) -> DVec2 {
        (self.min + self.max) * 0.5
    }
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y)
    }

    /// The part of the straight segment from `a` to `b` inside the rectangle (its edges
    /// included), by Liang–Barsky; the ends are clamped into it. `None` where they do not meet.
    pub fn clip(&self, a: DVec2, b: DVec2) -> Option<(DVec2, DVec2)> {
        let d = b - a;
        self.clip_fractions(a, b).map(|(t0, t1)| ((a + d * t0).clamp(self.min, self.max), (a + d * t1).clamp(self.min, self.max)))
    }

    /// [`Rect::clip`] as fractions of the segment from `a`: where its part inside starts and ends.
    pub fn clip_fractions(&self, a: DVec2, b: DVec2) -> Option<(f64, f64)> {
        let (min, max) = (self.min, self.max);
        let d = b - a;
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [(-d.x, a.x - min.x), (d.x, max.x - a.x), (-d.y, a.y - min.y), (d.y, max.y - a.y)] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        (t0 <= t1).then_some((t0, t1))
    }
}

/// The circle of an arc segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcGeom {
    pub center: DVec2,
    pub radius: f64,
    /// `a` less the centre.
    pub start: DVec2,
    /// `b` less the centre.
    pub end: DVec2,
    /// The segment's bulge: tan of a quarter of the signed sweep (counter-clockwise positive).
    pub bulge: f64,
    /// The end's pseudo-angle from the start along the sweep (see [`Segment::position_with`]).
    span: f64,
}

impl ArcGeom {
    /// Signed sweep (counter-clockwise positive), in (-2π, 2π).
    pub fn sweep(&self) -> f64 {
        4.0 * self.bulge.atan()
    }

    /// Whether the direction `v` from the centre lies within the sweep (by cross products).
    pub fn sweeps_over(&self, v: DVec2) -> bool {
        let (s, e) = if self.bulge > 0.0 { (self.start, self.end) } else { (self.end, self.start) };
        let (after_start, before_end) = (s.perp_dot(v) >= 0.0, v.perp_dot(e) >= 0.0);
        if self.bulge.abs() <= 1.0 {
            after_start && before_end
        } else {
            after_start || before_end
        }
    }
}

/// Where two segments meet: the point, and its position along each as a key from
/// [`Segment::position_with`] (0 at `a`, 1 at `b`, growing along the segment).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Crossing {
    pub t: f64,
    pub u: f64,
    pub p: DVec2,
}

impl Segment {
    pub fn line(a: DVec2, b: DVec2) -> Segment {
        Segment { a, b, bulge: 0.0 }
    }

    /// The arc from `a` to `b` about `center`, counter-clockwise or not (no trigonometry).
    /// Equal ends make a null arc (a full circle is two segments).
    pub fn arc(a: DVec2, b: DVec2, center: DVec2, ccw: bool) -> Segment {
        let (u, m) = bisect(center, a, b, ccw);
        Segment { a, b, bulge: quarter_tan(u, m, ccw) }
    }

    /// The arc about `center` of `radius` from `start` through a signed `sweep` (radians).
    pub fn arc_from(center: DVec2, radius: f64, start: f64, sweep: f64) -> Segment {
        let p = |th: f64| center + DVec2::new(th.cos(), th.sin()) * radius;
        Segment { a: p(start), b: p(start + sweep), bulge: (sweep / 4.0).tan() }
    }

    pub fn is_line(&self) -> bool {
        self.bulge.abs() < LINE_BULGE
    }

    pub fn chord(&self) -> f64 {
        self.a.distance(self.b)
    }

    /// Centre, radius, start angle and sweep of an arc (`None` for a line or a null chord).
    pub fn arc_geom(&self) -> Option<ArcGeom> {
        if self.is_line() {
            return None;
        }
        let d = self.b - self.a;
        let chord = d.length();
        if chord == 0.0 {
            return None;
        }
        let b = self.bulge;
        let left = DVec2::new(-d.y, d.x) / chord;
        let center = (self.a + self.b) * 0.5 + left * (chord * 0.5 * (1.0 - b * b) / (2.0 * b));
        let radius = chord * (1.0 + b * b) / (4.0 * b.abs());
        let (start, end) = (self.a - center, self.b - center);
        let span = pseudo_angle(start.dot(end), start.perp_dot(end) * b.signum());
        Some(ArcGeom { center, radius, start, end, bulge: b, span })
    }

    pub fn length(&self) -> f64 {
        match self.arc_geom() {
            Some(g) => g.radius * g.sweep().abs(),
            None => self.chord(),
        }
    }

    /// The point at parameter `t` (0 at `a`, 1 at `b`; arcs by angle).
    pub fn point_at(&self, t: f64) -> DVec2 {
        if t <= 0.0 {
            return self.a;
        }
        if t >= 1.0 {
            return self.b;
        }
        match self.arc_geom() {
            Some(g) => g.center + DVec2::from_angle(g.sweep() * t).rotate(g.start),
            None => self.a.lerp(self.b, t),
        }
    }

    /// The middle of the segment: for an arc, the chord's middle moved by the sagitta (bulge
    /// times half the chord) to the side the arc bulges to; no trigonometry.
    pub fn midpoint(&self) -> DVec2 {
        let d = self.b - self.a;
        (self.a + self.b) * 0.5 + DVec2::new(d.y, -d.x) * (self.bulge * 0.5)
    }

    /// Unit direction of travel at `p`, a point of the segment (no trigonometry).
    pub fn direction_at(&self, geom: Option<&ArcGeom>, p: DVec2) -> DVec2 {
        match geom {
            None => self.b - self.a,
            Some(g) => (p - g.center).perp() * g.bulge.signum(),
        }
        .normalize_or_zero()
    }

    /// Unit direction of travel at parameter `t`.
    pub fn tangent_at(&self, t: f64) -> DVec2 {
        match self.arc_geom() {
            Some(g) => DVec2::from_angle(g.sweep() * t).rotate(g.start).perp() / g.radius * g.bulge.signum(),
            None => (self.b - self.a).normalize_or_zero(),
        }
    }

    pub fn reversed(&self) -> Segment {
        Segment { a: self.b, b: self.a, bulge: -self.bulge }
    }

    /// The piece between parameters `t0 < t1`.
    pub fn sub(&self, t0: f64, t1: f64) -> Segment {
        match self.arc_geom() {
            Some(g) => {
                let at = |t: f64| {
                    if t <= 0.0 {
                        self.a
                    } else if t >= 1.0 {
                        self.b
                    } else {
                        g.center + DVec2::from_angle(g.sweep() * t).rotate(g.start)
                    }
                };
                Segment { a: at(t0), b: at(t1), bulge: (g.sweep() * (t1 - t0) / 4.0).tan() }
            }
            None => Segment { a: self.point_at(t0), b: self.point_at(t1), bulge: 0.0 },
        }
    }

    /// Bounding rectangle (arcs include the extreme points their sweep passes).
    pub fn bounds(&self) -> Rect {
        self.bounds_with(self.arc_geom().as_ref())
    }

    /// [`Segment::bounds`] with the arc's geometry at hand.
    pub fn bounds_with(&self, geom: Option<&ArcGeom>) -> Rect {
        let r = Rect::EMPTY.grow(self.a).grow(self.b);
        match geom {
            None => r,
            Some(g) => {
                let mut r = r;
                for dir in [DVec2::X, DVec2::Y, DVec2::NEG_X, DVec2::NEG_Y] {
                    if g.sweeps_over(dir) {
                        r = r.grow(g.center + dir * g.radius);
                    }
                }
                r
            }
        }
    }

    /// Parameter of the direction `dir` from an arc's centre, when the sweep passes it.
    fn angle_param(&self, g: &ArcGeom, dir: DVec2) -> Option<f64> {
        if !g.sweeps_over(dir) {
            return None;
        }
        let mut delta = g.start.perp_dot(dir).atan2(g.start.dot(dir));
        if g.bulge > 0.0 && delta < 0.0 {
            delta += TAU;
        } else if g.bulge < 0.0 && delta > 0.0 {
            delta -= TAU;
        }
        let t = delta / g.sweep();
        (0.0..=1.0).contains(&t).then_some(t)
    }

    /// Where a point on (or near) the segment's line or circle lies along it: a key that grows
    /// from 0 at `a` to 1 at `b`, with `slack` (mm) allowed past either end (clamped to it);
    /// `None` when the point lies beyond. For a line the key is the parameter; for an arc it is
    /// a pseudo-angle (monotone in the angle, found without trigonometry), so keys order points
    /// along a segment but are not proportional to arc length.
    /// The arc's geometry comes in `geom` (computed once by the caller).
    pub fn position_with(&self, geom: Option<&ArcGeom>, p: DVec2, slack: f64) -> Option<f64> {
        match geom {
            None => {
                let d = self.b - self.a;
                let len2 = d.length_squared();
                if len2 == 0.0 {
                    return (p.distance(self.a) <= slack).then_some(0.0);
                }
                let t = (p - self.a).dot(d) / len2;
                let s = slack / len2.sqrt();
                (t >= -s && t <= 1.0 + s).then(|| t.clamp(0.0, 1.0))
            }
            Some(g) => {
                let v = p - g.center;
                let k = pseudo_angle(g.start.dot(v), g.start.perp_dot(v) * g.bulge.signum());
                if k <= g.span {
                    Some(k / g.span)
                } else if p.distance_squared(self.b) <= slack * slack {
                    Some(1.0)
                } else if p.distance_squared(self.a) <= slack * slack {
                    Some(0.0)
                } else {
                    None
                }
            }
        }
    }

    /// The part of the segment from `p` to `q`, two points on it in that order (cuts found by
    /// [`Segment::crossings_with`]); an arc keeps its circle and gets the bulge of the part,
    /// without trigonometry.
    pub fn between(&self, geom: Option<&ArcGeom>, p: DVec2, q: DVec2) -> Segment {
        match geom {
            None => Segment::line(p, q),
            Some(g) => {
                let (u, m) = arc_part(g, p, q);
                Segment { a: p, b: q, bulge: quarter_tan(u, m, g.bulge > 0.0) }
            }
        }
    }

    /// The middle of the part from `p` to `q` (as in [`Segment::between`]).
    pub fn midpoint_between(&self, geom: Option<&ArcGeom>, p: DVec2, q: DVec2) -> DVec2 {
        match geom {
            None => (p + q) * 0.5,
            Some(g) => g.center + arc_part(g, p, q).1 * g.radius,
        }
    }

    /// The closest point of the segment to `q`, and its parameter.
    pub fn closest(&self, q: DVec2) -> (DVec2, f64) {
        self.closest_with(self.arc_geom().as_ref(), q)
    }

    /// [`Segment::closest`] with the arc's geometry at hand (from [`Segment::arc_geom`]).
    pub fn closest_with(&self, geom: Option<&ArcGeom>, q: DVec2) -> (DVec2, f64) {
        match geom {
            None => {
                let d = self.b - self.a;
                let len2 = d.length_squared();
                let t = if len2 > 0.0 { ((q - self.a).dot(d) / len2).clamp(0.0, 1.0) } else { 0.0 };
                (self.a.lerp(self.b, t), t)
            }
            Some(g) => {
                let v = q - g.center;
                if v.length_squared() > 0.0 {
                    if let Some(t) = self.angle_param(g, v) {
                        return (g.center + v.normalize() * g.radius, t);
                    }
                }
                if q.distance_squared(self.a) <= q.distance_squared(self.b) {
                    (self.a, 0.0)
                } else {
                    (self.b, 1.0)
                }
            }
        }
    }

    pub fn distance_to(&self, q: DVec2) -> f64 {
        self.closest(q).0.distance(q)
    }

    /// [`Segment::distance_to`] with the arc's geometry at hand; no trigonometry.
    pub fn distance_with(&self, geom: Option<&ArcGeom>, q: DVec2) -> f64 {
        match geom {
            Some(g) => {
                let v = q - g.center;
                if v != DVec2::ZERO && g.sweeps_over(v) {
                    (v.length() - g.radius).abs()
                } else {
                    q.distance(self.a).min(q.distance(self.b))
                }
            }
            None => self.closest_with(None, q).0.distance(q),
        }
    }

    /// How many times the ray from `q` towards +x crosses the segment, counting an end on the
    /// ray's line only when the segment rises above it there (half-open, so loops count each
    /// crossing once).
    pub fn ray_crossings(&self, q: DVec2) -> u32 {
        self.ray_crossings_with(self.arc_geom().as_ref(), q)
    }

    /// [`Segment::ray_crossings`] with the arc's geometry at hand.
    pub fn ray_crossings_with(&self, geom: Option<&ArcGeom>, q: DVec2) -> u32 {
        let mut count = 0;
        self.for_each_crossing_at_y(geom, q.y, |x| count += (q.x < x) as u32);
        count
    }

    /// The x of every point where the segment crosses the horizontal line at `y`, by the same
    /// half-open rule as [`Segment::ray_crossings`], so a loop's crossings pair up into spans.
    pub fn crossings_at_y(&self, y: f64) -> Vec<f64> {
        let mut xs = Vec::new();
        self.for_each_crossing_at_y(self.arc_geom().as_ref(), y, |x| xs.push(x));
        xs
    }

    /// Calls `visit` with the x of every crossing of the line at `y` (half-open at the ends).
    /// Arcs are taken in pieces that only rise or only fall, split at their highest and lowest
    /// points; no trigonometry.
    fn for_each_crossing_at_y(&self, geom: Option<&ArcGeom>, y: f64, mut visit: impl FnMut(f64)) {
        let straddles = |a: DVec2, b: DVec2| (a.y > y) != (b.y > y);
        let Some(&g) = geom else {
            let (a, b) = (self.a, self.b);
            if straddles(a, b) {
                visit(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
            return;
        };
        let dy = y - g.center.y;
        if dy.abs() > g.radius {
            return;
        }
        let mut cuts = [(0.0, self.a); 4];
        let mut n = 1;
        for dir in [DVec2::Y, DVec2::NEG_Y] {
            if g.sweeps_over(dir) {
                let p = g.center + dir * g.radius;
                if let Some(k) = self.position_with(Some(&g), p, 0.0).filter(|&k| k > 0.0 && k < 1.0) {
                    cuts[n] = (k, p);
                    n += 1;
                }
            }
        }
        cuts[..n].sort_by(|a, b| a.0.total_cmp(&b.0));
        cuts[n] = (1.0, self.b);
        let half = (g.radius * g.radius - dy * dy).max(0.0).sqrt();
        for k in 0..n {
            let (a, b) = (cuts[k].1, cuts[k + 1].1);
            if straddles(a, b) {
                let side = (self.midpoint_between(Some(&g), a, b).x - g.center.x).signum();
                visit(g.center.x + side * half);
            }
        }
    }

    /// Every point where the two segments meet, within `eps` (mm). Overlapping collinear lines
    /// and arcs on one circle give the ends of their overlap.
    pub fn crossings(&self, other: &Segment, eps: f64) -> Crossings {
        self.crossings_with(self.arc_geom().as_ref(), other, other.arc_geom().as_ref(), eps)
    }

    /// [`Segment::crossings`] with both arcs' geometry at hand (from [`Segment::arc_geom`]),
    /// for callers that test one segment against many.
    pub fn crossings_with(&self, g1: Option<&ArcGeom>, other: &Segment, g2: Option<&ArcGeom>, eps: f64) -> Crossings {
        let mut out = Crossings::default();
        match (g1, g2) {
            (None, None) => line_line(self, other, eps, &mut out),
            (None, Some(g)) => line_arc(self, other, g, eps, false, &mut out),
            (Some(g), None) => line_arc(other, self, g, eps, true, &mut out),
            (Some(g1), Some(g2)) => arc_arc(self, g1, other, g2, eps, &mut out),
        }
        out
    }
}

/// A pseudo-angle of the direction `(x, y)`: from 0 at +x counter-clockwise to 4, monotone in the
/// angle (1 at +y, 2 at −x, 3 at −y). NaN for the zero vector.
fn pseudo_angle(x: f64, y: f64) -> f64 {
    if y >= 0.0 {
        if x >= 0.0 {
            y / (x + y)
        } else {
            1.0 - x / (y - x)
        }
    } else if x <= 0.0 {
        2.0 - y / (-x - y)
    } else {
        3.0 + x / (x - y)
    }
}

/// For the part of an arc from `p` to `q` (in the sweep's direction): the unit direction of `p`
/// from the centre and that of the part's middle. The middle bisects the two directions; it is
/// taken from their sum when the part is short and from their difference turned a quarter
/// against the sweep otherwise, whichever is well conditioned.
fn arc_part(g: &ArcGeom, p: DVec2, q: DVec2) -> (DVec2, DVec2) {
    bisect(g.center, p, q, g.bulge > 0.0)
}

/// [`arc_part`] for the arc about `center` from `p` to `q`, counter-clockwise or not.
fn bisect(center: DVec2, p: DVec2, q: DVec2, ccw: bool) -> (DVec2, DVec2) {
    let u = (p - center).normalize_or_zero();
    let v = (q - center).normalize_or_zero();
    let turn = u.perp_dot(v) * if ccw { 1.0 } else { -1.0 }; // sin of the part's sweep
    let m = if u.dot(v) > 0.0 && turn > 0.0 {
        (u + v).normalize_or_zero() // under a quarter turn
    } else if u.dot(v) > 0.0 && turn < 0.0 {
        -(u + v).normalize_or_zero() // over three quarters
    } else {
        let d = v - u;
        (if ccw { DVec2::new(d.y, -d.x) } else { DVec2::new(-d.y, d.x) }).normalize_or_zero()
    };
    (u, m)
}

/// The bulge of an arc whose start direction from the centre is `u` and whose middle is `m`:
/// tan(θ/4) from the half sweep θ/2 between them, signed by the direction.
fn quarter_tan(u: DVec2, m: DVec2, ccw: bool) -> f64 {
    let t = u.perp_dot(m).abs() / (1.0 + u.dot(m));
    if ccw {
        t
    } else {
        -t
    }
}

/// Up to four crossings, without allocating.
#[derive(Clone, Copy, Debug, Default)]
pub struct Crossings {
    items: [Crossing; 4],
    len: usize,
}

impl Crossings {
    fn push(&mut self, c: Crossing) {
        if self.items[..self.len].iter().any(|o| o.p.distance_squared(c.p) == 0.0 && (o.t - c.t).abs() < 1e-15) {
            return;
        }
        if self.len < 4 {
            self.items[self.len] = c;
            self.len += 1;
        }
    }
    pub fn len(&self) -> usize {
        self.len
    }
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    pub fn iter(&self) -> impl Iterator<Item = Crossing> + '_ {
        self.items[..self.len].iter().copied()
    }
}

/// Adds `p` when it lies on both segments within `eps`.
fn try_point(s1: &Segment, s2: &Segment, p: DVec2, eps: f64, out: &mut Crossings) {
    try_point_with(s1, s1.arc_geom().as_ref(), s2, s2.arc_geom().as_ref(), p, eps, out);
}

fn try_point_with(s1: &Segment, g1: Option<&ArcGeom>, s2: &Segment, g2: Option<&ArcGeom>, p: DVec2, eps: f64, out: &mut Crossings) {
    if let (Some(t), Some(u)) = (s1.position_with(g1, p, eps), s2.position_with(g2, p, eps)) {
        out.push(Crossing { t, u, p });
    }
}

fn line_line(s1: &Segment, s2: &Segment, eps: f64, out: &mut Crossings) {
    let d1 = s1.b - s1.a;
    let d2 = s2.b - s2.a;
    // Quick rejection: the ends of either lie on one side of the other's line, farther than
    // eps (signed distances times the length, compared squared: no square root).
    let apart = |d: DVec2, o: DVec2, p: DVec2, q: DVec2| {
        let (cp, cq) = (d.perp_dot(p - o), d.perp_dot(q - o));
        cp * cq > 0.0 && cp.abs().min(cq.abs()).powi(2) > eps * eps * d.length_squared()
    };
    if apart(d1, s1.a, s2.a, s2.b) || apart(d2, s2.a, s1.a, s1.b) {
        return;
    }
    let (l1, l2) = (d1.length(), d2.length());
    if l1 == 0.0 || l2 == 0.0 {
        for p in [s1.a, s2.a] {
            if s1.distance_to(p) <= eps && s2.distance_to(p) <= eps {
                try_point(s1, s2, p, eps, out);
            }
        }
        return;
    }
    let denom = d1.perp_dot(d2);
    let w = s2.a - s1.a;
    // Parallel when the sine of the angle between them is below eps over the longer length.
    if denom.abs() > eps / l1.max(l2) * l1 * l2 {
        let t = w.perp_dot(d2) / denom;
        let u = w.perp_dot(d1) / denom;
        let (st, su) = (eps / l1, eps / l2);
        if t >= -st && t <= 1.0 + st && u >= -su && u <= 1.0 + su {
            let p = s1.a + d1 * t.clamp(0.0, 1.0);
            out.push(Crossing { t: t.clamp(0.0, 1.0), u: u.clamp(0.0, 1.0), p });
        }
        return;
    }
    // Parallel: collinear when s2 lies on s1's line; then the ends of the overlap.
    if (w.perp_dot(d1) / l1).abs() > eps {
        return;
    }
    for p in [s1.a, s1.b, s2.a, s2.b] {
        if s1.distance_to(p) <= eps && s2.distance_to(p) <= eps {
            try_point(s1, s2, p, eps, out);
        }
    }
}

fn line_arc(line: &Segment, arc: &Segment, g: &ArcGeom, eps: f64, swap: bool, out: &mut Crossings) {
    let d = line.b - line.a;
    let len2 = d.length_squared();
    let mut add = |t: f64, p: DVec2| {
        if let Some(u) = arc.position_with(Some(g), p, eps) {
            out.push(if swap { Crossing { t: u, u: t, p } } else { Crossing { t, u, p } });
        }
    };
    if len2 == 0.0 {
        if (line.a.distance(g.center) - g.radius).abs() <= eps {
            add(0.0, line.a);
        }
        return;
    }
    // The foot of the centre on the line, at parameter `s`, and its distance from the centre.
    let s = (g.center - line.a).dot(d) / len2;
    let foot = line.a + d * s;
    let h2 = foot.distance_squared(g.center);
    let reach = g.radius + eps;
    if h2 > reach * reach {
        return;
    }
    let len = len2.sqrt();
    let slack = eps / len;
    let on_line = |t: f64| t >= -slack && t <= 1.0 + slack;
    let half2 = g.radius * g.radius - h2;
    if half2 <= (eps * 0.5).powi(2) {
        // Tangent: the one point of the circle nearest the line.
        if on_line(s) {
            let n = (foot - g.center).normalize_or_zero();
            add(s.clamp(0.0, 1.0), if n == DVec2::ZERO { foot } else { g.center + n * g.radius });
        }
        return;
    }
    let ht = half2.sqrt() / len;
    for t in [s - ht, s + ht] {
        if on_line(t) {
            add(t.clamp(0.0, 1.0), line.a + d * t);
        }
    }
}

fn arc_arc(s1: &Segment, g1: &ArcGeom, s2: &Segment, g2: &ArcGeom, eps: f64, out: &mut Crossings) {
    let v = g2.center - g1.center;
    let dist = v.length();
    if dist <= eps && (g1.radius - g2.radius).abs() <= eps {
        // One circle: the ends of the overlap.
        for p in [s1.a, s1.b, s2.a, s2.b] {
            try_point_with(s1, Some(g1), s2, Some(g2), p, eps, out);
        }
        return;
    }
    if dist == 0.0 || dist > g1.radius + g2.radius + eps || dist < (g1.radius - g2.radius).abs() - eps {
        return;
    }
    let dir = v / dist;
    let x = (dist * dist + g1.radius * g1.radius - g2.radius * g2.radius) / (2.0 * dist);
    let h2 = g1.radius * g1.radius - x * x;
    let base = g1.center + dir * x;
    // Tangent circles: half the chord within eps.
    if h2 <= (eps * 0.5).powi(2) {
        try_point_with(s1, Some(g1), s2, Some(g2), base, eps, out);
        return;
    }
    let h = h2.sqrt();
    let n = DVec2::new(-dir.y, dir.x);
    try_point_with(s1, Some(g1), s2, Some(g2), base + n * h, eps, out);
    try_point_with(s1, Some(g1), s2, Some(g2), base - n * h, eps, out);
}

/// Cumulative arc lengths at the starts of a chain's segments, and its total.
/// The largest angle (radians) an arc of `radius` may turn between chords that stay within
/// `sag` of it (`radius (1 - cos(step / 2)) <= sag`); `None` when any chord does (the radius is
/// no larger than the sag).
pub fn chord_step(radius: f64, sag: f64) -> Option<f64> {
    (radius > sag).then(|| 2.0 * (1.0 - sag / radius).acos())
}

pub fn arc_lengths(segs: &[Segment]) -> (Vec<f64>, f64) {
    let mut at = Vec::with_capacity(segs.len());
    let mut s = 0.0;
    for seg in segs {
        at.push(s);
        s += seg.length();
    }
    (at, s)
}

/// The pieces of the closed chain `segs` from arc length `s0` to `s1` (`s1` may pass the end:
/// the chain repeats), cut where a segment ends and at the arc lengths `cut`, each with the
/// arc lengths it runs from and to.
pub fn pieces(segs: &[Segment], s0: f64, s1: f64, cut: impl Iterator<Item = f64>) -> Vec<(f64, f64, Segment)> {
    let (starts, total) = arc_lengths(segs);
    if total <= 0.0 || s1 <= s0 {
        return Vec::new();
    }
    // Every place where a segment ends or a cut is asked for.
    let mut cuts: Vec<f64> = cut.filter(|&s| s > s0 && s < s1).collect();
    let first_lap = (s0 / total).floor() as i64;
    let last_lap = (s1 / total).ceil() as i64;
    for lap in first_lap..=last_lap {
        for &st in &starts {
            let s = lap as f64 * total + st;
            if s > s0 && s < s1 {
                cuts.push(s);
            }
        }
    }
    cuts.push(s1);
    crate::geom::sort::sort_floats(&mut cuts);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    let mut out = Vec::with_capacity(cuts.len());
    let mut from = s0;
    for &to in &cuts {
        if to - from <= 1e-12 {
            continue;
        }
        let mid = (from + to) * 0.5;
        let local = mid.rem_euclid(total);
        let i = starts.partition_point(|&x| x <= local).saturating_sub(1);
        let seg = segs[i];
        let lap_start = mid - local + starts[i];
        let len = seg.length();
        let (ta, tb) = (((from - lap_start) / len).clamp(0.0, 1.0), ((to - lap_start) / len).clamp(0.0, 1.0));
        out.push((from, to, seg.sub(ta, tb)));
        from = to;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Parts of arcs cut by points (no trigonometry) against the same parts cut by angle.
    #[test]
    fn parts_by_points_match_parts_by_angle() {
        for &bulge in &[0.01, 0.3, 1.0, 2.5, 40.0, -0.01, -0.7, -1.0, -9.0] {
            let s = Segment { a: DVec2::new(3.0, -1.0), b: DVec2::new(-2.0, 4.0), bulge };
            let g = s.arc_geom().unwrap();
            let mut last = -1.0;
            for k in 0..=20 {
                let t = k as f64 / 20.0;
                let key = s.position_with(Some(&g), s.point_at(t), 0.0).unwrap();
                assert!(key > last || (k == 0 && key == 0.0), "bulge {bulge}: key {key} after {last} at t {t}");
                last = key;
            }
            assert!((last - 1.0).abs() < 1e-12);
            for (t0, t1) in [(0.0, 0.5), (0.1, 0.2), (0.3, 0.9999), (0.0, 1.0), (0.45, 0.55)] {
                let (p, q) = (s.point_at(t0), s.point_at(t1));
                let by_angle = s.sub(t0, t1);
                let by_points = s.between(Some(&g), p, q);
                assert!((by_points.bulge - by_angle.bulge).abs() < 1e-9 * by_angle.bulge.abs().max(1.0), "bulge {bulge} {t0}..{t1}: {} vs {}", by_points.bulge, by_angle.bulge);
                assert!(s.midpoint_between(Some(&g), p, q).distance(s.point_at((t0 + t1) * 0.5)) < 1e-12);
            }
            let made = Segment::arc(s.a, s.b, g.center, bulge > 0.0);
            assert!((made.bulge - bulge).abs() < 1e-9 * bulge.abs().max(1.0), "{} vs {bulge}", made.bulge);
            // Past the ends: within the slack counts as the end, farther does not.
            let beyond = s.b + (s.b - g.center).perp().normalize() * 1e-3 * bulge.signum();
            assert_eq!(s.position_with(Some(&g), beyond, 1e-2), Some(1.0));
            assert_eq!(s.position_with(Some(&g), beyond, 1e-4), None);
        }
    }

    #[test]
    fn arc_geometry_from_bulge() {
        // A counter-clockwise half circle of radius 1 from (1,0) to (-1,0) about the origin.
        let s = Segment { a: DVec2::new(1.0, 0.0), b: DVec2::new(-1.0, 0.0), bulge: 1.0 };
        let g = s.arc_geom().unwrap();
        assert!(g.center.length() < 1e-12 && (g.radius - 1.0).abs() < 1e-12);
        assert!((s.length() - PI).abs() < 1e-12);
        assert!(s.midpoint().distance(DVec2::new(0.0, 1.0)) < 1e-12);
        let b = s.bounds();
        assert!((b.max.y - 1.0).abs() < 1e-12 && b.min.y.abs() < 1e-12);
        let made = Segment::arc(s.a, s.b, DVec2::ZERO, true);
        assert!((made.bulge - 1.0).abs() < 1e-12);
    }

    #[test]
    fn crossings_of_each_kind() {
        let l1 = Segment::line(DVec2::new(-2.0, 0.0), DVec2::new(2.0, 0.0));
        let l2 = Segment::line(DVec2::new(0.0, -1.0), DVec2::new(0.0, 1.0));
        let c = l1.crossings(&l2, 1e-9);
        assert_eq!(c.len(), 1);
        assert!((c.iter().next().unwrap().t - 0.5).abs() < 1e-12);
        let circle_top = Segment { a: DVec2::new(1.0, 0.0), b: DVec2::new(-1.0, 0.0), bulge: 1.0 };
        let l3 = Segment::line(DVec2::new(-2.0, 0.5), DVec2::new(2.0, 0.5));
        assert_eq!(l3.crossings(&circle_top, 1e-9).len(), 2);
        assert_eq!(circle_top.crossings(&l3, 1e-9).len(), 2);
        let other = Segment { a: DVec2::new(2.0, 0.0), b: DVec2::new(0.0, 0.0), bulge: 1.0 };
        let c = circle_top.crossings(&other, 1e-9);
        assert_eq!(c.len(), 1, "{c:?}"); // at (0.5, 0.866); the other circle crossing is off both arcs
        let collinear = Segment::line(DVec2::new(1.0, 0.0), DVec2::new(3.0, 0.0));
        assert_eq!(l1.crossings(&collinear, 1e-9).len(), 2);
    }

    #[test]
    fn closest_point_on_an_arc() {
        let s = Segment { a: DVec2::new(1.0, 0.0), b: DVec2::new(-1.0, 0.0), bulge: 1.0 };
        assert!((s.distance_to(DVec2::new(0.0, 3.0)) - 2.0).abs() < 1e-12);
        assert!((s.distance_to(DVec2::new(0.0, -3.0)) - 10f64.sqrt()).abs() < 1e-12);
        assert!((s.distance_to(DVec2::ZERO) - 1.0).abs() < 1e-12);
    }
}
