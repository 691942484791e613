//! Seed 001 §4.2's case, shared by the native benchmark (`benches/zmap_die.rs`) and the same
//! code in headless Chromium (`tests/bench_wasm.rs`), so both print comparable figures.

use swarf::cutter::Cutter;
use swarf::geom::Tolerances;
use swarf::mesh::{sample::fuel_tank_die, Mesh};
use swarf::progress::Progress;

use swarf::zmap::{cc::cc_zmap, cl_exact::cl_exact, cl_inverse::cl_inverse_offset, Grid};

/// The die, its grid, and the paper's timings.
pub struct DieCase {
    pub mesh: Mesh,
    pub grid: Grid,
    pub floor: f64,
}

/// Seconds for one cutter.
pub struct DieFigures {
    pub diameter: f64,
    pub cc_seconds: f64,
    pub inverse_seconds: f64,
    pub exact_seconds: f64,
    /// Largest amount the inverse offset lies below the exact CL z-map (mm).
    pub inverse_error: f64,
    pub paper_inverse: f64,
    pub paper_exact: f64,
}

/// 580 × 430 quads: 498,800 top triangles plus walls and bottom.
pub fn die_case() -> DieCase {
    let mesh = fuel_tank_die(580, 430);
    let b = mesh.bounds();
    DieCase { grid: Grid::covering(b.min.truncate(), b.max.truncate(), 0.8), floor: b.min.z, mesh }
}

impl DieCase {
    pub fn describe(&self) -> String {
        format!("die 1190 × 890 mm, {} triangles, grid 0.8 mm = {} × {} nodes", self.mesh.faces.len(), self.grid.nx, self.grid.ny)
    }

    /// Times both builders for a 10 mm and a 20 mm ball with `clock` (seconds since an origin).
    pub fn run_with(&self, clock: &dyn Fn() -> f64) -> Vec<DieFigures> {
        let tol = Tolerances::default();
        [(10.0, 10.0, 355.0), (20.0, 15.0, 450.0)]
            .into_iter()
            .map(|(diameter, paper_inverse, paper_exact)| {
                let profile = Cutter::ball(diameter).profile();
                let t0 = clock();
                let cc = cc_zmap(&self.mesh, self.grid, self.floor, &tol);
                let t1 = clock();
                let inverse = cl_inverse_offset(&cc, &profile, &mut Progress::none()).unwrap();
                let t2 = clock();
                let exact = cl_exact(&self.mesh, &profile, self.grid, self.floor, &tol, &mut Progress::none()).unwrap();
                let t3 = clock();
                let inverse_error = exact.z.iter().zip(&inverse.z).map(|(e, i)| e - i).fold(0.0, f64::max);
                DieFigures { diameter, cc_seconds: t1 - t0, inverse_seconds: t2 - t1, exact_seconds: t3 - t2, inverse_error, paper_inverse, paper_exact }
            })
            .collect()
    }

    #[cfg(not(target_arch = "wasm32"))]
    pub fn run(&self) -> Vec<DieFigures> {
        let origin = std::time::Instant::now();
        self.run_with(&|| origin.elapsed().as_secs_f64())
    }
}

impl DieFigures {
    pub fn row(&self, platform: &str) -> String {
        format!(
            "| {platform} | φ{} ball | CC {:.3} s | inverse offset {:.3} s (paper {} s, {:.0}×) | exact {:.3} s (paper {} s, {:.0}×) | inverse below exact by up to {:.4} mm |",
            self.diameter,
            self.cc_seconds,
            self.inverse_seconds,
            self.paper_inverse,
            self.paper_inverse / self.inverse_seconds,
            self.exact_seconds,
            self.paper_exact,
            self.paper_exact / self.exact_seconds,
            self.inverse_error
        )
    }
}
