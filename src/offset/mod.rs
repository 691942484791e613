//! Offsetting closed loops of lines and arcs by path trimming (seed 003, Yang and Cho).
//!
//! The paper's steps, one function each:
//! 1. [`raw::raw_offset`] (§2-1): every entity moves to its side by the distance; an arc whose
//!    radius becomes zero is dropped, one whose radius would go negative turns about its centre.
//! 2. [`join::join_neighbours`] (§2-2): neighbours are cut at their crossing, or joined by an
//!    arc about the original corner where they do not meet; what is left past a crossing is
//!    trimmed at once (the paper's Fig. 7).
//! 3. [`trim`] (§2-3): the twisted parts are found (an entity crossed in its interior by
//!    another, or a point where three or more meet: [`trim::split_at_crossings`]), the pieces
//!    between those points that come closer to the input than the distance are trimmed
//!    ([`trim::discard_close`]), the rest are joined back into loops ([`trim::stitch`]) and loops
//!    that run the wrong way are dropped ([`trim::discard_wrong_way`]).
//!
//! Cutting every loop at every crossing first and trimming whole pieces afterwards makes the
//! paper's special case (a loop whose start lies in a twisted part) an ordinary one: pieces run
//! from crossing to crossing, through the loop's start, whichever vertex that is.
//!
//! All loops of a shape are offset together, so islands and the outer boundary that meet
//! merge, and a region that narrows splits. Micro-entities of the input below
//! `Tolerances::micro_entity` are merged into their neighbours ([`merge_micro_entities`]), as
//! the paper does for spline-heavy parts; the result keeps its short entities (only null ones
//! go), and the post writes arcs too short for the controller's resolution as lines.

pub mod check;
pub mod join;
pub mod raw;
pub mod trim;

use crate::drawing::{Loop, Shape, Vertex};
use crate::geom::segment::Segment;
use crate::geom::Tolerances;

/// The shape grown by `distance` (positive) or shrunk (negative), as loops of lines and arcs:
/// outer loops counter-clockwise, holes clockwise. Empty when the shape vanishes.
pub fn offset(shape: &Shape, distance: f64, tol: &Tolerances) -> Shape {
    let input: Vec<Loop> = shape.loops.iter().map(|l| merge_micro_entities(l, tol.micro_entity)).filter(|l| l.len() >= 2).collect();
    if distance == 0.0 || !distance.is_finite() {
        return Shape::from_oriented(input);
    }
    let input = Shape::from_oriented(input);
    let joined: Vec<Vec<Segment>> = input.loops.iter().map(|l| join::join_neighbours(l, &raw::raw_offset(l, distance), distance, tol.offset)).filter(|l| !l.is_empty()).collect();
    let cut = trim::split_at_crossings(&joined, tol.offset);
    let original = trim::Original::new(&input);
    let kept = trim::discard_close(&cut, &original, distance, tol.offset);
    let loops = trim::stitch(kept, tol.offset);
    let loops: Vec<Loop> = loops
        .into_iter()
        // Only null entities go from the result: merging a short one moves its neighbour's end
        // by up to its length, and the result must stay at the distance.
        .map(|l| merge_micro_entities(&l, tol.offset * 10.0))
        .filter(|l| l.len() >= 2 && l.area().abs() > tol.micro_entity * tol.micro_entity)
        .collect();
    Shape::from_oriented(trim::discard_wrong_way(loops, &original, distance))
}

/// The loop without entities shorter than `min_length`: each one's end is merged into its
/// start, and the entity that followed it starts there instead.
pub fn merge_micro_entities(l: &Loop, min_length: f64) -> Loop {
    let n = l.len();
    if n < 3 {
        return l.clone();
    }
    let mut out: Vec<Vertex> = Vec::with_capacity(n);
    for (i, v) in l.vertices.iter().enumerate() {
        match out.last_mut() {
            Some(last) if last.p.distance(v.p) < min_length && l.segment((i + n - 1) % n).length() < min_length => {
                last.bulge = v.bulge;
            }
            _ => out.push(*v),
        }
    }
    while out.len() > 2 && out[out.len() - 1].p.distance(out[0].p) < min_length {
        let last = out.pop().unwrap();
        if (Segment { a: last.p, b: out[0].p, bulge: last.bulge }).length() >= min_length {
            out.push(last);
            break;
        }
    }
    if out.len() < 2 {
        return l.clone();
    }
    Loop { vertices: out }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec2;
    use std::f64::consts::PI;

    fn tol() -> Tolerances {
        Tolerances::default()
    }

    #[test]
    fn square_grows_by_the_distance_with_round_corners() {
        let s = Shape::new(vec![Loop::rect(DVec2::ZERO, DVec2::splat(10.0))]);
        let o = offset(&s, 2.0, &tol());
        assert_eq!(o.loops.len(), 1);
        let expected = 100.0 + 40.0 * 2.0 + PI * 4.0;
        assert!((o.area() - expected).abs() < 1e-9, "{} vs {expected}", o.area());
    }

    #[test]
    fn square_shrinks_to_a_smaller_square_and_vanishes() {
        let s = Shape::new(vec![Loop::rect(DVec2::ZERO, DVec2::splat(10.0))]);
        let o = offset(&s, -2.0, &tol());
        assert_eq!(o.loops.len(), 1);
        assert!((o.area() - 36.0).abs() < 1e-9, "{}", o.area());
        assert!(offset(&s, -5.5, &tol()).is_empty());
    }

    #[test]
    fn circle_offsets_both_ways() {
        let s = Shape::new(vec![Loop::circle(DVec2::new(3.0, 4.0), 5.0)]);
        assert!((offset(&s, 1.0, &tol()).area() - PI * 36.0).abs() < 1e-9);
        assert!((offset(&s, -1.0, &tol()).area() - PI * 16.0).abs() < 1e-9);
        assert!(offset(&s, -5.0, &tol()).is_empty());
        assert!(offset(&s, -6.0, &tol()).is_empty());
    }

    #[test]
    fn hole_shrinks_when_the_region_grows() {
        let s = Shape::new(vec![Loop::rect(DVec2::splat(-10.0), DVec2::splat(10.0)), Loop::circle(DVec2::ZERO, 3.0)]);
        let o = offset(&s, 1.0, &tol());
        assert_eq!(o.loops.len(), 2);
        let expected = 400.0 + 80.0 + PI - PI * 4.0;
        assert!((o.area() - expected).abs() < 1e-9, "{}", o.area());
        let gone = offset(&s, 3.5, &tol());
        assert_eq!(gone.loops.len(), 1);
    }

    #[test]
    fn micro_entities_merge() {
        let mut l = Loop::rect(DVec2::ZERO, DVec2::splat(10.0));
        l.vertices.insert(2, Vertex { p: DVec2::new(10.0, 10.0 - 1e-6), bulge: 0.0 });
        assert_eq!(l.len(), 5);
        let m = merge_micro_entities(&l, 1e-4);
        assert_eq!(m.len(), 4);
        assert!((m.area() - 100.0).abs() < 1e-4);
    }
}
