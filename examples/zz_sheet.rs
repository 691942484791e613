use swarf::job::{Job, Operation};
fn main() {
    let mut job = Job::default_for_drawing();
    job.drawing.thickness = 10.0;
    if let Operation::Profile2d(p) = &mut job.operations[0] { p.tabs.width = 6.0; p.tabs.height = 2.0; p.lead_radius = Some(2.5); }
    let d = swarf::profile::import::read_drawing(swarf::profile::sample::plate_dxf().as_bytes(), Some("s.dxf"), &job.tolerances).unwrap();
    let out = swarf::job::run(&job, d, &mut swarf::progress::Progress::none()).unwrap();
    let mut zs: Vec<f64> = out.paths.iter().flat_map(|p| p.moves.iter().map(|m| m.to().z)).collect();
    zs.sort_by(|a,b| a.total_cmp(b)); zs.dedup();
    println!("{:?}", &zs[..5]);
    let g: Vec<&str> = out.gcode.lines().filter(|l| l.contains("Z-10.")).take(5).collect();
    println!("{:?}", g);
}
