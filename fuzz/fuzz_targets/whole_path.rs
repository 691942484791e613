//! The whole path on any bytes (issue 42): a file of any format, read as a part or drawing, a
//! small job whose settings come from the bytes too (among them the absurd: a step-down of
//! 1e-9, a tool of 1e9), planned, posted and verified. It gives a program or an error, never a
//! panic, and a program it gives has moves. Every operation kind that works on what the file
//! is (issue 56: each option family), with a tool of its kind, and any one of its numeric
//! settings (found in its defaults, so a new setting is fuzzed without a word here). Shared by
//! the fuzz target `job` and by `tests/fuzz_whole_path.rs`, which replays what the fuzzer kept.

use serde_json::{json, Value};
use swarf::job::{self, Job, Workpiece};
use swarf::machining::Works;
use swarf::operations::Operation;
use swarf::progress::Progress;

/// Values a setting is drawn from: the ordinary and the absurd.
pub const VALUES: [f64; 16] = [0.5, 1.0, 2.0, 3.0, 6.0, 0.1, 10.0, 25.4, 0.0, -1.0, 1e-9, 1e9, 1e308, f64::NAN, 0.001, 100.0];

/// The file names (so the formats) the rest of the bytes are read as.
pub const NAMES: [&str; 6] = ["f.stl", "f.obj", "f.gltf", "f.glb", "f.dxf", "f.svg"];

/// Bytes of the head: the format, the operation kind, the tool's diameter, which of the
/// kind's settings and its value, the stock's top margin and the sheet's thickness.
pub const HEAD: usize = 7;

/// The operation kinds that work on a drawing (`drawing`) or on a part, in a fixed order.
pub fn kinds(drawing: bool) -> Vec<Value> {
    let want = if drawing { Works::OnDrawing } else { Works::OnPart };
    Operation::defaults().iter().filter(|o| o.op().works() == want || o.op().works() == Works::Either).map(|o| serde_json::to_value(o).unwrap()).collect()
}

/// The paths (dot-separated, under the operation) of the numbers and unset numbers of `op`.
pub fn settings(op: &Value) -> Vec<String> {
    fn walk(value: &Value, prefix: &str, out: &mut Vec<String>) {
        match value {
            Value::Object(map) => {
                for (k, v) in map {
                    if !["kind", "name", "tool", "tools", "enabled", "number"].contains(&k.as_str()) {
                        walk(v, &if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") }, out);
                    }
                }
            }
            Value::Number(_) | Value::Null => out.push(prefix.to_string()),
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(op, "", &mut out);
    out
}

/// A tool such an operation takes, `diameter` across.
fn tool_for(kind: &str, diameter: f64) -> Value {
    match kind {
        "finishRaster" | "finishWaterline" => json!({ "number": 1, "shape": "ball", "diameter": diameter, "fluteLength": 30 }),
        "engrave" | "chamfer" | "vcarve" => json!({ "number": 1, "shape": "vBit", "diameter": diameter, "angle": 60, "fluteLength": 15 }),
        "drill" => json!({ "number": 1, "shape": "drill", "diameter": diameter, "fluteLength": 30 }),
        "threadMill" => json!({ "number": 1, "shape": "threadMill", "diameter": diameter, "fluteLength": 15 }),
        _ => json!({ "number": 1, "shape": "flat", "diameter": diameter, "fluteLength": 30 }),
    }
}

/// Runs the bytes through the whole path: the first [`HEAD`] choose the format, the operation,
/// its tool's diameter, one of its settings and its value, and two of the job's; the rest is
/// the file.
pub fn check(data: &[u8]) {
    if data.len() < HEAD {
        return;
    }
    let (head, file) = data.split_at(HEAD);
    let name = NAMES[head[0] as usize % NAMES.len()];
    let value = |k: usize| VALUES[head[k] as usize % VALUES.len()];
    let drawing = name.ends_with("dxf") || name.ends_with("svg");
    let kinds = kinds(drawing);
    let mut op = kinds[head[1] as usize % kinds.len()].clone();
    let kind = op["kind"].as_str().unwrap().to_string();
    // Where the defaults find nothing to cut on an ordinary drawing: its loops engraved, its
    // small holes threaded.
    match kind.as_str() {
        "engrave" => op["allLoops"] = json!(true),
        "threadMill" => op["maxDiameter"] = json!(6),
        _ => {}
    }
    let fields = settings(&op);
    if let Some(path) = fields.get(head[3] as usize % fields.len().max(1)) {
        let mut at = &mut op;
        for key in path.split('.') {
            at = &mut at[key];
        }
        *at = json!(value(4));
    }
    if kind == "roughOctree" {
        op["tools"] = json!([1]);
    } else {
        op["tool"] = json!(1);
    }
    let mut value_job = serde_json::to_value(Job::default()).unwrap();
    value_job["tools"] = json!([tool_for(&kind, value(2))]);
    value_job["operations"] = json!([op]);
    value_job["stock"]["marginTop"] = json!(value(5));
    value_job["drawing"]["thickness"] = json!(value(6));
    // A coarse simulation keeps each run short.
    value_job["simulation"]["cell"] = json!(1.0);
    // NaN is no JSON number: such a setting reads as null, which the strict reader refuses
    // where the setting may not be unset.
    let Ok(job) = Job::from_value(&value_job) else { return };
    let Ok(workpiece) = Workpiece::read(file, Some(name), &job.tolerances) else { return };
    if let Ok(out) = job::run(&job, workpiece, &mut Progress::none()) {
        assert!(!out.moves.is_empty(), "a program without moves");
        assert!(out.gcode.contains('G'), "a program without G words");
    }
}
