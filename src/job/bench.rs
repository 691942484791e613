//! Simulation of whole programs, timed: the raster finishing programs of the sample part and of
//! seed 001's die (the foundation issue's benchmark part). Shared by `cargo bench --bench
//! sim_program` and the wasm benchmark, so both time the same work.

use crate::sim::program::{simulate, ProgramMove};
use crate::sim::verify::{verify, VerifySettings};
use crate::sim::DexelStock;
use crate::cutter::Cutter;
use crate::geom::{Aabb, Tolerances};
use crate::job::{self, FinishRaster, Job, Operation, Simulation, Tool};
use crate::mesh::{sample, Mesh};
use crate::progress::Progress;

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
    let job = Job { simulation: Simulation { verify: false, cell: None }, ..job };
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
