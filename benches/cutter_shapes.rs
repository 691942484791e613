//! Issue 15: no cutter shape may cost more than 1.5 times another on the same job. Runs the
//! sample part's mould job (rough, raster shallow, waterline steep) with the finishing tool a
//! ball, a bull nose and a flat end of the same diameter, and prints each one's compute time as
//! a ratio to the ball's and to the fastest. The wasm rows: `bash scripts/bench-wasm.sh`.
//!
//! `cargo bench --bench cutter_shapes`

mod support;

use support::job::{cutter_shape_rows, cutter_shape_seconds};

fn main() {
    let start = std::time::Instant::now();
    let clock = || start.elapsed().as_secs_f64();
    let seconds = [0, 1, 2].map(|k| cutter_shape_seconds(k, 2, &clock));
    for row in cutter_shape_rows("native", &seconds) {
        println!("{row}");
    }
}
