//! Where a strategy may put the tool's centre: the stock's rectangle, or the part's silhouette
//! grown by a margin.

use crate::cutter::Profile;
use crate::geom::DVec2;
use crate::progress::Progress;
use crate::zmap::{cl_inverse::cl_inverse_offset, HeightField};

/// A region of the XY plane.
#[derive(Clone, Debug)]
pub enum Region {
    Rect { min: DVec2, max: DVec2 },
    /// Nodes of the grid with a value of at least one half are inside; a point belongs to the
    /// region of its nearest node.
    Mask(HeightField),
}

impl Region {
    /// The part's silhouette (nodes where the CC z-map stands above `floor`) grown by `margin`.
    pub fn silhouette(cc: &HeightField, floor: f64, margin: f64) -> Region {
        let mut covered = cc.clone();
        for z in &mut covered.z {
            *z = if *z > floor { 1.0 } else { 0.0 };
        }
        // Growing a 0/1 map by a disk is an inverse offset with a flat cutter of that radius.
        let grown = cl_inverse_offset(&covered, &Profile::new(margin.max(0.0), 0.0), &mut Progress::none())
            .expect("no progress sink, no cancel");
        Region::Mask(grown)
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
            Region::Mask(m) => {
                let u = ((p - m.origin) / m.spacing).round();
                u.x >= 0.0 && u.y >= 0.0 && (u.x as usize) < m.nx && (u.y as usize) < m.ny && m.at(u.x as usize, u.y as usize) >= 0.5
            }
        }
    }
}
