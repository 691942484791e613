//! The CL z-map builders against exact answers (seed 001): analytic tip heights for flat, ball
//! and bull-nose cutters over planes, steps, ridges, points and spheres.

mod common;

use common::*;
use swarf::cutter::{Cutter, Profile};
use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::mesh::Mesh;
use swarf::progress::Progress;
use swarf::zmap::drop::PointDrop;
use swarf::zmap::{cc::cc_zmap, cl_exact::cl_exact, cl_exact::cl_exact_at, cl_inverse::cl_inverse_offset, Grid, HeightField};

const EXACT: f64 = 1e-6;
const FLOOR: f64 = -1000.0;

fn exact(mesh: &Mesh, cutter: &Cutter, min: DVec2, max: DVec2, spacing: f64) -> HeightField {
    cl_exact(mesh, &cutter.profile(), Grid::covering(min, max, spacing), FLOOR, &Tolerances::DEFAULT, &mut Progress::none()).unwrap()
}

/// Checks every node within `[min, max]` against `expected`; returns the largest error.
fn check(field: &HeightField, min: DVec2, max: DVec2, tol: f64, expected: impl Fn(DVec2) -> f64) -> f64 {
    let grid = field.grid();
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for j in 0..field.ny {
        for i in 0..field.nx {
            let p = grid.node(i, j);
            if p.cmplt(min).any() || p.cmpgt(max).any() {
                continue;
            }
            let err = (field.at(i, j) - expected(p)).abs();
            assert!(err <= tol, "at {p}: got {} expected {} (error {err})", field.at(i, j), expected(p));
            worst = worst.max(err);
            checked += 1;
        }
    }
    assert!(checked > 50, "only {checked} nodes checked");
    worst
}

fn cutters() -> Vec<Cutter> {
    vec![Cutter::flat(6.0), Cutter::ball(6.0), Cutter::bull_nose(6.0, 1.0), Cutter::bull_nose(10.0, 2.5)]
}

#[test]
fn every_cutter_over_a_tilted_plane() {
    let (gx, gy) = (0.3, -0.45);
    let mesh = plane(40.0, 2.0, gx, gy);
    let n = DVec3::new(-gx, -gy, 1.0).normalize();
    let hn = n.truncate().length();
    for cutter in cutters() {
        let (r, a) = (cutter.radius(), cutter.corner());
        let field = exact(&mesh, &cutter, DVec2::splat(-30.0), DVec2::splat(30.0), 0.7);
        check(&field, DVec2::splat(-30.0), DVec2::splat(30.0), EXACT, |c| 2.0 + gx * c.x + gy * c.y + ((r - a) * hn + a) / n.z - a);
    }
}

#[test]
fn every_cutter_over_a_horizontal_plane_sits_on_it() {
    let mesh = plane(20.0, -3.0, 0.0, 0.0);
    for cutter in cutters() {
        let field = exact(&mesh, &cutter, DVec2::splat(-15.0), DVec2::splat(15.0), 0.5);
        check(&field, DVec2::splat(-15.0), DVec2::splat(15.0), EXACT, |_| -3.0);
    }
}

#[test]
fn flat_end_next_to_a_vertical_step() {
    let mesh = step(30.0, 5.0);
    let cutter = Cutter::flat(8.0);
    let field = exact(&mesh, &cutter, DVec2::splat(-20.0), DVec2::splat(20.0), 0.3);
    check(&field, DVec2::splat(-20.0), DVec2::splat(20.0), EXACT, |c| if c.x + 4.0 >= 0.0 { 5.0 } else { 0.0 });
}

#[test]
fn ball_and_bull_nose_next_to_a_vertical_step() {
    let mesh = step(30.0, 5.0);
    for cutter in [Cutter::ball(8.0), Cutter::bull_nose(8.0, 1.5)] {
        let p = cutter.profile();
        let field = exact(&mesh, &cutter, DVec2::splat(-20.0), DVec2::splat(20.0), 0.3);
        // Beside the wall the cutter hangs on the wall's top edge at horizontal distance -x.
        check(&field, DVec2::splat(-20.0), DVec2::splat(20.0), EXACT, |c| {
            if c.x >= 0.0 {
                5.0
            } else if -c.x <= p.radius {
                (5.0 - p.height(-c.x)).max(0.0)
            } else {
                0.0
            }
        });
    }
}

#[test]
fn ball_along_a_sharp_ridge() {
    let (h, s) = (10.0, 0.8);
    let mesh = roof(40.0, h, s);
    for cutter in [Cutter::ball(10.0), Cutter::ball(3.0)] {
        let r = cutter.radius();
        let n = DVec3::new(s, 0.0, 1.0).normalize(); // normal of the x < 0 side
        let field = exact(&mesh, &cutter, DVec2::splat(-25.0), DVec2::splat(25.0), 0.45);
        check(&field, DVec2::splat(-25.0), DVec2::splat(25.0), EXACT, |c| {
            let d = c.x.abs();
            // On a facet the ball touches at distance r·sin from the centre; past the ridge it
            // rides the edge.
            let facet = h - s * d + r / n.z - r;
            let edge = h + (r * r - d * d).max(0.0).sqrt() - r;
            if d >= r * n.x {
                facet
            } else {
                edge
            }
        });
    }
}

#[test]
fn bull_nose_and_flat_on_a_lone_vertex() {
    // A tiny tilted triangle far below a single raised vertex: the vertex decides nearby.
    let v = DVec3::new(0.0, 0.0, 4.0);
    let mesh = mesh(vec![[v, DVec3::new(30.0, -0.5, -50.0), DVec3::new(30.0, 0.5, -50.0)]]);
    for cutter in cutters() {
        let p = cutter.profile();
        let field = exact(&mesh, &cutter, DVec2::splat(-2.9), DVec2::new(-0.01, 2.9), 0.1);
        check(&field, DVec2::splat(-2.9), DVec2::new(-0.01, 2.9), EXACT, |c| {
            let r = c.length();
            if r <= p.radius {
                4.0 - p.height(r)
            } else {
                FLOOR
            }
        });
    }
}

#[test]
fn every_cutter_over_a_sphere_within_the_tessellation_sag() {
    let (rs, rim, spacing) = (30.0, 24.0, 0.4);
    let mesh = cap(rs, rim, spacing);
    // The mesh's vertices lie on the sphere and its facets inside it, no deeper than the sag
    // of the longest edge (a cell's diagonal, stretched by the slope at the rim).
    let chord = spacing * 2f64.sqrt() * rs / (rs * rs - rim * rim).sqrt();
    let depth = sag(rs, chord);
    for cutter in [Cutter::ball(10.0), Cutter::bull_nose(10.0, 2.0), Cutter::flat(6.0)] {
        let (r, a) = (cutter.radius(), cutter.corner());
        let field = exact(&mesh, &cutter, DVec2::splat(-12.0), DVec2::splat(12.0), 0.5);
        check(&field, DVec2::splat(-12.0), DVec2::splat(12.0), depth + EXACT, |c| over_sphere(rs, r, a, c));
        // And never above the true sphere's answer: the mesh is inside the sphere.
        let grid = field.grid();
        for j in 0..field.ny {
            for i in 0..field.nx {
                let c = grid.node(i, j);
                assert!(field.at(i, j) <= over_sphere(rs, r, a, c) + EXACT);
            }
        }
    }
}

/// The grid builder (which skips valley edges and prunes by bounds) against the brute-force
/// drop onto every facet, edge and vertex, on freeform parts with ridges and valleys.
#[test]
fn exact_grid_matches_the_pointwise_drop() {
    let demo = swarf::mesh::sample::demo_part();
    let die = swarf::mesh::sample::fuel_tank_die(60, 45);
    let bumpy = swarf::mesh::sample::height_field_solid(DVec2::splat(-10.0), DVec2::splat(10.0), 17, 13, -5.0, |x, y| (x * 1.3).sin() * (y * 0.9).cos() * 2.0 + (x * y * 0.05).sin());
    let cases: [(&Mesh, DVec2, DVec2, f64); 3] =
        [(&demo, DVec2::new(-48.0, -33.0), DVec2::new(48.0, 33.0), 1.3), (&die, DVec2::new(300.0, 200.0), DVec2::new(800.0, 600.0), 9.7), (&bumpy, DVec2::splat(-12.0), DVec2::splat(12.0), 0.37)];
    for (part, min, max, spacing) in cases {
        for cutter in [Cutter::bull_nose(6.0, 1.0), Cutter::ball(5.0), Cutter::flat(3.0), Cutter::bull_nose(20.0, 4.0), Cutter::v_bit(6.0, 90.0, 0.0), Cutter::v_bit(12.0, 60.0, 1.0)] {
            let field = exact(part, &cutter, min, max, spacing);
            check(&field, min, max, EXACT, |c| cl_exact_at(part, &cutter.profile(), c, &Tolerances::DEFAULT).unwrap_or(FLOOR).max(FLOOR));
        }
    }
}

/// Seed 001 §3.3: "for an upper hemisphere of radius 100 mm and a 10 mm ball offset, the
/// offset-facet method's largest error is under about 1/10 of the z-map inverse offset's at a
/// 1 mm grid".
#[test]
fn paper_claim_offset_facets_beat_inverse_offset_tenfold() {
    let (rs, rim) = (100.0, 80.0);
    let mesh = cap(rs, rim, 0.5);
    let cutter = Cutter::ball(10.0);
    let (min, max) = (DVec2::splat(-50.0), DVec2::splat(50.0)); // contacts well inside the rim
    let grid = Grid::covering(DVec2::splat(-rim), DVec2::splat(rim), 1.0);
    let tol = Tolerances::DEFAULT;
    let exact_field = cl_exact(&mesh, &cutter.profile(), grid, FLOOR, &tol, &mut Progress::none()).unwrap();
    let cc = cc_zmap(&mesh, grid, FLOOR, &tol);
    let inverse_field = cl_inverse_offset(&cc, &cutter.profile(), &mut Progress::none()).unwrap();
    let truth = |c: DVec2| over_sphere(rs, 5.0, 5.0, c);
    let exact_error = check(&exact_field, min, max, 1.0, truth);
    let inverse_error = check(&inverse_field, min, max, 1.0, truth);
    eprintln!("hemisphere R100, ball 10, grid 1: exact {exact_error:.6} mm, inverse offset {inverse_error:.6} mm");
    assert!(exact_error * 10.0 < inverse_error, "exact {exact_error} vs inverse {inverse_error}");
}

#[test]
fn inverse_offset_never_above_exact_and_converges_with_the_grid() {
    // The inverse offset sees the part only at the nodes, so it can only be lower.
    let mesh = cap(30.0, 24.0, 0.4);
    let cutter = Cutter::ball(6.0);
    let tol = Tolerances::DEFAULT;
    let mut previous = f64::INFINITY;
    for spacing in [1.0, 0.5, 0.25] {
        let grid = Grid::covering(DVec2::splat(-10.0), DVec2::splat(10.0), spacing);
        let e = cl_exact(&mesh, &cutter.profile(), grid, FLOOR, &tol, &mut Progress::none()).unwrap();
        let i = cl_inverse_offset(&cc_zmap(&mesh, grid, FLOOR, &tol), &cutter.profile(), &mut Progress::none()).unwrap();
        let worst = e.z.iter().zip(&i.z).map(|(e, i)| {
            assert!(i <= &(e + EXACT), "inverse {i} above exact {e}");
            e - i
        });
        let worst = worst.fold(0.0, f64::max);
        eprintln!("grid {spacing}: inverse offset up to {worst:.5} mm below exact");
        assert!(worst < previous);
        previous = worst;
    }
}

#[test]
fn cancel_stops_the_exact_builder() {
    let part = swarf::mesh::sample::demo_part();
    let mut calls = 0;
    let mut sink = |_: f64, _: &str| {
        calls += 1;
        calls < 2
    };
    let grid = Grid::covering(DVec2::splat(-50.0), DVec2::splat(50.0), 0.5);
    let result = cl_exact(&part, &Profile::new(3.0, 3.0), grid, FLOOR, &Tolerances::DEFAULT, &mut Progress::new(&mut sink));
    assert!(matches!(result, Err(swarf::Error::Cancelled)));
}

mod random_parts {
    use super::*;
    use proptest::prelude::*;
    use swarf::geom::DVec3;

    /// A rough closed height field: random heights, each quad split along a random diagonal.
    fn rough_part(heights: &[f64], diagonals: &[bool], n: usize, cell: f64) -> Mesh {
        let at = |i: usize, j: usize| DVec3::new(i as f64 * cell, j as f64 * cell, heights[j * (n + 1) + i]);
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if diagonals[j * n + i] {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 40, .. ProptestConfig::default() })]
        #[test]
        fn grid_builder_equals_the_brute_force_drop(
            heights in proptest::collection::vec(-3.0f64..3.0, 7 * 7),
            diagonals in proptest::collection::vec(any::<bool>(), 6 * 6),
            shape in 0usize..5,
            diameter in 0.8f64..9.0,
            corner_fraction in 0.05f64..0.95,
            spacing in 0.23f64..0.9,
        ) {
            let part = rough_part(&heights, &diagonals, 6, 1.5);
            let cutter = match shape {
                0 => Cutter::flat(diameter),
                1 => Cutter::ball(diameter),
                2 => Cutter::bull_nose(diameter, diameter / 2.0 * corner_fraction),
                // Cones: pointed, from 20° to 160° included, and with a flat tip.
                3 => Cutter::v_bit(diameter, 20.0 + 140.0 * corner_fraction, 0.0),
                _ => Cutter::v_bit(diameter, 30.0 + 120.0 * corner_fraction, diameter * corner_fraction * 0.6),
            };
            let (min, max) = (DVec2::splat(-2.0), DVec2::splat(11.0));
            let field = exact(&part, &cutter, min, max, spacing);
            let grid = field.grid();
            for j in 0..field.ny {
                for i in 0..field.nx {
                    let c = grid.node(i, j);
                    let brute = cl_exact_at(&part, &cutter.profile(), c, &Tolerances::DEFAULT).unwrap_or(FLOOR).max(FLOOR);
                    prop_assert!((field.at(i, j) - brute).abs() <= EXACT, "{} at {c}: grid {} brute force {brute}", cutter.describe(), field.at(i, j));
                }
            }
        }
    }
}

/// Issue 10's smallest case: a roof of four facets with a horizontal ridge along y = 0 at z = 1.
/// The two facets' normals have exactly opposite horizontal parts; a flat end or bull nose
/// standing over the ridge rests on it.
#[test]
fn flat_and_bull_nose_rest_on_a_horizontal_ridge() {
    let v = DVec3::new;
    let (l, h) = (20.0, 1.0);
    let roof = mesh(vec![
        [v(-l, -l, 0.0), v(l, -l, 0.0), v(l, 0.0, h)],
        [v(-l, -l, 0.0), v(l, 0.0, h), v(-l, 0.0, h)],
        [v(-l, 0.0, h), v(l, 0.0, h), v(l, l, 0.0)],
        [v(-l, 0.0, h), v(l, l, 0.0), v(-l, l, 0.0)],
    ]);
    for cutter in [Cutter::flat(6.0), Cutter::bull_nose(6.0, 1.0), Cutter::bull_nose(10.0, 2.5), Cutter::ball(6.0)] {
        let field = exact(&roof, &cutter, DVec2::splat(-15.0), DVec2::splat(15.0), 0.5);
        let node = field.grid().columns(10.0, 10.0).zip(field.grid().rows(0.0, 0.0)).map(|((i, _), (j, _))| field.at(i, j)).unwrap();
        let expected = cl_exact_at(&roof, &cutter.profile(), DVec2::new(10.0, 0.0), &Tolerances::DEFAULT).unwrap();
        assert!((node - expected).abs() < EXACT, "{}: {node} at (10, 0), expected {expected}", cutter.describe());
        if cutter.corner() == 0.0 {
            assert!((node - h).abs() < EXACT, "a flat end stands on the ridge: {node}");
        }
        check(&field, DVec2::splat(-15.0), DVec2::splat(15.0), EXACT, |c| cl_exact_at(&roof, &cutter.profile(), c, &Tolerances::DEFAULT).unwrap());
    }
}

/// Issue 10: the exact builder against the brute-force drop at every node, and ball <= bull nose
/// <= flat end at every node (for one diameter the ball's lower surface lies above the bull
/// nose's, which lies above the flat end's), on nearly flat faceted terrains with ridges and
/// valleys along, across and diagonal to the grid, for several corner radii.
#[test]
fn nearly_flat_ridges_and_valleys_every_node_exact_and_ordered() {
    let tol = Tolerances::DEFAULT;
    for (seed, lattice, shift) in [(1, 1.0, 0.0), (2, 1.5, 0.25), (3, 2.0, 0.1), (4, 1.0, 0.5)] {
        let part = faceted_terrain(seed, lattice, shift);
        let b = part.bounds();
        let (min, max) = (b.min.truncate() - 2.0, b.max.truncate() + 2.0);
        for d in [6.0, 10.0] {
            let family = [Cutter::ball(d), Cutter::bull_nose(d, d / 4.0), Cutter::bull_nose(d, d / 6.0), Cutter::bull_nose(d, 0.2), Cutter::flat(d)];
            let fields: Vec<HeightField> = family.iter().map(|c| exact(&part, c, min, max, 0.5)).collect();
            for (cutter, field) in family.iter().zip(&fields) {
                check(field, min, max, EXACT, |c| cl_exact_at(&part, &cutter.profile(), c, &tol).unwrap_or(FLOOR).max(FLOOR));
            }
            for pair in fields.windows(2) {
                for (k, (lower, upper)) in pair[0].z.iter().zip(&pair[1].z).enumerate() {
                    assert!(lower <= &(upper + EXACT), "seed {seed}, φ{d}: node {k}: {lower} above {upper} for a blunter cutter");
                }
            }
        }
    }
}

/// Issue 10: on every shared mesh, every node of the exact z-map against the brute-force drop,
/// and ball <= bull nose <= flat end at every node, for φ6 and φ10 with several corner radii
/// (grids of about 2,500 nodes over each part).
#[test]
fn every_shared_mesh_every_node_exact_and_ordered() {
    let Some(dir) = shared_data("meshes") else { return };
    let tol = Tolerances::DEFAULT;
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let mut meshes = 0;
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let Ok(part) = swarf::mesh::import::read_mesh_auto(&std::fs::read(&path).unwrap(), Some(&name), &tol) else { continue };
        meshes += 1;
        let started = std::time::Instant::now();
        let b = part.bounds();
        let (min, max) = (b.min.truncate() - 2.0, b.max.truncate() + 2.0);
        let size = max - min;
        let spacing = (size.x * size.y / 2500.0).sqrt();
        for d in [6.0, 10.0] {
            let family = [Cutter::ball(d), Cutter::bull_nose(d, d / 4.0), Cutter::bull_nose(d, d / 6.0), Cutter::flat(d)];
            let fields: Vec<HeightField> = family.iter().map(|c| exact(&part, c, min, max, spacing)).collect();
            for (cutter, field) in family.iter().zip(&fields) {
                // The brute force over every triangle; on the larger meshes over the triangles
                // within the cutter's reach (PointDrop, equal to the brute force in
                // tests/gouge_free.rs), which is the same drop without the far ones.
                if part.faces.len() <= 2000 {
                    check(field, min, max, EXACT, |c| cl_exact_at(&part, &cutter.profile(), c, &tol).unwrap_or(FLOOR).max(FLOOR));
                } else {
                    let drop = PointDrop::new(&part, &cutter.profile(), &tol);
                    check(field, min, max, EXACT, |c| drop.at(c, FLOOR));
                }
            }
            for pair in fields.windows(2) {
                for (k, (lower, upper)) in pair[0].z.iter().zip(&pair[1].z).enumerate() {
                    assert!(lower <= &(upper + EXACT), "{name}, φ{d}: node {k}: {lower} above {upper} for a blunter cutter");
                }
            }
        }
        eprintln!("{name}: {} triangles, {:.1} s", part.faces.len(), started.elapsed().as_secs_f64());
    }
    assert!(meshes >= 5, "only {meshes} shared meshes read");
}

/// Issue 39: a cone (a V-bit, pointed or with a flat tip) in the exact z-map, against closed
/// forms: on a plane flatter than its side it stands on its tip's rim, on a steeper one on its
/// rim; over a lone peak it stands as low as its side lets the peak in; beside a vertical step
/// its side meets the step's top edge.
#[test]
fn a_cone_over_planes_a_peak_and_a_step_stands_where_the_closed_forms_say() {
    let v = DVec3::new;
    for (angle, tip) in [(90.0f64, 0.0f64), (60.0, 0.0), (60.0, 1.0), (120.0, 0.4)] {
        let cutter = Cutter::v_bit(6.0, angle, tip);
        let (r, flat, taper) = (3.0, tip / 2.0, 1.0 / (angle / 2.0).to_radians().tan());
        // Planes rising along x at 10° and 70°.
        for slope in [10f64, 70.0] {
            let t = slope.to_radians().tan();
            let plane = mesh(vec![[v(-20.0, -20.0, -20.0 * t), v(20.0, -20.0, 20.0 * t), v(20.0, 20.0, 20.0 * t)], [v(-20.0, -20.0, -20.0 * t), v(20.0, 20.0, 20.0 * t), v(-20.0, 20.0, -20.0 * t)]]);
            let field = exact(&plane, &cutter, DVec2::splat(-10.0), DVec2::splat(10.0), 0.37);
            let contact = if t < taper { flat } else { r };
            check(&field, DVec2::splat(-10.0), DVec2::splat(10.0), EXACT, |c| (c.x + contact) * t - (contact - flat) * taper);
        }
        // A peak: a pyramid with 5° flanks, its apex at the origin, 1 mm high.
        let (s, h) = (20.0, 1.0);
        let peak = mesh(vec![
            [v(-s, -s, 0.0), v(s, -s, 0.0), v(0.0, 0.0, h)],
            [v(s, -s, 0.0), v(s, s, 0.0), v(0.0, 0.0, h)],
            [v(s, s, 0.0), v(-s, s, 0.0), v(0.0, 0.0, h)],
            [v(-s, s, 0.0), v(-s, -s, 0.0), v(0.0, 0.0, h)],
        ]);
        let field = exact(&peak, &cutter, DVec2::splat(-4.0), DVec2::splat(4.0), 0.29);
        // Within the tip's flat it stands on the apex; beyond, the apex enters its side (the
        // flanks are flatter than the side, so they never touch it first near the apex).
        let apex = |c: DVec2| {
            let d = c.length();
            if d <= r {
                h - if d <= flat { 0.0 } else { (d - flat) * taper }
            } else {
                f64::NEG_INFINITY
            }
        };
        let grid = field.grid();
        for j in 0..field.ny {
            for i in 0..field.nx {
                let c = grid.node(i, j);
                let brute = cl_exact_at(&peak, &cutter.profile(), c, &Tolerances::DEFAULT).unwrap();
                assert!((field.at(i, j) - brute).abs() < EXACT, "{} at {c}", cutter.describe());
                assert!(field.at(i, j) >= apex(c) - EXACT, "{} at {c}: {} under the apex's {}", cutter.describe(), field.at(i, j), apex(c));
                if c.length() <= flat {
                    assert!((field.at(i, j) - h).abs() < EXACT, "{} on the apex at {c}", cutter.describe());
                }
            }
        }
        // A vertical step 5 mm high at x = 0 (the floor at 0 for x < 0): beside it, within the
        // cone's radius, its side rests on the step's top edge.
        let step = mesh(vec![
            [v(-20.0, -20.0, 0.0), v(0.0, -20.0, 0.0), v(0.0, 20.0, 0.0)],
            [v(-20.0, -20.0, 0.0), v(0.0, 20.0, 0.0), v(-20.0, 20.0, 0.0)],
            [v(0.0, -20.0, 0.0), v(0.0, -20.0, 5.0), v(0.0, 20.0, 5.0)],
            [v(0.0, -20.0, 0.0), v(0.0, 20.0, 5.0), v(0.0, 20.0, 0.0)],
            [v(0.0, -20.0, 5.0), v(20.0, -20.0, 5.0), v(20.0, 20.0, 5.0)],
            [v(0.0, -20.0, 5.0), v(20.0, 20.0, 5.0), v(0.0, 20.0, 5.0)],
        ]);
        let field = exact(&step, &cutter, DVec2::new(-8.0, -3.0), DVec2::new(-0.01, 3.0), 0.23);
        check(&field, DVec2::new(-8.0, -3.0), DVec2::new(-0.01, 3.0), EXACT, |c| {
            let d = -c.x;
            if d <= flat {
                5.0
            } else if d <= r {
                (5.0 - (d - flat) * taper).max(0.0)
            } else {
                0.0
            }
        });
    }
}
