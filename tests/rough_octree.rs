//! Octree multi-tool roughing (seed 000): on parts whose answer is known, the tools chosen follow
//! the paper's rules (the largest first, later ones matched to halved octants with 0.5 <= γ <=
//! 0.95, the stop test before the profiling), every program is simulated clean (no gouge, no
//! rapid through stock, no tool body in material, no straight plunge into material), and after
//! the last tool the material left where that tool reaches is the allowance.

mod common;

use common::clean;
use swarf::cutter::Cutter;
use swarf::error::Error;
use swarf::geom::DVec2;
use swarf::job::{self, Job, JobOutput, Operation, Simulation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::sample::{height_field_solid, octree_mould};
use swarf::mesh::Mesh;
use swarf::operations::Roughing;
use swarf::operations::{RoughOctree, StageRole};
use swarf::progress::Progress;

fn flat(number: u32, d: f64) -> Tool {
    Tool { number, cutter: Cutter { flute_length: 3.0 * d, ..Cutter::flat(d) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() }
}

/// A block over `[-w, w] × [-h, h]`, top at z = 0, bottom at −30, sampled every 0.5 mm, with
/// the floors `floor(x, y)` (None: the top).
fn block(w: f64, h: f64, floor: impl Fn(f64, f64) -> Option<f64>) -> Mesh {
    let n = |e: f64| (2.0 * e / 0.5).round() as usize;
    height_field_solid(DVec2::new(-w, -h), DVec2::new(w, h), n(w), n(h), -30.0, move |x, y| floor(x, y).unwrap_or(0.0))
}

fn within(v: f64, lo: f64, hi: f64) -> bool {
    (lo..=hi).contains(&v)
}

const ALLOWANCE: f64 = 0.5;
const LEAVE: f64 = 0.5;

fn octree_job(tools: Vec<Tool>, op: RoughOctree) -> Job {
    Job {
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 1.0, ..Default::default() },
        tools,
        operations: vec![Operation::RoughOctree(RoughOctree { roughing: Roughing { allowance: ALLOWANCE, leave_stock: LEAVE, grid: 0.5, ..Roughing::default() }, ..op })],
        simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
        ..Job::default()
    }
}

/// The stages as (tool, role).
fn stages(out: &JobOutput) -> Vec<(u32, StageRole)> {
    out.operations[0].stages.as_ref().expect("stages reported").iter().map(|s| (s.tool, s.role)).collect()
}

/// The most material left above the floor allowance at cells whose every point within `reach`
/// lies on a floor (`floor(x, y)` the same all round): where the last tool's centre goes.
fn left_on_floors(out: &JobOutput, reach: f64, floor: impl Fn(f64, f64) -> Option<f64>) -> (f64, usize) {
    let v = out.verification.as_ref().unwrap();
    let g = v.stock.grid();
    let (mut worst, mut n) = (0.0f64, 0);
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            let Some(f) = floor(p.x, p.y) else { continue };
            let all_round = (0..16).all(|k| {
                let a = k as f64 * std::f64::consts::PI / 8.0;
                floor(p.x + reach * a.cos(), p.y + reach * a.sin()) == Some(f)
            });
            if all_round {
                worst = worst.max(v.stock.top(i, j) - f - ALLOWANCE);
                n += 1;
            }
        }
    }
    (worst, n)
}

fn slot_pocket(x: f64, y: f64) -> Option<f64> {
    if within(x, -30.0, 10.0) && within(y, -20.0, 20.0) || within(x, 10.0, 30.0) && within(y, -2.5, 2.5) {
        Some(-10.0)
    } else {
        None
    }
}

#[test]
fn a_box_pocket_with_a_narrow_slot_takes_the_big_tool_for_the_box_and_the_small_one_for_the_slot() {
    let job = octree_job(vec![flat(1, 12.0), flat(2, 3.0)], RoughOctree::default());
    let out = job::run(&job, block(40.0, 30.0, slot_pocket), &mut Progress::none()).unwrap();
    clean(&out);
    // φ12 first (octants of 10.2 mm); halved twice to 2.55 mm, γ = 0.85 for φ3, the smallest,
    // which profiles: the slot, 5 wide, takes a φ3 with its 0.5 mm leave-stock each side.
    assert_eq!(stages(&out), vec![(1, StageRole::First), (2, StageRole::Profile)]);
    let s = out.operations[0].stages.as_ref().unwrap();
    assert!((s[0].side.unwrap() - 10.2).abs() < 1e-9 && s[0].gamma == Some(0.85), "{s:?}");
    assert!(s[0].removed > 4.0 * s[1].removed, "the big tool clears the box: {s:?}");
    // The slot is cut to its floor's allowance along its middle, and so is the box's floor.
    let (worst, n) = left_on_floors(&out, 1.5 + LEAVE + 0.3, slot_pocket);
    assert!(n > 5000 && worst <= 0.0011, "{worst} mm above the allowance on {n} floor cells");
    let slot = out.verification.as_ref().unwrap();
    let g = slot.stock.grid();
    let middle = (0..g.nx).filter(|&i| within(g.node(i, 0).x, 14.0, 26.0)).map(|i| {
        let j = ((0.0 - g.origin.y) / g.spacing).round() as usize;
        slot.stock.top(i, j)
    });
    assert!(middle.clone().count() > 40 && middle.clone().all(|z| z <= -10.0 + ALLOWANCE + 0.0011), "{:?}", middle.collect::<Vec<_>>());
    // Two tools in one program, the report says why each.
    assert_eq!(out.operations[0].tools, vec![1, 2]);
    assert!(s[0].why.contains("largest") && s[1].why.contains("smallest"), "{s:?}");
    assert!(out.gcode.matches("M6").count() == 2, "a tool change per stage");
    assert!(!out.octants.is_empty() && out.octants[0].boxes.iter().any(|b| b.full));
}

fn stepped(x: f64, y: f64) -> Option<f64> {
    if within(x, -5.0, 5.0) && within(y, -4.0, 4.0) {
        Some(-18.0)
    } else if within(x, -15.0, 15.0) && within(y, -10.0, 10.0) {
        Some(-12.0)
    } else if within(x, -30.0, 30.0) && within(y, -20.0, 20.0) {
        Some(-6.0)
    } else {
        None
    }
}

#[test]
fn a_stepped_cavity_takes_a_tool_per_step_matched_to_halved_octants_the_smallest_only_where_it_must() {
    let job = octree_job(vec![flat(1, 16.0), flat(2, 8.0), flat(3, 4.0)], RoughOctree::default());
    let out = job::run(&job, block(40.0, 30.0, stepped), &mut Progress::none()).unwrap();
    clean(&out);
    // φ16 first (13.6 mm octants); 6.8 mm octants match φ8 (γ = 0.85), whose 2 mm levels leave
    // no steps worth a finer tool: it profiles everything it reaches, the middle step (30 × 20)
    // among it; the innermost (10 × 8, 9 wide with the allowance and leave-stock) is out of its
    // reach and takes φ4 (γ = 0.85 at 3.4 mm), the smallest, only there.
    let s = stages(&out);
    assert_eq!(s, vec![(1, StageRole::First), (2, StageRole::Profile), (3, StageRole::Rest)]);
    let r = out.operations[0].stages.as_ref().unwrap();
    assert!(r[0].side.is_some_and(|d| (d - 13.6).abs() < 1e-9), "{r:?}");
    assert!(r[1].why.contains("sized for the 6.80 mm blocks") && r[1].why.contains("85 %"), "{r:?}");
    // The φ4 cuts only inside the innermost step and the corners of the middle one (its
    // centres within its radius of what the φ8 cannot reach), not round the whole cavity.
    assert!(r[2].area < 0.4 * 20.0 * 16.0 && r[2].area < 0.2 * r[1].area, "{r:?}");
    // The innermost floor leaves the φ4's centres 15 mm², less than the flats the z-level
    // levels take (twice the cutter's area): it is cut at the level above, within the
    // stair-step (the φ4's axial depth, 1 mm); the other floors are flats.
    let (worst, n) = left_on_floors(&out, 2.0 + LEAVE + 0.3, stepped);
    assert!(n > 3000 && worst <= 1.0 + 0.0011, "{worst} mm above the allowance on {n} floor cells");
    let (worst, n) = left_on_floors(&out, 2.0 + LEAVE + 0.3, |x, y| stepped(x, y).filter(|&f| f > -15.0));
    assert!(n > 3000 && worst <= 0.02, "{worst} mm above the allowance on {n} cells of the outer floors");
}

fn boss_in_pocket(x: f64, y: f64) -> Option<f64> {
    if within(x, -8.0, 8.0) && within(y, -8.0, 8.0) {
        None
    } else if within(x, -30.0, 30.0) && within(y, -30.0, 30.0) {
        Some(-10.0)
    } else {
        None
    }
}

#[test]
fn a_boss_in_a_pocket_is_roughed_round_with_the_big_tool_and_its_corners_by_the_small_one() {
    let job = octree_job(vec![flat(1, 10.0), flat(2, 4.0)], RoughOctree::default());
    let out = job::run(&job, block(40.0, 40.0, boss_in_pocket), &mut Progress::none()).unwrap();
    clean(&out);
    assert_eq!(stages(&out), vec![(1, StageRole::First), (2, StageRole::Profile)]);
    let r = out.operations[0].stages.as_ref().unwrap();
    assert!(r[0].removed > 20.0 * r[1].removed, "the small tool only takes the corners: {r:?}");
    let (worst, n) = left_on_floors(&out, 2.0 + LEAVE + 0.3, boss_in_pocket);
    assert!(n > 10_000 && worst <= 0.0011, "{worst} mm above the allowance on {n} floor cells");
    // The φ10 never came nearer the boss than its radius and the leave-stock.
    let v = out.verification.as_ref().unwrap();
    let g = v.stock.grid();
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            if p.x.abs() < 8.0 + LEAVE - 0.3 && p.y.abs() < 8.0 + LEAVE - 0.3 {
                assert!(v.stock.top(i, j) > -1e-6, "the boss was cut at {p}");
            }
        }
    }
}

#[test]
fn the_mould_is_roughed_biggest_tool_first_and_clean() {
    let job = octree_job(vec![flat(1, 20.0), flat(2, 12.0), flat(3, 6.0), flat(4, 3.0)], RoughOctree::default());
    let out = job::run(&job, octree_mould(1.0), &mut Progress::none()).unwrap();
    clean(&out);
    let s = stages(&out);
    assert_eq!(s.first(), Some(&(1, StageRole::First)), "{s:?}");
    // The φ6 profiles (1.5 mm levels), the φ3 goes only where the φ6 cannot.
    assert_eq!(s[s.len() - 2..], [(3, StageRole::Profile), (4, StageRole::Rest)], "{s:?}");
    let r = out.operations[0].stages.as_ref().unwrap();
    // Each stage's report adds up to the operation's.
    let removed: f64 = r.iter().map(|s| s.removed).sum();
    assert!((removed - out.operations[0].removed.unwrap()).abs() < 1e-6 * removed, "{removed} against {:?}", out.operations[0].removed);
    let seconds: f64 = r.iter().map(|s| s.seconds).sum();
    assert!(seconds <= out.operations[0].seconds + 1e-6 && seconds > 0.95 * out.operations[0].seconds, "{seconds} against {}", out.operations[0].seconds);
    // The big tool does most of the work.
    assert!(r[0].removed > 0.6 * removed, "{r:?}");
}

#[test]
fn a_library_too_big_for_the_part_is_refused_naming_a_tool_that_would_do() {
    let pocket = |x: f64, y: f64| (within(x, -5.0, 5.0) && within(y, -5.0, 5.0)).then_some(-6.0);
    // The stock's top is the part's: only the pocket is to be cut.
    let mut job = octree_job(vec![flat(1, 20.0), flat(2, 16.0)], RoughOctree::default());
    job.stock.margin_top = 0.0;
    let e = job::run(&job, block(20.0, 20.0, pocket), &mut Progress::none()).unwrap_err();
    match &e {
        Error::Operation { operation, why } => {
            assert_eq!(operation, "octree rough");
            assert!(why.contains("no tool of the library can enter") && why.contains("flat end would"), "{why}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn its_settings_are_checked_with_their_paths() {
    let e = Job::from_json(r#"{"tools": [{"number": 1, "shape": "flat"}], "operations": [{"kind": "roughOctree", "tools": [1, 7]}]}"#).and_then(|j| j.validate().map(|_| j)).unwrap_err();
    assert!(e.to_string().contains("operations[0].tools: no tool number 7"), "{e}");
    let e = Job::from_json(r#"{"version": 2, "tools": [{"number": 1, "shape": "flat"}], "operations": [{"kind": "roughOctree", "stepoverFraction": 0.9}]}"#)
        .and_then(|j| j.validate().map(|_| j))
        .unwrap_err();
    assert!(e.to_string().contains("operations[0].stepoverFraction is at most 0.85"), "{e}");
    let e = Job::from_json(r#"{"tools": [{"number": 1, "shape": "ball"}], "operations": [{"kind": "roughOctree"}]}"#).unwrap();
    let err = job::run(&e, block(20.0, 20.0, |_, _| Some(-3.0)), &mut Progress::none()).unwrap_err();
    assert!(err.to_string().contains("no flat or bull-nose end"), "{err}");
}

/// The page's sample part roughed with the library of the page's octree test (flat ends of
/// φ16, φ6 and φ3): clean. Rings left out for sweeping only what earlier rings cleared once
/// moved a leaf's helix entry to an island's loop, whose straight way out of the helix gouged
/// the part 1.16 mm deep.
#[test]
fn the_sample_part_is_roughed_clean_with_three_flat_ends() {
    let mut job = Job::demo();
    job.tools = vec![flat(1, 6.0), flat(3, 16.0), flat(4, 3.0)];
    job.operations = vec![Operation::RoughOctree(RoughOctree { roughing: Roughing { grid: 0.5, ..Roughing::default() }, ..RoughOctree::default() })];
    let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    clean(&out);
    assert_eq!(stages(&out).len(), 3, "{:?}", stages(&out));
}

/// Issue 38's rocker arm (scale 100, Y up, flat ends φ20/12/6/3, allowance 0): the φ6 and φ3
/// stages went in from the air beside regions their octants cut short, across the part, 4.2 mm
/// deep at most (OpenCAMLib's drop cutter agreed: `gcheck.py` −4.17 mm). The program is clean.
#[test]
fn the_rocker_arms_octree_roughing_is_clean() {
    let (Some(job), Some(part)) = (common::shared_data("jobs/octree-rocker.json"), common::shared_data("meshes/c3d_rocker-arm.obj")) else { return };
    let job = Job::from_json(&std::fs::read_to_string(job).unwrap()).unwrap();
    let bytes = std::fs::read(&part).unwrap();
    let workpiece = swarf::job::Workpiece::read(&bytes, Some("c3d_rocker-arm.obj"), &job.tolerances).unwrap();
    let out = swarf::job::run(&job, workpiece, &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert_eq!(out.problem, None, "{:?}", v.report);
    assert_eq!(v.report.gouge_count, 0);
}

/// Issue 38: material the library's tools reach but cannot enter as the octree's blocks
/// (a pocket with no room for a helix over 2 × 2 blocks and no side open to the air) was
/// refused ("no tool of the library can enter … a φ1.5 flat end would") although z-level
/// roughing with the same tool cuts it. The largest tool that reaches what the smallest would
/// now takes it in levels, clean.
#[test]
fn a_pocket_no_block_can_be_entered_in_is_roughed_in_levels() {
    let pocket = |x: f64, y: f64| (within(x, -4.5, 4.5) && within(y, -4.5, 4.5)).then_some(-6.0);
    let mut job = octree_job(vec![flat(1, 6.0)], RoughOctree::default());
    job.stock.margin_top = 0.0;
    let out = job::run(&job, block(20.0, 20.0, pocket), &mut Progress::none()).unwrap();
    clean(&out);
    let stages = out.operations[0].stages.as_ref().unwrap();
    assert_eq!(stages.len(), 1, "{stages:?}");
    assert_eq!(stages[0].role, StageRole::Profile);
    assert!(stages[0].why.contains("no tool clears a whole block"), "{}", stages[0].why);
    // Most of the pocket, 9 × 9 × (6 − 0.5) mm, is taken.
    assert!(stages[0].removed > 0.6 * 9.0 * 9.0 * 5.5, "{stages:?}");
}

/// Issue 38's terraces: a convex part taken by a φ20 alone at 5 mm levels (δ 0.25) keeps steps
/// up to 5 mm high for the finishing tool; the operation says so. At δ 0.1 (2 mm levels) it
/// does not need to.
#[test]
fn steps_the_last_stage_leaves_for_finishing_are_named() {
    let dome = |x: f64, y: f64| Some(12.0 * (1.0 - (x / 30.0).powi(2)).max(0.0) * (1.0 - (y / 20.0).powi(2)).max(0.0) - 12.0);
    let warned = |delta: f64| {
        let job = octree_job(vec![flat(1, 20.0)], RoughOctree { delta, ..RoughOctree::default() });
        let out = job::run(&job, block(30.0, 20.0, dome), &mut Progress::none()).unwrap();
        clean(&out);
        out.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n")
    };
    let w = warned(0.25);
    assert!(w.contains("φ20, cuts levels 5.00 mm apart: on slopes it leaves steps up to that high"), "{w}");
    let w = warned(0.1);
    assert!(!w.contains("cuts levels"), "{w}");
}

/// The material a verified program left over the part (mm³), its allowance among it.
fn left(out: &JobOutput) -> f64 {
    let r = out.verification.as_ref().expect("verified").residual();
    r.z.iter().map(|z| z.max(0.0)).sum::<f64>() * r.spacing * r.spacing
}

/// Issue 38's target: octree roughing takes no longer than z-level roughing with one tool of
/// its library, the φ6, at the same axial depth (δ D = 1.5 mm), and leaves no more material —
/// on the generated mould with seed 000's library, and on the rocker arm with the issue's own
/// job. Before the smallest tool went only where the others cannot reach, it took 36.0 against
/// 59.0 min on the mould but 24:18 against 17:47 on the rocker arm.
#[test]
fn octree_roughing_beats_its_own_phi6_alone_leaving_no_more() {
    let compare = |name: &str, job: &Job, part: swarf::job::Workpiece| {
        let octree = job::run(job, part.clone(), &mut Progress::none()).unwrap();
        clean(&octree);
        let Operation::RoughOctree(op) = &job.operations[0] else { panic!("an octree job") };
        let mut single = job.clone();
        single.operations = vec![Operation::RoughZlevel(swarf::operations::RoughZlevel {
            tool: job.tools.iter().find(|t| t.cutter.diameter == 6.0).unwrap().number,
            steps: swarf::operations::Steps { stepdown: op.delta * 6.0, stepover_fraction: op.stepover_fraction },
            roughing: op.roughing,
            ..Default::default()
        })];
        let phi6 = job::run(&single, part, &mut Progress::none()).unwrap();
        clean(&phi6);
        let (a, b) = (octree.stats.seconds, phi6.stats.seconds);
        let (la, lb) = (left(&octree), left(&phi6));
        eprintln!("{name}: octree {:.1} min leaving {la:.0} mm³, φ6 alone {:.1} min leaving {lb:.0} mm³", a / 60.0, b / 60.0);
        assert!(a <= b && la <= lb, "{name}: octree {a:.0} s leaving {la:.0} mm³ against the φ6's {b:.0} s leaving {lb:.0} mm³");
    };
    let tools = vec![flat(1, 20.0), flat(2, 12.0), flat(3, 6.0), flat(4, 3.0)];
    compare("mould", &octree_job(tools, RoughOctree::default()), octree_mould(1.0).into());
    if let (Some(job), Some(part)) = (common::shared_data("jobs/octree-rocker.json"), common::shared_data("meshes/c3d_rocker-arm.obj")) {
        let job = Job::from_json(&std::fs::read_to_string(job).unwrap()).unwrap();
        let workpiece = swarf::job::Workpiece::read(&std::fs::read(&part).unwrap(), Some("c3d_rocker-arm.obj"), &job.tolerances).unwrap();
        compare("rocker arm", &job, workpiece);
    }
}

/// Issue 38: the profile's way is chosen by time. In a plain square pocket the φ12 leaves only
/// a band along the walls and the corners. 8 mm deep, the φ6 round everything and then the φ3
/// corner by corner (entered from the ground the φ6 cleared) is quicker than the φ3 round
/// everything at its finer levels; 3 mm deep, the φ3 round everything once is, its two levels
/// against the φ6's one and the φ3's corners. The report says which and by how much, and the
/// way kept is the quicker of the two it names.
#[test]
fn the_quicker_way_to_take_what_is_left_is_kept() {
    let seconds = |why: &str, after: &str| -> f64 {
        let rest = &why[why.find(after).unwrap_or_else(|| panic!("{after:?} in {why}")) + after.len()..];
        rest.trim_start().split(' ').next().unwrap().parse().unwrap_or_else(|e| panic!("{e}: {rest}"))
    };
    for (depth, want) in [(8.0, vec![(1, StageRole::First), (2, StageRole::Profile), (3, StageRole::Rest)]), (3.0, vec![(1, StageRole::First), (3, StageRole::Profile)])] {
        let pocket = move |x: f64, y: f64| (within(x, -20.0, 20.0) && within(y, -20.0, 20.0)).then_some(-depth);
        let job = octree_job(vec![flat(1, 12.0), flat(2, 6.0), flat(3, 3.0)], RoughOctree::default());
        let out = job::run(&job, block(30.0, 30.0, pocket), &mut Progress::none()).unwrap();
        clean(&out);
        assert_eq!(stages(&out), want, "{depth} mm deep");
        let why = &out.operations[0].stages.as_ref().unwrap()[1].why;
        let named = if want.len() == 3 { "it and then the φ3 only where it cannot reach:" } else { "quicker than the φ6 round everything and then the φ3 only where it cannot reach:" };
        assert!(why.contains(named), "{why}");
        // Either way the report names the kept way's time first, the other's after "against".
        let (kept, other) = (seconds(why, "cannot reach:"), seconds(why, "against"));
        assert!(kept < other, "{depth} mm deep: kept {kept} s against {other} s: {why}");
    }
}

/// Two pockets joined by a gully too narrow for the φ6 (5 mm: its centre would need 7 with the
/// leave-stock), off to the side of the stock's middle and running across the way out from it.
fn gully(x: f64, y: f64) -> Option<f64> {
    let pocket = within(x, 5.0, 35.0) && (within(y, -25.0, -6.0) || within(y, 6.0, 25.0));
    (pocket || (within(x, 17.5, 22.5) && within(y, -7.0, 7.0))).then_some(-10.0)
}

/// Issue 38: the smallest tool's rest regions were entered by a helix wherever the step out of
/// them away from the stock's middle met the part, though they opened onto ground the larger
/// tool had cleared another way (188 entries, most of its 253 s, for 1,228 mm³ on
/// ocl_mount_rush). A gully between two pockets opens onto them at both ends, across the way
/// out from the stock's middle: the φ3 goes in from the pockets at every level, never by a
/// helix or a ramp, and takes the gully down to its floor.
#[test]
fn a_gully_the_larger_tool_cannot_enter_is_entered_from_the_ground_it_cleared() {
    let job = octree_job(vec![flat(1, 12.0), flat(2, 6.0), flat(3, 3.0)], RoughOctree::default());
    let out = job::run(&job, block(40.0, 30.0, gully), &mut Progress::none()).unwrap();
    clean(&out);
    let s = stages(&out);
    assert_eq!(s.last(), Some(&(3, StageRole::Rest)), "{s:?}");
    let path = out.paths.iter().find(|p| p.tool == 3).expect("the φ3's path");
    let mut at = path.start;
    let mut descents = 0;
    for m in &path.moves {
        let to = m.to();
        if !matches!(m, swarf::toolpath::Move::Rapid { .. }) && to.z < at.z - 1e-9 {
            assert!(to.truncate().distance(at.truncate()) < 1e-9, "the φ3 descends sideways (a helix or a ramp) from {at} to {to}");
            descents += 1;
        }
        at = to;
    }
    assert!(descents >= 4, "{descents} descents: one a level at least");
    // The gully's middle is cut to its floor's allowance.
    let (worst, n) = left_on_floors(&out, 1.5 + LEAVE + 0.3, |x, y| gully(x, y).filter(|_| within(y, -5.0, 5.0)));
    assert!(n >= 30 && worst <= 0.0011, "{worst} mm above the allowance on {n} gully cells");
}

/// Issue 56: at a step-over of 0.03 of a φ6 (0.18 mm, under the 0.375 mm pixels the rings'
/// material map had) a ring whose band held no pixel's centre was left out, its band standing a
/// level high; the traverse over the level, taken as cleared, went through it (the sample's
/// octree roughing was refused: a rapid through stock). At 0.04 a ring was left out because a
/// pixel's centre lay exactly at the cutter's reach from the ring before, the cell of material
/// beside it a hair beyond. The map is now the simulation's own cells: both programs are clean.
#[test]
fn a_step_over_finer_than_the_rings_pixels_leaves_no_band_standing() {
    for stepover_fraction in [0.03, 0.04] {
        let mut job = Job::demo();
        job.operations = vec![Operation::RoughOctree(RoughOctree { tools: vec![1], stepover_fraction, ..RoughOctree::default() })];
        let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap_or_else(|e| panic!("{stepover_fraction}: {e}"));
        clean(&out);
    }
}
