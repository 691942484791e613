//! Linking cutting runs into one path (DESIGN.md idea 6), one pass over the runs with a
//! pluggable test of what a link must stay clear of ([`Keepout`]: the CL surface within a
//! region, ...). Between two runs the tool stays down and feeds straight across when that move
//! is short and the test accepts it; otherwise it retracts to a small gap above the highest
//! material the cutter would meet on the way across (the in-process stock; the clearance height
//! at most), moves over at rapid, drops at rapid to a small gap above the material that is
//! really there (the in-process stock under the cutter at that spot, never into it), and enters the material
//! ([`super::entry`]): a helix or a ramp, never a straight plunge into material.

use serde::{Deserialize, Serialize};

use super::entry::{enter_3d, Entry, Keepout, Kind};
use super::Move;
use crate::geom::{tolerance::BOUND_SLACK, DVec2, DVec3, Tolerances};
use crate::zmap::bounds::NodeBounds;
use crate::zmap::region::Region;
use crate::zmap::surface::{point_at, ClSurface};

/// How runs are joined.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct LinkSettings {
    /// Height of rapid moves between runs (mm, absolute). Set by the job from the stock top.
    pub clearance_z: f64,
    /// Height above the material at which a rapid descent stops and the feed begins (mm).
    /// Default value: 1.
    pub rapid_gap: f64,
    /// Longest link that may stay down (mm). Default value: 4.
    pub stay_down_max: f64,
    /// Retracts travel at the clearance height, not just above the material on the way.
    /// Default value: false.
    pub full_retract: bool,
}

impl Default for LinkSettings {
    fn default() -> Self {
        LinkSettings { clearance_z: 5.0, rapid_gap: 1.0, stay_down_max: 4.0, full_retract: false }
    }
}

/// The surface a path must stay on or above: a CL z-map lifted by the allowance, within a region.
pub struct Floor<'a> {
    pub cl: &'a ClSurface,
    pub allowance: f64,
    pub region: &'a Region,
    /// The heights of the cutter widened by the grid's spacing at the z-map's nodes
    /// ([`crate::zmap::drop::PointDrop::widened`]), where the strategy has them: each bounds
    /// the surface from above within a spacing of its node, so a move clear of the highest of
    /// them around it needs no exact drops ([`Floor::clears_by_bounds`]).
    pub bounds: Option<&'a NodeBounds>,
}

impl Floor<'_> {
    /// Whether the straight move from `a` to `b` surely clears the floor within the region by
    /// the widened heights alone: every point of the move lies within a spacing of a node of
    /// the cells around it, so the highest widened height at those nodes (each a bound from
    /// above of the surface within a spacing of it) bounds the surface all along; and those
    /// nodes all in the region, or the region a rectangle holding both ends. `false` says only
    /// that the bounds do not decide.
    pub fn clears_by_bounds(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
        let Some(wide) = self.bounds else { return false };
        let f = &self.cl.field;
        if wide.size() != (f.nx, f.ny) {
            return false;
        }
        let (lo, hi) = (a.truncate().min(b.truncate()), a.truncate().max(b.truncate()));
        let (u0, u1) = ((lo - f.origin) / f.spacing, (hi - f.origin) / f.spacing);
        // The nodes of every cell the move's box meets.
        let (i0, j0, i1, j1) = (u0.x.floor(), u0.y.floor(), u1.x.floor() + 1.0, u1.y.floor() + 1.0);
        if !(i0 >= 0.0 && j0 >= 0.0 && i1 < f.nx as f64 && j1 < f.ny as f64) || (i1 - i0 + 1.0) * (j1 - j0 + 1.0) > MOST_BOUND_NODES {
            return false;
        }
        let (i0, j0, i1, j1) = (i0 as usize, j0 as usize, i1 as usize, j1 as usize);
        let lowest = a.z.min(b.z) + tolerance - self.allowance - BOUND_SLACK;
        let in_region = match self.region {
            Region::Rect { .. } => self.region.contains(a.truncate()) && self.region.contains(b.truncate()),
            Region::Mask(m) if m.grid() == f.grid() => (j0..=j1).all(|j| (i0..=i1).all(|i| m.at(i, j) >= 0.5)),
            Region::Mask(_) => false,
        };
        in_region && (j0..=j1).all(|j| wide.row(j)[i0..=i1].iter().all(|&h| h <= lowest))
    }

    /// The points of the surface along the straight move from `a` to `b` ([`ClSurface::along`])
    /// when the move stays on or above the floor at every one (within `tolerance`), in the
    /// region or not; `None` from the first point it passes below.
    fn under(&self, a: DVec3, b: DVec3, tolerance: f64) -> Option<Vec<(f64, f64)>> {
        let above = |t: f64, z: f64| point_at(a, b, t).z + tolerance >= z + self.allowance;
        let along = self.cl.along_while(a.truncate(), b.truncate(), above);
        along.iter().all(|&(t, z)| above(t, z)).then_some(along)
    }
}

/// The most nodes [`Floor::clears_by_bounds`] looks at: a longer move's box holds more of the
/// surface than its way does, and the exact test is the better use of the time.
const MOST_BOUND_NODES: f64 = 400.0;

impl Keepout for Floor<'_> {
    /// Whether the straight move from `a` to `b` stays inside the region and on or above the
    /// floor (within `tolerance`): by the widened heights around it where they decide
    /// ([`Floor::clears_by_bounds`]), else checked at every point of the surface along it
    /// ([`ClSurface::along`]): a line at or above those points is at or above the polyline
    /// through them.
    fn clears(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
        if self.clears_by_bounds(a, b, tolerance) {
            return true;
        }
        // Above every point of the surface along it, each in the region: its ends (points of
        // it too) before any drop.
        if !(self.region.contains(a.truncate()) && self.region.contains(b.truncate())) {
            return false;
        }
        self.under(a, b, tolerance).is_some_and(|along| along.iter().all(|&(t, _)| self.region.contains(point_at(a, b, t).truncate())))
    }

    /// The surface alone (a lead-in from beside the stock may cross the region's edge).
    fn clears_part(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
        self.under(a, b, tolerance).is_some()
    }

    /// In the region, and on or above the surface there by one exact drop.
    fn admits(&self, p: DVec3, tolerance: f64) -> bool {
        self.region.contains(p.truncate()) && p.z + tolerance >= self.cl.height(p.truncate()) + self.allowance
    }
}

/// Feeds (mm/min) used by the linked path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feeds {
    pub cut: f64,
    pub plunge: f64,
}

/// What the linker needs besides the runs.
pub struct Linker<'a> {
    pub settings: LinkSettings,
    /// What a stay-down link and an entry must stay clear of.
    pub keep: &'a dyn Keepout,
    /// The highest tip height at which the cutter touches material at a point (the in-process
    /// stock; `-inf` where there is none).
    pub material: &'a dyn Fn(DVec2) -> f64,
    /// Whether `material` at a point stands above a height (the same answer, found sooner).
    pub material_above: &'a dyn Fn(DVec2, f64) -> bool,
    /// The highest tip height at which the cutter touches the material anywhere along the
    /// straight way between two points (the in-process stock as the operation found it, which
    /// holds all the material there is): a retract travels just above it.
    pub material_along: &'a dyn Fn(DVec2, DVec2) -> f64,
    /// The same, estimated as the stock model samples the material (not bounded from above):
    /// a start where it stands no more than `threshold` above the path is entered in the air.
    pub estimate: &'a dyn Fn(DVec2) -> f64,
    pub threshold: f64,
    pub entry: Entry,
    /// The cutter's radius (for the helix's size).
    pub radius: f64,
    pub feeds: Feeds,
    /// Where given (finishing), the highest material under the cutter's core (a flat of half
    /// its radius) along a straight way: a run is entered level from the air beside its start
    /// wherever that way is shorter than the helix or ramp down through the material and its
    /// core meets no more than the pass's own at its start (a waterline at the foot of a wall
    /// need not ramp down from the wall's top); from outside the operation's area only where
    /// the core meets nothing more than [`CORE_DEPTH`] radii above the start (the cutter's
    /// side meets the material, never a slot through stock the area leaves alone). Else, and
    /// without it, only where neither a helix nor a ramp fits.
    pub side_first: Option<&'a dyn Fn(DVec2, DVec2) -> f64>,
}

/// Entries of each kind a linked path made.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Entries {
    pub air: usize,
    pub helix: usize,
    pub ramp: usize,
    pub plunge: usize,
    /// Where each plunge went in (its run's first point).
    pub plunges: Vec<DVec3>,
    /// In level from the air beside the start, where a plunge would have been.
    pub side: usize,
}

impl Entries {
    fn count(&mut self, kind: Kind, at: DVec3) {
        match kind {
            Kind::Air => self.air += 1,
            Kind::Helix => self.helix += 1,
            Kind::Ramp => self.ramp += 1,
            Kind::Plunge => {
                self.plunge += 1;
                self.plunges.push(at);
            }
            Kind::Side => self.side += 1,
        }
    }
}

impl Linker<'_> {
    /// Joins `runs` into moves; returns where the path starts (above its first point, at the
    /// clearance height), the moves, ending at the clearance height, and how it entered.
    pub fn link(&self, runs: &[Vec<DVec3>], tolerances: &Tolerances) -> (DVec3, Vec<Move>, Entries) {
        self.link_fed(runs, None, None, tolerances)
    }

    /// [`Linker::link`] with a feed for each move along a run (`feeds[i][k]`: the move to
    /// `runs[i][k + 1]`) where given, the cutting feed elsewhere; and, where given, whether each
    /// run starts in material (`inside[i]`: the strategy may know better than the stock model,
    /// having cut the level itself), else as `estimate` says.
    pub fn link_fed(&self, runs: &[Vec<DVec3>], feeds: Option<&[Vec<f64>]>, inside: Option<&[bool]>, tolerances: &Tolerances) -> (DVec3, Vec<Move>, Entries) {
        let settings = &self.settings;
        let clearance = settings.clearance_z;
        let first = runs.iter().find_map(|r| r.first()).copied().unwrap_or(DVec3::new(0.0, 0.0, clearance));
        let start = first.truncate().extend(clearance);
        let mut moves = Vec::new();
        let mut entries = Entries::default();
        let mut at = start;
        let mut down = false;
        for (i, run) in runs.iter().enumerate().filter(|(_, r)| !r.is_empty()) {
            let p0 = run[0];
            let stay = down && at.distance(p0) <= settings.stay_down_max && self.keep.clears(at, p0, tolerances.height);
            // Staying down to a start lower than here, in material: across at this height,
            // then in by the entry (a link between levels ramps down, never drops straight).
            let across = at.truncate().extend(at.z.max(p0.z));
            let descends = stay && p0.z < at.z - tolerances.height && (self.estimate)(p0.truncate()) > p0.z + self.threshold;
            if descends && self.keep.clears(at, p0.truncate().extend(across.z), tolerances.height) {
                if p0.truncate() != at.truncate() {
                    moves.push(Move::Line { to: p0.truncate().extend(across.z), feed: self.feeds.cut });
                }
                let material = (self.material)(p0.truncate()).max(p0.z + self.threshold);
                let (entry, kind) = enter_3d(across.z, material, run, self.radius, &self.entry, self.keep, (self.feeds.plunge, self.feeds.cut), tolerances.height);
                entries.count(kind, p0);
                moves.extend(entry);
            } else if stay {
                moves.push(Move::Line { to: p0, feed: self.feeds.cut });
            } else {
                let material = (self.material)(p0.truncate());
                let top = (p0.z.max(material) + settings.rapid_gap).min(clearance);
                // Across at the rapid gap above the material on the way (the full clearance
                // only where that is as high): a short retract.
                let travel = |to: DVec2, stop: f64| if settings.full_retract { clearance } else { ((self.material_along)(at.truncate(), to) + settings.rapid_gap).max(stop).min(clearance) };
                let inside = inside.and_then(|f| f.get(i).copied()).unwrap_or_else(|| (self.estimate)(p0.truncate()) > p0.z + self.threshold);
                let (entry, kind) = enter_3d(top, if inside { material } else { f64::NEG_INFINITY }, run, self.radius, &self.entry, self.keep, (self.feeds.plunge, self.feeds.cut), tolerances.height);
                let side = match kind {
                    Kind::Plunge => self.beside(p0, tolerances.height, f64::INFINITY, |_| true),
                    Kind::Helix | Kind::Ramp => self.side_first.and_then(|core| {
                        // Shorter; its core meeting no more than the pass's at its start, and
                        // from outside the operation's area only beside the material.
                        let way = super::moves_length(p0.truncate().extend(top), &entry) - settings.rapid_gap;
                        let (h, shallow) = (tolerances.height, p0.z + CORE_DEPTH * self.radius);
                        let start = core(p0.truncate(), p0.truncate()).max(shallow);
                        self.beside(p0, h, way, |q| {
                            let meets = core(q, p0.truncate());
                            meets <= start && (meets <= shallow || self.keep.clears(q.extend(p0.z), p0, h))
                        })
                    }),
                    _ => None,
                };
                match side {
                    Some(q) => {
                        // Down in the air beside the start, then in level.
                        let stop = (p0.z + settings.rapid_gap).min(clearance);
                        retract(at, q, travel(q, stop), stop, &mut moves);
                        moves.push(Move::Line { to: q.extend(p0.z), feed: self.feeds.plunge });
                        moves.push(Move::Line { to: p0, feed: self.feeds.cut });
                        entries.count(Kind::Side, p0);
                    }
                    None => {
                        retract(at, p0.truncate(), travel(p0.truncate(), top), top, &mut moves);
                        entries.count(kind, p0);
                        moves.extend(entry);
                    }
                }
            }
            let fed = feeds.and_then(|f| f.get(i));
            moves.extend(run[1..].iter().enumerate().map(|(k, &p)| Move::Line { to: p, feed: fed.and_then(|f| f.get(k)).copied().unwrap_or(self.feeds.cut) }));
            at = *run.last().unwrap();
            down = true;
        }
        if down {
            moves.push(Move::Rapid { to: at.truncate().extend(clearance) });
        }
        (start, moves, entries)
    }
}

/// How high above a start the material under a lead-in's core may stand, in cutter radii
/// ([`Linker::side_first`]).
pub const CORE_DEPTH: f64 = 0.5;

/// Rings of places beside a start tried for a lead-in from the air, a half radius apart, and
/// directions tried on each.
const SIDE_RINGS: usize = 6;
const SIDE_DIRECTIONS: usize = 16;

impl Linker<'_> {
    /// Where the cutter may go down in the air beside `p0` and feed in level to it, instead of
    /// plunging there: the nearest place (within three radii) where it touches no material
    /// down to `p0`'s height and from which the level way in stays clear of the part. Where the
    /// material ends within reach, as at the stock's edge, a run is entered from the side.
    /// Only places nearer `p0` than `within` are tried (and asked of first: the material and
    /// the part are looked up over the cutter's whole disc).
    fn beside(&self, p0: DVec3, tolerance: f64, within: f64, also: impl Fn(DVec2) -> bool) -> Option<DVec2> {
        (1..=SIDE_RINGS).find_map(|ring| {
            let distance = 0.5 * self.radius * ring as f64;
            (0..SIDE_DIRECTIONS).find_map(|k| {
                let q = p0.truncate() + DVec2::from_angle(std::f64::consts::TAU * k as f64 / SIDE_DIRECTIONS as f64) * distance;
                (q.distance(p0.truncate()) < within && !(self.material_above)(q, p0.z + tolerance) && also(q) && self.keep.clears_part(q.extend(p0.z), p0, tolerance)).then_some(q)
            })
        })
    }
}

/// The retract between two cuts, as every strategy makes it (the 3D linker, the 2.5D cursor):
/// from `at` straight up to the `travel` height (when below it), across at rapid to above
/// `to` (level, at `at`'s height when that is higher: a control may move its axes one by one
/// on a rapid, so a rapid never slants), and down at rapid to `stop` (when below). What
/// follows (a feed down, an entry) is the caller's.
pub fn retract(at: DVec3, to: DVec2, travel: f64, stop: f64, out: &mut Vec<Move>) {
    if at.z < travel {
        out.push(Move::Rapid { to: at.truncate().extend(travel) });
    }
    let across = at.z.max(travel);
    if at.truncate() != to {
        out.push(Move::Rapid { to: to.extend(across) });
    }
    if stop < across {
        out.push(Move::Rapid { to: to.extend(stop) });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A region that refuses every helix, over a part no higher than `floor`.
    struct Walled {
        floor: f64,
    }
    impl Keepout for Walled {
        fn clears(&self, _: DVec3, _: DVec3, _: f64) -> bool {
            false
        }
        fn clears_part(&self, a: DVec3, b: DVec3, _: f64) -> bool {
            a.z >= self.floor && b.z >= self.floor
        }
    }

    /// A square stock of half-side `half` standing up to z = 0, for a cutter of radius 3: the
    /// highest tip height at which the cutter at `p` touches it.
    fn square(half: f64) -> impl Fn(DVec2) -> f64 {
        move |p: DVec2| {
            let outside = (p.abs() - DVec2::splat(half)).max(DVec2::ZERO).length();
            if outside < 3.0 {
                0.0
            } else {
                f64::NEG_INFINITY
            }
        }
    }

    fn linked(half: f64, run: &[DVec3]) -> (Vec<Move>, Entries) {
        let material = square(half);
        let along = |a: DVec2, b: DVec2| (0..=20).map(|k| material(a.lerp(b, k as f64 / 20.0))).fold(f64::NEG_INFINITY, f64::max);
        link_one(&Walled { floor: -5.0 }, &material, &along, None, run)
    }

    /// `run` linked alone by a linker of a φ6 cutter, clearance 5, over `material`.
    fn link_one(keep: &dyn Keepout, material: &dyn Fn(DVec2) -> f64, along: &dyn Fn(DVec2, DVec2) -> f64, side_first: Option<&dyn Fn(DVec2, DVec2) -> f64>, run: &[DVec3]) -> (Vec<Move>, Entries) {
        let linker = Linker {
            settings: LinkSettings { clearance_z: 5.0, ..LinkSettings::default() },
            keep,
            material,
            material_above: &|p, h| material(p) > h,
            material_along: along,
            estimate: material,
            threshold: 0.01,
            entry: Entry::default(),
            radius: 3.0,
            feeds: Feeds { cut: 1000.0, plunge: 300.0 },
            side_first,
        };
        let (_, moves, entries) = linker.link(&[run.to_vec()], &Tolerances::default());
        (moves, entries)
    }

    #[test]
    fn a_short_run_at_the_stocks_edge_is_entered_from_the_air_beside_it() {
        // 2 mm deep, 0.25 mm long, 1 mm inside the edge: no helix, no ramp.
        let run = [DVec3::new(9.0, 0.0, -2.0), DVec3::new(8.75, 0.0, -2.0)];
        let (moves, entries) = linked(10.0, &run);
        assert_eq!((entries.side, entries.plunge), (1, 0), "{moves:?}");
        let material = square(10.0);
        let mut at = DVec3::new(9.0, 0.0, 5.0);
        let mut descents = 0;
        for mv in &moves {
            let to = mv.to();
            if to.z < at.z - 1e-12 {
                // Every descent is in the air: the cutter touches nothing above where it ends.
                assert!(material(to.truncate()) <= to.z + 1e-9, "{at} -> {to}");
                descents += 1;
            }
            at = to;
        }
        assert!(descents >= 1);
        // In level to the run's start, at its height.
        let k = moves.iter().position(|m| m.to() == run[0]).expect("the run's start");
        assert_eq!(moves[k - 1].to().z, run[0].z);
        assert!(matches!(moves[k], Move::Line { feed, .. } if feed == 1000.0));
    }

    /// Clear of everything above a floor.
    struct Open;
    impl Keepout for Open {
        fn clears(&self, a: DVec3, b: DVec3, _: f64) -> bool {
            a.z >= -9.0 && b.z >= -9.0
        }
        fn clears_part(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
            self.clears(a, b, tolerance)
        }
    }

    /// A pass at the foot of a wall standing to z = 0 beside x < −2 (the cutter of radius 3
    /// touches it wherever its centre is left of x = 1), over a floor at −8.
    /// `core`: what the cutter's core meets on the way in (−8 at the start itself).
    fn at_a_walls_foot(side_first: bool, core: f64) -> (Vec<Move>, Entries) {
        let material = |p: DVec2| -> f64 {
            if p.x < 1.0 {
                0.0
            } else {
                -8.0
            }
        };
        let core = move |a: DVec2, b: DVec2| if a == b { -8.0 } else { core };
        let along = |a: DVec2, b: DVec2| material(a).max(material(b));
        let run = [DVec3::new(0.0, 0.0, -6.0), DVec3::new(0.0, 10.0, -6.0)];
        link_one(&Open, &material, &along, side_first.then_some(&core as &dyn Fn(DVec2, DVec2) -> f64), &run)
    }

    #[test]
    fn a_finishing_pass_at_a_walls_foot_is_led_in_from_the_air_not_helixed_from_the_top() {
        let (moves, entries) = at_a_walls_foot(true, -8.0);
        assert_eq!((entries.side, entries.helix, entries.ramp), (1, 0, 0), "{moves:?}");
        // Fed 6 mm down in the air (x ≥ 1), then level in: a few mm, against a 3° helix's
        // 6 / tan 3° = 115 mm.
        let (mut at, mut fed) = (DVec3::new(0.0, 0.0, 5.0), 0.0);
        for mv in &moves[..=moves.iter().position(|m| m.to() == DVec3::new(0.0, 0.0, -6.0)).unwrap()] {
            fed += if mv.feed().is_some() { mv.length(at) } else { 0.0 };
            if mv.to().z < at.z - 1e-12 {
                assert!(mv.to().x >= 1.0, "a descent where the wall is: {at} -> {}", mv.to());
            }
            at = mv.to();
        }
        assert!(fed < 10.0, "{fed}");
        // Roughing keeps its helix; so does a finish whose lead-in would slot through more
        // than the pass meets at its start (its core meeting material 3 mm over the start).
        for (side_first, core) in [(false, -8.0), (true, -3.0)] {
            let (_, entries) = at_a_walls_foot(side_first, core);
            assert_eq!((entries.side, entries.helix), (0, 1));
        }
    }

    #[test]
    fn far_from_any_edge_it_still_plunges_and_says_so() {
        let run = [DVec3::new(0.0, 0.0, -2.0), DVec3::new(0.25, 0.0, -2.0)];
        let (_, entries) = linked(100.0, &run);
        assert_eq!((entries.side, entries.plunge), (0, 1));
    }
}
