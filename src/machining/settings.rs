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
    /// A point picked on the part (the operation's `point`, in the setup's program
    /// coordinates as the page shows the part): its height.
    Point,
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
            // A point's height is its own (`Heights::from_z`); without one, the zero's.
            HeightFrom::Point => 0.0,
        }
    }

    /// The choices of a form's "from" field.
    pub const CHOICES: [(&'static str, &'static str); 7] = [
        ("zero", "the work zero (Z0)"),
        ("stockTop", "the stock's top"),
        ("stockBottom", "the stock's bottom"),
        ("partTop", "the part's top"),
        ("partBottom", "the part's bottom"),
        ("partingLine", "the parting line"),
        ("point", "a point picked on the part"),
    ];
}

/// Where an operation cuts and how high it moves between cuts, as Fusion's Heights tab has
/// them, flattened into each 3D operation's JSON (`operations[1].bottom`): a top and a bottom
/// height the operation cuts between, and its own clearance and retract in place of the job's
/// (`stock.clearance`, `stock.retract`). Each height is an offset from what its `…From`
/// names, so that it follows the stock or the part as a setup holds it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Heights {
    /// The highest the tool's tip cuts (mm from `topFrom`): a roughing's first level is a
    /// step-down below it, a finishing leaves what lies above it. Default value: none (the
    /// stock's top).
    pub top: Option<f64>,
    /// What `top` is measured from. Default value: stockTop.
    pub top_from: HeightFrom,
    /// The lowest the tool's tip goes (mm from `bottomFrom`): the operation stops there, over
    /// the part and beside it, as one side of a part machined from both stops at its parting
    /// line and leaves the rest joined to the stock the vise grips. Default value: none (the
    /// stock's bottom; the parting line itself where `bottomFrom` is `partingLine`).
    pub bottom: Option<f64>,
    /// What `bottom` is measured from. Default value: zero.
    pub bottom_from: HeightFrom,
    /// The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
    /// and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
    /// top).
    pub clearance: Option<f64>,
    /// What `clearance` is measured from. Default value: stockTop.
    pub clearance_from: HeightFrom,
    /// The gap above the material where the operation's rapid descents stop and the feed
    /// begins, and over which its short retracts travel (mm). Default value: none (the job's,
    /// `stock.retract`).
    pub retract: Option<f64>,
    /// The point a height `…From: point` is measured from: `[x, y, z]` (mm) in the setup's
    /// program coordinates, as the page picks it on the part it shows. Default value: none.
    pub point: Option<[f64; 3]>,
}

impl Default for Heights {
    fn default() -> Self {
        Heights { top: None, top_from: HeightFrom::StockTop, bottom: None, bottom_from: HeightFrom::Zero, clearance: None, clearance_from: HeightFrom::StockTop, retract: None, point: None }
    }
}

impl Heights {
    /// The height `from` names in a program whose stock box is `stock` and part `part`: the
    /// picked point's own for [`HeightFrom::Point`].
    pub fn from_z(&self, from: HeightFrom, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> f64 {
        match (from, self.point) {
            (HeightFrom::Point, Some(p)) => p[2],
            (from, _) => from.z(stock, part),
        }
    }

    /// The lowest tip height the operation may cut to in a program whose stock box is `stock`
    /// and part `part`: 0 from the parting line where only that is given; none without either.
    pub fn bottom_z(&self, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> Option<f64> {
        match (self.bottom, self.bottom_from) {
            (None, HeightFrom::PartingLine) => Some(HeightFrom::PartingLine.z(stock, part)),
            (b, from) => b.map(|b| self.from_z(from, stock, part) + b),
        }
    }

    /// The highest tip height the operation cuts at: none without a top height (the stock's
    /// top).
    pub fn top_z(&self, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> Option<f64> {
        self.top.map(|t| self.from_z(self.top_from, stock, part) + t)
    }

    /// The tip heights the operation cuts between, `(bottom, top)`, either open; an error
    /// naming `op` where the bottom is at or above the top or the top at or below the bottom
    /// of the stock (nothing to cut).
    pub fn window(&self, op: &str, stock: &crate::geom::Aabb, part: &crate::mesh::Mesh) -> crate::error::Result<(Option<f64>, Option<f64>)> {
        let (low, high) = (self.bottom_z(stock, part), self.top_z(stock, part));
        let nothing = |why: String, fix: &str| Err(crate::error::Error::operation(op, format!("{why}: nothing to cut; {fix}")));
        if let Some(z) = low.filter(|&z| z >= stock.max.z - 1e-6) {
            return nothing(format!("its bottom height (Z{z:.3}) is at or above the stock's top (Z{:.3})", stock.max.z), "give a lower 'Bottom height', or none");
        }
        if let Some(z) = high.filter(|&z| z <= stock.min.z + 1e-6) {
            return nothing(format!("its top height (Z{z:.3}) is at or below the stock's bottom (Z{:.3})", stock.min.z), "give a higher 'Top height', or none");
        }
        if let (Some(l), Some(h)) = (low, high) {
            if l >= h - 1e-6 {
                return nothing(format!("its bottom height (Z{l:.3}) is at or above its top height (Z{h:.3})"), "give a lower 'Bottom height' or a higher 'Top height'");
            }
        }
        Ok((low, high))
    }

    /// The safe heights the operation moves at: the job's `job`, with this operation's own
    /// clearance and retract where it has them; an error naming `op` and the field where its
    /// clearance is not above the stock and the fixtures (`lowest`, the job's own lowest
    /// clearance).
    pub fn safe(
        &self,
        op: &str,
        job: crate::machining::context::SafeHeights,
        lowest: f64,
        stock: &crate::geom::Aabb,
        part: &crate::mesh::Mesh,
    ) -> crate::error::Result<crate::machining::context::SafeHeights> {
        let mut safe = job;
        if let Some(c) = self.clearance {
            let z = self.from_z(self.clearance_from, stock, part) + c;
            if z <= lowest + 1e-6 {
                return Err(crate::error::Error::operation(
                    op,
                    format!("clearance: its clearance height (Z{z:.3}) is not above the stock's top and the fixtures (Z{lowest:.3} at the least): its rapids would cut; give a higher 'Clearance height', or none"),
                ));
            }
            safe.clearance = z;
        }
        if let Some(r) = self.retract {
            safe.gap = r;
        }
        Ok(safe)
    }

    /// Keeps the stretches of `runs` whose tip lies between `low` and `high` (either open),
    /// each run cut where it crosses either height (a stretch of a straight move is the same
    /// line, so what was clear of the part stays so).
    pub fn trim(runs: Vec<Vec<glam::DVec3>>, low: Option<f64>, high: Option<f64>) -> Vec<Vec<glam::DVec3>> {
        let (lo, hi) = (low.unwrap_or(f64::NEG_INFINITY), high.unwrap_or(f64::INFINITY));
        if lo == f64::NEG_INFINITY && hi == f64::INFINITY {
            return runs;
        }
        let inside = |p: glam::DVec3| p.z >= lo - 1e-9 && p.z <= hi + 1e-9;
        let mut out = Vec::new();
        for run in runs {
            let mut current: Vec<glam::DVec3> = Vec::new();
            for w in run.windows(2) {
                let (a, b) = (w[0], w[1]);
                // Where the move crosses either height, in order along it.
                let mut cuts: Vec<f64> = [lo, hi].iter().filter(|h| h.is_finite() && (a.z - **h) * (b.z - **h) < 0.0).map(|h| (h - a.z) / (b.z - a.z)).collect();
                cuts.sort_by(f64::total_cmp);
                cuts.push(1.0);
                let mut from = 0.0;
                for t in cuts {
                    let (p, q) = (a.lerp(b, from), a.lerp(b, t));
                    if inside(a.lerp(b, 0.5 * (from + t))) {
                        if current.is_empty() {
                            current.push(p);
                        }
                        current.push(q);
                    } else if current.len() > 1 {
                        out.push(std::mem::take(&mut current));
                    } else {
                        current.clear();
                    }
                    from = t;
                }
            }
            if current.len() > 1 {
                out.push(current);
            }
        }
        out
    }

    /// The stretches of a finishing's `runs` between its heights ([`Heights::trim`]); none,
    /// noted on `op`, where it had runs and none lies between them.
    pub fn keep(&self, op: &str, ctx: &mut crate::machining::context::Context, runs: Vec<Vec<glam::DVec3>>) -> crate::error::Result<Option<Vec<Vec<glam::DVec3>>>> {
        let (low, high) = self.window(op, &ctx.stock, &ctx.part)?;
        let had = !runs.is_empty();
        let kept = Heights::trim(runs, low, high);
        if had && kept.is_empty() {
            let (l, h) = (low.unwrap_or(ctx.stock.min.z), high.unwrap_or(ctx.stock.max.z));
            ctx.note(op, format!("nothing of its passes lies between its bottom and top heights (Z{l:.3} to Z{h:.3})"));
            return Ok(None);
        }
        // Passes wholly over the stock (an allowance of 1000 mm rose them to Z1000) cut air
        // alone: nothing to cut, as a waterline's or an adaptive's says.
        let top = ctx.stock.max.z;
        if let Some(lowest) = kept.iter().flatten().map(|p| p.z).reduce(f64::min).filter(|&z| z > top + 1e-6) {
            ctx.note(op, format!("nothing to cut: its lowest pass (Z{lowest:.3}) lies over the stock's top (Z{top:.3}); a smaller 'Leave on the part' (allowance) or a lower 'Top height' cuts"));
            return Ok(None);
        }
        Ok(Some(kept))
    }

    /// Checks the settings, each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        for (field, value) in [("top", self.top), ("bottom", self.bottom), ("clearance", self.clearance)] {
            if let Some(v) = value {
                crate::machining::finite(field, v)?;
            }
        }
        if let Some(r) = self.retract {
            positive("retract", r)?;
        }
        match self.point {
            Some(p) if !p.iter().all(|v| v.is_finite()) => return Err(FieldError { field: "point", message: "is three finite numbers, [x, y, z] in mm".into() }),
            None if [self.top_from, self.bottom_from, self.clearance_from].contains(&HeightFrom::Point) => {
                let field = if self.top_from == HeightFrom::Point {
                    "topFrom"
                } else if self.bottom_from == HeightFrom::Point {
                    "bottomFrom"
                } else {
                    "clearanceFrom"
                };
                return Err(FieldError { field, message: "is a picked point, but none is picked: pick one on the part (the operation's point, [x, y, z])".into() });
            }
            _ => {}
        }
        Ok(())
    }

    /// Their fields in an operation's form: the heights it cuts between, then its clearance
    /// and retract.
    pub fn fields() -> [FormField; 7] {
        use super::form::FieldUnit;
        [
            FormField::number("top", "Top height", FieldUnit::Length).empty("the stock's top").help("The highest the tool's tip cuts, from what 'Top from' names (negative: below it): a roughing's first level is a step-down below it, a finishing leaves what lies above."),
            FormField::choice("topFrom", "Top from", &HeightFrom::CHOICES),
            FormField::number("bottom", "Bottom height", FieldUnit::Length)
                .empty("the stock's bottom (or the parting line, where 'Bottom from' is it)")
                .help("The lowest the tool's tip goes, from what 'Bottom from' names (negative: below it): the operation stops there. One side of a part machined from both stops at the parting line (the part's widest section), so the other side's material still joins the part to what the vise holds."),
            FormField::choice("bottomFrom", "Bottom from", &HeightFrom::CHOICES),
            FormField::number("clearance", "Clearance height", FieldUnit::Length).empty("the job's (Stock: clearance)").help("The height this operation's rapids cross at, from what 'Clearance from' names: above the stock and any clamp."),
            FormField::choice("clearanceFrom", "Clearance from", &HeightFrom::CHOICES),
            FormField::length("retract", "Retract gap", 0.0).empty("the job's (Stock: retract)").help("How far above the material a rapid descent stops and the feed begins, and how high a short retract clears what it crosses."),
        ]
    }
}

/// How a 2D or hole operation moves between cuts, flattened into its JSON as the heights are
/// into a 3D operation's: its own clearance (and, for a 2D cut, retract) in place of the job's.
/// Its top and bottom are its own depths (a 2D cut's from the stock's top, a hole's from the
/// hole); a hole operation has [`Clearance`] alone, its `retract` being its R plane.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Moves {
    /// The height the operation's rapids cross at (mm from `clearanceFrom`), above the stock
    /// and the fixtures. Default value: none (the job's, `stock.clearance` above the stock's
    /// top).
    pub clearance: Option<f64>,
    /// What `clearance` is measured from. Default value: stockTop.
    pub clearance_from: HeightFrom,
    /// The gap above the material where rapid descents stop and the feed begins (mm).
    /// Default value: none (the job's, `stock.retract`).
    pub retract: Option<f64>,
    /// The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
    /// program coordinates. Default value: none.
    pub point: Option<[f64; 3]>,
}

impl Default for Moves {
    fn default() -> Self {
        Moves { clearance: None, clearance_from: HeightFrom::StockTop, retract: None, point: None }
    }
}

impl Moves {
    /// As the heights with neither top nor bottom (what the run applies and checks).
    pub fn heights(&self) -> Heights {
        Heights { clearance: self.clearance, clearance_from: self.clearance_from, retract: self.retract, point: self.point, ..Heights::default() }
    }

    /// Checks the settings, each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.heights().validate()
    }

    /// Their fields in a form: the clearance and the retract.
    pub fn fields() -> Vec<FormField> {
        Heights::fields()[4..7].to_vec()
    }
}

/// A hole operation's own clearance, flattened into its JSON ([`Moves`] without the retract:
/// a hole operation's `retract` is its R plane, its own field).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Clearance {
    /// The height the operation's rapids cross at and its cycles start from (mm from
    /// `clearanceFrom`), above the stock and the fixtures. Default value: none (the job's,
    /// `stock.clearance` above the stock's top).
    pub clearance: Option<f64>,
    /// What `clearance` is measured from. Default value: stockTop.
    pub clearance_from: HeightFrom,
    /// The point a clearance `from: point` is measured from: `[x, y, z]` (mm) in the setup's
    /// program coordinates. Default value: none.
    pub point: Option<[f64; 3]>,
}

impl Default for Clearance {
    fn default() -> Self {
        Clearance { clearance: None, clearance_from: HeightFrom::StockTop, point: None }
    }
}

impl Clearance {
    /// As the heights with its clearance alone.
    pub fn heights(&self) -> Heights {
        Moves { clearance: self.clearance, clearance_from: self.clearance_from, retract: None, point: self.point }.heights()
    }

    /// Checks the settings, each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.heights().validate()
    }

    /// Their fields in a form: the clearance.
    pub fn fields() -> Vec<FormField> {
        Heights::fields()[4..6].to_vec()
    }
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
    /// The heights it cuts between, its clearance and retract.
    #[serde(flatten)]
    #[ts(flatten)]
    pub heights: Heights,
}

impl Default for Roughing {
    fn default() -> Self {
        Roughing { allowance: 0.5, leave_stock: 0.5, direction: Direction::Climb, grid: 0.25, ramp_angle: 3.0, rest: true, heights: Heights::default() }
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
    pub fn fields() -> Vec<FormField> {
        let mut fields = vec![
            FormField::length("allowance", "Leave on floors", 0.0),
            FormField::length("leaveStock", "Leave on walls", 0.0),
            FormField::direction(),
            FormField::grid(),
            FormField::ramp_angle(),
            FormField::check("rest", "rest roughing: only what earlier operations left"),
        ];
        fields.extend(Heights::fields());
        fields
    }

    /// Checks the settings, each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        not_negative("allowance", self.allowance)?;
        not_negative("leaveStock", self.leave_stock)?;
        self.heights.validate()?;
        positive("grid", self.grid)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)
    }

    /// The material left on the part's surface: the smaller of the two allowances.
    pub fn allowance(&self) -> f64 {
        self.allowance.min(self.leave_stock)
    }
}
