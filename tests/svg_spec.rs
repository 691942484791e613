//! Issue 56: an SVG means what SVG's rules say, as the renderers people check drawings in draw
//! it. Each generated drawing is read by swarf and rendered by resvg; the region swarf's loops
//! enclose must be the one resvg fills (its area and its bounds, to the pixel), and its size the
//! one the file states. The cases: a width with no height, a viewBox of another aspect (SVG
//! scales uniformly), units on shapes' attributes, a nested `<svg>` with its viewBox and place,
//! shapes hidden by CSS, `display` or `visibility`, `<use>`, and a negative width (refused).

use swarf::drawing::import::read_drawing;
use swarf::drawing::{Drawing, Shape};
use swarf::geom::Tolerances;

const MM_PER_PX: f64 = 25.4 / 96.0;
/// Pixels of resvg's rendering per px of the drawing.
const ZOOM: f32 = 4.0;

fn read(svg: &str) -> Drawing {
    read_drawing(svg.as_bytes(), Some("case.svg"), &Tolerances::default()).unwrap_or_else(|e| panic!("{e}\n{svg}"))
}

/// What resvg fills: its area (mm², from the pixels' coverage) and bounds (mm, y up as swarf
/// reads the drawing), with the size of a pixel (mm).
fn rendered(svg: &str) -> (f64, [f64; 4], f64) {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).unwrap();
    let size = tree.size();
    let (w, h) = ((size.width() * ZOOM).ceil() as u32, (size.height() * ZOOM).ceil() as u32);
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).unwrap();
    resvg::render(&tree, resvg::tiny_skia::Transform::from_scale(ZOOM, ZOOM), &mut pixmap.as_mut());
    let pixel = MM_PER_PX / f64::from(ZOOM);
    let (mut covered, mut b) = (0.0, [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY]);
    for (k, p) in pixmap.pixels().iter().enumerate() {
        if p.alpha() == 0 {
            continue;
        }
        covered += f64::from(p.alpha()) / 255.0;
        let (i, j) = ((k as u32 % w) as f64, (k as u32 / w) as f64);
        b = [b[0].min(i * pixel), b[1].max((i + 1.0) * pixel), b[2].min(-(j + 1.0) * pixel), b[3].max(-j * pixel)];
    }
    (covered * pixel * pixel, b, pixel)
}

/// swarf's region and resvg's pixels agree; returns swarf's bounds (mm).
fn agrees(svg: &str) -> [f64; 4] {
    let d = read(svg);
    let shape = Shape::new(d.loops.iter().map(|l| l.path.clone()).collect());
    let r = shape.bounds();
    let (area, b, pixel) = rendered(svg);
    let ours = shape.area();
    // Antialiased edges: within a tenth of a pixel along the outlines.
    let slack = shape.length() * pixel * 0.1 + 1e-6;
    assert!((ours - area).abs() <= slack, "area {ours:.4} mm² read, {area:.4} mm² rendered (±{slack:.4})\n{svg}");
    let ours_b = [r.min.x, r.max.x, r.min.y, r.max.y];
    for k in 0..4 {
        assert!((ours_b[k] - b[k]).abs() <= 1.01 * pixel, "bounds {ours_b:?} read, {b:?} rendered\n{svg}");
    }
    ours_b
}

fn size_of(b: [f64; 4]) -> (f64, f64) {
    (b[1] - b[0], b[3] - b[2])
}

fn near(a: (f64, f64), b: (f64, f64)) -> bool {
    (a.0 - b.0).abs() < 1e-3 && (a.1 - b.1).abs() < 1e-3
}

const NS: &str = "xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\"";

#[test]
fn the_sizes_an_svg_states_are_its_sizes() {
    // The reference: mm on the root with a viewBox of the same aspect.
    let b = agrees(&format!(r#"<svg {NS} width="100mm" height="60mm" viewBox="0 0 100 60"><rect x="10" y="5" width="80" height="50"/></svg>"#));
    assert!(near(size_of(b), (80.0, 50.0)), "{b:?}");
    // A width alone: the height follows the viewBox's aspect (not 96 dpi).
    let b = agrees(&format!(r#"<svg {NS} width="100mm" viewBox="0 0 100 60"><rect x="10" y="5" width="80" height="50"/></svg>"#));
    assert!(near(size_of(b), (80.0, 50.0)), "{b:?}");
    // A square viewport over a 100 × 60 viewBox: scaled uniformly (meet), centred.
    let b = agrees(&format!(r#"<svg {NS} width="100mm" height="100mm" viewBox="0 0 100 60"><rect x="10" y="5" width="80" height="50"/></svg>"#));
    assert!(near(size_of(b), (80.0, 50.0)), "{b:?}");
    // … unless it asks to be stretched.
    let b = agrees(&format!(r#"<svg {NS} width="100mm" height="100mm" viewBox="0 0 100 60" preserveAspectRatio="none"><rect x="10" y="5" width="80" height="50"/></svg>"#));
    assert!(near(size_of(b), (80.0, 50.0 * 100.0 / 60.0)), "{b:?}");
    // Units on a shape's own attributes, in a px drawing.
    let b = agrees(&format!(r#"<svg {NS} width="400" height="300"><rect x="5mm" y="5mm" width="80mm" height="50mm"/></svg>"#));
    assert!(near(size_of(b), (80.0, 50.0)), "{b:?}");
    let b = agrees(&format!(r#"<svg {NS} width="400" height="300" viewBox="0 0 400 300"><circle cx="50" cy="50" r="5mm"/></svg>"#));
    assert!(near(size_of(b), (10.0, 10.0)), "{b:?}");
}

#[test]
fn a_nested_svg_is_placed_and_scaled_by_its_own_viewbox() {
    // A 10 × 10 viewBox drawn 50 × 50 at x 100: its 8 × 8 square is 40 × 40, at 105 (mm, as the
    // root is in mm); beside the root's own square, not a hole in it.
    let svg = format!(
        r#"<svg {NS} width="200mm" height="100mm" viewBox="0 0 200 100"><rect x="10" y="10" width="60" height="60"/><svg x="100" y="10" width="50" height="50" viewBox="0 0 10 10"><rect x="1" y="1" width="8" height="8"/></svg></svg>"#
    );
    let b = agrees(&svg);
    assert!(near(size_of(b), (145.0 - 10.0, 60.0)), "{b:?}");
    let d = read(&svg);
    assert_eq!(d.loops.len(), 2);
    let shape = Shape::new(d.loops.iter().map(|l| l.path.clone()).collect());
    assert!((shape.area() - (3600.0 + 1600.0)).abs() < 1e-3, "{}", shape.area());
}

#[test]
fn hidden_shapes_are_not_drawn_and_used_ones_are() {
    // Hidden three ways: by a class in a style sheet, by `display`, by `visibility`.
    let svg = format!(
        r#"<svg {NS} width="100mm" height="100mm" viewBox="0 0 100 100"><style>.gone {{ display: none }}</style><rect x="10" y="10" width="80" height="80"/><circle class="gone" cx="30" cy="30" r="5"/><circle display="none" cx="50" cy="50" r="5"/><circle visibility="hidden" cx="70" cy="70" r="5"/></svg>"#
    );
    agrees(&svg);
    let d = read(&svg);
    assert_eq!(d.loops.len(), 1, "only the square: {:?}", d.loops.iter().map(|l| l.path.bounds()).collect::<Vec<_>>());
    // A circle defined once and used three times: three holes.
    let svg = format!(
        r##"<svg {NS} width="100mm" height="100mm" viewBox="0 0 100 100"><defs><circle id="c" r="5"/></defs><rect x="10" y="10" width="80" height="80" fill="none" stroke="black"/><use xlink:href="#c" x="30" y="50"/><use href="#c" x="50" y="50"/><use href="#c" x="70" y="50"/></svg>"##
    );
    let d = read(&svg);
    let holes = swarf::holes::in_drawing(&d, 0.0, -6.0);
    assert_eq!(holes.len(), 3, "{holes:?}");
    for h in &holes {
        // Circles come out as the circles they are, not as the Béziers usvg draws them with.
        assert!((h.diameter - 10.0).abs() < 1e-4, "{h:?}");
    }
}

#[test]
fn circles_and_arcs_are_exact_arcs() {
    // A φ20 circle, an arc in a path, a rounded rect: every piece an arc on the true circle.
    let svg = format!(r#"<svg {NS} width="100mm" height="100mm" viewBox="0 0 100 100"><circle cx="50" cy="50" r="10"/></svg>"#);
    let d = read(&svg);
    assert_eq!(d.loops.len(), 1);
    let l = &d.loops[0].path;
    let c = l.bounds().center();
    for s in l.segments() {
        assert!(s.bulge != 0.0, "a line in a circle: {s:?}");
        for p in [s.a, s.b, s.midpoint()] {
            assert!((p.distance(c) - 10.0).abs() < 1e-4, "{p:?} is {} from the centre", p.distance(c));
        }
    }
    assert!((l.area().abs() - std::f64::consts::PI * 100.0).abs() < 1e-3, "{}", l.area());
    agrees(&svg);
    let svg = format!(r#"<svg {NS} width="100mm" height="100mm" viewBox="0 0 100 100"><path d="M 20 50 A 30 30 0 0 1 80 50 Z"/><rect x="10" y="60" width="80" height="30" rx="6"/></svg>"#);
    let d = read(&svg);
    agrees(&svg);
    let arcs: usize = d.loops.iter().map(|l| l.path.segments().filter(|s| s.bulge != 0.0).count()).sum();
    assert!(arcs >= 5, "{arcs} arcs");
}

#[test]
fn a_negative_size_is_refused_by_name() {
    let e = read_drawing(format!(r#"<svg {NS} width="-100mm" height="60mm" viewBox="0 0 100 60"><rect width="80" height="50"/></svg>"#).as_bytes(), Some("neg.svg"), &Tolerances::default())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(e.contains("SVG") && e.contains("size"), "{e}");
}
