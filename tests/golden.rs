//! Golden programs: the guard of issue 37's move. Each case runs one job and hashes its
//! program (FNV-1a, 64 bits, with its length); `tests/golden/programs.tsv` holds what the
//! code before the move wrote. A refactoring that changes a single byte of any program fails
//! here, naming the case. Cases on `../shared/data` are skipped where it is absent.
//!
//! A change meant to alter programs rewrites the file: `UPDATE_GOLDEN=1 cargo test --test
//! golden`, and says why in its commit.

mod common;

use serde_json::{json, Value};
use swarf::drawing::import::read_drawing;
use swarf::job::{self, Job, Workpiece};
use swarf::mesh::import::read_mesh_auto;
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;

const FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden/programs.tsv");

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// The tools every part case may use: a flat end, a ball and a bull nose.
fn tools() -> Value {
    json!([
        { "number": 1, "shape": "flat", "diameter": 6.0, "fluteLength": 30.0, "feedRate": 1200.0, "plungeRate": 300.0 },
        { "number": 2, "shape": "ball", "diameter": 6.0, "fluteLength": 30.0, "feedRate": 1500.0, "plungeRate": 300.0 },
        { "number": 3, "shape": "bullNose", "diameter": 8.0, "cornerRadius": 1.0, "fluteLength": 30.0, "feedRate": 1200.0, "plungeRate": 300.0 },
        { "number": 4, "shape": "flat", "diameter": 3.0, "fluteLength": 20.0, "feedRate": 800.0, "plungeRate": 200.0 },
    ])
}

/// The demo job with `operations` (and the tools above) in place of its own.
fn part_job(operations: Value) -> Job {
    let mut job = serde_json::to_value(Job::demo()).unwrap();
    job["tools"] = tools();
    job["operations"] = operations;
    job["simulation"]["verify"] = json!(false);
    Job::from_value(&job).unwrap()
}

fn drawing_job(operations: Value) -> Job {
    let mut job = serde_json::to_value(Job::default_for_drawing()).unwrap();
    job["operations"] = operations;
    job["simulation"]["verify"] = json!(false);
    Job::from_value(&job).unwrap()
}

/// The part operations of a case: one kind, one tool.
fn part_cases() -> Vec<(String, Value)> {
    let mut cases = Vec::new();
    for (tool, shape) in [(1, "flat"), (2, "ball"), (3, "bull")] {
        cases.push((format!("zlevel-{shape}"), json!([{ "kind": "roughZlevel", "tool": tool, "stepdown": 3.0, "grid": 0.5 }])));
        cases.push((format!("zigzag-{shape}"), json!([{ "kind": "roughZigzag", "tool": tool, "stepdown": 3.0, "grid": 0.5 }])));
        cases.push((format!("raster-{shape}"), json!([{ "kind": "finishRaster", "tool": tool, "stepover": 1.5, "grid": 0.5 }])));
    }
    cases.push(("waterline-ball".into(), json!([{ "kind": "finishWaterline", "tool": 2, "stepdown": 2.0, "grid": 0.5 }])));
    cases.push(("octree".into(), json!([{ "kind": "roughOctree", "tools": [], "grid": 0.5 }])));
    cases.push((
        "rest-after-zlevel".into(),
        json!([{ "kind": "roughZlevel", "tool": 1, "stepdown": 3.0, "grid": 0.5 }, { "kind": "roughZlevel", "tool": 4, "stepdown": 3.0, "grid": 0.5 }, { "kind": "finishRaster", "tool": 2, "stepover": 1.5, "grid": 0.5, "restOnly": true }]),
    ));
    cases
}

fn run(job: &Job, workpiece: Workpiece) -> String {
    job::run(job, workpiece, &mut Progress::none()).unwrap().gcode
}

/// Every case's name and program, where its part or drawing is here.
fn programs() -> Vec<(String, String)> {
    let mut out = Vec::new();
    // The demo, whole.
    out.push(("demo".to_string(), run(&Job::demo(), demo_part().into())));
    // The demo through a pool of workers: its surfaces made by another prepared copy.
    let job = Job::demo();
    let mut helper = job::prepare(&job, demo_part()).unwrap();
    let mut planner = job::prepare(&job, demo_part()).unwrap();
    for s in planner.surfaces().unwrap() {
        let z: Vec<f64> = [0, s.grid.ny / 3, s.grid.ny].windows(2).flat_map(|w| helper.surface_rows(s, w[0]..w[1], &mut Progress::none()).unwrap()).collect();
        planner.keep_surface(s, z).unwrap();
    }
    out.push(("demo-pool".to_string(), planner.run(&mut Progress::none()).unwrap().gcode));

    let tol = swarf::geom::Tolerances::default();
    for (part, units) in [("kiri_pocket-test.stl", "mm"), ("pycam_textbox.stl", "mm")] {
        let Some(path) = common::shared_data(&format!("meshes/{part}")) else { continue };
        let bytes = std::fs::read(path).unwrap();
        let mesh = read_mesh_auto(&bytes, Some(part), &tol).unwrap();
        for (name, ops) in part_cases() {
            let mut job = part_job(ops);
            job.part.units = serde_json::from_value(json!(units)).unwrap();
            out.push((format!("{part}/{name}"), run(&job, mesh.clone().into())));
        }
    }
    for drawing in ["tm_1002_tray_bottom.dxf", "pycam_polygons.svg"] {
        let Some(path) = common::shared_data(&format!("profiles/{drawing}")) else { continue };
        let bytes = std::fs::read(path).unwrap();
        let d = read_drawing(&bytes, Some(drawing), &tol).unwrap();
        let cases = [
            ("profile", json!([{ "kind": "profile2d", "tool": 1, "layers": [], "depth": 6.0, "stepdown": 2.0 }])),
            ("pocket", json!([{ "kind": "pocket2d", "tool": 1, "layers": [], "depth": 2.0, "stepdown": 1.0 }])),
            ("pocket-zigzag", json!([{ "kind": "pocket2d", "tool": 1, "layers": [], "depth": 2.0, "stepdown": 1.0, "pattern": "zigzag" }])),
            ("engrave", json!([{ "kind": "engrave", "tool": 1, "layers": [], "depth": 0.5, "allLoops": true }])),
        ];
        for (name, ops) in cases {
            let job = drawing_job(ops);
            match job::run(&job, d.clone(), &mut Progress::none()) {
                Ok(o) => out.push((format!("{drawing}/{name}"), o.gcode)),
                // An operation the drawing refuses is part of the record too.
                Err(e) => out.push((format!("{drawing}/{name}"), format!("error: {e}"))),
            }
        }
    }
    out
}

/// The page plans on one thread (wasm), the CLI on every core: the same programs either way,
/// on the demo part (always here) with the strategies that share their work between threads
/// (the levels' regions, the rings made ahead and the air judged behind, zigzag's levels, the
/// octree's stages, the simulated stock's bands), and on a shared part where it is here.
#[test]
fn one_thread_writes_the_programs_every_core_writes() {
    let mut cases: Vec<(String, Job, Workpiece)> = vec![("demo".into(), Job::demo(), demo_part().into())];
    let ops = [
        ("zlevel", json!([{ "kind": "roughZlevel", "tool": 1, "stepdown": 3.0, "grid": 0.5 }])),
        ("zigzag", json!([{ "kind": "roughZigzag", "tool": 1, "stepdown": 3.0, "grid": 0.5 }])),
        ("octree", json!([{ "kind": "roughOctree", "tools": [], "grid": 0.5 }])),
    ];
    for (name, op) in &ops {
        cases.push((format!("demo part/{name}"), part_job(op.clone()), demo_part().into()));
    }
    if let Some(path) = common::shared_data("meshes/pycam_textbox.stl") {
        let mesh = read_mesh_auto(&std::fs::read(path).unwrap(), Some("pycam_textbox.stl"), &swarf::geom::Tolerances::default()).unwrap();
        for (name, op) in &ops {
            let mut job = part_job(op.clone());
            job.simulation.verify = true;
            cases.push((format!("pycam_textbox/{name}"), job, mesh.clone().into()));
        }
    }
    // (On a machine of one core both runs are the same run.)
    for (name, job, workpiece) in cases {
        let every = run(&job, workpiece.clone());
        let one = swarf::parallel::alone(|| {
            assert_eq!(swarf::parallel::threads(), 1);
            run(&job, workpiece)
        });
        assert!(every == one, "{name}: {} bytes on every core, {} on one thread", every.len(), one.len());
    }
}

#[test]
fn every_golden_program_is_byte_identical() {
    let got: Vec<(String, u64, usize)> = programs().into_iter().map(|(n, g)| (n, fnv1a(g.as_bytes()), g.len())).collect();
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        let text: String = got.iter().map(|(n, h, l)| format!("{n}\t{h:016x}\t{l}\n")).collect();
        std::fs::create_dir_all(std::path::Path::new(FILE).parent().unwrap()).unwrap();
        std::fs::write(FILE, text).unwrap();
        return;
    }
    let want = std::fs::read_to_string(FILE).expect("tests/golden/programs.tsv (UPDATE_GOLDEN=1 writes it)");
    let want: std::collections::HashMap<&str, (&str, &str)> = want
        .lines()
        .filter_map(|l| {
            let mut f = l.split('\t');
            Some((f.next()?, (f.next()?, f.next()?)))
        })
        .collect();
    let mut changed = Vec::new();
    for (name, hash, len) in &got {
        let Some((h, l)) = want.get(name.as_str()) else { panic!("{name}: no golden program recorded") };
        if *h != format!("{hash:016x}") || *l != len.to_string() {
            changed.push(format!("{name}: {l} bytes {h} before, {len} bytes {hash:016x} now"));
        }
    }
    assert!(changed.is_empty(), "programs changed:\n{}", changed.join("\n"));
    assert!(got.len() >= 2, "the demo cases always run");
}
