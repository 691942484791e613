//! Scallop finishing (issue 60): the material left across a part whose surface is known
//! exactly, on steep ground and shallow, against the cusp asked for; every program simulated
//! clean and read by LinuxCNC's rs274.

mod common;

use common::{clean, rs274};
use swarf::cutter::Cutter;
use swarf::geom::DVec2;
use swarf::job::{self, Job, JobOutput, Operation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::Mesh;
use swarf::operations::FinishScallop;
use swarf::progress::Progress;

/// A dome of radius 20 about (25, 25, −5) on a 50 × 50 block whose top is z = 0: slopes from
/// level at its top to 75° where it meets the block, sampled every 0.1 mm.
fn dome() -> Mesh {
    round_top(dome_rho)
}

/// A vault: a cylinder of radius 20 along y, its axis at x = 25, z = −5, on the same block.
fn vault() -> Mesh {
    round_top(vault_rho)
}

/// How far from the axis (the vault's) or the centre (the dome's) a point lies in plan.
fn dome_rho(p: DVec2) -> f64 {
    p.distance(DVec2::splat(25.0))
}

fn vault_rho(p: DVec2) -> f64 {
    (p.x - 25.0).abs()
}

fn round_top(rho: fn(DVec2) -> f64) -> Mesh {
    swarf::mesh::sample::height_field_solid(DVec2::ZERO, DVec2::splat(50.0), 500, 500, -5.0, move |x, y| round_z(rho(DVec2::new(x, y))).max(0.0))
}

fn round_z(rho: f64) -> f64 {
    (400.0 - rho * rho).max(0.0).sqrt() - 5.0
}

fn scallop_job(op: FinishScallop, tool: Cutter) -> Job {
    Job {
        tools: vec![Tool { number: 1, name: "finisher".into(), cutter: Cutter { flute_length: 30.0, ..tool }, feed_rate: 1500.0, plunge_rate: 300.0, ..Tool::default() }],
        operations: vec![Operation::FinishScallop(op)],
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
        simulation: swarf::job::Simulation { verify: true, cell: Some(0.1), ..Default::default() },
        ..Job::default()
    }
}

/// The material left at every cell of the simulated stock over the dome and the flat about it
/// that a ball of radius `r` reaches (not in the ring where the dome meets the flat, nor at
/// the stock's edge), measured along the surface's normal: (left, steep) with steep over 30°.
fn left(out: &JobOutput, r: f64, rho_of: fn(DVec2) -> f64) -> Vec<(f64, bool)> {
    let v = out.verification.as_ref().expect("verified");
    let grid = v.stock.grid();
    let foot = (400.0f64 - 25.0).sqrt();
    let mut out = Vec::new();
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let p = grid.node(i, j);
            let rho = rho_of(p);
            if (rho > foot - 0.5 && rho < foot + r) || p.x.min(p.y).min(50.0 - p.x).min(50.0 - p.y) < 0.5 {
                continue;
            }
            let part = round_z(rho).max(0.0);
            let slope = if rho < foot { rho / (400.0 - rho * rho).sqrt() } else { 0.0 };
            let normal = (v.stock.top(i, j) - part) / (1.0 + slope * slope).sqrt();
            out.push((normal, slope > 30f64.to_radians().tan()));
        }
    }
    out
}

fn p95(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[(v.len() as f64 * 0.95) as usize]
}

/// A φ6 ball asked for a cusp of 0.02 on `part`: the 95th percentile of what is left, on the
/// steep and on the shallow, lies within the cusp; the steep gets passes closer in plan than
/// the flat (a plan step-over for that cusp leaves several times it on the flanks).
fn holds_the_cusp(part: Mesh, rho: fn(DVec2) -> f64, what: &str) {
    let cusp = 0.02;
    let job = scallop_job(FinishScallop { cusp, ..FinishScallop::default() }, Cutter::ball(6.0));
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    clean(&out);
    let left = left(&out, 3.0, rho);
    let steep: Vec<f64> = left.iter().filter(|l| l.1).map(|l| l.0).collect();
    let shallow: Vec<f64> = left.iter().filter(|l| !l.1).map(|l| l.0).collect();
    let (a, b) = (p95(steep.clone()), p95(shallow.clone()));
    eprintln!("{what}: left, 95th percentile: steep {a:.4} ({} cells), shallow {b:.4} ({} cells)", steep.len(), shallow.len());
    assert!(steep.len() > 10_000 && shallow.len() > 10_000);
    assert!(a <= cusp && b <= cusp, "{what}: steep {a:.4}, shallow {b:.4} against a cusp of {cusp}");
    // Nothing cut into the part.
    assert!(left.iter().all(|l| l.0 > -0.02), "a gouge of {:.4}", left.iter().map(|l| l.0).fold(0.0, f64::min));
    // The finish is fine everywhere, not the plan step's over the flanks: the mean too.
    let mean = steep.iter().sum::<f64>() / steep.len() as f64;
    assert!(mean < 0.6 * cusp, "{what}: {mean:.4} left on the steep, on average");
    rs274(&out.gcode, &job.tools);
}

#[test]
fn the_cusp_left_on_a_dome_is_the_one_asked_for_on_steep_and_shallow_ground() {
    holds_the_cusp(dome(), dome_rho, "dome");
}

#[test]
fn the_cusp_left_on_a_vault_is_the_one_asked_for_on_steep_and_shallow_ground() {
    holds_the_cusp(vault(), vault_rho, "vault");
}

/// A bull-nose end mill (φ6, corner 1) takes the step of its corner, and leaves no more.
#[test]
fn a_bull_nose_takes_the_step_of_its_corner() {
    let cusp = 0.02;
    let job = scallop_job(FinishScallop { cusp, ..FinishScallop::default() }, Cutter::bull_nose(6.0, 1.0));
    let out = job::run(&job, dome(), &mut Progress::none()).unwrap();
    clean(&out);
    let left = left(&out, 3.0, dome_rho);
    let all = p95(left.iter().map(|l| l.0).collect());
    eprintln!("bull-nose: left, 95th percentile {all:.4}");
    assert!(all <= cusp, "{all:.4} against a cusp of {cusp}");
}

/// A flat end mill has no corner to set a cusp by: the job says so.
#[test]
fn a_flat_end_mill_is_refused_with_a_reason() {
    let job = scallop_job(FinishScallop::default(), Cutter::flat(6.0));
    let err = job::run(&job, dome(), &mut Progress::none()).unwrap_err().to_string();
    assert!(err.contains("ball and bull-nose"), "{err}");
}

/// A cusp within the chordal tolerance can't be held: refused before any work, by name.
#[test]
fn a_cusp_below_the_tolerance_is_refused() {
    let job = scallop_job(FinishScallop { cusp: 0.001, ..FinishScallop::default() }, Cutter::ball(6.0));
    let err = job::run(&job, dome(), &mut Progress::none()).unwrap_err().to_string();
    assert!(err.contains("cusp"), "{err}");
}

/// Steep-and-shallow finishing at a cusp of 0.02 on the dome, with scallop passes and with
/// raster passes on the shallow: the 95th percentile left within the cusp on steep and shallow
/// ground alike; waterlines (feed moves at one height) on the flanks, clean, read by rs274.
#[test]
fn steep_and_shallow_holds_the_cusp_with_either_shallow_pattern() {
    use swarf::operations::finish_steep_shallow::{FinishSteepShallow, Shallow};
    let cusp = 0.02;
    for shallow in [Shallow::Scallop, Shallow::Raster] {
        let mut job = scallop_job(FinishScallop::default(), Cutter::ball(6.0));
        job.operations = vec![Operation::FinishSteepShallow(FinishSteepShallow { cusp, shallow, ..FinishSteepShallow::default() })];
        let out = job::run(&job, dome(), &mut Progress::none()).unwrap();
        clean(&out);
        let left = left(&out, 3.0, dome_rho);
        let steep = p95(left.iter().filter(|l| l.1).map(|l| l.0).collect());
        let flat = p95(left.iter().filter(|l| !l.1).map(|l| l.0).collect());
        // Level feed moves on the flanks (above the flat, off the top): the waterlines.
        let level = out.moves.iter().filter(|m| !m.mv.is_rapid() && (m.from.z - m.mv.to().z).abs() < 1e-9 && m.from.z > 3.0 && m.from.z < 12.0).count();
        eprintln!("steep and shallow, {shallow:?}: left p95 steep {steep:.4}, shallow {flat:.4}; {level} level moves on the flanks; {:.0} s", out.cycle.paths.iter().sum::<f64>());
        assert!(steep <= cusp && flat <= cusp, "{shallow:?}: steep {steep:.4}, shallow {flat:.4}");
        assert!(level > 100, "{level} level moves on the flanks");
        rs274(&out.gcode, &job.tools);
    }
}
