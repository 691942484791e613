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
        let [region] = Region::silhouettes(cc, floor, [margin]);
        region
    }

    /// [`Region::silhouette`] grown by each of `margins`: the covered nodes' distance map
    /// ([`crate::zmap::distance::distance_to`]), made once, decides every node but those whose
    /// distance lies within a hair of a margin, which the rows decide as before.
    pub fn silhouettes<const N: usize>(cc: &HeightField, floor: f64, margins: [f64; N]) -> [Region; N] {
        let (nx, ny, spacing) = (cc.nx, cc.ny, cc.spacing);
        let covered: Vec<bool> = cc.z.iter().map(|&z| z > floor).collect();
        let distance = crate::zmap::distance::distance_to(&covered, nx, ny, spacing);
        let far = usize::MAX / 4;
        let mut along = vec![far; nx * ny]; // nodes to the nearest covered node in the row
        for j in 0..ny {
            let row = &mut along[j * nx..(j + 1) * nx];
            let mut last = far;
            for i in 0..nx {
                last = if covered[j * nx + i] { 0 } else { last.saturating_add(1) };
                row[i] = last;
            }
            last = far;
            for i in (0..nx).rev() {
                last = if row[i] == 0 { 0 } else { last.saturating_add(1) };
                row[i] = row[i].min(last);
            }
        }
        margins.map(|margin| {
            let reach = (margin.max(0.0) / spacing).floor() as usize;
            let limit = margin.max(0.0) * margin.max(0.0);
            // The distance map's square is the least of the rows' sums below to within
            // rounding: far enough from the limit it decides alone.
            let (sure_in, sure_out) = (limit * (1.0 - 1e-9), limit * (1.0 + 1e-9));
            let mut mask = cc.grid().filled(0.0);
            for j in 0..ny {
                for i in 0..nx {
                    let d2 = distance[j * nx + i] * distance[j * nx + i];
                    let inside = d2 <= sure_in
                        || (d2 <= sure_out
                            && (j.saturating_sub(reach)..=(j + reach).min(ny - 1)).any(|js| {
                                let (dx, dy) = (along[js * nx + i] as f64 * spacing, (js as f64 - j as f64) * spacing);
                                dx * dx + dy * dy <= limit
                            }));
                    if inside {
                        mask.z[j * nx + i] = 1.0;
                    }
                }
            }
            Region::Mask(mask)
        })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::zmap::Grid;

    /// The rows' test alone, every node: within the margin of a covered node along some row.
    fn by_rows(cc: &HeightField, floor: f64, margin: f64) -> Vec<bool> {
        let (nx, ny, s) = (cc.nx, cc.ny, cc.spacing);
        let limit = margin * margin;
        (0..nx * ny)
            .map(|c| {
                let (i, j) = (c % nx, c / nx);
                (0..ny).any(|js| {
                    (0..nx).any(|is| {
                        cc.at(is, js) > floor && {
                            let (dx, dy) = ((is.abs_diff(i)) as f64 * s, (js as f64 - j as f64) * s);
                            dx * dx + dy * dy <= limit
                        }
                    })
                })
            })
            .collect()
    }

    #[test]
    fn silhouettes_are_the_nodes_within_each_margin_of_a_covered_one() {
        // Sparse and dense masks; margins on a node's distance exactly (ties), between, and 0.
        let grid = Grid::covering(DVec2::ZERO, DVec2::new(14.5, 9.5), 0.5);
        for (seed, every) in [(1u64, 37), (2, 5), (3, 2)] {
            let mut cc = grid.filled(0.0);
            let mut x = seed;
            for z in cc.z.iter_mut() {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                if (x >> 33) % every == 0 {
                    *z = 1.0;
                }
            }
            let margins = [0.0, 0.5, 0.999, 1.0, 5.0_f64.sqrt() * 0.5, 1.3, 2.4999, 2.5, 3.0, 4.1];
            let made = Region::silhouettes(&cc, 0.5, margins);
            for (margin, region) in margins.iter().zip(made) {
                let Region::Mask(mask) = region else { panic!("a mask") };
                let got: Vec<bool> = mask.z.iter().map(|&v| v >= 0.5).collect();
                assert_eq!(got, by_rows(&cc, 0.5, *margin), "seed {seed}, margin {margin}");
            }
        }
    }
}
