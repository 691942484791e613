//! The part's CC z-map: at each node, the highest facet of the part over it (a zero-radius
//! drop). Vertical facets have no height of their own and are skipped; the facets they join
//! give the heights on either side.

use super::{Grid, HeightField};
use crate::cutter::FacetPlane;
use crate::geom::Tolerances;
use crate::mesh::Mesh;

/// Builds the CC z-map; nodes no facet covers hold `floor`.
pub fn cc_zmap(mesh: &Mesh, grid: Grid, floor: f64, tolerances: &Tolerances) -> HeightField {
    let mut field = grid.filled(floor);
    for t in mesh.triangles() {
        let Some(facet) = FacetPlane::new(t.a, t.b, t.c, tolerances.normal) else { continue };
        let b = t.bounds();
        let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(b.min.x, b.max.x), grid.rows(b.min.y, b.max.y)) else { continue };
        for j in j0..=j1 {
            let row = &mut field.z[j * grid.nx..(j + 1) * grid.nx];
            for (i, z) in row.iter_mut().enumerate().take(i1 + 1).skip(i0) {
                let p = grid.node(i, j);
                if facet.contains(p) {
                    *z = z.max(facet.z_at(p));
                }
            }
        }
    }
    field
}
