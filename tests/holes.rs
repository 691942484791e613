//! Holes found in generated parts and drawings with known holes, and drilled: canned cycles
//! read by LinuxCNC's interpreter move the tool as the same cycles written out as moves (GRBL's
//! form, which GRBL's own parser reads); the programs verify clean.

mod common;

use std::process::Command;

use swarf::cutter::Cutter;
use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::holes::{mesh::find, Bottom, Hole};
use swarf::job::{self, Job, Operation, Tool};
use swarf::machining::holes::HolePick;
use swarf::mesh::Mesh;
use swarf::operations::{Bore, Chamfer, ChamferEdges, Drill, DrillCycle, Face, FacePattern, Hand, ReturnLevel, ThreadMill};
use swarf::post::Dialect;
use swarf::progress::Progress;

/// A hole of the generated block.
#[derive(Clone, Copy)]
enum Kind {
    Through { d: f64 },
    Blind { d: f64, depth: f64, cone: bool },
    Counterbore { big: f64, deep: f64, d: f64 },
}

#[derive(Clone, Copy)]
struct Spec {
    tile: (usize, usize),
    kind: Kind,
    /// Where the first vertex of its circles lies (radians): holes not lined up with the grid.
    phase: f64,
    sides: usize,
}

/// Half a drill's 118° point.
const POINT: f64 = 59.0 * std::f64::consts::PI / 180.0;

/// A block of `nx` × `ny` square tiles of side `side`, `thick` deep (top at 0), with the holes
/// of `specs` at their tiles' centres (tessellated cylinders, floors, cone bottoms, a
/// counterbore's annulus). Tiles meet at T-junctions, as many exported parts do.
fn block(nx: usize, ny: usize, side: f64, thick: f64, specs: &[Spec]) -> Mesh {
    let mut tris: Vec<[DVec3; 3]> = Vec::new();
    let mut push = |t: [DVec3; 3], hint: DVec3| {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        tris.push(if n.dot(hint) < 0.0 { [t[0], t[2], t[1]] } else { t });
    };
    let half = side / 2.0;
    for i in 0..nx {
        for j in 0..ny {
            let c = DVec2::new((i as f64 + 0.5) * side, (j as f64 + 0.5) * side);
            let spec = specs.iter().find(|s| s.tile == (i, j));
            let square = |z: f64| [c + DVec2::new(-half, -half), c + DVec2::new(half, -half), c + DVec2::new(half, half), c + DVec2::new(-half, half)].map(|p| p.extend(z));
            let plain = |z: f64, up: f64, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
                let q = square(z);
                push([q[0], q[1], q[2]], DVec3::Z * up);
                push([q[0], q[2], q[3]], DVec3::Z * up);
            };
            let Some(s) = spec else {
                plain(0.0, 1.0, &mut push);
                plain(-thick, -1.0, &mut push);
                continue;
            };
            let n = s.sides;
            let at = |k: usize, r: f64, z: f64| (c + DVec2::from_angle(s.phase + std::f64::consts::TAU * k as f64 / n as f64) * r).extend(z);
            // The face between the tile's square and a circle of radius `r` at `z`.
            let ring = |r: f64, z: f64, up: f64, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
                let on_square = |a: f64| {
                    let d = DVec2::from_angle(a);
                    (c + d * (half / d.x.abs().max(d.y.abs()))).extend(z)
                };
                for k in 0..n {
                    let (a0, a1) = (s.phase + std::f64::consts::TAU * k as f64 / n as f64, s.phase + std::f64::consts::TAU * (k + 1) as f64 / n as f64);
                    let (c0, c1) = (at(k, r, z), at(k + 1, r, z));
                    let mut outer = vec![on_square(a0)];
                    for q in 0..4 {
                        // The square's corners at 45°, 135°, …: those strictly inside this sector.
                        let corner = std::f64::consts::FRAC_PI_4 + q as f64 * std::f64::consts::FRAC_PI_2;
                        let mut rel = (corner - a0).rem_euclid(std::f64::consts::TAU);
                        if rel > 0.0 && rel < a1 - a0 {
                            rel += a0;
                            outer.push((c + DVec2::from_angle(rel) * half * std::f64::consts::SQRT_2).extend(z));
                        }
                    }
                    outer.push(on_square(a1));
                    push([c1, c0, outer[0]], DVec3::Z * up);
                    for w in outer.windows(2) {
                        push([c1, w[0], w[1]], DVec3::Z * up);
                    }
                }
            };
            let wall = |r: f64, top: f64, bottom: f64, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
                for k in 0..n {
                    let (a, b, cc, d) = (at(k, r, top), at(k + 1, r, top), at(k + 1, r, bottom), at(k, r, bottom));
                    let inward = (c - ((a + b) / 2.0).truncate()).extend(0.0);
                    push([a, b, cc], inward);
                    push([a, cc, d], inward);
                }
            };
            let floor = |r: f64, z: f64, cone: bool, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
                let apex = c.extend(if cone { z - r / POINT.tan() } else { z });
                for k in 0..n {
                    push([apex, at(k, r, z), at(k + 1, r, z)], DVec3::Z);
                }
            };
            match s.kind {
                Kind::Through { d } => {
                    ring(d / 2.0, 0.0, 1.0, &mut push);
                    wall(d / 2.0, 0.0, -thick, &mut push);
                    ring(d / 2.0, -thick, -1.0, &mut push);
                }
                Kind::Blind { d, depth, cone } => {
                    ring(d / 2.0, 0.0, 1.0, &mut push);
                    wall(d / 2.0, 0.0, -depth, &mut push);
                    floor(d / 2.0, -depth, cone, &mut push);
                    plain(-thick, -1.0, &mut push);
                }
                Kind::Counterbore { big, deep, d } => {
                    ring(big / 2.0, 0.0, 1.0, &mut push);
                    wall(big / 2.0, 0.0, -deep, &mut push);
                    for k in 0..n {
                        let (a, b, cc, e) = (at(k, big / 2.0, -deep), at(k + 1, big / 2.0, -deep), at(k + 1, d / 2.0, -deep), at(k, d / 2.0, -deep));
                        push([a, b, cc], DVec3::Z);
                        push([a, cc, e], DVec3::Z);
                    }
                    wall(d / 2.0, -deep, -thick, &mut push);
                    ring(d / 2.0, -thick, -1.0, &mut push);
                }
            }
        }
    }
    // The block's sides.
    let (w, h) = (nx as f64 * side, ny as f64 * side);
    let corners = [DVec2::new(0.0, 0.0), DVec2::new(w, 0.0), DVec2::new(w, h), DVec2::new(0.0, h)];
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        let out = DVec2::new(b.y - a.y, a.x - b.x).extend(0.0);
        push([a.extend(0.0), b.extend(0.0), b.extend(-thick)], out);
        push([a.extend(0.0), b.extend(-thick), a.extend(-thick)], out);
    }
    Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap()
}

const SIDE: f64 = 14.0;
const THICK: f64 = 10.0;

fn specs() -> Vec<Spec> {
    vec![
        Spec { tile: (0, 0), kind: Kind::Through { d: 6.0 }, phase: 0.0, sides: 64 },
        Spec { tile: (1, 0), kind: Kind::Blind { d: 8.0, depth: 5.0, cone: false }, phase: 0.12, sides: 48 },
        Spec { tile: (2, 0), kind: Kind::Blind { d: 5.0, depth: 6.0, cone: true }, phase: 0.05, sides: 40 },
        Spec { tile: (0, 1), kind: Kind::Counterbore { big: 11.0, deep: 3.0, d: 6.6 }, phase: 0.3, sides: 64 },
        // 0.75 mm from the block's side.
        Spec { tile: (2, 1), kind: Kind::Through { d: 12.5 }, phase: 0.7, sides: 72 },
        Spec { tile: (1, 2), kind: Kind::Through { d: 6.0 }, phase: 0.2, sides: 32 },
    ]
}

/// What each spec's holes must be: (centre, diameter, top, bottom, through, bottom).
fn expected(specs: &[Spec]) -> Vec<(DVec2, f64, f64, f64, Bottom)> {
    let mut out = Vec::new();
    for s in specs {
        let c = DVec2::new((s.tile.0 as f64 + 0.5) * SIDE, (s.tile.1 as f64 + 0.5) * SIDE);
        match s.kind {
            Kind::Through { d } => out.push((c, d, 0.0, -THICK, Bottom::Open)),
            Kind::Blind { d, depth, cone } => out.push((c, d, 0.0, -depth, if cone { Bottom::Cone } else { Bottom::Flat })),
            Kind::Counterbore { big, deep, d } => {
                out.push((c, big, 0.0, -deep, Bottom::Flat));
                out.push((c, d, -deep, -THICK, Bottom::Open));
            }
        }
    }
    out
}

#[test]
fn every_hole_of_a_generated_block_is_found_with_its_size_and_depth() {
    let specs = specs();
    let part = block(3, 3, SIDE, THICK, &specs);
    let started = std::time::Instant::now();
    let found = find(&part);
    eprintln!("{} holes found in {} triangles in {:.1} ms", found.len(), part.faces.len(), started.elapsed().as_secs_f64() * 1e3);
    let want = expected(&specs);
    assert_eq!(found.len(), want.len(), "{found:#?}");
    for (c, d, top, bottom, shape) in want {
        let h: &Hole = found.iter().find(|h| h.center.distance(c) < 0.01 && (h.diameter - d).abs() < 0.01).unwrap_or_else(|| panic!("no φ{d} hole at {c}: {found:#?}"));
        // The fitted circle passes through the tessellation's vertices: the diameter is exact.
        assert!((h.diameter - d).abs() < 0.01 && (h.top - top).abs() < 0.01 && (h.bottom - bottom).abs() < 0.01, "{h:?} against φ{d} {top}..{bottom}");
        assert_eq!((h.through, h.bottom_shape), (shape == Bottom::Open, shape), "{h:?}");
    }
    // A counterbore is two holes on one axis, the wider first.
    let k = found.iter().position(|h| (h.diameter - 11.0).abs() < 0.01).unwrap();
    assert!((found[k + 1].diameter - 6.6).abs() < 0.01 && found[k + 1].center.distance(found[k].center) < 1e-6);
}

#[test]
fn parts_without_holes_have_none() {
    assert!(find(&block(3, 2, SIDE, THICK, &[])).is_empty(), "a plain block");
    assert!(find(&swarf::mesh::sample::demo_part()).is_empty(), "the sample part");
    assert!(find(&common::mesa(20.0, 5.0, 30.0)).is_empty(), "a mesa");
    // A round boss is no hole: its normals point away from its axis.
    let n = 48;
    let at = |k: usize, z: f64| (DVec2::from_angle(std::f64::consts::TAU * k as f64 / n as f64) * 5.0).extend(z);
    let mut tris = Vec::new();
    for k in 0..n {
        tris.push([at(k, 0.0), at(k + 1, 0.0), at(k + 1, 8.0)]);
        tris.push([at(k, 0.0), at(k + 1, 8.0), at(k, 8.0)]);
        tris.push([DVec3::new(0.0, 0.0, 8.0), at(k, 8.0), at(k + 1, 8.0)]);
        tris.push([DVec3::ZERO, at(k + 1, 0.0), at(k, 0.0)]);
    }
    assert!(find(&common::mesh(tris)).is_empty(), "a round boss");
}

fn drill_tool(number: u32, cutter: Cutter) -> Tool {
    Tool { number, cutter: Cutter { flute_length: 30.0, ..cutter }, spindle_rpm: 3000.0, feed_rate: 300.0, plunge_rate: 150.0, ..Tool::default() }
}

fn drilling_job(dialect: Dialect) -> Job {
    let mut job = Job {
        tools: vec![drill_tool(1, Cutter { shape: swarf::cutter::Shape::SpotDrill, diameter: 10.0, angle: Some(90.0), ..Cutter::default() }), drill_tool(2, Cutter::drill(6.0, 118.0))],
        ..Job::default()
    };
    job.post.dialect = dialect;
    let six = |cycle| Drill { tool: 2, cycle, pick: HolePick { min_diameter: Some(5.9), max_diameter: Some(6.1), ..HolePick::default() }, ..Drill::default() };
    job.operations = vec![
        Operation::Drill(Drill {
            name: "spot".into(),
            tool: 1,
            cycle: DrillCycle::Spot,
            pick: HolePick { max_diameter: Some(7.0), ..HolePick::default() },
            return_to: ReturnLevel::Retract,
            ..Drill::default()
        }),
        Operation::Drill(Drill { name: "peck".into(), ..six(DrillCycle::Peck) }),
        Operation::Drill(Drill { name: "chip".into(), peck: 1.5, return_to: ReturnLevel::Retract, ..six(DrillCycle::ChipBreak) }),
        Operation::Drill(Drill { name: "dwell".into(), dwell: 0.5, ..six(DrillCycle::Dwell) }),
    ];
    job
}

/// rs274's motions of a program: (call, end) for each traverse and feed that goes somewhere
/// (the interpreter repeats a cycle's position when the tool is already there), and the dwells.
fn canon(gcode: &str, tools: &[Tool]) -> Vec<(String, DVec3)> {
    let out = common::rs274(gcode, tools);
    let mut motions: Vec<(String, DVec3)> = out
        .lines()
        .filter_map(|line| {
            let call = line.split_once('(').map(|(a, b)| (a.split_whitespace().last().unwrap_or(""), b))?;
            let args: Vec<f64> = call.1.trim_end_matches(')').split([',', ' ']).filter_map(|w| w.trim().parse().ok()).collect();
            match call.0 {
                "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => Some((call.0.to_string(), DVec3::new(args[0], args[1], args[2]))),
                "DWELL" => Some(("DWELL".to_string(), DVec3::splat(args[0]))),
                _ => None,
            }
        })
        .collect();
    motions.dedup_by(|b, a| b.0 != "DWELL" && b.1 == a.1);
    motions
}

/// A clamp over one hole of the block (issue 57): the drilling leaves that hole out whole and
/// says so, drills the rest, and its program runs clear of the clamp.
#[test]
fn a_hole_under_a_clamp_is_left_out_and_said() {
    use swarf::job::fixtures::{FixtureBox, Fixtures};
    let part = block(3, 3, SIDE, THICK, &specs());
    let mut job = drilling_job(Dialect::LinuxCnc);
    let free = job::run(&job, part.clone(), &mut Progress::none()).expect("drilled");
    let cycles = |out: &job::JobOutput| out.paths.iter().map(|p| p.cycles.iter().map(|c| c.at).collect::<Vec<_>>()).collect::<Vec<_>>();
    let all = cycles(&free);
    let (c, top) = (all[1][0], free.stock.max.z);
    job.fixtures = Fixtures { boxes: vec![FixtureBox { name: "the clamp".into(), min: [c.x - 4.0, c.y - 4.0, top], max: [c.x + 4.0, c.y + 4.0, top + 8.0] }], ..Fixtures::default() };
    let held = job::run(&job, part, &mut Progress::none()).expect("drilled");
    let v = held.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert_eq!((v.report.fixtures_checked, v.report.fixture_collision_count), (1, 0));
    // Each operation drills what it did but the hole under the clamp.
    for (before, after) in all.iter().zip(cycles(&held)) {
        let expected: Vec<DVec2> = before.iter().copied().filter(|&h| h != c).collect();
        assert_eq!(after, expected);
    }
    let said: Vec<String> = held.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(said.iter().filter(|w| w.contains("holes left out: drilling them would run into the clamp (1 mm clear of it)")).count(), all.iter().filter(|p| p.contains(&c)).count(), "{said:?}");
    // The holes after the one left out are still canned cycles, and read as LinuxCNC reads them.
    for word in ["G99 G81", "G98 G83", "G99 G73", "G98 G82"] {
        assert!(held.gcode.contains(word), "{word} in the program");
    }
    common::rs274(&held.gcode, &job.tools);
}

#[test]
fn holes_drilled_in_canned_cycles_move_as_the_same_cycles_written_out() {
    let specs = specs();
    let part = block(3, 3, SIDE, THICK, &specs);
    let job = drilling_job(Dialect::LinuxCnc);
    let out = job::run(&job, part.clone(), &mut Progress::none()).expect("drilled");
    let v = out.verification.as_ref().expect("verified");
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let gcode = &out.gcode;
    for word in ["G99 G81", "G98 G83", "G99 G73", "G98 G82", "G80"] {
        assert!(gcode.contains(word), "{word} in the program");
    }
    assert!(gcode.contains(" P0.5 "), "G82's dwell in seconds");
    // Where the drill goes: the placed holes, as `swarf holes` lists them.
    let holes = job.holes(part.clone()).unwrap();
    let through: Vec<&Hole> = holes.iter().filter(|h| (h.diameter - 6.0).abs() < 0.01).collect();
    assert_eq!(through.len(), 2);
    let tip = 3.0 / POINT.tan();
    for h in &through {
        // A feed's Z is written rounded up.
        let bottom = ((h.bottom - tip - 0.5) * 1000.0 - 1e-6).ceil() / 1000.0;
        let text = format!("X{} Y{} Z{}", short(h.center.x), short(h.center.y), short(bottom));
        assert!(gcode.contains(&text), "the drill goes through by its point and 0.5 mm: {text}");
    }
    // The same paths written by a post without canned cycles: rs274 makes the same motions
    // of both.
    let mut expanded = job.clone();
    expanded.post.custom = Some(swarf::post::Post { canned_cycles: false, ..Dialect::LinuxCnc.post() });
    let out2 = job::run(&expanded, part.clone(), &mut Progress::none()).unwrap();
    assert!(!out2.gcode.contains("G83") && !out2.gcode.lines().any(|l| l == "G80"), "no canned cycle written");
    assert!(out2.gcode.contains("G4 P0.5"), "the dwell written out");
    let (a, b) = (canon(gcode, &job.tools), canon(&out2.gcode, &job.tools));
    assert!(a.len() > 40, "{} motions", a.len());
    assert_eq!(a.len(), b.len(), "as many motions in both");
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert!(x.0 == y.0 && x.1.distance(y.1) < 2e-3, "motion {k}: {x:?} canned against {y:?} written out");
    }
    assert!((out.cycle.seconds - out2.cycle.seconds).abs() < 0.5, "cycle {} against {}", out.cycle.seconds, out2.cycle.seconds);
    // Read back, the canned program is the planned one.
    let read = swarf::job::verify_gcode(&job, part.clone(), gcode, None, &mut Progress::none()).unwrap();
    assert!(read.report.is_clean(), "{}", read.report.describe());
    let planned: usize = out.paths.iter().map(|p| p.moves.len()).sum();
    let read_back: usize = swarf::post::read::read_gcode(gcode, 1).unwrap().iter().map(|p| p.moves.len()).sum();
    assert!(read_back >= planned && read_back <= planned + 12, "read back {read_back} moves against {planned} planned");
}

/// A length as the LinuxCNC post writes it.
fn short(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

#[test]
fn grbl_gets_the_cycles_as_moves_its_own_parser_reads() {
    let part = block(3, 3, SIDE, THICK, &specs());
    for dialect in [Dialect::Grbl, Dialect::GrblHal] {
        let out = job::run(&drilling_job(dialect), part.clone(), &mut Progress::none()).unwrap();
        assert!(out.verification.as_ref().unwrap().report.is_clean());
        for word in ["G81", "G82", "G83", "G73", "G80", "G98", "G99"] {
            assert!(!out.gcode.contains(word), "{dialect:?}: no {word}");
        }
        assert!(out.gcode.contains("G4 P0.5"));
        // GRBL 1.1h's parser reads every line as grblHAL does but grblHAL's tool changes (M6).
        let without_changes: String = out.gcode.lines().filter(|l| !l.contains("M6")).map(|l| format!("{l}\n")).collect();
        if let Some(said) = common::grblcheck(&without_changes) {
            said.unwrap_or_else(|e| panic!("{dialect:?}: {e}"));
        }
    }
}

#[test]
fn fanuc_dwells_in_milliseconds_and_reads_back_alike() {
    let part = block(3, 3, SIDE, THICK, &specs());
    let out = job::run(&drilling_job(Dialect::Fanuc), part.clone(), &mut Progress::none()).unwrap();
    assert!(out.gcode.lines().any(|l| l.contains("G82") && l.contains(" P500 ")), "G82 P500");
    let paths = swarf::post::read::read_gcode(&out.gcode, 1).unwrap();
    let dwells: f64 = paths.iter().map(|p| p.dwell_seconds()).sum();
    assert!((dwells - 1.0).abs() < 1e-9, "two holes dwell 0.5 s each: {dwells}");
}

/// What the job's checks say as the settings are typed, once the holes are known (issue 55),
/// at `path`: the same words the plan refuses with. Without the holes nothing is said.
fn said_as_typed(job: &Job, part: &Mesh, path: &str, words: &str) {
    assert!(job.problems().is_empty(), "{:?}", job.problems());
    let holes = job.holes(part.clone()).unwrap();
    let problems = job.problems_with(job::Known { holes: Some(&holes), ..Default::default() });
    let p = problems.iter().find(|p| p.path == path).unwrap_or_else(|| panic!("nothing at {path}: {problems:?}"));
    assert!(p.message.contains(words), "{}", p.message);
}

#[test]
fn a_drill_deeper_than_its_flutes_and_a_spot_without_a_cone_are_refused() {
    let part = block(3, 3, SIDE, THICK, &specs());
    // The holes known, a good job is clean.
    let job = drilling_job(Dialect::LinuxCnc);
    let holes = job.holes(part.clone()).unwrap();
    assert!(job.problems_with(job::Known { holes: Some(&holes), ..Default::default() }).is_empty());
    let mut job = drilling_job(Dialect::LinuxCnc);
    job.tools[1].cutter.flute_length = 8.0;
    let e = job::run(&job, part.clone(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("deeper than T2's flutes (8 mm)"), "{e}");
    // As typed: at the drilling's tool (its depth is the hole's own), or at its depth.
    said_as_typed(&job, &part, "operations[1].tool", "deeper than T2's flutes (8 mm)");
    if let Operation::Drill(d) = &mut job.operations[1] {
        d.depth = Some(9.0);
    }
    said_as_typed(&job, &part, "operations[1].depth", "9.00 mm deep, deeper than T2's flutes (8 mm)");
    let mut job = drilling_job(Dialect::LinuxCnc);
    job.tools[0].cutter = Cutter::flat(6.0);
    let e = job::run(&job, part.clone(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("spotting needs a spot drill"), "{e}");
    // A peck deeper than the hole is named.
    let mut job = drilling_job(Dialect::LinuxCnc);
    if let Operation::Drill(d) = &mut job.operations[1] {
        d.peck = 20.0;
    }
    let e = job::run(&job, part.clone(), &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("the peck (20 mm) is deeper than the hole"), "{e}");
    said_as_typed(&job, &part, "operations[1].peck", "the peck (20 mm) is deeper than the hole");
    // A cone in a 3D operation is named.
    let mut job = drilling_job(Dialect::LinuxCnc);
    job.operations = vec![Operation::RoughZlevel(swarf::operations::RoughZlevel { tool: 2, ..Default::default() })];
    let e = job::run(&job, part, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("T2 is a 6 mm drill 118°: 'rough' cuts with flat, ball and bull-nose tools") || e.contains("T2 is a 6 mm drill 118°"), "{e}");
}

#[test]
fn a_drawings_circles_are_spotted_and_drilled_through_the_sheet() {
    // A plate 60 × 40 with four φ5 holes, a φ8 one, and a slot that is no hole.
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40">
      <rect x="0" y="0" width="60" height="40" fill="none" stroke="black"/>
      <circle cx="8" cy="8" r="2.5"/><circle cx="52" cy="8" r="2.5"/><circle cx="52" cy="32" r="2.5"/><circle cx="8" cy="32" r="2.5"/>
      <circle cx="30" cy="20" r="4"/>
      <rect x="20" y="30" width="20" height="4" rx="2"/>
    </svg>"#;
    let drawing = swarf::drawing::import::read_drawing(svg.as_bytes(), Some("plate.svg"), &Tolerances::DEFAULT).unwrap();
    let mut job = Job::default_for_drawing();
    job.drawing.thickness = 6.0;
    let holes = job.holes(drawing.clone()).unwrap();
    assert_eq!(holes.len(), 5, "{holes:#?}");
    assert_eq!(holes.iter().filter(|h| (h.diameter - 5.0).abs() < 1e-6).count(), 4);
    assert!(holes.iter().all(|h| h.through && (h.top - 0.0).abs() < 1e-9 && (h.bottom + 6.0).abs() < 1e-9));
    job.tools = vec![drill_tool(1, Cutter { shape: swarf::cutter::Shape::SpotDrill, diameter: 10.0, angle: Some(90.0), ..Cutter::default() }), drill_tool(2, Cutter::drill(5.0, 118.0))];
    let profile = job.operations[0].clone();
    job.tools.push(Tool { number: 3, cutter: Cutter::flat(3.0), ..Tool::default() });
    let profile = match profile {
        Operation::Profile2d(p) => Operation::Profile2d(swarf::operations::Profile2d { tool: 3, ..p }),
        other => other,
    };
    job.operations = vec![
        Operation::Drill(Drill { name: "spot".into(), tool: 1, cycle: DrillCycle::Spot, ..Drill::default() }),
        Operation::Drill(Drill { name: "drill".into(), tool: 2, cycle: DrillCycle::Peck, pick: HolePick { max_diameter: Some(5.1), ..HolePick::default() }, ..Drill::default() }),
        profile,
    ];
    // Drilled alone, the holes are the drill's to cut: the sheet's verification holds the rest.
    let alone = Job { operations: job.operations[..2].to_vec(), ..job.clone() };
    let out = job::run(&alone, drawing.clone(), &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.is_clean(), "{}", out.verification.as_ref().unwrap().report.describe());
    // A drill wider than the holes cuts into the plate: a gouge.
    let mut wide = alone.clone();
    wide.tools[1].cutter.diameter = 5.5;
    let out = job::run(&wide, drawing.clone(), &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.gouge_count > 0, "a φ5.5 drill in φ5 holes gouges");
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl] {
        job.post.dialect = dialect;
        let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap();
        assert!(out.verification.as_ref().unwrap().report.is_clean(), "{}", out.verification.as_ref().unwrap().report.describe());
        canon(&out.gcode, &job.tools);
        if dialect == Dialect::Grbl {
            if let Some(said) = common::grblcheck(&out.gcode) {
                said.unwrap();
            }
        } else {
            assert_eq!(out.gcode.matches("G98 G83").count(), 4, "four φ5 holes pecked");
            assert_eq!(out.gcode.matches("G98 G81").count(), 5, "five spots");
        }
    }
}

/// What `swarf ARGS [--job JOB] PART` prints, `part` (and `job`) written to a scratch folder
/// named for `what`; it must succeed.
fn listed(what: &str, args: &[&str], part: &Mesh, job: Option<&Job>) -> String {
    let dir = std::env::temp_dir().join(format!("swarf-{what}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("part.stl"), part.to_binary_stl()).unwrap();
    let mut command = Command::new(env!("CARGO_BIN_EXE_swarf"));
    command.args(args);
    if let Some(job) = job {
        std::fs::write(dir.join("job.json"), serde_json::to_string(job).unwrap()).unwrap();
        command.arg("--job").arg(dir.join("job.json"));
    }
    let out = command.arg(dir.join("part.stl")).output().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "swarf {args:?}: {text}{}", String::from_utf8_lossy(&out.stderr));
    text
}

/// `swarf holes` lists a part's holes with their sizes.
#[test]
fn the_cli_lists_holes() {
    let part = block(3, 3, SIDE, THICK, &specs());
    let dir = std::env::temp_dir().join(format!("swarf-holes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stl = dir.join("block.stl");
    std::fs::write(&stl, part.to_binary_stl()).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_swarf")).arg("holes").arg(&stl).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("7 holes: 1 × φ5, 2 × φ6, 1 × φ6.6, 1 × φ8, 1 × φ11, 1 × φ12.5"), "{text}");
    assert!(text.contains("blind, cone bottom") && text.contains("blind, flat bottom") && text.contains("through"), "{text}");
    // A drawing's circles, listed by `swarf drawing` with its loops.
    let svg = dir.join("plate.svg");
    std::fs::write(&svg, r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40"><rect x="0" y="0" width="60" height="40" fill="none" stroke="black"/><circle cx="8" cy="8" r="2.5"/><circle cx="52" cy="8" r="2.5"/><circle cx="30" cy="20" r="4"/></svg>"#).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_swarf")).arg("drawing").arg(&svg).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("holes: 2 × φ5, 1 × φ8") && text.contains("φ8.000 at (30.000, -20.000) mm"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The nearest the tool's edge comes to a hole's wall (its radius minus the tool centre's
/// distance from the axis and the tool's radius), along every move of `path` near the hole,
/// at points 0.05 mm apart.
fn nearest_to_wall(path: &swarf::toolpath::Toolpath, hole: &Hole, r_tool: f64) -> f64 {
    let mut nearest = f64::INFINITY;
    for (a, b, _) in path.segments(0.01) {
        let n = ((a.distance(b) / 0.05).ceil() as usize).max(1);
        for k in 0..=n {
            let p = a.lerp(b, k as f64 / n as f64);
            if p.z < hole.top && p.truncate().distance(hole.center) < hole.diameter {
                nearest = nearest.min(hole.diameter / 2.0 - p.truncate().distance(hole.center) - r_tool);
            }
        }
    }
    nearest
}

fn boring_job(dialect: Dialect, bore: Bore) -> Job {
    let mut job = Job { tools: vec![Tool { number: 1, cutter: Cutter { flute_length: 15.0, ..Cutter::flat(4.0) }, feed_rate: 600.0, plunge_rate: 200.0, ..Tool::default() }], ..Job::default() };
    job.post.dialect = dialect;
    job.operations = vec![Operation::Bore(bore)];
    job
}

#[test]
fn holes_wider_than_the_tool_are_bored_on_a_helix_never_nearer_the_wall_than_asked() {
    let part = block(3, 3, SIDE, THICK, &specs());
    // The φ12.5 through hole (rings: three times the tool), the φ8 blind one and the φ11
    // counterbore, with a finishing step and 0.1 mm left on the walls.
    for (leave, finish) in [(0.0, 0.0), (0.1, 0.2)] {
        let bore = Bore { pick: HolePick { min_diameter: Some(7.9), ..HolePick::default() }, leave_stock: leave, finish_step: finish, pitch: 1.0, ..Bore::default() };
        let job = boring_job(Dialect::LinuxCnc, bore);
        let out = job::run(&job, part.clone(), &mut Progress::none()).expect("bored");
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{}", v.report.describe());
        let holes = job.holes(part.clone()).unwrap();
        for h in holes.iter().filter(|h| h.diameter > 7.9) {
            let near = nearest_to_wall(&out.paths[0], h, 2.0);
            assert!(near >= leave - 1e-6 && near <= leave + 0.01, "φ{} with {leave} left: the tool comes {near:.4} mm from the wall", h.diameter);
        }
        // Helices: arcs that move Z, at most a pitch per turn, counter-clockwise (climb).
        let mut at = out.paths[0].start;
        let mut helices = 0;
        for m in &out.paths[0].moves {
            if let swarf::toolpath::Move::Arc { to, clockwise, center, .. } = *m {
                assert!(!clockwise, "climb: counter-clockwise");
                if (to.z - at.z).abs() > 1e-9 {
                    helices += 1;
                    let turn = swarf::toolpath::arc_sweep(at, to, center, false).abs() / std::f64::consts::TAU;
                    assert!((to.z - at.z).abs() <= 1.0 * turn + 1e-6, "a pitch of at most 1 mm a turn: {at} to {to} about {center}, {turn} turns");
                }
            }
            at = m.to();
        }
        assert!(helices > 20, "{helices} helical arcs");
        canon(&out.gcode, &job.tools);
        // Whatever is left in the holes is under the leave-stock (the floor of the blind
        // hole flat, the wall at its radius): the simulated stock inside them.
        let residual = v.report.residual_max;
        assert!(residual.is_finite());
    }
    // GRBL reads the helices.
    let out = job::run(&boring_job(Dialect::Grbl, Bore { pick: HolePick { min_diameter: Some(12.0), ..HolePick::default() }, ..Bore::default() }), part.clone(), &mut Progress::none()).unwrap();
    if let Some(said) = common::grblcheck(&out.gcode) {
        said.unwrap();
    }
    // A tool as wide as the hole is refused by name.
    let mut wide = boring_job(Dialect::LinuxCnc, Bore { pick: HolePick { max_diameter: Some(5.5), ..HolePick::default() }, ..Bore::default() });
    wide.tools[0].cutter.diameter = 5.0;
    let e = job::run(&wide, part.clone(), &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("does not fit the φ5 hole"), "{e}");
    said_as_typed(&wide, &part, "operations[0].tool", "does not fit the φ5 hole");
}

#[test]
fn chamfers_lie_on_the_cone_at_the_asked_width_and_nowhere_else() {
    let part = block(3, 3, SIDE, THICK, &specs());
    let mut job = Job { tools: vec![Tool { number: 1, cutter: Cutter { flute_length: 10.0, ..Cutter::v_bit(6.0, 90.0, 0.0) }, ..Tool::default() }], ..Job::default() };
    job.stock.margin_top = 0.0;
    let width = 0.6;
    job.operations = vec![Operation::Chamfer(Chamfer { width, pick: HolePick { max_diameter: Some(8.5), ..HolePick::default() }, ..Chamfer::default() })];
    let out = job::run(&job, part.clone(), &mut Progress::none()).expect("chamfered");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert!(out.warnings.iter().any(|w| w.to_string().contains("1 holes lie below the part around them")), "the counterbore's hole is left: {:?}", out.warnings);
    let grid = v.stock.grid();
    let holes = job.holes(part.clone()).unwrap();
    let mut checked = 0;
    for h in holes.iter().filter(|h| h.diameter < 8.5 && h.top > -1e-9) {
        let r_hole = h.diameter / 2.0;
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let p = grid.node(i, j);
                let r = p.distance(h.center);
                let top = v.stock.top(i, j);
                if r > r_hole + 0.05 && r < r_hole + width - 0.05 {
                    // On the 45° cone: as deep below the top as it is inside the chamfer's rim.
                    let ideal = h.top - (r_hole + width - r);
                    assert!((top - ideal).abs() < 0.01, "φ{} at r {r:.3}: stock at {top:.4}, the chamfer at {ideal:.4}", h.diameter);
                    checked += 1;
                } else if r > r_hole + width + 0.05 && r < r_hole + width + 3.0 {
                    assert!(top >= h.top - 1e-6, "φ{} at r {r:.3}: cut to {top:.4} beyond the chamfer", h.diameter);
                }
            }
        }
    }
    assert!(checked > 50, "{checked} cells on the chamfers");
    canon(&out.gcode, &job.tools);
    // A chamfer the cone cannot make in one circle is refused by name.
    let mut wide = job.clone();
    wide.operations = vec![Operation::Chamfer(Chamfer { width: 3.5, ..Chamfer::default() })];
    let e = job::run(&wide, part, &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("needs a cone"), "{e}");
}

fn threading_job(dialect: Dialect, op: ThreadMill) -> Job {
    let tool =
        Tool { number: 1, cutter: Cutter { shape: swarf::cutter::Shape::ThreadMill, diameter: 4.0, flute_length: 12.0, ..Cutter::default() }, feed_rate: 300.0, plunge_rate: 200.0, ..Tool::default() };
    let mut job = Job { tools: vec![tool], ..Job::default() };
    job.stock.margin_top = 0.0;
    job.post.dialect = dialect;
    job.operations = vec![Operation::ThreadMill(op)];
    job
}

#[test]
fn threads_are_milled_a_pitch_a_turn_to_their_major_diameter() {
    let part = block(3, 3, SIDE, THICK, &specs());
    // M6 in the φ5 blind hole, M8 in the counterbore's φ6.6 hole; right hand in two passes,
    // then left hand.
    for (thread, pick, hand) in [("M6", (4.9, 5.1), Hand::Right), ("M8", (6.5, 6.7), Hand::Right), ("M6", (4.9, 5.1), Hand::Left)] {
        let op = ThreadMill { thread: thread.into(), hand, passes: 2, pick: HolePick { min_diameter: Some(pick.0), max_diameter: Some(pick.1), ..HolePick::default() }, ..ThreadMill::default() };
        let (major, pitch) = op.size().unwrap();
        let job = threading_job(Dialect::LinuxCnc, op);
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap_or_else(|e| panic!("{thread}: {e}"));
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{thread}: {}", v.report.describe());
        let h = job.holes(part.clone()).unwrap().into_iter().find(|h| h.diameter > pick.0 && h.diameter < pick.1).unwrap();
        // Every helical arc about the hole's axis: counter-clockwise (climb), half a pitch a
        // half turn, rising for a right-hand thread; the last pass's radius reaches the major
        // diameter with the tool's edge.
        let (mut at, mut rises, mut falls, mut widest) = (out.paths[0].start, 0, 0, 0.0f64);
        for m in &out.paths[0].moves {
            if let swarf::toolpath::Move::Arc { to, center, clockwise, .. } = *m {
                assert!(!clockwise, "{thread}: climb");
                if center.distance(h.center) < 1e-9 {
                    let turn = swarf::toolpath::arc_sweep(at, to, center, false) / std::f64::consts::TAU;
                    assert!(((to.z - at.z).abs() - pitch * turn).abs() < 1e-6, "{thread}: {} mm in {turn} turns", to.z - at.z);
                    if to.z > at.z {
                        rises += 1
                    } else {
                        falls += 1
                    }
                    widest = widest.max(to.truncate().distance(center));
                }
            }
            at = m.to();
        }
        assert!(if hand == Hand::Right { rises > 10 && falls == 0 } else { falls > 10 && rises == 0 }, "{thread} {hand:?}: {rises} up, {falls} down");
        assert!((widest + 2.0 - major / 2.0).abs() < 1e-9, "{thread}: the tool reaches φ{}", 2.0 * (widest + 2.0));
        // The simulated stock: the thread's annulus cut, nothing beyond the major diameter.
        let grid = v.stock.grid();
        let (mut cut, mut beyond) = (0, 0);
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let r = grid.node(i, j).distance(h.center);
                let top = v.stock.top(i, j);
                if r > h.diameter / 2.0 + 0.05 && r < major / 2.0 - 0.05 {
                    assert!(top < h.top - 1.0, "{thread}: the thread's annulus at r {r:.3} stands at {top:.3}");
                    cut += 1;
                } else if r > major / 2.0 + 0.05 && r < major / 2.0 + 2.0 && top < h.top - 1e-6 {
                    beyond += 1;
                }
            }
        }
        assert!(cut > 10 && beyond == 0, "{thread}: {cut} cells cut in the annulus, {beyond} beyond it");
        canon(&out.gcode, &job.tools);
    }
    let grbl = threading_job(Dialect::Grbl, ThreadMill { thread: "M6".into(), pick: HolePick { max_diameter: Some(5.1), ..HolePick::default() }, ..ThreadMill::default() });
    let out = job::run(&grbl, part.clone(), &mut Progress::none()).unwrap();
    if let Some(said) = common::grblcheck(&out.gcode) {
        said.unwrap();
    }
    // A thread mill wider than the minor diameter, and a thread in a wider hole, are refused.
    let e = job::run(
        &threading_job(Dialect::LinuxCnc, ThreadMill { thread: "M4".into(), pick: HolePick { max_diameter: Some(5.1), ..HolePick::default() }, ..ThreadMill::default() }),
        part.clone(),
        &mut Progress::none(),
    )
    .map(|_| ())
    .unwrap_err()
    .to_string();
    assert!(e.contains("does not fit the thread's minor diameter"), "{e}");
    let e = job::run(
        &threading_job(Dialect::LinuxCnc, ThreadMill { thread: "M6".into(), pick: HolePick { min_diameter: Some(7.0), max_diameter: Some(9.0), ..HolePick::default() }, ..ThreadMill::default() }),
        part,
        &mut Progress::none(),
    )
    .map(|_| ())
    .unwrap_err()
    .to_string();
    assert!(e.contains("wider than the thread's major diameter"), "{e}");
}

#[test]
fn facing_leaves_the_top_flat_at_its_height_over_the_whole_stock() {
    // The generated block under 2.5 mm of stock, faced down to its top at 1 mm a level.
    let part = block(3, 3, SIDE, THICK, &[]);
    for pattern in [FacePattern::Zigzag, FacePattern::Spiral] {
        let mut job = Job { tools: vec![Tool { number: 1, cutter: Cutter::flat(10.0), feed_rate: 1200.0, ..Tool::default() }], ..Job::default() };
        job.stock.margin_top = 2.5;
        job.operations = vec![Operation::Face(Face { pattern, ..Face::default() })];
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap_or_else(|e| panic!("{pattern:?}: {e}"));
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{pattern:?}: {}", v.report.describe());
        let grid = v.stock.grid();
        let (mut lowest, mut highest) = (f64::INFINITY, f64::NEG_INFINITY);
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let top = v.stock.top(i, j);
                lowest = lowest.min(top);
                highest = highest.max(top);
            }
        }
        // The part's top is at 0 (placed), the stock's at 2.5: every cell at 0, no ridge.
        assert!(lowest > -0.01 && highest < 0.01, "{pattern:?}: the faced top spans {lowest:.4} to {highest:.4}");
        // Three levels (2.5 mm at most 1 mm each), each entered from outside the stock.
        let levels: Vec<f64> = out.paths[0]
            .moves
            .iter()
            .filter_map(|m| match m {
                swarf::toolpath::Move::Rapid { to } if to.z < 2.0 => Some(to.z),
                _ => None,
            })
            .collect();
        assert_eq!(levels.len(), 3, "{pattern:?}: {levels:?}");
        canon(&out.gcode, &job.tools);
        if let Some(said) =
            common::grblcheck(&job::run(&Job { post: swarf::post::PostSettings { dialect: Dialect::Grbl, ..job.post.clone() }, ..job.clone() }, part.clone(), &mut Progress::none()).unwrap().gcode)
        {
            said.unwrap();
        }
        eprintln!("{pattern:?}: cycle {:.0} s", out.cycle.seconds);
    }
    // A sheet is faced by a depth.
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40"><rect x="0" y="0" width="60" height="40" fill="none" stroke="black"/></svg>"#;
    let drawing = swarf::drawing::import::read_drawing(svg.as_bytes(), Some("sheet.svg"), &Tolerances::DEFAULT).unwrap();
    let mut job = Job::default_for_drawing();
    job.tools = vec![Tool { number: 1, cutter: Cutter::flat(10.0), ..Tool::default() }];
    job.operations = vec![Operation::Face(Face::default())];
    let e = job::run(&job, drawing.clone(), &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("give the depth"), "{e}");
    job.operations = vec![Operation::Face(Face { depth: Some(0.5), ..Face::default() })];
    let out = job::run(&job, drawing, &mut Progress::none()).unwrap();
    let lowest = out.paths[0].moves.iter().map(|m| m.to().z).fold(f64::INFINITY, f64::min);
    assert!((lowest + 0.5).abs() < 1e-9, "faced to {lowest}");
    // What facing takes is the sheet's to lose: no gouge (before, every cell was one).
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean() && v.report.gouge_count == 0, "{}", v.report.describe());
}

/// Facing a chosen region of a drawing: the inside of loop 1 (a 20 × 15 rectangle in a 60 × 40
/// sheet) faced, the tool past it by the overlap and no further; with no overlap, inside it.
#[test]
fn a_drawings_chosen_loops_are_faced_and_nothing_beyond() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40"><rect x="0" y="0" width="60" height="40" fill="none" stroke="black"/><rect x="10" y="10" width="20" height="15" fill="none" stroke="black"/></svg>"#;
    let drawing = swarf::drawing::import::read_drawing(svg.as_bytes(), Some("sheet.svg"), &Tolerances::DEFAULT).unwrap();
    // Loop 1 placed (the SVG's y down, the sheet's up from its lower left corner).
    let (lo, hi) = (DVec2::new(10.0, 15.0), DVec2::new(30.0, 30.0));
    // How far a point lies outside the rectangle (negative inside: how far in from its edge).
    let outside = |p: DVec2| {
        let d = (lo - p).max(p - hi);
        if d.x > 0.0 || d.y > 0.0 {
            d.max(DVec2::ZERO).length()
        } else {
            d.x.max(d.y)
        }
    };
    let r = 5.0;
    for (pattern, overlap, depth, stepdown, levels) in [(FacePattern::Zigzag, 0.5, 0.5, 1.0, 1), (FacePattern::Spiral, 0.0, 1.5, 0.5, 3)] {
        let mut job = Job::default_for_drawing();
        job.tools = vec![Tool { number: 1, cutter: Cutter::flat(2.0 * r), ..Tool::default() }];
        job.operations = vec![Operation::Face(Face { depth: Some(depth), stepdown, overlap, pattern, loops: vec![1], ..Face::default() })];
        let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap_or_else(|e| panic!("{pattern:?}: {e}"));
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{pattern:?}: {}", v.report.describe());
        // The tool reaches `overlap` diameters past the loop: faced within, untouched beyond.
        let past = overlap * 2.0 * r;
        let grid = v.stock.grid();
        let cell = grid.spacing * std::f64::consts::SQRT_2;
        let (mut faced, mut kept) = (0, 0);
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let p = grid.node(i, j);
                let (d, top) = (outside(p), v.stock.top(i, j));
                // Within: everywhere inside the reach, but for a round tool's corners when it
                // stays inside (no overlap): there only where it is the radius from a corner.
                let corners = [lo, hi, DVec2::new(lo.x, hi.y), DVec2::new(hi.x, lo.y)];
                let reached = d < past - cell && (past > 0.0 || corners.iter().all(|c| c.distance(p) > r + cell));
                if reached {
                    assert!((top + depth).abs() < 0.01, "{pattern:?}: at {p:?} ({d:.3} outside) the top is {top:.4}, not {}", -depth);
                    faced += 1;
                } else if d > past + cell {
                    assert!(top > -1e-6, "{pattern:?}: at {p:?}, {d:.3} outside the loop, beyond the tool's reach, the sheet is cut to {top:.4}");
                    kept += 1;
                }
            }
        }
        assert!(faced > 1000 && kept > 1000, "{pattern:?}: {faced} cells faced, {kept} kept");
        // The depth in its levels.
        let mut zs: Vec<i64> = out.paths[0].moves.iter().filter(|m| !m.is_rapid()).map(|m| (m.to().z * 1000.0).round() as i64).collect();
        zs.sort();
        zs.dedup();
        assert_eq!(zs.iter().filter(|&&z| z < 0 && (z % 500) == 0).count(), levels, "{pattern:?}: levels {zs:?}");
        canon(&out.gcode, &job.tools);
    }
    // Loops are a drawing's: a 3D part is faced whole.
    let mut job = Job { tools: vec![Tool { number: 1, cutter: Cutter::flat(10.0), ..Tool::default() }], ..Job::default() };
    job.stock.margin_top = 1.0;
    job.operations = vec![Operation::Face(Face { loops: vec![0], ..Face::default() })];
    let e = job::run(&job, block(3, 3, SIDE, THICK, &[]), &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("faces a drawing's loops"), "{e}");
}

/// The shared plate drawing (tm_LM2.dxf, 40 loops on layers HOLES and IZREZ): its circles
/// spotted, the φ3.2 ones pecked, the φ12 ones chamfered, the outline profiled, in one program
/// that verifies clean and that LinuxCNC's interpreter and GRBL's parser read.
#[test]
fn a_shared_plate_is_spotted_drilled_chamfered_and_cut_out() {
    let Some(path) = common::shared_data("profiles/tm_LM2.dxf") else { return };
    let drawing = swarf::drawing::import::read_drawing(&std::fs::read(path).unwrap(), Some("tm_LM2.dxf"), &Tolerances::DEFAULT).unwrap();
    let mut job = Job::default_for_drawing();
    let holes = job.holes(drawing.clone()).unwrap();
    // Its 36 circles, and 31 POINTs (its dimensions' anchors, at the plate's corners among
    // them: drill marks the operations below leave out unless asked for).
    assert_eq!(holes.iter().filter(|h| !h.mark).count(), 36, "{}", swarf::machining::holes::sizes(&holes).join(", "));
    assert_eq!(holes.iter().filter(|h| h.mark).count(), 31);
    job.tools = vec![
        drill_tool(1, Cutter { shape: swarf::cutter::Shape::SpotDrill, diameter: 10.0, angle: Some(90.0), ..Cutter::default() }),
        drill_tool(2, Cutter::drill(3.2, 118.0)),
        drill_tool(3, Cutter { flute_length: 10.0, ..Cutter::v_bit(16.0, 90.0, 0.0) }),
        Tool { number: 4, cutter: Cutter::flat(3.0), ..Tool::default() },
    ];
    let profile = match job.operations[0].clone() {
        Operation::Profile2d(p) => Operation::Profile2d(swarf::operations::Profile2d { tool: 4, layers: vec!["IZREZ".into()], ..p }),
        other => panic!("{other:?}"),
    };
    job.operations = vec![
        Operation::Drill(Drill { name: "spot".into(), tool: 1, cycle: DrillCycle::Spot, spot_diameter: Some(3.0), ..Drill::default() }),
        Operation::Drill(Drill {
            name: "drill".into(),
            tool: 2,
            cycle: DrillCycle::Peck,
            pick: HolePick { min_diameter: Some(3.19), max_diameter: Some(3.21), ..HolePick::default() },
            ..Drill::default()
        }),
        Operation::Chamfer(Chamfer { tool: 3, width: 0.5, pick: HolePick { min_diameter: Some(11.9), ..HolePick::default() }, ..Chamfer::default() }),
        profile,
    ];
    for dialect in [Dialect::LinuxCnc, Dialect::Grbl] {
        job.post.dialect = dialect;
        let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap_or_else(|e| panic!("{dialect:?}: {e}"));
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{dialect:?}: {}", v.report.describe());
        canon(&out.gcode, &job.tools);
        if dialect == Dialect::Grbl {
            let without_changes: String = out.gcode.lines().filter(|l| !l.contains("M6")).map(|l| format!("{l}\n")).collect();
            if let Some(said) = common::grblcheck(&without_changes) {
                said.unwrap();
            }
        } else {
            assert_eq!(out.gcode.matches("G81 ").count(), 36, "every circle spotted");
            assert_eq!(out.gcode.matches("G83 ").count(), 26, "the φ3.2 holes pecked");
        }
    }
}

/// A DXF's POINTs are drill marks: listed by `swarf drawing` after the loops, drilled as wide
/// as the drill (with the drawing's circles, in one short path), left out of a bore of all the
/// holes and refused where picked by number; a drawing of marks alone is drilled too.
#[test]
fn a_drawings_points_are_drill_marks() {
    let point = |x: f64, y: f64, layer: &str| format!("0\nPOINT\n8\n{layer}\n10\n{x}\n20\n{y}\n30\n0\n");
    let outline = "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n80\n20\n0\n10\n80\n20\n50\n10\n0\n20\n50\n";
    let circle = "0\nCIRCLE\n8\n0\n10\n40\n20\n25\n40\n6\n";
    let marks = [point(10.0, 10.0, "DRILL"), point(70.0, 10.0, "DRILL"), point(70.0, 40.0, "DRILL")].concat();
    let dxf = format!("0\nSECTION\n2\nENTITIES\n{outline}{circle}{marks}0\nENDSEC\n0\nEOF\n");
    let drawing = swarf::drawing::import::read_drawing(dxf.as_bytes(), Some("marks.dxf"), &Tolerances::DEFAULT).unwrap();
    assert_eq!(drawing.points.len(), 3);
    assert!(drawing.ignored.is_empty(), "{:?}", drawing.ignored);
    assert!(drawing.layers.contains(&"DRILL".to_string()));
    let mut job = Job::default_for_drawing();
    job.drawing.thickness = 4.0;
    let holes = job.holes(drawing.clone()).unwrap();
    assert_eq!(holes.len(), 4, "{holes:#?}");
    let marks: Vec<&Hole> = holes.iter().filter(|h| h.mark).collect();
    assert_eq!(marks.len(), 3);
    // Numbered after the drawing's two loops.
    assert_eq!(marks.iter().map(|h| h.loop_index.unwrap()).collect::<Vec<_>>(), vec![2, 3, 4]);
    assert!(marks.iter().all(|h| h.diameter == 0.0 && h.through && h.layer.as_deref() == Some("DRILL")));
    // Drilled, all four: the marks at the drill's own width, and the program clean.
    job.tools = vec![drill_tool(1, Cutter::drill(4.0, 118.0)), Tool { number: 2, cutter: Cutter::flat(6.0), ..Tool::default() }];
    // "All the holes" is the circle alone: a DXF's points are as often its dimensions' anchors.
    job.operations = vec![Operation::Drill(Drill { name: "drill".into(), tool: 1, cycle: DrillCycle::Peck, ..Drill::default() })];
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap();
    assert_eq!(out.gcode.matches("G98 G83").count(), 1, "{}", out.gcode);
    job.operations = vec![Operation::Drill(Drill { name: "drill".into(), tool: 1, cycle: DrillCycle::Peck, pick: HolePick { marks: true, ..HolePick::default() }, ..Drill::default() })];
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap();
    let report = &out.verification.as_ref().unwrap().report;
    assert!(report.is_clean(), "{}", report.describe());
    assert_eq!(out.gcode.matches("G98 G83").count(), 4, "{}", out.gcode);
    canon(&out.gcode, &job.tools);
    // Only the φ12 circle is said to be wider than the drill: the marks are its own width.
    assert!(!out.warnings.iter().any(|w| w.message.contains("narrower")), "{:?}", out.warnings);
    assert!(out.warnings.iter().any(|w| w.message.starts_with("1 holes are wider")), "{:?}", out.warnings);
    // Picked by a diameter range, the marks (no diameter) are not taken.
    let mut ranged = job.clone();
    ranged.operations = vec![Operation::Drill(Drill { name: "drill".into(), tool: 1, pick: HolePick { max_diameter: Some(20.0), ..HolePick::default() }, ..Drill::default() })];
    let out = job::run(&ranged, drawing.clone(), &mut Progress::none()).unwrap();
    assert_eq!(out.gcode.matches("G98 G81").count(), 1);
    // A bore of all the holes bores the circle; a bore of a mark by number is refused.
    let bore = |pick: HolePick| Job { operations: vec![Operation::Bore(Bore { name: "bore".into(), tool: 2, pick, ..Bore::default() })], ..job.clone() };
    let out = job::run(&bore(HolePick::default()), drawing.clone(), &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.is_clean());
    match job::run(&bore(HolePick { holes: vec![1, 3], ..HolePick::default() }), drawing.clone(), &mut Progress::none()) {
        Err(e) => assert!(e.to_string().contains("holes 3 are drill marks"), "{e}"),
        Ok(_) => panic!("a drill mark was bored"),
    }
    // Picked by number, a mark is drilled without `marks`.
    let numbered = Job { operations: vec![Operation::Drill(Drill { name: "drill".into(), tool: 1, pick: HolePick { holes: vec![3, 4], ..HolePick::default() }, ..Drill::default() })], ..job.clone() };
    let out = job::run(&numbered, drawing.clone(), &mut Progress::none()).unwrap();
    assert_eq!(out.gcode.matches("G98 G81").count(), 2);
    // Marks alone: a drawing of points is a drilling job, the marks asked for.
    let only = format!("0\nSECTION\n2\nENTITIES\n{}0\nENDSEC\n0\nEOF\n", [point(0.0, 0.0, "0"), point(30.0, 0.0, "0"), point(30.0, 20.0, "0")].concat());
    let drawing = swarf::drawing::import::read_drawing(only.as_bytes(), Some("only.dxf"), &Tolerances::DEFAULT).unwrap();
    match job::run(&Job { operations: vec![Operation::Drill(Drill { name: "drill".into(), tool: 1, ..Drill::default() })], ..job.clone() }, drawing.clone(), &mut Progress::none()) {
        Err(e) => assert!(e.to_string().contains("there are 3 drill marks; drill marks (POINTs) are taken by number, or all of them with marks: true"), "{e}"),
        Ok(_) => panic!("marks drilled unasked"),
    }
    let out = job::run(&job, drawing, &mut Progress::none()).unwrap();
    assert_eq!(out.gcode.matches("G98 G83").count(), 3);
    assert!(out.verification.as_ref().unwrap().report.is_clean());
    // The command line lists them.
    let dir = std::env::temp_dir().join(format!("swarf-marks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("marks.dxf");
    std::fs::write(&file, &dxf).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_swarf")).arg("drawing").arg(&file).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("drill mark 2: at (10.000, 10.000) mm, layer DRILL") && text.contains("holes: 3 drill marks, 1 × φ12"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A drawing's loops chamfered (issue 40): outside the outlines, inside the holes, concave and
/// convex corners alike. The cone never reaches into the part beyond the chamfer: along every
/// move, at points 0.05 mm apart, the axis keeps from every drawn loop at least the distance
/// at which the cone's width at the top is the chamfer's; the simulated stock lies on the
/// 45° bevel within the width and is untouched beyond it; a hole too small for the cone is
/// left with a warning.
#[test]
fn a_drawings_loops_are_chamfered_outside_outlines_and_inside_holes_and_nowhere_beyond() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40">
      <path d="M 0 0 H 60 V 40 H 30 V 20 H 0 Z"/>
      <circle cx="15" cy="10" r="5"/><rect x="40" y="10" width="12" height="6"/><circle cx="50" cy="30" r="0.15"/>
    </svg>"#;
    let drawing = swarf::drawing::import::read_drawing(svg.as_bytes(), Some("l.svg"), &Tolerances::DEFAULT).unwrap();
    let mut job = Job::default_for_drawing();
    job.drawing.thickness = 6.0;
    job.tools = vec![Tool { number: 1, cutter: Cutter { flute_length: 10.0, ..Cutter::v_bit(6.0, 90.0, 0.0) }, ..Tool::default() }];
    let (width, extra) = (0.5, 0.2);
    job.operations = vec![Operation::Chamfer(Chamfer { edges: ChamferEdges::Loops, width, extra_depth: extra, ..Chamfer::default() })];
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).expect("chamfered");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert!(out.warnings.iter().any(|w| w.to_string().contains("1 loops are too small")), "{:?}", out.warnings);
    // The axis's distance from the edge where the 90° cone is the chamfer's width at the top.
    let away = extra;
    let placed = {
        let mut d = drawing.clone();
        job.drawing.apply(&mut d);
        d
    };
    let edges: Vec<&swarf::drawing::Loop> = placed.loops.iter().map(|l| &l.path).filter(|l| l.area().abs() > 1.0).collect();
    let (mut checked, mut nearest) = (0, f64::INFINITY);
    for path in &out.paths {
        for (a, b, _) in path.segments(0.01) {
            let n = ((a.distance(b) / 0.05).ceil() as usize).max(1);
            for k in 0..=n {
                let p = a.lerp(b, k as f64 / n as f64);
                if p.z >= 0.0 {
                    continue;
                }
                // The cone's width at the top for a tip this deep: never more than the chamfer
                // past the nearest edge.
                let reach = -p.z;
                let d = edges.iter().map(|l| l.distance_to(p.truncate())).fold(f64::INFINITY, f64::min);
                assert!(reach - d <= width + 1e-6, "at {p:?} the cone reaches {:.4} mm past an edge", reach - d);
                if (p.z - (-width - extra)).abs() < 1e-9 {
                    nearest = nearest.min(d);
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 1000, "{checked} points checked");
    assert!((nearest - away).abs() < 1e-3, "the axis comes {nearest:.4} mm from an edge, not {away}");
    // The stock: on the bevel within the width, untouched beyond it.
    let shape = swarf::drawing::Shape::new(edges.iter().map(|l| (*l).clone()).collect());
    let (mut on, mut beyond) = (0, 0);
    for (p, _, d, top) in common::cells(&v.stock, &shape).filter(|c| c.1) {
        if d > 0.05 && d < width - 0.05 {
            // Never below the bevel; on it, but where the axis turns a concave corner of the
            // part (its path's sharp corner keeps farther from the cells beside it).
            let ideal = -(width - d);
            assert!(top >= ideal - 0.01, "at {p:?}, {d:.3} mm in: stock at {top:.4}, below the bevel at {ideal:.4}");
            let corner = edges.iter().flat_map(|l| l.vertices.iter()).any(|v| v.p.distance(p) < 2.0 * width);
            if !corner {
                assert!((top - ideal).abs() < 0.01, "at {p:?}, {d:.3} mm in: stock at {top:.4}, the bevel at {ideal:.4}");
                on += 1;
            }
        } else if d > width + 0.05 {
            assert!(top >= -1e-6, "at {p:?}, {d:.3} mm in: cut to {top:.4} beyond the chamfer");
            beyond += 1;
        }
    }
    assert!(on > 200 && beyond > 1000, "{on} cells on the bevel, {beyond} beyond");
    canon(&out.gcode, &job.tools);
    if let Some(said) =
        common::grblcheck(&job::run(&Job { post: swarf::post::PostSettings { dialect: Dialect::Grbl, ..job.post.clone() }, ..job.clone() }, drawing.clone(), &mut Progress::none()).unwrap().gcode)
    {
        said.unwrap();
    }
    // On a 3D part, loops are a drawing's.
    let part = block(3, 3, SIDE, THICK, &specs());
    let e = job::run(&Job { tools: job.tools.clone(), operations: job.operations.clone(), ..Job::default() }, part, &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("drawings"), "{e}");
}

/// A part's sharp top edges chamfered (issue 40): a block with a pocket in its top and a step
/// down at one end. The top face's outline and the pocket's rim drop down steep walls and are
/// found sharp; the pocket floor's and the step's lower face's edges meet walls going up and
/// are not (a chamfer cannot follow them). The simulated stock lies on the 45° bevel within the
/// chamfer's width of every sharp edge and is untouched beyond it; the program is clean and
/// rs274 runs it.
#[test]
fn a_parts_sharp_top_edges_are_chamfered_and_nowhere_beyond() {
    let inside = |x: f64, y: f64, x0: f64, x1: f64, y0: f64, y1: f64| (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
    let top = move |x: f64, y: f64| {
        if inside(x, y, -8.0, 8.0, -5.0, 5.0) {
            -6.0
        } else if x > 22.0 {
            -3.0
        } else {
            0.0
        }
    };
    let part = swarf::mesh::sample::height_field_solid(DVec2::new(-30.0, -20.0), DVec2::new(30.0, 20.0), 240, 160, -10.0, top);
    let edges = swarf::mesh::edges::top_edges(&part);
    let sharp: Vec<&swarf::mesh::edges::TopEdge> = edges.iter().filter(|e| e.sharp).collect();
    // The top face (z 0): its outline and the pocket's rim; the step's face (z -3): its
    // outline but where it meets the top face's wall going up, so not sharp all round; the
    // pocket's floor (z -6) meets walls going up only: no edge to break, not listed.
    assert_eq!(sharp.len(), 2, "{edges:?}");
    assert!(sharp.iter().all(|e| e.z.abs() < 1e-9), "{edges:?}");
    assert!(edges.len() == 3 && edges.iter().any(|e| (e.z + 3.0).abs() < 1e-9 && !e.sharp), "{edges:?}");
    let mut job = Job::default();
    job.part = swarf::mesh::placement::PartSetup { placement: swarf::mesh::placement::Placement::Keep, ..Default::default() };
    job.stock = swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() };
    job.simulation.cell = Some(0.05);
    job.tools = vec![Tool { number: 1, cutter: Cutter { flute_length: 10.0, ..Cutter::v_bit(6.0, 90.0, 0.0) }, ..Tool::default() }];
    let (width, extra) = (0.8, 0.2);
    job.operations = vec![Operation::Chamfer(Chamfer { edges: ChamferEdges::PartEdges, width, extra_depth: extra, ..Chamfer::default() })];
    let out = job::run(&job, part.clone(), &mut Progress::none()).expect("chamfered");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    // The stock over the top face: on the bevel within the width of its sharp edges, untouched
    // beyond. (The height field's walls lean across one sample, 0.25 mm: the edges are where
    // the top face ends.)
    let shape = swarf::drawing::Shape::new(sharp.iter().map(|e| e.outline.clone()).collect());
    let (mut on, mut beyond) = (0, 0);
    for (p, held, d, z) in common::cells(&v.stock, &shape) {
        if !held {
            continue;
        }
        let corner = sharp.iter().flat_map(|e| e.outline.vertices.iter()).any(|w| w.p.distance(p) < 2.0 * width);
        if d > 0.05 && d < width - 0.05 && !corner {
            let ideal = -(width - d);
            assert!((z - ideal).abs() < 0.02, "at {p:?}, {d:.3} mm in: stock at {z:.4}, the bevel at {ideal:.4}");
            on += 1;
        } else if d > width + 0.05 && p.x < 21.0 {
            assert!(z >= -1e-6, "at {p:?}, {d:.3} mm in: cut to {z:.4} beyond the chamfer");
            beyond += 1;
        }
    }
    assert!(on > 2000 && beyond > 10_000, "{on} cells on the bevel, {beyond} beyond");
    canon(&out.gcode, &job.tools);
    // The command line lists them, numbered as the chamfer takes them.
    let text = listed("edges", &["edges"], &part, Some(&job));
    assert!(
        text.contains(&format!("{} top edges, 2 sharp", edges.len())) && text.contains("edge 0: the outline of a face at Z0.000, 184.0 mm long, X-30.000..22.000 Y-20.000..20.000: sharp"),
        "{text}"
    );
    // Edges named that are not sharp are refused by name.
    let blunt = edges.iter().position(|e| !e.sharp).unwrap();
    job.operations = vec![Operation::Chamfer(Chamfer { edges: ChamferEdges::PartEdges, width, loops: vec![blunt], ..Chamfer::default() })];
    let e = job::run(&job, part, &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains(&format!("top edge {blunt} is not sharp all round")), "{e}");
}

/// A plate 40 × 40 (top at -12) with a φ10 stud 12 mm high on its middle, the stud's wall in
/// `sides` facets.
fn stud_part(sides: usize) -> Mesh {
    let v = DVec3::new;
    let (r, top, plate, base) = (5.0, 0.0, -12.0, -20.0);
    let mut tris = Vec::new();
    let at = |k: usize, z: f64| {
        let a = std::f64::consts::TAU * k as f64 / sides as f64;
        v(r * a.cos(), r * a.sin(), z)
    };
    for k in 0..sides {
        let (b0, b1, t0, t1) = (at(k, plate), at(k + 1, plate), at(k, top), at(k + 1, top));
        tris.push([b0, b1, t1]);
        tris.push([b0, t1, t0]);
        tris.push([v(0.0, 0.0, top), t0, t1]);
    }
    let (s, lo, hi) = (20.0, base, plate);
    tris.push([v(-s, -s, hi), v(s, -s, hi), v(s, s, hi)]);
    tris.push([v(-s, -s, hi), v(s, s, hi), v(-s, s, hi)]);
    tris.push([v(-s, -s, lo), v(s, s, lo), v(s, -s, lo)]);
    tris.push([v(-s, -s, lo), v(-s, s, lo), v(s, s, lo)]);
    for (a, b) in [((-s, -s), (s, -s)), ((s, -s), (s, s)), ((s, s), (-s, s)), ((-s, s), (-s, -s))] {
        tris.push([v(a.0, a.1, lo), v(b.0, b.1, lo), v(b.0, b.1, hi)]);
        tris.push([v(a.0, a.1, lo), v(b.0, b.1, hi), v(a.0, a.1, hi)]);
    }
    Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap()
}

/// Issue 39: an external thread milled on a part's stud: the stud found as a boss (and listed
/// by `swarf holes --bosses`), roughed round, then M10 right hand in two passes and left hand:
/// every helical arc about the stud's axis clockwise (climb outside), a pitch a turn, down for
/// a right-hand thread and up for a left-hand one, never nearer the axis than the thread's
/// root; the simulated stud keeps its major diameter above the thread and is cut to the root
/// within it; the program is clean and rs274 runs it.
#[test]
fn an_external_thread_is_milled_round_a_stud() {
    let part = stud_part(64);
    let bosses = swarf::holes::mesh::bosses(&part);
    assert_eq!(bosses.len(), 1, "{bosses:?}");
    let b = &bosses[0];
    assert!(b.center.length() < 1e-9 && (b.diameter - 10.0).abs() < 1e-3 && (b.top - 0.0).abs() < 1e-9 && (b.bottom + 12.0).abs() < 1e-9, "{b:?}");
    assert!(swarf::holes::mesh::find(&part).is_empty(), "a stud is no hole");
    let thread_mill =
        Tool { number: 2, cutter: Cutter { shape: swarf::cutter::Shape::ThreadMill, diameter: 6.0, flute_length: 14.0, ..Cutter::default() }, feed_rate: 300.0, plunge_rate: 200.0, ..Tool::default() };
    let flat = Tool { number: 1, cutter: Cutter { flute_length: 25.0, ..Cutter::flat(6.0) }, ..Tool::default() };
    for (hand, passes) in [(Hand::Right, 2), (Hand::Left, 1)] {
        let mut job = Job { tools: vec![flat.clone(), thread_mill.clone()], ..Job::default() };
        job.part.placement = swarf::mesh::placement::Placement::Keep;
        job.stock.margin_top = 0.0;
        job.stock.margin_xy = 0.0;
        job.operations = vec![
            Operation::RoughZlevel(swarf::operations::RoughZlevel {
                tool: 1,
                steps: swarf::operations::Steps { stepdown: 3.0, stepover_fraction: 0.4 },
                roughing: swarf::operations::Roughing { allowance: 0.0, leave_stock: 0.0, ..Default::default() },
                ..Default::default()
            }),
            Operation::ThreadMill(ThreadMill { tool: 2, thread: "M10".into(), external: true, hand, passes, length: Some(10.0), ..ThreadMill::default() }),
        ];
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap_or_else(|e| panic!("{hand:?}: {e}"));
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{hand:?}: {}", v.report.describe());
        let (major, pitch) = (10.0, 1.5);
        let root = major / 2.0 - swarf::machining::threads::external_depth(pitch);
        let path = out.paths.iter().find(|p| p.tool == 2).unwrap();
        let (mut at, mut rises, mut falls, mut nearest) = (path.start, 0, 0, f64::INFINITY);
        for m in &path.moves {
            nearest = nearest.min(m.to().truncate().length() - 3.0);
            if let swarf::toolpath::Move::Arc { to, center, clockwise, .. } = *m {
                if center.length() < 1e-9 {
                    assert!(clockwise, "{hand:?}: climb round the outside");
                    let turn = swarf::toolpath::arc_sweep(at, to, center, true).abs() / std::f64::consts::TAU;
                    assert!(((to.z - at.z).abs() - pitch * turn).abs() < 1e-6, "{hand:?}: {} mm in {turn} turns", to.z - at.z);
                    if to.z > at.z {
                        rises += 1
                    } else {
                        falls += 1
                    }
                }
            }
            at = m.to();
        }
        assert!(if hand == Hand::Right { falls > 10 && rises == 0 } else { rises > 10 && falls == 0 }, "{hand:?}: {rises} up, {falls} down");
        assert!((nearest - root).abs() < 1e-9, "{hand:?}: the tool's edge comes to r {nearest:.4}, the root is at {root:.4}");
        // The simulated stud: its core inside the root untouched, the ring between the root and
        // the major diameter cut where the thread's form runs out over the top.
        let grid = v.stock.grid();
        let (mut core, mut ring) = (0, 0);
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let r = grid.node(i, j).length();
                let top = v.stock.top(i, j);
                if r < root - 0.1 {
                    assert!(top > -1e-3, "{hand:?}: the stud's core at r {r:.3} is cut to {top:.3}");
                    core += 1;
                } else if r > root + 0.1 && r < major / 2.0 - 0.1 && top < -0.1 {
                    ring += 1;
                }
            }
        }
        assert!(core > 100 && ring > 10, "{hand:?}: {core} core cells, {ring} ring cells cut");
        canon(&out.gcode, &job.tools);
    }
    // Listed by the command line.
    let text = listed("bosses", &["holes", "--bosses"], &part, None);
    assert!(text.contains("φ10.000, top 0.000, bottom -12.000") && text.contains("\n1 boss\n"), "{text}");
    // A stud wider than the thread is refused by name.
    let mut job = Job { tools: vec![thread_mill], ..Job::default() };
    job.operations = vec![Operation::ThreadMill(ThreadMill { tool: 2, thread: "M8".into(), external: true, ..ThreadMill::default() })];
    let e = job::run(&job, part, &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("wider than the thread's major diameter φ8"), "{e}");
}

/// Issue 55: holes are judged against the circles their facets approximate. A φ6.35 hole of 32
/// sides lies 0.015 mm inside its circle between vertices, a φ12 of 32 sides 0.029 mm: a
/// clearance drill 0.0125 mm over on the radius and a bore to the φ12 are clean, not "gouges …
/// 10 mm deep"; a φ6.4 drill in the φ6.35 holes is refused in a machinist's words, with how
/// far over on the radius.
#[test]
fn holes_are_judged_as_their_circles_and_an_oversize_drill_is_said_as_one() {
    let specs = [
        Spec { tile: (0, 0), kind: Kind::Through { d: 6.35 }, phase: 0.1, sides: 32 },
        Spec { tile: (1, 0), kind: Kind::Through { d: 6.35 }, phase: 0.4, sides: 32 },
        Spec { tile: (2, 0), kind: Kind::Through { d: 12.0 }, phase: 0.05, sides: 32 },
    ];
    let part = block(3, 1, SIDE, THICK, &specs);
    let drill = |d: f64| {
        let mut job = Job { tools: vec![drill_tool(2, Cutter::drill(d, 118.0))], ..Job::default() };
        job.simulation.cell = Some(0.05);
        job.operations = vec![Operation::Drill(Drill { tool: 2, cycle: DrillCycle::Peck, pick: HolePick { max_diameter: Some(7.0), ..HolePick::default() }, ..Drill::default() })];
        job
    };
    // 0.0125 mm over on the radius: within the gouge tolerance of the true circle.
    let out = job::run(&drill(6.375), part.clone(), &mut Progress::none()).expect("planned");
    assert!(out.problem.is_none(), "{:?}", out.problem);
    // Bored to the φ12's size.
    let mut bore = boring_job(Dialect::LinuxCnc, Bore { pick: HolePick { min_diameter: Some(11.0), ..HolePick::default() }, pitch: 1.0, ..Bore::default() });
    bore.simulation.cell = Some(0.05);
    let out = job::run(&bore, part.clone(), &mut Progress::none()).expect("bored");
    assert!(out.problem.is_none(), "{:?}", out.problem);
    // 0.025 mm over on the radius: said as such, first.
    let out = job::run(&drill(6.4), part.clone(), &mut Progress::none()).expect("planned");
    let problem = out.problem.expect("a φ6.4 drill in φ6.35 holes cuts the walls back");
    let words = "φ6.4 drill (T2) in φ6.35 holes: 0.025 mm oversize on the radius";
    assert!(problem.contains(words), "{problem}");
    // `swarf verify` on the program says it alike (the simulation's report carries it).
    let v = job::verify_gcode(&drill(6.4), part.clone(), &out.gcode, Some(0.05), &mut Progress::none()).unwrap();
    assert!(v.report.problem().is_some_and(|p| p.starts_with(words)), "{:?}", v.report.problem());
    assert!(v.report.describe().contains(words), "{}", v.report.describe());
}

/// Issue 55's judging of holes as circles never forgives what stands inside a hole: a boss in a
/// moat (the moat's wall a hole to the finder) plunged into is a gouge, and the moat's wall cut
/// back is one too.
#[test]
fn what_stands_inside_a_hole_is_judged_as_the_mesh_has_it() {
    let (n, outer, boss, side) = (48usize, 10.0, 4.0, 15.0);
    let at = |r: f64, k: usize, z: f64| (DVec2::from_angle(std::f64::consts::TAU * (k % n) as f64 / n as f64) * r).extend(z);
    // The point of the square's edge in the direction of circle point k.
    let edge = |k: usize, z: f64| {
        let d = DVec2::from_angle(std::f64::consts::TAU * (k % n) as f64 / n as f64);
        (d * (side / d.x.abs().max(d.y.abs()))).extend(z)
    };
    let mut tris = Vec::new();
    for k in 0..n {
        // The plate's top around the moat, the moat's wall (facing the axis), its floor, the
        // boss's wall (facing out) and its top 1 mm below the plate's.
        tris.push([at(outer, k, 0.0), edge(k, 0.0), edge(k + 1, 0.0)]);
        tris.push([at(outer, k, 0.0), edge(k + 1, 0.0), at(outer, k + 1, 0.0)]);
        tris.push([at(outer, k, 0.0), at(outer, k + 1, 0.0), at(outer, k + 1, -5.0)]);
        tris.push([at(outer, k, 0.0), at(outer, k + 1, -5.0), at(outer, k, -5.0)]);
        tris.push([at(outer, k, -5.0), at(outer, k + 1, -5.0), at(boss, k + 1, -5.0)]);
        tris.push([at(outer, k, -5.0), at(boss, k + 1, -5.0), at(boss, k, -5.0)]);
        tris.push([at(boss, k, -5.0), at(boss, k + 1, -5.0), at(boss, k + 1, -1.0)]);
        tris.push([at(boss, k, -5.0), at(boss, k + 1, -1.0), at(boss, k, -1.0)]);
        tris.push([DVec3::new(0.0, 0.0, -1.0), at(boss, k, -1.0), at(boss, k + 1, -1.0)]);
    }
    let part = common::mesh(tris);
    let found = find(&part);
    assert!(found.iter().any(|h| (h.diameter - 2.0 * outer).abs() < 0.01), "the moat's wall is a hole to the finder: {found:?}");
    let mut job = Job { tools: vec![Tool { number: 1, cutter: Cutter { flute_length: 20.0, ..Cutter::flat(3.0) }, ..Tool::default() }], ..Job::default() };
    job.part.placement = swarf::mesh::placement::Placement::Keep;
    job.simulation.cell = Some(0.1);
    let verify = |gcode: &str| job::verify_gcode(&job, part.clone(), gcode, None, &mut Progress::none()).unwrap().report;
    // Into the boss's top, 2 mm.
    let boss_plunge = verify("G21 G90\nT1 M6\nG0 Z5\nG0 X0 Y0\nG1 Z-3 F100\nG0 Z5\nM30\n");
    assert!(boss_plunge.gouge_count > 0 && boss_plunge.gouge_max > 1.9, "{}", boss_plunge.describe());
    // Down the moat beside the boss, clear of both walls: clean.
    let moat = verify("G21 G90\nT1 M6\nG0 Z5\nG0 X7 Y0\nG1 Z-5 F100\nG0 Z5\nM30\n");
    assert_eq!(moat.gouge_count, 0, "{}", moat.describe());
    // Into the moat's wall, 0.5 mm past its circle: a gouge.
    let wall = verify("G21 G90\nT1 M6\nG0 Z5\nG0 X9 Y0\nG1 Z-4 F100\nG0 Z5\nM30\n");
    assert!(wall.gouge_count > 0, "{}", wall.describe());
}

/// Issue 56: a perforated panel's holes are ordered in time in proportion to their number (30,000
/// took 10 s, each step looking at every hole left and 2-opt at every pair; now a fraction of a
/// second), and the tour stays short: on a grid at an 8 mm pitch, within 5 % of a hole a pitch.
#[test]
fn a_perforated_panels_holes_are_ordered_in_proportion_to_their_number() {
    let grid = |n: usize| -> Vec<DVec2> {
        let cols = ((n as f64 * 1.5).sqrt().ceil()) as usize;
        (0..n).map(|k| DVec2::new(9.0 + 8.0 * (k % cols) as f64, 9.0 + 8.0 * (k / cols) as f64)).collect()
    };
    let time = |n: usize| {
        let points = grid(n);
        let (tour, took) = common::cpu_timed(|| swarf::holes::order(&points, DVec2::ZERO));
        let mut seen = tour.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..n).collect::<Vec<_>>(), "every hole once");
        let length = swarf::holes::tour_length(&points, &tour, DVec2::ZERO);
        let least = 8.0 * (n - 1) as f64 + points[0].length();
        assert!(length <= 1.05 * least, "{n} holes: a tour of {length:.0} mm, {least:.0} at least");
        took
    };
    let (small, large) = (time(3_000).max(1e-3), time(30_000));
    assert!(large < 40.0 * small, "3,000 holes ordered in {small:.3} s, 30,000 in {large:.3} s");
}

/// The work zero on a hole's centre (`zero.at`, set by `Job::zero_on` from a hole as found):
/// in each setup of a block drilled from both sides, and in a job without setups; the hole then
/// lies at X0 Y0, the zero's height kept. The setup sheet says where the zero is.
#[test]
fn the_zero_goes_on_a_holes_centre() {
    let part = block(3, 3, SIDE, THICK, &specs());
    let mut job = drilling_job(Dialect::LinuxCnc);
    let ops = std::mem::take(&mut job.operations);
    job.setups = vec![
        job::Setup { name: "top".into(), operations: ops.clone(), ..Default::default() },
        job::Setup { name: "bottom".into(), flip: job::Flip::AboutX, work_offset: Some("G55".into()), operations: ops, ..Default::default() },
    ];
    let placed = {
        let mut p = part.clone();
        job.part.apply(&mut p);
        p.bounds()
    };
    for k in 0..2 {
        let (sub, held, _) = job.for_setup(k, part.clone()).unwrap();
        let holes = sub.holes(held).unwrap();
        let h = holes.iter().find(|h| h.through && h.diameter > 12.0).expect("the φ12.5 through hole, from either side");
        let height = job.setups[k].zero.or(job.stock.zero).map(|z| z.height).unwrap_or_default();
        let zero = job.zero_on(&placed, Some(k), DVec2::new(h.center[0], h.center[1])).unwrap();
        assert_eq!(zero.height, height);
        job.setups[k].zero = Some(zero);
        let (sub, held, _) = job.for_setup(k, part.clone()).unwrap();
        let moved = sub.holes(held).unwrap().into_iter().find(|g| g.through && g.diameter > 12.0).unwrap();
        assert!(moved.center[0].abs() < 1e-9 && moved.center[1].abs() < 1e-9, "setup {k}: the hole is at {:?}", moved.center);
    }
    // Without setups.
    let mut plain = drilling_job(Dialect::LinuxCnc);
    let h = plain.holes(part.clone()).unwrap().into_iter().find(|h| h.diameter < 7.0 && h.through).unwrap();
    plain.stock.zero = Some(plain.zero_on(&placed, None, DVec2::new(h.center[0], h.center[1])).unwrap());
    let again = plain.holes(part.clone()).unwrap();
    assert!(again.iter().any(|g| g.center[0].abs() < 1e-9 && g.center[1].abs() < 1e-9 && (g.diameter - h.diameter).abs() < 1e-9));
    // The sheet says where it is.
    let setups = job::run_setups(&job, part, &mut Progress::none()).unwrap();
    let sheets: Vec<_> = setups.iter().map(|s| job::sheet::SheetSetup::of(&s.name, &s.output)).collect();
    let html = job::sheet::setup_sheet(&job, "block.stl", &sheets);
    assert_eq!(html.matches("X0 Y0 at the centre of the φ").count(), 2, "{html:.3000}");
    assert_eq!(html.matches("from the centre of the stock seen from above): the stock's left side at X").count(), 2, "{html:.3000}");
    assert!(setups.iter().all(|s| s.output.zero_at));
    // The holes are looked for only where a zero was put at a point: the same job with no
    // zero's `at` (X0 Y0 where the part is placed) says no hole, and finds none to say.
    let mut bare = job.clone();
    for s in &mut bare.setups {
        s.zero = None;
    }
    bare.stock.zero = None;
    assert!(!bare.zero_at(Some(0)) && !bare.zero_at(None));
}

/// Issue 92: 3D finishing leaves holes to the hole operations. A φ6 ball's waterline over a
/// block with φ6.35 holes (one blind, one through) once ringed every level inside them, each
/// ring entered straight down ("entries found no room for a helix or a ramp and feed straight
/// down into material"); the rings in holes narrower than 1.5 tool diameters are left out, and
/// the note names the holes.
#[test]
fn a_waterline_leaves_narrow_holes_to_the_hole_operations() {
    let specs = [Spec { tile: (0, 0), kind: Kind::Blind { d: 6.35, depth: 8.0, cone: false }, phase: 0.1, sides: 48 }, Spec { tile: (1, 1), kind: Kind::Through { d: 6.35 }, phase: 0.0, sides: 48 }];
    let part = block(2, 2, 20.0, 12.0, &specs);
    let ball = Tool { number: 1, cutter: Cutter { flute_length: 30.0, ..Cutter::ball(6.0) }, ..Tool::default() };
    let waterline = swarf::operations::FinishWaterline { tool: 1, ..Default::default() };
    let mut job = Job { tools: vec![ball], operations: vec![Operation::FinishWaterline(waterline)], ..Job::default() };
    job.stock.margin_top = 0.0;
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    let said: Vec<String> = out.warnings.iter().map(|w| w.to_string()).collect();
    assert!(!said.iter().any(|w| w.contains("no room for a helix")), "{said:?}");
    assert!(said.iter().any(|w| w.contains("left to the hole operations") && w.contains("φ6.350")), "{said:?}");
    // No cutting move inside either hole below its top.
    let placed = swarf::holes::mesh::find(&out.part);
    assert_eq!(placed.len(), 2);
    for h in &placed {
        let inside = out.moves.iter().filter(|m| !m.mv.is_rapid()).any(|m| m.mv.to().truncate().distance(h.center) < h.diameter / 2.0 - 0.01 && m.mv.to().z < h.top - 0.5);
        assert!(!inside, "a cut inside the hole at {:?}", h.center);
    }
}
