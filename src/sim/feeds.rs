//! Feeds held to what the spindle can take (issue 58's feed optimisation, its slowing half).
//! The simulation measured the material each move removes; over [`RATE_CELLS`] cells of path
//! ([`removal_rates`]) that is the cut's removal rate at the programmed feeds. Where a stretch
//! removes more a minute than the machine's spindle can cut in the stock's material
//! ([`crate::cutting::rate_limit`]), the feeds of the moves it is measured at are lowered (to
//! whole mm/min, never up) and the rates measured again, until no stretch does. The moves
//! keep their places, so each still removes what it did and its rate falls with its feed,
//! exactly: no second simulation is needed. Drilling cycles keep their feeds (a drill's
//! thrust is no milling cut, and a canned cycle has one feed).

use super::program::{removal_rates, ProgramMove, RATE_CELLS};
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
    // Each move's path and its index there.
    let places: Vec<(usize, usize)> = paths.iter().enumerate().flat_map(|(p, path)| (0..path.moves.len()).map(move |i| (p, i))).collect();
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
    let mut clock = moves.first().map_or(0.0, |m| m.start);
    for (k, m) in moves.iter_mut().enumerate() {
        if slowed[k] {
            let to = feeds[k].expect("only feed moves are slowed");
            set_feed(&mut m.mv, to);
            set_feed(&mut paths[places[k].0].moves[places[k].1], to);
            m.seconds = timings[k].seconds;
        }
        m.start = clock;
        clock += m.seconds;
    }
    Held { slowed: (0..moves.len()).filter(|&k| slowed[k]).collect(), rates }
}

fn set_feed(m: &mut Move, to: f64) {
    if let Move::Line { feed, .. } | Move::Arc { feed, .. } = m {
        *feed = to;
    }
}
