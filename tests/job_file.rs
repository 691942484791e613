//! Job files as a user writes them: every field that does not fit or is not known is named by
//! its path, files without a version still load, and a file from a newer swarf is refused.

mod common;

use swarf::job::{self, Job, JOB_VERSION};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;

fn error_of(text: &str) -> String {
    Job::from_json(text).map(|_| ()).unwrap_err().to_string()
}

fn default_json() -> serde_json::Value {
    serde_json::to_value(Job::default()).unwrap()
}

#[test]
fn every_job_the_core_writes_reads_back() {
    for job in [Job::default(), Job::default_for_drawing()] {
        let text = serde_json::to_string_pretty(&job).unwrap();
        assert_eq!(Job::from_json(&text).unwrap(), job);
        assert!(text.contains(&format!("\"version\": {JOB_VERSION}")));
    }
    // A file without a version (older swarf) and one with only a few fields.
    let mut old = default_json();
    old.as_object_mut().unwrap().remove("version");
    assert_eq!(Job::from_json(&old.to_string()).unwrap(), Job::default());
    let short = r#"{"tools":[{"number":2,"shape":"flat","diameter":4}],"operations":[{"kind":"finishRaster","tool":2,"stepover":0.8}]}"#;
    let job = Job::from_json(short).unwrap();
    assert_eq!(job.tools[0].cutter.radius(), 2.0);
}

#[test]
fn a_misspelt_field_is_named_with_what_it_may_mean() {
    let mut v = default_json();
    let op = v["operations"][0].as_object_mut().unwrap();
    let stepover = op.remove("stepover").unwrap();
    op.insert("stepOver".into(), stepover);
    v["tools"][0].as_object_mut().unwrap().insert("feedrate".into(), 900.into());
    v.as_object_mut().unwrap().insert("colour".into(), "red".into());
    let e = error_of(&v.to_string());
    assert!(e.contains("operations[0].stepOver (did you mean stepover?)"), "{e}");
    assert!(e.contains("tools[0].feedrate (did you mean feedRate?)"), "{e}");
    assert!(e.contains("colour"), "{e}");
}

#[test]
fn unknown_kinds_wrong_types_and_newer_versions_say_where() {
    let mut v = default_json();
    v["operations"].as_array_mut().unwrap().push(serde_json::json!({"kind": "roughTrochoidal", "tool": 1}));
    let e = error_of(&v.to_string());
    assert!(e.contains("operations[1]") && e.contains("roughTrochoidal"), "{e}");

    let mut v = default_json();
    v["operations"][0]["stepover"] = "fine".into();
    let e = error_of(&v.to_string());
    assert!(e.contains(r#"operations[0].stepover: expected a number, got "fine""#), "{e}");

    // A wrong type is said in a user's words, with its path.
    let mut v = default_json();
    v["stock"]["marginXy"] = "5".into();
    assert_eq!(error_of(&v.to_string()), r#"stock.marginXy: expected a number, got "5""#);
    let mut v = default_json();
    v["tools"][0]["number"] = (-2).into();
    assert_eq!(error_of(&v.to_string()), "tools[0].number: expected a whole number, 0 or more, got -2");

    let mut v = default_json();
    v["post"]["dialect"] = "heidenhain".into();
    let e = error_of(&v.to_string());
    assert!(e.contains("post.dialect") && e.contains("heidenhain"), "{e}");

    let mut v = default_json();
    v["version"] = 99.into();
    let e = error_of(&v.to_string());
    assert!(e.contains("version 99") && e.contains(&format!("up to {JOB_VERSION}")), "{e}");

    assert!(error_of("{\"name\": ").contains("not JSON"));
}

#[test]
fn a_missing_tool_number_is_named() {
    let mut v = default_json();
    v["operations"][0]["tool"] = 7.into();
    let job = Job::from_json(&v.to_string()).unwrap();
    let e = job::run(&job, demo_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("no tool number 7"), "{e}");
}

/// One word, one meaning: `stepover` is a distance in millimetres (raster finishing), and the
/// step-over that is a fraction of the tool's diameter (roughing, pockets) is
/// `stepoverFraction` since version 2. A version-1 file is still read as it was written; a
/// version-2 file that says `stepover` on a roughing is told the field it means. No message
/// blames a "job file": the same reader reads what the page and portals send.
#[test]
fn stepover_is_millimetres_and_a_version_1_file_reads_as_it_was_written() {
    let v1 = r#"{"tools":[{"number":1,"shape":"flat","diameter":6}],"operations":[{"kind":"roughZlevel","tool":1,"stepover":0.3},{"kind":"finishRaster","tool":1,"stepover":0.8}]}"#;
    let job = Job::from_json(v1).unwrap();
    assert_eq!(job.version, JOB_VERSION);
    let json = serde_json::to_value(&job).unwrap();
    assert_eq!(json["operations"][0]["stepoverFraction"], 0.3);
    assert!(json["operations"][0].get("stepover").is_none());
    assert_eq!(json["operations"][1]["stepover"], 0.8);
    // Written back, it reads as version 2.
    assert_eq!(Job::from_json(&json.to_string()).unwrap(), job);
    let v2 = v1.replace(r#"{"tools""#, r#"{"version":2,"tools""#);
    let e = error_of(&v2);
    assert!(e.contains("operations[0].stepover (did you mean stepoverFraction?)"), "{e}");
    assert!(!e.contains("job file"), "{e}");
}

/// A tab's height is measured from the sheet's bottom since version 2 (it was from the cut's
/// final depth, 0.2 mm below the bottom for a cut through): a version-1 file keeps its tabs'
/// tops where they were.
#[test]
fn a_version_1_tab_height_keeps_its_top() {
    let v1 = r#"{"drawing":{"thickness":6},"tools":[{"number":1,"shape":"flat","diameter":3}],"operations":[{"kind":"profile2d","tool":1,"tabs":{"count":4,"height":1.5}},{"kind":"profile2d","tool":1,"depth":7,"tabs":{"count":2}},{"kind":"profile2d","tool":1,"depth":3,"tabs":{"count":2,"height":1}}]}"#;
    let job = Job::from_json(v1).unwrap();
    let heights: Vec<f64> = job
        .operations
        .iter()
        .map(|o| match o {
            swarf::job::Operation::Profile2d(p) => p.tabs.height,
            _ => unreachable!(),
        })
        .collect();
    // Through by the default 0.2, through by 1 (default height 1.5), and not through.
    assert_eq!(heights.len(), 3);
    assert!((heights[0] - 1.3).abs() < 1e-12 && (heights[1] - 0.5).abs() < 1e-12 && heights[2] == 1.0, "{heights:?}");
}

#[test]
fn a_roughing_setting_shared_by_the_roughing_kinds_is_named_by_its_path() {
    // The roughing kinds' shared settings are flattened into each one's JSON: a bad value is
    // still named by its own path.
    for kind in ["roughZlevel", "roughZigzag", "roughAdaptive", "roughOctree"] {
        let mut job = serde_json::to_value(Job::demo()).unwrap();
        job["operations"][0] = serde_json::json!({ "kind": kind, "allowance": "lots" });
        let e = Job::from_value(&job).unwrap_err().to_string();
        assert!(e.starts_with("operations[0].allowance: "), "{kind}: {e}");
        job["operations"][0] = serde_json::json!({ "kind": kind, "leaveStock": -1.0 });
        let e = Job::from_value(&job).unwrap().validate().unwrap_err().to_string();
        assert!(e.contains("operations[0].leaveStock must be zero or more"), "{kind}: {e}");
        job["operations"][0] = serde_json::json!({ "kind": kind, "ramp_angle": 3.0 });
        let e = Job::from_value(&job).unwrap_err().to_string();
        assert!(e.contains("operations[0].ramp_angle (did you mean rampAngle?)"), "{kind}: {e}");
    }
}

/// Issue 55: a stock box smaller than the part is an error naming by how much on which side,
/// at `stock.sizeBox` in the checks the page marks as the user types (given the part's
/// bounds) and when the job runs; a part reaching below the box's bottom is a warning; a box
/// that holds the part runs as before.
#[test]
fn a_stock_box_smaller_than_the_part_is_refused_naming_the_sides() {
    use swarf::geom::{Aabb, DVec3};
    let part = swarf::mesh::sample::demo_part();
    let mut job = swarf::job::Job::demo();
    let mut placed = part.clone();
    job.place(&mut placed);
    let b = placed.bounds();
    // A 40 × 40 box under the 90 × 60 sample.
    job.stock.size_box = Some(Aabb { min: DVec3::new(-20.0, -20.0, b.min.z - 1.0), max: DVec3::new(20.0, 20.0, b.max.z + 1.0) });
    let problems = job.problems_with(swarf::job::Known { part: Some(&b), holes: None });
    let p = problems.iter().find(|p| p.path == "stock.sizeBox").unwrap_or_else(|| panic!("{problems:?}"));
    let (dx, dy) = ((b.max.x - 20.0), (b.max.y - 20.0));
    for side in [format!("{dx:.3} mm at -X"), format!("{dx:.3} mm at +X"), format!("{dy:.3} mm at -Y"), format!("{dy:.3} mm at +Y")] {
        assert!(p.message.contains(&side), "{side}: {}", p.message);
    }
    assert!(!p.message.contains("at the top"), "{}", p.message);
    // Without the part the job alone cannot tell.
    assert!(job.problems().iter().all(|p| p.path != "stock.sizeBox"));
    let e = match swarf::job::run(&job, part.clone(), &mut swarf::progress::Progress::none()) {
        Ok(_) => panic!("the run must be refused"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("sticks out of the stock") && e.contains("at +X"), "{e}");
    // Only the top out: named alone.
    job.stock.size_box = Some(Aabb { min: b.min - DVec3::splat(5.0), max: DVec3::new(b.max.x + 5.0, b.max.y + 5.0, b.max.z - 2.0) });
    let p = job.problems_with(swarf::job::Known { part: Some(&b), holes: None }).into_iter().find(|p| p.path == "stock.sizeBox").expect("the top sticks out");
    assert!(p.message.contains("2.000 mm at the top") && !p.message.contains("at -X"), "{}", p.message);
    // Below the bottom only: a warning, and the program is made.
    job.stock.size_box = Some(Aabb { min: DVec3::new(b.min.x - 5.0, b.min.y - 5.0, b.min.z + 3.0), max: b.max + DVec3::splat(1.0) });
    assert!(job.problems_with(swarf::job::Known { part: Some(&b), holes: None }).iter().all(|p| p.path != "stock.sizeBox"));
    let out = swarf::job::run(&job, part.clone(), &mut swarf::progress::Progress::none()).expect("a part below the box's bottom runs");
    assert!(out.warnings.iter().any(|w| w.to_string().contains("3.000 mm below the stock box's bottom")), "{:?}", out.warnings);
    // A box that holds the part: nothing said.
    job.stock.size_box = Some(Aabb { min: b.min - DVec3::splat(2.0), max: b.max + DVec3::splat(2.0) });
    assert!(job.problems_with(swarf::job::Known { part: Some(&b), holes: None }).is_empty(), "{:?}", job.problems_with(swarf::job::Known { part: Some(&b), holes: None }));
}

/// Issue 55: inside a tool a misspelt field gets its "did you mean" and a wrong value is named
/// at its field; the messages the page shows at a field do not repeat its path.
#[test]
fn a_tools_fields_are_named_and_a_fields_message_does_not_repeat_its_path() {
    let job = |tool: &str| format!(r#"{{"tools":[{tool}],"operations":[{{"kind":"roughZlevel","tool":1}}]}}"#);
    let e = error_of(&job(r#"{"number":1,"shape":"flat","diamter":6}"#));
    assert!(e.contains("tools[0].diamter (did you mean diameter?)"), "{e}");
    let e = error_of(&job(r#"{"number":1,"shape":"flat","fluteLenght":20}"#));
    assert!(e.contains("(did you mean fluteLength?)"), "{e}");
    let e = error_of(&job(r#"{"number":1,"shape":"flat","diameter":"x"}"#));
    assert!(e.starts_with("tools[0].diameter: expected a number"), "{e}");
    // A name far from every field gets no guess.
    let e = error_of(&job(r#"{"number":1,"shape":"flat","colour":"red"}"#));
    assert!(e.contains("tools[0].colour") && !e.contains("did you mean"), "{e}");
    use swarf::job::Problem;
    let bare = |path: &str, message: &str| Problem { path: path.into(), message: message.into() }.at_field().message;
    assert_eq!(bare("operations[0].stepdown", "operations[0].stepdown must be a positive number (got -1) ('rough')"), "must be a positive number (got -1) ('rough')");
    assert_eq!(bare("tools[0].diameter", "tools[0] (tool 1): the cutter diameter must lie between 0.01 and 1000 mm (got -6)"), "the cutter diameter must lie between 0.01 and 1000 mm (got -6)");
    assert_eq!(bare("tools[0].diamter", "unknown field: tools[0].diamter (did you mean diameter?)"), "unknown field (did you mean diameter?)");
    assert_eq!(bare("stock.marginXy", "stock.marginXy: expected a number, got \"5\""), "expected a number, got \"5\"");
    // Every problem of a job with many, at its field: none names its path again.
    let mut job = swarf::job::Job::demo();
    job.tools[0].cutter.diameter = -6.0;
    job.stock.margin_xy = -2.0;
    let problems = job.problems();
    assert!(problems.len() >= 2, "{problems:?}");
    for p in problems {
        let path = p.path.clone();
        let at = p.at_field();
        assert!(!at.message.contains(&path) && !at.message.starts_with(':') && !at.message.is_empty(), "{path}: {}", at.message);
    }
}

/// Issue 55: a tool wider than the whole part is refused at once (a φ150 on the 90 mm sample
/// planned for minutes to a program that left 10 mm); a face mill wider than the part still
/// faces it, with the warning.
#[test]
fn a_tool_wider_than_the_whole_part_is_refused_at_once_unless_it_faces() {
    let mut job = swarf::job::Job::demo();
    for t in &mut job.tools {
        t.cutter.diameter = 150.0;
        t.cutter.flute_length = 50.0;
    }
    let (e, took) = common::cpu_timed(|| match swarf::job::run(&job, demo_part(), &mut Progress::none()) {
        Ok(_) => panic!("a φ150 tool on a 90 × 60 mm part ran"),
        Err(e) => e.to_string(),
    });
    assert!(e.contains("smaller than the φ150 tool") && e.contains("choose a smaller tool"), "{e}");
    assert!(took < 5.0, "refused after {took:.2} s of CPU");
    job.operations = vec![swarf::job::Operation::Face(swarf::operations::Face { tool: 1, ..Default::default() })];
    let out = swarf::job::run(&job, demo_part(), &mut Progress::none()).expect("a wide face mill faces the part");
    assert!(out.warnings.iter().any(|w| w.to_string().contains("smaller than the φ150 tool")), "{:?}", out.warnings);
}

/// The example jobs beside the project (`examples/*/*.json`: the two-sided plate, issue 61's
/// mould core) read and pass the core's checks as they are, and the mould core's are the ten
/// operations the page benchmark names.
#[test]
fn the_example_jobs_read_and_pass_the_checks() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut read = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let folder = entry.unwrap().path();
        if !folder.is_dir() {
            continue;
        }
        for file in std::fs::read_dir(&folder).unwrap() {
            let file = file.unwrap().path();
            if file.extension().is_some_and(|e| e == "json") {
                let job = Job::from_json(&std::fs::read_to_string(&file).unwrap()).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                job.validate().unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                read.push((file.file_stem().unwrap().to_string_lossy().into_owned(), job));
            }
        }
    }
    let mould = &read.iter().find(|(name, _)| name == "mould-core").expect("examples/mould-core/mould-core.json").1;
    let kinds: Vec<String> = mould.operations.iter().map(|o| serde_json::to_value(o).unwrap()["kind"].as_str().unwrap().to_owned()).collect();
    assert_eq!(kinds, ["face", "roughZlevel", "roughZlevel", "finishRaster", "finishWaterline", "drill", "drill", "drill", "bore", "chamfer"]);
    assert!(read.iter().any(|(name, _)| name == "two-sided"));
}
