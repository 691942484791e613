//! Issue 92's heights on every 3D operation: a top and a bottom height each operation cuts
//! between, each from the stock, the part, the zero or the parting line, and its own clearance
//! and retract in place of the job's.

mod common;

use glam::DVec3;
use swarf::job::{self, Job, Operation};
use swarf::mesh::sample::demo_part;
use swarf::operations::{FinishRaster, FinishScallop, FinishSteepShallow, HeightFrom, Heights, RoughZlevel, Roughing};
use swarf::progress::Progress;

/// Runs are cut exactly where they cross the heights: a run falling from Z0 to Z-20 over
/// X0..X20 kept between Z-15 and Z-5 starts at X5 Z-5 and ends at X15 Z-15; one that dips
/// below the bottom and comes back is two runs; an open window keeps every run as it was.
#[test]
fn runs_are_cut_where_they_cross_the_heights() {
    let fall = vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(20.0, 0.0, -20.0)];
    let kept = Heights::trim(vec![fall.clone()], Some(-15.0), Some(-5.0));
    assert_eq!(kept.len(), 1);
    assert!(kept[0][0].distance(DVec3::new(5.0, 0.0, -5.0)) < 1e-12, "{:?}", kept[0]);
    assert!(kept[0][1].distance(DVec3::new(15.0, 0.0, -15.0)) < 1e-12, "{:?}", kept[0]);
    let dip = vec![DVec3::new(0.0, 0.0, -10.0), DVec3::new(10.0, 0.0, -20.0), DVec3::new(20.0, 0.0, -10.0)];
    let kept = Heights::trim(vec![dip], Some(-15.0), None);
    assert_eq!(kept.len(), 2, "{kept:?}");
    assert!(kept[0].last().unwrap().distance(DVec3::new(5.0, 0.0, -15.0)) < 1e-12);
    assert!(kept[1][0].distance(DVec3::new(15.0, 0.0, -15.0)) < 1e-12);
    assert_eq!(Heights::trim(vec![fall.clone()], None, None), vec![fall.clone()]);
    // Wholly outside: nothing.
    assert!(Heights::trim(vec![fall], Some(5.0), None).is_empty());
}

/// The cutter of the demo job's tool `number`.
fn demo_cutter(number: u32) -> swarf::cutter::Cutter {
    Job::demo().tools.into_iter().find(|t| t.number == number).unwrap().cutter
}

/// The feed moves of a program's last tool (its finishing), each from where it starts to where
/// it ends.
fn feeds(out: &job::JobOutput) -> Vec<(DVec3, DVec3)> {
    let last = out.moves.last().map(|m| m.tool);
    out.moves.iter().filter(|m| !m.mv.is_rapid() && Some(m.tool) == last).map(|m| (m.from, m.mv.to())).collect()
}

/// Each 3D finishing kind given a top 4 mm and a bottom 12 mm under the part's top (the demo
/// part's top is Z0) cuts between them: no feed goes below the bottom, no pass follows the
/// part's surface (by the exact drop) above the top (only the entries' and links' feeds stand
/// there, above the surface), and it cuts near both; the program is clean. Without the heights
/// the same finishing follows the surface above the top.
#[test]
fn a_finishing_cuts_between_its_top_and_bottom_heights() {
    let window = Heights { top: Some(-4.0), top_from: HeightFrom::PartTop, bottom: Some(-12.0), bottom_from: HeightFrom::PartTop, ..Heights::default() };
    let kinds = |h: Heights, ball: u32| {
        [
            Operation::FinishRaster(FinishRaster { tool: ball, heights: h, ..FinishRaster::default() }),
            Operation::FinishScallop(FinishScallop { tool: ball, heights: h, ..FinishScallop::default() }),
            Operation::FinishSteepShallow(FinishSteepShallow { tool: ball, heights: h, ..FinishSteepShallow::default() }),
        ]
    };
    for (k, (with, without)) in kinds(window, 2).into_iter().zip(kinds(Heights::default(), 2)).enumerate() {
        // After the demo's roughing, as a finishing is cut.
        let mut job = Job::demo();
        job.operations.truncate(1);
        job.operations.push(with);
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        common::clean(&out);
        let moves = feeds(&out);
        let name = &out.operations[1].name;
        let lowest = moves.iter().map(|(a, b)| a.z.min(b.z)).fold(f64::INFINITY, f64::min);
        assert!(lowest >= -12.0 - 1e-6, "{name}: down to Z{lowest}");
        // A pass follows the part's surface; the feeds of entries and links stand above it.
        let following = |out: &job::JobOutput, moves: &[(DVec3, DVec3)]| {
            let tool = demo_cutter(2);
            let judge = common::Judge { part: &out.part, profile: tool.profile(), floor: out.stock.min.z };
            moves
                .iter()
                .filter(|(a, b)| a.z.min(b.z) > -4.0 + 1e-3)
                .filter(|(a, b)| {
                    let m = a.lerp(*b, 0.5);
                    (m.z - judge.exact(m.truncate())).abs() < 0.01
                })
                .count()
        };
        assert_eq!(following(&out, &moves), 0, "{name}: passes above its top");
        assert!(moves.iter().any(|(a, b)| a.z.min(b.z) < -11.0), "{name}: nothing cut near its bottom");
        assert!(moves.iter().any(|(a, b)| a.z.max(b.z) > -5.0 && a.z.max(b.z) <= -4.0 + 1e-6), "{name}: nothing cut near its top");
        if k == 0 {
            let mut job = Job::demo();
            job.operations.truncate(1);
            job.operations.push(without);
            let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
            assert!(following(&out, &feeds(&out)) > 100, "{name} without heights: no passes above Z-4");
        }
    }
}

/// A z-level roughing given a top 5 mm under the stock's top starts its levels a step-down
/// below it (no level higher), and its bottom 10 mm above the stock's bottom ends them there.
#[test]
fn a_roughings_levels_lie_between_its_top_and_bottom_heights() {
    let mut job = Job::demo();
    let heights = Heights { top: Some(-5.0), top_from: HeightFrom::StockTop, bottom: Some(10.0), bottom_from: HeightFrom::StockBottom, ..Heights::default() };
    let op = RoughZlevel { roughing: Roughing { heights, ..Roughing::default() }, ..RoughZlevel::default() };
    let stepdown = op.steps.stepdown;
    job.operations = vec![Operation::RoughZlevel(op)];
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    common::clean(&out);
    let (top, bottom) = (out.stock.max.z - 5.0, out.stock.min.z + 10.0);
    // A level is a feed at one height.
    let mut levels: Vec<f64> = feeds(&out).iter().filter(|(a, b)| (a.z - b.z).abs() < 1e-9 && a.truncate().distance(b.truncate()) > 1.0).map(|(a, _)| a.z).collect();
    levels.sort_by(f64::total_cmp);
    levels.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    let (low, high) = (levels[0], *levels.last().unwrap());
    assert!((high - (top - stepdown)).abs() < 1e-6, "the first level at Z{high}, not a step-down under the top Z{top}");
    assert!(low >= bottom - 1e-6 && low < bottom + stepdown, "the last level at Z{low}, the bottom Z{bottom}");
}

/// An operation's own clearance is where its rapids cross and where the program starts and
/// ends (above the job's); its own retract gap is where its descents stop; a clearance at or
/// below the stock's top is refused naming the field.
#[test]
fn an_operations_clearance_and_retract_are_its_own() {
    let mut job = Job::demo();
    let heights = Heights { clearance: Some(25.0), clearance_from: HeightFrom::StockTop, retract: Some(3.0), ..Heights::default() };
    job.operations = vec![Operation::FinishRaster(FinishRaster { tool: 2, heights, ..FinishRaster::default() })];
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    common::clean(&out);
    let clearance = out.stock.max.z + 25.0;
    assert!((out.clearance_z - clearance).abs() < 1e-9, "the program's clearance Z{}", out.clearance_z);
    let rapids: Vec<f64> = out.moves.iter().filter(|m| m.mv.is_rapid()).map(|m| m.mv.to().z).collect();
    let highest = rapids.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!((highest - clearance).abs() < 1e-9, "rapids up to Z{highest}");
    assert!(out.gcode.contains(&format!("Z{:.3}", clearance)) || out.gcode.contains(&format!("Z{}", clearance)), "no move to the clearance in the program");
    // The job's own clearance (5 above the stock) is not used: rapids stand at the clearance or
    // at the retract gap above the material.
    assert!(!rapids.iter().any(|z| (z - (out.stock.max.z + job.stock.clearance)).abs() < 1e-9), "a rapid at the job's clearance");
    // Rapids come down to the retract gap over the stock's top (nothing is cut before it):
    // 3 mm with its own, the job's 1 mm without.
    let mut plain = Job::demo();
    plain.operations = vec![Operation::FinishRaster(FinishRaster { tool: 2, ..FinishRaster::default() })];
    let base = job::run(&plain, demo_part(), &mut Progress::none()).unwrap();
    let lowest_rapid = |o: &job::JobOutput| o.moves.iter().filter(|m| m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min) - o.stock.max.z;
    assert!((lowest_rapid(&out) - 3.0).abs() < 1e-6, "rapids down to {} over the stock with a 3 mm gap", lowest_rapid(&out));
    assert!((lowest_rapid(&base) - job.stock.retract).abs() < 1e-6, "rapids down to {} over the stock with the job's gap", lowest_rapid(&base));
    // A clearance in the stock is refused, naming it.
    let mut low = Job::demo();
    let heights = Heights { clearance: Some(-1.0), clearance_from: HeightFrom::StockTop, ..Heights::default() };
    low.operations = vec![Operation::FinishRaster(FinishRaster { tool: 2, heights, ..FinishRaster::default() })];
    let e = job::run(&low, demo_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("clearance") && e.contains("not above the stock's top"), "{e}");
}

/// A bottom above the top, or a top under the stock, is refused, each naming the field.
#[test]
fn heights_that_leave_nothing_are_refused() {
    for (heights, word) in [
        (Heights { top: Some(-10.0), top_from: HeightFrom::PartTop, bottom: Some(-5.0), bottom_from: HeightFrom::PartTop, ..Heights::default() }, "'Bottom height' or a higher 'Top height'"),
        (Heights { top: Some(-1.0), top_from: HeightFrom::StockBottom, ..Heights::default() }, "'Top height'"),
    ] {
        let mut job = Job::demo();
        job.operations = vec![Operation::FinishRaster(FinishRaster { tool: 2, heights, ..FinishRaster::default() })];
        let e = job::run(&job, demo_part(), &mut Progress::none()).unwrap_err().to_string();
        assert!(e.contains(word) && e.contains("nothing to cut"), "{e}");
    }
    let bad = serde_json::json!({"kind": "finishRaster", "top": "high"});
    let e = Operation::from_json(&bad).unwrap_err();
    assert!(e.starts_with("top"), "{e}");
}

/// A height from a point picked on the part is measured from the point's Z: a roughing's
/// bottom 9 mm under a point at Z-3 is the same program as one at Z-12 from the zero; a height
/// from a point with none picked is refused naming its field.
#[test]
fn a_height_from_a_picked_point_is_from_its_z() {
    let program = |heights: Heights| {
        let mut job = Job::demo();
        job.operations = vec![Operation::RoughZlevel(RoughZlevel { roughing: Roughing { heights, ..Roughing::default() }, ..RoughZlevel::default() })];
        job::run(&job, demo_part(), &mut Progress::none()).map(|out| out.gcode.lines().filter(|l| !l.starts_with('(')).collect::<Vec<_>>().join("\n"))
    };
    let picked = program(Heights { bottom: Some(-9.0), bottom_from: HeightFrom::Point, point: Some([10.0, -4.0, -3.0]), ..Heights::default() }).unwrap();
    let zero = program(Heights { bottom: Some(-12.0), bottom_from: HeightFrom::Zero, ..Heights::default() }).unwrap();
    assert!(picked == zero, "the programs differ");
    let e = program(Heights { bottom: Some(-9.0), bottom_from: HeightFrom::Point, ..Heights::default() }).unwrap_err().to_string();
    assert!(e.contains("bottomFrom") && e.contains("none is picked"), "{e}");
}

/// A 2D cut and a hole operation have their own clearance too (their depths are their top and
/// bottom): a drawing's profile with a clearance 20 mm over the stock's top and a 2.5 mm
/// retract crosses at it and comes down to the gap; the two-sided example's drilling with one
/// 30 mm over its stock returns to it (its initial height); a clearance inside the stock is
/// refused naming the field, as a 3D operation's is.
#[test]
fn a_2d_and_a_hole_operations_clearance_is_their_own() {
    use swarf::operations::{Moves, Profile2d};
    let drawing = swarf::drawing::import::read_drawing(swarf::drawing::sample::plate_dxf().as_bytes(), Some("plate.dxf"), &Default::default()).unwrap();
    let moves = Moves { clearance: Some(20.0), retract: Some(2.5), ..Moves::default() };
    let mut job = Job::default_for_drawing();
    let Operation::Profile2d(p) = &job.operations[0] else { unreachable!() };
    job.operations = vec![Operation::Profile2d(Profile2d { moves, ..p.clone() })];
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap();
    common::clean(&out);
    let top = out.stock.max.z;
    let rapids: Vec<f64> = out.moves.iter().filter(|m| m.mv.is_rapid()).map(|m| m.mv.to().z).collect();
    let highest = rapids.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!((highest - (top + 20.0)).abs() < 1e-9, "rapids up to Z{highest}, the stock's top Z{top}");
    assert!(!rapids.iter().any(|z| (z - (top + job.stock.clearance)).abs() < 1e-9), "a rapid at the job's clearance");
    let lowest = rapids.iter().copied().fold(f64::INFINITY, f64::min) - top;
    assert!((lowest - 2.5).abs() < 1e-6, "rapids down to {lowest} over the stock");
    // The hole operation: the two-sided example's first setup, its drilling's own clearance.
    let mut two = Job::two_sided();
    let mut ops = two.setups[0].operations.clone();
    for op in &mut ops {
        if let Operation::Drill(d) = op {
            d.moves = swarf::operations::Clearance { clearance: Some(30.0), ..Default::default() };
        }
    }
    two.operations = ops;
    two.setups.clear();
    let out = job::run(&two, swarf::mesh::sample::two_sided_part(), &mut Progress::none()).unwrap();
    let initial = out.stock.max.z + 30.0;
    let drilled = out.gcode.lines().skip_while(|l| !l.starts_with("G98 G8")).take(1).count();
    assert_eq!(drilled, 1, "no canned cycle");
    assert!(out.gcode.contains(&format!("Z{initial:.3}")) || out.gcode.contains(&format!("Z{}", initial)), "no move to the drilling's clearance Z{initial}");
    // Refused inside the stock, naming the field.
    job.operations = vec![Operation::Profile2d(Profile2d { moves: Moves { clearance: Some(-1.0), ..Moves::default() }, ..p_default(&job) })];
    let e = job::run(&job, drawing, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("clearance") && e.contains("not above the stock's top"), "{e}");
    // A clearance from a point with none picked is named.
    let mut job = Job::demo();
    job.operations = vec![Operation::from_json(&serde_json::json!({"kind": "drill", "clearance": 5, "clearanceFrom": "point"})).unwrap()];
    let e = job.problems().into_iter().map(|p| format!("{}: {}", p.path, p.message)).collect::<Vec<_>>().join("; ");
    assert!(e.contains("clearanceFrom") && e.contains("none is picked"), "{e}");
}

fn p_default(job: &Job) -> swarf::operations::Profile2d {
    let Operation::Profile2d(p) = &job.operations[0] else { unreachable!() };
    swarf::operations::Profile2d { moves: Default::default(), ..p.clone() }
}

/// Issue 94: an allowance far over the stock lifts every pass of a 3D finishing into the air
/// (1000 mm made a 1:28:37 program up to Z1000): each kind says it has nothing to cut, as a
/// waterline does, and the job makes no program of air.
#[test]
fn a_finishing_lifted_over_the_stock_has_nothing_to_cut() {
    use swarf::operations::FinishPencil;
    let kinds = [
        Operation::FinishRaster(FinishRaster { tool: 2, allowance: 1000.0, ..FinishRaster::default() }),
        Operation::FinishScallop(FinishScallop { tool: 2, allowance: 1000.0, ..FinishScallop::default() }),
        Operation::FinishSteepShallow(FinishSteepShallow { tool: 2, allowance: 1000.0, ..FinishSteepShallow::default() }),
        Operation::FinishPencil(FinishPencil { tool: 2, allowance: 1000.0, ..FinishPencil::default() }),
    ];
    for op in kinds {
        let mut job = Job::demo();
        let name = op.name().to_owned();
        if matches!(op, Operation::FinishPencil(_)) {
            // The sample's inside corners are tighter than a φ1 ball, not a φ6.
            job.tools[1].cutter = swarf::cutter::Cutter { flute_length: 10.0, ..swarf::cutter::Cutter::ball(1.0) };
        }
        job.operations = vec![op];
        let e = job::run(&job, demo_part(), &mut Progress::none()).unwrap_err().to_string();
        assert!(e.contains("nothing to cut") && e.contains("lies over the stock's top"), "{name}: {e}");
    }
}
