//! The space a cutter sweeps in one move, seen from below. For 3-axis milling the material a
//! move removes is everything above the *lower envelope* of the swept cutter: at each point
//! (x, y) the lowest height the cutter's lower surface reaches during the move. Every stock
//! model of seed 002 asks only this question (at a cell's centre, at a supersample, or as
//! bounds over an octant's footprint), so the geometry lives here once.
//!
//! The envelope is exact: for a flat end and a ball in closed form (a flat end reaches lowest at
//! an end of the interval of the move during which it covers the point; a ball sweeps a capsule,
//! whose lower surface is one of the end spheres or the cylinder between them); for a bull nose
//! by the contact search the CL z-map's edge drop uses ([`Profile::contact_along`]), since
//! `z(t) + height(|q - c(t)|)` is convex in the move's parameter. Planar arcs are exact too,
//! and so is a flat end's helical arc (by the window of angles over which it covers a point,
//! from the law of cosines); other cutters' helical arcs are split into chords.

use crate::cutter::Profile;
use crate::geom::tolerance::FLOAT_SLACK;
use crate::geom::{DVec2, DVec3};
use crate::toolpath::{arc_sweep, Move};

/// The path of the cutter's tip during one sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Path {
    /// A straight move from `a` to `b`.
    Line { a: DVec3, b: DVec3 },
    /// An arc about `center`, from angle `start` through the signed `sweep` (radians,
    /// counter-clockwise positive), starting at height `z` and rising `rise` evenly on the way
    /// (0 for a planar arc; a helix only for a flat end, whose envelope it has in closed form).
    Arc { center: DVec2, radius: f64, start: f64, sweep: f64, z: f64, rise: f64 },
}

/// A cutter moving along a path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    pub profile: Profile,
    pub path: Path,
    /// The footprint's bounding rectangle in XY.
    pub min: DVec2,
    pub max: DVec2,
    /// The lowest tip height of the move: no point of the envelope lies below it.
    pub lowest_tip: f64,
    /// A line's constants, worked out once for the many points asked about.
    line: LineConstants,
    /// An arc's ends, worked out once for the many points asked about.
    ends: ArcEnds,
}

/// An arc's ends in XY and their unit directions from its centre (each a sine and a cosine a
/// point asked about needed twice).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct ArcEnds {
    points: [DVec2; 2],
    dirs: [DVec2; 2],
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct LineConstants {
    /// The move in XY, 1 / its squared length (0 for a vertical move), its length and 1 / it.
    d: DVec2,
    inv_len2: f64,
    len_xy: f64,
    inv_len_xy: f64,
    /// Unit direction in 3D, its length, and 1 / (1 - uz²) (0 when vertical).
    u: DVec3,
    length: f64,
    inv_along: f64,
}

impl Sweep {
    pub fn line(profile: Profile, a: DVec3, b: DVec3) -> Sweep {
        let r = DVec2::splat(profile.radius);
        let d = (b - a).truncate();
        let len2 = d.length_squared();
        let length = a.distance(b);
        let u = if length > 0.0 { (b - a) / length } else { DVec3::Z };
        let along = 1.0 - u.z * u.z;
        let len_xy = len2.sqrt();
        let line = LineConstants {
            d,
            inv_len2: if len2 > 0.0 { 1.0 / len2 } else { 0.0 },
            len_xy,
            inv_len_xy: if len2 > 0.0 { 1.0 / len_xy } else { 0.0 },
            u,
            length,
            inv_along: if along > 1e-12 { 1.0 / along } else { 0.0 },
        };
        Sweep { profile, path: Path::Line { a, b }, min: a.truncate().min(b.truncate()) - r, max: a.truncate().max(b.truncate()) + r, lowest_tip: a.z.min(b.z), line, ends: ArcEnds::default() }
    }

    /// A planar arc from `from` (its z is the arc's) about `center`, sweeping `sweep` radians.
    pub fn arc(profile: Profile, from: DVec3, center: DVec2, sweep: f64) -> Sweep {
        let v = from.truncate() - center;
        let radius = v.length();
        let start = v.y.atan2(v.x);
        let (mut min, mut max) = (from.truncate(), from.truncate());
        let dirs = [DVec2::from_angle(start), DVec2::from_angle(start + sweep)];
        let end = center + dirs[1] * radius;
        min = min.min(end);
        max = max.max(end);
        // The circle's extreme points in X and Y that the arc passes.
        for k in 0..4 {
            let angle = k as f64 * std::f64::consts::FRAC_PI_2;
            if angle_within(start, sweep, angle) {
                let p = center + DVec2::from_angle(angle) * radius;
                min = min.min(p);
                max = max.max(p);
            }
        }
        let r = DVec2::splat(profile.radius);
        let ends = ArcEnds { points: [center + dirs[0] * radius, end], dirs };
        Sweep { profile, path: Path::Arc { center, radius, start, sweep, z: from.z, rise: 0.0 }, min: min - r, max: max + r, lowest_tip: from.z, line: LineConstants::default(), ends }
    }

    /// A flat end's helical arc from `from` about `center`, sweeping `sweep` radians while its
    /// height changes evenly by `rise`.
    fn helix(profile: Profile, from: DVec3, center: DVec2, sweep: f64, rise: f64) -> Sweep {
        debug_assert!(profile.is_flat());
        let mut s = Sweep::arc(profile, from, center, sweep);
        if let Path::Arc { rise: r, .. } = &mut s.path {
            *r = rise;
        }
        s.lowest_tip = from.z.min(from.z + rise);
        s
    }

    /// The sweeps of one programmed move from `from`: a line, a planar arc, a flat end's helix,
    /// or another cutter's helix split into chords that stay within `chordal` of it.
    pub fn of_move(profile: Profile, from: DVec3, mv: &Move, chordal: f64) -> Vec<Sweep> {
        match *mv {
            Move::Rapid { to } | Move::Line { to, .. } => vec![Sweep::line(profile, from, to)],
            Move::Arc { to, center, clockwise, .. } => {
                let sweep = arc_sweep(from, to, center, clockwise);
                let radius = (from.truncate() - center).length();
                if to.z == from.z {
                    return vec![Sweep::arc(profile, from, center, sweep)];
                }
                if profile.is_flat() {
                    return vec![Sweep::helix(profile, from, center, sweep, to.z - from.z)];
                }
                let step = crate::geom::segment::chord_step(radius, chordal).unwrap_or(sweep.abs());
                let count = ((sweep.abs() / step.max(1e-3)).ceil() as usize).clamp(1, 100_000);
                let v = from.truncate() - center;
                let start = v.y.atan2(v.x);
                let mut out = Vec::with_capacity(count);
                let mut at = from;
                for k in 1..=count {
                    let f = k as f64 / count as f64;
                    let p = if k == count { to } else { (center + DVec2::from_angle(start + sweep * f) * radius).extend(from.z + (to.z - from.z) * f) };
                    out.push(Sweep::line(profile, at, p));
                    at = p;
                }
                out
            }
        }
    }

    /// The lowest height the cutter's lower surface reaches over `q` during the sweep, or
    /// infinity where the cutter never passes over `q`.
    #[inline]
    pub fn lowest(&self, q: DVec2) -> f64 {
        let p = &self.profile;
        let r2 = p.radius * p.radius;
        match self.path {
            Path::Line { a, b } => {
                let k = &self.line;
                let d = k.d;
                let w = q - a.truncate();
                let dz = b.z - a.z;
                if dz == 0.0 {
                    let t = (w.dot(d) * k.inv_len2).clamp(0.0, 1.0);
                    let dist2 = (w - d * t).length_squared();
                    return if dist2 > r2 {
                        f64::INFINITY
                    } else if p.flat_radius() == 0.0 && !p.is_cone() {
                        a.z + p.radius - (r2 - dist2).sqrt()
                    } else {
                        a.z + p.height(dist2.sqrt())
                    };
                }
                if p.flat_radius() == 0.0 && !p.is_cone() {
                    return self.ball_line(a, b, q);
                }
                if p.corner > 0.0 || p.is_cone() {
                    // Behind the lower end (rising moves) or past it (falling ones), every
                    // position of the move stands no lower and no nearer than that end: the
                    // cutter there is the envelope, without the contact search.
                    let (end, beyond) = if dz > 0.0 { (a, -w.dot(d)) } else { (b, (q - b.truncate()).dot(d)) };
                    if beyond >= 0.0 {
                        let dist2 = (q - end.truncate()).length_squared();
                        return if dist2 > r2 { f64::INFINITY } else { end.z + p.height(dist2.sqrt()) };
                    }
                }
                // The interval of t during which the cutter's axis is within R of q.
                let (t0, t1) = if k.inv_len2 > 0.0 {
                    let s = w.dot(d);
                    let disc = s * s - (w.length_squared() - r2) / k.inv_len2;
                    if disc < 0.0 {
                        return f64::INFINITY;
                    }
                    let root = disc.sqrt();
                    (((s - root) * k.inv_len2).max(0.0), ((s + root) * k.inv_len2).min(1.0))
                } else if w.length_squared() <= r2 {
                    (0.0, 1.0)
                } else {
                    return f64::INFINITY;
                };
                if t0 > t1 {
                    return f64::INFINITY;
                }
                if p.corner == 0.0 && !p.is_cone() {
                    // Flat end: the bottom is level, so the lowest point is at an end.
                    a.z + dz * if dz > 0.0 { t0 } else { t1 }
                } else if k.inv_len2 > 0.0 {
                    // With τ = s_w - L t the signed distance along the move from the axis to
                    // q, the height is a.z + m s_w - (m τ - height(sqrt(perp² + τ²))): its lowest
                    // point is the cutter's contact with a line of slope m, as for an edge drop.
                    let len = k.len_xy;
                    let s_w = w.dot(d) * k.inv_len_xy;
                    let perp2 = (w.length_squared() - s_w * s_w).max(0.0);
                    let m = dz * k.inv_len_xy;
                    let (lo, hi) = (s_w - len * t1, s_w - len * t0);
                    // Most points are passed lowest at an end of the interval (F falls all along
                    // it, or rises): the end's slope and height come from one evaluation.
                    let at = |tau: f64, height: f64| a.z + m * (s_w - tau) + height;
                    let (slope, height) = p.slope_and_height(m, perp2, lo);
                    if slope <= 0.0 {
                        return at(lo, height);
                    }
                    let (slope, height) = p.slope_and_height(m, perp2, hi);
                    if slope >= 0.0 {
                        return at(hi, height);
                    }
                    let tau = p.contact_between(m, perp2, lo, hi);
                    let t = (s_w - tau) * k.inv_len_xy;
                    a.z + dz * t + p.height((perp2 + tau * tau).sqrt().min(p.radius))
                } else {
                    // A vertical move: the lower end, at q's distance from the axis.
                    a.z.min(b.z) + p.height(w.length().min(p.radius))
                }
            }
            Path::Arc { center, radius, start, sweep, z, rise } if rise != 0.0 => helix_lowest(q, center, radius, start, sweep, z, rise, p.radius),
            Path::Arc { center, radius, start, sweep, z, .. } => {
                // Farther from the whole circle than the cutter's radius (beyond a rounding's
                // margin), farther from the arc: passed over without its angle.
                let beyond = p.radius * (1.0 + FLOAT_SLACK) + FLOAT_SLACK;
                let dist = arc_distance(q, center, radius, start, sweep, &self.ends, false, beyond).0;
                if dist <= p.radius {
                    z + p.height(dist)
                } else {
                    f64::INFINITY
                }
            }
        }
    }

    /// Lower surface of the capsule a ball sweeps when its tip goes from `a` to `b` (not level).
    /// The capsule is convex, so a vertical line enters it once: through the cylinder about the
    /// centres' segment when that crossing lies between the ends, otherwise through an end
    /// sphere; a line that misses the infinite cylinder misses the capsule.
    #[inline]
    fn ball_line(&self, a: DVec3, b: DVec3, q: DVec2) -> f64 {
        let r = self.profile.radius;
        let r2 = r * r;
        let k = &self.line;
        let sphere = |c: DVec3| {
            let d2 = (q - c.truncate()).length_squared();
            if d2 <= r2 {
                c.z + r - (r2 - d2).sqrt()
            } else {
                f64::INFINITY
            }
        };
        if k.inv_along == 0.0 {
            return sphere(if a.z < b.z { a } else { b }); // vertical: the lower end
        }
        // Points (q, centre_z + h) on the cylinder: h^2 (1 - uz^2) - 2 h uz s0 + |w|^2 - s0^2 - r^2 = 0.
        let w = q - a.truncate();
        let s0 = w.x * k.u.x + w.y * k.u.y;
        let half_b = -k.u.z * s0;
        let c = w.length_squared() - s0 * s0 - r2;
        let disc = half_b * half_b - c / k.inv_along;
        if disc < 0.0 {
            return f64::INFINITY;
        }
        let h = (-half_b - disc.sqrt()) * k.inv_along;
        let s = s0 + h * k.u.z;
        if s < 0.0 {
            sphere(a)
        } else if s > k.length {
            sphere(b)
        } else {
            a.z + r + h
        }
    }

    /// Horizontal distance from `q` to the tip's path, and the tip's height at the nearest point.
    pub fn nearest(&self, q: DVec2) -> (f64, f64) {
        match self.path {
            Path::Line { a, b } => {
                let d = (b - a).truncate();
                let len2 = d.length_squared();
                let t = if len2 > 0.0 { ((q - a.truncate()).dot(d) / len2).clamp(0.0, 1.0) } else { 0.0 };
                let p = a.lerp(b, t);
                // A vertical move is nearest along its whole length: its lowest point counts.
                let z = if len2 > 0.0 { p.z } else { a.z.min(b.z) };
                ((q - p.truncate()).length(), z)
            }
            Path::Arc { center, radius, start, sweep, z, rise } => {
                let (dist, t) = arc_distance(q, center, radius, start, sweep, &self.ends, rise != 0.0, f64::INFINITY);
                (dist, z + rise * t)
            }
        }
    }

    /// Bounds of the envelope over the rectangle `[lo, hi]`: no point of it lies below the first
    /// value, and every point of it lies at or below the second (infinite when the cutter may
    /// miss part of the rectangle).
    pub fn bounds_over(&self, lo: DVec2, hi: DVec2) -> (f64, f64) {
        if lo.x > self.max.x || hi.x < self.min.x || lo.y > self.max.y || hi.y < self.min.y {
            return (f64::INFINITY, f64::INFINITY);
        }
        let p = &self.profile;
        let centre = (lo + hi) * 0.5;
        let half_diagonal = (hi - lo).length() * 0.5;
        let (dist, z) = self.nearest(centre);
        let near = dist - half_diagonal;
        let lower = if near > p.radius { f64::INFINITY } else { self.lowest_tip + p.height(near.max(0.0)) };
        let far = dist + half_diagonal;
        let upper = if far <= p.radius { z + p.height(far) } else { f64::INFINITY };
        (lower, upper)
    }

    /// A bound under [`Sweep::nearest`]'s distance at `q`, cheaper to find: an arc's distance
    /// from its circle, less a rounding's margin; 0 for a line.
    #[inline]
    pub fn nearest_at_least(&self, q: DVec2) -> f64 {
        match self.path {
            Path::Line { .. } => 0.0,
            Path::Arc { center, radius, .. } => {
                let off = ((q - center).length() - radius).abs();
                off - FLOAT_SLACK * (1.0 + off)
            }
        }
    }

    /// Whether the rim of the footprint (where the envelope ends) may pass within `reach` of `q`.
    #[inline]
    pub fn rim_near(&self, q: DVec2, reach: f64) -> bool {
        (self.nearest(q).0 - self.profile.radius).abs() <= reach
    }
}

/// Whether the direction `angle` lies on the arc starting at `start` and sweeping `sweep`.
fn angle_within(start: f64, sweep: f64, angle: f64) -> bool {
    let tau = std::f64::consts::TAU;
    let delta = (angle - start).rem_euclid(tau);
    if sweep >= 0.0 {
        delta <= sweep
    } else {
        delta == 0.0 || tau - delta <= -sweep
    }
}

/// How far an arc starting at `start` and turning the way `sweep` does turns to reach the
/// direction `angle` (radians, in [0, 2π)).
fn turned(start: f64, sweep: f64, angle: f64) -> f64 {
    if sweep >= 0.0 {
        (angle - start).rem_euclid(std::f64::consts::TAU)
    } else {
        (start - angle).rem_euclid(std::f64::consts::TAU)
    }
}

/// Whether the direction `v` (from an arc's centre, `len` long) lies on the arc, from the sides
/// of its ends' directions it lies on, where it lies clear of them and of their opposites (past
/// [`FLOAT_SLACK`] of a turn): the answer [`angle_within`] gives, without an arc tangent. `None`
/// nearer than that, where the angle decides.
fn side_within(v: DVec2, len: f64, sweep: f64, ends: &ArcEnds) -> Option<bool> {
    use std::f64::consts::{PI, TAU};
    if sweep.abs() >= TAU {
        return Some(true);
    }
    // As a counter-clockwise arc from `a` to `b`.
    let [a, b] = if sweep >= 0.0 { ends.dirs } else { [ends.dirs[1], ends.dirs[0]] };
    let m = FLOAT_SLACK * len;
    // Positive where `v` lies counter-clockwise of `a`, and `b` of `v`.
    let (after, before) = (a.perp_dot(v), v.perp_dot(b));
    if sweep.abs() < PI {
        // Less than half a turn: on the arc where both hold.
        if after > m && before > m {
            Some(true)
        } else if after < -m || before < -m {
            Some(false)
        } else {
            None
        }
    } else if after < -m && before < -m {
        // Half a turn or more: off it only where `v` lies within the rest (half a turn or less)
        // from `b` round to `a`.
        Some(false)
    } else if after > m || before > m {
        Some(true)
    } else {
        None
    }
}

/// Horizontal distance from `q` to an arc (its ends `ends`), and the fraction of the arc (0 at
/// its start, 1 at its end) at the nearest point, where `fraction` asks for it (0 otherwise).
/// A point farther than `beyond` from the arc's circle gets its distance from the circle (less
/// than the arc's, enough to say it lies beyond), found without the arc's angle.
#[allow(clippy::too_many_arguments)]
fn arc_distance(q: DVec2, center: DVec2, radius: f64, start: f64, sweep: f64, ends: &ArcEnds, fraction: bool, beyond: f64) -> (f64, f64) {
    let v = q - center;
    let len = v.length();
    if len == 0.0 {
        return (radius, 0.0);
    }
    let off = (len - radius).abs();
    if off > beyond {
        return (off, 0.0);
    }
    let side = side_within(v, len, sweep, ends);
    if side == Some(true) && !fraction {
        return (off, 0.0);
    }
    if side != Some(false) {
        let angle = v.y.atan2(v.x);
        if angle_within(start, sweep, angle) {
            return (off, if sweep == 0.0 { 0.0 } else { (turned(start, sweep, angle) / sweep.abs()).min(1.0) });
        }
    }
    let (da, db) = (q.distance(ends.points[0]), q.distance(ends.points[1]));
    if da <= db {
        (da, 0.0)
    } else {
        (db, 1.0)
    }
}

/// The lowest height a flat end of radius `reach` reaches over `q` on a helical arc (about
/// `center` at `radius`, from angle `start` through `sweep`, from height `z` rising `rise`), or
/// infinity where it never covers `q`. The end covers `q` while the angle to its axis lies
/// within `α` of `q`'s own angle about the centre (`cos α = (d² + r² − R²) / 2dr`, law of
/// cosines): the turns of that window met by the arc's angles, taken at the arc's end that is
/// lowest (the latest angle on a descent, the earliest on a climb).
#[allow(clippy::too_many_arguments)]
fn helix_lowest(q: DVec2, center: DVec2, radius: f64, start: f64, sweep: f64, z: f64, rise: f64, reach: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let v = q - center;
    let d = v.length();
    let total = sweep.abs();
    let height = |turned: f64| z + rise * if total > 0.0 { turned / total } else { 0.0 };
    let half = if d == 0.0 || radius == 0.0 {
        if (d - radius).abs() <= reach {
            PI
        } else {
            return f64::INFINITY;
        }
    } else {
        let cos = (d * d + radius * radius - reach * reach) / (2.0 * d * radius);
        if cos > 1.0 {
            return f64::INFINITY;
        }
        cos.max(-1.0).acos()
    };
    // The window's middle, as an angle turned from the start in the arc's direction.
    let middle = turned(start, sweep, v.y.atan2(v.x));
    if half >= PI {
        return height(if rise < 0.0 { total } else { 0.0 });
    }
    if rise < 0.0 {
        // The latest angle covered: in the last window that starts by the end.
        let n = ((total - middle + half) / TAU).floor();
        let end = middle + n * TAU + half;
        if end < 0.0 {
            return f64::INFINITY;
        }
        height(end.min(total))
    } else {
        let n = ((-half - middle) / TAU).ceil();
        let begin = middle + n * TAU - half;
        if begin > total {
            return f64::INFINITY;
        }
        height(begin.max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The envelope by brute force: the lowest cutter height over `q` at many points of the move.
    fn brute(sweep: &Sweep, samples: usize) -> impl Fn(DVec2) -> f64 + '_ {
        move |q| {
            let p = &sweep.profile;
            let mut lowest = f64::INFINITY;
            for k in 0..=samples {
                let t = k as f64 / samples as f64;
                let (c, z) = match sweep.path {
                    Path::Line { a, b } => (a.lerp(b, t).truncate(), a.z + (b.z - a.z) * t),
                    Path::Arc { center, radius, start, sweep, z, rise } => (center + DVec2::from_angle(start + sweep * t) * radius, z + rise * t),
                };
                let d = (q - c).length();
                if d <= p.radius {
                    lowest = lowest.min(z + p.height(d));
                }
            }
            lowest
        }
    }

    #[test]
    fn envelope_equals_brute_force_for_every_shape_and_slope() {
        // Flat, ball, bull nose, a drill's 118° point and a V-bit's 90° cone from a 1 mm tip.
        let profiles = [Profile::new(3.0, 0.0), Profile::new(3.0, 3.0), Profile::new(3.0, 1.0), Profile::cone(3.0, 0.0, 59f64.to_radians()), Profile::cone(3.0, 0.5, 45f64.to_radians())];
        let paths = [
            (DVec3::new(0.0, 0.0, 0.0), DVec3::new(10.0, 2.0, 0.0)),
            (DVec3::new(0.0, 0.0, 0.0), DVec3::new(10.0, 2.0, -3.0)),
            (DVec3::new(0.0, 0.0, -1.0), DVec3::new(-4.0, 6.0, 2.5)),
            (DVec3::new(1.0, 1.0, 5.0), DVec3::new(1.0, 1.0, -2.0)),
        ];
        for profile in profiles {
            for (a, b) in paths {
                let sweep = Sweep::line(profile, a, b);
                let exact = brute(&sweep, 20_000);
                for i in 0..40 {
                    for j in 0..40 {
                        let q = DVec2::new(-8.0 + i as f64 * 0.53, -6.0 + j as f64 * 0.41);
                        let (fast, slow) = (sweep.lowest(q), exact(q));
                        if slow.is_finite() {
                            // The brute force samples the move, so it can only be higher.
                            assert!(fast <= slow + 1e-9 && fast >= slow - 2e-3, "{profile:?} {a} {b} at {q}: {fast} vs {slow}");
                        } else {
                            assert!(fast >= sweep.lowest_tip, "{q}: {fast}");
                        }
                    }
                }
            }
        }
    }

    /// An arc's distance as the angle alone decides it (an arc tangent for every point).
    fn by_angle(q: DVec2, center: DVec2, radius: f64, start: f64, sweep: f64) -> (f64, f64) {
        let v = q - center;
        let len = v.length();
        if len == 0.0 {
            return (radius, 0.0);
        }
        let angle = v.y.atan2(v.x);
        if angle_within(start, sweep, angle) {
            return ((len - radius).abs(), if sweep == 0.0 { 0.0 } else { (turned(start, sweep, angle) / sweep.abs()).min(1.0) });
        }
        let (a, b) = (center + DVec2::from_angle(start) * radius, center + DVec2::from_angle(start + sweep) * radius);
        let (da, db) = (q.distance(a), q.distance(b));
        if da <= db {
            (da, 0.0)
        } else {
            (db, 1.0)
        }
    }

    #[test]
    fn an_arcs_distance_by_the_sides_of_its_ends_is_the_angles_to_the_bit() {
        use std::f64::consts::{PI, TAU};
        let profile = Profile::new(3.0, 0.0);
        let center = DVec2::new(123.4, -56.7);
        let mut checked = 0;
        for start in [0.0, 0.3, -2.9, PI, 3.0 * PI / 2.0] {
            for sweep in [0.0, 1e-12, 0.4, -0.4, PI - 1e-12, PI, -PI, PI + 1e-12, 4.0, -4.0, TAU - 1e-12, TAU, -TAU] {
                for r in [1e-6, 0.5, 40.0] {
                    let from = (center + DVec2::from_angle(start) * r).extend(-2.0);
                    let s = Sweep::arc(profile, from, center, sweep);
                    let Path::Arc { start: a0, radius, .. } = s.path else { unreachable!() };
                    // Directions on every side, at the ends, their opposites and just off them.
                    let mut angles: Vec<f64> = (0..72).map(|k| k as f64 * TAU / 72.0 + 0.01).collect();
                    for edge in [a0, a0 + sweep, a0 + PI, a0 + sweep + PI] {
                        angles.extend([edge, edge + 1e-15, edge - 1e-15, edge + 1e-10, edge - 1e-10]);
                    }
                    for angle in angles {
                        for d in [0.0, radius * 0.5, radius, radius + 1.0, 3.0 * radius + 2.5] {
                            let q = center + DVec2::from_angle(angle) * d;
                            let want = by_angle(q, center, radius, a0, sweep);
                            let got = arc_distance(q, center, radius, a0, sweep, &s.ends, true, f64::INFINITY);
                            assert!(want.0.to_bits() == got.0.to_bits() && want.1.to_bits() == got.1.to_bits(), "start {a0} sweep {sweep} r {radius} at {angle} {d}: {want:?} vs {got:?}");
                            let alone = arc_distance(q, center, radius, a0, sweep, &s.ends, false, f64::INFINITY);
                            assert_eq!(want.0.to_bits(), alone.0.to_bits(), "start {a0} sweep {sweep} r {radius} at {angle} {d}");
                            // Within the cutter's radius, the same distance; beyond it, beyond it still.
                            let cut = arc_distance(q, center, radius, a0, sweep, &s.ends, false, 3.0 * (1.0 + FLOAT_SLACK) + FLOAT_SLACK).0;
                            assert!(if want.0 <= 3.0 { cut.to_bits() == want.0.to_bits() } else { cut > 3.0 }, "start {a0} sweep {sweep} r {radius} at {angle} {d}: {cut} vs {want:?}");
                            // The bound under the distance holds.
                            assert!(s.nearest_at_least(q) <= want.0);
                            checked += 1;
                        }
                    }
                }
            }
        }
        assert!(checked > 80_000, "{checked}");
    }

    #[test]
    fn arc_envelope_equals_brute_force() {
        for profile in [Profile::new(2.0, 0.0), Profile::new(2.0, 2.0), Profile::new(2.0, 0.5), Profile::cone(2.0, 0.0, 45f64.to_radians())] {
            for sweep_angle in [1.0, -2.5, 4.0, -std::f64::consts::TAU] {
                let sweep = Sweep::arc(profile, DVec3::new(5.0, 1.0, -1.0), DVec2::new(1.0, 1.0), sweep_angle);
                let exact = brute(&sweep, 20_000);
                for i in 0..40 {
                    for j in 0..40 {
                        let q = DVec2::new(-6.0 + i as f64 * 0.37, -6.0 + j as f64 * 0.37);
                        let (fast, slow) = (sweep.lowest(q), exact(q));
                        assert!(fast <= slow + 1e-9, "{q}: {fast} vs {slow}");
                        if slow.is_finite() {
                            assert!(fast >= slow - 1e-3, "{q}: {fast} vs {slow}");
                        }
                        let inside = q.x >= sweep.min.x && q.x <= sweep.max.x && q.y >= sweep.min.y && q.y <= sweep.max.y;
                        assert!(inside || !fast.is_finite(), "{q} outside the footprint box");
                    }
                }
            }
        }
    }

    #[test]
    fn bounds_hold_over_rectangles() {
        let profile = Profile::new(2.0, 2.0);
        let sweep = Sweep::line(profile, DVec3::new(0.0, 0.0, -1.0), DVec3::new(8.0, 3.0, -2.0));
        for i in 0..30 {
            for j in 0..30 {
                let lo = DVec2::new(-3.0 + i as f64 * 0.45, -3.0 + j as f64 * 0.3);
                let hi = lo + DVec2::new(0.5, 0.5);
                let (lower, upper) = sweep.bounds_over(lo, hi);
                for s in 0..=4 {
                    for t in 0..=4 {
                        let q = lo + (hi - lo) * DVec2::new(s as f64 / 4.0, t as f64 / 4.0);
                        let e = sweep.lowest(q);
                        assert!(e >= lower - 1e-12 && e <= upper + 1e-12, "{lo}: {e} not in [{lower}, {upper}]");
                    }
                }
            }
        }
    }

    #[test]
    fn helix_is_split_into_chords_within_tolerance() {
        let from = DVec3::new(5.0, 0.0, 0.0);
        let mv = Move::Arc { to: DVec3::new(5.0, 0.0, -2.0), center: DVec2::ZERO, clockwise: false, feed: 100.0 };
        let sweeps = Sweep::of_move(Profile::new(1.0, 0.5), from, &mv, 0.001);
        assert!(sweeps.len() > 20);
        let last = match sweeps.last().unwrap().path {
            Path::Line { b, .. } => b,
            _ => unreachable!(),
        };
        assert_eq!(last, DVec3::new(5.0, 0.0, -2.0));
        for s in &sweeps {
            if let Path::Line { a, b } = s.path {
                let mid = (a + b).truncate() * 0.5;
                assert!(5.0 - mid.length() <= 0.001 + 1e-12);
            }
        }
    }

    /// A flat end's helix is one sweep, its envelope the lowest of a dense scan of the helix
    /// at every point (descending and climbing, either way round, less than and more than a
    /// turn, a tool wider than the helix and one narrower), and the bounds hold over it.
    #[test]
    fn a_flat_ends_helix_is_exact() {
        let mut checked = 0;
        for (tool, helix) in [(1.0, 3.0), (2.0, 1.0), (1.5, 1.5)] {
            let profile = Profile::new(tool, 0.0);
            for (turn, rise) in [(2.0, -1.5), (-2.0, -1.5), (5.0, 2.0), (-7.0, 0.7), (std::f64::consts::TAU, -3.0), (0.3, -0.2)] {
                let from = DVec3::new(1.0 + helix * 0.6, -2.0 + helix * 0.8, 4.0);
                let center = DVec2::new(1.0, -2.0);
                let end = center + DVec2::from_angle((0.8f64).atan2(0.6) + turn) * helix;
                let mv = Move::Arc { to: end.extend(from.z + rise), center, clockwise: turn < 0.0, feed: 100.0 };
                let sweeps = Sweep::of_move(profile, from, &mv, 0.001);
                assert_eq!(sweeps.len(), 1);
                let sweep = sweeps[0];
                let exact = brute(&sweep, 20_000);
                for i in 0..40 {
                    for j in 0..40 {
                        // Off the round figures, where a point on the rim is in or out by rounding.
                        let q = DVec2::new(-5.0123 + i as f64 * 0.3, -8.0071 + j as f64 * 0.3);
                        let (fast, slow) = (sweep.lowest(q), exact(q));
                        assert!(fast <= slow + 1e-9, "{tool} {helix} {turn} {rise} at {q}: {fast} vs {slow} {:?}", sweep.path);
                        if slow.is_finite() {
                            assert!(fast >= slow - 1e-3, "{tool} {helix} {turn} {rise} at {q}: {fast} vs {slow} {:?}", sweep.path);
                            checked += 1;
                        } else {
                            // The scan may miss a sliver at the rim, never more.
                            assert!(!fast.is_finite() || sweep.nearest(q).0 >= tool - 1e-3, "{q}: {fast}");
                        }
                        assert!(fast >= sweep.lowest_tip);
                        let inside = q.x >= sweep.min.x && q.x <= sweep.max.x && q.y >= sweep.min.y && q.y <= sweep.max.y;
                        assert!(inside || !fast.is_finite(), "{q} outside the footprint box");
                        let (lower, upper) = sweep.bounds_over(q - 0.1, q + 0.1);
                        assert!(fast >= lower - 1e-12 && fast <= upper + 1e-12, "{q}: {fast} not in [{lower}, {upper}]");
                    }
                }
            }
        }
        assert!(checked > 3_000, "{checked}");
    }

    /// The bull nose's sloped sweeps against a dense scan of the move, at random points of
    /// random moves' footprints.
    #[test]
    fn bull_nose_sweeps_match_a_dense_scan() {
        let p = Profile::new(3.0, 1.0);
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut checked = 0;
        for _ in 0..150 {
            let a = DVec3::new(rnd() * 10.0 - 5.0, rnd() * 10.0 - 5.0, rnd() * 4.0 - 2.0);
            let b = DVec3::new(rnd() * 10.0 - 5.0, rnd() * 10.0 - 5.0, rnd() * 4.0 - 2.0);
            let sweep = Sweep::line(p, a, b);
            let exact = brute(&sweep, 20_000);
            for _ in 0..20 {
                let q = DVec2::new(sweep.min.x + rnd() * (sweep.max.x - sweep.min.x), sweep.min.y + rnd() * (sweep.max.y - sweep.min.y));
                let (fast, slow) = (sweep.lowest(q), exact(q));
                if slow.is_finite() {
                    assert!(fast <= slow + 1e-9 && fast >= slow - 2e-3, "{a} {b} at {q}: {fast} vs {slow}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 1000, "{checked}");
    }
}
