//! Units, up axis and placement of an imported part. Inside swarf everything is millimetres
//! with Z up; files come in inches or with Y up, and a user either wants the part set on the
//! stock (top at z = 0, centred in XY) or kept exactly where the file puts it.

use serde::{Deserialize, Serialize};

use super::Mesh;
use crate::geom::DVec3;

/// Length unit of a file or of G-code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
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
}

/// Which axis of the file points up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum UpAxis {
    #[default]
    Z,
    Y,
}

/// Where the part goes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Placement {
    /// Part top at z = 0, part centred on the XY origin (and so in the stock).
    #[default]
    CenterTop,
    /// Coordinates exactly as in the file (after units and up axis), so that other tools can
    /// check the G-code against the same file.
    Keep,
}

/// How to read a part's coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, rename_all = "camelCase")]
pub struct PartSetup {
    /// Unit of the file's coordinates. Default value: mm.
    pub units: Units,
    /// The file's up axis. Default value: Z.
    pub up_axis: UpAxis,
    /// Where the part goes. Default value: centerTop.
    pub placement: Placement,
}

impl PartSetup {
    /// Converts the mesh to millimetres with Z up and places it.
    pub fn apply(&self, mesh: &mut Mesh) {
        let scale = self.units.mm();
        let up = self.up_axis;
        mesh.transform(|v| {
            let v = v * scale;
            match up {
                UpAxis::Z => v,
                // A quarter turn about X: the file's +Y becomes +Z, its +Z becomes -Y.
                UpAxis::Y => DVec3::new(v.x, -v.z, v.y),
            }
        });
        if self.placement == Placement::CenterTop {
            let b = mesh.bounds();
            let shift = DVec3::new(-b.center().x, -b.center().y, -b.max.z);
            mesh.transform(|v| v + shift);
        }
    }
}
