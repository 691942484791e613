//! Seed 001 §3.3, the exact CL z-map: the cutter is dropped onto every facet (the offset facet,
//! eq. 2), every edge and every vertex of the mesh, each rasterised over just the nodes it can
//! affect, and the heights are max-combined. The edges and vertices are the paper's
//! "singularities" (gaps and twists of the offset surface, §2.2): dropping onto them fills the
//! gaps, and taking the maximum removes the twists.
//!
//! Steps, in order:
//! 1. facets: the nodes whose contact point falls in the facet are the facet's projection
//!    shifted against its uphill direction by `R - a + a |n_xy|`;
//! 2. vertices: each vertex once, over the nodes within R of it — or only those its normal
//!    cone's offsets reach (the argument of step 3): for a ball or bull nose, whose lower
//!    surface is smooth, the cone of directions that clear every neighbour (empty at a saddle);
//!    for a flat end, at locally convex vertices, the hull of the facets' normals;
//! 3. edges: each edge shared by two facets once, over the nodes within R of it, skipped at a
//!    node where a cheap upper bound shows it cannot rise above what steps 1 and 2 found.
//!    A cutter touching an edge at an interior point with contact direction d (from the contact
//!    into the cutter) cuts into an adjacent facet unless d lies in the edge's normal cone, the
//!    arc between the two facets' normals; then that facet's own features stand higher. So a
//!    concave edge (a valley, whose cone is empty) is skipped whole, and a convex edge (a
//!    ridge: the paper's "gap") visits only the nodes its cone's offsets can reach — a thin
//!    strip on a smooth surface instead of the whole disk of radius R.

use super::{Grid, HeightField};
use crate::cutter::{FacetPlane, Profile};
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3, Tolerances};
use crate::mesh::{EdgeFaces, Mesh};
use crate::progress::Progress;

/// How many features are handled between two progress reports.
const REPORT_EVERY: usize = 4096;

/// Builds the CL z-map of `profile` over `mesh`; nodes the cutter cannot reach the part from
/// hold `floor`.
pub fn cl_exact(mesh: &Mesh, profile: &Profile, grid: Grid, floor: f64, tolerances: &Tolerances, progress: &mut Progress) -> Result<HeightField> {
    let mut field = grid.filled(floor);
    let up_normals: Vec<Option<DVec3>> = (0..mesh.faces.len()).map(|f| up_normal(mesh, f, tolerances)).collect();
    let kinds: Vec<(EdgeFaces, EdgeKind)> = mesh.edges_with_faces().into_iter().map(|e| (e, edge_kind(mesh, &e, &up_normals))).collect();
    let vertex_reach = if profile.corner > 0.0 { vertex_cones(mesh, &kinds) } else { vertex_reaches(mesh, &kinds, &up_normals) };
    let edges: Vec<([u32; 2], Reach)> = kinds
        .iter()
        .filter_map(|(e, kind)| match *kind {
            EdgeKind::Valley => None,
            EdgeKind::Ridge(n1, n2) => Some((e.edge, Reach::Cone(n1, n2))),
            EdgeKind::Other => Some((e.edge, Reach::Capsule)),
        })
        .collect();
    let total = (mesh.faces.len() + edges.len() + mesh.vertices.len()) as f64;
    let mut done = 0usize;
    let tick = |done: usize, progress: &mut Progress| -> Result<()> {
        if done % REPORT_EVERY == 0 && !progress.report(done as f64 / total) {
            return Err(Error::Cancelled);
        }
        Ok(())
    };

    for t in mesh.triangles() {
        tick(done, progress)?;
        done += 1;
        let Some(facet) = FacetPlane::new(t.a, t.b, t.c, tolerances.normal) else { continue };
        let shift = facet.uphill * (profile.radius - profile.corner + profile.corner * facet.slope_sin);
        let b = t.bounds();
        let (lo, hi) = (b.min.truncate() - shift, b.max.truncate() - shift);
        for_nodes_in_box(&grid, lo, hi, &mut |i, j, c| {
            if let Some(z) = profile.drop_facet(c, &facet) {
                raise(&mut field, i, j, z);
            }
        });
    }

    let v = &mesh.vertices;
    let margin = DVec2::splat(REGION_MARGIN * (1.0 + profile.radius));
    for (k, &p) in v.iter().enumerate() {
        tick(done, progress)?;
        done += 1;
        let mut visit = |i: usize, j: usize, c: DVec2| {
            let cell = &mut field.z[j * grid.nx + i];
            let r2 = (p.truncate() - c).length_squared();
            // The drop is v.z - height(r): it cannot beat the cell where the cutter has risen
            // by the difference.
            if r2 <= profile.radius * profile.radius && r2 < profile.reach_squared(p.z - *cell) {
                *cell = cell.max(p.z - profile.height(r2.sqrt()));
            }
        };
        match &vertex_reach[k] {
            None => for_nodes_in_disk(&grid, p.truncate(), profile.radius, &mut visit),
            Some(normals) if normals.is_empty() => {} // its cone is empty: never the contact
            Some(normals) => {
                let (lo, hi) = cone_hull_offsets(profile, normals);
                for_nodes_in_box(&grid, p.truncate() + lo - margin, p.truncate() + hi + margin, &mut visit);
            }
        }
    }
    for ([a, b], reach) in edges {
        tick(done, progress)?;
        done += 1;
        let (p, q) = (v[a as usize], v[b as usize]);
        let (offset_lo, offset_hi) = match reach {
            Reach::Capsule => (DVec2::splat(-profile.radius), DVec2::splat(profile.radius)),
            Reach::Cone(n1, n2) => cone_offsets(profile, n1, n2),
        };
        let lo = p.truncate().min(q.truncate()) + offset_lo - margin;
        let hi = p.truncate().max(q.truncate()) + offset_hi + margin;
        for_nodes_in_box(&grid, lo, hi, &mut |i, j, c| {
            let cell = &mut field.z[j * grid.nx + i];
            if let Some(z) = profile.drop_edge_above(c, p, q, *cell) {
                *cell = cell.max(z);
            }
        });
    }

    Ok(field)
}

/// The exact CL height over one point (the same drops, over the whole mesh): the reference the
/// tests and `swarf verify` compare grid heights and tool paths against.
pub fn cl_exact_at(mesh: &Mesh, profile: &Profile, c: DVec2, tolerances: &Tolerances) -> Option<f64> {
    let mut best: Option<f64> = None;
    let mut raise = |z: Option<f64>| {
        if let Some(z) = z {
            best = Some(best.map_or(z, |b| b.max(z)));
        }
    };
    for t in mesh.triangles() {
        if let Some(facet) = FacetPlane::new(t.a, t.b, t.c, tolerances.normal) {
            raise(profile.drop_facet(c, &facet));
        }
        for (p, q) in [(t.a, t.b), (t.b, t.c), (t.c, t.a)] {
            raise(profile.drop_edge(c, p, q));
        }
    }
    for &p in &mesh.vertices {
        raise(profile.drop_vertex(c, p));
    }
    best
}

/// Widening of an edge's region (relative to the cutter radius) against rounding.
const REGION_MARGIN: f64 = 1e-9;

/// Which nodes an edge can decide.
#[derive(Clone, Copy)]
enum Reach {
    /// All within the cutter radius.
    Capsule,
    /// Those whose contact direction lies in the cone between the two facets' normals.
    Cone(DVec3, DVec3),
}

enum EdgeKind {
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
fn cone_offsets(profile: &Profile, n1: DVec3, n2: DVec3) -> (DVec2, DVec2) {
    cone_hull_offsets(profile, &[n1, n2])
}

/// The same box over the spherical hull of several normals (the normal cone of a convex vertex).
/// On the sphere's upper half, d_xy is extreme on the hull's boundary, whose arcs are among the
/// arcs between pairs of normals; the horizontal direction d_xy / |d_xy| stays within the
/// smallest angular interval holding the normals' directions, unless that spans half a turn or
/// more, or a normal is vertical (then the flat bottom can rest on the feature: a whole disk).
fn cone_hull_offsets(profile: &Profile, normals: &[DVec3]) -> (DVec2, DVec2) {
    let (a, flat) = (profile.corner, profile.radius - profile.corner);
    let (mut d_lo, mut d_hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for (k, &n1) in normals.iter().enumerate() {
        for &n2 in &normals[k..] {
            let (lo, hi) = arc_box(n1, n2);
            d_lo = d_lo.min(lo);
            d_hi = d_hi.max(hi);
        }
    }
    let (u_lo, u_hi) = if flat > 0.0 { direction_box(normals) } else { (DVec2::ZERO, DVec2::ZERO) };
    // a and R - a are not negative, so the box of the sum is the sum of the scaled boxes.
    (d_lo * a + u_lo * flat, d_hi * a + u_hi * flat)
}

/// Box of d_xy along the great-circle arc from `n1` to `n2`: its ends, and where a coordinate
/// is extreme inside it.
fn arc_box(n1: DVec3, n2: DVec3) -> (DVec2, DVec2) {
    let cos = n1.dot(n2).clamp(-1.0, 1.0);
    let angle = cos.acos();
    let w = (n2 - n1 * cos).try_normalize().unwrap_or(DVec3::ZERO);
    let at = |t: f64| (n1 * t.cos() + w * t.sin()).truncate();
    let (mut lo, mut hi) = (n1.truncate().min(n2.truncate()), n1.truncate().max(n2.truncate()));
    for (u, v) in [(n1.x, w.x), (n1.y, w.y)] {
        let t0 = v.atan2(u);
        for t in [t0, t0 + std::f64::consts::PI, t0 - std::f64::consts::PI] {
            if t > 0.0 && t < angle {
                lo = lo.min(at(t));
                hi = hi.max(at(t));
            }
        }
    }
    (lo, hi)
}

/// Box of the unit horizontal directions of the normals' spherical hull.
fn direction_box(normals: &[DVec3]) -> (DVec2, DVec2) {
    let whole = (DVec2::splat(-1.0), DVec2::splat(1.0));
    let mut angles = Vec::with_capacity(normals.len());
    for n in normals {
        match n.truncate().try_normalize() {
            Some(u) => angles.push(u.y.atan2(u.x)),
            None => return whole,
        }
    }
    angles.sort_by(f64::total_cmp);
    // The interval is the circle minus its widest gap between neighbouring directions.
    let tau = std::f64::consts::TAU;
    let (mut gap, mut start) = (angles[0] + tau - angles[angles.len() - 1], angles[0]);
    for w in angles.windows(2) {
        if w[1] - w[0] > gap {
            gap = w[1] - w[0];
            start = w[1];
        }
    }
    let span = tau - gap;
    if span >= std::f64::consts::PI - REGION_MARGIN {
        return whole;
    }
    let point = |t: f64| DVec2::new(t.cos(), t.sin());
    let (mut lo, mut hi) = (point(start).min(point(start + span)), point(start).max(point(start + span)));
    for k in -4..=8 {
        let axis = k as f64 * std::f64::consts::FRAC_PI_2;
        if axis > start && axis < start + span {
            lo = lo.min(point(axis));
            hi = hi.max(point(axis));
        }
    }
    (lo, hi)
}

/// Relative slack when testing a candidate direction against a vertex's constraints (keeps
/// directions that rounding puts a hair outside: the region can only grow).
const CONE_SLACK: f64 = 1e-9;

/// For a cutter with a smooth lower surface (ball, bull nose), the corners of each vertex's
/// normal cone `{d : d·(w - v) <= 0 for every neighbour w, d_z >= 0}`: a cutter touching only
/// the vertex has one contact direction d, and it must lie there or the cutter would cut into a
/// facet. The corners are where two constraint planes meet and all constraints hold. An empty
/// list (a saddle, a pit) means the vertex is never the highest contact; `None` means the fan is
/// too degenerate to tell (visit the whole disk).
fn vertex_cones(mesh: &Mesh, kinds: &[(EdgeFaces, EdgeKind)]) -> Vec<Option<Vec<DVec3>>> {
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
    let mut constraints = Vec::new();
    (0..v.len())
        .map(|k| {
            constraints.clear();
            constraints.extend_from_slice(&directions[start[k]..start[k + 1]]);
            if constraints.len() < 3 {
                return None;
            }
            constraints.push(DVec3::NEG_Z); // d_z >= 0
            let holds = |d: DVec3| constraints.iter().all(|c| d.dot(*c) <= CONE_SLACK);
            let mut corners = Vec::new();
            for (i, ci) in constraints.iter().enumerate() {
                for cj in &constraints[i + 1..] {
                    let Some(d) = ci.cross(*cj).try_normalize() else { continue };
                    for d in [d, -d] {
                        if holds(d) {
                            corners.push(d);
                        }
                    }
                }
            }
            Some(corners)
        })
        .collect()
}

/// For each vertex, the normals of its facets when it is locally convex (so that its normal
/// cone is their spherical hull): interior to a manifold fan, every edge a ridge, and the fan's
/// facets winding the same way in projection (no fold). `None`: visit the whole disk.
fn vertex_reaches(mesh: &Mesh, kinds: &[(EdgeFaces, EdgeKind)], up: &[Option<DVec3>]) -> Vec<Option<Vec<DVec3>>> {
    let n = mesh.vertices.len();
    let mut convex = vec![true; n];
    let mut ridges = vec![0u32; n];
    for (e, kind) in kinds {
        let ridge = matches!(kind, EdgeKind::Ridge(..));
        for &v in &e.edge {
            convex[v as usize] &= ridge;
            ridges[v as usize] += ridge as u32;
        }
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
            (convex[v] && ridges[v] as usize == fans[v].len() && fans[v].len() >= 3)
                .then(|| fans[v].iter().map(|&f| up[f as usize].unwrap()).collect())
        })
        .collect()
}

/// The unit normal of a facet turned upward, or `None` for a vertical or degenerate facet.
fn up_normal(mesh: &Mesh, face: usize, tolerances: &Tolerances) -> Option<DVec3> {
    let n = mesh.triangle(face).cross().try_normalize()?;
    let n = if n.z < 0.0 { -n } else { n };
    (n.z > tolerances.normal).then_some(n)
}

/// Classifies an edge by its two facets (normals turned upward): a valley when each facet's far
/// corner lies on or above the other's plane, a ridge when each lies below.
fn edge_kind(mesh: &Mesh, e: &EdgeFaces, up: &[Option<DVec3>]) -> EdgeKind {
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

#[inline]
fn raise(field: &mut HeightField, i: usize, j: usize, z: f64) {
    let cell = &mut field.z[j * field.nx + i];
    if z > *cell {
        *cell = z;
    }
}

#[inline]
fn for_nodes_in_box(grid: &Grid, lo: DVec2, hi: DVec2, f: &mut impl FnMut(usize, usize, DVec2)) {
    let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(lo.x, hi.x), grid.rows(lo.y, hi.y)) else { return };
    for j in j0..=j1 {
        for i in i0..=i1 {
            f(i, j, grid.node(i, j));
        }
    }
}

#[inline]
fn for_nodes_in_disk(grid: &Grid, center: DVec2, radius: f64, f: &mut impl FnMut(usize, usize, DVec2)) {
    let Some((j0, j1)) = grid.rows(center.y - radius, center.y + radius) else { return };
    for j in j0..=j1 {
        let dy = grid.node(0, j).y - center.y;
        let half = (radius * radius - dy * dy).max(0.0).sqrt();
        let Some((i0, i1)) = grid.columns(center.x - half, center.x + half) else { continue };
        for i in i0..=i1 {
            f(i, j, grid.node(i, j));
        }
    }
}

