//! Keeping clear of what holds the stock ([`crate::job::fixtures`]) the operations that plan
//! without it: facing, the 2D operations and the hole operations cut where their settings and
//! the drawing say, not on the CL surface the 3D ones are dropped onto (where the fixtures join
//! the part). Their paths are walked as the verification walks them
//! ([`crate::sim::fixtures::depth_into`], at points [`crate::sim::fixtures::sample_step`]
//! apart): a cut that would come into a fixture's clearance lifts over it at the clearance
//! height and comes back down where it is clear, like a tab; a drilling cycle whose hole would
//! reach into one is left out whole. What was lifted over or left out is given back for the
//! operation to say.

use crate::cutter::Cutter;
use crate::geom::{DVec2, DVec3};
use crate::job::fixtures::Held;
use crate::sim::fixtures::{along, depth_into, sample_step};
use crate::toolpath::{arc_sweep, Move, Toolpath};

/// The heights a path lifts over the fixtures at.
#[derive(Clone, Copy, Debug)]
pub struct Over {
    /// Rapids over a fixture run here: above every fixture and the stock.
    pub clearance: f64,
    /// The stock's top: a descent back into the cut is rapid down to `gap` above it.
    pub top: f64,
    pub gap: f64,
    /// The feed of the descent into the cut (mm/min).
    pub plunge: f64,
}

/// What keeping a path clear did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cleared {
    /// Where a cut lifted over a fixture, each with the fixture's name.
    pub lifted: Vec<(String, DVec3)>,
    /// The holes whose cycles were left out, each with the fixture's name.
    pub skipped: Vec<(String, DVec2)>,
}

/// The fixture whose clearance the tool at `p` comes into (within `near`), if any.
fn hit<'a>(c: &Cutter, p: DVec3, keep_out: &'a [Held], near: f64) -> Option<&'a Held> {
    keep_out.iter().find(|h| depth_into(c, p, &h.solid) > -near)
}

/// Whether move `m` from `from` cannot come near any fixture: its box, grown by the tool's
/// reach, misses them all.
fn far(c: &Cutter, from: DVec3, m: &Move, keep_out: &[Held], near: f64) -> bool {
    let (lo, hi) = m.bounds(from);
    let reach = c.diameter.max(c.shank_diameter.unwrap_or(0.0)) / 2.0 + near;
    keep_out.iter().all(|h| {
        let b = &h.solid;
        lo.z >= b.max.z + near || lo.x > b.max.x + reach || hi.x < b.min.x - reach || lo.y > b.max.y + reach || hi.y < b.min.y - reach
    })
}

/// The piece of move `m` (from its start) that ends at `to`, started at `at`: a line, or an
/// arc about the same centre (a line where the piece is too short to tell its sweep).
fn piece(m: &Move, at: DVec3, to: DVec3) -> Move {
    match *m {
        Move::Arc { center, clockwise, feed, .. } if at.truncate().distance(to.truncate()) > 1e-4 && arc_sweep(at, to, center, clockwise).abs() < std::f64::consts::TAU - 1e-9 => {
            Move::Arc { to, center, clockwise, feed }
        }
        Move::Arc { feed, .. } | Move::Line { feed, .. } => Move::Line { to, feed },
        Move::Rapid { .. } => Move::Rapid { to },
    }
}

/// Keeps `path`, cut by `cutter`, clear of `keep_out` (each fixture grown by its clearance): a
/// feed move that would come into one lifts over it at `over.clearance` and comes back down
/// where the tool is clear; a drilling cycle that would is left out whole. Rapids are kept as
/// they are (the verification still judges them).
pub fn keep_clear(path: &mut Toolpath, cutter: &Cutter, keep_out: &[Held], over: Over) -> Cleared {
    let mut cleared = Cleared::default();
    if keep_out.is_empty() {
        return cleared;
    }
    // A point this near a clearance counts as in it: the verification judges the moves at
    // other points the same distance apart.
    let near = sample_step(cutter);
    let moves = std::mem::take(&mut path.moves);
    let cycles = std::mem::take(&mut path.cycles);
    let mut out: Vec<Move> = Vec::with_capacity(moves.len());
    // Where the tool stands in the program as written, and in the one made.
    let (mut at, mut pos) = (path.start, path.start);
    let mut lifted = false;
    let mut i = 0;
    while i < moves.len() {
        if let Some(cycle) = cycles.iter().find(|c| c.first == i && c.count > 0) {
            let span = &moves[i..i + cycle.count];
            let mut from = at;
            let mut blocked = None;
            for (j, m) in span.iter().enumerate() {
                // Lifted, the tool comes to the hole at the clearance height, not as written.
                let judged = j > 0 || !lifted;
                if judged && blocked.is_none() && !far(cutter, from, m, keep_out, near) {
                    let n = (m.length(from) / near).ceil().max(1.0) as usize;
                    blocked = (0..=n).find_map(|j| hit(cutter, along(from, m, j as f64 / n as f64), keep_out, near));
                }
                from = m.to();
            }
            if let Some(h) = blocked {
                cleared.skipped.push((h.name.clone(), cycle.at));
                // The next hole is come to from the clearance height, over the one left out.
                if !lifted && pos.z < over.clearance {
                    pos.z = over.clearance;
                    out.push(Move::Rapid { to: pos });
                }
                lifted = true;
            } else if lifted {
                // The cycle starts where the tool stands: at the clearance height.
                let c = crate::toolpath::cycle::Cycle { first: out.len(), initial: over.clearance, ..*cycle };
                let made = c.moves();
                path.cycles.push(crate::toolpath::cycle::Cycle { count: made.len(), ..c });
                out.extend(made);
                pos = out.last().map_or(pos, Move::to);
                lifted = false;
            } else {
                path.cycles.push(crate::toolpath::cycle::Cycle { first: out.len(), ..*cycle });
                out.extend_from_slice(span);
                pos = from;
            }
            at = from;
            i += cycle.count;
            continue;
        }
        let m = moves[i];
        i += 1;
        let to = m.to();
        if m.is_rapid() {
            if lifted {
                out.push(Move::Rapid { to: to.truncate().extend(over.clearance) });
                lifted = false;
            }
            out.push(m);
            (at, pos) = (to, to);
            continue;
        }
        if !lifted && far(cutter, at, &m, keep_out, near) {
            out.push(m);
            (at, pos) = (to, to);
            continue;
        }
        let n = (m.length(at) / near).ceil().max(1.0) as usize;
        for j in 0..=n {
            let p = along(at, &m, j as f64 / n as f64);
            match (lifted, hit(cutter, p, keep_out, near)) {
                (false, Some(h)) => {
                    if j > 0 {
                        let last = along(at, &m, (j - 1) as f64 / n as f64);
                        if last.distance(pos) > 1e-9 {
                            out.push(piece(&m, pos, last));
                        }
                        pos = last;
                    }
                    cleared.lifted.push((h.name.clone(), pos));
                    out.push(Move::Rapid { to: pos.truncate().extend(over.clearance) });
                    lifted = true;
                }
                (true, None) => {
                    out.push(Move::Rapid { to: p.truncate().extend(over.clearance) });
                    let down = over.top + over.gap;
                    if down > p.z && down < over.clearance {
                        out.push(Move::Rapid { to: p.truncate().extend(down) });
                    }
                    out.push(Move::Line { to: p, feed: over.plunge });
                    pos = p;
                    lifted = false;
                }
                _ => {}
            }
        }
        if !lifted && to.distance(pos) > 1e-9 {
            out.push(piece(&m, pos, to));
            pos = to;
        }
        at = to;
    }
    if lifted {
        out.push(Move::Rapid { to: at.truncate().extend(over.clearance) });
    }
    path.moves = out;
    cleared
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Aabb;
    use crate::sim::fixtures::collisions;
    use crate::sim::program::ProgramMove;

    fn program(path: &Toolpath, cutter: &Cutter) -> Vec<ProgramMove> {
        let mut at = path.start;
        path.moves
            .iter()
            .map(|&mv| {
                let m = ProgramMove { path: 0, tool: path.tool, cutter: cutter.clone(), from: at, mv, start: 0.0, seconds: 0.0, air: false, holder: None };
                at = mv.to();
                m
            })
            .collect()
    }

    #[test]
    fn a_cut_lifts_over_a_clamp_and_comes_back_down_beyond_it() {
        let cutter = Cutter { flute_length: 20.0, ..Cutter::flat(6.0) };
        let clamp = Held::solid("clamp", Aabb { min: DVec3::new(20.0, -5.0, -10.0), max: DVec3::new(30.0, 5.0, 8.0) });
        let keep_out = [clamp];
        let start = DVec3::new(0.0, 0.0, 25.0);
        let moves = vec![
            Move::Rapid { to: DVec3::new(0.0, 0.0, 1.0) },
            Move::Line { to: DVec3::new(0.0, 0.0, -2.0), feed: 300.0 },
            Move::Line { to: DVec3::new(50.0, 0.0, -2.0), feed: 1000.0 },
            Move::Arc { to: DVec3::new(50.0, 0.0, -2.0), center: DVec2::new(40.0, 0.0), clockwise: false, feed: 1000.0 },
            Move::Rapid { to: DVec3::new(50.0, 0.0, 25.0) },
        ];
        let mut path = Toolpath { name: "profile".into(), tool: 1, spindle_rpm: 10000.0, start, moves, cycles: Vec::new() };
        let before = program(&path, &cutter);
        assert!(!collisions(&before, &keep_out, 0.0).is_empty(), "the test's path must run into the clamp");
        let over = Over { clearance: 25.0, top: 0.0, gap: 1.0, plunge: 300.0 };
        let cleared = keep_clear(&mut path, &cutter, &keep_out, over);
        let after = program(&path, &cutter);
        assert!(collisions(&after, &keep_out, 0.0).is_empty(), "{:?}", collisions(&after, &keep_out, 0.0));
        // It lifted twice: along the line, and on the arc round (40, 0) of radius 10.
        assert_eq!(cleared.lifted.len(), 2, "{cleared:?}");
        assert!((cleared.lifted[0].1.x - 17.0).abs() < 0.1, "{:?}", cleared.lifted[0]);
        // The tool comes back to the line's end and the arc's, and keeps cutting at -2 where
        // it is clear: the feed beyond the clamp is still there.
        let cut: f64 = after.iter().filter(|m| !m.mv.is_rapid() && m.from.z == -2.0 && m.mv.to().z == -2.0).map(|m| m.mv.length(m.from)).sum();
        let whole = 50.0 + std::f64::consts::TAU * 10.0;
        assert!(cut > 17.0 + 17.0 && cut < whole - 16.0 - 5.0, "{cut}");
        assert_eq!(path.moves.last().unwrap().to(), DVec3::new(50.0, 0.0, 25.0));
    }
}
