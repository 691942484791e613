//! What a helper worker of the page's pool holds, step by step (resident memory natively, Linux):
//! `cargo run --release --example helper_memory -- JOB.json PART.stl`.
use swarf::geom::Tolerances;
use swarf::job::{self, Job};
use swarf::progress::Progress;

fn resident_mb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status.lines().find_map(|l| l.strip_prefix("VmRSS:")).and_then(|v| v.trim().trim_end_matches(" kB").trim().parse::<f64>().ok()).unwrap_or(0.0) / 1024.0
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let job = Job::from_json(&std::fs::read_to_string(&args[1]).unwrap()).unwrap();
    let bytes = std::fs::read(&args[2]).unwrap();
    println!("{:>8.0} MB  start, the part's bytes read", resident_mb());
    let part = swarf::mesh::import::read_mesh_auto(&bytes, Some(&args[2]), &Tolerances::default()).unwrap();
    println!("{:>8.0} MB  the part read ({} triangles)", resident_mb(), part.faces.len());
    {
        let profile = swarf::cutter::Cutter::ball(10.0).profile();
        let tol = Tolerances::default();
        let index = swarf::zmap::drop::PointDrop::new(&part, &profile, &tol);
        println!("{:>8.0} MB  a drop index of a φ10 ball", resident_mb());
        let builder = index.builder(&part, &tol);
        println!("{:>8.0} MB  its exact builder", resident_mb());
        std::mem::drop((builder, index));
    }
    println!("{:>8.0} MB  both dropped", resident_mb());
    let mut plan = job::prepare(&job, part).unwrap();
    println!("{:>8.0} MB  the job prepared", resident_mb());
    let surfaces = plan.surfaces().unwrap();
    for s in &surfaces {
        let rows = plan.surface_rows(*s, 0..s.grid.ny / 2, &mut Progress::none()).unwrap();
        println!("{:>8.0} MB  half of a surface's rows ({} heights)", resident_mb(), rows.len());
    }
    let rasters = plan.rasters(&surfaces).unwrap();
    for r in &rasters {
        let passes = plan.raster_passes(r.operation, 0..r.passes / 2).unwrap();
        println!("{:>8.0} MB  half of a raster's passes ({} passes)", resident_mb(), passes.len());
    }
}
