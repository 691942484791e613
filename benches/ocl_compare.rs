//! swarf's exact CL z-map (seed 001 §3.3) against OpenCAMLib's BatchDropCutter, side by side in
//! one run, on `../shared/data/meshes/ocl_mount_rush.stl` at a 0.5 mm grid: time ratio and the
//! largest height difference, for a 6 mm ball, flat and bull nose (r 1).
//!
//! Run: `cargo bench --bench ocl_compare` (needs `pip install opencamlib`; the bench installs
//! it if pip can).

use std::process::Command;
use std::time::Instant;

use swarf::cutter::Cutter;
use swarf::geom::Tolerances;
use swarf::mesh::import::read_mesh_auto;
use swarf::progress::Progress;
use swarf::zmap::{cl_exact::cl_exact, Grid};

fn main() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes/ocl_mount_rush.stl");
    if !path.exists() {
        println!("skipped: {} is absent", path.display());
        return;
    }
    let has_ocl = |()| Command::new("python3").args(["-c", "import opencamlib"]).status().map(|s| s.success()).unwrap_or(false);
    if !has_ocl(()) {
        let _ = Command::new("python3").args(["-m", "pip", "install", "--quiet", "opencamlib"]).status();
    }
    if !has_ocl(()) {
        println!("skipped: the opencamlib Python package is not installed (pip install opencamlib)");
        return;
    }
    let tol = Tolerances::default();
    let mesh = read_mesh_auto(&std::fs::read(&path).unwrap(), Some("ocl_mount_rush.stl"), &tol).unwrap();
    let b = mesh.bounds();
    let spacing = 0.5;
    let grid = Grid::covering(b.min.truncate(), b.max.truncate(), spacing);
    let floor = b.min.z - 10.0;
    println!("ocl_mount_rush.stl: {} triangles, grid {} × {} = {} points at {spacing} mm", mesh.faces.len(), grid.nx, grid.ny, grid.nodes());
    println!("| cutter | OpenCAMLib s | swarf s | swarf points/s | ratio | max |Δz| mm |");
    println!("|---|---|---|---|---|---|");
    for (name, shape, cutter) in [("6 mm ball", "ball", Cutter::ball(6.0)), ("6 mm flat", "flat", Cutter::flat(6.0)), ("6 mm bull nose r1", "bullNose", Cutter::bull_nose(6.0, 1.0))] {
        let out = Command::new("python3")
            .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/benches/ocl_dropcutter.py"))
            .arg(&path)
            .args([grid.origin.x, grid.origin.y, spacing].map(|v| format!("{v:.17}")))
            .args([grid.nx.to_string(), grid.ny.to_string(), format!("{floor:.17}"), shape.into(), "6".into(), "1".into()])
            .output()
            .expect("python3");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let ocl: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let ocl_seconds = ocl["seconds"].as_f64().unwrap();
        if shape == "ball" {
            println!("(OpenCAMLib BatchDropCutter on {} threads; swarf on {} threads)\n", ocl["threads"], swarf::parallel::threads());
        }
        let ocl_z: Vec<f64> = ocl["z"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let mut best = f64::INFINITY;
        let mut field = None;
        for _ in 0..5 {
            let started = Instant::now();
            field = Some(cl_exact(&mesh, &cutter.profile(), grid, floor, &tol, &mut Progress::none()).unwrap());
            best = best.min(started.elapsed().as_secs_f64());
        }
        let field = field.unwrap();
        let worst = field.z.iter().zip(&ocl_z).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        println!(
            "| {name} | {ocl_seconds:.3} | {best:.4} | {:.0} | {:.0}× | {worst:.2e} |",
            grid.nodes() as f64 / best,
            ocl_seconds / best
        );
    }
}
