//! The job as one serde type: stock, tools, operations, post and simulation settings, with
//! what a job file may hold and what each setting means; checked as a whole ([`Job::problems`]).

use serde::{Deserialize, Serialize};

use super::fixtures::Fixtures;
use crate::drawing::Drawing;
use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec2, DVec3, Tolerances};
use crate::mesh::{placement::PartSetup, Mesh};
use crate::operations::{FinishRaster, Operation};
use crate::post::PostSettings;
use crate::sim::verify::VerifySettings;
use crate::tool::Tool;

/// Which height of the setup is Z0 in the program.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ZeroHeight {
    #[default]
    PartTop,
    StockTop,
    StockBottom,
}

/// Which point of the stock seen from above is X0 Y0.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ZeroCorner {
    #[default]
    Center,
    /// The front left corner (least X, least Y).
    FrontLeft,
    FrontRight,
    BackLeft,
    BackRight,
}

/// The work zero: where the program's origin is on the setup.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct WorkZero {
    /// Default value: partTop.
    pub height: ZeroHeight,
    /// Default value: center.
    pub corner: ZeroCorner,
    /// X0 Y0 at this point instead of `corner`: how far it lies from the stock's centre seen
    /// from above, in X and Y as the setup holds the part (mm); the page sets it on a hole's
    /// centre ([`Job::zero_on`]). Default value: none.
    pub at: Option<[f64; 2]>,
}

impl WorkZero {
    /// The point of `stock` (around a part whose top is `part_top`) that becomes the origin.
    pub fn point(&self, stock: &Aabb, part_top: f64) -> DVec3 {
        let z = match self.height {
            ZeroHeight::PartTop => part_top,
            ZeroHeight::StockTop => stock.max.z,
            ZeroHeight::StockBottom => stock.min.z,
        };
        let (lo, hi, c) = (stock.min, stock.max, stock.center());
        let (x, y) = match (self.at, self.corner) {
            (Some([dx, dy]), _) => (c.x + dx, c.y + dy),
            (None, corner) => match corner {
                ZeroCorner::Center => (c.x, c.y),
                ZeroCorner::FrontLeft => (lo.x, lo.y),
                ZeroCorner::FrontRight => (hi.x, lo.y),
                ZeroCorner::BackLeft => (lo.x, hi.y),
                ZeroCorner::BackRight => (hi.x, hi.y),
            },
        };
        DVec3::new(x, y, z)
    }
}

/// The stock, as a machinist sets it: margins around the placed part on every side, or an
/// explicit box; the heights of moves between cuts; and the work zero.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Stock {
    /// Extra stock around the part in X and Y (mm, each side). Default value: 5.
    pub margin_xy: f64,
    /// Extra stock above the part's top (mm). Default value: 1.
    pub margin_top: f64,
    /// Extra stock below the part's bottom (mm). Default value: 0.
    pub margin_bottom: f64,
    /// Margins on each side in X and Y, `[left (-X), right (+X), front (-Y), back (+Y)]` (mm),
    /// instead of `marginXy`. Default value: none.
    pub margin_sides: Option<[f64; 4]>,
    /// The stock as an explicit box (mm, where the part is placed), instead of margins.
    /// Default value: none.
    pub size_box: Option<Aabb>,
    /// Height above the stock top for rapid moves where they cannot go lower (mm): the start
    /// and end of each operation, and retracts over stock standing that high. Default value: 5.
    pub clearance: f64,
    /// Gap above the material under the tool where a rapid descent stops and the feed begins,
    /// and above the material on the way where a retract travels across (mm): the short
    /// retract. Default value: 1.
    pub retract: f64,
    /// How a retract between two cuts travels across: `minimum`, the retract gap above the
    /// highest material on the way (the clearance where the stock stands that high); `full`,
    /// at the clearance height, over clamps and fixtures the stock does not show (a z-level
    /// roughing still crosses what it has cleared just above its levels). Default value:
    /// minimum.
    pub retracts: Retracts,
    /// Feed (mm/min) of the moves a roughing or pocket level knows cut nothing: stretches of
    /// rings over ground an earlier ring of the level took, stay-down links across it, the way
    /// in from beside the stock. They stay in the path (the tool down, as G1), only faster, and
    /// the verification holds each to cutting nothing. At most the rapid rate and the machine's fastest feed; no faster than
    /// the tool's feed keeps them at it. Default value: the post's rapid rate.
    pub air_feed: Option<f64>,
    /// Moves part and stock so that this point is the program's origin (for parts; a sheet's
    /// top is always Z0). Default value: none (as the part's placement puts it).
    pub zero: Option<WorkZero>,
    /// Round bar stock instead of a box: its diameter and the axis it lies along, centred on
    /// the part, as long as the part and the margins along its axis (the margins across it
    /// are the bar's). Default value: none.
    pub bar: Option<Bar>,
    /// What the stock is: the tools' speeds and feeds follow from it ([`crate::cutting`]).
    /// Default value: none (every tool's as typed).
    pub material: Option<crate::cutting::Material>,
    /// A mesh as the stock instead of a box: a casting or a near-net blank, in the part's own
    /// coordinates (both from one CAD model), placed with the part; its box is the stock's
    /// ([`super::blank`]). Default value: none.
    pub mesh: Option<super::blank::MeshFile>,
}

/// Round bar stock ([`Stock::bar`]): the material a sawn length of bar holds, so that the
/// operations, the air-cut skipping and the verification see the air round it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Bar {
    /// The bar's diameter (mm). Default value: 50.
    pub diameter: f64,
    /// The axis it lies along: `z` stands it on end (a disc, a knob cut from its end), `x` or
    /// `y` lays it in the vise. Default value: z.
    pub axis: BarAxis,
}

impl Default for Bar {
    fn default() -> Self {
        Bar { diameter: 50.0, axis: BarAxis::Z }
    }
}

/// The axis of bar stock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum BarAxis {
    X,
    Y,
    #[default]
    Z,
}

impl BarAxis {
    /// The axis as a unit vector.
    pub fn unit(self) -> DVec3 {
        match self {
            BarAxis::X => DVec3::X,
            BarAxis::Y => DVec3::Y,
            BarAxis::Z => DVec3::Z,
        }
    }

    /// The axis nearest the direction `v`.
    pub fn along(v: DVec3) -> BarAxis {
        let v = v.abs();
        if v.x >= v.y && v.x >= v.z {
            BarAxis::X
        } else if v.y >= v.z {
            BarAxis::Y
        } else {
            BarAxis::Z
        }
    }
}

impl Bar {
    /// The material over `p` of this bar filling `stock` (its bounding box), as `(floor, top)`
    /// (empty outside it).
    pub fn material(&self, stock: &Aabb) -> impl Fn(DVec2) -> (f64, f64) {
        let (c, r, axis) = (stock.center(), self.diameter / 2.0, self.axis);
        let (bottom, top) = (stock.min.z, stock.max.z);
        move |p: DVec2| {
            let across = match axis {
                BarAxis::Z => return if (p - c.truncate()).length() <= r { (bottom, top) } else { (f64::NEG_INFINITY, f64::NEG_INFINITY) },
                BarAxis::X => p.y - c.y,
                BarAxis::Y => p.x - c.x,
            };
            if across.abs() >= r {
                return (f64::NEG_INFINITY, f64::NEG_INFINITY);
            }
            let h = (r * r - across * across).sqrt();
            (c.z - h, c.z + h)
        }
    }

    /// How far `p` lies from the axis of this bar filling `stock`.
    pub fn distance(&self, stock: &Aabb, p: DVec3) -> f64 {
        let (d, a) = (p - stock.center(), self.axis.unit());
        (d - a * d.dot(a)).length()
    }
}

/// How retracts between cuts travel ([`Stock::retracts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Retracts {
    /// Just above the material on the way: the shortest in time.
    #[default]
    Minimum,
    /// At the clearance height.
    Full,
}

impl Default for Stock {
    fn default() -> Self {
        Stock {
            margin_xy: 5.0,
            margin_top: 1.0,
            margin_bottom: 0.0,
            margin_sides: None,
            size_box: None,
            clearance: 5.0,
            retract: 1.0,
            retracts: Retracts::Minimum,
            air_feed: None,
            zero: None,
            bar: None,
            material: None,
            mesh: None,
        }
    }
}

/// How far a part may stand out of an explicit stock box before it counts (mm): the box as
/// typed to a micrometre.
pub const PART_OUTSIDE: f64 = 1e-3;

/// Where a part with bounds `part` sticks out of the stock box `stock` and by how much (mm),
/// beyond [`PART_OUTSIDE`]: each side as the page names it (`-X`, `+X`, `-Y`, `+Y`, `the top`,
/// `the bottom`). Only an explicit box (`sizeBox`) can leave it out: margins are never
/// negative.
pub fn part_outside(stock: &Aabb, part: &Aabb) -> Vec<(&'static str, f64)> {
    let sides = [
        ("-X", stock.min.x - part.min.x),
        ("+X", part.max.x - stock.max.x),
        ("-Y", stock.min.y - part.min.y),
        ("+Y", part.max.y - stock.max.y),
        ("the top", part.max.z - stock.max.z),
        ("the bottom", stock.min.z - part.min.z),
    ];
    sides.into_iter().filter(|(_, by)| *by > PART_OUTSIDE).collect()
}

/// The error for a part sticking out of the stock at its sides or top (the material to make it
/// is not there): `None` where it fits, or only reaches below the stock's bottom (a relief cut
/// from a thinner board: [`below_bottom`] warns of that).
pub fn part_outside_error(stock: &Aabb, part: &Aabb) -> Option<String> {
    let out: Vec<String> = part_outside(stock, part).into_iter().filter(|(side, _)| *side != "the bottom").map(|(side, by)| format!("{by:.3} mm at {side}")).collect();
    if out.is_empty() {
        return None;
    }
    let (s, p) = (stock.size(), part.size());
    Some(format!(
        "the part sticks out of the stock by {}: the stock box is {:.3} × {:.3} × {:.3} mm, the part {:.3} × {:.3} × {:.3} mm (Stock → stock as a box: make it larger, or empty for the part with its margins)",
        out.join(", "),
        s.x,
        s.y,
        s.z,
        p.x,
        p.y,
        p.z
    ))
}

/// A warning for a part reaching below the stock box's bottom: its lowest part is not made.
pub fn below_bottom(stock: &Aabb, part: &Aabb) -> Option<String> {
    let (_, by) = part_outside(stock, part).into_iter().find(|(side, _)| *side == "the bottom")?;
    Some(format!("the part reaches {by:.3} mm below the stock box's bottom: that much of its bottom is not made (Stock → stock as a box)"))
}

impl Stock {
    /// The stock box around a part with bounds `part`.
    pub fn around(&self, part: &Aabb) -> Aabb {
        if let Some(b) = self.size_box {
            return b;
        }
        let [l, r, f, k] = self.margin_sides.unwrap_or([self.margin_xy; 4]);
        let boxed = Aabb { min: part.min - DVec3::new(l, f, self.margin_bottom), max: part.max + DVec3::new(r, k, self.margin_top) };
        let Some(bar) = self.bar else { return boxed };
        // Across its axis the bar's own size, about the part's centre; along it the margins.
        let (c, half) = (part.center(), bar.diameter / 2.0);
        let round = Aabb { min: c - DVec3::splat(half), max: c + DVec3::splat(half) };
        match bar.axis {
            BarAxis::X => Aabb { min: DVec3::new(boxed.min.x, round.min.y, round.min.z), max: DVec3::new(boxed.max.x, round.max.y, round.max.z) },
            BarAxis::Y => Aabb { min: DVec3::new(round.min.x, boxed.min.y, round.min.z), max: DVec3::new(round.max.x, boxed.max.y, round.max.z) },
            BarAxis::Z => Aabb { min: DVec3::new(round.min.x, round.min.y, boxed.min.z), max: DVec3::new(round.max.x, round.max.y, boxed.max.z) },
        }
    }

    /// The settings that do not fit: each field with why.
    fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        // Rapids run at the clearance height: at or below the stock's top they would cut.
        let size = crate::limits::MAX_SIZE;
        if !(self.clearance > 0.0 && self.clearance <= size) {
            out.push(("clearance", format!("(the height of rapid moves above the stock's top) must be a positive number of mm, at most {size} (got {})", crate::limits::shown(self.clearance))));
        }
        if !(self.retract > 0.0 && self.retract <= size) {
            out.push(("retract", format!("must be a positive number of mm, at most {size} (got {})", crate::limits::shown(self.retract))));
        }
        for (field, v) in [("marginXy", self.margin_xy), ("marginTop", self.margin_top), ("marginBottom", self.margin_bottom)] {
            if !(v >= 0.0 && v <= size) {
                out.push((field, format!("must be zero or more mm, at most {size} (got {})", crate::limits::shown(v))));
            }
        }
        if let Some(sides) = self.margin_sides {
            if sides.iter().any(|v| !(*v >= 0.0 && *v <= size)) {
                out.push(("marginSides", format!("must be zero or more mm, at most {size} (got {sides:?})")));
            }
        }
        if let Some(b) = self.size_box {
            let extent = b.size();
            if !(extent.x > 0.0 && extent.y > 0.0 && extent.z > 0.0 && extent.max_element() <= size && b.min.is_finite()) {
                out.push(("sizeBox", format!("must have a positive size on every axis, at most {size} mm")));
            }
        }
        if let Some(bar) = self.bar {
            if !(bar.diameter > 0.0 && bar.diameter <= size) {
                out.push(("bar.diameter", format!("must be a positive number of mm, at most {size} (got {})", crate::limits::shown(bar.diameter))));
            }
        }
        if let Some(file) = self.mesh.as_ref().filter(|f| f.given.is_none()) {
            if let Err(e) = file.mesh() {
                out.push(("mesh", format!("(the stock's mesh) cannot be read: {e}")));
            } else if self.bar.is_some() {
                out.push(("mesh", "(the stock's mesh) and bar: the stock is a bar or a mesh, not both".to_owned()));
            }
        }
        if let Some([dx, dy]) = self.zero.and_then(|z| z.at) {
            if !(crate::limits::in_size(dx) && crate::limits::in_size(dy)) {
                out.push(("zero.at", format!("(X0 Y0 from the stock's centre) must be on the stock: each at most {size} mm (got [{}, {}])", crate::limits::shown(dx), crate::limits::shown(dy))));
            }
        }
        if let Some(f) = self.air_feed {
            if !(0.0..=crate::limits::MAX_FEED).contains(&f) {
                out.push(("airFeed", format!("must be zero or more mm/min, at most {} (got {})", crate::limits::MAX_FEED, crate::limits::shown(f))));
            }
        }
        out
    }
}

/// A setting of a job that does not fit: its path in the job and the whole message.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
pub struct Problem {
    /// The field's path (`operations[0].stepdown`, `stock.marginXy`).
    pub path: String,
    /// What is wrong: naming the field (as the CLI says it), or, as `checkJob` gives it for a
    /// page that shows it at the field, without the path ([`Problem::at_field`]).
    pub message: String,
}

impl Problem {
    /// The problem with its message no longer repeating its path: "must be a positive number
    /// …" for `operations[0].stepdown`, "the cutter diameter must lie between …" for
    /// `tools[0].diameter`, "unknown field (did you mean diameter?)" for `tools[0].diamter`.
    pub fn at_field(self) -> Problem {
        let Problem { path, message } = self;
        // The object the path starts with (`tools[0]`, `operations[2]`, `stock`).
        let head = path.split('.').next().unwrap_or_default();
        let bare = if let Some(rest) = message.strip_prefix(&path) {
            rest.to_owned()
        } else if let Some(k) = message.find(&path) {
            // "unknown field: tools[0].diamter (did you mean diameter?)".
            format!("{}{}", message[..k].trim_end().trim_end_matches(':'), &message[k + path.len()..])
        } else if let Some(rest) = message.strip_prefix(head).filter(|_| !head.is_empty()) {
            // "tools[0] (tool 1): the cutter diameter …": what stands before the colon names
            // the object the field belongs to.
            rest.split_once(": ").map_or(rest, |(_, after)| after).to_owned()
        } else {
            message
        };
        let bare = bare.trim_start_matches([':', ' ']).to_owned();
        Problem { path, message: bare }
    }
}

/// What a job works on: a part, or a drawing for 2.5D operations.
#[derive(Clone, Debug)]
pub enum Workpiece {
    Mesh(Mesh),
    Drawing(Drawing),
}

impl From<Mesh> for Workpiece {
    fn from(m: Mesh) -> Self {
        Workpiece::Mesh(m)
    }
}

impl Workpiece {
    /// Reads the part or drawing in `bytes` (a DXF or SVG by its name or content is a drawing,
    /// anything else a mesh: STL, glTF/GLB, OBJ). The page, the CLI and the engine read a
    /// workpiece through this one function; an error names the file (`part.stl: …`).
    pub fn read(bytes: &[u8], name: Option<&str>, tolerances: &Tolerances) -> Result<Workpiece> {
        let shown = name.unwrap_or("the file");
        if crate::drawing::import::is_drawing(name, bytes) {
            crate::drawing::import::read_drawing(bytes, name, tolerances).map(Workpiece::Drawing).map_err(|e| Error::Input(format!("{shown}: {e}")))
        } else {
            crate::mesh::import::read_mesh_auto(bytes, name, tolerances).map(Workpiece::Mesh).map_err(|e| Error::Input(format!("{shown}: {e}")))
        }
    }
}

impl From<Drawing> for Workpiece {
    fn from(d: Drawing) -> Self {
        Workpiece::Drawing(d)
    }
}

/// Simulating the program after it is made (seed 002), to verify it and to show the cut.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Simulation {
    /// Simulate and verify every program. Default value: true.
    pub verify: bool,
    /// Cell size of the simulated stock (mm). Default value: the size that gives the stock
    /// about a million cells, and no smaller than 0.05 mm.
    pub cell: Option<f64>,
    /// Feeds along the path from what the simulation measured: each cut's feed raised for its
    /// chip's thinning, up to its tool's chip load and under the air feed, and each move that
    /// removes nothing at the air feed ([`crate::sim::feeds::speed_up`]). Default value: false.
    pub optimize_feeds: bool,
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation { verify: true, cell: None, optimize_feeds: false }
    }
}

/// Cells the simulated stock gets when the job does not say.
pub const SIMULATION_CELLS: f64 = 1.0e6;

impl Simulation {
    /// The cell size for a stock.
    pub fn cell_for(&self, stock: &Aabb) -> f64 {
        self.cell.unwrap_or_else(|| {
            let size = stock.size();
            ((size.x * size.y / SIMULATION_CELLS).sqrt()).max(0.05)
        })
    }
}

/// The job file format this swarf writes and reads (files from a newer one are refused; older
/// ones are read as they were written, [`super::read`]). Version 2: the step-over that is a fraction of
/// the tool's diameter (roughing, pockets) is `stepoverFraction`, and `stepover` is a distance
/// in millimetres wherever it appears.
pub const JOB_VERSION: u32 = 2;

/// The version of a job file that has none: written before versions were.
fn first_version() -> u32 {
    1
}

/// Everything needed to turn a part into G-code.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Job {
    /// Version of the job file's format ([`JOB_VERSION`] when written by this swarf); a file
    /// without one is read as version 1. Default value: the current version.
    #[serde(default = "first_version")]
    pub version: u32,
    /// Program title. Default value: "swarf job".
    pub name: String,
    pub part: PartSetup,
    /// How a DXF or SVG drawing is placed (ignored for parts).
    pub drawing: DrawingSetup,
    pub stock: Stock,
    pub tools: Vec<Tool>,
    pub operations: Vec<Operation>,
    pub post: PostSettings,
    pub simulation: Simulation,
    pub tolerances: Tolerances,
    /// The part machined from more than one side: each setup holds it its own way up, with
    /// its own work offset and operations, and starts from the stock the one before left
    /// ([`crate::job::setups`]). Empty: the job is one setup, its `operations`. Default value:
    /// none.
    pub setups: Vec<Setup>,
    /// What holds the stock (a vise, clamps), kept out of by every operation and checked
    /// against every move ([`crate::job::fixtures`]); a setup may name its own. Default value:
    /// none.
    pub fixtures: Fixtures,
    /// The machine's limits: its spindle's speed range and fastest feed, which the speeds and
    /// feeds from the material keep to. Default value: a hobby router (8000–24000 rpm, 5000
    /// mm/min).
    pub machine: crate::cutting::Machine,
}

/// How a setup turns the part over from the setup before it (the first: from the part as
/// placed), about an axis through the stock's centre, as a machinist turns it in the vise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Flip {
    /// The same face up.
    #[default]
    None,
    /// Over about the X axis: the bottom up, front and back swapped.
    AboutX,
    /// Over about the Y axis: the bottom up, left and right swapped.
    AboutY,
}

/// Which face of the part (as the job places it) a setup holds up, towards the spindle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
pub enum Up {
    /// The part's top, as placed.
    #[serde(rename = "+z")]
    PlusZ,
    /// Its bottom.
    #[serde(rename = "-z")]
    MinusZ,
    /// Its right side (+X) up: stood on its left side.
    #[serde(rename = "+x")]
    PlusX,
    #[serde(rename = "-x")]
    MinusX,
    /// Its back (+Y) up: stood on its front.
    #[serde(rename = "+y")]
    PlusY,
    #[serde(rename = "-y")]
    MinusY,
}

/// One setup of a part machined from more than one side.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Setup {
    /// Its name, in its program's name and on its setup sheet. Default value: "Setup N".
    pub name: String,
    /// How the part is turned over from the setup before. Default value: none.
    pub flip: Flip,
    /// Which face of the part it holds up, whatever the setups before did (instead of a
    /// `flip` from the setup before): `+z` its top, `-z` its bottom, `+x`, `-x`, `+y`, `-y` a
    /// side, the part stood on the opposite one. Default value: none (as `flip` says).
    pub up: Option<Up>,
    /// Then a turn about the spindle, counter-clockwise seen from above (degrees: 0, 90, 180
    /// or 270). Default value: 0.
    pub turn: u32,
    /// The work offset its program selects: `G54` to `G59`, or one the control has besides
    /// (`G59.1` to `G59.3` on LinuxCNC and grblHAL, `G54.1 P1` to `G54.1 P48` on Fanuc).
    /// Default value: the job's post's.
    pub work_offset: Option<String>,
    /// The point of the stock, as this setup holds it, that is its program's origin. Default
    /// value: the job's `stock.zero`.
    pub zero: Option<WorkZero>,
    /// What this setup cuts, in order. Default value: none.
    pub operations: Vec<Operation>,
    /// What holds the stock in this setup. Default value: the job's `fixtures`.
    pub fixtures: Option<Fixtures>,
}

impl Default for Setup {
    fn default() -> Self {
        Setup { name: String::new(), flip: Flip::None, up: None, turn: 0, work_offset: None, zero: None, operations: Vec::new(), fixtures: None }
    }
}

impl Default for Job {
    fn default() -> Self {
        Job {
            version: JOB_VERSION,
            name: "swarf job".into(),
            part: PartSetup::default(),
            drawing: DrawingSetup::default(),
            stock: Stock::default(),
            tools: vec![Tool::default()],
            operations: vec![Operation::FinishRaster(FinishRaster::default())],
            post: PostSettings::default(),
            simulation: Simulation::default(),
            tolerances: Tolerances::default(),
            setups: Vec::new(),
            fixtures: Fixtures::default(),
            machine: crate::cutting::Machine::default(),
        }
    }
}

impl Job {
    /// Places the part as the job says and returns the stock box around it (both moved to the
    /// work zero when the stock names one).
    pub fn place(&self, part: &mut Mesh) -> Aabb {
        self.place_part(part);
        let (stock, shift) = self.stock_at_zero(&part.bounds());
        if self.stock.zero.is_some() {
            part.transform(|v| v + shift);
        }
        stock
    }

    /// Places a part as read (its units, axes and turn, then where `part.placement` puts it:
    /// with a mesh stock, the blank's top centred, the part keeping its place in it), before
    /// any work zero.
    pub fn place_part(&self, part: &mut Mesh) {
        self.part.turn(part);
        let shift = match self.turned_blank() {
            Some(blank) => self.part.shift(&blank.bounds()),
            None => self.part.shift(&part.bounds()),
        };
        part.transform(|v| v + shift);
    }

    /// The mesh stock's file read and turned as the part is, not yet placed (none without a
    /// file to read: no mesh stock, one given already placed, or one that cannot be read,
    /// which [`Job::problems`] names).
    fn turned_blank(&self) -> Option<Mesh> {
        let file = self.stock.mesh.as_ref().filter(|f| f.given.is_none())?;
        let mut blank = (*file.mesh().ok()?).clone();
        self.part.turn(&mut blank);
        Some(blank)
    }

    /// The mesh stock placed with the part ([`Job::place_part`]), before any work zero.
    pub fn blank(&self) -> Option<std::sync::Arc<Mesh>> {
        if let Some(given) = self.stock.mesh.as_ref().and_then(|f| f.given.clone()) {
            return Some(given);
        }
        let mut blank = self.turned_blank()?;
        let shift = self.part.shift(&blank.bounds());
        blank.transform(|v| v + shift);
        Some(std::sync::Arc::new(blank))
    }

    /// The stock's box round a part placed with `bounds` (before any work zero): the explicit
    /// box, the mesh stock's, or the margins round the part (a bar's across its axis).
    pub fn stock_box(&self, bounds: &Aabb) -> Aabb {
        match (self.stock.size_box, self.blank()) {
            (None, Some(blank)) => blank.bounds(),
            _ => self.stock.around(bounds),
        }
    }

    /// The stock box round a part placed with `bounds`, moved to the work zero when the stock
    /// names one, and the move.
    pub fn stock_at_zero(&self, bounds: &Aabb) -> (Aabb, DVec3) {
        let stock = self.stock_box(bounds);
        let shift = self.stock.zero.map_or(DVec3::ZERO, |zero| -zero.point(&stock, bounds.max.z));
        (Aabb { min: stock.min + shift, max: stock.max + shift }, shift)
    }

    /// The least material any operation leaves on the part (mm); infinite without operations.
    pub fn allowance(&self) -> f64 {
        self.operations.iter().filter(|o| o.op().enabled()).map(Operation::allowance).fold(f64::INFINITY, f64::min)
    }

    /// How the job's program is verified on `stock`: its simulation cell (unless `cell`
    /// overrides it) and the least allowance of its operations (0 without operations).
    pub fn verify_settings(&self, stock: &Aabb, cell: Option<f64>) -> VerifySettings {
        let allowance = self.allowance();
        VerifySettings { cell: cell.unwrap_or_else(|| self.simulation.cell_for(stock)), allowance: if allowance.is_finite() { allowance } else { 0.0 } }
    }

    /// Checks the job before any work: the first of its [`Job::problems`].
    pub fn validate(&self) -> Result<()> {
        match self.problems().into_iter().next() {
            Some(p) => Err(Error::Input(p.message)),
            None => Ok(()),
        }
    }

    /// Every setting of the job that does not fit, each named by its path in the job
    /// (`tools[1].feedRate`, `operations[0].stepdown`): the page marks each at its field as the
    /// user types, with the core's own checks. An operation or a tool says its first.
    pub fn problems(&self) -> Vec<Problem> {
        self.problems_with(Known::default())
    }

    /// [`Job::problems`], and what does not fit what is `known` of the workpiece: with the
    /// placed part's bounds (as the page shows them), a stock box the part sticks out of; with
    /// the holes found in it, a hole operation's settings that do not fit the holes it takes (a
    /// hole deeper than the flutes, a peck deeper than the hole).
    pub fn problems_with(&self, known: Known) -> Vec<Problem> {
        if self.setups.is_empty() {
            return self.problems_of_one(known);
        }
        // The job's own settings, then each setup's: its operations as a job of their own.
        let mut out = Job { operations: Vec::new(), setups: Vec::new(), ..self.clone() }.problems_of_one(known);
        let mut say = |path: String, message: String| out.push(Problem { path, message });
        if self.setups.len() > crate::limits::MAX_SETUPS {
            say("setups".into(), format!("setups: {} setups, more than a part has sides (at most {})", self.setups.len(), crate::limits::MAX_SETUPS));
        }
        for (k, setup) in self.setups.iter().enumerate() {
            if setup.up.is_some() && setup.flip != Flip::None {
                say(format!("setups[{k}].up"), format!("setups[{k}]: give the face up (up) or a flip from the setup before (flip), not both"));
            }
            if setup.turn % 90 != 0 || setup.turn >= 360 {
                say(format!("setups[{k}].turn"), format!("setups[{k}].turn turns the part about the spindle by 0, 90, 180 or 270 degrees (got {})", setup.turn));
            }
            let post = self.post.post();
            if let Some(w) = setup.work_offset.as_deref().filter(|w| !post.has_work_offset(w)) {
                say(format!("setups[{k}].workOffset"), format!("setups[{k}].workOffset must be {} (got {w:?})", post.work_offsets_words()));
            }
            for (path, message) in setup.fixtures.as_ref().map(|f| f.problems(&format!("setups[{k}].fixtures"))).unwrap_or_default() {
                say(path, message);
            }
            if !setup.operations.iter().any(|o| o.op().enabled()) {
                say(format!("setups[{k}].operations"), format!("setups[{k}].operations: the setup has nothing to cut"));
            }
            let one = Job { operations: setup.operations.clone(), setups: Vec::new(), ..self.clone() };
            for p in one.problems_of_one(Known::default()).into_iter().filter(|p| p.path.starts_with("operations")) {
                say(format!("setups[{k}].{}", p.path), format!("setups[{k}].{}", p.message));
            }
        }
        out
    }

    /// [`Job::problems_with`] of a job of one setup.
    fn problems_of_one(&self, known: Known) -> Vec<Problem> {
        let part = known.part;
        let mut out = Vec::new();
        let mut say = |path: String, message: String| out.push(Problem { path, message });
        for (path, message) in self.fixtures.problems("fixtures") {
            say(path, message);
        }
        let positive = |v: f64| v > 0.0 && v.is_finite();
        if self.tools.len() > crate::limits::MAX_TOOLS {
            say("tools".into(), format!("tools: {} tools, more than a library holds (at most {})", self.tools.len(), crate::limits::MAX_TOOLS));
        }
        if self.operations.len() > crate::limits::MAX_OPERATIONS {
            say("operations".into(), format!("operations: {} operations, more than a job needs (at most {}); split the job", self.operations.len(), crate::limits::MAX_OPERATIONS));
        }
        for (field, message) in self.tolerances.problems() {
            say(format!("tolerances.{field}"), format!("tolerances.{field} {message}"));
        }
        for (field, message) in self.machine.problems() {
            say(format!("machine.{field}"), format!("machine.{field} {message}"));
        }
        for (i, tool) in self.tools.iter().enumerate() {
            if let Err(e) = tool.cutter.validate() {
                let field = match e {
                    crate::cutter::CutterError::Diameter(_) => "diameter",
                    crate::cutter::CutterError::CornerRadius { .. } => "cornerRadius",
                    crate::cutter::CutterError::FluteLength(_) => "fluteLength",
                    crate::cutter::CutterError::Angle(_) => "angle",
                    crate::cutter::CutterError::TipDiameter { .. } => "tipDiameter",
                };
                say(format!("tools[{i}].{field}"), format!("tools[{i}] (tool {}): {e}", tool.number));
            }
            for (field, v, most) in
                [("spindleRpm", tool.spindle_rpm, crate::limits::MAX_RPM), ("feedRate", tool.feed_rate, crate::limits::MAX_FEED), ("plungeRate", tool.plunge_rate, crate::limits::MAX_FEED)]
            {
                if !(positive(v) && v <= most) {
                    say(format!("tools[{i}].{field}"), format!("tools[{i}].{field} must be a positive number, at most {most} (got {})", crate::limits::shown(v)));
                }
            }
            // What the post writes of them: a speed or a feed that rounds to nothing is one the
            // control refuses (`F0`) or stops the spindle with (`S0`).
            let per_unit = 1.0 / self.post.units.mm();
            let decimals = self.post.post().feed_decimals;
            let written = |v: f64, decimals: usize| crate::post::number(v, decimals).parse::<f64>().unwrap_or(0.0);
            if positive(tool.spindle_rpm) && written(tool.spindle_rpm, 0) < 1.0 {
                say(format!("tools[{i}].spindleRpm"), format!("tools[{i}].spindleRpm is written as whole turns a minute: {} is S0, no spindle at all", crate::limits::shown(tool.spindle_rpm)));
            }
            for (field, v) in [("feedRate", tool.feed_rate), ("plungeRate", tool.plunge_rate)] {
                if positive(v) && written(v * per_unit, decimals) <= 0.0 {
                    say(
                        format!("tools[{i}].{field}"),
                        format!(
                            "tools[{i}].{field} of {} mm/min is written F0 with the post's {decimals} decimals ({}), which a control refuses",
                            crate::limits::shown(v),
                            if per_unit == 1.0 { "mm/min" } else { "in/min" }
                        ),
                    );
                }
            }
            for (field, message) in tool.holder.iter().flat_map(|h| h.problems()) {
                say(format!("tools[{i}].holder.{field}"), format!("tools[{i}].holder.{field} {message}"));
            }
            if !(1..=crate::limits::MAX_FLUTES).contains(&tool.flutes) {
                say(format!("tools[{i}].flutes"), format!("tools[{i}].flutes must be 1 to {} (got {})", crate::limits::MAX_FLUTES, tool.flutes));
            }
            if tool.stick_out.is_some_and(|s| !(s >= tool.cutter.flute_length && s <= crate::limits::MAX_SIZE)) {
                say(format!("tools[{i}].stickOut"), format!("tools[{i}].stickOut must be at least the flute length ({} mm) and at most 10 m", tool.cutter.flute_length));
            }
            if let Some(j) = self.tools[..i].iter().position(|t| t.number == tool.number) {
                say(format!("tools[{i}].number"), format!("tools[{i}].number: tools[{j}] has the number {} too", tool.number));
            }
        }
        if let Err(e) = self.post.validate(&self.tools) {
            say(e.split([' ', ':']).next().filter(|p| p.starts_with("post.")).unwrap_or("post").to_owned(), e);
        }
        if !positive(self.part.scale) {
            say("part.scale".into(), format!("part.scale must be a positive number (got {})", crate::limits::shown(self.part.scale)));
        }
        if self.part.rotation % 90 != 0 || self.part.rotation >= 360 {
            say("part.rotation".into(), format!("part.rotation turns the part about Z by 0, 90, 180 or 270 degrees (got {})", self.part.rotation));
        }
        for (field, message) in self.stock.problems() {
            say(format!("stock.{field}"), format!("stock.{field} {message}"));
        }
        // Only a box can leave the part out (margins are checked on their own above).
        if let (Some(part), Some(_)) = (part, self.stock.size_box) {
            if let Some(message) = part_outside_error(&self.stock_box(part), part) {
                say("stock.sizeBox".into(), message);
            }
        }
        let thickness = self.drawing.thickness;
        if !(positive(thickness) && thickness <= crate::limits::MAX_SIZE) {
            say(
                "drawing.thickness".into(),
                format!("drawing.thickness: the sheet thickness must be a positive number of mm, at most {} (got {})", crate::limits::MAX_SIZE, crate::limits::shown(thickness)),
            );
        }
        for (i, op) in self.operations.iter().enumerate() {
            let o = op.op();
            let missing = o.tools().into_iter().find(|n| !self.tools.iter().any(|t| t.number == *n));
            if let Some(number) = missing {
                let have: Vec<String> = self.tools.iter().map(|t| t.number.to_string()).collect();
                let field = if o.tools().len() == 1 && o.tools()[0] == o.tool() { "tool" } else { "tools" };
                say(
                    format!("operations[{i}].{field}"),
                    format!("operations[{i}].{field}: no tool number {number} in the tool library (it has {})", if have.is_empty() { "none".into() } else { have.join(", ") }),
                );
            } else if let Some((t, takes)) = self.tools.iter().filter(|t| o.tools().contains(&t.number)).find_map(|t| o.takes(&t.cutter).err().map(|w| (t, w))) {
                let field = if o.tools().len() == 1 && o.tools()[0] == o.tool() { "tool" } else { "tools" };
                say(format!("operations[{i}].{field}"), format!("operations[{i}].{field}: T{} is a {}: '{}' cuts with {takes}", t.number, t.cutter.describe(), o.name()));
            } else if let Err(e) = o.validate() {
                say(format!("operations[{i}].{}", e.field), format!("operations[{i}].{} {} ('{}')", e.field, e.message, o.name()));
            } else if let Some((step, tool)) = deeper_than_the_flutes(op, &self.tools) {
                // Two settings that do not fit each other, said as they are typed (issue 55),
                // not after the plan by the simulation's "bury the tool".
                say(
                    format!("operations[{i}].stepdown"),
                    format!(
                        "operations[{i}].stepdown: the step-down ({} mm) is deeper than T{}'s flutes ({} mm): its body would rub the material; step down at most {} mm, or give T{} its real flute length ('{}')",
                        crate::limits::shown(step),
                        tool.number,
                        crate::limits::shown(tool.cutter.flute_length),
                        crate::limits::shown(tool.cutter.flute_length),
                        tool.number,
                        o.name()
                    ),
                );
            } else if let (Some(holes), Some(tool)) = (known.holes, self.tools.iter().find(|t| t.number == o.tool())) {
                for (field, message) in o.hole_problems(holes, tool) {
                    say(format!("operations[{i}].{field}"), format!("operations[{i}].{field}: {message} ('{}')", o.name()));
                }
            }
        }
        out
    }
}

/// What is known of the workpiece beside the job, for the checks that need it
/// ([`Job::problems_with`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Known<'a> {
    /// The placed part's bounds.
    pub part: Option<&'a Aabb>,
    /// The holes found in the part or drawing, numbered as the operations take them.
    pub holes: Option<&'a [crate::holes::Hole]>,
}

/// The step-down of an operation that steps down into material at its tool's full width
/// ([`crate::machining::Operate::stepdown`]), with its tool, where it is deeper than the tool's
/// flutes.
fn deeper_than_the_flutes<'a>(op: &Operation, tools: &'a [Tool]) -> Option<(f64, &'a Tool)> {
    let step = op.op().stepdown()?;
    let tool = tools.iter().find(|t| t.number == op.op().tool())?;
    (step > tool.cutter.flute_length + 1e-9).then_some((step, tool))
}

/// The units a drawing's numbers are in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum DrawingUnits {
    /// As the file says ($INSUNITS, the SVG's width and viewBox; px at 96 per inch).
    #[default]
    File,
    Mm,
    Inch,
}

/// Where a drawing is put.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum DrawingOrigin {
    /// As drawn.
    Keep,
    /// Its lower left corner at X0 Y0.
    #[default]
    LowerLeft,
    /// Its centre at X0 Y0.
    Center,
}

/// How a drawing becomes a sheet on the machine: the stock's top is Z0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct DrawingSetup {
    /// Default value: file.
    pub units: DrawingUnits,
    /// Default value: lower left.
    pub origin: DrawingOrigin,
    /// Thickness of the sheet (mm). Default value: 6.
    pub thickness: f64,
}

impl Default for DrawingSetup {
    fn default() -> Self {
        DrawingSetup { units: DrawingUnits::File, origin: DrawingOrigin::LowerLeft, thickness: 6.0 }
    }
}

impl DrawingSetup {
    /// Scales the drawing to the chosen units and moves it to the chosen origin.
    pub fn apply(&self, d: &mut Drawing) {
        let wanted = match self.units {
            DrawingUnits::File => d.scale,
            DrawingUnits::Mm => 1.0,
            DrawingUnits::Inch => 25.4,
        };
        let k = if d.scale > 0.0 { wanted / d.scale } else { 1.0 };
        d.transform(k, DVec2::ZERO);
        d.scale = wanted;
        let b = d.bounds();
        let shift = match self.origin {
            DrawingOrigin::Keep => DVec2::ZERO,
            DrawingOrigin::LowerLeft => -b.min,
            DrawingOrigin::Center => -b.center(),
        };
        if !b.is_empty() {
            d.transform(1.0, shift);
        }
    }
}

impl Job {
    /// Whether setup `setup`'s work zero (the job's where it has none; the job's own with no
    /// setup named) puts X0 Y0 at a point (`zero.at`).
    pub fn zero_at(&self, setup: Option<usize>) -> bool {
        setup.and_then(|k| self.setups.get(k)).and_then(|s| s.zero).or(self.stock.zero).and_then(|z| z.at).is_some()
    }

    /// Each tool's speeds and feeds as this job cuts them ([`crate::cutting::cutting_data`]).
    pub fn cutting_data(&self) -> Vec<crate::cutting::CuttingData> {
        let deepest = self.deepest_cuts();
        self.tools.iter().zip(deepest).map(|(t, depth)| crate::cutting::cutting_data_at(t, self.stock.material, &self.machine, depth)).collect()
    }

    /// How deep each tool cuts at most, as its operations say (in the order of `tools`): a
    /// step-down where the operation steps down, else (a finishing) the most any operation
    /// of the job leaves on the part for it; none where an operation using it says neither,
    /// or none uses it (a cut as deep as it is wide).
    pub fn deepest_cuts(&self) -> Vec<Option<f64>> {
        let all: Vec<&Operation> = self.operations.iter().chain(self.setups.iter().flat_map(|s| s.operations.iter())).filter(|o| o.op().enabled()).collect();
        let left = all.iter().map(|o| o.op().allowance()).fold(0.0, f64::max);
        self.tools
            .iter()
            .map(|t| {
                let mut deepest: Option<f64> = None;
                for o in all.iter().filter(|o| o.op().tools().contains(&t.number)) {
                    let depth = o.op().stepdown().or_else(|| (o.is_finishing() && left > 0.0).then_some(left))?;
                    deepest = Some(deepest.map_or(depth, |d| d.max(depth)));
                }
                deepest
            })
            .collect()
    }

    /// The feed of a G1 its operation knows cuts nothing: the stock's `airFeed` (the rapid
    /// rate by default), no faster than the machine's rapids or its feeds.
    pub fn air_feed(&self) -> f64 {
        self.stock.air_feed.unwrap_or(self.post.rapid_rate).min(self.post.rapid_rate).min(self.machine.max_feed)
    }

    /// How the job's rapids are timed: at its machine's rates per axis where known, else at
    /// the post's `rapidRate` along each move.
    pub fn rapids(&self) -> crate::toolpath::Rapids {
        crate::toolpath::Rapids { rate: self.post.rapid_rate, axes: self.machine.rapids }
    }

    /// The job's post settings as its programs are written: timing rapids as [`Job::rapids`].
    pub fn post_for_machine(&self) -> crate::post::PostSettings {
        crate::post::PostSettings { rapid_axes: self.machine.rapids, tool_changer: self.machine.tool_changer, length_sensor: self.machine.length_sensor, ..self.post.clone() }
    }

    /// The job with its tools' speeds and feeds from the stock's material, where they take
    /// them: what runs, is timed and posted.
    pub fn with_cutting_data(&self) -> std::borrow::Cow<'_, Job> {
        let max = self.machine.max_feed;
        if self.stock.material.is_none() && self.tools.iter().all(|t| t.feed_rate <= max && t.plunge_rate <= max) {
            return std::borrow::Cow::Borrowed(self);
        }
        let mut job = self.clone();
        for (t, c) in job.tools.iter_mut().zip(self.cutting_data()) {
            t.spindle_rpm = c.spindle_rpm;
            t.feed_rate = c.feed_rate;
            t.plunge_rate = c.plunge_rate;
        }
        std::borrow::Cow::Owned(job)
    }

    /// What is said of the tools the machine does not suit: feeds as typed faster than it goes
    /// (each held at its fastest by [`crate::cutting::cutting_data`]), or a spindle whose
    /// slowest speed runs a tool far faster at its edge than the material's chart gives.
    pub fn machine_warnings(&self) -> Vec<crate::error::Warning> {
        let m = &self.machine;
        let shown = crate::limits::shown;
        self.tools
            .iter()
            .zip(self.cutting_data())
            .filter_map(|(t, c)| {
                let why = if !c.from_material && (c.feed_rate < t.feed_rate || c.plunge_rate < t.plunge_rate) {
                    format!("its feed as typed (F{}, plunge F{}) is faster than the {}'s fastest, {} mm/min: held at it", shown(t.feed_rate), shown(t.plunge_rate), m.name, shown(m.max_feed))
                } else {
                    let over = crate::cutting::surface_too_fast(t, self.stock.material.filter(|_| c.from_material)?, m)?;
                    format!("the {}'s slowest spindle speed, {} rpm, runs it at {over}", m.name, shown(m.spindle_min))
                };
                Some(crate::error::Warning::of(&format!("T{}", t.number), why))
            })
            .chain(self.too_deep())
            .collect()
    }

    /// Operations in a material whose levels cut deeper than the speeds' chart allows at its
    /// feeds: the charts' chip loads are for a cut at most as deep as the tool is wide at full
    /// width (a slot), so a level cleared at full width deeper than the tool's diameter is said
    /// with the figures. Adaptive clearing holds the tool to a light width, and cuts as deep as
    /// its flutes reach (what `Job::problems` holds it to).
    fn too_deep(&self) -> Vec<crate::error::Warning> {
        let Some(material) = self.stock.material else { return Vec::new() };
        let shown = crate::limits::shown;
        let all = self.operations.iter().chain(self.setups.iter().flat_map(|s| s.operations.iter()));
        all.filter(|o| o.op().enabled())
            .filter(|o| !matches!(o, Operation::RoughAdaptive(_)) && !matches!(o, Operation::Pocket2d(p) if p.pattern == crate::machining::settings::PocketPattern::Adaptive))
            .filter_map(|o| {
                let depth = o.op().stepdown()?;
                let tool = self.tools.iter().find(|t| t.number == o.op().tool() && t.speeds != crate::tool::Speeds::AsTyped)?;
                let d = tool.cutter.diameter;
                (depth > d + 1e-9 && !tool.cutter.is_cone()).then(|| {
                    crate::error::Warning::of(
                        o.name(),
                        format!(
                            "its step-down of {} mm is {:.1} × its φ{} tool's diameter: the {} chart's feeds are for a cut at most one diameter deep at full width; at {} mm deep in {} lower the step-down to {} mm or less, or clear it adaptively (a light width, as deep as the flutes)",
                            shown(depth),
                            depth / d,
                            shown(d),
                            material.words(),
                            shown(depth),
                            material.words(),
                            shown(d)
                        ),
                    )
                })
            })
            .collect()
    }
}

/// A work zero (`field`) is on the stock, whose box in the program's frame is `stock`: X0 Y0
/// within its outline seen from above (a setup's zero `at` far off it, `[1e6, 0]`, wrote
/// `G0 X-999987.768`).
pub fn zero_on_stock(stock: &Aabb, field: &str) -> crate::error::Result<()> {
    const SLACK: f64 = 1e-9;
    if stock.min.x <= SLACK && stock.max.x >= -SLACK && stock.min.y <= SLACK && stock.max.y >= -SLACK {
        return Ok(());
    }
    let (c, size) = (stock.center(), stock.size());
    Err(crate::error::Error::Input(format!(
        "{field}: X0 Y0 at X{:+.3} Y{:+.3} from the stock's centre lies off the {:.3} × {:.3} mm stock; put it on the stock (the page's \"X0 Y0 on the picked hole\" puts it on a hole's centre)",
        -c.x, -c.y, size.x, size.y
    )))
}
