//! A program as the simulation walks it: every move with where it starts, the cutter doing it,
//! and when it runs; and the simulation of those moves on a stock model, with the volume each
//! one removed (its material removal rate, MRR, is that volume over its duration).

use super::sweep::Sweep;
use super::StockModel;
use crate::cutter::Cutter;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::progress::Progress;
use crate::tool::Tool;
use crate::toolpath::{Move, Rapids, Toolpath};

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
    /// A feed move faster than its tool's feed: one its operation knew to cut nothing (the air
    /// feed, [`crate::machining::air`]), held to that as a rapid is.
    pub air: bool,
    /// Its tool's holder as rings `(radius, rise above the tip)` ([`crate::tool::Holder::rings`]).
    pub holder: Option<std::sync::Arc<Vec<(f64, f64)>>>,
}

/// The moves of `paths`, each with its tool from `tools`, timed at their feeds and `rapids`;
/// a feed move faster than its tool's feed and at `air_feed` or above is one in air
/// ([`ProgramMove::air`]; a cut the feed optimisation sped up, [`crate::sim::feeds`], stays
/// under it).
pub fn program_moves(paths: &[Toolpath], tools: &[Tool], rapids: Rapids, air_feed: f64) -> Result<Vec<ProgramMove>> {
    let mut out = Vec::new();
    let mut clock = 0.0;
    for (k, path) in paths.iter().enumerate() {
        let tool = tools.iter().find(|t| t.number == path.tool).ok_or_else(|| Error::Input(format!("the program uses tool number {}, which is not in the tool library", path.tool)))?;
        let holder = tool.holder_rings();
        let mut at = path.start;
        // A drilling cycle's dwell at the bottom counts in the move that reached it.
        let dwells: std::collections::HashMap<usize, f64> = path.cycles.iter().filter(|c| c.kind == crate::toolpath::cycle::CycleKind::Dwell).map(|c| (c.bottom_move(), c.dwell)).collect();
        for (i, mv) in path.moves.iter().enumerate() {
            let (seconds, air) = match *mv {
                Move::Rapid { to } => (rapids.seconds(at, to), false),
                Move::Line { feed, .. } | Move::Arc { feed, .. } => (mv.length(at) / feed * 60.0, feed > tool.feed_rate * (1.0 + 1e-9) && feed >= air_feed * (1.0 - 1e-9)),
            };
            let seconds = seconds + dwells.get(&i).copied().unwrap_or(0.0);
            out.push(ProgramMove { path: k, tool: tool.number, cutter: tool.cutter.clone(), from: at, mv: *mv, start: clock, seconds, air, holder: holder.clone() });
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

    /// The lowest and highest y any part of the tool reaches during the move, its body above
    /// the flutes included.
    pub fn y_span(&self) -> (f64, f64) {
        let reach = self.cutter.diameter.max(self.cutter.shank_diameter.unwrap_or(0.0)) * 0.5;
        let (lo, hi) = match self.mv {
            Move::Rapid { to } | Move::Line { to, .. } => (self.from.y.min(to.y), self.from.y.max(to.y)),
            Move::Arc { center, .. } => {
                let r = (self.from.truncate() - center).length();
                (center.y - r, center.y + r)
            }
        };
        (lo - reach, hi + reach)
    }

    /// What timing its removal rate needs of it ([`removal_rates`]).
    pub fn timing(&self) -> Timing {
        Timing { length: self.mv.length(self.from), seconds: self.seconds, rapid: self.mv.is_rapid() }
    }
}

/// A move's length (mm), duration (s) and kind, as [`removal_rates`] takes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    pub length: f64,
    pub seconds: f64,
    pub rapid: bool,
}

/// Cells of path over which a move's material removal rate is measured. The simulation knows
/// volume cell by cell: a move shorter than a cell is credited with the whole columns of the
/// cells whose centres it uncovers, so its volume over its own duration is no rate at all (a
/// 0.0001 mm step of a raster pass "removing" 0.08 mm³ read as 775,000 mm³/min where the
/// cut runs at 6,000). Over ten cells of path the cells at the window's two ends are within a
/// tenth or so of the volume, and the rate is the cut's.
pub const RATE_CELLS: f64 = 10.0;

/// The material removal rate (mm³/min) of each of `moves` that removed `volumes` (as many):
/// the volume removed along `span` mm of its run of feed moves centred on the move's middle
/// (the whole run where the run is shorter), over the time that stretch takes; 0 for rapids.
pub fn removal_rates(moves: &[Timing], volumes: &[f64], span: f64) -> Vec<f64> {
    let mut rates = vec![0.0; moves.len()];
    let mut k = 0;
    while k < moves.len() {
        if moves[k].rapid {
            k += 1;
            continue;
        }
        let end = (k..moves.len()).find(|&e| moves[e].rapid).unwrap_or(moves.len());
        // Lengths, volumes and times summed along the run, at the moves' ends.
        let (mut at, mut vol, mut time) = (vec![0.0], vec![0.0], vec![0.0]);
        for (m, v) in moves[k..end].iter().zip(&volumes[k..end]) {
            at.push(at.last().unwrap() + m.length);
            vol.push(vol.last().unwrap() + v);
            time.push(time.last().unwrap() + m.seconds);
        }
        let total = *at.last().unwrap();
        // Volume and time up to `s` mm along the run, each move taken as even along its length.
        let upto = |s: f64| {
            let i = at.partition_point(|&a| a <= s).clamp(1, at.len() - 1) - 1;
            let f = if at[i + 1] > at[i] { ((s - at[i]) / (at[i + 1] - at[i])).clamp(0.0, 1.0) } else { 1.0 };
            (vol[i] + f * (vol[i + 1] - vol[i]), time[i] + f * (time[i + 1] - time[i]))
        };
        for i in 0..end - k {
            let (a, b) = if total <= span {
                (0.0, total)
            } else {
                let lo = (0.5 * (at[i] + at[i + 1]) - 0.5 * span).clamp(0.0, total - span);
                (lo, lo + span)
            };
            let ((v0, t0), (v1, t1)) = (upto(a), upto(b));
            rates[k + i] = if t1 > t0 { (v1 - v0) / (t1 - t0) * 60.0 } else { 0.0 };
        }
        k = end;
    }
    rates
}

/// Numbers per move in [`encode`]'s flat form.
const ENCODED: usize = 12;

/// `moves` as flat numbers, for a worker of the page's pool that cuts them into its bands of
/// the stock ([`decode`] reads them back): per move its tool number, its kind (0 rapid, 1 line,
/// 2 clockwise arc, 3 counter-clockwise arc), where it starts and ends, an arc's centre, the
/// feed, and how long it takes.
pub fn encode(moves: &[ProgramMove]) -> Vec<f64> {
    let mut out = Vec::with_capacity(moves.len() * ENCODED);
    for m in moves {
        let (kind, centre, feed) = match m.mv {
            Move::Rapid { .. } => (0.0, [0.0; 2], 0.0),
            Move::Line { feed, .. } => (1.0, [0.0; 2], feed),
            Move::Arc { center, clockwise, feed, .. } => (if clockwise { 2.0 } else { 3.0 }, center.to_array(), feed),
        };
        let to = m.mv.to();
        out.extend([m.tool as f64, kind, m.from.x, m.from.y, m.from.z, to.x, to.y, to.z, centre[0], centre[1], feed, m.seconds]);
    }
    out
}

/// The moves [`encode`] wrote, each with its tool's cutter from `tools` (their paths and start
/// times are not kept: a band's cut does not need them).
pub fn decode(flat: &[f64], tools: &[Tool]) -> Result<Vec<ProgramMove>> {
    if flat.len() % ENCODED != 0 {
        return Err(Error::Input(format!("{} numbers are not whole moves of {ENCODED}", flat.len())));
    }
    flat.chunks_exact(ENCODED)
        .map(|v| {
            let tool = tools.iter().find(|t| t.number as f64 == v[0]).ok_or_else(|| Error::Input(format!("the moves name tool {}, which is not in the tool library", v[0])))?;
            let to = DVec3::new(v[5], v[6], v[7]);
            let center = crate::geom::DVec2::new(v[8], v[9]);
            let mv = match v[1] as u8 {
                0 => Move::Rapid { to },
                1 => Move::Line { to, feed: v[10] },
                2 | 3 => Move::Arc { to, center, clockwise: v[1] == 2.0, feed: v[10] },
                _ => return Err(Error::Input(format!("no move is of kind {}", v[1]))),
            };
            Ok(ProgramMove { path: 0, tool: tool.number, cutter: tool.cutter.clone(), from: DVec3::new(v[2], v[3], v[4]), mv, start: 0.0, seconds: v[11], air: false, holder: tool.holder_rings() })
        })
        .collect()
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
