//! Waterline finishing: contours of a ball around a hemisphere at the closed-form radius, and the
//! mould job (rough, raster the shallow, waterline the steep) clean and finished.

mod common;

use swarf::cutter::Cutter;
use swarf::job::{self, Job, Operation, Simulation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::sample::demo_part;
use swarf::operations::FinishWaterline;
use swarf::progress::Progress;
use swarf::toolpath::Move;

#[test]
fn waterlines_round_a_hemisphere_lie_on_the_closed_form_circles() {
    let (rs, r) = (10.0, 3.0);
    let part = common::cap(rs, 9.9, 0.2);
    let job = Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 5.0, margin_top: 0.5, ..Default::default() },
        tools: vec![Tool { cutter: Cutter::ball(2.0 * r), ..Tool::default() }],
        operations: vec![Operation::FinishWaterline(FinishWaterline { stepdown: 1.0, slope_min: 25.0, ..FinishWaterline::default() })],
        simulation: Simulation { verify: true, cell: Some(0.2), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    // Level moves (feeds at one height, away from entries) stand on the circle where the ball
    // touches the sphere at that height: the faceted cap lies inside the sphere, so a little in.
    let mut at = out.paths[0].start;
    let mut checked = 0;
    for m in &out.paths[0].moves {
        let to = m.to();
        if matches!(m, Move::Line { .. }) && (to.z - at.z).abs() < 1e-9 && to.z > 0.5 {
            let rho = ((rs + r).powi(2) - (to.z + r).powi(2)).sqrt();
            let d = to.truncate().length();
            // (the contour keeps back from the level's edge by `contour::back_off`, 0.0125 mm
            // here, with 0.0018 mm of slack, and its cutter is grown by the resolution the job is
            // planned for, the inch's 0.0018 mm)
            let grown = job.post.planning_resolution();
            assert!(d <= rho + 0.0125 + 0.0018 + grown && d >= rho - 0.25, "at z {}: {d} from the axis, the sphere's circle {rho}, from {at}", to.z);
            checked += 1;
        }
        at = to;
    }
    assert!(checked > 200, "{checked}");
}

#[test]
fn the_mould_job_roughs_and_finishes_the_sample_part_clean() {
    let job = Job { simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() }, ..Job::demo() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert_eq!(out.operations.len(), 3);
    // The finish leaves (nearly) nothing: the roughing's stair-step is gone from shallow and
    // steep areas alike.
    assert!(v.report.residual_max < 0.15, "{}", v.report.describe());
    let rough = &out.operations[0];
    assert!(rough.left_max.unwrap() > 1.0, "{rough:?}");
    // No straight plunge into material anywhere.
    for (m, &vol) in out.moves.iter().zip(&v.volumes) {
        if let Move::Line { to, .. } = m.mv {
            if to.truncate().distance(m.from.truncate()) < 1e-9 && to.z < m.from.z - 1e-9 {
                // A start counts as in the air when the stock there stands no more than the gouge
                // tolerance (0.02 mm) above the cutter: up to that skin over its footprint.
                assert!(vol < 0.02 * std::f64::consts::PI * 9.0 + 1e-6, "a straight plunge from {} to {to} in {} removed {vol} mm³", m.from, out.paths[m.path].name);
            }
        }
    }
}

/// Levels by the scallop round a hemisphere: on the sphere the ball's centre rides (radius
/// R + r), neighbouring levels lie about s = sqrt(8 r h) apart along it, the spacing that leaves a
/// scallop h on a flat, wherever the slope is; where the slope is steep the step down is nearly s,
/// where it is shallow much less.
#[test]
fn levels_by_the_scallop_lie_a_scallops_width_apart_along_a_hemisphere() {
    let (rs, r, h) = (10.0, 3.0, 0.01);
    let part = common::cap(rs, 9.9, 0.2);
    let job = Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 5.0, margin_top: 0.5, ..Default::default() },
        tools: vec![Tool { cutter: Cutter::ball(2.0 * r), ..Tool::default() }],
        operations: vec![Operation::FinishWaterline(FinishWaterline { scallop: Some(h), slope_min: 25.0, ..FinishWaterline::default() })],
        simulation: Simulation { verify: true, cell: Some(0.2), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.is_clean());
    // The levels: heights of level feeds.
    let mut levels: Vec<f64> = Vec::new();
    let mut at = out.paths[0].start;
    for m in &out.paths[0].moves {
        let to = m.to();
        if matches!(m, Move::Line { .. }) && (to.z - at.z).abs() < 1e-12 && !levels.iter().any(|&z| (z - to.z).abs() < 1e-9) {
            levels.push(to.z);
        }
        at = to;
    }
    levels.sort_by(|a, b| b.total_cmp(a));
    let (rho, s) = (rs + r, (8.0 * r * h).sqrt());
    let elevation = |z: f64| ((z + r) / rho).clamp(-1.0, 1.0).asin();
    let mut checked = 0;
    for w in levels.windows(2) {
        if w[1] < 0.5 {
            continue; // the cap's rim
        }
        let apart = rho * (elevation(w[0]) - elevation(w[1]));
        assert!(apart <= 1.1 * s && apart >= 0.85 * s, "levels {} and {}: {apart} mm apart along the sphere, s = {s}", w[0], w[1]);
        checked += 1;
    }
    assert!(checked >= 10, "{levels:?}");
    // Steeper lower down: the steps grow towards the equator.
    let steps: Vec<f64> = levels.windows(2).filter(|w| w[1] >= 0.5).map(|w| w[0] - w[1]).collect();
    assert!(steps.last().unwrap() > &(1.5 * steps[0]), "{steps:?}");
}

/// The page's warm-up job (swarf.js runs it in a worker of its own as an engine starts, so that
/// the browser compiles the code before the user's first job) runs each strategy of the mould
/// job, and the zigzag, on its small part, clean. Natively it takes about 0.1 s.
#[test]
fn the_warm_up_job_runs_each_strategy_on_its_small_part_clean() {
    let job = Job::warm_up();
    let start = std::time::Instant::now();
    let out = job::run(&job, swarf::mesh::sample::warm_up_part(), &mut Progress::none()).unwrap();
    let seconds = start.elapsed().as_secs_f64();
    let v = out.verification.as_ref().expect("the warm-up verifies, as the page's jobs do");
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let kinds: Vec<String> = job.operations.iter().map(|o| serde_json::to_value(o).unwrap()["kind"].as_str().unwrap().to_string()).collect();
    assert_eq!(kinds, ["roughZlevel", "roughZigzag", "finishRaster", "finishWaterline"]);
    assert_eq!(out.paths.len(), 4);
    for path in &out.paths {
        assert!(path.moves.len() > 20, "{}: {} moves", path.name, path.moves.len());
    }
    eprintln!("warm-up: {} moves, {seconds:.3} s", out.moves.len());
}

/// Issue 38: waterline finishing after roughing plunged straight down in 157 and 269 entries on
/// two mould inserts ("found no room for a helix or a ramp"). On the generated mould (walls,
/// ribs, pockets and slots) and the shared parts, a φ6 flat z-level rough then a φ6 ball
/// waterline (their default settings) enters every level from the air beside it, from
/// the level above along the surface or from what the roughing cleared: no such warning, and no
/// straight plunge into material.
#[test]
fn waterline_after_roughing_never_plunges_into_material() {
    let mut parts = vec![("generated mould", swarf::mesh::sample::octree_mould(1.0))];
    for file in ["kiri_pocket-test.stl", "pycam_textbox.stl"] {
        if let Some(path) = common::shared_data(&format!("meshes/{file}")) {
            parts.push((file, swarf::mesh::import::read_mesh_auto(&std::fs::read(path).unwrap(), Some(file), &swarf::geom::tolerance::Tolerances::default()).unwrap()));
        }
    }
    for (name, part) in parts {
        let job = Job {
            part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
            tools: vec![
                Tool { number: 1, cutter: Cutter { flute_length: 40.0, ..Cutter::flat(6.0) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() },
                Tool { number: 2, cutter: Cutter { flute_length: 40.0, ..Cutter::ball(6.0) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() },
            ],
            operations: vec![Operation::RoughZlevel(swarf::operations::RoughZlevel { tool: 1, ..Default::default() }), Operation::FinishWaterline(FinishWaterline { tool: 2, ..Default::default() })],
            simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
            ..Job::default()
        };
        let out = job::run(&job, part, &mut Progress::none()).unwrap();
        common::clean(&out);
        let plunges: Vec<String> = out.warnings.iter().map(|w| w.to_string()).filter(|w| w.contains("no room")).collect();
        assert!(plunges.is_empty(), "{name}: {plunges:?}");
    }
}

/// Waterline rest finishing: after a φ6 ball's waterline on the sample part, a φ3 ball's with
/// `restOnly` cuts only where the φ6 left material (its corners and the foot of its walls): a
/// fraction of a whole φ3 waterline's feed, as clean, leaving as little; and the same φ6 run again
/// with `restOnly` finds nothing to cut.
#[test]
fn waterline_rest_only_takes_what_a_larger_ball_left() {
    let tools = vec![
        Tool { number: 1, name: "6 mm ball".into(), cutter: Cutter { flute_length: 30.0, ..Cutter::ball(6.0) }, feed_rate: 1500.0, plunge_rate: 300.0, ..Tool::default() },
        Tool { number: 2, name: "3 mm ball".into(), cutter: Cutter { flute_length: 30.0, ..Cutter::ball(3.0) }, feed_rate: 1200.0, plunge_rate: 300.0, ..Tool::default() },
    ];
    let wl = |tool: u32, rest_only: bool| Operation::FinishWaterline(FinishWaterline { tool, rest_only, slope_min: 40.0, stepdown: 0.5, ..FinishWaterline::default() });
    let demo = Job::demo();
    let run = |ops: Vec<Operation>| {
        let job = Job { tools: tools.clone(), operations: ops, simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() }, ..demo.clone() };
        job::run(&job, demo_part(), &mut Progress::none()).unwrap()
    };
    let rough = demo.operations[0].clone();
    let rough = match rough {
        Operation::RoughZlevel(mut r) => {
            r.tool = 1;
            Operation::RoughZlevel(r)
        }
        other => other,
    };
    let whole = run(vec![rough.clone(), wl(1, false), wl(2, false)]);
    let rest = run(vec![rough.clone(), wl(1, false), wl(2, true)]);
    common::clean(&rest);
    let (w, r) = (&whole.operations[2], &rest.operations[2]);
    eprintln!(
        "φ3 waterline whole: {:.0} mm fed, {:.0} s, removed {:.1} mm³; rest only: {:.0} mm fed, {:.0} s, removed {:.1} mm³",
        w.feed_length,
        w.seconds,
        w.removed.unwrap(),
        r.feed_length,
        r.seconds,
        r.removed.unwrap()
    );
    assert!(r.feed_length > 0.0 && r.feed_length < 0.6 * w.feed_length, "rest {:.0} mm against {:.0}", r.feed_length, w.feed_length);
    assert!(r.removed.unwrap() > 0.9 * w.removed.unwrap(), "rest removed {:?} against {:?}", r.removed, w.removed);
    let (lw, lr) = (whole.verification.as_ref().unwrap().report.residual_max, rest.verification.as_ref().unwrap().report.residual_max);
    assert!(lr <= lw + 0.02, "left {lr:.3} after the rest, {lw:.3} after the whole");
    let again = run(vec![rough, wl(1, false), wl(1, true)]);
    assert!(again.operations[2].feed_length < 0.05 * again.operations[1].feed_length, "{:?}", again.operations[2]);
}

/// Issue 92: waterline finishing stops at its bottom height. On the sample part (its top at
/// Z0), a waterline whose bottom is 10 mm under the part's top makes no level below it, and
/// still finishes the walls above it.
#[test]
fn a_waterline_stops_at_its_bottom_height() {
    use swarf::operations::{HeightFrom, Heights};
    let mut job = Job::demo();
    let ball = job.tools.iter().find(|t| matches!(t.cutter.shape, swarf::cutter::Shape::Ball)).map(|t| t.number).unwrap();
    job.operations = vec![Operation::FinishWaterline(FinishWaterline {
        tool: ball,
        heights: Heights { bottom: Some(-10.0), bottom_from: HeightFrom::PartTop, ..Heights::default() },
        ..FinishWaterline::default()
    })];
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let cuts: Vec<f64> = out.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).collect();
    let lowest = cuts.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(lowest >= -10.0 - 1e-6, "down to Z{lowest}");
    assert!(cuts.iter().filter(|&&z| z < -5.0).count() > 10, "no levels between Z-5 and its bottom");
}
