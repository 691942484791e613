//! Simulating whole finishing programs on the z-map stock: the sample part at a million cells,
//! and seed 001's die (the foundation issue's benchmark part) at a million cells and at 0.1 mm.
//!
//! Run: `cargo bench --bench sim_program` (native; add `-- --die-fine` for the die at 0.1 mm,
//! about 106 million cells). The wasm figures: `bash scripts/bench-wasm.sh`.

mod support;

use support::job::{die_case, sample_case};

fn main() {
    let origin = std::time::Instant::now();
    let clock = || origin.elapsed().as_secs_f64();
    let sample = sample_case(&clock);
    println!("{}", sample.job_row("native"));
    println!("{}", sample.run(sample.cell_for(1e6), None, &clock).row("native"));
    let die = die_case(&clock);
    println!("{}", die.job_row("native"));
    println!("{}", die.run(die.cell_for(1e6), None, &clock).row("native"));
    println!("{}", die.run(die.cell_for(1e6), Some(100_000), &clock).row("native"));
    if std::env::args().any(|a| a == "--die-fine") {
        println!("{}", die.run(0.1, None, &clock).row("native"));
    }
}
