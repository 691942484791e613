//! The removal rate along a program over windows of its path (seed 004 §3.2's measure, taken
//! by the project's own simulation rather than the pixel map a strategy plans on): the
//! program's moves cut into short pieces, simulated on a dexel stock, and the volume each
//! piece removed summed over consecutive stretches of at least `ds` of cutting at one height.
//! Entries (helices, ramps and a ramp's way back along the path to where it began) are left out.

use super::program::ProgramMove;
use super::verify::Simulator;
use crate::error::Result;
use crate::geom::{Aabb, DVec2, Tolerances};
use crate::progress::Progress;
use crate::toolpath::{arc_sweep, Move};

/// The removal rate (mm³/min) over each window of at least `ds` mm of the level cutting moves
/// of `moves`, simulated on a stock of `cell` mm over `stock`.
pub fn windowed_rates(moves: &[ProgramMove], stock: &Aabb, cell: f64, ds: f64) -> Result<Vec<f64>> {
    Ok(windowed_runs(moves, stock, cell, ds)?.concat())
}

/// [`windowed_rates`] by runs: the windows of each stretch of level moves between two moves
/// that are not (a rapid, an entry, a step down), in order; a run shorter than `ds` has none.
pub fn windowed_runs(moves: &[ProgramMove], stock: &Aabb, cell: f64, ds: f64) -> Result<Vec<Vec<f64>>> {
    let mut pieces: Vec<(ProgramMove, bool)> = Vec::new();
    // Where the current descent began, while the tool descends, and after it.
    let mut descent: Option<DVec2> = None;
    let mut began = None;
    for m in moves {
        let level = !m.mv.is_rapid() && (m.mv.to().z - m.from.z).abs() < 1e-9;
        let back = level && descent.is_some_and(|a| m.mv.to().truncate().distance(a) < 1e-9);
        let counted = level && !back;
        if !m.mv.is_rapid() && m.mv.to().z < m.from.z - 1e-9 {
            began = began.or(Some(m.from.truncate()));
            descent = began;
        } else {
            began = None;
            if level {
                descent = None;
            }
        }
        let len = m.mv.length(m.from);
        let n = if m.mv.is_rapid() { 1 } else { (len / (0.25 * ds)).ceil().max(1.0) as usize };
        let mut from = m.from;
        for k in 1..=n {
            let t = k as f64 / n as f64;
            let (mv, to) = match m.mv {
                Move::Line { to, feed } => {
                    let p = if k == n { to } else { m.from.lerp(to, t) };
                    (Move::Line { to: p, feed }, p)
                }
                Move::Arc { to, center, clockwise, feed } => {
                    let sweep = arc_sweep(m.from, to, center, clockwise);
                    let a = (m.from.truncate() - center).to_angle() + sweep * t;
                    let r = m.from.truncate().distance(center);
                    let p = if k == n { to } else { (center + DVec2::from_angle(a) * r).extend(m.from.z + (to.z - m.from.z) * t) };
                    (Move::Arc { to: p, center, clockwise, feed }, p)
                }
                Move::Rapid { to } => (Move::Rapid { to }, to),
            };
            pieces.push((ProgramMove { from, mv, seconds: m.seconds / n as f64, ..m.clone() }, counted));
            from = to;
        }
    }
    let all: Vec<ProgramMove> = pieces.iter().map(|p| p.0.clone()).collect();
    let mut sim = Simulator::new(stock, cell)?;
    sim.run(&all, &Tolerances::DEFAULT, &mut Progress::none(), 1.0)?;
    let mut runs = vec![Vec::new()];
    let (mut vol, mut len, mut minutes) = (0.0, 0.0, 0.0);
    for ((m, counted), v) in pieces.iter().zip(sim.volumes()) {
        if !counted {
            (vol, len, minutes) = (0.0, 0.0, 0.0);
            if runs.last().is_some_and(|run| !run.is_empty()) {
                runs.push(Vec::new());
            }
            continue;
        }
        vol += v;
        len += m.mv.length(m.from);
        minutes += m.seconds / 60.0;
        if len >= ds - 1e-9 {
            runs.last_mut().expect("a run").push(vol / minutes);
            (vol, len, minutes) = (0.0, 0.0, 0.0);
        }
    }
    runs.retain(|run| !run.is_empty());
    Ok(runs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutter::Cutter;
    use crate::job::{Job, Tool};
    use crate::post::read::read_gcode;
    use crate::sim::program::program_moves;
    use glam::DVec3;

    /// Two slots at one height, a rapid between: two runs of windows, and inside the stock each
    /// window's rate is a full slot's, D × ap × feed.
    #[test]
    fn a_rapid_between_two_slots_makes_two_runs_each_a_full_slot_inside() {
        let tool = Tool { number: 1, cutter: Cutter::flat(6.0), ..Tool::default() };
        let program = "G0 X-5 Y5 Z12\nG1 Z8 F500\nG1 X15 F1000\nG0 Z12\nG0 X-5 Y15\nG1 Z8 F500\nG1 X15 F1000\nG0 Z12\n";
        let paths = read_gcode(program, 1).unwrap();
        let job = Job::default();
        let moves = program_moves(&paths, &[tool], job.rapids(), job.air_feed()).unwrap();
        let stock = Aabb { min: DVec3::ZERO, max: DVec3::new(40.0, 20.0, 10.0) };
        let runs = windowed_runs(&moves, &stock, 0.05, 2.0).unwrap();
        assert_eq!(runs.iter().map(Vec::len).collect::<Vec<_>>(), [10, 10]);
        assert_eq!(windowed_rates(&moves, &stock, 0.05, 2.0).unwrap(), runs.concat());
        let slot = 6.0 * 2.0 * 1000.0;
        for run in &runs {
            // Windows k = 4.. span x in [3, 15]: the tool's whole front in the stock.
            for &rate in &run[4..] {
                assert!((rate / slot - 1.0).abs() < 0.02, "{rate} against {slot}");
            }
            // Entering the stock, less.
            assert!(run[0] < 0.5 * slot);
        }
    }
}
