//! Triangle meshes: the part as swarf sees it, in millimetres with Z up.
//!
//! Every importer hands its triangles to [`Mesh::from_triangles`], which checks coordinates,
//! drops degenerate triangles (counting them) and welds identical vertices, so that edges
//! shared by two facets are stored once (the exact CL builder visits each edge once).

pub mod edges;
pub mod import;
pub mod placement;
pub mod sample;
pub mod section;

use std::collections::HashMap;

use crate::geom::{Aabb, DVec3, Tolerances, Triangle};
use import::ImportError;

/// An edge (vertex indices, smaller first) and the faces that share it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeFaces {
    pub edge: [u32; 2],
    /// The first two faces; the second is `u32::MAX` on a boundary edge.
    pub faces: [u32; 2],
    /// How many faces share the edge.
    pub count: u8,
}

/// The root of `k`'s set in a union-find forest (`parent[k] == k` at a root), halving the path
/// on the way: how facets are joined into walls and faces.
pub(crate) fn union_root(parent: &mut [usize], mut k: usize) -> usize {
    while parent[k] != k {
        parent[k] = parent[parent[k]];
        k = parent[k];
    }
    k
}

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub vertices: Vec<DVec3>,
    pub faces: Vec<[u32; 3]>,
    /// Triangles dropped at import because their area was below the tolerance.
    pub dropped_degenerate: usize,
    /// Triangles dropped at import because the file held the same triangle (the same three
    /// vertices) before: a copy adds nothing to the part and only slows every operation.
    pub dropped_duplicates: usize,
    /// The file's format states its unit as metres (glTF, by its specification); others say
    /// nothing and are taken as millimetres unless the user says otherwise.
    pub in_metres: bool,
}

impl Mesh {
    /// Builds a mesh from loose triangles: rejects non-finite coordinates and coordinates
    /// beyond [`crate::limits::MAX_COORDINATE`], drops degenerate triangles and copies of a
    /// triangle, welds bitwise-identical vertices.
    pub fn from_triangles(triangles: impl IntoIterator<Item = [DVec3; 3]>, tolerances: &Tolerances) -> Result<Mesh, ImportError> {
        let mut mesh = Mesh::default();
        let mut index: HashMap<[u64; 3], u32> = HashMap::new();
        let mut seen = 0usize;
        let mut faces: std::collections::HashSet<[u32; 3]> = std::collections::HashSet::new();
        for (i, tri) in triangles.into_iter().enumerate() {
            seen += 1;
            if let Some(bad) = tri.iter().find(|v| !v.is_finite()) {
                return Err(ImportError::NonFinite { triangle: i, value: format!("{bad}") });
            }
            if let Some(far) = tri.iter().flat_map(|v| v.to_array()).find(|c| c.abs() > crate::limits::MAX_COORDINATE) {
                return Err(ImportError::OutOfRange { triangle: i + 1, value: crate::limits::shown(far) });
            }
            if Triangle::new(tri[0], tri[1], tri[2]).cross().length() * 0.5 <= tolerances.degenerate_area {
                mesh.dropped_degenerate += 1;
                continue;
            }
            let mut face = [0u32; 3];
            for (k, v) in tri.iter().enumerate() {
                let key = [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
                face[k] = *index.entry(key).or_insert_with(|| {
                    mesh.vertices.push(*v);
                    (mesh.vertices.len() - 1) as u32
                });
            }
            let mut key = face;
            key.sort_unstable();
            if !faces.insert(key) {
                mesh.dropped_duplicates += 1;
                continue;
            }
            mesh.faces.push(face);
        }
        if seen == 0 {
            return Err(ImportError::NoTriangles);
        }
        if mesh.faces.is_empty() {
            return Err(ImportError::AllDegenerate { count: seen });
        }
        Ok(mesh)
    }

    pub fn triangle(&self, face: usize) -> Triangle {
        let [a, b, c] = self.faces[face];
        Triangle::new(self.vertices[a as usize], self.vertices[b as usize], self.vertices[c as usize])
    }

    pub fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.faces.len()).map(|f| self.triangle(f))
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.vertices)
    }

    /// Each undirected edge once, with the faces that share it: the first two, and how many
    /// there are (one on a boundary, three and more where the mesh is not a manifold).
    pub fn edges_with_faces(&self) -> Vec<EdgeFaces> {
        // Half-edges bucketed by their lower vertex (a counting sort), then each small bucket
        // sorted by the upper vertex: the faces of an edge end up side by side.
        let n = self.vertices.len();
        let mut start = vec![0usize; n + 1];
        for f in &self.faces {
            for [a, b] in [[f[0], f[1]], [f[1], f[2]], [f[2], f[0]]] {
                start[a.min(b) as usize + 1] += 1;
            }
        }
        for k in 0..n {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut half = vec![(0u32, 0u32); start[n]]; // (upper vertex, face) in lower-vertex buckets
        for (face, f) in self.faces.iter().enumerate() {
            for [a, b] in [[f[0], f[1]], [f[1], f[2]], [f[2], f[0]]] {
                let low = a.min(b) as usize;
                half[fill[low]] = (a.max(b), face as u32);
                fill[low] += 1;
            }
        }
        let mut out: Vec<EdgeFaces> = Vec::with_capacity(half.len() / 2 + 1);
        for low in 0..n {
            let bucket = &mut half[start[low]..start[low + 1]];
            bucket.sort_unstable();
            for &(high, face) in bucket.iter() {
                let edge = [low as u32, high];
                match out.last_mut() {
                    Some(e) if e.edge == edge => {
                        if e.count < 2 {
                            e.faces[e.count as usize] = face;
                        }
                        e.count = e.count.saturating_add(1);
                    }
                    _ => out.push(EdgeFaces { edge, faces: [face, u32::MAX], count: 1 }),
                }
            }
        }
        out
    }

    /// Holes in a surface that should be closed (a file cut short, a bad export): the edges
    /// that border one triangle only, less those that close against other such edges (a crack
    /// at a T-junction, where one long edge meets a row of short ones along the same line, or a
    /// seam exported as two coincident rings: no gap at all) and less a relief's open side (a
    /// loop running along the rim of the part's outline seen from above around all of it).
    /// Vertices are welded within a millionth of the part's size first. Returns the middles
    /// of the holes' edges.
    pub fn open_edges(&self) -> Vec<DVec3> {
        let b = self.bounds();
        let size = b.size().max_element().max(1e-9);
        let eps = 1e-6 * size;
        let key = |v: DVec3| [(v.x / eps).round() as i64, (v.y / eps).round() as i64, (v.z / eps).round() as i64];
        let mut ids: HashMap<[i64; 3], u32> = HashMap::new();
        let welded: Vec<u32> = self
            .vertices
            .iter()
            .map(|&v| {
                let n = ids.len() as u32;
                *ids.entry(key(v)).or_insert(n)
            })
            .collect();
        let mut position = vec![DVec3::ZERO; ids.len()];
        for (v, &w) in self.vertices.iter().zip(&welded) {
            position[w as usize] = *v;
        }
        // An edge is open where one triangle has it, taken in that triangle's direction.
        let mut count: HashMap<(u32, u32), ((u32, u32), u32)> = HashMap::new();
        for f in &self.faces {
            let f = f.map(|v| welded[v as usize]);
            if f[0] == f[1] || f[1] == f[2] || f[2] == f[0] {
                continue;
            }
            for k in 0..3 {
                let (a, c) = (f[k], f[(k + 1) % 3]);
                count.entry((a.min(c), a.max(c))).or_insert(((a, c), 0)).1 += 1;
            }
        }
        // (In the order of their welded ends, so that the same part says the same every run.)
        let mut open: Vec<(u32, u32)> = count.into_values().filter(|&(_, n)| n == 1).map(|(e, _)| e).collect();
        open.sort_unstable();
        let open: Vec<(DVec3, DVec3)> = open.into_iter().map(|(a, c)| (position[a as usize], position[c as usize])).collect();
        // Open edges by the cells of a 64³ grid over the part they pass through.
        let cell = size / 64.0;
        let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        let cells_of = |(p, q): (DVec3, DVec3)| {
            let n = (p.distance(q) / (0.5 * cell)).ceil() as usize;
            let mut out: Vec<[i64; 3]> = (0..=n).map(|i| p.lerp(q, i as f64 / n.max(1) as f64)).map(|x| ((x - b.min) / cell).floor().as_i64vec3().to_array()).collect();
            out.dedup();
            out
        };
        for (k, &e) in open.iter().enumerate() {
            for c in cells_of(e) {
                cells.entry(c).or_default().push(k);
            }
        }
        let gaps: Vec<(DVec3, DVec3)> = open
            .iter()
            .enumerate()
            .filter(|&(k, &e)| {
                let mut near: Vec<usize> = cells_of(e).iter().flat_map(|c| cells[c].iter().copied()).filter(|&j| j != k).collect();
                near.sort_unstable();
                near.dedup();
                !closed_against(e, near.iter().map(|&j| open[j]), eps)
            })
            .map(|(_, &e)| e)
            .collect();
        // The rest as loops of touching edges (by their welded ends).
        let mut parent: HashMap<[i64; 3], [i64; 3]> = HashMap::new();
        fn root(parent: &mut HashMap<[i64; 3], [i64; 3]>, x: [i64; 3]) -> [i64; 3] {
            let mut r = x;
            while let Some(&p) = parent.get(&r).filter(|&&p| p != r) {
                r = p;
            }
            parent.insert(x, r);
            r
        }
        for &(p, q) in &gaps {
            let (rp, rq) = (root(&mut parent, key(p)), root(&mut parent, key(q)));
            if rp != rq {
                parent.insert(rp, rq);
            }
        }
        let slack = 1e-6 * size.max(1.0);
        let on_rim = |p: DVec3| (p.x - b.min.x).abs() <= slack || (p.x - b.max.x).abs() <= slack || (p.y - b.min.y).abs() <= slack || (p.y - b.max.y).abs() <= slack;
        // Per loop: its area seen from above, whether it runs along the rim all the way, its
        // edges' middles.
        let mut loops: HashMap<[i64; 3], (f64, bool, Vec<DVec3>)> = HashMap::new();
        for &(p, q) in &gaps {
            let l = loops.entry(root(&mut parent, key(p))).or_insert((0.0, true, Vec::new()));
            l.0 += 0.5 * (p.x * q.y - q.x * p.y);
            l.1 &= on_rim(p) && on_rim(q);
            l.2.push((p + q) * 0.5);
        }
        let outline = (b.max.x - b.min.x) * (b.max.y - b.min.y);
        let mut holes: Vec<Vec<DVec3>> = loops.into_values().filter(|(area, rim, _)| !(*rim && area.abs() >= 0.9 * outline)).map(|(_, _, m)| m).collect();
        holes.sort_by(|a, b| a[0].to_array().partial_cmp(&b[0].to_array()).unwrap_or(std::cmp::Ordering::Equal));
        holes.into_iter().flatten().collect()
    }

    /// Applies `f` to every vertex.
    pub fn transform(&mut self, f: impl Fn(DVec3) -> DVec3) {
        for v in &mut self.vertices {
            *v = f(*v);
        }
    }

    /// Binary STL of this mesh (used for the built-in sample and by the CLI).
    pub fn to_binary_stl(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(84 + 50 * self.faces.len());
        let mut header = [0u8; 80];
        header[..21].copy_from_slice(b"swarf binary STL mesh");
        out.extend_from_slice(&header);
        out.extend_from_slice(&(self.faces.len() as u32).to_le_bytes());
        for t in self.triangles() {
            let n = t.normal().unwrap_or(DVec3::Z);
            for v in [n, t.a, t.b, t.c] {
                for c in v.to_array() {
                    out.extend_from_slice(&(c as f32).to_le_bytes());
                }
            }
            out.extend_from_slice(&[0, 0]);
        }
        out
    }
}

/// Whether the open edge `(p, q)` closes against the open edges `others`: those on its line
/// (within `eps`) cover all of its length, as a crack at a T-junction or a doubled seam has them.
fn closed_against((p, q): (DVec3, DVec3), others: impl Iterator<Item = (DVec3, DVec3)>, eps: f64) -> bool {
    let length = p.distance(q);
    if length <= eps {
        return true;
    }
    let dir = (q - p) / length;
    let on_line = |x: DVec3| (x - p - dir * (x - p).dot(dir)).length() <= 10.0 * eps;
    // The parts of its length the others cover, as intervals along it.
    let mut covered: Vec<(f64, f64)> = others
        .filter(|&(a, c)| on_line(a) && on_line(c))
        .map(|(a, c)| {
            let (s, t) = ((a - p).dot(dir), (c - p).dot(dir));
            (s.min(t).max(0.0), s.max(t).min(length))
        })
        .filter(|(s, t)| t > s)
        .collect();
    crate::geom::sort::sort_by_float(&mut covered, |a| a.0);
    let mut reach = 0.0;
    for (s, t) in covered {
        if s > reach + 10.0 * eps {
            return false;
        }
        reach = f64::max(reach, t);
    }
    reach >= length - 10.0 * eps
}
