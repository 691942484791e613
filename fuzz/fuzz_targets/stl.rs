//! Any bytes read as Stl (see invariants.rs).
#![no_main]

mod invariants;

libfuzzer_sys::fuzz_target!(|data: &[u8]| invariants::check(data, swarf::mesh::import::MeshFormat::Stl));
