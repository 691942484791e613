//! Scrubbing through a simulated program: the stock after any number of moves, fast enough to
//! animate. Moving forward applies the moves in between; moving back restarts from the nearest
//! checkpoint, which the first pass forward leaves every `1 / CHECKPOINTS` of the program.

use super::program::ProgramMove;
use super::DexelStock;

/// Stock copies kept along the program.
const CHECKPOINTS: usize = 8;

/// A program being played back on a z-map stock.
pub struct Playback {
    moves: Vec<ProgramMove>,
    chordal: f64,
    stock: DexelStock,
    at: usize,
    every: usize,
    checkpoints: Vec<Option<DexelStock>>,
    tops: Vec<f32>,
}

impl Playback {
    /// Starts at the uncut `stock`.
    pub fn new(stock: DexelStock, moves: Vec<ProgramMove>, chordal: f64) -> Playback {
        let every = moves.len().div_ceil(CHECKPOINTS).max(1);
        let mut checkpoints = vec![None; moves.len() / every + 1];
        checkpoints[0] = Some(stock.clone());
        let mut p = Playback { moves, chordal, stock, at: 0, every, checkpoints, tops: Vec::new() };
        p.refresh();
        p
    }

    /// Starts at the end of the program, whose simulation gave `finished` from `fresh`.
    pub fn at_end(fresh: DexelStock, finished: DexelStock, moves: Vec<ProgramMove>, chordal: f64) -> Playback {
        let mut p = Playback::new(fresh, moves, chordal);
        p.stock = finished;
        p.at = p.moves.len();
        p.refresh();
        p
    }

    pub fn moves(&self) -> &[ProgramMove] {
        &self.moves
    }

    pub fn stock(&self) -> &DexelStock {
        &self.stock
    }

    /// The material's height over every cell (row-major, f32 for drawing) after the first
    /// `count` moves.
    pub fn seek(&mut self, count: usize) -> &[f32] {
        let count = count.min(self.moves.len());
        if count < self.at {
            let k = (0..=count / self.every).rev().find(|&k| self.checkpoints[k].is_some()).unwrap_or(0);
            self.stock = self.checkpoints[k].clone().expect("checkpoint 0 is kept from the start");
            self.at = k * self.every;
        }
        while self.at < count {
            self.moves[self.at].cut(&mut self.stock, self.chordal);
            self.at += 1;
            if self.at % self.every == 0 && self.checkpoints[self.at / self.every].is_none() {
                self.checkpoints[self.at / self.every] = Some(self.stock.clone());
            }
        }
        self.refresh();
        &self.tops
    }

    fn refresh(&mut self) {
        let g = self.stock.grid();
        self.tops.clear();
        self.tops.extend((0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).map(|(i, j)| self.stock.top(i, j) as f32));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::{self, Job, Simulation};
    use crate::progress::Progress;

    #[test]
    fn seeking_back_and_forth_gives_the_same_stock_as_simulating_straight() {
        let job = Job { simulation: Simulation { verify: false, ..Simulation::default() }, ..Job::default() };
        let out = job::run(&job, crate::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
        let fresh = DexelStock::new(&out.stock, 0.5, 1);
        let mut p = Playback::new(fresh.clone(), out.moves.clone(), 0.002);
        let n = out.moves.len();
        let end = p.seek(n).to_vec();
        let mut from_end = Playback::at_end(fresh.clone(), p.stock().clone(), out.moves.clone(), 0.002);
        assert_eq!(from_end.seek(n / 3), p.seek(n / 3));
        let middle = p.seek(n / 3).to_vec();
        assert_eq!(p.seek(n), &end[..]);
        let mut straight = fresh;
        for m in &out.moves[..n / 3] {
            m.cut(&mut straight, 0.002);
        }
        let g = straight.grid();
        for j in 0..g.ny {
            for i in 0..g.nx {
                assert_eq!(middle[j * g.nx + i], straight.top(i, j) as f32);
            }
        }
        assert!(end.iter().zip(&middle).any(|(a, b)| a < b), "the rest of the program cuts");
    }
}
