//! Tool paths as data: rapid, linear feed and arc moves, each path with its tool. Linking and
//! point reduction are passes over this data ([`link`], [`reduce`]), not parts of a strategy.

pub mod arcfit;
pub mod cycle;
pub mod entry;
pub mod link;
pub mod reduce;

use serde::{Deserialize, Serialize};

use crate::geom::{DVec2, DVec3};

/// One motion of the machine. Coordinates are absolute, in mm.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "camelCase")]
pub enum Move {
    /// Positioning at the machine's rapid rate (G0).
    Rapid { to: DVec3 },
    /// Straight cut at `feed` mm/min (G1).
    Line { to: DVec3, feed: f64 },
    /// Arc in the XY plane about `center`, to `to` (the z of `to` may differ: a helix), at
    /// `feed` mm/min (G2 clockwise, G3 counter-clockwise).
    Arc { to: DVec3, center: DVec2, clockwise: bool, feed: f64 },
}

impl Move {
    pub fn to(&self) -> DVec3 {
        match *self {
            Move::Rapid { to } | Move::Line { to, .. } | Move::Arc { to, .. } => to,
        }
    }

    pub fn is_rapid(&self) -> bool {
        matches!(self, Move::Rapid { .. })
    }

    /// The least and greatest corner of the box the tip sweeps from `from`: an arc's by its
    /// ends and the quarter points of its circle it passes.
    pub fn bounds(&self, from: DVec3) -> (DVec3, DVec3) {
        let to = self.to();
        let (mut lo, mut hi) = (from.min(to), from.max(to));
        if let Move::Arc { center, clockwise, .. } = *self {
            let a = from.truncate() - center;
            let (r, start, sweep) = (a.length(), a.y.atan2(a.x), arc_sweep(from, to, center, clockwise));
            for k in 0..4 {
                let angle = k as f64 * std::f64::consts::FRAC_PI_2;
                // How far round from the start, the way the arc turns, this quarter point lies.
                let round = ((angle - start) * sweep.signum()).rem_euclid(std::f64::consts::TAU);
                if round <= sweep.abs() {
                    let p = (center + r * DVec2::new(angle.cos(), angle.sin())).extend(from.z);
                    (lo, hi) = (lo.min(p), hi.max(p));
                }
            }
        }
        (lo, hi)
    }

    /// Its feed (mm/min), or none for a rapid.
    pub fn feed(&self) -> Option<f64> {
        match *self {
            Move::Line { feed, .. } | Move::Arc { feed, .. } => Some(feed),
            Move::Rapid { .. } => None,
        }
    }

    /// Length of the move from `from`.
    pub fn length(&self, from: DVec3) -> f64 {
        match *self {
            Move::Rapid { to } | Move::Line { to, .. } => from.distance(to),
            Move::Arc { to, center, clockwise, .. } => {
                let planar = (from.truncate() - center).length() * arc_sweep(from, to, center, clockwise).abs();
                (planar * planar + (to.z - from.z).powi(2)).sqrt()
            }
        }
    }
}

/// The length of `moves` made one after another from `from`.
pub fn moves_length(from: DVec3, moves: &[Move]) -> f64 {
    moves.iter().scan(from, |at, m| Some(m.length(std::mem::replace(at, m.to())))).sum()
}

/// Signed angle swept by an arc from `from` to `to` about `center` (negative when clockwise);
/// equal start and end points make a full circle, as in G-code.
pub fn arc_sweep(from: DVec3, to: DVec3, center: DVec2, clockwise: bool) -> f64 {
    let (a, b) = (from.truncate() - center, to.truncate() - center);
    let mut sweep = a.angle_to(b); // (-pi, pi], counter-clockwise positive
    if clockwise && sweep > 0.0 || !clockwise && sweep < 0.0 {
        sweep -= sweep.signum() * std::f64::consts::TAU;
    }
    if sweep == 0.0 {
        sweep = if clockwise { -std::f64::consts::TAU } else { std::f64::consts::TAU };
    }
    sweep
}

/// The moves of one operation with one tool, starting at the clearance height.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Toolpath {
    /// Name of the operation that made it.
    pub name: String,
    /// Tool number (index into the job's tool library by number).
    pub tool: u32,
    /// Spindle speed (rpm).
    pub spindle_rpm: f64,
    /// Where the path starts: above its first point at the clearance height.
    pub start: DVec3,
    pub moves: Vec<Move>,
    /// Drilling cycles among the moves: each marks the moves one cycle makes at one hole, for
    /// a post to write as a canned cycle where the control has them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub cycles: Vec<cycle::Cycle>,
}

/// Lengths and an estimated time of a path.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct PathStats {
    pub moves: usize,
    pub feed_length: f64,
    pub rapid_length: f64,
    /// Estimated cycle time (seconds) at the programmed feeds and the given rapid rate.
    pub seconds: f64,
}

impl std::ops::Add for PathStats {
    type Output = PathStats;

    fn add(self, other: PathStats) -> PathStats {
        PathStats { moves: self.moves + other.moves, feed_length: self.feed_length + other.feed_length, rapid_length: self.rapid_length + other.rapid_length, seconds: self.seconds + other.seconds }
    }
}

/// How fast rapids go, for the cycle time: one rate along the move (the post's `rapidRate`), or
/// each axis at its own (a machine's `rapids`), a rapid then taking as long as its slowest
/// axis needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rapids {
    /// mm/min along the move.
    pub rate: f64,
    /// mm/min in X, Y and Z, instead of `rate`.
    pub axes: Option<[f64; 3]>,
}

impl Rapids {
    /// One rate along every rapid (mm/min).
    pub fn at(rate: f64) -> Rapids {
        Rapids { rate, axes: None }
    }

    /// Seconds a rapid from `from` to `to` takes.
    pub fn seconds(&self, from: DVec3, to: DVec3) -> f64 {
        let d = (to - from).abs();
        60.0 * match self.axes {
            Some([x, y, z]) => (d.x / x).max(d.y / y).max(d.z / z),
            None => d.length() / self.rate,
        }
    }

    /// In words, for a program's head, in its unit (`mm` millimetres to the unit, named
    /// `unit`): "rapids at 3000 mm/min", "rapids at X 10000, Y 10000, Z 5000 mm/min",
    /// "rapids at 118.1 in/min".
    pub fn describe(&self, mm: f64, unit: &str) -> String {
        let rate = |v: f64| crate::limits::shown((v / mm * 10.0).round() / 10.0);
        match self.axes {
            Some([x, y, z]) => format!("rapids at X {}, Y {}, Z {} {unit}/min", rate(x), rate(y), rate(z)),
            None => format!("rapids at {} {unit}/min", rate(self.rate)),
        }
    }
}

impl Toolpath {
    /// Lengths, and time at the feeds and `rapids`.
    pub fn stats(&self, rapids: Rapids) -> PathStats {
        let mut stats = PathStats { moves: self.moves.len(), ..PathStats::default() };
        let mut at = self.start;
        for m in &self.moves {
            let length = m.length(at);
            match *m {
                Move::Rapid { .. } => {
                    stats.rapid_length += length;
                    stats.seconds += rapids.seconds(at, m.to());
                }
                Move::Line { feed, .. } | Move::Arc { feed, .. } => {
                    stats.feed_length += length;
                    stats.seconds += length / feed * 60.0;
                }
            }
            at = m.to();
        }
        stats.seconds += self.dwell_seconds();
        stats
    }

    /// Seconds its cycles dwell at the bottom of their holes.
    pub fn dwell_seconds(&self) -> f64 {
        self.cycles.iter().filter(|c| c.kind == cycle::CycleKind::Dwell).map(|c| c.dwell).sum()
    }

    /// The path as line segments for drawing: each segment's two end points, and whether it is
    /// a rapid. Arcs are split into chords of at most `arc_step` radians.
    pub fn segments(&self, arc_step: f64) -> Vec<(DVec3, DVec3, bool)> {
        let mut out = Vec::with_capacity(self.moves.len());
        let mut at = self.start;
        for m in &self.moves {
            match *m {
                Move::Rapid { to } => out.push((at, to, true)),
                Move::Line { to, .. } => out.push((at, to, false)),
                Move::Arc { to, center, clockwise, .. } => {
                    let a = at.truncate() - center;
                    let radius = a.length();
                    let sweep = arc_sweep(at, to, center, clockwise);
                    let steps = ((sweep.abs() / arc_step).ceil() as usize).max(1);
                    let start_angle = a.y.atan2(a.x);
                    let mut prev = at;
                    for k in 1..=steps {
                        let f = k as f64 / steps as f64;
                        let th = start_angle + sweep * f;
                        let p = if k == steps { to } else { (center + DVec2::new(th.cos(), th.sin()) * radius).extend(at.z + (to.z - at.z) * f) };
                        out.push((prev, p, false));
                        prev = p;
                    }
                }
            }
            at = m.to();
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An arc's box holds the quarter points it passes and none it does not: a quarter from
    /// +X to +Y counter-clockwise stays in the first quadrant, the same ends clockwise go round
    /// the other three, and a full circle's box is its circle's.
    #[test]
    fn an_arcs_box_is_its_ends_and_the_quarter_points_it_passes() {
        let (from, to, center) = (DVec3::new(10.0, 0.0, 0.0), DVec3::new(0.0, 10.0, -1.0), DVec2::ZERO);
        let ccw = Move::Arc { to, center, clockwise: false, feed: 100.0 };
        assert_eq!(ccw.bounds(from), (DVec3::new(0.0, 0.0, -1.0), DVec3::new(10.0, 10.0, 0.0)));
        let cw = Move::Arc { to, center, clockwise: true, feed: 100.0 };
        assert_eq!(cw.bounds(from), (DVec3::new(-10.0, -10.0, -1.0), DVec3::new(10.0, 10.0, 0.0)));
        let full = Move::Arc { to: from, center, clockwise: false, feed: 100.0 };
        let (lo, hi) = full.bounds(from);
        assert!((lo - DVec3::new(-10.0, -10.0, 0.0)).length() < 1e-12 && (hi - DVec3::new(10.0, 10.0, 0.0)).length() < 1e-12, "{lo} {hi}");
        assert_eq!(Move::Line { to, feed: 1.0 }.bounds(from), (DVec3::new(0.0, 0.0, -1.0), DVec3::new(10.0, 10.0, 0.0)));
    }
}
