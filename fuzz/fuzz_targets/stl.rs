//! Any bytes read as Stl: an error or a mesh, never a panic; a mesh has only finite,
//! non-degenerate triangles and faces that index its vertices.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf::geom::Tolerances;
use swarf::mesh::import::{read_mesh, MeshFormat};

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = read_mesh(data, MeshFormat::Stl, &Tolerances::DEFAULT) {
        assert!(mesh.vertices.iter().all(|v| v.is_finite()));
        assert!(mesh.faces.iter().flatten().all(|&i| (i as usize) < mesh.vertices.len()));
        assert!(!mesh.faces.is_empty());
    }
});
