//! Seed 004's zigzag roughing on parts: the paper's pocket and the sample part, every program
//! simulated (no gouge, no rapid through stock, no straight plunge into material), the load
//! after correction held at the reference outside slots, and rs274-clean arcs.

mod common;

use common::clean;
use swarf::cutter::Cutter;
use swarf::job::{self, Job, JobOutput, Operation, Simulation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::sample::{demo_part, paper_pocket};
use swarf::operations::Roughing;
use swarf::operations::Steps;
use swarf::operations::{LoadControl, LoadReport, Passes, RoughZigzag};
use swarf::progress::Progress;
use swarf::sim::windows::windowed_rates;

fn flat(number: u32, d: f64) -> Tool {
    Tool { number, name: format!("{d} mm flat"), cutter: Cutter::flat(d), feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() }
}

/// The paper's case: φ10 flat, radial depth 3 mm, axial 0.5 mm, one level.
fn paper_job(load: LoadControl) -> Job {
    let op = RoughZigzag {
        tool: 1,
        load,
        pixel: Some(0.05),
        roughing: Roughing { allowance: 0.0, leave_stock: 0.0, grid: 0.5, ..Roughing::default() },
        steps: Steps { stepdown: 0.5, stepover_fraction: 0.3 },
        ..RoughZigzag::default()
    };
    let mut job = Job {
        tools: vec![flat(1, 10.0)],
        operations: vec![Operation::RoughZigzag(op)],
        simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        ..Job::default()
    };
    // The stock is the plate: only the pocket is cut.
    (job.stock.margin_xy, job.stock.margin_top, job.stock.margin_bottom) = (0.0, 0.0, 0.0);
    job
}

/// The removal rate over windows of Δs of the cutting moves at one height (entries left out)
/// by the project's own simulation at `cell`, over the reference rate.
fn simulated_rates(out: &JobOutput, cell: f64, ds: f64, reference: f64) -> Vec<f64> {
    windowed_rates(&out.moves, &out.stock, cell, ds).unwrap().into_iter().map(|r| r / reference).collect()
}

#[test]
fn the_papers_pocket_is_cleared_with_the_load_held() {
    let mut seconds = Vec::new();
    for load in [LoadControl::None, LoadControl::Feed, LoadControl::Path] {
        let job = paper_job(load);
        let out = job::run(&job, paper_pocket(0.5, 0.5), &mut Progress::none()).unwrap();
        clean(&out);
        assert!(out.gcode.contains("G2") || out.gcode.contains("G3") || load != LoadControl::Path);
        let report = out.operations[0].load.clone().unwrap();
        let (plain, _) = LoadReport::peak_and_spread(&report.plain);
        let (cut, _) = LoadReport::peak_and_spread(&report.cut);
        assert!(plain > 3.0, "the plain path slots (10 / 3 the reference): {plain}");
        // The project's simulation, over windows of 3 Δs (its cells are 0.1 mm).
        let rates = simulated_rates(&out, 0.05, report.sampling, 3.0 * 0.5 * 1000.0);
        let worst = rates.iter().copied().fold(0.0, f64::max);
        eprintln!("{load:?}: {} ; simulated peak {worst:.2} over {} windows", out.operations[0].describe(), rates.len());
        match load {
            LoadControl::None => assert!(cut > 3.0 && worst > 3.0, "{cut} {worst}"),
            _ => {
                assert!(cut <= 1.1 + 1e-9, "{cut}");
                assert!(worst <= 1.1, "simulated: {worst}");
            }
        }
        seconds.push(out.operations[0].seconds);
    }
    // At the feed its peak allows (1.1 × the reference), the plain path takes longer than
    // either way of holding the load.
    let plain_at_its_feed = seconds[0] * 3.0 / 1.1;
    assert!(seconds[1] < 0.9 * plain_at_its_feed && seconds[2] < 0.9 * plain_at_its_feed, "{seconds:?}");
}

#[test]
fn the_sample_part_is_roughed_clean_to_the_stair_step_both_ways() {
    let (stepdown, allowance, leave) = (2.0, 0.5, 0.5);
    for passes in [Passes::Zigzag, Passes::OneWay] {
        let op = RoughZigzag {
            tool: 1,
            passes,
            angle: 30.0,
            roughing: Roughing { allowance, leave_stock: leave, ..Roughing::default() },
            steps: Steps { stepdown, ..Steps::default() },
            ..RoughZigzag::default()
        };
        let job = Job { tools: vec![flat(1, 6.0)], operations: vec![Operation::RoughZigzag(op)], simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() }, ..Job::default() };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        clean(&out);
        assert!(out.warnings.iter().all(|w| !w.message.contains("straight down")), "{:?}", out.warnings);
        let r = &out.operations[0];
        assert!(r.left_max.unwrap() <= stepdown + allowance + leave * 3.0, "{passes:?}: {r:?}");
        let load = r.load.as_ref().unwrap();
        assert!(LoadReport::peak_and_spread(&load.cut).0 <= 1.1 + 1e-9, "{passes:?}");
        eprintln!("{passes:?}: {}", r.describe());
    }
}

/// A real terrain (OpenCAMLib's Mount Rushmore, from `../shared/data`): its levels' regions
/// run along cliffs, where a step of the corrected path a few microns past the region's edge
/// is a gouge millimetres deep. Every program clean by the job's simulation.
#[test]
fn a_terrain_with_cliffs_is_roughed_without_a_gouge_with_the_load_held() {
    let Some(dir) = common::shared_data("meshes") else { return };
    let bytes = std::fs::read(dir.join("ocl_mount_rush.stl")).unwrap();
    let part = swarf::mesh::import::read_mesh_auto(&bytes, Some("ocl_mount_rush.stl"), &swarf::geom::tolerance::Tolerances::default()).unwrap();
    let op = RoughZigzag {
        tool: 1,
        load: LoadControl::Path,
        roughing: Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() },
        steps: Steps { stepdown: 2.0, stepover_fraction: 0.4 },
        ..RoughZigzag::default()
    };
    let mut job = Job { tools: vec![flat(1, 6.0)], operations: vec![Operation::RoughZigzag(op)], part: PartSetup { placement: Placement::Keep, ..PartSetup::default() }, ..Job::default() };
    (job.stock.margin_xy, job.stock.margin_top, job.stock.margin_bottom) = (0.0, 0.0, 0.0);
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    clean(&out);
    // The load was held by extra path (the test tests the correction).
    let load = out.operations[0].load.as_ref().unwrap();
    assert!(LoadReport::peak_and_spread(&load.load).1 < LoadReport::peak_and_spread(&load.plain).1);
}
