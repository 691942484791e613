//! Seed 001 §3.3, the exact CL z-map: the cutter is dropped onto every facet (the offset facet,
//! eq. 2), every edge and every vertex of the mesh, each rasterised over just the nodes it can
//! affect, and the heights are max-combined. The edges and vertices are the paper's
//! "singularities" (gaps and twists of the offset surface, §2.2): dropping onto them fills the
//! gaps, and taking the maximum removes the twists.
//!
//! Steps, in order:
//! 1. facets: the nodes whose contact point falls in the facet are the facet's projection
//!    shifted against its uphill direction by `R - a + a |n_xy|`;
//! 2. vertices: each vertex once, over the nodes within R of it;
//! 3. edges: each edge shared by two facets once, over the nodes within R of it, skipped at a
//!    node where a cheap upper bound shows it cannot rise above what steps 1 and 2 found.
//!    Concave edges (valleys) are skipped whole: a cutter resting on a valley's edge already
//!    cuts into one of its two upward facets, whose own drops stand higher, so a valley edge is
//!    never the highest contact (only ridges are the paper's "gaps").

use super::{Grid, HeightField};
use crate::cutter::{FacetPlane, Profile};
use crate::error::{Error, Result};
use crate::geom::{DVec2, Tolerances};
use crate::mesh::Mesh;
use crate::progress::Progress;

/// How many features are handled between two progress reports.
const REPORT_EVERY: usize = 4096;

/// Builds the CL z-map of `profile` over `mesh`; nodes the cutter cannot reach the part from
/// hold `floor`.
pub fn cl_exact(mesh: &Mesh, profile: &Profile, grid: Grid, floor: f64, tolerances: &Tolerances, progress: &mut Progress) -> Result<HeightField> {
    let mut field = grid.filled(floor);
    let edges: Vec<[u32; 2]> = mesh.edges_with_faces().into_iter().filter(|(e, f)| !is_valley(mesh, *e, f, tolerances)).map(|(e, _)| e).collect();
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
        for_nodes_in_box(&grid, lo, hi, |i, j, c| {
            if let Some(z) = profile.drop_facet(c, &facet) {
                raise(&mut field, i, j, z);
            }
        });
    }

    let v = &mesh.vertices;
    for &p in v {
        tick(done, progress)?;
        done += 1;
        for_nodes_in_disk(&grid, p.truncate(), profile.radius, |i, j, c| {
            if let Some(z) = profile.drop_vertex(c, p) {
                raise(&mut field, i, j, z);
            }
        });
    }
    for [a, b] in edges {
        tick(done, progress)?;
        done += 1;
        let (p, q) = (v[a as usize], v[b as usize]);
        let r = DVec2::splat(profile.radius);
        let lo = p.truncate().min(q.truncate()) - r;
        let hi = p.truncate().max(q.truncate()) + r;
        for_nodes_in_box(&grid, lo, hi, |i, j, c| {
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

/// Whether the edge joins exactly two upward-facing facets each of whose far corner lies on or
/// above the other's plane.
fn is_valley(mesh: &Mesh, edge: [u32; 2], faces: &[u32], tolerances: &Tolerances) -> bool {
    let [f1, f2] = faces else { return false };
    let v = &mesh.vertices;
    let far = |f: u32| mesh.faces[f as usize].into_iter().find(|k| !edge.contains(k)).map(|k| v[k as usize]);
    let up_normal = |f: u32| {
        let t = mesh.triangle(f as usize);
        let n = t.cross().try_normalize()?;
        let n = if n.z < 0.0 { -n } else { n };
        (n.z > tolerances.normal).then_some(n)
    };
    let a = v[edge[0] as usize];
    match (far(*f1), far(*f2), up_normal(*f1), up_normal(*f2)) {
        (Some(c1), Some(c2), Some(n1), Some(n2)) => (c2 - a).dot(n1) >= 0.0 && (c1 - a).dot(n2) >= 0.0,
        _ => false,
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
fn for_nodes_in_box(grid: &Grid, lo: DVec2, hi: DVec2, mut f: impl FnMut(usize, usize, DVec2)) {
    let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(lo.x, hi.x), grid.rows(lo.y, hi.y)) else { return };
    for j in j0..=j1 {
        for i in i0..=i1 {
            f(i, j, grid.node(i, j));
        }
    }
}

#[inline]
fn for_nodes_in_disk(grid: &Grid, center: DVec2, radius: f64, mut f: impl FnMut(usize, usize, DVec2)) {
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

