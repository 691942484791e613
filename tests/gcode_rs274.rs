//! Every program the post writes is run through LinuxCNC's own interpreter (`rs274` from
//! Debian's linuxcnc-uspace), and the canonical moves it prints are checked against the tool
//! path move by move.

mod common;

use swarf::cutter::Cutter;
use swarf::geom::{DVec2, DVec3};
use swarf::job::{self, FinishRaster, Job, Operation, Tool};
use swarf::mesh::placement::Units;
use swarf::mesh::sample::demo_part;
use swarf::operations::Roughing;
use swarf::operations::Steps;
use swarf::post::{write_gcode, Dialect, PostSettings};
use swarf::progress::Progress;
use swarf::toolpath::{Move, Toolpath};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Rapid,
    Feed,
    Arc { center: DVec2, ccw: bool },
}

/// Runs rs274 on the program; returns its canonical motions (kind, end point in program units).
fn interpret(gcode: &str, tools: &[Tool]) -> Vec<(Kind, DVec3)> {
    common::rs274(gcode, tools).lines().filter_map(parse_canon).collect()
}

fn numbers(args: &str) -> Vec<f64> {
    args.split([',', ' ']).filter_map(|w| w.trim().parse().ok()).collect()
}

/// The call of a line of rs274's output (`   7 N..... STRAIGHT_FEED(…)`; the N field holds
/// the program's line number where it has them).
fn canon_call(line: &str) -> Option<&str> {
    let line = line.trim_start();
    let (_, rest) = line.split_once(' ')?;
    let (n, call) = rest.trim_start().split_once(' ')?;
    n.starts_with('N').then_some(call.trim_start())
}

fn parse_canon(line: &str) -> Option<(Kind, DVec3)> {
    let call = canon_call(line)?;
    let (name, rest) = call.split_once('(')?;
    let args = numbers(rest.trim_end_matches(')'));
    match name {
        "STRAIGHT_TRAVERSE" => Some((Kind::Rapid, DVec3::new(args[0], args[1], args[2]))),
        "STRAIGHT_FEED" => Some((Kind::Feed, DVec3::new(args[0], args[1], args[2]))),
        // ARC_FEED(end1, end2, centre1, centre2, rotation, end3, a, b, c, ...)
        "ARC_FEED" => Some((Kind::Arc { center: DVec2::new(args[2], args[3]), ccw: args[4] > 0.0 }, DVec3::new(args[0], args[1], args[5]))),
        _ => None,
    }
}

/// The motions the program should make, in program units, without motions that go nowhere.
fn expected(paths: &[Toolpath], clearance: f64, scale: f64) -> Vec<(Kind, DVec3)> {
    expected_at(paths, clearance, scale, None)
}

/// As [`expected`], leaving out the moves the writer leaves out: those whose coordinates,
/// rounded to `unit` (a feed's Z up), equal the last move kept.
fn expected_at(paths: &[Toolpath], clearance: f64, scale: f64, unit: Option<f64>) -> Vec<(Kind, DVec3)> {
    let mut out = Vec::new();
    for path in paths {
        out.push((Kind::Rapid, path.start.truncate().extend(clearance)));
        out.push((Kind::Rapid, path.start));
        for m in &path.moves {
            out.push(match *m {
                Move::Rapid { to } => (Kind::Rapid, to),
                Move::Line { to, .. } => (Kind::Feed, to),
                Move::Arc { to, center, clockwise, .. } => (Kind::Arc { center: center * scale, ccw: !clockwise }, to),
            });
        }
    }
    let mut result: Vec<(Kind, DVec3)> = Vec::new();
    let rounded = |k: Kind, p: DVec3| unit.map(|u| DVec3::new((p.x / u).round(), (p.y / u).round(), if k == Kind::Feed { (p.z / u - 1e-9).ceil() } else { (p.z / u).round() }));
    let mut last_rounded = None;
    for (k, p) in out {
        let p = p * scale;
        if matches!(k, Kind::Arc { .. }) || result.last().is_none_or(|(_, q)| q.distance(p) > 1e-9) {
            let r = rounded(k, p);
            if r.is_some() && r == last_rounded && !matches!(k, Kind::Arc { .. }) {
                continue;
            }
            last_rounded = r;
            result.push((k, p));
        }
    }
    result
}

/// Compares the interpreter's motions with the path's, within the program's rounding.
fn compare(actual: &[(Kind, DVec3)], expected: &[(Kind, DVec3)], resolution: f64) {
    // The program starts with a retract to the clearance height from wherever the machine is.
    let actual: Vec<_> = actual.iter().skip_while(|(k, p)| *k == Kind::Rapid && p.x == 0.0 && p.y == 0.0).copied().collect();
    let mut a = actual.iter().peekable();
    let mut checked = 0;
    for (kind, point) in expected {
        // Moves whose rounded coordinates equal the previous ones are not written.
        let Some(&(mut k, mut p)) = a.peek().copied() else { panic!("the program ends early, expected {kind:?} to {point}") };
        // X and Y are rounded to the nearest (half a unit, `resolution`), a feed's Z up (a unit).
        if p.distance(*point) > resolution * 3.0 {
            // A motion of the interpreter's own between two of the path's (a tool change's
            // retract) is passed over when the one after it is the path's.
            let mut ahead = a.clone();
            ahead.next();
            match ahead.peek().copied() {
                Some(&(k2, p2)) if p2.distance(*point) <= resolution * 3.0 => {
                    a.next();
                    (k, p) = (k2, p2);
                }
                _ => continue,
            }
        }
        let _ = p;
        a.next();
        match (&k, kind) {
            (Kind::Arc { center: c1, ccw: w1 }, Kind::Arc { center: c2, ccw: w2 }) => {
                // The interpreter's centre is the rounded start plus the rounded I, J: two
                // roundings of half the resolution on each axis.
                assert!(c1.distance(*c2) <= resolution * 2.0 * std::f64::consts::SQRT_2 && w1 == w2, "arc centre {c1} vs {c2}");
            }
            _ => assert_eq!(std::mem::discriminant(&k), std::mem::discriminant(kind), "at {point}"),
        }
        checked += 1;
    }
    assert!(checked as f64 >= expected.len() as f64 * 0.95, "only {checked} of {} moves matched", expected.len());
    // What is left after the path: the final retract.
    let rest: Vec<_> = a.collect();
    assert!(rest.len() <= 1 && rest.iter().all(|(k, _)| *k == Kind::Rapid), "unexpected motions after the path: {rest:?}");
}

fn demo_job(dialect: Dialect, units: Units) -> Job {
    Job {
        name: format!("demo {dialect:?} {units:?}"),
        tools: vec![Tool { number: 3, cutter: Cutter::ball(6.0), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { tool: 3, stepover: 2.0, grid: 0.5, angle: 30.0, ..FinishRaster::default() })],
        post: PostSettings { dialect, units, ..PostSettings::default() },
        ..Job::default()
    }
}

#[test]
fn demo_programs_run_in_linuxcnc_for_every_dialect_and_unit() {
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl, Dialect::Mach3] {
        for units in [Units::Mm, Units::Inch] {
            let job = demo_job(dialect, units);
            let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
            let scale = 1.0 / units.mm();
            let resolution = if units == Units::Mm { 0.0005 } else { 0.00005 };
            let actual = interpret(&out.gcode, &job.tools);
            compare(&actual, &expected_at(&out.paths, out.clearance_z, scale, Some(2.0 * resolution)), resolution);
        }
    }
}

/// The tool-change calls rs274 makes (`CHANGE_TOOL`, `PROGRAM_STOP` for a GRBL pause), in order.
fn tool_calls(gcode: &str, tools: &[Tool]) -> Vec<String> {
    common::rs274(gcode, tools)
        .lines()
        .filter_map(|l| canon_call(l).map(str::to_owned))
        .filter(|c| c.starts_with("CHANGE_TOOL(") || c.starts_with("PROGRAM_STOP") || c.starts_with("USE_TOOL_LENGTH_OFFSET"))
        .collect()
}

#[test]
fn two_tool_programs_change_tools_as_each_dialect_does() {
    let tools = vec![Tool { number: 1, cutter: Cutter::ball(6.0), ..Tool::default() }, Tool { number: 2, cutter: Cutter::ball(3.0), ..Tool::default() }];
    let ops = vec![
        Operation::FinishRaster(FinishRaster { name: "coarse".into(), tool: 1, stepover: 2.0, allowance: 0.3, grid: 0.5, ..FinishRaster::default() }),
        Operation::FinishRaster(FinishRaster { name: "fine".into(), tool: 2, stepover: 1.5, grid: 0.5, angle: 90.0, ..FinishRaster::default() }),
    ];
    for dialect in [Dialect::LinuxCnc, Dialect::Mach3, Dialect::Grbl] {
        let job = Job { tools: tools.clone(), operations: ops.clone(), post: PostSettings { dialect, ..PostSettings::default() }, ..Job::default() };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        // rs274 accepts it, and ends where the program does.
        let actual = interpret(&out.gcode, &job.tools);
        let last = out.paths.last().unwrap().moves.last().unwrap().to();
        assert!(actual.iter().rev().any(|(_, p)| p.truncate().distance(last.truncate()) < 0.001), "{:?}", actual.last());
        assert!(actual.len() * 10 > out.moves.len() * 9, "{} motions for {} moves", actual.len(), out.moves.len());
        let calls = tool_calls(&out.gcode, &job.tools);
        if dialect == Dialect::Grbl {
            // No tool changer: a spindle stop and a pause naming the tool to load.
            assert!(!out.gcode.contains("M6") && !out.gcode.contains("G43"));
            assert!(out.gcode.contains("M5\nG0 Z") && out.gcode.contains("(change to tool 2: ") && out.gcode.contains(")\nM0\n"), "{}", &out.gcode[..400]);
            assert_eq!(calls.iter().filter(|c| c.starts_with("PROGRAM_STOP")).count(), 1, "{calls:?}");
        } else {
            let changes: Vec<&String> = calls.iter().filter(|c| c.starts_with("CHANGE_TOOL")).collect();
            assert_eq!(changes.len(), 2, "{calls:?}");
            assert!(calls.iter().filter(|c| c.starts_with("USE_TOOL_LENGTH_OFFSET")).count() >= 2, "{calls:?}");
        }
    }
}

#[test]
fn dialect_headers_and_footers() {
    let out = |d| job::run(&demo_job(d, Units::Mm), demo_part(), &mut Progress::none()).unwrap().gcode;
    let grbl = out(Dialect::Grbl);
    assert!(!grbl.contains("M6") && !grbl.contains("G43") && grbl.contains("G21") && grbl.contains("M3") && grbl.trim_end().ends_with("M30"));
    let linuxcnc = out(Dialect::LinuxCnc);
    assert!(linuxcnc.contains("T3 M6") && linuxcnc.contains("G43 H3") && linuxcnc.trim_end().ends_with("M2"));
    let fanuc = out(Dialect::Fanuc);
    assert!(fanuc.starts_with("%\nO0001") && fanuc.trim_end().ends_with('%'));
    let inch = job::run(&demo_job(Dialect::LinuxCnc, Units::Inch), demo_part(), &mut Progress::none()).unwrap().gcode;
    assert!(inch.contains("G20") && !inch.contains("G21"));
}

#[test]
fn arcs_and_helices_go_out_as_g2_g3_with_relative_centres() {
    let tools = vec![Tool { number: 1, cutter: Cutter::flat(6.0), ..Tool::default() }];
    let moves = vec![
        Move::Line { to: DVec3::new(10.0, 0.0, -1.0), feed: 300.0 },
        Move::Arc { to: DVec3::new(0.0, 10.0, -1.0), center: DVec2::ZERO, clockwise: false, feed: 800.0 },
        Move::Arc { to: DVec3::new(10.0, 0.0, -1.0), center: DVec2::ZERO, clockwise: true, feed: 800.0 },
        // A full helical turn down by 1 mm.
        Move::Arc { to: DVec3::new(10.0, 0.0, -2.0), center: DVec2::ZERO, clockwise: false, feed: 800.0 },
        Move::Arc { to: DVec3::new(14.0, 4.0, -2.0), center: DVec2::new(14.0, 0.0), clockwise: true, feed: 800.0 },
        Move::Rapid { to: DVec3::new(14.0, 4.0, 5.0) },
    ];
    let path = Toolpath { name: "arcs".into(), tool: 1, spindle_rpm: 10000.0, start: DVec3::new(10.0, 0.0, 5.0), moves, cycles: Vec::new() };
    for units in [Units::Mm, Units::Inch] {
        let settings = PostSettings { units, ..PostSettings::default() };
        let gcode = write_gcode("arcs", std::slice::from_ref(&path), &tools, 5.0, &settings).unwrap();
        assert!(gcode.contains("G3 X0 Y10 I-10 J0") || units == Units::Inch, "{gcode}");
        let resolution = if units == Units::Mm { 0.0005 } else { 0.00005 };
        compare(&interpret(&gcode, &tools), &expected(std::slice::from_ref(&path), 5.0, 1.0 / units.mm()), resolution);
        // The full circle is one G3 with the same start and end.
        assert!(gcode.lines().any(|l| l.starts_with("G3") && l.contains(if units == Units::Mm { "Z-2" } else { "Z-0.0787" })));
    }
    let stats = path.stats(swarf::toolpath::Rapids::at(3000.0));
    let expected_feed = 6.0 + 2.0 * std::f64::consts::FRAC_PI_2 * 10.0 + (std::f64::consts::TAU * 10.0f64).hypot(1.0) + std::f64::consts::FRAC_PI_2 * 4.0;
    assert!((stats.feed_length - expected_feed).abs() < 1e-9, "{} vs {expected_feed}", stats.feed_length);
}

/// An arc shorter than the program's resolution would read as a full circle when its ends
/// round to one point: it goes out as a line.
#[test]
fn arcs_shorter_than_the_resolution_go_out_as_lines() {
    let tools = vec![Tool { number: 1, cutter: Cutter::flat(3.0), ..Tool::default() }];
    let moves = vec![
        Move::Line { to: DVec3::new(10.0, 0.0, -1.0), feed: 300.0 },
        Move::Arc { to: DVec3::new(10.0, 0.0002, -1.0), center: DVec2::new(9.96, 0.0), clockwise: false, feed: 800.0 },
        Move::Line { to: DVec3::new(10.0, 5.0, -1.0), feed: 300.0 },
    ];
    let path = Toolpath { name: "tiny".into(), tool: 1, spindle_rpm: 10000.0, start: DVec3::new(10.0, 0.0, 5.0), moves, cycles: Vec::new() };
    let gcode = write_gcode("tiny", std::slice::from_ref(&path), &tools, 5.0, &PostSettings::default()).unwrap();
    assert!(!gcode.lines().any(|l| l.starts_with("G2 ") || l.starts_with("G3 ")), "{gcode}");
    assert!(!gcode.lines().any(|l| l.starts_with('F')), "a feed without a move: {gcode}");
    let canon = interpret(&gcode, &tools);
    assert!(canon.iter().all(|(k, _)| !matches!(k, Kind::Arc { .. })));
}

/// An arc whose centre lies farther than the post's largest radius (a curve bowing 1e-4 mm over
/// 40 mm: its centre 2 km away) is written as lines: GRBL computes arcs in float32, which puts
/// such a centre a quarter of a millimetre off. GRBL's posts write arcs up to 2 m, the others up
/// to 100 m; the lines keep within the chord error, and each control reads the program.
#[test]
fn arcs_larger_than_the_post_takes_go_out_as_lines() {
    let tools = vec![Tool { number: 1, cutter: Cutter::flat(3.0), ..Tool::default() }];
    let bowed = |radius: f64| {
        // From (−20, 0) to (20, 0) on a circle of `radius` below them, bowing up.
        let centre = DVec2::new(0.0, -(radius * radius - 400.0).sqrt());
        vec![
            Move::Line { to: DVec3::new(-20.0, 0.0, -1.0), feed: 300.0 },
            Move::Arc { to: DVec3::new(20.0, 0.0, -1.0), center: centre, clockwise: true, feed: 800.0 },
            Move::Line { to: DVec3::new(20.0, 5.0, -1.0), feed: 300.0 },
        ]
    };
    for (dialect, radius, as_arc) in
        [(Dialect::Grbl, 2_000_000.0, false), (Dialect::Grbl, 5_000.0, false), (Dialect::Grbl, 500.0, true), (Dialect::LinuxCnc, 2_000_000.0, false), (Dialect::LinuxCnc, 5_000.0, true)]
    {
        let path = Toolpath { name: "bowed".into(), tool: 1, spindle_rpm: 10000.0, start: DVec3::new(-20.0, 0.0, 5.0), moves: bowed(radius), cycles: Vec::new() };
        let settings = PostSettings { dialect, ..PostSettings::default() };
        let gcode = write_gcode("bowed", std::slice::from_ref(&path), &tools, 5.0, &settings).unwrap();
        let arcs = gcode.lines().filter(|l| l.starts_with("G2 ") || l.starts_with("G3 ")).count();
        assert_eq!(arcs > 0, as_arc, "{dialect:?} r {radius}: {gcode}");
        // Every point the control passes lies within the chord error of the arc.
        let Move::Arc { center, .. } = bowed(radius)[1] else { unreachable!() };
        let (mut x, mut y) = (f64::NAN, f64::NAN);
        for l in gcode.lines().filter(|l| !l.starts_with('(')) {
            let word = |w: char| l.split_whitespace().find_map(|t| t.strip_prefix(w)).and_then(|v| v.parse::<f64>().ok());
            let moved = word('X').is_some() || word('Y').is_some();
            (x, y) = (word('X').unwrap_or(x), word('Y').unwrap_or(y));
            if moved && x.abs() < 20.0 && y > 0.0 {
                assert!(((DVec2::new(x, y) - center).length() - radius).abs() < 0.002, "{dialect:?} r {radius}: {l}");
            }
        }
        if dialect == Dialect::Grbl {
            if let Some(read) = common::grblcheck(&gcode) {
                read.unwrap_or_else(|e| panic!("r {radius}: {e}\n{gcode}"));
            }
        } else {
            interpret(&gcode, &tools);
        }
    }
}

/// A level arc between two lines at a height the program's resolution does not hold is written
/// at the same Z as the lines (rounded up, like every feed's Z): not a helix a hair thin, and
/// never below the path.
#[test]
fn a_level_arc_is_written_at_its_lines_height() {
    let tools = vec![Tool { number: 1, cutter: Cutter::flat(3.0), ..Tool::default() }];
    let z = 29.84649;
    let moves = vec![
        Move::Line { to: DVec3::new(10.0, 0.0, z), feed: 300.0 },
        Move::Arc { to: DVec3::new(0.0, 10.0, z), center: DVec2::ZERO, clockwise: false, feed: 800.0 },
        Move::Line { to: DVec3::new(-5.0, 10.0, z), feed: 300.0 },
    ];
    let path = Toolpath { name: "level".into(), tool: 1, spindle_rpm: 10000.0, start: DVec3::new(10.0, 0.0, 35.0), moves, cycles: Vec::new() };
    let gcode = write_gcode("level", std::slice::from_ref(&path), &tools, 35.0, &PostSettings::default()).unwrap();
    let arc = gcode.lines().find(|l| l.starts_with("G3 ")).unwrap_or_else(|| panic!("no arc: {gcode}"));
    assert!(!arc.contains('Z'), "the arc changes Z: {arc}");
    let canon = interpret(&gcode, &tools);
    let fed: Vec<f64> = canon.iter().filter(|(k, _)| !matches!(k, Kind::Rapid)).map(|(_, p)| p.z).collect();
    assert!(fed.len() >= 3 && fed.iter().all(|&h| (h - fed[0]).abs() < 1e-12 && h >= z), "{fed:?}\n{gcode}");
}

/// swarf's own G-code reader (for `swarf verify`) must read a program as LinuxCNC does.
#[test]
fn the_reader_reads_programs_as_linuxcnc_does() {
    let mut programs = Vec::new();
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl, Dialect::Mach3] {
        for units in [Units::Mm, Units::Inch] {
            let job = demo_job(dialect, units);
            let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
            programs.push((out.gcode, job.tools, units));
        }
    }
    let tools = vec![Tool { number: 1, cutter: Cutter::flat(6.0), ..Tool::default() }];
    let text = "G21 G90 G17\nT1 M6\nG0 Z5\nG0 X10 Y0\nG1 Z-1 F300\nG3 X0 Y10 R10 F800\nG2 X-10 Y0 R-10\nG91 G1 X5 Y-2\nG90 G90.1 G3 X5 Y-2 Z-2 I0 J0\nG0 Z5\nM2\n";
    programs.push((text.to_string(), tools, Units::Mm));
    for (gcode, tools, units) in programs {
        let scale = 1.0 / units.mm();
        let resolution = if units == Units::Mm { 0.0005 } else { 0.00005 };
        let linuxcnc = interpret(&gcode, &tools);
        let read = swarf::post::read::read_gcode(&gcode, tools[0].number).unwrap();
        let mine: Vec<(Kind, DVec3)> = read
            .iter()
            .flat_map(|p| p.moves.iter())
            .map(|m| match *m {
                Move::Rapid { to } => (Kind::Rapid, to * scale),
                Move::Line { to, .. } => (Kind::Feed, to * scale),
                Move::Arc { to, center, clockwise, .. } => (Kind::Arc { center: center * scale, ccw: !clockwise }, to * scale),
            })
            .collect();
        assert!(!mine.is_empty() && linuxcnc.len() >= mine.len() && linuxcnc.len() - mine.len() <= 4, "{} moves read, {} by LinuxCNC", mine.len(), linuxcnc.len());
        // LinuxCNC starts at a known origin; the reader starts once X, Y and Z are all known.
        let tail = &linuxcnc[linuxcnc.len() - mine.len()..];
        for ((k1, p1), (k2, p2)) in tail.iter().zip(&mine) {
            assert!(p1.distance(*p2) <= resolution, "{p1} vs {p2}");
            match (k1, k2) {
                (Kind::Arc { center: c1, ccw: w1 }, Kind::Arc { center: c2, ccw: w2 }) => assert!(c1.distance(*c2) <= resolution * 2.0 && w1 == w2),
                _ => assert_eq!(k1, k2),
            }
        }
    }
}

#[test]
fn sheet_programs_with_helices_ramps_and_tabs_run_in_linuxcnc() {
    use swarf::drawing::import::read_drawing;
    use swarf::drawing::sample::plate_dxf;
    use swarf::operations::{Pocket2d, PocketPattern};
    use swarf::operations::{Profile2d, Tabs};
    let drawing = read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Default::default()).unwrap();
    for (dialect, units) in [(Dialect::LinuxCnc, Units::Mm), (Dialect::Grbl, Units::Inch)] {
        let mut job = Job::default_for_drawing();
        job.post = PostSettings { dialect, units, ..PostSettings::default() };
        job.operations = vec![
            Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], pattern: PocketPattern::Offset, ..Pocket2d::default() }),
            Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], pattern: PocketPattern::Zigzag, angle: 30.0, ..Pocket2d::default() }),
            Operation::Profile2d(Profile2d { layers: vec!["CUT".into()], tabs: Tabs { count: 3, ..Tabs::default() }, ..Profile2d::default() }),
        ];
        let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap();
        assert!(out.paths.iter().flat_map(|p| &p.moves).any(|m| matches!(m, Move::Arc { to, .. } if to.z != 0.0)), "helices expected");
        let scale = 1.0 / units.mm();
        let resolution = if units == Units::Mm { 0.0005 } else { 0.00005 };
        let actual = interpret(&out.gcode, &job.tools);
        compare(&actual, &expected(&out.paths, out.clearance_z, scale), resolution);
    }
}

#[test]
fn roughing_then_finishing_programs_run_in_linuxcnc_with_arcs() {
    use swarf::operations::RoughZlevel;
    let tools = vec![Tool { number: 1, cutter: Cutter { flute_length: 40.0, ..Cutter::flat(6.0) }, ..Tool::default() }, Tool { number: 2, cutter: Cutter::ball(6.0), ..Tool::default() }];
    let ops = vec![Operation::RoughZlevel(RoughZlevel { tool: 1, ..RoughZlevel::default() }), Operation::FinishRaster(FinishRaster { tool: 2, stepover: 1.5, grid: 0.5, ..FinishRaster::default() })];
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl] {
        let job = Job { tools: tools.clone(), operations: ops.clone(), post: PostSettings { dialect, ..PostSettings::default() }, ..Job::default() };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        let actual = interpret(&out.gcode, &job.tools);
        let arcs = actual.iter().filter(|(k, _)| matches!(k, Kind::Arc { .. })).count();
        assert!(arcs > 100, "{dialect:?}: {arcs} arcs");
        let last = out.paths.last().unwrap().moves.last().unwrap().to();
        assert!(actual.iter().rev().any(|(_, p)| p.truncate().distance(last.truncate()) < 0.001));
    }
}

#[test]
fn zigzag_roughing_with_its_arcs_and_feeds_runs_in_linuxcnc_move_for_move() {
    use swarf::operations::RoughZigzag;
    let tools = vec![Tool { number: 1, cutter: Cutter { flute_length: 40.0, ..Cutter::flat(6.0) }, ..Tool::default() }];
    let job =
        Job { tools, operations: vec![Operation::RoughZigzag(RoughZigzag { tool: 1, angle: 30.0, steps: Steps { stepdown: 4.0, ..Steps::default() }, ..RoughZigzag::default() })], ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.is_clean());
    let actual = interpret(&out.gcode, &job.tools);
    assert!(actual.iter().filter(|(k, _)| matches!(k, Kind::Arc { .. })).count() > 10);
    compare(&actual, &expected_at(&out.paths, out.clearance_z, 1.0, Some(0.001)), 0.0005);
    // The lowered feeds are written.
    let feeds: std::collections::BTreeSet<String> = out.gcode.split_whitespace().filter(|w| w.starts_with('F')).map(str::to_string).collect();
    assert!(feeds.len() > 3, "{feeds:?}");
}

#[test]
fn octree_roughing_with_its_chosen_tools_runs_in_linuxcnc_move_for_move() {
    use swarf::mesh::sample::height_field_solid;
    use swarf::operations::RoughOctree;
    let within = |v: f64, lo: f64, hi: f64| (lo..=hi).contains(&v);
    let part = height_field_solid(DVec2::new(-40.0, -30.0), DVec2::new(40.0, 30.0), 160, 120, -30.0, move |x, y| {
        if within(x, -30.0, 10.0) && within(y, -20.0, 20.0) || within(x, 10.0, 30.0) && within(y, -2.5, 2.5) {
            -10.0
        } else {
            0.0
        }
    });
    let flat = |number: u32, d: f64| Tool { number, cutter: Cutter { flute_length: 3.0 * d, ..Cutter::flat(d) }, ..Tool::default() };
    let job = Job {
        tools: vec![flat(1, 12.0), flat(2, 3.0)],
        operations: vec![Operation::RoughOctree(RoughOctree { roughing: Roughing { grid: 0.5, ..Roughing::default() }, ..RoughOctree::default() })],
        ..Job::default()
    };
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.is_clean());
    assert_eq!(out.operations[0].tools, vec![1, 2]);
    let actual = interpret(&out.gcode, &job.tools);
    assert!(actual.iter().filter(|(k, _)| matches!(k, Kind::Arc { .. })).count() > 10);
    compare(&actual, &expected_at(&out.paths, out.clearance_z, 1.0, Some(0.001)), 0.0005);
    let changes = tool_calls(&out.gcode, &job.tools).into_iter().filter(|c| c.starts_with("CHANGE_TOOL")).count();
    assert_eq!(changes, 2, "a tool change per chosen tool");
}

#[test]
fn each_dialect_names_the_extension_its_controllers_expect() {
    let ext: Vec<String> = Dialect::ALL.iter().map(|d| d.extension()).collect();
    assert_eq!(ext, vec!["ngc", "nc", "nc", "tap", "nc", "nc"]);
}

/// A move of a program in mm, from where the one before it ended.
#[derive(Clone, Copy, Debug)]
struct Span {
    from: DVec3,
    to: DVec3,
    /// An arc's centre and whether it turns counter-clockwise.
    arc: Option<(DVec2, bool)>,
}

impl Span {
    fn sweep(&self) -> f64 {
        let (c, ccw) = self.arc.unwrap();
        swarf::toolpath::arc_sweep(self.from, self.to, c, !ccw)
    }

    fn at(&self, t: f64) -> DVec3 {
        match self.arc {
            None => self.from.lerp(self.to, t),
            Some((c, _)) => {
                let r = (self.from.truncate() - c).length();
                let a = (self.from.truncate() - c).to_angle() + self.sweep() * t;
                (c + DVec2::from_angle(a) * r).extend(self.from.z + (self.to.z - self.from.z) * t)
            }
        }
    }

    fn distance(&self, p: DVec3) -> f64 {
        let mut ts = vec![0.0, 1.0];
        match self.arc {
            None => {
                let d = self.to - self.from;
                if d.length_squared() > 0.0 {
                    ts.push(((p - self.from).dot(d) / d.length_squared()).clamp(0.0, 1.0));
                }
            }
            Some((c, _)) => {
                let sweep = self.sweep();
                let phi = (((p.truncate() - c).to_angle() - (self.from.truncate() - c).to_angle()) * sweep.signum()).rem_euclid(std::f64::consts::TAU);
                if phi <= sweep.abs() {
                    ts.push(phi / sweep.abs());
                }
            }
        }
        ts.into_iter().map(|t| self.at(t).distance(p)).fold(f64::INFINITY, f64::min)
    }
}

/// The interpreter's motions as spans in mm, from the first that reaches `first`.
fn canon_spans(actual: &[(Kind, DVec3)], mm: f64, first: DVec3) -> Vec<Span> {
    let start = actual.iter().position(|(_, p)| (*p * mm).distance(first) < 1e-3).unwrap_or_else(|| panic!("the program never reaches the path's start {first}: {:?}", &actual[..4.min(actual.len())]));
    actual[start..]
        .windows(2)
        .map(|w| Span {
            from: w[0].1 * mm,
            to: w[1].1 * mm,
            arc: match w[1].0 {
                Kind::Arc { center, ccw } => Some((center * mm, ccw)),
                _ => None,
            },
        })
        .collect()
}

/// The paths as the program should move: to each start above it, the moves, a retract at each
/// change of tool and at the end.
fn path_spans(paths: &[Toolpath], clearance: f64) -> Vec<Span> {
    let mut out = Vec::new();
    let mut at: Option<DVec3> = None;
    let mut tool = None;
    let push = |out: &mut Vec<Span>, at: &mut Option<DVec3>, to: DVec3, arc| {
        if let Some(from) = *at {
            out.push(Span { from, to, arc });
        }
        *at = Some(to);
    };
    for path in paths {
        if let (Some(p), true) = (at, tool != Some(path.tool)) {
            push(&mut out, &mut at, p.truncate().extend(clearance), None);
        }
        tool = Some(path.tool);
        push(&mut out, &mut at, path.start.truncate().extend(clearance), None);
        push(&mut out, &mut at, path.start, None);
        for m in &path.moves {
            let arc = match *m {
                Move::Arc { center, clockwise, .. } => Some((center, !clockwise)),
                _ => None,
            };
            push(&mut out, &mut at, m.to(), arc);
        }
    }
    let last = at.unwrap();
    push(&mut out, &mut at, last.truncate().extend(clearance), None);
    out
}

/// Every span of `a`, at five points along it, lies within `tol` of a span of `b`, taken in
/// order (a point may match from a few spans back, for moves split differently).
fn follows(a: &[Span], b: &[Span], tol: f64) -> Result<(), String> {
    let mut cursor = 0usize;
    for (i, s) in a.iter().enumerate() {
        for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let p = s.at(t);
            let from = cursor.saturating_sub(4);
            let Some(k) = (from..b.len()).find(|&k| b[k].distance(p) <= tol) else {
                let near = b[from..].iter().map(|q| q.distance(p)).fold(f64::INFINITY, f64::min);
                return Err(format!("move {i} ({s:?}) at {t}: {p} is {near:.6} mm from the other path"));
            };
            cursor = k;
        }
    }
    Ok(())
}

#[test]
fn every_built_in_post_reproduces_the_paths_in_linuxcnc_and_grbl_reads_its_own() {
    use swarf::operations::RoughZlevel;
    use swarf::post::grbl::{check, Flavour};
    use swarf::post::{write_program, Post};
    use swarf::tool::Coolant;
    let tools = vec![
        Tool { number: 1, cutter: Cutter { flute_length: 40.0, ..Cutter::flat(6.0) }, coolant: Coolant::Flood, ..Tool::default() },
        Tool { number: 2, cutter: Cutter::ball(6.0), coolant: Coolant::Mist, ..Tool::default() },
    ];
    let ops = vec![Operation::RoughZlevel(RoughZlevel { tool: 1, ..RoughZlevel::default() }), Operation::FinishRaster(FinishRaster { tool: 2, stepover: 2.0, grid: 0.5, ..FinishRaster::default() })];
    let job = Job { tools: tools.clone(), operations: ops, simulation: swarf::job::Simulation { verify: false, cell: None, ..Default::default() }, ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert!(out.paths.iter().flat_map(|p| &p.moves).any(|m| matches!(m, Move::Arc { to, .. } if to.z < 0.0)), "helices expected");
    let expected = path_spans(&out.paths, out.clearance_z);
    for dialect in Dialect::ALL {
        let post = dialect.post();
        // Four decimals: the rounding (0.05 µm) is well under the micrometre checked.
        let settings = PostSettings { dialect, decimals: Some(4), ..PostSettings::default() };
        // GRBL 1.1 has no mist (M7 is off in its default build): its second tool floods.
        let mut tools = tools.clone();
        if post.coolant_mist.is_none() {
            assert!(write_program("every post", &out.paths, &tools, out.clearance_z, &settings).unwrap_err().to_string().contains("no coolantMist word"));
            tools[1].coolant = Coolant::Flood;
        }
        let (gcode, time) = write_program("every post", &out.paths, &tools, out.clearance_z, &settings).unwrap();
        // LinuxCNC reads every built-in dialect but Fanuc's program number (an O word is a
        // subroutine label to it).
        let readable: String = gcode.lines().filter(|l| !l.starts_with('O')).map(|l| format!("{l}\n")).collect();
        let actual = interpret(&readable, &tools);
        let canon = canon_spans(&actual, 1.0, expected[0].from);
        follows(&expected, &canon, 0.001).unwrap_or_else(|e| panic!("{dialect:?}: the path is not in the program: {e}"));
        follows(&canon, &expected, 0.001).unwrap_or_else(|e| panic!("{dialect:?}: the program leaves the path: {e}"));
        let arcs = gcode.lines().filter(|l| l.contains("G2 ") || l.contains("G3 ")).count();
        let calls = tool_calls(&readable, &tools);
        match dialect {
            Dialect::Grbl => {
                check(&gcode, Flavour::Grbl11).unwrap_or_else(|e| panic!("GRBL 1.1 refuses: {e}"));
                if let Some(said) = common::grblcheck(&gcode) {
                    said.unwrap_or_else(|e| panic!("GRBL 1.1h's own parser refuses the program: {e}"));
                }
                assert!(!gcode.contains("M6") && gcode.contains("M0\n") && calls.iter().any(|c| c.starts_with("PROGRAM_STOP")));
            }
            Dialect::GrblHal => {
                check(&gcode, Flavour::GrblHal).unwrap_or_else(|e| panic!("grblHAL refuses: {e}"));
                assert!(check(&gcode, Flavour::Grbl11).is_err(), "a tool change GRBL 1.1 would refuse");
                // GRBL 1.1h's parser reads every other line as grblHAL does: grblHAL's tool
                // changes (M6) and mist (M7, which GRBL 1.1 builds without) aside.
                let without_changes: String = gcode.lines().filter(|l| !l.contains("M6") && !l.contains("M7")).map(|l| format!("{l}\n")).collect();
                if let Some(said) = common::grblcheck(&without_changes) {
                    said.unwrap_or_else(|e| panic!("GRBL 1.1h's own parser refuses the grblHAL program: {e}"));
                }
                assert!(common::grblcheck(&gcode).is_none_or(|r| r.is_err()), "GRBL 1.1h refuses M6");
            }
            Dialect::Fanuc => {
                assert!(gcode.starts_with("%\nO0001 (every post)\nN10 ") && gcode.trim_end().ends_with('%'));
                assert!(gcode.contains(" R") && !gcode.contains(" I"), "arcs by R");
                assert!(gcode.contains("G4 P2000"), "the spindle's dwell in milliseconds");
            }
            Dialect::Generic => {
                assert!(gcode.lines().all(|l| !l.starts_with("G2") || !l.contains('Z') || !l.contains("G3")));
                assert!(
                    gcode.contains("G1 X") && gcode.lines().filter(|l| l.starts_with("G1")).all(|l| l.contains(" X") && l.contains(" Y") && l.contains(" Z") && l.contains(" F")),
                    "every word on every line"
                );
            }
            _ => {}
        }
        if post.tool_change.is_empty() {
            assert_eq!(calls.iter().filter(|c| c.starts_with("CHANGE_TOOL")).count(), 0);
        } else {
            assert_eq!(calls.iter().filter(|c| c.starts_with("CHANGE_TOOL")).count(), 2, "{dialect:?}: {calls:?}");
        }
        assert!(arcs > 20, "{dialect:?}: {arcs} arcs");
        // Coolant per tool: flood for the flat end, mist for the ball, off before the change and at the end.
        let flood = gcode.find("\nM8").or_else(|| gcode.find(" M8")).expect("flood");
        let off = flood + gcode[flood..].find("M9").expect("coolant off before the change");
        let second = if post.coolant_mist.is_some() { "M7" } else { "M8" };
        let mist = off + gcode[off..].find(second).expect("the second tool's coolant");
        assert!(gcode[mist..].contains("M9"), "{dialect:?}");
        assert!(gcode.contains("G54") || post.work_offset.is_none());
        // The head states the cycle time: motion plus one tool change.
        let motion: f64 = out.paths.iter().map(|p| p.stats(settings.rapids()).seconds).sum();
        assert_eq!(time.tool_changes, 1);
        assert!(time.seconds >= motion + 15.0 && time.seconds < motion + 15.0 + 60.0 + post.spindle_dwell * 2.0, "{dialect:?}: {} s against {motion} s of moves", time.seconds);
        assert!(gcode.contains(&format!("cycle time {}", swarf::post::clock(time.seconds))), "{dialect:?}");
        // Every built-in post is data that reads back as itself.
        assert_eq!(Post::from_json(&serde_json::to_string(&post).unwrap()).unwrap(), post);
    }
}

#[test]
fn swarf_verify_reads_every_built_in_post_back_and_grbl_programs_must_be_grbl_s() {
    use swarf::post::write_gcode;
    let tools = vec![Tool { number: 1, cutter: Cutter::ball(6.0), ..Tool::default() }];
    let job = Job { tools: tools.clone(), operations: vec![Operation::FinishRaster(FinishRaster { stepover: 3.0, grid: 0.5, ..FinishRaster::default() })], ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let reference = out.verification.as_ref().unwrap().report.clone();
    for dialect in Dialect::ALL {
        let mut job = job.clone();
        job.post.dialect = dialect;
        let gcode = write_gcode(&job.name, &out.paths, &tools, out.clearance_z, &job.post).unwrap();
        let v = job::verify_gcode(&job, demo_part(), &gcode, None, &mut Progress::none()).unwrap_or_else(|e| panic!("{dialect:?}: {e}"));
        assert!(v.report.is_clean(), "{dialect:?}: {}", v.report.describe());
        // The same cut as the job's own simulation, within a cell's rounding.
        let (a, b) = (v.report.removed, reference.removed);
        assert!((a - b).abs() <= 0.002 * b, "{dialect:?}: {a} mm³ removed against {b}");
    }
    // A LinuxCNC program is no GRBL program: its tool change is named.
    let mut grbl = job.clone();
    grbl.post.dialect = Dialect::Grbl;
    let linuxcnc = write_gcode(&job.name, &out.paths, &tools, out.clearance_z, &job.post).unwrap();
    let e = match job::verify_gcode(&grbl, demo_part(), &linuxcnc, None, &mut Progress::none()) {
        Ok(_) => panic!("a LinuxCNC program passed as a GRBL one"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("M6 is not a command GRBL 1.1"), "{e}");
}

/// Comments are ASCII on every built-in post: an operation named with "φ" and "×" is written
/// as "D" and "x" (a Fanuc program once had 6 lines a Fanuc control may refuse).
#[test]
fn comments_are_ascii_on_every_built_in_post() {
    let mut job = demo_job(Dialect::LinuxCnc, Units::Mm);
    job.name = "plate φ20 × 3".into();
    let Operation::FinishRaster(r) = &mut job.operations[0] else { unreachable!() };
    r.name = "finish φ6 ball – 30°".into();
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    for dialect in Dialect::ALL {
        let settings = PostSettings { dialect, ..PostSettings::default() };
        let (gcode, _) = swarf::post::write_program(&job.name, &out.paths, &job.tools, out.clearance_z, &settings).unwrap();
        let bad: Vec<&str> = gcode.lines().filter(|l| !l.is_ascii()).collect();
        assert!(bad.is_empty(), "{dialect:?}: {bad:?}");
        assert!(gcode.contains("finish D6 ball - 30 deg"), "{dialect:?}");
    }
}

/// Fanuc's N numbers never come back to N10: a program longer than the post's step allows is
/// numbered by ones, and past the largest number the rest goes unnumbered; every number read is
/// greater than the one before, and rs274 reads the program.
#[test]
fn line_numbers_never_wrap() {
    let tools = vec![Tool { number: 1, cutter: Cutter::flat(6.0), ..Tool::default() }];
    let path = |n: usize| Toolpath {
        name: "zigzag".into(),
        tool: 1,
        spindle_rpm: 10000.0,
        start: DVec3::new(0.0, 0.0, 1.0),
        moves: (0..n).map(|k| Move::Line { to: DVec3::new((k % 2) as f64, k as f64 * 0.001, 0.0), feed: 500.0 }).collect(),
        cycles: Vec::new(),
    };
    let settings = PostSettings { dialect: Dialect::Fanuc, ..PostSettings::default() };
    for (moves, step, unnumbered) in [(5_000, 10, false), (50_000, 1, false), (120_000, 1, true)] {
        let gcode = write_gcode("long", &[path(moves)], &tools, 5.0, &settings).unwrap();
        let numbers: Vec<u64> = gcode.lines().filter_map(|l| l.strip_prefix('N')?.split(' ').next()?.parse().ok()).collect();
        assert!(numbers.windows(2).all(|w| w[1] == w[0] + step), "{moves} moves: numbers go by {step}");
        assert!(*numbers.last().unwrap() <= 99_999);
        let bare = gcode.lines().filter(|l| !l.starts_with('N') && !l.starts_with('O') && *l != "%").count();
        assert_eq!(bare > 0, unnumbered, "{moves} moves");
        if moves == 5_000 {
            let readable: String = gcode.lines().filter(|l| !l.starts_with('O')).map(|l| format!("{l}\n")).collect();
            assert!(interpret(&readable, &tools).len() > 4_000);
        }
    }
}

/// A job is planned once, in millimetres, and the post only writes it: the same job with its
/// program in inches follows exactly the mm program's path (it once followed a path up to 1.39 mm
/// away, planned at the inch resolution), and rs274 reads both to within their resolutions.
#[test]
fn a_program_in_inches_follows_the_mm_programs_path() {
    use swarf::operations::RoughZlevel;
    let mut job = demo_job(Dialect::LinuxCnc, Units::Mm);
    job.tools.push(Tool { number: 1, cutter: Cutter { flute_length: 30.0, ..Cutter::flat(6.0) }, ..Tool::default() });
    job.operations.insert(0, Operation::RoughZlevel(RoughZlevel { tool: 1, roughing: Roughing { grid: 0.5, ..Roughing::default() }, ..RoughZlevel::default() }));
    let mm = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    job.post.units = Units::Inch;
    let inch = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert_eq!(mm.paths, inch.paths);
    for (out, units, resolution) in [(&mm, Units::Mm, 0.0005), (&inch, Units::Inch, 0.00005)] {
        let actual = interpret(&out.gcode, &job.tools);
        compare(&actual, &expected_at(&out.paths, out.clearance_z, 1.0 / units.mm(), Some(2.0 * resolution)), resolution);
    }
}

/// Issue 62: every comment fits its control's line, broken between words, and holds none of
/// the post's reserved characters: a job and a tool named at 300 characters with a `%` in
/// them, a tip diameter of 1e-300, the GRBL tool-change note.
#[test]
fn every_comment_fits_its_controls_line_whole_words_and_no_reserved_characters() {
    use swarf::post::write_program;
    let long = |what: &str| format!("{what} 50% {}", "walnut sign with rounded letters ".repeat(9)).trim_end().to_owned();
    let tools = vec![Tool { number: 1, name: long("tool"), cutter: Cutter::ball(6.0), ..Tool::default() }, Tool { number: 2, cutter: Cutter::v_bit(6.0, 60.0, 1e-300), ..Tool::default() }];
    let ops = vec![
        Operation::FinishRaster(FinishRaster { name: long("operation"), tool: 1, stepover: 2.0, grid: 0.5, ..FinishRaster::default() }),
        Operation::FinishRaster(FinishRaster { tool: 2, stepover: 3.0, grid: 0.5, angle: 90.0, ..FinishRaster::default() }),
    ];
    let job = Job { name: long("job"), tools: tools.clone(), operations: ops, simulation: swarf::job::Simulation { verify: false, ..Default::default() }, ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    for dialect in Dialect::ALL {
        let post = dialect.post();
        let max = post.max_line_length.unwrap_or_else(|| panic!("{dialect:?} names the longest line its control reads"));
        let settings = PostSettings { dialect, ..PostSettings::default() };
        let (gcode, _) = write_program(&job.name, &out.paths, &tools, out.clearance_z, &settings).unwrap();
        for line in gcode.lines() {
            assert!(line.chars().count() <= max, "{dialect:?}: a line of {} characters, more than {max}: {line}", line.chars().count());
            if post.tape_marked() && line != "%" {
                assert!(!line.contains('%'), "{dialect:?}: a % inside the program ends it on the control: {line}");
            }
        }
        // Every comment's words whole: the comments joined again hold each name and note in full.
        let said: String = gcode.lines().filter_map(|l| l.split_once(['(', ';']).map(|(_, c)| c.trim_end_matches(')').trim().to_owned())).collect::<Vec<_>>().join(" ");
        let percent = if post.tape_marked() { " percent" } else { "%" };
        for name in [&job.name, &tools[0].name] {
            let words = name.replace('%', percent);
            assert!(said.contains(&words), "{dialect:?}: {words:?} not whole in the comments:\n{said}");
        }
        if dialect == Dialect::Grbl {
            assert!(said.contains("then set Z zero again with the new tool -touch off- and resume"), "{said}");
            if let Some(said) = common::grblcheck(&gcode) {
                said.unwrap_or_else(|e| panic!("GRBL 1.1h's own parser refuses the program: {e}"));
            }
        }
        // LinuxCNC reads every line of its own dialect's and of the RS-274 posts'.
        if matches!(dialect, Dialect::LinuxCnc | Dialect::Mach3 | Dialect::Generic | Dialect::Grbl) {
            common::rs274(&gcode, &tools);
        }
    }
}

/// Issue 58: the machine's tool changer and length sensor in the program. Without a changer
/// a post with M6 still calls it (the control stops for the operator) and the comment before
/// it says which tool to put in by hand and how to measure it; with a sensor the operator
/// measures it there instead of touching off Z; a changer the post cannot call is warned of.
#[test]
fn tool_changes_follow_the_machines_changer_and_length_sensor() {
    use swarf::cutting::Machine;
    let tools = vec![Tool { number: 1, cutter: Cutter::ball(6.0), ..Tool::default() }, Tool { number: 2, cutter: Cutter::ball(3.0), ..Tool::default() }];
    let ops = vec![
        Operation::FinishRaster(FinishRaster { name: "coarse".into(), tool: 1, stepover: 3.0, allowance: 0.3, grid: 0.5, ..FinishRaster::default() }),
        Operation::FinishRaster(FinishRaster { name: "fine".into(), tool: 2, stepover: 3.0, grid: 0.5, angle: 90.0, ..FinishRaster::default() }),
    ];
    let builtin = |name: &str| Machine::builtin().into_iter().find(|m| m.name == name).unwrap();
    let run = |dialect: Dialect, machine: Machine| {
        let job = Job {
            tools: tools.clone(),
            operations: ops.clone(),
            machine,
            post: PostSettings { dialect, ..PostSettings::default() },
            simulation: swarf::job::Simulation { verify: false, ..Default::default() },
            ..Job::default()
        };
        job::run(&job, demo_part(), &mut Progress::none()).unwrap()
    };
    // The small VMC changes and measures its tools: M6 alone.
    let vmc = run(Dialect::LinuxCnc, builtin("small VMC"));
    assert!(!vmc.gcode.contains("by hand") && vmc.gcode.contains("T2 M6"), "{}", &vmc.gcode[..600]);
    // The router changes by hand and has no sensor: told before each M6, touching off Z.
    let router = run(Dialect::LinuxCnc, builtin("hobby router"));
    let said = "(change to tool 2 by hand: 3 mm ball end; set Z zero again with the new tool -touch off-)\nT2 M6";
    assert!(router.gcode.contains(said), "{}", router.gcode.lines().filter(|l| l.contains("tool")).collect::<Vec<_>>().join("\n"));
    assert!(router.gcode.contains("(change to tool 1 by hand"));
    assert_eq!(tool_calls(&router.gcode, &tools).iter().filter(|c| c.starts_with("CHANGE_TOOL")).count(), 2);
    // With a sensor on GRBL (no M6): the pause asks for the new tool measured on it.
    let sensed = run(Dialect::Grbl, Machine { length_sensor: Some(true), ..builtin("hobby router") });
    let pause = sensed.gcode.find("(change to tool 2: 3 mm ball end; then measure it on the tool length sensor").expect("the pause's note");
    assert!(sensed.gcode[pause..].lines().take(3).any(|l| l == "M0") && !sensed.gcode.contains("touch off"), "{}", &sensed.gcode[pause..pause + 200]);
    // A machine not said: the program as the post writes it.
    let unknown = run(Dialect::LinuxCnc, Machine::default());
    assert!(!unknown.gcode.contains("by hand"));
    // The VMC's changer on GRBL 1.1, which cannot call it: said.
    let grbl = run(Dialect::Grbl, builtin("small VMC"));
    assert!(grbl.warnings.iter().any(|w| w.to_string().contains("has a tool changer, but the post GRBL 1.1 has no tool change word")), "{:?}", grbl.warnings);
    assert!(!vmc.warnings.iter().any(|w| w.to_string().contains("tool changer")));
}
