//! Issue 58: speeds and feeds from the stock's material. Each tool's spindle speed and feed
//! against the closed form `n = 1000·vc/(π·D)`, `f = fz·z·n` with the table's figures, held to
//! the machine's spindle range and feed; a tool whose speeds are its own keeps them; the
//! program a job with a material writes runs at them, and says so on the setup sheet.

mod common;

use std::f64::consts::PI;

use swarf::cutter::{Cutter, Shape};
use swarf::cutting::{cutting_data, Machine, Material};
use swarf::drawing::import::read_drawing;
use swarf::drawing::sample::plate_dxf;
use swarf::job::{self, Job, Tool};
use swarf::progress::Progress;
use swarf::tool::{Speeds, ToolMaterial};

const SFM: f64 = 0.3048;
const IN: f64 = 25.4;

fn mill(d: f64, flutes: u32) -> Tool {
    Tool { number: 1, cutter: Cutter::flat(d), flutes, ..Tool::default() }
}

/// The closed form, held to `machine`: (rpm, feed). Where the spindle's slowest is faster than
/// the speed wanted, the feed is the one the wanted speed gives (a thinner chip a tooth).
fn closed(vc: Option<f64>, fz: f64, teeth: f64, d: f64, machine: &Machine) -> (f64, f64) {
    let wanted = vc.map_or(machine.spindle_max, |vc| 1000.0 * vc / (PI * d));
    let n = wanted.clamp(machine.spindle_min, machine.spindle_max).round();
    let turns = if n > wanted.round() { wanted } else { n };
    (n, (fz * teeth * turns).min(machine.max_feed).round())
}

#[test]
fn speeds_and_feeds_follow_the_table_in_closed_form() {
    let router = Machine::default();
    let vmc = Machine::builtin().into_iter().find(|m| m.name == "small VMC").unwrap();
    // (material, tool, machine, cutting speed m/min, chip load mm at that diameter, teeth)
    let cases: Vec<(Material, Tool, &Machine, Option<f64>, f64, f64)> = vec![
        // φ1/4" carbide, 2 flutes, in 6061: 1150 SFM (the middle of 800–1500), 0.002" a tooth.
        (Material::Aluminium6061, mill(6.35, 2), &router, Some(1150.0 * SFM), 0.002 * IN, 2.0),
        // Held at the router's top speed: φ3 carbide in aluminium wants 25,900 rpm.
        (Material::Aluminium6061, mill(3.0, 3), &router, Some(1150.0 * SFM), 0.001 * IN * 3.0 / 3.175, 3.0),
        // HSS at its own chart's 75 SFM; between the table's diameters the chip load is interpolated.
        (Material::MildSteel, Tool { tool_material: ToolMaterial::Hss, ..mill(8.0, 4) }, &vmc, Some(75.0 * SFM), (0.0015 + (8.0 - 6.35) / 3.175 * 0.0005) * IN, 4.0),
        (Material::Stainless304, mill(12.7, 4), &vmc, Some(175.0 * SFM), 0.0015 * IN, 4.0),
        (Material::Brass, mill(20.0, 3), &vmc, Some(1150.0 * SFM), 0.003 * IN, 3.0),
        // Wood at the spindle's top speed; the feed held at the router's 5000 mm/min.
        (Material::Mdf, mill(6.35, 2), &router, None, 0.0135 * IN, 2.0),
        (Material::Plywood, mill(3.175, 1), &router, None, 0.004 * IN, 1.0),
        // The router's 8000 rpm floor is faster than acrylic's 350 SFM wants (5348 rpm): the
        // feed the chart's speed gives, a thinner chip a tooth.
        (Material::Acrylic, mill(6.35, 1), &router, Some(350.0 * SFM), 0.0065 * IN, 1.0),
        // Coated carbide a quarter faster in the metals, as carbide in plastics.
        (Material::MildSteel, Tool { tool_material: ToolMaterial::Coated, ..mill(10.0, 3) }, &vmc, Some(200.0 * SFM * 1.25), (0.002 + (10.0 - 9.525) / 3.175 * 0.001) * IN, 3.0),
        (Material::Hdpe, Tool { tool_material: ToolMaterial::Coated, ..mill(6.35, 2) }, &router, Some(500.0 * SFM), 0.0075 * IN, 2.0),
        // A drill's two lips, whatever its flutes say.
        (Material::Aluminium6061, Tool { cutter: Cutter::drill(6.35, 118.0), flutes: 4, ..mill(6.35, 4) }, &vmc, Some(1150.0 * SFM), 0.002 * IN, 2.0),
    ];
    for (material, tool, machine, vc, fz, teeth) in cases {
        let c = cutting_data(&tool, Some(material), machine);
        let (n, f) = closed(vc, fz, teeth, tool.cutter.diameter, machine);
        assert!(c.from_material && c.source.is_some());
        assert_eq!(c.spindle_rpm, n, "{material:?} φ{}: {}", tool.cutter.diameter, c.reason);
        assert!((c.feed_rate - f).abs() <= 1.0, "{material:?} φ{}: {} against {f}: {}", tool.cutter.diameter, c.feed_rate, c.reason);
        assert!(c.spindle_rpm >= machine.spindle_min && c.spindle_rpm <= machine.spindle_max && c.feed_rate <= machine.max_feed);
        let plunge = if tool.cutter.shape == Shape::Drill { c.feed_rate } else { (c.feed_rate / 2.0).round() };
        assert!((c.plunge_rate - plunge).abs() <= 1.0);
    }
    // What held them is said.
    let c = cutting_data(&mill(3.0, 3), Some(Material::Aluminium6061), &router);
    assert!(c.reason.contains("held at the machine's 24000 rpm"), "{}", c.reason);
    let c = cutting_data(&mill(12.7, 3), Some(Material::Mdf), &router);
    assert!(c.reason.contains("held at the machine's 5000 mm/min"), "{}", c.reason);
    // A tool whose speeds are its own, and a job without a material, keep the typed ones.
    let own = Tool { speeds: Speeds::AsTyped, spindle_rpm: 9000.0, feed_rate: 700.0, ..mill(6.0, 2) };
    let c = cutting_data(&own, Some(Material::Brass), &router);
    assert_eq!((c.spindle_rpm, c.feed_rate, c.from_material), (9000.0, 700.0, false));
    let c = cutting_data(&mill(6.0, 2), None, &router);
    assert_eq!((c.spindle_rpm, c.feed_rate), (12000.0, 1000.0));
}

#[test]
fn a_job_in_a_material_runs_at_its_speeds_and_feeds() {
    let drawing = read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Default::default()).unwrap();
    let mut job = Job::default_for_drawing();
    job.stock.material = Some(Material::Plywood);
    job.tools[0].flutes = 2;
    let c = &job.cutting_data()[0];
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).unwrap();
    assert!(out.gcode.lines().any(|l| l == format!("S{} M3", c.spindle_rpm)), "{}", &out.gcode[..600]);
    // The feeds the program runs at: the material's, not the typed 800 mm/min.
    let feeds = |gcode: &str| -> Vec<f64> { gcode.split_whitespace().filter_map(|w| w.strip_prefix('F')?.parse().ok()).collect() };
    let fs = feeds(&out.gcode);
    assert!(fs.contains(&c.feed_rate) && fs.contains(&c.plunge_rate), "{fs:?}");
    assert!(!fs.contains(&800.0));
    // The sheet says where they come from.
    let sheet = swarf::job::sheet::SheetSetup::of("sheet", &out);
    let html = swarf::job::sheet::setup_sheet(&job, "plate.dxf", &[sheet]);
    assert!(html.contains("in plywood: the spindle's top speed"), "{html:.4000}");
    // Typed speeds stay typed.
    job.tools[0].speeds = Speeds::AsTyped;
    let out = job::run(&job, drawing, &mut Progress::none()).unwrap();
    assert!(out.gcode.contains("S12000 M3") && feeds(&out.gcode).contains(&800.0));
    // The machine's limits are checked like any setting.
    job.machine.spindle_max = 50.0;
    job.machine.spindle_min = 100.0;
    assert_eq!(job.problems()[0].path, "machine.spindleMax");
    job.machine = Machine::default();
    job.tools[0].flutes = 0;
    assert_eq!(job.problems()[0].path, "tools[0].flutes");
}

/// Every built-in machine makes the sample job in aluminium inside its limits: each spindle
/// speed in its range, each feed at most its fastest, the program within its travel. A stock
/// wider than a machine travels is a program not safe to run, the axis and the machine named;
/// a machine whose travel is not known is not checked.
#[test]
fn every_built_in_machine_keeps_its_programs_inside_its_limits() {
    use swarf::toolpath::Move;
    for machine in Machine::builtin() {
        let mut job = Job::demo();
        job.stock.material = Some(Material::Aluminium6061);
        job.machine = machine.clone();
        let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
        assert_eq!(out.problem, None, "{}", machine.name);
        for p in &out.paths {
            assert!(p.spindle_rpm >= machine.spindle_min && p.spindle_rpm <= machine.spindle_max, "{}: S{}", machine.name, p.spindle_rpm);
            for m in &p.moves {
                if let Move::Line { feed, .. } | Move::Arc { feed, .. } = *m {
                    assert!(feed <= machine.max_feed + 1e-9, "{}: F{feed}", machine.name);
                }
            }
        }
    }
    // Faced from a stock 330 mm wide: more than the benchtop mill's 300 mm of X.
    let mut job = Job::demo();
    job.operations = vec![swarf::operations::Operation::Face(swarf::operations::Face { tool: 1, ..Default::default() })];
    job.stock.margin_xy = 120.0;
    job.machine = Machine::builtin().into_iter().find(|m| m.name == "benchtop mill").unwrap();
    let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    let problem = out.problem.clone().unwrap_or_default();
    assert!(problem.contains("mm in X") && problem.contains("more than the benchtop mill's 300 mm of travel"), "{problem}");
    assert!(out.gcode_marked().contains("NOT SAFE TO RUN"));
    job.machine.travel = None;
    assert_eq!(job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap().problem, None);
    // A travel that does not read is named at its field.
    job.machine.travel = Some([300.0, 0.0, 250.0]);
    assert!(job.problems().iter().any(|p| p.path == "machine.travel"), "{:?}", job.problems());
}

/// A machine's rapid rates per axis (`machine.rapids`) time its rapids: each takes as long as
/// its slowest axis needs, in the program's head, its cycle time and the simulation's clock
/// alike; the paths are the same as with the post's one rate, and the cycle differs from it by
/// exactly what the rapids' times differ by. A rate that does not read is named at its field.
#[test]
fn rapids_take_as_long_as_their_slowest_axis() {
    use swarf::toolpath::{Move, Rapids};
    // Closed form: 300, 400 and 50 mm at 10000, 10000 and 5000 mm/min: Y's 0.04 min.
    let axes = Rapids { rate: 3000.0, axes: Some([10000.0, 10000.0, 5000.0]) };
    let (a, b) = (swarf::geom::DVec3::ZERO, swarf::geom::DVec3::new(300.0, -400.0, 50.0));
    assert!((axes.seconds(a, b) - 2.4).abs() < 1e-12);
    assert!((Rapids::at(3000.0).seconds(a, b) - a.distance(b) / 3000.0 * 60.0).abs() < 1e-12);
    let mut job = Job::demo();
    job.machine = Machine::builtin().into_iter().find(|m| m.name == "benchtop mill").unwrap();
    let timed = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    let [x, y, z] = job.machine.rapids.unwrap();
    job.machine.rapids = None;
    let along = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    assert_eq!(timed.paths, along.paths);
    let (mut per_axis, mut one_rate, mut rapids) = (0.0, 0.0, 0);
    for m in &timed.moves {
        if let Move::Rapid { to } = m.mv {
            let d = (to - m.from).abs();
            let t = 60.0 * (d.x / x).max(d.y / y).max(d.z / z);
            assert!((m.seconds - t).abs() < 1e-9, "the simulation's clock: {} s against {t} s", m.seconds);
            per_axis += t;
            one_rate += m.from.distance(to) / job.post.rapid_rate * 60.0;
            rapids += 1;
        }
    }
    assert!(rapids > 10 && (per_axis - one_rate).abs() > 1.0, "{rapids} rapids: {per_axis} s against {one_rate} s");
    assert!(timed.cycle.seconds != along.cycle.seconds);
    // The post times the moves it writes: a path of known moves, at 3000, 3000 and 2000 mm/min
    // a rapid 100 × 50 mm across (2 s), 4 mm down (0.12 s), 2 mm down at F300 (0.4 s), 30 mm
    // across at F600 (3 s) and 6 mm up (0.18 s).
    let path = swarf::toolpath::Toolpath {
        name: "known".into(),
        tool: 1,
        spindle_rpm: 10000.0,
        start: swarf::geom::DVec3::new(0.0, 0.0, 5.0),
        moves: vec![
            Move::Rapid { to: swarf::geom::DVec3::new(100.0, 50.0, 5.0) },
            Move::Rapid { to: swarf::geom::DVec3::new(100.0, 50.0, 1.0) },
            Move::Line { to: swarf::geom::DVec3::new(100.0, 50.0, -1.0), feed: 300.0 },
            Move::Line { to: swarf::geom::DVec3::new(130.0, 50.0, -1.0), feed: 600.0 },
            Move::Rapid { to: swarf::geom::DVec3::new(130.0, 50.0, 5.0) },
        ],
        cycles: Vec::new(),
    };
    let post = swarf::post::PostSettings { rapid_axes: Some([x, y, z]), ..job.post.clone() };
    let (_, cycle) = swarf::post::write_program("known", std::slice::from_ref(&path), &job.tools, 5.0, &post).unwrap();
    assert!((cycle.paths[0] - 5.7).abs() < 1e-9, "{:?}", cycle.paths);
    assert!((path.stats(post.rapids()).seconds - 5.7).abs() < 1e-9);
    assert!(timed.gcode.contains("rapids at X 3000, Y 3000, Z 2000 mm/min"), "{}", &timed.gcode[..600]);
    job.machine.rapids = Some([3000.0, -1.0, 2000.0]);
    assert!(job.problems().iter().any(|p| p.path == "machine.rapids"), "{:?}", job.problems());
}

/// Spindle power (`machine.power`, the material's specific cutting force): Mitsubishi
/// Materials' worked example comes out (2 mm deep, 80 mm wide at 280 mm/min in Kc 1800 N/mm²
/// steel: 1.68 kW); a spindle too weak for the cuts has the feeds held down wherever the
/// simulation measures a cut taking more than it has, to no more than it, measured again here
/// from the moves as held: the moves keep their places, feeds are only lowered, to whole
/// mm/min, the program runs longer and each operation says so; in wood, which has no specific
/// cutting force, nothing changes.
#[test]
fn feeds_are_held_to_what_the_spindle_can_take() {
    use swarf::sim::program::{removal_rates, ProgramMove, RATE_CELLS};
    use swarf::toolpath::Move;
    assert!((swarf::cutting::power(2.0 * 80.0 * 280.0, 1800.0) - 1.68).abs() < 1e-9);
    let mut job = Job::demo();
    job.stock.material = Some(Material::MildSteel);
    job.machine = Machine::builtin().into_iter().find(|m| m.name == "benchtop mill").unwrap();
    job.machine.power = None;
    let free = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    job.machine.power = Some(0.02);
    let limit = swarf::cutting::rate_limit(&job.machine, job.stock.material).unwrap();
    assert!((limit - 0.02 * 60e6 * 0.8 / 2200.0).abs() < 1e-9);
    let held = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    let v = held.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let rates = |out: &swarf::job::JobOutput| {
        let v = out.verification.as_ref().unwrap();
        let timings: Vec<_> = out.moves.iter().map(ProgramMove::timing).collect();
        removal_rates(&timings, &v.volumes, RATE_CELLS * v.stock.grid().spacing)
    };
    let (before, after) = (rates(&free), rates(&held));
    let peak = |r: &[f64]| r.iter().copied().fold(0.0, f64::max);
    eprintln!("peak {:.0} mm³/min as planned, {:.0} held, the limit {limit:.0}; cycle {:.0} s, held {:.0} s", peak(&before), peak(&after), free.cycle.seconds, held.cycle.seconds);
    assert!(peak(&before) > 1.5 * limit, "the spindle is too weak for the cuts as planned");
    assert!(peak(&after) <= limit * (1.0 + 1e-9), "{} mm³/min held against {limit}", peak(&after));
    assert!((peak(&after) - v.report.mrr_max).abs() < 1e-6 * limit, "the report's peak is the held one");
    // The same moves, their feeds only lowered, to whole mm/min.
    assert_eq!(free.moves.len(), held.moves.len());
    let mut slowed = 0;
    for (a, b) in free.moves.iter().zip(&held.moves) {
        assert_eq!(a.mv.to(), b.mv.to());
        if let (Move::Line { feed: fa, .. } | Move::Arc { feed: fa, .. }, Move::Line { feed: fb, .. } | Move::Arc { feed: fb, .. }) = (a.mv, b.mv) {
            assert!(fb <= fa);
            if fb < fa {
                assert_eq!(fb, fb.round());
                slowed += 1;
            }
        }
    }
    assert!(slowed > 10 && held.cycle.seconds > free.cycle.seconds, "{slowed} moves slowed");
    // Said per operation, with the power as planned; each operation's peak power at most the spindle's.
    assert!(held.warnings.iter().any(|w| w.message.contains("feeds held down so that no cut takes more than the benchtop mill's 0.02 kW spindle in mild steel")), "{:?}", held.warnings);
    for o in &held.operations {
        assert!(o.power_max.unwrap() <= 0.02 + 1e-9, "{}", o.describe());
    }
    assert!(free.operations.iter().any(|o| o.power_max.unwrap() > 0.02));
    // LinuxCNC reads the held program.
    assert!(common::rs274(&held.gcode, &job.tools).contains("STRAIGHT_FEED"));
    // In hardwood the tables give no specific cutting force: nothing is held.
    job.stock.material = Some(Material::Hardwood);
    let wood = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    assert!(wood.operations.iter().all(|o| o.power_max.is_none()) && !wood.warnings.iter().any(|w| w.message.contains("feeds held down")));
    // A power that does not read is named at its field.
    job.machine.power = Some(-1.0);
    assert!(job.problems().iter().any(|p| p.path == "machine.power"), "{:?}", job.problems());
}

/// A flat end mill fed along a wall, its edge `ae` into it: the simulation's nearest cut is
/// the wall, and the optimised feed is the tool makers' radial chip thinning,
/// `f·D / (2√(ae·D − ae²))` for `ae` under the radius, the feed itself from the radius on,
/// within what a cell of the simulation can tell.
#[test]
fn a_cut_along_a_wall_is_sped_up_by_its_chips_thinning() {
    use swarf::geom::{Aabb, DVec3};
    use swarf::sim::feeds::{speed_up, MAX_SPEEDUP};
    use swarf::sim::program::program_moves;
    use swarf::sim::verify::Simulator;
    use swarf::toolpath::{Move, Rapids, Toolpath};
    let (d, feed, cell) = (10.0, 1000.0, 0.05);
    let stock = Aabb { min: DVec3::new(0.0, 0.0, 0.0), max: DVec3::new(40.0, 20.0, 10.0) };
    let tool = Tool { number: 1, cutter: Cutter::flat(d), flutes: 2, spindle_rpm: 10_000.0, feed_rate: feed, ..Tool::default() };
    for ae in [0.25, 0.5, 1.0, 2.0, 3.5, 5.0, 7.0] {
        // Along X at y = ae − R: the tool's edge `ae` into the stock's side at y = 0.
        let y = ae - d / 2.0;
        let start = DVec3::new(-10.0, y, 5.0);
        let path = Toolpath { name: "wall".into(), tool: 1, spindle_rpm: 10_000.0, start, moves: vec![Move::Line { to: DVec3::new(50.0, y, 5.0), feed }], cycles: Vec::new() };
        let mut paths = vec![path];
        let mut moves = program_moves(&paths, std::slice::from_ref(&tool), Rapids::at(10_000.0), 10_000.0).unwrap();
        let mut sim = Simulator::new(&stock, cell).unwrap();
        sim.run(&moves, &swarf::geom::Tolerances::default(), &mut Progress::none(), 1.0).unwrap();
        let (volumes, nearest) = (sim.volumes().to_vec(), sim.nearest().to_vec());
        assert!((volumes[0] - 40.0 * ae.min(20.0) * 5.0).abs() < 40.0 * cell * 5.0, "ae {ae}: {} mm³", volumes[0]);
        speed_up(&mut paths, &mut moves, &volumes, &nearest, cell, 10_000.0);
        let Move::Line { feed: got, .. } = paths[0].moves[0] else { unreachable!() };
        assert_eq!(moves[0].mv.feed(), Some(got));
        let closed = |ae: f64| if ae >= d / 2.0 { feed } else { (feed * d / (2.0 * (ae * d - ae * ae).sqrt())).min(MAX_SPEEDUP * feed) };
        // Never above the closed form (the chip no thicker than in a slot), and no lower than
        // the closed form for a cut a cell wider.
        eprintln!("ae {ae}: {got} mm/min, closed form {:.0}", closed(ae));
        assert!(got <= closed(ae) + 1e-9 && got >= closed(ae + cell * 1.5).max(feed) - 1.0, "ae {ae}: {got} against {:.1}", closed(ae));
        assert!(ae >= d / 2.0 || got > feed, "ae {ae}: a light cut runs faster");
    }
}

/// The demo job with its feeds optimised: the same moves, cuts faster where their chips thin
/// and moves in air at the air feed, its thickest chip measured no thicker than each tool's
/// chip load at its feed; a shorter cycle; the program read back verifies clean (a raised cut
/// is not taken for a move in air) and LinuxCNC reads it.
#[test]
fn optimised_feeds_run_faster_within_each_tools_chip_load() {
    use swarf::sim::feeds::chips;
    let mut job = Job::demo();
    let plain = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    assert!(plain.feeds.is_none());
    job.simulation.optimize_feeds = true;
    let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    common::clean(&out);
    let report = out.feeds.clone().expect("the optimisation's report");
    eprintln!("{}; cycle {:.0} s against {:.0} s", report.describe(), out.cycle.seconds, plain.cycle.seconds);
    assert!(report.faster > 100 && report.aired > 0, "{report:?}");
    assert!(out.cycle.seconds < 0.95 * plain.cycle.seconds && report.seconds < report.plain, "{:.0} s against {:.0} s", out.cycle.seconds, plain.cycle.seconds);
    assert!((report.plain - plain.moves.iter().map(|m| m.seconds).sum::<f64>()).abs() < 1e-6 * report.plain);
    // The same moves, feeds only raised.
    assert_eq!(plain.moves.len(), out.moves.len());
    for (a, b) in plain.moves.iter().zip(&out.moves) {
        assert_eq!((a.from, a.mv.to()), (b.from, b.mv.to()));
        assert!(b.mv.feed() >= a.mv.feed());
        // A move now at the air feed is one in air, as the read-back program takes it.
        if b.mv.feed() == Some(job.air_feed()) && b.mv.feed() > a.mv.feed() {
            assert!(b.air, "{b:?}");
        }
    }
    let v = out.verification.as_ref().unwrap();
    let cell = v.stock.grid().spacing;
    let measured = chips(&out.moves, &v.volumes, &v.nearest, cell, &job.tools);
    for (m, chip) in out.moves.iter().zip(&measured) {
        let tool = job.tools.iter().find(|t| t.number == m.tool).unwrap();
        let load = tool.feed_rate / (tool.spindle_rpm * tool.flutes as f64);
        assert!(*chip <= load * (1.0 + 1e-9), "T{} chip {chip} mm/tooth over its {load}", m.tool);
    }
    for o in &out.operations {
        assert!(o.chip_max.is_some_and(|c| c > 0.0), "{}", o.describe());
    }
    // Read back from the G-code, the program verifies clean: no raised cut is taken for air.
    let again = job::verify_gcode(&job, swarf::mesh::sample::demo_part(), &out.gcode, None, &mut Progress::none()).unwrap();
    assert!(again.report.is_clean(), "{}", again.report.describe());
    assert!(common::rs274(&out.gcode, &job.tools).contains("STRAIGHT_FEED"));
}

/// Issue 93, the machine: feeds as typed faster than the machine goes are held at its fastest
/// and said (F8000 on a 5000 mm/min router once ran as typed); a fastest feed under 1 mm/min is
/// refused (1e-12 made every feed F1); a machine named as a built-in one takes its limits (a
/// "small VMC" by name once kept the router's); a name of none with no limits is refused; a
/// spindle whose slowest speed runs a tool far past its material's surface speed is warned of
/// with the figures (a φ12 in mild steel on a router's 8000 rpm floor).
#[test]
fn the_machine_means_what_it_says() {
    // Typed feeds held at the router's 5000 mm/min, with a warning naming the tool.
    let mut job = Job::demo();
    job.tools[0].feed_rate = 8000.0;
    let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    assert!(out.warnings.iter().any(|w| w.to_string().contains("T1") && w.to_string().contains("F8000") && w.to_string().contains("held at it")), "{:?}", out.warnings);
    let fastest = out.moves.iter().filter(|m| !m.mv.is_rapid() && !m.air).filter_map(|m| m.mv.feed()).fold(0.0, f64::max);
    assert!(fastest <= 5000.0 + 1e-9, "a feed of {fastest} mm/min");
    // A fastest feed under 1 mm/min.
    let e = Job::from_json(r#"{ "machine": { "name": "slow", "spindleMin": 1000, "spindleMax": 10000, "maxFeed": 1e-12 } }"#).and_then(|j| j.validate().map(|_| j)).unwrap_err().to_string();
    assert!(e.contains("maxFeed") && e.contains("at least 1 mm/min"), "{e}");
    // By name.
    let vmc = Job::from_json(r#"{ "machine": { "name": "small VMC" } }"#).unwrap();
    assert_eq!(vmc.machine, Machine::builtin()[2]);
    let own = Job::from_json(r#"{ "machine": { "name": "small VMC", "maxFeed": 8000 } }"#).unwrap();
    assert_eq!((own.machine.max_feed, own.machine.spindle_max), (8000.0, 12000.0));
    let e = Job::from_json(r#"{ "machine": { "name": "Shapeoko" } }"#).unwrap_err().to_string();
    assert!(e.contains("machine.name: \"Shapeoko\" is none of the built-in machines") && e.contains("spindleMin"), "{e}");
    // A φ12 carbide in mild steel on the router's 8000 rpm floor: π·12·8000/1000 = 301.6 m/min.
    let mut job = Job::demo();
    job.stock.material = Some(Material::MildSteel);
    job.tools[0].cutter = Cutter::flat(12.0);
    let said = job.machine_warnings();
    let vc = Material::MildSteel.cutting_speed(ToolMaterial::Carbide).unwrap();
    let at = (PI * 12.0 * 8000.0 / 1000.0).round();
    assert!(said.iter().any(|w| w.to_string().contains(&format!("{at} m/min at the surface")) && w.to_string().contains(&format!("{:.1} ×", PI * 12.0 * 8.0 / vc))), "{said:?}");
    let data = cutting_data(&job.tools[0], job.stock.material, &job.machine);
    assert!(data.reason.contains("too fast for it"), "{}", data.reason);
    // On the benchtop mill (100 rpm at its slowest) nothing is said.
    job.machine = Machine::builtin()[1].clone();
    assert!(job.machine_warnings().is_empty());
}

/// Issue 93: speeds a machinist would run. Mild steel with carbide runs inside the carbide
/// chart's 100–300 SFM (not at HSS's end); a ball end takes its speed from the circle its
/// corner cuts at its depth of cut (`2·√(d·(D − d))`), a bull nose's likewise, a flat its
/// diameter; a job's finishing ball cuts at the allowance its roughing left, its roughing ball
/// at its step-down; a spindle floor faster than the chart keeps the chart's feed with a
/// thinner chip and says so.
#[test]
fn speeds_are_the_charts_for_the_tool_and_its_depth_of_cut() {
    use swarf::cutting::{cutting_data_at, effective_diameter};
    let vmc = Machine::builtin().into_iter().find(|m| m.name == "small VMC").unwrap();
    let (lo, hi) = Material::MildSteel.carbide_range().unwrap();
    let vc = Material::MildSteel.cutting_speed(ToolMaterial::Carbide).unwrap();
    assert!(vc > lo && vc < hi && (lo - 100.0 * SFM).abs() < 1e-9 && (hi - 300.0 * SFM).abs() < 1e-9, "{vc} m/min");
    assert!(vc > 2.0 * Material::MildSteel.cutting_speed(ToolMaterial::Hss).unwrap());
    // Effective diameters in closed form.
    assert!((effective_diameter(&Cutter::ball(6.0), 0.5) - 2.0 * (0.5f64 * 5.5).sqrt()).abs() < 1e-12);
    assert_eq!(effective_diameter(&Cutter::ball(6.0), 3.0), 6.0);
    assert_eq!(effective_diameter(&Cutter::flat(6.0), 0.5), 6.0);
    assert!((effective_diameter(&Cutter::bull_nose(10.0, 1.0), 0.25) - (8.0 + 2.0 * (0.25f64 * 1.75).sqrt())).abs() < 1e-12);
    let ball = Tool { cutter: Cutter::ball(6.0), flutes: 2, ..mill(6.0, 2) };
    let c = cutting_data_at(&ball, Some(Material::MildSteel), &vmc, Some(0.5));
    let d_eff = 2.0 * (0.5f64 * 5.5).sqrt();
    assert_eq!(c.spindle_rpm, (1000.0 * vc / (PI * d_eff)).round(), "{}", c.reason);
    assert!(c.reason.contains("at φ3.32 (where its corner cuts 0.5 mm deep)"), "{}", c.reason);
    // In a job: the demo's ball finishes what the roughing left (0.5 mm) and runs faster than
    // its flat, of the same diameter.
    let mut job = Job::demo();
    job.stock.material = Some(Material::MildSteel);
    job.machine = vmc.clone();
    assert_eq!(job.deepest_cuts(), vec![Some(2.0), Some(0.5)]);
    let data = job.cutting_data();
    assert!(data[1].spindle_rpm > 1.7 * data[0].spindle_rpm, "{} against {}", data[1].reason, data[0].reason);
    // The router's 8000 rpm floor runs a φ12 HSS in mild steel far over its chart: the feed
    // stays the chart's speed's.
    let router = Machine::default();
    let big = Tool { tool_material: ToolMaterial::Hss, ..mill(12.0, 4) };
    let c = cutting_data(&big, Some(Material::MildSteel), &router);
    let wanted = 1000.0 * 75.0 * SFM / (PI * 12.0);
    let fz = Material::MildSteel.chip_load(12.0);
    assert_eq!(c.spindle_rpm, 8000.0);
    assert!((c.feed_rate - (fz * 4.0 * wanted).round()).abs() <= 1.0, "{}", c.reason);
    assert!(c.reason.contains("the chip a tooth thinned"), "{}", c.reason);
}

/// A level cut at full width deeper than the tool is wide is beyond the chart's condition and
/// said with the figures (a φ3 in mild steel at a 9 mm step-down); within a diameter, or
/// cleared adaptively, nothing is said.
#[test]
fn a_cut_deeper_than_the_chart_takes_is_said() {
    use swarf::operations::{Operation, RoughAdaptive, RoughZlevel, Steps};
    let mut job = Job::demo();
    job.stock.material = Some(Material::MildSteel);
    job.machine = Machine::builtin().into_iter().find(|m| m.name == "small VMC").unwrap();
    job.tools[0].cutter = Cutter { flute_length: 12.0, ..Cutter::flat(3.0) };
    let steps = Steps { stepdown: 9.0, ..Steps::default() };
    job.operations = vec![Operation::RoughZlevel(RoughZlevel { tool: 1, steps, ..RoughZlevel::default() })];
    let said: Vec<String> = job.machine_warnings().iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.contains("step-down of 9 mm is 3.0 × its φ3 tool's diameter") && w.contains("mild steel")), "{said:?}");
    // Said when the job runs.
    let out = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    assert!(out.warnings.iter().any(|w| w.to_string().contains("3.0 × its φ3")), "{:?}", out.warnings);
    job.operations = vec![Operation::RoughZlevel(RoughZlevel { tool: 1, steps: Steps { stepdown: 3.0, ..steps }, ..RoughZlevel::default() })];
    assert!(job.machine_warnings().is_empty());
    job.operations = vec![Operation::RoughAdaptive(RoughAdaptive { tool: 1, stepdown: 9.0, ..RoughAdaptive::default() })];
    assert!(job.machine_warnings().is_empty());
    // Without a material nothing is known to be too deep.
    job.stock.material = None;
    job.operations = vec![Operation::RoughZlevel(RoughZlevel { tool: 1, steps, ..RoughZlevel::default() })];
    assert!(job.machine_warnings().is_empty());
}

/// BENCHMARKS.md's speeds-and-feeds table: swarf's figures beside the published charts, 4
/// metals × 5 tools (φ1/8", 1/4", 3/8", 1/2" flats, 2 flutes for aluminium and brass, 4 for
/// the steels, and a φ1/4" ball at a 0.5 mm depth of cut) × carbide and HSS, on a machine
/// that limits neither speed nor feed: each surface speed inside the carbide chart's SFM range
/// (Torbide Tooling) or at the HSS chart's figure (Newson Tool), each chip load the chart's
/// at that diameter. `cargo test --release --test cutting the_chart -- --nocapture` prints it.
#[test]
fn the_chart_beside_published_figures() {
    use swarf::cutting::cutting_data_at;
    let open = Machine { name: "unlimited".into(), spindle_min: 0.0, spindle_max: 100_000.0, max_feed: 100_000.0, ..Machine::default() };
    // (material, carbide SFM range, HSS SFM, chip load in inches a tooth at 1/8", 1/4", 3/8", 1/2")
    let charts = [
        (Material::Aluminium6061, (800.0, 1500.0), 600.0, [0.001, 0.002, 0.003, 0.004]),
        (Material::MildSteel, (100.0, 300.0), 75.0, [0.0005, 0.0015, 0.002, 0.003]),
        (Material::Stainless304, (100.0, 250.0), 55.0, [0.0001, 0.0005, 0.001, 0.0015]),
        (Material::Brass, (800.0, 1500.0), 600.0, [0.001, 0.002, 0.0025, 0.003]),
    ];
    eprintln!("| material | tool | made of | swarf: SFM (m/min) | rpm | in a tooth | mm/min | chart: SFM | chart: in a tooth | |");
    eprintln!("|---|---|---|---|---|---|---|---|---|---|");
    for (material, (lo, hi), hss, chips) in charts {
        let flutes = if matches!(material, Material::MildSteel | Material::Stainless304) { 4 } else { 2 };
        for (k, (d, ball)) in [(3.175, false), (6.35, false), (9.525, false), (12.7, false), (6.35, true)].into_iter().enumerate() {
            for made in [ToolMaterial::Carbide, ToolMaterial::Hss] {
                let cutter = if ball { Cutter::ball(d) } else { Cutter::flat(d) };
                let tool = Tool { cutter, tool_material: made, ..mill(d, flutes) };
                let depth = ball.then_some(0.5);
                let c = cutting_data_at(&tool, Some(material), &open, depth);
                let at = depth.map_or(d, |a| 2.0 * (a * (d - a)).sqrt());
                let sfm = PI * at * c.spindle_rpm / 1000.0 / SFM;
                let ipt = c.feed_rate / (c.spindle_rpm * flutes as f64) / IN;
                let chip = chips[if ball { 1 } else { k }];
                let (chart_sfm, within) = match made {
                    ToolMaterial::Hss => (format!("{hss}"), (sfm - hss).abs() / hss < 0.01),
                    _ => (format!("{lo}–{hi}"), sfm >= lo * 0.99 && sfm <= hi * 1.01),
                };
                let chip_ok = (ipt - chip).abs() / chip < 0.02;
                assert!(within && chip_ok, "{material:?} φ{d} {made:?}: {sfm:.0} SFM, {ipt:.4} in a tooth: {}", c.reason);
                let tool_words = if ball { format!("φ{d} ball, 0.5 mm deep (φ{at:.2} cutting)") } else { format!("φ{d} flat") };
                eprintln!(
                    "| {} | {tool_words}, {flutes} fl | {} | {sfm:.0} ({:.0}) | {:.0} | {ipt:.4} | {:.0} | {chart_sfm} | {chip} | within |",
                    material.words(),
                    made.words(),
                    sfm * SFM,
                    c.spindle_rpm,
                    c.feed_rate
                );
            }
        }
    }
}
