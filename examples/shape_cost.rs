//! Times each operation of the mould job with a bull nose (for profiling the cutter's cost).
use std::time::Instant;
use swarf::cutter::Cutter;
use swarf::job::{self, Job};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;
fn main() {
    let corner: f64 = std::env::args().nth(1).map_or(1.0, |a| a.parse().unwrap());
    for k in [1usize, 2] {
        let mut job = Job::demo();
        job.tools[1].cutter = if corner == 0.0 { Cutter { flute_length: 30.0, ..Cutter::ball(6.0) } } else { Cutter { flute_length: 30.0, ..Cutter::bull_nose(6.0, corner) } };
        job.operations = vec![job.operations[k].clone()];
        job.simulation.verify = false;
        let t = Instant::now();
        job::run(&job, demo_part(), &mut Progress::none()).unwrap();
        println!("op {k}: {:.2} s", t.elapsed().as_secs_f64());
    }
}
