//! Seed 004's case: zigzag roughing of the paper-like pocket, the plain path against the
//! feed-lowered and the corrected one (path length, load over the reference, cycle times,
//! compute time). It also writes the pocket as `target/paper_pocket.stl`, for the peers.
//!
//! Run: `cargo bench --bench zigzag` (native). The wasm figures: `bash scripts/bench-wasm.sh`.
//! The load of any programs with a flat end of diameter D on a part (the peers' side by side):
//! `cargo bench --bench zigzag -- load D PART.stl PROGRAM.ngc...`; their engagement (adaptive
//! clearing's measure): `cargo bench --bench zigzag -- engagement D AP AE FEED PART.stl PROGRAM.ngc...`.

mod support;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    if args.first().map(String::as_str) == Some("load") {
        let diameter: f64 = args[1].parse().expect("the tool's diameter");
        let stl = std::fs::read(&args[2]).expect("the part");
        let part = swarf::mesh::import::read_mesh_auto(&stl, Some("part.stl"), &Default::default()).expect("the part reads");
        for program in &args[3..] {
            let gcode = std::fs::read_to_string(program).expect("the program");
            let (peak, mean, n) = support::job::program_load(part.clone(), &gcode, diameter, 0.1, 1.2).expect("the program simulates");
            println!("{program}: removal rate per 1.2 mm of level cutting: peak {peak:.0} mm³/min, mean {mean:.0} mm³/min over {n} windows");
        }
        return;
    }
    if args.first().map(String::as_str) == Some("engagement") {
        // `-- engagement D AP AE FEED PART.stl PROGRAM.ngc...`: each program's engagement along
        // its level cutting (issue 59's measure), by the simulation: the volume each window of
        // 1.2 mm removed over its length and the depth AP is the radial cut `ae` it stands for,
        // and `arccos(1 − ae/r)` its angle, against the target of a straight cut AE deep.
        let num = |k: usize| -> f64 { args[k].parse().expect("a number") };
        let (diameter, ap, ae, feed) = (num(1), num(2), num(3), num(4));
        let r = diameter / 2.0;
        let angle = |ae: f64| (1.0 - ae / r).clamp(-1.0, 1.0).acos();
        let target = angle(ae);
        let part = swarf::mesh::import::read_mesh_auto(&std::fs::read(&args[5]).expect("the part"), Some("part.stl"), &Default::default()).expect("the part reads");
        for program in &args[6..] {
            let gcode = std::fs::read_to_string(program).expect("the program");
            let runs = support::job::program_runs(part.clone(), &gcode, diameter, 0.1, 1.2).expect("the program simulates");
            // Windows that cut (more than a twentieth of the target's rate), and whether both
            // windows beside them in their run cut too (the tool inside a front, not entering
            // or leaving one).
            let cuts = |rate: f64| rate / feed / ap > 0.05 * ae;
            let mut windows: Vec<(f64, bool)> = Vec::new();
            for run in &runs {
                for (k, &rate) in run.iter().enumerate().filter(|&(_, &rate)| cuts(rate)) {
                    let inside = k > 0 && k + 1 < run.len() && cuts(run[k - 1]) && cuts(run[k + 1]);
                    windows.push((angle(rate / feed / ap), inside));
                }
            }
            let share = |of: &dyn Fn(f64, bool) -> bool, among: &dyn Fn(bool) -> bool| {
                let n = windows.iter().filter(|w| among(w.1)).count();
                (windows.iter().filter(|w| among(w.1) && of(w.0, w.1)).count() as f64 / n.max(1) as f64, n)
            };
            let held = |a: f64, _: bool| (a - target).abs() <= 0.1 * target;
            let (within, n) = share(&held, &|_| true);
            let (over, _) = share(&|a, _| a > 1.3 * target, &|_| true);
            let (inside, fronts) = share(&held, &|inside| inside);
            let (edges, _) = share(&held, &|inside| !inside);
            let peak = windows.iter().map(|w| w.0).fold(0.0, f64::max);
            println!(
                "{program}: engagement over {n} windows of 1.2 mm cutting: {:.1} % within ±10 % of {:.1}°, {:.1} % above 1.3×, peak {:.1}°; inside fronts ({:.1} % of the windows) {:.1} % within, entering or leaving one {:.1} %",
                100.0 * within,
                target.to_degrees(),
                100.0 * over,
                peak.to_degrees(),
                100.0 * fronts as f64 / n.max(1) as f64,
                100.0 * inside,
                100.0 * edges
            );
            // The angle itself, sampled every 0.1 mm: the share of the cutting length (where
            // the tool stands in more than a twentieth of the target's cut) in the band.
            let sampled = support::job::program_engagement(part.clone(), &gcode, diameter, 0.05, 0.1).expect("the program simulates");
            let cutting: Vec<(f64, f64)> = sampled.concat().into_iter().filter(|&(_, a)| a > angle(0.05 * ae)).collect();
            let total = cutting.iter().map(|c| c.0).sum::<f64>().max(1e-12);
            let by = |keep: &dyn Fn(f64) -> bool| 100.0 * cutting.iter().filter(|c| keep(c.1)).map(|c| c.0).sum::<f64>() / total + 0.0;
            println!(
                "{program}: engagement sampled every 0.1 mm over {:.0} mm of cutting: {:.1} % within ±10 %, {:.1} % below, {:.1} % above 1.3×, peak {:.1}°",
                total,
                by(&|a| (a - target).abs() <= 0.1 * target),
                by(&|a| a < 0.9 * target),
                by(&|a| a > 1.3 * target),
                cutting.iter().map(|c| c.1).fold(0.0, f64::max).to_degrees()
            );
        }
        return;
    }
    let origin = std::time::Instant::now();
    let clock = || origin.elapsed().as_secs_f64();
    if args.first().map(String::as_str) == Some("stages") {
        // `-- stages JOB.json PART.stl`: where a job's time goes.
        let job = swarf::job::Job::from_json(&std::fs::read_to_string(&args[1]).expect("the job")).expect("a job");
        let part = swarf::mesh::import::read_mesh_auto(&std::fs::read(&args[2]).expect("the part"), Some("part.stl"), &Default::default()).expect("the part reads");
        let (stages, _) = support::job::stage_seconds(&job, part, &clock);
        for (stage, s) in stages {
            println!("{s:8.3} s  {stage}");
        }
        return;
    }
    let stl = swarf::mesh::sample::paper_pocket(0.5, 0.5).to_binary_stl();
    let _ = std::fs::write(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/paper_pocket.stl"), stl);
    println!("| platform | load held by | feed length (mm) | plain path's load: peak (spread) | as cut, at its feeds: peak (spread) | mm at a lowered feed | cycle time as programmed (s) | at the feed each allows (s) | compute (s) |");
    for row in support::job::zigzag_rows("native", &clock) {
        println!("{row}");
    }
    // Beside FreeCAD's Adaptive (scripts/bench-zigzag-peers.sh), where ../shared/data is beside
    // the project.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes");
    if let Ok(stl) = std::fs::read(dir.join("kiri_pocket-test.stl")) {
        for row in support::job::zigzag_peer_rows("kiri_pocket-test", &stl, "native", &clock) {
            println!("{row}");
        }
    }
}
