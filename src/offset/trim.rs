//! Step 3 of seed 003 (§2-3, Figs. 8–9): path trimming. The joined loops are cut wherever an
//! entity is crossed in its interior by another or three or more entities meet; the pieces
//! between cuts that come closer to the input than the distance are the twisted parts and go;
//! the rest are joined back into loops.

use crate::drawing::{Loop, Shape};
use crate::geom::index::RectIndex;
use crate::geom::segment::{ArcGeom, Rect, Segment};
use crate::geom::DVec2;

/// A piece of a joined loop between two cuts (or a whole loop that nothing crosses), kept.
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

/// A cut of a joined loop: on segment `g` (numbered over all loops) at `key` (a position along
/// the segment from `Segment::position_with`, 0 at its start), made by crossing number `x`.
/// It lies at the crossing, or at the segment's start when `key` is 0 (snapped to the vertex).
#[derive(Clone, Copy, Debug)]
struct Cut {
    g: u32,
    x: u32,
    key: f64,
}

/// The joined loops and where they are cut: every crossing between their segments (also
/// between different loops, so islands and boundaries that meet are cut too). The slices
/// between cuts are visited without being built ([`CutLoops::for_each_slice`]), since most of
/// them are twisted parts that go.
pub struct CutLoops {
    /// All loops' segments, loop after loop; loop `k` is `segs[first[k]..first[k + 1]]`.
    segs: Vec<Segment>,
    first: Vec<usize>,
    geoms: Vec<Option<ArcGeom>>,
    /// Sorted along the loops, loop after loop.
    cuts: Vec<Cut>,
    /// Per loop, its cuts: `cuts[cut_first[k]..cut_first[k + 1]]`.
    cut_first: Vec<usize>,
    /// The crossings, by number: each makes a cut on both segments that meet there.
    crossings: Vec<DVec2>,
    eps: f64,
}

/// Finds every crossing between the joined loops' segments and cuts the loops there. Touching
/// at a vertex counts: a point where three or more entities meet is a cut.
pub fn split_at_crossings(loops: &[Vec<Segment>], eps: f64) -> CutLoops {
    let mut first = vec![0];
    let mut segs: Vec<Segment> = Vec::new();
    let mut owner: Vec<u32> = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        segs.extend_from_slice(l);
        owner.extend(std::iter::repeat_n(k as u32, l.len()));
        first.push(segs.len());
    }
    let geoms: Vec<Option<ArcGeom>> = segs.iter().map(Segment::arc_geom).collect();
    let rects: Vec<Rect> = segs.iter().zip(&geoms).map(|(s, g)| s.bounds_with(g.as_ref()).expand(eps)).collect();
    let index = RectIndex::new(&rects);
    let snap = SNAP * eps;
    // Next and previous segment along the same loop.
    let next = |g: usize| if g + 1 == first[owner[g] as usize + 1] { first[owner[g] as usize] } else { g + 1 };
    let before = |g: usize| if g == first[owner[g] as usize] { first[owner[g] as usize + 1] - 1 } else { g - 1 };
    let mut cuts: Vec<Cut> = Vec::with_capacity(segs.len() * 2);
    let mut crossings: Vec<DVec2> = Vec::new();
    index.pairs(|g, h| {
        let (sg, sh) = (&segs[g], &segs[h]);
        // In a loop of three or more, neighbours meet once at their vertex (which is no cut).
        let loop_of_three = first[owner[g] as usize + 1] - first[owner[g] as usize] > 2;
        if loop_of_three
            && (h == next(g) && meet_only_at_vertex(sg, geoms[g].as_ref(), sh, geoms[h].as_ref(), eps) || g == next(h) && meet_only_at_vertex(sh, geoms[h].as_ref(), sg, geoms[g].as_ref(), eps))
        {
            return;
        }
        for c in sg.crossings_with(geoms[g].as_ref(), sh, geoms[h].as_ref(), eps).iter() {
            let near = |p: DVec2| c.p.distance_squared(p) <= snap * snap;
            if (h == next(g) && near(sg.b) && near(sh.a)) || (h == before(g) && near(sg.a) && near(sh.b)) {
                continue; // the vertex the two share
            }
            let x = crossings.len() as u32;
            crossings.push(c.p);
            for (s, key) in [(g, c.t), (h, c.u)] {
                // A cut within `snap` of an end moves onto the vertex (the next one's start).
                let seg = &segs[s];
                cuts.push(if c.p.distance_squared(seg.a) <= snap * snap {
                    Cut { g: s as u32, x, key: 0.0 }
                } else if c.p.distance_squared(seg.b) <= snap * snap {
                    Cut { g: next(s) as u32, x, key: 0.0 }
                } else {
                    Cut { g: s as u32, x, key: key.max(f64::MIN_POSITIVE) }
                });
            }
        }
    });
    sort_along(&mut cuts, segs.len());
    // Cuts on one segment closer than `snap` are one.
    let at = |c: &Cut| if c.key == 0.0 { segs[c.g as usize].a } else { crossings[c.x as usize] };
    cuts.dedup_by(|b, a| b.g == a.g && at(b).distance_squared(at(a)) <= snap * snap);
    let cut_first = first.iter().map(|&g| if g == segs.len() { cuts.len() } else { cuts.partition_point(|c| (c.g as usize) < g) }).collect();
    CutLoops { segs, first, geoms, cuts, cut_first, crossings, eps }
}

/// Whether `s1` and the segment `s2` that follows it (from `s1.b`) can have no point in common
/// but that vertex, by a test cheaper than finding their crossings: lines that do not turn back
/// by more than a right angle, a line and an arc tangent there (a line touches a circle once),
/// and arcs of one circle (within `eps`) running the same way, each under a half turn.
fn meet_only_at_vertex(s1: &Segment, g1: Option<&ArcGeom>, s2: &Segment, g2: Option<&ArcGeom>, eps: f64) -> bool {
    /// Directions closer than this (sine of the angle) count as tangent: the second point where
    /// the line meets the circle then lies within 2e-12 radii of the vertex.
    const TANGENT: f64 = 1e-12;
    let (t1, t2) = (s1.direction_at(g1, s1.b), s2.direction_at(g2, s2.a));
    match (g1, g2) {
        (None, None) => t1.dot(t2) > 0.0,
        (Some(_), None) | (None, Some(_)) => t1.dot(t2) > 0.0 && t1.perp_dot(t2).abs() < TANGENT,
        (Some(a), Some(b)) => a.bulge.signum() == b.bulge.signum() && a.bulge.abs() < 1.0 && b.bulge.abs() < 1.0 && a.center.distance(b.center) <= eps && (a.radius - b.radius).abs() <= eps,
    }
}

/// Sorts cuts along the loops' `m` segments, in place: by segment (counted, then each moved
/// into its segment's range: an American flag sort), then by key within a segment.
fn sort_along(cuts: &mut [Cut], m: usize) {
    let mut starts = vec![0usize; m + 1];
    for c in cuts.iter() {
        starts[c.g as usize + 1] += 1;
    }
    for i in 0..m {
        starts[i + 1] += starts[i];
    }
    let mut next = starts.clone();
    for b in 0..m {
        while next[b] < starts[b + 1] {
            let to = cuts[next[b]].g as usize;
            if to == b {
                next[b] += 1;
            } else {
                cuts.swap(next[b], next[to]);
                next[to] += 1;
            }
        }
    }
    for b in 0..m {
        let bucket = &mut cuts[starts[b]..starts[b + 1]];
        if bucket.len() > 1 {
            bucket.sort_unstable_by(|a, b| a.key.total_cmp(&b.key));
        }
    }
}

/// The part of one segment that a slice runs along, from `from` to `to`.
#[derive(Clone, Copy, Debug)]
pub struct Piece<'a> {
    seg: &'a Segment,
    geom: Option<&'a ArcGeom>,
    from: DVec2,
    to: DVec2,
}

impl Piece<'_> {
    /// Whether the piece is its whole segment.
    fn whole(&self) -> bool {
        self.from == self.seg.a && self.to == self.seg.b
    }

    pub fn midpoint(&self) -> DVec2 {
        if self.whole() {
            self.seg.midpoint()
        } else {
            self.seg.midpoint_between(self.geom, self.from, self.to)
        }
    }

    pub fn segment(&self) -> Segment {
        if self.whole() {
            *self.seg
        } else {
            self.seg.between(self.geom, self.from, self.to)
        }
    }
}

/// A slice seen in passing: its pieces (those longer than `eps`), where it came from, the
/// crossings it runs between (by number; none for a whole loop), and whether it is a whole
/// loop.
pub struct SliceView<'p, 'a> {
    pub pieces: &'p [Piece<'a>],
    pub source: usize,
    pub ends: Option<(usize, usize)>,
    pub closed: bool,
}

impl SliceView<'_, '_> {
    /// The slice built: its pieces as segments, each starting where the one before ends.
    pub fn build(&self) -> Slice {
        let mut segs: Vec<Segment> = self.pieces.iter().map(Piece::segment).collect();
        for k in 1..segs.len() {
            segs[k].a = segs[k - 1].b;
        }
        let last = segs.len() - 1;
        segs[last].b = self.pieces[last].to;
        Slice { segs, source: self.source, closed: self.closed }
    }
}

impl CutLoops {
    /// Calls `visit` with every slice: each loop from cut to cut, through its start, and the
    /// loops nothing cuts whole. Slices whose pieces are all shorter than `eps` are skipped.
    pub fn for_each_slice<'s>(&'s self, mut visit: impl FnMut(&SliceView<'_, 's>)) {
        let mut pieces: Vec<Piece<'s>> = Vec::new();
        for k in 0..self.first.len() - 1 {
            let (g0, m) = (self.first[k], self.first[k + 1] - self.first[k]);
            let piece = |i: usize, from: DVec2, to: DVec2| Piece { seg: &self.segs[g0 + i], geom: self.geoms[g0 + i].as_ref(), from, to };
            let c = &self.cuts[self.cut_first[k]..self.cut_first[k + 1]];
            if c.is_empty() {
                pieces.clear();
                pieces.extend((0..m).map(|i| piece(i, self.segs[g0 + i].a, self.segs[g0 + i].b)));
                visit(&SliceView { pieces: &pieces, source: k, ends: None, closed: true });
                continue;
            }
            let at = |c: &Cut| if c.key == 0.0 { self.segs[c.g as usize].a } else { self.crossings[c.x as usize] };
            for j in 0..c.len() {
                let (from, to) = (c[j], c[(j + 1) % c.len()]);
                let (p0, p1) = (at(&from), at(&to));
                let (i0, mut i1) = (from.g as usize - g0, to.g as usize - g0);
                if (to.g, to.key) <= (from.g, from.key) {
                    i1 += m; // through the loop's start
                }
                pieces.clear();
                for i in i0..=i1 {
                    let s = &self.segs[g0 + i % m];
                    let a = if i == i0 { p0 } else { s.a };
                    let b = if i == i1 { p1 } else { s.b };
                    if a.distance_squared(b) > self.eps * self.eps {
                        pieces.push(piece(i % m, a, b));
                    }
                }
                if pieces.is_empty() {
                    continue;
                }
                // The slice runs exactly from cut to cut, whatever short pieces were left out.
                pieces[0].from = p0;
                let last = pieces.len() - 1;
                pieces[last].to = p1;
                visit(&SliceView { pieces: &pieces, source: k, ends: Some((from.x as usize, to.x as usize)), closed: false });
            }
        }
    }
}

/// The input shape, indexed for distance and containment queries.
pub struct Original {
    segs: Vec<Segment>,
    geoms: Vec<Option<ArcGeom>>,
    index: RectIndex,
}

impl Original {
    pub fn new(shape: &Shape) -> Original {
        let segs: Vec<Segment> = shape.segments().collect();
        let geoms: Vec<Option<ArcGeom>> = segs.iter().map(|s| s.arc_geom()).collect();
        let rects: Vec<Rect> = segs.iter().zip(&geoms).map(|(s, g)| s.bounds_with(g.as_ref())).collect();
        let index = RectIndex::new(&rects);
        Original { segs, geoms, index }
    }

    /// Distance from `q` to the input's boundary, or `cap` when it is at least that far.
    pub fn distance(&self, q: DVec2, cap: f64) -> f64 {
        self.nearest(q, cap).map_or(cap, |(_, d)| d)
    }

    /// The entities whose bounds come closer than `radius` to `p`: every one that can come
    /// closer than `cap` to a point within `radius - cap` of `p`, for [`Original::distance_among`].
    pub fn near(&self, p: DVec2, radius: f64) -> Vec<usize> {
        let mut ids = Vec::new();
        self.index.any_within(p, radius, |i| {
            ids.push(i);
            false
        });
        ids
    }

    /// [`Original::distance`] among the entities `ids` ([`Original::near`] a point, for many
    /// points about it: a lead arc's samples look the walls up once, not once each).
    pub fn distance_among(&self, ids: &[usize], q: DVec2, cap: f64) -> f64 {
        ids.iter().map(|&i| self.segs[i].distance_with(self.geoms[i].as_ref(), q)).fold(cap, f64::min)
    }

    /// The entity nearest `q` (its position in the shape's segments, loop after loop) and its
    /// distance, among those closer than `cap`.
    pub fn nearest(&self, q: DVec2, cap: f64) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        self.index.any_within(q, cap, |i| {
            let d = self.segs[i].distance_with(self.geoms[i].as_ref(), q);
            if d < best.map_or(cap, |b| b.1) {
                best = Some((i, d));
            }
            false
        });
        best
    }

    /// Whether `q` lies closer than `limit` to the input. `hint` is tried first and set to
    /// the entity found closer: neighbouring slices are usually too close to the same entity.
    fn closer_than(&self, q: DVec2, limit: f64, hint: &mut usize) -> bool {
        if self.segs.get(*hint).is_some_and(|o| o.distance_with(self.geoms[*hint].as_ref(), q) < limit) {
            return true;
        }
        self.index.any_within(q, limit, |i| {
            let close = self.segs[i].distance_with(self.geoms[i].as_ref(), q) < limit;
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
        self.index.query(&Rect { min: q, max: DVec2::new(f64::INFINITY, q.y) }, |i| count += self.segs[i].ray_crossings_with(self.geoms[i].as_ref(), q));
        count % 2 == 1
    }

    /// Whether `q` lies in the offset region: within the distance of the input or inside it
    /// when growing; inside it and farther than the distance when shrinking.
    pub fn in_offset_region(&self, q: DVec2, distance: f64) -> bool {
        let (inside, mut hint) = (self.contains(q), usize::MAX);
        if distance > 0.0 {
            inside || self.closer_than(q, distance, &mut hint)
        } else {
            inside && !self.closer_than(q, -distance, &mut hint)
        }
    }
}

/// Slack under the distance within which a piece still counts as at the distance (mm per mm of
/// distance, and at least `eps` times this).
const CLOSE_SLACK: f64 = 10.0;

/// Drops the twisted parts: the slices with a point closer to the input than the distance;
/// builds the rest. A slice is either wholly at the distance or wholly too close: every point
/// of a raw offset lies within the distance of the entity it came from, and to pass from "at
/// the distance" to "closer" a slice would have to cross the raw offset (or join arc) of the
/// input part it comes closer to, where it would have been cut. (That holds for a slice that
/// crosses the input too: it is at distance zero there, so wholly too close.) So its ends decide
/// first (each crossing is tested once, for all the slices that end there), then the midpoint
/// of its middle piece.
pub fn discard_close(cut: &CutLoops, original: &Original, distance: f64, eps: f64) -> Vec<Slice> {
    let limit = distance.abs() - CLOSE_SLACK * eps * distance.abs().max(1.0);
    let mut hint = usize::MAX;
    // Per crossing: 0 not tested yet, 1 at the distance, 2 too close.
    let mut state = vec![0u8; cut.crossings.len()];
    let mut kept = Vec::new();
    cut.for_each_slice(|s| {
        if let Some((a, b)) = s.ends {
            for x in [a, b] {
                if state[x] == 0 {
                    state[x] = if original.closer_than(cut.crossings[x], limit, &mut hint) { 2 } else { 1 };
                }
                if state[x] == 2 {
                    return;
                }
            }
        }
        if original.closer_than(s.pieces[s.pieces.len() / 2].midpoint(), limit, &mut hint) {
            return;
        }
        kept.push(s.build());
    });
    kept
}

/// Joins the kept slices end to start into loops. Ends match within a few `eps`; a slice
/// from the same joined loop is preferred where several start at one point. Where three or
/// more offset entities cross within a hair of one another (the corners of a staircase offset
/// by a multiple of its step), the crossings cut slivers a few hundred-thousandths long between
/// them, whose ends match the long slices' there: a chain that took a sliver (or began at one)
/// ran into the junction's other slivers and was lost, and the loop with it (a 114 × 34 mm
/// region offset by 4.8 mm came out empty). So a slice no longer than the match is left out
/// (its ends are one point to it), a slice under ten matches long is taken only where no longer
/// one starts, and chains start from the longer slices first.
pub fn stitch(slices: Vec<Slice>, eps: f64) -> Vec<Loop> {
    let near = SNAP * 10.0 * eps;
    let mut loops = Vec::new();
    let mut open: Vec<Slice> = Vec::new();
    let mut length = Vec::new();
    for s in slices {
        let l: f64 = s.segs.iter().map(Segment::length).sum();
        if s.closed {
            loops.push(Loop::from_segments(&s.segs));
        } else if l > near {
            open.push(s);
            length.push(l);
        }
    }
    let mut by_x: Vec<usize> = (0..open.len()).collect();
    crate::geom::sort::sort_by_float(&mut by_x, |&a| open[a].start().x);
    let xs: Vec<f64> = by_x.iter().map(|&i| open[i].start().x).collect();
    let sliver: Vec<bool> = length.iter().map(|&l| l <= 10.0 * near).collect();
    let starts: Vec<usize> = (0..open.len()).filter(|&k| !sliver[k]).chain((0..open.len()).filter(|&k| sliver[k])).collect();
    let mut used = vec![false; open.len()];
    for first in starts {
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
                if used[c] || open[c].start().distance(end) > near {
                    continue;
                }
                let same = open[c].source == open[current].source;
                if best.is_none_or(|b| sliver[b] && !sliver[c] || sliver[b] == sliver[c] && same) {
                    best = Some(c);
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
