//! Linking cutting runs into one path: between two runs the tool stays down and feeds straight
//! across when that straight move stays on or above the CL surface (plus allowance) and inside
//! the region and is short; otherwise it retracts to the clearance height, moves over at rapid,
//! drops at rapid to a small gap above the next start, or above the stock's top when the start
//! lies lower (a rapid never enters uncut stock), and feeds down the rest.

use serde::{Deserialize, Serialize};

use super::Move;
use crate::geom::{DVec3, Tolerances};
use crate::strategy::region::Region;
use crate::zmap::surface::{point_at, ClSurface};

/// How runs are joined.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, rename_all = "camelCase")]
pub struct LinkSettings {
    /// Height of rapid moves between runs (mm, absolute). Set by the job from the stock top.
    pub clearance_z: f64,
    /// Height above a run's start at which a rapid descent stops and the feed begins (mm).
    /// Default value: 1.
    pub rapid_gap: f64,
    /// Longest link that may stay down (mm). Default value: 4.
    pub stay_down_max: f64,
    /// Top of the stock (mm, absolute): rapid descents stop `rapid_gap` above it. Default value:
    /// none (descend to `rapid_gap` above the start).
    pub stock_top: Option<f64>,
}

impl Default for LinkSettings {
    fn default() -> Self {
        LinkSettings { clearance_z: 5.0, rapid_gap: 1.0, stay_down_max: 4.0, stock_top: None }
    }
}

/// The surface a path must stay on or above: a CL z-map lifted by the allowance, within a region.
pub struct Floor<'a> {
    pub cl: &'a ClSurface,
    pub allowance: f64,
    pub region: &'a Region,
}

impl Floor<'_> {
    /// Whether the straight move from `a` to `b` stays inside the region and on or above the
    /// floor (within `tolerance`), checked at every point of the surface along it
    /// ([`ClSurface::along`]): a line at or above those points is at or above the polyline
    /// through them.
    pub fn clears(&self, a: DVec3, b: DVec3, tolerance: f64) -> bool {
        self.cl.along(a.truncate(), b.truncate()).into_iter().all(|(t, z)| {
            let p = point_at(a, b, t);
            self.region.contains(p.truncate()) && p.z + tolerance >= z + self.allowance
        })
    }
}

/// Feeds (mm/min) used by the linked path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feeds {
    pub cut: f64,
    pub plunge: f64,
}

/// Joins `runs` into moves; returns where the path starts (above its first point, at the
/// clearance height) and the moves, ending at the clearance height.
pub fn link_runs(runs: &[Vec<DVec3>], floor: &Floor, settings: &LinkSettings, feeds: Feeds, tolerances: &Tolerances) -> (DVec3, Vec<Move>) {
    let clearance = settings.clearance_z;
    let first = runs.iter().find_map(|r| r.first()).copied().unwrap_or(DVec3::new(0.0, 0.0, clearance));
    let start = first.truncate().extend(clearance);
    let mut moves = Vec::new();
    let mut at = start;
    let mut down = false;
    for run in runs.iter().filter(|r| !r.is_empty()) {
        let entry = run[0];
        let stay = down && at.distance(entry) <= settings.stay_down_max && floor.clears(at, entry, tolerances.height);
        if stay {
            moves.push(Move::Line { to: entry, feed: feeds.cut });
        } else {
            if down {
                moves.push(Move::Rapid { to: at.truncate().extend(clearance) });
            }
            if at.truncate() != entry.truncate() || !down && at.z != clearance {
                moves.push(Move::Rapid { to: entry.truncate().extend(clearance) });
            }
            let gap = (entry.z.max(settings.stock_top.unwrap_or(f64::NEG_INFINITY)) + settings.rapid_gap).min(clearance);
            if gap < clearance {
                moves.push(Move::Rapid { to: entry.truncate().extend(gap) });
            }
            moves.push(Move::Line { to: entry, feed: feeds.plunge });
        }
        moves.extend(run[1..].iter().map(|&p| Move::Line { to: p, feed: feeds.cut }));
        at = *run.last().unwrap();
        down = true;
    }
    if down {
        moves.push(Move::Rapid { to: at.truncate().extend(clearance) });
    }
    (start, moves)
}
