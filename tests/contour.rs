//! The region a cutter's centre may occupy at a level (`zmap/contour.rs`), against regions known
//! in closed form, and on spiky parts: no boundary point and no point inside stands above the
//! level on the exact surface (by more than `along`'s interpolation allowance, 0.001 mm).

mod common;

use common::{mesh, spiky_terrain, Lcg};
use swarf::cutter::Cutter;
use swarf::drawing::Shape;
use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::mesh::Mesh;
use swarf::progress::Progress;
use swarf::zmap::contour::LevelMap;
use swarf::zmap::{cl_exact::cl_exact, drop::PointDrop, surface::ClSurface, Grid};

fn surface(part: &Mesh, grid: Grid, floor: f64, cutter: &Cutter) -> ClSurface {
    let tol = Tolerances::DEFAULT;
    let field = cl_exact(part, &cutter.profile(), grid, floor, &tol, &mut Progress::none()).unwrap();
    ClSurface::new(field, PointDrop::new(part, &cutter.profile(), &tol), floor, true, tol.interpolation)
}

/// An axis-aligned box's faces (no bottom) between `lo` and `hi`.
fn boxed(lo: DVec3, hi: DVec3) -> Vec<[DVec3; 3]> {
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let (a, b, c, d) = (v(lo.x, lo.y, hi.z), v(hi.x, lo.y, hi.z), v(hi.x, hi.y, hi.z), v(lo.x, hi.y, hi.z));
    let (e, f, g, h) = (v(lo.x, lo.y, lo.z), v(hi.x, lo.y, lo.z), v(hi.x, hi.y, lo.z), v(lo.x, hi.y, lo.z));
    vec![[a, b, c], [a, c, d], [e, f, b], [e, b, a], [f, g, c], [f, c, b], [g, h, d], [g, d, c], [h, e, a], [h, a, d]]
}

/// A flat square plate at z = 0.
fn plate(half: f64) -> Vec<[DVec3; 3]> {
    let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    vec![[v(-half, -half), v(half, -half), v(half, half)], [v(-half, -half), v(half, half), v(-half, half)]]
}

/// Every point of the shape's boundary (every 0.02 mm) stands at or below the level.
fn boundary_clears(cl: &ClSurface, shape: &Shape, level: f64) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    let mut at = None;
    for s in shape.segments() {
        let n = (s.length() / 0.02).ceil().max(1.0) as usize;
        for k in 0..=n {
            let over = cl.height(s.point_at(k as f64 / n as f64)) - level;
            if over > worst {
                worst = over;
                at = Some((s.a, s.b, k as f64 / n as f64));
            }
        }
    }
    if worst > 0.001 + 1e-6 {
        eprintln!("worst {worst} on {at:?}");
    }
    worst
}

/// Distance from a point to the rectangle [-a, a]².
fn to_square(p: DVec2, a: f64) -> f64 {
    let d = DVec2::new((p.x.abs() - a).max(0.0), (p.y.abs() - a).max(0.0));
    d.length()
}

#[test]
fn a_flat_end_keeps_its_radius_from_a_box() {
    let mut tris = plate(30.0);
    tris.extend(boxed(DVec3::new(-10.0, -10.0, 0.0), DVec3::new(10.0, 10.0, 8.0)));
    let part = mesh(tris);
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-25.0), DVec2::splat(25.0), 0.25);
    let cl = surface(&part, grid, -1.0, &Cutter::flat(6.0));
    let map = LevelMap::of_part(&cl, &part, &tol);
    let region = map.region(&cl, 4.0, &|_, _| true, &tol);
    // The grid's border and the box grown by the radius: two loops, one a hole.
    assert_eq!(region.loops.len(), 2, "{:?}", region.loops.iter().map(|l| l.len()).collect::<Vec<_>>());
    let hole = region.loops.iter().find(|l| !l.is_ccw()).expect("a hole around the box");
    for v in &hole.vertices {
        let d = to_square(v.p, 10.0);
        assert!((3.0 - 1e-9..=3.0 + 0.25 * 1.5).contains(&d), "{} at {}", d, v.p);
    }
    // Its area: the box grown by the radius (a rounded square), within a grid cell along the rim.
    let grown = 20.0 * 20.0 + 4.0 * 20.0 * 3.0 + std::f64::consts::PI * 9.0;
    let rim = 4.0 * 20.0 + 2.0 * std::f64::consts::PI * 3.0;
    assert!((hole.area().abs() - grown) >= 0.0 && (hole.area().abs() - grown) <= rim * 0.25, "{} vs {grown}", hole.area().abs());
    assert!(boundary_clears(&cl, &region, 4.0) <= 0.001 + 1e-6);
}

#[test]
fn a_ball_around_a_hemisphere_stays_outside_the_closed_form_circle() {
    let (rs, r, level) = (10.0, 3.0, 4.0);
    let part = common::cap(rs, 9.9, 0.2);
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-16.0), DVec2::splat(16.0), 0.25);
    let cl = surface(&part, grid, -1.0, &Cutter::ball(2.0 * r));
    let map = LevelMap::of_part(&cl, &part, &tol);
    let region = map.region(&cl, level, &|_, _| true, &tol);
    let hole = region.loops.iter().find(|l| !l.is_ccw()).expect("a hole around the hemisphere");
    // The ball's centre on the sphere grown by r stands at level + r: at distance rho.
    let rho = ((rs + r).powi(2) - (level + r).powi(2)).sqrt();
    for v in &hole.vertices {
        let d = v.p.length();
        // The faceted cap lies inside the sphere: the hole may be smaller by the facets' sag,
        // and larger by up to a grid cell's diagonal.
        assert!(d >= rho - 0.05 && d <= rho + 0.36, "{d} vs {rho}");
    }
    assert!(boundary_clears(&cl, &region, level) <= 0.001 + 1e-6);
}

#[test]
fn a_pocket_with_an_island_gives_a_ring() {
    // A block 10 high with a 30 mm pocket down to 0 and a 6 mm pillar back up to 10 in it.
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut tris = Vec::new();
    // The top around the pocket, as four strips.
    for (lo, hi) in [((-25.0, -25.0), (25.0, -15.0)), ((-25.0, 15.0), (25.0, 25.0)), ((-25.0, -15.0), (-15.0, 15.0)), ((15.0, -15.0), (25.0, 15.0))] {
        let (a, b, c, d) = (v(lo.0, lo.1, 10.0), v(hi.0, lo.1, 10.0), v(hi.0, hi.1, 10.0), v(lo.0, hi.1, 10.0));
        tris.push([a, b, c]);
        tris.push([a, c, d]);
    }
    // The pocket's walls (facing in) and floor.
    let (p, q) = (-15.0, 15.0);
    for (a, b) in [((p, p), (q, p)), ((q, p), (q, q)), ((q, q), (p, q)), ((p, q), (p, p))] {
        tris.push([v(a.0, a.1, 0.0), v(a.0, a.1, 10.0), v(b.0, b.1, 10.0)]);
        tris.push([v(a.0, a.1, 0.0), v(b.0, b.1, 10.0), v(b.0, b.1, 0.0)]);
    }
    tris.push([v(p, p, 0.0), v(q, p, 0.0), v(q, q, 0.0)]);
    tris.push([v(p, p, 0.0), v(q, q, 0.0), v(p, q, 0.0)]);
    tris.extend(boxed(DVec3::new(-3.0, -3.0, 0.0), DVec3::new(3.0, 3.0, 10.0)));
    let part = mesh(tris);
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-22.0), DVec2::splat(22.0), 0.25);
    let cl = surface(&part, grid, -1.0, &Cutter::flat(6.0));
    let map = LevelMap::of_part(&cl, &part, &tol);
    let region = map.region(&cl, 5.0, &|_, _| true, &tol);
    assert_eq!(region.loops.len(), 2);
    let outer = region.loops.iter().find(|l| l.is_ccw()).unwrap();
    let hole = region.loops.iter().find(|l| !l.is_ccw()).unwrap();
    for v in &outer.vertices {
        assert!(v.p.x.abs().max(v.p.y.abs()) <= 12.0 + 1e-9 && v.p.x.abs().max(v.p.y.abs()) >= 12.0 - 0.36, "{}", v.p);
    }
    for v in &hole.vertices {
        let d = to_square(v.p, 3.0);
        assert!((3.0 - 1e-9..=3.0 + 0.36).contains(&d), "{d}");
    }
    let area = region.area();
    let expected = 24.0 * 24.0 - (36.0 + 4.0 * 6.0 * 3.0 + std::f64::consts::PI * 9.0);
    assert!(area <= expected + 1e-6 && area >= expected - (4.0 * 24.0 + 50.0) * 0.25, "{area} vs {expected}");
    assert!(boundary_clears(&cl, &region, 5.0) <= 0.001 + 1e-6);
}

#[test]
fn on_spiky_parts_nothing_of_the_region_stands_above_the_level() {
    let tol = Tolerances::DEFAULT;
    for (seed, cutter) in [(1, Cutter::flat(4.0)), (2, Cutter::ball(4.0)), (3, Cutter::bull_nose(4.0, 0.5)), (4, Cutter::ball(2.0))] {
        let part = spiky_terrain(seed, 8.0, 1.37, 3.0);
        let grid = Grid::covering(DVec2::splat(-10.0), DVec2::splat(10.0), 0.5);
        let cl = surface(&part, grid, -1.0, &cutter);
        let map = LevelMap::of_part(&cl, &part, &tol);
        let mut rng = Lcg(seed);
        for level in [0.5, 1.2, 2.0, 2.6] {
            let region = map.region(&cl, level, &|_, _| true, &tol);
            let worst = boundary_clears(&cl, &region, level);
            assert!(worst <= 0.001 + 1e-6, "{} seed {seed} level {level}: boundary {worst} above", cutter.describe());
            // Points inside: at most the cutter's rise half a cell from its axis above.
            let rise = cutter.profile().height(0.25 * std::f64::consts::SQRT_2) + 1e-6;
            let b = region.bounds();
            let mut inside = 0;
            for _ in 0..4000 {
                let p = DVec2::new(b.min.x + rng.next() * (b.max.x - b.min.x), b.min.y + rng.next() * (b.max.y - b.min.y));
                if region.contains(p) {
                    inside += 1;
                    let over = cl.height(p) - level;
                    assert!(over <= rise, "{} seed {seed} level {level}: {over} above at {p}", cutter.describe());
                }
            }
            assert!(inside > 0 || region.is_empty());
        }
    }
}

#[test]
fn a_pocket_corner_between_nodes_is_reached() {
    // A 30.2 mm square pocket 10 deep: a φ6 flat end's centre may go within ±12.1, a square
    // whose corners fall between the 0.25 mm grid's nodes (which would chamfer them).
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut tris = Vec::new();
    let (p, q) = (-15.1, 15.1);
    for (lo, hi) in [((-25.0, -25.0), (25.0, p)), ((-25.0, q), (25.0, 25.0)), ((-25.0, p), (p, q)), ((q, p), (25.0, q))] {
        let (a, b, c, d) = (v(lo.0, lo.1, 10.0), v(hi.0, lo.1, 10.0), v(hi.0, hi.1, 10.0), v(lo.0, hi.1, 10.0));
        tris.push([a, b, c]);
        tris.push([a, c, d]);
    }
    for (a, b) in [((p, p), (q, p)), ((q, p), (q, q)), ((q, q), (p, q)), ((p, q), (p, p))] {
        tris.push([v(a.0, a.1, 0.0), v(a.0, a.1, 10.0), v(b.0, b.1, 10.0)]);
        tris.push([v(a.0, a.1, 0.0), v(b.0, b.1, 10.0), v(b.0, b.1, 0.0)]);
    }
    tris.push([v(p, p, 0.0), v(q, p, 0.0), v(q, q, 0.0)]);
    tris.push([v(p, p, 0.0), v(q, q, 0.0), v(p, q, 0.0)]);
    let part = mesh(tris);
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-22.0), DVec2::splat(22.0), 0.25);
    let cl = surface(&part, grid, -1.0, &Cutter::flat(6.0));
    let region = LevelMap::of_part(&cl, &part, &tol).region(&cl, 5.0, &|_, _| true, &tol);
    assert_eq!(region.loops.len(), 1);
    // The sides stand the back-off in from ±12.1; the corners where those sides meet.
    let corner = 12.1 - swarf::zmap::contour::back_off(&cl, &tol);
    for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
        let c = DVec2::new(sx * corner, sy * corner);
        let nearest = region.loops[0].vertices.iter().map(|v| v.p.distance(c)).fold(f64::INFINITY, f64::min);
        assert!(nearest <= 0.002, "corner {c}: nearest boundary point {nearest:.4} mm away");
    }
    for v in &region.loops[0].vertices {
        assert!(v.p.x.abs().max(v.p.y.abs()) <= 12.1 + 1e-6, "{}", v.p);
    }
    assert!(boundary_clears(&cl, &region, 5.0) <= 0.001 + 1e-6);
    let area = region.area().abs();
    let side = 2.0 * corner;
    assert!(area >= side * side - 0.01 && area <= 24.2 * 24.2, "{area} against {}", side * side);
}

/// Cliffs: a flat end's and a bull nose's centre stands at the level up to the foot of a
/// wall's top edge and corners, and jumps there (round a corner, along a circle of the tool's
/// radius). A node of the grid just short of such a cliff made the boundary run along its foot
/// from the node itself (no room to back off), and a chord from it clipped the circle: a sliver
/// 0.03 mm long on pycam's textbox, found by gcheck. Boxes whose corner's circle passes a few
/// microns from a node, in many directions; every 0.002 mm along the boundary judged. (These
/// boxes came out clean before the fix too: the textbox's case needs its own facets; gcheck on
/// the real parts is the record, in BENCHMARKS.md.)
#[test]
fn the_boundary_keeps_off_cliffs_round_corners() {
    let tol = Tolerances::DEFAULT;
    let mut fails = Vec::new();
    for cutter in [Cutter::flat(6.0), Cutter::bull_nose(6.0, 1.0)] {
        for k in 0..16 {
            for gap in [0.001, 0.004, 0.009] {
                // The box's corner at the tool's radius plus `gap` from the node (0, 0), the box
                // stretching away from the node.
                let dir = DVec2::from_angle(0.1 + k as f64 * std::f64::consts::TAU / 16.0);
                let corner = dir * (3.0 + gap);
                let lo = DVec2::new(if dir.x > 0.0 { corner.x } else { corner.x - 6.0 }, if dir.y > 0.0 { corner.y } else { corner.y - 6.0 });
                let mut tris = plate(14.0);
                tris.extend(boxed(lo.extend(0.0), (lo + DVec2::splat(6.0)).extend(8.0)));
                let part = mesh(tris);
                let grid = Grid::covering(DVec2::splat(-12.0), DVec2::splat(12.0), 0.25);
                let cl = surface(&part, grid, -1.0, &cutter);
                let level = 3.0;
                let region = LevelMap::of_part(&cl, &part, &tol).region(&cl, level, &|_, _| true, &tol);
                let mut worst = f64::NEG_INFINITY;
                for s in region.segments() {
                    let n = (s.length() / 0.002).ceil().max(1.0) as usize;
                    for q in 0..=n {
                        worst = worst.max(cl.height(s.point_at(q as f64 / n as f64)) - level);
                    }
                }
                if worst > 0.001 + 1e-6 {
                    fails.push((cutter.corner_radius, k, gap, worst));
                }
            }
        }
    }
    assert!(fails.is_empty(), "the boundary stands above the level (corner radius, direction, gap, height): {fails:?}");
}

/// The level map bounds the surface along every grid edge from above (the widened cutter at the
/// edge's lower end), so an edge it does not look at exactly cannot hide a ridge: on spiky
/// terrain, for every cutter shape, plain and grown by a program's resolution (a grown ball is
/// a larger ball lifted), every edge's bound is at least the highest of its exact profile, and
/// most bounds are within a tenth of a millimetre of it (the bound is of use).
#[test]
fn the_level_maps_bounds_hold_every_edges_exact_profile() {
    let part = spiky_terrain(7, 8.0, 1.3, 5.0);
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-10.0), DVec2::splat(10.0), 0.25);
    for cutter in [Cutter::flat(6.0), Cutter::ball(6.0), Cutter::bull_nose(6.0, 1.0)] {
        for rho in [0.0, 0.01] {
            let drop = PointDrop::grown(&part, &cutter.profile(), rho, &tol);
            let field = drop.field(&part, grid, -5.0, &tol, &mut Progress::none()).unwrap();
            let cl = ClSurface::new(field, drop, -5.0, true, tol.interpolation);
            let map = LevelMap::of_part(&cl, &part, &tol);
            let (right, up) = map.bounds();
            let f = &cl.field;
            let node = |c: usize| f.origin + DVec2::new((c % f.nx) as f64, (c / f.nx) as f64) * f.spacing;
            let (mut edges, mut close) = (0, 0);
            for c in 0..f.nx * f.ny {
                for (other, bound) in [(c + 1, right[c]), (c + f.nx, up[c])] {
                    if (other == c + 1 && c % f.nx + 1 == f.nx) || other >= f.nx * f.ny {
                        assert_eq!(bound, f64::NEG_INFINITY);
                        continue;
                    }
                    let top = cl.along(node(c), node(other)).into_iter().fold(f64::NEG_INFINITY, |m, (_, z)| m.max(z)) + 2.0 * tol.interpolation;
                    assert!(bound >= top, "{cutter:?} ρ {rho}: the bound {bound} under the exact {top} from {} to {}", node(c), node(other));
                    edges += 1;
                    close += (bound - top <= 0.1) as usize;
                }
            }
            assert!(close * 10 >= edges * 7, "{cutter:?} ρ {rho}: only {close} of {edges} bounds within 0.1 mm");
        }
    }
}

/// A floor's node bounds (the widened cutter's heights at the nodes) decide a move only where
/// it clears the exact surface all along: on spiky terrain, for every cutter shape, plain and
/// grown, moves at heights about the surface's highest along them, each judged by the exact
/// drop and the region at 400 points wherever the bounds call it clear (within a rectangle and
/// within the part's silhouette); and the bounds decide many of those a few tenths above
/// (they spare the exact test there).
#[test]
fn a_floors_node_bounds_clear_only_moves_the_exact_surface_clears() {
    use swarf::toolpath::link::Floor;
    use swarf::zmap::region::Region;
    let part = spiky_terrain(11, 8.0, 1.3, 5.0);
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-10.0), DVec2::splat(10.0), 0.25);
    let region = Region::Rect { min: DVec2::splat(-10.0), max: DVec2::splat(10.0) };
    let mut rng = Lcg(5);
    for cutter in [Cutter::flat(6.0), Cutter::ball(6.0), Cutter::bull_nose(6.0, 1.0)] {
        for rho in [0.0, 0.01] {
            let drop = PointDrop::grown(&part, &cutter.profile(), rho, &tol);
            let field = drop.field(&part, grid, -5.0, &tol, &mut Progress::none()).unwrap();
            let wide = drop.field_by(&drop.widened(&part, grid.spacing, &tol), grid, -5.0, &mut Progress::none()).unwrap().z;
            let wide = swarf::zmap::bounds::NodeBounds::whole(grid.nx, grid.ny, wide).unwrap();
            let cl = ClSurface::new(field, drop.clone(), -5.0, true, tol.interpolation);
            let allowance = 0.3;
            // Within the stock's rectangle, and within the part's silhouette on the same grid
            // (where a point belongs to its nearest node's side).
            let silhouette = Region::silhouette(&cl.field, 0.5, 1.0);
            let (mut high, mut decided) = (0, 0);
            for n in 0..600 {
                let region = if n % 3 == 2 { &silhouette } else { &region };
                let floor = Floor { cl: &cl, allowance, region, bounds: Some(&wide) };
                let a = DVec2::new(16.0 * rng.next() - 8.0, 16.0 * rng.next() - 8.0);
                let b = (a + DVec2::from_angle(std::f64::consts::TAU * rng.next()) * (0.1 + 3.9 * rng.next())).clamp(DVec2::splat(-9.0), DVec2::splat(9.0));
                let exact: Vec<f64> = (0..=400).map(|k| drop.at(a.lerp(b, k as f64 / 400.0), -5.0)).collect();
                let top = exact.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let rise = 1.5 * rng.next() - 0.5;
                let (za, zb) = (top + allowance + rise, top + allowance + rise + 0.3 * rng.next());
                if floor.clears_by_bounds(a.extend(za), b.extend(zb), tol.height) {
                    decided += (rise > 0.3) as usize;
                    for (k, &z) in exact.iter().enumerate() {
                        let t = k as f64 / 400.0;
                        assert!(region.contains(a.lerp(b, t)), "{cutter:?} ρ {rho}: {a} to {b} cleared by the bounds, yet out of the region at t {t}");
                        assert!(
                            za + (zb - za) * t + tol.height >= z + allowance - 1e-9,
                            "{cutter:?} ρ {rho}: {a} to {b} cleared by the bounds, yet {} under the surface at t {t}",
                            z + allowance - za - (zb - za) * t
                        );
                    }
                }
                high += (rise > 0.3) as usize;
            }
            assert!(decided * 2 >= high, "{cutter:?} ρ {rho}: the bounds decided only {decided} of {high} moves 0.3 mm or more above the surface");
        }
    }
}

/// Where a keep mask ends a region (no material within reach there, another tool's octants),
/// its corner is no corner of the part's: it stays chamfered, never put back towards the
/// refused node. Put back, a ring there took a φ3 beside material in a crevice that no level
/// above it had come as near to (ocl_wheel_in_box, after a φ20: its shank 10.5 mm deep in it).
#[test]
fn a_region_is_never_squared_off_past_a_node_its_keep_mask_refuses() {
    let part = mesh(plate(20.0));
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-10.0), DVec2::splat(10.0), 0.5);
    let cl = surface(&part, grid, -1.0, &Cutter::flat(3.0));
    let map = LevelMap::of_part(&cl, &part, &tol);
    // Nodes up to 3 mm on either axis kept: the region's corner lies by (3, 3).
    let (origin, spacing) = (cl.field.origin, cl.field.spacing);
    let node = move |i: usize, j: usize| origin + DVec2::new(i as f64, j as f64) * spacing;
    let keep = move |i: usize, j: usize| {
        let p = node(i, j);
        p.x <= 3.0 + 1e-9 && p.y <= 3.0 + 1e-9
    };
    let region = map.region(&cl, 1.0, &keep, &tol);
    assert_eq!(region.loops.len(), 1);
    // The refused corner node (3.5, 3.5) and the cell towards it stay out; the chamfer runs
    // from next to (3.5, 3) to next to (3, 3.5).
    for p in [DVec2::new(3.4, 3.4), DVec2::new(3.3, 3.3)] {
        assert!(
            !region.contains(p),
            "{p} is in the region, past the kept nodes' corner: {:?}",
            region.loops[0].vertices.iter().filter(|v| v.p.x > 2.0 && v.p.y > 2.0).map(|v| v.p).collect::<Vec<_>>()
        );
    }
    assert!(region.contains(DVec2::new(3.1, 3.1)) && region.contains(DVec2::new(3.4, 2.9)));
    for v in &region.loops[0].vertices {
        assert!(v.p.x + v.p.y <= 7.0 + 1e-9, "{} lies past the chamfer", v.p);
    }
}

/// The points of a region's loops, in order.
fn points(shape: &Shape) -> Vec<Vec<DVec2>> {
    shape.loops.iter().map(|l| l.vertices.iter().map(|v| v.p).collect()).collect()
}

#[test]
fn a_crossing_kept_from_one_level_gives_every_other_level_the_region_a_fresh_map_gives() {
    // Walls off the grid's lines (a wall's foot is the same crossing at every level below its
    // top) and a terrain (every level its own crossings), on a flat end and a ball.
    let mut walls = plate(30.0);
    walls.extend(boxed(DVec3::new(-10.13, -7.71, 0.0), DVec3::new(9.37, 11.09, 8.0)));
    walls.extend(boxed(DVec3::new(-20.3, -20.6, 0.0), DVec3::new(-14.9, 14.2, 3.3)));
    let tol = Tolerances::DEFAULT;
    let grid = Grid::covering(DVec2::splat(-25.0), DVec2::splat(25.0), 0.5);
    let levels = [7.5, 0.5, 5.25, 2.0, 3.1, 6.0, 1.2];
    for (part, cutter) in [(mesh(walls), Cutter::flat(6.0)), (spiky_terrain(7, 20.0, 4.0, 6.0), Cutter::ball(6.0))] {
        let cl = surface(&part, grid, -1.0, &cutter);
        let kept = LevelMap::of_part(&cl, &part, &tol);
        let mut taken = Vec::new();
        for &level in &levels {
            let fresh = LevelMap::of_part(&cl, &part, &tol);
            let expected = fresh.region(&cl, level, &|_, _| true, &tol);
            let region = kept.region(&cl, level, &|_, _| true, &tol);
            assert_eq!(points(&region), points(&expected), "level {level}");
            assert!(!expected.loops.is_empty(), "level {level} has a region");
            taken.push((kept.profiles_taken(), fresh.profiles_taken()));
        }
        if cutter.profile().is_ball() {
            continue;
        }
        // Below the walls' tops the crossings at their feet were all taken by the first level
        // under them: the levels after it take only the few a level's own crossings add.
        let fresh_total: usize = taken.iter().map(|t| t.1).sum();
        let kept_total = taken.last().unwrap().0;
        assert!(kept_total * 3 < fresh_total, "the kept map took {kept_total} profiles, fresh maps {fresh_total}");
    }
}
