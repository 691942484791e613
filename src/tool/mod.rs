//! Tools of the library: a cutter (its shape, [`crate::cutter`]) with its cutting data. The
//! strategies, the simulation and the post-processor read tools; none of them needs the job.

use serde::{Deserialize, Serialize};

use crate::cutter::Cutter;

pub mod holder;
pub mod library;

pub use holder::{Holder, HolderSection};

/// A tool in the library: a cutter with its cutting data.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Tool {
    /// Tool number (T word, pocket). Default value: 1.
    pub number: u32,
    /// Free text for the library and the program's comments. Default value: empty.
    pub name: String,
    #[serde(flatten)]
    pub cutter: Cutter,
    /// Spindle speed (rpm), where the tool's speeds are as typed or the stock's material is
    /// not set. Default value: 12000.
    pub spindle_rpm: f64,
    /// Cutting feed (mm/min). Default value: 1000.
    pub feed_rate: f64,
    /// Feed for vertical entries (mm/min). Default value: 300.
    pub plunge_rate: f64,
    /// How far the tool stands out of its holder (mm): where the holder's face is, for the
    /// verification, the library and the setup sheet.
    /// Default value: none.
    pub stick_out: Option<f64>,
    /// Coolant while this tool cuts: off, flood (M8) or mist (M7), as the post writes them.
    /// Default value: off.
    pub coolant: Coolant,
    /// Cutting edges (flutes) of a mill; a drill has its two lips. Default value: 2.
    pub flutes: u32,
    /// What its edges are made of: `carbide` or `hss`. Default value: carbide.
    pub tool_material: ToolMaterial,
    /// Where its speed and feeds come from: `fromMaterial` (the stock's material, where the job
    /// names one; [`crate::cutting`]) or `asTyped` (`spindleRpm`, `feedRate`, `plungeRate`).
    /// Default value: fromMaterial.
    pub speeds: Speeds,
    /// What holds it (a collet chuck, a router's nut), `stickOut` below its face (the flute
    /// length where that is not set): the verification finds it in material. Default value:
    /// none.
    pub holder: Option<Holder>,
    /// What the library it came from gave that swarf does not model, as that library wrote it:
    /// each field by format and place (`freecad:parameter.Length`), its value as JSON text
    /// (`"\"50.0000 mm\""`). Written back when the tool goes out to the same kind of library,
    /// so a round trip keeps what swarf does not use. Default value: none.
    #[serde(skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    #[ts(as = "Option<std::collections::BTreeMap<String, String>>", optional)]
    pub library_fields: std::collections::BTreeMap<String, String>,
}

/// What a tool's cutting edges are made of.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ToolMaterial {
    #[default]
    Carbide,
    /// High-speed steel (cobalt HSS too): its own chart's speeds, a half to a third of
    /// carbide's.
    Hss,
    /// Coated carbide (TiN, TiAlN, AlTiN): a quarter faster than carbide in the metals.
    Coated,
}

impl ToolMaterial {
    /// Its name in a machinist's words.
    pub fn words(self) -> &'static str {
        match self {
            ToolMaterial::Carbide => "carbide",
            ToolMaterial::Hss => "HSS",
            ToolMaterial::Coated => "coated carbide",
        }
    }
}

/// Where a tool's spindle speed and feeds come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Speeds {
    /// From the stock's material (where the job names one), else as typed.
    #[default]
    FromMaterial,
    /// As typed in the tool (`spindleRpm`, `feedRate`, `plungeRate`), whatever the material.
    AsTyped,
}

/// Coolant for a tool.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Coolant {
    #[default]
    Off,
    Flood,
    Mist,
}

impl Default for Tool {
    fn default() -> Self {
        Tool {
            number: 1,
            name: String::new(),
            cutter: Cutter::default(),
            spindle_rpm: 12000.0,
            feed_rate: 1000.0,
            plunge_rate: 300.0,
            stick_out: None,
            coolant: Coolant::Off,
            flutes: 2,
            tool_material: ToolMaterial::Carbide,
            speeds: Speeds::FromMaterial,
            holder: None,
            library_fields: Default::default(),
        }
    }
}

impl Tool {
    /// Its holder's rings, `(radius, rise above the tip)` ([`Holder::rings`]), if it has one.
    pub fn holder_rings(&self) -> Option<std::sync::Arc<Vec<(f64, f64)>>> {
        self.holder.as_ref().map(|h| std::sync::Arc::new(h.rings(self.standing_out())))
    }

    /// How far it stands out of its holder (mm): its `stickOut`, else its flutes' length.
    pub fn standing_out(&self) -> f64 {
        self.stick_out.unwrap_or(self.cutter.flute_length)
    }

    pub fn describe(&self) -> String {
        if self.name.is_empty() {
            self.cutter.describe()
        } else {
            format!("{}: {}", self.name, self.cutter.describe())
        }
    }
}
