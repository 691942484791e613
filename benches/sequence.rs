//! Jobs as sequences: the die with two rasters sharing a cutter and a grid (the second
//! operation's CL z-map comes from the job's cache), and the sample part's two-tool job, with
//! the time the in-process stock takes.
//!
//! Run: `cargo bench --bench sequence` (native). The wasm figures: `bash scripts/bench-wasm.sh`.

fn main() {
    let origin = std::time::Instant::now();
    let clock = || origin.elapsed().as_secs_f64();
    for row in swarf::job::bench::sequence_rows("native", &clock) {
        println!("{row}");
    }
}
