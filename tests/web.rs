//! The pipeline in a real browser (headless Chromium through wasm-bindgen-test): the wasm
//! boundary the page's worker calls, on the built-in sample, with bad input and cancel.
#![cfg(target_arch = "wasm32")]

use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

use swarf::cutter::Cutter;
use swarf::geom::{DVec2, Tolerances};
use swarf::progress::Progress;
use swarf::wasm::{default_job, load_part, run_job, sample_part};
use swarf::zmap::{cl_exact::cl_exact, Grid};

wasm_bindgen_test_configure!(run_in_browser);

fn keep_going() -> js_sys::Function {
    js_sys::Function::new_with_args("fraction, stage", "return true")
}

fn job_with(grid: f64, stepover: f64) -> JsValue {
    let job = default_job().unwrap();
    let op = js_sys::Reflect::get(&js_sys::Reflect::get(&job, &"operations".into()).unwrap(), &0.into()).unwrap();
    js_sys::Reflect::set(&op, &"grid".into(), &grid.into()).unwrap();
    js_sys::Reflect::set(&op, &"stepover".into(), &stepover.into()).unwrap();
    job
}

#[wasm_bindgen_test]
fn sample_part_loads_and_is_placed() {
    let setup = js_sys::JSON::parse(r#"{"units":"mm","upAxis":"z","placement":"centerTop"}"#).unwrap();
    let view = load_part(&sample_part(), "sample.stl", setup, JsValue::NULL).unwrap();
    let b = view.bounds();
    assert!(b[5].abs() < 1e-4, "top at z = 0, got {}", b[5]);
    assert!((b[0] + b[3]).abs() < 1e-4 && (b[1] + b[4]).abs() < 1e-4, "centred");
    assert_eq!(view.positions().length() as usize, view.triangles() * 9);
}

#[wasm_bindgen_test]
fn job_runs_in_the_browser_and_writes_gcode() {
    let result = run_job(job_with(0.5, 2.0), &sample_part(), "sample.stl", &keep_going()).unwrap();
    let gcode = result.gcode();
    assert!(gcode.contains("G21") && gcode.contains("T1 M6") && gcode.trim_end().ends_with("M2"));
    assert!(result.feeds().length() > 6 * 1000, "feeds drawn as segments");
    let summary = result.summary().unwrap();
    let seconds = js_sys::Reflect::get(&summary, &"seconds".into()).unwrap().as_f64().unwrap();
    assert!(seconds > 10.0, "a cycle-time estimate");
}

#[wasm_bindgen_test]
fn the_browser_gives_the_same_heights_as_native_math() {
    // The exact builder at one node, against the analytic height of a ball on a tilted plane.
    let mesh = swarf::mesh::Mesh::from_triangles(vec![[glam::DVec3::new(-20.0, -20.0, -4.0), glam::DVec3::new(20.0, -20.0, 4.0), glam::DVec3::new(20.0, 20.0, 4.0)]], &Tolerances::DEFAULT).unwrap();
    let grid = Grid::covering(DVec2::new(8.0, -4.0), DVec2::new(8.0, -4.0), 1.0);
    let field = cl_exact(&mesh, &Cutter::ball(6.0).profile(), grid, -100.0, &Tolerances::DEFAULT, &mut Progress::none()).unwrap();
    let n = glam::DVec3::new(-0.2, 0.0, 1.0).normalize();
    let expected = 0.2 * 8.0 + 3.0 / n.z - 3.0;
    assert!((field.z[0] - expected).abs() < 1e-9, "{} vs {expected}", field.z[0]);
}

#[wasm_bindgen_test]
fn bad_files_and_bad_jobs_give_messages_not_panics() {
    let bytes = sample_part();
    let error = |r: Result<swarf::wasm::JobResult, wasm_bindgen::JsError>| {
        let value: JsValue = r.err().expect("an error").into();
        js_sys::Reflect::get(&value, &"message".into()).unwrap().as_string().unwrap()
    };
    assert!(error(run_job(job_with(0.5, 2.0), &bytes[..500], "broken.stl", &keep_going())).contains("truncated"));
    assert!(error(run_job(job_with(0.5, -1.0), &bytes, "sample.stl", &keep_going())).contains("stepover"));
    let nan = job_with(f64::NAN, 1.0);
    assert!(error(run_job(nan, &bytes, "sample.stl", &keep_going())).contains("grid"));
}

#[wasm_bindgen_test]
fn returning_false_from_progress_cancels() {
    let stop = js_sys::Function::new_with_args("fraction, stage", "return fraction < 0.05");
    let r = run_job(job_with(0.2, 1.0), &sample_part(), "sample.stl", &stop);
    let value: JsValue = r.err().expect("cancelled").into();
    assert_eq!(js_sys::Reflect::get(&value, &"message".into()).unwrap().as_string().unwrap(), "cancelled");
}

/// Seed 002's groove in the browser: the same volumes as natively, and the supersampled octree
/// within 0.1 % of the closed form at 0.5 mm cells.
#[wasm_bindgen_test]
fn paper_groove_in_wasm() {
    use swarf::sim::paper::{Case, Cut};
    use swarf::sim::Model;
    for case in Case::ALL.iter().filter(|c| c.cut == Cut::Groove) {
        let v = case.simulate(Model::SupersampledOctree, 0.5);
        assert!(((v - case.exact_volume()) / case.exact_volume()).abs() < 1e-3, "{}: {v}", case.label());
    }
}

/// A job run in the page carries its simulation: scrubbing back to the start shows the uncut
/// block, the end the cut one, and the report is clean.
#[wasm_bindgen_test]
fn job_result_scrubs_its_simulation() {
    let mut result = run_job(job_with(0.5, 2.0), &sample_part(), "sample.stl", &keep_going()).unwrap();
    assert!(result.has_simulation());
    let grid = result.sim_grid();
    let (nx, ny, top) = (grid[3] as usize, grid[4] as usize, grid[6] as f32);
    let times = result.times().to_vec();
    let moves = times.len() - 1;
    assert!(moves > 100 && times.windows(2).all(|w| w[0] <= w[1]));
    let end = result.seek(moves).to_vec();
    assert_eq!(end.len(), nx * ny);
    let start = result.seek(0).to_vec();
    assert!(start.iter().all(|&z| z == top));
    assert!(end.iter().filter(|&&z| z < top - 1.0).count() > nx * ny / 2);
    let report = result.report().unwrap();
    let gouges = js_sys::Reflect::get(&report, &"gougeCount".into()).unwrap().as_f64().unwrap();
    assert_eq!(gouges, 0.0);
    assert_eq!(result.mrr().length() as usize, moves);
}
