//! Parts swarf makes itself: the built-in sample of the page and `swarf demo`, the synthetic die
//! of seed 001's benchmark, and analytic shapes for tests. Each is a closed solid whose top is a
//! height field `z = f(x, y)` over a rectangle, with walls and a flat bottom.

use super::Mesh;
use crate::geom::{DVec2, DVec3, Tolerances};

/// A closed solid over `[min, max]` whose top is `top(x, y)`, sampled on `nx × ny` quads, with
/// its bottom at `bottom`.
pub fn height_field_solid(min: DVec2, max: DVec2, nx: usize, ny: usize, bottom: f64, top: impl Fn(f64, f64) -> f64) -> Mesh {
    two_height_solid(min, max, nx, ny, &|_, _| bottom, &top, &[])
}

/// A round vertical hole in a generated solid: true cylinder walls (`sides` facets), set in a
/// square of grid cells round its centre whose faces are fanned between the square's edge and
/// the hole's rim (so the square must sit where the faces it replaces are flat enough to be
/// one face, and off the solid's edge).
#[derive(Clone, Copy, Debug)]
pub struct Bore {
    pub center: DVec2,
    pub diameter: f64,
    /// Half the side of the square of cells it is set in (mm, more than the radius).
    pub half: f64,
    pub sides: usize,
    pub kind: BoreKind,
}

/// Where a [`Bore`] opens.
#[derive(Clone, Copy, Debug)]
pub enum BoreKind {
    /// From the top to the bottom.
    Through,
    /// From the top, this deep below the top at its centre, ending in a drill's 118° cone.
    FromTop(f64),
    /// From the bottom, this high above the bottom at its centre, ending in a drill's cone.
    FromBottom(f64),
}

/// Half a drill's 118° point.
const DRILL_POINT: f64 = 59.0 * std::f64::consts::PI / 180.0;

/// A closed solid over `[min, max]` between `bottom(x, y)` and `top(x, y)` (the top higher
/// everywhere), both sampled on `nx × ny` quads, with walls between their edges; a flat bottom
/// is one face of two triangles.
fn two_height_solid(min: DVec2, max: DVec2, nx: usize, ny: usize, bottom: &dyn Fn(f64, f64) -> f64, top: &dyn Fn(f64, f64) -> f64, bores: &[Bore]) -> Mesh {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let xy = |i: usize, j: usize| DVec2::new(min.x + (max.x - min.x) * i as f64 / nx as f64, min.y + (max.y - min.y) * j as f64 / ny as f64);
    let at = |i: usize, j: usize| {
        let p = xy(i, j);
        p.extend(top(p.x, p.y))
    };
    let under = |i: usize, j: usize| {
        let p = xy(i, j);
        p.extend(bottom(p.x, p.y))
    };
    let mut tris = Vec::with_capacity(4 * nx * ny + 4 * (nx + ny));
    // Each bore's square as cell indices [i0, i1) × [j0, j1).
    let index = |v: f64, lo: f64, hi: f64, n: usize| (((v - lo) / (hi - lo) * n as f64).round().max(0.0) as usize).min(n);
    let squares: Vec<[usize; 4]> = bores
        .iter()
        .map(|b| {
            [index(b.center.x - b.half, min.x, max.x, nx), index(b.center.x + b.half, min.x, max.x, nx), index(b.center.y - b.half, min.y, max.y, ny), index(b.center.y + b.half, min.y, max.y, ny)]
        })
        .collect();
    let in_bore = |i: usize, j: usize, top_side: bool| {
        bores.iter().zip(&squares).any(|(b, &[i0, i1, j0, j1])| {
            let opens = match b.kind {
                BoreKind::Through => true,
                BoreKind::FromTop(_) => top_side,
                BoreKind::FromBottom(_) => !top_side,
            };
            opens && (i0..i1).contains(&i) && (j0..j1).contains(&j)
        })
    };
    for j in 0..ny {
        for i in 0..nx {
            if in_bore(i, j, true) {
                continue;
            }
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    let mut wall = |(i, j): (usize, usize), (k, l): (usize, usize)| {
        let (p, q) = (at(i, j), at(k, l));
        tris.push([p, under(i, j), under(k, l)]);
        tris.push([p, under(k, l), q]);
    };
    for i in 0..nx {
        wall((i + 1, 0), (i, 0));
        wall((i, ny), (i + 1, ny));
    }
    for j in 0..ny {
        wall((0, j), (0, j + 1));
        wall((nx, j + 1), (nx, j));
    }
    // A flat bottom is one face (as the sample part has always had); any other is a grid
    // facing down.
    let z0 = bottom(min.x, min.y);
    let flat = bores.is_empty() && (0..=ny).all(|j| (0..=nx).all(|i| under(i, j).z == z0));
    if flat {
        let corners = [min.extend(z0), DVec3::new(max.x, min.y, z0), max.extend(z0), DVec3::new(min.x, max.y, z0)];
        tris.push([corners[0], corners[2], corners[1]]);
        tris.push([corners[0], corners[3], corners[2]]);
    } else {
        for j in 0..ny {
            for i in 0..nx {
                if in_bore(i, j, false) {
                    continue;
                }
                let (a, b, c, d) = (under(i, j), under(i + 1, j), under(i + 1, j + 1), under(i, j + 1));
                tris.push([a, c, b]);
                tris.push([a, d, c]);
            }
        }
    }
    for (b, &[i0, i1, j0, j1]) in bores.iter().zip(&squares) {
        // The square's edge from its lower left corner, anticlockwise seen from above.
        let mut edge: Vec<(usize, usize)> = (i0..i1).map(|i| (i, j0)).collect();
        edge.extend((j0..j1).map(|j| (i1, j)));
        edge.extend((i0 + 1..=i1).rev().map(|i| (i, j1)));
        edge.extend((j0 + 1..=j1).rev().map(|j| (i0, j)));
        let angle = |p: DVec2| (p - b.center).to_angle();
        let start = angle(xy(i0, j0));
        let n = b.sides.max(6);
        let rim = |k: usize| b.center + DVec2::from_angle(start + std::f64::consts::TAU * k as f64 / n as f64) * (b.diameter / 2.0);
        // Anticlockwise angle from the start, in [0, 2π].
        let turned = |p: DVec2, last: bool| {
            let a = (angle(p) - start).rem_euclid(std::f64::consts::TAU);
            if last && a < 1e-9 {
                std::f64::consts::TAU
            } else {
                a
            }
        };
        let mut push = |t: [DVec3; 3], hint: DVec3| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            tris.push(if n.dot(hint) < 0.0 { [t[0], t[2], t[1]] } else { t });
        };
        // The face between the square's edge and the rim, at the height `z` of each point.
        let annulus = |z: &dyn Fn(DVec2) -> f64, up: f64, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
            let (mut e, mut k) = (0, 0);
            let lift = |p: DVec2| p.extend(z(p));
            while e < edge.len() || k < n {
                let (p, q) = (xy(edge[e % edge.len()].0, edge[e % edge.len()].1), xy(edge[(e + 1) % edge.len()].0, edge[(e + 1) % edge.len()].1));
                let next_edge = turned(q, e + 1 == edge.len());
                let next_rim = std::f64::consts::TAU * (k + 1) as f64 / n as f64;
                if k == n || (e < edge.len() && next_edge <= next_rim) {
                    push([lift(p), lift(q), lift(rim(k % n))], DVec3::Z * up);
                    e += 1;
                } else {
                    push([lift(p), lift(rim((k + 1) % n)), lift(rim(k % n))], DVec3::Z * up);
                    k += 1;
                }
            }
        };
        let wall = |from: &dyn Fn(DVec2) -> f64, to: &dyn Fn(DVec2) -> f64, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
            for k in 0..n {
                let (p, q) = (rim(k), rim((k + 1) % n));
                let inward = (b.center - (p + q) / 2.0).extend(0.0);
                push([p.extend(from(p)), q.extend(from(q)), q.extend(to(q))], inward);
                push([p.extend(from(p)), q.extend(to(q)), p.extend(to(p))], inward);
            }
        };
        let cone = |z: f64, down: f64, push: &mut dyn FnMut([DVec3; 3], DVec3)| {
            let apex = b.center.extend(z + down * b.diameter / 2.0 / DRILL_POINT.tan());
            for k in 0..n {
                push([apex, rim(k).extend(z), rim((k + 1) % n).extend(z)], DVec3::Z * -down);
            }
        };
        let (t, u) = (|p: DVec2| top(p.x, p.y), |p: DVec2| bottom(p.x, p.y));
        match b.kind {
            BoreKind::Through => {
                annulus(&t, 1.0, &mut push);
                wall(&t, &u, &mut push);
                annulus(&u, -1.0, &mut push);
            }
            BoreKind::FromTop(depth) => {
                let floor = top(b.center.x, b.center.y) - depth;
                annulus(&t, 1.0, &mut push);
                wall(&t, &|_| floor, &mut push);
                cone(floor, -1.0, &mut push);
            }
            BoreKind::FromBottom(height) => {
                let floor = bottom(b.center.x, b.center.y) + height;
                annulus(&u, -1.0, &mut push);
                wall(&|_| floor, &u, &mut push);
                cone(floor, 1.0, &mut push);
            }
        }
    }
    Mesh::from_triangles(tris, &Tolerances::DEFAULT).expect("a generated solid has triangles")
}

/// A part with features on both sides, for setups: an 80 × 50 × 16 mm plate (top at z = 0)
/// with a 30 × 20 mm pocket 5 deep, a dome 1.5 high and 26 across and four φ5.5 holes through its corners
/// (M5 clearance, at x ±32, y ±17) on top, and underneath a slot 10 wide and 4 deep across its
/// width and a round boss φ16 standing 2 mm below the rest of the bottom, with a φ4.2 hole 8
/// deep in it (M5 tapping size, a drill's point at its end). Its holes are true cylinders; its
/// other walls lean by the half-millimetre grid it is sampled on.
pub fn two_sided_part() -> Mesh {
    let corner = |x: f64, y: f64| Bore { center: DVec2::new(x, y), diameter: 5.5, half: 4.0, sides: 48, kind: BoreKind::Through };
    two_height_solid(
        DVec2::new(-40.0, -25.0),
        DVec2::new(40.0, 25.0),
        160,
        100,
        &|x, y| {
            if (x - 20.0).abs() < 5.0 {
                -12.0 // the slot
            } else if (x + 15.0).hypot(y) < 8.0 {
                -18.0 // the boss
            } else {
                -16.0
            }
        },
        &|x, y| {
            if (x + 15.0).abs() < 15.0 && y.abs() < 10.0 {
                -5.0 // the pocket
            } else {
                // The dome: 1.5 high, 13 across its foot, meeting the plate level (the
                // level of the holes' tops) with no edge.
                let u = ((x - 22.0).powi(2) + y.powi(2)) / (13.0 * 13.0);
                1.5 * (1.0 - u).max(0.0).powi(3) - 1.5
            }
        },
        &[
            corner(-32.0, -17.0),
            corner(32.0, -17.0),
            corner(32.0, 17.0),
            corner(-32.0, 17.0),
            Bore { center: DVec2::new(-15.0, 0.0), diameter: 4.2, half: 4.0, sides: 40, kind: BoreKind::FromBottom(8.0) },
        ],
    )
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The two-sided plate is one closed solid whose holes are found as drawn: four through
    /// holes from the top, and the boss's blind hole only from below.
    #[test]
    fn the_two_sided_plates_holes_are_found_from_the_side_they_open_on() {
        let part = two_sided_part();
        assert!(part.open_edges().is_empty(), "the plate is closed");
        let holes = crate::holes::mesh::find(&part);
        let through: Vec<_> = holes.iter().filter(|h| h.through).collect();
        assert_eq!(through.len(), 4, "{holes:?}");
        for h in &through {
            assert!((h.diameter - 5.5).abs() < 1e-6 && (h.center.x.abs() - 32.0).abs() < 1e-6 && (h.center.y.abs() - 17.0).abs() < 1e-6, "{h:?}");
            assert!((h.bottom + 16.0).abs() < 1e-9 && (h.top + 1.5).abs() < 1e-9, "{h:?}");
        }
        assert_eq!(holes.len(), 4, "the boss's hole opens downwards: not one to drill from the top: {holes:?}");
        let mut turned = part.clone();
        for v in &mut turned.vertices {
            (v.y, v.z) = (-v.y, -v.z);
        }
        let below = crate::holes::mesh::find(&turned);
        let blind: Vec<_> = below.iter().filter(|h| !h.through).collect();
        assert_eq!((below.len(), blind.len()), (5, 1), "{below:?}");
        let h = blind[0];
        assert!((h.diameter - 4.2).abs() < 1e-6 && (h.center.x + 15.0).abs() < 1e-6 && h.center.y.abs() < 1e-6, "{h:?}");
        assert!((h.top - 18.0).abs() < 1e-9 && (h.bottom - 10.0).abs() < 1e-9 && h.bottom_shape == crate::holes::Bottom::Cone, "{h:?}");
    }
}
