//! Step 3 of seed 003 (§2-3, Figs. 8–9): path trimming. The joined loops are cut wherever an
//! entity is crossed in its interior by another or three or more entities meet; the pieces
//! between cuts that come closer to the input than the distance are the twisted parts and go;
//! the rest are joined back into loops.

use crate::geom::index::RectIndex;
use crate::geom::segment::{ArcGeom, Rect, Segment};
use crate::geom::DVec2;
use crate::profile::{Loop, Shape};

/// A piece of a joined loop between two cuts (or a whole loop that nothing crosses).
#[derive(Clone, Debug)]
pub struct Slice {
    pub segs: Vec<Segment>,
    /// Which joined loop it came from.
    pub source: usize,
    /// A whole loop, uncut.
    pub closed: bool,
}

impl Slice {
    fn start(&self) -> DVec2 {
        self.segs[0].a
    }
    fn end(&self) -> DVec2 {
        self.segs[self.segs.len() - 1].b
    }
}

/// Cuts closer than this many `eps` to a segment's end are moved onto the vertex.
const SNAP: f64 = 10.0;

/// Finds every crossing between the joined loops' segments (also between different loops, so
/// islands and boundaries that meet are cut too) and cuts the loops into slices there.
/// Touching at a vertex counts: a point where three or more entities meet is a cut.
pub fn split_at_crossings(loops: &[Vec<Segment>], eps: f64) -> Vec<Slice> {
    let mut owner: Vec<(usize, usize)> = Vec::new();
    let mut segs: Vec<Segment> = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        for (i, s) in l.iter().enumerate() {
            owner.push((k, i));
            segs.push(*s);
        }
    }
    let rects: Vec<Rect> = segs.iter().map(|s| s.bounds().expand(eps)).collect();
    let index = RectIndex::new(&rects);
    let geoms: Vec<Option<ArcGeom>> = segs.iter().map(|s| s.arc_geom()).collect();
    let lens: Vec<f64> = segs.iter().zip(&geoms).map(|(s, g)| g.map_or(s.chord(), |g| g.radius * g.sweep.abs())).collect();
    // Cuts per loop as (position along the loop = segment index + parameter, point).
    let mut cuts: Vec<Vec<(f64, DVec2)>> = vec![Vec::new(); loops.len()];
    let snap = SNAP * eps;
    let mut add_cut = |g: usize, t: f64, p: DVec2| {
        let (k, i) = owner[g];
        let m = loops[k].len();
        let pos = if t * lens[g] <= snap {
            i as f64
        } else if (1.0 - t) * lens[g] <= snap {
            ((i + 1) % m) as f64
        } else {
            i as f64 + t
        };
        cuts[k].push((pos, p));
    };
    for g in 0..segs.len() {
        let (k, i) = owner[g];
        let m = loops[k].len();
        index.query(&rects[g], |h| {
            if h <= g {
                return;
            }
            let (kh, j) = owner[h];
            let next = kh == k && j == (i + 1) % m;
            let prev = kh == k && i == (j + 1) % m;
            for c in segs[g].crossings_with(geoms[g].as_ref(), &segs[h], geoms[h].as_ref(), eps).iter() {
                let g_end = (1.0 - c.t) * lens[g] <= snap;
                let g_start = c.t * lens[g] <= snap;
                let h_end = (1.0 - c.u) * lens[h] <= snap;
                let h_start = c.u * lens[h] <= snap;
                if (next && g_end && h_start) || (prev && g_start && h_end) {
                    continue; // the vertex the two share
                }
                add_cut(g, c.t, c.p);
                add_cut(h, c.u, c.p);
            }
        });
    }
    let mut slices = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        let m = l.len();
        let mut c = std::mem::take(&mut cuts[k]);
        if c.is_empty() {
            slices.push(Slice { segs: l.clone(), source: k, closed: true });
            continue;
        }
        c.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        c.dedup_by(|b, a| b.0 - a.0 <= snap / lens_at(l, a.0).max(snap) && b.1.distance(a.1) <= snap);
        // A cut at a vertex takes the vertex's own point.
        for cut in &mut c {
            if cut.0.fract() == 0.0 {
                cut.1 = l[cut.0 as usize % m].a;
            }
        }
        for j in 0..c.len() {
            let (from, p0) = c[j];
            let (mut to, p1) = c[(j + 1) % c.len()];
            if to <= from {
                to += m as f64;
            }
            if let Some(segs) = extract(l, from, to, p0, p1, eps) {
                slices.push(Slice { segs, source: k, closed: false });
            }
        }
    }
    slices
}

fn lens_at(l: &[Segment], pos: f64) -> f64 {
    l[pos as usize % l.len()].length()
}

/// The part of loop `l` between two positions, starting exactly at `p0` and ending at `p1`.
fn extract(l: &[Segment], from: f64, to: f64, p0: DVec2, p1: DVec2, eps: f64) -> Option<Vec<Segment>> {
    let m = l.len();
    let mut out = Vec::new();
    let mut p = from;
    while p < to {
        let i = p.floor();
        let e = (i + 1.0).min(to);
        let s = l[i as usize % m];
        let (t0, t1) = (p - i, e - i);
        let piece = if t0 <= 0.0 && t1 >= 1.0 { s } else { s.sub(t0, t1) };
        if piece.length() > eps {
            out.push(piece);
        }
        p = e;
    }
    if out.is_empty() {
        return None;
    }
    out[0].a = p0;
    for k in 1..out.len() {
        out[k].a = out[k - 1].b;
    }
    let last = out.len() - 1;
    out[last].b = p1;
    if out[last].a == out[last].b {
        out.pop();
    }
    (!out.is_empty()).then_some(out)
}

/// The input shape, indexed for distance and crossing queries.
pub struct Original<'a> {
    #[allow(dead_code)]
    shape: &'a Shape,
    segs: Vec<Segment>,
    geoms: Vec<Option<ArcGeom>>,
    index: RectIndex,
}

impl<'a> Original<'a> {
    pub fn new(shape: &'a Shape) -> Original<'a> {
        let segs: Vec<Segment> = shape.segments().collect();
        let rects: Vec<Rect> = segs.iter().map(|s| s.bounds()).collect();
        let index = RectIndex::new(&rects);
        let geoms = segs.iter().map(|s| s.arc_geom()).collect();
        Original { shape, segs, geoms, index }
    }

    /// Distance from `q` to the input's boundary, or `cap` when it is at least that far.
    pub fn distance(&self, q: DVec2, cap: f64) -> f64 {
        let mut best = cap;
        self.index.any_within(q, cap, |i| {
            best = best.min(self.segs[i].distance_with(self.geoms[i].as_ref(), q));
            false
        });
        best
    }

    /// Whether the midpoint of `s` lies closer than `limit` to the input. `hint` is tried
    /// first and set to the entity found closer: neighbouring slices are usually too close to
    /// the same entity.
    fn closer_than(&self, s: &Segment, limit: f64, hint: &mut usize) -> bool {
        let mid = s.midpoint();
        if self.segs.get(*hint).is_some_and(|o| o.distance_with(self.geoms[*hint].as_ref(), mid) < limit) {
            return true;
        }
        self.index.any_within(mid, limit, |i| {
            let close = self.segs[i].distance_with(self.geoms[i].as_ref(), mid) < limit;
            if close {
                *hint = i;
            }
            close
        })
    }

    /// Whether `q` lies inside the input (rays crossing the entities the index finds on the
    /// ray's way).
    pub fn contains(&self, q: DVec2) -> bool {
        let mut count = 0;
        self.index.query(&Rect { min: q, max: DVec2::new(f64::INFINITY, q.y) }, |i| count += self.segs[i].ray_crossings(q));
        count % 2 == 1
    }

    /// Whether `s` crosses or touches the input.
    fn crosses(&self, s: &Segment, eps: f64) -> bool {
        let mut crosses = false;
        let g = s.arc_geom();
        self.index.query(&s.bounds().expand(eps), |i| {
            crosses = crosses || !self.segs[i].crossings_with(self.geoms[i].as_ref(), s, g.as_ref(), eps).is_empty();
        });
        crosses
    }

    /// Whether `q` lies in the offset region: within the distance of the input or inside it
    /// when growing; inside it and farther than the distance when shrinking.
    pub fn in_offset_region(&self, q: DVec2, distance: f64) -> bool {
        let inside = self.contains(q);
        let d = self.distance(q, distance.abs() * 2.0 + 1.0);
        if distance > 0.0 {
            inside || d < distance
        } else {
            inside && d > -distance
        }
    }
}

/// Slack under the distance within which a piece still counts as at the distance (mm per mm of
/// distance, and at least `eps` times this).
const CLOSE_SLACK: f64 = 10.0;

/// Drops the twisted parts: the slices with a point closer to the input than the distance.
/// A slice that does not cross the input is either wholly at the distance or wholly too
/// close, since to change it would have to cross the raw offset of the input's nearest part
/// (and would have been cut there); so the midpoints of its first, middle and last segments
/// decide, and a slice that crosses the input goes.
pub fn discard_close(slices: Vec<Slice>, original: &Original, distance: f64, eps: f64) -> Vec<Slice> {
    let limit = distance.abs() - CLOSE_SLACK * eps * distance.abs().max(1.0);
    let mut hint = usize::MAX;
    slices
        .into_iter()
        .filter(|s| {
            let n = s.segs.len();
            let probes = [0, n / 2, n - 1];
            !probes.iter().any(|&k| original.closer_than(&s.segs[k], limit, &mut hint))
                && !s.segs.iter().any(|seg| original.crosses(seg, eps))
        })
        .collect()
}

/// Joins the kept slices end to start into loops. Ends match within a few `eps`; a slice
/// from the same joined loop is preferred where several start at one point.
pub fn stitch(slices: Vec<Slice>, eps: f64) -> Vec<Loop> {
    let near = SNAP * 10.0 * eps;
    let mut loops = Vec::new();
    let mut open: Vec<Slice> = Vec::new();
    for s in slices {
        if s.closed {
            loops.push(Loop::from_segments(&s.segs));
        } else {
            open.push(s);
        }
    }
    let mut by_x: Vec<usize> = (0..open.len()).collect();
    by_x.sort_by(|&a, &b| open[a].start().x.total_cmp(&open[b].start().x));
    let xs: Vec<f64> = by_x.iter().map(|&i| open[i].start().x).collect();
    let mut used = vec![false; open.len()];
    for first in 0..open.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut chain: Vec<Segment> = open[first].segs.clone();
        let start = open[first].start();
        let mut current = first;
        loop {
            let end = open[current].end();
            if end.distance(start) <= near {
                let last = chain.len() - 1;
                chain[last].b = start;
                loops.push(Loop::from_segments(&chain));
                break;
            }
            let lo = xs.partition_point(|&x| x < end.x - near);
            let candidates = by_x[lo..].iter().take_while(|&&i| open[i].start().x <= end.x + near).copied();
            let mut best: Option<usize> = None;
            for c in candidates {
                if !used[c] && open[c].start().distance(end) <= near {
                    if best.is_none() || open[c].source == open[current].source {
                        best = Some(c);
                    }
                }
            }
            let Some(next) = best else { break };
            used[next] = true;
            let last = chain.len() - 1;
            chain[last].b = open[next].start();
            chain.extend_from_slice(&open[next].segs);
            current = next;
        }
    }
    loops
}

/// Drops loops that run the wrong way: the side a loop keeps on its left must be inside the
/// offset region.
pub fn discard_wrong_way(loops: Vec<Loop>, original: &Original, distance: f64) -> Vec<Loop> {
    let step = 1e-5 * distance.abs().max(1.0);
    loops
        .into_iter()
        .filter(|l| {
            let s = l.segments().max_by(|a, b| a.length().total_cmp(&b.length())).unwrap();
            let t = s.tangent_at(0.5);
            let q = s.midpoint() + DVec2::new(-t.y, t.x) * step;
            original.in_offset_region(q, distance)
        })
        .collect()
}
