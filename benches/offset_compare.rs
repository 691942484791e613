//! swarf's offsetter (seed 003) against cavalier_contours, side by side in one run on the same
//! inputs: time ratio, and whether both agree on area, length and loop count. Then a random
//! corpus of 10,000 shapes, every result of both checked by `offset::check::problems`.
//!
//! `cargo bench --bench offset_compare` (add `-- quick` for fewer repetitions).

use std::time::Instant;

use cavalier_contours::polyline::{PlineSource, PlineSourceMut, Polyline};
use cavalier_contours::shape_algorithms::Shape as CavShape;
use swarf::drawing::{Loop, Shape, Vertex};
use swarf::geom::{DVec2, Tolerances};
use swarf::offset::check::{problems, random_shape, star, Rng};
use swarf::offset::offset;

fn to_cav(shape: &Shape) -> CavShape<f64> {
    let plines = shape.loops.iter().map(|l| {
        let mut p = Polyline::new_closed();
        for v in &l.vertices {
            p.add(v.p.x, v.p.y, v.bulge);
        }
        p
    });
    CavShape::from_plines(plines)
}

fn from_cav(shape: &CavShape<f64>) -> Shape {
    let loops =
        shape.ccw_plines.iter().chain(shape.cw_plines.iter()).map(|ip| Loop { vertices: ip.polyline.iter_vertexes().map(|v| Vertex { p: DVec2::new(v.x, v.y), bulge: v.bulge }).collect() }).collect();
    Shape::from_oriented(loops)
}

/// cavalier_contours offsets a counter-clockwise loop inwards for a positive distance.
fn cav_offset(shape: &CavShape<f64>, d: f64) -> CavShape<f64> {
    shape.parallel_offset(-d, &Default::default())
}

fn time<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = f();
    for _ in 0..reps {
        let t = Instant::now();
        out = f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    (best, out)
}

fn cases() -> Vec<(String, Shape, Vec<f64>)> {
    let mut cases = Vec::new();
    let radii: Vec<f64> = (0..2000).map(|k| if k % 2 == 0 { 100.0 } else { 80.0 }).collect();
    cases.push(("star, 2000 lines".to_string(), Shape::new(vec![star(DVec2::ZERO, &radii, &[], 0.0)]), vec![-1.0, -5.0, 0.2, 1.0, 5.0]));
    // 667 spikes whose tips are arcs: valley, tip start, arc cap to tip end (2001 entities).
    let mut capped = Vec::new();
    for k in 0..667 {
        let th = std::f64::consts::TAU * k as f64 / 667.0;
        let w = std::f64::consts::TAU / 667.0 / 6.0;
        capped.push(Vertex { p: DVec2::from_angle(th) * 80.0, bulge: 0.0 });
        capped.push(Vertex { p: DVec2::from_angle(th + 2.0 * w) * 100.0, bulge: 0.4 });
        capped.push(Vertex { p: DVec2::from_angle(th + 4.0 * w) * 100.0, bulge: 0.0 });
    }
    cases.push(("star with arc caps".to_string(), Shape::new(vec![Loop { vertices: capped }]), vec![-1.0, -5.0, 0.2, 1.0, 5.0]));
    let k = (std::f64::consts::TAU / 2000.0 / 4.0).tan();
    let circle = star(DVec2::ZERO, &vec![100.0; 2000], &[k], 0.0);
    cases.push(("circle of 2000 arcs".to_string(), Shape::new(vec![circle]), vec![-1.0, -50.0, 1.0, 50.0]));
    let mut plate = vec![DVec2::new(0.0, 0.0), DVec2::new(410.0, 0.0), DVec2::new(410.0, 100.0)];
    for s in (0..20).rev() {
        let x = 10.0 + s as f64 * 20.0;
        plate.extend([DVec2::new(x + 3.0, 100.0), DVec2::new(x + 3.0, 40.0), DVec2::new(x, 40.0), DVec2::new(x, 100.0)]);
    }
    plate.push(DVec2::new(0.0, 100.0));
    cases.push(("plate, 20 slots 3 wide".to_string(), Shape::new(vec![Loop::polygon(&plate)]), vec![-1.0, -3.0, 1.0, 2.0, 6.0]));
    for (name, path) in [("tm_LM2.dxf", "../shared/data/profiles/tm_LM2.dxf"), ("tm_1002_tray_bottom.dxf", "../shared/data/profiles/tm_1002_tray_bottom.dxf")] {
        match std::fs::read(path).ok().and_then(|b| swarf::drawing::import::read_drawing(&b, Some(name), &Tolerances::default()).ok()) {
            Some(drawing) => match drawing.shape(&[]) {
                Ok(shape) => cases.push((name.to_string(), shape, vec![-1.0, -3.0, 1.0, 3.0])),
                Err(e) => println!("{name}: {e}"),
            },
            None => println!("{path}: not found or not readable; skipped"),
        }
    }
    cases
}

fn main() {
    let quick = std::env::args().any(|a| a == "quick");
    let reps = if quick { 2 } else { 10 };
    let tol = Tolerances::default();
    println!("| input | entities | d | swarf ms | cavalier ms | ratio | area swarf / cavalier | loops | agree |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let (mut ours_total, mut theirs_total) = (0.0, 0.0);
    for (name, shape, distances) in cases() {
        let cav = to_cav(&shape);
        let entities: usize = shape.loops.iter().map(|l| l.len()).sum();
        for d in distances {
            let (t_ours, ours) = time(reps, || offset(&shape, d, &tol));
            let (t_cav, theirs) = time(reps, || cav_offset(&cav, d));
            let theirs = from_cav(&theirs);
            ours_total += t_ours;
            theirs_total += t_cav;
            let agree = (ours.area() - theirs.area()).abs() <= 1e-6 * ours.area().abs().max(1.0)
                && (ours.length() - theirs.length()).abs() <= 1e-6 * ours.length().max(1.0)
                && ours.loops.len() == theirs.loops.len();
            println!(
                "| {name} | {entities} | {d} | {:.3} | {:.3} | {:.2} | {:.3} / {:.3} | {} / {} | {} |",
                t_ours * 1e3,
                t_cav * 1e3,
                t_ours / t_cav,
                ours.area(),
                theirs.area(),
                ours.loops.len(),
                theirs.loops.len(),
                if agree { "yes" } else { "NO" }
            );
        }
    }
    println!("total: swarf {:.1} ms, cavalier_contours {:.1} ms, ratio {:.2}", ours_total * 1e3, theirs_total * 1e3, ours_total / theirs_total);

    let count = if quick { 1000 } else { 10_000 };
    let mut rng = Rng::new(42);
    let (mut shapes, mut bad_ours, mut bad_theirs, mut disagree) = (0, 0, 0, 0);
    let (mut t_ours, mut t_theirs) = (0.0, 0.0);
    let mut first_bad = None;
    while shapes < count {
        let Some(shape) = random_shape(&mut rng) else { continue };
        let d = if rng.next_f64() < 0.5 { -rng.range(0.05, 8.0) } else { rng.range(0.05, 8.0) };
        shapes += 1;
        let t = Instant::now();
        let ours = offset(&shape, d, &tol);
        t_ours += t.elapsed().as_secs_f64();
        let cav = to_cav(&shape);
        let t = Instant::now();
        let theirs = cav_offset(&cav, d);
        t_theirs += t.elapsed().as_secs_f64();
        let theirs = from_cav(&theirs);
        let p = problems(&shape, d, &ours, 1e-6, 4);
        if !p.is_empty() {
            bad_ours += 1;
            first_bad.get_or_insert((shapes, d, p));
        }
        bad_theirs += (!problems(&shape, d, &theirs, 1e-6, 4).is_empty()) as usize;
        disagree += ((ours.area() - theirs.area()).abs() > 1e-6 * ours.area().abs().max(1.0)) as usize;
    }
    println!(
        "random corpus: {shapes} shapes; invalid results: swarf {bad_ours}, cavalier_contours {bad_theirs}; area disagreements {disagree}; time swarf {:.0} ms, cavalier {:.0} ms (ratio {:.2})",
        t_ours * 1e3,
        t_theirs * 1e3,
        t_ours / t_theirs
    );
    if let Some((k, d, p)) = first_bad {
        println!("first invalid swarf result: shape {k}, d = {d}: {p:?}");
    }
}
