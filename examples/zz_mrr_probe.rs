use swarf::job::{Job, Operation};
use swarf::progress::Progress;
fn main() {
    let mut job = Job::demo();
    job.operations.retain(|o| o.name() == "finish shallow");
    if let Operation::FinishRaster(r) = &mut job.operations[0] { r.stepover = 1.5; r.grid = 0.5; r.slope_max = None; }
    let part = swarf::mesh::sample::demo_part();
    let out = swarf::job::run(&job, part, &mut Progress::none()).unwrap();
    let v = out.verification.as_ref().unwrap();
    println!("peak {:.0} ops {:?}", v.report.mrr_max, out.operations.iter().map(|o| o.mrr_max).collect::<Vec<_>>());
    let full = Job::demo();
    let out = swarf::job::run(&full, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
    println!("demo ops {:?}", out.operations.iter().map(|o| (o.name.clone(), o.mrr_max)).collect::<Vec<_>>());
}
