//! Jobs as machining sequences: operations plan in one context, see the stock the earlier ones
//! left (entering just above it), share z-maps, and make one program with tool changes; bad
//! jobs get messages that name the field or the operation.

use swarf::cutter::Cutter;
use swarf::error::{Error, ErrorKind};
use swarf::geom::DVec2;
use swarf::job::{self, FinishRaster, Job, Operation, Simulation, Tool};
use swarf::mesh::sample::demo_part;
use swarf::operations::Pocket2d;
use swarf::operations::Profile2d;
use swarf::progress::Progress;
use swarf::toolpath::Move;

fn ball(number: u32, diameter: f64) -> Tool {
    Tool { number, name: format!("{diameter} mm ball"), cutter: Cutter::ball(diameter), ..Tool::default() }
}

fn raster(name: &str, tool: u32, stepover: f64, allowance: f64, grid: f64) -> Operation {
    Operation::FinishRaster(FinishRaster { name: name.into(), tool, stepover, allowance, grid, ..FinishRaster::default() })
}

/// A coarse raster with a φ6 ball leaving 0.3 mm, then a fine one with a φ3 ball.
fn two_rasters() -> Job {
    Job {
        tools: vec![ball(1, 6.0), ball(2, 3.0)],
        operations: vec![raster("coarse", 1, 1.5, 0.3, 0.5), raster("fine", 2, 0.75, 0.0, 0.5)],
        simulation: Simulation { verify: true, cell: Some(0.25), ..Default::default() },
        ..Job::default()
    }
}

#[test]
fn a_two_tool_raster_sequence_enters_just_above_the_stock_the_first_left() {
    let job = two_rasters();
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert_eq!(out.paths.len(), 2);
    assert_eq!(out.path_operations, vec![0, 1]);
    assert_eq!((out.paths[0].tool, out.paths[1].tool), (1, 2));
    // One program with a tool change to T2 and its length offset.
    let t2 = out.gcode.find("T2 M6").expect("a tool change to T2");
    assert!(out.gcode[t2..].starts_with("T2 M6\nG43 H2"), "{}", &out.gcode[t2..t2 + 20]);
    assert!(out.gcode.find("T1 M6").unwrap() < t2);

    // The stock the first operation left, simulated on its own at the same cell.
    let first = Job { operations: vec![job.operations[0].clone()], ..job.clone() };
    let left = job::run(&first, demo_part(), &mut Progress::none()).unwrap().verification.unwrap().stock;
    let fine = Cutter::ball(3.0).profile();
    let (stock_top, gap) = (out.stock.max.z, job.stock.retract);
    let mut at = out.paths[1].start;
    let (mut descents, mut below_raw_top, mut across, mut low_across) = (0, 0, 0, 0);
    for (k, m) in out.paths[1].moves.iter().enumerate() {
        if let Move::Rapid { to } = *m {
            if to.truncate() != at.truncate() {
                // Across level (a control may move its axes one by one), the gap above the
                // material anywhere on the way (the short retract), never higher than the
                // clearance.
                assert!((to.z - at.z).abs() < 1e-12, "a slanting rapid {at} -> {to}");
                let material = left.touch_along(at.truncate(), to.truncate(), &fine, true);
                assert!(to.z >= material + gap - 1e-9 && to.z <= out.clearance_z + 1e-9, "across at {} from {at} to {to}, the material on the way at {material}", to.z);
                across += 1;
                if to.z < stock_top {
                    low_across += 1;
                }
            }
            if to.z < at.z && to.truncate() == at.truncate() {
                // A rapid descent stops the gap above the material that is really there, or
                // above the start when that is higher (then it feeds straight down to it).
                let material = left.touch(to.truncate(), &fine, true);
                let next = out.paths[1].moves[k + 1];
                let above_start = matches!(next, Move::Line { to: p, .. } if p.truncate() == to.truncate() && (to.z - gap - p.z).abs() < 1e-9 && p.z >= material);
                assert!((to.z - (material + gap)).abs() < 1e-9 || above_start, "descent to {} at {}, the material there is at {material}, then {next:?}", to.z, to.truncate());
                // ... and never into it.
                assert!(to.z > material, "{to}");
                descents += 1;
                if to.z < stock_top + gap - 1.0 {
                    below_raw_top += 1;
                }
            }
        }
        at = m.to();
    }
    assert!(descents > 0);
    assert!(below_raw_top * 2 > descents, "{below_raw_top} of {descents} descents went below the raw block's top");
    assert!(low_across * 2 > across, "{low_across} of {across} rapids across went below the raw block's top");
    // The report per operation adds up to the program.
    let ops = &out.operations;
    assert_eq!(ops.len(), 2);
    assert_eq!(ops[0].moves + ops[1].moves, out.moves.len());
    let removed: f64 = ops.iter().map(|o| o.removed.unwrap()).sum();
    assert!((removed - v.report.removed).abs() < 1e-6 * v.report.removed);
    // Their times are the program's (the paths as the post wrote them, each with its way down
    // from the clearance height): the moves' and a little more.
    assert!((ops[0].seconds + ops[1].seconds - out.cycle.paths.iter().sum::<f64>()).abs() < 1e-6);
    let moves: f64 = out.moves.iter().map(|m| m.seconds).sum();
    assert!(ops[0].seconds + ops[1].seconds >= moves - 1e-6 && ops[0].seconds + ops[1].seconds < moves + 10.0, "{ops:?} against {moves} s of moves");
    assert!(ops[0].removed.unwrap() > 10.0 * ops[1].removed.unwrap(), "{ops:?}");
    // The coarse pass leaves its allowance and more (scallops); the fine one takes it down.
    assert!(ops[0].left_max.unwrap() > 0.3 && ops[1].left_mean.unwrap() < ops[0].left_mean.unwrap(), "{ops:?}");
}

/// With full retracts (clamps the stock does not show), every rapid across goes at the
/// clearance height; with the default minimum ones the same job is quicker.
#[test]
fn full_retracts_travel_at_the_clearance_height() {
    let mut job = two_rasters();
    let minimum = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    job.stock.retracts = swarf::job::Retracts::Full;
    let full = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert!(full.verification.as_ref().unwrap().report.is_clean());
    let across = |out: &swarf::job::JobOutput| {
        let mut heights = Vec::new();
        for path in &out.paths {
            let mut at = path.start;
            for m in &path.moves {
                if let Move::Rapid { to } = *m {
                    if to.truncate() != at.truncate() {
                        heights.push(to.z);
                    }
                }
                at = m.to();
            }
        }
        heights
    };
    let (low, high) = (across(&minimum), across(&full));
    assert!(!high.is_empty() && high.iter().all(|&z| (z - full.clearance_z).abs() < 1e-9), "{high:?}");
    assert!(low.iter().any(|&z| z < minimum.clearance_z - 1.0), "{low:?}");
    let seconds = |out: &swarf::job::JobOutput| out.moves.iter().map(|m| m.seconds).sum::<f64>();
    assert!(seconds(&minimum) < seconds(&full), "{} s with minimum retracts, {} s with full ones", seconds(&minimum), seconds(&full));
}

#[test]
fn a_second_operation_on_the_same_cutter_and_grid_gets_its_z_map_from_the_cache() {
    let job = Job {
        tools: vec![ball(1, 6.0)],
        operations: vec![raster("across", 1, 2.0, 0.0, 0.5), Operation::FinishRaster(FinishRaster { name: "along".into(), angle: 90.0, stepover: 2.0, grid: 0.5, ..FinishRaster::default() })],
        simulation: Simulation { verify: false, cell: Some(0.5), ..Default::default() },
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert_eq!((out.cache.hits, out.cache.misses), (1, 1));
    assert_eq!(out.paths.len(), 2);
}

#[test]
fn rest_only_cuts_only_where_the_earlier_operations_left_material() {
    let mut job = two_rasters();
    job.tools = vec![ball(1, 6.0)];
    job.operations = vec![raster("first", 1, 1.0, 0.0, 0.5), raster("again", 1, 1.0, 0.0, 0.5)];
    let Operation::FinishRaster(again) = &mut job.operations[1] else { unreachable!() };
    again.rest_only = true;
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert!(out.verification.as_ref().unwrap().report.is_clean());
    // The same cutter over the same passes finds (nearly) nothing left.
    let ops = &out.operations;
    assert!(ops[1].feed_length < 0.05 * ops[0].feed_length, "{ops:?}");
    assert!(ops[1].removed.unwrap() < 1e-3 * ops[0].removed.unwrap().max(1.0) + 1.0, "{ops:?}");
}

#[test]
fn no_flat_or_bull_nose_end_feeds_straight_down_into_material() {
    for cutter in [Cutter::flat(6.0), Cutter::bull_nose(6.0, 1.0), Cutter::ball(6.0)] {
        let job = Job {
            tools: vec![Tool { cutter: cutter.clone(), ..Tool::default() }],
            operations: vec![raster("finish", 1, 2.0, 0.0, 0.5)],
            simulation: Simulation { verify: true, cell: Some(0.5), ..Default::default() },
            ..Job::default()
        };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{}: {}", cutter.describe(), v.report.describe());
        // Every vertical feed removes (nearly) nothing: entries into material are helices or ramps.
        for (m, &vol) in out.moves.iter().zip(&v.volumes) {
            if let Move::Line { to, .. } = m.mv {
                if to.truncate().distance(m.from.truncate()) < 1e-9 && to.z < m.from.z {
                    assert!(vol < 0.05, "{}: a straight plunge to {to} removed {vol} mm³", cutter.describe());
                }
            }
        }
        assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    }
}

/// The sample mould job with its finisher a flat end or a bull nose: after the roughing, some
/// raster runs start at the stock's edge or in a shallow step too short to ramp on as before;
/// they are entered from the air beside the stock or by a ramp of a few legs, never by a feed
/// straight down into material.
#[test]
fn the_mould_job_with_a_flat_or_bull_nose_finisher_never_plunges() {
    for cutter in [Cutter::flat(6.0), Cutter::bull_nose(6.0, 1.0)] {
        let mut job = Job::demo();
        job.tools[1].cutter = Cutter { flute_length: 30.0, ..cutter.clone() };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{}: {}", cutter.describe(), v.report.describe());
        assert!(out.warnings.iter().all(|w| !w.message.contains("straight down")), "{}: {:?}", cutter.describe(), out.warnings);
        for (m, &vol) in out.moves.iter().zip(&v.volumes) {
            if let Move::Line { to, .. } = m.mv {
                if to.truncate().distance(m.from.truncate()) < 1e-9 && to.z < m.from.z {
                    assert!(vol < 0.05, "{}: a straight plunge to {to} removed {vol} mm³", cutter.describe());
                }
            }
        }
    }
}

#[test]
fn a_pocket_then_a_profile_with_two_tools_make_one_clean_program() {
    use swarf::drawing::import::read_drawing;
    use swarf::drawing::sample::plate_dxf;
    let drawing = read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Default::default()).unwrap();
    let mut job = Job::default_for_drawing();
    job.tools = vec![Tool { number: 4, cutter: Cutter::flat(6.0), ..Tool::default() }, Tool { number: 2, cutter: Cutter::flat(3.0), ..Tool::default() }];
    job.operations = vec![
        Operation::Pocket2d(Pocket2d { tool: 4, layers: vec!["POCKET".into()], ..Pocket2d::default() }),
        Operation::Profile2d(Profile2d { tool: 2, layers: vec!["CUT".into()], ..Profile2d::default() }),
    ];
    let out = job::run(&job, drawing, &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert!(out.gcode.contains("T4 M6") && out.gcode.contains("T2 M6"));
    assert_eq!(out.operations.iter().map(|o| o.tools.clone()).collect::<Vec<_>>(), vec![vec![4], vec![2]]);
    assert!(out.operations.iter().all(|o| o.removed.unwrap() > 0.0));
}

#[test]
fn bad_jobs_get_messages_naming_the_field_or_the_operation() {
    let part = demo_part;
    let run = |job: &Job| job::run(job, part(), &mut Progress::none()).unwrap_err();
    // A missing tool number.
    let mut job = two_rasters();
    job.operations[1] = raster("fine", 7, 0.75, 0.0, 0.5);
    let e = run(&job);
    assert_eq!(e.kind(), ErrorKind::Input);
    assert_eq!(e.to_string(), "operations[1].tool: no tool number 7 in the tool library (it has 1, 2)");
    // A bad setting, named by its path.
    let mut job = two_rasters();
    job.operations[1] = raster("fine", 2, -1.0, 0.0, 0.5);
    assert!(run(&job).to_string().contains("operations[1].stepover must be a positive number, at most 10000 (got -1)"), "{}", run(&job));
    let mut job = two_rasters();
    job.tools[1].feed_rate = 0.0;
    assert!(run(&job).to_string().contains("tools[1].feedRate must be a positive number"), "{}", run(&job));
    let mut job = two_rasters();
    job.tools[1].number = 1;
    assert!(run(&job).to_string().contains("tools[1].number: tools[0] has the number 1 too"), "{}", run(&job));
    // An operation that cannot be done: a 2.5D operation on a part, a tool too big for a pocket.
    let mut job = two_rasters();
    job.operations.push(Operation::Pocket2d(Pocket2d { tool: 1, ..Pocket2d::default() }));
    let e = run(&job);
    assert!(matches!(&e, Error::Operation { operation, .. } if operation == "pocket"), "{e}");
    assert_eq!(e.kind(), ErrorKind::Operation);
    use swarf::drawing::import::read_drawing;
    use swarf::drawing::sample::plate_dxf;
    let drawing = read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Default::default()).unwrap();
    let mut job = Job::default_for_drawing();
    job.tools = vec![Tool { cutter: Cutter::flat(200.0), ..Tool::default() }];
    job.operations = vec![Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], ..Pocket2d::default() })];
    let e = job::run(&job, drawing, &mut Progress::none()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Operation, "{e}");
    assert!(e.to_string().starts_with("pocket: ") && e.to_string().contains("does not fit"), "{e}");
    // An unknown kind in a job file.
    let e = Job::from_json(r#"{"operations": [{"kind": "finishRastr"}]}"#).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Input);
    assert!(e.to_string().contains("operations[0]") && e.to_string().contains("finishRastr"), "{e}");
}

#[test]
fn the_work_zero_moves_part_and_stock() {
    use swarf::job::{WorkZero, ZeroCorner, ZeroHeight};
    let mut job = two_rasters();
    job.operations.truncate(1);
    job.simulation.verify = false;
    job.stock.zero = Some(WorkZero { height: ZeroHeight::StockBottom, corner: ZeroCorner::FrontLeft, at: None });
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    assert!(out.stock.min.distance(swarf::geom::DVec3::ZERO) < 1e-9, "{:?}", out.stock);
    // Nothing below the stock's bottom, nothing beyond its front and left sides but entries
    // (a helix about a start near the edge may reach past it, in the air).
    let bad: Vec<_> = out.paths[0].moves.iter().filter(|m| !(m.to().z >= -1e-9 && m.to().x >= -6.0 && m.to().y >= -6.0)).take(3).collect();
    assert!(bad.is_empty(), "{bad:?} {:?}", out.stock);
    let b = out.part.bounds();
    assert!((b.min.x - 5.0).abs() < 1e-9 && (b.min.y - 5.0).abs() < 1e-9 && b.min.z.abs() < 1e-9, "{b:?}");
    let _ = DVec2::ZERO;
}

#[test]
fn a_second_pocket_deeper_in_the_same_loops_starts_where_the_first_stopped() {
    use swarf::drawing::import::read_drawing;
    use swarf::drawing::sample::plate_dxf;
    let drawing = read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Default::default()).unwrap();
    let mut job = Job::default_for_drawing();
    job.tools = vec![Tool { number: 1, cutter: Cutter::flat(6.0), ..Tool::default() }];
    let pocket = |name: &str, depth: f64| Operation::Pocket2d(Pocket2d { name: name.into(), tool: 1, depth, stepdown: 1.0, layers: vec!["POCKET".into()], ..Pocket2d::default() });
    // The pocket's outline (not its island) cut inside, deeper, with no lead arc (one would
    // reach the island).
    let outline = drawing.loops.iter().position(|l| l.layer == "POCKET" && l.path.bounds().size().x > 30.0).unwrap();
    let wall = Profile2d {
        name: "wall".into(),
        tool: 1,
        side: swarf::operations::Side::Inside,
        depth: Some(5.0),
        loops: vec![outline],
        lead_radius: Some(0.0),
        layers: vec!["POCKET".into()],
        ..Profile2d::default()
    };
    job.operations = vec![pocket("first", 2.0), pocket("deeper", 4.0), pocket("again", 4.0), Operation::Profile2d(wall)];
    let out = job::run(&job, drawing, &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    // The third pocket finds nothing left and says so.
    assert_eq!(out.path_operations, vec![0, 1, 3]);
    assert!(out.warnings.iter().any(|w| w.operation.as_deref() == Some("again") && w.message.contains("no material left")), "{:?}", out.warnings);
    // The second enters a gap above the first one's floor, never from the sheet's top, and
    // never feeds through the 2 mm the first one cleared.
    // So does the profile along the pocket's walls, below the second one's floor.
    let gap = job.stock.retract;
    for (path, floor) in [(&out.paths[1], -2.0), (&out.paths[2], -4.0)] {
        let mut at = path.start;
        let mut descents = 0;
        for m in &path.moves {
            let to = m.to();
            match m {
                Move::Rapid { .. } if to.z < at.z && to.truncate() == at.truncate() => {
                    assert!(to.z <= floor + gap + 1e-9, "{}: a rapid descent stops at {to}, above the floor before plus the gap", path.name);
                    descents += 1;
                }
                Move::Rapid { .. } => {}
                _ => assert!(to.z <= floor + 1e-9 || to.truncate() == at.truncate(), "{}: a feed at {to} above the floor before", path.name),
            }
            at = to;
        }
        assert!(descents > 0);
    }
    // Each takes off about the same: 2 mm over the same region.
    let (a, b) = (out.operations[0].removed.unwrap(), out.operations[1].removed.unwrap());
    assert!((a - b).abs() < 0.05 * a, "{a} {b}");
    assert!(out.operations[1].seconds < out.operations[0].seconds * 1.2, "{:?}", out.operations);
}

/// The cycle time adds up: the program's head breaks it into the operations, the tool changes
/// and the rest, whose whole seconds sum to the total it states; the job's per-operation times
/// are the head's (once 1–2 s off, and the page's "1:00:51 (1:00:33 of moves + 15 s)" did not
/// add up), with a dwell and a slow tool change counted where they belong.
#[test]
fn the_cycle_time_adds_up_in_the_programs_head_and_the_report() {
    let mut job = two_rasters();
    job.post.dialect = swarf::post::Dialect::Fanuc; // a spindle dwell of 2 s at each start
    job.post.tool_change_seconds = 40.0;
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let clock = |t: &str| t.split(':').fold(0u64, |acc, v| acc * 60 + v.trim().parse::<u64>().unwrap());
    let head: Vec<&str> = out.gcode.lines().take(20).collect();
    let total_line = head.iter().find(|l| l.contains("cycle time")).expect("the head states the cycle time");
    let total = clock(total_line.split("cycle time ").nth(1).unwrap().split(' ').next().unwrap());
    let items: Vec<(String, u64)> = head
        .iter()
        .filter(|l| l.contains("(  "))
        .map(|l| {
            let inner = l.split("(  ").nth(1).unwrap().trim_end_matches(')');
            let (label, t) = inner.rsplit_once(": ").unwrap();
            (label.to_owned(), clock(t))
        })
        .collect();
    assert_eq!(items.iter().map(|i| i.1).sum::<u64>(), total, "{items:?} against {total}");
    assert_eq!(total, out.cycle.seconds.round() as u64);
    assert_eq!(items.iter().map(|i| (i.0.clone(), i.1)).collect::<Vec<_>>(), out.time.iter().map(|i| (i.label.clone(), i.seconds)).collect::<Vec<_>>());
    let labels: Vec<&str> = items.iter().map(|i| i.0.as_str()).collect();
    assert_eq!(labels, ["coarse with T1", "fine with T2", "1 tool change", "retracts and spindle starts"]);
    assert_eq!(items[2].1, 40);
    assert!(items[3].1 >= 4, "two dwells of 2 s: {items:?}");
    // The report's operations take the head's times.
    for (op, item) in out.operations.iter().zip(&items) {
        assert!((op.seconds - item.1 as f64).abs() <= 1.0, "{} {} against {}", op.name, op.seconds, item.1);
    }
    let parts = out.cycle.paths.iter().sum::<f64>() + out.cycle.tool_change_seconds + out.cycle.other_seconds;
    assert!((parts - out.cycle.seconds).abs() < 1e-9);
}
