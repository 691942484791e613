//! Seed 001's application example at its size (§4.2): a 1190 × 890 mm freeform die (a
//! synthetic stand-in for the paper's car fuel-tank die) of about 500,000 triangles, CC z-map
//! at 0.8 mm, CL z-maps for a 10 mm and a 20 mm ball by both builders, beside the paper's
//! 10 s / 15 s (inverse offset) and 355 s / 450 s (offset facets).
//!
//! Run: `cargo bench --bench zmap_die` (native). The wasm figures come from the same code in
//! headless Chromium: `bash scripts/bench-wasm.sh`.

mod support;

use support::zmap::{die_case, DieFigures};

fn main() {
    let case = die_case();
    println!("{}", case.describe());
    let figures: Vec<DieFigures> = case.run();
    for f in &figures {
        println!("{}", f.row("native"));
    }
}
