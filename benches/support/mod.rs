//! What the benchmarks share with each other, with the wasm benchmark (`tests/bench_wasm.rs`)
//! and with the tests that check a benchmark's case: dev-only, not part of the library.
#![allow(dead_code)]

pub mod job;
pub mod zmap;
