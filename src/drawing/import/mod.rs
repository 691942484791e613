//! Reading 2D drawings: ASCII DXF ([`dxf`]) and SVG ([`svg`]). Curves become arcs within
//! `Tolerances::arc_fit`, everything is scaled to millimetres, and the pieces are chained into
//! loops ([`super::chain`]). Nothing is ever fetched.

pub mod dxf;
pub mod svg;

use thiserror::Error;

use super::chain::chain;
use super::Drawing;
use crate::geom::segment::Segment;
use crate::geom::{DVec2, Tolerances};

/// What can be wrong with a drawing file, for the person who dropped it.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DrawingError {
    #[error("the file is empty")]
    Empty,
    #[error("binary DXF is not supported; save the drawing as ASCII DXF")]
    BinaryDxf,
    #[error("the DXF file is broken at line {line}: {message}")]
    Dxf { line: usize, message: String },
    #[error("the SVG file is broken: {0}")]
    Svg(String),
    #[error("the drawing has a coordinate that is not a finite number ({0})")]
    NonFinite(String),
    #[error("the drawing has no lines, arcs or curves to machine{0}")]
    NothingToMachine(String),
    #[error("{what} is {} mm across, larger than any machine (at most 10 m): a coordinate out of range, or a drawing in the wrong unit", crate::limits::shown(size.round()))]
    TooLarge { what: String, size: f64 },
    #[error("{what} has a coordinate of {value} mm, out of range for any drawing (more than 10 km from the origin, in millimetres as placed): a number damaged in the file?")]
    OutOfRange { what: String, value: String },
    #[error("the drawing has more than {max} lines and arcs once its curves are fitted", max = crate::limits::MAX_PIECES)]
    TooManyPieces,
    #[error("the {format} ends at line {line} without its {marker}: the file was cut short (a download or a copy that stopped?); open the whole file")]
    CutShort { format: &'static str, line: usize, marker: &'static str },
    #[error("this is a part ({0}), not a drawing: a drawing is a DXF or an SVG; a part is machined with a part's job")]
    NotADrawing(&'static str),
    /// A file of another kind, known by its first bytes ([`crate::file_kind::Foreign`]).
    #[error("the file is {}, not a drawing swarf reads (DXF or SVG): {}", .0.describe(), .0.for_a_drawing())]
    Foreign(crate::file_kind::Foreign),
}

/// Drawing formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrawingFormat {
    Dxf,
    Svg,
}

impl DrawingFormat {
    /// From the file name's extension, then from the content.
    pub fn detect(name: Option<&str>, bytes: &[u8]) -> Option<DrawingFormat> {
        match crate::file_kind::extension(name).as_deref() {
            Some("dxf") => return Some(DrawingFormat::Dxf),
            Some("svg") => return Some(DrawingFormat::Svg),
            _ => {}
        }
        let head = String::from_utf8_lossy(&bytes[..bytes.len().min(512)]).to_ascii_lowercase();
        if head.contains("<svg") || head.trim_start().starts_with("<?xml") {
            Some(DrawingFormat::Svg)
        } else if head.contains("section") {
            Some(DrawingFormat::Dxf)
        } else {
            None
        }
    }
}

/// Whether a file name or content looks like a drawing rather than a part.
pub fn is_drawing(name: Option<&str>, bytes: &[u8]) -> bool {
    DrawingFormat::detect(name, bytes).is_some()
}

/// Pieces read from a file, before chaining: segments in mm with their layers.
#[derive(Default)]
pub(crate) struct Pieces {
    pub segments: Vec<(Segment, String)>,
    /// Drill marks (DXF POINTs), in mm, with their layers.
    pub points: Vec<(DVec2, String)>,
    pub layers: Vec<String>,
    pub ignored: Vec<(String, usize)>,
    pub units: String,
    pub scale: f64,
    /// The line of the file the element being read starts on, and its name.
    pub line: usize,
    pub element: String,
    /// The drawing's extremes so far (least x, most x, least y, most y), each with the line of
    /// the element that reaches it: a drawing too large names the element farthest out.
    extremes: Option<[(f64, usize); 4]>,
}

impl Pieces {
    pub fn push(&mut self, s: Segment, layer: &str) {
        let b = s.bounds();
        self.reach(b.min, b.max, layer);
        self.segments.push((s, layer.to_string()));
    }

    /// A drill mark at `at` (mm).
    pub fn point(&mut self, at: DVec2, layer: &str) {
        self.reach(at, at, layer);
        self.points.push((at, layer.to_string()));
    }

    /// Notes the layer, and the extremes an element from `min` to `max` reaches.
    pub(crate) fn reach(&mut self, min: DVec2, max: DVec2, layer: &str) {
        if !self.layers.iter().any(|l| l == layer) {
            self.layers.push(layer.to_string());
        }
        let line = self.line;
        let e = self.extremes.get_or_insert([(min.x, line), (max.x, line), (min.y, line), (max.y, line)]);
        for (k, v) in [min.x, max.x, min.y, max.y].into_iter().enumerate() {
            if (k % 2 == 0 && v < e[k].0) || (k % 2 == 1 && v > e[k].0) {
                e[k] = (v, line);
            }
        }
    }

    /// Refuses what is larger than any machine: the element at `self.line` (a curve, before it
    /// is fitted: `extent` its size, mm), named `what`.
    pub fn fits(&self, what: &str, extent: f64) -> Result<(), DrawingError> {
        if extent.is_finite() && extent <= crate::limits::MAX_SIZE {
            Ok(())
        } else {
            Err(DrawingError::TooLarge { what: format!("the {what} at line {}", self.line), size: extent })
        }
    }

    /// Refuses the element at `self.line`, named `what`, when a point of it (`at`, mm) lies past
    /// [`crate::limits::MAX_COORDINATE`] from the origin: so far out a double no longer holds
    /// its shape to the tolerance, and fitting arcs to it would never end.
    pub fn near_origin(&self, what: &str, at: DVec2) -> Result<(), DrawingError> {
        if at.abs().max_element() <= crate::limits::MAX_COORDINATE {
            Ok(())
        } else {
            Err(DrawingError::OutOfRange { what: format!("the {what} at line {}", self.line), value: crate::limits::shown(at.abs().max_element()) })
        }
    }

    /// Refuses a drawing larger than any machine, naming the element farthest out.
    fn check_size(&self) -> Result<(), DrawingError> {
        let Some(e) = self.extremes else { return Ok(()) };
        if let Some(&(v, line)) = e.iter().find(|(v, _)| v.abs() > crate::limits::MAX_COORDINATE) {
            return Err(DrawingError::OutOfRange { what: format!("the element at line {line}"), value: crate::limits::shown(v.abs()) });
        }
        let (w, h) = (e[1].0 - e[0].0, e[3].0 - e[2].0);
        let size = w.max(h);
        if size.is_finite() && size <= crate::limits::MAX_SIZE {
            return Ok(());
        }
        // The element farthest from the origin: an outlier's coordinate is.
        let far = e.iter().max_by(|a, b| a.0.abs().total_cmp(&b.0.abs())).map_or(0, |x| x.1);
        Err(DrawingError::TooLarge { what: format!("the drawing (its element at line {far} reaches farthest out)"), size })
    }
    pub fn ignore(&mut self, kind: &str) {
        match self.ignored.iter_mut().find(|(k, _)| k == kind) {
            Some((_, n)) => *n += 1,
            None => self.ignored.push((kind.to_string(), 1)),
        }
    }
}

/// The part format a file plainly is (by its name, a GLB's magic or an STL's `solid`), to
/// say so rather than read its bytes as a DXF's.
fn part_format(name: Option<&str>, bytes: &[u8]) -> Option<&'static str> {
    let ext = crate::file_kind::extension(name);
    match ext.as_deref() {
        Some("stl") => Some("an STL"),
        Some("obj") => Some("an OBJ"),
        Some("glb") | Some("gltf") => Some("a glTF"),
        _ if bytes.starts_with(b"glTF") => Some("a glTF"),
        _ if bytes.trim_ascii_start().starts_with(b"solid") => Some("an STL"),
        _ => None,
    }
}

/// Reads a DXF or SVG drawing and chains it into loops, in millimetres.
pub fn read_drawing(bytes: &[u8], name: Option<&str>, tol: &Tolerances) -> Result<Drawing, DrawingError> {
    if bytes.is_empty() {
        return Err(DrawingError::Empty);
    }
    if let Some(kind) = crate::file_kind::Foreign::of(name, bytes) {
        return Err(DrawingError::Foreign(kind));
    }
    let mut pieces = match DrawingFormat::detect(name, bytes) {
        Some(DrawingFormat::Svg) => svg::read_svg(bytes, tol)?,
        Some(DrawingFormat::Dxf) => dxf::read_dxf(bytes, tol)?,
        None => match part_format(name, bytes) {
            Some(format) => return Err(DrawingError::NotADrawing(format)),
            None => dxf::read_dxf(bytes, tol)?,
        },
    };
    if let Some((s, _)) = pieces.segments.iter().find(|(s, _)| !(s.a.is_finite() && s.b.is_finite() && s.bulge.is_finite())) {
        return Err(DrawingError::NonFinite(format!("{:?} to {:?}", s.a, s.b)));
    }
    pieces.check_size()?;
    if pieces.segments.len() > crate::limits::MAX_PIECES {
        return Err(DrawingError::TooManyPieces);
    }
    if pieces.segments.is_empty() && pieces.points.is_empty() {
        let ignored = if pieces.ignored.is_empty() { String::new() } else { format!(" (ignored: {})", pieces.ignored.iter().map(|(k, n)| format!("{n} {k}")).collect::<Vec<_>>().join(", ")) };
        return Err(DrawingError::NothingToMachine(ignored));
    }
    // The same entity drawn twice (a LINE copied onto itself, an SVG path repeated) would
    // leave a stray piece at every joint: one of each is kept, and how many went is said.
    let before = pieces.segments.len();
    pieces.segments = super::chain::without_duplicates(pieces.segments, tol.chain);
    if pieces.segments.len() < before {
        pieces.ignored.push(("duplicated entities (drawn twice on the same layer)".into(), before - pieces.segments.len()));
    }
    // Every piece is chained, however short (a curve drawn finely divided is a curve); what
    // is shorter than the chaining tolerance all told, alone, is an artefact (an SVG arc that
    // starts where it ends draws nothing), left out and said.
    let (mut loops, mut open) = chain(pieces.segments, tol.chain, tol.arc_fit);
    let before = loops.len() + open.len();
    loops.retain(|l| l.path.length() >= tol.chain);
    open.retain(|o| o.path.iter().map(|s| s.length()).sum::<f64>() >= tol.chain * 0.5);
    if loops.len() + open.len() < before {
        pieces.ignored.push(("pieces shorter than the chaining tolerance".into(), before - loops.len() - open.len()));
    }
    let points = pieces.points.into_iter().map(|(at, layer)| crate::drawing::DrawnPoint { at, layer }).collect();
    Ok(Drawing { loops, open, points, layers: pieces.layers, ignored: pieces.ignored, units: pieces.units, scale: pieces.scale })
}
