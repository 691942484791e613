//! A whole finishing job on seed 001's die, timed by stage: `cargo run --release --example die_job`.
use std::time::Instant;
use swarf::cutter::Cutter;
use swarf::job::{self, FinishRaster, Job, Operation, Tool};
use swarf::progress::Progress;

fn main() {
    let part = swarf::mesh::sample::fuel_tank_die(580, 430);
    let job = Job {
        tools: vec![Tool { cutter: Cutter::ball(10.0), ..Tool::default() }],
        operations: vec![Operation::FinishRaster(FinishRaster { grid: 0.8, stepover: 2.0, ..FinishRaster::default() })],
        ..Job::default()
    };
    let started = Instant::now();
    let mut last = String::new();
    let mut sink = |_: f64, stage: &str| {
        if stage != last {
            println!("{:7.3} s  {stage}", started.elapsed().as_secs_f64());
            last = stage.to_owned();
        }
        true
    };
    let out = job::run(&job, part, &mut Progress::new(&mut sink)).unwrap();
    println!("{:7.3} s  done: {} moves, {} lines of G-code", started.elapsed().as_secs_f64(), out.stats.moves, out.gcode.lines().count());
}
