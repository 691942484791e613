//! Z-level roughing: every program simulated (no gouge, no rapid through stock, no tool body in
//! material, no straight plunge into material), the material it leaves where the tool reaches
//! bounded by the allowances and the stair-step between levels, and LinuxCNC's rs274 reads it.

#[path = "../benches/support/mod.rs"]
mod support;

mod common;

use common::clean;

use common::mesh;
use swarf::cutter::Cutter;
use swarf::geom::{DVec2, DVec3};
use swarf::job::{self, FinishRaster, Job, Operation, Simulation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::sample::demo_part;
use swarf::operations::Roughing;
use swarf::operations::Steps;
use swarf::operations::{Order, RoughZlevel};
use swarf::progress::Progress;
use swarf::toolpath::Move;

fn flat(number: u32, d: f64) -> Tool {
    Tool { number, cutter: Cutter { flute_length: 40.0, ..Cutter::flat(d) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() }
}

fn rough(allowance: f64, leave: f64) -> Operation {
    Operation::RoughZlevel(RoughZlevel { roughing: Roughing { allowance, leave_stock: leave, ..Roughing::default() }, ..RoughZlevel::default() })
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

/// The allowances the box on the plate is roughed to (floors, walls).
const BOX_ALLOWANCE: f64 = 0.5;
const BOX_LEAVE: f64 = 0.3;

/// The box on the plate z-level roughed (φ6 flat end, the stock its box and 1 mm above it), its
/// program simulated and clean.
fn rough_box_on_plate() -> job::JobOutput {
    let job = Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 1.0, ..Default::default() },
        tools: vec![flat(1, 6.0)],
        operations: vec![rough(BOX_ALLOWANCE, BOX_LEAVE)],
        simulation: Simulation { verify: true, cell: Some(0.2), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, box_on_plate(), &mut Progress::none()).unwrap();
    clean(&out);
    out
}

#[test]
fn a_box_on_a_plate_is_roughed_to_the_allowances() {
    let (allowance, leave) = (BOX_ALLOWANCE, BOX_LEAVE);
    let out = rough_box_on_plate();
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
fn a_flats_level_is_cut_only_where_the_level_below_cannot_go() {
    // The box's top (8 + 0.5) is a flat between the stock's top (9) and the first step-down
    // level (7): its level is cut about the box alone; the plate around it is taken from 9 to 7
    // by the step-down level, not also in a thin pass at 8.5.
    let (allowance, leave) = (BOX_ALLOWANCE, BOX_LEAVE);
    let out = rough_box_on_plate();
    let r = 3.0;
    // Centres at the flat's level: over the box's top, or within the cutter (grown by the
    // leave-stock) of it, and a node and a half of the grid past that (the band), and the
    // region's boundary up to a node further.
    let reach = 10.0 + r + leave + 2.5 * 0.25 + 1e-6;
    let at_flat: Vec<DVec3> = out.paths[0].moves.iter().filter(|m| !m.is_rapid()).map(|m| m.to()).filter(|p| (p.z - 8.501).abs() < 5e-4).collect();
    let zs: std::collections::BTreeSet<i64> = out.paths[0].moves.iter().map(|m| (m.to().z * 1e4).round() as i64).collect();
    assert!(at_flat.len() > 20, "the flat's level is cut: {} {zs:?}", at_flat.len());
    for p in &at_flat {
        assert!(p.x.abs().max(p.y.abs()) <= reach, "the flat's level is cut at {p}, off the box");
    }
    // The plate is still cleared to its allowance, from the stock's top down in 2 mm steps.
    let v = out.verification.as_ref().unwrap();
    let g = v.stock.grid();
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            if p.x.abs().max(p.y.abs()) > 10.0 + leave + 0.3 && p.x.abs() < 29.0 && p.y.abs() < 29.0 {
                assert!(v.stock.top(i, j) <= allowance + 0.0011, "{} left on the plate at {p}", v.stock.top(i, j));
            }
        }
    }
    assert!(out.operations[0].mrr_max.unwrap() <= 1000.0 * 2.0 * 6.0 + 1e-6, "{:?}", out.operations);
}

#[test]
fn the_sample_part_roughed_then_finished_is_clean_and_leaves_at_most_the_stair_step() {
    let (stepdown, allowance, leave) = (2.0, 0.5, 0.5);
    let job = Job {
        tools: vec![flat(1, 6.0), Tool { number: 2, cutter: Cutter::ball(6.0), ..Tool::default() }],
        operations: vec![Operation::RoughZlevel(RoughZlevel {
            roughing: Roughing { allowance, leave_stock: leave, ..Roughing::default() },
            steps: Steps { stepdown, ..Steps::default() },
            ..RoughZlevel::default()
        })],
        simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
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

/// Z-level roughs `part` (φ6 flat end, step-down 2, no allowances, the stock its box) cleanly,
/// and every descent fed between two cuts (a ramp or a helix) drops at most the step-down plus
/// the rapid gap: each level is entered from the level cut above it, never from the stock's
/// top through the depth the operation has cleared already. Returns how many descending moves
/// came within 1 mm of `near`.
fn entered_from_the_level_above(part: swarf::mesh::Mesh, units: swarf::mesh::placement::PartUnits, near: &[DVec2]) -> usize {
    let job = Job {
        part: PartSetup { placement: Placement::Keep, units, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
        tools: vec![flat(1, 6.0)],
        operations: vec![Operation::RoughZlevel(RoughZlevel {
            roughing: Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() },
            steps: Steps { stepdown: 2.0, ..Steps::default() },
            ..RoughZlevel::default()
        })],
        simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    clean(&out);
    let (gap, mut at, mut from, mut deepest, mut counted) = (job.stock.retract, out.paths[0].start, None::<f64>, 0.0f64, 0);
    for m in &out.paths[0].moves {
        let to = m.to();
        match m {
            Move::Rapid { .. } => from = None,
            _ if to.z < at.z - 1e-9 => {
                let top = *from.get_or_insert(at.z);
                deepest = deepest.max(top - to.z);
                if near.iter().any(|c| to.truncate().distance(*c) < 1.0) {
                    counted += 1;
                }
            }
            _ if to.z > at.z + 1e-9 => from = None,
            _ => {}
        }
        at = to;
    }
    assert!(deepest <= 2.0 + gap + 1e-6, "a descent of {deepest} mm");
    counted
}

/// Wells a little wider than the tool, 18 mm deep in a 20 mm plate, off the grid by different
/// amounts: entered level by level.
#[test]
fn a_narrow_well_is_entered_from_the_level_above_not_from_the_top() {
    // Nine wells, from 0.25 to 0.65 mm wider than the tool.
    let wells: Vec<(DVec2, f64)> = (0..9).map(|k| (DVec2::new(-10.0 + 10.0 * (k % 3) as f64 + 0.037 * k as f64, -10.0 + 10.0 * (k / 3) as f64 + 0.061 * k as f64), 3.25 + 0.05 * k as f64)).collect();
    let centres: Vec<DVec2> = wells.iter().map(|w| w.0).collect();
    let part = swarf::mesh::sample::height_field_solid(DVec2::splat(-16.0), DVec2::splat(16.0), 513, 513, 0.0, |x, y| {
        let p = DVec2::new(x, y);
        if wells.iter().any(|(c, r)| p.distance(*c) < *r) {
            2.0
        } else {
            20.0
        }
    });
    let in_wells = entered_from_the_level_above(part, Default::default(), &centres);
    assert!(in_wells > 50, "{in_wells} descending moves in the wells");
}

/// The shared feature-type part (drawn in inches) has holes a little wider than the tool,
/// 36 mm deep, whose tiny regions start their rings on a vertex of the region the level above
/// cleared: they were entered from the stock's top at several levels (its program took 67
/// minutes instead of 33).
#[test]
fn the_feature_type_parts_holes_are_entered_from_the_level_above() {
    let Some(dir) = common::shared_data("meshes") else { return };
    let bytes = std::fs::read(dir.join("tm_featuretype.stl")).unwrap();
    let part = swarf::mesh::import::read_mesh_auto(&bytes, Some("tm_featuretype.stl"), &swarf::geom::tolerance::Tolerances::default()).unwrap();
    let holes = [DVec2::new(0.0, -25.4), DVec2::new(0.0, 25.4)];
    let in_holes = entered_from_the_level_above(part, swarf::mesh::placement::PartUnits::Inch, &holes);
    assert!(in_holes > 50, "{in_holes} descending moves in the holes");
}

/// Two square pockets 12 mm deep in a plate: cut region by region, the tool goes from one to
/// the other once; level by level, once a level. Both programs are clean and remove the same.
#[test]
fn regions_first_goes_from_pocket_to_pocket_once() {
    let centres = [DVec2::new(-15.0, 0.0), DVec2::new(15.0, 0.0)];
    let part = swarf::mesh::sample::height_field_solid(DVec2::new(-30.0, -15.0), DVec2::new(30.0, 15.0), 241, 121, 0.0, |x, y| {
        let p = DVec2::new(x, y);
        if centres.iter().any(|c| (p - *c).abs().max_element() < 7.0) {
            4.0
        } else {
            16.0
        }
    });
    let run = |order: Order| {
        let job = Job {
            part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
            stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
            tools: vec![flat(1, 6.0)],
            operations: vec![Operation::RoughZlevel(RoughZlevel {
                order,
                roughing: Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() },
                steps: Steps { stepdown: 2.0, ..Steps::default() },
                ..RoughZlevel::default()
            })],
            simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
            ..Job::default()
        };
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap();
        clean(&out);
        // The pocket each cut below the plate's top is in, in program order.
        let mut at = out.paths[0].start;
        let (mut switches, mut last, mut rapid) = (0, None, 0.0);
        for m in &out.paths[0].moves {
            let to = m.to();
            if m.is_rapid() {
                rapid += at.distance(to);
            } else if to.z < 15.0 {
                let pocket = to.x > 0.0;
                if last.is_some_and(|l| l != pocket) {
                    switches += 1;
                }
                last = Some(pocket);
            }
            at = to;
        }
        (switches, rapid, out.verification.unwrap().report.removed)
    };
    let (by_regions, by_levels) = (run(Order::Regions), run(Order::Levels));
    assert_eq!(by_regions.0, 1, "{by_regions:?}");
    assert!(by_levels.0 >= 5, "{by_levels:?}");
    assert!(by_regions.1 < 0.7 * by_levels.1, "rapids {by_regions:?} against {by_levels:?}");
    assert!((by_regions.2 - by_levels.2).abs() <= 1e-3 * by_levels.2, "removed {by_regions:?} against {by_levels:?}");
}

/// Where the rings along the outer boundary and those round an island meet (a boss on a plate,
/// the stock the part's box: cleared from the outside in), a ring whose tool would sweep only
/// what the rings before it cleared is left out: little of the feed at depth runs in the air.
#[test]
fn rings_in_the_air_are_left_out() {
    let part = swarf::mesh::sample::height_field_solid(DVec2::new(-30.0, -20.0), DVec2::new(30.0, 20.0), 241, 161, 0.0, |x, y| if x.abs() < 10.0 && y.abs() < 5.0 { 10.0 } else { 4.0 });
    let job = Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
        tools: vec![flat(1, 6.0)],
        operations: vec![rough(0.0, 0.0)],
        simulation: Simulation { verify: true, cell: Some(0.2), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    clean(&out);
    let v = out.verification.as_ref().unwrap();
    let (mut fed, mut air) = (0.0, 0.0);
    for (m, &volume) in out.moves.iter().zip(&v.volumes) {
        if let Move::Line { to, .. } | Move::Arc { to, .. } = m.mv {
            let length = m.from.distance(to);
            if (to.z - m.from.z).abs() < 1e-9 {
                fed += length;
                if volume < 1e-6 {
                    air += length;
                }
            }
        }
    }
    // 292 of 3,571 mm (links through what the level cleared, and rings partly in the air,
    // make the rest). It was 180 of 3,470 mm while the map let a ring go that left a sliver
    // the full 6 mm high standing between its neighbours' cuts: nothing stands higher than a
    // level's step now.
    assert!(v.report.residual_max <= 2.0 + 1e-6, "{} mm of material left", v.report.residual_max);
    assert!(air < 0.085 * fed, "{air} of {fed} mm at depth in the air");
}

/// The moves of `out` at a feed faster than their tool's: those an operation knew to cut
/// nothing (the air feed).
fn air_moves(out: &job::JobOutput) -> Vec<&swarf::sim::program::ProgramMove> {
    out.moves.iter().filter(|m| m.air).collect()
}

/// Stretches of rings over ground an earlier ring took, stay-down links across it and ways in
/// from beside the stock run at the air feed (the rapid rate by default): the path is the same,
/// the cycle shorter, and those moves remove nothing, in the job's own simulation and in one on
/// cells a fifth the size.
#[test]
fn moves_over_cleared_ground_run_at_the_air_feed_and_cut_nothing() {
    for (name, part, keep) in [("box on a plate", box_on_plate(), true), ("sample part", demo_part(), false)] {
        let mut job = Job {
            part: PartSetup { placement: if keep { Placement::Keep } else { Placement::default() }, ..PartSetup::default() },
            stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 1.0, ..Default::default() },
            tools: vec![flat(1, 6.0)],
            operations: vec![rough(0.0, 0.0)],
            simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
            ..Job::default()
        };
        let fast = job::run(&job, part.clone(), &mut Progress::none()).unwrap();
        clean(&fast);
        job.stock.air_feed = Some(0.0);
        let slow = job::run(&job, part.clone(), &mut Progress::none()).unwrap();
        clean(&slow);
        let rapid = job.post.rapid_rate;
        let air = air_moves(&fast);
        let air_length: f64 = air.iter().map(|m| m.mv.length(m.from)).sum();
        let v = fast.verification.as_ref().unwrap();
        let air_removed: f64 = fast.moves.iter().zip(&v.volumes).filter(|(m, _)| m.air).map(|(_, &v)| v).sum();
        // An independent simulation on cells a fifth the size, of the raw box.
        let mut fine = swarf::sim::DexelStock::new(&fast.stock, 0.05, 1);
        let mut fine_air = 0.0f64;
        let mut fine_worst = 0.0f64;
        for m in &fast.moves {
            let vol = m.cut(&mut fine, 0.001);
            if m.air {
                fine_air += vol;
                fine_worst = fine_worst.max(vol);
            }
        }
        eprintln!(
            "{name}: air {} moves, {air_length:.1} mm; removed {air_removed} (cell 0.25), {fine_air} (cell 0.05, worst {fine_worst}); cycle {:.1} s vs {:.1} s",
            air.len(),
            fast.cycle.seconds,
            slow.cycle.seconds
        );
        assert!(air.iter().all(|m| matches!(m.mv, Move::Line { feed, .. } | Move::Arc { feed, .. } if feed == rapid)), "{name}");
        assert!(air_length > if keep { 150.0 } else { 400.0 }, "{name}: {air_length} mm at the air feed");
        assert!(air_removed <= 1e-6 && fine_air <= 1e-6, "{name}: the air moves removed {air_removed} mm³ ({fine_air} on finer cells)");
        assert!(fast.cycle.seconds < slow.cycle.seconds - air_length / 1000.0 * 60.0 * 0.5, "{name}: {} s against {} s", fast.cycle.seconds, slow.cycle.seconds);
        // The same way: the path without the air feed passes the same points in the same
        // order, and is as long.
        let length = |o: &job::JobOutput| o.moves.iter().map(|m| m.mv.length(m.from)).sum::<f64>();
        assert!((length(&fast) - length(&slow)).abs() < 1e-6 * length(&slow), "{name}: {} against {}", length(&fast), length(&slow));
        let mut ends = fast.moves.iter().map(|m| m.mv.to());
        assert!(slow.moves.iter().all(|m| ends.any(|p| p.distance(m.mv.to()) < 1e-9)), "{name}: the air feed changed the path");
        assert!(slow.moves.iter().all(|m| !m.air));
    }
}

/// Rest roughing: a φ20, then a φ3 with 9 mm flutes, region by region on ocl_mount_rush. The
/// φ3 never works a level beside material a level above it left standing (the region of the
/// level just above that holds a region need not be the only one within its reach): its body
/// stays out of the material (this program buried it 12 times when a region was cut before a
/// higher one beside it).
#[test]
fn rest_roughing_never_works_a_level_beside_material_left_above_it() {
    let Some(dir) = common::shared_data("meshes") else { return };
    let bytes = std::fs::read(dir.join("ocl_mount_rush.stl")).unwrap();
    let part = swarf::mesh::import::read_mesh_auto(&bytes, Some("ocl_mount_rush.stl"), &swarf::geom::tolerance::Tolerances::default()).unwrap();
    let tool = |number: u32, d: f64| Tool { number, cutter: Cutter { flute_length: 3.0 * d, ..Cutter::flat(d) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() };
    let stage = |tool: u32, stepdown: f64| {
        Operation::RoughZlevel(RoughZlevel {
            tool,
            roughing: Roughing { allowance: 0.5, leave_stock: 0.5, grid: 0.5, ..Roughing::default() },
            steps: Steps { stepdown, stepover_fraction: 0.5 },
            ..RoughZlevel::default()
        })
    };
    let job = Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 1.0, ..Default::default() },
        tools: vec![tool(1, 20.0), tool(4, 3.0)],
        operations: vec![stage(1, 5.0), stage(4, 0.75)],
        simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, part, &mut Progress::none()).unwrap();
    clean(&out);
}

/// ocl_wheel_in_box roughed as `cargo bench --bench octree` roughs it (the octree's four flat
/// ends, and z-level φ20 then φ3): the φ3's body stays out of the material in the crevices the
/// φ20 left. Two causes buried it: a region's corner put back past where its keep mask ended
/// it (10.5 mm past the flutes), and a node a lower level keeps for its floor, touching by a
/// sliver a crevice's material that no level above came that near (1.5 mm past); the octree's
/// program buried it 6 times.
#[test]
fn rest_roughing_keeps_the_tools_body_out_of_the_crevices_a_bigger_tool_left() {
    let Some(dir) = common::shared_data("meshes") else { return };
    let bytes = std::fs::read(dir.join("ocl_wheel_in_box.stl")).unwrap();
    let part = swarf::mesh::import::read_mesh_auto(&bytes, Some("ocl_wheel_in_box.stl"), &swarf::geom::tolerance::Tolerances::default()).unwrap();
    for (label, job) in support::job::octree_jobs(0.25, 0.5, 0.5, 0.25) {
        if label.contains("alone") {
            continue;
        }
        let out = job::run(&job, part.clone(), &mut Progress::none()).unwrap_or_else(|e| panic!("{label}: {e}"));
        let v = out.verification.as_ref().expect("verified");
        assert_eq!(v.report.body_collision_count, 0, "{label}: {}", v.report.describe());
        clean(&out);
    }
}

/// Issue 38's guards: settings off by orders of magnitude are refused before any work starts,
/// naming the setting, in well under a second; a part the stock does not hold is refused.
#[test]
fn absurd_settings_and_a_part_outside_the_stock_are_refused_at_once() {
    use swarf::job::{self, Job, Operation};
    use swarf::mesh::sample::demo_part;
    use swarf::progress::Progress;
    let refused = |job: &Job| common::cpu_timed(|| job::run(job, demo_part(), &mut Progress::none()).unwrap_err().to_string());
    // A step-down of 0.001 mm: tens of thousands of levels.
    let mut job = Job::demo();
    if let Operation::RoughZlevel(o) = &mut job.operations[0] {
        o.steps.stepdown = 0.001;
    }
    let (e, s) = refused(&job);
    assert!(e.contains("a step-down of 0.001 mm makes") && e.contains("levels") && e.starts_with("rough"), "{e}");
    assert!(s < 1.0, "{s} s");
    // Zigzag, waterline, raster and octree alike.
    let mut job = Job::demo();
    for op in &mut job.operations {
        match op {
            Operation::FinishWaterline(o) => (o.stepdown, o.scallop) = (0.0005, None),
            Operation::FinishRaster(o) => o.stepover = 0.001,
            _ => {}
        }
    }
    let (e, _) = refused(&job);
    assert!(e.contains("a step-over of 0.001 mm makes") && e.contains("passes"), "{e}");
    job.operations.retain(|o| matches!(o, Operation::FinishWaterline(_)));
    let (e, _) = refused(&job);
    assert!(e.contains("a step-down of 0.0005 mm makes") && e.contains("levels"), "{e}");
    let mut job = Job::demo();
    job.operations = vec![Operation::RoughOctree(swarf::operations::RoughOctree { delta: 0.0001, ..Default::default() })];
    let (e, s) = refused(&job);
    assert!(e.contains("delta is at least 0.01") && e.contains("got 0.0001"), "{e}");
    assert!(s < 1.0, "{s} s");
    // A stock box that does not hold the part: below it, above it, beside it.
    for (z0, z1, x0, what) in [(100.0, 200.0, -200.0, "below the stock's bottom"), (-200.0, -100.0, -200.0, "above the stock's top"), (-200.0, 200.0, 500.0, "beside the stock")] {
        let mut job = Job::demo();
        job.stock.size_box = Some(swarf::geom::Aabb { min: swarf::geom::DVec3::new(x0, -200.0, z0), max: swarf::geom::DVec3::new(x0 + 400.0, 200.0, z1) });
        let (e, _) = refused(&job);
        assert!(e.contains(what), "{what}: {e}");
    }
}

/// A region's rings leave nothing standing between them: where a level's last ring would only
/// take a sliver between the two halves of the ring before it, the sliver is cut (it was left
/// once: a 0.3 mm wall the full step high in the middle of the rocker arm's first level, that
/// the next traverse over the level's region, taken as cleared, ran through). A channel across
/// the stock between two walls, cut from the air inwards (the outermost ring first), at widths
/// around that case, each roughed with a φ12 flat end at 3 mm steps and a step-over of 0.45:
/// the channel's floor is bare all across, and the program clean.
#[test]
fn a_regions_rings_leave_no_sliver_standing_between_them() {
    let (floor, top) = (14.0, 20.0);
    for k in 0..15 {
        let half = 17.45 + 0.05 * k as f64;
        let part = swarf::mesh::sample::height_field_solid(DVec2::new(-40.0, -30.0), DVec2::new(40.0, 30.0), 320, 240, 0.0, |_, y| if y.abs() < half { floor } else { top });
        let job = Job {
            part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
            stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
            tools: vec![flat(1, 12.0)],
            operations: vec![Operation::RoughZlevel(RoughZlevel {
                steps: Steps { stepdown: 3.0, stepover_fraction: 0.45 },
                roughing: Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() },
                ..RoughZlevel::default()
            })],
            simulation: Simulation { verify: true, cell: Some(0.1), ..Default::default() },
            ..Job::default()
        };
        let out = job::run(&job, part, &mut Progress::none()).unwrap();
        clean(&out);
        let stock = &out.verification.as_ref().unwrap().stock;
        let grid = stock.grid();
        let mut highest = f64::NEG_INFINITY;
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                if grid.node(i, j).y.abs() < half - 6.5 {
                    highest = highest.max(stock.top(i, j));
                }
            }
        }
        assert!(highest < floor + 0.01, "a channel {:.2} mm wide: stock stands {:.3} mm over its floor", 2.0 * half, highest - floor);
    }
}

/// Issue 38's terrain: z-level roughing (φ6 flat, step-down 2, step-over 0.4, the stock the
/// part's box) links its regions at depth: a traverse goes just over what still stands on its
/// way (the in-process stock as the operation's own pieces left it), not over the stock's top,
/// and the rapids come to under a fifth of the feed. A generated range of peaks, and the shared
/// ocl_mount_rush (3.57 m of rapids for 12.86 m of feed before, 0.28).
#[test]
fn a_terrains_regions_are_linked_at_depth() {
    let peaks = [(-25.0, 10.0, 4.0, 15.0), (-10.0, -10.0, 5.0, 14.0), (5.0, 10.0, 5.0, 13.0), (20.0, -10.0, 5.0, 12.0), (28.0, 12.0, 4.0, 10.0)];
    let terrain = swarf::mesh::sample::height_field_solid(DVec2::new(-35.0, -20.0), DVec2::new(35.0, 20.0), 140, 80, 0.0, |x, y| {
        1.0 + peaks.iter().map(|&(px, py, s, h)| h * (-((x - px).powi(2) + (y - py).powi(2)) / (s * s)).exp()).sum::<f64>()
    });
    let mut parts = vec![("generated peaks", terrain)];
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes");
    if let Ok(bytes) = std::fs::read(dir.join("ocl_mount_rush.stl")) {
        parts.push(("ocl_mount_rush", swarf::mesh::import::read_mesh_auto(&bytes, Some("ocl_mount_rush.stl"), &swarf::geom::tolerance::Tolerances::default()).unwrap()));
    }
    for (name, part) in parts {
        let job = Job { simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() }, ..support::job::peer_rough_job() };
        let out = job::run(&job, part, &mut Progress::none()).unwrap();
        clean(&out);
        // Replayed on a stock of the simulation's cells: where the tool rises to cross over,
        // it rises no higher than the gap over what stands on its way then (judged with a
        // cutter 0.05 mm wider, so that a cell at the rim of a cut counts as standing), give or
        // take the planner's own margin: it judges the way on cells of an eighth of the
        // cutter's radius, each as high as the highest simulation cell it holds (half a
        // millimetre here), and the part by a bound from its z-map's nodes where that stands
        // no more than the gap higher (before, traverses rose up to 16 mm higher here).
        const SLACK: f64 = 1.5;
        const STEPDOWN: f64 = 2.0;
        let mut stock = swarf::sim::DexelStock::new(&out.stock, 0.25, 1);
        let mut high = Vec::new();
        for (k, m) in out.moves.iter().enumerate() {
            let next = out.moves.get(k + 1).map(|n| n.mv.to());
            if let (true, Some(to)) = (m.mv.is_rapid(), next) {
                let (lift, over) = (m.mv.to(), to);
                if lift.truncate() == m.from.truncate() && lift.z > m.from.z && over.z == lift.z && over.truncate() != lift.truncate() && k > 0 {
                    let wider = swarf::cutter::Profile::new(m.cutter.radius() + 0.05, m.cutter.profile().corner);
                    let stands = stock.touch_along(lift.truncate(), over.truncate(), &wider, true);
                    // Nor lower than the gap over the level above the cut it comes down to.
                    let land = out.moves[k..].iter().find(|n| !n.mv.is_rapid()).map_or(f64::NEG_INFINITY, |n| n.mv.to().z + STEPDOWN);
                    if lift.z > stands.max(land) + job.stock.retract + SLACK {
                        high.push((lift, over, stands));
                    }
                }
            }
            for sweep in swarf::sim::sweep::Sweep::of_move(m.cutter.profile(), m.from, &m.mv, 0.002) {
                swarf::sim::StockModel::apply(&mut stock, &sweep);
            }
        }
        let worst = high.iter().map(|h| h.0.z - h.2).fold(0.0, f64::max);
        assert!(high.is_empty(), "{name}: {} traverses higher than the gap over what stands on their way, up to {worst:.3} mm, as {:?}", high.len(), high.first());
        let (rapid, feed) = (out.stats.rapid_length, out.stats.feed_length);
        eprintln!("{name}: {rapid:.0} mm of rapids for {feed:.0} mm of feed ({:.3})", rapid / feed);
        assert!(rapid < 0.2 * feed, "{name}: {rapid:.0} mm of rapids for {feed:.0} mm of feed");
        common::rs274(&out.gcode, &job.tools);
    }
}

/// The shared parts roughed with issue 12's settings (φ6 flat, step-down 2, step-over 0.4, no
/// allowance, the part's box for stock) verify clean. pycam_textbox's pocket region at Z−2 once
/// lost its rings past the second (its offset by 4.8 mm came out empty): the level left the
/// pocket's middle standing, the flat at −2.05 under it cut it, and six traverses at Z−1 went
/// through what stood.
#[test]
fn the_shared_parts_roughed_by_levels_verify_clean() {
    let Some(dir) = common::shared_data("meshes") else { return };
    for name in ["pycam_textbox.stl", "kiri_pocket-test.stl"] {
        let bytes = std::fs::read(dir.join(name)).unwrap();
        let part = swarf::mesh::import::read_mesh_auto(&bytes, Some(name), &swarf::geom::tolerance::Tolerances::default()).unwrap();
        let job = Job {
            part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
            stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, margin_bottom: 0.0, ..Default::default() },
            tools: vec![Tool { number: 1, cutter: Cutter { flute_length: 50.0, ..Cutter::flat(6.0) }, ..Tool::default() }],
            operations: vec![Operation::RoughZlevel(RoughZlevel {
                roughing: Roughing { allowance: 0.0, leave_stock: 0.0, grid: 0.5, ..Roughing::default() },
                steps: Steps { stepdown: 2.0, stepover_fraction: 0.4 },
                ..RoughZlevel::default()
            })],
            ..Job::default()
        };
        let out = job::run(&job, part, &mut Progress::none()).unwrap();
        clean(&out);
    }
}

/// Issue 62: a roughing after a larger tool's is named rest roughing in its report, with
/// what it took of the leftovers; the first is not, nor is a second roughing with the same or
/// a larger tool.
#[test]
fn a_roughing_after_a_larger_tool_is_reported_as_rest_roughing_with_what_it_took() {
    let op = |name: &str, tool: u32| Operation::RoughZlevel(RoughZlevel { name: name.into(), tool, steps: Steps { stepdown: 3.0, ..Steps::default() }, ..RoughZlevel::default() });
    let job = Job { tools: vec![flat(1, 10.0), flat(2, 4.0)], operations: vec![op("big", 1), op("small", 2)], ..Job::default() };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    clean(&out);
    let (big, small) = (&out.operations[0], &out.operations[1]);
    assert!(big.rest_after.is_empty() && small.rest_after == vec![1], "{:?} {:?}", big.rest_after, small.rest_after);
    let (a, b) = (big.removed.unwrap(), small.removed.unwrap());
    assert!(b > 0.0 && b < 0.2 * a, "the rest pass took {b:.0} mm³ after {a:.0}");
    assert!(small.describe().contains("rest roughing after T1") && !big.describe().contains("rest roughing"), "{}", small.describe());
    assert!(!out.warnings.iter().any(|w| w.message.starts_with("rest roughing is off")), "with rest on nothing is said of it");
    // The other way round: the small tool first, the big one is no rest roughing.
    let swapped = Job { operations: vec![op("small", 2), op("big", 1)], simulation: Simulation { verify: false, ..Simulation::default() }, ..job.clone() };
    let out = job::run(&swapped, demo_part(), &mut Progress::none()).unwrap();
    assert!(out.operations.iter().all(|o| o.rest_after.is_empty()));
    // Rest roughing off: the small tool plans against the stock as it came, so it cuts the
    // air the big one cleared again (a longer path, said), takes what the rest pass took (a
    // little more: it skips no scrap thinner than the rest pass's reach) and is no rest
    // roughing in its report.
    let mut off = job.clone();
    let Operation::RoughZlevel(o) = &mut off.operations[1] else { unreachable!() };
    o.roughing.rest = false;
    let whole = job::run(&off, demo_part(), &mut Progress::none()).unwrap();
    clean(&whole);
    let again = &whole.operations[1];
    assert!(again.rest_after.is_empty() && !again.describe().contains("rest roughing"), "{}", again.describe());
    assert!(again.feed_length > 1.5 * small.feed_length, "rest off fed {:.0} mm, rest on {:.0} mm", again.feed_length, small.feed_length);
    let (c, d) = (again.removed.unwrap(), small.removed.unwrap());
    assert!(c >= 0.99 * d && c < 1.1 * d, "rest off took {c:.0} mm³, rest on {d:.0} mm³");
    assert!(whole.warnings.iter().any(|w| w.operation.as_deref() == Some("small") && w.message.starts_with("rest roughing is off")), "{:?}", whole.warnings);
    // The first operation has nothing before it: rest off changes nothing there.
    let mut first_off = job.clone();
    let Operation::RoughZlevel(o) = &mut first_off.operations[0] else { unreachable!() };
    o.roughing.rest = false;
    let first = job::run(&first_off, demo_part(), &mut Progress::none()).unwrap();
    assert_eq!(first.operations[0].feed_length, big.feed_length);
    assert!(!first.warnings.iter().any(|w| w.message.starts_with("rest roughing is off")));
}

/// Issue 92: a roughing stops at its bottom height. On the demo part (its top at Z0), each
/// level roughing kind given a bottom 12 mm below the part's top (`bottomFrom: partTop`) cuts
/// nothing below it, over the part or beside it: the stock keeps its material under that height
/// all round (as a first side stops at its parting line, the rest still joined to what the vise
/// grips); the same height from the zero cuts the same; a bottom above the stock's top is
/// refused naming the field.
#[test]
fn a_roughing_stops_at_its_bottom_height() {
    use swarf::operations::{HeightFrom, Heights, RoughAdaptive, RoughZigzag};
    let part_box = {
        let mut p = demo_part();
        Job::demo().place(&mut p);
        p.bounds()
    };
    assert!(part_box.max.z.abs() < 1e-9 && part_box.min.z < -20.0, "{part_box:?}");
    let with = |bottom: f64, from: HeightFrom| Roughing { heights: Heights { bottom: Some(bottom), bottom_from: from, ..Heights::default() }, ..Roughing::default() };
    let kinds = |r: Roughing| {
        [
            Operation::RoughZlevel(RoughZlevel { roughing: r, ..RoughZlevel::default() }),
            Operation::RoughZigzag(RoughZigzag { roughing: r, ..RoughZigzag::default() }),
            Operation::RoughAdaptive(RoughAdaptive { roughing: r, ..RoughAdaptive::default() }),
        ]
    };
    let mut programs = Vec::new();
    for r in [with(-12.0, HeightFrom::PartTop), with(-12.0, HeightFrom::Zero)] {
        for op in kinds(r) {
            let mut job = Job::demo();
            job.tools = vec![flat(1, 6.0)];
            job.operations = vec![op];
            let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
            clean(&out);
            let lowest = out.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min);
            assert!(lowest >= -12.0 - 1e-6, "{}: cut down to Z{lowest}", out.operations[0].name);
            assert!(lowest < -11.0, "{}: stopped at Z{lowest}, above its bottom", out.operations[0].name);
            // Every column of the stock still holds material up to Z-12 at least.
            let stock = &out.verification.as_ref().unwrap().stock;
            let g = stock.grid();
            let least = (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).map(|(i, j)| stock.top(i, j)).fold(f64::INFINITY, f64::min);
            assert!(least >= -12.0 - 1e-6, "{}: a column cut down to Z{least}", out.operations[0].name);
            programs.push(out.gcode.lines().filter(|l| !l.starts_with('(') && !l.starts_with(';')).collect::<Vec<_>>().join("\n"));
        }
    }
    // The part's top is Z0: the same height from either is the same program.
    assert_eq!(programs[..3], programs[3..]);
    let mut job = Job::demo();
    job.tools = vec![flat(1, 6.0)];
    job.operations = vec![kinds(with(2.0, HeightFrom::StockTop))[0].clone()];
    let e = job::run(&job, demo_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("bottom height") && e.contains("nothing to cut"), "{e}");
}
