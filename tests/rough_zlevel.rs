//! Z-level roughing: every program simulated (no gouge, no rapid through stock, no tool body in
//! material, no straight plunge into material), the material it leaves where the tool reaches
//! bounded by the allowances and the stair-step between levels, and LinuxCNC's rs274 reads it.

mod common;

use common::clean;

use common::mesh;
use swarf::cutter::Cutter;
use swarf::geom::{DVec2, DVec3};
use swarf::job::{self, FinishRaster, Job, Operation, Simulation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;
use swarf::strategy::rough_zlevel::RoughZlevel;
use swarf::toolpath::Move;

fn flat(number: u32, d: f64) -> Tool {
    Tool { number, cutter: Cutter { flute_length: 40.0, ..Cutter::flat(d) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() }
}

fn rough(allowance: f64, leave: f64) -> Operation {
    Operation::RoughZlevel(RoughZlevel { allowance, leave_stock: leave, ..RoughZlevel::default() })
}

/// A plate 60 mm square at z = 0 with a 20 mm box 8 high on it, and a step 3 high.
fn box_on_plate() -> swarf::mesh::Mesh {
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut tris = vec![[v(-30.0, -30.0, 0.0), v(30.0, -30.0, 0.0), v(30.0, 30.0, 0.0)], [v(-30.0, -30.0, 0.0), v(30.0, 30.0, 0.0), v(-30.0, 30.0, 0.0)]];
    let (lo, hi) = (v(-10.0, -10.0, 0.0), v(10.0, 10.0, 8.0));
    let (a, b, c, d) = (v(lo.x, lo.y, hi.z), v(hi.x, lo.y, hi.z), v(hi.x, hi.y, hi.z), v(lo.x, hi.y, hi.z));
    let (e, f, g, h) = (v(lo.x, lo.y, 0.0), v(hi.x, lo.y, 0.0), v(hi.x, hi.y, 0.0), v(lo.x, hi.y, 0.0));
    tris.extend([[a, b, c], [a, c, d], [e, f, b], [e, b, a], [f, g, c], [f, c, b], [g, h, d], [g, d, c], [h, e, a], [h, a, d]]);
    mesh(tris)
}


#[test]
fn a_box_on_a_plate_is_roughed_to_the_allowances() {
    let (allowance, leave) = (0.5, 0.3);
    let job = Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 1.0, ..Default::default() },
        tools: vec![flat(1, 6.0)],
        operations: vec![rough(allowance, leave)],
        simulation: Simulation { verify: true, cell: Some(0.2) },
        ..Job::default()
    };
    let out = job::run(&job, box_on_plate(), &mut Progress::none()).unwrap();
    clean(&out);
    let v = out.verification.as_ref().unwrap();
    // On the plate away from the box and on the box's top, the floor is left at the allowance.
    let g = v.stock.grid();
    let (mut plate, mut top) = (0, 0);
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            let d = DVec2::new((p.x.abs() - 10.0).max(0.0), (p.y.abs() - 10.0).max(0.0)).length();
            let left = v.stock.top(i, j);
            if d > leave + 0.3 && p.x.abs() < 29.0 && p.y.abs() < 29.0 {
                // (floors are cut 0.001 mm above the allowance: `rough_zlevel.rs`)
                assert!(left <= allowance + 0.0011, "{left} left on the plate at {p}");
                plate += 1;
            }
            if p.x.abs() < 9.5 && p.y.abs() < 9.5 {
                assert!(left <= 8.0 + allowance + 0.0011 && left >= 8.0 + allowance - 1e-6, "{left} on the box top at {p}");
                top += 1;
            }
            // The walls keep the radial allowance: nothing is cut within it.
            if d > 0.0 && d < leave - 0.2 {
                assert!(left > 8.0 - 1e-6, "the wall's leave-stock was cut at {p}: {left}");
            }
        }
    }
    assert!(plate > 10_000 && top > 5_000, "{plate} {top}");
    // One level on the box's top (a flat), and the floor.
    let zs: std::collections::BTreeSet<i64> = out.paths[0].moves.iter().filter(|m| matches!(m, Move::Arc { .. })).map(|m| (m.to().z * 1000.0).round() as i64).collect();
    assert!(zs.contains(&8501) && zs.contains(&501), "{zs:?}");
}

#[test]
fn the_sample_part_roughed_then_finished_is_clean_and_leaves_at_most_the_stair_step() {
    let (stepdown, allowance, leave) = (2.0, 0.5, 0.5);
    let job = Job {
        tools: vec![flat(1, 6.0), Tool { number: 2, cutter: Cutter::ball(6.0), ..Tool::default() }],
        operations: vec![Operation::RoughZlevel(RoughZlevel { stepdown, allowance, leave_stock: leave, ..RoughZlevel::default() })],
        simulation: Simulation { verify: true, cell: Some(0.25) },
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    clean(&out);
    let r = &out.operations[0];
    // Above the part: the stair-step (a level's height) over the allowances, where the slope
    // turns the radial allowance into more height.
    let left = r.left_max.unwrap();
    assert!(left <= stepdown + allowance + leave * 3.0, "{r:?}");
    assert!(out.gcode.contains("\nG2 ") || out.gcode.contains("\nG3 "), "arcs come out as G2/G3");
    // Then a raster finish with the ball: the whole sequence is clean, and the finish enters
    // the roughed part just above what the roughing left.
    let mut seq = job.clone();
    seq.operations.push(Operation::FinishRaster(FinishRaster { tool: 2, stepover: 1.0, grid: 0.5, ..FinishRaster::default() }));
    let out = job::run(&seq, demo_part(), &mut Progress::none()).unwrap();
    clean(&out);
    let fin = &out.operations[1];
    assert!(fin.removed.unwrap() < 0.2 * out.operations[0].removed.unwrap(), "{:?}", out.operations);
    assert!(fin.mrr_max.unwrap() < out.operations[0].mrr_max.unwrap() * 1.5, "{:?}", out.operations);
}
