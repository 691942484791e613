//! Simulation of whole programs, timed: the raster finishing programs of the sample part and of
//! seed 001's die (the foundation issue's benchmark part). Shared by `cargo bench --bench
//! sim_program` and the wasm benchmark, so both time the same work.

use swarf::cutter::Cutter;
use swarf::geom::{Aabb, Tolerances};
use swarf::job::{self, FinishRaster, Job, Operation, Simulation, Tool};
use swarf::mesh::{sample, Mesh};
use swarf::operations::Steps;
use swarf::progress::Progress;
use swarf::sim::program::{simulate, ProgramMove};
use swarf::sim::verify::{verify, VerifySettings};
use swarf::sim::DexelStock;

/// A part with its finishing program, made once.
pub struct ProgramCase {
    pub name: &'static str,
    pub part: Mesh,
    pub stock: Aabb,
    pub moves: Vec<ProgramMove>,
    /// Making the program: CL z-map, passes, links and G-code, without simulation (s).
    pub job_seconds: f64,
}

/// One timing.
#[derive(Clone, Debug)]
pub struct ProgramFigures {
    pub name: String,
    pub cell: f64,
    pub cells: usize,
    pub moves: usize,
    /// Simulating every move on the z-map stock (s).
    pub simulate_seconds: f64,
    /// The whole verification: simulation, the part's CC z-map, gouge, collision and residual
    /// checks (s).
    pub verify_seconds: f64,
    pub removed: f64,
}

impl ProgramFigures {
    pub fn row(&self, platform: &str) -> String {
        format!(
            "{platform:<16} {:<34} cell {:.3} mm, {:>9} cells, {:>7} moves: simulate {:.3} s, verify {:.3} s ({:.0} mm³ removed)",
            self.name, self.cell, self.cells, self.moves, self.simulate_seconds, self.verify_seconds, self.removed
        )
    }
}

fn case(name: &'static str, job: Job, part: Mesh, clock: &dyn Fn() -> f64) -> ProgramCase {
    let job = Job { simulation: Simulation { verify: false, cell: None, ..Default::default() }, ..job };
    let start = clock();
    let out = job::run(&job, part, &mut Progress::none()).expect("the benchmark job runs");
    let job_seconds = clock() - start;
    ProgramCase { name, part: out.part, stock: out.stock, moves: out.moves, job_seconds }
}

/// The page's sample part with the default job (φ6 ball, stepover 0.5 mm).
pub fn sample_case(clock: &dyn Fn() -> f64) -> ProgramCase {
    case("sample part, φ6 ball, stepover 0.5", Job::default(), sample::demo_part(), clock)
}

/// Seed 001's die (about 500,000 triangles) finished with a φ10 ball, stepover 2 mm, on a 0.8 mm
/// CL z-map: the foundation issue's benchmark job.
pub fn die_case(clock: &dyn Fn() -> f64) -> ProgramCase {
    let job = Job {
        tools: vec![Tool { cutter: Cutter::ball(10.0), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { grid: 0.8, stepover: 2.0, ..FinishRaster::default() })],
        ..Job::default()
    };
    case("die, φ10 ball, stepover 2", job, sample::fuel_tank_die(580, 430), clock)
}

impl ProgramCase {
    /// What making the program took.
    pub fn job_row(&self, platform: &str) -> String {
        format!("{platform:<16} {:<34} job (CL z-map, passes, links, G-code): {:.3} s, {} moves", self.name, self.job_seconds, self.moves.len())
    }

    /// Simulates and verifies the first `moves` moves (all when `None`) on cells of `cell` mm.
    pub fn run(&self, cell: f64, moves: Option<usize>, clock: &dyn Fn() -> f64) -> ProgramFigures {
        let moves = &self.moves[..moves.unwrap_or(self.moves.len()).min(self.moves.len())];
        let tol = Tolerances::default();
        let start = clock();
        let mut stock = DexelStock::new(&self.stock, cell, 1);
        let removed: f64 = simulate(&mut stock, moves, tol.chordal, &mut Progress::none()).expect("not cancelled").iter().sum();
        let simulate_seconds = clock() - start;
        let start = clock();
        let v = verify(&self.part, &self.stock, moves, &VerifySettings { cell, allowance: 0.0 }, &tol, &mut Progress::none()).expect("not cancelled");
        let verify_seconds = clock() - start;
        let name = match moves.len() == self.moves.len() {
            true => self.name.to_string(),
            false => format!("{} (first {} moves)", self.name, moves.len()),
        };
        ProgramFigures { name, cell, cells: v.report.cells, moves: moves.len(), simulate_seconds, verify_seconds, removed }
    }

    /// The cell size that gives the stock about `cells` cells.
    pub fn cell_for(&self, cells: f64) -> f64 {
        let s = self.stock.size();
        (s.x * s.y / cells).sqrt()
    }
}

/// Stage times of a job: each progress stage's name with the seconds until the next stage began
/// (the last one until the job ended), in order.
pub fn stage_seconds(job: &Job, part: Mesh, clock: &dyn Fn() -> f64) -> (Vec<(String, f64)>, job::JobOutput) {
    let mut marks: Vec<(String, f64)> = Vec::new();
    let mut sink = |_: f64, stage: &str| {
        if marks.last().is_none_or(|(s, _)| s != stage) {
            marks.push((stage.to_string(), clock()));
        }
        true
    };
    let out = job::run(job, part, &mut Progress::new(&mut sink)).expect("the benchmark job runs");
    let end = clock();
    let times = (0..marks.len()).map(|k| (marks[k].0.clone(), marks.get(k + 1).map_or(end, |m| m.1) - marks[k].1)).collect();
    (times, out)
}

fn seconds_of(stages: &[(String, f64)], name: &str) -> f64 {
    stages.iter().filter(|(s, _)| s == name).map(|(_, t)| t).sum()
}

/// Figures of a two-operation sequence.
#[derive(Clone, Debug)]
pub struct SequenceFigures {
    pub name: String,
    /// The whole job (s).
    pub total: f64,
    /// Each operation's CL z-map stage (s): the second gets the first's from the cache when
    /// they share cutter and grid.
    pub zmaps: [f64; 2],
    /// The in-process stock after the first operation (s): with verification on, this is
    /// simulation the verification would have run anyway.
    pub in_process: f64,
    /// The verification of the whole program at the end: the last operation's simulation and
    /// the judging (s).
    pub verify: f64,
    pub cache_hits: usize,
}

impl SequenceFigures {
    pub fn row(&self, platform: &str) -> String {
        format!(
            "{platform:<16} {:<52} total {:.3} s; CL z-map op 1 {:.3} s, op 2 {:.4} s ({} cache hit); in-process stock after op 1 {:.3} s; last simulation and verification {:.3} s",
            self.name, self.total, self.zmaps[0], self.zmaps[1], self.cache_hits, self.in_process, self.verify
        )
    }
}

/// Runs a two-operation job and takes its stages apart.
pub fn sequence(name: &str, job: &Job, part: Mesh, clock: &dyn Fn() -> f64) -> SequenceFigures {
    let start = clock();
    let (stages, out) = stage_seconds(job, part, clock);
    let total = clock() - start;
    let op = |k: usize| job.operations[k].name().to_string();
    SequenceFigures {
        name: name.to_string(),
        total,
        zmaps: [seconds_of(&stages, &format!("{}: CL z-map", op(0))), seconds_of(&stages, &format!("{}: CL z-map", op(1)))],
        in_process: seconds_of(&stages, &format!("{}: in-process stock", op(0))),
        verify: seconds_of(&stages, &format!("{}: in-process stock", op(1))),
        cache_hits: out.cache.hits,
    }
}

/// Two raster finishes with one cutter and grid, across and along: the second operation's
/// CL z-map comes from the cache.
pub fn two_rasters(tool: Tool, grid: f64, stepover: f64) -> Job {
    let raster = |name: &str, angle: f64| Operation::FinishRaster(FinishRaster { name: name.into(), grid, stepover, angle, ..FinishRaster::default() });
    Job { tools: vec![tool], operations: vec![raster("across", 0.0), raster("along", 90.0)], ..Job::default() }
}

/// The sample part's two-tool sequence: a φ6 ball leaving 0.3 mm at stepover 1.5, then a φ3
/// ball at stepover 0.5, grid 0.25.
pub fn sample_two_tools(verify: bool) -> Job {
    let ball = |number: u32, d: f64| Tool { number, cutter: Cutter::ball(d), ..Tool::default() };
    let raster = |name: &str, tool: u32, stepover: f64, allowance: f64| Operation::FinishRaster(FinishRaster { name: name.into(), tool, stepover, allowance, ..FinishRaster::default() });
    Job {
        tools: vec![ball(1, 6.0), ball(2, 3.0)],
        operations: vec![raster("coarse", 1, 1.5, 0.3), raster("fine", 2, 0.5, 0.0)],
        simulation: Simulation { verify, cell: None, ..Default::default() },
        ..Job::default()
    }
}

/// The sequence figures: the die with two rasters sharing a φ10 ball and a 0.8 mm grid, and
/// the sample part's two-tool job with and without verification.
pub fn sequence_rows(platform: &str, clock: &dyn Fn() -> f64) -> Vec<String> {
    let die = two_rasters(Tool { cutter: Cutter::ball(10.0), ..Tool::default() }, 0.8, 2.0);
    let die = Job { simulation: Simulation { verify: false, cell: None, ..Default::default() }, ..die };
    let mut rows = vec![sequence("die, φ10 ball, two rasters (0°, 90°), grid 0.8", &die, sample::fuel_tank_die(580, 430), clock).row(platform)];
    for verify in [true, false] {
        let name = format!("sample part, φ6 then φ3 ball, verify {}", if verify { "on" } else { "off" });
        rows.push(sequence(&name, &sample_two_tools(verify), sample::demo_part(), clock).row(platform));
    }
    rows
}

/// Issue 12's roughing settings: a φ6 flat end, step-down 2, step-over 0.4, no allowance, the
/// stock the part's box, feed 1000, plunge 250, rapids 5000 mm/min; the part kept where it is.
pub fn peer_rough_job() -> Job {
    use swarf::operations::RoughZlevel;
    let tool = Tool { cutter: Cutter { flute_length: 50.0, ..Cutter::flat(6.0) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() };
    Job {
        part: swarf::mesh::placement::PartSetup { placement: swarf::mesh::placement::Placement::Keep, ..Default::default() },
        stock: job::Stock { margin_xy: 0.0, margin_top: 0.0, margin_bottom: 0.0, ..Default::default() },
        post: swarf::post::PostSettings { rapid_rate: 5000.0, ..Default::default() },
        tools: vec![tool],
        operations: vec![Operation::RoughZlevel(RoughZlevel {
            roughing: swarf::machining::settings::Roughing { allowance: 0.0, leave_stock: 0.0, ..Default::default() },
            steps: Steps { stepdown: 2.0, stepover_fraction: 0.4 },
            ..RoughZlevel::default()
        })],
        simulation: Simulation { verify: false, cell: None, ..Default::default() },
        ..Job::default()
    }
}

/// Roughing a part (STL bytes) with [`peer_rough_job`]: its stages' times, without simulation.
pub fn rough_row(name: &str, stl: &[u8], platform: &str, clock: &dyn Fn() -> f64) -> String {
    let part = swarf::mesh::import::read_mesh_auto(stl, Some("part.stl"), &Tolerances::default()).expect("the part reads");
    let start = clock();
    let (stages, out) = stage_seconds(&peer_rough_job(), part, clock);
    let total = clock() - start;
    let of = |s: &str| seconds_of(&stages, &format!("z-level rough: {s}"));
    format!(
        "{platform:<16} rough {name:<20} total {total:.3} s: CL z-map {:.3} s, level map and regions {:.3} s, rings {:.3} s; {} moves, {:.0} s on the machine",
        of("CL z-map"),
        of("levels"),
        of("rings"),
        out.moves.len(),
        out.stats.seconds
    )
}

/// Seed 004's case: the paper-like pocket ([`sample::paper_pocket`], 120 × 85 mm, two
/// islands), a φ10 flat end at feed 1000, radial depth 3 mm, axial 0.5 mm, one level, zigzag
/// roughing with the load held by `load`; the stock the plate.
pub fn paper_zigzag_job(load: swarf::machining::settings::LoadControl) -> Job {
    use swarf::operations::RoughZigzag;
    let tool = Tool { cutter: Cutter::flat(10.0), feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() };
    let op = RoughZigzag {
        roughing: swarf::machining::settings::Roughing { allowance: 0.0, leave_stock: 0.0, grid: 0.5, ..Default::default() },
        load,
        steps: Steps { stepdown: 0.5, stepover_fraction: 0.3 },
        ..RoughZigzag::default()
    };
    Job { tools: vec![tool], operations: vec![Operation::RoughZigzag(op)], ..peer_rough_job() }
}

/// Seed 004's figures on its case, for the plain path, the feed lowered where it overloads,
/// and the path corrected: path length, the load's peak and spread over the reference (per
/// Δs, on the pixel map), the cycle time as programmed and at the feed each allows (the plain
/// path at the one constant feed its peak load allows, 1.1 × the reference), and compute time.
pub fn zigzag_rows(platform: &str, clock: &dyn Fn() -> f64) -> Vec<String> {
    use swarf::machining::{report::LoadReport, settings::LoadControl};
    let part = sample::paper_pocket(0.5, 0.5);
    let mut rows = Vec::new();
    for load in [LoadControl::None, LoadControl::Feed, LoadControl::Path] {
        let job = paper_zigzag_job(load);
        let start = clock();
        let out = swarf::job::run(&job, part.clone(), &mut Progress::none()).expect("the paper's pocket roughs");
        let compute = clock() - start;
        let r = &out.operations[0];
        let l = r.load.as_ref().expect("a load report");
        let (plain, plain_spread) = LoadReport::peak_and_spread(&l.plain);
        let (cut, cut_spread) = LoadReport::peak_and_spread(&l.cut);
        let rapid = r.rapid_length / job.post.rapid_rate * 60.0;
        let allowed = match load {
            LoadControl::None => (r.seconds - rapid) * cut / 1.1 + rapid,
            _ => r.seconds,
        };
        rows.push(format!(
            "| {platform} | {load:?} | {:.0} | {plain:.2} ({plain_spread:.2}) | {cut:.2} ({cut_spread:.2}) | {:.0} | {:.0} | {:.0} | {compute:.2} |",
            r.feed_length, l.slowed, r.seconds, allowed
        ));
    }
    rows
}

/// The removal rate of any program (G-code text, swarf's or a peer's) with a flat end of
/// `diameter` on a part placed as in [`peer_rough_job`] (the stock the part's box), over
/// windows of `ds` mm of level cutting (entries left out), by the project's simulation at
/// `cell`: the highest window and the mean (mm³/min), and the number of windows.
pub fn program_load(part: Mesh, gcode: &str, diameter: f64, cell: f64, ds: f64) -> swarf::error::Result<(f64, f64, usize)> {
    let rates = program_rates(part, gcode, diameter, cell, ds)?;
    let mean = rates.iter().sum::<f64>() / rates.len().max(1) as f64;
    Ok((rates.iter().copied().fold(0.0, f64::max), mean, rates.len()))
}

/// The removal rate (mm³/min) over each window of at least `ds` mm of a program's level cutting
/// (a flat end of `diameter` on the part's box as stock), simulated at `cell`.
pub fn program_rates(part: Mesh, gcode: &str, diameter: f64, cell: f64, ds: f64) -> swarf::error::Result<Vec<f64>> {
    Ok(program_runs(part, gcode, diameter, cell, ds)?.concat())
}

/// The engagement along a program's level cutting as issue 59 defines it
/// (`swarf::sim::windows::engagement_runs`), on the stock of [`program_rates`] at `cell`,
/// sampled every `most` mm: each piece's length and angle (radians), by runs.
pub fn program_engagement(part: Mesh, gcode: &str, diameter: f64, cell: f64, most: f64) -> swarf::error::Result<Vec<Vec<(f64, f64)>>> {
    let (moves, stock) = program_on_box(part, gcode, diameter)?;
    swarf::sim::windows::engagement_runs(&moves, &stock, cell, most, &Tolerances::default())
}

/// A program's moves with a flat end of `diameter` (flutes long enough for anything) and the
/// stock [`peer_rough_job`] places the part in (its box).
fn program_on_box(part: Mesh, gcode: &str, diameter: f64) -> swarf::error::Result<(Vec<swarf::sim::program::ProgramMove>, swarf::geom::Aabb)> {
    let mut job = peer_rough_job();
    let mut part = part;
    let stock = job.place(&mut part);
    job.tools[0].cutter = Cutter { flute_length: 1e3, ..Cutter::flat(diameter) };
    let paths = swarf::post::read::read_gcode(gcode, 1)?;
    Ok((swarf::sim::program::program_moves(&paths, &job.tools, job.rapids(), job.air_feed())?, stock))
}

/// [`program_rates`] by runs of level cutting (`swarf::sim::windows::windowed_runs`).
pub fn program_runs(part: Mesh, gcode: &str, diameter: f64, cell: f64, ds: f64) -> swarf::error::Result<Vec<Vec<f64>>> {
    let (moves, stock) = program_on_box(part, gcode, diameter)?;
    swarf::sim::windows::windowed_runs(&moves, &stock, cell, ds)
}

/// Issue 12's settings (φ6 flat, step-down 2, step-over 0.4, no allowance, the stock the
/// part's box) with zigzag roughing on a 0.5 mm grid, the load held by `load`.
pub fn peer_zigzag_job(load: swarf::machining::settings::LoadControl) -> Job {
    use swarf::operations::RoughZigzag;
    let op = RoughZigzag {
        roughing: swarf::machining::settings::Roughing { allowance: 0.0, leave_stock: 0.0, grid: 0.5, ..Default::default() },
        load,
        steps: Steps { stepdown: 2.0, stepover_fraction: 0.4 },
        ..RoughZigzag::default()
    };
    Job { operations: vec![Operation::RoughZigzag(op)], ..peer_rough_job() }
}

/// Zigzag roughing of a part (STL bytes) with [`peer_zigzag_job`], each way of holding the
/// load: compute time (without simulation) and the cycle time as programmed.
pub fn zigzag_peer_rows(name: &str, stl: &[u8], platform: &str, clock: &dyn Fn() -> f64) -> Vec<String> {
    use swarf::machining::settings::LoadControl;
    let part = swarf::mesh::import::read_mesh_auto(stl, Some("part.stl"), &Tolerances::default()).expect("the part reads");
    [LoadControl::Path, LoadControl::Feed, LoadControl::None]
        .into_iter()
        .map(|load| {
            let start = clock();
            let out = swarf::job::run(&peer_zigzag_job(load), part.clone(), &mut Progress::none()).expect("the part roughs");
            format!("| {platform} | {name} | {load:?} | compute {:.3} s | {:.0} s on the machine |", clock() - start, out.stats.seconds)
        })
        .collect()
}

/// Seed 000's comparison: a library of φ20, φ12, φ6 and φ3 flat ends (flutes three diameters
/// long, feed 1000, plunge 250, rapids 5000 mm/min), axial depth `delta` × D and rings
/// `stepover` × D apart for every tool, allowances 0.5; the stock the part's box with 1 mm on
/// top. Returns the jobs: octree multi-tool roughing, z-level roughing with each tool of the
/// library alone (the best single tool is what the octree must beat, issue 38), and z-level
/// roughing with the φ20 then with the φ3 (which sees what the φ20 left).
pub fn octree_jobs(delta: f64, stepover: f64, grid: f64, cell: f64) -> Vec<(String, Job)> {
    use swarf::operations::RoughOctree;
    use swarf::operations::RoughZlevel;
    let flat = |number: u32, d: f64| Tool { number, cutter: Cutter { flute_length: 3.0 * d, ..Cutter::flat(d) }, feed_rate: 1000.0, plunge_rate: 250.0, ..Tool::default() };
    let tools = vec![flat(1, 20.0), flat(2, 12.0), flat(3, 6.0), flat(4, 3.0)];
    let zlevel = |tool: u32, d: f64| {
        Operation::RoughZlevel(RoughZlevel {
            name: format!("z-level φ{d}"),
            tool,
            roughing: swarf::machining::settings::Roughing { grid, ..Default::default() },
            steps: Steps { stepdown: delta * d, stepover_fraction: stepover },
            ..RoughZlevel::default()
        })
    };
    let base = Job {
        part: swarf::mesh::placement::PartSetup { placement: swarf::mesh::placement::Placement::Keep, ..Default::default() },
        stock: job::Stock { margin_xy: 0.0, margin_top: 1.0, margin_bottom: 0.0, ..Default::default() },
        post: swarf::post::PostSettings { rapid_rate: 5000.0, ..Default::default() },
        tools,
        simulation: Simulation { verify: true, cell: Some(cell), ..Default::default() },
        ..Job::default()
    };
    let mut jobs = vec![(
        "octree (φ20 φ12 φ6 φ3)".to_string(),
        Job {
            operations: vec![Operation::RoughOctree(RoughOctree {
                delta,
                stepover_fraction: stepover,
                roughing: swarf::machining::settings::Roughing { grid, ..Default::default() },
                ..RoughOctree::default()
            })],
            ..base.clone()
        },
    )];
    for (tool, d) in [(1, 20.0), (2, 12.0), (3, 6.0), (4, 3.0)] {
        jobs.push((format!("z-level φ{d} alone"), Job { operations: vec![zlevel(tool, d)], ..base.clone() }));
    }
    jobs.push(("z-level φ20, then φ3".to_string(), Job { operations: vec![zlevel(1, 20.0), zlevel(4, 3.0)], ..base }));
    jobs
}

/// One row per job of [`octree_jobs`] on `part`: machine time, material left above the part
/// plus allowance (mm³), what verification found, compute time; each job's time over the
/// octree job's.
pub fn octree_rows(name: &str, part: &Mesh, platform: &str, clock: &dyn Fn() -> f64) -> Vec<String> {
    let mut rows = Vec::new();
    let mut reference = None;
    let mut best: Option<(String, f64)> = None;
    let mut octree_left: Option<f64> = None;
    for (label, job) in octree_jobs(0.25, 0.5, 0.5, 0.25) {
        let start = clock();
        let out = match job::run(&job, part.clone(), &mut Progress::none()) {
            Ok(out) => out,
            Err(e) => {
                rows.push(format!("{platform:<16} octree {name:<18} {label:<24} failed: {e}"));
                continue;
            }
        };
        let compute = clock() - start;
        let v = out.verification.as_ref().expect("verified");
        let left = left_off_walls(v, 0.5);
        // The best single tool: the fastest clean one that leaves no more than the octree
        // (issue 38's target; a big tool alone is quick because it leaves much more).
        let leaves_no_more = octree_left.is_none_or(|o: f64| left.1 <= 1.05 * o + 1.0);
        if label.ends_with("alone") && v.report.is_clean() && leaves_no_more && best.as_ref().is_none_or(|b: &(String, f64)| out.stats.seconds < b.1) {
            best = Some((label.clone(), out.stats.seconds));
        }
        octree_left.get_or_insert(left.1);
        let seconds = out.stats.seconds;
        let ratio = seconds / *reference.get_or_insert(seconds);
        let tools: Vec<String> = out.operations.iter().flat_map(|o| o.tools.iter().map(|t| format!("T{t}"))).collect();
        rows.push(format!(
            "{platform:<16} octree {name:<18} {label:<24} {:>6.1} min ({ratio:.2} of the octree's), left {:>7.0} mm³ ({:.0} off the walls' leave-stock), {} gouges, {} rapids in stock, {} body hits, tools {}, computed in {compute:.1} s",
            seconds / 60.0,
            left.0,
            left.1,
            v.report.gouge_count,
            v.report.rapid_collision_count,
            v.report.body_collision_count,
            tools.join(" ")
        ));
    }
    if let (Some(octree), Some((label, seconds))) = (reference, best) {
        rows.push(format!(
            "{platform:<16} octree {name:<18} the best single tool leaving no more than the octree: {label}, {:.1} min; the octree's time over it: {:.2}",
            seconds / 60.0,
            octree / seconds
        ));
    }
    rows
}

/// The material a program left above the part plus its allowance (mm³): all of it, and off the
/// band of `leave` (and a cell) beside steep walls, where every program keeps the wall's
/// leave-stock and the cells' centres judge it by the floor below.
pub fn left_off_walls(v: &swarf::sim::verify::Verification, leave: f64) -> (f64, f64) {
    let r = v.residual();
    let g = v.stock.grid();
    let cell = g.spacing;
    let reach = ((leave + cell) / cell).ceil() as isize;
    let (mut all, mut off) = (0.0, 0.0);
    for j in 0..g.ny as isize {
        for i in 0..g.nx as isize {
            let c = (j as usize) * g.nx + i as usize;
            let here = v.part.z[c];
            if here.is_nan() {
                continue;
            }
            let left = r.z[c].max(0.0) * cell * cell;
            all += left;
            let wall = (-reach..=reach).any(|dj| {
                (-reach..=reach).any(|di| {
                    let (a, b) = (i + di, j + dj);
                    a >= 0 && b >= 0 && (a as usize) < g.nx && (b as usize) < g.ny && v.part.z[b as usize * g.nx + a as usize] > here + 1.0
                })
            });
            if !wall {
                off += left;
            }
        }
    }
    (all, off)
}

/// Issue 15's cutter shapes: a ball, a bull nose and a flat end of 6 mm, finishing the sample
/// part's mould job.
pub fn cutter_shapes() -> [(&'static str, Cutter); 3] {
    [("ball φ6", Cutter::ball(6.0)), ("bull nose φ6 r1", Cutter::bull_nose(6.0, 1.0)), ("flat φ6", Cutter::flat(6.0))]
}

/// The sample part's mould job (z-level rough with a φ6 flat end, raster shallow, waterline
/// steep, verified) with [`cutter_shapes`]`()[shape]` finishing: its compute time, best of `runs`.
pub fn cutter_shape_seconds(shape: usize, runs: usize, clock: &dyn Fn() -> f64) -> f64 {
    let mut job = Job::demo();
    job.tools[1].cutter = Cutter { flute_length: 30.0, ..cutter_shapes()[shape].1 };
    (0..runs.max(1))
        .map(|_| {
            let start = clock();
            job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).expect("the mould job runs");
            clock() - start
        })
        .fold(f64::INFINITY, f64::min)
}

/// Rows of [`cutter_shape_seconds`] for every shape: each one's time, as a ratio to the ball's
/// and to the fastest shape's, and last the largest ratio between two shapes.
pub fn cutter_shape_rows(platform: &str, seconds: &[f64; 3]) -> Vec<String> {
    let (ball, fastest) = (seconds[0], seconds.iter().copied().fold(f64::INFINITY, f64::min));
    let slowest = seconds.iter().copied().fold(0.0, f64::max);
    let mut rows: Vec<String> =
        cutter_shapes().iter().zip(seconds).map(|((name, _), t)| format!("{platform:<16} {name:<16} {t:>7.2} s  {:>5.2} × ball  {:>5.2} × fastest", t / ball, t / fastest)).collect();
    rows.push(format!("{platform:<16} largest ratio between two shapes: {:.2}", slowest / fastest));
    rows
}
