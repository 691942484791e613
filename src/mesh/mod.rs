//! Triangle meshes: the part as swarf sees it, in millimetres with Z up.
//!
//! Every importer hands its triangles to [`Mesh::from_triangles`], which checks coordinates,
//! drops degenerate triangles (counting them) and welds identical vertices, so that edges
//! shared by two facets are stored once (the exact CL builder visits each edge once).

pub mod import;
pub mod placement;
pub mod sample;

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

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub vertices: Vec<DVec3>,
    pub faces: Vec<[u32; 3]>,
    /// Triangles dropped at import because their area was below the tolerance.
    pub dropped_degenerate: usize,
    /// The file's format states its unit as metres (glTF, by its specification); others say
    /// nothing and are taken as millimetres unless the user says otherwise.
    pub in_metres: bool,
}

impl Mesh {
    /// Builds a mesh from loose triangles: rejects non-finite coordinates, drops degenerate
    /// triangles, welds bitwise-identical vertices.
    pub fn from_triangles(triangles: impl IntoIterator<Item = [DVec3; 3]>, tolerances: &Tolerances) -> Result<Mesh, ImportError> {
        let mut mesh = Mesh::default();
        let mut index: HashMap<[u64; 3], u32> = HashMap::new();
        let mut seen = 0usize;
        for (i, tri) in triangles.into_iter().enumerate() {
            seen += 1;
            if let Some(bad) = tri.iter().find(|v| !v.is_finite()) {
                return Err(ImportError::NonFinite { triangle: i, value: format!("{bad}") });
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
