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
        let starts = self.bands(&grid, parallel::threads());
        let cancelled = AtomicBool::new(false);
        // The bands' slices of the field, the first for this thread.
        let mut chunks = Vec::with_capacity(starts.len());
        let mut rest: &mut [f64] = &mut field.z;
        for (k, &j0) in starts.iter().enumerate() {
            let j1 = starts.get(k + 1).copied().unwrap_or(grid.ny);
            let (band, after) = rest.split_at_mut((j1 - j0) * grid.nx);
            chunks.push((j0, band));
            rest = after;
        }
        let mut chunks = chunks.into_iter();
        let (_, first) = chunks.next().expect("a grid has a row");
        let result = std::thread::scope(|scope| {
            for (j0, chunk) in chunks {
                let cancelled = &cancelled;
                scope.spawn(move || fill(&self.features, &self.profile, &grid, j0, chunk, cancelled, None));
            }
            fill(&self.features, &self.profile, &grid, 0, first, &cancelled, Some(progress))
        });
        result.map(|()| field)
    }

    /// The first rows of `count` bands of `grid` (the first 0) that take about the same work:
    /// each feature's nodes counted over the rows of its box, as many in each row (its box's
    /// columns), and each row's own nodes. Equal bands of rows were uneven where the part is:
    /// on mount_rush at 0.1 mm one took 0.032 s and the other 0.083 s.
    fn bands(&self, grid: &Grid, count: usize) -> Vec<usize> {
        let count = count.clamp(1, grid.ny.max(1));
        if count == 1 {
            return vec![0];
        }
        // Work per row as differences: +w where a box's rows begin, -w after they end.
        let mut change = vec![0.0f64; grid.ny + 1];
        let mut add = |lo: DVec2, hi: DVec2| {
            if let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(lo.x, hi.x), grid.rows(lo.y, hi.y)) {
                let w = (i1 - i0 + 1) as f64;
                change[j0] += w;
                change[j1 + 1] -= w;
            }
        };
        let f = &self.features;
        for (_, lo, hi) in &f.facets {
            add(*lo, *hi);
        }
        let r = DVec2::splat(self.profile.radius);
        for &(p, reach) in &f.vertices {
            match reach {
                VertexReach::Offsets(lo, hi) => add(lo, hi),
                VertexReach::Never => {}
                _ => add(p.truncate() - r, p.truncate() + r),
            }
        }
        for e in &f.edges {
            add(e.lo, e.hi);
        }
        let mut work = Vec::with_capacity(grid.ny);
        let mut running = 0.0;
        for c in &change[..grid.ny] {
            running += c;
            work.push(running + grid.nx as f64);
        }
        let total: f64 = work.iter().sum();
        let mut starts = vec![0];
        let mut done = 0.0;
        for (j, w) in work.iter().enumerate() {
            if done >= total * starts.len() as f64 / count as f64 && starts.len() < count && j > *starts.last().expect("a first band") {
                starts.push(j);
            }
            done += w;
        }
        starts
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
        // No point of the edge stands above its top, nor its drop: where a node already stands
        // there, the edge cannot raise it (most nodes of a smooth part, whose facets decide).
        let top = e.p.z.max(e.q.z);
        for_nodes_near_edge(grid, e, profile.radius, j0, j1, &mut |i, j, c| {
            let cell = &mut band[at(i, j)];
            if top <= *cell {
                return;
            }
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

/// Calls `f` for the nodes of rows `rows_from..rows_to` where the edge `e` may decide: in its
/// box, and in each row only between the ends of where two convex sets meet the row (an edge's
/// drop needs both): the edge swept by its offsets' box (the tip stands at a point of the edge
/// plus an offset of its normal cone, [`EdgeRegion`]), and the capsule of the cutter's radius
/// about it (farther, the cutter does not reach it). A diagonal edge's box holds many nodes
/// neither reaches (on mount_rush at 0.1 mm, 93 % of the box's nodes were turned away by the
/// drop itself). An edge vertical in plan is never visited: its top vertex decides.
fn for_nodes_near_edge(grid: &Grid, e: &EdgeRegion, radius: f64, rows_from: usize, rows_to: usize, f: &mut impl FnMut(usize, usize, DVec2)) {
    let (p, q) = (e.p.truncate(), e.q.truncate());
    let d = q - p;
    if d.length_squared() <= 0.0 {
        return;
    }
    let Some((j0, j1)) = grid.rows(e.lo.y, e.hi.y) else { return };
    // The capsule's straight part, a rectangle (a little wide against rounding: the drop
    // itself decides at its rim).
    let reach = radius + REGION_MARGIN * (1.0 + radius);
    let n = d.perp().normalize() * reach;
    let rectangle = [p + n, q + n, q - n, p - n];
    for j in j0.max(rows_from)..=j1.min(rows_to.saturating_sub(1)) {
        let y = grid.node(0, j).y;
        // The edge's points whose offsets reach the row, and so the row's span.
        let (below, above) = (y - e.offset_hi.y, y - e.offset_lo.y);
        let (t0, t1) = if d.y != 0.0 {
            let (a, b) = ((below - p.y) / d.y, (above - p.y) / d.y);
            (a.min(b).max(0.0), a.max(b).min(1.0))
        } else if p.y >= below && p.y <= above {
            (0.0, 1.0)
        } else {
            continue;
        };
        if t0 > t1 {
            continue;
        }
        let (xa, xb) = (p.x + d.x * t0, p.x + d.x * t1);
        let (mut lo, mut hi) = ((xa.min(xb) + e.offset_lo.x).max(e.lo.x), (xa.max(xb) + e.offset_hi.x).min(e.hi.x));
        // The capsule's span: its end disks' and its rectangle's.
        let (mut c_lo, mut c_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for end in [p, q] {
            let dy = y - end.y;
            if dy.abs() <= reach {
                let half = (reach * reach - dy * dy).sqrt();
                (c_lo, c_hi) = (c_lo.min(end.x - half), c_hi.max(end.x + half));
            }
        }
        for k in 0..4 {
            let (u, v) = (rectangle[k], rectangle[(k + 1) % 4]);
            if (u.y - y) * (v.y - y) <= 0.0 {
                let x = if u.y == v.y {
                    (u.x, v.x)
                } else {
                    let x = u.x + (y - u.y) / (v.y - u.y) * (v.x - u.x);
                    (x, x)
                };
                (c_lo, c_hi) = (c_lo.min(x.0.min(x.1)), c_hi.max(x.0.max(x.1)));
            }
        }
        lo = lo.max(c_lo);
        hi = hi.min(c_hi);
        if let Some((i0, i1)) = grid.columns(lo, hi) {
            for i in i0..=i1 {
                f(i, j, grid.node(i, j));
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::Cutter;
    use crate::mesh::sample::{demo_part, height_field_solid};

    /// Whether some point of the edge plus an offset within `[lo, hi]` is `c`: the segment
    /// clipped to the box `c - hi ..= c - lo` (Liang–Barsky).
    fn swept_to(e: &EdgeRegion, c: DVec2) -> bool {
        let (p, d) = (e.p.truncate(), (e.q - e.p).truncate());
        let (lo, hi) = (c - e.offset_hi, c - e.offset_lo);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (start, step, min, max) in [(p.x, d.x, lo.x, hi.x), (p.y, d.y, lo.y, hi.y)] {
            if step == 0.0 {
                if start < min || start > max {
                    return false;
                }
                continue;
            }
            let (a, b) = ((min - start) / step, (max - start) / step);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        t0 <= t1
    }

    /// The rows' spans visit every node of an edge's box that the edge's offsets reach and
    /// its drop touches, for every cutter on a part with ridges, valleys, walls and a rough
    /// top, and a good share fewer nodes than the box holds.
    #[test]
    fn the_nodes_near_an_edge_hold_every_node_it_can_decide() {
        let rough = height_field_solid(DVec2::ZERO, DVec2::splat(12.0), 9, 7, 0.0, |x, y| 4.0 + (0.9 * x).sin() * 1.5 + (1.3 * y).cos() + 0.1 * x);
        let tolerances = Tolerances::default();
        let (mut boxed, mut visited) = (0usize, 0usize);
        for mesh in [demo_part(), rough] {
            for cutter in [Cutter::flat(6.0), Cutter::ball(6.0), Cutter::bull_nose(6.0, 1.0), Cutter::v_bit(6.0, 90.0, 0.0)] {
                let builder = ExactBuilder::new(&mesh, &cutter.profile(), &tolerances);
                let b = mesh.bounds();
                let grid = Grid::covering(b.min.truncate() - 4.0, b.max.truncate() + 4.0, 0.37);
                for e in &builder.features.edges {
                    let mut near = std::collections::HashSet::new();
                    for_nodes_near_edge(&grid, e, builder.profile.radius, 0, grid.ny, &mut |i, j, _| {
                        near.insert((i, j));
                    });
                    visited += near.len();
                    for_nodes_in_box(&grid, e.lo, e.hi, 0, grid.ny, &mut |i, j, c| {
                        boxed += 1;
                        if swept_to(e, c) && builder.profile.drop_edge_above(c, e.p, e.q, f64::NEG_INFINITY).is_some() {
                            assert!(near.contains(&(i, j)), "{cutter:?}: edge {} – {} decides at {c} but the spans skip it", e.p, e.q);
                        }
                    });
                }
            }
        }
        assert!(visited * 10 < boxed * 9, "{visited} of {boxed}");
    }
}
