//! Polygons of many corners as triangles: an OBJ face, or a glTF triangle fan that is one. A
//! fan from one corner of a polygon of 100,000 corners is as many slivers each reaching across
//! the part, so that every bucket of a drop index and every node of a z-map meets every one
//! (past ten minutes on a φ80 disc); a strip across the polygon makes thin bands instead.

use crate::geom::DVec3;

/// The most corners a polygon is triangulated as a fan from its first.
pub(super) const FAN_MOST: usize = 32;

/// Largest distance a corner may stand off its polygon's plane, or inside the line through its
/// neighbours, for the polygon to count as flat and convex, as a fraction of its size: what a
/// file's single-precision coordinates round a flat convex outline to (a 100,000-gon of radius
/// 40 stored as f32 turns back by a few millionths of a millimetre here and there).
const FLAT: f64 = 1e-6;

/// The triangles of a polygon of `n` corners, as corner positions in its order (each turning
/// as the polygon does): a fan from the first corner up to [`FAN_MOST`] corners, larger ones
/// as a strip across it.
pub(super) fn triangulate(n: usize) -> Vec<[usize; 3]> {
    if n < 3 {
        return Vec::new();
    }
    if n <= FAN_MOST {
        return (1..n - 1).map(|k| [0, k, k + 1]).collect();
    }
    // The edge across the polygon steps forward from its front and back from its back in turn.
    let (mut a, mut b) = (0, n - 1);
    let mut out = Vec::with_capacity(n - 2);
    let mut front = true;
    while b - a >= 2 {
        if front {
            out.push([a, a + 1, b]);
            a += 1;
        } else {
            out.push([a, b - 1, b]);
            b -= 1;
        }
        front = !front;
    }
    out
}

/// The polygon a triangle fan covers, when it is flat and convex (within [`FLAT`]) so that
/// [`triangulate`]'s strip covers the same region: the fan's own corners when they make such a
/// polygon (a fan from a corner of it), or its rim without the hub when the rim closes on its
/// first corner round a hub inside it (a fan from the centre of a disc). `None` for any other
/// fan, which is kept as the file gives it.
pub(super) fn fan_polygon(fan: &[DVec3]) -> Option<&[DVec3]> {
    if flat_convex(fan).is_some() {
        return Some(fan);
    }
    let (&hub, rest) = fan.split_first()?;
    let (&last, rim) = rest.split_last()?;
    if rim.first() != Some(&last) {
        return None;
    }
    let (up, slack) = flat_convex(rim)?;
    let n = rim.len();
    let inside = (0..n).all(|i| {
        let (a, b) = (rim[i], rim[(i + 1) % n]);
        (hub - a).dot(up).abs() <= slack && (b - a).cross(hub - a).dot(up) >= -slack * (b - a).length()
    });
    inside.then_some(rim)
}

/// The plane's normal and the slack, when `ring` is a flat convex polygon that goes round once
/// (within [`FLAT`]).
fn flat_convex(ring: &[DVec3]) -> Option<(DVec3, f64)> {
    let n = ring.len();
    if n < 3 {
        return None;
    }
    // Newell's normal: the polygon's area vector, whatever its shape.
    let normal = (0..n).fold(DVec3::ZERO, |s, i| s + ring[i].cross(ring[(i + 1) % n]));
    let up = normal.try_normalize()?;
    let (lo, hi) = ring.iter().fold((ring[0], ring[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let slack = FLAT * (hi - lo).length();
    if ring.iter().any(|p| (*p - ring[0]).dot(up).abs() > slack) {
        return None;
    }
    // Every corner on the outer side of the line through its neighbours (or on it), and the
    // turns adding up to one whole turn: a simple convex polygon.
    let mut turned = 0.0;
    for i in 0..n {
        let (a, p, b) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
        let (e1, e2) = (p - a, b - p);
        let cross = e1.cross(e2).dot(up);
        // Twice the triangle's area over its base: how far the corner stands off the line.
        if cross < -slack * (b - a).length() {
            return None;
        }
        turned += cross.atan2(e1.dot(e2));
    }
    ((turned - std::f64::consts::TAU).abs() < 1e-6).then_some((up, slack))
}
