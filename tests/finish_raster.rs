//! Raster finishing: the path never goes below the CL surface plus allowance, follows it within
//! the chordal tolerance, stays in its boundary, and links without gouging.

mod common;

use proptest::prelude::*;
use swarf::cutter::Cutter;
use swarf::geom::{DVec2, DVec3, Tolerances};
use swarf::job::{self, Boundary, FinishRaster, Job, Operation, Tool};
use swarf::machining::raster::{raster_runs, Pattern, RasterPasses};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;
use swarf::toolpath::Move;
use swarf::zmap::region::Region;
use swarf::zmap::{cl_exact::cl_exact, drop::PointDrop, surface::ClSurface, Grid};

fn demo_cl(grid: f64, cutter: &Cutter) -> ClSurface {
    let part = demo_part();
    let b = part.bounds();
    let g = Grid::covering(b.min.truncate() - 5.0, b.max.truncate() + 5.0, grid);
    surface(&part, g, b.min.z, cutter)
}

fn surface(part: &swarf::mesh::Mesh, grid: Grid, floor: f64, cutter: &Cutter) -> ClSurface {
    let tol = Tolerances::DEFAULT;
    let field = cl_exact(part, &cutter.profile(), grid, floor, &tol, &mut Progress::none()).unwrap();
    ClSurface::new(field, PointDrop::new(part, &cutter.profile(), &tol), floor, true, tol.interpolation)
}

/// Largest depth by which the polyline goes below the exact `cl + allowance`, checked at 25
/// points a millimetre along every segment (and at every breakpoint of the grid).
fn worst_gouge(cl: &ClSurface, points: &[DVec3], allowance: f64) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    for w in points.windows(2) {
        let n = ((w[0].truncate().distance(w[1].truncate()) * 25.0).ceil() as usize).max(1);
        let dense = (0..=n).map(|k| k as f64 / n as f64);
        for t in dense.chain(cl.field.breakpoints(w[0].truncate(), w[1].truncate())) {
            let p = w[0].lerp(w[1], t);
            worst = worst.max(cl.height(p.truncate()) + allowance - p.z);
        }
    }
    worst
}

/// What the issue asks of every feed move: at or above the exact surface less this (mm).
const CHORDAL: f64 = 0.002;

fn passes(angle: f64, stepover: f64, allowance: f64) -> RasterPasses {
    RasterPasses { angle_deg: angle, stepover, pattern: Pattern::Zigzag, allowance, tolerance: 0.01, skip_floor: None }
}

#[test]
fn runs_never_dip_below_the_cl_surface_and_stay_within_tolerance() {
    let cutter = Cutter::ball(6.0);
    let cl = demo_cl(0.5, &cutter);
    let region = Region::Rect { min: cl.field.origin, max: cl.field.max_extent() };
    for (angle, allowance) in [(0.0, 0.0), (90.0, 0.3), (33.0, 0.0), (-71.5, 0.5)] {
        let runs = raster_runs(&cl, &region, &passes(angle, 1.5, allowance), &mut Progress::none()).unwrap();
        assert!(runs.len() > 20);
        for run in &runs {
            let gouge = worst_gouge(&cl, run, allowance);
            assert!(gouge <= CHORDAL, "angle {angle}: {gouge} mm below the CL surface");
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
    let runs = raster_runs(&cl, &Region::Rect { min, max }, &passes(0.0, 2.0, 0.0), &mut Progress::none()).unwrap();
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
    // Between two rapids, the cutting moves of a pass advance in +Y only (angle 90°), once the
    // entry (a helix or a ramp, ending where the rapid descent came down, the last time the
    // path is there) is done.
    let (mut passes, mut retracts) = (0, 0);
    let mut at = out.paths[0].start;
    let mut k = 0;
    while k < moves.len() {
        if let Move::Rapid { to } = moves[k] {
            // Up from a cut: a retract (to the clearance, or the short retract just above the
            // stock on the way).
            if to.truncate() == at.truncate() && to.z > at.z {
                retracts += 1;
            }
            at = to;
            k += 1;
            continue;
        }
        let end = (k..moves.len()).find(|&e| moves[e].is_rapid()).unwrap_or(moves.len());
        let p0 = at.truncate();
        let entered = (k..end).rev().find(|&e| moves[e].to().truncate() == p0).map_or(k, |e| e + 1);
        let mut from = if entered > k { moves[entered - 1].to() } else { at };
        for m in &moves[entered..end] {
            let to = m.to();
            if to.truncate() != from.truncate() {
                assert!(to.y >= from.y - 1e-9, "a one-way pass went backwards: {from} -> {to}");
                passes += 1;
            }
            from = to;
        }
        at = moves[end - 1].to();
        k = end;
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
        let judge = common::Judge { part: &out.part, profile: cutter.profile(), floor: out.stock.min.z };
        let deepest = judge.deepest(path.start, &path.moves, allowance, 20.0);
        assert!(deepest.depth <= CHORDAL, "{}: {:.4} mm below the exact CL at {}", cutter.describe(), deepest.depth, deepest.at);
        assert!(deepest.points > 5000);
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
    let cl = surface(&out.part, grid, b.min.z, &cutter);
    let mut at = path.start;
    let (mut rapids, mut feeds, mut across, mut lowest) = (0, 0, 0, f64::INFINITY);
    for m in &path.moves {
        let to = m.to();
        match m {
            Move::Line { .. } => {
                feeds += 1;
                assert!(worst_gouge(&cl, &[at, to], 0.0) <= CHORDAL, "feed from {at} to {to} gouges");
            }
            Move::Rapid { .. } => {
                rapids += 1;
                // Rapids are vertical, or across no lower than the rapid gap (1 mm) above the
                // surface all the way (the stock on the way was the box above the part).
                let vertical = at.truncate() == to.truncate() && (to.z >= at.z || to.z > cl.height(to.truncate()));
                assert!(vertical || worst_gouge(&cl, &[at, to], 1.0) <= 1e-9, "rapid {at} -> {to}");
                if !vertical {
                    across += 1;
                    lowest = lowest.min(at.z.min(to.z));
                }
            }
            Move::Arc { .. } => unreachable!(),
        }
        at = to;
    }
    assert!(feeds > 1000 && rapids > 0);
    // The stock's top is the part's top plus its margin: the short retract travels the gap
    // above it, below the clearance (5 mm above it).
    assert!(across > 0 && lowest < out.clearance_z - 3.0 && lowest >= b.max.z + 1.0 - 1e-9, "{across} rapids across, the lowest at {lowest}");
    assert_eq!(at.z, out.clearance_z, "the path ends at the clearance height");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]
    #[test]
    fn any_angle_and_stepover_stays_above(angle in -180.0f64..180.0, stepover in 0.7f64..6.0, allowance in 0.0f64..1.0) {
        let cl = demo_cl(0.8, &Cutter::bull_nose(6.0, 1.0));
        let region = Region::Rect { min: cl.field.origin + DVec2::splat(3.0), max: cl.field.max_extent() - DVec2::splat(3.0) };
        for run in raster_runs(&cl, &region, &passes(angle, stepover, allowance), &mut Progress::none()).unwrap() {
            prop_assert!(worst_gouge(&cl, &run, allowance) <= CHORDAL);
            prop_assert!(run.iter().all(|p| region.contains(p.truncate())));
        }
    }
}

/// The inverse-offset builder (seed 001 §3.1) through the whole job, with the stock boundary:
/// its z-map sees the part only at the nodes and sits below the exact one, but the path takes
/// its heights from the exact drop (`zmap/surface.rs`), so it is as gouge-free as the exact
/// builder's.
#[test]
fn inverse_offset_job_is_as_exact_as_the_exact_one() {
    use swarf::zmap::ClBuilder;
    let cutter = Cutter::ball(6.0);
    let job = Job {
        tools: vec![Tool { cutter: cutter.clone(), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { builder: ClBuilder::InverseOffset, boundary: Boundary::Stock, stepover: 2.0, grid: 0.3, ..FinishRaster::default() })],
        ..Job::default()
    };
    let out = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let judge = common::Judge { part: &out.part, profile: cutter.profile(), floor: out.stock.min.z };
    let deepest = judge.deepest(out.paths[0].start, &out.paths[0].moves, 0.0, 20.0);
    assert!(deepest.points > 10000);
    assert!(deepest.depth <= CHORDAL, "{:.4} mm below the exact CL at {}", deepest.depth, deepest.at);
}
