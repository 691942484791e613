//! Parts with known answers, made by the tests themselves.
#![allow(dead_code)]

use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::mesh::Mesh;

pub fn mesh(tris: Vec<[DVec3; 3]>) -> Mesh {
    Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap()
}

/// The plane z = z0 + gx x + gy y over [-half, half]², as two triangles.
pub fn plane(half: f64, z0: f64, gx: f64, gy: f64) -> Mesh {
    let p = |x: f64, y: f64| DVec3::new(x, y, z0 + gx * x + gy * y);
    let (a, b, c, d) = (p(-half, -half), p(half, -half), p(half, half), p(-half, half));
    mesh(vec![[a, b, c], [a, c, d]])
}

/// A step: z = 0 for x < 0 and z = h for x >= 0, over [-half, half]², with the vertical wall.
pub fn step(half: f64, h: f64) -> Mesh {
    let v = DVec3::new;
    mesh(vec![
        [v(-half, -half, 0.0), v(0.0, -half, 0.0), v(0.0, half, 0.0)],
        [v(-half, -half, 0.0), v(0.0, half, 0.0), v(-half, half, 0.0)],
        [v(0.0, -half, 0.0), v(0.0, -half, h), v(0.0, half, h)],
        [v(0.0, -half, 0.0), v(0.0, half, h), v(0.0, half, 0.0)],
        [v(0.0, -half, h), v(half, -half, h), v(half, half, h)],
        [v(0.0, -half, h), v(half, half, h), v(0.0, half, h)],
    ])
}

/// A roof: z = h - s |x| over [-half, half]², its sharp ridge along the Y axis.
pub fn roof(half: f64, h: f64, s: f64) -> Mesh {
    let v = |x: f64, y: f64| DVec3::new(x, y, h - s * x.abs());
    mesh(vec![
        [v(-half, -half), v(0.0, -half), v(0.0, half)],
        [v(-half, -half), v(0.0, half), v(-half, half)],
        [v(0.0, -half), v(half, -half), v(half, half)],
        [v(0.0, -half), v(half, half), v(0.0, half)],
    ])
}

/// The upper half of a sphere of radius `r` about the origin, tessellated as a height field on
/// an xy grid of `spacing` with every vertex on the sphere (so the mesh lies inside it), up to
/// the radius `rim` where the surface is still far from vertical.
pub fn cap(r: f64, rim: f64, spacing: f64) -> Mesh {
    let n = (2.0 * rim / spacing).ceil() as i64;
    let at = |i: i64, j: i64| {
        let (x, y) = (-rim + i as f64 * spacing, -rim + j as f64 * spacing);
        DVec3::new(x, y, (r * r - x * x - y * y).max(0.0).sqrt())
    };
    let inside = |p: DVec3| p.truncate().length() <= rim;
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if [a, b, c, d].iter().all(|&p| inside(p)) {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
    }
    mesh(tris)
}

/// Largest sag of a chord of length `chord` below a sphere of radius `r`.
pub fn sag(r: f64, chord: f64) -> f64 {
    r - (r * r - chord * chord / 4.0).sqrt()
}

/// Exact tip height of a cutter (radius `cr`, corner `a`) over a sphere of radius `rs` about the
/// origin, standing at `c`.
pub fn over_sphere(rs: f64, cr: f64, a: f64, c: DVec2) -> f64 {
    let off = (c.length() - (cr - a)).max(0.0);
    ((rs + a).powi(2) - off * off).sqrt() - a
}

/// Where the repository's shared data lives, if it is beside the checkout.
pub fn shared_data(rel: &str) -> Option<std::path::PathBuf> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data").join(rel);
    if p.exists() {
        Some(p)
    } else {
        eprintln!("skipping: {} is absent (shared data is not beside this checkout)", p.display());
        None
    }
}
