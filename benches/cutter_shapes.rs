//! Issue 15: no cutter shape may cost more than 1.5 times another on the same job. Runs the
//! sample part's mould job (rough, raster shallow, waterline steep) with the finishing tool a
//! ball, a bull nose and a flat end of the same diameter, and prints each one's compute time as
//! a ratio to the ball's, with the time of its simulation alone.
//!
//! `cargo bench --bench cutter_shapes`

use std::time::Instant;

use swarf::cutter::Cutter;
use swarf::job::{self, Job};
use swarf::mesh::sample::demo_part;
use swarf::progress::Progress;

fn main() {
    let shapes = [("ball φ6", Cutter { flute_length: 30.0, ..Cutter::ball(6.0) }), ("bull nose φ6 r1", Cutter { flute_length: 30.0, ..Cutter::bull_nose(6.0, 1.0) }), ("flat φ6", Cutter { flute_length: 30.0, ..Cutter::flat(6.0) })];
    let mut reference = None;
    println!("{:<18} {:>10} {:>10} {:>8}", "finishing cutter", "job (s)", "no sim (s)", "× ball");
    for (name, cutter) in shapes {
        let mut job = Job::demo();
        job.tools[1].cutter = cutter;
        let best = |verify: bool| {
            let mut job = job.clone();
            job.simulation.verify = verify;
            (0..2).map(|_| {
                let t = Instant::now();
                job::run(&job, demo_part(), &mut Progress::none()).unwrap();
                t.elapsed().as_secs_f64()
            }).fold(f64::INFINITY, f64::min)
        };
        let (whole, plan) = (best(true), best(false));
        let ratio = whole / *reference.get_or_insert(whole);
        println!("{name:<18} {whole:>10.2} {plan:>10.2} {ratio:>8.2}");
    }
}
