//! V-carving (issue 40): generated letters with known geometry carved with a 90° V-bit. The
//! simulated stock lies on the distance-field surface (as deep below the top as the point is in
//! from the outline), so the walls meet the outline at the top within 0.02 mm; the depth along
//! the medial axis is the analytic half width; nothing is cut outside the regions; the
//! flat-bottomed variant leaves its floor at its depth with a second, flat tool; rs274 and
//! GRBL's parser read the programs; the shared drawings carve clean.

mod common;

use swarf::cutter::Cutter;
use swarf::drawing::Shape;
use swarf::geom::Tolerances;
use swarf::job::{self, Job, Operation, Tool};
use swarf::operations::{Engrave, VCarve};
use swarf::post::Dialect;
use swarf::progress::Progress;

/// A bar 40 × 8, an L with a reflex corner, and a ring (φ20 round a φ10 island).
const LETTERS: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="60mm" viewBox="0 0 100 60">
  <rect x="5" y="5" width="40" height="8"/>
  <path d="M 55 5 H 90 V 13 H 63 V 40 H 55 Z"/>
  <circle cx="25" cy="38" r="10"/><circle cx="25" cy="38" r="5"/>
</svg>"#;

fn carving(op: VCarve) -> (Job, swarf::drawing::Drawing) {
    let drawing = swarf::drawing::import::read_drawing(LETTERS.as_bytes(), Some("letters.svg"), &Tolerances::DEFAULT).unwrap();
    let mut job = Job::default_for_drawing();
    job.drawing.thickness = 10.0;
    job.tools = vec![
        Tool { number: 1, cutter: Cutter { flute_length: 12.0, ..Cutter::v_bit(12.0, 90.0, 0.0) }, feed_rate: 1200.0, plunge_rate: 400.0, ..Tool::default() },
        Tool { number: 2, cutter: Cutter::flat(1.5), ..Tool::default() },
    ];
    job.operations = vec![Operation::VCarve(op)];
    job.simulation.cell = Some(0.05);
    (job, drawing)
}

/// LinuxCNC's rs274 reads `gcode`, the job's program, and GRBL 1.1's parser the same job
/// posted for GRBL (where grblcheck is built).
fn controllers_read(job: &Job, drawing: swarf::drawing::Drawing, gcode: &str) {
    common::rs274(gcode, &job.tools);
    let mut grbl = job.clone();
    grbl.post.dialect = Dialect::Grbl;
    if let Some(said) = common::grblcheck(&job::run(&grbl, drawing, &mut Progress::none()).unwrap().gcode) {
        said.unwrap();
    }
}

/// The regions as the job places them, to measure the stock against.
fn placed(job: &Job, drawing: &swarf::drawing::Drawing) -> Shape {
    let mut d = drawing.clone();
    job.drawing.apply(&mut d);
    Shape::new(d.loops.iter().map(|l| l.path.clone()).collect())
}

#[test]
fn letters_are_carved_to_the_distance_from_their_outline() {
    let (job, drawing) = carving(VCarve::default());
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).expect("carved");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let shape = placed(&job, &drawing);
    // Along the bar's middle line the tool is as deep as half its width; round the ring, half
    // the ring's width.
    let of_area = |area: f64| shape.loops.iter().find(|l| (l.area().abs() - area).abs() < 1.0).map(|l| l.bounds()).unwrap();
    let bar = of_area(320.0);
    let centre = of_area(std::f64::consts::PI * 100.0).center();
    let (mut middle, mut round) = (0, 0);
    for path in &out.paths {
        // Where the moves along the axis meet (below the sheet's top).
        for (a, _, _) in path.segments(0.01) {
            if a.z >= 0.0 {
                continue;
            }
            let p = a.truncate();
            if (p.y - bar.center().y).abs() < 1e-6 && p.x > bar.min.x + 3.9 && p.x < bar.max.x - 3.9 {
                assert!((a.z + 4.0).abs() < 1e-6, "the bar's middle at {a:?}");
                middle += 1;
            }
            if (p.distance(centre) - 7.5).abs() < 1e-3 {
                assert!((a.z + 2.5).abs() < 2e-3, "the ring's middle at {a:?}");
                round += 1;
            }
        }
    }
    assert!(middle >= 2 && round > 10, "{middle} points along the bar's middle, {round} round the ring");
    // The stock: on the surface as deep as the point is in from the outline, untouched outside.
    let (mut inside, mut outside) = (0, 0);
    for (p, holds, d, top) in common::cells(&v.stock, &shape) {
        if holds {
            if d > 0.02 {
                assert!((top + d).abs() < 0.02, "at {p:?}, {d:.3} mm in: the stock at {top:.4}");
                inside += 1;
            }
        } else if d > 0.02 {
            assert!(top >= -1e-9, "at {p:?}, {d:.3} mm outside: cut to {top:.4}");
            outside += 1;
        }
    }
    assert!(inside > 50_000 && outside > 100_000, "{inside} cells inside, {outside} outside");
    controllers_read(&job, drawing, &out.gcode);
}

#[test]
fn a_flat_depth_leaves_a_floor_cleared_by_the_flat_tool() {
    let depth = 1.5;
    let (job, drawing) = carving(VCarve { max_depth: Some(depth), flat_tool: Some(2), ..VCarve::default() });
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).expect("carved");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    assert_eq!(out.paths.len(), 2, "the flat tool's path, then the V-bit's");
    assert_eq!(out.paths[0].tool, 2);
    let shape = placed(&job, &drawing);
    let (mut floor, mut walls) = (0, 0);
    for (p, _, d, top) in common::cells(&v.stock, &shape).filter(|c| c.1) {
        // The floor's sharp corners are the V-bit's: the flat tool's round end leaves them.
        let corner = shape.loops.iter().flat_map(|l| l.vertices.iter()).any(|v| v.p.distance(p) < 3.0 * depth);
        if d > depth + 0.05 && !corner {
            assert!((top + depth).abs() < 0.01, "at {p:?}, {d:.3} mm in: the floor at {top:.4}");
            floor += 1;
        } else if d > 0.02 && d < depth - 0.05 {
            assert!((top + d).abs() < 0.02, "at {p:?}, {d:.3} mm in: the wall at {top:.4}");
            walls += 1;
        }
    }
    assert!(floor > 10_000 && walls > 10_000, "{floor} cells on the floor, {walls} on the walls");
    common::rs274(&out.gcode, &job.tools);
    // Without a flat tool the floor is left, and said to be.
    let (job, drawing) = carving(VCarve { max_depth: Some(depth), ..VCarve::default() });
    let out = job::run(&job, drawing, &mut Progress::none()).unwrap();
    assert!(out.warnings.iter().any(|w| w.to_string().contains("is left: name a flatTool")), "{:?}", out.warnings);
}

#[test]
fn a_v_carve_takes_a_v_bit_and_works_on_drawings() {
    let (mut job, drawing) = carving(VCarve { tool: 2, ..VCarve::default() });
    let e = job::run(&job, drawing.clone(), &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("V-carving needs a V-bit"), "{e}");
    job.operations = vec![Operation::VCarve(VCarve::default())];
    let part = swarf::mesh::sample::demo_part();
    let e = job::run(&Job { tools: job.tools.clone(), operations: job.operations.clone(), ..Job::default() }, part, &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("drawings"), "{e}");
}

/// Issue 56: a loop that crosses itself (a bow tie) is refused where it crosses, not carved
/// into a gouge 6 mm deep ("gouges the part", its cause unsaid).
#[test]
fn a_loop_crossing_itself_is_refused_where_it_crosses() {
    let bow = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40"><path d="M5 5 L55 35 L55 5 L5 35 Z"/></svg>"#;
    let drawing = swarf::drawing::import::read_drawing(bow.as_bytes(), Some("bow.svg"), &Tolerances::DEFAULT).unwrap();
    let (job, _) = carving(VCarve::default());
    let e = job::run(&job, drawing, &mut Progress::none()).map(|_| ()).unwrap_err().to_string();
    // Lower-left origin: the crossing at (30, 20) of the file is (25, 15) on the machine.
    assert!(e.contains("crosses itself or another loop at X25.000 Y15.000"), "{e}");
}

/// A single-line font's strokes (open chains) engraved by the V-bit at a fixed depth: the
/// groove a V as deep as asked along the line, as wide at the top as the cone there, nothing
/// cut beyond; the verification holds the groove to that width (it allowed the bit's whole
/// radius before).
#[test]
fn open_chains_are_engraved_by_the_v_bit_at_their_depth() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40"><rect x="0" y="0" width="60" height="40" fill="none" stroke="black"/><path d="M 10 30 L 40 30 L 40 10" fill="none" stroke="black"/></svg>"#;
    let drawing = swarf::drawing::import::read_drawing(svg.as_bytes(), Some("stroke.svg"), &Tolerances::DEFAULT).unwrap();
    let (mut job, _) = carving(VCarve::default());
    let depth = 1.5;
    job.operations = vec![Operation::Engrave(Engrave { depth, stepdown: depth, ..Engrave::default() })];
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).expect("engraved");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let mut d = drawing.clone();
    job.drawing.apply(&mut d);
    let stroke = &d.open[0].path;
    // A 90° V-bit: the groove's wall one millimetre out for each millimetre up.
    let (mut inside, mut outside) = (0, 0);
    let grid = v.stock.grid();
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let p = grid.node(i, j);
            let off = stroke.iter().map(|s| s.distance_to(p)).fold(f64::INFINITY, f64::min);
            let top = v.stock.top(i, j);
            if off < depth - 0.05 {
                assert!((top + depth - off).abs() < 0.03, "at {p:?}, {off:.3} from the stroke: the stock at {top:.4}, the V at {:.4}", off - depth);
                inside += 1;
            } else if off > depth + 0.05 {
                assert!(top >= -1e-9, "at {p:?}, {off:.3} from the stroke: cut to {top:.4}");
                outside += 1;
            }
        }
    }
    assert!(inside > 10_000 && outside > 100_000, "{inside} cells in the groove, {outside} beside");
    controllers_read(&job, drawing, &out.gcode);
}

/// The shared drawings carve clean (their loops as regions, a 60° V-bit flat at 2 mm).
#[test]
fn the_shared_drawings_carve_clean() {
    for name in ["pycam_polygons.svg", "tm_tray-easy1.svg", "tm_1002_tray_bottom.dxf"] {
        let Some(path) = common::shared_data(&format!("profiles/{name}")) else { return };
        let drawing = swarf::drawing::import::read_drawing(&std::fs::read(path).unwrap(), Some(name), &Tolerances::DEFAULT).unwrap();
        let mut job = Job::default_for_drawing();
        job.tools =
            vec![Tool { number: 1, cutter: Cutter { flute_length: 12.0, ..Cutter::v_bit(12.0, 60.0, 0.0) }, ..Tool::default() }, Tool { number: 2, cutter: Cutter::flat(3.0), ..Tool::default() }];
        job.operations = vec![Operation::VCarve(VCarve { max_depth: Some(2.0), flat_tool: Some(2), ..VCarve::default() })];
        let started = std::time::Instant::now();
        let out = job::run(&job, drawing, &mut Progress::none()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{name}: {}", v.report.describe());
        common::rs274(&out.gcode, &job.tools);
        println!("{name}: {} moves, {:.0} s on the machine, {:.2} s to plan and verify", out.moves.len(), out.stats.seconds, started.elapsed().as_secs_f64());
    }
}

/// Issue 62: with no loops picked, a sign of letters drawn on a background rectangle carves
/// the letters (the regions the cone reaches across), not the background, and says which it
/// left and why; the letters' stock is as when they are drawn alone, the background untouched.
#[test]
fn with_nothing_picked_a_sign_carves_its_letters_not_its_background() {
    let sign = LETTERS.replace("<rect x=\"5\"", "<rect x=\"0\" y=\"0\" width=\"100\" height=\"60\"/>\n  <rect x=\"5\"");
    let drawing = swarf::drawing::import::read_drawing(sign.as_bytes(), Some("sign.svg"), &Tolerances::DEFAULT).unwrap();
    let (job, _) = carving(VCarve::default());
    let out = job::run(&job, drawing.clone(), &mut Progress::none()).expect("carved");
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let said = out.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n");
    assert!(said.contains("no loops picked") && said.contains("not that background") && said.contains("(100.0 × 60.0 mm)") && said.contains("Loops"), "{said}");
    assert!(!said.contains("carved flat"), "{said}");
    // The letters: the sign's loops but its largest, as placed.
    let all = placed(&job, &drawing);
    let largest = all.loops.iter().map(|l| l.area().abs()).fold(0.0, f64::max);
    let letters = Shape::new(all.loops.iter().filter(|l| l.area().abs() < largest).cloned().collect());
    let (mut inside, mut outside) = (0, 0);
    for (p, holds, d, top) in common::cells(&v.stock, &letters) {
        if holds && d > 0.02 {
            assert!((top + d).abs() < 0.02, "at {p:?}, {d:.3} mm into a letter: the stock at {top:.4}");
            inside += 1;
        } else if !holds && d > 0.02 {
            assert!(top >= -1e-9, "at {p:?}, {d:.3} mm outside the letters (the background, the ring's island): cut to {top:.4}");
            outside += 1;
        }
    }
    assert!(inside > 50_000 && outside > 100_000, "{inside} cells inside, {outside} outside");
    // The warning offers the letters' loops to pick (the page's "pick these" button): picked,
    // they carve the same, and nothing is said.
    let offered = out.warnings.iter().find(|w| !w.loops.is_empty()).map(|w| w.loops.clone()).expect("loops offered");
    assert!(!offered.contains(&0) && offered.len() >= 3, "{offered:?}");
    let (mut chosen, _) = carving(VCarve { loops: offered.clone(), ..VCarve::default() });
    chosen.simulation.verify = false;
    let again = job::run(&chosen, drawing.clone(), &mut Progress::none()).expect("carved");
    assert_eq!(
        again.gcode.lines().filter(|l| !l.starts_with('(')).collect::<Vec<_>>(),
        out.gcode.lines().filter(|l| !l.starts_with('(')).collect::<Vec<_>>(),
        "loops {offered:?} picked carve otherwise"
    );
    assert!(!again.warnings.iter().any(|w| w.to_string().contains("no loops picked")), "{:?}", again.warnings);
    // Picked, the background is carved (flat, as deep as the cone goes), as asked.
    let (mut picked, _) = carving(VCarve { loops: vec![0], ..VCarve::default() });
    picked.simulation.verify = false;
    let out = job::run(&picked, drawing, &mut Progress::none()).expect("carved");
    assert!(out.warnings.iter().any(|w| w.to_string().contains("carved flat")), "{:?}", out.warnings);
}
