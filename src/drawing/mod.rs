//! 2D profiles: closed loops of lines and arcs (vertex and bulge, as in DXF polylines), shapes
//! made of outer loops and holes, and drawings read from DXF and SVG ([`import`]) and chained
//! into loops ([`chain`]).

pub mod arcfit;
pub mod chain;
pub mod import;
pub mod medial;
pub mod sample;

use serde::{Deserialize, Serialize};

use crate::geom::segment::{Rect, Segment};
use crate::geom::DVec2;

/// A loop corner and the bulge of the segment that leaves it (0: a line).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Vertex {
    pub p: DVec2,
    pub bulge: f64,
}

/// A closed loop: the last vertex's segment runs back to the first.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Loop {
    pub vertices: Vec<Vertex>,
}

impl Loop {
    /// The loop through chained segments (each starts where the one before ends).
    pub fn from_segments(segments: &[Segment]) -> Loop {
        Loop { vertices: segments.iter().map(|s| Vertex { p: s.a, bulge: s.bulge }).collect() }
    }

    /// A circle as two half arcs, counter-clockwise from its rightmost point.
    pub fn circle(center: DVec2, radius: f64) -> Loop {
        let r = DVec2::new(radius, 0.0);
        Loop { vertices: vec![Vertex { p: center + r, bulge: 1.0 }, Vertex { p: center - r, bulge: 1.0 }] }
    }

    /// A rectangle, counter-clockwise.
    pub fn rect(min: DVec2, max: DVec2) -> Loop {
        let v = |x, y| Vertex { p: DVec2::new(x, y), bulge: 0.0 };
        Loop { vertices: vec![v(min.x, min.y), v(max.x, min.y), v(max.x, max.y), v(min.x, max.y)] }
    }

    /// A polygon of lines through `points`.
    pub fn polygon(points: &[DVec2]) -> Loop {
        Loop { vertices: points.iter().map(|&p| Vertex { p, bulge: 0.0 }).collect() }
    }

    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    pub fn segment(&self, i: usize) -> Segment {
        let n = self.vertices.len();
        let (v, w) = (self.vertices[i], self.vertices[(i + 1) % n]);
        Segment { a: v.p, b: w.p, bulge: v.bulge }
    }

    pub fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        (0..self.vertices.len()).map(|i| self.segment(i))
    }

    /// Signed area: positive when counter-clockwise. Chords by the shoelace formula, plus each
    /// arc's circular segment, R²(θ − sin θ)/2 with the sweep's sign.
    pub fn area(&self) -> f64 {
        self.segments()
            .map(|s| {
                let chord = s.a.perp_dot(s.b) * 0.5;
                match s.arc_geom() {
                    Some(g) => chord + g.radius * g.radius * 0.5 * (g.sweep() - g.sweep().sin()),
                    None => chord,
                }
            })
            .sum()
    }

    pub fn is_ccw(&self) -> bool {
        self.area() > 0.0
    }

    pub fn length(&self) -> f64 {
        self.segments().map(|s| s.length()).sum()
    }

    pub fn bounds(&self) -> Rect {
        self.segments().fold(Rect::EMPTY, |r, s| r.union(s.bounds()))
    }

    /// The loop running counter-clockwise (itself or reversed).
    pub fn counter_clockwise(&self) -> Loop {
        if self.is_ccw() {
            self.clone()
        } else {
            self.reversed()
        }
    }

    /// The same loop run the other way.
    pub fn reversed(&self) -> Loop {
        let n = self.vertices.len();
        let vertices = (0..n)
            .map(|k| {
                let i = n - 1 - k;
                // Segment i (from i to i+1) becomes the segment from i+1 to i.
                Vertex { p: self.vertices[(i + 1) % n].p, bulge: -self.vertices[i].bulge }
            })
            .collect();
        Loop { vertices }
    }

    /// Whether `q` lies inside (crossings of a ray, arcs in monotone pieces).
    pub fn contains(&self, q: DVec2) -> bool {
        self.segments().map(|s| s.ray_crossings(q)).sum::<u32>() % 2 == 1
    }

    /// Distance from `q` to the loop.
    pub fn distance_to(&self, q: DVec2) -> f64 {
        self.segments().map(|s| s.distance_to(q)).fold(f64::INFINITY, f64::min)
    }

    pub fn translated(&self, by: DVec2) -> Loop {
        Loop { vertices: self.vertices.iter().map(|v| Vertex { p: v.p + by, bulge: v.bulge }).collect() }
    }

    /// Rotated by `angle` (radians) about the origin.
    pub fn rotated(&self, angle: f64) -> Loop {
        let r = DVec2::from_angle(angle);
        Loop { vertices: self.vertices.iter().map(|v| Vertex { p: r.rotate(v.p), bulge: v.bulge }).collect() }
    }

    /// The same loop starting at vertex `k`.
    pub fn rotate_start(&self, k: usize) -> Loop {
        let mut vertices = self.vertices.clone();
        vertices.rotate_left(k % self.vertices.len().max(1));
        Loop { vertices }
    }

    /// A point strictly inside the loop near its first segment (for nesting tests).
    pub fn probe_point(&self) -> DVec2 {
        let s = self.segment(0);
        s.midpoint()
    }
}

/// A region: outer loops counter-clockwise, holes clockwise, each hole inside an outer loop.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Shape {
    pub loops: Vec<Loop>,
}

impl Shape {
    /// Writes the shape to `out` as flat numbers (for a worker of the page's pool): its number
    /// of loops, and per loop its number of vertices, then each vertex's x, y and bulge.
    pub fn to_flat(&self, out: &mut Vec<f64>) {
        out.push(self.loops.len() as f64);
        for l in &self.loops {
            out.push(l.vertices.len() as f64);
            out.extend(l.vertices.iter().flat_map(|v| [v.p.x, v.p.y, v.bulge]));
        }
    }

    /// The shapes [`Shape::to_flat`] wrote one after another in `flat`, as they were.
    pub fn all_from_flat(flat: &[f64]) -> Option<Vec<Shape>> {
        let mut at = 0;
        let mut next = || {
            let v = *flat.get(at)?;
            at += 1;
            Some(v)
        };
        let mut out = Vec::new();
        while let Some(loops) = next() {
            let mut shape = Shape { loops: Vec::with_capacity(loops as usize) };
            for _ in 0..loops as usize {
                let count = next()? as usize;
                let mut vertices = Vec::with_capacity(count);
                for _ in 0..count {
                    vertices.push(Vertex { p: DVec2::new(next()?, next()?), bulge: next()? });
                }
                shape.loops.push(Loop { vertices });
            }
            out.push(shape);
        }
        Some(out)
    }

    /// The region bounded by `loops` (any orientation, any order): a loop nested inside an odd
    /// number of others is a hole. Loops are turned to run counter-clockwise when outer and
    /// clockwise when holes.
    pub fn new(loops: Vec<Loop>) -> Shape {
        let mut depth = vec![0usize; loops.len()];
        each_around(&loops, |i, _| depth[i] += 1);
        let loops = loops.into_iter().zip(depth).map(|(l, d)| if l.is_ccw() == (d % 2 == 0) { l } else { l.reversed() }).collect();
        Shape { loops }
    }

    /// Each loop's parent: the innermost loop around it (position in `loops`), none for an
    /// outermost one.
    pub fn parents(&self) -> Vec<Option<usize>> {
        let area: Vec<f64> = self.loops.iter().map(|l| l.area().abs()).collect();
        let mut parent: Vec<Option<usize>> = vec![None; self.loops.len()];
        each_around(&self.loops, |i, j| {
            if parent[i].is_none_or(|k| area[j] < area[k]) {
                parent[i] = Some(j);
            }
        });
        parent
    }

    /// A shape whose loops already run the right way.
    pub fn from_oriented(loops: Vec<Loop>) -> Shape {
        Shape { loops }
    }

    pub fn is_empty(&self) -> bool {
        self.loops.is_empty()
    }

    pub fn area(&self) -> f64 {
        self.loops.iter().map(|l| l.area()).sum()
    }

    pub fn length(&self) -> f64 {
        self.loops.iter().map(|l| l.length()).sum()
    }

    pub fn bounds(&self) -> Rect {
        self.loops.iter().fold(Rect::EMPTY, |r, l| r.union(l.bounds()))
    }

    /// Even-odd containment.
    pub fn contains(&self, q: DVec2) -> bool {
        self.loops.iter().filter(|l| l.contains(q)).count() % 2 == 1
    }

    pub fn distance_to(&self, q: DVec2) -> f64 {
        self.loops.iter().map(|l| l.distance_to(q)).fold(f64::INFINITY, f64::min)
    }

    pub fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        self.loops.iter().flat_map(|l| l.segments())
    }

    /// The spans inside the shape of the horizontal line at each height of `ys` (ascending),
    /// left to right: each segment is asked only on the rows its height reaches, so the work
    /// goes with the rows plus the crossings, not with their product (a perforated panel's
    /// thousands of holes on as many rows).
    pub fn spans_on_rows(&self, ys: &[f64]) -> Vec<Vec<(f64, f64)>> {
        debug_assert!(ys.windows(2).all(|w| w[0] <= w[1]));
        let mut xs: Vec<Vec<f64>> = vec![Vec::new(); ys.len()];
        for s in self.segments() {
            let b = s.bounds();
            let (first, last) = (ys.partition_point(|&y| y < b.min.y), ys.partition_point(|&y| y <= b.max.y));
            for (row, &y) in xs[first..last].iter_mut().zip(&ys[first..last]) {
                row.extend(s.crossings_at_y(y));
            }
        }
        xs.into_iter()
            .map(|mut row| {
                crate::geom::sort::sort_floats(&mut row);
                row.chunks_exact(2).map(|p| (p[0], p[1])).collect()
            })
            .collect()
    }

    /// The outer loops, each with the holes directly inside it (its islands).
    pub fn regions(&self) -> Vec<Shape> {
        let outers: Vec<usize> = (0..self.loops.len()).filter(|&i| self.loops[i].is_ccw()).collect();
        let mut regions: Vec<Vec<Loop>> = outers.iter().map(|&i| vec![self.loops[i].clone()]).collect();
        let bounds: Vec<Rect> = outers.iter().map(|&i| self.loops[i].bounds()).collect();
        let index = crate::geom::index::RectIndex::new(&bounds);
        for hole in self.loops.iter().filter(|l| !l.is_ccw()) {
            // The smallest outer loop around the hole (among those whose bounds hold it).
            let p = hole.probe_point();
            let mut around = Vec::new();
            index.query(&hole.bounds(), |k| around.push(k));
            around.sort_unstable();
            let owner = around.into_iter().map(|k| (k, &outers[k])).filter(|(_, &i)| encloses(&self.loops[i], hole, p)).min_by(|a, b| self.loops[*a.1].area().total_cmp(&self.loops[*b.1].area()));
            if let Some((k, _)) = owner {
                regions[k].push(hole.clone());
            }
        }
        regions.into_iter().map(Shape::from_oriented).collect()
    }
}

/// Whether `outer` encloses `inner` (tested at `probe`, a point of `inner`; a point on the
/// outer loop itself falls back to the inner loop's other vertices).
/// Calls `around(i, j)` for every loop `j` of `loops` that encloses loop `i`: the candidates
/// from an index of their bounds (a panel's 100,000 holes compared pair by pair took 12 s).
fn each_around(loops: &[Loop], mut around: impl FnMut(usize, usize)) {
    let bounds: Vec<Rect> = loops.iter().map(|l| l.bounds()).collect();
    let index = crate::geom::index::RectIndex::new(&bounds);
    for i in 0..loops.len() {
        let p = loops[i].probe_point();
        index.query(&bounds[i], |j| {
            if j != i && bounds[j].overlaps(&bounds[i]) && encloses(&loops[j], &loops[i], p) {
                around(i, j);
            }
        });
    }
}

fn encloses(outer: &Loop, inner: &Loop, probe: DVec2) -> bool {
    let mut points = std::iter::once(probe).chain(inner.vertices.iter().map(|v| v.p));
    let scale = outer.bounds().size().max_element().max(1.0);
    points.find(|&p| outer.distance_to(p) > 1e-9 * scale).is_some_and(|p| outer.contains(p))
}

/// A drill mark: a POINT entity of a DXF, in mm.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DrawnPoint {
    pub at: DVec2,
    pub layer: String,
}

/// Where a chain of segments failed to close.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct OpenChain {
    pub layer: String,
    #[ts(type = "[number, number]")]
    pub start: DVec2,
    #[ts(type = "[number, number]")]
    pub end: DVec2,
    pub segments: usize,
    /// The chain itself, from `start` to `end` (for engraving).
    #[serde(skip)]
    #[ts(skip)]
    pub path: Vec<crate::geom::segment::Segment>,
}

/// A closed loop with the layer it was drawn on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct DrawnLoop {
    pub layer: String,
    #[serde(flatten)]
    pub path: Loop,
}

/// A 2D drawing read from a file, in millimetres.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Drawing {
    pub loops: Vec<DrawnLoop>,
    pub open: Vec<OpenChain>,
    /// Drill marks: a DXF's POINT entities, each a place to drill.
    #[serde(default)]
    pub points: Vec<DrawnPoint>,
    /// Every layer that holds geometry, in the file's order.
    pub layers: Vec<String>,
    /// Entities that were ignored (text, dimensions, points ...), by kind, with counts.
    pub ignored: Vec<(String, usize)>,
    /// The file's units, as read (the drawing itself is in mm).
    pub units: String,
    /// Millimetres per file unit applied on reading.
    pub scale: f64,
}

/// A drawing that cannot be machined as it is.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProfileError {
    #[error("{} open chain{}: {}", .0.len(), if .0.len() == 1 { "" } else { "s" }, describe_open(.0))]
    OpenChains(Vec<OpenChain>),
    #[error("the drawing has no closed loops{0}")]
    Empty(String),
}

fn describe_open(open: &[OpenChain]) -> String {
    let mut parts: Vec<String> = open.iter().take(5).map(|o| format!("layer {} from ({:.3}, {:.3}) to ({:.3}, {:.3})", o.layer, o.start.x, o.start.y, o.end.x, o.end.y)).collect();
    if open.len() > 5 {
        parts.push(format!("and {} more", open.len() - 5));
    }
    parts.join("; ")
}

impl Drawing {
    /// Where two of its closed loops cross or touch, if any do: the first pair found (their
    /// numbers, as `swarf drawing` lists the loops) and a point they share. Loops that nest (a
    /// hole in an outline) or stand apart never meet; two that cross draw no one part, and a
    /// cut round each goes into the other.
    pub fn crossing_loops(&self) -> Option<(usize, usize, DVec2)> {
        let segments: Vec<(usize, Segment)> = self.loops.iter().enumerate().flat_map(|(k, l)| l.path.segments().map(move |s| (k, s))).collect();
        let rects: Vec<Rect> = segments.iter().map(|(_, s)| s.bounds()).collect();
        let mut found = None;
        crate::geom::index::RectIndex::new(&rects).pairs(|i, j| {
            let ((k, a), (l, b)) = (&segments[i], &segments[j]);
            if found.is_some() || k == l {
                return;
            }
            if let Some(c) = a.crossings_with(a.arc_geom().as_ref(), b, b.arc_geom().as_ref(), crate::geom::tolerance::FLOAT_SLACK).iter().next() {
                found = Some((*k.min(l), *k.max(l), c.p));
            }
        });
        found
    }

    /// The loops on `layers` (all layers when empty) as one shape. Open chains beside them are
    /// left out ([`Drawing::open_note`] says where); on layers with open chains and no loop,
    /// the error says where they are.
    pub fn shape(&self, layers: &[String]) -> Result<Shape, ProfileError> {
        let on = |layer: &String| layers.is_empty() || layers.contains(layer);
        let loops: Vec<Loop> = self.loops.iter().filter(|l| on(&l.layer)).map(|l| l.path.clone()).collect();
        let open: Vec<OpenChain> = self.open.iter().filter(|o| on(&o.layer)).cloned().collect();
        if loops.is_empty() && !open.is_empty() {
            return Err(ProfileError::OpenChains(open));
        }
        if loops.is_empty() {
            let which = if layers.is_empty() { String::new() } else { format!(" on layers {}", layers.join(", ")) };
            return Err(ProfileError::Empty(which));
        }
        Ok(Shape::new(loops))
    }

    /// The warning for the open chains on `layers` that an operation cutting their closed loops
    /// leaves uncut, if there are any.
    pub fn open_note(&self, layers: &[String]) -> Option<String> {
        let open: Vec<OpenChain> = self.open.iter().filter(|o| layers.is_empty() || layers.contains(&o.layer)).cloned().collect();
        (!open.is_empty()).then(|| format!("{} open chain{} left uncut (only closed loops are cut): {}", open.len(), if open.len() == 1 { " is" } else { "s are" }, describe_open(&open)))
    }

    pub fn bounds(&self) -> Rect {
        let loops = self.loops.iter().fold(Rect::EMPTY, |r, l| r.union(l.path.bounds()));
        // An open chain's whole course (an arc of it may bow out past its ends).
        let open = self.open.iter().fold(loops, |r, o| o.path.iter().fold(r.grow(o.start).grow(o.end), |r, s| r.union(s.bounds())));
        self.points.iter().fold(open, |r, p| r.grow(p.at))
    }

    /// Moves and scales the drawing (mm per drawing unit).
    pub fn transform(&mut self, scale: f64, offset: DVec2) {
        let f = |p: DVec2| p * scale + offset;
        for l in &mut self.loops {
            for v in &mut l.path.vertices {
                v.p = f(v.p);
            }
        }
        for o in &mut self.open {
            o.start = f(o.start);
            o.end = f(o.end);
            // The chain itself too (a bulge is the same under scaling and moving).
            for s in &mut o.path {
                s.a = f(s.a);
                s.b = f(s.b);
            }
        }
        for p in &mut self.points {
            p.at = f(p.at);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spans of the line at `y` inside `shape`, from every segment's crossings with it.
    fn spans_at(shape: &Shape, y: f64) -> Vec<(f64, f64)> {
        let mut xs: Vec<f64> = shape.segments().flat_map(|s| s.crossings_at_y(y)).collect();
        crate::geom::sort::sort_floats(&mut xs);
        xs.chunks_exact(2).map(|p| (p[0], p[1])).collect()
    }

    /// The spans of many rows at once are each row's own, on rows that meet vertices, arcs'
    /// tops and nothing, in a plate with round holes and a diamond.
    #[test]
    fn spans_on_rows_are_each_rows_spans() {
        let mut loops = vec![Loop::circle(DVec2::new(5.0, 5.0), 2.0), Loop::circle(DVec2::new(12.0, 5.5), 1.5)];
        loops.push(Loop::rect(DVec2::new(-1.0, -1.0), DVec2::new(20.0, 12.0)));
        loops.push(Loop::polygon(&[DVec2::new(8.0, 8.0), DVec2::new(9.0, 9.0), DVec2::new(8.0, 10.0), DVec2::new(7.0, 9.0)]));
        let shape = Shape::new(loops);
        let mut ys: Vec<f64> = (0..=70).map(|k| -2.0 + k as f64 * 0.25).chain([3.0, 7.0, 9.0, 9.0, 10.0]).collect();
        crate::geom::sort::sort_floats(&mut ys);
        let many = shape.spans_on_rows(&ys);
        assert_eq!(many.len(), ys.len());
        let mut crossed = 0;
        for (y, spans) in ys.iter().zip(&many) {
            assert_eq!(spans, &spans_at(&shape, *y), "at y {y}");
            crossed += spans.len();
        }
        assert!(crossed > 60, "{crossed}");
    }

    #[test]
    fn area_containment_and_nesting() {
        let c = Loop::circle(DVec2::ZERO, 2.0);
        assert!((c.area() - std::f64::consts::PI * 4.0).abs() < 1e-9);
        assert!(c.contains(DVec2::new(1.9, 0.1)) && !c.contains(DVec2::new(1.5, 1.5)));
        let r = Loop::rect(DVec2::splat(-5.0), DVec2::splat(5.0));
        assert!((r.reversed().area() + 100.0).abs() < 1e-9);
        let shape = Shape::new(vec![c.clone(), r.reversed()]);
        assert!(shape.loops[1].is_ccw() && !shape.loops[0].is_ccw());
        assert!((shape.area() - (100.0 - std::f64::consts::PI * 4.0)).abs() < 1e-9);
        assert!(!shape.contains(DVec2::ZERO) && shape.contains(DVec2::new(4.0, 4.0)));
        let regions = shape.regions();
        assert_eq!(regions.len(), 1);
        assert_eq!(regions[0].loops.len(), 2);
    }
}
