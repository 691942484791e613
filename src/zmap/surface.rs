//! The CL surface a path may stand on, everywhere along it — not only at the z-map's nodes.
//!
//! Nodes cannot see a ridge, a knee or a vertex that lies between them, so no rule over node
//! heights alone can say how high the surface stands between them. Instead the height of a path
//! is computed where the path is, by the exact drop itself ([`super::drop::PointDrop`], the
//! same facet, edge and vertex drops as the grid builder):
//!
//! 1. a straight move from `a` to `b` is cut evenly into pieces no longer than the probe spacing
//!    (for a ball the grid spacing and at most half its radius, for other cutters half that),
//!    and sampled where it passes closest to each peak of the mesh within the cutter's reach (a
//!    vertex with no higher neighbour: the top of a spike or a mesa's corner, whose bump under a
//!    grazing cutter can be narrower than any probe spacing); a node's height comes from the
//!    z-map when the builder was exact, any other point gets the exact drop;
//! 2. every piece is probed at its midpoint and quarters, so the exact drop is sampled at least
//!    every quarter of the probe spacing, and split at its midpoint, and the halves again, while
//!    the exact height at the midpoint or at a quarter is off the chord by more than the
//!    subdivision tolerance (above: the surface rises between the samples; below: it bends or
//!    steps, and a bend can hide a rise beside it); a half's midpoint is its parent's quarter,
//!    so each split costs two drops;
//! 3. a piece still off its chord when it is shorter than [`MIN_PIECE`] (a cliff, where the
//!    cutter's side leaves a wall) is held level at the highest of its three heights, with
//!    vertical steps at its ends;
//! 4. the points found are held to every vertex within reach: where the cutter standing on that
//!    vertex alone would stand higher than them (nearest it, or just inside either end of its
//!    reach, where a flat end's rim steps off it), that point is probed and the move walked
//!    again.
//!
//! **The argument.** The CL surface is the upper envelope of the drops onto single triangles,
//! and each of those is concave along a line: a triangle and the cutter are convex bodies, so
//! the tip positions where the cutter touches the triangle form a convex set whose upper
//! boundary is the drop. Where one triangle decides the height at both ends of a piece (on a
//! smooth surface the contact slides across a facet or along a ridge), its drop minus the chord
//! is concave and zero at both ends, so if it rises h above the chord anywhere it rises at least
//! h/2 at the midpoint: the midpoint test with tolerance τ bounds the rise by 2τ. Where another
//! feature takes over between two samples, the subdivision finds it when its drop stands above
//! the chord at a probe; what could still hide is a feature whose reach begins and ends between
//! two probes (the rim of a cutter brushing a wall's top edge, a spike narrower than the probe
//! spacing). For a ball the part of a vertex's drop that rises above a chord is a circular cap no
//! higher than half its width, so the probe spacing bounds it; that is why the spacing is tied to
//! the cutter radius as well as to the grid. This is a bound by construction where one feature
//! decides, not a proof for every feature, so the tests judge every path of every cutter against
//! the brute-force drop at 20 points per millimetre or more, on parts built to have ridges,
//! knees and spikes between nodes, and every program is simulated before it is handed over.
//!
//! Every point the path is given is at or above the exact surface there (step 3 only adds points above),
//! and point reduction ([`crate::toolpath::reduce`]) never lowers a path below its samples: a
//! straight line that is at or above two samples is at or above the segment between them.

use super::drop::PointDrop;
use super::HeightField;
use crate::geom::{tolerance::GRID_SNAP, DVec2};

/// Shortest piece subdivision makes (mm): a piece still off its chord at this length is held
/// level at its highest sample. Short, because at a cliff where a ball's equator leaves a wall
/// the surface rises by sqrt(2 R x) within x of the edge: 1e-7 mm keeps that under 0.001 mm
/// for radii up to 5 mm, and costs about 21 halvings per cliff.
pub const MIN_PIECE: f64 = 1e-7;

/// The CL surface of one cutter over one part: the z-map's nodes and the exact drop between them.
#[derive(Clone, Debug)]
pub struct ClSurface {
    pub field: HeightField,
    drop: std::sync::Arc<PointDrop>,
    floor: f64,
    /// Whether the field's nodes hold the exact drop (and may stand in for it).
    nodes_exact: bool,
    /// Largest rise of the exact surface above a chord that subdivision accepts (mm).
    tolerance: f64,
    /// Longest piece left without a probe at its midpoint (mm).
    probe: f64,
}

impl ClSurface {
    /// The surface of `drop`'s cutter; `field` is its z-map (`nodes_exact` when built by the
    /// exact builder), `floor` the height where no part is under the cutter, `tolerance` the
    /// subdivision tolerance (mm).
    pub fn new(field: HeightField, drop: impl Into<std::sync::Arc<PointDrop>>, floor: f64, nodes_exact: bool, tolerance: f64) -> ClSurface {
        let drop = drop.into();
        // A ball's drops onto single features are caps of its radius; a bull nose's torus and
        // a flat end's rim make narrower ones (a rim brushing an edge), which get half the
        // spacing (on mount_rush, φ6 r1 at grid 0.5: 0.0019 mm below the surface with the
        // ball's spacing, 0.0004 mm with this one).
        //
        // A round cutter's cap of radius ρ (the ball's radius, a bull nose's corner) can also
        // peak between two quarter samples s apart: at most s²/(8ρ) above them. The spacing keeps
        // that under the tolerance, so the quarters see every cap higher than twice the
        // tolerance (a raster on the sample part with a φ6 r1 bull nose at grid 0.8 hid a
        // 0.002 mm cap between quarters 0.1 mm apart).
        let p = drop.profile();
        let cap = |rho: f64| if rho > 0.0 { (128.0 * rho * tolerance).sqrt() } else { f64::INFINITY };
        let probe = if p.is_ball() { field.spacing.min(p.radius / 2.0) } else { (field.spacing / 2.0).min(p.radius / 4.0) };
        let probe = probe.min(cap(p.corner));
        ClSurface { field, drop, floor, nodes_exact, tolerance, probe }
    }

    /// The height where no part is under the cutter.
    pub fn floor(&self) -> f64 {
        self.floor
    }

    /// The exact drop the surface stands on between its nodes.
    pub fn drop(&self) -> &PointDrop {
        &self.drop
    }

    /// The cutter's profile (as grown for the program's resolution, when it was).
    pub fn profile(&self) -> &crate::cutter::Profile {
        self.drop.profile()
    }

    /// The exact height at `p`: the lowest tip height at which the cutter does not cut the part.
    pub fn height(&self, p: DVec2) -> f64 {
        if self.nodes_exact {
            let f = &self.field;
            let u = (p - f.origin) / f.spacing;
            let (i, j) = (u.x.round(), u.y.round());
            if (u.x - i).abs() <= GRID_SNAP && (u.y - j).abs() <= GRID_SNAP && i >= 0.0 && j >= 0.0 && (i as usize) < f.nx && (j as usize) < f.ny {
                return f.at(i as usize, j as usize);
            }
        }
        self.drop.at(p, self.floor)
    }

    /// The surface along the straight move from `a` to `b` as points `(t, z)` (t from 0 to 1,
    /// sorted): the exact height at each, and between two of them the surface no higher than
    /// the chord plus the tolerance (see the module's argument).
    pub fn along(&self, a: DVec2, b: DVec2) -> Vec<(f64, f64)> {
        self.along_while(a, b, |_, _| true)
    }

    /// [`ClSurface::along`] as far as its first point above `stop`, which ends it: the same
    /// points up to there, without the work beyond (where only whether, or where first, the
    /// surface rises above a height matters).
    pub fn along_until(&self, a: DVec2, b: DVec2, stop: f64) -> Vec<(f64, f64)> {
        self.along_while(a, b, |_, z| z <= stop)
    }

    /// Whether the surface stays at or below `h` all along the move from `a` to `b` (every
    /// point of [`ClSurface::along`], looked at as far as the first above).
    pub fn stays_below(&self, a: DVec2, b: DVec2, h: f64) -> bool {
        self.along_until(a, b, h).last().is_some_and(|&(_, z)| z <= h)
    }

    /// [`ClSurface::along`] as far as its first point `(t, z)` that `ok` refuses, which ends
    /// it: the same points up to there.
    pub fn along_while(&self, a: DVec2, b: DVec2, ok: impl Fn(f64, f64) -> bool) -> Vec<(f64, f64)> {
        let len = (b - a).length();
        let at = |t: f64| self.height(point_at(a, b, t));
        // The ends, split evenly into pieces no longer than the probe spacing.
        let n = (len / self.probe).ceil().max(1.0);
        let mut ts: Vec<f64> = (0..=n as usize).map(|k| k as f64 / n).collect();
        // Every peak within reach is probed where the move passes closest to it.
        let d = b - a;
        if len > 0.0 {
            let reach = self.drop.profile().radius;
            self.drop.peaks_near(a, b, |v| {
                let t = (v.truncate() - a).dot(d) / (len * len);
                if t > 0.0 && t < 1.0 && (v.truncate() - point_at(a, b, t)).length() <= reach {
                    ts.push(t);
                }
            });
            crate::geom::sort::sort_floats(&mut ts);
            ts.dedup();
        }
        // Every vertex within reach is then held to the points found: where its own drop (the
        // cutter standing on it alone) stands above them by more than the tolerance, at the
        // point nearest it or at either end of its reach, that point is probed and the move
        // walked again.
        let mut out = self.walk(&ts, &at, len, &ok);
        for _ in 0..MAX_REWALKS {
            let more = if len > 0.0 { self.vertices_above(a, b, &out) } else { Vec::new() };
            if more.is_empty() {
                break;
            }
            ts.extend(more);
            crate::geom::sort::sort_floats(&mut ts);
            ts.dedup();
            out = self.walk(&ts, &at, len, &ok);
        }
        out
    }

    /// The points along a move probed at `ts` and refined between them, as far as the first
    /// that `ok` refuses.
    fn walk(&self, ts: &[f64], at: &impl Fn(f64) -> f64, len: f64, ok: &impl Fn(f64, f64) -> bool) -> Vec<(f64, f64)> {
        let mut out = Vec::with_capacity(ts.len() * 3);
        out.push((ts[0], at(ts[0])));
        if !ok(out[0].0, out[0].1) {
            return out;
        }
        for &t in &ts[1..] {
            let end = (t, at(t));
            let zm = at(0.5 * (out.last().expect("a first point").0 + t));
            let Some(z) = self.refine(at, len, end, zm, ok, &mut out) else { break };
            out.push((t, z));
            if !ok(t, z) {
                break;
            }
        }
        out
    }

    /// Where along the move from `a` to `b` a single vertex's drop stands above `points` (the
    /// polyline found so far) by more than the tolerance: the point nearest the vertex, or
    /// either end of the vertex's reach just inside it. A flat end's rim leaving a vertex steps
    /// down there, and where another feature falls steeply beside the step, the corner of the
    /// plateau it leaves can stand above the chord between two probes (0.019 mm on a random
    /// part, X-3.015 Y0.250, φ6 flat end).
    fn vertices_above(&self, a: DVec2, b: DVec2, points: &[(f64, f64)]) -> Vec<f64> {
        let d = b - a;
        let len2 = d.length_squared();
        let len = len2.sqrt();
        let reach = self.drop.profile().radius;
        let last = points.last().map_or(0.0, |p| p.0);
        let mut more = Vec::new();
        self.drop.vertices_near(a, b, reach, |v| {
            let tc = (v.truncate() - a).dot(d) / len2;
            let off = (v.truncate() - point_at(a, b, tc)).length();
            if off > reach {
                return;
            }
            let w = ((reach * reach - off * off).sqrt() - MIN_PIECE).max(0.0) / len;
            for t in [tc, tc - w, tc + w] {
                if t <= 0.0 || t >= 1.0 || t > last {
                    continue;
                }
                let r = v.truncate().distance(point_at(a, b, t));
                if r > reach {
                    continue;
                }
                let own = self.drop.on_vertex(v, r, self.floor);
                if own > polyline_at(points, t) + self.tolerance {
                    more.push(t);
                }
            }
        });
        more
    }

    /// An upper bound of the exact surface anywhere along the straight move from `a` to `b`,
    /// from the nodes alone: the highest node within the cutter's radius and half a node
    /// diagonal of the move, plus the cutter's rise that far off its axis (every point of the
    /// part under the cutter lies within half a diagonal of a node, whose drop that point holds
    /// up to the rise). `None` where the nodes are not the exact drop.
    pub fn bound_along(&self, a: DVec2, b: DVec2) -> Option<f64> {
        if !self.nodes_exact {
            return None;
        }
        let f = &self.field;
        let half = f.spacing * std::f64::consts::FRAC_1_SQRT_2;
        let p = self.profile();
        let reach = p.radius + half;
        let (lo, hi) = ((a.min(b) - DVec2::splat(reach) - f.origin) / f.spacing, (a.max(b) + DVec2::splat(reach) - f.origin) / f.spacing);
        let (i0, j0) = (lo.x.ceil().max(0.0) as usize, lo.y.ceil().max(0.0) as usize);
        let (i1, j1) = (hi.x.floor().min(f.nx as f64 - 1.0), hi.y.floor().min(f.ny as f64 - 1.0));
        let mut top = self.floor;
        if i1 >= 0.0 && j1 >= 0.0 {
            let way = crate::geom::segment::Segment::line(a, b);
            for j in j0..=j1 as usize {
                for i in i0..=i1 as usize {
                    let q = f.origin + DVec2::new(i as f64, j as f64) * f.spacing;
                    if way.distance_with(None, q) <= reach {
                        top = top.max(f.at(i, j));
                    }
                }
            }
        }
        Some(top + p.height(half))
    }

    /// Subdivides the piece from the last point of `out` to `end`, whose midpoint stands at
    /// `zm`, pushing the points between; returns the height `end` is left at, or `None` once
    /// it has pushed a point `ok` refuses.
    fn refine(&self, at: &impl Fn(f64) -> f64, len: f64, end: (f64, f64), zm: f64, ok: &impl Fn(f64, f64) -> bool, out: &mut Vec<(f64, f64)>) -> Option<f64> {
        let start = *out.last().expect("a piece starts at a point");
        let piece = (end.0 - start.0) * len;
        let tm = 0.5 * (start.0 + end.0);
        let (t1, t3) = (0.5 * (start.0 + tm), 0.5 * (tm + end.0));
        let (z1, z3) = (at(t1), at(t3));
        // Off the chord either way, at the midpoint or a quarter: above, the surface rises
        // between the samples; below, it bends or steps, and a bend or step can hide a rise
        // beside it (an S-shaped stretch can cross the chord at the midpoint).
        let chord = |t: f64| start.1 + (end.1 - start.1) * (t - start.0) / (end.0 - start.0);
        let bent = [(t1, z1), (tm, zm), (t3, z3)].iter().any(|&(t, z)| (z - chord(t)).abs() > self.tolerance);
        if !bent && piece <= self.probe {
            return Some(end.1);
        }
        if bent && piece <= MIN_PIECE {
            // Held level at the top, rising and falling vertically at the ends: the samples
            // keep their exact heights, so the pieces beside this one are judged as they are.
            let top = start.1.max(z1).max(zm).max(z3).max(end.1);
            if top > start.1 {
                out.push((start.0, top));
                if !ok(start.0, top) {
                    return None;
                }
            }
            if top > end.1 {
                out.push((end.0, top));
            }
            return Some(end.1);
        }
        let z = self.refine(at, len, (tm, zm), z1, ok, out)?;
        out.push((tm, z));
        if !ok(tm, z) {
            return None;
        }
        self.refine(at, len, end, z3, ok, out)
    }
}

/// Most times a move is walked again for vertices found above it ([`ClSurface::along_while`]):
/// each walk probes every vertex found by the one before, so one more is rarely needed.
const MAX_REWALKS: usize = 3;

/// The height of the polyline `points` (sorted by `t`, vertical steps as two points at one `t`,
/// whose higher one counts) at `t`.
fn polyline_at(points: &[(f64, f64)], t: f64) -> f64 {
    let k = points.partition_point(|p| p.0 < t);
    let mut z = f64::NEG_INFINITY;
    for p in &points[k..] {
        if p.0 > t {
            break;
        }
        z = z.max(p.1);
    }
    if k > 0 && k < points.len() && points[k].0 > t {
        let (p, q) = (points[k - 1], points[k]);
        z = z.max(p.1 + (q.1 - p.1) * (t - p.0) / (q.0 - p.0));
    }
    z
}

/// The point at `t` from `a` to `b`, written so that a coordinate `a` and `b` share comes out
/// exactly (a pass along a grid line or a region's edge stays on it).
#[inline]
pub fn point_at<V: std::ops::Add<Output = V> + std::ops::Sub<Output = V> + std::ops::Mul<f64, Output = V> + Copy>(a: V, b: V, t: f64) -> V {
    a + (b - a) * t
}
