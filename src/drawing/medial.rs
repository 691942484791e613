//! The medial axis of a drawing's region, for V-carving: the points inside it with two or more
//! nearest points on its boundary, each with its clearance (its distance to the boundary). Made
//! from the Voronoi diagram of the boundary's segments (arcs taken as chords within a given
//! tolerance), which `boostvoronoi` builds by Boost.Polygon's sweepline on integer coordinates:
//! the diagram's primary edges inside the region are the axis. An edge between two segments is
//! straight; one between a segment and a corner (a reflex vertex of the boundary) is a parabola,
//! sampled here from its own equation, so every point's clearance is exact for the chords.

use boostvoronoi::{Builder, SourceCategory};

use super::Shape;
use crate::geom::segment::{chord_step, Segment};
use crate::geom::DVec2;
use crate::mesh::union_root;

/// A piece of the medial axis: points along it and their clearances (mm).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Branch {
    pub points: Vec<DVec2>,
    pub clearance: Vec<f64>,
}

impl Branch {
    pub fn reversed(&self) -> Branch {
        Branch { points: self.points.iter().rev().copied().collect(), clearance: self.clearance.iter().rev().copied().collect() }
    }
}

/// A boundary site of the diagram: a segment, or one of its ends.
#[derive(Clone, Copy, Debug)]
enum Site {
    Point(DVec2),
    Segment(DVec2, DVec2),
}

impl Site {
    fn distance(&self, p: DVec2) -> f64 {
        match *self {
            Site::Point(q) => p.distance(q),
            Site::Segment(a, b) => Segment::line(a, b).distance_to(p),
        }
    }
}

/// The boundary of `region` as closed polygons: lines as they are, arcs as chords no farther
/// than `chord` from them.
fn polygons(region: &Shape, chord: f64) -> Vec<Vec<DVec2>> {
    region
        .loops
        .iter()
        .map(|l| {
            let mut pts = Vec::new();
            for s in l.segments() {
                match s.arc_geom() {
                    None => pts.push(s.a),
                    Some(g) => {
                        let sweep = g.sweep().abs();
                        let step = chord_step(g.radius, chord).unwrap_or(sweep);
                        let n = ((sweep / step.max(1e-3)).ceil() as usize).clamp(1, 10_000);
                        pts.extend((0..n).map(|k| s.point_at(k as f64 / n as f64)));
                    }
                }
            }
            pts
        })
        .collect()
}

/// The medial axis of `region` (outlines counter-clockwise with their islands, as a [`Shape`]
/// holds them): each primary Voronoi edge inside the region as a branch, its ends alone where
/// the clearance changes linearly along it (a straight edge between two segments), else
/// sampled at most `step` apart; branches joined end to end where they meet. `reach` is the
/// largest clearance the carving uses (its cone's at its deepest; beyond it a floor's walls
/// are cut apart from the axis): spikes into corners that carve nothing the rest of the axis
/// and those walls leave are left out ([`SPIKE_SLIVER`]).
pub fn medial_axis(region: &Shape, chord: f64, step: f64, reach: f64) -> Result<Vec<Branch>, String> {
    let b = region.bounds();
    if b.is_empty() {
        return Ok(Vec::new());
    }
    // Integer coordinates for the sweepline: 10 nm, or coarser for a very large drawing.
    let scale = (1e5f64).min(1e9 / b.size().max_element().max(1e-9));
    let origin = b.min;
    let quantize = |p: DVec2| [((p.x - origin.x) * scale).round() as i32, ((p.y - origin.y) * scale).round() as i32];
    let back = |q: [i32; 2]| origin + DVec2::new(q[0] as f64, q[1] as f64) / scale;
    let mut segments: Vec<[i32; 4]> = Vec::new();
    for poly in polygons(region, chord) {
        let mut q: Vec<[i32; 2]> = Vec::new();
        for p in poly {
            let p = quantize(p);
            if q.last() != Some(&p) {
                q.push(p);
            }
        }
        while q.len() > 1 && q.first() == q.last() {
            q.pop();
        }
        if q.len() < 3 {
            continue;
        }
        for k in 0..q.len() {
            let (a, c) = (q[k], q[(k + 1) % q.len()]);
            segments.push([a[0], a[1], c[0], c[1]]);
        }
    }
    if segments.is_empty() {
        return Ok(Vec::new());
    }
    let sites: Vec<(DVec2, DVec2)> = segments.iter().map(|s| (back([s[0], s[1]]), back([s[2], s[3]]))).collect();
    // The diagram is of segments that meet only at their ends: a loop crossing itself or
    // another would give an axis outside the region (or none).
    if let Some(q) = crossing(&segments) {
        let p = origin + q / scale;
        return Err(format!("the outline crosses itself or another loop at X{:.3} Y{:.3}: a V-carve follows loops that do not cross; mend the drawing there", p.x, p.y));
    }
    let diagram = Builder::<i32, f64>::default()
        .with_segments(segments.iter())
        .and_then(|b| b.build())
        .map_err(|e| format!("the medial axis could not be built from these {} segments ({e:?}); a drawing of loops that touch or nearly cross is the usual cause", segments.len()))?;
    let site_of = |cell: boostvoronoi::CellIndex| -> Result<Site, String> {
        let cell = diagram.get_cell(cell).map_err(|e| e.to_string())?.get();
        let (a, c) = sites[cell.source_index()];
        Ok(match cell.source_category() {
            SourceCategory::SegmentStart => Site::Point(a),
            SourceCategory::SegmentEnd => Site::Point(c),
            _ => Site::Segment(a, c),
        })
    };
    let vertex = |v: boostvoronoi::VertexIndex| -> Result<DVec2, String> {
        let v = diagram.vertex_get(v).map_err(|e| e.to_string())?.get();
        Ok(origin + DVec2::new(v.x(), v.y()) / scale)
    };
    // Each edge once (an edge and its twin), both ends finite, primary, inside the region.
    let mut edges: Vec<(usize, usize, Branch)> = Vec::new();
    for e in diagram.edges() {
        let edge = e.get();
        let id = edge.id();
        let twin = edge.twin().map_err(|e| e.to_string())?;
        if twin.0 < id.0 || !edge.is_primary() {
            continue;
        }
        let (Some(v0), Some(v1)) = (edge.vertex0(), diagram.edge_get_vertex1(id).map_err(|e| e.to_string())?) else { continue };
        let (p0, p1) = (vertex(v0)?, vertex(v1)?);
        let s1 = site_of(edge.cell().map_err(|e| e.to_string())?)?;
        let s2 = site_of(diagram.get_edge(twin).map_err(|e| e.to_string())?.get().cell().map_err(|e| e.to_string())?)?;
        if needless_spike(s1, s2, p0, p1, reach, SPIKE_SLIVER * chord) {
            continue;
        }
        let points = match (edge.is_curved(), s1, s2) {
            (true, Site::Point(p), Site::Segment(a, c)) | (true, Site::Segment(a, c), Site::Point(p)) => parabola(p, a, c, p0, p1, step),
            // Between two segments the clearance is the distance to either's line, which changes
            // linearly along a straight edge: its ends are enough.
            (false, Site::Segment(..), Site::Segment(..)) => vec![p0, p1],
            _ => line(p0, p1, step),
        };
        // Inside the region: judged at the edge's middle (never at an end, which may lie on
        // the boundary while the edge runs outside it).
        let mid = if points.len() == 2 { points[0].lerp(points[1], 0.5) } else { points[points.len() / 2] };
        if !region.contains(mid) || region.distance_to(mid) <= 1e-9 {
            continue;
        }
        let clearance = points.iter().map(|&q| s1.distance(q).min(s2.distance(q))).collect();
        edges.push((v0.0, v1.0, Branch { points, clearance }));
    }
    // Edges shorter than the slivers spikes are dropped by are taken as their ends met: the
    // tangle of tiny edges where an arc's chord spikes would meet, near its centre, becomes one
    // junction the branches run through.
    let tiny = SPIKE_SLIVER * chord;
    let mut parent: Vec<usize> = (0..edges.iter().map(|e| e.0.max(e.1) + 1).max().unwrap_or(0)).collect();
    let mut kept = Vec::with_capacity(edges.len());
    for (v0, v1, b) in edges {
        if b.points.windows(2).map(|p| p[0].distance(p[1])).sum::<f64>() < tiny {
            let (r0, r1) = (union_root(&mut parent, v0), union_root(&mut parent, v1));
            parent[r0] = r1;
        } else {
            kept.push((v0, v1, b));
        }
    }
    let kept = kept.into_iter().map(|(v0, v1, b)| (union_root(&mut parent, v0), union_root(&mut parent, v1), b)).collect();
    Ok(joined(kept))
}

/// A spike into a corner is left out where all it would carve, beside what the rest of the
/// axis carves, lies within this many chord tolerances of the corner: the corners between an
/// arc's chords or a flattened curve's (the chords stand within one chord tolerance of the
/// curve, and a convex curve's spikes run to its centre of curvature, carving slivers about as
/// thick as that), well within the walls' 0.02 mm.
pub const SPIKE_SLIVER: f64 = 4.0;

/// Whether the edge `p0`–`p1` between two sites is a spike into a corner of the boundary that
/// carves nothing the rest of the axis leaves: an edge between two segments meeting at a
/// corner, from the corner in, where they turn so little that the cone on the rest of the axis
/// reaches within `sliver` of the corner (the corner lies `c (1/cos(φ/2) − 1)` beyond the reach
/// of the axis point at clearance `c` the spike runs to, for a turn of φ; `c` no more than the
/// `reach` the carving uses). These are the corners between an arc's chords (no corner at all
/// on the drawn arc, and one spike each would carve it a bristle of dead-end branches) and a
/// polyline's flattest bends; a drawn corner keeps its spike.
fn needless_spike(s1: Site, s2: Site, p0: DVec2, p1: DVec2, reach: f64, sliver: f64) -> bool {
    let (Site::Segment(a1, b1), Site::Segment(a2, b2)) = (s1, s2) else { return false };
    // The corner they share, and the segments' directions through it.
    let (corner, d_in, d_out) = if b1 == a2 {
        (b1, b1 - a1, b2 - a2)
    } else if b2 == a1 {
        (b2, b2 - a2, b1 - a1)
    } else {
        return false;
    };
    let far = if p0.distance(corner) < 1e-9 {
        p1
    } else if p1.distance(corner) < 1e-9 {
        p0
    } else {
        return false;
    };
    let cos = d_in.normalize_or_zero().dot(d_out.normalize_or_zero()).clamp(-1.0, 1.0);
    let half = cos.acos() / 2.0;
    let c = s1.distance(far).min(reach);
    c * (1.0 / half.cos() - 1.0) <= sliver
}

/// Where two of `segments` (integer coordinates, as the diagram takes them) cross or overlap
/// other than at an end they share: a point of the first such pair found.
fn crossing(segments: &[[i32; 4]]) -> Option<DVec2> {
    let ends = |s: &[i32; 4]| [[s[0] as i64, s[1] as i64], [s[2] as i64, s[3] as i64]];
    let side = |a: [i64; 2], b: [i64; 2], c: [i64; 2]| ((b[0] - a[0]) as i128 * (c[1] - a[1]) as i128 - (b[1] - a[1]) as i128 * (c[0] - a[0]) as i128).signum();
    let within = |a: [i64; 2], b: [i64; 2], c: [i64; 2]| a[0].min(b[0]) <= c[0] && c[0] <= a[0].max(b[0]) && a[1].min(b[1]) <= c[1] && c[1] <= a[1].max(b[1]);
    let rects: Vec<crate::geom::segment::Rect> =
        segments.iter().map(|s| crate::geom::segment::Rect::EMPTY.grow(DVec2::new(s[0] as f64, s[1] as f64)).grow(DVec2::new(s[2] as f64, s[3] as f64))).collect();
    let mut found = None;
    crate::geom::index::RectIndex::new(&rects).pairs(|i, j| {
        if found.is_some() {
            return;
        }
        let ([a, b], [c, d]) = (ends(&segments[i]), ends(&segments[j]));
        let shared = [a, b].iter().filter(|p| **p == c || **p == d).count();
        let (d1, d2, d3, d4) = (side(a, b, c), side(a, b, d), side(c, d, a), side(c, d, b));
        let touching = |p: [i64; 2]| [a, b, c, d].iter().filter(|&&q| q == p).count() < 2;
        let at = |p: [i64; 2]| DVec2::new(p[0] as f64, p[1] as f64);
        found = if d1 * d2 < 0 && d3 * d4 < 0 {
            // A proper crossing, where the lines meet.
            let (a, b, c, d) = (at(a), at(b), at(c), at(d));
            Some(a + (b - a) * ((c - a).perp_dot(d - c) / (b - a).perp_dot(d - c)))
        } else if shared == 0 || (d1 == 0 && d2 == 0) {
            // One's end on the other (not the end they share), or the two along one line.
            [(d1, a, b, c), (d2, a, b, d), (d3, c, d, a), (d4, c, d, b)].into_iter().find(|&(o, p, q, r)| o == 0 && within(p, q, r) && touching(r)).map(|t| at(t.3))
        } else {
            None
        };
    });
    found
}

/// Points from `a` to `b` at most `step` apart.
fn line(a: DVec2, b: DVec2, step: f64) -> Vec<DVec2> {
    let n = ((a.distance(b) / step).ceil() as usize).max(1);
    (0..=n).map(|k| a.lerp(b, k as f64 / n as f64)).collect()
}

/// Points of the parabola equidistant from the point `p` and the line through `a` and `c`, from
/// `p0` to `p1` (both on it), at most about `step` apart.
fn parabola(p: DVec2, a: DVec2, c: DVec2, p0: DVec2, p1: DVec2, step: f64) -> Vec<DVec2> {
    let u = (c - a).normalize();
    let mut n = u.perp();
    let mut py = (p - a).dot(n);
    if py < 0.0 {
        n = -n;
        py = -py;
    }
    if py < 1e-9 {
        return line(p0, p1, step);
    }
    let px = (p - a).dot(u);
    let (x0, x1) = ((p0 - a).dot(u), (p1 - a).dot(u));
    let y = |x: f64| ((x - px).powi(2) + py * py) / (2.0 * py);
    // The ends as the diagram put them must lie on the parabola; where the point nearly lies on
    // the line (a spike's parabola, a few nanometres wide) its heights blow up with any error in
    // the ends (a wrench's outline once asked 20 GB of points here): the chord serves.
    let (y0, y1) = ((p0 - a).dot(n), (p1 - a).dot(n));
    let off = (y(x0) - y0).abs().max((y(x1) - y1).abs());
    if !(off <= step.max(p0.distance(p1) * 1e-3)) {
        return line(p0, p1, step);
    }
    // Its length is at most its run along the line plus its rise and fall (down to its vertex,
    // py / 2, where that lies between the ends).
    let lowest = if (x0.min(x1)..=x0.max(x1)).contains(&px) { py / 2.0 } else { y0.min(y1) };
    let length = (x1 - x0).abs() + (y0 - lowest).abs() + (y1 - lowest).abs();
    let count = (length / step).ceil().clamp(2.0, crate::limits::MAX_PATH_POINTS) as usize;
    let mut out: Vec<DVec2> = (0..=count).map(|k| x0 + (x1 - x0) * k as f64 / count as f64).map(|x| a + u * x + n * y(x)).collect();
    // The ends exactly where the diagram put them.
    out[0] = p0;
    out[count] = p1;
    out
}

/// Branches joined end to end at the vertices they share: each chain grows at its end while an
/// unused branch meets it there.
fn joined(edges: Vec<(usize, usize, Branch)>) -> Vec<Branch> {
    let mut at: std::collections::HashMap<usize, Vec<usize>> = std::collections::HashMap::new();
    for (k, (v0, v1, _)) in edges.iter().enumerate() {
        at.entry(*v0).or_default().push(k);
        at.entry(*v1).or_default().push(k);
    }
    let mut used = vec![false; edges.len()];
    let mut out = Vec::new();
    for start in 0..edges.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (begin, mut end, first) = &edges[start];
        let mut chain = first.clone();
        // On from its end, then (reversed) on from its start: a chain begun mid-way along a
        // run of edges takes the whole run.
        for forward in [true, false] {
            if !forward {
                chain = chain.reversed();
                end = *begin;
            }
            while let Some(&k) = at.get(&end).and_then(|list| list.iter().find(|&&k| !used[k])) {
                used[k] = true;
                let (v0, v1, b) = &edges[k];
                let next = if *v0 == end { b.clone() } else { b.reversed() };
                end = if *v0 == end { *v1 } else { *v0 };
                chain.points.extend_from_slice(&next.points[1..]);
                chain.clearance.extend_from_slice(&next.clearance[1..]);
            }
        }
        out.push(chain);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::{Loop, Vertex};

    /// A rectangle's axis: the middle line and the four branches to its corners, each point as
    /// far from the boundary as the axis says.
    #[test]
    fn a_rectangles_medial_axis_is_its_middle_line_and_corner_bisectors() {
        let (w, h) = (40.0, 10.0);
        let region = Shape::new(vec![Loop::rect(DVec2::ZERO, DVec2::new(w, h))]);
        let axis = medial_axis(&region, 0.001, 0.1, f64::INFINITY).unwrap();
        let mut points = 0;
        let mut middle = 0.0f64;
        for b in &axis {
            for (p, c) in b.points.iter().zip(&b.clearance) {
                let exact = p.x.min(w - p.x).min(p.y).min(h - p.y);
                assert!((c - exact).abs() < 1e-6, "at {p:?}: clearance {c}, the boundary {exact} away");
                points += 1;
                middle = middle.max(*c);
            }
        }
        // Straight edges between two sides are their ends alone: the middle line and four
        // half-diagonals.
        assert!(points >= 5, "{points} points");
        assert!((middle - h / 2.0).abs() < 1e-6);
        // Total length: the middle line w − h and four half-diagonals of h/2 · √2.
        let length: f64 = axis.iter().map(|b| b.points.windows(2).map(|p| p[0].distance(p[1])).sum::<f64>()).sum();
        assert!((length - (w - h + 4.0 * h / 2.0 * 2f64.sqrt())).abs() < 1e-3, "{length}");
    }

    /// Between the points of a branch its clearance is what the points' say, linearly: a ring
    /// (a circle round an island, both as chords) checked at points 0.01 mm apart.
    #[test]
    fn between_its_points_a_branch_keeps_its_clearance() {
        let region = Shape::new(vec![Loop::circle(DVec2::ZERO, 10.0), Loop::circle(DVec2::ZERO, 5.0)]);
        let axis = medial_axis(&region, 0.002, 0.1, f64::INFINITY).unwrap();
        let mut worst = 0.0f64;
        for b in &axis {
            for k in 1..b.points.len() {
                let n = ((b.points[k - 1].distance(b.points[k]) / 0.01).ceil() as usize).max(1);
                for i in 0..=n {
                    let t = i as f64 / n as f64;
                    let p = b.points[k - 1].lerp(b.points[k], t);
                    let c = b.clearance[k - 1] + (b.clearance[k] - b.clearance[k - 1]) * t;
                    worst = worst.max((c - region.distance_to(p)).abs());
                }
            }
        }
        assert!(worst < 0.005, "off by {worst} mm between points");
    }

    /// A ring's axis is its middle circle alone: no bristle of spikes into the corners between
    /// the chords its circles are taken as (one a chord before: hundreds of dead-end branches,
    /// each a retract and a plunge when carved); a drawn corner keeps its spike.
    #[test]
    fn an_arcs_chords_give_no_spikes_and_a_drawn_corner_keeps_its_own() {
        let region = Shape::new(vec![Loop::circle(DVec2::ZERO, 10.0), Loop::circle(DVec2::ZERO, 4.0)]);
        let axis = medial_axis(&region, 0.002, 0.1, f64::INFINITY).unwrap();
        let lowest = axis.iter().flat_map(|b| b.clearance.iter().copied()).fold(f64::INFINITY, f64::min);
        assert!(axis.len() <= 2 && lowest > 3.0 - 0.002, "{} branches, the lowest clearance {lowest}", axis.len());
        let length: f64 = axis.iter().map(|b| b.points.windows(2).map(|p| p[0].distance(p[1])).sum::<f64>()).sum();
        assert!((length - 2.0 * std::f64::consts::PI * 7.0).abs() < 0.01, "{length}");
        // An octagon turns 45° at each corner: eight spikes, each down to the corner.
        let octagon: Vec<DVec2> = (0..8).map(|k| DVec2::from_angle(k as f64 * std::f64::consts::FRAC_PI_4) * 10.0).collect();
        let axis = medial_axis(&Shape::new(vec![Loop::polygon(&octagon)]), 0.002, 0.1, f64::INFINITY).unwrap();
        let corners = octagon.iter().filter(|c| axis.iter().any(|b| b.points.iter().any(|p| p.distance(**c) < 1e-4))).count();
        assert_eq!(corners, 8, "{axis:?}");
    }

    /// A slot (two half circles joined by lines) has one branch: its middle line, whole,
    /// whichever of its many edges (between the circles' chords) the diagram lists first.
    #[test]
    fn a_slots_axis_is_one_branch() {
        let (a, b, r) = (DVec2::new(0.0, 0.0), DVec2::new(40.0, 0.0), 6.0);
        let slot = Loop {
            vertices: vec![
                Vertex { p: a - DVec2::Y * r, bulge: 0.0 },
                Vertex { p: b - DVec2::Y * r, bulge: 1.0 },
                Vertex { p: b + DVec2::Y * r, bulge: 0.0 },
                Vertex { p: a + DVec2::Y * r, bulge: 1.0 },
            ],
        };
        let axis = medial_axis(&Shape::new(vec![slot]), 0.002, 0.1, f64::INFINITY).unwrap();
        assert_eq!(
            axis.len(),
            1,
            "{} branches: {:?}",
            axis.len(),
            axis.iter().map(|b| (b.points[0], b.clearance[0], *b.points.last().unwrap(), *b.clearance.last().unwrap(), b.points.len())).collect::<Vec<_>>()
        );
        let ends = [axis[0].points[0], *axis[0].points.last().unwrap()];
        assert!(ends.iter().any(|p| p.distance(a) < 0.01) && ends.iter().any(|p| p.distance(b) < 0.01), "{ends:?}");
    }

    /// A point a hair off its line makes a parabola whose heights blow up with any error in
    /// the ends the diagram gives: the chord between them then, a hundred points, not the
    /// billions (20 GB) the parabola's own heights asked.
    #[test]
    fn a_parabola_whose_point_nearly_lies_on_its_line_stays_small() {
        let points = parabola(DVec2::new(0.0, 1e-8), DVec2::new(-10.0, 0.0), DVec2::new(10.0, 0.0), DVec2::new(0.0, 5.0), DVec2::new(1.0, 5.0), 0.01);
        assert!(points.len() < 200, "{} points", points.len());
        assert_eq!((points[0], *points.last().unwrap()), (DVec2::new(0.0, 5.0), DVec2::new(1.0, 5.0)));
    }

    #[test]
    fn crossing_segments_are_found_and_a_shared_end_is_not_a_crossing() {
        let square = [[0, 0, 10, 0], [10, 0, 10, 10], [10, 10, 0, 10], [0, 10, 0, 0]];
        assert_eq!(crossing(&square), None);
        let bow = [[0, 0, 10, 10], [10, 10, 10, 0], [10, 0, 0, 10], [0, 10, 0, 0]];
        assert_eq!(crossing(&bow), Some(DVec2::new(5.0, 5.0)));
        // A spike folding back on itself along one line.
        let fold = [[0, 0, 10, 0], [10, 0, 4, 0], [4, 0, 0, 5], [0, 5, 0, 0]];
        assert!(crossing(&fold).is_some());
    }

    /// An L's reflex corner makes a parabola: its points are as far from the corner as from the
    /// side they face.
    #[test]
    fn a_reflex_corner_gives_a_parabola_at_its_true_clearance() {
        let region = Shape::new(vec![Loop::polygon(&[DVec2::new(0.0, 0.0), DVec2::new(30.0, 0.0), DVec2::new(30.0, 10.0), DVec2::new(10.0, 10.0), DVec2::new(10.0, 30.0), DVec2::new(0.0, 30.0)])]);
        let axis = medial_axis(&region, 0.001, 0.05, f64::INFINITY).unwrap();
        for b in &axis {
            for (p, c) in b.points.iter().zip(&b.clearance) {
                let exact = region.distance_to(*p);
                assert!((c - exact).abs() < 1e-6, "at {p:?}: clearance {c}, the boundary {exact} away");
            }
        }
        // Beside the corner (10, 10), the axis is the parabola as far from it as from the wall
        // y = 0: y = ((x − 10)² + 100) / 20.
        let on =
            axis.iter().flat_map(|b| b.points.iter()).filter(|p| p.x > 6.5 && p.x < 9.5 && p.y < 8.0).inspect(|p| assert!((p.y - ((p.x - 10.0).powi(2) + 100.0) / 20.0).abs() < 1e-6, "{p:?}")).count();
        assert!(on > 20, "{on} points on the parabola");
    }
}
