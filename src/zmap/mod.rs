//! Height fields on a regular XY grid (z-maps), and the builders of seed 001:
//!
//! 1. [`cc::cc_zmap`]: the part's own surface height at each node (the CC z-map).
//! 2. [`cl_inverse::cl_inverse_offset`]: the CL z-map by inverse offset of the CC z-map (§3.1).
//! 3. [`cl_exact::cl_exact`]: the CL z-map by dropping the cutter onto every facet, edge and
//!    vertex of the mesh (§3.3, the offset-facet model with its edge and vertex "singularities"
//!    handled by the same drop).
//!
//! [`drop::PointDrop`] gives the same exact drop at any point, and [`surface::ClSurface`] the
//! surface along a path, between the nodes too. Both CL builders return the lowest safe tip height at every node; nodes the part does not
//! reach hold the floor given when the grid was laid out.

pub mod cc;

pub mod bounds;
pub mod cl_exact;
pub mod cl_inverse;
mod cone;
pub mod contour;
pub mod distance;
pub mod drop;
pub mod io;
pub mod region;
pub mod surface;

use serde::{Deserialize, Serialize};

use crate::geom::DVec2;

/// A regular grid of heights: node (i, j) stands at `origin + (i, j) * spacing`.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightField {
    pub origin: DVec2,
    pub spacing: f64,
    pub nx: usize,
    pub ny: usize,
    /// Row-major heights: `z[j * nx + i]`.
    pub z: Vec<f64>,
}

/// Where a height field's nodes stand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    pub origin: DVec2,
    pub spacing: f64,
    pub nx: usize,
    pub ny: usize,
}

/// Which CL z-map builder an operation uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ClBuilder {
    /// Seed 001 §3.3: exact drop onto facets, edges and vertices.
    #[default]
    Exact,
    /// Seed 001 §3.1: inverse offset of the CC z-map; faster, but it only sees the part at the
    /// grid's nodes, so it sits below the exact surface: on smooth surfaces by the paper's δ
    /// (second order in the spacing s), and where a ball rolls over a wall's top edge that lies
    /// between nodes by up to sqrt(2 R s). For previews and comparison: a path never takes its
    /// heights from it (`surface.rs` drops the cutter exactly wherever the path is).
    InverseOffset,
}

/// Largest number of nodes a grid may have ([`crate::limits::MAX_NODES`]); above it the user is
/// asked for a coarser spacing instead of running out of memory in the browser.
pub use crate::limits::MAX_NODES;

impl Grid {
    /// The grid covering `[min, max]` at `spacing`, or a message a user understands when the
    /// spacing is not a positive number or the grid would exceed [`MAX_NODES`] (counted before
    /// anything is allocated, so a part with a 10¹² mm triangle asks for a coarser grid instead
    /// of overflowing).
    pub fn checked(min: DVec2, max: DVec2, spacing: f64) -> Result<Grid, String> {
        if !(spacing > 0.0 && spacing.is_finite()) {
            return Err(format!("the grid spacing must be a positive number (got {spacing})"));
        }
        if !(min.is_finite() && max.is_finite()) {
            return Err("the part's extent is not finite".into());
        }
        let count = |lo: f64, hi: f64| ((hi - lo) / spacing).ceil().max(0.0) + 1.0;
        let nodes = count(min.x, max.x) * count(min.y, max.y);
        if nodes > MAX_NODES as f64 {
            return Err(format!(
                "a {spacing} mm grid over {:.1} × {:.1} mm needs {:.0} million nodes (at most {} million); choose a coarser grid",
                max.x - min.x,
                max.y - min.y,
                nodes / 1e6,
                MAX_NODES / 1_000_000
            ));
        }
        Ok(Grid::covering(min, max, spacing))
    }

    /// The grid covering `[min, max]` with nodes at `spacing`, the last row and column on or
    /// beyond `max`.
    pub fn covering(min: DVec2, max: DVec2, spacing: f64) -> Grid {
        let count = |lo: f64, hi: f64| (((hi - lo) / spacing).ceil().max(0.0) as usize) + 1;
        Grid { origin: min, spacing, nx: count(min.x, max.x), ny: count(min.y, max.y) }
    }

    pub fn nodes(&self) -> usize {
        self.nx * self.ny
    }

    #[inline]
    pub fn node(&self, i: usize, j: usize) -> DVec2 {
        self.origin + DVec2::new(i as f64, j as f64) * self.spacing
    }

    /// The index (row after row) of the node nearest `p`, or `None` off the grid.
    #[inline]
    pub fn nearest(&self, p: DVec2) -> Option<usize> {
        let u = ((p - self.origin) / self.spacing).round();
        (u.x >= 0.0 && u.y >= 0.0 && (u.x as usize) < self.nx && (u.y as usize) < self.ny).then(|| u.y as usize * self.nx + u.x as usize)
    }

    /// Node indices i with x-coordinate in `[lo, hi]`, or `None`.
    #[inline]
    pub fn columns(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
        span(self.origin.x, self.spacing, self.nx, lo, hi)
    }

    /// Node indices j with y-coordinate in `[lo, hi]`, or `None`.
    #[inline]
    pub fn rows(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
        span(self.origin.y, self.spacing, self.ny, lo, hi)
    }

    pub fn filled(&self, z: f64) -> HeightField {
        HeightField { origin: self.origin, spacing: self.spacing, nx: self.nx, ny: self.ny, z: vec![z; self.nodes()] }
    }
}

#[inline]
fn span(origin: f64, spacing: f64, count: usize, lo: f64, hi: f64) -> Option<(usize, usize)> {
    let a = ((lo - origin) / spacing).ceil().max(0.0);
    let b = ((hi - origin) / spacing).floor().min(count as f64 - 1.0);
    (a <= b).then_some((a as usize, b as usize))
}

impl HeightField {
    pub fn grid(&self) -> Grid {
        Grid { origin: self.origin, spacing: self.spacing, nx: self.nx, ny: self.ny }
    }

    #[inline]
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }

    pub fn max_extent(&self) -> DVec2 {
        self.grid().node(self.nx - 1, self.ny - 1)
    }

    /// The surface between the nodes: each cell is split along its diagonal from (i, j) to
    /// (i + 1, j + 1) into two planar triangles, so the surface is piecewise linear and a
    /// straight line over it is exactly the polyline through its [`HeightField::breakpoints`].
    /// Points outside the grid take the height at the nearest edge.
    #[inline]
    pub fn sample(&self, p: DVec2) -> f64 {
        let u = ((p - self.origin) / self.spacing).clamp(DVec2::ZERO, DVec2::new((self.nx - 1) as f64, (self.ny - 1) as f64));
        let i = (u.x.floor() as usize).min(self.nx.saturating_sub(2));
        let j = (u.y.floor() as usize).min(self.ny.saturating_sub(2));
        let (fx, fy) = (u.x - i as f64, u.y - j as f64);
        let i1 = (i + 1).min(self.nx - 1);
        let j1 = (j + 1).min(self.ny - 1);
        let (z00, z10, z01, z11) = (self.at(i, j), self.at(i1, j), self.at(i, j1), self.at(i1, j1));
        if fx >= fy {
            z00 + fx * (z10 - z00) + fy * (z11 - z10)
        } else {
            z00 + fy * (z01 - z00) + fx * (z11 - z01)
        }
    }

    /// Parameters t in [0, 1] (sorted, with 0 and 1) where the segment `a`–`b` crosses a grid
    /// line or a cell diagonal: between two of them the surface along the segment is linear.
    pub fn breakpoints(&self, a: DVec2, b: DVec2) -> Vec<f64> {
        let ua = (a - self.origin) / self.spacing;
        let ub = (b - self.origin) / self.spacing;
        let mut ts = vec![0.0, 1.0];
        let mut crossings = |from: f64, to: f64| {
            if from == to {
                return;
            }
            let (lo, hi) = (from.min(to), from.max(to));
            let mut k = lo.ceil();
            while k <= hi {
                let t = (k - from) / (to - from);
                if t > 0.0 && t < 1.0 {
                    ts.push(t);
                }
                k += 1.0;
            }
        };
        crossings(ua.x, ub.x);
        crossings(ua.y, ub.y);
        crossings(ua.x - ua.y, ub.x - ub.y);
        crate::geom::sort::sort_floats(&mut ts);
        ts.dedup();
        ts
    }

    pub fn min(&self) -> f64 {
        self.z.iter().copied().fold(f64::INFINITY, f64::min)
    }

    pub fn max(&self) -> f64 {
        self.z.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }
}
