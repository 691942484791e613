//! A program as the simulation walks it: every move with where it starts, the cutter doing it,
//! and when it runs; and the simulation of those moves on a stock model, with the volume each
//! one removed (its material removal rate, MRR, is that volume over its duration).

use super::sweep::Sweep;
use super::StockModel;
use crate::cutter::Cutter;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::tool::Tool;
use crate::progress::Progress;
use crate::toolpath::{Move, Toolpath};

/// One move of a program, ready to simulate.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramMove {
    /// Index of the tool path it belongs to.
    pub path: usize,
    pub tool: u32,
    pub cutter: Cutter,
    pub from: DVec3,
    pub mv: Move,
    /// When it starts and how long it takes (seconds, at the programmed feeds).
    pub start: f64,
    pub seconds: f64,
}

/// The moves of `paths`, each with its tool from `tools`, timed at their feeds and `rapid_rate`.
pub fn program_moves(paths: &[Toolpath], tools: &[Tool], rapid_rate: f64) -> Result<Vec<ProgramMove>> {
    let mut out = Vec::new();
    let mut clock = 0.0;
    for (k, path) in paths.iter().enumerate() {
        let tool = tools.iter().find(|t| t.number == path.tool).ok_or_else(|| Error::Input(format!("the program uses tool number {}, which is not in the tool library", path.tool)))?;
        let mut at = path.start;
        for mv in &path.moves {
            let rate = match *mv {
                Move::Rapid { .. } => rapid_rate,
                Move::Line { feed, .. } | Move::Arc { feed, .. } => feed,
            };
            let seconds = mv.length(at) / rate * 60.0;
            out.push(ProgramMove { path: k, tool: tool.number, cutter: tool.cutter.clone(), from: at, mv: *mv, start: clock, seconds });
            clock += seconds;
            at = mv.to();
        }
    }
    Ok(out)
}

impl ProgramMove {
    /// The sweeps of this move (one, or a helix's chords within `chordal`).
    pub fn sweeps(&self, chordal: f64) -> Vec<Sweep> {
        Sweep::of_move(self.cutter.profile(), self.from, &self.mv, chordal)
    }

    /// Cuts `stock` with this move; returns the volume removed (mm³).
    pub fn cut(&self, stock: &mut dyn StockModel, chordal: f64) -> f64 {
        self.sweeps(chordal).iter().map(|s| stock.apply(s)).sum()
    }

    /// Material removal rate (mm³/min) of a move that removed `volume`.
    pub fn mrr(&self, volume: f64) -> f64 {
        if self.seconds > 0.0 {
            volume / self.seconds * 60.0
        } else {
            0.0
        }
    }
}

/// Simulates `moves` on `stock` and returns the volume each removed (mm³).
pub fn simulate(stock: &mut dyn StockModel, moves: &[ProgramMove], chordal: f64, progress: &mut Progress) -> Result<Vec<f64>> {
    let mut volumes = Vec::with_capacity(moves.len());
    for (k, m) in moves.iter().enumerate() {
        if k % 4096 == 0 && !progress.report(k as f64 / moves.len() as f64) {
            return Err(Error::Cancelled);
        }
        volumes.push(m.cut(stock, chordal));
    }
    Ok(volumes)
}
