//! A job: stock, tools, operations and post settings, as one serde type. The same JSON drives
//! the page, the CLI and the tests; [`run`] turns a job and a part or drawing into tool paths
//! and G-code, reporting progress and stopping when cancelled.
//!
//! A job is a machining sequence: its operations plan one after the other in one shared
//! [`Context`] (the placed part or drawing, the stock, the safe heights, the tool library, the
//! caches), and after each one its moves are applied to the in-process stock, so the next one
//! enters and links over the material that is really there (DESIGN.md ideas 5 and 6).

pub mod bench;
pub mod drawing;

pub mod pool;
pub mod project;
pub mod read;
pub mod report;

use serde::{Deserialize, Serialize};

pub use self::drawing::{DrawingOrigin, DrawingSetup, DrawingUnits};
pub use self::report::OperationReport;
pub use crate::operations::{Boundary, FinishRaster, Operation};
pub use crate::tool::Tool;

use crate::cutter::Cutter;
use crate::error::{Error, Result, Warning};
use crate::operations::Profile2d;
use crate::geom::{Aabb, DVec3, Tolerances};
use crate::mesh::{placement::PartSetup, Mesh};
use crate::post::{write_mapped, CycleTime, PostSettings, TimeItem};
use crate::profile::Drawing;
use crate::progress::Progress;
use crate::sim::program::{program_moves, ProgramMove};
use crate::sim::verify::{BandCut, Simulator, Verification, VerifySettings};
use crate::sim::DexelStock;
use crate::machining::context::{Caches, CacheCounts, Context, SafeHeights, Sheet};
use crate::machining::report::{Groove, LoadReport, Planned, SheetCut, StageOctants, StageReport};
use crate::machining::Works;
use crate::toolpath::{PathStats, Toolpath};
use crate::zmap::cc::cc_zmap;
use crate::zmap::HeightField;

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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct WorkZero {
    /// Default value: partTop.
    pub height: ZeroHeight,
    /// Default value: center.
    pub corner: ZeroCorner,
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
        let (x, y) = match self.corner {
            ZeroCorner::Center => (c.x, c.y),
            ZeroCorner::FrontLeft => (lo.x, lo.y),
            ZeroCorner::FrontRight => (hi.x, lo.y),
            ZeroCorner::BackLeft => (lo.x, hi.y),
            ZeroCorner::BackRight => (hi.x, hi.y),
        };
        DVec3::new(x, y, z)
    }
}

/// The stock, as a machinist sets it: margins around the placed part on every side, or an
/// explicit box; the heights of moves between cuts; and the work zero.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
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
    /// the verification holds each to cutting nothing. At most the rapid rate; no faster than
    /// the tool's feed keeps them at it. Default value: the post's rapid rate.
    pub air_feed: Option<f64>,
    /// Moves part and stock so that this point is the program's origin (for parts; a sheet's
    /// top is always Z0). Default value: none (as the part's placement puts it).
    pub zero: Option<WorkZero>,
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
        Stock { margin_xy: 5.0, margin_top: 1.0, margin_bottom: 0.0, margin_sides: None, size_box: None, clearance: 5.0, retract: 1.0, retracts: Retracts::Minimum, air_feed: None, zero: None }
    }
}

impl Stock {
    /// The stock box around a part with bounds `part`.
    pub fn around(&self, part: &Aabb) -> Aabb {
        if let Some(b) = self.size_box {
            return b;
        }
        let [l, r, f, k] = self.margin_sides.unwrap_or([self.margin_xy; 4]);
        Aabb { min: part.min - DVec3::new(l, f, self.margin_bottom), max: part.max + DVec3::new(r, k, self.margin_top) }
    }

    /// The settings that do not fit: each field with why.
    fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        // Rapids run at the clearance height: at or below the stock's top they would cut.
        if !(self.clearance > 0.0 && self.clearance.is_finite()) {
            out.push(("clearance", format!("(the height of rapid moves above the stock's top) must be a positive number (got {})", self.clearance)));
        }
        if !(self.retract > 0.0 && self.retract.is_finite()) {
            out.push(("retract", format!("must be a positive number (got {})", self.retract)));
        }
        for (field, v) in [("marginXy", self.margin_xy), ("marginTop", self.margin_top), ("marginBottom", self.margin_bottom)] {
            if !(v >= 0.0 && v.is_finite()) {
                out.push((field, format!("must be zero or more (got {v})")));
            }
        }
        if let Some(sides) = self.margin_sides {
            if sides.iter().any(|v| !(*v >= 0.0 && v.is_finite())) {
                out.push(("marginSides", format!("must be zero or more (got {sides:?})")));
            }
        }
        if let Some(b) = self.size_box {
            let size = b.size();
            if !(size.x > 0.0 && size.y > 0.0 && size.z > 0.0 && size.is_finite()) {
                out.push(("sizeBox", "must have a positive size on every axis".into()));
            }
        }
        if let Some(f) = self.air_feed {
            if !(f >= 0.0 && f.is_finite()) {
                out.push(("airFeed", format!("must be zero or more (mm/min; got {f})")));
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
    /// What is wrong, naming the field.
    pub message: String,
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
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation { verify: true, cell: None }
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
/// ones are read as they were written, [`read`]). Version 2: the step-over that is a fraction of
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
        }
    }
}

/// What a job produced.
#[derive(Clone, Debug)]
pub struct JobOutput {
    /// The part as placed (mm, Z up); empty for a drawing.
    pub part: Mesh,
    /// The drawing as placed, for 2.5D jobs.
    pub drawing: Option<Drawing>,
    pub stock: Aabb,
    pub clearance_z: f64,
    pub paths: Vec<Toolpath>,
    /// Per tool path, the index of the operation that made it.
    pub path_operations: Vec<usize>,
    pub gcode: String,
    /// The line of `gcode` each move of `moves` ended on ([`crate::post::Written::move_lines`]).
    pub move_lines: Vec<u32>,
    /// The program's cycle time as the post wrote it: per tool path, tool changes, in all.
    pub cycle: CycleTime,
    /// The cycle time by operation, tool changes and the rest, in whole seconds that sum to
    /// the whole: the breakdown the program's head, the CLI and the page show.
    pub time: Vec<TimeItem>,
    pub stats: PathStats,
    /// Every move of the program, timed, in order.
    pub moves: Vec<ProgramMove>,
    /// What each operation did: time, length, volume removed, peak MRR, what it left.
    pub operations: Vec<OperationReport>,
    /// The simulation of the program and what it found, when the job asked for it.
    pub verification: Option<Verification>,
    /// Things the user should know that did not stop the job, with their operation.
    pub warnings: Vec<Warning>,
    /// What makes the program unsafe to run (a gouge, a rapid through stock, the tool's body in
    /// material: [`crate::sim::verify::Report::problem`]), when verification found it. Such a
    /// program is not a finished one: [`JobOutput::checked`] turns it into an error, the CLI
    /// writes it only when asked to, and the page keeps its download behind a confirmation.
    pub problem: Option<String>,
    /// Lookups of the CL surface cache: a second operation on the same cutter and grid hits.
    pub cache: CacheCounts,
    /// The octants of each stage of octree roughing (seed 000), for the view.
    pub octants: Vec<StageOctants>,
}

impl JobOutput {
    /// The output, or [`Error::Unsafe`] when verification found a problem.
    pub fn checked(self) -> Result<JobOutput> {
        match self.problem {
            Some(problem) => Err(Error::Unsafe(problem)),
            None => Ok(self),
        }
    }

    /// The G-code with a warning comment at its head naming the problem, if there is one (for
    /// a program written anyway).
    pub fn gcode_marked(&self) -> String {
        marked(&self.gcode, self.problem.as_deref())
    }
}

/// `gcode` with a warning comment at its head naming `problem`, if there is one.
pub fn marked(gcode: &str, problem: Option<&str>) -> String {
    match problem {
        Some(problem) => {
            // A program that starts with a tape mark (Fanuc) keeps it first.
            let warning = format!("(WARNING: NOT SAFE TO RUN: {})\n", crate::post::comment(problem));
            match gcode.strip_prefix("%\n") {
                Some(rest) => format!("%\n{warning}{rest}"),
                None => format!("{warning}{gcode}"),
            }
        }
        None => gcode.to_owned(),
    }
}

impl Job {
    /// The default job for a drawing: a φ3 flat end mill cutting the drawing's parts out of
    /// a 6 mm sheet (holes inside, outlines outside), four tabs a part.
    pub fn default_for_drawing() -> Job {
        let tool = Tool { number: 1, name: "3 mm flat end mill".into(), cutter: Cutter::flat(3.0), feed_rate: 800.0, plunge_rate: 200.0, ..Tool::default() };
        let profile = Profile2d { tabs: crate::operations::Tabs { count: 4, ..Default::default() }, ..Profile2d::default() };
        Job { name: "swarf sheet job".into(), tools: vec![tool], operations: vec![Operation::Profile2d(profile)], ..Job::default() }
    }

    /// The mould job the demo and the page's sample part run: z-level roughing with a φ6 flat
    /// end (leaving 0.5 mm), then a φ6 ball finishing the shallow areas by raster and the steep
    /// ones by waterline.
    pub fn demo() -> Job {
        use crate::operations::FinishWaterline;
        use crate::operations::RoughZlevel;
        let flat = Tool { number: 1, name: "6 mm flat end mill".into(), cutter: Cutter { flute_length: 30.0, ..Cutter::flat(6.0) }, feed_rate: 1200.0, plunge_rate: 300.0, ..Tool::default() };
        let ball = Tool { number: 2, name: "6 mm ball end mill".into(), cutter: Cutter { flute_length: 30.0, ..Cutter::ball(6.0) }, ..Tool::default() };
        let steep = 40.0;
        Job {
            name: "swarf demo".into(),
            tools: vec![flat, ball],
            operations: vec![
                Operation::RoughZlevel(RoughZlevel { name: "rough".into(), tool: 1, ..RoughZlevel::default() }),
                Operation::FinishRaster(FinishRaster { name: "finish shallow".into(), tool: 2, stepover: 0.5, slope_max: Some(steep), ..FinishRaster::default() }),
                Operation::FinishWaterline(FinishWaterline { name: "finish steep".into(), tool: 2, scallop: Some(0.01), slope_min: steep, ..FinishWaterline::default() }),
            ],
            ..Job::default()
        }
    }

    /// The job swarf.js's engine runs once as it starts, in a worker of its own, on
    /// [`crate::mesh::sample::warm_up_part`] (0.1 s natively, about 0.6 s in a fresh browser):
    /// the demo's three operations with a zigzag roughing between, so that the browser has
    /// compiled (and mostly optimised) the code a user's first job runs before the user asks
    /// for it. Without it that first job runs partly in baseline code: the pocket test's
    /// zigzag 0.16–0.21 s against 0.10 s (BENCHMARKS.md, "The warm-up in a worker of its own").
    pub fn warm_up() -> Job {
        use crate::machining::settings::Roughing;
        use crate::operations::RoughZigzag;
        let mut job = Job::demo();
        job.name = "warm-up".into();
        job.operations.insert(1, Operation::RoughZigzag(RoughZigzag { name: "zigzag".into(), tool: 1, roughing: Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() }, ..RoughZigzag::default() }));
        // Coarse and small: what matters is that each strategy's code runs, not the finish.
        job.tools[0].cutter = Cutter { flute_length: 15.0, ..Cutter::flat(3.0) };
        job.tools[1].cutter = Cutter { flute_length: 15.0, ..Cutter::ball(3.0) };
        for op in &mut job.operations {
            match op {
                Operation::RoughZlevel(o) => (o.roughing.grid, o.stepdown) = (0.5, 2.0),
                Operation::RoughZigzag(o) => (o.roughing.grid, o.stepdown, o.stepover_fraction) = (0.5, 3.0, 0.8),
                Operation::FinishRaster(o) => (o.grid, o.stepover) = (0.5, 2.0),
                Operation::FinishWaterline(o) => (o.grid, o.stepdown, o.scallop) = (0.5, 1.5, None),
                _ => {}
            }
        }
        job
    }

    /// Places the part as the job says and returns the stock box around it (both moved to the
    /// work zero when the stock names one).
    pub fn place(&self, part: &mut Mesh) -> Aabb {
        self.part.apply(part);
        let bounds = part.bounds();
        let stock = self.stock.around(&bounds);
        match self.stock.zero {
            Some(zero) => {
                let shift = -zero.point(&stock, bounds.max.z);
                part.transform(|v| v + shift);
                Aabb { min: stock.min + shift, max: stock.max + shift }
            }
            None => stock,
        }
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
        let mut out = Vec::new();
        let mut say = |path: String, message: String| out.push(Problem { path, message });
        let positive = |v: f64| v > 0.0 && v.is_finite();
        for (i, tool) in self.tools.iter().enumerate() {
            if let Err(e) = tool.cutter.validate() {
                let field = match e {
                    crate::cutter::CutterError::Diameter(_) => "diameter",
                    crate::cutter::CutterError::CornerRadius { .. } => "cornerRadius",
                    crate::cutter::CutterError::FluteLength(_) => "fluteLength",
                };
                say(format!("tools[{i}].{field}"), format!("tools[{i}] (tool {}): {e}", tool.number));
            }
            for (field, v) in [("spindleRpm", tool.spindle_rpm), ("feedRate", tool.feed_rate), ("plungeRate", tool.plunge_rate)] {
                if !positive(v) {
                    say(format!("tools[{i}].{field}"), format!("tools[{i}].{field} must be a positive number (got {v})"));
                }
            }
            if tool.stick_out.is_some_and(|s| !(s >= tool.cutter.flute_length && s.is_finite())) {
                say(format!("tools[{i}].stickOut"), format!("tools[{i}].stickOut must be at least the flute length ({} mm)", tool.cutter.flute_length));
            }
            if let Some(j) = self.tools[..i].iter().position(|t| t.number == tool.number) {
                say(format!("tools[{i}].number"), format!("tools[{i}].number: tools[{j}] has the number {} too", tool.number));
            }
        }
        if let Err(e) = self.post.validate(&self.tools) {
            say(e.split([' ', ':']).next().filter(|p| p.starts_with("post.")).unwrap_or("post").to_owned(), e);
        }
        if !positive(self.part.scale) {
            say("part.scale".into(), format!("part.scale must be a positive number (got {})", self.part.scale));
        }
        if self.part.rotation % 90 != 0 || self.part.rotation >= 360 {
            say("part.rotation".into(), format!("part.rotation turns the part about Z by 0, 90, 180 or 270 degrees (got {})", self.part.rotation));
        }
        for (field, message) in self.stock.problems() {
            say(format!("stock.{field}"), format!("stock.{field} {message}"));
        }
        let thickness = self.drawing.thickness;
        if !positive(thickness) {
            say("drawing.thickness".into(), format!("drawing.thickness: the sheet thickness must be a positive number (got {thickness})"));
        }
        for (i, op) in self.operations.iter().enumerate() {
            let o = op.op();
            let missing = o.tools().into_iter().find(|n| !self.tools.iter().any(|t| t.number == *n));
            if let Some(number) = missing {
                let have: Vec<String> = self.tools.iter().map(|t| t.number.to_string()).collect();
                let field = if o.tools().len() == 1 && o.tools()[0] == o.tool() { "tool" } else { "tools" };
                say(format!("operations[{i}].{field}"), format!("operations[{i}].{field}: no tool number {number} in the tool library (it has {})", if have.is_empty() { "none".into() } else { have.join(", ") }));
            } else if let Err(e) = o.validate() {
                say(format!("operations[{i}].{}", e.field), format!("operations[{i}].{} {} ('{}')", e.field, e.message, o.name()));
            }
        }
        out
    }

    /// The context the operations plan in, with the part placed and the in-process stock
    /// fresh.
    fn context(&self, workpiece: Workpiece) -> Result<Context> {
        let resolution = self.post.planning_resolution();
        let (part, sheet, stock) = match workpiece {
            Workpiece::Mesh(mut part) => {
                let stock = self.place(&mut part);
                (part, None, stock)
            }
            Workpiece::Drawing(mut d) => {
                let (stock, thickness) = drawing::place(self, &mut d)?;
                (Mesh::default(), Some(Sheet { drawing: d, thickness }), stock)
            }
        };
        let cell = self.simulation.cell_for(&stock);
        Ok(Context {
            part,
            sheet,
            stock,
            heights: SafeHeights { clearance: stock.max.z + self.stock.clearance, gap: self.stock.retract, full: self.stock.retracts == Retracts::Full },
            tools: self.tools.clone(),
            tolerances: self.tolerances,
            resolution,
            caches: Caches::default(),
            sim: Simulator::new(&stock, cell)?,
            warnings: Vec::new(),
            rapid_rate: self.post.rapid_rate,
            air_feed: self.stock.air_feed.unwrap_or(self.post.rapid_rate).min(self.post.rapid_rate),
            operation: 0,
            given_passes: Default::default(),
            given_regions: Vec::new(),
        })
    }
}

/// Verifies a G-code program (swarf's or another's) against a job's part, stock and tools:
/// the part is placed as the job says, the program read with [`crate::post::read::read_gcode`]
/// (after GRBL's word-set check, [`crate::post::grbl::check`], when the job's post is GRBL's)
/// (the job's first tool until the program picks one), and `cell` overrides the job's cell size.
pub fn verify_gcode(job: &Job, mut part: Mesh, gcode: &str, cell: Option<f64>, progress: &mut Progress) -> Result<Verification> {
    job.validate()?;
    let stock = job.place(&mut part);
    // A program for GRBL must first be one GRBL reads.
    if job.post.custom.is_none() {
        use crate::post::{grbl, Dialect};
        let flavour = match job.post.dialect {
            Dialect::Grbl => Some(grbl::Flavour::Grbl11),
            Dialect::GrblHal => Some(grbl::Flavour::GrblHal),
            _ => None,
        };
        if let Some(flavour) = flavour {
            grbl::check(gcode, flavour)?;
        }
    }
    let first_tool = job.tools.first().map_or(1, |t| t.number);
    let paths = crate::post::read::read_gcode(gcode, first_tool)?;
    let moves = program_moves(&paths, &job.tools, job.post.rapid_rate)?;
    crate::sim::verify::verify(&part, &stock, &moves, &job.verify_settings(&stock, cell), &job.tolerances, progress)
}

/// Places the part (or drawing), plans every operation in turn in one context, applying each
/// one's moves to the in-process stock before the next, and writes the G-code; the simulation
/// that carried the stock verifies the whole program.
pub fn run(job: &Job, workpiece: impl Into<Workpiece>, progress: &mut Progress) -> Result<JobOutput> {
    prepare(job, workpiece)?.run(progress)
}

/// Checks the job against the workpiece, places it and makes the context every operation
/// plans in.
pub fn prepare(job: &Job, workpiece: impl Into<Workpiece>) -> Result<Prepared> {
    job.validate()?;
    let workpiece = workpiece.into();
    let on = match workpiece {
        Workpiece::Mesh(_) => Works::OnPart,
        Workpiece::Drawing(_) => Works::OnDrawing,
    };
    for op in job.operations.iter().filter(|o| o.op().enabled()) {
        let o = op.op();
        if o.works() != on {
            let why = match on {
                Works::OnPart => "works on DXF or SVG drawings, not on a 3D part",
                Works::OnDrawing => "works on 3D parts, not on drawings",
            };
            return Err(Error::operation(o.name(), why));
        }
    }
    let mut warnings = match &workpiece {
        Workpiece::Mesh(m) => part_warnings(m),
        Workpiece::Drawing(_) => Vec::new(),
    };
    let ctx = job.context(workpiece)?;
    if ctx.sheet.is_none() {
        if let Some(w) = tool_larger_than_part(job, &ctx.part) {
            warnings.push(w);
        }
    }
    if !job.operations.iter().any(|o| o.op().enabled()) {
        return Err(Error::Nothing("every operation of the job is disabled".into()));
    }
    Ok(Prepared { job: job.clone(), ctx, warnings, given: Default::default() })
}

/// A job with its part placed and its context made, ready to plan ([`Prepared::run`]); a pool
/// of workers can first make its CL surfaces and raster passes in pieces ([`pool`]).
pub struct Prepared {
    job: Job,
    ctx: Context,
    warnings: Vec<Warning>,
    /// Raster passes a pool made, by operation.
    given: pool::GivenPasses,
}

impl Prepared {
    /// [`run`] from here.
    pub fn run(self, progress: &mut Progress) -> Result<JobOutput> {
        let mut running = self.start();
        while running.plan_next(progress)? {
            running.simulate(progress)?;
        }
        running.finish(progress)
    }

    /// Starts planning, operation by operation ([`Running`]).
    pub fn start(mut self) -> Running {
        self.give_passes();
        let Prepared { job, ctx, warnings, .. } = self;
        let enabled: Vec<usize> = (0..job.operations.len()).filter(|&k| job.operations[k].op().enabled()).collect();
        Running {
            job,
            ctx,
            warnings,
            enabled,
            next: 0,
            paths: Vec::new(),
            path_operations: Vec::new(),
            move_ranges: Vec::new(),
            all_moves: Vec::new(),
            snapshots: Vec::new(),
            loads: Vec::new(),
            cuts: Vec::new(),
            grooves: Vec::new(),
            octants: Vec::new(),
            pending: Vec::new(),
            bands_out: 0,
        }
    }
}

/// A job being planned operation by operation ([`Prepared::start`]): each operation's moves cut
/// the in-process stock before the next operation plans (and the last one's too when the program
/// is verified). [`Running::simulate`] cuts them here; a pool of workers can cut them instead,
/// in bands of the stock ([`Running::take_bands`], [`crate::sim::verify::cut_bands`],
/// [`Running::absorb`]), with the same result.
pub struct Running {
    job: Job,
    ctx: Context,
    warnings: Vec<Warning>,
    enabled: Vec<usize>,
    /// How many of `enabled` are planned.
    next: usize,
    paths: Vec<Toolpath>,
    path_operations: Vec<usize>,
    move_ranges: Vec<std::ops::Range<usize>>,
    all_moves: Vec<ProgramMove>,
    snapshots: Vec<Option<HeightField>>,
    loads: Vec<(Option<LoadReport>, Option<Vec<StageReport>>)>,
    /// Where the operations cut a sheet, and the grooves they engraved: what a drawing's
    /// program is verified against.
    cuts: Vec<SheetCut>,
    grooves: Vec<Groove>,
    /// Octree roughing's octants, for the view.
    octants: Vec<StageOctants>,
    /// The last planned operation's moves, until they have cut the in-process stock.
    pending: Vec<ProgramMove>,
    /// How many bands of the stock [`Running::take_bands`] handed out.
    bands_out: usize,
}

impl Running {
    /// Shares of the bar each operation's planning and simulation take.
    fn shares(&self) -> (f64, f64) {
        if self.job.simulation.verify {
            (0.85, 0.15)
        } else {
            (0.95, 0.05)
        }
    }

    /// Plans the next enabled operation; false once all are planned. Its moves are then
    /// [`Running::pending`] until they cut the in-process stock, unless there are none or
    /// nothing needs them to (the last operation of a program that is not verified).
    pub fn plan_next(&mut self, progress: &mut Progress) -> Result<bool> {
        if !self.pending.is_empty() {
            return Err(Error::Input("the last operation's moves have not cut the in-process stock yet".into()));
        }
        let Some(&k) = self.enabled.get(self.next) else {
            return Ok(false);
        };
        let n = self.next;
        self.next += 1;
        let (plan_share, _) = self.shares();
        let count = self.enabled.len() as f64;
        let o = self.job.operations[k].op();
        progress.frame(n as f64 / count, plan_share / count, Some(o.name()));
        self.ctx.operation = k;
        let planned = o.plan(&mut self.ctx, progress);
        // Regions a pool made were for this operation only.
        self.ctx.given_regions.clear();
        let Planned { paths, cuts, grooves, load, stages, octants } = planned?;
        self.loads.push((load, stages));
        self.cuts.extend(cuts);
        self.grooves.extend(grooves);
        self.octants.extend(octants);
        let first_path = self.paths.len();
        self.path_operations.extend(std::iter::repeat_n(k, paths.len()));
        self.paths.extend(paths);
        let moves = timed_moves(&self.paths, first_path, self.all_moves.last(), &self.job.tools, self.job.post.rapid_rate)?;
        if !moves.is_empty() && (self.job.simulation.verify || self.next < self.enabled.len()) {
            self.pending = moves;
        } else {
            self.settle(moves);
        }
        Ok(true)
    }

    /// The moves waiting to cut the in-process stock (none when nothing waits).
    pub fn pending(&self) -> &[ProgramMove] {
        &self.pending
    }

    /// Cuts the in-process stock with the pending moves, here.
    pub fn simulate(&mut self, progress: &mut Progress) -> Result<()> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let (plan_share, sim_share) = self.shares();
        let count = self.enabled.len() as f64;
        let n = (self.next - 1) as f64;
        progress.frame(n / count + plan_share / count, sim_share / count, Some(self.job.operations[self.enabled[self.next - 1]].op().name()));
        if !progress.stage("in-process stock", 0.0, 1.0) {
            return Err(Error::Cancelled);
        }
        let moves = std::mem::take(&mut self.pending);
        self.ctx.sim.run(&moves, &self.job.tolerances, progress, 1.0)?;
        self.settle(moves);
        Ok(())
    }

    /// The in-process stock in the bands of rows it is cut in, for a pool to cut with the
    /// pending moves; [`Running::absorb`] takes them back.
    pub fn take_bands(&mut self) -> Vec<DexelStock> {
        let bands = self.ctx.sim.take_bands();
        self.bands_out = bands.len();
        bands
    }

    /// Takes back the stock's bands (all of them, in order) after the pending moves cut them,
    /// with what each band made of them (see [`crate::sim::verify::Simulator::absorb`]).
    pub fn absorb(&mut self, bands: Vec<DexelStock>, cuts: &[BandCut]) -> Result<()> {
        if bands.len() != self.bands_out || cuts.len() != bands.len() {
            return Err(Error::Input(format!("{} of the stock's {} bands came back, with {} cuts", bands.len(), self.bands_out, cuts.len())));
        }
        let moves = std::mem::take(&mut self.pending);
        if let Some(&(k, ..)) = cuts.iter().flat_map(|c| c.moves.last()).find(|c| c.0 >= moves.len()) {
            return Err(Error::Input(format!("a band's cut names move {k} of {}", moves.len())));
        }
        self.ctx.sim.absorb(bands, cuts, &moves);
        self.settle(moves);
        Ok(())
    }

    /// Adds the last planned operation's moves to the program, once the stock is cut.
    fn settle(&mut self, moves: Vec<ProgramMove>) {
        // What the operation left is judged against the part only when the program is verified.
        self.snapshots.push(self.job.simulation.verify.then(|| self.ctx.sim.stock().heights()));
        self.move_ranges.push(self.all_moves.len()..self.all_moves.len() + moves.len());
        self.all_moves.extend(moves);
    }

    /// Writes the program once every operation is planned and has cut the stock, and judges it
    /// when the job verifies.
    pub fn finish(self, progress: &mut Progress) -> Result<JobOutput> {
        if self.next < self.enabled.len() || !self.pending.is_empty() {
            return Err(Error::Input("the job is not planned to its end yet".into()));
        }
        let Running { job, ctx, mut warnings, enabled, paths, path_operations, move_ranges, all_moves, snapshots, loads, cuts, grooves, octants, .. } = self;
        let job = &job;
        let verify = job.simulation.verify;
        let mut ctx = ctx;
        progress.frame(0.0, 1.0, None);
        warnings.append(&mut ctx.warnings);
        let crate::post::Written { gcode, cycle, move_lines } = write_mapped(&job.name, &paths, &job.tools, ctx.heights.clearance, &job.post)?;
        let stats = paths.iter().fold(PathStats::default(), |s, p| s + p.stats(job.post.rapid_rate));
        if all_moves.iter().all(|m| matches!(m.mv, crate::toolpath::Move::Rapid { .. })) {
            let why = if warnings.is_empty() { String::new() } else { format!(" ({})", warnings.iter().map(Warning::to_string).collect::<Vec<_>>().join("; ")) };
            return Err(Error::Nothing(format!("the program has no cutting moves{why}")));
        }
        let Context { part, sheet, stock, heights, caches, sim, .. } = ctx;
        // The simulation that carried the in-process stock judges the whole program.
        let (verification, sim) = if verify {
            let settings = job.verify_settings(&stock, None);
            let tol = job.tolerances;
            let v = match &sheet {
                None => sim.finish(|grid| cc_zmap(&part, grid, f64::NEG_INFINITY, &tol), settings.allowance, &tol),
                Some(_) => sim.finish(|grid| drawing::surface(&cuts, &grooves, grid, tol.gouge, &tol), settings.allowance, &tol),
            };
            (Some(v), None)
        } else {
            (None, Some(sim))
        };
        let (volumes, rates) = match (&verification, &sim) {
            (Some(v), _) => (&v.volumes[..], v.rates.clone()),
            (None, Some(sim)) => (sim.volumes(), sim.rates()),
            (None, None) => (&[][..], Vec::new()),
        };
        let mut operations = report::per_operation(job, &enabled, &all_moves, &move_ranges, volumes, &rates, &snapshots, verification.as_ref());
        for (o, (load, stages)) in operations.iter_mut().zip(loads) {
            o.load = load;
            o.stages = stages;
            // Its time as the program's head states it: its paths' as the post wrote them.
            o.seconds = path_operations.iter().zip(&cycle.paths).filter(|(&k, _)| k == o.index).map(|(_, s)| s).sum();
        }
        let time = cycle.items(&CycleTime::groups(&paths));
        let problem = verification.as_ref().and_then(|v| v.report.problem());
        progress.stage("done", 1.0, 0.0);
        let drawing = sheet.map(|s| s.drawing);
        let (clearance_z, cache) = (heights.clearance, caches.counts);
        Ok(JobOutput { part, drawing, stock, clearance_z, paths, path_operations, gcode, move_lines, cycle, time, stats, moves: all_moves, operations, verification, warnings, problem, cache, octants })
    }
}

/// What the user should know of a part as read: triangles dropped, and holes in its surface
/// (edges bordering one triangle, off the rim of its outline; [`Mesh::open_edges`]).
pub fn part_warnings(mesh: &Mesh) -> Vec<Warning> {
    let mut out = Vec::new();
    if mesh.dropped_degenerate > 0 {
        out.push(Warning::job(format!("{} degenerate triangles (zero area) were ignored", mesh.dropped_degenerate)).note());
    }
    let open = mesh.open_edges();
    if !open.is_empty() {
        out.push(Warning::counted(None, "edges of the part's surface border one triangle only: it has holes, and a cutter goes down through them (a file cut short or a bad export?)", &open));
    }
    out
}

/// A warning when the smallest tool the job uses is wider than the placed part is in X or Y:
/// most often a part read in the wrong unit (a glTF in metres read as millimetres is a thousand
/// times too small).
fn tool_larger_than_part(job: &Job, part: &Mesh) -> Option<Warning> {
    let used: Vec<u32> = job.operations.iter().filter(|o| o.op().enabled()).flat_map(|o| o.op().tools()).collect();
    let smallest = job.tools.iter().filter(|t| used.is_empty() || used.contains(&t.number)).min_by(|a, b| a.cutter.diameter.total_cmp(&b.cutter.diameter))?;
    let size = part.bounds().size();
    (smallest.cutter.diameter > size.x.min(size.y)).then(|| {
        Warning::job(format!(
            "the part is {:.2} × {:.2} × {:.2} mm, smaller than the φ{} tool T{}: is its unit right? (part.units: {:?}, part.scale: {})",
            size.x, size.y, size.z, smallest.cutter.diameter, smallest.number, job.part.units, job.part.scale
        ))
    })
}

/// The moves of `paths[first..]`, timed on from the program's last move so far.
fn timed_moves(paths: &[Toolpath], first: usize, last: Option<&ProgramMove>, tools: &[Tool], rapid_rate: f64) -> Result<Vec<ProgramMove>> {
    let clock = last.map_or(0.0, |m| m.start + m.seconds);
    let mut moves = program_moves(&paths[first..], tools, rapid_rate)?;
    for m in &mut moves {
        m.path += first;
        m.start += clock;
    }
    Ok(moves)
}
