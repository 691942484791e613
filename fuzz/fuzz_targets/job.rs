//! The whole path on any bytes: file → part or drawing → a small job with fuzzed settings →
//! program (see `whole_path.rs`).
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "whole_path.rs"]
mod whole_path;

fuzz_target!(|data: &[u8]| whole_path::check(data));
