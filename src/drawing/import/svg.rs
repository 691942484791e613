//! SVG, read to SVG's own rules by `usvg` (the resvg project's simplifier, as the renderers
//! people check drawings in read it): CSS, units on every attribute, the viewBox with
//! `preserveAspectRatio`, nested `<svg>`, `<use>`, transforms and visibility become plain paths
//! in the document's px (96 per inch). swarf keeps the geometry: each path after its transform
//! becomes lines and arcs within tolerance, a Bézier that is a circular arc's (usvg draws
//! circles, rounded corners and path arcs so) taken as that arc exactly; y is flipped so the
//! drawing reads as on screen.
//!
//! Before usvg, a walk of the XML (roxmltree's, with svgtypes for its numbers) refuses what no
//! drawing holds, naming its line (nesting past any drawing, numbers and arcs past any
//! machine), says what is left out (shapes whose sizes are ≤ 0 or not numbers, text, images),
//! and names the layers (Inkscape's labels).

use std::str::FromStr;

use glam::DAffine2;
use roxmltree::Node;
use svgtypes::{Length, LengthUnit, PointsParser, SimplePathSegment, SimplifyingPathParser, Transform};

use super::{DrawingError, Pieces};
use crate::drawing::arcfit::fit_arcs;
use crate::geom::segment::Segment;
use crate::geom::{DVec2, Tolerances};

const MM_PER_PX: f64 = 25.4 / 96.0;

fn mm_per(unit: LengthUnit) -> Option<f64> {
    match unit {
        LengthUnit::None | LengthUnit::Px => Some(MM_PER_PX),
        LengthUnit::Mm => Some(1.0),
        LengthUnit::Cm => Some(10.0),
        LengthUnit::In => Some(25.4),
        LengthUnit::Pt => Some(25.4 / 72.0),
        LengthUnit::Pc => Some(25.4 / 6.0),
        _ => None,
    }
}

fn length_mm(text: Option<&str>) -> Option<f64> {
    let l = Length::from_str(text?).ok()?;
    Some(l.number * mm_per(l.unit)?)
}

fn number(node: &Node, name: &str) -> f64 {
    node.attribute(name).and_then(|t| Length::from_str(t).ok()).map(|l| l.number).filter(|v| v.is_finite()).unwrap_or(0.0)
}

/// Whether each of `names` is absent (0 by SVG's rules) or a finite number: an element with one
/// that is not is left out, and counted.
fn readable(node: &Node, names: &[&str]) -> bool {
    names.iter().all(|&name| node.attribute(name).is_none_or(|t| Length::from_str(t).is_ok_and(|l| l.number.is_finite())))
}

/// The walk of the XML before usvg: refusals, what is left out, and the layers' names.
struct Reader<'d> {
    pieces: Pieces,
    doc: &'d roxmltree::Document<'d>,
    /// Each named group's id, with the layer it names (its `inkscape:label`, or the id of an
    /// Inkscape layer).
    layers: std::collections::HashMap<String, String>,
    /// Each element's id, with the line it starts on.
    lines: std::collections::HashMap<String, usize>,
}

pub(crate) fn read_svg(bytes: &[u8], tol: &Tolerances) -> Result<Pieces, DrawingError> {
    let text = std::str::from_utf8(bytes).map_err(|_| DrawingError::Svg("not UTF-8 text".into()))?;
    // A DOCTYPE line (matplotlib writes one) is read; nothing it names is fetched (no entity
    // resolver: an external entity is dropped), and the parser keeps its guard against
    // entity expansion bombs.
    let options = roxmltree::ParsingOptions { allow_dtd: true, nodes_limit: 20_000_000, ..roxmltree::ParsingOptions::default() };
    let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| DrawingError::Svg(e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" {
        return Err(DrawingError::Svg(format!("the root element is <{}>, not <svg>", root.tag_name().name())));
    }
    // The walk: at 96 px per inch, the root's viewBox scaled to its size (near enough to refuse
    // what is past any machine; usvg sizes the drawing).
    let (view_box, bad_view_box) = match view_box_of(&root) {
        Ok(vb) => (vb, false),
        Err(()) => (None, true),
    };
    let mut to_mm = DAffine2::from_scale(DVec2::new(MM_PER_PX, -MM_PER_PX));
    if let Some(vb) = view_box {
        let w = length_mm(root.attribute("width")).unwrap_or(vb[2] * MM_PER_PX);
        let h = length_mm(root.attribute("height")).unwrap_or(vb[3] * MM_PER_PX);
        to_mm = DAffine2::from_scale(DVec2::new(w / vb[2], -h / vb[3])) * DAffine2::from_translation(DVec2::new(-vb[0], -vb[1]));
    }
    let mut reader = Reader { pieces: Pieces::default(), doc: &doc, layers: Default::default(), lines: Default::default() };
    if bad_view_box {
        reader.pieces.ignore("viewBox that is not four numbers with a positive width and height (the drawing read at 96 px per inch)");
    }
    reader.walk(root, to_mm, "0", 1)?;
    reader.pieces.check_size()?;
    let Reader { pieces: walked, layers, lines, .. } = reader;

    // usvg's reading: every href to an image resolved to nothing (nothing is ever fetched or
    // read from disk). Every field is given: usvg's default resolvers (which decode images and
    // read files) are never made, and stay out of the wasm.
    let opt = usvg::Options {
        resources_dir: None,
        dpi: 96.0,
        font_family: String::new(),
        font_size: 12.0,
        languages: Vec::new(),
        shape_rendering: usvg::ShapeRendering::default(),
        text_rendering: usvg::TextRendering::default(),
        image_rendering: usvg::ImageRendering::default(),
        default_size: usvg::Size::from_wh(100.0, 100.0).expect("a size"),
        image_href_resolver: usvg::ImageHrefResolver { resolve_data: Box::new(|_, _, _| None), resolve_string: Box::new(|_, _| None) },
        style_sheet: None,
    };
    let tree = usvg::Tree::from_xmltree(&doc, &opt).map_err(|e| DrawingError::Svg(e.to_string()))?;
    let size = tree.size();
    // Millimetres per user unit of the root (its viewBox's, uniformly scaled unless it asks
    // otherwise): what "units: as the file says" keeps.
    let (w_mm, h_mm) = (f64::from(size.width()) * MM_PER_PX, f64::from(size.height()) * MM_PER_PX);
    let (units, scale) = match view_box {
        Some(vb) => (format!("viewBox scaled to {w_mm:.3} × {h_mm:.3} mm"), aspect_scale(root.attribute("preserveAspectRatio").unwrap_or(""), w_mm / vb[2], h_mm / vb[3])),
        None => ("px (96 per inch)".to_string(), MM_PER_PX),
    };
    let mut paths = Paths { tol, pieces: Pieces { units, scale, ignored: walked.ignored, ..Pieces::default() }, layers: &layers, lines: &lines, size: f64::from(size.width().max(size.height())) };
    // The transforms are composed here in f64 from each group's own (usvg keeps f32), the
    // root's viewBox mapping worked out again in f64 where it is the plain one: a drawing in
    // mm stays exact to the micron's thousandth, not to f32's 1e-7 of its size.
    let root = to_f64(tree.root().transform());
    paths.group(tree.root(), DAffine2::from_scale(DVec2::new(MM_PER_PX, -MM_PER_PX)) * root, "0", viewport(&root_el_facts(&doc), size))?;
    Ok(paths.pieces)
}

/// What the root `<svg>` says of its viewport: its width and height (px) where given in
/// absolute units, its viewBox, and its `preserveAspectRatio`; `None` where it has a
/// transform of its own or sizes in percent (usvg's f32 mapping is kept then).
struct RootFacts {
    width: Option<f64>,
    height: Option<f64>,
    view_box: [f64; 4],
    aspect: String,
}

fn root_el_facts(doc: &roxmltree::Document) -> Option<RootFacts> {
    let root = doc.root_element();
    if root.attribute("transform").is_some() {
        return None;
    }
    let px = |name: &str| -> Option<Option<f64>> {
        match root.attribute(name) {
            None => Some(None),
            Some(t) => {
                let l = Length::from_str(t).ok()?;
                (l.unit != LengthUnit::Percent).then(|| mm_per(l.unit).map(|k| l.number * k / MM_PER_PX))
            }
        }
    };
    Some(RootFacts { width: px("width")?, height: px("height")?, view_box: view_box_of(&root).ok()??, aspect: root.attribute("preserveAspectRatio").unwrap_or("").to_string() })
}

/// The root's viewBox: `Ok(None)` where it has none, `Err` where it is not four numbers with a
/// positive width and height.
fn view_box_of(root: &Node) -> Result<Option<[f64; 4]>, ()> {
    let Some(text) = root.attribute("viewBox") else { return Ok(None) };
    let v: Vec<f64> = text.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).map(|s| s.parse().unwrap_or(f64::NAN)).collect();
    match v[..] {
        [x, y, w, h] if v.iter().all(|x| x.is_finite()) && w > 0.0 && h > 0.0 => Ok(Some([x, y, w, h])),
        _ => Err(()),
    }
}

/// The scale of a viewBox fitted to a viewport `sx` by `sy` (viewport over viewBox) as
/// `preserveAspectRatio` says: stretched (`none`, the horizontal), or uniform, to fit
/// (`meet`, the default) or to fill (`slice`).
fn aspect_scale(aspect: &str, sx: f64, sy: f64) -> f64 {
    let mut words = aspect.split_whitespace().skip_while(|w| *w == "defer");
    match (words.next(), words.next()) {
        (Some("none"), _) => sx,
        (_, Some("slice")) => sx.max(sy),
        _ => sx.min(sy),
    }
}

/// The root's viewBox mapping in f64, as SVG gives it (a missing width or height from the
/// other by the viewBox's aspect; uniform scaling aligned as `preserveAspectRatio` says, or
/// stretched for `none`), when `facts` are known and usvg's own size agrees.
fn viewport(facts: &Option<RootFacts>, size: usvg::Size) -> Option<DAffine2> {
    let f = facts.as_ref()?;
    let [x, y, vw, vh] = f.view_box;
    let (w, h) = match (f.width, f.height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, vh * w / vw),
        (None, Some(h)) => (vw * h / vh, h),
        (None, None) => (vw, vh),
    };
    // usvg's size, within its f32: else this reading is not the one it made.
    if (w - f64::from(size.width())).abs() > 1e-5 * w || (h - f64::from(size.height())).abs() > 1e-5 * h {
        return None;
    }
    let align = f.aspect.split_whitespace().find(|w| *w != "defer").unwrap_or("xMidYMid");
    let (sx, sy) = (w / vw, h / vh);
    if align == "none" {
        return Some(DAffine2::from_scale(DVec2::new(sx, sy)) * DAffine2::from_translation(DVec2::new(-x, -y)));
    }
    let s = aspect_scale(&f.aspect, sx, sy);
    let at = |word: &str, min: &str, mid: &str, room: f64| {
        if word.contains(min) {
            0.0
        } else if word.contains(mid) {
            room / 2.0
        } else {
            room
        }
    };
    let (tx, ty) = (at(&align[..align.len().min(4)], "xMin", "xMid", w - vw * s), at(&align[align.len().min(4)..], "YMin", "YMid", h - vh * s));
    Some(DAffine2::from_translation(DVec2::new(tx, ty)) * DAffine2::from_scale(DVec2::splat(s)) * DAffine2::from_translation(DVec2::new(-x, -y)))
}

/// usvg's transform (f32) as an f64 one.
fn to_f64(t: usvg::Transform) -> DAffine2 {
    DAffine2::from_cols_array(&[t.sx, t.ky, t.kx, t.sy, t.tx, t.ty].map(f64::from))
}

/// Whether two transforms are the same within f32's precision, their moves on a drawing
/// `size` across (px).
fn alike(a: DAffine2, b: DAffine2, size: f64) -> bool {
    let (a, b) = (a.to_cols_array(), b.to_cols_array());
    a.iter().zip(&b).enumerate().all(|(k, (x, y))| (x - y).abs() <= 1e-5 * x.abs().max(y.abs()).max(if k >= 4 { size } else { 1.0 }))
}

/// The paths usvg made, as lines and arcs in mm.
struct Paths<'a> {
    tol: &'a Tolerances,
    pieces: Pieces,
    layers: &'a std::collections::HashMap<String, String>,
    lines: &'a std::collections::HashMap<String, usize>,
    /// The drawing's viewport, its larger side (px).
    size: f64,
}

impl Paths<'_> {
    /// The paths in `g`, whose own transform is in `m` (to mm); `view` the root's viewBox
    /// mapping in f64, taken for the group usvg wraps the drawing in when it is that mapping.
    fn group(&mut self, g: &usvg::Group, m: DAffine2, layer: &str, view: Option<DAffine2>) -> Result<(), DrawingError> {
        for node in g.children() {
            match node {
                usvg::Node::Group(child) => {
                    let layer = self.layers.get(child.id()).map_or(layer, String::as_str).to_string();
                    let own = to_f64(child.transform());
                    let own = match view {
                        Some(v) if child.id().is_empty() && alike(own, v, self.size) => v,
                        _ => own,
                    };
                    self.group(child, m * own, &layer, None)?;
                }
                usvg::Node::Path(p) if !p.is_visible() => self.pieces.ignore("hidden shapes (visibility: hidden)"),
                usvg::Node::Path(p) => self.path(p, m, layer)?,
                // Images are said by the walk; text is not read without fonts.
                _ => {}
            }
        }
        Ok(())
    }

    fn path(&mut self, p: &usvg::Path, m: DAffine2, layer: &str) -> Result<(), DrawingError> {
        if let Some(&line) = self.lines.get(p.id()) {
            self.pieces.line = line;
        }
        self.pieces.element = if p.id().is_empty() { "<path>".into() } else { format!("#{}", p.id()) };
        let pt = |q: usvg::tiny_skia_path::Point| DVec2::new(f64::from(q.x), f64::from(q.y));
        let (mut start, mut at) = (DVec2::ZERO, DVec2::ZERO);
        // Arcs of one circle in a row (a circle is four): drawn together on the circle through
        // their end points, which usvg keeps exact where the control points are not.
        let mut run: Vec<Arc> = Vec::new();
        for seg in p.data().segments() {
            use usvg::tiny_skia_path::PathSegment as S;
            if let S::CubicTo(q1, q2, q) = seg {
                let (p0, p1, p2, p3) = (at, pt(q1), pt(q2), pt(q));
                at = p3;
                match circular(p0, p1, p2, p3) {
                    Some(arc) => {
                        if run.last().is_some_and(|last| !last.same_circle(&arc)) {
                            self.arcs(&mut run, m, layer)?;
                        }
                        run.push(arc);
                    }
                    None => {
                        self.arcs(&mut run, m, layer)?;
                        let f = |t: f64| {
                            let u = 1.0 - t;
                            m.transform_point2(p0 * (u * u * u) + p1 * (3.0 * u * u * t) + p2 * (3.0 * u * t * t) + p3 * (t * t * t))
                        };
                        self.curve(&f, 2, layer)?;
                    }
                }
                continue;
            }
            self.arcs(&mut run, m, layer)?;
            match seg {
                S::MoveTo(q) => {
                    start = pt(q);
                    at = start;
                }
                S::LineTo(q) => {
                    let to = pt(q);
                    self.line(m, at, to, layer);
                    at = to;
                }
                S::QuadTo(q1, q) => {
                    let (p0, p1, p2) = (at, pt(q1), pt(q));
                    let f = |t: f64| {
                        let u = 1.0 - t;
                        m.transform_point2(p0 * (u * u) + p1 * (2.0 * u * t) + p2 * (t * t))
                    };
                    self.curve(&f, 2, layer)?;
                    at = p2;
                }
                S::Close => {
                    self.line(m, at, start, layer);
                    at = start;
                }
                S::CubicTo(..) => {}
            }
        }
        self.arcs(&mut run, m, layer)
    }

    /// Draws the arcs of `run` (of one circle, end to end) and empties it: on the circle
    /// through three of their end points where there are three, else each as found.
    fn arcs(&mut self, run: &mut Vec<Arc>, m: DAffine2, layer: &str) -> Result<(), DrawingError> {
        let ends: Vec<DVec2> = run.iter().map(|a| a.from).chain(run.last().map(|a| a.to)).collect();
        let n = ends.len();
        // The first end point, one a third of the way along, one two thirds.
        let circle = if n >= 3 { circumcircle(ends[0], ends[n / 3], ends[2 * n / 3]) } else { None };
        for arc in run.drain(..) {
            let (c, r) = match circle {
                Some((c, r)) if (c - arc.center).length() <= arc.slack && (r - arc.radius).abs() <= arc.slack => (c, r),
                _ => (arc.center, arc.radius),
            };
            let a0 = (arc.from - c).to_angle();
            // The sweep to its end point on this circle, the way the Bézier turns.
            let mut sweep = (arc.to - c).to_angle() - a0;
            while sweep - arc.sweep > std::f64::consts::PI {
                sweep -= std::f64::consts::TAU;
            }
            while arc.sweep - sweep > std::f64::consts::PI {
                sweep += std::f64::consts::TAU;
            }
            let f = |t: f64| m.transform_point2(c + DVec2::from_angle(a0 + sweep * t) * r);
            self.curve(&f, 1, layer)?;
        }
        Ok(())
    }

    fn line(&mut self, m: DAffine2, a: DVec2, b: DVec2, layer: &str) {
        let (a, b) = (m.transform_point2(a), m.transform_point2(b));
        if a != b {
            self.pieces.push(Segment::line(a, b), layer);
        }
    }

    fn curve(&mut self, f: &dyn Fn(f64) -> DVec2, pieces: usize, layer: &str) -> Result<(), DrawingError> {
        let what = self.pieces.element.clone();
        self.pieces.near_origin(&what, f(0.0))?;
        let mut out = Vec::new();
        fit_arcs(f, 0.0, 1.0, pieces, self.tol.arc_fit, &mut out);
        for s in out {
            self.pieces.push(s, layer);
        }
        Ok(())
    }
}

/// A circular arc a cubic Bézier is drawn for, in the Bézier's own coordinates.
#[derive(Clone, Copy, Debug)]
struct Arc {
    from: DVec2,
    to: DVec2,
    center: DVec2,
    radius: f64,
    /// Radians, counter-clockwise positive.
    sweep: f64,
    /// What the f32 numbers it was found from may be out by.
    slack: f64,
}

impl Arc {
    /// Whether `next` goes on along the same circle from this one's end.
    fn same_circle(&self, next: &Arc) -> bool {
        let slack = self.slack.max(next.slack);
        self.to.distance(next.from) <= slack && self.center.distance(next.center) <= slack && (self.radius - next.radius).abs() <= slack && self.sweep.signum() == next.sweep.signum()
    }
}

/// The circle through three points: its centre and radius (`None` where they are in a line).
fn circumcircle(a: DVec2, b: DVec2, c: DVec2) -> Option<(DVec2, f64)> {
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * ab.perp_dot(ac);
    if d.abs() <= 1e-12 * ab.length_squared().max(ac.length_squared()) {
        return None;
    }
    let center = a + DVec2::new(ac.y * ab.length_squared() - ab.y * ac.length_squared(), ab.x * ac.length_squared() - ac.x * ab.length_squared()) / d;
    Some((center, (center.distance(a) + center.distance(b) + center.distance(c)) / 3.0))
}

/// The circular arc a cubic Bézier is drawn for, where it is one (its arms along the arc's
/// tangents, each 4/3·tan(θ/4) of the radius long, as usvg and kurbo draw arcs), within the
/// precision of the f32 numbers usvg keeps.
fn circular(p0: DVec2, p1: DVec2, p2: DVec2, p3: DVec2) -> Option<Arc> {
    let (d0, d3, chord) = (p1 - p0, p3 - p2, p3 - p0);
    let (l0, l3, l) = (d0.length(), d3.length(), chord.length());
    if l0 == 0.0 || l3 == 0.0 || l == 0.0 {
        return None;
    }
    // The half sweep: the angle from the chord to each tangent, alike at both ends and on the
    // same turn.
    let half = chord.angle_to(d0);
    let other = d3.angle_to(chord);
    if half.abs() < 1e-6 || half.abs() > std::f64::consts::FRAC_PI_2 + 1e-9 {
        return None;
    }
    let r = l / (2.0 * half.abs().sin());
    // What the f32 numbers may be out by: their magnitude's precision, with room.
    let size = [p0, p1, p2, p3].iter().map(|p| p.abs().max_element()).fold(r, f64::max);
    let slack = 4e-6 * size;
    let arm = 4.0 / 3.0 * (half.abs() / 2.0).tan() * r;
    if (half - other).abs() * l0.min(l3) > slack || (l0 - arm).abs() > slack || (l3 - arm).abs() > slack {
        return None;
    }
    // The centre: a radius from the start, square to its tangent, toward the turn.
    let n = if half < 0.0 { d0.perp() } else { -d0.perp() } / l0;
    let center = p0 + n * r;
    if ((p3 - center).length() - r).abs() > slack {
        return None;
    }
    Some(Arc { from: p0, to: p3, center, radius: r, sweep: -2.0 * half, slack })
}

fn hidden(node: &Node) -> bool {
    node.attribute("display") == Some("none") || node.attribute("style").is_some_and(|s| s.replace(' ', "").contains("display:none"))
}

impl Reader<'_> {
    /// The line `node` starts on.
    fn line(&self, node: &Node) -> usize {
        self.doc.text_pos_at(node.range().start).row as usize
    }

    /// Reads the elements in `node`, `depth` deep, refusing nesting deeper than
    /// [`crate::limits::MAX_NESTING`] before the walk would overflow the stack.
    fn walk(&mut self, node: Node, parent: DAffine2, layer: &str, depth: usize) -> Result<(), DrawingError> {
        if depth > crate::limits::MAX_NESTING {
            return Err(DrawingError::Svg(format!("elements nest deeper than {} at line {}: no drawing needs that many groups in groups", crate::limits::MAX_NESTING, self.line(&node))));
        }
        for child in node.children().filter(|c| c.is_element()) {
            if hidden(&child) {
                continue;
            }
            self.pieces.line = self.line(&child);
            if let Some(id) = child.attribute("id") {
                self.lines.insert(id.to_string(), self.pieces.line);
            }
            self.pieces.element = format!("<{}>", child.tag_name().name());
            let mut m = parent;
            if let Some(t) = child.attribute("transform") {
                match Transform::from_str(t) {
                    Ok(t) => m = parent * DAffine2::from_cols_array(&[t.a, t.b, t.c, t.d, t.e, t.f]),
                    Err(_) => {
                        self.pieces.ignore("elements with unreadable transforms");
                        continue;
                    }
                }
                if !m.is_finite() {
                    return Err(DrawingError::TooLarge {
                        what: format!("the <{}> at line {} (its transform scales it past any number)", child.tag_name().name(), self.pieces.line),
                        size: f64::INFINITY,
                    });
                }
            }
            let name = child.tag_name().name();
            match name {
                "g" | "a" | "switch" => {
                    let label =
                        child.attributes().find(|a| a.name() == "label").map(|a| a.value()).or_else(|| (child.attribute("groupmode") == Some("layer")).then(|| child.attribute("id")).flatten());
                    if let (Some(label), Some(id)) = (label, child.attribute("id")) {
                        self.layers.insert(id.to_string(), label.to_string());
                    }
                    let label = label.map(str::to_string).unwrap_or_else(|| layer.to_string());
                    self.walk(child, m, &label, depth + 1)?;
                }
                "svg" => self.walk(child, m, layer, depth + 1)?,
                "path" => self.path(child.attribute("d").unwrap_or(""), m, layer)?,
                "rect" if !readable(&child, &["x", "y", "width", "height", "rx", "ry"]) => self.pieces.ignore(&format!("rects with a size or place that is not a number on layer {layer}")),
                "rect" => self.rect(&child, m, layer)?,
                "circle" | "ellipse" if !readable(&child, &["cx", "cy", "r", "rx", "ry"]) => self.pieces.ignore(&format!("{name}s with a centre or radius that is not a number on layer {layer}")),
                "circle" | "ellipse" => {
                    let (cx, cy) = (number(&child, "cx"), number(&child, "cy"));
                    let (rx, ry) = if name == "circle" { (number(&child, "r"), number(&child, "r")) } else { (number(&child, "rx"), number(&child, "ry")) };
                    if rx > 0.0 && ry > 0.0 {
                        self.ellipse(m, DVec2::new(cx, cy), DVec2::new(rx, ry), layer)?;
                    } else {
                        self.pieces.ignore(&format!("{name}s with a radius ≤ 0 on layer {layer}"));
                    }
                }
                "polygon" | "polyline" => {
                    let points: Vec<DVec2> = PointsParser::from(child.attribute("points").unwrap_or("")).map(|(x, y)| DVec2::new(x, y)).collect();
                    if points.iter().any(|p| !p.is_finite()) {
                        self.pieces.ignore(&format!("{name}s with a point that is not a number on layer {layer}"));
                    } else {
                        self.lines(&points, name == "polygon", m, layer);
                    }
                }
                "line" if !readable(&child, &["x1", "y1", "x2", "y2"]) => self.pieces.ignore(&format!("lines with an end that is not a number on layer {layer}")),
                "line" => {
                    let a = DVec2::new(number(&child, "x1"), number(&child, "y1"));
                    let b = DVec2::new(number(&child, "x2"), number(&child, "y2"));
                    self.lines(&[a, b], false, m, layer);
                }
                "defs" | "clipPath" | "mask" | "symbol" | "marker" | "pattern" | "title" | "desc" | "metadata" | "namedview" | "style" => {}
                "text" | "image" => self.pieces.ignore(name),
                _ => {}
            }
        }
        Ok(())
    }

    /// Notes where the lines through `points` reach (the walk checks; usvg draws).
    fn lines(&mut self, points: &[DVec2], closed: bool, m: DAffine2, layer: &str) {
        let n = points.len();
        let count = if closed { n } else { n.saturating_sub(1) };
        for i in 0..count {
            let (a, b) = (m.transform_point2(points[i]), m.transform_point2(points[(i + 1) % n]));
            self.pieces.reach(a.min(b), a.max(b), layer);
        }
    }

    /// Refuses a curve whose defining points (after the transform) are `hull` where it is
    /// larger than any machine or lies past any drawing: a curve lies in their hull.
    fn curve(&mut self, layer: &str, hull: &[DVec2]) -> Result<(), DrawingError> {
        let (lo, hi) = hull.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let extent = if hull.iter().all(|p| p.is_finite()) { (hi - lo).max_element() } else { f64::INFINITY };
        let what = self.pieces.element.clone();
        self.pieces.fits(&what, extent)?;
        if let Some(&p) = hull.first() {
            self.pieces.near_origin(&what, p)?;
        }
        if extent.is_finite() {
            self.pieces.reach(lo, hi, layer);
        }
        Ok(())
    }

    /// An ellipse (or an arc of it) about `c` with radii `r`: its bounding box's corners are
    /// its hull.
    fn ellipse(&mut self, m: DAffine2, c: DVec2, r: DVec2, layer: &str) -> Result<(), DrawingError> {
        let hull = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| m.transform_point2(c + DVec2::new(r.x * x, r.y * y)));
        self.curve(layer, &hull)
    }

    fn rect(&mut self, node: &Node, m: DAffine2, layer: &str) -> Result<(), DrawingError> {
        let (x, y, w, h) = (number(node, "x"), number(node, "y"), number(node, "width"), number(node, "height"));
        if !(w > 0.0 && h > 0.0) {
            self.pieces.ignore(&format!("rects with a width or height ≤ 0 on layer {layer}"));
            return Ok(());
        }
        let (mut rx, mut ry) = (number(node, "rx"), number(node, "ry"));
        if node.attribute("rx").is_none() {
            rx = ry;
        }
        if node.attribute("ry").is_none() {
            ry = rx;
        }
        let (rx, ry) = (rx.clamp(0.0, w / 2.0), ry.clamp(0.0, h / 2.0));
        if rx == 0.0 || ry == 0.0 {
            let p = |px, py| DVec2::new(px, py);
            self.lines(&[p(x, y), p(x + w, y), p(x + w, y + h), p(x, y + h)], true, m, layer);
            return Ok(());
        }
        use std::f64::consts::FRAC_PI_2 as Q;
        let corners = [(x + w - rx, y + ry, -Q), (x + w - rx, y + h - ry, 0.0), (x + rx, y + h - ry, Q), (x + rx, y + ry, 2.0 * Q)];
        for (k, &(cx, cy, start)) in corners.iter().enumerate() {
            self.ellipse(m, DVec2::new(cx, cy), DVec2::new(rx, ry), layer)?;
            let (nx, ny, _) = corners[(k + 1) % 4];
            let end = DVec2::new(cx, cy) + DVec2::new(rx * (start + Q).cos(), ry * (start + Q).sin());
            let next = DVec2::new(nx, ny) + DVec2::new(rx * (start + Q).cos(), ry * (start + Q).sin());
            self.lines(&[end, next], false, m, layer);
        }
        Ok(())
    }

    fn path(&mut self, d: &str, m: DAffine2, layer: &str) -> Result<(), DrawingError> {
        // The parser turns arcs into Béziers before they reach us, as many as the radius asks
        // for: an arc past any drawing is refused first (a radius of 1e38 never ends).
        for seg in svgtypes::PathParser::from(d).flatten() {
            if let svgtypes::PathSegment::EllipticalArc { rx, ry, x, y, .. } = seg {
                let far = [rx, ry, x, y].into_iter().map(f64::abs).fold(0.0, f64::max);
                if far.is_nan() || far > crate::limits::MAX_COORDINATE {
                    return Err(DrawingError::OutOfRange { what: format!("the arc of the <path> at line {}", self.pieces.line), value: crate::limits::shown(far) });
                }
            }
        }
        let (mut start, mut at) = (DVec2::ZERO, DVec2::ZERO);
        for seg in SimplifyingPathParser::from(d) {
            let Ok(seg) = seg else {
                self.pieces.ignore("path data after an error");
                break;
            };
            match seg {
                SimplePathSegment::MoveTo { x, y } => {
                    start = DVec2::new(x, y);
                    at = start;
                }
                SimplePathSegment::LineTo { x, y } => {
                    let to = DVec2::new(x, y);
                    if !to.is_finite() {
                        self.pieces.ignore(&format!("path data after a point that is not a number on layer {layer}"));
                        break;
                    }
                    self.lines(&[at, to], false, m, layer);
                    at = to;
                }
                SimplePathSegment::CurveTo { x1, y1, x2, y2, x, y } => {
                    let p3 = DVec2::new(x, y);
                    self.curve(layer, &[at, DVec2::new(x1, y1), DVec2::new(x2, y2), p3].map(|p| m.transform_point2(p)))?;
                    at = p3;
                }
                SimplePathSegment::Quadratic { x1, y1, x, y } => {
                    let p2 = DVec2::new(x, y);
                    self.curve(layer, &[at, DVec2::new(x1, y1), p2].map(|p| m.transform_point2(p)))?;
                    at = p2;
                }
                SimplePathSegment::ClosePath => {
                    if at != start {
                        self.lines(&[at, start], false, m, layer);
                    }
                    at = start;
                }
            }
        }
        Ok(())
    }
}
