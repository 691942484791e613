//! swarf's exact CL z-map (seed 001 §3.3) against OpenCAMLib's BatchDropCutter, side by side in
//! one run.
//!
//! 1. Speed: `../shared/data/meshes/ocl_mount_rush.stl` at a 0.5 mm grid (`SPACING=0.1` for
//!    issue 61's 372,380 nodes), a 6 mm ball, flat, bull nose (r 1) and 90° V-bit: time ratio
//!    and the largest height difference (`SPEED_ONLY=1` stops there).
//! 2. Heights on every shared mesh: each one written as the binary STL OpenCAMLib reads (so both
//!    see the same triangles), a grid of about 20,000 nodes over it, φ6 ball, flat, bull nose r1,
//!    φ10 bull nose r2.5, and pointed V-bits (OpenCAMLib's `ConeCutter`) of 90° φ6 and 60°
//!    φ10: the largest difference and how many nodes differ by more than 1e-6 mm, and at the
//!    node where they differ most, how far each is from the brute-force drop over every
//!    triangle, and how far each stands above a drop that shares no code with swarf's: every
//!    triangle within reach sampled on a barycentric lattice, the highest of `z - height(r)`
//!    (a lower bound of the exact drop, within the lattice's spacing of it).
//!
//! Run: `cargo bench --bench ocl_compare` (needs OpenCAMLib: `pip install opencamlib`, in the
//! Python that `$PYTHON` names, `python3` by default; the bench installs it if pip can).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use swarf::cutter::Cutter;
use swarf::geom::Tolerances;
use swarf::mesh::import::read_mesh_auto;
use swarf::mesh::Mesh;
use swarf::progress::Progress;
use swarf::zmap::{cl_exact::cl_exact, cl_exact::cl_exact_at, Grid};

fn python() -> String {
    std::env::var("PYTHON").unwrap_or_else(|_| "python3".into())
}

/// OpenCAMLib's heights over `grid` and its run time.
fn ocl(stl: &Path, grid: Grid, floor: f64, shape: &str, diameter: f64, corner: f64) -> (Vec<f64>, f64, serde_json::Value) {
    let out = Command::new(python())
        .arg(concat!(env!("CARGO_MANIFEST_DIR"), "/benches/ocl_dropcutter.py"))
        .arg(stl)
        .args([grid.origin.x, grid.origin.y, grid.spacing].map(|v| format!("{v:.17}")))
        .args([grid.nx.to_string(), grid.ny.to_string(), format!("{floor:.17}"), shape.into(), diameter.to_string(), corner.to_string()])
        .output()
        .expect("python");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let z = v["z"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    (z, v["seconds"].as_f64().unwrap(), v["threads"].clone())
}

/// The mesh as a binary STL (its coordinates came from f32 files, so nothing is lost).
fn write_stl(mesh: &Mesh, path: &Path) {
    let mut b = vec![0u8; 80];
    b.extend((mesh.faces.len() as u32).to_le_bytes());
    for f in &mesh.faces {
        b.extend([0f32; 3].iter().flat_map(|x| x.to_le_bytes()));
        for &i in f {
            let v = mesh.vertices[i as usize];
            b.extend([v.x as f32, v.y as f32, v.z as f32].iter().flat_map(|x| x.to_le_bytes()));
        }
        b.extend([0u8; 2]);
    }
    std::fs::write(path, b).unwrap();
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes");
    if !dir.exists() {
        println!("skipped: {} is absent", dir.display());
        return;
    }
    let has_ocl = || Command::new(python()).args(["-c", "import opencamlib"]).status().map(|s| s.success()).unwrap_or(false);
    if !has_ocl() {
        let _ = Command::new(python()).args(["-m", "pip", "install", "--quiet", "opencamlib"]).status();
    }
    if !has_ocl() {
        println!("skipped: the opencamlib Python package is not installed (pip install opencamlib; set PYTHON to a Python that has it)");
        return;
    }
    let tol = Tolerances::default();
    speed(&dir.join("ocl_mount_rush.stl"), &tol);
    if std::env::var_os("SPEED_ONLY").is_none() {
        heights(&dir, &tol);
    }
}

fn speed(path: &Path, tol: &Tolerances) {
    let mesh = read_mesh_auto(&std::fs::read(path).unwrap(), Some("ocl_mount_rush.stl"), tol).unwrap();
    let b = mesh.bounds();
    // SPACING=0.1 for issue 61's grid (372,000 nodes); 0.5 by default.
    let spacing: f64 = std::env::var("SPACING").ok().and_then(|s| s.parse().ok()).unwrap_or(0.5);
    let grid = Grid::covering(b.min.truncate(), b.max.truncate(), spacing);
    let floor = b.min.z - 10.0;
    println!("ocl_mount_rush.stl: {} triangles, grid {} × {} = {} points at {spacing} mm", mesh.faces.len(), grid.nx, grid.ny, grid.nodes());
    println!("| cutter | OpenCAMLib s | swarf s | swarf points/s | ratio | max |Δz| mm |");
    println!("|---|---|---|---|---|---|");
    for (name, shape, corner, cutter) in [
        ("6 mm ball", "ball", 1.0, Cutter::ball(6.0)),
        ("6 mm flat", "flat", 1.0, Cutter::flat(6.0)),
        ("6 mm bull nose r1", "bullNose", 1.0, Cutter::bull_nose(6.0, 1.0)),
        ("6 mm V-bit 90°", "cone", 45.0, Cutter::v_bit(6.0, 90.0, 0.0)),
    ] {
        let (ocl_z, ocl_seconds, threads) = ocl(path, grid, floor, shape, 6.0, corner);
        if shape == "ball" {
            println!("(OpenCAMLib BatchDropCutter on {threads} threads; swarf on {} threads)\n", swarf::parallel::threads());
        }
        let mut best = f64::INFINITY;
        let mut field = None;
        for _ in 0..5 {
            let started = Instant::now();
            field = Some(cl_exact(&mesh, &cutter.profile(), grid, floor, tol, &mut Progress::none()).unwrap());
            best = best.min(started.elapsed().as_secs_f64());
        }
        let field = field.unwrap();
        let worst = field.z.iter().zip(&ocl_z).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        println!("| {name} | {ocl_seconds:.3} | {best:.4} | {:.0} | {:.0}× | {worst:.2e} |", grid.nodes() as f64 / best, ocl_seconds / best);
    }
}

fn heights(dir: &Path, tol: &Tolerances) {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let scratch = std::env::temp_dir().join(format!("swarf-ocl-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    println!("\nEvery shared mesh, about 20,000 nodes each:\n");
    println!("| mesh | triangles | grid mm | cutter | max |Δz| mm | nodes off by > 1e-6 mm | there, swarf / OpenCAMLib off the brute force mm | there, swarf / OpenCAMLib over the sampled drop mm |");
    println!("|---|---|---|---|---|---|---|---|");
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let Ok(mesh) = read_mesh_auto(&std::fs::read(&path).unwrap(), Some(&name), tol) else {
            println!("| {name} | (not a mesh swarf reads) |");
            continue;
        };
        let stl = scratch.join("mesh.stl");
        write_stl(&mesh, &stl);
        let b = mesh.bounds();
        let (min, max) = (b.min.truncate() - 3.0, b.max.truncate() + 3.0);
        let size = max - min;
        // An irrational-ish spacing keeps nodes off the meshes' round coordinates.
        let spacing = (size.x * size.y / 20_000.0).sqrt() * 1.000_37;
        let grid = Grid::covering(min, max, spacing);
        let floor = b.min.z - 10.0;
        for (cname, shape, d, corner, cutter) in [
            ("φ6 ball", "ball", 6.0, 0.0, Cutter::ball(6.0)),
            ("φ6 flat", "flat", 6.0, 0.0, Cutter::flat(6.0)),
            ("φ6 bull r1", "bullNose", 6.0, 1.0, Cutter::bull_nose(6.0, 1.0)),
            ("φ10 bull r2.5", "bullNose", 10.0, 2.5, Cutter::bull_nose(10.0, 2.5)),
            // OpenCAMLib's ConeCutter is pointed; its angle is the half angle.
            ("φ6 V 90°", "cone", 6.0, 45.0, Cutter::v_bit(6.0, 90.0, 0.0)),
            ("φ10 V 60°", "cone", 10.0, 30.0, Cutter::v_bit(10.0, 60.0, 0.0)),
        ] {
            let (ocl_z, _, _) = ocl(&stl, grid, floor, shape, d, corner);
            let field = cl_exact(&mesh, &cutter.profile(), grid, floor, tol, &mut Progress::none()).unwrap();
            let diffs: Vec<f64> = field.z.iter().zip(&ocl_z).map(|(a, b)| (a - b).abs()).collect();
            let (k, worst) = diffs.iter().copied().enumerate().fold((0, 0.0), |a, (k, x)| if x > a.1 { (k, x) } else { a });
            let off = diffs.iter().filter(|&&x| x > 1e-6).count();
            // Who is right where they differ most: the brute-force drop over every triangle.
            let at = grid.node(k % grid.nx, k / grid.nx);
            let brute = cl_exact_at(&mesh, &cutter.profile(), at, tol).unwrap_or(floor).max(floor);
            let sampled = sampled_drop(&mesh, &cutter.profile(), at, 120).max(floor);
            println!(
                "| {name} | {} | {spacing:.3} | {cname} | {worst:.2e} | {off} of {} | {:.1e} / {:.1e} | {:+.1e} / {:+.1e} |",
                mesh.faces.len(),
                grid.nodes(),
                (field.z[k] - brute).abs(),
                (ocl_z[k] - brute).abs(),
                field.z[k] - sampled,
                ocl_z[k].max(floor) - sampled
            );
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
}

/// The drop of `profile` at `c` found by sampling: every triangle within its reach on a
/// barycentric lattice of `n` steps a side (and so its edges and corners), the highest
/// `z - height(r)` within the radius. It shares nothing with swarf's drop but the cutter's
/// height function, and stands below the exact drop by no more than the lattice lets a
/// contact fall between its points.
fn sampled_drop(mesh: &Mesh, profile: &swarf::cutter::Profile, c: swarf::geom::DVec2, n: usize) -> f64 {
    let r = profile.radius;
    let mut best = f64::NEG_INFINITY;
    for t in mesh.triangles() {
        let b = t.bounds();
        if b.min.x > c.x + r || b.max.x < c.x - r || b.min.y > c.y + r || b.max.y < c.y - r {
            continue;
        }
        for i in 0..=n {
            for j in 0..=n - i {
                let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                let p = t.a + (t.b - t.a) * u + (t.c - t.a) * v;
                let d = p.truncate().distance(c);
                if d <= r {
                    best = best.max(p.z - profile.height(d));
                }
            }
        }
    }
    best
}
