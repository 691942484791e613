//! ASCII DXF: LINE, ARC, CIRCLE, LWPOLYLINE and POLYLINE (with bulges), ELLIPSE and SPLINE
//! (as arcs within tolerance) from the ENTITIES section, with their layers, and POINTs as drill
//! marks; `$INSUNITS` scales to millimetres. Text, dimensions, hatches and block references
//! are counted and ignored. The entities DXF places in their own plane (ARC, CIRCLE, LWPOLYLINE,
//! a 2D POLYLINE: their Object Coordinate System, set by the extrusion 210/220/230) are read as
//! drawn when it faces +Z, mirrored when it faces −Z, and left out with a note when it stands
//! out of the XY plane (a circle in YZ is not a hole in XY); LINE, POINT, SPLINE, a 3D POLYLINE
//! and an ELLIPSE's axes are in world coordinates, projected onto XY. Files with a byte-order mark
//! or any line ends (CR LF, LF, old Mac's CR) read alike. The group-code reader is a few lines;
//! the entity geometry is swarf's own.

use std::f64::consts::TAU;

use super::{DrawingError, Pieces};
use crate::drawing::arcfit::fit_arcs;
use crate::geom::segment::Segment;
use crate::geom::{DVec2, Tolerances};

/// One entity: its type, the line it starts on, and its group codes and values.
struct Entity<'a> {
    kind: &'a str,
    line: usize,
    groups: Vec<(i32, &'a str)>,
}

impl Entity<'_> {
    fn text(&self, code: i32) -> Option<&str> {
        self.groups.iter().find(|g| g.0 == code).map(|g| g.1)
    }
    fn num(&self, code: i32) -> Result<Option<f64>, DrawingError> {
        match self.text(code) {
            None => Ok(None),
            Some(t) => parse(t, self.line).map(Some),
        }
    }
    fn need(&self, code: i32) -> Result<f64, DrawingError> {
        self.num(code)?.ok_or_else(|| DrawingError::Dxf { line: self.line, message: format!("{} without group {code}", self.kind) })
    }
    fn or(&self, code: i32, default: f64) -> Result<f64, DrawingError> {
        Ok(self.num(code)?.unwrap_or(default))
    }
    fn all(&self, code: i32) -> Result<Vec<f64>, DrawingError> {
        self.groups.iter().filter(|g| g.0 == code).map(|g| parse(g.1, self.line)).collect()
    }
    fn layer(&self) -> &str {
        self.text(8).unwrap_or("0")
    }
    /// Where the entity's own plane faces: its extrusion (210, 220, 230; +Z when absent).
    fn facing(&self) -> Result<Facing, DrawingError> {
        let n = [self.or(210, 0.0)?, self.or(220, 0.0)?, self.or(230, 1.0)?];
        let length = n.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(length > 0.0) {
            return Ok(Facing::Up);
        }
        // Within a millionth of a radian of ±Z: the XY plane (a writer's rounding of 0, 0, 1).
        Ok(match n[2] / length {
            z if z >= 1.0 - 1e-12 => Facing::Up,
            z if z <= -1.0 + 1e-12 => Facing::Down,
            _ => Facing::Out([n[0] / length, n[1] / length, n[2] / length]),
        })
    }
}

/// Where an entity's plane faces: up (as drawn), down (its OCS mirrored in x), or out of the XY
/// plane (its normal).
#[derive(Clone, Copy, PartialEq)]
enum Facing {
    Up,
    Down,
    Out([f64; 3]),
}

/// The largest start or end angle of an ARC (degrees), ten turns: writers give −90 or 450, none
/// 1e300 (whose difference from its start is no angle at all).
const MAX_ARC_ANGLE: f64 = 3600.0;

/// A line of the file as a message quotes it: its first 40 characters, anything unprintable (a
/// binary file's bytes) escaped.
fn shown(text: &str) -> String {
    let head: String = text.chars().take(40).collect();
    let more = if text.chars().count() > 40 { "…" } else { "" };
    format!("{}{more}", head.chars().map(|c| if c.is_control() || c == '\u{FFFD}' { format!("\\x{:02x}", c as u32 & 0xff) } else { c.to_string() }).collect::<String>())
}

fn parse(t: &str, line: usize) -> Result<f64, DrawingError> {
    let v: f64 = t.trim().parse().map_err(|_| DrawingError::Dxf { line, message: format!("'{}' is not a number", shown(t.trim())) })?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(DrawingError::NonFinite(format!("line {line}: {v}")))
    }
}

/// Millimetres per drawing unit for a `$INSUNITS` value, and its name.
fn units(code: i64) -> (f64, &'static str) {
    match code {
        1 => (25.4, "inch"),
        2 => (304.8, "feet"),
        4 => (1.0, "mm"),
        5 => (10.0, "cm"),
        6 => (1000.0, "m"),
        8 => (25.4e-6, "microinch"),
        9 => (25.4e-3, "mil"),
        10 => (914.4, "yard"),
        13 => (1e-3, "micron"),
        14 => (100.0, "dm"),
        // The rest of the header's table: each its own size (a drawing in miles or light
        // years is then larger than any machine, and said so, not read as millimetres).
        3 => (1_609_344.0, "mile"),
        7 => (1e6, "km"),
        11 => (1e-7, "ångström"),
        12 => (1e-6, "nm"),
        15 => (1e4, "decametre"),
        16 => (1e5, "hectometre"),
        17 => (1e12, "gigametre"),
        18 => (1.495_978_707e14, "astronomical unit"),
        19 => (9.460_730_472_580_8e18, "light year"),
        20 => (3.085_677_581e19, "parsec"),
        21 => (1200.0 / 3937.0 * 1000.0, "US survey foot"),
        22 => (1000.0 / 39.37, "US survey inch"),
        23 => (3600.0 / 3937.0 * 1000.0, "US survey yard"),
        24 => (6_336_000.0 / 3937.0 * 1000.0, "US survey mile"),
        0 => (1.0, "unitless (read as mm)"),
        _ => (1.0, "an unknown $INSUNITS (read as mm)"),
    }
}

pub(crate) fn read_dxf(bytes: &[u8], tol: &Tolerances) -> Result<Pieces, DrawingError> {
    if bytes.starts_with(b"AutoCAD Binary DXF") {
        return Err(DrawingError::BinaryDxf);
    }
    // A byte-order mark is no part of the first group code; old Mac files end lines with CR.
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let text = String::from_utf8_lossy(bytes);
    let mut lines: Vec<&str> = text.split('\n').flat_map(|l| l.strip_suffix('\r').unwrap_or(l).split('\r')).collect();
    if lines.last() == Some(&"") {
        lines.pop();
    }
    if lines.len() < 2 {
        return Err(DrawingError::Dxf { line: 1, message: "too short to be a DXF file".into() });
    }
    let mut pairs: Vec<(i32, &str, usize)> = Vec::with_capacity(lines.len() / 2);
    for k in 0..lines.len() / 2 {
        let line = 2 * k + 1;
        let code: i32 = lines[2 * k].trim().parse().map_err(|_| DrawingError::Dxf { line, message: format!("expected a group code, found '{}'", shown(lines[2 * k].trim())) })?;
        pairs.push((code, lines[2 * k + 1].trim(), line + 1));
    }
    // A DXF ends with `0 EOF`: a file without it was cut short, and what it holds is not the
    // whole drawing.
    if !pairs.last().is_some_and(|&(code, value, _)| code == 0 && value.eq_ignore_ascii_case("EOF")) {
        return Err(DrawingError::CutShort { format: "DXF", line: lines.len(), marker: "EOF marker (0 / EOF)" });
    }
    // Sections: the header's $INSUNITS and the entities.
    let mut scale = (1.0, "unitless (read as mm)");
    let mut entities: Vec<Entity> = Vec::new();
    let mut section = "";
    let mut i = 0;
    while i < pairs.len() {
        let (code, value, line) = pairs[i];
        if code == 0 && value == "SECTION" {
            section = pairs.get(i + 1).map(|p| p.1).unwrap_or("");
            i += 2;
            continue;
        }
        if code == 0 && value == "ENDSEC" {
            section = "";
            i += 1;
            continue;
        }
        if section == "HEADER" && code == 9 && value == "$INSUNITS" {
            if let Some(p) = pairs.get(i + 1) {
                scale = units(p.1.parse().unwrap_or(0));
            }
        }
        if section == "ENTITIES" && code == 0 {
            let mut groups = Vec::new();
            let mut j = i + 1;
            while j < pairs.len() && pairs[j].0 != 0 {
                groups.push((pairs[j].0, pairs[j].1));
                j += 1;
            }
            entities.push(Entity { kind: value, line, groups });
            i = j;
            continue;
        }
        i += 1;
    }
    let mut pieces = Pieces { units: scale.1.to_string(), scale: scale.0, ..Pieces::default() };
    let s = scale.0;
    let mut k = 0;
    while k < entities.len() {
        let e = &entities[k];
        pieces.line = e.line;
        let mut out: Vec<Segment> = Vec::new();
        // The entities drawn in their own plane: left out (and said) where it is not XY's.
        let in_own_plane = matches!(e.kind, "ARC" | "CIRCLE" | "LWPOLYLINE" | "ELLIPSE") || (e.kind == "POLYLINE" && (e.or(70, 0.0)? as i64) & (8 | 16 | 64) == 0);
        let facing = if in_own_plane { e.facing()? } else { Facing::Up };
        if let Facing::Out(n) = facing {
            pieces.ignore(&format!("{}s out of the XY plane (facing {:.3}, {:.3}, {:.3}) on layer {}", e.kind, n[0], n[1], n[2], e.layer()));
            k += 1;
            if e.kind == "POLYLINE" {
                while k < entities.len() && matches!(entities[k].kind, "VERTEX" | "SEQEND") {
                    k += 1;
                }
            }
            continue;
        }
        // Mirrored where the OCS faces −Z (an ELLIPSE's axes are in world coordinates: its
        // facing turns its sweep instead).
        let mirrored = facing == Facing::Down && e.kind != "ELLIPSE";
        match e.kind {
            "LINE" => {
                let a = DVec2::new(e.need(10)?, e.need(20)?);
                let b = DVec2::new(e.need(11)?, e.need(21)?);
                out.push(Segment::line(a, b));
            }
            "ARC" | "CIRCLE" => {
                let c = DVec2::new(e.need(10)?, e.need(20)?);
                let r = e.need(40)?;
                let (start, sweep) = if e.kind == "CIRCLE" {
                    (0.0, TAU)
                } else {
                    let (a0, a1) = (e.need(50)?, e.need(51)?);
                    if a0.abs().max(a1.abs()) > MAX_ARC_ANGLE {
                        return Err(DrawingError::Dxf {
                            line: e.line,
                            message: format!("an ARC whose start or end angle ({}°, {}°) is not an angle (degrees, within ±{MAX_ARC_ANGLE})", crate::limits::shown(a0), crate::limits::shown(a1)),
                        });
                    }
                    let (a0, a1) = (a0.to_radians(), a1.to_radians());
                    let mut sweep = (a1 - a0).rem_euclid(TAU);
                    if sweep == 0.0 {
                        sweep = TAU;
                    }
                    (a0, sweep)
                };
                if r > 0.0 {
                    pieces.fits(e.kind, 2.0 * r * s)?;
                    // Halves, so no segment's bulge runs away near a full turn.
                    let n = if sweep > TAU / 2.0 { 2 } else { 1 };
                    for h in 0..n {
                        out.push(Segment::arc_from(c, r, start + sweep * h as f64 / n as f64, sweep / n as f64));
                    }
                } else {
                    pieces.ignore(&format!("{} with a radius ≤ 0 on layer {}", if e.kind == "CIRCLE" { "circles" } else { "arcs" }, e.layer()));
                }
            }
            "LWPOLYLINE" => {
                let closed = (e.or(70, 0.0)? as i64) & 1 == 1;
                let mut vertices: Vec<(DVec2, f64)> = Vec::new();
                for (code, value) in &e.groups {
                    match code {
                        10 => vertices.push((DVec2::new(parse(value, e.line)?, 0.0), 0.0)),
                        20 => {
                            if let Some(v) = vertices.last_mut() {
                                v.0.y = parse(value, e.line)?;
                            }
                        }
                        42 => {
                            if let Some(v) = vertices.last_mut() {
                                v.1 = parse(value, e.line)?;
                            }
                        }
                        _ => {}
                    }
                }
                polyline(&vertices, closed, &mut out);
            }
            "POLYLINE" => {
                let flags = e.or(70, 0.0)? as i64;
                let mut vertices = Vec::new();
                let mut j = k + 1;
                while j < entities.len() && entities[j].kind == "VERTEX" {
                    let v = &entities[j];
                    vertices.push((DVec2::new(v.or(10, 0.0)?, v.or(20, 0.0)?), v.or(42, 0.0)?));
                    j += 1;
                }
                if j < entities.len() && entities[j].kind == "SEQEND" {
                    j += 1;
                }
                if flags & (16 | 64) != 0 {
                    pieces.ignore("POLYLINE meshes");
                } else {
                    polyline(&vertices, flags & 1 == 1, &mut out);
                }
                emit(&mut pieces, out, e.layer(), s, mirrored);
                k = j;
                continue;
            }
            "ELLIPSE" => {
                let c = DVec2::new(e.need(10)?, e.need(20)?);
                let major = DVec2::new(e.need(11)?, e.need(21)?);
                let ratio = e.need(40)?;
                if !(ratio > 0.0) || major.length() == 0.0 {
                    pieces.ignore(&format!("ellipses with no width (an axis or ratio of 0) on layer {}", e.layer()));
                    k += 1;
                    continue;
                }
                pieces.fits("ELLIPSE", 2.0 * major.length() * ratio.max(1.0) * s)?;
                pieces.near_origin("ELLIPSE", c * s)?;
                // The parameters are angles in radians, from 0 to 2π: one far past that is not
                // an angle any writer meant (a parameter of 1e300 would ask for endless arcs).
                let (mut t0, mut t1) = (e.or(41, 0.0)?, e.or(42, TAU)?);
                if t0.abs().max(t1.abs()) > 2.0 * TAU {
                    return Err(DrawingError::Dxf {
                        line: e.line,
                        message: format!("an ELLIPSE whose start or end parameter ({}, {}) is not an angle from 0 to 2π", crate::limits::shown(t0), crate::limits::shown(t1)),
                    });
                }
                let span = t1 - t0;
                t0 = t0.rem_euclid(TAU);
                t1 = if span.abs() >= TAU { t0 + TAU } else { t1.rem_euclid(TAU) };
                if t1 <= t0 {
                    t1 += TAU;
                }
                // The minor axis is the normal × the major: turned back where it faces −Z.
                let minor = major.perp() * if facing == Facing::Down { -ratio } else { ratio };
                let f = |t: f64| c + major * t.cos() + minor * t.sin();
                let pieces_n = ((t1 - t0) / (TAU / 8.0)).ceil().max(1.0) as usize;
                fit_arcs(&f, t0, t1, pieces_n, tol.arc_fit / s, &mut out);
            }
            "SPLINE" => spline(e, tol.arc_fit / s, s, &pieces, &mut out)?,
            "POINT" => {
                // A drill mark: a place to drill, no geometry to cut along.
                let at = DVec2::new(e.need(10)?, e.need(20)?) * s;
                pieces.near_origin("POINT", at)?;
                pieces.point(at, e.layer());
            }
            "VERTEX" | "SEQEND" => {}
            other => pieces.ignore(other),
        }
        emit(&mut pieces, out, e.layer(), s, mirrored);
        k += 1;
    }
    Ok(pieces)
}

/// Scales (and mirrors) segments into millimetres.
fn emit(pieces: &mut Pieces, out: Vec<Segment>, layer: &str, scale: f64, mirrored: bool) {
    for seg in out {
        let f = |p: DVec2| if mirrored { DVec2::new(-p.x, p.y) * scale } else { p * scale };
        let bulge = if mirrored { -seg.bulge } else { seg.bulge };
        pieces.push(Segment { a: f(seg.a), b: f(seg.b), bulge }, layer);
    }
}

fn polyline(vertices: &[(DVec2, f64)], closed: bool, out: &mut Vec<Segment>) {
    let n = vertices.len();
    let count = if closed { n } else { n.saturating_sub(1) };
    for i in 0..count {
        let (a, bulge) = vertices[i];
        let b = vertices[(i + 1) % n].0;
        out.push(Segment { a, b, bulge });
    }
}

/// A B-spline (rational when it has weights) evaluated by de Boor's algorithm and fitted
/// with arcs; a spline with only fit points is taken through them as lines.
fn spline(e: &Entity, tol: f64, scale: f64, pieces: &Pieces, out: &mut Vec<Segment>) -> Result<(), DrawingError> {
    let bad = |message: String| DrawingError::Dxf { line: e.line, message };
    let degree = e.or(71, 3.0)?;
    if !(1.0..=crate::limits::MAX_SPLINE_DEGREE as f64).contains(&degree) || degree.fract() != 0.0 {
        return Err(bad(format!("a SPLINE of degree {degree} (a degree is a whole number from 1 to {})", crate::limits::MAX_SPLINE_DEGREE)));
    }
    let degree = degree as usize;
    let knots = e.all(40)?;
    let xs = e.all(10)?;
    let ys = e.all(20)?;
    let weights = e.all(41)?;
    let n = xs.len().min(ys.len());
    if n == 0 {
        let (fx, fy) = (e.all(11)?, e.all(21)?);
        let fit: Vec<(DVec2, f64)> = fx.iter().zip(&fy).map(|(&x, &y)| (DVec2::new(x, y), 0.0)).collect();
        polyline(&fit, false, out);
        return Ok(());
    }
    if n <= degree || knots.len() != n + degree + 1 {
        return Err(bad(format!("SPLINE with {n} control points, degree {degree} and {} knots", knots.len())));
    }
    if knots.windows(2).any(|k| k[1] < k[0]) {
        return Err(bad("a SPLINE whose knots decrease".into()));
    }
    if weights.len() == n && weights.iter().any(|&w| w <= 0.0) {
        return Err(bad("a SPLINE with a weight of 0 or less (weights are positive)".into()));
    }
    let w: Vec<f64> = if weights.len() == n { weights } else { vec![1.0; n] };
    let ctrl: Vec<DVec2> = (0..n).map(|i| DVec2::new(xs[i], ys[i])).collect();
    // The curve lies in its control points' hull.
    let (lo, hi) = ctrl.iter().fold((ctrl[0], ctrl[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    pieces.fits("SPLINE", (hi - lo).max_element() * scale)?;
    pieces.near_origin("SPLINE", lo.abs().max(hi.abs()) * scale)?;
    let (t0, t1) = (knots[degree], knots[n]);
    let eval = |t: f64| -> DVec2 {
        // The knot span holding t.
        let mut span = degree;
        while span < n - 1 && knots[span + 1] <= t {
            span += 1;
        }
        let mut d: Vec<(DVec2, f64)> = (0..=degree).map(|j| (ctrl[span - degree + j] * w[span - degree + j], w[span - degree + j])).collect();
        for r in 1..=degree {
            for j in (r..=degree).rev() {
                let i = span - degree + j;
                let denom = knots[i + degree + 1 - r] - knots[i];
                let alpha = if denom == 0.0 { 0.0 } else { (t - knots[i]) / denom };
                d[j] = (d[j - 1].0 * (1.0 - alpha) + d[j].0 * alpha, d[j - 1].1 * (1.0 - alpha) + d[j].1 * alpha);
            }
        }
        d[degree].0 / d[degree].1
    };
    if t1 > t0 {
        fit_arcs(&eval, t0, t1, (n - degree).max(1) * 2, tol, out);
    }
    Ok(())
}
