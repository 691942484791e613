//! Prints how long each stage of the mould job takes, with the finishing cutter a ball, a bull
//! nose (r1) or a flat end of 6 mm: `cargo run --release --example stage_times -- bull`.
use std::time::Instant;
use swarf::cutter::Cutter;
use swarf::job::{self, Job};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;
fn main() {
    let mut job = Job::demo();
    let cutter = match std::env::args().nth(1).as_deref() {
        Some("bull") => Cutter::bull_nose(6.0, 1.0),
        Some("flat") => Cutter::flat(6.0),
        _ => Cutter::ball(6.0),
    };
    job.tools[1].cutter = Cutter { flute_length: 30.0, ..cutter };
    let t = Instant::now();
    let mut last = (String::new(), 0.0);
    let mut sink = |_f: f64, stage: &str| {
        if stage != last.0 {
            let now = t.elapsed().as_secs_f64();
            if !last.0.is_empty() {
                println!("{:>6.2} s  {}", now - last.1, last.0);
            }
            last = (stage.to_string(), now);
        }
        true
    };
    job::run(&job, demo_part(), &mut Progress::new(&mut sink)).unwrap();
    println!("total {:.2} s", t.elapsed().as_secs_f64());
}
