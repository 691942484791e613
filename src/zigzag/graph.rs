//! Seed 004 §2.1–2.2: the intersection-points graph of a region and scan lines, and the
//! direction-parallel path found by walking it with a stack.
//!
//! Scan lines at the step-over cross the region's boundary (the tool centre's region: already
//! offset by the tool radius and allowances) at nodes. Each node links left or right to its
//! partner on the same line (the span between them lies in the region: the paper's step 2), and
//! up or down to the first node met along the boundary on the next or previous line (steps 3 and
//! 4: the first and last nodes of a line, its "end" nodes, are linked the same way, by the
//! boundary). The walk (§2.2) cuts a span, moves up (or down) along the boundary to the next
//! line and cuts back, pushing every unvisited neighbour it passes on a stack; when it is stuck
//! it pops the stack, so the tool leaves the material only where the region forces it.

use crate::drawing::{Loop, Shape};
use crate::geom::segment::{arc_lengths, pieces, Segment};
use crate::geom::DVec2;

/// Points for moving along `piece`, a piece of a region's boundary (the region on its left),
/// from its start, short of its end, each line between them within `chord` of it and never
/// outside the region: along an arc that bends the region's way (the region inside its
/// circle) the points lie on the arc; along one that bends away (a hole's side) they stand
/// out so that each line between them touches the arc from the region's side.
pub fn along_boundary(piece: &Segment, chord: f64, out: &mut Vec<DVec2>) {
    out.push(piece.a);
    let Some(g) = piece.arc_geom() else { return };
    let sweep = g.sweep();
    // Sub-arcs of angle d: a chord's sagitta and a tangent polygon's overshoot are both
    // about r d² / 8.
    let n = ((sweep.abs() / (8.0 * chord / g.radius).sqrt().max(1e-6)).ceil() as usize).max(1);
    let d = sweep / n as f64;
    let a0 = (piece.a - g.center).to_angle();
    if sweep > 0.0 {
        out.extend((1..n).map(|k| g.center + DVec2::from_angle(a0 + d * k as f64) * g.radius));
    } else {
        let rho = g.radius / (0.5 * d).cos();
        out.extend((0..n).map(|k| g.center + DVec2::from_angle(a0 + d * (k as f64 + 0.5)) * rho));
    }
}

/// One crossing of a scan line with the region's boundary.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Where it is, in the scan frame (scan lines run along +x).
    pub p: DVec2,
    /// Its scan line, from the bottom.
    pub line: usize,
    /// The boundary loop it lies on and its arc length along that loop.
    pub on: usize,
    pub s: f64,
    /// The other end of its span on the same line (the paper's left-right link).
    pub partner: usize,
    /// The first node met along the boundary on the line above, and below.
    pub up: Option<usize>,
    pub down: Option<usize>,
    /// Whether the boundary leads up (or down) from here going forward along its loop.
    up_forward: bool,
    /// The first or last node of its line (the paper's end mark).
    pub end: bool,
}

/// The intersection-points graph of a region.
#[derive(Clone, Debug)]
pub struct Graph {
    pub nodes: Vec<Node>,
    /// The region's loops in the scan frame, as segments with their arc lengths.
    loops: Vec<(Vec<Segment>, Vec<f64>, f64)>,
    /// The scan direction (radians from +x).
    pub angle: f64,
    /// Heights of the scan lines in the scan frame.
    pub lines: Vec<f64>,
}

/// How spans are cut.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pattern {
    /// Back and forth, the direction alternating from line to line (the paper's path).
    Zigzag,
    /// Every span the same way, returning along the span just cut before moving up.
    OneWay,
}

impl Graph {
    /// The graph of `region` (outer loops counter-clockwise, holes clockwise) and scan lines at
    /// `angle` (radians from +x), at most `step` apart.
    pub fn new(region: &Shape, angle: f64, step: f64) -> Graph {
        let turned: Vec<Loop> = region.loops.iter().map(|l| l.rotated(-angle)).collect();
        let bounds = Shape::from_oriented(turned.clone()).bounds();
        // Lines strictly inside, evenly spaced no more than a step apart, the first and last
        // no farther than a step from the region's bottom and top (the boundary pass cuts
        // there).
        let height = bounds.max.y - bounds.min.y;
        let count = ((height / step).ceil() as usize).saturating_sub(1);
        let gap = height / (count + 1) as f64;
        let lines: Vec<f64> = (1..=count).map(|j| bounds.min.y + gap * j as f64).collect();
        let loops: Vec<(Vec<Segment>, Vec<f64>, f64)> = turned
            .iter()
            .map(|l| {
                let segs: Vec<Segment> = l.segments().collect();
                let (starts, total) = arc_lengths(&segs);
                (segs, starts, total)
            })
            .collect();
        let mut nodes = Vec::new();
        for (j, &y) in lines.iter().enumerate() {
            let first = nodes.len();
            for (on, (segs, starts, _)) in loops.iter().enumerate() {
                for (k, seg) in segs.iter().enumerate() {
                    for x in seg.crossings_at_y(y) {
                        let p = DVec2::new(x, y);
                        let s = starts[k] + seg.closest(p).1 * seg.length();
                        nodes.push(Node { p, line: j, on, s, partner: 0, up: None, down: None, up_forward: false, end: false });
                    }
                }
            }
            // Step 1: the ends; step 2: spans pair the crossings in order along the line.
            crate::geom::sort::sort_by_float(&mut nodes[first..], |a| a.p.x);
            let n = nodes.len() - first;
            if n % 2 == 1 {
                // A line grazing a vertex: drop the odd crossing out (the half-open rule makes
                // this rare).
                nodes.truncate(first + n - 1);
            }
            let n = nodes.len() - first;
            for k in 0..n {
                nodes[first + k].partner = first + (k ^ 1);
                nodes[first + k].end = k == 0 || k + 1 == n;
            }
        }
        // Steps 3 and 4: along each loop, a node links to the next node met on a neighbouring
        // line (end nodes included).
        for on in 0..loops.len() {
            let mut along: Vec<usize> = (0..nodes.len()).filter(|&i| nodes[i].on == on).collect();
            crate::geom::sort::sort_by_float(&mut along, |&a| nodes[a].s);
            let n = along.len();
            for k in 0..n {
                let (a, b) = (along[k], along[(k + 1) % n]);
                if n < 2 || a == b {
                    continue;
                }
                let (la, lb) = (nodes[a].line, nodes[b].line);
                if lb == la + 1 {
                    nodes[a].up = Some(b);
                    nodes[a].up_forward = true;
                    nodes[b].down = Some(a);
                } else if la == lb + 1 {
                    nodes[a].down = Some(b);
                    nodes[b].up = Some(a);
                    nodes[b].up_forward = false;
                }
            }
        }
        Graph { nodes, loops, angle, lines }
    }

    /// The boundary between node `a` and its neighbour `b` (up or down), as points in the scan
    /// frame within `chord` of the boundary, from `a` to `b`.
    fn boundary(&self, a: usize, b: usize, chord: f64) -> Vec<DVec2> {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        let (segs, _, total) = &self.loops[na.on];
        // Forward along the loop when b is a's forward neighbour.
        let forward = (na.up == Some(b) && na.up_forward) || (na.down == Some(b) && !nb.up_forward);
        let (s0, s1) = if forward { (na.s, if nb.s < na.s { nb.s + total } else { nb.s }) } else { (nb.s, if na.s < nb.s { na.s + total } else { na.s }) };
        let mut pts = Vec::new();
        for (_, _, piece) in pieces(segs, s0, s1, std::iter::empty()) {
            along_boundary(&piece, chord, &mut pts);
        }
        // The samples run from the point at s0, short of the one at s1.
        if pts.is_empty() {
            pts.push(if forward { na.p } else { nb.p });
        }
        if forward {
            pts[0] = na.p;
            pts.push(nb.p);
        } else {
            pts[0] = nb.p;
            pts.reverse();
            pts.insert(0, na.p);
        }
        pts
    }

    /// Back from the scan frame.
    pub fn world(&self, p: DVec2) -> DVec2 {
        DVec2::from_angle(self.angle).rotate(p)
    }

    /// The walk of §2.2: runs of points (in the region's frame) the tool cuts without leaving
    /// the region's material; a new run starts where the walk pops its stack. Climb spans keep
    /// the uncut material (above, as the walk goes up) on the tool's right: they run along -x.
    /// Every span is cut once.
    pub fn walk(&self, pattern: Pattern, climb: bool, chord: f64) -> Vec<Vec<DVec2>> {
        let nodes = &self.nodes;
        let n = nodes.len();
        let mut visited = vec![false; n];
        let mut runs = Vec::new();
        // One-way spans run along -x when climbing.
        let starts_span = |x: usize| (nodes[x].p.x > nodes[nodes[x].partner].p.x) == climb;
        // Step 1 of the walk: the lowest line's first node, on the side the first span starts
        // from.
        while let Some(first) = (0..n).filter(|&i| !visited[i]).min_by(|&a, &b| nodes[a].line.cmp(&nodes[b].line).then(nodes[a].p.x.total_cmp(&nodes[b].p.x))) {
            let first = if starts_span(first) { first } else { nodes[first].partner };
            let mut stack = vec![first];
            while let Some(x) = stack.pop() {
                if visited[x] {
                    continue;
                }
                let mut cur = if pattern == Pattern::OneWay && !starts_span(x) { nodes[x].partner } else { x };
                let mut run: Vec<DVec2> = Vec::new();
                loop {
                    let m = nodes[cur].partner;
                    visited[cur] = true;
                    visited[m] = true;
                    if run.last() != Some(&nodes[cur].p) {
                        run.push(nodes[cur].p);
                    }
                    run.push(nodes[m].p);
                    // One way: back along the span just cut, then on from its start.
                    let pivot = if pattern == Pattern::OneWay {
                        run.push(nodes[cur].p);
                        cur
                    } else {
                        m
                    };
                    let up = |i: usize| nodes[i].up.filter(|&k| !visited[k]);
                    let down = |i: usize| nodes[i].down.filter(|&k| !visited[k]);
                    // Up first, as the walk started at the bottom; down where up is done.
                    let mut next = up(pivot).or_else(|| down(pivot));
                    if pattern == Pattern::OneWay && next.is_some_and(|y| !starts_span(y)) {
                        stack.push(next.unwrap());
                        next = None;
                    }
                    for y in [up(cur), down(cur), up(m), down(m)].into_iter().flatten() {
                        if Some(y) != next {
                            stack.push(y);
                        }
                    }
                    let Some(y) = next else { break };
                    let way = self.boundary(pivot, y, chord);
                    run.extend(way.into_iter().skip(1));
                    cur = y;
                }
                runs.push(run.into_iter().map(|p| self.world(p)).collect());
            }
        }
        runs
    }

    /// The number of spans.
    pub fn spans(&self) -> usize {
        self.nodes.len() / 2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Loop {
        Loop::rect(DVec2::new(x0, y0), DVec2::new(x1, y1))
    }

    #[test]
    fn moves_along_a_boundary_arc_never_leave_the_region_and_stay_within_the_chord() {
        let c = DVec2::new(3.0, -2.0);
        for ccw in [true, false] {
            // The region on the left: inside the circle going counter-clockwise, outside it
            // going clockwise (a hole).
            let arc = Segment::arc(c + DVec2::new(7.0, 0.0), c + DVec2::new(0.0, 7.0), c, ccw);
            let mut pts = Vec::new();
            along_boundary(&arc, 0.002, &mut pts);
            pts.push(arc.b);
            assert!(pts.len() > 10);
            for w in pts.windows(2) {
                for k in 0..=20 {
                    let d = w[0].lerp(w[1], k as f64 / 20.0).distance(c);
                    if ccw {
                        assert!((7.0 - 0.0021..=7.0 + 1e-12).contains(&d), "{d}");
                    } else {
                        assert!((7.0 - 1e-12..=7.0 + 0.0021).contains(&d), "{d}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_rectangle_is_one_run_that_cuts_every_line() {
        let g = Graph::new(&Shape::new(vec![rect(0.0, 0.0, 40.0, 20.0)]), 0.0, 2.0);
        assert_eq!(g.lines, (1..10).map(|j| 2.0 * j as f64).collect::<Vec<_>>());
        assert_eq!(g.nodes.len(), 18);
        assert!(g.nodes.iter().all(|n| n.end));
        assert!(g.nodes.iter().all(|n| (n.line == 0 || n.down.is_some()) && (n.line == 8 || n.up.is_some())));
        let runs = g.walk(Pattern::Zigzag, true, 0.001);
        assert_eq!(runs.len(), 1, "{runs:?}");
        // Every span once: 9 spans of 40 mm and 8 steps up of 2 mm along the sides.
        let len: f64 = runs[0].windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!((len - (9.0 * 40.0 + 8.0 * 2.0)).abs() < 1e-9, "{len}");
        // Climbing, the first span runs along -x from the bottom right.
        assert_eq!(runs[0][0], DVec2::new(40.0, 2.0));
    }

    #[test]
    fn a_u_shape_pops_its_stack_once() {
        // A U opening upwards: a base 40 × 10, two prongs 10 wide and 20 tall.
        let u = Loop::polygon(&[
            DVec2::new(0.0, 0.0),
            DVec2::new(40.0, 0.0),
            DVec2::new(40.0, 30.0),
            DVec2::new(30.0, 30.0),
            DVec2::new(30.0, 10.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(10.0, 30.0),
            DVec2::new(0.0, 30.0),
        ]);
        let g = Graph::new(&Shape::new(vec![u]), 0.0, 1.0);
        let runs = g.walk(Pattern::Zigzag, true, 0.001);
        assert_eq!(runs.len(), 2, "one prong is reached by the stack: {}", runs.len());
        let spans: usize = g.spans();
        let cut: usize = runs.iter().map(|r| r.windows(2).filter(|w| (w[0].y - w[1].y).abs() < 1e-12 && w[0].distance(w[1]) > 5.0).count()).sum();
        assert_eq!(cut, spans);
    }

    #[test]
    fn islands_split_lines_into_spans_and_the_walk_cuts_each_once() {
        for islands in [1, 2] {
            let mut loops = vec![rect(0.0, 0.0, 60.0, 30.0)];
            for k in 0..islands {
                let x = 15.0 + 25.0 * k as f64;
                loops.push(rect(x, 10.0, x + 8.0, 20.0).reversed());
            }
            let g = Graph::new(&Shape::new(loops), 0.0, 1.5);
            // Lines through the islands have 2 + 2 × islands nodes.
            let mid = g.lines.iter().position(|&y| (y - 15.0).abs() < 1.0).unwrap();
            assert_eq!(g.nodes.iter().filter(|n| n.line == mid).count(), 2 + 2 * islands);
            let runs = g.walk(Pattern::Zigzag, false, 0.001);
            let cut: usize = runs.iter().map(|r| r.windows(2).filter(|w| (w[0].y - w[1].y).abs() < 1e-12 && w[0].distance(w[1]) > 1.6).count()).sum();
            assert_eq!(cut, g.spans(), "{islands} islands");
            assert!(runs.len() <= 1 + 2 * islands, "{islands} islands: {} runs", runs.len());
        }
    }

    #[test]
    fn one_way_cuts_every_span_in_the_same_direction() {
        let g = Graph::new(&Shape::new(vec![rect(0.0, 0.0, 30.0, 12.0)]), 0.0, 3.0);
        for climb in [true, false] {
            let runs = g.walk(Pattern::OneWay, climb, 0.001);
            assert_eq!(runs.len(), 1);
            let r = &runs[0];
            // Spans: out along the line, then back; the outward one points -x when climbing.
            let out: Vec<f64> = r.windows(3).filter(|w| (w[0] - w[2]).length() < 1e-12 && w[0].distance(w[1]) > 20.0).map(|w| (w[1].x - w[0].x).signum()).collect();
            assert_eq!(out.len(), g.spans());
            assert!(out.iter().all(|&d| d == if climb { -1.0 } else { 1.0 }), "{out:?}");
        }
    }
}
