//! Normal cones of edges and vertices (seed 001 §2.2's gaps and twists, made into a speed-up).
//!
//! A cutter touching a feature at a single point has a contact direction d (from the contact
//! into the cutter). If d points into one of the feature's adjacent facets, the cutter cuts into
//! that facet, and the facet's own drops stand higher than this one: the feature is not the
//! highest contact there. So a feature needs only the nodes whose contact direction lies in its
//! normal cone, mapped to tip offsets. A concave edge's cone is empty (it never decides), a
//! convex edge's is the arc between its facets' normals, and a saddle vertex's is empty.

use crate::cutter::{FacetPlane, Profile};
use crate::geom::{DVec2, DVec3, Tolerances};
use crate::mesh::{EdgeFaces, Mesh};

/// Widening of an edge's region (relative to the cutter radius) against rounding.
pub(super) const REGION_MARGIN: f64 = 1e-9;

/// What an edge is, for the drop.
pub(super) enum EdgeKind {
    /// Concave: never the highest contact.
    Valley,
    /// Convex between two upward facets with these normals.
    Ridge(DVec3, DVec3),
    /// Boundary, non-manifold, or next to a vertical facet.
    Other,
}

/// The box of tip offsets `c - e` over the contact directions `d` of an edge's normal cone
/// (the great-circle arc from `n1` to `n2`): a cutter touching the edge at `e` with direction
/// `d` stands at `e_xy + a d_xy + (R - a) d_xy / |d_xy|` (any point within `R - a` of `e` when
/// `d` is vertical). Outside the cone it would cut into one of the two facets.
pub(super) fn cone_offsets(profile: &Profile, n1: DVec3, n2: DVec3) -> (DVec2, DVec2) {
    cone_hull_offsets(profile, &[n1, n2])
}

/// The same box over the spherical hull of several normals (the normal cone of a vertex). Its
/// d_xy is extreme on the hull's boundary, made of arcs between the normals; an arc strays
/// from its chord by at most its sagitta 1 - cos(Θ/2), and projecting onto the plane shortens
/// nothing, so the normals' box grown by the widest pair's sagitta holds it. The horizontal
/// direction d_xy / |d_xy| stays within the shortest arc of the circle holding the normals'
/// directions, unless that spans half a turn or more or a normal is vertical (then the flat
/// bottom can rest on the feature: a whole disk).
pub(super) fn cone_hull_offsets(profile: &Profile, normals: &[DVec3]) -> (DVec2, DVec2) {
    let (a, flat) = (profile.corner, profile.radius - profile.corner);
    let (d_lo, d_hi) = match normals {
        [n1, n2] => arc_box(*n1, *n2),
        _ => {
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            let mut widest = 1.0f64; // smallest cosine between two normals
            for (k, n) in normals.iter().enumerate() {
                lo = lo.min(n.truncate());
                hi = hi.max(n.truncate());
                for m in &normals[k + 1..] {
                    widest = widest.min(n.dot(*m));
                }
            }
            let sagitta = 1.0 - ((1.0 + widest.clamp(-1.0, 1.0)) / 2.0).sqrt() + REGION_MARGIN;
            (lo - sagitta, hi + sagitta)
        }
    };
    let (u_lo, u_hi) = if flat > 0.0 { direction_box(normals) } else { (DVec2::ZERO, DVec2::ZERO) };
    // a and R - a are not negative, so the box of the sum is the sum of the scaled boxes.
    (d_lo * a + u_lo * flat, d_hi * a + u_hi * flat)
}

/// Box of d_xy along the great-circle arc from `n1` to `n2` (shorter than half a turn): its
/// ends, and, for each axis direction, the point of the arc's circle nearest to it (where that
/// coordinate is extreme) if it lies between the ends.
fn arc_box(n1: DVec3, n2: DVec3) -> (DVec2, DVec2) {
    let (mut lo, mut hi) = (n1.truncate().min(n2.truncate()), n1.truncate().max(n2.truncate()));
    let Some(m) = n1.cross(n2).try_normalize() else { return (lo, hi) };
    for axis in [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y] {
        let Some(d) = (axis - m * axis.dot(m)).try_normalize() else { continue };
        if n1.cross(d).dot(m) > 0.0 && d.cross(n2).dot(m) > 0.0 {
            lo = lo.min(d.truncate());
            hi = hi.max(d.truncate());
        }
    }
    (lo, hi)
}

/// Box of the unit horizontal directions of the normals' spherical hull: the shortest arc of the
/// unit circle holding all their directions, or the whole disk when that arc is half a turn or
/// more, or a normal is vertical. Two normals whose horizontal parts point exactly opposite ways
/// (a horizontal ridge between facets of equal slope) span half a turn: the great-circle arc
/// between them passes through the vertical, so the flat bottom can rest on the edge from any
/// side.
fn direction_box(normals: &[DVec3]) -> (DVec2, DVec2) {
    let whole = (DVec2::splat(-1.0), DVec2::splat(1.0));
    let mut angles = Vec::with_capacity(normals.len());
    for n in normals {
        let Some(u) = n.truncate().try_normalize() else { return whole };
        angles.push(u.y.atan2(u.x));
    }
    crate::geom::sort::sort_floats(&mut angles);
    // The arc holding every direction is the circle less its largest gap between neighbours.
    let tau = std::f64::consts::TAU;
    let (mut gap, mut from) = (angles[0] + tau - angles[angles.len() - 1], angles[0]);
    for w in angles.windows(2) {
        if w[1] - w[0] > gap {
            (gap, from) = (w[1] - w[0], w[1]);
        }
    }
    let span = tau - gap;
    if span >= std::f64::consts::PI - REGION_MARGIN {
        return whole;
    }
    let (from, to) = (from - REGION_MARGIN, from + span + REGION_MARGIN);
    let at = |a: f64| DVec2::new(a.cos(), a.sin());
    let (mut lo, mut hi) = (at(from).min(at(to)), at(from).max(at(to)));
    // An axis direction inside the arc is where a coordinate is extreme.
    for k in -4..=4 {
        let axis = k as f64 * std::f64::consts::FRAC_PI_2;
        if axis > from && axis < to {
            lo = lo.min(at(axis));
            hi = hi.max(at(axis));
        }
    }
    (lo, hi)
}

/// Relative slack when testing a candidate direction against a vertex's constraints (keeps
/// directions that rounding puts a hair outside: the region can only grow).
const CONE_SLACK: f64 = 1e-9;

/// Which nodes a vertex can decide.
#[derive(Clone, Copy, Debug)]
pub(super) enum VertexReach {
    /// All within the cutter radius.
    Disk,
    /// Only those at the cutter radius (a flat end's rim resting on it).
    Rim,
    /// None: its normal cone is empty.
    Never,
    /// Those in this box of tip offsets from the vertex.
    Offsets(DVec2, DVec2),
}

/// Most corners kept for one vertex's cone; a fan with more visits the whole disk.
const MAX_CORNERS: usize = 16;

/// For a cutter with a smooth lower surface (ball, bull nose), each vertex's normal cone
/// `{d : d·(w - v) <= 0 for every neighbour w, d_z >= 0}`: a cutter touching only the vertex
/// has one contact direction d, and it must lie there or the cutter would cut into a facet. The
/// cone's corners are where two constraint planes meet and all constraints hold; none (a
/// saddle, a pit) means the vertex is never the highest contact.
pub(super) fn vertex_cones(mesh: &Mesh, kinds: &[(EdgeFaces, EdgeKind)], profile: &Profile) -> Vec<VertexReach> {
    let v = &mesh.vertices;
    // Unit directions to the neighbours, grouped by vertex (counting sort by vertex).
    let mut start = vec![0usize; v.len() + 1];
    for (e, _) in kinds {
        start[e.edge[0] as usize + 1] += 1;
        start[e.edge[1] as usize + 1] += 1;
    }
    for k in 0..v.len() {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut directions = vec![DVec3::ZERO; start[v.len()]];
    for (e, _) in kinds {
        let [a, b] = e.edge;
        let d = (v[b as usize] - v[a as usize]).normalize_or_zero();
        directions[fill[a as usize]] = d;
        fill[a as usize] += 1;
        directions[fill[b as usize]] = -d;
        fill[b as usize] += 1;
    }
    crate::parallel::map(v.len(), |k| {
        let neighbours = &directions[start[k]..start[k + 1]];
        if neighbours.len() < 3 {
            return VertexReach::Disk;
        }
        let constraints = || neighbours.iter().copied().chain(std::iter::once(DVec3::NEG_Z)); // d_z >= 0
        let mut corners = [DVec3::ZERO; MAX_CORNERS];
        let mut count = 0;
        for (i, ci) in constraints().enumerate() {
            for cj in constraints().skip(i + 1) {
                // Both signs of the unnormalised cross product at once: scaling keeps the
                // constraints' signs, and the slack scales with the length.
                let d = ci.cross(cj);
                let length = d.length();
                if length == 0.0 {
                    continue;
                }
                let slack = CONE_SLACK * length;
                let (mut plus, mut minus) = (true, true);
                for c in constraints() {
                    let t = d.dot(c);
                    plus &= t <= slack;
                    minus &= -t <= slack;
                    if !plus && !minus {
                        break;
                    }
                }
                for (ok, d) in [(plus, d / length), (minus, -d / length)] {
                    if ok {
                        if count == MAX_CORNERS {
                            return VertexReach::Disk;
                        }
                        corners[count] = d;
                        count += 1;
                    }
                }
            }
        }
        if count == 0 {
            return VertexReach::Never;
        }
        let (lo, hi) = cone_hull_offsets(profile, &corners[..count]);
        VertexReach::Offsets(lo, hi)
    })
}

/// For a flat end, whose tip height over a node is the highest point of the part under its
/// disk: a locally convex vertex (interior to a manifold fan, every edge a ridge, the fan's
/// facets winding the same way in projection) reaches the offsets of its normal cone, the
/// spherical hull of its facets' normals; a vertex with a neighbour above it has higher points
/// arbitrarily close, so it can be the highest point under the disk only on the rim; the others
/// (weak local maxima) reach the whole disk.
pub(super) fn vertex_reaches(mesh: &Mesh, kinds: &[(EdgeFaces, EdgeKind)], up: &[Option<DVec3>], profile: &Profile) -> Vec<VertexReach> {
    let n = mesh.vertices.len();
    let mut convex = vec![true; n];
    let mut ridges = vec![0u32; n];
    let mut below = vec![false; n]; // a neighbour stands higher
    let z = |v: u32| mesh.vertices[v as usize].z;
    for (e, kind) in kinds {
        let ridge = matches!(kind, EdgeKind::Ridge(..));
        let [a, b] = e.edge;
        for v in [a, b] {
            convex[v as usize] &= ridge;
            ridges[v as usize] += ridge as u32;
        }
        below[a as usize] |= z(b) > z(a);
        below[b as usize] |= z(a) > z(b);
    }
    let mut fans: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut winding = vec![0i8; n];
    for (f, face) in mesh.faces.iter().enumerate() {
        let t = mesh.triangle(f);
        let sign = crate::geom::orient2d(t.a.truncate(), t.b.truncate(), t.c.truncate()).signum() as i8;
        for &v in face {
            let v = v as usize;
            fans[v].push(f as u32);
            if up[f].is_none() || sign == 0 || (winding[v] != 0 && winding[v] != sign) {
                convex[v] = false;
            }
            winding[v] = sign;
        }
    }
    (0..n)
        .map(|v| {
            // In a closed fan there are as many edges as facets.
            if convex[v] && ridges[v] as usize == fans[v].len() && fans[v].len() >= 3 {
                let normals: Vec<DVec3> = fans[v].iter().map(|&f| up[f as usize].unwrap()).collect();
                let (lo, hi) = cone_hull_offsets(profile, &normals);
                VertexReach::Offsets(lo, hi)
            } else if below[v] {
                VertexReach::Rim
            } else {
                VertexReach::Disk
            }
        })
        .collect()
}

/// An edge that may be the highest contact somewhere: its ends, the box of tip positions over
/// which it can decide (its normal cone's offsets, grown by [`REGION_MARGIN`]), those offsets
/// themselves (the tip stands at a point of the edge plus one of them), and the first face it
/// belongs to.
#[derive(Clone, Copy, Debug)]
pub(super) struct EdgeRegion {
    pub p: DVec3,
    pub q: DVec3,
    pub lo: DVec2,
    pub hi: DVec2,
    pub offset_lo: DVec2,
    pub offset_hi: DVec2,
    pub face: u32,
}

/// Every edge of `mesh` but its valleys (which never decide), once each, with the region of
/// tip positions its normal cone lets it decide for `profile`; `kinds` as [`edge_kind`] gives
/// them.
pub(super) fn edge_regions(mesh: &Mesh, kinds: &[(EdgeFaces, EdgeKind)], profile: &Profile) -> Vec<EdgeRegion> {
    let margin = DVec2::splat(REGION_MARGIN * (1.0 + profile.radius));
    let v = &mesh.vertices;
    kinds
        .iter()
        .filter_map(|(e, kind)| {
            // (A cone's tip and rims have a fan of normals each, so the normal cones' argument
            // does not hold for it: every edge, valleys too, reaches its whole disk.)
            let (offset_lo, offset_hi) = match *kind {
                _ if profile.is_cone() => (DVec2::splat(-profile.radius), DVec2::splat(profile.radius)),
                EdgeKind::Valley => return None,
                EdgeKind::Ridge(n1, n2) => cone_offsets(profile, n1, n2),
                EdgeKind::Other => (DVec2::splat(-profile.radius), DVec2::splat(profile.radius)),
            };
            let (p, q) = (v[e.edge[0] as usize], v[e.edge[1] as usize]);
            let (offset_lo, offset_hi) = (offset_lo - margin, offset_hi + margin);
            let lo = p.truncate().min(q.truncate()) + offset_lo;
            let hi = p.truncate().max(q.truncate()) + offset_hi;
            Some(EdgeRegion { p, q, lo, hi, offset_lo, offset_hi, face: e.faces[0] })
        })
        .collect()
}

/// The edges of `mesh` with their kinds, from the facets' upward normals.
pub(super) fn edge_kinds(mesh: &Mesh, tolerances: &Tolerances) -> (Vec<Option<DVec3>>, Vec<(EdgeFaces, EdgeKind)>) {
    let up: Vec<Option<DVec3>> = (0..mesh.faces.len()).map(|f| up_normal(mesh, f, tolerances)).collect();
    let kinds = mesh.edges_with_faces().into_iter().map(|e| (e, edge_kind(mesh, &e, &up))).collect();
    (up, kinds)
}

/// The unit normal of a facet turned upward, or `None` for a vertical or degenerate facet.
pub(super) fn up_normal(mesh: &Mesh, face: usize, tolerances: &Tolerances) -> Option<DVec3> {
    let t = mesh.triangle(face);
    FacetPlane::new(t.a, t.b, t.c, tolerances.normal).map(|facet| facet.normal)
}

/// Classifies an edge by its two facets (normals turned upward): a valley when each facet's far
/// corner lies on or above the other's plane, a ridge when each lies below.
pub(super) fn edge_kind(mesh: &Mesh, e: &EdgeFaces, up: &[Option<DVec3>]) -> EdgeKind {
    if e.count != 2 {
        return EdgeKind::Other;
    }
    let v = &mesh.vertices;
    let far = |f: u32| mesh.faces[f as usize].into_iter().find(|k| !e.edge.contains(k)).map(|k| v[k as usize]);
    let [f1, f2] = e.faces;
    let a = v[e.edge[0] as usize];
    match (far(f1), far(f2), up[f1 as usize], up[f2 as usize]) {
        (Some(c1), Some(c2), Some(n1), Some(n2)) => {
            let (above1, above2) = ((c2 - a).dot(n1), (c1 - a).dot(n2));
            if above1 >= 0.0 && above2 >= 0.0 {
                EdgeKind::Valley
            } else if above1 < 0.0 && above2 < 0.0 {
                EdgeKind::Ridge(n1, n2)
            } else {
                EdgeKind::Other // rounding disagrees: take no chances
            }
        }
        _ => EdgeKind::Other,
    }
}
