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
//!    for a flat end, the hull of the facets' normals at locally convex vertices, and only the
//!    rim at vertices with a higher neighbour;
//! 3. edges: each edge shared by two facets once, over the nodes within R of it, skipped at a
//!    node where a cheap upper bound shows it cannot rise above what steps 1 and 2 found.
//!    A cutter touching an edge at an interior point with contact direction d (from the contact
//!    into the cutter) cuts into an adjacent facet unless d lies in the edge's normal cone, the
//!    arc between the two facets' normals; then that facet's own features stand higher. So a
//!    concave edge (a valley, whose cone is empty) is skipped whole, and a convex edge (a
//!    ridge: the paper's "gap") visits only the nodes its cone's offsets can reach — a thin
//!    strip on a smooth surface instead of the whole disk of radius R.

use std::sync::atomic::{AtomicBool, Ordering};

use super::cone::{edge_kinds, edge_regions, vertex_cones, vertex_reaches, EdgeRegion, VertexReach, REGION_MARGIN};
use super::{Grid, HeightField};
use crate::cutter::{FacetPlane, Profile};
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3, Tolerances};
use crate::mesh::Mesh;
use crate::parallel;
use crate::progress::Progress;

/// How many features are handled between two progress reports.
const REPORT_EVERY: usize = 4096;

/// The mesh's features, each with the box of nodes it can decide.
struct Features {
    facets: Vec<(FacetPlane, DVec2, DVec2)>,
    /// A vertex, and the nodes it can decide.
    vertices: Vec<(DVec3, VertexReach)>,
    edges: Vec<EdgeRegion>,
}

impl Features {
    fn new(mesh: &Mesh, profile: &Profile, tolerances: &Tolerances) -> Features {
        let margin = DVec2::splat(REGION_MARGIN * (1.0 + profile.radius));
        let facets = mesh
            .triangles()
            .filter_map(|t| {
                let facet = FacetPlane::new(t.a, t.b, t.c, tolerances.normal)?;
                let shift = facet.uphill * profile.plane_contact(facet.slope_sin, facet.normal.z);
                let b = t.bounds();
                Some((facet, b.min.truncate() - shift, b.max.truncate() - shift))
            })
            .collect();
        let (up, kinds) = edge_kinds(mesh, tolerances);
        // A cone's tip and rims are edges of its lower surface, with a fan of normals each:
        // the normal cones' arguments (one contact direction shared by the cutter and the
        // feature) do not hold there, so every vertex reaches its whole disk.
        let reach = if profile.is_cone() {
            vec![VertexReach::Disk; mesh.vertices.len()]
        } else if profile.corner > 0.0 {
            vertex_cones(mesh, &kinds, profile)
        } else {
            vertex_reaches(mesh, &kinds, &up, profile)
        };
        let v = &mesh.vertices;
        let vertices = v
            .iter()
            .zip(&reach)
            .filter_map(|(&p, reach)| match *reach {
                VertexReach::Never => None,
                VertexReach::Offsets(lo, hi) => Some((p, VertexReach::Offsets(p.truncate() + lo - margin, p.truncate() + hi + margin))),
                other => Some((p, other)),
            })
            .collect();
        let edges = edge_regions(mesh, &kinds, profile);
        Features { facets, vertices, edges }
    }

    fn count(&self) -> usize {
        self.facets.len() + self.vertices.len() + self.edges.len()
    }
}

/// Builds the CL z-map of `profile` over `mesh`; nodes the cutter cannot reach the part from
/// hold `floor`. Natively the rows are split into one band per core.
pub fn cl_exact(mesh: &Mesh, profile: &Profile, grid: Grid, floor: f64, tolerances: &Tolerances, progress: &mut Progress) -> Result<HeightField> {
    ExactBuilder::new(mesh, profile, tolerances).field(grid, floor, progress)
}

/// The exact builder with the mesh's features prepared for one cutter: it fills the whole grid
/// ([`ExactBuilder::field`], a band of rows per core) or any band of its rows
/// ([`ExactBuilder::rows`], what a worker of the page's pool computes; every node's height is
/// the same whichever band holds it).
pub struct ExactBuilder {
    features: Features,
    profile: Profile,
}

impl ExactBuilder {
    pub fn new(mesh: &Mesh, profile: &Profile, tolerances: &Tolerances) -> ExactBuilder {
        ExactBuilder { features: Features::new(mesh, profile, tolerances), profile: *profile }
    }

    /// The whole CL z-map on `grid`, `floor` where no feature reaches.
    pub fn field(&self, grid: Grid, floor: f64, progress: &mut Progress) -> Result<HeightField> {
        let mut field = grid.filled(floor);
        let bands = parallel::threads();
        let rows = grid.ny.div_ceil(bands).max(1);
        let cancelled = AtomicBool::new(false);
        let mut chunks = field.z.chunks_mut(rows * grid.nx).enumerate();
        let (_, first) = chunks.next().expect("a grid has a row");
        let result = std::thread::scope(|scope| {
            for (k, chunk) in chunks {
                let cancelled = &cancelled;
                scope.spawn(move || fill(&self.features, &self.profile, &grid, k * rows, chunk, cancelled, None));
            }
            fill(&self.features, &self.profile, &grid, 0, first, &cancelled, Some(progress))
        });
        result.map(|()| field)
    }

    /// The heights of rows `rows` of the CL z-map on `grid` (row after row, `floor` where no
    /// feature reaches).
    pub fn rows(&self, grid: Grid, floor: f64, rows: std::ops::Range<usize>, progress: &mut Progress) -> Result<Vec<f64>> {
        let rows = rows.start.min(grid.ny)..rows.end.min(grid.ny);
        let mut band = vec![floor; rows.len() * grid.nx];
        fill(&self.features, &self.profile, &grid, rows.start, &mut band, &AtomicBool::new(false), Some(progress))?;
        Ok(band)
    }
}

/// Drops every feature onto the nodes of rows `j0..` held in `band`; stops when `cancelled`.
fn fill(features: &Features, profile: &Profile, grid: &Grid, j0: usize, band: &mut [f64], cancelled: &AtomicBool, mut progress: Option<&mut Progress>) -> Result<()> {
    let j1 = j0 + band.len() / grid.nx;
    let total = features.count() as f64;
    let mut done = 0usize;
    let mut tick = |done: &mut usize| -> Result<()> {
        *done += 1;
        if *done % REPORT_EVERY == 0 {
            if let Some(p) = progress.as_deref_mut() {
                if !p.report(*done as f64 / total) {
                    cancelled.store(true, Ordering::Relaxed);
                }
            }
            if cancelled.load(Ordering::Relaxed) {
                return Err(Error::Cancelled);
            }
        }
        Ok(())
    };
    let at = |i: usize, j: usize| (j - j0) * grid.nx + i;

    for (facet, lo, hi) in &features.facets {
        tick(&mut done)?;
        for_nodes_in_box(grid, *lo, *hi, j0, j1, &mut |i, j, c| {
            if let Some(z) = profile.drop_facet(c, facet) {
                let cell = &mut band[at(i, j)];
                *cell = cell.max(z);
            }
        });
    }
    for &(p, reach) in &features.vertices {
        tick(&mut done)?;
        let mut visit = |i: usize, j: usize, c: DVec2| {
            let cell = &mut band[at(i, j)];
            let r2 = (p.truncate() - c).length_squared();
            // The drop is v.z - height(r): it cannot beat the cell where the cutter has risen
            // by the difference.
            if r2 <= profile.radius * profile.radius && r2 < profile.reach_squared(p.z - *cell) {
                *cell = cell.max(p.z - profile.height(r2.sqrt()));
            }
        };
        match reach {
            VertexReach::Disk => for_nodes_in_disk(grid, p.truncate(), profile.radius, 0.0, j0, j1, &mut visit),
            VertexReach::Rim => {
                let inner = profile.radius - REGION_MARGIN * (1.0 + profile.radius);
                for_nodes_in_disk(grid, p.truncate(), profile.radius, inner, j0, j1, &mut visit)
            }
            VertexReach::Offsets(lo, hi) => for_nodes_in_box(grid, lo, hi, j0, j1, &mut visit),
            VertexReach::Never => {}
        }
    }
    for e in &features.edges {
        tick(&mut done)?;
        for_nodes_in_box(grid, e.lo, e.hi, j0, j1, &mut |i, j, c| {
            let cell = &mut band[at(i, j)];
            if let Some(z) = profile.drop_edge_above(c, e.p, e.q, *cell) {
                *cell = cell.max(z);
            }
        });
    }
    Ok(())
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

#[inline]
/// Calls `f` for the nodes in the box whose row lies in `rows_from..rows_to`.
fn for_nodes_in_box(grid: &Grid, lo: DVec2, hi: DVec2, rows_from: usize, rows_to: usize, f: &mut impl FnMut(usize, usize, DVec2)) {
    let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(lo.x, hi.x), grid.rows(lo.y, hi.y)) else { return };
    for j in j0.max(rows_from)..=j1.min(rows_to.saturating_sub(1)) {
        for i in i0..=i1 {
            f(i, j, grid.node(i, j));
        }
    }
}

#[inline]
/// Calls `f` for the nodes at a distance from `center` between `inner` (roughly: the nodes
/// just inside it may come too) and `radius`, whose row lies in `rows_from..rows_to`.
fn for_nodes_in_disk(grid: &Grid, center: DVec2, radius: f64, inner: f64, rows_from: usize, rows_to: usize, f: &mut impl FnMut(usize, usize, DVec2)) {
    let Some((j0, j1)) = grid.rows(center.y - radius, center.y + radius) else { return };
    for j in j0.max(rows_from)..=j1.min(rows_to.saturating_sub(1)) {
        let dy = grid.node(0, j).y - center.y;
        let half = (radius * radius - dy * dy).max(0.0).sqrt();
        let hole = if inner > 0.0 && dy.abs() < inner { (inner * inner - dy * dy).sqrt() } else { -1.0 };
        let mut run = |lo: f64, hi: f64| {
            if let Some((i0, i1)) = grid.columns(lo, hi) {
                for i in i0..=i1 {
                    f(i, j, grid.node(i, j));
                }
            }
        };
        if hole > 0.0 {
            run(center.x - half, center.x - hole);
            run(center.x + hole, center.x + half);
        } else {
            run(center.x - half, center.x + half);
        }
    }
}
