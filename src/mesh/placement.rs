//! Units, up axis and placement of an imported part. Inside swarf everything is millimetres
//! with Z up; files come in inches or with Y up, and a user either wants the part set on the
//! stock (top at z = 0, centred in XY) or kept exactly where the file puts it.

use serde::{Deserialize, Serialize};

use super::Mesh;
use crate::geom::DVec3;

/// Length unit of a file or of G-code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Units {
    #[default]
    Mm,
    Inch,
}

impl Units {
    /// Millimetres per unit.
    pub fn mm(self) -> f64 {
        match self {
            Units::Mm => 1.0,
            Units::Inch => 25.4,
        }
    }

    /// Its short name in figures: "mm", "in".
    pub fn short(self) -> &'static str {
        match self {
            Units::Mm => "mm",
            Units::Inch => "in",
        }
    }
}

/// Which axis of the file points up: the part is turned so that it points along +Z (a turn,
/// never a mirror).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
pub enum UpAxis {
    #[default]
    #[serde(rename = "z")]
    Z,
    #[serde(rename = "y")]
    Y,
    #[serde(rename = "x")]
    X,
    /// The file's −Z points up: the part turned over.
    #[serde(rename = "-z")]
    MinusZ,
    #[serde(rename = "-y")]
    MinusY,
    #[serde(rename = "-x")]
    MinusX,
}

impl UpAxis {
    /// The point `v` of the file turned so that this axis points along +Z.
    pub fn turn(self, v: DVec3) -> DVec3 {
        match self {
            UpAxis::Z => v,
            // A quarter turn about X: the file's +Y becomes +Z, its +Z becomes -Y.
            UpAxis::Y => DVec3::new(v.x, -v.z, v.y),
            UpAxis::MinusY => DVec3::new(v.x, v.z, -v.y),
            // A quarter turn about Y: the file's +X becomes +Z, its +Z becomes -X.
            UpAxis::X => DVec3::new(-v.z, v.y, v.x),
            UpAxis::MinusX => DVec3::new(v.z, v.y, -v.x),
            // A half turn about X.
            UpAxis::MinusZ => DVec3::new(v.x, -v.y, -v.z),
        }
    }
}

/// Where the part goes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Placement {
    /// Part top at z = 0, part centred on the XY origin (and so in the stock).
    #[default]
    CenterTop,
    /// Coordinates exactly as in the file (after units and up axis), so that other tools can
    /// check the G-code against the same file.
    Keep,
}

/// The unit of a part file's coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum PartUnits {
    /// As the format says: metres for glTF (its specification), millimetres for STL and OBJ
    /// (which say nothing; millimetres is what CAD exports them in).
    #[default]
    Auto,
    Mm,
    Inch,
    #[serde(rename = "m")]
    Metre,
}

impl PartUnits {
    /// Millimetres per unit of `mesh`'s file.
    pub fn mm(self, mesh: &Mesh) -> f64 {
        match self {
            PartUnits::Auto if mesh.in_metres => 1000.0,
            PartUnits::Auto | PartUnits::Mm => 1.0,
            PartUnits::Inch => 25.4,
            PartUnits::Metre => 1000.0,
        }
    }
}

/// The sizes a part milled on a CNC is likely to have across (mm): smaller or larger, it was
/// most likely read in the wrong unit.
pub const LIKELY_ACROSS: [f64; 2] = [5.0, 3000.0];

impl PartUnits {
    /// For a part `across` mm at its widest, outside [`LIKELY_ACROSS`]: the unit that would
    /// make it a size parts have (its name, and the words of the page's choice for it) and the
    /// size it would then have. Inches before metres for a small part (a part drawn in inches
    /// is the common slip, one in metres the rarer); millimetres for a large one read in
    /// inches or metres.
    pub fn likely(across: f64) -> Option<(&'static str, &'static str, f64)> {
        let [low, high] = LIKELY_ACROSS;
        let fits = |mm: f64| (2.0 * low..=high).contains(&mm);
        if !across.is_finite() || across <= 0.0 || (low..=high).contains(&across) {
            return None;
        }
        let candidates: &[(&str, &str, f64)] = if across < low { &[("inches", "inch", 25.4), ("metres", "metres", 1000.0)] } else { &[("millimetres", "mm", 1.0 / 25.4), ("millimetres", "mm", 1e-3)] };
        candidates.iter().map(|&(unit, choice, k)| (unit, choice, across * k)).find(|&(_, _, mm)| fits(mm))
    }
}

/// How to read a part's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct PartSetup {
    /// Unit of the file's coordinates. Default value: auto (metres for glTF, else mm).
    pub units: PartUnits,
    /// A free factor on top of the unit (a model made at half size: 2). Default value: 1.
    pub scale: f64,
    /// The file's up axis. Default value: z.
    pub up_axis: UpAxis,
    /// A turn about Z after that, in degrees counterclockwise seen from above: 0, 90, 180 or
    /// 270. Default value: 0.
    pub rotation: u32,
    /// Where the part goes. Default value: centerTop.
    pub placement: Placement,
}

impl Default for PartSetup {
    fn default() -> Self {
        PartSetup { units: PartUnits::Auto, scale: 1.0, up_axis: UpAxis::Z, rotation: 0, placement: Placement::CenterTop }
    }
}

impl PartSetup {
    /// Converts the mesh to millimetres with Z up, turns it about Z and places it.
    pub fn apply(&self, mesh: &mut Mesh) {
        self.turn(mesh);
        let shift = self.shift(&mesh.bounds());
        mesh.transform(|v| v + shift);
    }

    /// Converts the mesh to millimetres with Z up and turns it about Z, without placing it.
    pub fn turn(&self, mesh: &mut Mesh) {
        let scale = self.units.mm(mesh) * self.scale;
        // Applied once: the mesh is in millimetres from here on.
        mesh.in_metres = false;
        let (up, quarter) = (self.up_axis, (self.rotation / 90) % 4);
        mesh.transform(|v| {
            let v = up.turn(v * scale);
            match quarter {
                1 => DVec3::new(-v.y, v.x, v.z),
                2 => DVec3::new(-v.x, -v.y, v.z),
                3 => DVec3::new(v.y, -v.x, v.z),
                _ => v,
            }
        });
    }

    /// The move that places a turned mesh whose box is `turned`: its top's centre to the
    /// origin (`centerTop`), or none (`keep`).
    pub fn shift(&self, turned: &crate::geom::Aabb) -> DVec3 {
        match self.placement {
            Placement::CenterTop if !turned.is_empty() => DVec3::new(-turned.center().x, -turned.center().y, -turned.max.z),
            _ => DVec3::ZERO,
        }
    }
}
