//! Holes: where they are (a drawing's circles, [`in_drawing`]; a part's vertical cylindrical
//! bores, [`mesh`]), and the order a drilling operation visits them in (nearest neighbour,
//! then 2-opt, [`order`]).

pub mod mesh;

use serde::{Deserialize, Serialize};

use crate::drawing::Drawing;
use crate::geom::DVec2;

/// A round vertical hole.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Hole {
    /// Centre (mm).
    #[ts(type = "[number, number]")]
    pub center: DVec2,
    pub diameter: f64,
    /// Where the hole starts and ends (Z, mm); a drawing's holes go through the sheet.
    pub top: f64,
    pub bottom: f64,
    /// Open at the bottom.
    pub through: bool,
    /// How its bottom ends where it is blind: flat, or a cone (a drill's point).
    pub bottom_shape: Bottom,
    /// The number `swarf drawing` lists a drawing's hole by: its loop's, or for a drill mark the
    /// number after the loops (the loops' count plus the mark's place among the marks).
    pub loop_index: Option<usize>,
    /// The drawing's layer, for a drawing's hole.
    pub layer: Option<String>,
    /// A drill mark (a DXF POINT): a place to drill with no diameter of its own (`diameter` is
    /// 0); drilling makes it as wide as its drill, and the operations that need a hole's size
    /// (bore, chamfer, thread) refuse it.
    #[serde(default)]
    pub mark: bool,
}

/// A blind hole's bottom.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Bottom {
    Flat,
    /// A cone, as a drill leaves it.
    Cone,
    /// None: the hole goes through.
    Open,
}

impl Hole {
    /// Its depth from its top.
    pub fn depth(&self) -> f64 {
        self.top - self.bottom
    }
}

/// How far from a circle a polygon's vertex may lie for the loop to be taken as one (a circle
/// written as a polyline), relative to its radius.
const ROUND: f64 = 1e-3;

/// The fewest vertices a polygon needs to be taken as a circle.
const FEWEST_SIDES: usize = 8;

/// The drawing's closed loops that are circles (a CIRCLE, two or more arcs about one centre,
/// or a polyline of at least eight vertices all within 0.1 % of the radius from a circle), as
/// holes through a sheet from `top` to `bottom`, in the drawing's loop order; then its drill
/// marks (DXF POINTs), numbered after the loops.
pub fn in_drawing(drawing: &Drawing, top: f64, bottom: f64) -> Vec<Hole> {
    drawing
        .loops
        .iter()
        .enumerate()
        .filter_map(|(k, l)| {
            let (center, radius) = circle_of(&l.path)?;
            Some(Hole { center, diameter: 2.0 * radius, top, bottom, through: true, bottom_shape: Bottom::Open, loop_index: Some(k), layer: Some(l.layer.clone()), mark: false })
        })
        .chain(drawing.points.iter().enumerate().map(|(i, p)| Hole {
            center: p.at,
            diameter: 0.0,
            top,
            bottom,
            through: true,
            bottom_shape: Bottom::Open,
            loop_index: Some(drawing.loops.len() + i),
            layer: Some(p.layer.clone()),
            mark: true,
        }))
        .collect()
}

/// The centre and radius of a loop that is a circle.
pub fn circle_of(path: &crate::drawing::Loop) -> Option<(DVec2, f64)> {
    let segments: Vec<_> = path.segments().collect();
    if segments.is_empty() {
        return None;
    }
    if segments.iter().all(|s| !s.is_line()) {
        let arcs: Vec<_> = segments.iter().filter_map(|s| s.arc_geom()).collect();
        let (c, r) = (arcs.first()?.center, arcs.first()?.radius);
        let sweep: f64 = arcs.iter().map(|a| a.sweep()).sum();
        let same = arcs.iter().all(|a| a.center.distance(c) <= ROUND * r && (a.radius - r).abs() <= ROUND * r);
        return (same && (sweep.abs() - std::f64::consts::TAU).abs() < 1e-6).then_some((c, r));
    }
    if segments.len() < FEWEST_SIDES || segments.iter().any(|s| !s.is_line()) {
        return None;
    }
    // The centre of the vertices' bounding box, checked against every vertex.
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for s in &segments {
        lo = lo.min(s.a);
        hi = hi.max(s.a);
    }
    let c = (lo + hi) * 0.5;
    let r = segments.iter().map(|s| s.a.distance(c)).sum::<f64>() / segments.len() as f64;
    // Every vertex on the circle, and no side longer than a sixth of the turn.
    let round = segments.iter().all(|s| (s.a.distance(c) - r).abs() <= ROUND * r && s.a.distance(s.b) <= r * 1.01);
    (r > 0.0 && round).then_some((c, r))
}

/// The order to visit `points` in, from `start`: nearest neighbour first, then 2-opt (a
/// stretch of the tour reversed wherever that shortens it) until no reversal does. The tour
/// is open (it ends at its last point). Past 2,000 points (a perforated panel's tens of
/// thousands), the nearest is found in a grid and 2-opt reverses stretches of at most 64
/// points: the work grows with the points, not with their square (30,000 holes took 10 s).
pub fn order(points: &[DVec2], start: DVec2) -> Vec<usize> {
    let n = points.len();
    let mut tour = if n <= EXHAUSTIVE { nearest_first(points, start) } else { nearest_first_in_grid(points, start) };
    let window = if n <= EXHAUSTIVE { n } else { WINDOW };
    // 2-opt on the open path start → tour[0] → … → tour[n-1].
    let at = |tour: &[usize], i: usize| if i == 0 { start } else { points[tour[i - 1]] };
    let mut improved = true;
    let mut rounds = 0;
    while improved && rounds < 100 {
        improved = false;
        rounds += 1;
        for i in 1..=n {
            for j in i + 1..=n.min(i + window) {
                // Reverse tour[i-1..j]: the edges (at(i-1), at(i)) and (at(j), at(j+1)) become
                // (at(i-1), at(j)) and (at(i), at(j+1)); the last point has no edge after it.
                let (a, b, c) = (at(&tour, i - 1), at(&tour, i), at(&tour, j));
                let d = (j < n).then(|| at(&tour, j + 1));
                let before = a.distance(b) + d.map_or(0.0, |d| c.distance(d));
                let after = a.distance(c) + d.map_or(0.0, |d| b.distance(d));
                if after < before - 1e-9 {
                    tour[i - 1..j].reverse();
                    improved = true;
                }
            }
        }
    }
    tour
}

/// Up to this many points, the tour is searched exhaustively (every point for the nearest,
/// every stretch for 2-opt).
const EXHAUSTIVE: usize = 2000;
/// The longest stretch 2-opt reverses past [`EXHAUSTIVE`] points.
const WINDOW: usize = 64;

/// Nearest neighbour first, from `start`: each next point the nearest left.
fn nearest_first(points: &[DVec2], start: DVec2) -> Vec<usize> {
    let mut tour = Vec::with_capacity(points.len());
    let mut left: Vec<usize> = (0..points.len()).collect();
    let mut here = start;
    while !left.is_empty() {
        let (k, _) = left.iter().enumerate().min_by(|a, b| points[*a.1].distance_squared(here).total_cmp(&points[*b.1].distance_squared(here))).expect("points left");
        let next = left.swap_remove(k);
        here = points[next];
        tour.push(next);
    }
    tour
}

/// [`nearest_first`] with the points left in a grid of about one a cell, searched ring by ring
/// out from where the tour stands until no nearer one can lie further out.
fn nearest_first_in_grid(points: &[DVec2], start: DVec2) -> Vec<usize> {
    let n = points.len();
    let (lo, hi) = points.iter().fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let size = (hi - lo).max(DVec2::splat(1e-9));
    let cell = (size.x * size.y / n as f64).sqrt().max(size.max_element() / n as f64).max(1e-9);
    let (gx, gy) = (((size.x / cell).floor() as usize + 1).min(1 << 15), ((size.y / cell).floor() as usize + 1).min(1 << 15));
    let key = |p: DVec2| (((p.x - lo.x) / cell).floor().clamp(0.0, (gx - 1) as f64) as usize, ((p.y - lo.y) / cell).floor().clamp(0.0, (gy - 1) as f64) as usize);
    let mut buckets: Vec<Vec<usize>> = vec![Vec::new(); gx * gy];
    for (k, &p) in points.iter().enumerate() {
        let (i, j) = key(p);
        buckets[j * gx + i].push(k);
    }
    let mut tour = Vec::with_capacity(n);
    let mut here = start;
    while tour.len() < n {
        let (ci, cj) = key(here);
        let mut best: Option<(f64, usize)> = None;
        for ring in 0..gx.max(gy) {
            // A point in this ring or further out lies at least `ring - 1` cells from here
            // (from outside the grid, further: its cell is the nearest edge's).
            if best.is_some_and(|(d, _)| d.sqrt() < (ring as f64 - 1.0) * cell) {
                break;
            }
            let (i0, i1, j0, j1) = (ci as i64 - ring as i64, ci as i64 + ring as i64, cj as i64 - ring as i64, cj as i64 + ring as i64);
            for j in j0.max(0)..=j1.min(gy as i64 - 1) {
                for i in i0.max(0)..=i1.min(gx as i64 - 1) {
                    if ring > 0 && i != i0 && i != i1 && j != j0 && j != j1 {
                        continue;
                    }
                    for &k in &buckets[j as usize * gx + i as usize] {
                        let d = points[k].distance_squared(here);
                        if best.is_none_or(|(b, bk)| (d, k) < (b, bk)) {
                            best = Some((d, k));
                        }
                    }
                }
            }
        }
        let (_, next) = best.expect("points left");
        let (i, j) = key(points[next]);
        buckets[j * gx + i].retain(|&k| k != next);
        here = points[next];
        tour.push(next);
    }
    tour
}

/// The length of the open tour from `start` through `points` in `order`.
pub fn tour_length(points: &[DVec2], order: &[usize], start: DVec2) -> f64 {
    let mut here = start;
    let mut total = 0.0;
    for &k in order {
        total += here.distance(points[k]);
        here = points[k];
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_opt_untangles_a_crossed_tour_and_never_lengthens_it() {
        let mut seed = 5u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [1, 2, 5, 40, 200] {
            let points: Vec<DVec2> = (0..n).map(|_| DVec2::new(rnd() * 100.0, rnd() * 60.0)).collect();
            let tour = order(&points, DVec2::ZERO);
            let mut sorted = tour.clone();
            sorted.sort();
            assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "every hole once");
            // Against nearest neighbour alone.
            let mut left: Vec<usize> = (0..n).collect();
            let (mut here, mut greedy) = (DVec2::ZERO, 0.0);
            while !left.is_empty() {
                let (k, _) = left.iter().enumerate().min_by(|a, b| points[*a.1].distance(here).total_cmp(&points[*b.1].distance(here))).unwrap();
                let p = points[left.swap_remove(k)];
                greedy += here.distance(p);
                here = p;
            }
            assert!(tour_length(&points, &tour, DVec2::ZERO) <= greedy + 1e-9);
        }
        // A grid of holes: the tour is the snake, 9 steps of 10 mm and the way in.
        let grid: Vec<DVec2> = (0..10).map(|k| DVec2::new((k % 5) as f64 * 10.0, (k / 5) as f64 * 10.0)).collect();
        let tour = order(&grid, DVec2::ZERO);
        assert!((tour_length(&grid, &tour, DVec2::ZERO) - 90.0).abs() < 1e-9, "{tour:?}");
    }

    #[test]
    fn circles_are_found_in_arcs_and_in_fine_polylines_only() {
        let c = DVec2::new(3.0, -2.0);
        assert_eq!(circle_of(&crate::drawing::Loop::circle(c, 2.5)), Some((c, 2.5)));
        let polygon = |n: usize, r: f64| crate::drawing::Loop::polygon(&(0..n).map(|k| c + DVec2::from_angle(k as f64 * std::f64::consts::TAU / n as f64) * r).collect::<Vec<_>>());
        let (found, r) = circle_of(&polygon(64, 4.0)).expect("a 64-gon is a circle");
        assert!(found.distance(c) < 1e-9 && (r - 4.0).abs() < 4e-3);
        assert_eq!(circle_of(&polygon(6, 4.0)), None, "a hexagon is no hole");
        assert_eq!(circle_of(&crate::drawing::Loop::rect(DVec2::ZERO, DVec2::ONE)), None);
    }
}
