//! The settings the operations share: the words of the job file that mean the same in every
//! operation that has them (a cutting direction, an order, a pattern, how the load is held,
//! how material is entered), and the roughing kinds' common settings ([`Steps`], [`Roughing`]), flattened
//! into each roughing kind's JSON and validated once.

use serde::{Deserialize, Serialize};

use super::form::FormField;
use super::{not_negative, positive, FieldError};

/// Cutting direction for a spindle turning clockwise (M3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Direction {
    /// Down milling: the part on the tool's right.
    #[default]
    Climb,
    Conventional,
}

/// The order a level-by-level roughing cuts in (`order` of z-level roughing).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Order {
    /// Each connected region of a level, then the regions under it down to their floors
    /// (nearest first), before the next region of that level.
    #[default]
    Regions,
    /// Each level everywhere, from the top down.
    Levels,
}

/// How the pocket is cleared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum PocketPattern {
    /// Rings parallel to the walls.
    #[default]
    Offset,
    /// Parallel passes, back and forth, then a finishing ring.
    Zigzag,
    /// The tool held at the step-over's engagement angle all along (adaptive clearing:
    /// [`crate::machining::adaptive`]), then a finishing ring.
    Adaptive,
}

/// How the tool enters material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum EntryKind {
    /// A helix where it fits, else a ramp.
    #[default]
    Helix,
    /// Down along the path at the ramp angle.
    Ramp,
}

/// How the load is held at the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum LoadControl {
    /// Extra path where the plain path would overload the tool (seed 004 §3.3); the feed drops
    /// only where no extra path helps.
    #[default]
    Path,
    /// The plain path, with the feed lowered wherever it would overload the tool.
    Feed,
    /// The plain path at the tool's feed.
    None,
}

/// How far apart the levels and the rings or passes of a roughing are, in its JSON as its own
/// fields (`operations[1].stepdown`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Steps {
    /// Largest depth between levels (mm). Default value: 2.
    pub stepdown: f64,
    /// Distance between rings or passes as a fraction of the tool diameter. Default value: 0.4.
    pub stepover_fraction: f64,
}

impl Default for Steps {
    fn default() -> Self {
        Steps { stepdown: 2.0, stepover_fraction: 0.4 }
    }
}

impl Steps {
    /// Their fields in a roughing's form.
    pub fn fields() -> [FormField; 2] {
        [FormField::length("stepdown", "Step-down", 0.01), FormField::fraction("stepoverFraction", "Step-over", "fraction of the tool's diameter", 1.0)]
    }

    /// Checks the steps, each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        positive("stepdown", self.stepdown)?;
        crate::machining::fraction("stepoverFraction", self.stepover_fraction)
    }
}

/// What a height given on an operation is measured from (its `bottomFrom`), as Fusion's
/// Heights tab has them: the setup's work zero, the stock's top or bottom, or the part's top or
/// bottom as the setup holds it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum HeightFrom {
    /// Z0 of the setup's program.
    #[default]
    Zero,
    StockTop,
    StockBottom,
    PartTop,
    PartBottom,
    /// The part's widest horizontal section as the setup holds it
    /// ([`crate::mesh::Mesh::widest_section`]): where a part machined from both sides is
    /// parted, each side cut down to it from its own face.
    PartingLine,
}

impl HeightFrom {
    /// Its height in a program whose stock box is `stock` and part `part` (none for a
    /// drawing, whose part is its sheet: the stock's box then).
    pub fn z(self, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> f64 {
        let boxed = if part.faces.is_empty() { *stock } else { part.bounds() };
        match self {
            HeightFrom::Zero => 0.0,
            HeightFrom::StockTop => stock.max.z,
            HeightFrom::StockBottom => stock.min.z,
            HeightFrom::PartTop => boxed.max.z,
            HeightFrom::PartBottom => boxed.min.z,
            HeightFrom::PartingLine => part.widest_section().unwrap_or(boxed.min.z),
        }
    }

    /// The lowest tip height an operation whose bottom height is `bottom` from this may cut to,
    /// in a program whose stock box is `stock` and part `part`: 0 from the parting line where
    /// only that is given; none without either.
    pub fn bottom_z(self, bottom: Option<f64>, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> Option<f64> {
        match (bottom, self) {
            (None, HeightFrom::PartingLine) => Some(self.z(stock, part)),
            (b, from) => b.map(|b| from.z(stock, part) + b),
        }
    }

    /// A form's "Bottom height" and "Bottom from" fields (`bottom`, `bottomFrom`).
    pub fn bottom_fields() -> [FormField; 2] {
        [
            FormField::number("bottom", "Bottom height", super::form::FieldUnit::Length)
                .empty("the stock's bottom (or the parting line, where 'Bottom from' is it)")
                .help("The lowest the tool's tip goes, from what 'Bottom from' names (negative: below it): the operation stops there. One side of a part machined from both stops at the parting line (the part's widest section), so the other side's material still joins the part to what the vise holds."),
            FormField::choice("bottomFrom", "Bottom from", &HeightFrom::CHOICES),
        ]
    }

    /// The choices of a form's "from" field.
    pub const CHOICES: [(&'static str, &'static str); 6] = [
        ("zero", "the work zero (Z0)"),
        ("stockTop", "the stock's top"),
        ("stockBottom", "the stock's bottom"),
        ("partTop", "the part's top"),
        ("partBottom", "the part's bottom"),
        ("partingLine", "the parting line"),
    ];
}

/// What every roughing kind leaves and how it cuts, in each one's JSON as its own fields
/// (`operations[1].allowance`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Roughing {
    /// Material left on floors (axial, mm). Default value: 0.5.
    pub allowance: f64,
    /// Material left on walls (radial, mm). Default value: 0.5.
    pub leave_stock: f64,
    /// Default value: climb.
    pub direction: Direction,
    /// Spacing of the CL z-map (mm). Default value: 0.25.
    pub grid: f64,
    /// Steepest descent of helices and ramps (degrees). Default value: 3.
    pub ramp_angle: f64,
    /// Rest roughing: plan against what the earlier operations left (the in-process stock),
    /// so that after a larger tool only its leftovers are cut and no air it cleared; off, plan
    /// against the setup's stock as it came, as if nothing had been cut. Default value: true.
    pub rest: bool,
    /// The lowest the tool's tip goes (mm from `bottomFrom`): the roughing stops there, over
    /// the part and beside it, as one side of a part machined from both stops at its parting
    /// line and leaves the rest joined to the stock the vise grips. Default value: none (the
    /// stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
    pub bottom: Option<f64>,
    /// What `bottom` is measured from. Default value: zero.
    pub bottom_from: HeightFrom,
}

impl Default for Roughing {
    fn default() -> Self {
        Roughing { allowance: 0.5, leave_stock: 0.5, direction: Direction::Climb, grid: 0.25, ramp_angle: 3.0, rest: true, bottom: None, bottom_from: HeightFrom::Zero }
    }
}

/// What a roughing's form says of rest roughing, its `rest` box.
pub const REST_HINT: &str = "Rest roughing (on by default): after a larger tool it cuts only what that tool left (the in-process stock), never the air it cleared; the results say what it took. Off, it plans against the setup's stock as it came.";

/// The first fields of a one-tool roughing's form: its name and tool, its steps, what it
/// leaves and how it cuts, and whether it cuts the flats.
pub fn roughing_form() -> Vec<FormField> {
    let mut fields = FormField::name_and_tool().to_vec();
    fields.extend(Steps::fields());
    fields.extend(Roughing::fields());
    fields.push(FormField::check("flats", "also cut every flat at its own height"));
    fields
}

impl Roughing {
    /// Their fields in a roughing's form.
    pub fn fields() -> [FormField; 8] {
        let [bottom, bottom_from] = HeightFrom::bottom_fields();
        [
            FormField::length("allowance", "Leave on floors", 0.0),
            FormField::length("leaveStock", "Leave on walls", 0.0),
            FormField::direction(),
            FormField::grid(),
            FormField::ramp_angle(),
            FormField::check("rest", "rest roughing: only what earlier operations left"),
            bottom,
            bottom_from,
        ]
    }

    /// The lowest tip height it may cut to in a program whose stock box is `stock` and part
    /// `part` ([`HeightFrom::bottom_z`]).
    pub fn bottom_z(&self, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> Option<f64> {
        self.bottom_from.bottom_z(self.bottom, stock, part)
    }

    /// Checks the settings, each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        not_negative("allowance", self.allowance)?;
        not_negative("leaveStock", self.leave_stock)?;
        if let Some(b) = self.bottom {
            crate::machining::finite("bottom", b)?;
        }
        positive("grid", self.grid)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)
    }

    /// The material left on the part's surface: the smaller of the two allowances.
    pub fn allowance(&self) -> f64 {
        self.allowance.min(self.leave_stock)
    }
}
