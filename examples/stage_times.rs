//! Prints how long each stage of the demo job takes (for deciding what a worker pool splits).
use std::time::Instant;
use swarf::job::{self, Job};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;
fn main() {
    let job = Job::demo();
    let t = Instant::now();
    let mut last = (String::new(), 0.0);
    let mut sink = |_f: f64, stage: &str| {
        if stage != last.0 {
            let now = t.elapsed().as_secs_f64();
            println!("{:>7.2} s  +{:.2}  {:?} -> {:?}", now, now - last.1, last.0, stage);
            last = (stage.to_string(), now);
        }
        true
    };
    job::run(&job, demo_part(), &mut Progress::new(&mut sink)).unwrap();
    println!("total {:.2} s", t.elapsed().as_secs_f64());
}
