//! Every malformed file and absurd setting answered in seconds (issue 42): the cases of
//! `../shared/data/bad/` run through the `swarf` binary under a 1 GB memory limit, each within
//! 5 s, with a message naming the file's element or the job's field (or a program with a
//! warning where the file holds elements that draw nothing), never a panic, a stack overflow, a
//! memory abort or a file cut short machined as if whole; and one generated case of each class,
//! run in the process, that needs no shared data.

mod common;

use std::os::unix::process::ExitStatusExt;
use std::process::Command;

use swarf::geom::{DVec3, Tolerances};
use swarf::job::{self, Job, Workpiece};
use swarf::progress::Progress;

/// The most CPU time any case may take (s) with all its work on one thread (they take 0.1 s):
/// CPU time, which a busy machine does not stretch as it does the wall clock's.
const SECONDS: f64 = 5.0;

/// The CPU time a case run by the `swarf` binary may take (s), over all its threads (the
/// command line works on every core: two here, so twice [`SECONDS`]); past it the kernel stops
/// the run (`ulimit -t`, SIGXCPU).
const CLI_CPU_SECONDS: u32 = 10;

/// What each row of `MANIFEST.tsv` must answer, by its number (`tests/bad_cases.tsv`, which the
/// page's test reads too): `Err(words)` an error whose message holds the words, `Ok(words)` a
/// program with a warning that holds them.
fn expected(file: &str) -> Option<Result<String, String>> {
    let table = include_str!("bad_cases.tsv");
    table.lines().skip(1).find_map(|row| {
        let [tags, answer, words, ..] = row.split('\t').collect::<Vec<_>>()[..] else { return None };
        tags.split(' ').any(|t| t == &file[..3]).then(|| if answer == "warning" { Ok(words.to_string()) } else { Err(words.to_string()) })
    })
}

#[test]
fn every_shared_bad_case_is_answered_in_seconds_within_a_gigabyte() {
    let Some(dir) = common::shared_data("bad") else { return };
    let manifest = std::fs::read_to_string(dir.join("MANIFEST.tsv")).unwrap();
    let out_dir = std::env::temp_dir().join(format!("swarf-bad-{}", std::process::id()));
    std::fs::create_dir_all(&out_dir).unwrap();
    let mut failures = Vec::new();
    let mut count = 0;
    for row in manifest.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let cols: Vec<&str> = row.split('\t').collect();
        let (file, job) = (cols[0], cols[1]);
        // A `*_value.json` row is the job itself, run on the part its second column names.
        let (job_path, part_path) = if job.starts_with("job_") {
            (dir.join(job), dir.join(file))
        } else {
            let part = job.split("part: ").nth(1).and_then(|p| p.strip_suffix(')')).unwrap();
            (dir.join(file), dir.join(part))
        };
        let Some(want) = expected(file) else {
            failures.push(format!("{file}: a new case; say what it must answer"));
            continue;
        };
        let program = out_dir.join(format!("{file}.ngc"));
        let _ = std::fs::remove_file(&program);
        // `ulimit -v`: the address space a run may take, 1 GB; `ulimit -t`: its CPU time.
        let script = format!("ulimit -v 1048576; ulimit -t {CLI_CPU_SECONDS}; exec \"$0\" run \"$1\" \"$2\" -o \"$3\" -q");
        let out = Command::new("sh").args(["-c", &script, env!("CARGO_BIN_EXE_swarf")]).arg(&job_path).arg(&part_path).arg(&program).output().unwrap();
        count += 1;
        let stderr = String::from_utf8_lossy(&out.stderr);
        let text = format!("{}{stderr}", String::from_utf8_lossy(&out.stdout));
        let code = out.status.code();
        if matches!(out.status.signal(), Some(libc::SIGXCPU | libc::SIGKILL)) {
            failures.push(format!("{file}: stopped after {CLI_CPU_SECONDS} s of CPU"));
            continue;
        }
        if stderr.contains("panicked") || stderr.contains("overflow") || stderr.contains("memory allocation") || !matches!(code, Some(0 | 1)) {
            failures.push(format!("{file}: died (exit {code:?}): {}", stderr.lines().take(3).collect::<Vec<_>>().join(" / ")));
            continue;
        }
        match want {
            Err(words) => {
                if code != Some(1) || !text.contains(&words) {
                    failures.push(format!("{file}: expected an error saying '{words}', got exit {code:?}: {}", text.trim()));
                } else if program.exists() {
                    failures.push(format!("{file}: refused, yet a program was written"));
                }
            }
            Ok(words) => {
                if code != Some(0) || !text.contains(&words) || !program.exists() {
                    failures.push(format!("{file}: expected a program and a warning saying '{words}', got exit {code:?}: {}", text.trim()));
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&out_dir);
    assert!(count >= 40, "only {count} cases in the manifest");
    assert!(failures.is_empty(), "{} of {count} cases answered wrongly:\n{}", failures.len(), failures.join("\n"));
}

/// Reads `bytes` as the file `name` and runs the job on it, within [`SECONDS`] of CPU: the
/// error's message, or the run's warnings.
fn answer(job: &Job, bytes: &[u8], name: &str) -> Result<Vec<String>, String> {
    let (result, took) = common::cpu_timed(|| Workpiece::read(bytes, Some(name), &job.tolerances).and_then(|w| job::run(job, w, &mut Progress::none())));
    assert!(took < SECONDS, "{name}: took {took:.2} s of CPU");
    result.map(|out| out.warnings.iter().map(|w| w.message.clone()).collect()).map_err(|e| e.to_string())
}

fn refused(job: &Job, bytes: &[u8], name: &str, words: &str) {
    match answer(job, bytes, name) {
        Err(e) => assert!(e.contains(words), "{name}: the message does not say '{words}': {e}"),
        Ok(_) => panic!("{name}: machined, though it should be refused ('{words}')"),
    }
}

fn warned(job: &Job, bytes: &[u8], name: &str, words: &str) {
    match answer(job, bytes, name) {
        Ok(warnings) => assert!(warnings.iter().any(|w| w.contains(words)), "{name}: no warning says '{words}': {warnings:?}"),
        Err(e) => panic!("{name}: refused ({e}), though it holds a drawing to machine"),
    }
}

/// Each job of `cases` (JSON) is refused on the workpiece in `bytes` within the time allowed,
/// its message saying the case's words.
fn settings_refused(cases: &[(serde_json::Value, &str)], bytes: &[u8], name: &str) {
    for (value, words) in cases {
        let (result, took) = common::cpu_timed(|| Job::from_value(value).and_then(|job| job::run(&job, Workpiece::read(bytes, Some(name), &job.tolerances)?, &mut Progress::none())));
        assert!(took < SECONDS, "{value}: took {took:.2} s of CPU");
        match result {
            Err(e) => assert!(e.to_string().contains(words), "expected '{words}': {e}"),
            Ok(_) => panic!("accepted a job that should be refused ('{words}')"),
        }
    }
}

/// A profile of a drawing with a φ3 flat end, its program simulated.
fn drawing_job() -> Job {
    Job { operations: vec![job::Operation::Profile2d(swarf::operations::Profile2d::default())], ..Job::default() }
}

/// A DXF of a 40 mm square and a circle, with `extra` entities after them, ending as given.
fn dxf(extra: &str, end: &str) -> Vec<u8> {
    let square = "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n40\n20\n0\n10\n40\n20\n40\n10\n0\n20\n40\n";
    format!("0\nSECTION\n2\nENTITIES\n{square}0\nCIRCLE\n8\n0\n10\n20\n20\n20\n40\n8\n{extra}0\nENDSEC\n{end}").into_bytes()
}

fn svg(inner: &str, view_box: &str) -> Vec<u8> {
    format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" viewBox=\"{view_box}\"><rect x=\"10\" y=\"10\" width=\"60\" height=\"40\"/>{inner}</svg>").into_bytes()
}

#[test]
fn generated_drawings_cut_short_out_of_range_or_endless_are_refused_at_once() {
    let job = drawing_job();
    let eof = "0\nEOF\n";
    // Cut short: no EOF marker.
    refused(&job, &dxf("", ""), "cut.dxf", "without its EOF marker");
    // Out of range, and curves that would never end.
    refused(&job, &dxf("0\nCIRCLE\n8\n0\n10\n0\n20\n0\n40\n1e308\n", eof), "huge.dxf", "larger than any machine");
    refused(&job, &dxf("0\nLINE\n8\n0\n10\n0\n20\n0\n11\n1e300\n21\n0\n", eof), "far.dxf", "out of range for any drawing");
    let ellipse = |end: &str, ratio: &str| format!("0\nELLIPSE\n8\n0\n10\n20\n20\n20\n11\n5\n21\n0\n40\n{ratio}\n41\n0\n42\n{end}\n");
    refused(&job, &dxf(&ellipse("1e300", "0.5"), eof), "ellipse-end.dxf", "not an angle");
    refused(&job, &dxf(&ellipse("6.2", "1e308"), eof), "ellipse-ratio.dxf", "larger than any machine");
    let spline = |degree: &str, weight: &str| {
        let mut s = format!("0\nSPLINE\n8\n0\n71\n{degree}\n");
        for k in [0, 0, 0, 0, 1, 1, 1, 1] {
            s += &format!("40\n{k}\n");
        }
        for (x, y) in [(0, 0), (10, 5), (20, 5), (30, 0)] {
            s += &format!("10\n{x}\n20\n{y}\n41\n{weight}\n");
        }
        s
    };
    refused(&job, &dxf(&spline("1e20", "1"), eof), "spline-degree.dxf", "SPLINE of degree");
    refused(&job, &dxf(&spline("3", "0"), eof), "spline-weights.dxf", "weight of 0");
    // A good spline of the same shape still reads.
    assert!(answer(&job, &dxf(&spline("3", "1"), eof), "spline.dxf").is_ok());
    // SVG: nesting, transforms and sizes past any machine.
    let deep = format!("{}{}", "<g>".repeat(100_000), "</g>".repeat(100_000));
    refused(&job, &svg(&deep, "0 0 100 100"), "deep.svg", "nest deeper than 256");
    refused(&job, &svg("<g transform=\"scale(1e200) scale(1e200)\"><circle r=\"5\"/></g>", "0 0 100 100"), "scale.svg", "larger than any machine");
    refused(&job, &svg("<circle cx=\"5\" cy=\"5\" r=\"1e308\"/>", "0 0 100 100"), "circle.svg", "larger than any machine");
    refused(&job, &svg("<ellipse rx=\"1e308\" ry=\"1e-308\"/>", "0 0 100 100"), "ellipse.svg", "larger than any machine");
    refused(&job, &svg("<path d=\"M 0 0 L 1e308 5 L 5 5 Z\"/>", "0 0 100 100"), "path.svg", "out of range for any drawing");
    refused(&job, &svg("<ellipse rx=\"4\" ry=\"2\"/>", "0 7e117 1 100"), "far.svg", "out of range for any drawing");
    refused(&job, &svg("<path d=\"M 0 0 A 5 5 0 0 1 7e38 10\"/>", "0 0 100 100"), "arc.svg", "out of range for any drawing");
    refused(&job, &svg("<g transform=\"skewX(90)\"><circle r=\"5\"/></g>", "0 0 100 100"), "skew.svg", "larger than any machine");
    refused(&job, svg("", "0 0 100 100").split_at(60).0, "cut.svg", "SVG");
}

#[test]
fn generated_elements_that_draw_nothing_are_counted_and_named() {
    let job = drawing_job();
    let eof = "0\nEOF\n";
    warned(&job, &dxf("0\nCIRCLE\n8\nHOLES\n10\n5\n20\n5\n40\n0\n0\nCIRCLE\n8\nHOLES\n10\n5\n20\n5\n40\n-5\n", eof), "zero.dxf", "2 circles with a radius ≤ 0 on layer HOLES");
    warned(&job, &svg("<circle cx=\"5\" cy=\"5\" r=\"-1\"/>", "0 0 100 100"), "r.svg", "circles with a radius ≤ 0");
    warned(&job, &svg("<circle cx=\"5\" cy=\"5\" r=\"nan\"/>", "0 0 100 100"), "nan.svg", "not a number");
    warned(&job, &svg("<rect x=\"5\" y=\"5\" width=\"-10\" height=\"4\"/>", "0 0 100 100"), "rect.svg", "rects with a width or height ≤ 0");
    warned(&job, &svg("<line x1=\"0\" y1=\"0\" x2=\"nan\" y2=\"4\"/>", "0 0 100 100"), "line.svg", "lines with an end that is not a number");
    warned(&job, &svg("", "nan nan nan nan"), "viewbox.svg", "viewBox");
    warned(&job, &svg("", "0 0 0 0"), "viewbox0.svg", "viewBox");
}

/// An ASCII STL of `facets` triangles, the `k`-th vertex's x replaced by `x` when given.
fn stl(facets: &[[DVec3; 3]], bad: Option<(usize, &str)>) -> Vec<u8> {
    let mut s = String::from("solid t\n");
    let mut k = 0;
    for f in facets {
        s += "facet normal 0 0 1\nouter loop\n";
        for v in f {
            let x = match bad {
                Some((at, x)) if at == k => x.to_string(),
                _ => v.x.to_string(),
            };
            s += &format!("vertex {x} {} {}\n", v.y, v.z);
            k += 1;
        }
        s += "endloop\nendfacet\n";
    }
    s += "endsolid t\n";
    s.into_bytes()
}

#[test]
fn generated_parts_out_of_range_or_repeated_are_refused_or_read_once() {
    let part = swarf::mesh::sample::demo_part();
    let facets: Vec<[DVec3; 3]> = part.triangles().map(|t| [t.a, t.b, t.c]).collect();
    let job = Job { simulation: job::Simulation { verify: false, cell: None, ..Default::default() }, ..Job::default() };
    refused(&job, &stl(&facets, Some((4, "1e308"))), "inf.stl", "out of range for any part");
    refused(&job, &stl(&facets, Some((4, "1e39"))), "e39.stl", "out of range for any part");
    // A part read 1000 times too large (a unit off) is refused with its size before any work.
    let mut scaled = job.clone();
    scaled.part.scale = 1000.0;
    refused(&scaled, &stl(&facets, None), "metres.stl", "larger than any machine");
    // The same triangles 3,000 times over: read once, with a note, as fast as the part alone.
    let small = [[DVec3::new(0.0, 0.0, 0.0), DVec3::new(20.0, 0.0, 0.0), DVec3::new(0.0, 20.0, 5.0)], [DVec3::new(20.0, 0.0, 0.0), DVec3::new(20.0, 20.0, 5.0), DVec3::new(0.0, 20.0, 5.0)]];
    let repeated: Vec<[DVec3; 3]> = small.iter().cycle().take(6000).copied().collect();
    let mesh = swarf::mesh::Mesh::from_triangles(repeated, &Tolerances::DEFAULT).unwrap();
    assert_eq!((mesh.faces.len(), mesh.dropped_duplicates), (2, 5998));
    warned(&job, &stl(&small.iter().cycle().take(6000).copied().collect::<Vec<_>>(), None), "copies.stl", "5998 triangles were copies");
}

#[test]
fn generated_absurd_settings_are_refused_naming_the_field() {
    let part = swarf::mesh::sample::demo_part();
    let stl = part.to_binary_stl();
    let base = Job { simulation: job::Simulation { verify: false, cell: None, ..Default::default() }, ..Job::default() };
    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = serde_json::to_value(&base).unwrap();
        f(&mut v);
        v
    };
    let cases: Vec<(serde_json::Value, &str)> = vec![
        (edit(&|v| v["tolerances"]["interpolation"] = 1e-9.into()), "tolerances.interpolation"),
        (edit(&|v| v["tolerances"]["chordal"] = (-1.0).into()), "tolerances.chordal"),
        (edit(&|v| v["stock"]["clearance"] = 1e308.into()), "stock.clearance"),
        (edit(&|v| v["stock"]["marginXy"] = 1e9.into()), "stock.marginXy"),
        (edit(&|v| v["tools"][0]["diameter"] = 1e9.into()), "diameter"),
        (edit(&|v| v["tools"][0]["diameter"] = 1e-9.into()), "diameter"),
        (edit(&|v| v["tools"][0]["cornerRadius"] = (-1.0).into()), "corner radius"),
        (edit(&|v| v["tools"][0]["feedRate"] = 1e12.into()), "feedRate"),
        (edit(&|v| v["post"]["rapidRate"] = 1e300.into()), "post.rapidRate"),
        (edit(&|v| v["operations"][0]["allowance"] = 1e9.into()), "operations[0].allowance"),
        (edit(&|v| v["operations"][0]["rampAngle"] = 1e308.into()), "operations[0].rampAngle"),
        (
            edit(&|v| {
                let op = v["operations"][0].clone();
                v["operations"] = serde_json::Value::Array(vec![op; 200]);
            }),
            "200 operations",
        ),
    ];
    settings_refused(&cases, &stl, "part.stl");
    // A job that names a key twice.
    let text = serde_json::to_string(&base).unwrap();
    let doubled = text.replacen("\"operations\":", "\"operations\":[],\"operations\":", 1);
    let e = Job::from_json(&doubled).unwrap_err().to_string();
    assert!(e.contains("\"operations\" twice"), "{e}");
    // A step-down of a nanometre on a drawing: refused before the levels are cut.
    let mut job = drawing_job();
    if let Some(serde_json::Value::Object(op)) = serde_json::to_value(&job.operations[0]).ok().as_mut() {
        op.insert("stepdown".into(), 1e-9.into());
        job.operations[0] = serde_json::from_value(serde_json::Value::Object(op.clone())).unwrap();
    }
    refused(&job, &dxf("", "0\nEOF\n"), "fine.dxf", "step-down of");
}

/// A profile that finds nothing to cut says why (it once said only `profile: `): 300 holes
/// smaller than the tool, cut inside.
#[test]
fn a_profile_with_nothing_to_cut_says_why() {
    let mut s = String::from("0\nSECTION\n2\nENTITIES\n");
    for i in 0..300 {
        s += &format!("0\nCIRCLE\n8\n0\n10\n{}\n20\n{}\n40\n1.0\n", (i % 20) * 5, (i / 20) * 5);
    }
    s += "0\nENDSEC\n0\nEOF\n";
    let mut job = drawing_job();
    job.operations = vec![job::Operation::Profile2d(swarf::operations::Profile2d { side: swarf::operations::Side::Inside, ..Default::default() })];
    match answer(&job, s.as_bytes(), "holes.dxf") {
        Err(e) => assert!(e.contains("300 loops are smaller than the φ"), "{e}"),
        Ok(_) => panic!("holes smaller than the tool were cut"),
    }
}

/// The Khronos Duck is 1.7 m long by the glTF's metres: the default job's raster finish over
/// it would be 20 million points (it ran 59 s and took 10 GB before failing); the work is
/// estimated and refused before it starts, naming the settings.
#[test]
fn the_duck_at_its_glb_size_is_refused_before_the_work_starts() {
    let Some(path) = common::shared_data("meshes/tm_Duck.glb") else { return };
    let bytes = std::fs::read(path).unwrap();
    match answer(&Job::default(), &bytes, "tm_Duck.glb") {
        Err(e) => assert!(e.contains("million points") && e.contains("step-over"), "{e}"),
        Ok(_) => panic!("the Duck at 1.7 m was machined with the default job"),
    }
}

/// Issue 56: options whose work had no bound (each once aborted on memory at 3.6–5.4 GB) are
/// refused before the work, in a moment, naming the setting: a helical entry of radius 1e-9
/// (z-level roughing, a pocket), a bore's pitch of 1e-9 or 0.001 (7,500 turns: 37 s and a 31-hour
/// program) and its step-over of 1e-9, a thread's pitch of 1e-9.
#[test]
fn options_whose_work_has_no_bound_are_refused_before_it() {
    let stl = swarf::mesh::sample::demo_part().to_binary_stl();
    let part = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = serde_json::to_value(Job { simulation: job::Simulation { verify: false, cell: None, ..Default::default() }, ..Job::default() }).unwrap();
        f(&mut v);
        v
    };
    let zlevel = part(&|v| v["operations"] = serde_json::json!([{ "kind": "roughZlevel", "name": "r", "tool": 1, "helixRadius": 1e-9 }]));
    let zigzag = |op: serde_json::Value, tool: Option<serde_json::Value>| {
        part(&|v| {
            v["operations"] = serde_json::json!([op.clone()]);
            if let Some(t) = &tool {
                v["tools"] = serde_json::json!([t]);
            }
        })
    };
    let cases: Vec<(serde_json::Value, &str)> = vec![
        (zlevel, "a helix radius of 1e-9 mm makes"),
        (zigzag(serde_json::json!({ "kind": "roughZigzag", "name": "z", "tool": 1, "sampling": 0.001 }), None), "a sampling of 0.001 mm weighs the load at about 2.92 million points over a level"),
        (
            zigzag(serde_json::json!({ "kind": "roughZigzag", "name": "z", "tool": 1 }), Some(serde_json::json!({ "number": 1, "shape": "flat", "diameter": 0.01 }))),
            "the φ0.01 tool's step-over of 0.004 mm",
        ),
    ];
    settings_refused(&cases, &stl, "part.stl");
    let square = dxf("", "0\nEOF\n");
    let sheet = |op: serde_json::Value| {
        let mut v = serde_json::to_value(drawing_job()).unwrap();
        v["operations"] = serde_json::json!([op]);
        v["tools"] = serde_json::json!([
            { "number": 1, "shape": "flat", "diameter": 3.0, "fluteLength": 20.0 },
            { "number": 2, "shape": "threadMill", "diameter": 10.0, "fluteLength": 20.0 }
        ]);
        v
    };
    let cases: Vec<(serde_json::Value, &str)> = vec![
        (sheet(serde_json::json!({ "kind": "pocket2d", "name": "p", "tool": 1, "depth": 2.0, "helixRadius": 1e-9 })), "a helix radius of 1e-9 mm makes"),
        (sheet(serde_json::json!({ "kind": "bore", "name": "b", "tool": 1, "pitch": 1e-9 })), "a pitch of 1e-9 mm makes"),
        (sheet(serde_json::json!({ "kind": "bore", "name": "b", "tool": 1, "pitch": 0.001 })), "turns over"),
        (sheet(serde_json::json!({ "kind": "bore", "name": "b", "tool": 1, "stepoverFraction": 1e-9 })), "rings over"),
        (sheet(serde_json::json!({ "kind": "threadMill", "name": "t", "tool": 2, "majorDiameter": 16.0, "pitch": 1e-9 })), "a pitch of 1e-9 mm makes"),
    ];
    settings_refused(&cases, &square, "square.dxf");
}

/// Issue 56: settings that pass their own range but write a program no control runs, or run
/// away, are refused naming the field, at once: tabs past any sheet (a height of 1e300 once
/// panicked in the removal rates), closer than their own width, more than a part is held by, or
/// as tall as the sheet over the cut's floor (the tool in the air over them); a spindle speed
/// written S0, a feed written F0; a list where the job's settings belong.
#[test]
fn settings_a_control_cannot_run_are_refused_naming_the_field() {
    let square = dxf("", "0\nEOF\n");
    let profile = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = serde_json::to_value(drawing_job()).unwrap();
        v["operations"][0]["tabs"] = serde_json::json!({ "count": 4, "width": 4.0, "height": 1.5 });
        f(&mut v);
        v
    };
    let cases: Vec<(serde_json::Value, &str)> = vec![
        (profile(&|v| v["operations"][0]["tabs"]["height"] = 1e300.into()), "operations[0].tabs.height must be zero or more, at most 10000"),
        (profile(&|v| v["operations"][0]["tabs"]["width"] = 0.0.into()), "operations[0].tabs.width must be a positive number"),
        (profile(&|v| v["operations"][0]["tabs"]["count"] = 100_000.into()), "operations[0].tabs.count must be at most 1000 tabs"),
        (
            profile(&|v| {
                v["operations"][0]["tabs"]["count"] = 0.into();
                v["operations"][0]["tabs"]["spacing"] = 1e-9.into();
            }),
            "operations[0].tabs.spacing must be at least the tabs' width (4 mm)",
        ),
        (profile(&|v| v["operations"][0]["tabs"]["height"] = 6.2.into()), "tabs.height (6.2 mm) reaches the sheet's top from the cut's floor (6 mm below it)"),
        (profile(&|v| v["tools"][0]["spindleRpm"] = 0.5.into()), "tools[0].spindleRpm is written as whole turns a minute: 0.5 is S0"),
        (profile(&|v| v["tools"][0]["feedRate"] = 1e-9.into()), "tools[0].feedRate of 1e-9 mm/min is written F0"),
        (
            profile(&|v| {
                v["post"]["units"] = "inch".into();
                v["tools"][0]["plungeRate"] = 1.0.into();
            }),
            "tools[0].plungeRate of 1 mm/min is written F0 with the post's 1 decimals (in/min)",
        ),
    ];
    settings_refused(&cases, &square, "square.dxf");
    // Tabs as tall as the sheet less a hair: cut, the tabs standing.
    let ok = Job::from_value(&profile(&|v| v["operations"][0]["tabs"]["height"] = 5.9.into())).unwrap();
    assert!(answer(&ok, &square, "square.dxf").is_ok());
    // A list where the job, or a part of it, belongs.
    for (text, words) in [("[]", "the job is a list, not an object of settings"), (r#"{"stock": []}"#, "stock: a list, where its settings belong in an object")] {
        let e = Job::from_json(text).unwrap_err().to_string();
        assert!(e.contains(words), "{text}: {e}");
    }
}

/// Issue 56: what a file says besides its solid is never part of it, and its units are its
/// own: an OBJ's polyline (`l`) above a cube leaves the cube 10 mm tall; an ASCII STL vertex
/// with a fourth number is refused, not read as its first three; a DXF in miles is larger than
/// any machine and one in nanometres tiny, not either read as millimetres.
#[test]
fn what_a_file_says_besides_its_solid_is_never_part_of_it() {
    use swarf::mesh::import::read_mesh_auto;
    let mut obj = String::from("v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 10\nv 10 0 10\nv 10 10 10\nv 0 10 10\nv 0 0 30\n");
    obj += "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nl 1 9\n";
    let cube = read_mesh_auto(obj.as_bytes(), Some("cube.obj"), &Tolerances::default()).unwrap();
    let b = cube.bounds();
    assert!((b.max.z - b.min.z - 10.0).abs() < 1e-9, "the cube reads {} tall", b.max.z - b.min.z);
    let stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0 7\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    let e = read_mesh_auto(stl.as_bytes(), Some("t.stl"), &Tolerances::default()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("line 5") && e.contains("three numbers"), "{e}");
    let square = |code: i64| {
        format!("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n{code}\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n1\n20\n0\n10\n1\n20\n1\n10\n0\n20\n1\n0\nENDSEC\n0\nEOF\n")
    };
    let e = swarf::drawing::import::read_drawing(square(3).as_bytes(), Some("miles.dxf"), &Tolerances::default()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("larger than any machine"), "{e}");
    let d = swarf::drawing::import::read_drawing(square(12).as_bytes(), Some("nm.dxf"), &Tolerances::default());
    // A square a nanometre wide is nothing to machine (refused or read a nanometre wide).
    if let Ok(d) = d {
        assert!(d.units.contains("nm") && d.bounds().size().max_element() < 1e-5, "{} {:?}", d.units, d.bounds());
    }
    let d = swarf::drawing::import::read_drawing(square(7).as_bytes(), Some("km.dxf"), &Tolerances::default()).map(|_| ()).unwrap_err().to_string();
    assert!(d.contains("larger than any machine"), "{d}");
}

/// Issue 56: a check that checked nothing never says "clean". A simulation cell wider than the
/// smallest tool's radius (the job's 1e300, `swarf verify --cell 1e6`) could not see that tool's
/// cuts nor a gouge by it; a gouge tolerance of 10 mm (once inside its range) passed a program
/// cutting 9 mm into the part. Each is refused naming the setting; cells as fine as the tool
/// are taken.
#[test]
fn checks_that_could_not_see_are_refused() {
    let part = swarf::mesh::sample::demo_part();
    let stl = part.to_binary_stl();
    let job_with = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = serde_json::to_value(Job::default()).unwrap();
        f(&mut v);
        v
    };
    let cases: Vec<(serde_json::Value, &str)> = vec![
        (job_with(&|v| v["simulation"]["cell"] = 1e300.into()), "simulation.cell: cells of 1e300 mm are wider than the radius of T1"),
        (job_with(&|v| v["simulation"]["cell"] = 3.5.into()), "choose cells of at most 3 mm"),
        (job_with(&|v| v["tolerances"]["gouge"] = 10.0.into()), "tolerances.gouge must lie between 1e-4 and 5e-1 (got 10): a coarser one is no longer a tolerance"),
    ];
    settings_refused(&cases, &stl, "part.stl");
    // The job's program, checked by `swarf verify` with cells of a kilometre: refused; with
    // cells as fine as the tool: checked.
    let mut job = Job::default();
    job.simulation.verify = false;
    let out = job::run(&job, Workpiece::read(&stl, Some("part.stl"), &job.tolerances).unwrap(), &mut Progress::none()).unwrap();
    let e = job::run::verify_gcode(&job, part.clone(), &out.gcode, Some(1e6), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("the cell: cells of 1000000 mm are wider than the radius"), "{e}");
    assert!(job::run::verify_gcode(&job, part, &out.gcode, Some(0.5), &mut Progress::none()).is_ok());
}

/// Issue 56: a part handed to the drawing reader (`swarf drawing part.stl`) is named as a part,
/// and a binary file's bytes never reach a message: they are escaped, the quote cut short.
#[test]
fn a_part_is_not_read_as_a_drawing_and_binary_bytes_are_not_printed() {
    use swarf::drawing::import::read_drawing;
    let stl = swarf::mesh::sample::demo_part().to_binary_stl();
    let e = read_drawing(&stl, Some("part.stl"), &Tolerances::default()).unwrap_err().to_string();
    assert!(e.contains("this is a part (an STL), not a drawing"), "{e}");
    let e = read_drawing(b"solid x\nfacet normal 0 0 1\n", None, &Tolerances::default()).unwrap_err().to_string();
    assert!(e.contains("not a drawing"), "{e}");
    let e = read_drawing(&stl, None, &Tolerances::default()).unwrap_err().to_string();
    assert!(!e.chars().any(|c| c.is_control() || c == '\u{FFFD}') && e.len() < 400, "{e:?}");
}

/// Issue 56: a program that gouges says why where the drawing does, before the simulation's
/// cells: a drill wider than the drawing's holes, loops that cross; and a coarse chordal
/// tolerance no longer reads as a gouge where the program follows the part.
#[test]
fn a_gouge_says_its_cause() {
    let problem = |job: &Job, bytes: &[u8]| {
        let out = job::run(job, Workpiece::read(bytes, Some("plate.dxf"), &job.tolerances).unwrap(), &mut Progress::none()).unwrap();
        out.problem.unwrap_or_else(|| panic!("the program verified clean"))
    };
    let square = |x: f64, y: f64, side: f64| format!("0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n{x}\n20\n{y}\n10\n{}\n20\n{y}\n10\n{}\n20\n{}\n10\n{x}\n20\n{}\n", x + side, x + side, y + side, y + side);
    let circle = |x: f64, y: f64, r: f64| format!("0\nCIRCLE\n8\n0\n10\n{x}\n20\n{y}\n40\n{r}\n");
    let drawing = |entities: &str| format!("0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n").into_bytes();

    // A φ6 drill in φ5 holes.
    let plate = drawing(&(square(0.0, 0.0, 60.0) + &circle(15.0, 20.0, 2.5) + &circle(40.0, 20.0, 2.5)));
    let job = Job {
        tools: vec![serde_json::from_value(serde_json::json!({ "number": 1, "shape": "drill", "diameter": 6.0, "angle": 118, "fluteLength": 20, "feedRate": 200, "plungeRate": 100 })).unwrap()],
        operations: vec![serde_json::from_value(serde_json::json!({ "kind": "drill", "tool": 1 })).unwrap()],
        ..Job::default()
    };
    let p = problem(&job, &plate);
    assert!(p.starts_with("φ6 drill (T1) in φ5 holes: 0.500 mm oversize on the radius (the first at X"), "{p}");

    // Two squares that cross, each profiled outside.
    let crossing = drawing(&(square(0.0, 0.0, 30.0) + &square(20.0, 20.0, 30.0)));
    let p = problem(&drawing_job(), &crossing);
    assert!(p.starts_with("the drawing's loops 0 and 1 cross (at X"), "{p}");
    assert!(p.contains("it gouges the part"), "{p}");
    // Apart, the same squares verify clean.
    let apart = drawing(&(square(0.0, 0.0, 30.0) + &square(40.0, 40.0, 30.0)));
    let out = job::run(&drawing_job(), Workpiece::read(&apart, Some("plate.dxf"), &Tolerances::default()).unwrap(), &mut Progress::none()).unwrap();
    assert_eq!(out.problem, None);

    // A disc profiled with a chordal tolerance of 0.5 mm: its ramp's helices are simulated
    // within a tenth of the gouge tolerance, and its program (arcs) verifies clean.
    let disc = drawing(&circle(30.0, 30.0, 25.0));
    let mut job = drawing_job();
    job.tolerances.chordal = 0.5;
    let out = job::run(&job, Workpiece::read(&disc, Some("disc.dxf"), &job.tolerances).unwrap(), &mut Progress::none()).unwrap();
    assert_eq!(out.problem, None);
}

/// Issue 62: a file of another kind is named by its first bytes, whatever its name says, by
/// the part reader and the drawing reader alike, with what to do; a drawing given for a part
/// is named a drawing (`swarf edges plate.dxf` answered with an STL's message).
#[test]
fn a_file_of_another_kind_says_what_it_is() {
    use swarf::drawing::import::read_drawing;
    use swarf::mesh::import::read_mesh_auto;
    let tol = swarf::geom::Tolerances::default();
    let padded = |head: &[u8]| {
        let mut b = head.to_vec();
        b.resize(2000, b'x');
        b
    };
    let cases: [(&[u8], &str); 6] = [
        (b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR", "a PNG image"),
        (b"\xFF\xD8\xFF\xE0\0\x10JFIF\0", "a JPEG image"),
        (b"%PDF-1.7\n", "a PDF document"),
        (b"PK\x03\x04\x14\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x10\0\0\x003D/3dmodel.model", "a 3MF package"),
        (b"PK\x03\x04\x14\0\0\0", "a ZIP archive"),
        (b"ISO-10303-21;\nHEADER;\n", "a STEP model"),
    ];
    for (head, what) in cases {
        let bytes = padded(head);
        for name in [Some("part.stl"), Some("part.obj"), Some("part.glb"), None] {
            let e = read_mesh_auto(&bytes, name, &tol).unwrap_err().to_string();
            assert!(e.starts_with(&format!("the file is {what}")) && e.contains("not a part swarf reads (STL, glTF/GLB or OBJ)"), "{name:?}: {e}");
        }
        for name in [Some("plate.dxf"), Some("plate.svg"), None] {
            let e = read_drawing(&bytes, name, &tol).unwrap_err().to_string();
            assert!(e.starts_with(&format!("the file is {what}")) && e.contains("not a drawing swarf reads (DXF or SVG)"), "{name:?}: {e}");
        }
    }
    let dxf = swarf::drawing::sample::plate_dxf();
    let e = read_mesh_auto(dxf.as_bytes(), Some("plate.dxf"), &tol).unwrap_err().to_string();
    assert!(e.starts_with("the file is a DXF drawing, not a 3D part"), "{e}");
    // A binary STL whose header happens to start like a PNG is still an STL.
    let mut stl = b"\x89PNG\r\n\x1a\n".to_vec();
    stl.resize(80, 0);
    stl.extend(1u32.to_le_bytes());
    for v in [[0.0f32, 0.0, 1.0], [0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 10.0, 0.0]] {
        stl.extend(v.iter().flat_map(|c| c.to_le_bytes()));
    }
    stl.extend([0u8; 2]);
    assert_eq!(read_mesh_auto(&stl, Some("odd.stl"), &tol).unwrap().triangles().count(), 1);
}
