//! Passes a constant distance apart across the surface (issue 60's scallop finishing): the
//! offsets of an area's edge measured over the CL surface rather than in the plane, so that on
//! a steep face the passes close up in plan and the cusp between them stays the one asked for.
//!
//! 1. the distance of every node of the area from its edge, over the CL z-map: Dijkstra's
//!    shortest paths along 16 neighbours, each step the chord between the tip's two positions
//!    ([`geodesic`]);
//! 2. its level lines at half a step from the edge and a step apart, by marching squares
//!    ([`iso_lines`]);
//! 3. where two fronts stop short of each other (the distance's ridges), a pass along the ridge
//!    through the nodes no pass came near ([`ridge_lines`]).

use std::collections::{BinaryHeap, HashMap};

use crate::geom::DVec2;
use crate::zmap::HeightField;

/// The steepest step between two nodes the distance crosses (degrees): a steeper one is a wall
/// the CL surface jumps, which the passes reach from either side rather than across.
pub const STEEPEST: f64 = 85.0;

/// The step between passes (mm) that leaves a cusp of `cusp` between two passes of a ball (or
/// a bull-nose's corner) of radius `radius` on a plane: the chord of the circle at `cusp` below
/// its top, 2√(2rh − h²).
pub fn stepover_for_cusp(radius: f64, cusp: f64) -> f64 {
    let h = cusp.min(radius);
    2.0 * (2.0 * radius * h - h * h).max(0.0).sqrt()
}

/// The step across the surface for the operation `op`'s `cusp` with a corner of `radius`: the
/// cusp less the `chordal` tolerance the passes are reduced within (a chord may cut the ridge's
/// top by that much less); refused where nothing is left of it.
pub fn cusp_step(op: &str, cusp: f64, radius: f64, chordal: f64) -> crate::error::Result<f64> {
    let h = cusp - chordal;
    if !(h > 0.0) {
        return Err(crate::error::Error::operation(op, format!("a cusp of {cusp} mm is within the job's chordal tolerance ({chordal} mm): ask for a larger cusp")));
    }
    Ok(stepover_for_cusp(radius, h))
}

/// The 16 neighbours of a node: the 8 around it and the 8 a knight's move away, so the
/// distance's direction is off the true one by at most 9.5° on a plane (under 1.4 % longer).
const NEIGHBOURS: [(isize, isize); 16] = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1), (2, 1), (2, -1), (-2, 1), (-2, -1), (1, 2), (1, -2), (-1, 2), (-1, -2)];

/// The nodes inside the area with a neighbour (of 4) outside it or off the grid: where the
/// distance starts.
pub fn boundary_nodes(f: &HeightField, inside: &[bool]) -> Vec<usize> {
    let (nx, ny) = (f.nx, f.ny);
    (0..nx * ny)
        .filter(|&n| {
            let (i, j) = (n % nx, n / nx);
            inside[n] && (i == 0 || j == 0 || i + 1 == nx || j + 1 == ny || !inside[n - 1] || !inside[n + 1] || !inside[n - nx] || !inside[n + nx])
        })
        .collect()
}

/// The shortest distance over the surface `f` from `sources` (each with its starting distance)
/// to every node inside the area, through nodes inside it: steps to the 16 neighbours, each
/// the chord in space between the two nodes, none steeper than [`STEEPEST`]. Nodes outside the
/// area or out of reach are ∞.
pub fn geodesic(f: &HeightField, inside: &[bool], sources: &[(usize, f64)]) -> Vec<f64> {
    let (nx, ny) = (f.nx as isize, f.ny as isize);
    let s = f.spacing;
    let steep = STEEPEST.to_radians().tan();
    let mut d = vec![f64::INFINITY; f.z.len()];
    // Distances are never negative: their bits order as the numbers do.
    let mut heap: BinaryHeap<std::cmp::Reverse<(u64, usize)>> = BinaryHeap::new();
    for &(n, d0) in sources {
        if inside[n] && d0 < d[n] {
            d[n] = d0;
            heap.push(std::cmp::Reverse((d0.to_bits(), n)));
        }
    }
    while let Some(std::cmp::Reverse((bits, n))) = heap.pop() {
        let dn = f64::from_bits(bits);
        if dn > d[n] {
            continue;
        }
        let (i, j) = ((n as isize) % nx, (n as isize) / nx);
        for (di, dj) in NEIGHBOURS {
            let (x, y) = (i + di, j + dj);
            if x < 0 || y < 0 || x >= nx || y >= ny {
                continue;
            }
            let m = (y * nx + x) as usize;
            if !inside[m] {
                continue;
            }
            let flat = s * ((di * di + dj * dj) as f64).sqrt();
            let rise = (f.z[m] - f.z[n]).abs();
            if rise > steep * flat {
                continue;
            }
            let dm = dn + (flat * flat + rise * rise).sqrt();
            if dm < d[m] {
                d[m] = dm;
                heap.push(std::cmp::Reverse((dm.to_bits(), m)));
            }
        }
    }
    d
}

/// The lines where `v` (on `f`'s grid, ∞ and NaN counted as below every level) crosses each of
/// `levels`, by marching squares (a saddle split by its centre's mean), chained into polylines:
/// closed ones end where they start. Each runs with the higher side on its left.
pub fn iso_lines(f: &HeightField, v: &[f64], levels: &[f64]) -> Vec<Vec<Vec<DVec2>>> {
    levels.iter().map(|&level| level_lines(f, v, level)).collect()
}

fn level_lines(f: &HeightField, v: &[f64], level: f64) -> Vec<Vec<DVec2>> {
    let nx = f.nx;
    let value = |n: usize| if v[n].is_finite() { v[n] } else { f64::NEG_INFINITY };
    let above = |n: usize| value(n) >= level;
    // An edge's id: 2 n for the one from node n along +x, 2 n + 1 along +y.
    let crossing = |e: usize| {
        let n = e / 2;
        let m = if e % 2 == 0 { n + 1 } else { n + nx };
        let (a, b) = (value(n), value(m));
        let t = if a.is_finite() && b.is_finite() && a != b {
            ((level - a) / (b - a)).clamp(0.0, 1.0)
        } else if a.is_finite() {
            1.0
        } else {
            0.0
        };
        let (p, q) = (f.grid().node(n % nx, n / nx), f.grid().node(m % nx, m / nx));
        p + (q - p) * t
    };
    // Each segment: its two edges, the first to the second with the higher side on the left.
    let mut segments: Vec<[usize; 2]> = Vec::new();
    for j in 0..f.ny.saturating_sub(1) {
        for i in 0..nx.saturating_sub(1) {
            let c = [j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i];
            let up = c.map(above);
            if up.iter().all(|&u| u) || up.iter().all(|&u| !u) {
                continue;
            }
            // The cell's edges, counter-clockwise from its bottom: corner k lies between edges
            // k − 1 and k.
            let edges = [2 * c[0], 2 * c[1] + 1, 2 * c[3], 2 * c[0] + 1];
            let around = |k: usize| [edges[(k + 3) % 4], edges[k]];
            let mut cut = |k: usize| {
                // Around corner k: from the edge after it to the edge before it keeps the
                // corner on the left; a corner below wants the other way.
                let [a, b] = around(k);
                segments.push(if up[k] { [b, a] } else { [a, b] });
            };
            let count = (0..4).filter(|&k| up[k] != up[(k + 1) % 4]).count();
            if count == 4 {
                let centre = c.iter().map(|&n| value(n).max(level - 1e9)).sum::<f64>() / 4.0 >= level;
                for k in 0..4 {
                    if up[k] != centre {
                        cut(k);
                    }
                }
            } else {
                // One corner alone on its side, or two beside each other.
                match (0..4).find(|&k| up[k] != up[(k + 1) % 4] && up[k] != up[(k + 3) % 4]) {
                    Some(k) => cut(k),
                    None => {
                        // Two and two: the line crosses from one side's edge to the other's.
                        let k = (0..4).find(|&k| up[k] && up[(k + 1) % 4]).expect("two corners above beside each other");
                        // Corners k, k + 1 above: the line runs from the edge after k + 1 to the
                        // edge before k (edge k − 1), keeping them on its left.
                        segments.push([edges[(k + 1) % 4], edges[(k + 3) % 4]]);
                    }
                }
            }
        }
    }
    chain(&segments, crossing)
}

/// Joins segments that share an end (an edge's crossing) into polylines.
fn chain(segments: &[[usize; 2]], point: impl Fn(usize) -> DVec2) -> Vec<Vec<DVec2>> {
    let mut from: HashMap<usize, usize> = HashMap::with_capacity(segments.len());
    let mut to: HashMap<usize, usize> = HashMap::with_capacity(segments.len());
    for (s, &[a, b]) in segments.iter().enumerate() {
        from.insert(a, s);
        to.insert(b, s);
    }
    let mut used = vec![false; segments.len()];
    let mut lines = Vec::new();
    // Open lines first, from their starts (an edge no segment ends at), then the closed ones.
    let starts = (0..segments.len()).filter(|&s| !to.contains_key(&segments[s][0])).chain(0..segments.len());
    for start in starts.collect::<Vec<_>>() {
        if used[start] {
            continue;
        }
        let mut edges = vec![segments[start][0]];
        let mut s = start;
        loop {
            used[s] = true;
            let end = segments[s][1];
            edges.push(end);
            match from.get(&end) {
                Some(&next) if !used[next] => s = next,
                _ => break,
            }
        }
        lines.push(edges.into_iter().map(&point).collect());
    }
    lines
}

/// The distance over the surface `f` from the polylines `lines` to every node inside the
/// area: the lines' points (every half a grid step) are its sources, at their plan distance
/// from the four nodes about them.
pub fn distance_from_lines(f: &HeightField, inside: &[bool], lines: &[Vec<DVec2>]) -> Vec<f64> {
    let g = f.grid();
    let mut best: HashMap<usize, f64> = HashMap::new();
    for line in lines {
        for w in line.windows(2) {
            let n = ((w[0].distance(w[1]) / (0.5 * f.spacing)).ceil() as usize).max(1);
            for k in 0..=n {
                let p = w[0].lerp(w[1], k as f64 / n as f64);
                let u = (p - f.origin) / f.spacing;
                let (i, j) = (u.x.floor().max(0.0) as usize, u.y.floor().max(0.0) as usize);
                for (x, y) in [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)] {
                    if x < f.nx && y < f.ny {
                        let d = g.node(x, y).distance(p);
                        let e = best.entry(y * f.nx + x).or_insert(f64::INFINITY);
                        *e = e.min(d);
                    }
                }
            }
        }
    }
    let sources: Vec<(usize, f64)> = best.into_iter().collect();
    geodesic(f, inside, &sources)
}

/// The nodes inside the area farther than `reach` (over the surface) from every pass.
pub fn uncovered(f: &HeightField, inside: &[bool], passes: &[Vec<DVec2>], reach: f64) -> Vec<bool> {
    let near = distance_from_lines(f, inside, passes);
    (0..inside.len()).map(|n| inside[n] && near[n] > reach).collect()
}

/// The distance's ridges through the nodes in `wanted`: the concave creases of −`d` there
/// (bent by at least 20°: across a ridge the distance rises then falls), chained.
pub fn ridge_lines(f: &HeightField, d: &[f64], wanted: &[bool], tolerance: f64) -> Vec<Vec<DVec2>> {
    let top = d.iter().copied().filter(|x| x.is_finite()).fold(0.0, f64::max);
    let minus = HeightField { z: d.iter().map(|&x| if x.is_finite() { -x } else { -top - 1.0 }).collect(), ..f.clone() };
    let crease = crate::machining::pencil::crease_nodes(&minus, 20f64.to_radians(), f64::NEG_INFINITY);
    let marked: Vec<bool> = crease.iter().zip(wanted).map(|(&c, &w)| c && w).collect();
    crate::machining::pencil::chains(&minus, &marked, 0.0, tolerance).into_iter().filter(|l| l.len() > 1).collect()
}

/// A node farther than this share of the step from every pass is left to a ridge's pass.
pub const REACH: f64 = 0.6;

/// The passes over the area (`inside`, on `f`'s nodes) a `step` apart across the surface, in
/// the order to cut them: the level lines of the distance from its edge, half a step from it
/// and a step apart, and a pass along each ridge where two fronts left nodes farther than
/// [`REACH`] steps from any; lines simplified within a quarter of `grid`. `None` past
/// [`crate::machining::MAX_PASSES`] levels.
pub fn passes(f: &HeightField, inside: &[bool], step: f64, grid: f64) -> Option<Vec<Vec<DVec2>>> {
    let sources: Vec<(usize, f64)> = boundary_nodes(f, inside).into_iter().map(|n| (n, 0.0)).collect();
    let d = geodesic(f, inside, &sources);
    let top = d.iter().copied().filter(|x| x.is_finite()).fold(0.0, f64::max);
    if top / step > crate::machining::MAX_PASSES {
        return None;
    }
    let levels: Vec<f64> = (0..).map(|k| (k as f64 + 0.5) * step).take_while(|&l| l < top).collect();
    let mut lines: Vec<Vec<DVec2>> = iso_lines(f, &d, &levels).into_iter().flatten().filter(|l| l.len() > 1).collect();
    let left = uncovered(f, inside, &lines, REACH * step);
    if left.iter().any(|&u| u) {
        lines.extend(ridge_lines(f, &d, &left, 0.25 * grid));
    }
    Some(order(lines))
}

/// Passes in the order to cut them: from the end of one to the nearest start of another (a
/// closed pass starts at its point nearest to where the tool is), the first the first given.
pub fn order(mut passes: Vec<Vec<DVec2>>) -> Vec<Vec<DVec2>> {
    let mut out: Vec<Vec<DVec2>> = Vec::with_capacity(passes.len());
    let mut at: Option<DVec2> = None;
    while !passes.is_empty() {
        let Some(here) = at else {
            let first = passes.remove(0);
            at = first.last().copied();
            out.push(first);
            continue;
        };
        let mut best = (f64::INFINITY, 0, 0, false);
        for (k, p) in passes.iter().enumerate() {
            let closed = p.len() > 2 && p[0].distance(p[p.len() - 1]) < 1e-9;
            if closed {
                for (i, q) in p.iter().enumerate() {
                    let d = q.distance_squared(here);
                    if d < best.0 {
                        best = (d, k, i, false);
                    }
                }
            } else {
                for (rev, q) in [(false, p[0]), (true, p[p.len() - 1])] {
                    let d = q.distance_squared(here);
                    if d < best.0 {
                        best = (d, k, 0, rev);
                    }
                }
            }
        }
        let (_, k, i, rev) = best;
        let mut p = passes.swap_remove(k);
        if i > 0 {
            p.pop();
            p.rotate_left(i);
            p.push(p[0]);
        }
        if rev {
            p.reverse();
        }
        at = p.last().copied();
        out.push(p);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(n: usize, s: f64) -> HeightField {
        HeightField { origin: DVec2::ZERO, spacing: s, nx: n, ny: n, z: vec![0.0; n * n] }
    }

    #[test]
    fn on_a_plane_the_distance_is_the_distance_to_the_edge_within_the_stencils_error() {
        let f = flat(41, 0.5);
        let inside = vec![true; f.z.len()];
        let sources: Vec<(usize, f64)> = boundary_nodes(&f, &inside).into_iter().map(|n| (n, 0.0)).collect();
        let d = geodesic(&f, &inside, &sources);
        for j in 0..41 {
            for i in 0..41 {
                let want = (i.min(40 - i).min(j).min(40 - j)) as f64 * 0.5;
                let got = d[j * 41 + i];
                assert!(got >= want - 1e-9 && got <= want * 1.014 + 1e-9, "{i} {j}: {got} against {want}");
            }
        }
    }

    #[test]
    fn on_a_slope_the_distance_grows_by_the_slopes_length() {
        // z = x: the distance from the left edge along the slope is √2 x.
        let mut f = flat(21, 0.5);
        for j in 0..21 {
            for i in 0..21 {
                f.z[j * 21 + i] = i as f64 * 0.5;
            }
        }
        let inside = vec![true; f.z.len()];
        let sources: Vec<(usize, f64)> = (0..21).map(|j| (j * 21, 0.0)).collect();
        let d = geodesic(&f, &inside, &sources);
        assert!((d[10 * 21 + 20] - 10.0 * 2f64.sqrt()).abs() < 1e-9);
    }

    #[test]
    fn a_circles_level_line_is_one_closed_loop_with_the_inside_on_its_left() {
        let f = flat(41, 0.25);
        let v: Vec<f64> = (0..f.z.len()).map(|n| 3.0 - f.grid().node(n % 41, n / 41).distance(DVec2::splat(5.0))).collect();
        let lines = &iso_lines(&f, &v, &[1.0])[0];
        assert_eq!(lines.len(), 1);
        let line = &lines[0];
        assert!(line[0].distance(line[line.len() - 1]) < 1e-12, "closed");
        for p in line {
            assert!((p.distance(DVec2::splat(5.0)) - 2.0).abs() < 0.01, "{p}");
        }
        // Counter-clockwise: the higher values (the circle's inside) on the left.
        let area: f64 = line.windows(2).map(|w| w[0].perp_dot(w[1])).sum::<f64>() / 2.0;
        assert!((area - std::f64::consts::PI * 4.0).abs() < 0.05, "{area}");
    }

    #[test]
    fn the_step_for_a_cusp() {
        assert!((stepover_for_cusp(3.0, 0.01) - 2.0 * (0.06f64 - 0.0001).sqrt()).abs() < 1e-12);
    }
}
