//! Reads G-code back into tool paths, so programs swarf did not write can be simulated and
//! verified. It knows what the dialects of [`super::Dialect`] write and the common words around
//! them: G0–G3 (arcs by I/J or R, in the XY plane), G17, G20/G21, G90/G91, G90.1/G91.1, G94,
//! feeds, tool changes (T, M6), spindle and coolant words, comments, and the drilling cycles
//! G81, G82, G83 and G73 with G98/G99 and G80 (read into the moves LinuxCNC makes of them,
//! [`crate::toolpath::cycle`]; G82's P in seconds, or in milliseconds in a program with an O
//! number, as Fanuc's). What it cannot simulate faithfully (other planes, cutter compensation,
//! other canned cycles, machine coordinates, rotary axes, inverse-time feed) is refused with
//! the line number, never skipped silently.

use crate::geom::{DVec2, DVec3};
use crate::toolpath::cycle::{Cycle, CycleKind};
use crate::toolpath::{Move, Toolpath};

/// Why a program could not be read.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[error("G-code line {line}: {message}")]
pub struct ReadError {
    pub line: usize,
    pub message: String,
}

/// Largest difference between an arc's start and end radius (mm) that is taken as rounding
/// (LinuxCNC's own limit is of this order).
const ARC_RADIUS_SLACK: f64 = 0.01;

struct State {
    scale: f64,
    incremental: bool,
    arc_incremental: bool,
    motion: Option<u32>,
    feed: Option<f64>,
    spindle: f64,
    selected: Option<u32>,
    position: [Option<f64>; 3],
    /// G98 (back to the starting height after a drilling cycle) rather than G99 (to R).
    to_initial: bool,
    /// A drilling cycle's sticky words: R, the bottom Z, Q and P (in mm and as written).
    cycle_r: Option<f64>,
    cycle_z: Option<f64>,
    cycle_q: Option<f64>,
    cycle_p: Option<f64>,
}

/// The program's tool paths: a new one at each tool change. `default_tool` is used until the
/// program selects one (GRBL programs never do).
pub fn read_gcode(text: &str, default_tool: u32) -> Result<Vec<Toolpath>, ReadError> {
    let mut st = State {
        scale: 1.0,
        incremental: false,
        arc_incremental: true,
        motion: None,
        feed: None,
        spindle: 0.0,
        selected: None,
        position: [None; 3],
        to_initial: true,
        cycle_r: None,
        cycle_z: None,
        cycle_q: None,
        cycle_p: None,
    };
    let dwell_in_millis = text.lines().any(|l| l.trim_start().strip_prefix('O').is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit())));
    let mut paths: Vec<Toolpath> = Vec::new();
    let mut tool = default_tool;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let err = |message: String| ReadError { line, message };
        let words = words(raw).map_err(err)?;
        if words.is_empty() {
            continue;
        }
        let mut axes: [Option<f64>; 3] = [None; 3];
        let (mut i, mut j, mut r) = (None, None, None);
        let (mut q, mut p) = (None, None);
        let mut motion_word = None;
        let mut change_tool = false;
        let mut end = false;
        for &(letter, value) in &words {
            match letter {
                'G' => {
                    let code = (value * 10.0).round() as u32;
                    match code {
                        0 | 10 | 20 | 30 => motion_word = Some(code / 10),
                        800 => st.motion = None,
                        170 | 400 | 490 | 430 | 940 | 540..=590 | 610 | 640 | 40 => {}
                        200 => st.scale = 25.4,
                        210 => st.scale = 1.0,
                        900 => st.incremental = false,
                        910 => st.incremental = true,
                        901 => st.arc_incremental = false,
                        911 => st.arc_incremental = true,
                        180 | 190 => return Err(err("arcs outside the XY plane (G18/G19) are not simulated".into())),
                        410 | 420 => return Err(err("cutter radius compensation (G41/G42) is not simulated; post the program with compensation off".into())),
                        810 | 820 | 830 | 730 => motion_word = Some(code / 10),
                        980 => st.to_initial = true,
                        990 => st.to_initial = false,
                        840..=890 | 760 => return Err(err(format!("canned cycle G{value} is not simulated"))),
                        280 | 300 | 530 | 920 => return Err(err(format!("G{value} moves in machine or offset coordinates, which are not simulated"))),
                        930 => return Err(err("inverse-time feed (G93) is not simulated".into())),
                        _ => return Err(err(format!("G{value} is not understood"))),
                    }
                }
                'M' => match value as u32 {
                    6 => change_tool = true,
                    2 | 30 => end = true,
                    0 | 1 | 3 | 4 | 5 | 7 | 8 | 9 => {}
                    other => return Err(err(format!("M{other} is not understood"))),
                },
                'X' => axes[0] = Some(value),
                'Y' => axes[1] = Some(value),
                'Z' => axes[2] = Some(value),
                'I' => i = Some(value),
                'J' => j = Some(value),
                'R' => r = Some(value),
                'F' => st.feed = Some(value),
                'S' => st.spindle = value,
                'T' => st.selected = Some(value as u32),
                'Q' => q = Some(value),
                'P' => p = Some(value),
                'H' | 'D' | 'N' | 'O' | 'K' => {}
                'A' | 'B' | 'C' | 'U' | 'V' | 'W' => return Err(err(format!("the {letter} axis is not simulated (3-axis only)"))),
                other => return Err(err(format!("the word {other} is not understood"))),
            }
        }
        if change_tool {
            tool = st.selected.unwrap_or(tool);
            paths.push(empty_path(tool, st.spindle));
        }
        if let Some(m) = motion_word {
            st.motion = Some(m);
        }
        if let Some(kind) = st.motion.and_then(cycle_kind) {
            // A drilling cycle: its words stick from block to block; a block with X or Y (or
            // the cycle's own G word) drills a hole.
            st.cycle_r = r.map(|v| v * st.scale).or(st.cycle_r);
            st.cycle_z = axes[2].map(|v| v * st.scale).or(st.cycle_z);
            st.cycle_q = q.map(|v| v * st.scale).or(st.cycle_q);
            st.cycle_p = p.or(st.cycle_p);
            if axes[0].is_some() || axes[1].is_some() || motion_word.is_some() {
                drill(&mut st, kind, [axes[0], axes[1]], &mut paths, tool, dwell_in_millis).map_err(err)?;
            }
        } else if axes.iter().any(Option::is_some) {
            let Some(motion) = st.motion else { return Err(err("coordinates without a motion mode (G0, G1, G2 or G3)".into())) };
            let from = st.position;
            let mut to = from;
            for k in 0..3 {
                if let Some(v) = axes[k] {
                    let v = v * st.scale;
                    to[k] = Some(if st.incremental { from[k].ok_or_else(|| err("an incremental move before the position is known".into()))? + v } else { v });
                }
            }
            st.position = to;
            let (Some(fx), Some(fy), Some(fz)) = (from[0], from[1], from[2]) else { continue };
            let (from, to) = (DVec3::new(fx, fy, fz), DVec3::new(to[0].unwrap_or(fx), to[1].unwrap_or(fy), to[2].unwrap_or(fz)));
            let path = path_from(&mut paths, tool, st.spindle, from);
            let feed = || st.feed.map(|f| f * st.scale).filter(|f| *f > 0.0).ok_or_else(|| err("a feed move before any feed rate (F)".into()));
            let mv = match motion {
                0 => Move::Rapid { to },
                1 => Move::Line { to, feed: feed()? },
                _ => {
                    let clockwise = motion == 2;
                    let center = match (i, j, r) {
                        (_, _, Some(r)) if i.is_none() && j.is_none() => center_from_radius(from, to, r * st.scale, clockwise).map_err(err)?,
                        (None, None, _) => return Err(err("an arc needs I and J, or R".into())),
                        _ => {
                            let off = DVec2::new(i.unwrap_or(0.0), j.unwrap_or(0.0)) * st.scale;
                            if st.arc_incremental {
                                from.truncate() + off
                            } else {
                                off
                            }
                        }
                    };
                    let (r0, r1) = ((from.truncate() - center).length(), (to.truncate() - center).length());
                    if (r0 - r1).abs() > ARC_RADIUS_SLACK {
                        return Err(err(format!("the arc's start and end radii differ ({r0:.4} and {r1:.4} mm)")));
                    }
                    // A control refuses an arc about its own start (LinuxCNC: "zero radius
                    // arc"): no circle to follow.
                    if r0.max(r1) <= ARC_RADIUS_SLACK {
                        return Err(err(format!("an arc of zero radius (its centre at its start, X{:.4} Y{:.4}): no circle to follow", center.x, center.y)));
                    }
                    Move::Arc { to, center, clockwise, feed: feed()? }
                }
            };
            path.moves.push(mv);
        }
        if end {
            break;
        }
    }
    paths.retain(|p| !p.moves.is_empty());
    Ok(paths)
}

/// A tool's path before its first move (its start is where the tool stands then).
fn empty_path(tool: u32, spindle: f64) -> Toolpath {
    Toolpath { name: format!("T{tool}"), tool, spindle_rpm: spindle, start: DVec3::NAN, moves: Vec::new(), cycles: Vec::new() }
}

/// The path the next move goes into (a first one for `tool` in a program that never changes
/// tools), started at `from` if it has no move yet.
fn path_from(paths: &mut Vec<Toolpath>, tool: u32, spindle: f64, from: DVec3) -> &mut Toolpath {
    if paths.is_empty() {
        paths.push(empty_path(tool, spindle));
    }
    let path = paths.last_mut().expect("pushed above");
    if path.start.is_nan() {
        path.start = from;
    }
    path
}

/// The drilling cycle's G word's kind (motion 81, 82, 83, 73).
fn cycle_kind(motion: u32) -> Option<CycleKind> {
    match motion {
        81 => Some(CycleKind::Drill),
        82 => Some(CycleKind::Dwell),
        83 => Some(CycleKind::Peck),
        73 => Some(CycleKind::ChipBreak),
        _ => None,
    }
}

/// One hole of a drilling cycle at X, Y (those given; the others where the tool is), as the
/// moves LinuxCNC makes of it: up to R first where the tool stands below it.
fn drill(st: &mut State, kind: CycleKind, xy: [Option<f64>; 2], paths: &mut Vec<Toolpath>, tool: u32, dwell_in_millis: bool) -> Result<(), String> {
    if st.incremental {
        return Err("drilling cycles in incremental distance mode (G91) are not simulated".into());
    }
    let [Some(x0), Some(y0), Some(z0)] = st.position else { return Err("a drilling cycle before the tool's position is known".into()) };
    let r = st.cycle_r.ok_or("a drilling cycle needs R, the height it feeds from")?;
    let bottom = st.cycle_z.ok_or("a drilling cycle needs Z, the hole's bottom")?;
    if r < bottom {
        return Err(format!("a drilling cycle's R ({r}) is below its bottom Z ({bottom})"));
    }
    let feed = st.feed.map(|f| f * st.scale).filter(|f| *f > 0.0).ok_or("a drilling cycle before any feed rate (F)")?;
    let peck = match kind {
        CycleKind::Peck | CycleKind::ChipBreak => st.cycle_q.filter(|q| *q > 0.0).ok_or("a peck cycle (G83, G73) needs a positive Q")?,
        _ => 0.0,
    };
    let dwell = match kind {
        CycleKind::Dwell => st.cycle_p.filter(|p| *p >= 0.0).ok_or("G82 needs P, its dwell")? / if dwell_in_millis { 1000.0 } else { 1.0 },
        _ => 0.0,
    };
    let at = DVec2::new(xy[0].map_or(x0, |v| v * st.scale), xy[1].map_or(y0, |v| v * st.scale));
    let path = path_from(paths, tool, st.spindle, DVec3::new(x0, y0, z0));
    if z0 < r {
        path.moves.push(Move::Rapid { to: DVec3::new(x0, y0, r) });
    }
    let initial = z0.max(r);
    let mut cycle = Cycle { kind, first: path.moves.len(), count: 0, at, initial, r, bottom, to_initial: st.to_initial, peck, dwell, feed };
    let moves = cycle.moves();
    cycle.count = moves.len();
    path.moves.extend(moves);
    path.cycles.push(cycle);
    st.position = [Some(at.x), Some(at.y), Some(cycle.clear())];
    Ok(())
}

/// The centre of an arc given by its radius (negative: the longer way round).
fn center_from_radius(from: DVec3, to: DVec3, r: f64, clockwise: bool) -> Result<DVec2, String> {
    let (a, b) = (from.truncate(), to.truncate());
    let half = (b - a) * 0.5;
    let d = half.length();
    if d == 0.0 {
        return Err("an R-format arc must not end where it starts".into());
    }
    let h2 = r * r - d * d;
    if h2 < -ARC_RADIUS_SLACK * r.abs() {
        return Err(format!("the arc's radius {:.4} mm is shorter than half its chord", r.abs()));
    }
    let h = h2.max(0.0).sqrt();
    // Counter-clockwise with a positive radius: the centre lies left of the chord.
    let left = DVec2::new(-half.y, half.x) / d;
    let side = if clockwise == (r > 0.0) { -1.0 } else { 1.0 };
    Ok(a + half + left * h * side)
}

/// The words of a line, comments removed.
pub(crate) fn words(line: &str) -> Result<Vec<(char, f64)>, String> {
    let mut out = Vec::new();
    let mut chars = line.trim().chars().peekable();
    if chars.peek() == Some(&'%') {
        return Ok(out);
    }
    while let Some(c) = chars.next() {
        match c {
            '(' => {
                for c in chars.by_ref() {
                    if c == ')' {
                        break;
                    }
                }
            }
            ';' => break,
            c if c.is_whitespace() => {}
            c if c.is_ascii_alphabetic() => {
                let mut number = String::new();
                while let Some(&d) = chars.peek() {
                    if d.is_ascii_digit() || d == '.' || ((d == '-' || d == '+') && number.is_empty()) {
                        number.push(d);
                        chars.next();
                    } else if d == ' ' && number.is_empty() {
                        chars.next();
                    } else {
                        break;
                    }
                }
                let value: f64 = number.parse().map_err(|_| format!("the word {c} has no number"))?;
                if !value.is_finite() {
                    return Err(format!("the word {c} has no number"));
                }
                out.push((c.to_ascii_uppercase(), value));
            }
            '/' if out.is_empty() => {} // block delete: read the block anyway
            other => return Err(format!("unexpected character {other:?}")),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modal_words_units_and_arcs() {
        let text = "%\nO0001 (demo)\nG21 G90 G17\nT2 M6\nG43 H2\nS9000 M3\nG0 Z5\nX10 Y0\nG1 Z-1 F300\nX20\nG2 X30 Y10 I0 J10 F600\nG3 X20 Y20 R10\nG91 G1 X-5\nG20 G90 G0 Z1\nM30\nG0 X99\n";
        let paths = read_gcode(text, 1).unwrap();
        assert_eq!(paths.len(), 1);
        let p = &paths[0];
        assert_eq!(p.tool, 2);
        assert_eq!(p.start, DVec3::new(10.0, 0.0, 5.0));
        let expect = [
            Move::Line { to: DVec3::new(10.0, 0.0, -1.0), feed: 300.0 },
            Move::Line { to: DVec3::new(20.0, 0.0, -1.0), feed: 300.0 },
            Move::Arc { to: DVec3::new(30.0, 10.0, -1.0), center: DVec2::new(20.0, 10.0), clockwise: true, feed: 600.0 },
            Move::Arc { to: DVec3::new(20.0, 20.0, -1.0), center: DVec2::new(20.0, 10.0), clockwise: false, feed: 600.0 },
            Move::Line { to: DVec3::new(15.0, 20.0, -1.0), feed: 600.0 },
            Move::Rapid { to: DVec3::new(15.0, 20.0, 25.4) },
        ];
        assert_eq!(p.moves.len(), expect.len());
        for (a, b) in p.moves.iter().zip(expect) {
            match (a, b) {
                (Move::Arc { center: c1, to: t1, .. }, Move::Arc { center: c2, to: t2, .. }) => {
                    assert!(c1.distance(c2) < 1e-9 && t1.distance(t2) < 1e-9, "{a:?} vs {b:?}")
                }
                _ => assert_eq!(*a, b),
            }
        }
    }

    #[test]
    fn unsupported_words_are_refused_with_their_line() {
        for (text, needle) in [
            ("G0 X0 Y0 Z0\nG18\n", "line 2"),
            ("G41 D1\n", "compensation"),
            ("G0 X0 Y0 Z5\nG84 X1 Y1 Z-1 R1\n", "canned cycle"),
            ("G0 X0 Y0 Z5\nG81 X1 Y1 Z-1 R1\n", "before any feed rate"),
            ("G0 X0 Y0 Z5\nG83 X1 Y1 Z-1 R1 F100\n", "positive Q"),
            ("G0 X0 Y0 Z5\nG81 X1 Y1 Z2 R1 F100\n", "below its bottom"),
            ("G91\nG0 X0 Y0 Z5\nG81 X1 Y1 Z-1 R1 F100\n", "incremental"),
            ("G0 X0 Y0 Z0 A90\n", "A axis"),
            ("G0 X0 Y0 Z0\nG1 X5\n", "feed rate"),
            ("G0 X0 Y0 Z0\nG2 X5 Y0 F100\n", "I and J"),
            ("G0 X0 Y0 Z0\nG2 X10 Y0 I3 J0 F100\n", "radii differ"),
            ("G0 X0 Y0 Z0\nG2 X0 Y0 I0 J0 F100\n", "zero radius"),
            ("G0 X0 Y0 Z0\nG2 X0 Y0 Z-1 I0 J0 F100\n", "zero radius"),
            ("X1\n", "motion mode"),
            ("G1 X#1\n", "no number"),
            ("G0 X0 Y0 Z0\nG1 X1 Y1 F100 $\n", "unexpected character"),
        ] {
            let e = read_gcode(text, 1).unwrap_err();
            assert!(e.to_string().contains(needle), "{text:?}: {e}");
        }
    }
}
