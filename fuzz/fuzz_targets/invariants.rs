//! What every importer promises on any bytes: an error or a mesh, never a panic; a mesh has only
//! finite, non-degenerate triangles and faces that index its vertices.

use swarf::geom::Tolerances;
use swarf::mesh::import::{read_mesh, MeshFormat};

pub fn check(data: &[u8], format: MeshFormat) {
    if let Ok(mesh) = read_mesh(data, format, &Tolerances::DEFAULT) {
        assert!(mesh.vertices.iter().all(|v| v.is_finite()));
        assert!(mesh.faces.iter().flatten().all(|&i| (i as usize) < mesh.vertices.len()));
        assert!(!mesh.faces.is_empty());
    }
}
