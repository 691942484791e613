//! The whole path on any bytes (issue 42): a file of any format, read as a part or drawing, a
//! small job whose settings come from the bytes too (among them the absurd: a step-down of
//! 1e-9, a tool of 1e9), planned, posted and verified. It gives a program or an error, never a
//! panic, and a program it gives has moves. Shared by the fuzz target `job` and by
//! `tests/fuzz_whole_path.rs`, which replays what the fuzzer kept.

use swarf::job::{self, Job, Workpiece};
use swarf::progress::Progress;

/// Values a setting is drawn from: the ordinary and the absurd.
const VALUES: [f64; 16] = [0.5, 1.0, 2.0, 3.0, 6.0, 0.1, 10.0, 25.4, 0.0, -1.0, 1e-9, 1e9, 1e308, f64::NAN, 0.001, 100.0];

/// The file names (so the formats) the rest of the bytes are read as.
const NAMES: [&str; 6] = ["f.stl", "f.obj", "f.gltf", "f.glb", "f.dxf", "f.svg"];

/// Runs the bytes through the whole path: the first six choose the format, the operation and
/// four settings; the rest is the file.
pub fn check(data: &[u8]) {
    if data.len() < 6 {
        return;
    }
    let (head, file) = data.split_at(6);
    let name = NAMES[head[0] as usize % NAMES.len()];
    let value = |k: usize| VALUES[head[k] as usize % VALUES.len()];
    let drawing = name.ends_with("dxf") || name.ends_with("svg");
    let kinds: &[&str] = if drawing { &["profile2d", "pocket2d", "engrave"] } else { &["roughZlevel", "finishRaster", "finishWaterline"] };
    let kind = kinds[head[1] as usize % kinds.len()];
    let mut value_job = serde_json::to_value(Job::default()).unwrap();
    value_job["tools"][0]["diameter"] = serde_json::json!(value(2));
    value_job["operations"] = serde_json::json!([{ "kind": kind, "tool": 1 }]);
    let field = match kind {
        "finishRaster" => "stepover",
        _ => "stepdown",
    };
    value_job["operations"][0][field] = serde_json::json!(value(3));
    value_job["stock"]["marginTop"] = serde_json::json!(value(4));
    value_job["drawing"]["thickness"] = serde_json::json!(value(5));
    // A coarse simulation keeps each run short.
    value_job["simulation"]["cell"] = serde_json::json!(1.0);
    // NaN is no JSON number: such a setting reads as null, which the strict reader refuses.
    let Ok(job) = Job::from_value(&value_job) else { return };
    let Ok(workpiece) = Workpiece::read(file, Some(name), &job.tolerances) else { return };
    if let Ok(out) = job::run(&job, workpiece, &mut Progress::none()) {
        assert!(!out.moves.is_empty(), "a program without moves");
        assert!(out.gcode.contains('G'), "a program without G words");
    }
}
