//! Setups (issue 57): a part machined from both sides, each setup from the stock the one before
//! left, each program verified and read by the controls.

mod common;

use swarf::job::{run_setups, Job, Operation};
use swarf::mesh::sample::two_sided_part;
use swarf::progress::Progress;
use swarf::sim::StockModel;

/// The two-sided job's operation named `name` (its top setup's): "face", "rough", "drill" or
/// "finish".
fn op(name: &str) -> swarf::job::Operation {
    Job::two_sided().setups[0].operations.iter().find(|o| o.name() == name).cloned().unwrap()
}

/// The two-sided job with only its roughing and finishing on each side: for parts without its
/// holes, or whose stock's top is the part's.
fn milled_only() -> Job {
    let mut job = Job::two_sided();
    for s in &mut job.setups {
        s.operations.retain(|o| matches!(o.name(), "rough" | "finish"));
    }
    job
}

#[test]
fn a_plate_with_features_on_both_sides_is_machined_in_two_setups() {
    let job = Job::two_sided();
    let part = two_sided_part();
    let t = std::time::Instant::now();
    let setups = run_setups(&job, part.clone(), &mut Progress::none()).unwrap();
    eprintln!("planned in {:.1} s", t.elapsed().as_secs_f64());
    assert_eq!(setups.len(), 2);
    for s in &setups {
        let v = s.output.verification.as_ref().unwrap();
        eprintln!(
            "{}: {} moves, removed {:.0} mm³, left {:.3} mm at most, cycle {:.0} s, {}",
            s.name,
            s.output.moves.len(),
            v.volumes.iter().sum::<f64>(),
            v.report.residual_max,
            s.output.cycle.seconds,
            v.report.describe()
        );
        common::clean(&s.output);
    }
    assert!(setups[0].output.gcode.contains("\nG54\n"));
    assert!(setups[1].output.gcode.contains("\nG55\n"));
    // Each side's holes drilled from that side: the four φ5.5 through the corners from the top
    // (the boss's hole opens downwards there: not one to drill), the boss's φ4.2 from below;
    // at the end of each setup every hole it sees is empty down to its bottom, and at the end
    // the through holes are empty all through (the top's stock under them faced and roughed
    // away from below).
    for (k, (s, (seen, tool, not))) in setups.iter().zip([(4, "T3", "T4"), (5, "T4", "T3")]).enumerate() {
        let holes = swarf::holes::mesh::find(&s.output.part);
        assert_eq!(holes.len(), seen, "{}: {holes:?}", s.name);
        assert!(s.output.gcode.contains(&format!("{tool} M6")) && !s.output.gcode.contains(&format!("{not} M6")), "{}", s.name);
        let stock = &s.output.verification.as_ref().unwrap().stock;
        let g = stock.grid();
        for h in &holes {
            let c = g.nearest(h.center).unwrap();
            let (i, j) = (c % g.nx, c / g.nx);
            let (floor, top) = (stock.floor(i, j), stock.top(i, j));
            assert!(top <= h.bottom + 1e-6 && (k == 0 || !h.through || top <= floor), "{}: the hole at {:?} holds material from {floor} to {top}", s.name, h.center);
        }
    }
    assert!(setups[1].output.verification.as_ref().unwrap().report.residual_max < 3.5, "the bottom's stock carried a cell off at the holes' rims");
    // The stock carried exactly: what both setups removed and what the second left add up to
    // the raw block, and what is left holds the part.
    let raw = setups[0].output.stock;
    let block = raw.size().x * raw.size().y * raw.size().z;
    let removed: f64 = setups.iter().map(|s| s.output.verification.as_ref().unwrap().volumes.iter().sum::<f64>()).sum();
    let left = setups[1].output.verification.as_ref().unwrap().stock.volume();
    // Between its top and bottom: each facet's area seen from above (up positive, down
    // negative) times its mean height; walls add nothing.
    let solid: f64 = part.triangles().map(|t| (t.b - t.a).cross(t.c - t.a).z / 2.0 * (t.a.z + t.b.z + t.c.z) / 3.0).sum();
    eprintln!("block {block:.0} mm³, removed {removed:.0}, left {left:.0}, part {solid:.0}");
    assert!((removed + left - block).abs() < 1e-6 * block, "the second setup removed material the first had taken, or none it had left");
    assert!(left > solid, "the part is cut into: {left} mm³ left of a {solid} mm³ part");
    // Left over: the roughing's 0.5 mm on the outside walls (260 mm round, 18 mm high), which
    // the raster does not finish, and at most 0.1 mm over the faces both setups finish.
    let over = 0.5 * 260.0 * 18.0 + 0.1 * 2.0 * 80.0 * 50.0;
    assert!(left - solid < over, "{} mm³ left over the part", left - solid);
    // Without the carried stock the second setup would cut the air round the part again.
    let bottom = setups[1].output.verification.as_ref().unwrap().volumes.iter().sum::<f64>();
    assert!(bottom < 0.6 * (block - solid), "{bottom}");
    // Both programs are ones LinuxCNC's interpreter reads, each in its own work offset; written
    // for GRBL, GRBL's own parser reads them; and OpenCAMLib's drop cutter (the shared tools'
    // gcheck.py) finds no gouge in either against the part as its setup holds it.
    for s in &setups {
        let canon = common::rs274(&s.output.gcode, &job.tools);
        assert!(canon.contains("STRAIGHT_FEED"), "{}", s.name);
        let grbl = swarf::post::PostSettings { dialect: swarf::post::Dialect::Grbl, ..job.post.clone() };
        let gcode = swarf::post::write_gcode(&s.name, &s.output.paths, &job.tools, s.output.clearance_z, &grbl).unwrap();
        if let Some(said) = common::grblcheck(&gcode) {
            said.unwrap_or_else(|e| panic!("{}: {e}", s.name));
        }
        // The drop cutter judges the milling: a drill the size of its hole reaches past the
        // facets inscribed in the hole's circle (by their sagitta) all the way down, which a
        // drop onto the facets takes for a gouge; the simulation judges the drilling (above).
        let milled: Vec<_> = s.output.paths.iter().filter(|p| job.tools.iter().any(|t| t.number == p.tool && !matches!(t.cutter.shape, swarf::cutter::Shape::Drill))).cloned().collect();
        assert_eq!(milled.len(), s.output.paths.len() - 1, "{}", s.name);
        let milling = swarf::post::write_gcode(&s.name, &milled, &job.tools, s.output.clearance_z, &job.post).unwrap();
        if let Some(said) = common::gcheck(&milling, &s.output.part, &job.tools) {
            assert!(said.contains("gcheck: OK"), "{}: {said}", s.name);
        }
    }
}

/// Three setups: the top, the same face turned a quarter (carried exactly), then the part
/// turned over about Y: what they remove and what is left still add up to the block, the
/// programs stay clean, and the job file reads back the same.
#[test]
fn a_turn_and_a_flip_about_y_carry_the_stock_too() {
    use swarf::job::{Flip, Setup};
    let mut job = Job::two_sided();
    let (rough, finish) = (op("rough"), op("finish"));
    job.setups = vec![
        Setup { name: "rough top".into(), operations: vec![rough.clone()], ..Setup::default() },
        Setup { name: "finish top".into(), turn: 90, work_offset: Some("G56".into()), operations: vec![finish], ..Setup::default() },
        Setup { name: "bottom".into(), flip: Flip::AboutY, turn: 270, work_offset: Some("G57".into()), operations: vec![rough], ..Setup::default() },
    ];
    let text = serde_json::to_string(&job).unwrap();
    assert_eq!(Job::from_json(&text).unwrap(), job);
    let setups = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let raw = setups[0].output.stock;
    let block = raw.size().x * raw.size().y * raw.size().z;
    let removed: Vec<f64> = setups.iter().map(|s| s.output.verification.as_ref().unwrap().volumes.iter().sum::<f64>()).collect();
    let left = setups[2].output.verification.as_ref().unwrap().stock.volume();
    eprintln!("removed {removed:?}, left {left:.0} of {block:.0}");
    assert!((removed.iter().sum::<f64>() + left - block).abs() < 1e-6 * block);
    for s in &setups {
        common::clean(&s.output);
    }
    // Turned a quarter, the stock box is too: 56 × 86 where the first setup's is 86 × 56.
    let turned = setups[1].output.stock.size();
    assert!((turned.x - raw.size().y).abs() < 1e-9 && (turned.y - raw.size().x).abs() < 1e-9, "{turned}");
    // The finish removes only what the roughing left, far less than the roughing did.
    assert!(removed[1] < 0.3 * removed[0], "{removed:?}");
    assert!(setups[1].output.gcode.contains("\nG56\n") && setups[2].output.gcode.contains("\nG57\n"));
}

/// Setup settings are checked as every field is, named by their path, and a job of setups
/// does not also list operations beside them.
#[test]
fn setups_are_checked_before_any_work() {
    let mut job = Job::two_sided();
    job.setups[1].work_offset = Some("G92".into());
    job.setups[1].turn = 45;
    job.setups[0].operations[0] = swarf::job::Operation::FinishRaster(swarf::job::FinishRaster { tool: 9, ..Default::default() });
    let problems: Vec<String> = job.problems().into_iter().map(|p| p.path).collect();
    assert_eq!(problems, ["setups[0].operations[0].tool", "setups[1].turn", "setups[1].workOffset"]);
    let e = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("setups[0].operations[0].tool: no tool number 9"), "{e}");
    let mut text: serde_json::Value = serde_json::to_value(Job::two_sided()).unwrap();
    text["operations"] = serde_json::to_value(Job::demo().operations).unwrap();
    let e = Job::from_json(&text.to_string()).unwrap_err().to_string();
    assert!(e.contains("lists its operations in each setup"), "{e}");
    // A job of setups is not run as one.
    let e = swarf::job::run(&Job::two_sided(), two_sided_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("2 setups"), "{e}");
}

/// The setup sheet says, for each setup, how to hold the part, its work offset and zero, the
/// stock, a picture from above, the tools and operations with their times, as the programs do.
#[test]
fn the_setup_sheet_says_how_to_hold_the_part_for_each_setup() {
    let job = Job::two_sided();
    let setups = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let sheets: Vec<_> = setups.iter().map(|s| swarf::job::sheet::SheetSetup::of(&s.name, &s.output)).collect();
    let sheet = swarf::job::sheet::setup_sheet(&job, "plate <2>.stl", &sheets);
    assert!(sheet.starts_with("<!doctype html>") && sheet.trim_end().ends_with("</html>"));
    assert!(sheet.contains("plate &lt;2&gt;.stl"), "the part's name is escaped");
    assert_eq!(sheet.matches("<section>").count(), 2);
    assert_eq!(sheet.matches("<svg ").count(), 2);
    assert!(sheet.contains("<h2>1: top</h2>") && sheet.contains("<h2>2: bottom</h2>"));
    assert!(sheet.contains("<td>G54</td>") && sheet.contains("<td>G55</td>"));
    assert!(sheet.contains("turn the part over about X"));
    assert!(sheet.contains("86.0 × 56.0 × 20.0 mm"));
    for s in &setups {
        // The program's head and the sheet give the same times.
        assert!(sheet.contains(&format!("cycle time {}", swarf::post::clock(s.output.cycle.seconds))), "{}", s.name);
        for item in &s.output.time {
            if item.seconds > 0 {
                assert!(s.output.gcode.contains(&format!("(  {}: {})", item.label, swarf::post::clock(item.seconds as f64))), "{}", item.label);
            }
            assert!(sheet.contains(&format!("<td>{}</td><td class=n>{}</td>", item.label, swarf::post::clock(item.seconds as f64))), "{}", item.label);
        }
    }
    let total: f64 = setups.iter().map(|s| s.output.cycle.seconds).sum();
    assert!(sheet.contains(&format!("cycle time {} in all", swarf::post::clock(total))));
    for tool in ["<tr><td>T1</td><td>6 mm flat end mill", "<tr><td>T2</td><td>6 mm ball end mill"] {
        assert_eq!(sheet.matches(tool).count(), 2, "{tool} in both setups");
    }
    // The part drawn in shades: the pocket (deep) darker than the plate's top.
    assert!(sheet.matches("<rect ").count() > 100);
}

/// A round solid: a cylinder of radius `r` about the Z axis from `bottom` to `top`, `n` sides.
fn puck(r: f64, bottom: f64, top: f64, n: usize) -> swarf::mesh::Mesh {
    use swarf::geom::DVec3;
    let rim = |k: usize, z: f64| {
        let t = std::f64::consts::TAU * k as f64 / n as f64;
        DVec3::new(r * t.cos(), r * t.sin(), z)
    };
    let mut tris = Vec::new();
    for k in 0..n {
        let (a, b) = (k, (k + 1) % n);
        tris.push([DVec3::new(0.0, 0.0, top), rim(a, top), rim(b, top)]);
        tris.push([DVec3::new(0.0, 0.0, bottom), rim(b, bottom), rim(a, bottom)]);
        tris.push([rim(a, bottom), rim(b, bottom), rim(b, top)]);
        tris.push([rim(a, bottom), rim(b, top), rim(a, top)]);
    }
    swarf::mesh::Mesh::from_triangles(tris, &swarf::geom::Tolerances::DEFAULT).unwrap()
}

/// Bar stock: a φ40 puck from a φ46 bar stood on end, and a block lying in a φ30 bar along X.
/// The bar's material is what the simulation starts from (the removed and the left add up to
/// the bar, not the box round it), the air round the bar is never cut (the program is shorter
/// than the same from the box) and a part that does not fit the bar is refused.
#[test]
fn bar_stock_is_round_and_its_air_is_not_cut() {
    use swarf::job::{Bar, BarAxis};
    let job_for = |bar: Option<Bar>| {
        let mut job = milled_only();
        let operations = job.setups[0].operations.clone();
        job.setups.clear();
        job.operations = operations;
        job.stock.bar = bar;
        job
    };
    let part = puck(20.0, -10.0, 0.0, 96);
    let bar = Bar { diameter: 46.0, axis: BarAxis::Z };
    let round = swarf::job::run(&job_for(Some(bar)), part.clone(), &mut Progress::none()).unwrap();
    let boxed = swarf::job::run(&job_for(None), part.clone(), &mut Progress::none()).unwrap();
    common::clean(&round);
    let v = round.verification.as_ref().unwrap();
    let size = round.stock.size();
    assert!((size.x - 46.0).abs() < 1e-9 && (size.y - 46.0).abs() < 1e-9, "the bar's box: {size}");
    let material = std::f64::consts::PI * 23.0 * 23.0 * size.z;
    let (removed, left) = (v.volumes.iter().sum::<f64>(), v.stock.volume());
    eprintln!("bar: removed {removed:.0} + left {left:.0} of {material:.0} mm³; cycle {:.0} s from the bar, {:.0} s from the box", round.cycle.seconds, boxed.cycle.seconds);
    assert!((removed + left - material).abs() < 0.01 * material, "{removed} + {left} against the bar's {material}");
    assert!(round.cycle.seconds < 0.9 * boxed.cycle.seconds, "{} s from the bar, {} s from the box", round.cycle.seconds, boxed.cycle.seconds);
    // The page's playback starts from the bar, not from the box round it: before the first
    // move a corner of the box holds no material, the bar's middle its whole height.
    let mut view = swarf::view::ResultView::of(&job_for(Some(bar)), round.clone());
    let g = v.stock.grid();
    let tops = view.simulation.as_mut().unwrap().playback.seek(0).to_vec();
    let (corner, middle) = (tops[0] as f64, tops[(g.ny / 2) * g.nx + g.nx / 2] as f64);
    assert!(corner <= round.stock.min.z + 1e-6, "a corner of the box starts at {corner}");
    assert!((middle - round.stock.max.z).abs() < 1e-4, "the bar's middle starts at {middle}");
    // Too thin a bar.
    let e = swarf::job::run(&job_for(Some(Bar { diameter: 39.0, ..bar })), part, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("outside a φ39 bar; choose a bar of at least φ40"), "{e}");
    // A block lying in a bar along X: the bar's round top is the stock's.
    let block = swarf::mesh::sample::height_field_solid(swarf::geom::DVec2::new(-30.0, -8.0), swarf::geom::DVec2::new(30.0, 8.0), 4, 4, -16.0, |_, _| 0.0);
    let lying = swarf::job::run(&job_for(Some(Bar { diameter: 30.0, axis: BarAxis::X })), block, &mut Progress::none()).unwrap();
    common::clean(&lying);
    let v = lying.verification.as_ref().unwrap();
    let size = lying.stock.size();
    let material = std::f64::consts::PI * 15.0 * 15.0 * size.x;
    let (removed, left) = (v.volumes.iter().sum::<f64>(), v.stock.volume());
    eprintln!("lying bar: removed {removed:.0} + left {left:.0} of {material:.0} mm³");
    assert!((size.y - 30.0).abs() < 1e-9 && (size.z - 30.0).abs() < 1e-9, "{size}");
    assert!((removed + left - material).abs() < 0.01 * material, "{removed} + {left} against the bar's {material}");
}

/// A part in a bar is held by the bar: a φ40 puck cut from the end of a φ46 bar stood on end
/// (the bar's round side is what holds it, as a vise's or a chuck's jaws do) is still joined to
/// the bar as the job ends, and the job says to part it off below the puck's bottom; roughed
/// down past its bottom with nothing left on the floor (the bar's air beside it as it came is
/// no side to hold it by) the job says it cuts the part free instead; a block in a bar lying
/// along X is held by the bar's sides as well.
#[test]
fn a_part_in_a_bar_is_held_by_the_bar_and_parted_off() {
    use swarf::job::{Bar, BarAxis};
    use swarf::operations::{HeightFrom, Heights};
    let job_for = |bar: Bar, bottom: Option<f64>, allowance: f64| {
        let mut job = milled_only();
        let mut operations = job.setups[0].operations.clone();
        job.setups.clear();
        for op in &mut operations {
            if let Operation::RoughZlevel(r) = op {
                r.roughing.heights = Heights { bottom, bottom_from: HeightFrom::StockBottom, ..Heights::default() };
                r.roughing.allowance = allowance;
            }
        }
        job.operations = operations;
        job.stock.bar = Some(bar);
        job.stock.margin_bottom = 6.0;
        job
    };
    let part = puck(20.0, -10.0, 0.0, 96);
    let bar = Bar { diameter: 46.0, axis: BarAxis::Z };
    let said = |out: &swarf::job::JobOutput| out.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n");
    let held = swarf::job::run(&job_for(bar, Some(3.0), 0.5), part.clone(), &mut Progress::none()).unwrap();
    let words = said(&held);
    eprintln!("{words}");
    assert!(words.contains("still joined to the φ46 bar") && words.contains("below its bottom (Z-10.000"), "{words}");
    assert!(!words.contains("cuts the part free"), "{words}");
    let freed = swarf::job::run(&job_for(bar, Some(-1.0), 0.0), part.clone(), &mut Progress::none()).unwrap();
    let words = said(&freed);
    let lowest = freed.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min);
    eprintln!("{words}\nlowest feed Z{lowest:.3}, stock {:?}", freed.stock);
    assert!(words.contains("cuts the part free") && !words.contains("still joined"), "{words}");
    let block = swarf::mesh::sample::height_field_solid(swarf::geom::DVec2::new(-30.0, -8.0), swarf::geom::DVec2::new(30.0, 8.0), 4, 4, -16.0, |_, _| 0.0);
    let lying = swarf::job::run(&job_for(Bar { diameter: 34.0, axis: BarAxis::X }, Some(3.0), 0.5), block, &mut Progress::none()).unwrap();
    let words = said(&lying);
    assert!(words.contains("still joined to the φ34 bar") && words.contains("below its bottom (Z-16.000"), "{words}");
}

/// A cast blank round the two-sided plate: its top 1 mm over the plate's, its sides drafted
/// down from the plate's edges (6 mm out in X, 4 in Y), its bottom 0.5 mm under the boss. In
/// the part's own coordinates, as a CAD model exports both.
fn cast_blank() -> swarf::mesh::Mesh {
    use swarf::geom::DVec2;
    swarf::mesh::sample::height_field_solid(DVec2::new(-46.0, -29.0), DVec2::new(46.0, 29.0), 92, 58, -18.5, |x, y| 1.0 - 1.5 * (x.abs() - 40.0).max(0.0) - 2.0 * (y.abs() - 25.0).max(0.0))
}

/// [`cast_blank`]'s volume: its 92 × 58 × 19.5 mm box less its drafts (the grid's nodes on their
/// edges, so its facets are exact).
const CAST_BLANK_VOLUME: f64 = 92.0 * 58.0 * 19.5 - 1.5 * (6.0 * 6.0) * 58.0 - 2.0 * (4.0 * 4.0) * 92.0;

/// Stock from a mesh (a casting): the job carries the file; the blank is placed with the part
/// (its top's centre at the origin, the part 1 mm under it as in the files); the simulation
/// starts from the blank's material, not its box (the removed and the left add up to the
/// blank); the air round the drafted sides is not cut (the program is shorter than the same
/// from the blank's box); both setups run from it and verify clean; a blank that cannot be
/// read is named at its field, and a part outside its blank is refused.
#[test]
fn a_cast_blank_is_the_stock_and_its_air_is_not_cut() {
    use swarf::job::blank::MeshFile;
    let blank = cast_blank();
    let file = MeshFile::embedded("casting.stl", &blank.to_binary_stl());
    let job_for = |mesh: Option<MeshFile>| {
        let mut job = milled_only();
        let operations = job.setups[0].operations.clone();
        job.setups.clear();
        job.operations = operations;
        job.stock.zero = None;
        job.stock.mesh = mesh;
        job
    };
    let job = job_for(Some(file.clone()));
    // The job carries the file through JSON.
    let back = Job::from_json(&serde_json::to_string(&job).unwrap()).unwrap();
    assert_eq!(back.stock.mesh.as_ref().map(|f| &f.name), Some(&"casting.stl".to_owned()));
    let cast = swarf::job::run(&back, two_sided_part(), &mut Progress::none()).unwrap();
    common::clean(&cast);
    // The stock's box is the blank's, its top at 0; the part's top 1 mm under it.
    let b = blank.bounds();
    assert!((cast.stock.size() - b.size()).length() < 1e-3 && cast.stock.max.z.abs() < 1e-4, "{:?}", cast.stock);
    let mut placed = two_sided_part();
    job.place(&mut placed);
    assert!((placed.bounds().max.z + 1.0).abs() < 1e-3, "{:?}", placed.bounds());
    let v = cast.verification.as_ref().unwrap();
    let material = CAST_BLANK_VOLUME;
    let (removed, left) = (v.volumes.iter().sum::<f64>(), v.stock.volume());
    let mut boxed_job = job_for(None);
    boxed_job.stock.size_box = Some(cast.stock);
    let boxed = swarf::job::run(&boxed_job, two_sided_part(), &mut Progress::none()).unwrap();
    eprintln!("cast blank: removed {removed:.0} + left {left:.0} of {material:.0} mm³; cycle {:.0} s from the blank, {:.0} s from its box", cast.cycle.seconds, boxed.cycle.seconds);
    assert!((removed + left - material).abs() < 0.01 * material, "{removed} + {left} against the blank's {material}");
    assert!(cast.cycle.seconds < 0.95 * boxed.cycle.seconds, "{} s from the blank, {} s from its box", cast.cycle.seconds, boxed.cycle.seconds);
    // Both sides from the blank: the second setup starts from what the first left.
    let mut two = Job::two_sided();
    two.stock.mesh = Some(file.clone());
    let sides = run_setups(&two, two_sided_part(), &mut Progress::none()).unwrap();
    for s in &sides {
        let v = s.output.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{}: {}", s.name, v.report.describe());
    }
    // A blank that cannot be read, and one the part does not fit.
    let bad = job_for(Some(MeshFile::embedded("casting.stl", b"solid")));
    let problems: Vec<String> = bad.problems().into_iter().map(|p| format!("{}: {}", p.path, p.message)).collect();
    assert!(problems.iter().any(|p| p.starts_with("stock.mesh:") && p.contains("casting.stl")), "{problems:?}");
    let small = swarf::mesh::sample::height_field_solid(swarf::geom::DVec2::new(-30.0, -20.0), swarf::geom::DVec2::new(30.0, 20.0), 4, 4, -18.5, |_, _| 1.0);
    let e = swarf::job::run(&job_for(Some(MeshFile::embedded("small.stl", &small.to_binary_stl()))), two_sided_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("at -X"), "{e}");
}

/// The page's pool runs a job with setups one setup at a time: every worker prepares that setup
/// (the part held as it holds it) and the planner carries in what the setup before left. The
/// programs and stocks are those of the job run whole, and each setup's playback starts from
/// the stock it was given.
#[test]
fn the_pool_runs_setups_one_at_a_time_as_the_job_runs_whole() {
    use swarf::job::wire::PoolWorker;
    use swarf::job::Workpiece;
    let job = Job::two_sided();
    let whole = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let mut before: Option<(swarf::sim::DexelStock, swarf::job::setups::Orientation)> = None;
    for (k, w) in whole.iter().enumerate() {
        let mut worker = PoolWorker::prepare_setup(&job, Workpiece::Mesh(two_sided_part()), k).unwrap();
        let place = worker.setup().unwrap().clone();
        assert_eq!((place.index, place.more, place.orientation), (k, k == 0, w.orientation));
        // The first setup has nothing to carry in.
        if let Some((left, from)) = &before {
            worker.carry_from(left, from).unwrap();
        }
        let out = worker.run(&mut Progress::none()).unwrap();
        assert_eq!(out.gcode, w.output.gcode, "setup {k}");
        let v = out.verification.clone().unwrap();
        assert_eq!(v.stock.heights().z, w.output.verification.as_ref().unwrap().stock.heights().z);
        assert_eq!(v.start.is_some(), k > 0);
        let mut view = swarf::view::ResultView::of(worker.job(), out);
        let start: Vec<f32> = view.simulation.as_mut().unwrap().playback.seek(0).to_vec();
        match &v.start {
            Some(s) => assert_eq!(start, s.heights().z.iter().map(|&z| z as f32).collect::<Vec<_>>()),
            None => assert!(start.iter().all(|&z| (z as f64 - w.output.stock.max.z).abs() < 1e-4)),
        }
        before = Some((v.stock, place.orientation));
    }
    // The frames a view shows before a run are those the run holds the part in.
    let mut placed = two_sided_part();
    job.part.apply(&mut placed);
    let frames = swarf::view::SetupView::frames(&job, &placed.bounds());
    for (f, w) in frames.iter().zip(&whole) {
        assert_eq!(f.rotation, w.orientation.rotation.to_cols_array());
        assert_eq!(f.shift, w.orientation.shift.to_array());
        assert_eq!(f.stock, w.output.stock);
    }
    // No such setup, a job's setup named for a job without setups, a drawing turned over.
    let e = PoolWorker::prepare_setup(&job, Workpiece::Mesh(two_sided_part()), 2).err().unwrap().to_string();
    assert!(e.contains("the job has 2 setups"), "{e}");
    let mut first = PoolWorker::prepare_setup(&job, Workpiece::Mesh(two_sided_part()), 0).unwrap();
    let (left, from) = before.unwrap();
    first.carry_from(&left, &from).unwrap();
    let mut plain = PoolWorker::prepare(Job::demo(), Workpiece::Mesh(swarf::mesh::sample::demo_part())).unwrap();
    assert!(plain.carry_from(&left, &from).is_err());
}

/// A third setup stands the plate on its front (its back up, `up: "+y"`) and finishes that side
/// (the roughing of the two before left its wall 0.5 mm):
/// it starts from all the material the two before left and no more than half a cell past it
/// (a column here is a line across their columns, each run of material through it a span of
/// its own, the cavities between air), its box is the raw block stood on end, and its program
/// is clean.
#[test]
fn a_setup_stands_the_part_on_its_side() {
    use swarf::job::{Setup, Up};
    let mut job = Job::two_sided();
    let finish = op("finish");
    job.setups.push(Setup { name: "back".into(), up: Some(Up::PlusY), work_offset: Some("G56".into()), operations: vec![finish], ..Setup::default() });
    let setups = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    assert_eq!(setups.len(), 3);
    let (raw, side) = (setups[0].output.stock.size(), setups[2].output.stock.size());
    assert!((side.x - raw.x).abs() < 1e-9 && (side.y - raw.z).abs() < 1e-9 && (side.z - raw.y).abs() < 1e-9, "{raw} stood on end is {side}");
    for s in &setups {
        common::clean(&s.output);
    }
    let v = setups[2].output.verification.as_ref().unwrap();
    let start = v.start.as_ref().expect("carried").volume();
    let left = setups[1].output.verification.as_ref().unwrap().stock.volume();
    let removed: f64 = v.volumes.iter().sum();
    eprintln!("the side setup starts from {start:.0} mm³ (the bottom left {left:.0}), removes {removed:.0}; {}", v.report.describe());
    assert!(start >= left - 1e-6 * left && start <= raw.x * raw.y * raw.z, "{start} against {left}");
    // The cavities the setups before cut (the pocket, the slot, the holes, seen from the side)
    // carried as air, each run of material only half a cell longer each way: within 1.5 % of
    // what was left (55,648 against 55,214 mm³; one span a column, the cavities filled, made it
    // 58,958, and the pocket alone is 3,000).
    assert!(start <= 1.015 * left, "{start} against {left}");
    let carried = v.start.as_ref().unwrap();
    let g = carried.grid();
    let hollow = (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).filter(|&(i, j)| carried.spans(i, j).count() > 1).count();
    assert!(hollow > 1000, "{hollow} columns cross a cavity");
    assert!(removed > 0.0 && (start - removed - v.stock.volume()).abs() < 1e-6 * start);
    assert!(setups[2].output.gcode.contains("\nG56\n"));
    let sheets: Vec<_> = setups.iter().map(|s| swarf::job::sheet::SheetSetup::of(&s.name, &s.output)).collect();
    assert!(swarf::job::sheet::setup_sheet(&job, "plate.stl", &sheets).contains("stand the part on its side, its back (+Y) face up"));
    // Both a face up and a flip: named.
    job.setups[2].flip = swarf::job::Flip::AboutX;
    assert_eq!(job.problems()[0].path, "setups[2].up");
}

/// A setup's work offset is one its control has: Fanuc's extended `G54.1 P7` is written as
/// such; GRBL 1.1 has no `G59.1` (LinuxCNC has), and the message says what it has.
#[test]
fn a_setups_work_offset_is_one_its_control_has() {
    use swarf::post::Dialect;
    let mut job = Job::two_sided();
    job.post.dialect = Dialect::Fanuc;
    job.setups[1].work_offset = Some("G54.1 P7".into());
    assert!(job.problems().is_empty(), "{:?}", job.problems());
    let setups = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    // (Fanuc numbers its lines.)
    assert!(setups[1].output.gcode.lines().any(|l| l.ends_with(" G54.1 P7")), "{}", &setups[1].output.gcode[..400]);
    let sheets: Vec<_> = setups.iter().map(|s| swarf::job::sheet::SheetSetup::of(&s.name, &s.output)).collect();
    assert_eq!(sheets[1].work_offset.as_deref(), Some("G54.1 P7"));
    job.setups[1].work_offset = Some("G54.1 P49".into());
    assert_eq!(job.problems()[0].message, "setups[1].workOffset must be one of G54 to G59, G54.1 P1 to G54.1 P48 (Fanuc) (got \"G54.1 P49\")");
    job.post.dialect = Dialect::Grbl;
    job.setups[1].work_offset = Some("G59.1".into());
    assert_eq!(job.problems()[0].message, "setups[1].workOffset must be one of G54 to G59 (GRBL 1.1) (got \"G59.1\")");
    job.post.dialect = Dialect::LinuxCnc;
    assert!(job.problems().is_empty());
}

/// What a setup's operations pick from is found in the part as that setup holds it: from the
/// top, the highest edge is the rim of the face round the pocket, under the dome; from below,
/// the boss's end (the plate's lowest face) is the highest face and its rim the highest edge.
#[test]
fn a_setup_finds_its_edges_in_the_part_as_it_holds_it() {
    let job = Job::two_sided();
    let highest = |k: usize| {
        let (sub, held, _) = job.for_setup(k, two_sided_part()).unwrap();
        let top = held.bounds().max.z;
        let edges = sub.top_edges(held).unwrap();
        eprintln!("setup {k}: {} top edges at z {:?}, the part's top at {top:.3}", edges.len(), edges.iter().map(|e| (e.z * 1000.0).round() / 1000.0).collect::<Vec<_>>());
        (edges.iter().map(|e| e.z).fold(f64::NEG_INFINITY, f64::max), top, edges.len())
    };
    let (top_edge, top_top, top_count) = highest(0);
    let (bottom_edge, bottom_top, bottom_count) = highest(1);
    assert!(top_count > 0 && bottom_count > 0);
    // From below, the boss's end is the part's top, and its rim the highest edge.
    assert!((bottom_edge - bottom_top).abs() < 1e-6, "{bottom_edge} against {bottom_top}");
    // From the top, the dome rises 1.5 mm above the face round the pocket, whose rim is the
    // highest edge (the part as placed: 2 edges; from below: the boss, the bottom face, the slot).
    assert!((top_top - top_edge - 1.5).abs() < 1e-6, "{top_edge} against {top_top}");
    assert_ne!(top_count, bottom_count);
    let (_, _, orientation) = job.for_setup(1, two_sided_part()).unwrap();
    assert_eq!(orientation.rotation.z_axis.z, -1.0);
    assert!(job.for_setup(2, two_sided_part()).is_err());
}

/// Every setup in one program (`post.oneProgram`): the setups' programs one after another, an
/// operator stop between them that says how to hold the part, where to set the zero and, on a
/// control without a tool changer, which tool to put in; one head and one end of program; the
/// lines numbered on where the post numbers them. LinuxCNC's interpreter and GRBL's parser
/// read it, and it cuts what the programs cut.
#[test]
fn every_setup_in_one_program_stops_between_them() {
    use swarf::post::{write_program, Dialect, PostSettings};
    let mut job = Job::two_sided();
    job.post.one_program = true;
    let setups = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let names = job.setup_names();
    // Each setup's program for `dialect`, as the job's own setups post it.
    let posted = |dialect: Dialect| -> Vec<(swarf::job::sheet::SheetSetup, String)> {
        setups
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let settings = PostSettings { dialect, work_offset: job.setups[k].work_offset.clone(), ..job.post.clone() };
                let (gcode, _) = write_program(&names[k], &s.output.paths, &job.tools, s.output.clearance_z, &settings).unwrap();
                (swarf::job::sheet::SheetSetup::of(&names[k], &s.output), gcode)
            })
            .collect()
    };
    let join = |dialect: Dialect| {
        let programs = posted(dialect);
        let mut j = job.clone();
        j.post.dialect = dialect;
        let refs: Vec<_> = programs.iter().map(|(s, g)| (s, g.as_str(), None)).collect();
        (swarf::job::setups::one_program(&j, &refs).unwrap(), programs)
    };
    let feeds = |canon: &str| canon.lines().filter(|l| l.contains("STRAIGHT_FEED") || l.contains("ARC_FEED")).count();

    // LinuxCNC: one end, one stop, the second setup's offset after it; the same cuts.
    let (one, programs) = join(Dialect::LinuxCnc);
    let lines: Vec<&str> = one.lines().collect();
    assert_eq!(lines.iter().filter(|l| **l == "M2").count(), 1);
    assert_eq!(*lines.last().unwrap(), "M2");
    let stop = lines.iter().position(|l| *l == "M0").expect("an operator stop between the setups");
    // The message: the comments over the stop.
    let said_over = |lines: &[&str], stop: usize| {
        lines[..stop].iter().rev().take_while(|l| l.starts_with('(')).map(|l| l.trim_matches(|c| c == '(' || c == ')')).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join(" ")
    };
    let said = said_over(&lines, stop);
    assert!(said.starts_with("setup 2 of 2, ") && said.contains("turn the part over about X") && said.contains("set the zero of G55"), "{said}");
    assert!(lines[..stop].contains(&"G54") && lines[stop..].contains(&"G55") && !lines[stop..].contains(&"G54"));
    let canon = common::rs274(&one, &job.tools);
    let apart: usize = programs.iter().map(|(_, g)| feeds(&common::rs274(g, &job.tools))).sum();
    assert_eq!(feeds(&canon), apart, "the joined program cuts what the setups' programs cut");
    assert!(canon.contains("PROGRAM_STOP") || canon.contains("PROGRAM_END"), "{canon:.300}");

    // Fanuc: the tape marks and the program number once, the lines numbered on without a
    // number coming back.
    let (one, _) = join(Dialect::Fanuc);
    let lines: Vec<&str> = one.lines().collect();
    assert_eq!(lines.first(), Some(&"%"));
    assert_eq!(lines.last(), Some(&"%"));
    assert_eq!(lines.iter().filter(|l| **l == "%").count(), 2);
    assert_eq!(lines.iter().filter(|l| l.starts_with('O')).count(), 1);
    let numbers: Vec<u64> = lines.iter().filter_map(|l| l.strip_prefix('N')?.split(' ').next()?.parse().ok()).collect();
    assert!(numbers.len() > 100 && numbers.windows(2).all(|w| w[0] < w[1]), "line numbers come back");
    assert_eq!(lines.iter().filter(|l| l.ends_with(" M30")).count(), 1);

    // GRBL: no tool changer: the stop names the tool to put in; its parser reads it all.
    let (one, _) = join(Dialect::Grbl);
    let lines: Vec<&str> = one.lines().collect();
    let from = lines.iter().position(|l| l.starts_with("(setup 2 of 2")).unwrap();
    let said = said_over(&lines, from + lines[from..].iter().position(|l| *l == "M0").unwrap());
    assert!(said.contains("set the zero of G55; put in T"), "{said}");
    assert!(one.lines().all(|l| l.len() <= 80));
    if let Some(read) = common::grblcheck(&one) {
        read.unwrap();
    }
}

/// What the view shows before a run ([`swarf::view::SetupView::stage`]) is what the run has:
/// the stock at the work zero and the fixtures round it, for a job without setups and for each
/// setup of one with them.
#[test]
fn the_stage_before_a_run_is_the_runs_stock_and_fixtures() {
    use swarf::job::fixtures::{Fixtures, Vise};
    use swarf::job::{WorkZero, ZeroCorner, ZeroHeight};
    let mut job = Job::two_sided();
    job.fixtures = Fixtures { vise: Some(Vise { grip: 8.0, ..Vise::default() }), ..Fixtures::default() };
    let mut placed = two_sided_part();
    job.place_part(&mut placed);
    let whole = run_setups(&job, two_sided_part(), &mut Progress::none()).unwrap();
    let stage = swarf::view::SetupView::stage(&job, &placed.bounds());
    assert_eq!(stage.len(), 2);
    for (k, (s, w)) in stage.iter().zip(&whole).enumerate() {
        assert!((s.stock.min - w.output.stock.min).length() < 1e-9 && (s.stock.max - w.output.stock.max).length() < 1e-9, "setup {k}: {:?} against {:?}", s.stock, w.output.stock);
        assert_eq!(s.fixtures.len(), 2, "setup {k}");
    }
    let mut one = job.clone();
    one.operations = one.setups[0].operations.clone();
    one.setups.clear();
    one.stock.zero = Some(WorkZero { corner: ZeroCorner::FrontLeft, height: ZeroHeight::StockTop, ..WorkZero::default() });
    let out = swarf::job::run(&one, two_sided_part(), &mut Progress::none()).unwrap();
    let stage = swarf::view::SetupView::stage(&one, &placed.bounds());
    assert_eq!(stage.len(), 1);
    assert!((stage[0].stock.min - out.stock.min).length() < 1e-9 && (stage[0].stock.max - out.stock.max).length() < 1e-9);
    assert!(stage[0].stock.min.x.abs() < 1e-9 && stage[0].stock.min.y.abs() < 1e-9 && stage[0].stock.max.z.abs() < 1e-9);
    // The part moves with the stock: by the frame's shift.
    let shift = swarf::geom::DVec3::from_array(stage[0].shift);
    let mut moved = two_sided_part();
    one.place(&mut moved);
    assert!((moved.bounds().min - (placed.bounds().min + shift)).length() < 1e-9);
}

/// A shared part with features on both sides: the rocker arm (a machined part scanned, scale
/// 100, Y up) roughed, its shallow faces finished by raster and its steep ones by waterline (the
/// demo's mould job), from the top, then turned over about X and the same from below, the
/// second setup from the stock the first left. Both programs are clean and read by LinuxCNC's
/// interpreter, OpenCAMLib's drop cutter finds no gouge in either against the part as its
/// setup holds it, what they removed and what is left add up to the block, and what is left
/// over the part is the finish's scallops and corners, not the roughing's levels.
#[test]
fn a_shared_part_is_machined_from_both_sides() {
    let Some(file) = common::shared_data("meshes/c3d_rocker-arm.obj") else { return };
    let mut job = Job::two_sided();
    let demo = Job::demo();
    for s in &mut job.setups {
        s.operations = demo.operations.clone();
    }
    job.part.scale = 100.0;
    job.part.up_axis = swarf::mesh::placement::UpAxis::Y;
    // It stands 4x mm tall: tools that reach its depth from either side.
    for t in &mut job.tools {
        t.cutter.flute_length = 60.0;
    }
    let bytes = std::fs::read(&file).unwrap();
    let part = match swarf::job::Workpiece::read(&bytes, Some("c3d_rocker-arm.obj"), &job.tolerances).unwrap() {
        swarf::job::Workpiece::Mesh(m) => m,
        _ => unreachable!("a mesh"),
    };
    let t = std::time::Instant::now();
    let setups = run_setups(&job, part, &mut Progress::none()).unwrap();
    eprintln!("planned and verified in {:.1} s", t.elapsed().as_secs_f64());
    let raw = setups[0].output.stock;
    eprintln!("stock {:?}", raw.size());
    let block = raw.size().x * raw.size().y * raw.size().z;
    let removed: Vec<f64> = setups.iter().map(|s| s.output.verification.as_ref().unwrap().volumes.iter().sum::<f64>()).collect();
    let left = setups[1].output.verification.as_ref().unwrap().stock.volume();
    for s in &setups {
        let v = s.output.verification.as_ref().unwrap();
        eprintln!("{}: cycle {:.0} s, removed {:.0} mm³, {}", s.name, s.output.cycle.seconds, v.volumes.iter().sum::<f64>(), v.report.describe());
        common::clean(&s.output);
        assert!(v.report.residual_mean < 0.25, "{}: {} mm left on average", s.name, v.report.residual_mean);
        assert!(common::rs274(&s.output.gcode, &job.tools).contains("STRAIGHT_FEED"), "{}", s.name);
        if let Some(said) = common::gcheck(&s.output.gcode, &s.output.part, &job.tools) {
            assert!(said.contains("gcheck: OK"), "{}: {said}", s.name);
        }
    }
    eprintln!("block {block:.0} mm³, removed {removed:?}, left {left:.0}");
    assert!((removed.iter().sum::<f64>() + left - block).abs() < 1e-6 * block);
    assert!(removed[1] > 0.1 * removed[0], "the bottom had its own to cut: {removed:?}");
}

/// A prism whose end is the convex pentagon (0, 0), (40, 0), (40, 8), (25, 14), (0, 14) in X
/// and Z, 30 mm deep in Y: a part that is not symmetric, its top sloping down at one end.
fn sloped_block() -> swarf::mesh::Mesh {
    use swarf::geom::DVec3;
    let outline = [(0.0, 0.0), (40.0, 0.0), (40.0, 8.0), (25.0, 14.0), (0.0, 14.0)];
    let at = |k: usize, y: f64| DVec3::new(outline[k % 5].0, y, outline[k % 5].1);
    let mut tris = Vec::new();
    for k in 1..4 {
        // The front (y = 0, facing -Y) and the back (y = 30, facing +Y).
        tris.push([at(0, 0.0), at(k, 0.0), at(k + 1, 0.0)]);
        tris.push([at(0, 30.0), at(k + 1, 30.0), at(k, 30.0)]);
    }
    for k in 0..5 {
        tris.push([at(k, 0.0), at(k, 30.0), at(k + 1, 30.0)]);
        tris.push([at(k, 0.0), at(k + 1, 30.0), at(k + 1, 0.0)]);
    }
    common::mesh(tris)
}

/// Issue 92: the setup sheet's zero is the program's. Each setup's sheet says what Z0 is on and
/// where the stock's top and sides lie from the zero; held to where the program puts them: the
/// stock the setup starts from (carried from the one before, independently of the run) has its
/// highest material at the stated top, its sides at the stated X and Y, and the part as the
/// program holds it has its top at Z0 where the sheet says Z0 is on it. For the two-sided
/// example, and for a part that is not symmetric turned over about X and about Y with more
/// stock below it than above and no zero given (the bottom's Z0 was once 2 mm above the part's
/// face while the sheet said its top: an operator touching off the face cut 2 mm too deep).
#[test]
fn every_setups_sheet_states_the_zero_its_program_uses() {
    use swarf::geom::DVec2;
    use swarf::job::setups::{carried, laid_like};
    use swarf::sim::dexel::DexelStock;
    let mut cases = vec![("two-sided", Job::two_sided(), two_sided_part())];
    for flip in [swarf::job::Flip::AboutX, swarf::job::Flip::AboutY] {
        let mut job = Job::two_sided();
        job.stock.zero = None;
        job.stock.margin_bottom = 3.0;
        job.stock.margin_top = 1.0;
        for s in &mut job.setups {
            s.operations.retain(|o| matches!(o.name(), "face" | "rough"));
        }
        job.setups[1].flip = flip;
        cases.push(if flip == swarf::job::Flip::AboutX { ("sloped, over X", job, sloped_block()) } else { ("sloped, over Y", job, sloped_block()) });
    }
    // The number after `words` in `text`, up to the next space, comma, semicolon or bracket.
    let number_after = |text: &str, words: &str| -> f64 {
        let rest = text.split(words).nth(1).unwrap_or_else(|| panic!("no '{words}' in: {text}"));
        rest.split([' ', ',', ';', ')']).next().unwrap().parse::<f64>().unwrap_or_else(|e| panic!("'{words}' then {rest}: {e}"))
    };
    for (name, job, part) in cases {
        let setups = run_setups(&job, part, &mut Progress::none()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let sheets: Vec<_> = setups.iter().map(|s| swarf::job::sheet::SheetSetup::of(&s.name, &s.output)).collect();
        let html = swarf::job::sheet::setup_sheet(&job, "part.stl", &sheets);
        let sections: Vec<&str> = html.split("<section>").skip(1).collect();
        assert_eq!(sections.len(), setups.len(), "{name}");
        let mut before: Option<(DexelStock, swarf::job::setups::Orientation)> = None;
        for (k, (s, section)) in setups.iter().zip(&sections).enumerate() {
            let out = &s.output;
            let v = out.verification.as_ref().unwrap();
            common::clean(out);
            let said = section.split("<th>Zero (X0 Y0 Z0)</th><td>").nth(1).unwrap().split("</td>").next().unwrap();
            assert!(said == sheets[k].zero, "{name} {}: the sheet shows its figures: {said}", s.name);
            // The stock as this setup starts: the raw box, or what the setup before left.
            let cell = v.stock.grid().spacing;
            let start = match &before {
                None => DexelStock::new(&out.stock, cell, 1).with_spans(|_, spans| spans.push((out.stock.min.z, out.stock.max.z))),
                Some((left, from)) => DexelStock::new(&out.stock, cell, 1).laid_from(laid_like(left, from, &s.orientation)).with_spans(|p, spans| carried(left, from, &s.orientation, p, spans)),
            };
            let g = start.grid();
            let mut highest = f64::NEG_INFINITY;
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for j in 0..g.ny {
                for i in 0..g.nx {
                    if start.top(i, j) > start.floor(i, j) {
                        highest = highest.max(start.top(i, j));
                        (lo, hi) = (lo.min(g.node(i, j)), hi.max(g.node(i, j)));
                    }
                }
            }
            let top = if said.contains("touch off the stock's top as Z0") { 0.0 } else { number_after(said, "touch off the stock's top and set it as Z") };
            assert!((highest - top).abs() < 1e-6, "{name} {}: the sheet puts the stock's top at Z{top}, the program at Z{highest}: {said}", s.name);
            // The stated sides hold the stock's cells, within a cell.
            for (words, at) in [("left side at X", lo.x), ("its right at X", hi.x), ("its front at Y", lo.y), ("its back at Y", hi.y)] {
                let stated = number_after(said, words);
                assert!((stated - at).abs() <= cell, "{name} {}: {words}{stated}, the stock's cells reach {at}", s.name);
            }
            let bottom = number_after(said, "the stock's bottom is Z");
            assert!((bottom - out.stock.min.z).abs() < 1e-3, "{name} {}: {said}", s.name);
            let held = out.part.bounds();
            if said.starts_with("Z0 on the part's top as held") {
                assert!(held.max.z.abs() < 1e-6, "{name} {}: the part's top at Z{}: {said}", s.name, held.max.z);
                let below = if said.contains("which is the stock's top") { 0.0 } else { number_after(said, "as held, ") };
                assert!((below - top).abs() < 1e-3, "{name} {}: {said}", s.name);
            }
            if said.contains("X0 Y0 at the centre of the part seen from above") {
                assert!(held.center().truncate().length() < 1e-6, "{name} {}: {said}", s.name);
            }
            eprintln!("{name} {}: {said}", s.name);
            before = Some((v.stock.clone(), s.orientation));
        }
        // The turned setups' zero is the part's top as held, without a zero given.
        if job.stock.zero.is_none() {
            assert!(sheets[1].zero.starts_with("Z0 on the part's top as held, 3.000 mm below the stock's top"), "{name}: {}", sheets[1].zero);
            assert!(setups[1].output.part.bounds().max.z.abs() < 1e-6);
        }
    }
}

/// The pieces of material of `stock` (spans of neighbouring columns overlapping by more than
/// 0.01 mm), found by a flood over the columns: whether every span holding `part_top` (the part
/// there: a column's part top height, or none) is in a piece with a span `gripped(i, j, floor,
/// top)` accepts. The test's own check, written apart from `swarf::sim::hold`.
fn part_is_gripped(stock: &swarf::sim::dexel::DexelStock, part_top: impl Fn(usize, usize) -> Option<f64>, gripped: impl Fn(usize, usize, f64, f64) -> bool) -> bool {
    let g = stock.grid();
    let spans: Vec<Vec<(f64, f64)>> = (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).map(|(i, j)| stock.spans(i, j).filter(|(f, t)| t > f).collect()).collect();
    let mut seen: Vec<Vec<bool>> = spans.iter().map(|s| vec![false; s.len()]).collect();
    let mut queue = std::collections::VecDeque::new();
    for j in 0..g.ny {
        for i in 0..g.nx {
            for (k, &(f, t)) in spans[j * g.nx + i].iter().enumerate() {
                if gripped(i, j, f, t) {
                    seen[j * g.nx + i][k] = true;
                    queue.push_back((i, j, k));
                }
            }
        }
    }
    while let Some((i, j, k)) = queue.pop_front() {
        let (f, t) = spans[j * g.nx + i][k];
        let near = [(i.wrapping_sub(1), j), (i + 1, j), (i, j.wrapping_sub(1)), (i, j + 1)];
        for (a, b) in near {
            if a >= g.nx || b >= g.ny {
                continue;
            }
            for (m, &(f2, t2)) in spans[b * g.nx + a].iter().enumerate() {
                if !seen[b * g.nx + a][m] && t.min(t2) - f.max(f2) > 0.01 {
                    seen[b * g.nx + a][m] = true;
                    queue.push_back((a, b, m));
                }
            }
        }
    }
    (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).all(|(i, j)| {
        let Some(h) = part_top(i, j) else { return true };
        spans[j * g.nx + i].iter().enumerate().filter(|(_, &(f, t))| f < h - 0.01 && t > h - 0.01).all(|(k, _)| seen[j * g.nx + i][k])
    })
}

/// Issue 92, done when: the shared rocker arm, from a box in a vise closing on X, machined on
/// both sides with a parting line, comes off whole. Each side faces and roughs down to the
/// parting line (its widest section: `bottomFrom: partingLine`), the second a 1 mm skin short
/// of it, so the material beyond still joins the part to the jaws; the second setup's jaws
/// close on what the first left.
/// The test's own check finds the part joined to the material the jaws grip at the start and
/// end of every setup; no gouge; every program read by rs274 and GRBL's parser; each sheet's
/// zero where its program puts it. Cut down to the stock's bottom without a parting line and
/// without fixtures, the first setup leaves a web the second faces away: said, naming it.
#[test]
fn the_rocker_arm_comes_off_whole_from_a_box_in_a_vise() {
    use swarf::job::fixtures::{Vise, ViseAxis};
    use swarf::operations::HeightFrom;
    let Some(file) = common::shared_data("meshes/c3d_rocker-arm.obj") else { return };
    let bytes = std::fs::read(&file).unwrap();
    let read = |job: &Job| match swarf::job::Workpiece::read(&bytes, Some("c3d_rocker-arm.obj"), &job.tolerances).unwrap() {
        swarf::job::Workpiece::Mesh(m) => m,
        _ => unreachable!("a mesh"),
    };
    let mut job = Job::two_sided();
    job.part.scale = 100.0;
    job.part.up_axis = swarf::mesh::placement::UpAxis::Y;
    job.stock.zero = None;
    job.stock.margin_bottom = 3.0;
    job.fixtures.vise = Some(Vise { grip: 6.0, closes: ViseAxis::X, ..Vise::default() });
    for t in &mut job.tools {
        t.cutter.flute_length = 35.0;
    }
    // Each side roughed to the parting line (the part's widest section), the second a 1 mm
    // skin short of it.
    for (k, s) in job.setups.iter_mut().enumerate() {
        s.operations.retain(|o| matches!(o.name(), "face" | "rough"));
        for o in &mut s.operations {
            if let swarf::job::Operation::RoughZlevel(r) = o {
                r.roughing.heights.bottom = (k == 1).then_some(1.0);
                r.roughing.heights.bottom_from = HeightFrom::PartingLine;
            }
        }
    }
    let widest = {
        let mut p = read(&job);
        job.place_part(&mut p);
        let b = p.bounds();
        let z = p.widest_section().unwrap();
        assert!(z > b.min.z + 1.0 && z < b.max.z - 1.0, "the rocker's widest section at {z} in {b:?}");
        z - b.max.z
    };
    let setups = run_setups(&job, read(&job), &mut Progress::none()).unwrap();
    let sheets: Vec<_> = setups.iter().map(|s| swarf::job::sheet::SheetSetup::of(&s.name, &s.output)).collect();
    for (k, s) in setups.iter().enumerate() {
        let out = &s.output;
        let v = out.verification.as_ref().unwrap();
        common::clean(out);
        assert!(out.problem.is_none(), "{}: {:?}", s.name, out.problem);
        assert!(!out.warnings.iter().any(|w| w.to_string().contains("free")), "{}: {:?}", s.name, out.warnings);
        // The jaws close on the material 3 mm high or more within their 6 mm from the stock's
        // bottom, found here from the stock as the setup starts.
        let (lo, hi) = (out.stock.min.z, out.stock.min.z + 6.0);
        let start = v.start.clone().unwrap_or_else(|| swarf::sim::dexel::DexelStock::new(&out.stock, v.stock.grid().spacing, 1).with_spans(|_, sp| sp.push((out.stock.min.z, out.stock.max.z))));
        let g = start.grid();
        let band: Vec<usize> = (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).filter(|&(i, j)| start.spans(i, j).any(|(f, t)| t.min(hi) - f.max(lo) >= 3.0)).map(|(i, _)| i).collect();
        let (i_lo, i_hi) = (*band.iter().min().unwrap(), *band.iter().max().unwrap());
        let part = &v.part;
        for (when, stock) in [("starts", &start), ("ends", &v.stock)] {
            let held = part_is_gripped(stock, |i, j| Some(part.z[j * part.nx + i]).filter(|z| z.is_finite()), |i, _, f, t| (i == i_lo || i == i_hi) && t.min(hi) - f.max(lo) > 0.01);
            assert!(held, "{} {when}: the part is not joined to what the jaws grip", s.name);
        }
        assert!(common::rs274(&out.gcode, &job.tools).contains("STRAIGHT_FEED"), "{}", s.name);
        let grbl = swarf::post::PostSettings { dialect: swarf::post::Dialect::Grbl, ..job.post.clone() };
        let gcode = swarf::post::write_gcode(&s.name, &out.paths, &job.tools, out.clearance_z, &grbl).unwrap();
        if let Some(said) = common::grblcheck(&gcode) {
            said.unwrap_or_else(|e| panic!("{}: {e}", s.name));
        }
        // The sheet's zero: Z0 on the part's top as held, the stock's top above it by the
        // margin over that face (1 mm over the top, 3 under the bottom).
        assert!(out.part.bounds().max.z.abs() < 1e-6, "{}", s.name);
        let margin = if k == 0 { 1.0 } else { 3.0 };
        assert!(sheets[k].zero.contains(&format!("touch off the stock's top and set it as Z+{margin:.3}")), "{}: {}", s.name, sheets[k].zero);
        // The first side roughs down to the parting line and no further.
        if k == 0 {
            let lowest = out.moves.iter().filter(|m| !m.mv.is_rapid()).map(|m| m.mv.to().z).fold(f64::INFINITY, f64::min);
            assert!((lowest - widest).abs() < 1e-6, "{}: down to Z{lowest}, the parting line at Z{widest}", s.name);
        }
        eprintln!("{}: {} moves, cycle {:.0} s; {}", s.name, out.moves.len(), out.cycle.seconds, sheets[k].zero);
    }
    // Without the parting line and without fixtures: the first side roughs down to the
    // stock's bottom, and the second's facing cuts away the web it left; nothing joins the part
    // to the stock's sides after it, which the second setup says, naming the facing.
    let mut free = job.clone();
    free.fixtures.vise = None;
    for s in &mut free.setups {
        for o in &mut s.operations {
            if let swarf::job::Operation::RoughZlevel(r) = o {
                (r.roughing.heights.bottom, r.roughing.heights.bottom_from) = (None, HeightFrom::Zero);
            }
        }
    }
    let out = run_setups(&free, read(&free), &mut Progress::none()).unwrap();
    assert!(!out[0].output.warnings.iter().any(|w| w.to_string().contains("free")), "{:?}", out[0].output.warnings);
    let said: Vec<String> = out[1].output.warnings.iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.starts_with("face") && w.contains("cuts the part free")), "{said:?}");
}

/// Issue 94: a work zero `at` a point off the stock is refused naming the field (a setup's `[1e6, 0]`
/// wrote `G0 X-999987.768`); one on the stock runs, with X0 Y0 there.
#[test]
fn a_zero_off_the_stock_is_refused() {
    use swarf::job::WorkZero;
    let mut job = Job::demo();
    job.stock.zero = Some(WorkZero { at: Some([900.0, 0.0]), ..WorkZero::default() });
    let e = swarf::job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("stock.zero.at: X0 Y0 at X+900.000") && e.contains("lies off the"), "{e}");
    job.stock.zero = Some(WorkZero { at: Some([5.0, -5.0]), ..WorkZero::default() });
    let out = swarf::job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    let c = out.stock.center();
    assert!((c.x + 5.0).abs() < 1e-9 && (c.y - 5.0).abs() < 1e-9, "the stock's centre at {c}");
    // A setup's own.
    let mut two = Job::two_sided();
    two.setups[1].zero = Some(WorkZero { at: Some([0.0, -500.0]), ..WorkZero::default() });
    let e = run_setups(&two, two_sided_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("zero.at") && e.contains("lies off the"), "{e}");
}

/// Issue 92: a sheet whose zero is on a hole says so. The two-sided example's top, its zero
/// put on a corner hole's centre (as the page's "X0 Y0 on the picked hole" does): the sheet
/// says X0 Y0 is the centre of that hole, with its diameter and its distance from the stock's
/// centre; the program's X0 Y0 is the hole's axis.
#[test]
fn a_zero_on_a_hole_is_said_on_the_sheet() {
    let mut job = Job::two_sided();
    job.operations = job.setups[0].operations.clone();
    job.setups.clear();
    let part = two_sided_part();
    let holes = job.holes(part.clone()).unwrap();
    let hole = holes.iter().find(|h| h.through).expect("a hole through the plate").clone();
    let mut placed = part.clone();
    job.place_part(&mut placed);
    job.stock.zero = Some(job.zero_on(&placed.bounds(), None, hole.center).unwrap());
    let out = swarf::job::run(&job, part, &mut Progress::none()).unwrap();
    let sheet = swarf::job::sheet::SheetSetup::of("Top", &out);
    let d = swarf::limits::shown((hole.diameter * 1000.0).round() / 1000.0);
    assert!(sheet.zero.contains(&format!("X0 Y0 at the centre of the φ{d} hole")), "{}", sheet.zero);
    // The hole, as the program holds the part, is on X0 Y0.
    let at = swarf::holes::mesh::find(&out.part).into_iter().map(|h| h.center.length()).fold(f64::INFINITY, f64::min);
    assert!(at < 1e-3, "the nearest hole's axis is {at} mm from X0 Y0");
}

/// Issue 94: with setups, an error names what the user set, not a field the setups made. A bar
/// too small for the part, in a job turned over, says the bar's diameter (its setup's stock is
/// a box round the bar: it once gave a box's advice, "stock.sizeBox").
#[test]
fn a_setups_error_names_what_the_user_set() {
    use swarf::job::{Bar, BarAxis};
    let mut job = milled_only();
    job.stock.bar = Some(Bar { diameter: 20.0, axis: BarAxis::Z });
    let part = puck(20.0, -10.0, 0.0, 96);
    let e = swarf::job::run_setups(&job, part, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("outside a φ20 bar; choose a bar of at least φ40"), "{e}");
    assert!(!e.contains("sizeBox"), "{e}");
}

/// Issue 94: a blank the part is not inside, or one that is open, is refused naming it, before
/// any work: the cast blank raised 2.5 mm (its bottom 2 mm over the boss's; once "gouges the
/// part in 640 cells"), and the cast blank with its bottom faces left out (once "nothing to
/// cut").
#[test]
fn a_blank_short_of_the_part_or_open_is_refused_naming_it() {
    use swarf::job::blank::MeshFile;
    let job_for = |blank: &swarf::mesh::Mesh| {
        let mut job = milled_only();
        let operations = job.setups[0].operations.clone();
        job.setups.clear();
        job.operations = operations;
        job.stock.zero = None;
        job.stock.mesh = Some(MeshFile::embedded("casting.stl", &blank.to_binary_stl()));
        job
    };
    // The blank as it is runs (the setups' own test holds it clean).
    let blank = cast_blank();
    let mut short = blank.clone();
    short.transform(|v| if v.z < -18.0 { swarf::geom::DVec3::new(v.x, v.y, v.z + 2.5) } else { v });
    let e = swarf::job::run(&job_for(&short), two_sided_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("stock.mesh: the part is not inside the blank") && e.contains("below the blank's bottom"), "{e}");
    // The blank's bottom left out: its faces whose vertices are all on the bottom.
    let mut open = blank.clone();
    let low = open.bounds().min.z + 1e-9;
    let vertices = open.vertices.clone();
    open.faces.retain(|f| !f.iter().all(|&v| vertices[v as usize].z <= low));
    let e = swarf::job::run(&job_for(&open), two_sided_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("stock.mesh: the blank is open") && e.contains("its bottom or its top is missing"), "{e}");
}
