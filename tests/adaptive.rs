//! Adaptive clearing (issue 59) on drawings and parts: every program simulated clean (no
//! gouge, no rapid through stock, no straight plunge into material), read by LinuxCNC's rs274,
//! the material removed against its closed form, and the engagement along the cut held.

mod common;

use common::{clean, rs274};
use std::f64::consts::PI;
use swarf::cutter::Cutter;
use swarf::drawing::{Drawing, DrawnLoop, Loop};
use swarf::geom::DVec2;
use swarf::job::{self, Job, JobOutput, Operation, Tool};
use swarf::machining::adaptive::Adaptive;
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::sample::demo_part;
use swarf::operations::{Pocket2d, Roughing};
use swarf::operations::{PocketPattern, RoughAdaptive, RoughZlevel};
use swarf::progress::Progress;
use swarf::toolpath::Move;

fn flat(number: u32, d: f64) -> Tool {
    Tool { number, name: format!("{d} mm flat"), cutter: Cutter::flat(d), feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() }
}

/// A drawing of `loops` on layer 0, in millimetres.
fn drawing_of(loops: Vec<Loop>) -> Drawing {
    let loops = loops.into_iter().map(|path| DrawnLoop { layer: "0".into(), path }).collect();
    Drawing { loops, layers: vec!["0".into()], units: "mm".into(), scale: 1.0, ..Drawing::default() }
}

fn pocket_job(tools: Vec<Tool>, pockets: Vec<Pocket2d>) -> Job {
    let mut job = Job { tools, operations: pockets.into_iter().map(Operation::Pocket2d).collect(), ..Job::default_for_drawing() };
    job.simulation.cell = Some(0.1);
    job
}

fn adaptive(tool: u32, load: f64, depth: f64, stepdown: f64) -> Pocket2d {
    Pocket2d { tool, pattern: PocketPattern::Adaptive, stepover_fraction: load, depth, stepdown, ..Pocket2d::default() }
}

/// The volume the simulation removed.
fn removed(out: &JobOutput) -> f64 {
    out.verification.as_ref().unwrap().volumes.iter().sum()
}

/// The length of the moves that removed material (by the simulation).
fn cutting_length(out: &JobOutput) -> f64 {
    let v = out.verification.as_ref().unwrap();
    out.moves.iter().zip(&v.volumes).filter(|(_, &vol)| vol > 1e-3).map(|(m, _)| m.from.distance(m.mv.to())).sum()
}

/// How many moves at one height (along a level, not its entries) are arcs, and how many there
/// are.
fn level_moves(out: &JobOutput) -> (usize, usize) {
    let (mut arcs, mut n) = (0, 0);
    for m in &out.moves {
        if m.mv.is_rapid() || (m.mv.to().z - m.from.z).abs() > 1e-9 {
            continue;
        }
        n += 1;
        arcs += matches!(m.mv, Move::Arc { .. }) as usize;
    }
    (arcs, n)
}

/// A square pocket 40 × 40 with a round island (r 6) in the middle, φ6 at a tenth of its
/// diameter, 6 deep in one level: clean, the closed-form volume, arcs, and read by rs274.
#[test]
fn a_pocket_with_an_island_is_cleared_in_arcs() {
    let d = drawing_of(vec![Loop::rect(DVec2::ZERO, DVec2::splat(40.0)), Loop::circle(DVec2::splat(20.0), 6.0).reversed()]);
    let job = pocket_job(vec![flat(1, 6.0)], vec![adaptive(1, 0.1, 6.0, 6.0)]);
    let out = job::run(&job, d, &mut Progress::none()).unwrap();
    clean(&out);
    // The square less the island less the four corners a φ6 tool cannot reach.
    let expected = (40.0 * 40.0 - PI * 36.0 - 4.0 * 9.0 * (1.0 - PI / 4.0)) * 6.0;
    let got = removed(&out);
    assert!((got - expected).abs() < 0.01 * expected, "removed {got:.0} mm³, expected {expected:.0}");
    let (arcs, n) = level_moves(&out);
    assert!(arcs * 4 > n, "{arcs} arcs of {n} moves along the level");
    // The engagement the simulation measured, in the report: most of the cut at the target.
    let e = out.operations[0].engagement.as_ref().expect("an engagement report");
    assert!((e.target - Adaptive::angle_of(0.6, 3.0).to_degrees()).abs() < 1e-9);
    assert!(e.within > 0.75 && e.over < 0.02, "{}", e.describe());
    assert_eq!(e.moves.len(), out.operations[0].moves);
    rs274(&out.gcode, &job.tools);
}

/// The engagement the report measures from the simulation, against the angle of the tool's
/// circle in the material sampled at 3,600 points: a φ6 tool along a wall `ae` into it
/// (`arccos(1 − ae/r)`), and round a hole of radius 8 `ae` out from its edge, climbing
/// (counter-clockwise, the material outside the arc) and conventional (clockwise).
#[test]
fn the_engagement_measured_is_the_angle_of_the_tool_in_the_material() {
    use swarf::geom::{Aabb, DVec3};
    use swarf::job::report::EngagementReport;
    use swarf::machining::report::EngagementTarget;
    use swarf::sim::program::program_moves;
    use swarf::sim::verify::Simulator;
    use swarf::toolpath::{Rapids, Toolpath};
    let (r, cell, z) = (3.0, 0.05, 5.0);
    let stock = Aabb { min: DVec3::new(-20.0, -20.0, 0.0), max: DVec3::new(20.0, 20.0, 10.0) };
    // The angle of the front half of the tool's circle at `c` (going along `dir`) in `material`.
    let sampled = |c: DVec2, dir: DVec2, material: &dyn Fn(DVec2) -> bool| {
        let n = 3600;
        (0..n).map(|k| DVec2::from_angle(PI * (k as f64 + 0.5) / n as f64 - PI / 2.0).rotate(dir)).filter(|&u| material(c + r * u)).count() as f64 * PI / n as f64
    };
    let measure = |paths: &[Toolpath], tools: &[Tool], climb: bool| {
        let moves = program_moves(paths, tools, Rapids::at(10_000.0), 10_000.0).unwrap();
        let mut sim = Simulator::new(&stock, cell).unwrap();
        sim.run(&moves, &swarf::geom::Tolerances::default(), &mut Progress::none(), 1.0).unwrap();
        let last = paths.last().unwrap().moves.len();
        let k = moves.len() - last;
        EngagementReport::measure(EngagementTarget { angle: 1.0, climb, levels: Vec::new() }, &moves[k..], &sim.volumes()[k..], &sim.nearest()[k..], cell)
    };
    let tools = [flat(1, 2.0 * r), flat(2, 16.0)];
    for ae in [0.3, 0.6, 1.5, 2.4] {
        // Along +X with the stock's side at y = 10 on its left less `ae`: conventional.
        let y = 10.0 - r + ae;
        let wall =
            Toolpath { name: "wall".into(), tool: 1, spindle_rpm: 10_000.0, start: DVec3::new(-30.0, y, z), moves: vec![Move::Line { to: DVec3::new(30.0, y, z), feed: 1000.0 }], cycles: Vec::new() };
        let lower = Toolpath {
            name: "side".into(),
            tool: 2,
            spindle_rpm: 10_000.0,
            start: DVec3::new(-30.0, 2.0, z),
            moves: (0..=8).map(|k| Move::Line { to: DVec3::new(30.0 * if k % 2 == 0 { 1.0 } else { -1.0 }, 2.0 - k as f64, z), feed: 1000.0 }).collect(),
            cycles: Vec::new(),
        };
        // The stock below y = 10 cleared to z first by the φ16 (its centre at y ≤ 2).
        let got = measure(&[lower, wall], &tools, false);
        let exact = sampled(DVec2::new(0.0, y), DVec2::X, &|p| p.y > 10.0);
        assert!((exact - Adaptive::angle_of(ae, r)).abs() < 0.01);
        let m = got.moves[0].expect("the cut counts") as f64;
        eprintln!("along a wall, ae {ae}: {m:.2}° measured, {:.2}° exact", exact.to_degrees());
        assert!((m - exact.to_degrees()).abs() < 2.0, "along a wall ae {ae}: {m:.1}° measured, {:.1}° exact", exact.to_degrees());
        for climb in [true, false] {
            // A hole of radius 8 plunged by the φ16, then round it at 8 − r + ae.
            let rho = 8.0 - r + ae;
            let plunge = Toolpath {
                name: "hole".into(),
                tool: 2,
                spindle_rpm: 10_000.0,
                start: DVec3::new(0.0, 0.0, 12.0),
                moves: vec![Move::Line { to: DVec3::new(0.0, 0.0, z), feed: 250.0 }],
                cycles: Vec::new(),
            };
            let a = DVec3::new(rho, 0.0, z);
            let round: Vec<Move> = [DVec3::new(-rho, 0.0, z), a].into_iter().map(|to| Move::Arc { to, center: DVec2::ZERO, clockwise: !climb, feed: 1000.0 }).collect();
            let circle = Toolpath { name: "round".into(), tool: 1, spindle_rpm: 10_000.0, start: a, moves: round, cycles: Vec::new() };
            let got = measure(&[plunge, circle], &tools, climb);
            let dir = if climb { DVec2::Y } else { -DVec2::Y };
            let exact = sampled(DVec2::new(rho, 0.0), dir, &|p| p.length() > 8.0);
            let m = got.moves[0].expect("the cut counts") as f64;
            eprintln!("round a hole, ae {ae}, climb {climb}: {m:.2}° measured, {:.2}° exact", exact.to_degrees());
            assert!((m - exact.to_degrees()).abs() < 2.0, "round a hole ae {ae}, climb {climb}: {m:.1}° measured, {:.1}° exact", exact.to_degrees());
        }
    }
}

/// A channel 8 mm wide (narrower than twice the φ6 tool) and 40 long, closed at both ends: a
/// small helix where the helix does not fit, then the channel cleared, clean, in trochoidal
/// loops rather than a slot: the tool's centre, with 2 mm of room across, loops from side to
/// side as it advances (turning back on itself across the channel again and again), and the
/// engagement stays at the load's (a slot would read 90° all along).
#[test]
fn a_channel_narrower_than_twice_the_tool_is_cleared() {
    let d = drawing_of(vec![Loop::rect(DVec2::ZERO, DVec2::new(40.0, 8.0))]);
    let job = pocket_job(vec![flat(1, 6.0)], vec![adaptive(1, 0.1, 4.0, 4.0)]);
    let out = job::run(&job, d, &mut Progress::none()).unwrap();
    clean(&out);
    let expected = (40.0 * 8.0 - 4.0 * 9.0 * (1.0 - PI / 4.0)) * 4.0;
    let got = removed(&out);
    assert!((got - expected).abs() < 0.01 * expected, "removed {got:.0} mm³, expected {expected:.0}");
    let e = out.operations[0].engagement.as_ref().expect("an engagement report");
    assert!(e.within >= 0.7 && e.over <= 0.05 && e.mean < 1.2 * e.target, "{}", e.describe());
    // Loops: the level's cutting moves cross the channel's middle line many times, both ways.
    let (mut up, mut down) = (0, 0);
    for m in out.moves.iter().filter(|m| !m.mv.is_rapid() && m.from.z < -3.9 && m.mv.to().z < -3.9) {
        let (a, b) = (m.from.y - 4.0, m.mv.to().y - 4.0);
        if a < 0.0 && b >= 0.0 {
            up += 1;
        } else if a >= 0.0 && b < 0.0 {
            down += 1;
        }
    }
    assert!(up >= 100 && down >= 100, "the middle line crossed {up} times up and {down} down");
    rs274(&out.gcode, &job.tools);
}

/// Rest clearing: a φ10 clears a 30 × 30 pocket, then a φ4 only the corners it left (the
/// in-process stock is the material): clean, the φ4's closed-form volume, and a fraction of the
/// φ10's cutting length.
#[test]
fn a_smaller_tool_after_a_larger_one_cuts_only_what_is_left() {
    let d = drawing_of(vec![Loop::rect(DVec2::ZERO, DVec2::splat(30.0))]);
    let first = pocket_job(vec![flat(1, 10.0)], vec![adaptive(1, 0.15, 3.0, 3.0)]);
    let big = job::run(&first, d.clone(), &mut Progress::none()).unwrap();
    let both = pocket_job(vec![flat(1, 10.0), flat(2, 4.0)], vec![adaptive(1, 0.15, 3.0, 3.0), Pocket2d { name: "rest".into(), ..adaptive(2, 0.15, 3.0, 3.0) }]);
    let out = job::run(&both, d.clone(), &mut Progress::none()).unwrap();
    clean(&out);
    let corners = |r: f64| 4.0 * r * r * (1.0 - PI / 4.0) * 3.0;
    let rest = removed(&out) - removed(&big);
    let expected = corners(5.0) - corners(2.0);
    assert!((rest - expected).abs() < 0.05 * expected, "the φ4 removed {rest:.1} mm³, expected {expected:.1}");
    // Against the φ4 clearing the pocket alone.
    let alone = job::run(&pocket_job(vec![flat(2, 4.0)], vec![adaptive(2, 0.15, 3.0, 3.0)]), d, &mut Progress::none()).unwrap();
    let (rest_len, alone_len) = (cutting_length(&out) - cutting_length(&big), cutting_length(&alone));
    assert!(rest_len < 0.15 * alone_len, "the rest pass cut along {rest_len:.0} mm, the φ4 alone {alone_len:.0}");
    rs274(&out.gcode, &both.tools);
}

/// A 3D part (the sample), adaptive roughing at a deep step-down: clean, and no more material
/// left than z-level roughing at the same allowances leaves (to the simulation's cell), in
/// G2/G3 arcs that rs274 reads; a pass entered from above goes down the way its level's passes
/// cleared at the air feed, not the plunge.
#[test]
fn the_sample_part_is_roughed_adaptively() {
    let roughing = Roughing { grid: 0.5, ..Roughing::default() };
    let run = |op: Operation| {
        let job = Job {
            tools: vec![flat(1, 6.0)],
            operations: vec![op],
            part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
            simulation: swarf::job::Simulation { verify: true, cell: Some(0.25), ..Default::default() },
            ..Job::default()
        };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        clean(&out);
        rs274(&out.gcode, &job.tools);
        out
    };
    let adaptive = run(Operation::RoughAdaptive(RoughAdaptive { stepdown: 4.0, stepover_fraction: 0.15, roughing, ..RoughAdaptive::default() }));
    assert!(adaptive.gcode.contains("G2") || adaptive.gcode.contains("G3"));
    // Straight descents: at the plunge feed only the gap above the material, where the passes
    // have cleared the way down at the air feed (they took 2.2 s a level each at the plunge).
    let descents = |feed: f64| {
        let down = adaptive.moves.iter().filter(|m| matches!(m.mv, Move::Line { .. }) && m.mv.feed() == Some(feed) && m.mv.to().truncate().distance(m.from.truncate()) < 1e-9);
        down.map(|m| m.from.z - m.mv.to().z).filter(|&d| d > 0.0).collect::<Vec<f64>>()
    };
    let (plunged, aired) = (descents(250.0), descents(Job::default().air_feed()));
    let (p, a) = (plunged.iter().sum::<f64>(), aired.iter().sum::<f64>());
    assert!(!aired.is_empty() && p < 0.1 * a, "{} descents at the plunge feed, {p:.1} mm; {} at the air feed, {a:.1} mm", plunged.len(), aired.len());
    let zlevel = run(Operation::RoughZlevel(RoughZlevel { steps: swarf::operations::Steps { stepdown: 4.0, stepover_fraction: 0.4 }, roughing, ..RoughZlevel::default() }));
    let (a, z) = (removed(&adaptive), removed(&zlevel));
    assert!(a > z * 0.995, "adaptive removed {a:.0} mm³, z-level {z:.0}");
    // The step range set (the longest at half the tool's radius): a different path, as clean,
    // read by rs274, removing as much, with no warning that it stopped short.
    let ranged = run(Operation::RoughAdaptive(RoughAdaptive { stepdown: 4.0, stepover_fraction: 0.15, roughing, min_step: Some(0.3), max_step: Some(1.5), ..RoughAdaptive::default() }));
    assert_ne!(ranged.gcode, adaptive.gcode);
    let r = removed(&ranged);
    assert!(r > a * 0.995, "with the step range, {r:.0} mm³ against {a:.0}");
    assert!(ranged.warnings.iter().all(|w| !w.message.contains("stopped")), "{:?}", ranged.warnings);
}

/// PyCAM's text box (shared data; skipped where absent), its box the stock: the stock's corners
/// outside the block's rounded ones are material along the stock's edge. Planned with the
/// tool's centre kept within the stock's edge, each corner took a helix down for every few
/// tenths of it: 7,411 helices, and 26 hours by the CLI. Passes now start in the air beside the
/// stock: clean (every entry down where the simulation holds nothing, beside it, or down a helix), read by
/// rs274, and the program within 2× z-level roughing's at the same step-down and radial cut
/// (1.5× today: the letters' narrow strokes make adaptive clearing's path longer,
/// BENCHMARKS.md).
#[test]
fn the_stocks_corners_are_entered_from_the_air_beside_it() {
    let Some(path) = common::shared_data("meshes/pycam_textbox.stl") else { return };
    let part = swarf::mesh::import::read_mesh_auto(&std::fs::read(path).unwrap(), Some("pycam_textbox.stl"), &Default::default()).unwrap();
    let roughing = Roughing { grid: 0.5, ..Roughing::default() };
    let run = |op: Operation| {
        let job = Job {
            tools: vec![flat(1, 3.0)],
            operations: vec![op],
            part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
            stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
            simulation: swarf::job::Simulation { verify: true, cell: Some(0.25), ..Default::default() },
            ..Job::default()
        };
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap();
        clean(&out);
        out
    };
    let adaptive = run(Operation::RoughAdaptive(RoughAdaptive { stepdown: 5.0, stepover_fraction: 0.15, roughing, ..RoughAdaptive::default() }));
    let zlevel = run(Operation::RoughZlevel(RoughZlevel { steps: swarf::operations::Steps { stepdown: 5.0, stepover_fraction: 0.15 }, roughing, ..RoughZlevel::default() }));
    // A helix: a run of arcs going down.
    let down_arc = |m: &swarf::sim::program::ProgramMove| matches!(m.mv, Move::Arc { .. }) && m.mv.to().z < m.from.z - 1e-9;
    let helices = adaptive.moves.iter().enumerate().filter(|&(k, m)| down_arc(m) && (k == 0 || !down_arc(&adaptive.moves[k - 1]))).count();
    let (a, z) = (adaptive.cycle.seconds, zlevel.cycle.seconds);
    assert!(a < 2.0 * z, "adaptive clearing runs {:.0} min ({helices} helices), z-level roughing {:.0} min", a / 60.0, z / 60.0);
    assert!(removed(&adaptive) > 0.99 * removed(&zlevel));
    rs274(&adaptive.gcode, &[flat(1, 3.0)]);
}
