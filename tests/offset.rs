//! The offsetter (seed 003) against exact answers and its properties: every result is closed,
//! free of self-crossings, oriented by its nesting, at the distance from the input everywhere,
//! and covers exactly the offset region; reversed, restarted, moved and turned inputs give the
//! same shape. Random shapes come from proptest and from the corpus the benchmark uses.

use std::f64::consts::PI;

use proptest::prelude::*;
use swarf::drawing::{Loop, Shape, Vertex};
use swarf::geom::{DVec2, Tolerances};
use swarf::offset::check::{problems, random_shape, shape_from_bytes, star, Rng};
use swarf::offset::offset;

const TOL: f64 = 1e-6;

fn tol() -> Tolerances {
    Tolerances::default()
}

fn assert_valid(input: &Shape, d: f64) -> Shape {
    let out = offset(input, d, &tol());
    let p = problems(input, d, &out, TOL, 8);
    assert!(p.is_empty(), "offset by {d}: {p:?}\ninput: {input:?}\noutput: {out:?}");
    out
}

/// Area, length and loop count: what "the same shape" means for metamorphic checks.
fn measure(s: &Shape) -> (f64, f64, usize) {
    (s.area(), s.length(), s.loops.len())
}

fn same(a: (f64, f64, usize), b: (f64, f64, usize)) -> bool {
    (a.0 - b.0).abs() <= 1e-6 * a.0.abs().max(1.0) && (a.1 - b.1).abs() <= 1e-6 * a.1.max(1.0) && a.2 == b.2
}

#[test]
fn exact_areas() {
    // Convex polygon grown by d: A + P·d + πd². Rectangle shrunk: (w − 2d)(h − 2d).
    let rect = Shape::new(vec![Loop::rect(DVec2::new(-3.0, 1.0), DVec2::new(17.0, 9.0))]);
    for d in [0.1, 1.0, 3.9] {
        let grown = assert_valid(&rect, d);
        assert!((grown.area() - (160.0 + 56.0 * d + PI * d * d)).abs() < 1e-9);
        let shrunk = assert_valid(&rect, -d);
        assert!((shrunk.area() - (20.0 - 2.0 * d) * (8.0 - 2.0 * d)).abs() < 1e-9);
    }
    assert!(offset(&rect, -4.0, &tol()).is_empty());
    let hexagon = Shape::new(vec![star(DVec2::new(2.0, -1.0), &[5.0; 6], &[], 0.3)]);
    let (a, p) = (hexagon.area(), hexagon.length());
    for d in [0.5, 2.0, 10.0] {
        assert!((assert_valid(&hexagon, d).area() - (a + p * d + PI * d * d)).abs() < 1e-8);
    }
}

#[test]
fn arcs_collapse_and_reverse() {
    // A slot (two half circles of radius 3 joined by lines): shrinking by 3 leaves nothing,
    // by 2 a slot of radius 1; growing by 2 a slot of radius 5. A rounded-corner square
    // shrunk past its corner radius gets sharp corners (the arcs reverse and are trimmed).
    let slot = Shape::new(vec![Loop {
        vertices: vec![
            Vertex { p: DVec2::new(0.0, -3.0), bulge: 0.0 },
            Vertex { p: DVec2::new(10.0, -3.0), bulge: 1.0 },
            Vertex { p: DVec2::new(10.0, 3.0), bulge: 0.0 },
            Vertex { p: DVec2::new(0.0, 3.0), bulge: 1.0 },
        ],
    }]);
    let area = |r: f64| 10.0 * 2.0 * r + PI * r * r;
    assert!((assert_valid(&slot, -2.0).area() - area(1.0)).abs() < 1e-9);
    assert!((assert_valid(&slot, 2.0).area() - area(5.0)).abs() < 1e-9);
    assert!(offset(&slot, -3.0, &tol()).area().abs() < 1e-6);
    let k = (PI / 8.0).tan();
    let rounded = Shape::new(vec![Loop {
        vertices: vec![
            Vertex { p: DVec2::new(1.0, 0.0), bulge: 0.0 },
            Vertex { p: DVec2::new(9.0, 0.0), bulge: k },
            Vertex { p: DVec2::new(10.0, 1.0), bulge: 0.0 },
            Vertex { p: DVec2::new(10.0, 9.0), bulge: k },
            Vertex { p: DVec2::new(9.0, 10.0), bulge: 0.0 },
            Vertex { p: DVec2::new(1.0, 10.0), bulge: k },
            Vertex { p: DVec2::new(0.0, 9.0), bulge: 0.0 },
            Vertex { p: DVec2::new(0.0, 1.0), bulge: k },
        ],
    }]);
    let shrunk = assert_valid(&rounded, -2.5);
    assert!((shrunk.area() - 25.0).abs() < 1e-9, "{}", shrunk.area());
    assert_eq!(shrunk.loops[0].len(), 4);
}

#[test]
fn islands_merge_with_each_other_and_the_boundary() {
    // Two round islands 6 apart in a 40 × 20 pocket: shrinking by 1.9 keeps them apart, by 3.5
    // merges them (their 7 mm grown discs overlap), by 5 the grown islands reach the long walls
    // and split the region in two.
    let pocket = Shape::new(vec![Loop::rect(DVec2::ZERO, DVec2::new(40.0, 20.0)), Loop::circle(DVec2::new(17.0, 10.0), 1.0), Loop::circle(DVec2::new(23.0, 10.0), 1.0)]);
    assert_eq!(assert_valid(&pocket, -1.9).loops.len(), 3);
    assert_eq!(assert_valid(&pocket, -3.5).loops.len(), 2);
    let split = assert_valid(&pocket, -5.0);
    assert_eq!(split.loops.len(), 2);
    assert!(split.loops.iter().all(|l| l.is_ccw()));
}

#[test]
fn narrow_slot_closes_when_the_tool_is_wider() {
    // A plate with a 4 mm slot cut into it from the side, offset as an outside profile.
    let plate = Shape::new(vec![Loop::polygon(&[
        DVec2::new(0.0, 0.0),
        DVec2::new(30.0, 0.0),
        DVec2::new(30.0, 20.0),
        DVec2::new(17.0, 20.0),
        DVec2::new(17.0, 5.0),
        DVec2::new(13.0, 5.0),
        DVec2::new(13.0, 20.0),
        DVec2::new(0.0, 20.0),
    ])]);
    let thin = assert_valid(&plate, 1.5);
    assert_eq!(thin.loops.len(), 1);
    let wide = assert_valid(&plate, 2.5);
    assert_eq!(wide.loops.len(), 1);
    // The 2.5 offset bridges the slot: only its mouth's round corners remain.
    assert!(wide.loops[0].len() < thin.loops[0].len());
    // Inward: the band below the slot is 5 mm tall, so shrinking by 2.6 splits the part in two.
    assert_eq!(assert_valid(&plate, -2.6).loops.len(), 2);
}

#[test]
fn metamorphic_variants_give_the_same_shape() {
    let mut rng = Rng::new(7);
    let mut tried = 0;
    while tried < 40 {
        let Some(shape) = random_shape(&mut rng) else { continue };
        tried += 1;
        let d = rng.range(-6.0, 6.0);
        let base = measure(&offset(&shape, d, &tol()));
        // Each variant: every loop changed alike, offset, compared with the base.
        let check = |what: &str, change: &dyn Fn(&Loop) -> Loop| {
            let variant = Shape::new(shape.loops.iter().map(change).collect());
            assert!(same(base, measure(&offset(&variant, d, &tol()))), "{what}, d = {d}");
        };
        check("reversed", &|l| l.reversed());
        for k in 1..shape.loops[0].len().min(6) {
            check(&format!("start {k}"), &|l| l.rotate_start(k));
        }
        check("moved", &|l| l.translated(DVec2::new(1234.5, -987.25)));
        check("turned", &|l| l.rotated(0.7));
    }
}

#[test]
fn random_corpus_is_valid() {
    let mut rng = Rng::new(2026);
    let mut checked = 0;
    while checked < 300 {
        let Some(shape) = random_shape(&mut rng) else { continue };
        for d in [rng.range(-8.0, -0.05), rng.range(0.05, 8.0)] {
            assert_valid(&shape, d);
        }
        checked += 1;
    }
}

/// Every input the fuzz target (`cargo fuzz run offset`) shrank to a failure, kept in
/// `tests/fuzz_regressions/offset-*.bin` and decoded as the target decodes it.
#[test]
fn kept_fuzz_failures() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with("offset-") {
            if let Some((shape, d)) = shape_from_bytes(&std::fs::read(&path).unwrap()) {
                assert_valid(&shape, d);
            }
        }
    }
}

fn shape_strategy() -> impl Strategy<Value = Shape> {
    (3usize..24, any::<u64>()).prop_filter_map("not simple", |(n, seed)| {
        let mut rng = Rng::new(seed);
        let radii: Vec<f64> = (0..n).map(|_| rng.range(4.0, 20.0)).collect();
        let bulges: Vec<f64> = (0..n).map(|_| if rng.next_f64() < 0.5 { rng.range(-0.5, 0.5) } else { 0.0 }).collect();
        let shape = Shape::new(vec![star(DVec2::ZERO, &radii, &bulges, 0.0)]);
        swarf::offset::check::self_crossings(&shape, 1e-9, 1e-8).is_empty().then_some(shape)
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn every_offset_is_valid(shape in shape_strategy(), d in -10.0f64..10.0) {
        prop_assume!(d.abs() > 1e-3);
        let out = offset(&shape, d, &tol());
        let p = problems(&shape, d, &out, TOL, 6);
        prop_assert!(p.is_empty(), "{:?}", p);
    }
}

/// A z-level roughing's region on a part's 0.5 mm grid (pycam_textbox's pocket at Z−2: its
/// outline a staircase of half-millimetre steps round the corners), shrunk every 0.2 mm: at
/// 4.8 mm, a multiple of the steps, three offset entities met within 2e-5 mm at each of its
/// four corners, the slivers between them broke the stitching, and the offset came out empty:
/// the roughing cut two rings of the pocket and took the rest for cleared.
#[test]
fn a_staircase_offset_by_a_multiple_of_its_step_keeps_its_loop() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions/staircase-region.json");
    let shape: Shape = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut last = shape.area();
    for k in 1..=60 {
        let d = 0.2 * k as f64;
        let out = assert_valid(&shape, -d);
        assert!(out.area() > 0.0 && out.area() < last, "offset by −{d}: area {} after {last}", out.area());
        last = out.area();
    }
}
