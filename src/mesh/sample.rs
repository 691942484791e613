//! Parts swarf makes itself: the built-in sample of the page and `swarf demo`, the synthetic die
//! of seed 001's benchmark, and analytic shapes for tests. Each is a closed solid whose top is a
//! height field `z = f(x, y)` over a rectangle, with walls and a flat bottom.

use super::Mesh;
use crate::geom::{DVec2, DVec3, Tolerances};

/// A closed solid over `[min, max]` whose top is `top(x, y)`, sampled on `nx × ny` quads, with
/// its bottom at `bottom`.
pub fn height_field_solid(min: DVec2, max: DVec2, nx: usize, ny: usize, bottom: f64, top: impl Fn(f64, f64) -> f64) -> Mesh {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let at = |i: usize, j: usize| {
        let x = min.x + (max.x - min.x) * i as f64 / nx as f64;
        let y = min.y + (max.y - min.y) * j as f64 / ny as f64;
        DVec3::new(x, y, top(x, y))
    };
    let mut tris = Vec::with_capacity(2 * nx * ny + 4 * (nx + ny) + 2);
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    let floor = |p: DVec3| DVec3::new(p.x, p.y, bottom);
    let mut wall = |p: DVec3, q: DVec3| {
        tris.push([p, floor(p), floor(q)]);
        tris.push([p, floor(q), q]);
    };
    for i in 0..nx {
        wall(at(i + 1, 0), at(i, 0));
        wall(at(i, ny), at(i + 1, ny));
    }
    for j in 0..ny {
        wall(at(0, j), at(0, j + 1));
        wall(at(nx, j + 1), at(nx, j));
    }
    let corners = [min.extend(bottom), DVec3::new(max.x, min.y, bottom), max.extend(bottom), DVec3::new(min.x, max.y, bottom)];
    tris.push([corners[0], corners[2], corners[1]]);
    tris.push([corners[0], corners[3], corners[2]]);
    Mesh::from_triangles(tris, &Tolerances::DEFAULT).expect("a generated solid has triangles")
}

/// The built-in sample part: a 90 × 60 mm mould insert with a dome, a hollow and a ridge, 25 mm
/// tall, top at about z = 0. Small enough to generate a path in a second in the page.
pub fn demo_part() -> Mesh {
    height_field_solid(DVec2::new(-45.0, -30.0), DVec2::new(45.0, 30.0), 90, 60, -25.0, |x, y| {
        let dome = 9.0 * (-((x - 14.0).powi(2) + (y - 4.0).powi(2)) / 180.0).exp();
        let hollow = -6.0 * (-((x + 20.0).powi(2) + (y + 6.0).powi(2)) / 90.0).exp();
        let ridge = 3.0 * (-(x + 0.6 * y + 4.0).powi(2) / 12.0).exp();
        let swell = 1.5 * (x / 11.0).sin() * (y / 9.0).cos();
        dome + hollow + ridge + swell - 10.0
    })
}

/// A synthetic stand-in for seed 001's car fuel-tank die (1190 × 890 mm): a smooth freeform
/// cavity with draft-like walls, bumps and a ridge, `2 * nx * ny` top triangles.
pub fn fuel_tank_die(nx: usize, ny: usize) -> Mesh {
    let (w, h) = (1190.0, 890.0);
    height_field_solid(DVec2::ZERO, DVec2::new(w, h), nx, ny, -250.0, move |x, y| {
        let (u, v) = (x / w - 0.5, y / h - 0.5);
        let r = ((u / 0.38).powi(2) + (v / 0.33).powi(2)).sqrt();
        let cavity = -120.0 / (1.0 + (-(r - 1.0) * -14.0).exp());
        let boss = 45.0 * (-((u - 0.12).powi(2) + (v + 0.05).powi(2)) / 0.006).exp();
        let inside = 1.0 / (1.0 + ((r - 1.0) * 14.0).exp());
        let channel = -25.0 * (-((u + 0.2 * v + 0.15).powi(2)) / 0.002).exp() * inside;
        let waves = 6.0 * (9.0 * u).sin() * (7.0 * v).cos();
        cavity + boss + channel + waves
    })
}

/// A pocket like seed 004's test piece (its Fig. 13, 120 × 85 mm), our own outline: a 120 ×
/// 85 mm pocket `depth` deep in a plate 10 mm wider on every side, with two islands standing
/// to the plate's top: a round one (radius 10 at (35, 45)) and a rectangular one (20 × 15 at
/// (80, 30)). Sampled every `spacing` mm: its walls slope across one sample.
pub fn paper_pocket(depth: f64, spacing: f64) -> Mesh {
    let (min, max) = (DVec2::new(-10.0, -10.0), DVec2::new(130.0, 95.0));
    let nx = ((max.x - min.x) / spacing).round() as usize;
    let ny = ((max.y - min.y) / spacing).round() as usize;
    height_field_solid(min, max, nx, ny, -depth - 10.0, move |x, y| {
        let in_pocket = (0.0..=120.0).contains(&x) && (0.0..=85.0).contains(&y);
        let round = DVec2::new(x - 35.0, y - 45.0).length() <= 10.0;
        let square = (80.0..=100.0).contains(&x) && (30.0..=45.0).contains(&y);
        if in_pocket && !round && !square {
            -depth
        } else {
            0.0
        }
    })
}

/// A mould like seed 000's examples, our own: a 150 × 124 mm block, top at z = 0, with a wide
/// cavity 24 deep (x −65…5, y −45…45: room for a φ20), beside it a field of channels 14 wide
/// between ribs 3 thick, 16 deep (x 5…65: a φ12 and the wall allowances fit), a pocket 8 wide
/// and 12 deep along the top edge (a φ6) and a slot 5 wide and 8 deep along the bottom edge (a
/// φ3). Sampled every `spacing` mm: its walls slope across one sample.
pub fn octree_mould(spacing: f64) -> Mesh {
    let (min, max) = (DVec2::new(-75.0, -62.0), DVec2::new(75.0, 62.0));
    let nx = ((max.x - min.x) / spacing).round() as usize;
    let ny = ((max.y - min.y) / spacing).round() as usize;
    height_field_solid(min, max, nx, ny, -35.0, move |x, y| {
        let within = |v: f64, lo: f64, hi: f64| (lo..=hi).contains(&v);
        if within(y, -45.0, 45.0) && within(x, -65.0, 5.0) {
            -24.0
        } else if within(y, -45.0, 45.0) && within(x, 5.0, 65.0) {
            let rib = [19.0, 36.0, 53.0].iter().any(|&r| within(x, r, r + 3.0));
            if rib {
                -4.0
            } else {
                -16.0
            }
        } else if within(y, 48.0, 56.0) && within(x, -60.0, -20.0) {
            -12.0
        } else if within(y, -56.0, -51.0) && within(x, -60.0, 20.0) {
            -8.0
        } else {
            0.0
        }
    })
}

/// The part of the page's warm-up ([`crate::job::Job::warm_up`]): a 16 × 12 mm insert with a
/// hollow (a closed pocket), a dome beside it and a ledge, 6 mm tall, sampled every 0.5 mm:
/// every z-level and finishing case in miniature, so that one small job runs each strategy's
/// code once.
pub fn warm_up_part() -> Mesh {
    height_field_solid(DVec2::new(-8.0, -6.0), DVec2::new(8.0, 6.0), 32, 24, -6.0, |x, y| {
        let hollow = if (x + 3.0).abs() <= 3.5 && y.abs() <= 3.5 { -3.0 } else { 0.0 };
        let dome = 2.0 * (-((x - 4.5).powi(2) + y.powi(2)) / 5.0).exp();
        let ledge = if y > 4.5 { -1.0 } else { 0.0 };
        hollow + dome + ledge
    })
}
