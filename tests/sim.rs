//! The stock models of seed 002 against closed-form removed volumes, and verification against
//! programs with known faults.

mod common;

use swarf::cutter::{Cutter, Profile};
use swarf::geom::{Aabb, DVec2, DVec3, Tolerances};
use swarf::job::{self, FinishRaster, Job, Operation, Tool};
use swarf::mesh::sample::demo_part;
use swarf::operations::Roughing;
use swarf::operations::Steps;
use swarf::progress::Progress;
use swarf::sim::paper::{Case, Cut, CELLS, DEPTH, RADIUS, STEP};
use swarf::sim::program::{program_moves, simulate};
use swarf::sim::verify::{verify, VerifySettings};
use swarf::sim::{DexelStock, Model, StockModel, Sweep, SUPERSAMPLES};
use swarf::toolpath::{Move, Toolpath};

/// The spacing at which a model samples the stock across a cut's walls.
fn spacing(model: Model, cell: f64) -> f64 {
    match model {
        Model::Zmap | Model::Octree => cell,
        Model::EnhancedZmap | Model::SupersampledOctree => cell / SUPERSAMPLES as f64,
    }
}

/// A bound on a model's error for a straight cut through the 30 mm block: across the path each
/// model samples the cross-section at its spacing s, which misjudges each of the two edges of the
/// sampled region (the cut's wall and the block's side or the other wall) by at most one sample
/// of the cut's depth; the classical octree also samples the floor, in z, at its leaf size.
fn bound(model: Model, cell: f64, case: &Case) -> f64 {
    let length = 30.0;
    let s = spacing(model, cell);
    let walls = 2.0 * s * DEPTH * length;
    let width = if case.cut == Cut::Groove { 2.0 * RADIUS } else { swarf::sim::paper::ENGAGEMENT };
    let floor = if model == Model::Octree { cell * width * length } else { 0.0 };
    walls + floor
}

#[test]
fn every_model_stays_within_its_sampling_bound_of_the_exact_volume() {
    for case in Case::ALL {
        let exact = case.exact_volume();
        for model in Model::ALL {
            for cell in CELLS {
                let volume = case.simulate(model, cell);
                let error = (volume - exact).abs();
                assert!(error <= bound(model, cell, &case), "{} {} {cell}: {volume} vs exact {exact}", case.label(), model.label());
            }
        }
    }
}

#[test]
fn supersampled_octree_is_within_a_tenth_of_a_percent_on_the_grooves_at_half_millimetre_cells() {
    for case in Case::ALL.iter().filter(|c| c.cut == Cut::Groove) {
        let volume = case.simulate(Model::SupersampledOctree, 0.5);
        let error = (volume - case.exact_volume()).abs() / case.exact_volume();
        assert!(error < 0.001, "{}: {:.4} %", case.label(), error * 100.0);
        // The classical octree at the same cells is far off (the paper's point).
        let plain = (case.simulate(Model::Octree, 0.5) - case.exact_volume()).abs() / case.exact_volume();
        assert!(plain > 10.0 * error, "{}: octree {plain} vs supersampled {error}", case.label());
    }
}

#[test]
fn per_move_removal_is_the_cross_section_times_the_step_once_inside_the_block() {
    for case in Case::ALL {
        let volumes = case.per_move(Model::SupersampledOctree, 0.1);
        let moves = case.moves();
        let total: f64 = volumes.iter().sum();
        assert!((total - case.simulate(Model::SupersampledOctree, 0.1)).abs() < 1e-9);
        for (v, (a, b)) in volumes.iter().zip(&moves) {
            // Wholly inside the block: the cutter entered at least a radius ago and leaves later.
            if a.x >= RADIUS && b.x <= 30.0 - RADIUS {
                let exact = case.section() * STEP;
                let bound = 2.0 * spacing(Model::SupersampledOctree, 0.1) * DEPTH * STEP;
                assert!((v - exact).abs() <= bound, "{} at x = {}: {v} vs {exact}", case.label(), a.x);
            }
        }
        // Before the block, nothing.
        assert_eq!(volumes[0], 0.0);
    }
}

#[test]
fn removed_volume_is_conserved_by_every_model() {
    let stock = Case::stock();
    let profile = Profile::new(3.0, 1.0);
    let moves = [(DVec3::new(-4.0, 3.0, -2.0), DVec3::new(12.0, 9.5, -3.5)), (DVec3::new(12.0, 9.5, -3.5), DVec3::new(25.0, 2.0, -1.0)), (DVec3::new(25.0, 2.0, -1.0), DVec3::new(25.0, 2.0, -6.0))];
    for model in Model::ALL {
        let mut s = model.stock(&stock, 0.3);
        let before = s.volume();
        let removed: f64 = moves.iter().map(|&(a, b)| s.apply(&Sweep::line(profile, a, b))).sum();
        assert!(removed > 0.0);
        assert!((before - s.volume() - removed).abs() < 1e-6 * before, "{}", model.label());
        // Cutting the same moves again removes nothing, except in the enhanced z-map: a cell
        // split after a move cut it holds that move's height at its centre in every sub-cell, so
        // the move, repeated, trims the sub-cells it reaches lower (a known limit of splitting
        // cells as cuts come, without their history).
        let again: f64 = moves.iter().map(|&(a, b)| s.apply(&Sweep::line(profile, a, b))).sum();
        let allowed = if model == Model::EnhancedZmap { 1e-3 * removed } else { 1e-9 };
        assert!(again.abs() <= allowed, "{}: {again} of {removed}", model.label());
    }
}

#[test]
fn a_circular_groove_by_a_planar_arc_removes_the_annulus() {
    // A φ4 flat end at depth 1.83 around a full circle of radius 6 mm removes d · 4 π ρ R.
    let stock = Aabb { min: DVec3::new(-10.0, -10.0, -5.0), max: DVec3::new(10.0, 10.0, 0.0) };
    let (rho, r, d) = (6.0, 2.0, 1.83);
    let exact = d * 4.0 * std::f64::consts::PI * rho * r;
    let mv = Move::Arc { to: DVec3::new(rho, 0.0, -d), center: DVec2::ZERO, clockwise: false, feed: 100.0 };
    for model in [Model::EnhancedZmap, Model::SupersampledOctree] {
        let mut s = model.stock(&stock, 0.2);
        let removed: f64 = Sweep::of_move(Profile::new(r, 0.0), DVec3::new(rho, 0.0, -d), &mv, 0.001).iter().map(|sw| s.apply(sw)).sum();
        // Two circular walls, sampled at cell / k.
        let bound = spacing(model, 0.2) * d * std::f64::consts::TAU * 2.0 * rho;
        assert!((removed - exact).abs() <= bound, "{}: {removed} vs {exact}", model.label());
    }
}

#[test]
fn the_zmap_holds_the_exact_envelope_at_its_cell_centres() {
    let stock = Aabb { min: DVec3::new(0.0, 0.0, -10.0), max: DVec3::new(20.0, 20.0, 0.0) };
    let sweep = Sweep::line(Profile::new(3.0, 3.0), DVec3::new(2.0, 4.0, -1.0), DVec3::new(17.0, 13.0, -4.0));
    let mut s = DexelStock::new(&stock, 0.25, 1);
    s.apply(&sweep);
    let g = s.grid();
    for j in 0..g.ny {
        for i in 0..g.nx {
            let expect = sweep.lowest(g.node(i, j)).clamp(-10.0, 0.0);
            assert!((s.top(i, j) - expect).abs() < 1e-12);
        }
    }
}

fn plate_job(stepover: f64, allowance: f64) -> Job {
    Job {
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
        part: swarf::mesh::placement::PartSetup { placement: swarf::mesh::placement::Placement::Keep, ..Default::default() },
        tools: vec![Tool { cutter: Cutter::ball(6.0), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { stepover, allowance, boundary: swarf::job::Boundary::Stock, grid: 0.25, ..FinishRaster::default() })],
        ..Job::default()
    }
}

#[test]
fn residual_on_a_flat_plate_is_the_scallop_height() {
    // A ball of radius R passing at stepover s over a plane leaves cusps R - sqrt(R² - s²/4).
    let (r, s): (f64, f64) = (3.0, 1.0);
    let scallop = r - (r * r - s * s / 4.0).sqrt();
    let part = common::plane(20.0, 0.0, 0.0, 0.0);
    // A plate needs thickness for the stock below its top: lower the bottom with a margin.
    let mut job = plate_job(s, 0.0);
    job.stock.margin_bottom = 5.0;
    job.stock.margin_top = 0.5;
    job.simulation.cell = Some(0.05);
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    let v = out.verification.unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    // Away from the plate's edges the residual peaks at the cusps.
    let residual = v.residual();
    let g = residual.grid();
    let mut peak: f64 = 0.0;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            if p.x.abs() < 15.0 && p.y.abs() < 10.0 {
                peak = peak.max(residual.at(i, j));
            }
        }
    }
    // The cusp lies between cell centres: sampled within the slope there times half a cell.
    // Point reduction may leave the path up to the chordal tolerance above the passes.
    assert!(peak <= scallop + Tolerances::DEFAULT.chordal + 1e-9 && peak >= scallop - 0.5 * 0.05 * (s / 2.0) / (r * r - s * s / 4.0).sqrt(), "peak {peak} vs scallop {scallop}");
}

#[test]
fn verification_finds_gouges_rapids_through_stock_and_a_buried_tool_body() {
    let job = Job { simulation: swarf::job::Simulation { verify: true, cell: Some(0.25), ..Default::default() }, ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let clean = out.verification.as_ref().unwrap();
    assert!(clean.report.is_clean(), "{}", clean.report.describe());
    assert!(clean.report.removed > 0.0 && clean.report.residual_mean >= 0.0);
    let settings = VerifySettings { cell: 0.25, allowance: 0.0 };
    let tol = Tolerances::default();
    let check = |paths: &[Toolpath], tools: &[Tool]| {
        let moves = program_moves(paths, tools, swarf::toolpath::Rapids::at(3000.0), 3000.0).unwrap();
        verify(&out.part, &out.stock, &moves, &settings, &tol, &mut Progress::none()).unwrap().report
    };
    // The same program 0.5 mm lower gouges by 0.5 mm.
    let mut lowered = out.paths.clone();
    for m in &mut lowered[0].moves {
        if let Move::Line { to, .. } = m {
            to.z -= 0.5;
        }
    }
    let r = check(&lowered, &job.tools);
    assert!(r.gouge_count > 0 && (r.gouge_max - 0.5).abs() < 0.05, "{}", r.describe());
    // A rapid through the middle of the stock.
    let mid = out.stock.center();
    let mut rapid = out.paths.clone();
    rapid[0].moves.insert(0, Move::Rapid { to: mid });
    let r = check(&rapid, &job.tools);
    // It plunges in (move 0) and the next rapid leaves through the stock again; the tool's tip
    // at the stock's middle also lies below the part.
    assert_eq!(r.rapid_collision_count, 2, "{}", r.describe());
    assert_eq!(r.rapid_collisions[0].move_index, Some(0));
    assert!(r.gouge_count > 0);
    // The same way fed at the air feed (faster than the tool's feed: a move its operation knew
    // to cut nothing) is as wrong; at the tool's feed it is a cut.
    let feed = job.tools[0].feed_rate;
    for (f, wrong) in [(feed * 3.0, 2), (feed, 0)] {
        let mut fed = rapid.clone();
        fed[0].moves[0] = Move::Line { to: mid, feed: f };
        let at = fed[0].moves.iter().position(|m| m.is_rapid()).unwrap();
        let to = fed[0].moves[at].to();
        fed[0].moves[at] = Move::Line { to, feed: f };
        let r = check(&fed, &job.tools);
        assert_eq!(r.rapid_collision_count, wrong, "at F{f}: {}", r.describe());
    }
    // A 2 mm flute length buries the body where the finishing pass meets uncut stock.
    let short = vec![Tool { cutter: Cutter { flute_length: 2.0, ..job.tools[0].cutter.clone() }, ..job.tools[0].clone() }];
    let r = check(&out.paths, &short);
    assert!(r.body_collision_count > 0 && r.gouge_count == 0, "{}", r.describe());
}

#[test]
fn what_the_page_runs_is_clean_and_the_program_simulates_the_same_from_its_gcode() {
    // The G-code read back gives the same removed volume as the tool paths it was written from.
    let job = Job { simulation: swarf::job::Simulation { verify: true, cell: Some(0.3), ..Default::default() }, ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let from_paths = out.verification.unwrap().report;
    let from_gcode = swarf::job::verify_gcode(&job, demo_part(), &out.gcode, Some(0.3), &mut Progress::none()).unwrap().report;
    assert!(from_paths.is_clean() && from_gcode.is_clean(), "{}\n{}", from_paths.describe(), from_gcode.describe());
    // Coordinates are rounded to 1 µm in the G-code.
    assert!((from_paths.removed - from_gcode.removed).abs() < 1e-4 * from_paths.removed, "{} vs {}", from_paths.removed, from_gcode.removed);
}

#[test]
fn simulation_can_be_cancelled() {
    let job = Job { simulation: swarf::job::Simulation { verify: false, cell: None, ..Default::default() }, ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let mut stock = DexelStock::new(&out.stock, 0.5, 1);
    let mut calls = 0;
    let mut sink = |_: f64, _: &str| {
        calls += 1;
        calls < 3
    };
    let r = simulate(&mut stock, &out.moves, 0.002, &mut Progress::new(&mut sink));
    assert!(matches!(r, Err(swarf::Error::Cancelled)));
}

/// A part whose top is the stock's top, roughed leaving 0.3 mm: the raw stock over the part's
/// top is already less than the allowance above it, and cells no move touched are not gouges
/// (the verification once refused every such program: "gouges the part in 4672 cells, 0.299 mm
/// deep", at cells the tool never reached). Every roughing kind verifies clean.
#[test]
fn stock_left_under_the_allowance_by_the_raw_block_is_not_a_gouge() {
    use swarf::operations::{RoughOctree, RoughZigzag, RoughZlevel};
    let part = swarf::mesh::sample::paper_pocket(8.0, 1.0);
    let flat = |n: u32, d: f64| Tool { number: n, cutter: Cutter { flute_length: 25.0, ..Cutter::flat(d) }, ..Tool::default() };
    let kinds = [
        Operation::RoughZlevel(RoughZlevel {
            tool: 1,
            roughing: Roughing { allowance: 0.3, leave_stock: 0.3, grid: 0.5, ..Roughing::default() },
            steps: Steps { stepdown: 3.0, ..Steps::default() },
            ..RoughZlevel::default()
        }),
        Operation::RoughZigzag(RoughZigzag {
            tool: 1,
            roughing: Roughing { allowance: 0.3, leave_stock: 0.3, grid: 0.5, ..Roughing::default() },
            steps: Steps { stepdown: 3.0, ..Steps::default() },
            ..RoughZigzag::default()
        }),
        Operation::RoughOctree(RoughOctree { tools: vec![1, 2], roughing: Roughing { allowance: 0.3, leave_stock: 0.3, grid: 0.5, ..Roughing::default() }, ..RoughOctree::default() }),
    ];
    for op in kinds {
        let mut job = Job { tools: vec![flat(1, 10.0), flat(2, 4.0)], operations: vec![op], ..Job::default() };
        job.stock.margin_top = 0.0;
        job.simulation.cell = Some(0.5);
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap();
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{}: {}", job.operations[0].name(), v.report.describe());
        assert!(v.report.removed > 1000.0, "{}: removed {}", job.operations[0].name(), v.report.removed);
    }
}

/// The removal rate of a finishing job is a rate the tool can cut at: no higher than a slot as
/// wide as the tool and as deep as its flutes at its feed. Measured move by move it was not:
/// a 0.0001 mm step of a raster pass is credited with the whole cells whose centres it
/// uncovers, and read as 775,675 mm³/min on the sample part (the page's plot flattened by one
/// spike).
#[test]
fn a_finishing_jobs_peak_removal_rate_is_one_the_tool_can_cut_at() {
    let mut job = Job::demo();
    job.operations.retain(|o| o.name() == "finish shallow");
    let Operation::FinishRaster(r) = &mut job.operations[0] else { unreachable!() };
    (r.stepover, r.grid, r.slope_max) = (1.5, 0.5, None);
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let tool = &job.tools.iter().find(|t| t.number == 2).unwrap();
    let slot = tool.cutter.diameter * tool.cutter.flute_length * tool.feed_rate;
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.mrr_max <= slot, "peak {} mm³/min against a full slot's {slot}", v.report.mrr_max);
    assert!(out.operations[0].mrr_max.unwrap() <= slot);
    assert_eq!(v.rates.len(), out.moves.len());
    // And it is a rate: the volume over the time of the cutting moves is under the peak.
    let cutting: f64 = out.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.seconds).sum();
    assert!(v.report.removed / cutting * 60.0 <= v.report.mrr_max);
}

/// The rate over a stretch of path: a straight slot cut in moves far shorter than a cell, each
/// credited with whole cells, reads as the slot's own rate.
#[test]
fn removal_rates_are_measured_over_a_stretch_of_path() {
    use swarf::sim::program::{removal_rates, Timing};
    // 20 mm of slot, 2 mm² of section at 600 mm/min (1200 mm³/min), in 0.01 mm moves whose
    // volume comes in cells of 0.1 mm: every tenth move has it all.
    let n = 2000;
    let moves: Vec<Timing> = (0..n).map(|_| Timing { length: 0.01, seconds: 0.01 / 600.0 * 60.0, rapid: false }).collect();
    let volumes: Vec<f64> = (0..n).map(|k| if k % 10 == 9 { 0.2 } else { 0.0 }).collect();
    let rates = removal_rates(&moves, &volumes, 1.0);
    for (k, r) in rates.iter().enumerate() {
        assert!((r - 1200.0).abs() <= 1200.0 * 0.02, "move {k}: {r}");
    }
    // A rapid splits the runs and reads 0; a run shorter than the stretch is taken whole.
    let short = [Timing { length: 0.5, seconds: 0.05, rapid: false }, Timing { length: 10.0, seconds: 0.1, rapid: true }];
    assert_eq!(removal_rates(&short, &[1.0, 5.0], 1.0), vec![1200.0, 0.0]);
}
