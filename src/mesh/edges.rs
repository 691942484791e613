//! A part's sharp top edges (issue 40's chamfer): where a horizontal face meets a steep wall
//! that falls away from it, found from the triangles. The horizontal facets are grouped into
//! flats (joined across shared edges, at one height); each flat's boundary is chained into
//! loops, and a loop is sharp when every one of its edges drops down a steep wall (a rounded or
//! bevelled edge, a step up to a higher face, or the mesh's open boundary is not); loops with no
//! such edge at all (a pocket's floor) are left out.

use crate::drawing::Loop;
use crate::geom::{DVec2, DVec3};
use crate::mesh::{union_root, Mesh};

/// A facet is a flat's when its upward normal is within this of vertical (cos 2°).
const FLAT_NORMAL_Z: f64 = 0.9994;
/// A wall is steep when its normal's vertical part is under this (the wall within 30° of
/// vertical).
const WALL_NORMAL_Z: f64 = 0.5;
/// Facets of one flat lie within this height of each other (mm).
const FLAT_HEIGHT: f64 = 1e-4;

/// One loop of a flat's boundary.
#[derive(Clone, Debug)]
pub struct TopEdge {
    /// The flat's height (mm).
    pub z: f64,
    /// Which flat it bounds (flats numbered from the highest).
    pub flat: usize,
    /// The loop, in plan.
    pub outline: Loop,
    /// Every edge of it drops down a steep wall: an edge a chamfer can break.
    pub sharp: bool,
}

/// The boundary loops of the part's horizontal faces that drop down a steep wall somewhere,
/// highest flat first, those that do all round marked sharp.
pub fn top_edges(mesh: &Mesh) -> Vec<TopEdge> {
    let normal = |f: usize| {
        let t = mesh.triangle(f);
        (t.b - t.a).cross(t.c - t.a).normalize_or_zero()
    };
    let normals: Vec<DVec3> = (0..mesh.faces.len()).map(normal).collect();
    let flat = |f: usize| normals[f].z >= FLAT_NORMAL_Z;
    let height = |f: usize| mesh.triangle(f).a.z;
    // Flats: union-find over edges shared by two flat facets at one height.
    let edges = mesh.edges_with_faces();
    let mut parent: Vec<usize> = (0..mesh.faces.len()).collect();
    for e in &edges {
        let [a, b] = e.faces.map(|f| f as usize);
        if e.count == 2 && flat(a) && flat(b) && (height(a) - height(b)).abs() <= FLAT_HEIGHT {
            let (ra, rb) = (union_root(&mut parent, a), union_root(&mut parent, b));
            parent[ra] = rb;
        }
    }
    // Each flat's boundary edges, directed with the flat on their left (the facet's winding
    // seen from above), with whether they drop down a steep wall.
    let mut boundary: std::collections::BTreeMap<usize, Vec<(u32, u32, bool)>> = std::collections::BTreeMap::new();
    for e in &edges {
        let faces: Vec<usize> = e.faces[..(e.count as usize).min(2)].iter().map(|&f| f as usize).collect();
        for (k, &f) in faces.iter().enumerate() {
            if !flat(f) {
                continue;
            }
            let other = faces.get(1 - k).copied();
            if other.is_some_and(|o| flat(o) && union_root(&mut parent, o) == union_root(&mut parent, f)) {
                continue;
            }
            // The edge as the facet runs it (counter-clockwise from above: the facet on its left).
            let face = mesh.faces[f];
            let at = |v: u32| face.iter().position(|&w| w == v).expect("the edge's vertex is the face's");
            let [p, q] = e.edge;
            let (from, to) = if (at(p) + 1) % 3 == at(q) { (p, q) } else { (q, p) };
            let sharp = e.count == 2
                && other.is_some_and(|o| {
                    let far = mesh.faces[o].into_iter().find(|v| !e.edge.contains(v)).map(|v| mesh.vertices[v as usize].z);
                    normals[o].z.abs() < WALL_NORMAL_Z && far.is_some_and(|z| z < height(f) - FLAT_HEIGHT)
                });
            boundary.entry(union_root(&mut parent, f)).or_default().push((from, to, sharp));
        }
    }
    let mut out = Vec::new();
    let mut flats: Vec<(f64, Vec<(u32, u32, bool)>)> = boundary.into_iter().map(|(f, b)| (height(f), b)).collect();
    crate::geom::sort::sort_by_float(&mut flats, |a| -a.0);
    for (n, (z, directed)) in flats.into_iter().enumerate() {
        let mut next: std::collections::HashMap<u32, Vec<usize>> = std::collections::HashMap::new();
        for (k, &(from, _, _)) in directed.iter().enumerate() {
            next.entry(from).or_default().push(k);
        }
        let mut used = vec![false; directed.len()];
        for start in 0..directed.len() {
            if used[start] {
                continue;
            }
            let (mut points, mut sharp, mut any, mut k) = (Vec::new(), true, false, start);
            let closed = loop {
                used[k] = true;
                let (from, to, s) = directed[k];
                points.push(mesh.vertices[from as usize].truncate());
                sharp &= s;
                any |= s;
                match next.get(&to).and_then(|ks| ks.iter().copied().find(|&j| !used[j])) {
                    Some(j) => k = j,
                    None => break directed[k].1 == directed[start].0,
                };
            };
            // (A loop with no edge down a wall, a pocket's floor or a near-level patch of a
            // curved surface, is no edge to break: not listed.)
            if closed && any && points.len() >= 3 {
                out.push(TopEdge { z, flat: n, outline: Loop::polygon(&simplified(&points)), sharp });
            }
        }
    }
    out
}

/// `points` (a closed loop) without the points that lie on the line through their neighbours
/// (a flat's facets split its straight edges).
fn simplified(points: &[DVec2]) -> Vec<DVec2> {
    let n = points.len();
    let keep: Vec<DVec2> = (0..n)
        .filter(|&i| {
            let (a, p, b) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            (p - a).perp_dot(b - p).abs() > 1e-9 * (p - a).length().max(1.0) * (b - p).length().max(1.0) || (p - a).dot(b - p) < 0.0
        })
        .map(|i| points[i])
        .collect();
    if keep.len() >= 3 {
        keep
    } else {
        points.to_vec()
    }
}
