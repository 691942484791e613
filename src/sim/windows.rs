//! The removal rate along a program over windows of its path (seed 004 §3.2's measure, taken
//! by the project's own simulation rather than the pixel map a strategy plans on): the
//! program's moves cut into short pieces, simulated on a dexel stock, and the volume each
//! piece removed summed over consecutive stretches of at least `ds` of cutting at one height.
//! Entries (helices and a helix's floor, ramps and a ramp's way back along the path to where it
//! began) are left out.

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
    let pieces = pieces(moves, 0.25 * ds);
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

/// `moves` cut into pieces of at most `most` mm (a rapid whole), each marked where it counts:
/// a level cutting move, not a ramp's way back along the path to where it began nor a helix's
/// floor (the circle round to where its descent ended).
fn pieces(moves: &[ProgramMove], most: f64) -> Vec<(ProgramMove, bool)> {
    let level = |m: &ProgramMove| !m.mv.is_rapid() && (m.mv.to().z - m.from.z).abs() < 1e-9;
    let descends = |m: &ProgramMove| !m.mv.is_rapid() && m.mv.to().z < m.from.z - 1e-9;
    // A helix's floor: the level moves straight after a descent that come back round to where
    // it ended within a circle of twice the tool's diameter.
    let mut floor = vec![false; moves.len()];
    for (k, m) in moves.iter().enumerate().filter(|(k, m)| descends(m) && moves.get(k + 1).is_some_and(level)) {
        let (end, most) = (m.mv.to().truncate(), 2.0 * std::f64::consts::TAU * m.cutter.diameter);
        let mut length = 0.0;
        for (j, n) in moves.iter().enumerate().skip(k + 1).take_while(|(_, n)| level(n)) {
            length += n.mv.length(n.from);
            if length > most {
                break;
            }
            if n.mv.to().truncate().distance(end) < 1e-6 {
                floor[k + 1..=j].fill(true);
                break;
            }
        }
    }
    let mut pieces: Vec<(ProgramMove, bool)> = Vec::new();
    // Where the current descent began, while the tool descends, and after it.
    let mut descent: Option<DVec2> = None;
    let mut began = None;
    for (k, m) in moves.iter().enumerate() {
        let level = level(m);
        let back = level && descent.is_some_and(|a| m.mv.to().truncate().distance(a) < 1e-9);
        let counted = level && !back && !floor[k];
        if descends(m) {
            began = began.or(Some(m.from.truncate()));
            descent = began;
        } else {
            began = None;
            if level {
                descent = None;
            }
        }
        let len = m.mv.length(m.from);
        let n = if m.mv.is_rapid() { 1 } else { (len / most).ceil().max(1.0) as usize };
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
    pieces
}

/// The engagement along the level cutting of `moves` as issue 59 defines it, on a stock of
/// `cell` mm over `stock`: at the end of each piece of at most `most` mm, before the piece
/// cuts, the angle of the front half of the tool's circle standing in the material the stock
/// still holds above the move's height, the pass's own cut so far subtracted, sampled at
/// the points [`crate::machining::adaptive::front_half`] gives. The last two tool diameters of level
/// pieces are kept off the stock and subtracted exactly (a point within the radius of one at
/// its height or below is cut): the cells the piece just before cut would otherwise take a
/// few degrees off the side of every sample. By runs as [`windowed_runs`] makes them: each
/// piece's length and angle (radians).
pub fn engagement_runs(moves: &[ProgramMove], stock: &Aabb, cell: f64, most: f64, tolerances: &Tolerances) -> Result<Vec<Vec<(f64, f64)>>> {
    let front = crate::machining::adaptive::front_half();
    let mut stock = super::verify::stock_for(stock, cell)?;
    let chordal = tolerances.simulated_chordal();
    let mut runs = vec![Vec::new()];
    // The level pieces not yet on the stock (oldest first), and their length.
    let mut recent: std::collections::VecDeque<ProgramMove> = std::collections::VecDeque::new();
    let mut held = 0.0;
    for (m, counted) in pieces(moves, most) {
        if counted {
            let (a, b) = (m.from.truncate(), m.mv.to().truncate());
            let d = match m.mv {
                Move::Arc { center, clockwise, .. } => {
                    let radial = (b - center).normalize_or_zero();
                    if clockwise {
                        -radial.perp()
                    } else {
                        radial.perp()
                    }
                }
                _ => (b - a).normalize_or_zero(),
            };
            if d != DVec2::ZERO {
                let (r, z) = (0.5 * m.cutter.diameter, m.mv.to().z);
                let slack = crate::geom::tolerance::MATERIAL_SLACK;
                let cut_by_recent = |q: DVec2| {
                    recent.iter().any(|p| {
                        let (pa, pb) = (p.from.truncate(), p.mv.to().truncate());
                        p.mv.to().z <= z + slack && crate::geom::segment::Segment::line(pa, pb).distance_with(None, q) <= 0.5 * p.cutter.diameter
                    })
                };
                let inside = front.iter().map(|&u| b + d.rotate(u) * r).filter(|&q| stock.top_near(q).is_some_and(|top| top > z + slack) && !cut_by_recent(q)).count();
                runs.last_mut().expect("a run").push((m.mv.length(m.from), std::f64::consts::PI * inside as f64 / front.len() as f64));
            }
            held += m.mv.length(m.from);
            recent.push_back(m);
            while held > 4.0 * recent.front().map_or(0.0, |p| p.cutter.diameter) {
                let old = recent.pop_front().expect("a piece");
                held -= old.mv.length(old.from);
                old.cut(&mut stock, chordal);
            }
            continue;
        }
        if runs.last().is_some_and(|run| !run.is_empty()) {
            runs.push(Vec::new());
        }
        m.cut(&mut stock, chordal);
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

    /// `program`'s moves with a φ6 flat end, and a 40 × 20 × 10 block of stock at the origin.
    fn slots(program: &str) -> (Vec<ProgramMove>, Aabb) {
        let tool = Tool { number: 1, cutter: Cutter::flat(6.0), ..Tool::default() };
        let job = Job::default();
        let moves = program_moves(&read_gcode(program, 1).unwrap(), &[tool], job.rapids(), job.air_feed()).unwrap();
        (moves, Aabb { min: DVec3::ZERO, max: DVec3::new(40.0, 20.0, 10.0) })
    }

    /// Two slots at one height, a rapid between: two runs of windows, and inside the stock each
    /// window's rate is a full slot's, D × ap × feed.
    #[test]
    fn a_rapid_between_two_slots_makes_two_runs_each_a_full_slot_inside() {
        let (moves, stock) = slots("G0 X-5 Y5 Z12\nG1 Z8 F500\nG1 X15 F1000\nG0 Z12\nG0 X-5 Y15\nG1 Z8 F500\nG1 X15 F1000\nG0 Z12\n");
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

    /// A helix's floor (the level circle back round to where it ended) is the entry's, not
    /// cutting to count: after it, only the way out counts.
    #[test]
    fn a_helix_floor_is_left_out_with_the_helix() {
        let (moves, stock) = slots("G0 X20 Y10 Z12\nG1 Z10.5 F500\nG3 X16 Y10 Z10 I-2 J0 F1000\nG3 X20 Y10 Z9.5 I2 J0\nG3 X16 Y10 I-2 J0\nG3 X20 Y10 I2 J0\nG1 X35\nG0 Z12\n");
        // The way out is 15 mm: 7 windows of 2 (the floor's 12.6 mm would make 13).
        assert_eq!(windowed_runs(&moves, &stock, 0.05, 2.0).unwrap().iter().map(Vec::len).collect::<Vec<_>>(), [7]);
        let runs = engagement_runs(&moves, &stock, 0.05, 0.25, &crate::geom::Tolerances::DEFAULT).unwrap();
        assert!((runs.concat().iter().map(|p| p.0).sum::<f64>() - 15.0).abs() < 1e-9);
    }

    /// A straight cut `ae` deep into a wall engages `arccos(1 − 2·ae/D)`: 53.13° for a φ6 at
    /// 1.2 mm, within 1.6° (a sample is 1.5°); a second pass along the same line cuts air.
    #[test]
    fn a_straight_cut_into_a_wall_engages_its_closed_form_angle() {
        // The material (y < 20) on the right of a pass along +x whose centre runs at 20 + r − ae.
        let (moves, stock) = slots("G0 X-5 Y21.8 Z12\nG1 Z8 F500\nG1 X35 F1000\nG0 Z12\nG0 X-5\nG1 Z8 F500\nG1 X35 F1000\nG0 Z12\n");
        let runs = engagement_runs(&moves, &stock, 0.05, 0.25, &crate::geom::Tolerances::DEFAULT).unwrap();
        assert_eq!(runs.len(), 2);
        let exact = (1.0 - 2.0 * 1.2 / 6.0_f64).acos();
        // x from 5 to 30: the tool's whole front in the stock.
        let steady = |run: &[(f64, f64)]| {
            run.iter()
                .scan(-5.0, |x, &(len, angle)| {
                    *x += len;
                    Some((*x, angle))
                })
                .filter(|&(x, _)| (5.0..30.0).contains(&x))
                .map(|(_, a)| a)
                .collect::<Vec<_>>()
        };
        let first = steady(&runs[0]);
        assert!(first.len() > 90);
        for a in first {
            assert!((a - exact).abs() < 1.6f64.to_radians(), "{:.2}° against {:.2}°", a.to_degrees(), exact.to_degrees());
        }
        assert!(steady(&runs[1]).iter().all(|&a| a == 0.0), "the second pass finds the material it cut");
    }
}
