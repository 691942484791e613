//! SVG: paths (lines, quadratic and cubic Béziers, elliptical arcs), rect (with rounded
//! corners), circle, ellipse, polygon, polyline and line, under nested transforms. Curves
//! become arcs within tolerance after the transforms (so skewed circles stay right). User
//! units become millimetres through the root's width/height and viewBox, else at 96 px per
//! inch; y is flipped so the drawing reads as on screen. Parsing is roxmltree's and
//! svgtypes'; what is made of the geometry is swarf's own.

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

struct Reader<'t, 'd> {
    tol: &'t Tolerances,
    pieces: Pieces,
    doc: &'d roxmltree::Document<'d>,
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
    // User units to mm: width over the viewBox's width when both are given.
    let view_box: Option<Vec<f64>> = root.attribute("viewBox").map(|v| v.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).map(|s| s.parse().unwrap_or(f64::NAN)).collect());
    let usable = |v: &Vec<f64>| v.len() == 4 && v.iter().all(|x| x.is_finite()) && v[2] > 0.0 && v[3] > 0.0;
    let bad_view_box = view_box.as_ref().is_some_and(|v| !usable(v));
    let mut to_mm = DAffine2::from_scale(DVec2::new(MM_PER_PX, -MM_PER_PX));
    let mut units = "px (96 per inch)".to_string();
    let mut scale = MM_PER_PX;
    if let Some(vb) = view_box.filter(usable) {
        let w = length_mm(root.attribute("width")).unwrap_or(vb[2] * MM_PER_PX);
        let h = length_mm(root.attribute("height")).unwrap_or(vb[3] * MM_PER_PX);
        to_mm = DAffine2::from_scale(DVec2::new(w / vb[2], -h / vb[3])) * DAffine2::from_translation(DVec2::new(-vb[0], -vb[1]));
        units = format!("viewBox scaled to {w:.3} × {h:.3} mm");
        scale = w / vb[2];
    }
    let mut reader = Reader { tol, pieces: Pieces { units, scale, ..Pieces::default() }, doc: &doc };
    if bad_view_box {
        reader.pieces.ignore("viewBox that is not four numbers with a positive width and height (the drawing read at 96 px per inch)");
    }
    reader.walk(root, to_mm, "0", 1)?;
    Ok(reader.pieces)
}

fn hidden(node: &Node) -> bool {
    node.attribute("display") == Some("none") || node.attribute("style").is_some_and(|s| s.replace(' ', "").contains("display:none"))
}

impl Reader<'_, '_> {
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
                        self.ellipse_arc(m, DVec2::new(cx, cy), DVec2::new(rx, ry), 0.0, std::f64::consts::TAU, layer)?;
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
                "text" | "image" | "use" => self.pieces.ignore(name),
                _ => {}
            }
        }
        Ok(())
    }

    fn lines(&mut self, points: &[DVec2], closed: bool, m: DAffine2, layer: &str) {
        let n = points.len();
        let count = if closed { n } else { n.saturating_sub(1) };
        for i in 0..count {
            let (a, b) = (m.transform_point2(points[i]), m.transform_point2(points[(i + 1) % n]));
            if a != b {
                self.pieces.push(Segment::line(a, b), layer);
            }
        }
    }

    /// Fits arcs to the curve `f` whose defining points (after the transform) are `hull`: a
    /// curve lies in their hull, refused when that is larger than any machine.
    fn curve(&mut self, f: &dyn Fn(f64) -> DVec2, t0: f64, t1: f64, pieces: usize, layer: &str, hull: &[DVec2]) -> Result<(), DrawingError> {
        let (lo, hi) = hull.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let extent = if hull.iter().all(|p| p.is_finite()) { (hi - lo).max_element() } else { f64::INFINITY };
        let what = self.pieces.element.clone();
        self.pieces.fits(&what, extent)?;
        if let Some(&p) = hull.first() {
            self.pieces.near_origin(&what, p)?;
        }
        let mut out = Vec::new();
        fit_arcs(f, t0, t1, pieces, self.tol.arc_fit, &mut out);
        for s in out {
            self.pieces.push(s, layer);
        }
        Ok(())
    }

    fn ellipse_arc(&mut self, m: DAffine2, c: DVec2, r: DVec2, t0: f64, t1: f64, layer: &str) -> Result<(), DrawingError> {
        let f = |t: f64| m.transform_point2(c + DVec2::new(r.x * t.cos(), r.y * t.sin()));
        let n = ((t1 - t0).abs() / (std::f64::consts::TAU / 8.0)).ceil().clamp(1.0, 8.0) as usize;
        // The ellipse's bounding box's corners: its hull.
        let hull = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| m.transform_point2(c + DVec2::new(r.x * x, r.y * y)));
        self.curve(&f, t0, t1, n, layer, &hull)
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
            self.ellipse_arc(m, DVec2::new(cx, cy), DVec2::new(rx, ry), start, start + Q, layer)?;
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
                    let (p0, p1, p2, p3) = (at, DVec2::new(x1, y1), DVec2::new(x2, y2), DVec2::new(x, y));
                    let f = |t: f64| {
                        let u = 1.0 - t;
                        m.transform_point2(p0 * (u * u * u) + p1 * (3.0 * u * u * t) + p2 * (3.0 * u * t * t) + p3 * (t * t * t))
                    };
                    self.curve(&f, 0.0, 1.0, 2, layer, &[p0, p1, p2, p3].map(|p| m.transform_point2(p)))?;
                    at = p3;
                }
                SimplePathSegment::Quadratic { x1, y1, x, y } => {
                    let (p0, p1, p2) = (at, DVec2::new(x1, y1), DVec2::new(x, y));
                    let f = |t: f64| {
                        let u = 1.0 - t;
                        m.transform_point2(p0 * (u * u) + p1 * (2.0 * u * t) + p2 * (t * t))
                    };
                    self.curve(&f, 0.0, 1.0, 2, layer, &[p0, p1, p2].map(|p| m.transform_point2(p)))?;
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
