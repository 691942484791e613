//! Any bytes read as Gltf (see invariants.rs).
#![no_main]

mod invariants;

libfuzzer_sys::fuzz_target!(|data: &[u8]| invariants::check(data, swarf::mesh::import::MeshFormat::Gltf));
