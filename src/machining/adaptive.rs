//! Adaptive clearing (issue 59): the tool held at a constant engagement angle, step by step,
//! on a map of the material left at one depth.
//!
//! **The engagement.** A tool moving forward cuts only with the front half of its circle (its
//! back half runs in what it has just cut). The engagement at a point is the angle of that
//! front half standing in material, measured on the pixel map of the level
//! ([`crate::zigzag::load::PixelMap`], seed 004 §3.2's map) at [`SAMPLES`] points of the
//! circle. A straight cut `ae` into a wall engages `arccos(1 − 2·ae/D)`: the target.
//!
//! **A pass.** From a point where the tool touches no material, headed with the material on
//! its right (climb; left for conventional), the tool takes steps. At each, the heading is
//! searched by bisection between a quarter turn towards the material and a quarter turn away
//! for the step of the shortest length whose engagement is nearest the target (more towards the
//! material, more engagement): along a wall it holds the step-over, into a corner it turns away
//! before the engagement climbs. Where the last step's curvature holds the engagement, the next
//! step runs on along it and twice as long, up to the longest step ([`StepRange`]); where it no
//! longer holds, the step is the shortest again, searched. Where even the hardest turn cuts too
//! little, it heads for the material and no further (turning past it would turn the pass round on the spot). A step
//! must keep the tool's centre in the region. A pass ends where every heading would take more
//! than [`MOST_OVER`] times the target (a front that would overload: the next pass starts
//! elsewhere), where no heading finds material, or after half a tool's radius of idle steps;
//! the steps after its last cut are not made (they would run in air at the cutting feed), nor
//! is a pass that cuts nothing (the wheel in a box's narrow levels tried 1,600 of them).
//!
//! **Between passes.** The next pass starts where the tool touches no material and material
//! lies within a step of its reach (a distance transform of the map in blocks, kept up to date in a
//! window about what each pass cut): first where a front of material begins (a step back along the
//! front the tool would be outside the region or out of reach of material, so the pass runs the
//! front's whole length), the nearest such point; reached staying down where the straight way
//! touches no material and stays in the region, else over the top. Where no such point is left but
//! material is, a helix goes down in the middle of it (the point of the region farthest from its
//! boundary among those over material; smaller than asked where the room is, down to
//! [`LEAST_HELIX`] of the tool's radius), and the passes spiral out from the hole it cuts.
//!
//! What the pixels leave against the region's boundary (a pixel or so) is for a boundary
//! contour cut after the passes to take off ([`crate::machining::rings`] does).

use crate::geom::DVec2;
use crate::zigzag::load::PixelMap;
use crate::zmap::distance::{distance_to, distance_within, distance_within_rows};
use std::f64::consts::{FRAC_PI_2, PI};

/// Points of the front half of the tool's circle at which the engagement is measured.
pub const SAMPLES: usize = 120;
/// Headings tried per step by bisection between the quarter turns.
const SEARCH: usize = 12;
/// Most steps in all, as a multiple of the steps the area needs at the target (plus a margin).
const STEP_BUDGET: f64 = 6.0;
/// A pass ends after this many tool radii of steps cutting (next to) nothing.
const IDLE: f64 = 0.5;
/// How near the target the last step's turn must keep the engagement to be taken again.
const KEEP: f64 = 0.04;
/// The smallest helix, as a fraction of the tool's radius.
pub const LEAST_HELIX: f64 = 0.2;
/// The most engagement a step may take, over the target: past it the pass ends.
pub const MOST_OVER: f64 = 1.25;
/// Most passes in all.
const MOST_PASSES: usize = 20_000;

/// How the passes are made.
#[derive(Clone, Copy, Debug)]
pub struct Adaptive {
    /// The tool's radius (mm).
    pub radius: f64,
    /// The target engagement angle (radians).
    pub target: f64,
    /// Material on the right (climb with a clockwise spindle).
    pub climb: bool,
    /// The helix's radius where one is needed (mm).
    pub helix_r: f64,
    /// The length of a step, where its heading is searched (mm).
    pub step: f64,
    /// The longest step, along a run the last step's curvature holds at the target (mm; at
    /// least `step`).
    pub longest: f64,
}

/// An adaptive step's length where none is set, as a fraction of the tool's radius.
pub const STEP: f64 = 0.1;
/// The longest adaptive step, as a fraction of the tool's radius (longer, a step runs past the
/// corners it should turn at).
pub const MOST_STEP: f64 = 0.5;

/// The range of an adaptive path's step length (mm), as the job sets it: the shortest, where the
/// path turns (each heading searched), and the longest, along a run that holds the engagement.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepRange {
    pub min: Option<f64>,
    pub max: Option<f64>,
}

impl StepRange {
    /// The shortest and the longest step as fractions of a tool radius `r`, each at most
    /// [`MOST_STEP`]: unset, [`STEP`]; one set alone, the other at least (at most) as long.
    pub fn fractions(&self, r: f64) -> (f64, f64) {
        let (min, max) = (self.min.map(|m| m / r), self.max.map(|m| m / r));
        let min = min.unwrap_or(max.map_or(STEP, |max| max.min(STEP))).min(MOST_STEP);
        let max = max.unwrap_or(STEP).max(min).min(MOST_STEP);
        (min, max)
    }

    /// Refuses a length that is not positive, or a longest step shorter than the shortest.
    pub fn validate(&self) -> Result<(), crate::machining::FieldError> {
        for (field, v) in [("minStep", self.min), ("maxStep", self.max)] {
            if let Some(v) = v {
                crate::machining::positive(field, v)?;
            }
        }
        match (self.min, self.max) {
            (Some(min), Some(max)) if max < min => Err(crate::machining::FieldError {
                field: "maxStep",
                message: format!("must be at least the shortest step, minStep ({} mm; got {} mm)", crate::limits::shown(min), crate::limits::shown(max)),
            }),
            _ => Ok(()),
        }
    }
}

/// The lightest optimal load adaptive clearing holds, as a fraction of the tool's diameter
/// (lighter, the engagement is a sliver of a degree, and the path runs for kilometres).
pub const LEAST_LOAD: f64 = 0.02;

/// Refuses an optimal load lighter than [`LEAST_LOAD`], naming the job file's field.
pub fn check_load(load: f64) -> Result<(), crate::machining::FieldError> {
    if load >= LEAST_LOAD {
        Ok(())
    } else {
        Err(crate::machining::FieldError {
            field: "stepoverFraction",
            message: format!(
                "must be at least {LEAST_LOAD} of the tool's diameter for adaptive clearing, which holds the engagement of that load (got {}): adaptive loads are usually 0.05 to 0.4",
                crate::limits::shown(load)
            ),
        })
    }
}

impl Adaptive {
    /// The engagement angle of a straight cut `ae` (mm) deep into a wall by a tool of radius `r`.
    pub fn angle_of(ae: f64, r: f64) -> f64 {
        (1.0 - ae / r).clamp(-1.0, 1.0).acos()
    }

    /// The radial cut (mm) of a level `depth` deep when the optimal load `ae` (mm) is set for
    /// levels `full` deep, with a tool of radius `r`: a shallower level (a flat, the last of a
    /// part) takes a proportionally wider cut, the same cross-section as a full level's, up to
    /// half the tool's radius (60° of its circle in the material: wider, the passes no longer
    /// hold it and the path grows again; a flat of the wheel in a box took 23 m at a radius,
    /// 13.5 m at half, 17 m at the load); a full level, or a load already wider, the load itself.
    pub fn shallow_step(ae: f64, full: f64, depth: f64, r: f64) -> f64 {
        if depth > 0.0 && depth < full {
            (ae * full / depth).min(0.5 * r).max(ae)
        } else {
            ae
        }
    }
}

/// The warning where a budget stopped adaptive clearing with material left ([`Plan::stopped`])
/// at the heights `z` (none: the operation's only depths).
pub fn unfinished(z: &[f64]) -> String {
    let at = if z.is_empty() { String::new() } else { format!(" at Z {}", z.iter().map(|z| crate::limits::shown((z * 1e3).round() / 1e3)).collect::<Vec<_>>().join(", ")) };
    format!("adaptive clearing stopped at its limit of steps or passes with material left{at}: a shortest step nearer {STEP} × the tool's radius, a heavier load or a larger tool needs fewer")
}

/// How a pass is entered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Entry {
    /// Down a helix about `centre` of this `radius`, ending at the pass's first point (the
    /// point of the circle at +X from the centre).
    Helix { centre: DVec2, radius: f64 },
    /// Staying down from where the last pass ended: the way touches no material.
    Down,
    /// From above: the first point touches no material at the depth.
    Above,
}

/// One pass: its entry and the points of the tool's centre.
#[derive(Clone, Debug)]
pub struct Pass {
    pub entry: Entry,
    pub points: Vec<DVec2>,
}

/// The passes and the engagement along them.
#[derive(Clone, Debug, Default)]
pub struct Plan {
    pub passes: Vec<Pass>,
    /// Each step's length (mm) and engagement (radians), pass after pass.
    pub engagement: Vec<(f64, f64)>,
    /// Whether a budget stopped the planning with material left.
    pub stopped: bool,
}

/// The passes clearing `map`'s material (the material the tool may cut: within its reach of the
/// map's region) with the tool's centre where the map allows it, starting from `from`.
pub fn plan(map: &mut PixelMap, a: &Adaptive, from: DVec2) -> Plan {
    let r = a.radius;
    let px = map.pixel();
    let step = a.step.max(2.0 * px);
    let mut out = Plan::default();
    // Blocks of pixels for the distance transforms: about a sixth of a step, so that some
    // lie within a step of the material's reach and clear of it.
    let k = ((step / 6.0 / px).floor() as usize).max(1);
    let block = k as f64 * px;
    let half_diag = block * std::f64::consts::FRAC_1_SQRT_2;
    let (origin, nx, ny) = map.grid();
    let (bx, by) = (nx.div_ceil(k), ny.div_ceil(k));
    let centre_of = |i: usize, j: usize| origin + (DVec2::new((i * k) as f64, (j * k) as f64) + DVec2::splat((k - 1) as f64 / 2.0)) * px;
    // Room for a helix: each block's distance from the region's outside.
    let outside: Vec<bool> = (0..bx * by).map(|n| !map.allowed(centre_of(n % bx, n / bx))).collect();
    let room = distance_to(&outside, bx, by, block);
    let ae = r * (1.0 - a.target.cos());
    let budget = (STEP_BUDGET * map.left() as f64 * px * px / (ae.max(px) * step)) as usize + 10_000;
    let mut steps = 0usize;
    let mut at = from;
    let mut tried = vec![false; bx * by];
    let side = if a.climb { 1.0 } else { -1.0 };
    // The material's blocks, each block's distance from them (within reach of a start), and
    // the blocks a pass may start from (clear of the material, within a step of its reach),
    // kept up to date in a window about what each pass cut.
    let cap = r + step + block;
    let (mut material, _, _) = map.blocks(k);
    // (What was cut before this plan is in the blocks already: only the passes' cuts count.)
    map.take_cut();
    let mut blocks_left = material.iter().filter(|&&m| m).count();
    let mut near = distance_within(&material, bx, by, block, cap);
    let block_at = |p: DVec2| {
        let u = ((p - origin) / block - DVec2::splat((k - 1) as f64 / 2.0 / k as f64)).round();
        (u.x >= 0.0 && u.y >= 0.0 && (u.x as usize) < bx && (u.y as usize) < by).then(|| u.y as usize * bx + u.x as usize)
    };
    // A start: a block clear of the material within a step of its reach, where the tool's
    // centre may stand, and whether a front begins there (a step back along it the tool would
    // be outside the region or out of reach of material).
    let start_at = |map: &PixelMap, near: &[f64], i: usize, j: usize| {
        let n = j * bx + i;
        let d = near[n];
        if !(i > 0 && j > 0 && i + 1 < bx && j + 1 < by && d - half_diag > r && d + half_diag <= r + step) {
            return None;
        }
        let c = centre_of(i, j);
        if !map.allowed(c) {
            return None;
        }
        let g = -DVec2::new(near[n + 1] - near[n - 1], near[n + bx] - near[n - bx]);
        let begins = !g.is_finite() || g.length() < 1e-12 || {
            let h = rotate(g.normalize(), side * FRAC_PI_2);
            let up = c - h * step;
            !map.allowed(up) || block_at(up).is_none_or(|m| near[m] - half_diag > r + step)
        };
        Some((n, begins, c))
    };
    let mut starts: Vec<(usize, bool, DVec2)> = (0..bx * by).filter_map(|n| start_at(map, &near, n % bx, n / bx)).collect();
    // Blocks `(i0, j0)` to `(i1, j1)` (exclusive) within `grow` mm (and a block or two) of the points' box.
    let window = |pts: &[DVec2], grow: f64| {
        let b = pts.iter().fold(crate::geom::segment::Rect::EMPTY, |b, &p| b.grow(p));
        let lo = ((b.min - origin) / block - DVec2::splat(grow / block + 1.0)).floor().max(DVec2::ZERO);
        let hi = ((b.max - origin) / block + DVec2::splat(grow / block + 2.0)).ceil();
        ((lo.x as usize, lo.y as usize), ((hi.x as usize).min(bx), (hi.y as usize).min(by)))
    };
    loop {
        if out.passes.len() >= MOST_PASSES || steps >= budget {
            out.stopped = true;
            break;
        }
        if blocks_left == 0 {
            break;
        }
        // The nearest block the tool stands clear of material by, within a step of reach;
        // of those, first the ones where a front begins (its pass runs the front's length).
        let mut best: Option<(bool, f64, usize)> = None;
        let mut at_start = 0;
        while at_start < starts.len() {
            let (n, begins, c) = starts[at_start];
            if tried[n] {
                // (Tried once, never again: out of the list.)
                starts.swap_remove(at_start);
                continue;
            }
            at_start += 1;
            let dist = c.distance_squared(at);
            if best.is_none_or(|(bb, b, _)| (begins && !bb) || (begins == bb && dist < b)) {
                best = Some((begins, dist, n));
            }
        }
        let best = best.map(|(_, d, n)| (d, n));
        let (start, entry, heading) = match best {
            Some((_, n)) => {
                tried[n] = true;
                let c = centre_of(n % bx, n / bx);
                if map.count(c, c) > 0 {
                    continue;
                }
                let Some(g) = material_direction(map, c, r + step) else { continue };
                let clear = map.count(at, c) == 0 && way_inside(map, at, c, px);
                (c, if clear { Entry::Down } else { Entry::Above }, rotate(g, side * FRAC_PI_2))
            }
            None => {
                // A helix in the middle of the material the region reaches: of the helix's
                // radius, or as large as fits down to [`LEAST_HELIX`] of the tool's radius (a
                // channel narrower than the helix).
                let mut middle: Option<(f64, usize)> = None;
                for n in 0..bx * by {
                    if material[n] && !tried[n] && middle.is_none_or(|(b, _)| room[n] > b) {
                        middle = Some((room[n], n));
                    }
                }
                let Some((room_there, n)) = middle else { break };
                let helix_r = a.helix_r.min(room_there - half_diag - px);
                if helix_r < LEAST_HELIX * r {
                    break;
                }
                tried[n] = true;
                let c = centre_of(n % bx, n / bx);
                let s = c + DVec2::new(helix_r, 0.0);
                if !map.allowed(s) {
                    continue;
                }
                let turns = 72;
                for t in 0..turns {
                    let (p, q) = (c + helix_r * DVec2::from_angle(t as f64 * 2.0 * PI / turns as f64), c + helix_r * DVec2::from_angle((t + 1) as f64 * 2.0 * PI / turns as f64));
                    map.cut(p, q);
                }
                (s, Entry::Helix { centre: c, radius: helix_r }, DVec2::new(0.0, side))
            }
        };
        let (points, engaged, removed) = pass(map, a, start, heading, step, &mut steps, budget);
        if removed == 0 && !matches!(entry, Entry::Helix { .. }) {
            // A pass that cut nothing is not made (its start stays tried).
            continue;
        }
        // What the pass (and its helix) cut lies within the box of the pixels they cut: the
        // blocks' distances change only within `cap` of that (and a pixel, for the blocks
        // whose pixels' neighbours were cut), and are found from the material within `cap`
        // of those.
        if let Some(cut) = map.take_cut() {
            let changed = cap + 2.0 * px;
            let (inner_lo, inner_hi) = window(&cut, changed);
            let (lo, hi) = window(&cut, changed + cap);
            let w = hi.0 - lo.0;
            let part = map.blocks_within(k, lo, hi);
            // (Worked along the inner window's rows only: the rest is there for their distances.)
            let d = distance_within_rows(&part, w, hi.1 - lo.1, block, cap, inner_lo.1 - lo.1..inner_hi.1 - lo.1);
            for j in lo.1..hi.1 {
                let now = &part[(j - lo.1) * w..(j - lo.1 + 1) * w];
                for (was, &now) in material[j * bx + lo.0..j * bx + hi.0].iter_mut().zip(now) {
                    blocks_left = blocks_left + now as usize - *was as usize;
                    *was = now;
                }
                if (inner_lo.1..inner_hi.1).contains(&j) {
                    let at = (j - inner_lo.1) * w + inner_lo.0 - lo.0;
                    near[j * bx + inner_lo.0..j * bx + inner_hi.0].copy_from_slice(&d[at..at + inner_hi.0 - inner_lo.0]);
                }
            }
            // The starts again where the distances changed, and a step and a block beyond
            // (where a front begins is judged a step back along it, by the distances' slope).
            let (lo, hi) = window(&cut, changed + step + block);
            // (The window's rows first: most starts lie outside them.)
            let inside = |n: usize| (lo.1 * bx..hi.1 * bx).contains(&n) && (lo.0..hi.0).contains(&(n % bx));
            starts.retain(|&(n, _, _)| !inside(n));
            for j in lo.1..hi.1 {
                starts.extend((lo.0..hi.0).filter_map(|i| start_at(map, &near, i, j)));
            }
        }
        out.engagement.extend(engaged);
        at = *points.last().expect("a pass starts at a point");
        out.passes.push(Pass { entry, points });
    }
    out
}

/// One pass from `start` headed along `heading`: the points, each step's engagement, and the
/// pixels it cut. Its steps are `step` long where the heading is searched, and up to
/// `a.longest` along a run the last step's curvature holds.
fn pass(map: &mut PixelMap, a: &Adaptive, start: DVec2, heading: DVec2, step: f64, steps: &mut usize, budget: usize) -> (Vec<DVec2>, Vec<(f64, f64)>, usize) {
    let side = if a.climb { 1.0 } else { -1.0 };
    let longest = a.longest.max(step);
    let mut points = vec![start];
    let mut engaged = Vec::new();
    // The last step's turn and length, the length of the step before it, and the next step's.
    let (mut p, mut h, mut last, mut last_len, mut before_len, mut len) = (start, heading, 0.5, step, step, step);
    let (mut idle, mut removed_all) = (0.0, 0);
    // The points up to the last step that cut.
    let mut cutting = 1;
    // A heading `u` from 0 (a quarter turn towards the material) to 1 (a quarter turn away).
    let dir = |h: DVec2, u: f64| rotate(h, side * (u - 0.5) * PI);
    // (Sampled four times per shortest step.)
    let fits = |map: &PixelMap, p: DVec2, q: DVec2| {
        let n = 4 * shortest_steps(p.distance(q), step);
        (1..=n).all(|k| map.allowed(p.lerp(q, k as f64 / n as f64)))
    };
    while *steps < budget {
        let e = |map: &PixelMap, u: f64, len: f64| {
            let d = dir(h, u);
            engagement(map, p + d * len, d, a.radius)
        };
        // [`IDLE`] tool radii of steps that cut nothing end the pass.
        if idle + step > IDLE * a.radius {
            break;
        }
        // The last step's curvature again where it holds the engagement within [`KEEP`] of the
        // target (a spiral runs on at one curvature: long arcs), the step twice as long as the
        // last up to the longest; where it does not hold, a longer step than the shortest is
        // tried again at the shortest, and the shortest searched by bisection for the heading
        // whose engagement is nearest the target (each heading's engagement kept with it).
        // (Between chords of one circle, the turn is as their lengths' sum: the last turn, from
        // the step before it to the last, scaled to the last step and this one.)
        let along = if len == last_len && last_len == before_len { last } else { (0.5 + (last - 0.5) * (last_len + len) / (before_len + last_len)).clamp(0.0, 1.0) };
        let same = e(map, along, len);
        let held = (same - a.target).abs() <= KEEP * a.target;
        if !held && len > step {
            len = step;
            continue;
        }
        let (mut u, mut angle) = if held {
            (along, same)
        } else {
            let e = |map: &PixelMap, u: f64| e(map, u, step);
            let hard = e(map, 0.0);
            if hard <= a.target {
                // Too light even turning hard: towards the material, no further (turning past
                // it would turn the pass round on the spot).
                let u = material_direction(map, p, a.radius + step).map_or(0.5, |g| (0.5 + side * h.angle_to(g) / PI).clamp(0.0, 0.5));
                (u, if u == 0.0 { hard } else { e(map, u) })
            } else {
                // (A quarter turn away is measured only if the search never leaves it.)
                let (mut lo, mut hi) = ((0.0, hard), (1.0, f64::NAN));
                for _ in 0..SEARCH {
                    let mid = 0.5 * (lo.0 + hi.0);
                    let at_mid = (mid, e(map, mid));
                    if at_mid.1 > a.target {
                        lo = at_mid;
                    } else {
                        hi = at_mid;
                    }
                }
                if hi.1.is_nan() {
                    hi.1 = e(map, 1.0);
                }
                if (lo.1 - a.target).abs() < (hi.1 - a.target).abs() {
                    lo
                } else {
                    hi
                }
            }
        };
        // Away from the material until the step stays in the region (a longer step than the
        // shortest is taken at the shortest instead).
        if len > step && !fits(map, p, p + dir(h, u) * len) {
            len = step;
            continue;
        }
        let searched = u;
        while u <= 1.0 && !fits(map, p, p + dir(h, u) * len) {
            u += 1.0 / 32.0;
        }
        if u > 1.0 {
            break;
        }
        let d = dir(h, u);
        let q = p + d * len;
        if u != searched {
            angle = engagement(map, q, d, a.radius);
        }
        // A front that would overload whichever way ends the pass (the next starts elsewhere).
        if angle > MOST_OVER * a.target {
            break;
        }
        let removed = map.cut(p, q);
        removed_all += removed;
        *steps += 1;
        engaged.push((len, angle));
        points.push(q);
        if removed > 0 {
            (idle, cutting) = (0.0, points.len());
        } else {
            idle += len;
        }
        (p, h, last, before_len, last_len) = (q, d, u, last_len, len);
        // Along a run that holds, the next step twice as long, up to the longest.
        len = if held { (2.0 * len).min(longest) } else { step };
    }
    // The steps after the last that cut are not made.
    points.truncate(cutting);
    engaged.truncate(cutting - 1);
    (points, engaged, removed_all)
}

/// The engagement angle of a tool of radius `r` at `q` moving along `d`: the front half of its
/// circle in material, measured at [`SAMPLES`] points.
pub fn engagement(map: &PixelMap, q: DVec2, d: DVec2, r: f64) -> f64 {
    let n = front_half().iter().filter(|&&u| map.material_near(q + d.rotate(u) * r)).count();
    PI * n as f64 / SAMPLES as f64
}

/// The [`SAMPLES`] directions of the front half of the tool's circle at which the engagement
/// is measured, about a heading along +x (rotate them by the heading).
pub fn front_half() -> &'static [DVec2] {
    static FRONT: std::sync::OnceLock<Vec<DVec2>> = std::sync::OnceLock::new();
    FRONT.get_or_init(|| (0..SAMPLES).map(|k| DVec2::from_angle(-FRAC_PI_2 + PI * (k as f64 + 0.5) / SAMPLES as f64)).collect())
}

/// The mean direction from `c` of the material on the circle of radius `reach` about it.
fn material_direction(map: &PixelMap, c: DVec2, reach: f64) -> Option<DVec2> {
    let mut sum = DVec2::ZERO;
    for k in 0..64 {
        let d = DVec2::from_angle(k as f64 * PI / 32.0);
        if map.material_near(c + d * reach) {
            sum += d;
        }
    }
    (sum.length() > 1e-9).then(|| sum.normalize())
}

/// Whether the straight way from `a` to `b` keeps the tool's centre in the map's region
/// (sampled every pixel).
fn way_inside(map: &PixelMap, a: DVec2, b: DVec2, px: f64) -> bool {
    let n = ((a.distance(b) / px).ceil() as usize).max(1);
    (0..=n).all(|k| map.allowed(a.lerp(b, k as f64 / n as f64)))
}

/// How many shortest steps of `step` (mm) a step `length` long spans (at least one; a step of
/// the shortest length, one).
pub(crate) fn shortest_steps(length: f64, step: f64) -> usize {
    (length / step - 1e-9).ceil().max(1.0) as usize
}

fn rotate(v: DVec2, angle: f64) -> DVec2 {
    DVec2::from_angle(angle).rotate(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::{Loop, Shape};

    /// A level shallower than the load's depth cuts wider by the same cross-section, up to half
    /// the radius; as deep, deeper or already wide, the load itself.
    #[test]
    fn a_shallow_level_cuts_wider_by_the_same_cross_section() {
        let (ae, r) = (1.5, 5.0);
        assert_eq!(Adaptive::shallow_step(ae, 10.0, 10.0, r), ae);
        assert_eq!(Adaptive::shallow_step(ae, 10.0, 12.0, r), ae);
        assert!((Adaptive::shallow_step(ae, 10.0, 8.0, r) - 1.875).abs() < 1e-12);
        assert_eq!(Adaptive::shallow_step(ae, 10.0, 2.0, r), 2.5);
        assert_eq!(Adaptive::shallow_step(3.0, 10.0, 2.0, r), 3.0);
        assert_eq!(Adaptive::shallow_step(ae, 10.0, 0.0, r), ae);
    }

    /// A square pocket: a helix in the middle, one pass spiralling out at the target (the
    /// engagement within 10 % of it over 95 % of the pass), then passes into the corners; next
    /// to nothing left.
    #[test]
    fn a_square_pocket_spirals_out_at_the_target() {
        let r = 3.0;
        let region = Shape { loops: vec![Loop::rect(DVec2::new(-12.0, -12.0), DVec2::new(12.0, 12.0))] };
        let reach = |p: DVec2| (p.abs() - DVec2::splat(12.0)).max(DVec2::ZERO).length() <= r - 3.0 * 0.075;
        let mut map = PixelMap::new(crate::geom::segment::Rect { min: DVec2::splat(-12.0), max: DVec2::splat(12.0) }, 0.075, r, reach, &region);
        let before = map.left();
        let a = Adaptive { radius: r, target: Adaptive::angle_of(0.6, r), climb: true, helix_r: 2.4, step: 0.3, longest: 0.3 };
        let plan = plan(&mut map, &a, DVec2::ZERO);
        assert!(matches!(plan.passes[0].entry, Entry::Helix { .. }));
        let spiral = &plan.engagement[..plan.passes[0].points.len() - 1];
        let held = spiral.iter().filter(|e| (e.1 - a.target).abs() <= 0.1 * a.target).count();
        assert!(held as f64 >= 0.95 * spiral.len() as f64, "{held} of {} steps within 10 %", spiral.len());
        assert!((map.left() as f64) < 0.001 * before as f64, "{} of {before} pixels left", map.left());
    }

    /// A pocket with a round island and a narrow neck: every pass (but a helix's) cuts, and its
    /// last step cuts (no pass, nor a pass's tail, runs in air), replayed on the map as it was.
    #[test]
    fn every_pass_ends_on_a_step_that_cuts() {
        let r = 3.0;
        let v = DVec2::new;
        let outer = Loop::polygon(&[v(-20.0, -12.0), v(20.0, -12.0), v(20.0, -1.0), v(32.0, -1.0), v(32.0, 1.0), v(20.0, 1.0), v(20.0, 12.0), v(-20.0, 12.0)]);
        let region = Shape::new(vec![outer, Loop::circle(v(-8.0, 0.0), 5.0)]);
        let bounds = region.bounds();
        // The material: within the tool's reach (less a few pixels) of the region.
        let reach = |p: DVec2| region.contains(p) || region.distance_to(p) <= r - 3.0 * 0.075;
        let mut map = PixelMap::new(bounds, 0.075, r, reach, &region);
        let fresh = map.clone();
        let a = Adaptive { radius: r, target: Adaptive::angle_of(0.6, r), climb: true, helix_r: 2.4, step: 0.3, longest: 0.3 };
        let plan = plan(&mut map, &a, DVec2::ZERO);
        assert!(plan.passes.len() > 3, "{} passes", plan.passes.len());
        let mut replay = fresh;
        for (k, pass) in plan.passes.iter().enumerate() {
            let mut cut = 0;
            if let Entry::Helix { centre, radius } = pass.entry {
                for t in 0..72 {
                    let at = |t: usize| centre + radius * DVec2::from_angle(t as f64 * 2.0 * PI / 72.0);
                    cut += replay.cut(at(t), at(t + 1));
                }
            }
            let steps: Vec<usize> = pass.points.windows(2).map(|w| replay.cut(w[0], w[1])).collect();
            assert!(cut + steps.iter().sum::<usize>() > 0, "pass {k} cuts nothing");
            assert!(steps.last().is_none_or(|&n| n > 0), "pass {k} ends on {} steps in air", steps.iter().rev().take_while(|&&n| n == 0).count());
        }
    }

    /// A straight cut along a wall settles at the step-over's engagement.
    #[test]
    fn along_a_wall_the_engagement_settles_at_the_target() {
        let r = 3.0;
        let region = Shape { loops: vec![Loop::rect(DVec2::new(-20.0, -20.0), DVec2::new(20.0, 20.0))] };
        let mut map = PixelMap::new(crate::geom::segment::Rect { min: DVec2::splat(-20.0), max: DVec2::splat(20.0) }, 0.075, r, |p| p.x >= 0.0, &region);
        let a = Adaptive { radius: r, target: Adaptive::angle_of(0.6, r), climb: true, helix_r: 1.0, step: 0.3, longest: 0.3 };
        let mut steps = 0;
        let (points, engaged, _) = pass(&mut map, &a, DVec2::new(-r - 0.1, -15.0), DVec2::new(0.0, 1.0), 0.3, &mut steps, 100);
        assert!(points.iter().skip(50).all(|p| (p.x + r - 0.6).abs() < 0.05), "the pass settles 0.6 into the wall");
        let late = &engaged[engaged.len() / 2..];
        assert!(late.iter().all(|e| (e.1 - a.target).abs() < 0.1 * a.target), "{late:?}");
    }

    /// Along a wall, where the curvature holds the engagement, the steps grow to the longest
    /// (a fixed step's pass takes more points for the same run) and the engagement still
    /// settles at the target; where it stops holding, a step is the shortest again.
    #[test]
    fn along_a_wall_the_steps_grow_to_the_longest() {
        let r = 3.0;
        let region = Shape { loops: vec![Loop::rect(DVec2::new(-20.0, -20.0), DVec2::new(20.0, 20.0))] };
        let fresh = PixelMap::new(crate::geom::segment::Rect { min: DVec2::splat(-20.0), max: DVec2::splat(20.0) }, 0.075, r, |p| p.x >= 0.0, &region);
        let run = |longest: f64| {
            let a = Adaptive { radius: r, target: Adaptive::angle_of(0.6, r), climb: true, helix_r: 1.0, step: 0.3, longest };
            let mut steps = 0;
            let (points, engaged, _) = pass(&mut fresh.clone(), &a, DVec2::new(-r - 0.1, -15.0), DVec2::new(0.0, 1.0), 0.3, &mut steps, 1000);
            (a, points, engaged)
        };
        let (_, fixed, _) = run(0.3);
        let (a, points, engaged) = run(1.2);
        let late = &engaged[engaged.len() / 2..];
        assert!(late.iter().all(|e| (e.1 - a.target).abs() < 0.1 * a.target), "{late:?}");
        assert!(engaged.iter().all(|e| e.0 >= 0.3 - 1e-12 && e.0 <= 1.2 + 1e-12));
        // (The engagement is read in whole samples of the circle, a fortieth of the target
        // here: a step whose heading drifts by one is taken at the shortest again.)
        let long = engaged.iter().filter(|e| e.0 > 0.3).map(|e| e.0).sum::<f64>();
        let all = engaged.iter().map(|e| e.0).sum::<f64>();
        assert!(long > 0.5 * all, "{long} of {all} mm in longer steps than the shortest");
        assert!(engaged.iter().any(|e| e.0 == 1.2), "steps at the longest");
        assert!(engaged.iter().any(|e| e.0 == 0.3), "the pass starts at the shortest step");
        // The same run along the wall (to the box's far side) in fewer points.
        let (last, last_fixed) = (points.last().unwrap().y, fixed.last().unwrap().y);
        assert!(last > 15.0 && last_fixed > 15.0, "{last} {last_fixed}");
        assert!(points.len() * 3 < fixed.len() * 2, "{} points against {}", points.len(), fixed.len());
    }

    /// The step range: unset, a tenth of the radius; one end set alone carries the other with
    /// it; at most half the radius; a longest shorter than the shortest refused by its name.
    #[test]
    fn the_step_range_defaults_and_bounds() {
        let r = 2.0;
        let range = |min: Option<f64>, max: Option<f64>| StepRange { min, max };
        assert_eq!(range(None, None).fractions(r), (STEP, STEP));
        assert_eq!(range(None, Some(0.6)).fractions(r), (STEP, 0.3));
        assert_eq!(range(None, Some(0.1)).fractions(r), (0.05, 0.05));
        assert_eq!(range(Some(0.4), None).fractions(r), (0.2, 0.2));
        assert_eq!(range(Some(0.1), None).fractions(r), (0.05, STEP));
        assert_eq!(range(Some(0.4), Some(30.0)).fractions(r), (0.2, MOST_STEP));
        assert_eq!(range(Some(0.6), Some(0.9)).validate(), Ok(()));
        assert_eq!(range(Some(0.9), Some(0.6)).validate().unwrap_err().field, "maxStep");
        assert_eq!(range(Some(0.0), None).validate().unwrap_err().field, "minStep");
    }
}
