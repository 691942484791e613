//! Bounds from above of a CL surface at the nodes of its grid: the heights of the cutter
//! widened by the grid's spacing ([`crate::zmap::drop::PointDrop::widened`]), each at least the
//! exact surface anywhere within a spacing of its node. The level maps take them for every
//! node ([`crate::zmap::contour::LevelMap`]); a link's or an entry's test
//! ([`crate::toolpath::link::Floor`]) asks only around the moves it checks, so they are made in
//! bands of rows as they are first asked for.

use std::ops::Range;
use std::sync::OnceLock;

/// Rows of nodes made at a time.
const BAND_ROWS: usize = 8;

/// What makes the heights of a range of rows (row after row).
type Make = Box<dyn Fn(Range<usize>) -> Vec<f64> + Send + Sync>;

/// The widened cutter's heights at every node of a grid, made band by band on demand.
pub struct NodeBounds {
    nx: usize,
    ny: usize,
    bands: Vec<OnceLock<Vec<f64>>>,
    make: Option<Make>,
}

impl NodeBounds {
    /// Heights for all `nx × ny` nodes, made already; `None` when `z` holds another number.
    pub fn whole(nx: usize, ny: usize, z: Vec<f64>) -> Option<NodeBounds> {
        if z.len() != nx * ny {
            return None;
        }
        let bands = z.chunks(BAND_ROWS * nx.max(1)).map(|c| OnceLock::from(c.to_vec())).collect();
        Some(NodeBounds { nx, ny, bands, make: None })
    }

    /// Heights for `nx × ny` nodes that `make` makes for a range of rows when first asked for.
    pub fn lazy(nx: usize, ny: usize, make: impl Fn(Range<usize>) -> Vec<f64> + Send + Sync + 'static) -> NodeBounds {
        let bands = (0..ny.div_ceil(BAND_ROWS)).map(|_| OnceLock::new()).collect();
        NodeBounds { nx, ny, bands, make: Some(Box::new(make)) }
    }

    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The heights of row `j` (made with its band when first asked for; `+inf`, which bounds
    /// anything, where they could not be made).
    pub fn row(&self, j: usize) -> &[f64] {
        let b = j / BAND_ROWS;
        let rows = b * BAND_ROWS..((b + 1) * BAND_ROWS).min(self.ny);
        let band = self.bands[b].get_or_init(|| {
            let z = self.make.as_ref().map(|m| m(rows.clone())).unwrap_or_default();
            if z.len() == rows.len() * self.nx {
                z
            } else {
                vec![f64::INFINITY; rows.len() * self.nx]
            }
        });
        let k = j - rows.start;
        &band[k * self.nx..(k + 1) * self.nx]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Arc;

    #[test]
    fn bands_are_made_once_and_only_when_asked_for() {
        let made = Arc::new(AtomicUsize::new(0));
        let counter = made.clone();
        let (nx, ny) = (5, 20);
        let b = NodeBounds::lazy(nx, ny, move |rows| {
            counter.fetch_add(1, Ordering::Relaxed);
            rows.flat_map(|j| (0..nx).map(move |i| (j * 10 + i) as f64)).collect()
        });
        assert_eq!(b.row(17)[3], 173.0);
        assert_eq!(b.row(16)[0], 160.0);
        assert_eq!(made.load(Ordering::Relaxed), 1);
        assert_eq!(b.row(2)[4], 24.0);
        assert_eq!(made.load(Ordering::Relaxed), 2);
        let whole = NodeBounds::whole(nx, ny, (0..nx * ny).map(|k| k as f64).collect()).unwrap();
        assert_eq!(whole.row(19)[4], 99.0);
        assert!(NodeBounds::whole(nx, ny, vec![0.0; 3]).is_none());
        // A maker that gives the wrong number bounds nothing below +inf.
        let bad = NodeBounds::lazy(nx, ny, |_| vec![0.0; 2]);
        assert_eq!(bad.row(0)[0], f64::INFINITY);
    }
}
