//! Reading 2D drawings: ASCII DXF ([`dxf`]) and SVG ([`svg`]). Curves become arcs within
//! `Tolerances::arc_fit`, everything is scaled to millimetres, and the pieces are chained into
//! loops ([`super::chain`]). Nothing is ever fetched.

pub mod dxf;
pub mod svg;

use thiserror::Error;

use super::chain::chain;
use super::Drawing;
use crate::geom::segment::Segment;
use crate::geom::Tolerances;

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
        match name.and_then(|n| n.rsplit_once('.')).map(|(_, e)| e.to_ascii_lowercase()).as_deref() {
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
    pub layers: Vec<String>,
    pub ignored: Vec<(String, usize)>,
    pub units: String,
    pub scale: f64,
}

impl Pieces {
    pub fn push(&mut self, s: Segment, layer: &str) {
        if !self.layers.iter().any(|l| l == layer) {
            self.layers.push(layer.to_string());
        }
        self.segments.push((s, layer.to_string()));
    }
    pub fn ignore(&mut self, kind: &str) {
        match self.ignored.iter_mut().find(|(k, _)| k == kind) {
            Some((_, n)) => *n += 1,
            None => self.ignored.push((kind.to_string(), 1)),
        }
    }
}

/// Reads a DXF or SVG drawing and chains it into loops, in millimetres.
pub fn read_drawing(bytes: &[u8], name: Option<&str>, tol: &Tolerances) -> Result<Drawing, DrawingError> {
    if bytes.is_empty() {
        return Err(DrawingError::Empty);
    }
    let pieces = match DrawingFormat::detect(name, bytes) {
        Some(DrawingFormat::Svg) => svg::read_svg(bytes, tol)?,
        _ => dxf::read_dxf(bytes, tol)?,
    };
    if let Some((s, _)) = pieces.segments.iter().find(|(s, _)| !(s.a.is_finite() && s.b.is_finite() && s.bulge.is_finite())) {
        return Err(DrawingError::NonFinite(format!("{:?} to {:?}", s.a, s.b)));
    }
    if pieces.segments.is_empty() {
        let ignored = if pieces.ignored.is_empty() { String::new() } else { format!(" (ignored: {})", pieces.ignored.iter().map(|(k, n)| format!("{n} {k}")).collect::<Vec<_>>().join(", ")) };
        return Err(DrawingError::NothingToMachine(ignored));
    }
    // Pieces shorter than half the chaining tolerance are bridged by it anyway; alone they are
    // artefacts (an SVG arc that starts where it ends draws nothing).
    let mut pieces = pieces;
    let before = pieces.segments.len();
    pieces.segments.retain(|(s, _)| s.length() >= tol.chain * 0.5);
    if pieces.segments.len() < before {
        pieces.ignored.push(("pieces shorter than the chaining tolerance".into(), before - pieces.segments.len()));
    }
    // The same entity drawn twice (a LINE copied onto itself, an SVG path repeated) would
    // leave a stray piece at every joint: one of each is kept, and how many went is said.
    let before = pieces.segments.len();
    pieces.segments = super::chain::without_duplicates(pieces.segments, tol.chain);
    if pieces.segments.len() < before {
        pieces.ignored.push(("duplicated entities (drawn twice on the same layer)".into(), before - pieces.segments.len()));
    }
    let (loops, open) = chain(pieces.segments, tol.chain);
    Ok(Drawing { loops, open, layers: pieces.layers, ignored: pieces.ignored, units: pieces.units, scale: pieces.scale })
}
