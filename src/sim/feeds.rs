//! Feeds along the path from what the simulation measured (issue 58's feed optimisation).
//!
//! **Held to the spindle** ([`hold_rate`]). The simulation measured the material each move
//! removes; over [`RATE_CELLS`] cells of path ([`removal_rates`]) that is the cut's removal
//! rate at the programmed feeds. Where a stretch removes more a minute than the machine's
//! spindle can cut in the stock's material ([`crate::cutting::rate_limit`]), the feeds of the
//! moves it is measured at are lowered (to whole mm/min, never up) and the rates measured
//! again, until no stretch does. The moves keep their places, so each still removes what it
//! did and its rate falls with its feed, exactly: no second simulation is needed. Drilling
//! cycles keep their feeds (a drill's thrust is no milling cut, and a canned cycle has one
//! feed).
//!
//! **Raised to the chip** ([`speed_up`], a job's `simulation.optimizeFeeds`). A tooth's chip
//! is thickest where its edge crosses the material nearest the path's centre line: with the
//! material's nearest edge `d` from the path (the simulation's nearest cut cell,
//! [`crate::sim::DexelStock::take_nearest`], less half a cell's diagonal, since a cell counts
//! as cut by its centre) the thickest chip is the feed per tooth times
//! [`thinning`]`(d) = √(1 − (d/R)²)`: radial chip thinning (a cut of width `ae` into a wall
//! has `d = R − ae`, and `1/thinning` is the tool makers' `D / (2√(ae·D − ae²))`). A cut's
//! feed is raised by `1/thinning`, so its thickest chip is the one its programmed feed cuts
//! in a slot, up to [`MAX_SPEEDUP`] times and under the air feed; a move that removed nothing
//! runs at the air feed. Moves going down into material (plunges, ramps, helices) and drilling
//! keep their feeds. The spindle's hold runs after, on the raised feeds.

use super::program::{removal_rates, ProgramMove, RATE_CELLS};
use crate::tool::Tool;
use crate::toolpath::{Move, Toolpath};

/// Rounds of measuring and lowering before giving up on a stretch (each lowers every move
/// over the limit to the feed that would bring its own rate to it).
const ROUNDS: usize = 200;

/// What [`hold_rate`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Held {
    /// The moves whose feeds were lowered (indices in the program).
    pub slowed: Vec<usize>,
    /// Each move's removal rate (mm³/min) at the feeds as held.
    pub rates: Vec<f64>,
}

/// Holds the program's `moves` (over `paths`, in their order; `volumes` what each removes, on
/// a stock of `cell` mm cells) to at most `limit` mm³/min, the same feeds written into
/// `paths` and each move's time and start made again.
pub fn hold_rate(paths: &mut [Toolpath], moves: &mut [ProgramMove], volumes: &[f64], cell: f64, limit: f64) -> Held {
    let span = RATE_CELLS * cell;
    let places = places(paths);
    debug_assert_eq!(places.len(), moves.len(), "the moves are the paths' moves");
    let fixed: Vec<bool> = places.iter().map(|&(p, _)| !paths[p].cycles.is_empty()).collect();
    let mut timings: Vec<_> = moves.iter().map(ProgramMove::timing).collect();
    let mut feeds: Vec<Option<f64>> = moves.iter().map(|m| m.mv.feed()).collect();
    let mut slowed = vec![false; moves.len()];
    let mut rates = removal_rates(&timings, volumes, span);
    for _ in 0..ROUNDS {
        let mut lowered = false;
        for k in 0..moves.len() {
            let Some(feed) = feeds[k] else { continue };
            if fixed[k] || rates[k] <= limit || feed <= 1.0 {
                continue;
            }
            let to = (feed * limit / rates[k]).floor().clamp(1.0, feed - 1.0);
            feeds[k] = Some(to);
            timings[k].seconds = timings[k].length / to * 60.0;
            (slowed[k], lowered) = (true, true);
        }
        if !lowered {
            break;
        }
        rates = removal_rates(&timings, volumes, span);
    }
    let slowed: Vec<usize> = (0..moves.len()).filter(|&k| slowed[k]).collect();
    refeed(paths, moves, &places, slowed.iter().map(|&k| (k, feeds[k].expect("only feed moves are slowed"))));
    Held { slowed, rates }
}

/// Each move's path and its index there, for `moves` over `paths` in their order.
fn places(paths: &[Toolpath]) -> Vec<(usize, usize)> {
    paths.iter().enumerate().flat_map(|(p, path)| (0..path.moves.len()).map(move |i| (p, i))).collect()
}

/// Sets the feeds `to` (move index, mm/min) in `moves` and in `paths` (at `places`), and
/// times every move again from the first one's start.
fn refeed(paths: &mut [Toolpath], moves: &mut [ProgramMove], places: &[(usize, usize)], to: impl Iterator<Item = (usize, f64)>) {
    for (k, feed) in to {
        let m = &mut moves[k];
        set_feed(&mut m.mv, feed);
        set_feed(&mut paths[places[k].0].moves[places[k].1], feed);
        m.seconds = m.mv.length(m.from) / feed * 60.0;
    }
    let mut clock = moves.first().map_or(0.0, |m| m.start);
    for m in moves.iter_mut() {
        m.start = clock;
        clock += m.seconds;
    }
}

/// The most [`speed_up`] raises a cut's feed, whatever its chip: past a few times the feed,
/// a chip thinned this much is as much rubbing as cutting, and tool makers' tables stop.
pub const MAX_SPEEDUP: f64 = 4.0;

/// The thickest chip a tooth of a cutter of radius `radius` cuts, as a fraction of its feed
/// per tooth, where the material's nearest edge is `reach` from the path's centre line (0 past
/// the rim).
pub fn thinning(reach: f64, radius: f64) -> f64 {
    let x = (reach / radius).clamp(0.0, 1.0);
    (1.0 - x * x).sqrt()
}

/// Where the material's nearest edge may stand for a move whose nearest cut cell's centre was
/// `nearest` from its path, on cells of side `cell`: half a cell's diagonal nearer.
pub fn reach(nearest: f64, cell: f64) -> f64 {
    (nearest - cell * std::f64::consts::FRAC_1_SQRT_2).max(0.0)
}

/// [`thinning`] for a move whose nearest cut cell's centre was `nearest` from its path (∞:
/// it only grazed, 0), on cells of side `cell`, by a cutter of radius `radius`.
fn measured_thinning(nearest: f64, cell: f64, radius: f64) -> f64 {
    if nearest.is_finite() {
        thinning(reach(nearest, cell), radius)
    } else {
        0.0
    }
}

/// The thickest chip of each move (mm per tooth, 0 for rapids and moves that cut nothing),
/// measured: its feed per tooth at its tool's speed times [`thinning`] of its [`reach`].
pub fn chips(moves: &[ProgramMove], volumes: &[f64], nearest: &[f64], cell: f64, tools: &[Tool]) -> Vec<f64> {
    moves
        .iter()
        .zip(volumes.iter().zip(nearest))
        .map(|(m, (&volume, &near))| {
            let (Some(feed), Some(tool)) = (m.mv.feed(), tools.iter().find(|t| t.number == m.tool)) else { return 0.0 };
            if volume <= 0.0 || tool.spindle_rpm <= 0.0 {
                return 0.0;
            }
            feed / (tool.spindle_rpm * tool.flutes.max(1) as f64) * measured_thinning(near, cell, m.cutter.diameter * 0.5)
        })
        .collect()
}

/// What [`speed_up`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sped {
    /// Cuts whose feeds were raised for their thinner chips.
    pub faster: usize,
    /// Moves that removed nothing, now at the air feed.
    pub aired: usize,
}

/// Raises the feeds of `moves` (over `paths`, in their order; `volumes` and `nearest` what the
/// simulation measured of each, on cells of side `cell`) for their chips' thinning, under
/// `air_feed` (module docs), the same feeds written into `paths` and the moves timed again.
pub fn speed_up(paths: &mut [Toolpath], moves: &mut [ProgramMove], volumes: &[f64], nearest: &[f64], cell: f64, air_feed: f64) -> Sped {
    let places = places(paths);
    debug_assert_eq!(places.len(), moves.len(), "the moves are the paths' moves");
    // A raised cut stays under the air feed, which marks a move in air ([`ProgramMove::air`]).
    let top = air_feed.ceil() - 1.0;
    let mut sped = Sped::default();
    let (mut to, mut aired) = (Vec::new(), Vec::new());
    for (k, m) in moves.iter().enumerate() {
        let Some(feed) = m.mv.feed() else { continue };
        if !paths[places[k].0].cycles.is_empty() || m.mv.to().z < m.from.z - 1e-9 {
            continue;
        }
        if volumes[k] <= 0.0 {
            if air_feed > feed {
                to.push((k, air_feed));
                aired.push(k);
            }
            continue;
        }
        let thin = measured_thinning(nearest[k], cell, m.cutter.diameter * 0.5);
        let raised = (feed / thin.max(1.0 / MAX_SPEEDUP)).floor().min(top);
        if raised > feed {
            to.push((k, raised));
            sped.faster += 1;
        }
    }
    refeed(paths, moves, &places, to.into_iter());
    // At the air feed, as a move its operation knew to be in air is ([`ProgramMove::air`]).
    for &k in &aired {
        moves[k].air = true;
    }
    sped.aired = aired.len();
    sped
}

fn set_feed(m: &mut Move, to: f64) {
    if let Move::Line { feed, .. } | Move::Arc { feed, .. } = m {
        *feed = to;
    }
}
