//! Jobs as sequences: the die with two rasters sharing a cutter and a grid (the second
//! operation's CL z-map comes from the job's cache), and the sample part's two-tool job, with
//! the time the in-process stock takes; and issue 12's roughing of the shared parts (compute time).
//!
//! Run: `cargo bench --bench sequence` (native). The wasm figures: `bash scripts/bench-wasm.sh`.

mod support;

fn main() {
    let origin = std::time::Instant::now();
    let clock = || origin.elapsed().as_secs_f64();
    for row in support::job::sequence_rows("native", &clock) {
        println!("{row}");
    }
    // Issue 12's roughing benchmark, where ../shared/data is beside the project.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes");
    for part in ["ocl_mount_rush", "kiri_pocket-test", "ocl_wheel_in_box", "pycam_textbox"] {
        if let Ok(stl) = std::fs::read(dir.join(format!("{part}.stl"))) {
            println!("{}", support::job::rough_row(part, &stl, "native", &clock));
        }
    }
}
