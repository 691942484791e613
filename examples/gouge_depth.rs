//! The deepest point of a program's feed moves below the exact CL surface of its tool, judged
//! at 20 points a millimetre by the exact drop (the figures of BENCHMARKS.md, "Gouge-free
//! between nodes"): `cargo run --release --example gouge_depth -- job.json part.stl program.ngc`.

use swarf::geom::DVec2;
use swarf::job::Job;
use swarf::mesh::import::read_mesh_auto;
use swarf::toolpath::Move;
use swarf::zmap::drop::PointDrop;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, job, part, program] = &args[..] else {
        eprintln!("usage: gouge_depth job.json part program.ngc");
        std::process::exit(2);
    };
    let job = Job::from_json(&std::fs::read_to_string(job).unwrap()).unwrap();
    let mut mesh = read_mesh_auto(&std::fs::read(part).unwrap(), Some(part), &job.tolerances).unwrap();
    let stock = job.place(&mut mesh);
    let tool = &job.tools[0];
    let drop = PointDrop::new(&mesh, &tool.cutter.profile(), &job.tolerances);
    let paths = swarf::post::read::read_gcode(&std::fs::read_to_string(program).unwrap(), tool.number).unwrap();
    let (mut worst, mut at, mut points) = (f64::NEG_INFINITY, DVec2::ZERO, 0usize);
    for path in &paths {
        let mut from = path.start;
        for m in &path.moves {
            let to = m.to();
            if let Move::Line { .. } = m {
                let n = ((from.truncate().distance(to.truncate()) * 20.0).ceil() as usize).max(1);
                for k in 0..=n {
                    let p = from.lerp(to, k as f64 / n as f64);
                    let depth = drop.at(p.truncate(), stock.min.z) - p.z;
                    points += 1;
                    if depth > worst {
                        (worst, at) = (depth, p.truncate());
                    }
                }
            }
            from = to;
        }
    }
    println!("{worst:.4} mm below at ({:.2}, {:.2}), {points} points", at.x, at.y);
}
