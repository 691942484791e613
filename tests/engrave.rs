//! Engraving: open chains and chosen loops cut with the tool's centre on the line, in passes no
//! deeper than the step-down, never fed straight down into material; the program verified
//! clean against the grooves the drawing means.

use swarf::cutter::Cutter;
use swarf::drawing::import::read_drawing;
use swarf::geom::Tolerances;
use swarf::job::{self, Job, Operation, Tool};
use swarf::operations::Engrave;
use swarf::operations::Profile2d;
use swarf::progress::Progress;
use swarf::toolpath::Move;

/// A 60 × 40 plate outline (layer CUT), a "Z" and an arc drawn as open polylines (layer TEXT),
/// and a small closed square (layer TEXT) to engrave by its index.
fn drawing_dxf() -> String {
    let mut s = String::from("0\nSECTION\n2\nENTITIES\n");
    let line = |s: &mut String, layer: &str, a: (f64, f64), b: (f64, f64)| {
        s.push_str(&format!("0\nLINE\n8\n{layer}\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n", a.0, a.1, b.0, b.1));
    };
    for (a, b) in [((0.0, 0.0), (60.0, 0.0)), ((60.0, 0.0), (60.0, 40.0)), ((60.0, 40.0), (0.0, 40.0)), ((0.0, 40.0), (0.0, 0.0))] {
        line(&mut s, "CUT", a, b);
    }
    // The Z: three strokes.
    for (a, b) in [((10.0, 30.0), (25.0, 30.0)), ((25.0, 30.0), (10.0, 10.0)), ((10.0, 10.0), (25.0, 10.0))] {
        line(&mut s, "TEXT", a, b);
    }
    // An open arc: centre (40, 20), radius 8, from 0° to 180°.
    s.push_str("0\nARC\n8\nTEXT\n10\n40\n20\n20\n40\n8\n50\n0\n51\n180\n");
    for (a, b) in [((45.0, 5.0), (52.0, 5.0)), ((52.0, 5.0), (52.0, 9.0)), ((52.0, 9.0), (45.0, 9.0)), ((45.0, 9.0), (45.0, 5.0))] {
        line(&mut s, "TEXT", a, b);
    }
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

fn job(ops: Vec<Operation>) -> Job {
    let tool = Tool { number: 1, cutter: Cutter::flat(1.0), feed_rate: 600.0, plunge_rate: 150.0, ..Tool::default() };
    Job { tools: vec![tool], operations: ops, ..Job::default_for_drawing() }
}

#[test]
fn open_chains_and_a_picked_loop_are_engraved_in_passes_ramping_down_and_verified_clean() {
    let drawing = read_drawing(drawing_dxf().as_bytes(), Some("z.dxf"), &Tolerances::default()).unwrap();
    assert_eq!(drawing.open.len(), 2, "the Z and the arc are open chains");
    let square = drawing.loops.iter().position(|l| l.layer == "TEXT").unwrap();
    let engrave = Engrave { layers: vec!["TEXT".into()], loops: vec![square], depth: 1.2, stepdown: 0.5, ..Engrave::default() };
    let profile = Profile2d { layers: vec!["CUT".into()], ..Profile2d::default() };
    let out = job::run(&job(vec![Operation::Engrave(engrave), Operation::Profile2d(profile)]), drawing.clone(), &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    assert!(v.report.is_clean(), "{}", v.report.describe());
    let path = &out.paths[0];
    let (mut at, mut deepest, mut passes_down) = (path.start, 0.0f64, 0);
    for m in &path.moves {
        let to = m.to();
        if let Move::Line { .. } = m {
            // Never straight down below the sheet's top: every descent into material runs along the line.
            let straight_down = to.truncate().distance(at.truncate()) < 1e-9 && to.z < at.z;
            assert!(!(straight_down && to.z < -1e-9), "a plunge into material to {to}");
        }
        if !m.is_rapid() && to.z < at.z - 1e-9 {
            passes_down += 1;
        }
        deepest = deepest.min(to.z);
        at = to;
    }
    assert!((deepest + 1.2).abs() < 1e-6, "engraved to {deepest}, not -1.2");
    assert!(passes_down > 6, "{passes_down} descending moves for 3 passes on 3 lines");
    // Every point of the Z's strokes is cut at full depth: the groove's centre lies on the line.
    let on_z = |x: f64, y: f64| path.moves.iter().any(|m| !m.is_rapid() && (m.to().z + 1.2).abs() < 1e-6 && m.to().truncate().distance(swarf::geom::DVec2::new(x, y)) < 1e-6);
    assert!(on_z(25.0, 30.0) && on_z(10.0, 10.0), "the Z's corners at full depth");
    // The program reads back as written.
    assert!(out.gcode.contains("(engrave)"));
}

#[test]
fn nothing_to_engrave_and_bad_settings_are_named() {
    let drawing = read_drawing(drawing_dxf().as_bytes(), Some("z.dxf"), &Tolerances::default()).unwrap();
    let only_cut = Engrave { layers: vec!["CUT".into()], ..Engrave::default() };
    let e = job::run(&job(vec![Operation::Engrave(only_cut)]), drawing.clone(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("no open chains on its layers"), "{e}");
    let deep = Engrave { depth: 50.0, ..Engrave::default() };
    let e = job::run(&job(vec![Operation::Engrave(deep)]), drawing.clone(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("deeper than the"), "{e}");
    let bad = Engrave { stepdown: 0.0, ..Engrave::default() };
    let e = job::run(&job(vec![Operation::Engrave(bad)]), drawing, &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("operations[0].stepdown"), "{e}");
}
