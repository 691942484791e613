//! 2.5D jobs on drawings, end to end: import, offset, profile and pocket paths, G-code, and the
//! simulation's verification against the part the drawing means. Tool centres never come
//! closer to the drawn walls than the tool radius; pockets remove their closed-form volume.

mod common;

use std::f64::consts::PI;

use swarf::cutter::Cutter;
use swarf::drawing::import::read_drawing;
use swarf::drawing::sample::plate_dxf;
use swarf::drawing::{Drawing, DrawnLoop, Loop, Shape};
use swarf::geom::{DVec2, Tolerances};
use swarf::job::{self, Job, Operation, Tool};
use swarf::offset::trim::Original;
use swarf::operations::{Direction, Profile2d, Tabs};
use swarf::operations::{EntryKind, Pocket2d, PocketPattern};
use swarf::post::Dialect;
use swarf::progress::Progress;
use swarf::toolpath::{arc_sweep, Move};

fn plate() -> Drawing {
    read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Tolerances::default()).unwrap()
}

fn job_with(ops: Vec<Operation>, diameter: f64) -> Job {
    let tool = Tool { number: 1, cutter: Cutter::flat(diameter), feed_rate: 800.0, plunge_rate: 200.0, ..Tool::default() };
    Job { tools: vec![tool], operations: ops, ..Job::default_for_drawing() }
}

/// The smallest distance from the points of cutting moves below the sheet top to the shape,
/// and where (up to 5 mm): every move sampled on its true line or arc at least every 0.01 mm.
fn approach_at(out: &job::JobOutput, shape: &Shape) -> (f64, DVec2) {
    let original = Original::new(shape);
    let mut worst = (f64::INFINITY, DVec2::ZERO);
    for p in &out.paths {
        let mut at = p.start;
        for m in &p.moves {
            let to = m.to();
            if !m.is_rapid() && at.z.max(to.z) < -1e-9 {
                let (a, b) = (at.truncate(), to.truncate());
                let (sweep, len) = match *m {
                    Move::Arc { center, clockwise, .. } => {
                        let sweep = arc_sweep(at, to, center, clockwise);
                        (sweep, sweep.abs() * center.distance(a))
                    }
                    _ => (0.0, a.distance(b)),
                };
                let n = ((len / 0.01).ceil() as usize).max(8);
                for k in 0..=n {
                    let f = k as f64 / n as f64;
                    let q = match *m {
                        Move::Arc { center, .. } => center + DVec2::from_angle(sweep * f).rotate(a - center),
                        _ => a.lerp(b, f),
                    };
                    let d = original.distance(q, 5.0);
                    if d < worst.0 {
                        worst = (d, q);
                    }
                }
            }
            at = to;
        }
    }
    worst
}

fn closest_approach(out: &job::JobOutput, shape: &Shape) -> f64 {
    approach_at(out, shape).0
}

#[test]
fn the_sample_plate_reads_as_drawn() {
    let d = plate();
    assert_eq!(d.loops.len(), 6);
    assert!(d.open.is_empty());
    assert_eq!(d.layers, vec!["CUT".to_string(), "POCKET".to_string()]);
    let cut = d.shape(&["CUT".into()]).unwrap();
    let expected = 120.0 * 80.0 - (4.0 - PI) * 36.0 - PI * 64.0 - 256.0 - (30.0 * 8.0 + PI * 16.0);
    assert!((cut.area() - expected).abs() < 1e-6, "{} vs {expected}", cut.area());
    assert_eq!(cut.loops.iter().filter(|l| l.is_ccw()).count(), 1);
}

#[test]
fn profile_cuts_the_plate_out_with_tabs_and_never_closer_than_the_radius() {
    let profile = Profile2d { layers: vec!["CUT".into()], tabs: Tabs { count: 4, ..Tabs::default() }, ..Profile2d::default() };
    let job = job_with(vec![Operation::Profile2d(profile)], 3.0);
    let out = job::run(&job, plate(), &mut Progress::none()).unwrap();
    let placed = out.drawing.as_ref().unwrap();
    let shape = placed.shape(&["CUT".into()]).unwrap();
    let approach = closest_approach(&out, &shape);
    assert!(approach >= 1.5 - 1e-6, "a cutting move came {approach} from the drawing");
    let report = &out.verification.as_ref().unwrap().report;
    assert!(report.is_clean(), "{}", report.describe());
    assert!(out.gcode.contains("G2") || out.gcode.contains("G3"));
    // The tabs: the final depth is −6.2 (the 6 mm sheet and 0.2 past it), and the outline's
    // path rises to the tab top, 1.5 mm over the sheet's bottom: −4.5.
    let zs: Vec<f64> = out.paths[0].moves.iter().map(|m| m.to().z).collect();
    assert!(zs.iter().any(|&z| (z + 6.2).abs() < 1e-9));
    assert!(zs.iter().any(|&z| (z + 4.5).abs() < 1e-9), "{zs:?}");
    // Holes first: the outline (the longest loop) is cut last.
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
}

#[test]
fn pockets_remove_their_closed_form_volume_for_every_pattern() {
    for pattern in [PocketPattern::Offset, PocketPattern::Zigzag, PocketPattern::Adaptive] {
        for entry in [EntryKind::Helix, EntryKind::Ramp] {
            let pocket = Pocket2d { layers: vec!["POCKET".into()], depth: 3.0, stepdown: 1.5, pattern, entry, ..Pocket2d::default() };
            let mut job = job_with(vec![Operation::Pocket2d(pocket)], 6.0);
            job.simulation.cell = Some(0.1);
            let out = job::run(&job, plate(), &mut Progress::none()).unwrap();
            let placed = out.drawing.as_ref().unwrap();
            let region = placed.shape(&["POCKET".into()]).unwrap();
            assert!(closest_approach(&out, &region) >= 3.0 - 1e-6);
            let v = out.verification.as_ref().unwrap();
            assert!(v.report.is_clean(), "{pattern:?} {entry:?}: {}", v.report.describe());
            // 40 × 24 less the island (r 4) less the four corners a φ6 tool cannot reach.
            let area = 40.0 * 24.0 - PI * 16.0 - 4.0 * 9.0 * (1.0 - PI / 4.0);
            let removed: f64 = v.volumes.iter().sum();
            let expected = area * 3.0;
            assert!((removed - expected).abs() < 0.01 * expected, "{pattern:?} {entry:?}: removed {removed:.1} mm³, expected {expected:.1}");
        }
    }
}

#[test]
fn a_tool_larger_than_the_pocket_is_a_clear_error() {
    let pocket = Pocket2d { layers: vec!["POCKET".into()], ..Pocket2d::default() };
    let job = job_with(vec![Operation::Pocket2d(pocket)], 30.0);
    let e = job::run(&job, plate(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("does not fit in the pocket"), "{e}");
}

#[test]
fn open_chains_are_reported_where_they_are() {
    let dxf = "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\nA\n10\n0\n20\n0\n11\n10\n21\n0\n0\nLINE\n8\nA\n10\n10\n20\n0\n11\n10\n21\n10\n0\nENDSEC\n0\nEOF\n";
    let d = read_drawing(dxf.as_bytes(), Some("open.dxf"), &Tolerances::default()).unwrap();
    assert_eq!(d.open.len(), 1);
    let job = job_with(vec![Operation::Profile2d(Profile2d::default())], 3.0);
    let e = job::run(&job, d, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("open chain") && e.contains("layer A") && e.contains("(0.000, 0.000)") && e.contains("(10.000, 10.000)"), "{e}");
}

#[test]
fn closed_loops_beside_open_chains_are_cut_and_the_chains_named() {
    // A 20 mm square and an open L on layer A, and an open chain alone on layer B.
    let dxf = "0\nSECTION\n2\nENTITIES\n\
0\nLINE\n8\nA\n10\n0\n20\n0\n11\n20\n21\n0\n0\nLINE\n8\nA\n10\n20\n20\n0\n11\n20\n21\n20\n\
0\nLINE\n8\nA\n10\n20\n20\n20\n11\n0\n21\n20\n0\nLINE\n8\nA\n10\n0\n20\n20\n11\n0\n21\n0\n\
0\nLINE\n8\nA\n10\n40\n20\n0\n11\n50\n21\n0\n0\nLINE\n8\nA\n10\n50\n20\n0\n11\n50\n21\n10\n\
0\nLINE\n8\nB\n10\n0\n20\n40\n11\n10\n21\n40\n0\nENDSEC\n0\nEOF\n";
    let d = read_drawing(dxf.as_bytes(), Some("mixed.dxf"), &Tolerances::default()).unwrap();
    assert_eq!((d.loops.len(), d.open.len()), (1, 2));
    let profile = Profile2d { layers: vec!["A".into()], ..Profile2d::default() };
    let out = profile_every_loop(d.clone(), 3.0, profile);
    assert!(out.moves.iter().any(|m| !m.mv.is_rapid()), "the square is cut");
    let note: Vec<&swarf::error::Warning> = out.warnings.iter().filter(|w| w.message.contains("open chain")).collect();
    assert_eq!(note.len(), 1, "{:?}", out.warnings);
    let m = &note[0].message;
    assert!(m.starts_with("1 open chain is left uncut") && (m.contains("layer A from (40.000, 0.000)") || m.contains("layer A from (50.000, 10.000)")), "{m}");
    // Layer B has nothing closed: refused, saying where its chain is.
    let job = job_with(vec![Operation::Profile2d(Profile2d { layers: vec!["B".into()], ..Profile2d::default() })], 3.0);
    let e = job::run(&job, d, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("open chain") && e.contains("layer B"), "{e}");
}

#[test]
fn dxf_units_bulges_ellipses_and_splines() {
    // Inches: a 1 × 1 square with one bulged side (a half circle out), and an ellipse.
    let dxf = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n1\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n\
0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n1\n20\n0\n42\n1\n10\n1\n20\n1\n10\n0\n20\n1\n\
0\nELLIPSE\n8\nE\n10\n5\n20\n5\n30\n0\n11\n2\n21\n0\n31\n0\n40\n0.5\n41\n0\n42\n6.283185307179586\n0\nENDSEC\n0\nEOF\n";
    let d = read_drawing(dxf.as_bytes(), Some("inch.dxf"), &Tolerances::default()).unwrap();
    assert_eq!(d.units, "inch");
    let square = d.shape(&["0".into()]).unwrap();
    let expected = (1.0 + PI / 8.0) * 25.4 * 25.4;
    assert!((square.area() - expected).abs() < 1e-6, "{}", square.area());
    let ellipse = d.shape(&["E".into()]).unwrap();
    let expected = PI * 2.0 * 1.0 * 25.4 * 25.4;
    assert!((ellipse.area() - expected).abs() < 0.01 * expected / 100.0 + 0.2, "{}", ellipse.area());
    // A clamped cubic B-spline with collinear control points is the straight line.
    let spline = "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n8\n0\n70\n8\n71\n3\n72\n8\n73\n4\n40\n0\n40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n40\n1\n40\n1\n\
10\n0\n20\n0\n10\n1\n20\n1\n10\n2\n20\n2\n10\n3\n20\n3\n0\nENDSEC\n0\nEOF\n";
    let d = read_drawing(spline.as_bytes(), Some("s.dxf"), &Tolerances::default()).unwrap();
    assert_eq!(d.open.len(), 1);
    assert!(d.open[0].end.distance(DVec2::new(3.0, 3.0)) < 1e-9);
}

#[test]
fn svg_shapes_transforms_and_arcs() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
      <g transform="translate(10 10)">
        <rect x="0" y="0" width="40" height="20" rx="5"/>
        <circle cx="70" cy="10" r="5" transform="scale(1)"/>
      </g>
      <path d="M 10 60 h 30 a 10 10 0 0 1 0 20 h -30 z"/>
      <polygon points="60,60 90,60 75,90"/>
    </svg>"#;
    let d = read_drawing(svg.as_bytes(), Some("t.svg"), &Tolerances::default()).unwrap();
    assert!(d.open.is_empty(), "{:?}", d.open);
    assert_eq!(d.loops.len(), 4);
    let areas: Vec<f64> = d.loops.iter().map(|l| l.path.area().abs()).collect();
    let near = |a: f64| areas.iter().any(|&x| (x - a).abs() < 0.2);
    assert!(near(40.0 * 20.0 - (4.0 - PI) * 25.0), "{areas:?}");
    assert!(near(PI * 25.0), "{areas:?}");
    assert!(near(30.0 * 20.0 + PI * 50.0), "{areas:?}"); // SVG arcs reach us as cubics
    assert!(near(0.5 * 30.0 * 30.0), "{areas:?}");
}

#[test]
fn an_svg_with_a_doctype_line_is_read_and_nothing_it_names_is_fetched() {
    // As matplotlib writes it: a DOCTYPE naming a DTD on the web, and an external entity
    // that must be dropped, never fetched.
    let svg = r#"<?xml version="1.0" encoding="utf-8" standalone="no"?>
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd" [
  <!ENTITY far SYSTEM "http://example.invalid/far.xml">
]>
<svg xmlns="http://www.w3.org/2000/svg" width="50mm" height="50mm" viewBox="0 0 50 50">
  <rect x="5" y="5" width="40" height="30"/>
</svg>"#;
    let d = read_drawing(svg.as_bytes(), Some("plot.svg"), &Tolerances::default()).unwrap();
    assert_eq!(d.loops.len(), 1);
    assert!((d.loops[0].path.area().abs() - 1200.0).abs() < 1e-6);
    // An entity bomb is still refused with a message, not a hang.
    let bomb = format!(
        r#"<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa">{}]><svg xmlns="http://www.w3.org/2000/svg">&j;</svg>"#,
        (b'b'..=b'j').map(|c| format!("<!ENTITY {} \"{}\">", c as char, format!("&{};", (c - 1) as char).repeat(10))).collect::<String>()
    );
    let e = read_drawing(bomb.as_bytes(), Some("bomb.svg"), &Tolerances::default()).unwrap_err();
    assert!(e.to_string().contains("SVG"), "{e}");
}

#[test]
fn real_profiles_read_and_cut_cleanly() {
    let Some(dir) = common::shared_data("profiles") else {
        eprintln!("../shared/data/profiles is absent; skipped");
        return;
    };
    for (file, loops) in [("tm_LM2.dxf", 40), ("tm_1002_tray_bottom.dxf", 24), ("pycam_polygons.svg", 3), ("tm_tray-easy1.svg", 383)] {
        let bytes = std::fs::read(dir.join(file)).unwrap();
        let d = read_drawing(&bytes, Some(file), &Tolerances::default()).unwrap();
        assert_eq!(d.loops.len(), loops, "{file}");
        assert!(d.open.is_empty(), "{file}: {:?}", d.open);
    }
    let bytes = std::fs::read(dir.join("tm_LM2.dxf")).unwrap();
    let d = read_drawing(&bytes, Some("tm_LM2.dxf"), &Tolerances::default()).unwrap();
    let job = job_with(vec![Operation::Profile2d(Profile2d::default())], 3.0);
    let out = job::run(&job, d, &mut Progress::none()).unwrap();
    let report = &out.verification.as_ref().unwrap().report;
    assert!(report.gouge_count == 0 && report.rapid_collision_count == 0, "{}", report.describe());
    let placed = out.drawing.as_ref().unwrap();
    assert!(closest_approach(&out, &placed.shape(&[]).unwrap()) >= 1.5 - 1e-6);
}

/// Material removed by moves that go straight down: a plunge into solid material. The
/// simulation's per-move volumes tell (1e-3 mm³ allows a graze).
fn plunged_volume(out: &job::JobOutput) -> f64 {
    let v = out.verification.as_ref().unwrap();
    out.moves.iter().zip(&v.volumes).filter(|(m, _)| matches!(m.mv, Move::Line { to, .. } if to.z < m.from.z && to.truncate().distance(m.from.truncate()) < 1e-9)).map(|(_, &vol)| vol).sum()
}

#[test]
fn no_operation_plunges_into_solid_material() {
    for op in [
        Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], entry: EntryKind::Helix, ..Pocket2d::default() }),
        Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], entry: EntryKind::Ramp, ..Pocket2d::default() }),
        Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], pattern: PocketPattern::Zigzag, ..Pocket2d::default() }),
        Operation::Pocket2d(Pocket2d { layers: vec!["POCKET".into()], pattern: PocketPattern::Adaptive, stepover_fraction: 0.1, ..Pocket2d::default() }),
        Operation::Profile2d(Profile2d { layers: vec!["CUT".into()], tabs: Tabs { count: 3, ..Tabs::default() }, ..Profile2d::default() }),
    ] {
        let mut job = job_with(vec![op.clone()], 6.0);
        job.simulation.cell = Some(0.2);
        let out = job::run(&job, plate(), &mut Progress::none()).unwrap();
        let plunged = plunged_volume(&out);
        assert!(plunged < 1e-3, "{}: {plunged} mm³ removed by straight plunges", op.name());
    }
}

#[test]
fn climb_and_conventional_run_opposite_ways_and_leave_stock_is_left() {
    // Outside a loop, climb milling with a clockwise spindle runs clockwise.
    let signed_area = |out: &job::JobOutput| -> f64 {
        let pts: Vec<DVec2> = out.paths[0].moves.iter().filter(|m| m.to().z < -1.0).map(|m| m.to().truncate()).collect();
        pts.windows(2).map(|w| w[0].perp_dot(w[1])).sum::<f64>() * 0.5
    };
    let outline = |direction| Profile2d { layers: vec!["CUT".into()], loops: vec![0], direction, lead_radius: Some(0.0), ..Profile2d::default() };
    let climb = job::run(&job_with(vec![Operation::Profile2d(outline(Direction::Climb))], 3.0), plate(), &mut Progress::none()).unwrap();
    let conventional = job::run(&job_with(vec![Operation::Profile2d(outline(Direction::Conventional))], 3.0), plate(), &mut Progress::none()).unwrap();
    assert!(signed_area(&climb) < 0.0 && signed_area(&conventional) > 0.0);
    let leave = Profile2d { layers: vec!["CUT".into()], leave_stock: 0.5, ..Profile2d::default() };
    let out = job::run(&job_with(vec![Operation::Profile2d(leave)], 3.0), plate(), &mut Progress::none()).unwrap();
    let shape = out.drawing.as_ref().unwrap().shape(&["CUT".into()]).unwrap();
    assert!(closest_approach(&out, &shape) >= 2.0 - 1e-6);
    let report = &out.verification.as_ref().unwrap().report;
    assert!(report.is_clean(), "{}", report.describe());
}

/// A drawing of `loops` on layer 0, in millimetres.
fn drawing_of(loops: Vec<Loop>) -> Drawing {
    let loops = loops.into_iter().map(|path| DrawnLoop { layer: "0".into(), path }).collect();
    Drawing { loops, layers: vec!["0".into()], units: "mm".into(), scale: 1.0, ..Drawing::default() }
}

/// A sheet part at `x`: a 30 × 20 outline with a round hole and a square one.
fn part_at(x: f64) -> Vec<Loop> {
    vec![Loop::rect(DVec2::new(x, 0.0), DVec2::new(x + 30.0, 20.0)), Loop::circle(DVec2::new(x + 8.0, 10.0), 4.0), Loop::rect(DVec2::new(x + 16.0, 6.0), DVec2::new(x + 24.0, 14.0))]
}

/// Runs a profile of every loop and checks what every drawing job must hold: no tool-centre
/// point of a cut closer to any drawn loop than the radius plus leave-stock (densely along
/// lines and arcs), and a clean simulation against the part the whole drawing means.
fn profile_every_loop(d: Drawing, diameter: f64, profile: Profile2d) -> job::JobOutput {
    let leave = profile.leave_stock;
    let mut job = job_with(vec![Operation::Profile2d(profile)], diameter);
    job.simulation.cell = Some(0.1);
    let out = job::run(&job, d, &mut Progress::none()).unwrap();
    let all = out.drawing.as_ref().unwrap().shape(&[]).unwrap();
    let (gap, at) = approach_at(&out, &all);
    assert!(gap >= diameter / 2.0 + leave - 1e-6, "a cut came {gap:.6} mm from the drawing at {at}");
    let report = &out.verification.as_ref().unwrap().report;
    assert!(report.is_clean(), "{}", report.describe());
    out
}

#[test]
fn holes_smaller_than_the_tool_are_named_in_one_warning() {
    // A plate with 14 holes of φ4 (a φ6 tool fits none) and one of φ10.
    let mut loops = vec![Loop::rect(DVec2::ZERO, DVec2::new(160.0, 30.0))];
    loops.extend((0..14).map(|k| Loop::circle(DVec2::new(8.0 + 10.0 * k as f64, 8.0), 2.0)));
    loops.push(Loop::circle(DVec2::new(80.0, 21.0), 5.0));
    let out = profile_every_loop(drawing_of(loops), 6.0, Profile2d::default());
    let small: Vec<&swarf::error::Warning> = out.warnings.iter().filter(|w| w.message.contains("not cut")).collect();
    assert_eq!(small.len(), 1, "{:?}", out.warnings);
    assert!(small[0].message.starts_with("14 loops are smaller than the φ6.000 tool"), "{}", small[0]);
    assert!(small[0].message.contains("loops 1, 2, 3") && small[0].message.contains("and 2 more"), "{}", small[0]);
}

#[test]
fn parts_nested_closer_than_the_tool_are_never_cut_into() {
    // Two parts 4.04 mm apart: a φ6 tool cannot pass between them, a φ3 can.
    let pair = || drawing_of([part_at(0.0), part_at(34.04)].concat());
    let out = profile_every_loop(pair(), 6.0, Profile2d::default());
    let merged: Vec<&swarf::error::Warning> = out.warnings.iter().filter(|w| w.message.contains("apart")).collect();
    assert_eq!(merged.len(), 1, "{:?}", out.warnings);
    assert!(merged[0].message.contains("loops 0 and 3 are 4.040 mm apart near (32.020,"), "{}", merged[0]);
    // One path around both outlines, holes inside each: five laps at the final depth.
    let out = profile_every_loop(pair(), 3.0, Profile2d::default());
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    // Lead arcs twice as wide as the gap still keep off the neighbour.
    let leads = Profile2d { lead_radius: Some(5.0), ..Profile2d::default() };
    let out = profile_every_loop(pair(), 3.0, leads);
    assert!(out.gcode.contains("G2") || out.gcode.contains("G3"));
    // A row of five parts 2 mm apart, with leave-stock, climb and conventional.
    let row = || drawing_of((0..5).flat_map(|k| part_at(k as f64 * 32.0)).collect());
    for direction in [Direction::Climb, Direction::Conventional] {
        let out = profile_every_loop(row(), 6.0, Profile2d { leave_stock: 0.3, direction, ..Profile2d::default() });
        assert_eq!(out.warnings.iter().filter(|w| w.message.contains("2.000 mm apart")).count(), 4, "{:?}", out.warnings);
    }
    // Only the first part picked: its path still keeps off its neighbour.
    let out = profile_every_loop(pair(), 6.0, Profile2d { loops: vec![0, 1, 2], ..Profile2d::default() });
    assert!(out.warnings.iter().any(|w| w.message.contains("loops 0 and 3")), "{:?}", out.warnings);
}

#[test]
fn holes_near_outlines_and_parts_nested_in_cut_outs() {
    // A hole 1 mm from the outline; a cut-out holding a small part 2 mm from its wall.
    let loops = vec![
        Loop::rect(DVec2::ZERO, DVec2::new(80.0, 50.0)),
        Loop::rect(DVec2::new(1.0, 10.0), DVec2::new(15.0, 40.0)),
        Loop::rect(DVec2::new(30.0, 10.0), DVec2::new(70.0, 40.0)),
        Loop::circle(DVec2::new(50.0, 25.0), 13.0),
    ];
    for (diameter, merges) in [(1.0, false), (3.0, true), (6.0, true)] {
        let out = profile_every_loop(drawing_of(loops.clone()), diameter, Profile2d { lead_radius: Some(4.0), ..Profile2d::default() });
        let named = out.warnings.iter().any(|w| w.message.contains("loops 2 and 3 are 2.000 mm apart"));
        assert_eq!(named, merges, "φ{diameter}: {:?}", out.warnings);
    }
}

/// A DXF of LINE, ARC, CIRCLE and ELLIPSE entities (`$INSUNITS` = `units`).
fn dxf(units: u32, entities: &[String]) -> Drawing {
    let text = format!("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n{units}\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{}0\nENDSEC\n0\nEOF\n", entities.concat());
    read_drawing(text.as_bytes(), Some("t.dxf"), &Tolerances::default()).unwrap()
}

fn line(a: DVec2, b: DVec2) -> String {
    format!("0\nLINE\n8\n0\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n", a.x, a.y, b.x, b.y)
}

fn arc(c: DVec2, r: f64, from: f64, to: f64) -> String {
    format!("0\nARC\n8\n0\n10\n{}\n20\n{}\n40\n{r}\n50\n{from}\n51\n{to}\n", c.x, c.y)
}

#[test]
fn large_inch_arcs_keep_the_radius_in_both_units() {
    // A 40° sector of radius 9.5 in with a 0.3 in hole, drawn in inches.
    let (r, sweep) = (9.5, 40f64.to_radians());
    let tip = DVec2::new(r * sweep.cos(), r * sweep.sin());
    let circle = "0\nCIRCLE\n8\n0\n10\n5\n20\n1.5\n40\n0.3\n".to_string();
    let d = dxf(1, &[line(DVec2::ZERO, DVec2::new(r, 0.0)), arc(DVec2::ZERO, r, 0.0, 40.0), line(tip, DVec2::ZERO), circle]);
    // The same drawing built here from its closed form, in mm.
    let k = 25.4;
    let exact = Shape::new(vec![
        Loop {
            vertices: vec![
                swarf::drawing::Vertex { p: DVec2::ZERO, bulge: 0.0 },
                swarf::drawing::Vertex { p: DVec2::new(r * k, 0.0), bulge: (sweep / 4.0).tan() },
                swarf::drawing::Vertex { p: tip * k, bulge: 0.0 },
            ],
        },
        Loop::circle(DVec2::new(5.0, 1.5) * k, 0.3 * k),
    ]);
    for units in [swarf::mesh::placement::Units::Mm, swarf::mesh::placement::Units::Inch] {
        let mut job = job_with(vec![Operation::Profile2d(Profile2d::default())], 6.0);
        job.drawing.origin = swarf::job::DrawingOrigin::Keep;
        job.post.units = units;
        job.simulation.cell = Some(0.25);
        let out = job::run(&job, d.clone(), &mut Progress::none()).unwrap();
        let (gap, at) = approach_at(&out, &exact);
        assert!(gap >= 3.0 - 1e-6, "{units:?}: {gap} at {at}");
        assert!(out.verification.as_ref().unwrap().report.is_clean());
    }
}

#[test]
fn ellipses_keep_the_radius_within_the_arc_fit() {
    // An elliptical plate (semi-axes 40 and 16) with an elliptical hole, and a half ellipse
    // closed by a line; in mm.
    let ellipse = |c: DVec2, major: DVec2, ratio: f64, from: f64, to: f64| format!("0\nELLIPSE\n8\n0\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n40\n{ratio}\n41\n{from}\n42\n{to}\n", c.x, c.y, major.x, major.y);
    let (c1, c2) = (DVec2::new(100.0, 100.0), DVec2::new(200.0, 100.0));
    let d = dxf(
        4,
        &[
            ellipse(c1, DVec2::new(40.0, 0.0), 0.4, 0.0, 2.0 * PI),
            ellipse(c1, DVec2::new(6.0, 8.0), 0.5, 0.0, 2.0 * PI),
            ellipse(c2, DVec2::new(0.0, 40.0), 0.3, 0.0, PI),
            line(c2 + DVec2::new(0.0, 40.0), c2 - DVec2::new(0.0, 40.0)),
        ],
    );
    // The curves as 20,000-sided polygons: closer to them than 2e-6 mm.
    let polygon = |c: DVec2, major: DVec2, ratio: f64, from: f64, to: f64, closed: bool| {
        let n = 20_000;
        let mut pts: Vec<DVec2> = (0..=n)
            .map(|i| {
                let t = from + (to - from) * i as f64 / n as f64;
                c + major * t.cos() + major.perp() * ratio * t.sin()
            })
            .collect();
        if closed {
            pts.pop();
        }
        Loop::polygon(&pts)
    };
    let exact = Shape::new(vec![
        polygon(c1, DVec2::new(40.0, 0.0), 0.4, 0.0, 2.0 * PI, true),
        polygon(c1, DVec2::new(6.0, 8.0), 0.5, 0.0, 2.0 * PI, true),
        polygon(c2, DVec2::new(0.0, 40.0), 0.3, 0.0, PI, false),
    ]);
    let mut job = job_with(vec![Operation::Profile2d(Profile2d::default())], 6.0);
    job.drawing.origin = swarf::job::DrawingOrigin::Keep;
    job.simulation.cell = Some(0.25);
    let out = job::run(&job, d, &mut Progress::none()).unwrap();
    let (gap, at) = approach_at(&out, &exact);
    let fit = Tolerances::default().arc_fit;
    assert!(gap >= 3.0 - fit - 2e-6, "{gap} at {at}");
    assert!(out.verification.as_ref().unwrap().report.is_clean());
}

#[test]
fn a_fanuc_program_with_a_problem_keeps_its_tape_mark_first() {
    // Flutes 2 mm long on a cut 6.2 mm deep: the simulation finds the tool's body in material.
    let mut job = job_with(vec![Operation::Profile2d(Profile2d::default())], 3.0);
    job.tools[0].cutter.flute_length = 2.0;
    job.post.dialect = Dialect::Fanuc;
    let out = job::run(&job, drawing_of(part_at(0.0)), &mut Progress::none()).unwrap();
    assert!(out.problem.is_some(), "{:?}", out.problem);
    let marked = out.gcode_marked();
    assert!(marked.starts_with("%\n(WARNING: NOT SAFE TO RUN"), "{}", &marked[..80]);
    assert!(marked.trim_end().ends_with('%'));
    // Rapids at or below the stock's top are refused before anything is made.
    job.stock.clearance = -1.0;
    let e = job::run(&job, drawing_of(part_at(0.0)), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("stock.clearance") && e.contains("-1"), "{e}");
}

/// Seed 004 §3 on a drawing: the zigzag pocket's passes hold the tool's load at the
/// step-over's, by extra path or by the feed, as the project's own simulation counts it (over
/// windows of three Δs, entries left out); the plain passes slot at the full diameter.
#[test]
fn a_zigzag_pocket_holds_its_load() {
    use swarf::operations::LoadControl;
    let (stepover, stepdown, feed) = (0.4, 1.5, 800.0);
    let reference = 6.0 * stepover * stepdown * feed;
    let mut seconds = Vec::new();
    for load in [LoadControl::None, LoadControl::Feed, LoadControl::Path] {
        let pocket = Pocket2d { layers: vec!["POCKET".into()], depth: 1.5, stepdown, stepover_fraction: stepover, pattern: PocketPattern::Zigzag, load, ..Pocket2d::default() };
        let mut job = job_with(vec![Operation::Pocket2d(pocket)], 6.0);
        job.simulation.cell = Some(0.1);
        let out = job::run(&job, plate(), &mut Progress::none()).unwrap();
        let v = out.verification.as_ref().unwrap();
        assert!(v.report.is_clean(), "{load:?}: {}", v.report.describe());
        let rates = swarf::sim::windows::windowed_rates(&out.moves, &out.stock, 0.05, 3.0 * 0.5 * 6.0 * stepover).unwrap();
        let worst = rates.iter().copied().fold(0.0, f64::max) / reference;
        eprintln!("{load:?}: {} ; simulated peak {worst:.2} over {} windows", out.operations[0].describe(), rates.len());
        match load {
            LoadControl::None => assert!(worst > 2.0, "the plain passes slot: {worst}"),
            _ => assert!(worst <= 1.15, "{load:?}: {worst}"),
        }
        if load == LoadControl::Path {
            assert!(out.gcode.contains("G2") || out.gcode.contains("G3"));
        }
        seconds.push(out.operations[0].seconds);
    }
    // Held, the pocket takes longer at the tool's feed than the plain one (which overloads).
    assert!(seconds[1] > seconds[0] && seconds[2] > seconds[0], "{seconds:?}");
}

/// A plate 80 × 60 whose φ20 hole at (40, 30) is drawn as `n` lines, and whose top-right
/// corner is rounded (r 10) by `fillet` lines: an SVG as an exporter flattening curves writes it.
fn finely_drawn_plate(n: usize, fillet: usize) -> String {
    let hole: Vec<String> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            format!("{:.9},{:.9}", 40.0 + 10.0 * t.cos(), 30.0 + 10.0 * t.sin())
        })
        .collect();
    let mut outline = vec!["0,0".to_string(), "80,0".to_string()];
    outline.extend((0..=fillet).map(|k| {
        let t = std::f64::consts::FRAC_PI_2 * k as f64 / fillet as f64;
        format!("{:.9},{:.9}", 70.0 + 10.0 * t.cos(), 50.0 + 10.0 * t.sin())
    }));
    outline.push("0,60".into());
    format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="80mm" height="60mm" viewBox="0 0 80 60"><polygon points="{}"/><polygon points="{}"/></svg>"#, outline.join(" "), hole.join(" "))
}

#[test]
fn a_curve_drawn_finely_divided_is_the_curve() {
    let tol = Tolerances::default();
    let area = 80.0 * 60.0 - (100.0 - 25.0 * PI) - 100.0 * PI;
    for (n, fillet) in [(100_000, 2_000), (5_000, 500), (64, 2)] {
        let text = finely_drawn_plate(n, fillet);
        let (d, read_in) = common::cpu_timed(|| read_drawing(text.as_bytes(), Some("plate.svg"), &tol).unwrap());
        assert!(d.open.is_empty(), "{n}: open {:?}", d.open.iter().map(|o| (o.start, o.end, o.segments)).collect::<Vec<_>>());
        assert_eq!(d.loops.len(), 2, "{n}: {:?} (ignored {:?})", d.loops.iter().map(|l| l.path.area()).collect::<Vec<_>>(), d.ignored);
        let shape = Shape::new(d.loops.iter().map(|l| l.path.clone()).collect());
        // The chords' sagitta: the polygon's own area, less than the circle's.
        let sag = |k: usize, r: f64, turn: f64| r * r * 0.5 * (turn - k as f64 * (turn / k as f64).sin());
        let expected = area + sag(n, 10.0, std::f64::consts::TAU) - sag(fillet, 10.0, std::f64::consts::FRAC_PI_2);
        assert!((shape.area() - expected).abs() < 2e-3 * 100.0, "{n}: area {} vs {expected}", shape.area());
        let pieces: usize = d.loops.iter().map(|l| l.path.len()).sum();
        if n >= 5_000 {
            // Fitted: a handful of arcs, not thousands of lines.
            assert!(pieces < 40, "{n}: {pieces} pieces");
            assert!(read_in < 2.0, "{n}: read in {read_in:.2} s of CPU");
        }
        // A φ3 tool profiles the plate and its hole, never closer to it than its radius.
        let profile = Profile2d::default();
        let out = job::run(&job_with(vec![Operation::Profile2d(profile)], 3.0), d, &mut Progress::none()).unwrap_or_else(|e| panic!("{n}: {e}"));
        let placed = out.drawing.as_ref().unwrap();
        let placed = Shape::new(placed.loops.iter().map(|l| l.path.clone()).collect());
        let approach = closest_approach(&out, &placed);
        assert!(approach >= 1.5 - 2.0 * tol.arc_fit, "{n}: a cutting move came {approach} from the drawing");
        // The hole is cut: some cutting move lies within 8.5 mm of its centre.
        let centre = placed.bounds().min + DVec2::new(40.0, 30.0);
        assert!(out.paths.iter().flat_map(|p| &p.moves).any(|m| !m.is_rapid() && (m.to().truncate() - centre).length() < 8.6), "{n}: the hole is not cut");
    }
}

/// A perforated panel: `n` φ4 holes at an 8 mm pitch inside its outline, as a DXF.
fn panel(n: usize) -> String {
    let cols = ((n as f64 * 1.5).sqrt().ceil()) as usize;
    let rows = n.div_ceil(cols);
    let (w, h) = ((cols * 8 + 10) as f64, (rows * 8 + 10) as f64);
    let mut s = String::from("0\nSECTION\n2\nENTITIES\n");
    s += &format!("0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n{w}\n20\n0\n10\n{w}\n20\n{h}\n10\n0\n20\n{h}\n");
    for k in 0..n {
        s += &format!("0\nCIRCLE\n8\n0\n10\n{}\n20\n{}\n40\n2\n", 9 + (k % cols) * 8, 9 + (k / cols) * 8);
    }
    s + "0\nENDSEC\n0\nEOF\n"
}

/// Issue 56: a panel's holes are read and nested in time in proportion to their number (100,000
/// holes took 15 s, each compared with every other to find which holds which; now under a
/// second): ten times the holes take well under a hundred times as long.
#[test]
fn a_perforated_panel_reads_in_proportion_to_its_holes() {
    let time = |n: usize| {
        let text = panel(n);
        let ((), took) = common::cpu_timed(|| {
            let d = read_drawing(text.as_bytes(), Some("panel.dxf"), &Tolerances::default()).unwrap();
            assert_eq!(d.loops.len(), n + 1);
            // Its holes found inside its plate (as every listing and operation finds them).
            let shape = Shape::new(d.loops.iter().map(|l| l.path.clone()).collect());
            assert_eq!(shape.regions().len(), 1, "one plate with its holes");
        });
        took
    };
    let (small, large) = (time(5_000).max(1e-3), time(50_000));
    eprintln!("panel: 5,000 holes {small:.3} s, 50,000 {large:.3} s of CPU");
    assert!(large < 40.0 * small, "5,000 holes read in {small:.3} s, 50,000 in {large:.3} s of CPU");
}

/// Issue 92: a profile's scrap is not material left on the part. The sample plate profiled
/// round its outline and holes: the sheet beyond the kerf and the holes' slugs fall away, and
/// the simulation's "material left on the part" was the scrap's height (the sheet's whole
/// thickness, painted as stock to remove). What is left on the part is now the part's own: its
/// top untouched, its walls cut to the drawing.
#[test]
fn a_profiles_scrap_is_not_material_left_on_the_part() {
    let d = read_drawing(plate_dxf().as_bytes(), Some("plate.dxf"), &Tolerances::default()).unwrap();
    let out = job::run(&job_with(vec![Operation::Profile2d(Profile2d::default())], 3.0), d, &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let thickness = -out.stock.min.z;
    assert!(v.report.residual_max < 0.25 * thickness, "{} mm left of a {thickness} mm sheet: {}", v.report.residual_max, v.report.describe());
}
