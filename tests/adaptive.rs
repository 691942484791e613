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
    rs274(&out.gcode, &job.tools);
}

/// A channel 8 mm wide (narrower than twice the φ6 tool) and 40 long, closed at both ends: a
/// small helix where the helix does not fit, then the channel cleared, clean.
#[test]
fn a_channel_narrower_than_twice_the_tool_is_cleared() {
    let d = drawing_of(vec![Loop::rect(DVec2::ZERO, DVec2::new(40.0, 8.0))]);
    let job = pocket_job(vec![flat(1, 6.0)], vec![adaptive(1, 0.1, 4.0, 4.0)]);
    let out = job::run(&job, d, &mut Progress::none()).unwrap();
    clean(&out);
    let expected = (40.0 * 8.0 - 4.0 * 9.0 * (1.0 - PI / 4.0)) * 4.0;
    let got = removed(&out);
    assert!((got - expected).abs() < 0.01 * expected, "removed {got:.0} mm³, expected {expected:.0}");
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
/// G2/G3 arcs that rs274 reads.
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
    let zlevel = run(Operation::RoughZlevel(RoughZlevel { steps: swarf::operations::Steps { stepdown: 4.0, stepover_fraction: 0.4 }, roughing, ..RoughZlevel::default() }));
    let (a, z) = (removed(&adaptive), removed(&zlevel));
    assert!(a > z * 0.995, "adaptive removed {a:.0} mm³, z-level {z:.0}");
}

/// PyCAM's text box (shared data; skipped where absent), its box the stock: the stock's corners
/// outside the block's rounded ones are material along the stock's edge. Planned with the
/// tool's centre kept within the stock's edge, each corner took a helix down for every few
/// tenths of it: 7,411 helices, and 26 hours by the CLI. Passes now start in the air beside the
/// stock: clean (every entry down where the simulation holds nothing, beside it, or down a helix), read by
/// rs274, and the program within 4× z-level roughing's at the same step-down and radial cut
/// (the letters' narrow strokes make adaptive clearing's path longer: BENCHMARKS.md).
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
    assert!(a < 4.0 * z, "adaptive clearing runs {:.0} min ({helices} helices), z-level roughing {:.0} min", a / 60.0, z / 60.0);
    assert!(removed(&adaptive) > 0.99 * removed(&zlevel));
    rs274(&adaptive.gcode, &[flat(1, 3.0)]);
}
