//! Benchmarks in the browser: the same code as the native benches, compiled to wasm and run in
//! headless Chromium. Not part of the test suite: `bash scripts/bench-wasm.sh` runs it and
//! prints the figures (the tests assert only that the figures were produced).
#![cfg(target_arch = "wasm32")]

#[path = "../benches/support/mod.rs"]
mod support;

use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

fn now() -> f64 {
    js_sys::Date::now() / 1000.0
}

#[wasm_bindgen_test]
fn die_zmaps_in_wasm() {
    let case = support::zmap::die_case();
    web_sys_log(&case.describe());
    for f in case.run_with(&now) {
        web_sys_log(&f.row("wasm (Chromium)"));
        assert!(f.exact_seconds > 0.0);
    }
}

fn web_sys_log(s: &str) {
    wasm_bindgen_test::console_log!("{}", s);
}

#[wasm_bindgen_test]
fn paper_table_2_in_wasm() {
    for row in swarf::sim::paper::table(&now, 20) {
        web_sys_log(&row.line("wasm"));
        assert!(row.volume > 0.0);
    }
}

#[wasm_bindgen_test]
fn program_simulation_in_wasm() {
    let sample = support::job::sample_case(&now);
    web_sys_log(&sample.job_row("wasm (Chromium)"));
    web_sys_log(&sample.run(sample.cell_for(1e6), None, &now).row("wasm (Chromium)"));
    let die = support::job::die_case(&now);
    web_sys_log(&die.job_row("wasm (Chromium)"));
    web_sys_log(&die.run(die.cell_for(1e6), None, &now).row("wasm (Chromium)"));
    let f = die.run(die.cell_for(1e6), Some(100_000), &now);
    web_sys_log(&f.row("wasm (Chromium)"));
    assert!(f.simulate_seconds > 0.0);
}

#[wasm_bindgen_test]
fn sequences_in_wasm() {
    let rows = support::job::sequence_rows("wasm (Chromium)", &now);
    for row in &rows {
        web_sys_log(row);
    }
    assert_eq!(rows.len(), 3);
}

#[wasm_bindgen_test]
fn roughing_in_wasm() {
    // Issue 12's benchmark part (read at build time from ../shared/data; this file is built
    // only by scripts/bench-wasm.sh).
    let stl = include_bytes!("../../shared/data/meshes/ocl_mount_rush.stl");
    let row = support::job::rough_row("ocl_mount_rush", stl, "wasm (Chromium)", &now);
    web_sys_log(&row);
    assert!(row.contains("total"));
}

#[wasm_bindgen_test]
fn zigzag_in_wasm() {
    let rows = support::job::zigzag_rows("wasm (Chromium)", &now);
    for row in &rows {
        web_sys_log(row);
    }
    assert_eq!(rows.len(), 3);
}

#[wasm_bindgen_test]
fn zigzag_pocket_test_in_wasm() {
    // Beside FreeCAD's Adaptive (scripts/bench-zigzag-peers.sh), the shared pocket test.
    let stl = include_bytes!("../../shared/data/meshes/kiri_pocket-test.stl");
    for row in support::job::zigzag_peer_rows("kiri_pocket-test", stl, "wasm (Chromium)", &now) {
        web_sys_log(&row);
    }
}

#[wasm_bindgen_test]
fn octree_roughing_in_wasm() {
    // Seed 000's comparison on the generated mould (octree, z-level with the φ3 alone, φ20 then φ3).
    let rows = support::job::octree_rows("mould", &swarf::mesh::sample::octree_mould(1.0), "wasm (Chromium)", &now);
    for row in &rows {
        web_sys_log(row);
    }
    assert_eq!(rows.len(), 3);
}
