//! Entering material (DESIGN.md idea 6: entries are a pass over paths, not part of a strategy).
//! A cutter never feeds straight down into material: it descends on a helix about a point near
//! the start, the largest that fits between a minimum and a maximum share of the tool's
//! diameter, or where none fits, on a ramp along the path itself; where the path starts outside
//! the material it feeds down in the air. (Where neither fits, the linker tries the air beside
//! the start before it plunges: [`Kind::Side`].) The ramp angle is the parameter; a helix's pitch
//! follows from it (a turn of circumference C drops C·tan(angle)).
//!
//! 3D paths (on a CL surface) get a helix of chords, each checked against what the path must
//! stay clear of ([`Keepout`]), or a ramp that rides the path's own points: the ramp's height
//! is the higher of the sloping line and the path, so it is never below a path that is itself
//! clear of the surface.

use serde::{Deserialize, Serialize};

use super::Move;
use crate::geom::{DVec2, DVec3};

/// How a cutter enters material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Entry {
    /// Steepest descent of a helix or ramp (degrees from horizontal). Default value: 3.
    pub ramp_angle: f64,
    /// Smallest helix diameter, as a share of the tool's diameter. Default value: 0.3.
    pub helix_min: f64,
    /// Largest helix diameter, as a share of the tool's diameter. Default value: 0.9.
    pub helix_max: f64,
}

/// The smallest share of the tool's diameter a helix may be, where it is one (0 turns the
/// helix off): a helix tighter than a twentieth of the tool turns thousands of times to go down
/// a millimetre, on the spot (an entry's helix of 1e-9 once ran for minutes).
pub const LEAST_HELIX_SHARE: f64 = 0.05;

impl Entry {
    /// Checks the settings, each named as the job file names it under `entry`.
    pub fn validate(&self) -> Result<(), crate::machining::FieldError> {
        crate::machining::angle("entry.rampAngle", self.ramp_angle, 0.1, 90.0)?;
        for (field, share) in [("entry.helixMin", self.helix_min), ("entry.helixMax", self.helix_max)] {
            if !(share == 0.0 || (LEAST_HELIX_SHARE..=10.0).contains(&share)) {
                return Err(crate::machining::FieldError {
                    field,
                    message: format!("is a share of the tool's diameter: 0 (no helix) or from {LEAST_HELIX_SHARE} to 10 (got {})", crate::limits::shown(share)),
                });
            }
        }
        Ok(())
    }
}

impl Default for Entry {
    fn default() -> Self {
        Entry { ramp_angle: 3.0, helix_min: 0.3, helix_max: 0.9 }
    }
}

/// What a move must stay clear of: the CL surface and a region, the in-process stock, ...
pub trait Keepout {
    /// Whether the straight move from `a` to `b` stays clear (within `tolerance`).
    fn clears(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool;

    /// Whether it stays clear of the part alone, wherever it goes: a lead-in from the air
    /// beside the stock may cross the edge of the region the paths keep to. As
    /// [`Keepout::clears`] unless the keepout knows the two apart.
    fn clears_part(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
        self.clears(a, b, tolerance)
    }

    /// Whether the point `p` may stand on a move that clears: `false` only where no move from
    /// or to it can (so a path whose corners are not all admitted is refused before any move
    /// of it is looked at). A keepout with a quick test of its own gives it; the rest admit
    /// every point (a move from `p` to itself is no such test: a pocket's boundary, where its
    /// paths start, holds no such move but many from it).
    fn admits(&self, _p: DVec3, _tolerance: f64) -> bool {
        true
    }
}

/// Helix diameters tried, largest first.
const HELIX_SIZES: usize = 5;
/// Directions of the helix's centre from the start point tried for each size.
const HELIX_DIRECTIONS: usize = 8;
/// Legs of a ramp along a path, forth and back, before it gives up (too deep for the path).
const MAX_RAMP_LEGS: usize = 200;
/// The shortest path a ramp runs along (mm), unless it gets down in a few legs.
const MIN_RAMP_RUN: f64 = 0.5;
/// Legs a ramp may take along a run shorter than [`shortest_ramp`]: a shallow step down at the
/// start of a short run ramps over it rather than plunging.
const SHORT_RAMP_LEGS: f64 = 8.0;
/// Chords per turn of a 3D helix.
const CHORDS_PER_TURN: usize = 24;

/// The shortest path a cutter of `radius` ramps along (mm): strategies that make short runs
/// leave out runs shorter than this where they would have to enter material.
pub fn shortest_ramp(radius: f64) -> f64 {
    (0.25 * radius).max(MIN_RAMP_RUN)
}

/// How an entry went in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The path starts where the cutter touches no material: fed straight down.
    Air,
    Helix,
    /// Along the path.
    Ramp,
    /// No helix fits and the path is too short to ramp on: fed straight down (a ball's tip
    /// cuts at its centre; the strategy warns for other shapes).
    Plunge,
    /// Instead of a plunge: down in the air beside the start, then in level
    /// ([`crate::toolpath::link::Linker`]'s, where the material ends within reach).
    Side,
}

/// The moves from above `run[0]` at height `top` down to `run[0]` (`top` above it), entering
/// material that stands up to `material` at the start, for a cutter of `radius`: a helix of
/// chords that `keep` accepts, else a ramp along `run`. Feeds: `plunge` straight down, `feed`
/// on a helix or ramp.
pub fn enter_3d(top: f64, material: f64, run: &[DVec3], radius: f64, entry: &Entry, keep: &dyn Keepout, feeds: (f64, f64), tolerance: f64) -> (Vec<Move>, Kind) {
    let p0 = run[0];
    let (plunge, feed) = feeds;
    if material <= p0.z + tolerance || top <= p0.z {
        return (vec![Move::Line { to: p0, feed: plunge }], Kind::Air);
    }
    let tan = entry.ramp_angle.to_radians().tan();
    if let Some(moves) = helix_3d(top, p0, radius, entry, tan, keep, feed, tolerance) {
        return (moves, Kind::Helix);
    }
    match ramp_along(top, run, radius, tan, feed) {
        Some(moves) => (moves, Kind::Ramp),
        None => (vec![Move::Line { to: p0, feed: plunge }], Kind::Plunge),
    }
}

/// A helix of chords from (p0, top) down to p0 in whole turns about a centre beside p0, the
/// largest that `keep` accepts (its lowest corners and chords are checked first: they fail
/// most often).
#[allow(clippy::too_many_arguments)]
fn helix_3d(top: f64, p0: DVec3, radius: f64, entry: &Entry, tan: f64, keep: &dyn Keepout, feed: f64, tolerance: f64) -> Option<Vec<Move>> {
    let (lo, hi) = (entry.helix_min * radius, entry.helix_max * radius);
    if !(hi > 0.0 && tan > 0.0) {
        return None;
    }
    let drop = top - p0.z;
    for s in 0..HELIX_SIZES {
        let r = if HELIX_SIZES > 1 { hi - (hi - lo) * s as f64 / (HELIX_SIZES - 1) as f64 } else { hi };
        if r <= 0.0 {
            continue;
        }
        let turns = (drop / (std::f64::consts::TAU * r * tan)).ceil().max(1.0);
        // Tighter still, the helix turns on the spot: a ramp (or the next entry) serves.
        if turns > crate::limits::MAX_TURNS {
            break;
        }
        let turns = turns as usize;
        let n = turns * CHORDS_PER_TURN;
        for d in 0..HELIX_DIRECTIONS {
            let dir = DVec2::from_angle(std::f64::consts::TAU * d as f64 / HELIX_DIRECTIONS as f64);
            let centre = p0.truncate() + dir * r;
            let start_angle = (-dir).to_angle();
            let point = |k: usize| {
                let a = start_angle + std::f64::consts::TAU * k as f64 / CHORDS_PER_TURN as f64;
                (centre + DVec2::from_angle(a) * r).extend(top - drop * k as f64 / n as f64)
            };
            // Its corners first, from the bottom: one test each, where a chord takes dozens.
            let fits = (0..=n).rev().all(|k| keep.admits(point(k), tolerance)) && (0..n).rev().all(|k| keep.clears(point(k), point(k + 1), tolerance));
            if fits {
                let mut moves: Vec<Move> = (1..n).map(|k| Move::Line { to: point(k), feed }).collect();
                moves.push(Move::Line { to: p0, feed });
                return Some(moves);
            }
        }
    }
    None
}

/// A ramp along `run` from (p0, top): forward and back along it as often as it takes, at the
/// higher of the sloping line and the run, until it meets the run; then back along the run to
/// p0. `None` when the run is too short to ramp on.
fn ramp_along(top: f64, run: &[DVec3], radius: f64, tan: f64, feed: f64) -> Option<Vec<Move>> {
    let length: f64 = run.windows(2).map(|w| w[0].truncate().distance(w[1].truncate())).sum();
    // Shorter than this, a ramp would go back and forth on the spot, unless the step down is
    // shallow enough for a few legs.
    if tan <= 0.0 || length <= 0.0 || (length < shortest_ramp(radius) && top - run[0].z > SHORT_RAMP_LEGS * length * tan) {
        return None;
    }
    let mut moves = Vec::new();
    let mut walked = 0.0;
    let ramp = |w: f64| top - w * tan;
    let n = run.len();
    // Legs alternate forward and back; a segment is (index of its start, index of its end).
    for leg in 0.. {
        let forward = leg % 2 == 0;
        for k in 0..n - 1 {
            let (ia, ib) = if forward { (k, k + 1) } else { (n - 1 - k, n - 2 - k) };
            let (a, b) = (run[ia], run[ib]);
            let step = a.truncate().distance(b.truncate());
            let (za, zb) = (ramp(walked), ramp(walked + step));
            if zb > b.z {
                moves.push(Move::Line { to: b.truncate().extend(zb), feed });
                walked += step;
                continue;
            }
            // The line meets the run on this segment: from there, home along the run.
            let (da, db) = ((za - a.z).max(0.0), zb - b.z);
            let t = if da - db > 0.0 { da / (da - db) } else { 0.0 };
            moves.push(Move::Line { to: a + (b - a) * t, feed });
            let nearer = ia.min(ib);
            moves.extend(run[..=nearer].iter().rev().map(|&p| Move::Line { to: p, feed }));
            return Some(moves);
        }
        if leg >= MAX_RAMP_LEGS {
            return None;
        }
    }
    None
}

/// A helix about `center` of `radius`, starting at angle 0, from height `from` down to `to`,
/// descending no steeper than `angle` (radians), ending with one level circle at `to` (a 2.5D
/// entry: the floor is flat, and the circle clears the core the descent left).
#[allow(clippy::too_many_arguments)]
pub fn helix(center: DVec2, radius: f64, from: f64, to: f64, angle: f64, clockwise: bool, feed: f64, out: &mut Vec<Move>) {
    let start = center + DVec2::new(radius, 0.0);
    let turn_drop = std::f64::consts::TAU * radius * angle.tan();
    let halves = (((from - to) / turn_drop) * 2.0).ceil().max(1.0) as usize;
    for h in 1..=halves {
        let z = from + (to - from) * h as f64 / halves as f64;
        let p = if h % 2 == 1 { center - DVec2::new(radius, 0.0) } else { start };
        out.push(Move::Arc { to: p.extend(z), center, clockwise, feed });
    }
    let at = if halves % 2 == 1 { center - DVec2::new(radius, 0.0) } else { start };
    let other = 2.0 * center - at;
    out.push(Move::Arc { to: other.extend(to), center, clockwise, feed });
    out.push(Move::Arc { to: at.extend(to), center, clockwise, feed });
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Above(f64);
    impl Keepout for Above {
        fn clears(&self, a: DVec3, b: DVec3, _: f64) -> bool {
            a.z >= self.0 && b.z >= self.0
        }
    }
    struct Never;
    impl Keepout for Never {
        fn clears(&self, _: DVec3, _: DVec3, _: f64) -> bool {
            false
        }
    }

    fn walk(from: DVec3, moves: &[Move]) -> Vec<DVec3> {
        std::iter::once(from).chain(moves.iter().map(Move::to)).collect()
    }

    #[test]
    fn a_helix_descends_no_steeper_than_the_angle_and_ends_at_the_start() {
        let p0 = DVec3::new(10.0, 5.0, -4.0);
        let run = [p0, DVec3::new(20.0, 5.0, -4.0)];
        let (moves, kind) = enter_3d(1.0, 0.0, &run, 3.0, &Entry::default(), &Above(-4.0), (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Helix);
        let pts = walk(p0.truncate().extend(1.0), &moves);
        assert!(pts.last().unwrap().distance(p0) < 1e-12);
        let tan = 3f64.to_radians().tan();
        for w in pts.windows(2) {
            let run = w[0].truncate().distance(w[1].truncate());
            assert!(w[0].z - w[1].z <= run * tan * 1.0001 + 1e-12, "{w:?}");
            assert!(w[1].z <= w[0].z + 1e-12);
        }
    }

    #[test]
    fn where_no_helix_fits_it_ramps_along_the_run_never_below_it() {
        // A run rising and falling: the ramp rides on it.
        let run: Vec<DVec3> = (0..=20).map(|i| DVec3::new(i as f64, 0.0, -2.0 + (i as f64 * 0.7).sin())).collect();
        let (moves, kind) = enter_3d(0.0, 0.0, &run, 3.0, &Entry::default(), &Never, (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Ramp);
        let pts = walk(run[0].truncate().extend(0.0), &moves);
        assert!(pts.last().unwrap().distance(run[0]) < 1e-12, "{:?}", pts.last());
        let run_z = |x: f64| {
            let i = (x.floor() as usize).min(19);
            let t = x - i as f64;
            run[i].z + (run[i + 1].z - run[i].z) * t
        };
        let tan = 3f64.to_radians().tan();
        for w in pts.windows(2) {
            for k in 0..=50 {
                let p = w[0] + (w[1] - w[0]) * (k as f64 / 50.0);
                assert!(p.z >= run_z(p.x) - 1e-9, "{p}");
            }
            let flat = w[0].truncate().distance(w[1].truncate());
            assert!(w[0].z - w[1].z <= flat * tan + 1e-9 || (w[1].z - run_z(w[1].x)).abs() < 1e-9, "{w:?}");
        }
    }

    #[test]
    fn a_short_run_ramps_down_a_shallow_step_and_plunges_only_down_a_deep_one() {
        let run = [DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.4, 0.0, -1.0)];
        let tan = 3f64.to_radians().tan();
        // 0.1 mm down takes 1.9 mm of ramp: five legs along 0.4 mm.
        let (moves, kind) = enter_3d(-0.9, 0.0, &run, 3.0, &Entry::default(), &Never, (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Ramp);
        let pts = walk(run[0].truncate().extend(-0.9), &moves);
        assert!(pts.last().unwrap().distance(run[0]) < 1e-12);
        for w in pts.windows(2) {
            assert!(w[0].z - w[1].z <= w[0].truncate().distance(w[1].truncate()) * tan + 1e-9, "{w:?}");
            assert!(w[1].x >= -1e-12 && w[1].x <= 0.4 + 1e-12 && w[1].z >= -1.0 - 1e-12);
        }
        // 1 mm down would take 48 legs on the spot.
        let (_, kind) = enter_3d(0.0, 0.0, &run, 3.0, &Entry::default(), &Never, (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Plunge);
    }

    /// Clear above a height within `half_width` of the line y = 5, counting the moves it is
    /// asked about.
    struct Counted {
        floor: f64,
        half_width: f64,
        moves: std::cell::Cell<usize>,
    }
    impl Keepout for Counted {
        fn clears(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
            self.moves.set(self.moves.get() + 1);
            self.admits(a, tolerance) && self.admits(b, tolerance)
        }
        fn admits(&self, p: DVec3, tolerance: f64) -> bool {
            p.z + tolerance >= self.floor && (p.y - 5.0).abs() <= self.half_width
        }
    }

    #[test]
    fn helices_whose_corners_are_refused_cost_no_move_tests() {
        // A slot 0.4 mm wide along the run: every helix (radius 0.9 to 2.7 mm) leaves it at a
        // corner, so none is tried move by move, and the entry ramps along the run.
        let p0 = DVec3::new(10.0, 5.0, -4.0);
        let run = [p0, DVec3::new(5.0, 5.0, -4.0)];
        let keep = Counted { floor: -4.0, half_width: 0.2, moves: std::cell::Cell::new(0) };
        let (_, kind) = enter_3d(1.0, 0.0, &run, 3.0, &Entry::default(), &keep, (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Ramp);
        assert_eq!(keep.moves.get(), 0);
        // Room for a helix: it is found, and its moves are each tested once.
        let keep = Counted { floor: -4.0, half_width: 10.0, moves: std::cell::Cell::new(0) };
        let (moves, kind) = enter_3d(1.0, 0.0, &run, 3.0, &Entry::default(), &keep, (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Helix);
        assert_eq!(keep.moves.get(), moves.len());
    }

    #[test]
    fn in_the_air_it_feeds_straight_down() {
        let run = [DVec3::new(0.0, 0.0, -1.0), DVec3::new(1.0, 0.0, -1.0)];
        let (moves, kind) = enter_3d(2.0, -1.5, &run, 3.0, &Entry::default(), &Never, (100.0, 500.0), 1e-6);
        assert_eq!(kind, Kind::Air);
        assert_eq!(moves, vec![Move::Line { to: run[0], feed: 100.0 }]);
    }
}
