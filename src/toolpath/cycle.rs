//! Drilling cycles as moves: G81 (drill), G82 (drill, dwell at the bottom), G83 (peck, out of
//! the hole after each peck) and G73 (chip break: back a little after each peck). A drilling
//! operation writes each hole's cycle as its moves and marks them with a [`Cycle`]; a post
//! whose control has canned cycles writes the marked moves as one `G8x` block, one without
//! (GRBL 1.1 refuses `G81`–`G83` with `error:20`) writes the moves themselves. The moves are
//! those LinuxCNC's interpreter makes of the block (`interp_cycles.cc`: the XY move at the
//! height the tool stands at, down to R at the rapid rate, the cycle (G83 out to R after each
//! peck), out to R (G99) or back to the starting height (G98)), so both programs move the tool
//! alike; G-code read back
//! ([`crate::post::read`]) turns a block into the same moves.

use serde::{Deserialize, Serialize};

use super::Move;
use crate::geom::DVec2;

/// How far above the last peck's depth G83 and G73 come back down (or back off) at the rapid
/// rate: LinuxCNC's `G83_RAPID_DELTA`, 0.010 inch.
pub const PECK_CLEARANCE: f64 = 0.254;

/// Which cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum CycleKind {
    /// G81: feed to the bottom, rapid out.
    Drill,
    /// G82: feed to the bottom, dwell, rapid out.
    Dwell,
    /// G83: pecks, out of the hole after each.
    Peck,
    /// G73: pecks, backing off a little after each to break the chip.
    ChipBreak,
}

impl CycleKind {
    /// Its G word.
    pub fn code(self) -> &'static str {
        match self {
            CycleKind::Drill => "G81",
            CycleKind::Dwell => "G82",
            CycleKind::Peck => "G83",
            CycleKind::ChipBreak => "G73",
        }
    }
}

/// One drilling cycle at one hole, and where its moves are in the tool path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct Cycle {
    pub kind: CycleKind,
    /// Its first move in the path's moves, and how many it makes.
    pub first: usize,
    pub count: usize,
    /// The hole's centre.
    pub at: DVec2,
    /// The height the tool stands at as the cycle starts (G98 returns to it), at or above `r`.
    pub initial: f64,
    /// The R plane: where feeding starts.
    pub r: f64,
    /// The bottom (Z).
    pub bottom: f64,
    /// Back to `initial` (G98) after the hole, else to `r` (G99).
    pub to_initial: bool,
    /// Peck depth (Q) of G83 and G73.
    pub peck: f64,
    /// Seconds at the bottom (P) of G82.
    pub dwell: f64,
    /// Feed (mm/min).
    pub feed: f64,
}

impl Cycle {
    /// The height the tool leaves the hole at.
    pub fn clear(&self) -> f64 {
        if self.to_initial {
            self.initial
        } else {
            self.r
        }
    }

    /// Its moves, from anywhere at the height `initial`: they end with the feed to the bottom
    /// and the rapid out.
    pub fn moves(&self) -> Vec<Move> {
        let at = |z: f64| self.at.extend(z);
        let (clear, feed) = (self.clear(), self.feed);
        let mut out = vec![Move::Rapid { to: at(self.initial) }];
        if self.initial != self.r {
            out.push(Move::Rapid { to: at(self.r) });
        }
        if matches!(self.kind, CycleKind::Peck | CycleKind::ChipBreak) {
            // As the interpreter counts them: from R down by the peck while above the bottom.
            let mut depth = self.r - self.peck;
            while depth > self.bottom {
                out.push(Move::Line { to: at(depth), feed });
                if self.kind == CycleKind::Peck {
                    // Out to R between pecks (LinuxCNC 2.8 on, as Fanuc), whatever G98 says.
                    out.push(Move::Rapid { to: at(self.r) });
                }
                out.push(Move::Rapid { to: at(depth + PECK_CLEARANCE) });
                depth -= self.peck;
            }
        }
        out.push(Move::Line { to: at(self.bottom), feed });
        out.push(Move::Rapid { to: at(clear) });
        out
    }

    /// The index in its path of the move that reaches the bottom, after which G82 dwells: the
    /// last but one of its [`Cycle::count`] moves.
    pub fn bottom_move(&self) -> usize {
        (self.first + self.count).saturating_sub(2)
    }
}

/// Whether `moves` are a cycle's moves `expected` (lines and rapids alike), each end within
/// `within` of where the cycle puts it.
pub fn same_moves(expected: &[Move], moves: &[Move], within: f64) -> bool {
    expected.len() == moves.len() && expected.iter().zip(moves).all(|(a, b)| a.is_rapid() == b.is_rapid() && !matches!(b, Move::Arc { .. }) && a.to().distance(b.to()) <= within)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cycle(kind: CycleKind) -> Cycle {
        Cycle { kind, first: 0, count: 0, at: DVec2::new(10.0, 5.0), initial: 15.0, r: 1.0, bottom: -7.5, to_initial: true, peck: 2.0, dwell: 0.5, feed: 100.0 }
    }

    #[test]
    fn pecks_are_counted_from_r_as_the_interpreter_counts_them() {
        let moves = cycle(CycleKind::Peck).moves();
        let bottom = Cycle { count: moves.len(), ..cycle(CycleKind::Peck) }.bottom_move();
        let feeds: Vec<f64> = moves.iter().filter(|m| !m.is_rapid()).map(|m| m.to().z).collect();
        assert_eq!(feeds, vec![-1.0, -3.0, -5.0, -7.0, -7.5]);
        assert_eq!(moves[bottom].to().z, -7.5);
        // Out to R after each peck, back to just above the last depth.
        assert_eq!(moves[3].to().z, 1.0);
        assert!((moves[4].to().z - (-1.0 + PECK_CLEARANCE)).abs() < 1e-12);
        let chip = cycle(CycleKind::ChipBreak).moves();
        assert!(chip.iter().all(|m| m.to().z <= 15.0));
        assert_eq!(chip.iter().filter(|m| m.to().z >= 1.0).count(), 3, "G73 stays in the hole between pecks");
        assert_eq!(cycle(CycleKind::Drill).moves().len(), 4);
    }
}
