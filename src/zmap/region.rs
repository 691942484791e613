//! Where a strategy may put the tool's centre: the stock's rectangle, or the part's silhouette
//! grown by a margin.

use crate::geom::DVec2;
use crate::zmap::HeightField;

/// A region of the XY plane.
#[derive(Clone, Debug)]
pub enum Region {
    Rect {
        min: DVec2,
        max: DVec2,
    },
    /// Nodes of the grid with a value of at least one half are inside; a point belongs to the
    /// region of its nearest node.
    Mask(HeightField),
}

impl Region {
    /// The part's silhouette (nodes where the CC z-map stands above `floor`) grown by `margin`:
    /// the nodes within `margin` of a covered node. For each row, two sweeps give every node's
    /// distance along the row to the nearest covered node; a node is inside when, for some row
    /// within the margin, that distance and the rows' gap lie within the margin.
    pub fn silhouette(cc: &HeightField, floor: f64, margin: f64) -> Region {
        let (nx, ny, spacing) = (cc.nx, cc.ny, cc.spacing);
        let far = usize::MAX / 4;
        let mut along = vec![far; nx * ny]; // nodes to the nearest covered node in the row
        for j in 0..ny {
            let row = &mut along[j * nx..(j + 1) * nx];
            let mut last = far;
            for i in 0..nx {
                last = if cc.at(i, j) > floor { 0 } else { last.saturating_add(1) };
                row[i] = last;
            }
            last = far;
            for i in (0..nx).rev() {
                last = if row[i] == 0 { 0 } else { last.saturating_add(1) };
                row[i] = row[i].min(last);
            }
        }
        let reach = (margin.max(0.0) / spacing).floor() as usize;
        let limit = margin.max(0.0) * margin.max(0.0);
        let mut mask = cc.grid().filled(0.0);
        for j in 0..ny {
            for i in 0..nx {
                let inside = (j.saturating_sub(reach)..=(j + reach).min(ny - 1)).any(|js| {
                    let (dx, dy) = (along[js * nx + i] as f64 * spacing, (js as f64 - j as f64) * spacing);
                    dx * dx + dy * dy <= limit
                });
                if inside {
                    mask.z[j * nx + i] = 1.0;
                }
            }
        }
        Region::Mask(mask)
    }

    pub fn bounds(&self) -> (DVec2, DVec2) {
        match self {
            Region::Rect { min, max } => (*min, *max),
            Region::Mask(m) => (m.origin, m.max_extent()),
        }
    }

    #[inline]
    pub fn contains(&self, p: DVec2) -> bool {
        match self {
            Region::Rect { min, max } => p.cmpge(*min).all() && p.cmple(*max).all(),
            Region::Mask(m) => m.grid().nearest(p).is_some_and(|c| m.z[c] >= 0.5),
        }
    }
}
