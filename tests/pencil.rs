//! Pencil finishing (issue 60) on parts whose inside corners are known exactly: every program
//! simulated clean and read by LinuxCNC's rs274, its passes where the ball touches two faces.

mod common;

use common::{clean, rs274};
use swarf::cutter::Cutter;
use swarf::geom::DVec2;
use swarf::job::{self, Job, JobOutput, Operation, Tool};
use swarf::mesh::placement::{PartSetup, Placement};
use swarf::mesh::Mesh;
use swarf::operations::FinishPencil;
use swarf::progress::Progress;

/// A 50 × 50 block 20 high with a 30 × 30 pocket 10 deep in its middle, the pocket's floor
/// meeting its walls in a fillet of radius `rf` (a quarter circle, mitred at the pocket's
/// corners), sampled every 0.2 mm (its walls lean across one sample: 0.2 mm over their 9 mm).
fn filleted_pocket(rf: f64) -> Mesh {
    swarf::mesh::sample::height_field_solid(DVec2::ZERO, DVec2::splat(50.0), 250, 250, 0.0, |x, y| {
        let d = (x - 10.0).min(40.0 - x).min(y - 10.0).min(40.0 - y);
        if d < 0.0 {
            20.0
        } else if d < rf {
            10.0 + rf - (rf * rf - (rf - d) * (rf - d)).sqrt()
        } else {
            10.0
        }
    })
}

fn pencil_job(ball: f64) -> Job {
    Job {
        tools: vec![Tool { number: 1, name: format!("{ball} mm ball"), cutter: Cutter { flute_length: 30.0, ..Cutter::ball(ball) }, feed_rate: 800.0, plunge_rate: 200.0, ..Tool::default() }],
        operations: vec![Operation::FinishPencil(FinishPencil::default())],
        part: PartSetup { placement: Placement::Keep, ..PartSetup::default() },
        stock: swarf::job::Stock { margin_xy: 0.0, margin_top: 0.0, ..Default::default() },
        simulation: swarf::job::Simulation { verify: true, cell: Some(0.2), ..Default::default() },
        ..Job::default()
    }
}

/// The points along the feed moves at the pocket's floor (the ball's tip on it), every 0.1 mm,
/// and their length.
fn along_the_floor(out: &JobOutput) -> (Vec<DVec2>, f64) {
    let (mut points, mut length) = (Vec::new(), 0.0);
    for m in &out.moves {
        let (a, b) = (m.from, m.mv.to());
        if m.mv.is_rapid() || (a.z - 10.0).abs() > 0.01 || (b.z - 10.0).abs() > 0.01 {
            continue;
        }
        let n = (a.distance(b) / 0.1).ceil().max(1.0) as usize;
        points.extend((0..=n).map(|k| a.truncate().lerp(b.truncate(), k as f64 / n as f64)));
        length += a.distance(b);
    }
    (points, length)
}

/// A fillet of radius 1 under a φ6 ball: the ball can't reach into it, and rests on the floor
/// and against the wall at once, its centre 3 from each; the pencil pass runs there (the square
/// 3 in from the pocket's walls, at the floor's height) all round, within half the grid.
#[test]
fn a_fillet_tighter_than_the_ball_is_traced_where_the_ball_touches_floor_and_wall() {
    let job = pencil_job(6.0);
    let out = job::run(&job, filleted_pocket(1.0), &mut Progress::none()).unwrap();
    clean(&out);
    let (points, length) = along_the_floor(&out);
    let off = |p: DVec2| {
        let d = DVec2::new((p.x - 25.0).abs(), (p.y - 25.0).abs());
        // From the square of half-side 12 about the pocket's centre.
        if d.x <= 12.0 && d.y <= 12.0 {
            (12.0 - d.x).min(12.0 - d.y)
        } else {
            (d - DVec2::splat(12.0)).max(DVec2::ZERO).length()
        }
    };
    // Every point of the line has the pass within 0.06 of it (half the grid, and the walls'
    // slope across one of the part's samples)...
    for k in 0..=480 {
        let t = 13.0 + 24.0 * (k % 120) as f64 / 120.0;
        let q = [DVec2::new(t, 13.0), DVec2::new(37.0, t), DVec2::new(50.0 - t, 37.0), DVec2::new(13.0, 50.0 - t)][k / 120 % 4];
        let near = points.iter().map(|p| p.distance(q)).fold(f64::INFINITY, f64::min);
        assert!(near <= 0.06, "the pass {near:.3} from the corner line at {q}");
    }
    // ... and nothing at the floor strays from it by more than a link between two corner
    // lines where they meet (the walls' and the mitre's up the pocket's corner).
    let worst = points.iter().map(|&p| off(p)).fold(0.0, f64::max);
    assert!(worst <= 0.25, "a point at the floor {worst:.3} off the line");
    assert!(length > 0.95 * 4.0 * 24.0, "{length:.1} mm of pass at the floor, of 96");
    rs274(&out.gcode, &job.tools);
}

/// A fillet of radius 5 under the same ball: the ball rolls round it with one contact, and
/// no pencil pass runs along the walls (only along the mitres where two fillets meet at the
/// pocket's corners).
#[test]
fn a_fillet_wider_than_the_ball_needs_no_pencil_pass_along_it() {
    let job = pencil_job(6.0);
    let out = job::run(&job, filleted_pocket(5.0), &mut Progress::none()).unwrap();
    clean(&out);
    let mut cut = 0;
    for m in out.moves.iter().filter(|m| !m.mv.is_rapid()) {
        let p = m.mv.to().truncate();
        assert!((p.x - 25.0).abs() > 6.0 && (p.y - 25.0).abs() > 6.0, "a pencil pass beside a wall at {p}");
        cut += 1;
    }
    eprintln!("{cut} feed moves, all near the pocket's corners");
}

/// Two parallel passes either side, 0.5 apart: on the floor beside the radius-1 fillet the
/// ball's tip runs 3.5 and 4 in from the walls as well as 3 (the surface is flat there, so the
/// distance across it is the plan's), all the way along each side; clean, read by rs274.
#[test]
fn parallel_passes_run_a_step_over_apart_beside_the_corner() {
    let mut job = pencil_job(6.0);
    job.operations = vec![Operation::FinishPencil(FinishPencil { passes: 2, stepover: Some(0.5), ..FinishPencil::default() })];
    let out = job::run(&job, filleted_pocket(1.0), &mut Progress::none()).unwrap();
    clean(&out);
    let (points, _) = along_the_floor(&out);
    for inset in [3.0, 3.5, 4.0] {
        // Along the middle of each side, away from the pocket's corners.
        for k in 0..=160 {
            let t = 17.0 + 16.0 * (k % 40) as f64 / 40.0;
            let (a, b) = (10.0 + inset, 40.0 - inset);
            let q = [DVec2::new(t, a), DVec2::new(b, t), DVec2::new(t, b), DVec2::new(a, t)][k / 40 % 4];
            let near = points.iter().map(|p| p.distance(q)).fold(f64::INFINITY, f64::min);
            assert!(near <= 0.08, "no pass within {near:.3} of {q}, {inset} in from the walls");
        }
    }
    // And none on the floor farther in than the last one.
    let farthest = points.iter().map(|p| (p.x - 10.0).min(40.0 - p.x).min(p.y - 10.0).min(40.0 - p.y)).fold(0.0, f64::max);
    assert!(farthest <= 4.1, "a pass {farthest:.2} in from the walls");
    rs274(&out.gcode, &job.tools);
}
