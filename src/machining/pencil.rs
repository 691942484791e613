//! Pencil lines (issue 60): the concave corners and fillets where a ball touches the part at
//! two places, found on the exact CL z-map. Where the ball touches two faces at once its tip's
//! surface has a crease (the surfaces it rides on either side meet at an angle, as two planes'
//! offsets do); a fillet no tighter than the ball leaves the CL surface smooth, and needs no
//! pencil pass.
//!
//! Steps, in order:
//! 1. at every node, how much the CL surface bends upward across it along the grid's axes and
//!    diagonals (the turn between the slopes either side);
//! 2. a node is on a crease where its bend is at least the least asked and no smaller than its
//!    two neighbours' along the same direction (one node across the crease), and it stands
//!    above the floor (beside the part the tool has nothing to cut);
//! 3. the crease nodes are chained along their 8-neighbours, straightest first, and each chain
//!    simplified within a tolerance; heights are the exact drop's along the result.

use crate::geom::DVec2;
use crate::zmap::HeightField;

/// The directions a bend is measured along: the grid's axes and diagonals.
const DIRECTIONS: [(isize, isize); 4] = [(1, 0), (0, 1), (1, 1), (1, -1)];

/// How much the surface `f` bends upward at node `(i, j)` along `d` (radians, the turn from the
/// slope before to the slope after; negative over a ridge), `None` at the field's edge.
fn bend(f: &HeightField, i: usize, j: usize, d: (isize, isize)) -> Option<f64> {
    let at = |k: isize| {
        let (x, y) = (i as isize + k * d.0, j as isize + k * d.1);
        (x >= 0 && y >= 0 && (x as usize) < f.nx && (y as usize) < f.ny).then(|| f.at(x as usize, y as usize))
    };
    let (a, z, b) = (at(-1)?, at(0)?, at(1)?);
    let h = f.spacing * ((d.0 * d.0 + d.1 * d.1) as f64).sqrt();
    Some(((b - z) / h).atan() - ((z - a) / h).atan())
}

/// The nodes of `f` on a concave crease (row-major, as `f.z`): a bend of at least `least`
/// radians along some direction, no smaller than either neighbour's along it, the node above
/// `floor`.
pub fn crease_nodes(f: &HeightField, least: f64, floor: f64) -> Vec<bool> {
    let mut marked = vec![false; f.nx * f.ny];
    for j in 0..f.ny {
        for i in 0..f.nx {
            if f.at(i, j) <= floor + crate::geom::tolerance::FLOAT_SLACK {
                continue;
            }
            marked[j * f.nx + i] = DIRECTIONS.iter().any(|&d| {
                let Some(b) = bend(f, i, j, d).filter(|&b| b >= least) else { return false };
                let side = |k: isize| {
                    let (x, y) = (i as isize + k * d.0, j as isize + k * d.1);
                    bend(f, x as usize, y as usize, d).unwrap_or(f64::NEG_INFINITY)
                };
                // (Of two equal neighbours across a crease between them, the first.)
                b > side(-1) && b >= side(1)
            });
        }
    }
    marked
}

/// The `marked` nodes of `f` chained into polylines along their 8-neighbours: each chain
/// starts at an end (a node with one marked neighbour) where it has one, and goes on to the
/// unvisited neighbour that turns least. Chains shorter than `shortest` are dropped; each is
/// simplified within `tolerance` (its points kept where a straight line would stray farther).
pub fn chains(f: &HeightField, marked: &[bool], shortest: f64, tolerance: f64) -> Vec<Vec<DVec2>> {
    let g = f.grid();
    let neighbours = |n: usize| {
        let (i, j) = ((n % f.nx) as isize, (n / f.nx) as isize);
        (-1..=1isize)
            .flat_map(move |dj| (-1..=1isize).map(move |di| (i + di, j + dj)))
            .filter(move |&(x, y)| (x, y) != (i, j) && x >= 0 && y >= 0 && (x as usize) < f.nx && (y as usize) < f.ny)
            .map(|(x, y)| y as usize * f.nx + x as usize)
            .filter(|&m| marked[m])
    };
    let point = |n: usize| g.node(n % f.nx, n / f.nx);
    let mut seen = vec![false; marked.len()];
    let ends: Vec<usize> = (0..marked.len()).filter(|&n| marked[n] && neighbours(n).count() == 1).collect();
    let rest = (0..marked.len()).filter(|&n| marked[n]);
    let mut out = Vec::new();
    for start in ends.into_iter().chain(rest) {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut chain = vec![start];
        let mut at = start;
        let mut heading: Option<DVec2> = None;
        while let Some(next) = neighbours(at).filter(|&m| !seen[m]).max_by(|&a, &b| {
            let turn = |m: usize| heading.map_or(0.0, |h| h.dot((point(m) - point(at)).normalize()));
            turn(a).total_cmp(&turn(b)).then(b.cmp(&a))
        }) {
            seen[next] = true;
            heading = Some((point(next) - point(at)).normalize());
            chain.push(next);
            at = next;
        }
        // A chain that came round to its start closes.
        if chain.len() > 2 && neighbours(at).any(|m| m == start) {
            chain.push(start);
        }
        let points: Vec<DVec2> = chain.into_iter().map(point).collect();
        let length: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
        if length >= shortest {
            out.push(simplify(&points, tolerance));
        }
    }
    out
}

/// `points` with as few kept as keeps every dropped one within `tolerance` of the line that
/// replaces it (greedy: each kept point reaches as far ahead as it can).
fn simplify(points: &[DVec2], tolerance: f64) -> Vec<DVec2> {
    if points.len() <= 2 {
        return points.to_vec();
    }
    let within = |a: usize, b: usize| {
        let s = crate::geom::segment::Segment::line(points[a], points[b]);
        points[a + 1..b].iter().all(|&p| s.closest_with(None, p).0.distance(p) <= tolerance)
    };
    let mut kept = vec![points[0]];
    let mut anchor = 0;
    while anchor < points.len() - 1 {
        let mut reach = anchor + 1;
        while reach + 1 < points.len() && within(anchor, reach + 1) {
            reach += 1;
        }
        kept.push(points[reach]);
        anchor = reach;
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A V-groove along Y (slopes of 45° either side of x = 2) and a step down along it: one
    /// crease, the groove's bottom, one node wide, chained into one straight line.
    #[test]
    fn a_grooves_bottom_is_one_straight_crease() {
        let (nx, ny, h) = (41, 21, 0.1);
        let z = (0..ny).flat_map(|_| (0..nx).map(move |i| 10.0 + (i as f64 * h - 2.0).abs())).collect();
        let f = HeightField { origin: DVec2::ZERO, spacing: h, nx, ny, z };
        let marked = crease_nodes(&f, 20f64.to_radians(), 0.0);
        let at: Vec<usize> = (0..marked.len()).filter(|&n| marked[n]).collect();
        assert_eq!(at.len(), ny, "one node across");
        assert!(at.iter().all(|&n| n % nx == 20));
        let lines = chains(&f, &marked, 1.0, 0.01);
        assert_eq!(lines.len(), 1);
        assert_eq!(lines[0].len(), 2, "{:?}", lines[0]);
        assert!((lines[0][0].distance(lines[0][1]) - 2.0).abs() < 1e-9);
        // A ridge is no crease.
        let f = HeightField { z: f.z.iter().map(|z| 30.0 - z).collect(), ..f };
        assert!(!crease_nodes(&f, 20f64.to_radians(), 0.0).contains(&true));
    }
}
