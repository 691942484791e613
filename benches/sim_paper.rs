//! Seed 002's Table 2, beside swarf's: the φ4 flat and ball end mills' groove and side cut, each
//! stock model, cells of 0.5, 0.3 and 0.1 mm; time and error of the removed volume against the
//! closed form (`swarf::sim::paper`).
//!
//! Run: `cargo bench --bench sim_paper` (native). The wasm figures: `bash scripts/bench-wasm.sh`.

use swarf::sim::paper::{table, PAPER_TABLE_2};

fn main() {
    println!("seed 002 Table 2 (paper, ms / error in its unit; cells 0.5, 0.3, 0.1 mm):");
    for (name, cells) in PAPER_TABLE_2 {
        let cols: Vec<String> = cells.iter().map(|(ms, err)| format!("{ms:>6.0} ms / {err:<6}")).collect();
        println!("  {name:<30} {}", cols.join("  "));
    }
    let origin = std::time::Instant::now();
    let clock = || origin.elapsed().as_secs_f64();
    for row in table(&clock, 5) {
        println!("{}", row.line("native"));
    }
}
