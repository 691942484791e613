//! Issue 58: a tool's holder, found in material by the verification. A 20 mm square pocket 20
//! deep roughed with a φ6 end mill in an ER20 chuck (its nut 34 mm across, wider than the
//! pocket): standing 12 mm out of the nut, the nut meets the plate's top once the tool is more
//! than 12 mm down, and the program is refused, saying where and how deep; standing 30 mm out,
//! it is clean. A section of a holder as a cone is checked in steps, never later than it meets.

use swarf::cutter::Cutter;
use swarf::geom::DVec2;
use swarf::job::{self, Job, Operation, Tool};
use swarf::mesh::sample::height_field_solid;
use swarf::operations::{FinishRaster, RoughZlevel};
use swarf::progress::Progress;
use swarf::tool::{Holder, HolderSection};

fn pocket() -> swarf::mesh::Mesh {
    height_field_solid(DVec2::new(-20.0, -20.0), DVec2::new(20.0, 20.0), 80, 80, -30.0, |x, y| if x.abs() < 10.0 && y.abs() < 10.0 { -20.0 } else { 0.0 })
}

fn job(stick_out: f64) -> Job {
    let er20 = Holder::builtin().into_iter().find(|h| h.name.starts_with("ER20")).unwrap();
    let tool = Tool { number: 1, cutter: Cutter { flute_length: 10.0, ..Cutter::flat(6.0) }, stick_out: Some(stick_out), holder: Some(er20), ..Tool::default() };
    let mut rough = RoughZlevel::default();
    rough.steps.stepdown = 5.0;
    Job { tools: vec![tool], operations: vec![Operation::RoughZlevel(rough)], ..Job::default() }
}

/// A 60 × 60 pocket 20 deep in an 80 × 80 plate: wide enough for an ER20's φ34 nut to go
/// down in its middle.
fn wide_pocket() -> swarf::mesh::Mesh {
    height_field_solid(DVec2::new(-40.0, -40.0), DVec2::new(40.0, 40.0), 160, 160, -30.0, |x, y| if x.abs() < 30.0 && y.abs() < 30.0 { -20.0 } else { 0.0 })
}

fn deepest_cut(out: &swarf::job::JobOutput) -> f64 {
    out.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min)
}

/// The holder meets the stock, not only the part (issue 58). A φ10 roughing (no holder) leaves
/// 2 mm on the wide pocket's floors and walls, and so on the plate's top under the stock's
/// margin; a φ6 ball in an ER20, 12 mm out, then finishes. Held to the part only, its nut came
/// down to half a millimetre over the plate: into the 2 mm the roughing left there, and the
/// program was refused. Held to the stock the roughing left as well, its holder meets nothing,
/// it says where it held the tool up, and in the middle of the pocket it still finishes the
/// floor. The same holder on a roughing tool goes down level by level through what the levels
/// above it cleared: to the floor in the middle, clean.
#[test]
fn a_holder_keeps_clear_of_the_stock_earlier_operations_left_and_goes_down_where_its_own_levels_cleared() {
    let er20 = Holder::builtin().into_iter().find(|h| h.name.starts_with("ER20")).unwrap();
    let big = Tool { number: 1, cutter: Cutter { flute_length: 25.0, ..Cutter::flat(10.0) }, stick_out: Some(40.0), ..Tool::default() };
    let ball = Tool { number: 2, cutter: Cutter { flute_length: 12.0, ..Cutter::ball(6.0) }, stick_out: Some(12.0), holder: Some(er20.clone()), ..Tool::default() };
    let mut rough = RoughZlevel::default();
    rough.steps.stepdown = 5.0;
    rough.roughing.allowance = 2.0;
    rough.roughing.leave_stock = 2.0;
    let finish = FinishRaster { tool: 2, stepover: 2.0, ..FinishRaster::default() };
    let j = Job { tools: vec![big, ball], operations: vec![Operation::RoughZlevel(rough), Operation::FinishRaster(finish)], ..Job::default() };
    let out = job::run(&j, wide_pocket(), &mut Progress::none()).unwrap();
    let r = &out.verification.as_ref().unwrap().report;
    assert_eq!(r.holder_collision_count, 0, "{}", r.describe());
    assert!(out.problem.is_none(), "{:?}", out.problem);
    let said: Vec<String> = out.warnings.iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.starts_with("raster finish") && w.contains("T2's holder (ER20") && w.contains("keeps clear of the part and the stock")), "{said:?}");
    assert!(deepest_cut(&out) < -19.9, "the ball finishes the floor in the middle: {}", deepest_cut(&out));

    let mut rough = RoughZlevel::default();
    rough.steps.stepdown = 4.0;
    let tool = Tool { number: 1, cutter: Cutter { flute_length: 12.0, ..Cutter::flat(6.0) }, stick_out: Some(12.0), holder: Some(er20), ..Tool::default() };
    let j = Job { tools: vec![tool], operations: vec![Operation::RoughZlevel(rough)], ..Job::default() };
    let out = job::run(&j, wide_pocket(), &mut Progress::none()).unwrap();
    let r = &out.verification.as_ref().unwrap().report;
    assert_eq!(r.holder_collision_count, 0, "{}", r.describe());
    assert!(out.problem.is_none(), "{:?}", out.problem);
    assert!(deepest_cut(&out) < -19.0, "the roughing reaches the floor in the middle: {}", deepest_cut(&out));
}

/// A 20 × 20 pocket 20 deep, an ER20's φ34 nut too wide to go in (issue 58). With 12 mm out
/// of it the roughing stops short where the nut would meet the plate and says so, the holder
/// clear of everything; with 30 mm out it reaches the floor. The program made without the
/// holder, verified against the job that has it (a peer's program that drives the holder in),
/// has the holder in material, found and refused.
#[test]
fn a_holder_too_short_stops_the_tool_short_and_a_program_that_drives_it_in_is_refused() {
    let short = job::run(&job(12.0), pocket(), &mut Progress::none()).unwrap();
    let r = &short.verification.as_ref().unwrap().report;
    assert_eq!(r.holder_collision_count, 0, "{}", r.describe());
    assert!(short.problem.is_none(), "{:?}", short.problem);
    let deepest = short.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min);
    // The nut's face 12 mm above the tip, half a millimetre clear of the plate's top.
    assert!((-11.5 - 1e-6..-10.0).contains(&deepest), "the tool down to {deepest}");
    let said: Vec<String> = short.warnings.iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.contains("T1's holder (ER20") && w.contains("material left there for a longer stick-out")), "{said:?}");
    let long = job::run(&job(30.0), pocket(), &mut Progress::none()).unwrap();
    let r = &long.verification.as_ref().unwrap().report;
    assert_eq!(r.holder_collision_count, 0, "{}", r.describe());
    assert!(long.problem.is_none(), "{:?}", long.problem);
    let deepest = long.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min);
    assert!(deepest < -19.0, "the long stick-out reaches the floor: {deepest}");
    // Nothing is held up in the pocket: only at the last level round the plate (29.5 mm down,
    // the margin's bottom), where the nut, 30 mm up, would come to the 0.5 mm left on the
    // plate's top.
    for w in long.warnings.iter().filter(|w| w.message.contains("holder")) {
        assert!(w.places.iter().all(|p| (p[0].abs() > 10.0 || p[1].abs() > 10.0) && p[2] < -28.0), "{w}");
    }
    // The program made as if there were no holder drives the nut into the plate.
    let mut bare = job(12.0);
    bare.tools[0].holder = None;
    let out = job::run(&bare, pocket(), &mut Progress::none()).unwrap();
    assert_eq!(out.verification.as_ref().unwrap().report.holder_collision_count, 0, "without a holder nothing is judged by one");
    let checked = job::verify_gcode(&job(12.0), pocket(), &out.gcode, None, &mut Progress::none()).unwrap();
    let r = &checked.report;
    assert!(r.holder_collision_count > 0, "{}", r.describe());
    let deepest = r.holder_collisions.iter().map(|f| f.amount).fold(0.0, f64::max);
    // The tool goes 19.5 mm down (0.5 left on the floor): the nut's face 12 mm above its tip
    // stands at most 7.5 mm under the plate's top.
    assert!(deepest > 1.0 && deepest < 7.5 + 0.6, "the nut {deepest} mm into the plate");
    assert!(r.problem().unwrap_or_default().contains("moves drive the tool's holder into material"), "{:?}", r.problem());
}

#[test]
fn a_holders_sections_are_rings_up_the_tool() {
    let h = Holder { name: "cone".into(), sections: vec![HolderSection { diameter: 20.0, length: 10.0, top_diameter: None }, HolderSection { diameter: 20.0, length: 8.0, top_diameter: Some(28.0) }] };
    let rings = h.rings(15.0);
    assert_eq!(rings[0], (10.0, 15.0));
    // The cone in four steps, each as wide as its wider end.
    assert_eq!(rings[1..].iter().map(|r| r.0).collect::<Vec<_>>(), vec![11.0, 12.0, 13.0, 14.0]);
    assert_eq!(rings[1..].iter().map(|r| r.1).collect::<Vec<_>>(), vec![25.0, 27.0, 29.0, 31.0]);
    let mut bad = h.clone();
    bad.sections[0].diameter = -1.0;
    assert_eq!(bad.problems()[0].0, "sections[0].diameter");
    let mut j = job(12.0);
    j.tools[0].holder = Some(bad);
    assert_eq!(j.problems()[0].path, "tools[0].holder.sections[0].diameter");
}

/// Issue 92: a finishing keeps its tool's flutes doing all the cutting. The wide pocket, 20 mm
/// deep, roughed with a long φ6 end mill and then finished by a raster with a φ6 ball whose
/// flutes are 12 mm (no holder): the ball's shank above its flutes would rub the pocket's
/// walls at its floor ("moves bury the tool deeper than its flute length", and no program).
/// Now it is held up where the shank would meet the walls, says so, and the program is clean;
/// away from the walls it still finishes the floor.
#[test]
fn a_finishing_keeps_its_shank_above_the_flutes_out_of_the_material() {
    let rougher = Tool { number: 1, cutter: Cutter { flute_length: 30.0, ..Cutter::flat(6.0) }, ..Tool::default() };
    let ball = Tool { number: 2, cutter: Cutter { flute_length: 12.0, ..Cutter::ball(6.0) }, ..Tool::default() };
    let mut rough = RoughZlevel::default();
    rough.steps.stepdown = 5.0;
    let raster = FinishRaster { tool: 2, stepover: 1.0, ..FinishRaster::default() };
    let job = Job { tools: vec![rougher, ball], operations: vec![Operation::RoughZlevel(rough), Operation::FinishRaster(raster)], ..Job::default() };
    let out = job::run(&job, wide_pocket(), &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert!(out.problem.is_none(), "{:?}", out.problem);
    let said: Vec<String> = out.warnings.iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.contains("T2's flutes (12 mm) take all it cuts")), "{said:?}");
    // The pocket's floor (its top at Z0 placed: the floor 20 below) is finished in its middle.
    let top = out.part.bounds().max.z;
    let floor_cut = out.moves.iter().filter(|m| m.path == 1 && !m.mv.is_rapid()).any(|m| {
        let to = m.mv.to();
        to.truncate().length() < 5.0 && to.z < top - 19.0
    });
    assert!(floor_cut, "the floor's middle is not finished");
}

/// Issue 92: zigzag and adaptive roughing with a holder that holds places up. The ER20's nut,
/// 12 mm up the tool, cannot follow the tool into the 20 × 20 pocket: its levels below 11.5 mm
/// are held up there, leaving material under them that later links must keep out of (the
/// issue found rapids through it on its own parts; this pocket is clean, and held so).
#[test]
fn links_over_a_holders_hold_up_keep_out_of_what_it_left() {
    use swarf::operations::{RoughAdaptive, RoughZigzag};
    let mut zigzag = RoughZigzag::default();
    zigzag.steps.stepdown = 4.0;
    let adaptive = RoughAdaptive { stepdown: 4.0, ..RoughAdaptive::default() };
    for op in [Operation::RoughZigzag(zigzag), Operation::RoughAdaptive(adaptive)] {
        let mut j = job(12.0);
        j.operations = vec![op];
        let out = job::run(&j, pocket(), &mut Progress::none()).unwrap();
        let r = &out.verification.as_ref().unwrap().report;
        assert!(r.is_clean() && out.problem.is_none(), "{}: {}", out.operations[0].name, r.describe());
    }
}
