//! Step 1 of seed 003 (§2-1, Figs. 1–3): the raw offset of every entity of a loop.

use crate::drawing::Loop;
use crate::geom::segment::Segment;
use crate::geom::DVec2;

/// One entity moved to its right by `distance` (to its left when negative). Lines move along
/// their normal. Arcs keep their centre and sweep and change radius: `R + d` for
/// counter-clockwise arcs, `R − d` for clockwise ones. A radius that becomes zero leaves the
/// entity `collapsed` to its centre (Fig. 2: it is dropped, its neighbours meet there); a radius
/// that would go negative puts the arc on the far side of its centre, turning against the
/// loop (Fig. 3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawEntity {
    pub seg: Segment,
    pub collapsed: bool,
}

/// Radii below this fraction of the distance count as zero.
const COLLAPSE: f64 = 1e-9;

/// The raw offset of every entity of `l`, in order (one per entity, collapsed ones included).
pub fn raw_offset(l: &Loop, distance: f64) -> Vec<RawEntity> {
    l.segments().map(|s| raw_entity(&s, distance)).collect()
}

pub fn raw_entity(s: &Segment, d: f64) -> RawEntity {
    match s.arc_geom() {
        None => {
            let t = (s.b - s.a).normalize_or_zero();
            let n = DVec2::new(t.y, -t.x) * d;
            RawEntity { seg: Segment { a: s.a + n, b: s.b + n, bulge: 0.0 }, collapsed: false }
        }
        Some(g) => {
            let r = if g.bulge > 0.0 { g.radius + d } else { g.radius - d };
            if r.abs() <= COLLAPSE * d.abs().max(g.radius) {
                return RawEntity { seg: Segment { a: g.center, b: g.center, bulge: 0.0 }, collapsed: true };
            }
            let k = r / g.radius;
            let seg = Segment { a: g.center + (s.a - g.center) * k, b: g.center + (s.b - g.center) * k, bulge: s.bulge };
            RawEntity { seg, collapsed: false }
        }
    }
}
