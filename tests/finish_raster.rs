//! Raster finishing: the path never goes below the CL surface plus allowance, follows it within
//! the chordal tolerance, stays in its boundary, and links without gouging.

mod common;

use proptest::prelude::*;
use swarf::cutter::Cutter;
use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::job::{self, Boundary, FinishRaster, Job, Operation, Tool};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;
use swarf::strategy::finish_raster::{raster_runs, Pattern, RasterPasses};
use swarf::strategy::region::Region;
use swarf::toolpath::Move;
use swarf::zmap::{cl_exact::cl_exact, cl_exact::cl_exact_at, surface::ClSurface, Grid};

fn demo_cl(grid: f64, cutter: &Cutter) -> ClSurface {
    let part = demo_part();
    let b = part.bounds();
    let g = Grid::covering(b.min.truncate() - 5.0, b.max.truncate() + 5.0, grid);
    ClSurface::new(cl_exact(&part, &cutter.profile(), g, b.min.z, &Tolerances::DEFAULT, &mut Progress::none()).unwrap(), Tolerances::DEFAULT.interpolation)
}

/// Largest depth by which the polyline goes below `cl + allowance`, checked at every breakpoint
/// of every segment (where the surface along it bends), so between checks both are linear.
fn worst_gouge(cl: &ClSurface, points: &[DVec3], allowance: f64) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    for w in points.windows(2) {
        for t in cl.breakpoints(w[0].truncate(), w[1].truncate()) {
            let p = w[0].lerp(w[1], t);
            worst = worst.max(cl.height(p.truncate()) + allowance - p.z);
        }
    }
    worst
}

fn passes(angle: f64, stepover: f64, allowance: f64) -> RasterPasses {
    RasterPasses { angle_deg: angle, stepover, pattern: Pattern::Zigzag, allowance, tolerance: 0.01 }
}

#[test]
fn runs_never_dip_below_the_cl_surface_and_stay_within_tolerance() {
    let cutter = Cutter::ball(6.0);
    let cl = demo_cl(0.5, &cutter);
    let region = Region::Rect { min: cl.field.origin, max: cl.field.max_extent() };
    for (angle, allowance) in [(0.0, 0.0), (90.0, 0.3), (33.0, 0.0), (-71.5, 0.5)] {
        let runs = raster_runs(&cl, &region, &passes(angle, 1.5, allowance));
        assert!(runs.len() > 20);
        for run in &runs {
            let gouge = worst_gouge(&cl, run, allowance);
            assert!(gouge <= 1e-9, "angle {angle}: {gouge} mm below the CL surface");
            // Reduced, but no point of the surface along the run more than the tolerance below.
            assert!(gouge >= -0.01 - 1e-9, "angle {angle}: path {gouge} mm above the surface everywhere");
        }
    }
}

#[test]
fn runs_cover_the_region_at_the_stepover() {
    let cutter = Cutter::ball(6.0);
    let cl = demo_cl(0.5, &cutter);
    let (min, max) = (cl.field.origin, cl.field.max_extent());
    let runs = raster_runs(&cl, &Region::Rect { min, max }, &passes(0.0, 2.0, 0.0));
    let mut ys: Vec<f64> = runs.iter().map(|r| r[0].y).collect();
    ys.dedup();
    assert_eq!(ys.first().copied(), Some(min.y));
    assert_eq!(ys.last().copied(), Some(max.y));
    assert!(ys.windows(2).all(|w| w[1] - w[0] <= 2.0 + 1e-9 && w[1] > w[0]));
    // Zigzag: consecutive passes run opposite ways.
    assert!(runs.windows(2).all(|w| (w[0][1].x - w[0][0].x).signum() != (w[1][1].x - w[1][0].x).signum()));
}

#[test]
fn one_way_passes_all_run_the_same_way_and_return_above_the_part() {
    let cutter = Cutter::ball(6.0);
    let job = Job {
        tools: vec![Tool { cutter: cutter.clone(), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { pattern: Pattern::OneWay, stepover: 3.0, grid: 0.5, angle: 90.0, ..FinishRaster::default() })],
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let moves = &out.paths[0].moves;
    // Between two rapids, the cutting moves of a pass advance in +Y only (angle 90°).
    let mut at = out.paths[0].start;
    let (mut passes, mut retracts) = (0, 0);
    for m in moves {
        match m {
            Move::Line { to, .. } if to.truncate() != at.truncate() => {
                assert!(to.y >= at.y - 1e-9, "a one-way pass went backwards: {at} -> {to}");
                passes += 1;
            }
            Move::Rapid { to } if to.z == out.clearance_z && at.z < out.clearance_z => retracts += 1,
            _ => {}
        }
        at = m.to();
    }
    assert!(passes > 500 && retracts >= 30, "{passes} cutting moves, {retracts} retracts");
}

#[test]
fn silhouette_boundary_keeps_the_centre_near_the_part() {
    let job = Job {
        tools: vec![Tool { cutter: Cutter::ball(6.0), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { boundary: Boundary::Silhouette, margin: Some(2.0), stepover: 2.0, grid: 0.5, ..FinishRaster::default() })],
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let part = out.part.bounds();
    for m in &out.paths[0].moves {
        if let Move::Line { to, .. } = m {
            assert!(to.x >= part.min.x - 2.0 - 0.5 && to.x <= part.max.x + 2.0 + 0.5, "{to}");
            assert!(to.y >= part.min.y - 2.0 - 0.5 && to.y <= part.max.y + 2.0 + 0.5, "{to}");
        }
    }
}

/// The silhouette grown by a margin is exactly the set of nodes within the margin of a covered
/// node: the same set as an inverse offset of the 0/1 coverage map with a flat cutter.
#[test]
fn silhouette_growth_is_the_disk_dilation() {
    use swarf::cutter::Profile;
    use swarf::zmap::{cc::cc_zmap, cl_inverse::cl_inverse_offset};
    let part = demo_part();
    let b = part.bounds();
    let grid = Grid::covering(b.min.truncate() - 8.0, b.max.truncate() + 8.0, 0.7);
    let cc = cc_zmap(&part, grid, b.min.z - 1.0, &Tolerances::DEFAULT);
    for margin in [0.0, 0.69, 0.7, 3.0, 5.3] {
        let Region::Mask(mask) = Region::silhouette(&cc, b.min.z - 1.0, margin) else { unreachable!() };
        let mut covered = cc.clone();
        covered.z.iter_mut().for_each(|z| *z = if *z > b.min.z - 1.0 { 1.0 } else { 0.0 });
        let reference = cl_inverse_offset(&covered, &Profile::new(margin, 0.0), &mut Progress::none()).unwrap();
        assert_eq!(mask.z, reference.z, "margin {margin}");
        assert!(mask.z.iter().sum::<f64>() > 100.0);
    }
}

/// The whole job, checked against the exact drop at every cutting point, for each cutter.
#[test]
fn job_paths_match_the_exact_cl_height_at_every_point() {
    for cutter in [Cutter::ball(6.0), Cutter::flat(4.0), Cutter::bull_nose(8.0, 2.0)] {
        let allowance = 0.2;
        let job = Job {
            tools: vec![Tool { cutter: cutter.clone(), ..Tool::default() }],
            operations: vec![Operation::FinishRaster(FinishRaster { stepover: 3.0, grid: 0.4, allowance, angle: 20.0, ..FinishRaster::default() })],
            ..Job::default()
        };
        let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        let path = &out.paths[0];
        let mut at = path.start;
        let mut checked = 0;
        for m in &path.moves {
            let to = m.to();
            if let Move::Line { .. } = m {
                let exact = cl_exact_at(&out.part, &cutter.profile(), to.truncate(), &Tolerances::DEFAULT).unwrap_or(f64::NEG_INFINITY);
                // On the nodes the path is exact; between them the surface is trusted to linear
                // interpolation only where it sags less than the tolerance (four times that at
                // a kink between nodes), or held higher.
                assert!(to.z >= exact + allowance - 4.0 * Tolerances::DEFAULT.interpolation, "{}: {to} is {} below the exact CL", cutter.describe(), exact + allowance - to.z);
                checked += 1;
            }
            at = to;
        }
        let _ = at;
        assert!(checked > 500);
    }
}

#[test]
fn links_stay_down_only_above_the_surface() {
    let cutter = Cutter::ball(6.0);
    let job = Job {
        tools: vec![Tool { cutter: cutter.clone(), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { stepover: 1.0, grid: 0.5, ..FinishRaster::default() })],
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let path = &out.paths[0];
    let b = out.stock;
    let grid = Grid::covering(b.min.truncate(), b.max.truncate(), 0.5);
    let cl = ClSurface::new(cl_exact(&out.part, &cutter.profile(), grid, b.min.z, &Tolerances::DEFAULT, &mut Progress::none()).unwrap(), Tolerances::DEFAULT.interpolation);
    let mut at = path.start;
    let (mut rapids, mut feeds) = (0, 0);
    for m in &path.moves {
        let to = m.to();
        match m {
            Move::Line { .. } => {
                feeds += 1;
                assert!(worst_gouge(&cl, &[at, to], 0.0) <= 1e-6, "feed from {at} to {to} gouges");
            }
            Move::Rapid { .. } => {
                rapids += 1;
                // Rapids are vertical, or horizontal at the clearance height.
                let vertical = at.truncate() == to.truncate() && (to.z >= at.z || to.z > cl.height(to.truncate()));
                assert!(vertical || (at.z == out.clearance_z && to.z == out.clearance_z), "rapid {at} -> {to}");
            }
            Move::Arc { .. } => unreachable!(),
        }
        at = to;
    }
    assert!(feeds > 1000 && rapids > 0);
    assert_eq!(at.z, out.clearance_z, "the path ends at the clearance height");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]
    #[test]
    fn any_angle_and_stepover_stays_above(angle in -180.0f64..180.0, stepover in 0.7f64..6.0, allowance in 0.0f64..1.0) {
        let cl = demo_cl(0.8, &Cutter::bull_nose(6.0, 1.0));
        let region = Region::Rect { min: cl.field.origin + DVec2::splat(3.0), max: cl.field.max_extent() - DVec2::splat(3.0) };
        for run in raster_runs(&cl, &region, &passes(angle, stepover, allowance)) {
            prop_assert!(worst_gouge(&cl, &run, allowance) <= 1e-9);
            prop_assert!(run.iter().all(|p| region.contains(p.truncate())));
        }
    }
}

/// The inverse-offset builder (seed 001 §3.1) through the whole job, with the stock boundary:
/// it sees the part only at the nodes, so its path may sit below the exact one — by little on
/// the surface, and by more where the tool rolls over a wall's top edge that lies between nodes
/// (there the edge can be missed by up to a node spacing horizontally).
#[test]
fn inverse_offset_job_runs_and_stays_near_the_exact_surface() {
    use swarf::zmap::ClBuilder;
    let cutter = Cutter::ball(6.0);
    let job = Job {
        tools: vec![Tool { cutter: cutter.clone(), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { builder: ClBuilder::InverseOffset, boundary: Boundary::Stock, stepover: 2.0, grid: 0.3, ..FinishRaster::default() })],
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let (part, spacing, radius) = (out.part.bounds(), 0.3, cutter.radius());
    let (mut checked, mut worst_inside, mut worst_edge) = (0, 0.0f64, 0.0f64);
    for m in &out.paths[0].moves {
        if let Move::Line { to, .. } = m {
            let exact = cl_exact_at(&out.part, &cutter.profile(), to.truncate(), &Tolerances::DEFAULT).unwrap_or(out.stock.min.z).max(out.stock.min.z);
            let below = exact - to.z;
            let inside = to.x.abs() <= part.max.x - radius - spacing && to.y.abs() <= part.max.y - radius - spacing;
            if inside {
                worst_inside = worst_inside.max(below);
            } else {
                worst_edge = worst_edge.max(below);
            }
            checked += 1;
        }
    }
    eprintln!("inverse offset below exact: {worst_inside:.4} mm on the surface, {worst_edge:.4} mm near the walls");
    assert!(checked > 1000);
    // On the surface: the ball's contact falls between nodes, a second-order error in the
    // spacing (seed 001 Fig. 4-b).
    assert!(worst_inside <= 0.1, "{worst_inside} mm below the exact CL on the surface");
    // At a wall whose top edge lies between nodes, the edge is seen up to one spacing s early,
    // and rolling over it the tip drops by up to sqrt(2 R s).
    assert!(worst_edge <= (2.0 * radius * spacing).sqrt(), "{worst_edge} mm below the exact CL near the walls");
}
