//! A part's horizontal sections: how much of its outline the solid covers at each height, and
//! the height where that is greatest (its widest section), where a part machined from both
//! sides is parted between them: each side is cut down to it from its own face, so neither
//! side's tool has to reach under the part's widest outline.
//!
//! The solid is read by vertical rays, not by its facets' windings (which files get wrong):
//! at each point of a grid over the part, the heights where the ray crosses a facet, sorted,
//! pair up into the runs of the solid along the ray (in, out, in, out). A section's area is
//! the grid's cell area times the rays whose runs hold its height.

use super::Mesh;

/// How many grid points along the part's longer side.
const RAYS: usize = 200;

/// How many heights the part's height is weighed in.
const SECTIONS: usize = 400;

/// The runs of the solid along vertical rays over `mesh`: the grid's cell area, and each ray's
/// heights (in, out, in, out …).
fn runs(mesh: &Mesh) -> (f64, Vec<Vec<f64>>) {
    let b = mesh.bounds();
    let size = b.max - b.min;
    let cell = size.x.max(size.y) / RAYS as f64;
    if !(cell > 0.0) {
        return (0.0, Vec::new());
    }
    let (nx, ny) = ((size.x / cell).ceil() as usize + 1, (size.y / cell).ceil() as usize + 1);
    // Off the round numbers a part's edges and vertices lie on.
    let shift = 0.381_966 * cell;
    let at = |i: usize, j: usize| (b.min.x + shift + i as f64 * cell, b.min.y + shift + j as f64 * cell);
    let mut hits: Vec<Vec<f64>> = vec![Vec::new(); nx * ny];
    for t in mesh.triangles() {
        let (a, p, q) = (t.a, t.b, t.c);
        let det = (p.x - a.x) * (q.y - a.y) - (q.x - a.x) * (p.y - a.y);
        if det.abs() < 1e-12 {
            continue;
        }
        let (lo_x, hi_x) = (a.x.min(p.x).min(q.x), a.x.max(p.x).max(q.x));
        let (lo_y, hi_y) = (a.y.min(p.y).min(q.y), a.y.max(p.y).max(q.y));
        let first = |lo: f64, origin: f64| (((lo - origin - shift) / cell).ceil().max(0.0)) as usize;
        let (i0, j0) = (first(lo_x, b.min.x), first(lo_y, b.min.y));
        for j in j0..ny {
            let y = at(0, j).1;
            if y > hi_y {
                break;
            }
            for i in i0..nx {
                let x = at(i, 0).0;
                if x > hi_x {
                    break;
                }
                let u = ((x - a.x) * (q.y - a.y) - (q.x - a.x) * (y - a.y)) / det;
                let v = ((p.x - a.x) * (y - a.y) - (x - a.x) * (p.y - a.y)) / det;
                if u >= 0.0 && v >= 0.0 && u + v <= 1.0 {
                    hits[j * nx + i].push(a.z + u * (p.z - a.z) + v * (q.z - a.z));
                }
            }
        }
    }
    for h in &mut hits {
        crate::geom::sort::sort_floats(h);
    }
    (cell * cell, hits)
}

impl Mesh {
    /// The area (mm²) of the solid's section at height `z`, to the rays' grid (a 200th of the
    /// part's longer side).
    pub fn section_area(&self, z: f64) -> f64 {
        let (area, hits) = runs(self);
        area * hits.iter().filter(|h| h.chunks_exact(2).any(|r| r[0] <= z && z < r[1])).count() as f64
    }

    /// The height of the part's widest horizontal section (the lowest of the widest ones):
    /// where a two-sided job parts the part between its sides. None for a part with no
    /// height.
    pub fn widest_section(&self) -> Option<f64> {
        let b = self.bounds();
        let h = b.max.z - b.min.z;
        if !(h > 0.0) || self.faces.is_empty() {
            return None;
        }
        let (_, hits) = runs(self);
        // How many rays' runs hold each band of heights: +1 where a run starts, -1 past it.
        let band = |z: f64| (((z - b.min.z) / h * SECTIONS as f64).floor().max(0.0) as usize).min(SECTIONS);
        let mut change = vec![0i64; SECTIONS + 1];
        for ray in &hits {
            for r in ray.chunks_exact(2) {
                let (lo, hi) = (band(r[0]), band(r[1]));
                if hi > lo {
                    change[lo] += 1;
                    change[hi] -= 1;
                }
            }
        }
        let (mut count, mut best) = (0i64, (0i64, 0usize));
        for (k, c) in change.iter().take(SECTIONS).enumerate() {
            count += c;
            if count > best.0 {
                best = (count, k);
            }
        }
        Some(b.min.z + h * (best.1 as f64 + 0.5) / SECTIONS as f64)
    }
}

#[cfg(test)]
mod tests {
    use crate::geom::{DVec3, Tolerances};
    use crate::mesh::Mesh;

    /// Two boxes stacked: 10 × 10 from 0 to 5, 20 × 30 from 5 to 8, some facets wound inward
    /// (as files have them): its sections are 100 and 600 mm² to the grid, and the widest is
    /// the upper box's, just above 5.
    #[test]
    fn a_sections_area_and_the_widest_are_found_whatever_the_windings() {
        let mut tris = Vec::new();
        let mut cuboid = |lo: DVec3, hi: DVec3, flip: bool| {
            let c = |i: usize| DVec3::new(if i & 1 == 0 { lo.x } else { hi.x }, if i & 2 == 0 { lo.y } else { hi.y }, if i & 4 == 0 { lo.z } else { hi.z });
            let faces: [[usize; 3]; 12] = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]];
            for (k, f) in faces.iter().enumerate() {
                tris.push(if flip && k % 2 == 0 { [c(f[0]), c(f[2]), c(f[1])] } else { [c(f[0]), c(f[1]), c(f[2])] });
            }
        };
        cuboid(DVec3::new(-5.0, -5.0, 0.0), DVec3::new(5.0, 5.0, 5.0), false);
        cuboid(DVec3::new(-10.0, -15.0, 5.0), DVec3::new(10.0, 15.0, 8.0), true);
        let m = Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap();
        assert!((m.section_area(2.5) - 100.0).abs() < 5.0, "{}", m.section_area(2.5));
        assert!((m.section_area(6.0) - 600.0).abs() < 15.0, "{}", m.section_area(6.0));
        let z = m.widest_section().unwrap();
        assert!(z > 5.0 && z < 5.1, "{z}");
        // A block of one section all the way: its bottom.
        let mut tris = Vec::new();
        let c = |i: usize| DVec3::new(if i & 1 == 0 { 0.0 } else { 9.0 }, if i & 2 == 0 { 0.0 } else { 4.0 }, if i & 4 == 0 { 0.0 } else { 3.0 });
        for f in [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]] {
            tris.push([c(f[0]), c(f[1]), c(f[2])]);
        }
        let block = Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap();
        assert!(block.widest_section().unwrap() < 0.01, "{:?}", block.widest_section());
    }
}
