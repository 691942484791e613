//! Clearing a region (islands respected) at one depth, as pockets and z-level roughing do.
//! Contour-parallel: rings are the region offset inwards (by the tool radius plus leave-stock
//! for a pocket), then by one step-over more each (seed 003 repeated; DESIGN.md idea 3), cut
//! inside-out: a region's inner rings before it,
//! staying down between rings where the straight link stays inside the pocket. Zigzag:
//! parallel passes across the first ring's region by seed 004's intersection-points graph
//! (the passes joined along the region's boundary), then that ring as a finishing contour.
//! Material is entered by a helix where one fits, else by ramping along the path, never by a
//! straight plunge.

use super::adaptive::{self, Adaptive, Entry, LEAST_HELIX};
use super::air::Refeed;
use super::path2d::{arc_lengths, follow, start_nearest, Cursor, Heights};
use super::settings::{EntryKind, LoadControl, PocketPattern};
use crate::drawing::{Loop, Shape};
use crate::geom::segment::{Rect, Segment};
use crate::geom::tolerance::{FLOAT_SLACK, FLOAT_ZERO, LEAST_STEP};
use crate::geom::{DVec2, DVec3, Tolerances};
use crate::offset::offset;
use crate::toolpath::arcfit;
use crate::toolpath::entry::helix;
use crate::toolpath::entry::Keepout;
use crate::toolpath::Move;
use crate::zigzag::graph::{Graph, Pattern};
use crate::zigzag::load::{self, Load, LoadProfile, PixelMap};
use std::f64::consts::{FRAC_PI_4, PI};

/// An adaptive map's pixel: at most the step-over over this many, and the tool's radius over
/// [`ADAPTIVE_R_PIXELS`] (the engagement is read to about a pixel of step-over).
const ADAPTIVE_AE_PIXELS: f64 = 10.0;
const ADAPTIVE_R_PIXELS: f64 = 40.0;
/// How many adaptive steps from a pass's start its entry may go down instead, where material
/// the passes so far only grazed stands under the tool at the start.
const ADAPTIVE_ASIDE: usize = 5;

/// How far from material a level's region keeps the centre of an adaptive tool of radius `r`
/// whose shortest step is `step` of its radius ([`adaptive::StepRange::fractions`]): two steps
/// past touching it, so that a pass can start in the air beside the stock or in what
/// an earlier operation cleared (standing clear of the material, within a step of it) instead
/// of helixing down into a region that lies along the stock's edge.
pub(crate) fn adaptive_reach(r: f64, step: f64) -> f64 {
    r * (1.0 + 2.0 * step)
}

/// What the passes of one adaptive level have surely cut, asked lazily at the entries that go
/// straight down: a cell of the in-process stock counts as cut where its centre lies within
/// `sure` of a pass (the tool's radius less what the fitted arcs may stray), as the simulation
/// cuts it. (The pass map's pixels, finer than the simulation's cells, may hold a cell the
/// tool only grazed for cut.) The passes' segments are kept in square buckets of the tool's
/// radius, so that an entry looks only at those near it.
struct Uncut<'m> {
    stock: &'m crate::sim::DexelStock,
    sure: f64,
    bucket: f64,
    segments: Vec<Segment>,
    buckets: std::collections::HashMap<(i64, i64), Vec<usize>>,
}

impl<'m> Uncut<'m> {
    fn new(stock: &'m crate::sim::DexelStock, sure: f64, r: f64) -> Self {
        Uncut { stock, sure, bucket: r.max(LEAST_STEP), segments: Vec::new(), buckets: Default::default() }
    }

    fn key(&self, p: DVec2) -> (i64, i64) {
        ((p.x / self.bucket).floor() as i64, (p.y / self.bucket).floor() as i64)
    }

    /// A pass along `points` (one point: a pass that stays in place).
    fn reach(&mut self, points: &[DVec2]) {
        for w in points.windows(2).chain(points.get(..1).filter(|_| points.len() == 1)) {
            let (a, b) = (w[0], *w.last().expect("a point"));
            let (lo, hi) = (self.key(a.min(b)), self.key(a.max(b)));
            let n = self.segments.len();
            self.segments.push(Segment::line(a, b));
            for i in lo.0..=hi.0 {
                for j in lo.1..=hi.1 {
                    self.buckets.entry((i, j)).or_default().push(n);
                }
            }
        }
    }

    /// Whether a tool of radius `r` going straight down at `p` to `z` meets no cell standing
    /// above `z` that no pass has surely cut.
    fn clear(&self, p: DVec2, r: f64, z: f64) -> bool {
        let g = self.stock.grid();
        let (lo, hi) = ((p - g.origin - DVec2::splat(r)) / g.spacing, (p - g.origin + DVec2::splat(r)) / g.spacing);
        if hi.x < 0.0 || hi.y < 0.0 {
            return true;
        }
        let (i0, j0) = (lo.x.ceil().max(0.0) as usize, lo.y.ceil().max(0.0) as usize);
        let (i1, j1) = ((hi.x.floor() as usize).min(g.nx - 1), (hi.y.floor() as usize).min(g.ny - 1));
        let mut cells: Vec<DVec2> = (j0..=j1).flat_map(|j| (i0..=i1).map(move |i| g.node(i, j))).filter(|&q| q.distance(p) <= r && load::material_at(self.stock, q, z)).collect();
        if cells.is_empty() {
            return true;
        }
        // The segments that may reach them, nearest first: the nearest cut most of them.
        let far = r + self.sure;
        let (lo, hi) = (self.key(p - DVec2::splat(far)), self.key(p + DVec2::splat(far)));
        let mut near: Vec<(f64, usize)> = (lo.0..=hi.0)
            .flat_map(|i| (lo.1..=hi.1).map(move |j| (i, j)))
            .filter_map(|k| self.buckets.get(&k))
            .flatten()
            .map(|&n| (segment_distance(p, &self.segments[n]), n))
            .filter(|&(d, _)| d <= far)
            .collect();
        // By distance, then by segment: by segment first, then (stably) by distance.
        crate::geom::sort::sort_by_float(&mut near, |t| t.1 as f64);
        crate::geom::sort::sort_by_float(&mut near, |t| t.0);
        near.dedup_by_key(|e| e.1);
        for (_, n) in near {
            cells.retain(|&q| segment_distance(q, &self.segments[n]) > self.sure);
            if cells.is_empty() {
                return true;
            }
        }
        false
    }
}

/// The distance from `q` to the line segment `s`.
fn segment_distance(q: DVec2, s: &Segment) -> f64 {
    s.closest_with(None, q).0.distance(q)
}

/// What clearing needs besides its settings: the tool's radius, the top of the material,
/// the feed and the cursor the moves start from.
pub struct RingSetup<'a, 'm> {
    pub tool_radius: f64,
    pub top: f64,
    pub feed: f64,
    pub cursor: &'a mut Cursor<'m>,
    pub tol: &'a Tolerances,
    /// Set where adaptive clearing stopped at a budget with material left
    /// ([`adaptive::Plan::stopped`]).
    pub unfinished: bool,
}

/// A region of one ring level and the regions one step further in that lie inside it.
struct Node {
    shape: Shape,
    children: Vec<Node>,
}

/// The rings of `region` for a tool of radius `reach`, from the offset `first` inwards every
/// `step` (outermost first; `forest` nests them). A step no wider than the tool's radius
/// leaves nothing between rings: a point deeper in than the last ring there reaches is deeper
/// than the next ring, which then exists. A wider step (a step-over above half the diameter)
/// can leave a strip where the region narrows between the last rings; a part of the region
/// that the next ring misses altogether (its core, 0.9 × `reach` in from the ring before)
/// gets a ring of its own, but a part the next ring only partly covers can keep a strip.
pub fn rings(region: &Shape, first: f64, step: f64, reach: f64, tol: &Tolerances) -> Vec<Shape> {
    let mut levels = Vec::new();
    let mut d = first;
    let mut ring = offset(region, -d, tol);
    while !ring.is_empty() && levels.len() <= 10_000 {
        let mut next = offset(region, -(d + step), tol);
        if step > reach {
            let core = offset(region, -(d + 0.9 * reach), tol);
            let inner = next.regions();
            for part in core.regions() {
                if !inner.iter().any(|n| part.contains(n.loops[0].probe_point())) {
                    next.loops.extend(part.loops);
                }
            }
        }
        levels.push(ring);
        ring = next;
        d += step;
    }
    levels
}

fn forest(levels: &[Shape]) -> Vec<Node> {
    fn build(levels: &[Shape], k: usize, parent: Option<&Shape>) -> Vec<Node> {
        if k >= levels.len() {
            return Vec::new();
        }
        levels[k]
            .regions()
            .into_iter()
            .filter(|r| parent.is_none_or(|p| p.contains(r.loops[0].probe_point())))
            .map(|r| {
                let children = build(levels, k + 1, Some(&r));
                Node { shape: r, children }
            })
            .collect()
    }
    build(levels, 0, None)
}

/// The map of the material at a depth that the zigzag passes cut, and the load they hold:
/// what the boundary ring after them is held by.
struct Held {
    map: PixelMap,
    limit: f64,
    ds: f64,
}

/// How a region is cleared at one depth.
#[derive(Clone, Copy, Debug)]
pub struct Clearing {
    /// Distance between rings or passes (mm).
    pub step: f64,
    pub climb: bool,
    pub pattern: PocketPattern,
    /// Direction of zigzag passes (radians from +X).
    pub angle: f64,
    /// How zigzag passes hold the load, and by how much over the reference.
    pub load: LoadControl,
    pub load_tolerance: f64,
    pub entry: EntryKind,
    /// Steepest descent of helices and ramps (radians).
    pub ramp_angle: f64,
    pub helix_r: f64,
    /// The depth adaptive clearing's load is set for (its step-down): a shallower level cuts
    /// wider, the same cross-section ([`crate::machining::adaptive::Adaptive::shallow_step`]);
    /// none (every other pattern), every level at `step`.
    pub depth: Option<f64>,
    /// The range of adaptive clearing's step length.
    pub adaptive_steps: adaptive::StepRange,
}

impl Clearing {
    /// The step of a level from `z_prev` down to `z` with a tool of radius `r`.
    pub fn step_between(&self, z_prev: f64, z: f64, r: f64) -> f64 {
        self.depth.map_or(self.step, |full| crate::machining::adaptive::Adaptive::shallow_step(self.step, full, z_prev - z, r))
    }

    /// Refuses a helical entry that would turn more than [`crate::limits::MAX_TURNS`] times to
    /// descend `descent` (mm; a level's step-down), naming the operation `op` and the radius.
    pub fn check_helix(&self, op: &str, descent: f64) -> crate::error::Result<()> {
        if self.entry != EntryKind::Helix {
            return Ok(());
        }
        let per_turn = std::f64::consts::TAU * self.helix_r * self.ramp_angle.tan();
        super::too_many(op, "helix turns", descent / per_turn, crate::limits::MAX_TURNS, "a helix radius of", self.helix_r, descent)
    }

    /// As a pocket clears by default, with a tool of radius `r`: climb, entered on a helix
    /// (0.8 r) or a 3° ramp, zigzag passes along X with the load held by the path.
    pub fn plain(step: f64, r: f64, pattern: PocketPattern) -> Clearing {
        Clearing {
            step,
            climb: true,
            pattern,
            angle: 0.0,
            load: LoadControl::Path,
            load_tolerance: 0.1,
            entry: EntryKind::Helix,
            ramp_angle: 3f64.to_radians(),
            helix_r: 0.8 * r,
            depth: None,
            adaptive_steps: adaptive::StepRange::default(),
        }
    }
}

/// Clears `region` from `s.top` down by `depth`, in passes of at most `stepdown`: its
/// tool-centre rings from `first` in from its boundary (a negative `first`: out past it) every
/// `clearing.step`, each pass by [`clear_rings`]. A 2.5D pocket, or facing a drawn region. None
/// when no ring fits.
pub fn clear_down(region: &Shape, first: f64, clearing: &Clearing, depth: f64, stepdown: f64, s: &mut RingSetup) -> Option<Vec<Move>> {
    let levels = rings(region, first, clearing.step, s.tool_radius, s.tol);
    if levels.is_empty() {
        return None;
    }
    let passes = (depth / stepdown.max(LEAST_STEP)).ceil().max(1.0) as usize;
    let mut out = Vec::new();
    for k in 1..=passes {
        let z_prev = s.top - depth * (k - 1) as f64 / passes as f64;
        let z = s.top - depth * k as f64 / passes as f64;
        out.extend(clear_rings(&levels, clearing, z_prev, z, s, None));
    }
    Some(out)
}

/// For a point of a region's outer boundary and a way out of it ([`way_out`]'s `k`), a point
/// beside it that way where the tool at the depth being cut touches no material (the air
/// beside the stock, or ground an earlier stage cleared), if there is one: such regions are
/// entered there and cleared from there inwards instead of from a helix.
pub type Air<'a> = &'a dyn Fn(DVec2, usize) -> Option<DVec2>;

/// The ways out of a region tried for a way in from the air, in order: away from the stock's
/// middle (the air beside the stock), then the eight compass directions (issue 38: a rest
/// region in a gully opens onto ground the larger tool cleared on either side, not towards the
/// stock's edge; its φ3 went in by 188 helices on ocl_mount_rush).
pub const WAYS_OUT: usize = 9;

/// The unit direction of way out `k` (below [`WAYS_OUT`]) from `p` of a region in a stock
/// whose middle is `middle`.
pub fn way_out(k: usize, p: DVec2, middle: DVec2) -> DVec2 {
    match k {
        0 => (p - middle).normalize_or_zero(),
        _ => DVec2::from_angle((k - 1) as f64 * std::f64::consts::FRAC_PI_4),
    }
}

/// Clears from `z_prev` (where the material starts) down to `z` the region whose tool-centre
/// rings are `levels` (the region itself first, then one step further in each), inner rings
/// first, each region entered by a helix or a ramp, ending with the outermost ring.
///
/// A region whose boundary reaches the `air` is cleared from the outside in: the loops that
/// run along its outer boundary, outermost first (the first entered in the air), then those
/// round its islands, farthest from them first; each takes off at most a step.
pub fn clear_rings(levels: &[Shape], clearing: &Clearing, z_prev: f64, z: f64, s: &mut RingSetup, air: Option<Air>) -> Vec<Move> {
    clear_rings_at_feed(levels, clearing, z_prev, z, s, air).run()
}

/// [`clear_rings`] with every feed move at the cutting feed, and the job that puts the
/// stretches of air at the air feed.
pub fn clear_rings_at_feed<'m>(levels: &[Shape], clearing: &Clearing, z_prev: f64, z: f64, s: &mut RingSetup<'_, 'm>, air: Option<Air>) -> Refeed<'m> {
    let stock = &s.cursor.stock;
    let mut job = Refeed { bounds: Rect::EMPTY, z, stock: stock.model(), profile: *stock.profile(), feed: s.cursor.air_feed, cutting: s.feed, from: s.cursor.at, moves: Vec::new() };
    let Some(boundary) = levels.first() else { return job };
    job.bounds = boundary.bounds().expand(s.tool_radius);
    // A level shallower than adaptive clearing's load is set for cuts wider.
    let clearing = &Clearing { step: clearing.step_between(z_prev, z, s.tool_radius), ..*clearing };
    // Cut only where the in-process stock has material, from where it starts.
    let Some(z_prev) = s.cursor.material_top(levels.iter().flat_map(|l| l.segments()), z_prev, z, s.tol.gouge) else { return job };
    s.cursor.safe = s.cursor.safe.min(z_prev + s.cursor.gap);
    let climb = clearing.climb;
    let orient = |l: &Loop| if climb { l.clone() } else { l.reversed() };
    let mut out = Vec::new();
    let forest = forest(levels);
    let swept = (clearing.pattern == PocketPattern::Offset).then(|| Swept::new(boundary, s.tool_radius, z, &s.cursor.stock, s.tol.chordal));
    let mut c = Clearer { s, boundary, angle: clearing.ramp_angle, helix_r: clearing.helix_r, entry: clearing.entry, out: &mut out, z_prev, z, step: clearing.step, swept };
    match clearing.pattern {
        PocketPattern::Offset => {
            for node in &forest {
                // Every point of the boundary tried one way out before the next way.
                let points = || node.shape.loops.iter().filter(|l| l.is_ccw()).flat_map(|l| l.vertices.iter().map(|v| v.p));
                match air.and_then(|air| (0..WAYS_OUT).find_map(|k| points().find_map(|p| air(p, k).map(|q| (p, q))))) {
                    Some((start, outside)) => c.cut_outside_in(node, start, outside, &orient),
                    None => c.cut_tree(node, &orient),
                }
            }
        }
        PocketPattern::Adaptive => {
            // Each pocket on its own: its passes, then its ring.
            for part in boundary.regions() {
                c.adaptive(&part, clearing);
                for l in &part.loops {
                    c.cut_loop(&orient(l), false);
                }
            }
        }
        PocketPattern::Zigzag => {
            // Each pocket (an outline and its islands) on its own: its passes, then its ring.
            for part in boundary.regions() {
                let mut held = c.zigzag(&part, clearing);
                for l in &part.loops {
                    let (from, before) = (c.out.len(), c.s.cursor.at);
                    c.cut_loop(&orient(l), false);
                    if let Some(h) = &mut held {
                        c.hold_by_feed(from, before, h);
                    }
                }
            }
        }
    }
    job.moves = out;
    job
}

/// The keep-out test of a pocket's links (the linker's [`Keepout`]): a straight move at depth
/// must stay inside the region the tool's centre may occupy (its boundary included: a move
/// may start or end on it).
pub struct Inside<'a>(pub &'a Shape);

impl Keepout for Inside<'_> {
    fn clears(&self, a: DVec3, b: DVec3, _tolerance: f64) -> bool {
        let (a, b) = (a.truncate(), b.truncate());
        let link = Segment::line(a, b);
        let at_end = |p: DVec2| p.distance(a) <= END_SLACK || p.distance(b) <= END_SLACK;
        self.0.contains((a + b) * 0.5) && self.0.segments().all(|s| s.crossings(&link, FLOAT_SLACK).iter().all(|c| at_end(c.p)))
    }
}

/// A link's crossing of the boundary this close to its ends is where it starts or ends on
/// the boundary (mm).
const END_SLACK: f64 = 1e-7;

struct Clearer<'a, 'b, 'm> {
    s: &'a mut RingSetup<'b, 'm>,
    boundary: &'a Shape,
    angle: f64,
    helix_r: f64,
    entry: EntryKind,
    out: &'a mut Vec<Move>,
    z_prev: f64,
    z: f64,
    /// The step between rings.
    step: f64,
    /// What the rings cut so far at this depth swept, where the material was.
    swept: Option<Swept>,
}

/// The material of one region at one depth as pixels (seed 004's pixel map), less what the
/// loops cut so far swept: a loop whose tool would sweep none of it runs in the air (where the
/// offsets round an island and those along the outer boundary meet, or over what an earlier
/// operation cleared) and is left out.
///
/// The map is the in-process stock as the program's simulation sees it (seed 002's z-map,
/// each cell's material at its centre): a pixel on each cell's centre, holding material where
/// the cell stands above the level. A loop counts the pixels within the cutter's radius and
/// the chordal tolerance (its arcs are judged as chords) and takes off those within the radius
/// less that tolerance, as the simulation cuts them; so a loop is left out only where its
/// cutter would meet no material the simulation holds. (A map of its own pixels, counted by
/// their centres, left a loop out whose sweep passed a pixel's centre at exactly the radius:
/// the sliver beside it, a few hundredths wide and standing the level's height, was in the
/// way of the traverses over the level, taken as cleared.) Over a region of more cells than a
/// map holds, the pixels are coarser and conservative: material where any cell whose square
/// meets the pixel's stands above the level, counted within the radius grown by a pixel's half
/// diagonal, taken off within the radius less it.
struct Swept {
    map: PixelMap,
    /// The radius each loop takes off the map.
    take: f64,
    chordal: f64,
}

impl Swept {
    fn new(region: &Shape, radius: f64, z: f64, stock: &super::path2d::InStock, chordal: f64) -> Swept {
        let model = stock.model();
        let reach = region.bounds().expand(radius + chordal + 2.0 * model.grid().spacing);
        if let Some(map) = PixelMap::on_cells(model, reach, z, radius + chordal) {
            return Swept { map, take: radius - chordal, chordal };
        }
        let px = load::pixel_for(region.bounds(), radius, radius / 8.0);
        let margin = std::f64::consts::FRAC_1_SQRT_2 * px + chordal;
        let half = DVec2::splat(0.5 * px);
        let map = PixelMap::of_material(region.bounds(), px, radius + margin, |p| model.material_over(p - half, p + half, z));
        Swept { map, take: radius - margin, chordal }
    }

    /// The loop as straight moves: its arcs as chords within the chordal tolerance.
    fn chords(&self, l: &Loop) -> Vec<(DVec2, DVec2)> {
        let mut out = Vec::new();
        for s in l.segments() {
            match s.arc_geom() {
                None => out.push((s.a, s.b)),
                Some(g) => {
                    let angle = g.start.angle_to(g.end).abs().max(FLOAT_SLACK);
                    let step = crate::geom::segment::chord_step(g.radius, self.chordal).unwrap_or(angle);
                    let n = ((angle / step.max(LEAST_STEP)).ceil() as usize).clamp(1, 1000);
                    let mut a = s.a;
                    for k in 1..=n {
                        let b = if k == n { s.b } else { s.point_at(k as f64 / n as f64) };
                        out.push((a, b));
                        a = b;
                    }
                }
            }
        }
        out
    }

    /// Whether the tool going round `l` sweeps material.
    fn cuts(&mut self, l: &Loop) -> bool {
        self.chords(l).into_iter().any(|(a, b)| self.map.count_past(a, b, 0) > 0)
    }

    /// Takes what the tool going round `l` surely sweeps off the material.
    fn cut(&mut self, l: &Loop) {
        if self.take <= 0.0 {
            return;
        }
        for (a, b) in self.chords(l) {
            self.map.cut_at(a, b, self.take);
        }
    }
}

impl Clearer<'_, '_, '_> {
    /// Whether `l` has material to cut (always, without a pixel map).
    fn has_material(&mut self, l: &Loop) -> bool {
        self.swept.as_mut().is_none_or(|s| s.cuts(l))
    }

    /// Notes `l` cut round at depth.
    fn swept(&mut self, l: &Loop) {
        if let Some(s) = &mut self.swept {
            s.cut(l);
        }
    }

    /// Whether the leaf ring region `leaf` (whose rings lie a step inside the ring before it)
    /// holds points farther than the tool's radius from that ring, over material: its points
    /// more than the radius less a step inside it, sampled along their outline every eighth of
    /// the radius.
    fn beyond_reach(&self, leaf: &Shape) -> bool {
        let r = self.s.tool_radius;
        let core = offset(leaf, -(r - self.step).max(0.0), self.s.tol);
        let every = (r / 8.0).max(LEAST_STEP);
        let found = core.segments().any(|seg| {
            let n = ((seg.length() / every).ceil() as usize).clamp(1, 10_000);
            (0..=n).any(|k| self.s.cursor.stock.material_at(seg.point_at(k as f64 / n as f64), self.z))
        });
        found
    }

    /// Whether a straight move at depth from `a` to `b` stays inside the pocket.
    fn inside(&self, a: DVec2, b: DVec2) -> bool {
        Inside(self.boundary).clears(a.extend(self.z), b.extend(self.z), 0.0)
    }

    fn at_depth(&self) -> bool {
        (self.s.cursor.at.z - self.z).abs() < FLOAT_SLACK
    }

    /// Inner regions first, then this one: a leaf is entered fresh, a parent is reached by
    /// staying down from its last child where the link allows.
    fn cut_tree(&mut self, node: &Node, orient: &dyn Fn(&Loop) -> Loop) {
        for child in &node.children {
            self.cut_tree(child, orient);
        }
        // A leaf's first loop cut is entered fresh: by the helix inside the leaf's outer loop
        // where that loop is the one (the helix's way out goes to it), else by a ramp.
        let leaf = node.children.is_empty();
        let mut fresh = leaf;
        for (i, l) in node.shape.loops.iter().enumerate() {
            if !self.has_material(l) {
                continue;
            }
            if !(fresh && i == 0 && self.entry == EntryKind::Helix && self.helix_into(&node.shape, &orient(l))) {
                self.cut_loop(&orient(l), fresh);
            }
            self.swept(l);
            fresh = false;
        }
    }

    /// A region open to the air, from the outside in: down in the air at `outside`, across to
    /// `start` on its outer boundary, its outer loops ring by ring inwards, then the loops round
    /// its islands from the innermost ring out to the walls.
    ///
    /// Cut from the outside in, a ring in the middle of the region comes after the rings on
    /// both sides of it: the pixel map may then find nothing left for it where the two cut
    /// within a pixel of each other, though a sliver stands between them. So a leaf ring whose
    /// region holds points beyond the reach of the ring before it, over material, is cut
    /// whatever the map says ([`Clearer::beyond_reach`]).
    fn cut_outside_in(&mut self, node: &Node, start: DVec2, outside: DVec2, orient: &dyn Fn(&Loop) -> Loop) {
        fn gather<'n>(c: &Clearer, node: &'n Node, depth: usize, out: &mut Vec<(usize, &'n Loop, bool)>) {
            let needed = node.children.is_empty() && c.beyond_reach(&node.shape);
            out.extend(node.shape.loops.iter().map(|l| (depth, l, needed)));
            for child in &node.children {
                gather(c, child, depth + 1, out);
            }
        }
        let mut loops = Vec::new();
        gather(self, node, 0, &mut loops);
        let mut outer: Vec<(usize, &Loop, bool)> = loops.iter().copied().filter(|(_, l, _)| l.is_ccw()).collect();
        let mut holes: Vec<(usize, &Loop, bool)> = loops.iter().copied().filter(|(_, l, _)| !l.is_ccw()).collect();
        crate::geom::sort::sort_by_float(&mut outer, |t| t.0 as f64);
        crate::geom::sort::sort_by_float(&mut holes, |t| -(t.0 as f64));
        let mut first = true;
        for (_, l, needed) in outer.into_iter().chain(holes) {
            // The first loop is cut whatever it sweeps: the way in from the air goes to it.
            if !first && !needed && !self.has_material(l) {
                continue;
            }
            let l = &orient(l);
            if first {
                // Down in the air beside the stock, in to the loop, then round.
                let segs = start_nearest(l, start);
                let (_, total) = arc_lengths(&segs);
                self.s.cursor.reposition(outside.extend(self.z), self.out);
                self.out.push(Move::Line { to: segs[0].a.extend(self.z), feed: self.s.feed });
                follow(&segs, 0.0, total, &Heights::constant(self.z), self.s.feed, self.out);
                self.s.cursor.moved(self.out);
                first = false;
            } else {
                self.cut_loop(l, false);
            }
            self.swept(l);
        }
    }

    /// Cuts a loop at depth, starting at its point nearest the tool; links down when the tool
    /// is at depth and the link stays inside, else ramps in along the loop.
    fn cut_loop(&mut self, l: &Loop, fresh: bool) {
        let segs = start_nearest(l, self.s.cursor.at.truncate());
        let (_, total) = arc_lengths(&segs);
        let start = segs[0].a;
        if !fresh && self.at_depth() && self.inside(self.s.cursor.at.truncate(), start) {
            self.out.push(Move::Line { to: start.extend(self.z), feed: self.s.feed });
            follow(&segs, 0.0, total, &Heights::constant(self.z), self.s.feed, self.out);
        } else {
            // Where material stands above the level before at the start (rest roughing beside
            // what an earlier tool left, which that level did not reach), the ramp starts on it.
            // Past the level before, the ramp starts no higher than an earlier level of the
            // operation cleared the material there.
            let cleared = self.s.cursor.safe_at.as_ref().is_none_or(|f| f(start));
            let top = if cleared { self.z_prev } else { self.s.cursor.stock.estimate(start).min(self.s.cursor.cleared(start).unwrap_or(f64::INFINITY)) };
            let from = if top > self.z_prev + self.s.tol.gouge { top } else { self.z_prev };
            self.s.cursor.reposition(start.extend(from), self.out);
            let ramp = Heights::ramp(0.0, from, self.z, self.angle);
            let run = (from - self.z) / self.angle.tan();
            follow(&segs, 0.0, run + total, &ramp, self.s.feed, self.out);
        }
        self.s.cursor.moved(self.out);
    }

    /// A helix down inside a leaf region, then out to its loop; false when none fits.
    fn helix_into(&mut self, region: &Shape, l: &Loop) -> bool {
        let room = offset(region, -self.helix_r, self.s.tol);
        let Some(c) = room.loops.first().map(|r| r.vertices[0].p) else { return false };
        let start = c + DVec2::new(self.helix_r, 0.0);
        self.s.cursor.reposition(start.extend(self.z_prev), self.out);
        helix(c, self.helix_r, self.z_prev, self.z, self.angle, false, self.s.feed, self.out);
        let segs = start_nearest(l, start);
        let (_, total) = arc_lengths(&segs);
        self.out.push(Move::Line { to: segs[0].a.extend(self.z), feed: self.s.feed });
        follow(&segs, 0.0, total, &Heights::constant(self.z), self.s.feed, self.out);
        self.s.cursor.moved(self.out);
        true
    }

    /// Parallel passes across `region` at the clearing's angle, at most its step apart, back
    /// and forth: the walk of seed 004's intersection-points graph ([`Graph`]), each run of it
    /// entered by a ramp along its first pass (or reached staying down where the link stays
    /// inside), and followed along the region's boundary between passes. Its load held as the
    /// clearing asks (§3, [`crate::zigzag::load`]), on a map of the material at this depth:
    /// extra path where a step would take more than the step-over's load, or a lower feed.
    fn zigzag(&mut self, region: &Shape, clearing: &Clearing) -> Option<Held> {
        let (step, climb) = (clearing.step, clearing.climb);
        let graph = Graph::new(region, clearing.angle, step);
        let r = self.s.tool_radius;
        let load = Load { ds: 0.5 * step, step, tolerance: clearing.load_tolerance, climb };
        let px = load::pixel_for(region.bounds(), r, load::default_pixel(step));
        let limit = load.reference(px) * (1.0 + clearing.load_tolerance);
        let z = self.z;
        let mut map = (clearing.load != LoadControl::None).then(|| {
            let stock = &self.s.cursor.stock;
            PixelMap::new(region.bounds(), px, r, |p| stock.material_at(p, z), region)
        });
        for run in graph.walk(Pattern::Zigzag, climb, self.s.tol.chordal) {
            let (pa, pb) = (run[0], run[1]);
            let at = self.s.cursor.at.truncate();
            // Staying down only where the straight link stays inside and, when the load is
            // held, keeps it.
            let keeps = |m: &mut PixelMap| load::link_keeps(m, &load::densify(&[at, pa], load.ds / load::SUBSTEPS as f64), limit, load.ds);
            if self.at_depth() && self.inside(at, pa) && map.as_mut().is_none_or(keeps) {
                if let Some(map) = &mut map {
                    map.cut(at, pa);
                }
                self.out.push(Move::Line { to: pa.extend(z), feed: self.s.feed });
            } else {
                self.s.cursor.reposition(pa.extend(self.z_prev), self.out);
                self.ramp_on_line(pa, pb);
            }
            match &mut map {
                None => self.out.extend(run[1..].iter().map(|p| Move::Line { to: p.extend(z), feed: self.s.feed })),
                Some(map) => {
                    let mut steps = LoadProfile::default();
                    let pts = match clearing.load {
                        LoadControl::Path => load::corrected(map, &run, &load, &mut steps),
                        _ => load::plain(map, &run, &load, &mut steps),
                    };
                    let moves: Vec<Move> =
                        pts[1..].iter().zip(&steps.counts).map(|(p, &(n, len))| Move::Line { to: p.extend(z), feed: self.s.feed * load::feed_share(n, len, limit, load.ds).unwrap_or(1.0) }).collect();
                    self.out.extend(arcfit::fit(&moves, pa.extend(z), self.s.tol.chordal, &|p| region.contains(p)));
                }
            }
            self.s.cursor.moved(self.out);
        }
        map.map(|map| Held { map, limit, ds: load.ds })
    }

    /// The moves from `from` on (the tool standing at `before`) with their feed lowered where
    /// the cut along the depth would take more than the held load: each move at the depth in
    /// pieces a quarter of Δs long, pieces at one feed joined again (arcs stay arcs on their
    /// circle). The boundary ring after the passes finishes the wall: held by the feed, as
    /// zigzag roughing holds its last contour.
    fn hold_by_feed(&mut self, from: usize, before: DVec3, held: &mut Held) {
        let moves: Vec<Move> = self.out.drain(from..).collect();
        let piece = held.ds / load::SUBSTEPS as f64;
        let mut at = before;
        for m in moves {
            let to = m.to();
            let level = (at.z - self.z).abs() < FLOAT_SLACK && (to.z - self.z).abs() < FLOAT_SLACK;
            // An arc: its centre, turn and signed sweep.
            let (feed, arc) = match m {
                Move::Line { feed, .. } if level => (feed, None),
                Move::Arc { feed, center, clockwise, .. } if level => (feed, Some((center, clockwise, crate::toolpath::arc_sweep(at, to, center, clockwise)))),
                _ => {
                    if !m.is_rapid() && at.z.min(to.z) <= self.z + FLOAT_SLACK {
                        held.map.cut(at.truncate(), to.truncate());
                    }
                    self.out.push(m);
                    at = to;
                    continue;
                }
            };
            let point = |t: f64| match arc {
                None => at.lerp(to, t),
                Some((c, _, sweep)) => (c + DVec2::from_angle(sweep * t).rotate(at.truncate() - c)).extend(self.z),
            };
            let length = match arc {
                None => at.distance(to),
                Some((c, _, sweep)) => sweep.abs() * c.distance(at.truncate()),
            };
            let n = (length / piece).ceil().max(1.0) as usize;
            let mut prev = at;
            let mut group: Option<(DVec3, f64)> = None;
            let emit = |out: &mut Vec<Move>, end: DVec3, f: f64| match arc {
                None => out.push(Move::Line { to: end, feed: f }),
                Some((center, clockwise, _)) => out.push(Move::Arc { to: end, center, clockwise, feed: f }),
            };
            for k in 1..=n {
                let q = if k == n { to } else { point(k as f64 / n as f64) };
                let count = held.map.cut(prev.truncate(), q.truncate()) as f64;
                let f = feed * load::feed_share(count, prev.distance(q), held.limit, held.ds).unwrap_or(1.0);
                match group {
                    Some((_, g)) if g == f => group = Some((q, f)),
                    Some((end, g)) => {
                        emit(self.out, end, g);
                        group = Some((q, f));
                    }
                    None => group = Some((q, f)),
                }
                prev = q;
            }
            if let Some((end, g)) = group {
                emit(self.out, end, g);
            }
            at = to;
        }
    }

    /// Adaptive clearing of `region` ([`adaptive::plan`]) on a map of the material the stock
    /// holds at this depth within the tool's reach of the region, less a pixel (what the
    /// pixels leave against the walls is the boundary ring's). Each pass is entered by its
    /// helix, staying down, or from above where its start stands clear of material; its points
    /// are fitted with lines and arcs.
    fn adaptive(&mut self, region: &Shape, clearing: &Clearing) {
        let r = self.s.tool_radius;
        let (z, feed) = (self.z, self.s.feed);
        let ae = clearing.step.min(2.0 * r);
        let px = load::pixel_for(region.bounds(), r, (ae / ADAPTIVE_AE_PIXELS).min(r / ADAPTIVE_R_PIXELS));
        // The map's rows, as it lays them.
        let (origin, _, ny) = PixelMap::layout(region.bounds(), px, r);
        let ys: Vec<f64> = (0..ny).map(|j| origin.y + j as f64 * px).collect();
        let spans = offset(region, r - px, self.s.tol).spans_on_rows(&ys);
        let stock = &self.s.cursor.stock;
        let reach = |p: DVec2| {
            let j = ((p.y - origin.y) / px).round();
            j >= 0.0 && spans.get(j as usize).is_some_and(|row| row.iter().any(|&(x0, x1)| p.x >= x0 && p.x <= x1))
        };
        // The passes are planned to a pixel, and fitted within half a pixel: planned that far
        // inside the region, so that the fitted lines and arcs stay in it.
        let fit = (0.5 * px).max(self.s.tol.chordal);
        let inner = offset(region, -fit, self.s.tol);
        if inner.is_empty() {
            return;
        }
        let mut map = PixelMap::new(region.bounds(), px, r, |p| reach(p) && stock.material_at(p, z), &inner);
        let (shortest, longest) = clearing.adaptive_steps.fractions(r);
        let step = (shortest * r).max(2.0 * px);
        let a = Adaptive { radius: r, target: Adaptive::angle_of(ae, r), climb: clearing.climb, helix_r: clearing.helix_r, step, longest: (longest * r).max(step) };
        let plan = adaptive::plan(&mut map, &a, self.s.cursor.at.truncate());
        self.s.unfinished |= plan.stopped;
        let mut left = Uncut::new(self.s.cursor.stock.model(), r - fit - self.s.tol.chordal, r);
        for pass in plan.passes {
            let first = pass.points[0];
            match pass.entry {
                Entry::Helix { centre, radius } => {
                    self.s.cursor.reposition((centre + DVec2::new(radius, 0.0)).extend(self.z_prev), self.out);
                    helix(centre, radius, self.z_prev, z, self.angle, false, feed, self.out);
                    self.out.push(Move::Line { to: first.extend(z), feed });
                }
                Entry::Down if self.at_depth() => self.out.push(Move::Line { to: first.extend(z), feed }),
                Entry::Down | Entry::Above => {
                    // Straight down where the simulation will hold nothing under the tool (at
                    // the air feed: the passes cleared the way down). Else (a cell the passes
                    // so far only grazed, which the map took for cut) down at the nearest point
                    // a few steps away where it holds nothing, in along a line in the region;
                    // else down a small helix beside the point, where one fits in the region.
                    let ok = |p: DVec2| map.allowed(p) || region.contains(p);
                    let hr = LEAST_HELIX * r;
                    let step = a.step;
                    let line_ok = |c: DVec2| {
                        let n = (c.distance(first) / px).ceil() as usize;
                        (0..=n).all(|k| ok(c.lerp(first, k as f64 / n.max(1) as f64)))
                    };
                    let aside =
                        || (1..=ADAPTIVE_ASIDE).flat_map(|k| (0..16).map(move |t| first + k as f64 * step * DVec2::from_angle(t as f64 * PI / 8.0))).find(|&c| left.clear(c, r, z) && line_ok(c));
                    let circle_ok = |c: DVec2| (0..24).all(|t| ok(c + hr * DVec2::from_angle(t as f64 * PI / 12.0)));
                    match left.clear(first, r, z) {
                        true => self.s.cursor.reposition_into_cleared(first.extend(z), self.out),
                        false => match aside() {
                            Some(c) => {
                                self.s.cursor.reposition_into_cleared(c.extend(z), self.out);
                                self.out.push(Move::Line { to: first.extend(z), feed });
                            }
                            None => match (0..8).map(|k| first - hr * DVec2::from_angle(k as f64 * FRAC_PI_4)).find(|&c| circle_ok(c)) {
                                Some(c) => {
                                    self.s.cursor.reposition((c + DVec2::new(hr, 0.0)).extend(self.z_prev), self.out);
                                    helix(c, hr, self.z_prev, z, self.angle, false, feed, self.out);
                                    self.out.push(Move::Line { to: first.extend(z), feed });
                                }
                                None => self.s.cursor.reposition(first.extend(z), self.out),
                            },
                        },
                    }
                }
            }
            if let Some(c) = match pass.entry {
                Entry::Helix { centre, radius } => Some((centre, radius)),
                _ => None,
            } {
                left.reach(&(0..=72).map(|t| c.0 + c.1 * DVec2::from_angle(t as f64 * PI / 36.0)).collect::<Vec<_>>());
            }
            left.reach(&pass.points);
            // (A step longer than the shortest is fitted through points a shortest step apart
            // along it: an arc through the steps' ends alone strays from the chords the map cut by
            // their sagitta, a tenth of a millimetre at half a radius.)
            let moves: Vec<Move> = pass
                .points
                .windows(2)
                .flat_map(|w| {
                    let n = adaptive::shortest_steps(w[0].distance(w[1]), a.step);
                    (1..=n).map(move |k| if k == n { w[1] } else { w[0].lerp(w[1], k as f64 / n as f64) })
                })
                .map(|p| Move::Line { to: p.extend(z), feed })
                .collect();
            // (The map's region, inside the region, answers most points at once.)
            self.out.extend(arcfit::fit(&moves, first.extend(z), fit, &|p| map.allowed(p) || region.contains(p)));
            self.s.cursor.moved(self.out);
        }
    }

    /// Back and forth along `a`–`b`, descending at the ramp angle, ending at `a` at depth.
    fn ramp_on_line(&mut self, a: DVec2, b: DVec2) {
        let len = a.distance(b).max(LEAST_STEP);
        let mut z = self.z_prev;
        let mut at_a = true;
        while z > self.z + FLOAT_ZERO {
            z = (z - len * self.angle.tan()).max(self.z);
            let to = if at_a { b } else { a };
            self.out.push(Move::Line { to: to.extend(z), feed: self.s.feed });
            at_a = !at_a;
        }
        if !at_a {
            self.out.push(Move::Line { to: a.extend(self.z), feed: self.s.feed });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::Profile;
    use crate::geom::Aabb;
    use crate::sim::sweep::Sweep;
    use crate::sim::{DexelStock, StockModel};

    /// Whatever the pixels, a region cleared from the outside in leaves nothing above its level
    /// within the cutter's reach of it (what the traverses over a level take as cleared): a
    /// sliver of material two cells wide standing a hair past the outer ring's reach, the
    /// region's edge moved across the map's pixels a hundredth at a time.
    #[test]
    fn a_sliver_a_hair_past_the_outer_rings_reach_is_cut_by_the_next() {
        let (r, tol) = (3.0, Tolerances::default());
        let profile = Profile::new(r, 0.0);
        let clearing = Clearing { entry: EntryKind::Ramp, ..Clearing::plain(0.24, r, PocketPattern::Offset) };
        for k in 0..12 {
            let x0 = 0.005 + 0.01 * k as f64;
            // Material at z 1 only in the cells whose centres are at x0 + r + 0.005 and + 0.025,
            // the rest lowered to -1, below the level at 0.
            let mut stock = DexelStock::new(&Aabb { min: DVec3::new(-5.0 + x0 - 0.005, -5.0, -2.0), max: DVec3::new(25.0, 25.0, 1.0) }, 0.02, 1);
            let wide = Profile::new(10.0, 0.0);
            let (lo, hi) = (x0 + r - 0.005, x0 + r + 0.035);
            stock.apply(&Sweep::line(wide, DVec3::new(lo - 10.0, -20.0, -1.0), DVec3::new(lo - 10.0, 45.0, -1.0)));
            stock.apply(&Sweep::line(wide, DVec3::new(hi + 10.0, -20.0, -1.0), DVec3::new(hi + 10.0, 45.0, -1.0)));
            let region = Shape::new(vec![Loop::rect(DVec2::new(x0, 0.0), DVec2::new(x0 + 20.0, 20.0))]);
            let levels = rings(&region, 0.0, clearing.step, r, &tol);
            let before = stock.clone();
            let mut cursor = Cursor {
                at: DVec3::new(x0 - 5.0, 10.0, 5.0),
                clearance: 5.0,
                safe: 2.0,
                gap: 1.0,
                full_retract: false,
                plunge: 300.0,
                traverse: None,
                safe_at: None,
                cleared_to: None,
                stock: super::super::path2d::InStock::new(&before, profile, tol.gouge),
                air_feed: 1000.0,
            };
            let mut setup = RingSetup { tool_radius: r, top: 1.0, feed: 1000.0, cursor: &mut cursor, tol: &tol, unfinished: false };
            let from = setup.cursor.at;
            let beside = |p: DVec2, _: usize| Some(p - DVec2::new(r + 1.0, 0.0));
            let moves = clear_rings(&levels, &clearing, 1.0, 0.0, &mut setup, Some(&beside));
            let mut at = from;
            for m in &moves {
                for s in Sweep::of_move(profile, at, m, tol.chordal) {
                    stock.apply(&s);
                }
                at = m.to();
            }
            let g = stock.grid();
            for j in 0..g.ny {
                for i in 0..g.nx {
                    let c = g.node(i, j);
                    let off = DVec2::new((x0 - c.x).max(c.x - x0 - 20.0).max(0.0), (-c.y).max(c.y - 20.0).max(0.0)).length();
                    assert!(off > r - 0.005 || stock.top(i, j) <= 1e-6, "edge at x {x0}: material at {:.3} over ({:.3}, {:.3}), {off:.3} from the region", stock.top(i, j), c.x, c.y);
                }
            }
        }
    }
}
