//! The CL surface a strategy may stand on, between the z-map's nodes.
//!
//! The CL heights at the nodes are exact (seed 001 §3.3), but a CL surface has cliffs where a
//! cutter leaves a vertical wall and steep convex rolls where it rounds over an edge: there the
//! true surface between two nodes lies far above the straight line joining them, and a path
//! that follows the line gouges. So each cell is one of two kinds:
//!
//! * **linear**: the corners' discrete second differences show no downward curvature whose sag
//!   over a cell could exceed the interpolation tolerance: the cell is split along its diagonal
//!   into two planar triangles ([`HeightField::sample`]);
//! * **held**: otherwise the cell is flat at its highest corner (it leaves a little material at
//!   the foot of a wall instead of cutting into its edge).
//!
//! On a border between cells the higher of the two sides counts, so a straight move sampled at
//! the [`HeightField::breakpoints`] never passes below either side.

use crate::geom::{tolerance::GRID_SNAP, DVec2};

use super::HeightField;

/// A CL z-map with each cell marked linear or held.
#[derive(Clone, Debug)]
pub struct ClSurface {
    pub field: HeightField,
    /// For cell (i, j) at `j * (nx - 1) + i`: its height if held, NaN if linear.
    held: Vec<f64>,
}

impl ClSurface {
    /// Marks the cells; `tolerance` (mm) is the largest sag trusted to linear interpolation.
    pub fn new(field: HeightField, tolerance: f64) -> ClSurface {
        let (nx, ny) = (field.nx, field.ny);
        let at = |i: usize, j: usize| field.at(i, j);
        // A node is "bent" when the surface curves down through it faster than the tolerance
        // allows: the sag of a parabola over one cell is -d2 / 8.
        let limit = -8.0 * tolerance;
        let bent = |i: usize, j: usize| {
            let z = at(i, j);
            let dx = (i > 0 && i + 1 < nx).then(|| at(i - 1, j) - 2.0 * z + at(i + 1, j));
            let dy = (j > 0 && j + 1 < ny).then(|| at(i, j - 1) - 2.0 * z + at(i, j + 1));
            let dd = (i > 0 && j > 0 && i + 1 < nx && j + 1 < ny).then(|| (at(i - 1, j - 1) - 2.0 * z + at(i + 1, j + 1)) / 2.0);
            [dx, dy, dd].into_iter().flatten().any(|d| d < limit)
        };
        let cells_x = nx.saturating_sub(1);
        let mut held = vec![f64::NAN; cells_x * ny.saturating_sub(1)];
        let bent_nodes: Vec<bool> = (0..nx * ny).map(|k| bent(k % nx, k / nx)).collect();
        for j in 0..ny.saturating_sub(1) {
            for i in 0..cells_x {
                let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
                if corners.iter().any(|&(a, b)| bent_nodes[b * nx + a]) {
                    held[j * cells_x + i] = corners.iter().map(|&(a, b)| at(a, b)).fold(f64::NEG_INFINITY, f64::max);
                }
            }
        }
        ClSurface { field, held }
    }

    /// The surface's height at `p`: on a border between cells, the highest of them.
    #[inline]
    pub fn height(&self, p: DVec2) -> f64 {
        let f = &self.field;
        let (cx, cy) = (f.nx.saturating_sub(1), f.ny.saturating_sub(1));
        if cx == 0 || cy == 0 {
            return f.sample(p);
        }
        let u = ((p - f.origin) / f.spacing).clamp(DVec2::ZERO, DVec2::new(cx as f64, cy as f64));
        let cells = |v: f64, count: usize| {
            let line = v.round();
            if (v - line).abs() <= GRID_SNAP {
                // On a grid line both cells beside it count.
                let k = line as usize;
                (k.min(count - 1), (k > 0 && k < count).then(|| k - 1))
            } else {
                ((v.floor() as usize).min(count - 1), None)
            }
        };
        let (ix, ix2) = cells(u.x, cx);
        let (iy, iy2) = cells(u.y, cy);
        let mut best = f64::NEG_INFINITY;
        for i in std::iter::once(ix).chain(ix2) {
            for j in std::iter::once(iy).chain(iy2) {
                let h = self.held[j * cx + i];
                best = best.max(if h.is_nan() { f.sample(p) } else { h });
            }
        }
        best
    }

    /// See [`HeightField::breakpoints`].
    pub fn breakpoints(&self, a: DVec2, b: DVec2) -> Vec<f64> {
        self.field.breakpoints(a, b)
    }
}
