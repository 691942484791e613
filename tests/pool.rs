//! A job made in pieces, as the page's pool of workers makes it (issue 15): bands of the exact
//! CL surfaces and ranges of raster passes made by one prepared copy of the job and kept by
//! another give the same program, byte for byte, as the job run whole.

use swarf::job::{self, Job};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;

/// The demo job (roughing, raster and waterline finishing), lighter.
fn job() -> Job {
    let mut job = Job::demo();
    job.simulation.verify = false;
    job
}

fn gcode_whole(job: &Job) -> String {
    job::run(job, demo_part(), &mut Progress::none()).unwrap().gcode
}

#[test]
fn a_job_made_by_a_pool_writes_the_same_program_as_one_made_whole() {
    let job = job();
    let whole = gcode_whole(&job);

    let mut helper = job::prepare(&job, demo_part()).unwrap();
    let mut planner = job::prepare(&job, demo_part()).unwrap();
    let surfaces = planner.surfaces().unwrap();
    // The roughing's grown flat end and the finishing ball (raster and waterline share it).
    assert_eq!(surfaces.len(), 2, "{surfaces:?}");
    assert_eq!(helper.surfaces().unwrap(), surfaces);
    for s in &surfaces {
        // Uneven bands, one of them empty, made by the helper.
        let ny = s.grid.ny;
        let cuts = [0, 7, 7, ny / 2, ny];
        let z: Vec<f64> = cuts.windows(2).flat_map(|w| helper.surface_rows(*s, w[0]..w[1], &mut Progress::none()).unwrap()).collect();
        planner.keep_surface(*s, z).unwrap();
    }
    let rasters = planner.rasters(&surfaces).unwrap();
    assert_eq!(rasters.len(), 1);
    let work = rasters[0];
    assert_eq!(work.surface, Some(1));
    assert!(work.passes > 100, "{work:?}");
    for first in (0..work.passes).step_by(37) {
        let passes = helper.raster_passes(work.operation, first..first + 37).unwrap();
        planner.keep_passes(work.operation, first, passes).unwrap();
    }
    // The level maps of the roughing's surface and the waterline's (the finishing ball's).
    // The raster's node bounds come with the waterline's level map (the same surface).
    let maps = planner.level_maps(&surfaces).unwrap();
    assert_eq!(maps, vec![0, 1]);
    for &k in &maps {
        let s = surfaces[k];
        let (mut right, mut up, mut wide) = (Vec::new(), Vec::new(), Vec::new());
        for w in [0, 5, s.grid.ny / 3, s.grid.ny].windows(2) {
            let (r, u, h) = helper.level_rows(s, w[0]..w[1]).unwrap();
            right.extend(r);
            up.extend(u);
            wide.extend(h);
        }
        planner.keep_level_map(s, right, up, wide).unwrap();
    }
    assert_eq!(planner.run(&mut Progress::none()).unwrap().gcode, whole);
}

#[test]
fn wrong_pieces_are_refused_and_missing_passes_are_made_by_the_planner() {
    let job = job();
    let mut planner = job::prepare(&job, demo_part()).unwrap();
    let surfaces = planner.surfaces().unwrap();
    let s = surfaces[0];
    let err = planner.keep_surface(s, vec![0.0; 3]).unwrap_err().to_string();
    assert!(err.contains("was given 3 heights"), "{err}");
    let work = planner.rasters(&surfaces).unwrap()[0];
    let err = planner.keep_passes(work.operation, work.passes, vec![Vec::new()]).unwrap_err().to_string();
    assert!(err.contains("given of an operation with"), "{err}");
    assert!(planner.keep_passes(0, 0, Vec::new()).is_err(), "operation 0 roughs");
    let err = planner.keep_level_map(s, vec![0.0; 2], vec![0.0; 2], Vec::new()).unwrap_err().to_string();
    assert!(err.contains("wrong number of heights"), "{err}");
    let n = s.grid.nx * s.grid.ny;
    let err = planner.keep_level_map(s, vec![0.0; n], vec![0.0; n], vec![0.0; 3]).unwrap_err().to_string();
    assert!(err.contains("node bounds") && err.contains("wrong number of heights"), "{err}");
    assert!(planner.keep_node_bounds(s, vec![0.0; n + 1]).is_err());
    // Only some passes given: the operation makes them all itself.
    let some = planner.raster_passes(work.operation, 0..10).unwrap();
    assert_eq!(some.len(), 10);
    planner.keep_passes(work.operation, 0, some).unwrap();
    assert_eq!(planner.run(&mut Progress::none()).unwrap().gcode, gcode_whole(&job));
}

#[test]
fn the_planner_cuts_on_the_surfaces_and_passes_it_was_given() {
    let mut job = job();
    job.operations.retain(|o| matches!(o, swarf::operations::Operation::FinishRaster(_)));
    let whole = gcode_whole(&job);
    let prepared = || job::prepare(&job, demo_part()).unwrap();
    // A kept surface is what the operation cuts on: the context's cache finds it.
    let mut planner = prepared();
    let s = planner.surfaces().unwrap()[0];
    let z = planner.surface_rows(s, 0..s.grid.ny, &mut Progress::none()).unwrap();
    planner.keep_surface(s, z).unwrap();
    let out = planner.run(&mut Progress::none()).unwrap();
    assert_eq!((out.cache.hits, out.cache.misses), (1, 0));
    assert_eq!(out.gcode, whole);
    // Passes that cut nothing: no raster moves.
    let mut planner = prepared();
    let work = planner.rasters(&planner.surfaces().unwrap()).unwrap()[0];
    planner.keep_passes(work.operation, 0, vec![Vec::new(); work.passes]).unwrap();
    let err = planner.run(&mut Progress::none()).unwrap_err().to_string();
    assert!(err.contains("no cutting moves"), "{err}");
    // The node bounds its links and entries take, given from bands (as a pool gives those of
    // a level map's surface): the same program as those it makes itself as it needs them;
    // bounds below everything (every move clears by them): another.
    let mut planner = prepared();
    let wide: Vec<f64> = (0..s.grid.ny).step_by(9).flat_map(|j| planner.level_rows(s, j..(j + 9).min(s.grid.ny)).unwrap().2).collect();
    planner.keep_node_bounds(s, wide).unwrap();
    assert_eq!(planner.run(&mut Progress::none()).unwrap().gcode, whole);
    let mut planner = prepared();
    planner.keep_node_bounds(s, vec![f64::NEG_INFINITY; s.grid.nx * s.grid.ny]).unwrap();
    assert_ne!(planner.run(&mut Progress::none()).unwrap().gcode, whole);
}

#[test]
fn the_planner_contours_on_the_level_maps_it_was_given() {
    let mut job = job();
    job.operations.retain(|o| matches!(o, swarf::operations::Operation::FinishWaterline(_)));
    let mut planner = job::prepare(&job, demo_part()).unwrap();
    let surfaces = planner.surfaces().unwrap();
    let s = surfaces[planner.level_maps(&surfaces).unwrap()[0]];
    // The map from bands, as a pool makes it: the same program.
    let (mut right, mut up) = (Vec::new(), Vec::new());
    for j in (0..s.grid.ny).step_by(7) {
        let (r, u, _) = planner.level_rows(s, j..j + 7).unwrap();
        right.extend(r);
        up.extend(u);
    }
    planner.keep_level_map(s, right, up, Vec::new()).unwrap();
    assert_eq!(planner.run(&mut Progress::none()).unwrap().gcode, gcode_whole(&job));
    // Bounds that no edge rises to: no ridge between nodes is looked for, so the contours are
    // not those of the part's own map.
    let mut planner = job::prepare(&job, demo_part()).unwrap();
    let n = s.grid.nx * s.grid.ny;
    planner.keep_level_map(s, vec![f64::NEG_INFINITY; n], vec![f64::NEG_INFINITY; n], Vec::new()).unwrap();
    let out = planner.run(&mut Progress::none()).map(|o| o.gcode).unwrap_or_default();
    assert_ne!(out, gcode_whole(&job));
}

/// Each operation's moves cut the in-process stock in groups of bands elsewhere, as the page's
/// pool cuts them: the moves and the bands written as flat numbers and read back, each group
/// cut on its own, the bands and their cuts taken back by the planner. The program, the stock
/// and every figure of the simulation are those of the job run whole.
#[test]
fn the_in_process_stock_cut_in_groups_of_bands_is_the_stock_cut_whole() {
    use swarf::sim::program::{decode, encode};
    use swarf::sim::verify::{cut_bands, BandCut};
    use swarf::sim::DexelStock;
    let job = Job::demo();
    let whole = job::run(&job, demo_part(), &mut Progress::none()).unwrap();
    let mut running = job::prepare(&job, demo_part()).unwrap().start();
    let (mut operations, mut groups_cut) = (0, 0);
    while running.plan_next(&mut Progress::none()).unwrap() {
        operations += 1;
        if running.pending().is_empty() {
            continue;
        }
        let moves = decode(&encode(running.pending()), &job.tools).unwrap();
        assert_eq!(moves.len(), running.pending().len());
        let bands = running.take_bands();
        assert!(bands.len() > 20, "{} bands", bands.len());
        // Uneven groups, one of a single band, each through its flat form and back.
        let (mut back, mut cuts) = (Vec::new(), Vec::new());
        for group in [&bands[..1], &bands[1..20], &bands[20..]] {
            let mut mine = DexelStock::all_from_flat(&DexelStock::all_to_flat(group)).unwrap();
            let cut = cut_bands(&mut mine, &moves, &job.tolerances, &mut Progress::none(), 1.0).unwrap();
            let flat: Vec<f64> = cut.iter().flat_map(BandCut::to_flat).collect();
            cuts.extend(BandCut::all_from_flat(&flat).unwrap());
            back.extend(mine);
            groups_cut += 1;
        }
        // Bands missing: refused, and nothing is lost.
        assert!(running.absorb(back[1..].to_vec(), &cuts[1..]).is_err());
        running.absorb(back, &cuts).unwrap();
    }
    assert_eq!((operations, groups_cut), (3, 9));
    let out = running.finish(&mut Progress::none()).unwrap();
    assert_eq!(out.gcode, whole.gcode);
    let (a, b) = (out.verification.unwrap(), whole.verification.unwrap());
    assert_eq!(a.stock.heights().z, b.stock.heights().z);
    assert_eq!(a.volumes, b.volumes);
    assert_eq!(format!("{:?}", a.report), format!("{:?}", b.report));
    assert!(a.report.removed > 1000.0);
}

/// The regions of the roughing's levels made by another copy of the job, as the page's pool
/// makes them just before the operation plans, are what it plans with: the same program as
/// the job run whole; regions given for other nodes are not taken, and regions given for the
/// very levels are (an empty one leaves its level out).
#[test]
fn the_roughing_plans_on_the_regions_a_pool_made_for_its_levels() {
    let job = job();
    let whole = gcode_whole(&job);
    let mut helper = job::prepare(&job, demo_part()).unwrap();
    let mut running = job::prepare(&job, demo_part()).unwrap().start();
    let work = running.region_work(&mut Progress::none()).unwrap().expect("the roughing has levels");
    assert!(work.levels.len() > 5, "{} levels", work.levels.len());
    let regions = helper.level_regions(work.request, &work.levels).unwrap();
    assert!(regions.iter().all(|r| !r.loops.is_empty()));
    // Through the flat form the page's workers pass them in.
    let mut flat = Vec::new();
    regions.iter().for_each(|r| r.to_flat(&mut flat));
    let regions = swarf::drawing::Shape::all_from_flat(&flat).unwrap();
    assert!(running.keep_regions(&work, regions[1..].to_vec()).is_err());
    running.keep_regions(&work, regions.clone()).unwrap();
    while running.plan_next(&mut Progress::none()).unwrap() {
        running.simulate(&mut Progress::none()).unwrap();
    }
    assert_eq!(running.finish(&mut Progress::none()).unwrap().gcode, whole);

    let plan = |given: Vec<swarf::drawing::Shape>, work: &swarf::machining::levels::RegionWork| {
        let mut running = job::prepare(&job, demo_part()).unwrap().start();
        running.keep_regions(work, given).unwrap();
        while running.plan_next(&mut Progress::none()).unwrap() {
            running.simulate(&mut Progress::none()).unwrap();
        }
        running.finish(&mut Progress::none()).unwrap().gcode
    };
    let mut empty = regions.clone();
    empty[0] = swarf::drawing::Shape::default();
    // For other nodes (one more kept): not taken.
    let mut other = work.clone();
    other.levels[0].1[0] ^= 1;
    assert_eq!(plan(empty.clone(), &other), whole);
    // For the very level: taken, and the top level is left out.
    assert_ne!(plan(empty, &work), whole);
}

/// The waterline's levels are known before it contours any (by the step-down, or by the
/// scallop from the steep cells across each), so a pool makes their regions as it makes the
/// roughing's: the job planned on them writes the program the job run whole writes, and a
/// region given for one of its levels is the one taken.
#[test]
fn the_waterline_plans_on_the_regions_a_pool_made_for_its_levels() {
    let job = job();
    let whole = gcode_whole(&job);
    let mut helper = job::prepare(&job, demo_part()).unwrap();
    let mut plan = |emptied: Option<usize>| {
        let mut running = job::prepare(&job, demo_part()).unwrap().start();
        let mut works = Vec::new();
        loop {
            if let Some(work) = running.region_work(&mut Progress::none()).unwrap() {
                let mut regions = helper.level_regions(work.request, &work.levels).unwrap();
                if emptied == Some(works.len()) {
                    let middle = regions.len() / 2;
                    regions[middle] = swarf::drawing::Shape::default();
                }
                running.keep_regions(&work, regions).unwrap();
                works.push(work.levels.len());
            }
            if !running.plan_next(&mut Progress::none()).unwrap() {
                break;
            }
            running.simulate(&mut Progress::none()).unwrap();
        }
        (running.finish(&mut Progress::none()).unwrap().gcode, works)
    };
    let (gcode, works) = plan(None);
    // The roughing's levels, then the waterline's.
    assert_eq!(works.len(), 2, "{works:?}");
    assert!(works[1] > 20, "{works:?}");
    assert_eq!(gcode, whole);
    // A level of the waterline's given empty halfway down the part: taken, and left out.
    assert_ne!(plan(Some(1)).0, whole);
}

/// The page's pool, natively: two workers (a planner and a helper) exchange the job's pieces in
/// the flat form they travel in between the browser's workers (`job::wire`), as `www/swarf.js`
/// shares them out, and the program is the job's run whole, byte for byte.
#[test]
fn the_pools_wire_format_gives_the_program_made_whole() {
    use swarf::job::wire::PoolWorker;
    let job = job();
    let whole = gcode_whole(&job);
    let mut planner = PoolWorker::prepare(job.clone(), demo_part().into()).unwrap();
    let mut helper = PoolWorker::prepare(job.clone(), demo_part().into()).unwrap();
    let needs = planner.needs().unwrap();
    assert_eq!(needs, helper.needs().unwrap());
    // Bands of rows of every surface, made by the helper and joined by the planner.
    for (k, s) in needs.surfaces.iter().enumerate() {
        let z: Vec<f64> = [0, s.ny / 3, s.ny].windows(2).flat_map(|w| helper.surface_rows(k, w[0], w[1]).unwrap()).collect();
        assert_eq!(z.len(), s.nx * s.ny);
        planner.keep_surface(k, z).unwrap();
    }
    // Raster passes in ranges.
    for r in &needs.rasters {
        for first in (0..r.passes).step_by(50) {
            let count = 50.min(r.passes - first);
            let flat = helper.raster_passes(r.operation, first, first + count).unwrap();
            planner.keep_passes(r.operation, first, count, &flat).unwrap();
        }
    }
    // Level maps in bands.
    for &k in &needs.level_maps {
        let s = needs.surfaces[k];
        let (mut right, mut up, mut wide) = (Vec::new(), Vec::new(), Vec::new());
        for w in [0, s.ny / 2, s.ny].windows(2) {
            let rows = helper.level_rows(k, w[0], w[1]).unwrap();
            let n = (w[1] - w[0]) * s.nx;
            right.extend_from_slice(&rows[..n]);
            up.extend_from_slice(&rows[n..2 * n]);
            wide.extend_from_slice(&rows[2 * n..]);
        }
        planner.keep_level_map(k, right.clone(), up.clone(), wide).unwrap();
        helper.keep_level_map(k, right, up, Vec::new()).unwrap();
    }
    planner.start().unwrap();
    let mut shared_regions = 0;
    loop {
        if let Some(work) = planner.region_work().unwrap() {
            let per = work.keep.len() / work.levels.len();
            let mut flat = Vec::new();
            for (k, &z) in work.levels.iter().enumerate() {
                // Every other level made by the helper.
                let worker = if k % 2 == 0 { &mut helper } else { &mut planner };
                flat.extend(worker.level_regions(work.surface, &[z], &work.keep[k * per..(k + 1) * per]).unwrap());
            }
            planner.keep_regions(&flat).unwrap();
            shared_regions += 1;
        }
        let Some(pending) = planner.plan_next(&mut Progress::none()).unwrap() else { break };
        if pending == 0 {
            continue;
        }
        helper.keep_moves(&planner.pending_moves().unwrap()).unwrap();
        let groups = planner.take_bands(3).unwrap();
        let (mut bands, mut cuts) = (Vec::new(), Vec::new());
        for (g, group) in groups.iter().enumerate() {
            let worker = if g % 2 == 0 { &mut helper } else { &mut planner };
            let (b, c) = worker.cut_bands(group).unwrap();
            bands.push(b);
            cuts.push(c);
        }
        planner.absorb(&bands, &cuts).unwrap();
    }
    assert!(shared_regions >= 2, "the roughing's and the waterline's levels went through the pool");
    assert_eq!(planner.finish(&mut Progress::none()).unwrap().gcode, whole);
}
