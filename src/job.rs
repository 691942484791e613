//! A job: stock, tools, operations and post settings, as one serde type. The same JSON drives
//! the page, the CLI and the tests; [`run`] turns a job and a part into tool paths and G-code,
//! reporting progress and stopping when cancelled.

use serde::{Deserialize, Serialize};

use crate::cutter::Cutter;
use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec3, Tolerances};
use crate::geom::DVec2;
use crate::mesh::{placement::PartSetup, Mesh};
use crate::profile::Drawing;
use crate::strategy::pocket2d::Pocket2d;
use crate::strategy::profile2d::Profile2d;
use crate::post::{write_gcode, PostSettings};
use crate::progress::Progress;
use crate::sim::program::{program_moves, ProgramMove};
use crate::sim::verify::{verify, Verification, VerifySettings};
use crate::strategy::finish_raster::{raster_runs, Pattern, RasterPasses};
use crate::strategy::region::Region;
use crate::toolpath::link::{link_runs, Feeds, Floor, LinkSettings};
use crate::toolpath::{PathStats, Toolpath};
use crate::zmap::drop::PointDrop;
use crate::zmap::surface::ClSurface;
use crate::zmap::{cc::cc_zmap, cl_inverse::cl_inverse_offset, ClBuilder, Grid, HeightField};

/// The stock: a box around the placed part.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, rename_all = "camelCase")]
pub struct Stock {
    /// Extra stock around the part in X and Y (mm, each side). Default value: 5.
    pub margin_xy: f64,
    /// Extra stock above the part's top (mm). Default value: 1.
    pub margin_top: f64,
    /// Extra stock below the part's bottom (mm). Default value: 0.
    pub margin_bottom: f64,
    /// Height above the stock top for rapid moves (mm). Default value: 5.
    pub clearance: f64,
}

impl Default for Stock {
    fn default() -> Self {
        Stock { margin_xy: 5.0, margin_top: 1.0, margin_bottom: 0.0, clearance: 5.0 }
    }
}

impl Stock {
    pub fn around(&self, part: &Aabb) -> Aabb {
        let grow = DVec3::new(self.margin_xy, self.margin_xy, 0.0);
        Aabb {
            min: part.min - grow - DVec3::new(0.0, 0.0, self.margin_bottom),
            max: part.max + grow + DVec3::new(0.0, 0.0, self.margin_top),
        }
    }
}

/// A tool in the library: a cutter with its cutting data.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, rename_all = "camelCase")]
pub struct Tool {
    /// Tool number (T word, pocket). Default value: 1.
    pub number: u32,
    /// Free text for the library and the program's comments. Default value: empty.
    pub name: String,
    #[serde(flatten)]
    pub cutter: Cutter,
    /// Spindle speed (rpm). Default value: 12000.
    pub spindle_rpm: f64,
    /// Cutting feed (mm/min). Default value: 1000.
    pub feed_rate: f64,
    /// Feed for vertical entries (mm/min). Default value: 300.
    pub plunge_rate: f64,
}

impl Default for Tool {
    fn default() -> Self {
        Tool { number: 1, name: String::new(), cutter: Cutter::default(), spindle_rpm: 12000.0, feed_rate: 1000.0, plunge_rate: 300.0 }
    }
}

impl Tool {
    pub fn describe(&self) -> String {
        if self.name.is_empty() {
            self.cutter.describe()
        } else {
            format!("{}: {}", self.name, self.cutter.describe())
        }
    }
}

/// Where the tool's centre may go.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Boundary {
    /// The stock's rectangle.
    Stock,
    /// The part's outline seen from above, grown by the operation's margin.
    #[default]
    Silhouette,
}

/// Raster finishing over the CL z-map (seed 001).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, rename_all = "camelCase")]
pub struct FinishRaster {
    /// Shown in the program's comments. Default value: "raster finish".
    pub name: String,
    /// Number of the tool to use. Default value: 1.
    pub tool: u32,
    /// Direction of the passes (degrees from +X). Default value: 0.
    pub angle: f64,
    /// Distance between passes (mm). Default value: 0.5.
    pub stepover: f64,
    /// Default value: zigzag.
    pub pattern: Pattern,
    /// Default value: silhouette.
    pub boundary: Boundary,
    /// Growth of the silhouette boundary (mm). Default value: the tool's radius.
    pub margin: Option<f64>,
    /// Material left on the part (mm). Default value: 0.
    pub allowance: f64,
    /// Spacing of the CL z-map (mm). Default value: 0.25.
    pub grid: f64,
    /// Default value: exact.
    pub builder: ClBuilder,
    /// Lowest tip height where the part is not under the tool (mm). Default value: stock bottom.
    pub floor: Option<f64>,
    /// Longest link that may stay down (mm). Default value: twice the stepover.
    pub stay_down_max: Option<f64>,
}

impl Default for FinishRaster {
    fn default() -> Self {
        FinishRaster {
            name: "raster finish".into(),
            tool: 1,
            angle: 0.0,
            stepover: 0.5,
            pattern: Pattern::Zigzag,
            boundary: Boundary::Silhouette,
            margin: None,
            allowance: 0.0,
            grid: 0.25,
            builder: ClBuilder::Exact,
            floor: None,
            stay_down_max: None,
        }
    }
}

/// One operation of a job.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "camelCase")]
pub enum Operation {
    /// On a part (mesh).
    FinishRaster(FinishRaster),
    /// On a drawing (DXF, SVG).
    Profile2d(Profile2d),
    /// On a drawing (DXF, SVG).
    Pocket2d(Pocket2d),
}

impl Operation {
    /// Where an operation's JSON does not fit its kind's type: `field: what is wrong`.
    fn field_error(value: &serde_json::Value) -> Option<String> {
        fn at<T: serde::de::DeserializeOwned>(value: &serde_json::Value) -> Option<String> {
            serde_path_to_error::deserialize::<_, T>(value).err().map(|e| format!("{}: {}", e.path(), e.inner()))
        }
        match value.get("kind")?.as_str()? {
            "finishRaster" => at::<FinishRaster>(value),
            "profile2d" => at::<Profile2d>(value),
            "pocket2d" => at::<Pocket2d>(value),
            _ => None,
        }
    }

    pub fn tool(&self) -> u32 {
        match self {
            Operation::FinishRaster(o) => o.tool,
            Operation::Profile2d(o) => o.tool,
            Operation::Pocket2d(o) => o.tool,
        }
    }

    pub fn name(&self) -> &str {
        match self {
            Operation::FinishRaster(o) => &o.name,
            Operation::Profile2d(o) => &o.name,
            Operation::Pocket2d(o) => &o.name,
        }
    }

    /// Material the operation leaves above the part's surface (mm). A 2.5D operation's
    /// leave-stock is on the walls, not on the surface: it has none (the part a drawing means
    /// for verification keeps the walls' leave-stock in its regions, `job2d.rs`).
    pub fn allowance(&self) -> f64 {
        match self {
            Operation::FinishRaster(o) => o.allowance,
            Operation::Profile2d(_) | Operation::Pocket2d(_) => 0.0,
        }
    }

    /// Material left on the walls by a 2.5D operation (mm).
    fn leave_stock(&self) -> Option<f64> {
        match self {
            Operation::FinishRaster(_) => None,
            Operation::Profile2d(o) => Some(o.leave_stock),
            Operation::Pocket2d(o) => Some(o.leave_stock),
        }
    }

    /// Whether it works on drawings rather than parts.
    pub fn is_2d(&self) -> bool {
        !matches!(self, Operation::FinishRaster(_))
    }
}

/// The units a drawing's numbers are in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum DrawingUnits {
    /// As the file says ($INSUNITS, the SVG's width and viewBox; px at 96 per inch).
    #[default]
    File,
    Mm,
    Inch,
}

/// Where a drawing is put.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
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
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
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
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
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

/// The job file format this swarf writes and reads (files from a newer one are refused).
pub const JOB_VERSION: u32 = 1;

/// The version of a job file that has none: written before versions were.
fn first_version() -> u32 {
    1
}

/// Everything needed to turn a part into G-code.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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

/// The fields of `input` that reading it did not use: those absent from the job it made,
/// written back (`canonical`), with a known field of the same object that differs only in case
/// or by underscores, as a hint.
fn unknown_fields(input: &serde_json::Value, canonical: &serde_json::Value, path: &str, out: &mut Vec<String>) {
    use serde_json::Value;
    match (input, canonical) {
        (Value::Object(given), Value::Object(known)) => {
            let squash = |k: &str| k.to_lowercase().replace(['_', '-'], "");
            for (k, v) in given {
                let here = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                match known.get(k) {
                    Some(w) => unknown_fields(v, w, &here, out),
                    None => match known.keys().find(|n| squash(n) == squash(k)) {
                        Some(n) => out.push(format!("{here} (did you mean {n}?)")),
                        None => out.push(here),
                    },
                }
            }
        }
        (Value::Array(given), Value::Array(known)) => {
            for (i, (v, w)) in given.iter().zip(known).enumerate() {
                unknown_fields(v, w, &format!("{path}[{i}]"), out);
            }
        }
        _ => {}
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
    pub gcode: String,
    pub stats: PathStats,
    /// Every move of the program, timed, in order.
    pub moves: Vec<ProgramMove>,
    /// The simulation of the program and what it found, when the job asked for it.
    pub verification: Option<Verification>,
    /// Things the user should know that did not stop the job.
    pub warnings: Vec<String>,
    /// What makes the program unsafe to run (a gouge, a rapid through stock, the tool's body in
    /// material: [`crate::sim::verify::Report::problem`]), when verification found it. Such a
    /// program is not a finished one: [`JobOutput::checked`] turns it into an error, the CLI
    /// writes it only when asked to, and the page keeps its download behind a confirmation.
    pub problem: Option<String>,
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
        match &self.problem {
            Some(problem) => {
                // A program that starts with a tape mark (Fanuc) keeps it first.
                let warning = format!("(WARNING: NOT SAFE TO RUN: {})\n", crate::post::comment(problem));
                match self.gcode.strip_prefix("%\n") {
                    Some(rest) => format!("%\n{warning}{rest}"),
                    None => format!("{warning}{}", self.gcode),
                }
            }
            None => self.gcode.clone(),
        }
    }
}

impl Job {
    /// The default job for a drawing: a φ3 flat end mill cutting the drawing's parts out of
    /// a 6 mm sheet (holes inside, outlines outside), four tabs a part.
    pub fn default_for_drawing() -> Job {
        let tool = Tool { number: 1, name: "3 mm flat end mill".into(), cutter: Cutter::flat(3.0), feed_rate: 800.0, plunge_rate: 200.0, ..Tool::default() };
        let profile = Profile2d { tabs: crate::strategy::profile2d::Tabs { count: 4, ..Default::default() }, ..Profile2d::default() };
        Job { name: "swarf sheet job".into(), tools: vec![tool], operations: vec![Operation::Profile2d(profile)], ..Job::default() }
    }

    /// Reads a job file. A value that does not fit is named by its path
    /// (`operations[1].stepover: invalid type ...`), and so is every field this version does
    /// not know (`operations[0].stepOver`, with the known field it may mean): a misspelt
    /// setting must not fall back to its default unseen. A file without a `version` is read as
    /// version 1; one from a newer swarf is refused.
    pub fn from_json(text: &str) -> Result<Job> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Input(format!("the job file is not JSON: {e}")))?;
        let job: Job = serde_path_to_error::deserialize(&value).map_err(|e| {
            let path = e.path().to_string();
            // An operation is read whole (its `kind` picks the type), so the path stops at it:
            // read it again as its kind's type to name the field.
            let op = value.get("operations").and_then(|ops| path.strip_prefix("operations[")?.strip_suffix(']')?.parse::<usize>().ok().and_then(|i| ops.get(i)));
            match op.and_then(Operation::field_error) {
                Some(inner) => Error::Input(format!("{path}.{inner}")),
                None if path == "." => Error::Input(e.into_inner().to_string()),
                None => Error::Input(format!("{path}: {}", e.into_inner())),
            }
        })?;
        if job.version > JOB_VERSION {
            return Err(Error::Input(format!(
                "the job file has version {}; this swarf reads versions up to {JOB_VERSION} (a newer swarf wrote it)",
                job.version
            )));
        }
        let canonical = serde_json::to_value(&job).map_err(|e| Error::Input(e.to_string()))?;
        let mut unknown = Vec::new();
        unknown_fields(&value, &canonical, "", &mut unknown);
        if !unknown.is_empty() {
            return Err(Error::Input(format!("unknown field{}: {}", if unknown.len() == 1 { "" } else { "s" }, unknown.join("; "))));
        }
        Ok(job)
    }

    pub fn tool(&self, number: u32) -> Result<&Tool> {
        self.tools.iter().find(|t| t.number == number).ok_or_else(|| Error::Job(format!("no tool number {number} in the tool library")))
    }

    /// Places the part as the job says and returns the stock box around it.
    pub fn place(&self, part: &mut Mesh) -> Aabb {
        self.part.apply(part);
        self.stock.around(&part.bounds())
    }

    /// The least material any operation leaves on the part (mm); infinite without operations.
    pub fn allowance(&self) -> f64 {
        self.operations.iter().map(Operation::allowance).fold(f64::INFINITY, f64::min)
    }

    /// Checks the job before any work.
    pub fn validate(&self) -> Result<()> {
        let positive = |what: &str, v: f64| {
            if v > 0.0 && v.is_finite() {
                Ok(())
            } else {
                Err(Error::Job(format!("{what} must be a positive number (got {v})")))
            }
        };
        for tool in &self.tools {
            tool.cutter.validate().map_err(|e| Error::Job(format!("tool {}: {e}", tool.number)))?;
            positive("the spindle speed", tool.spindle_rpm)?;
            positive("the feed rate", tool.feed_rate)?;
            positive("the plunge rate", tool.plunge_rate)?;
        }
        positive("the rapid rate", self.post.rapid_rate)?;
        // Rapids run at the clearance height: at or below the stock's top they would cut.
        positive("stock.clearance (the height of rapid moves above the stock's top)", self.stock.clearance)?;
        for op in &self.operations {
            self.tool(op.tool())?;
            if op.leave_stock().is_some_and(|l| !(l.is_finite() && l >= 0.0)) {
                return Err(Error::Job("the leave-stock must be zero or more".into()));
            }
            match op {
                Operation::Profile2d(p) => {
                    positive("the profile's step-down", p.stepdown)?;
                    positive("the ramp angle", p.ramp_angle)?;
                    if let Some(d) = p.depth {
                        positive("the profile's depth", d)?;
                    }
                }
                Operation::Pocket2d(p) => {
                    positive("the pocket's depth", p.depth)?;
                    positive("the pocket's step-down", p.stepdown)?;
                    positive("the step-over", p.stepover)?;
                    positive("the ramp angle", p.ramp_angle)?;
                }
                Operation::FinishRaster(f) => {
                    positive("the stepover", f.stepover)?;
                    positive("the grid spacing", f.grid)?;
                    if !(f.allowance.is_finite() && f.angle.is_finite()) {
                        return Err(Error::Job("the allowance and angle must be numbers".into()));
                    }
                }
            }
        }
        Ok(())
    }
}

/// Places the part (or drawing), runs every operation and writes the G-code.
pub fn run(job: &Job, workpiece: impl Into<Workpiece>, progress: &mut Progress) -> Result<JobOutput> {
    job.validate()?;
    let mut part = match workpiece.into() {
        Workpiece::Mesh(m) => m,
        Workpiece::Drawing(d) => return crate::job2d::run_drawing(job, d, progress),
    };
    if let Some(op) = job.operations.iter().find(|op| op.is_2d()) {
        return Err(Error::Job(format!("'{}' works on DXF or SVG drawings, not on a 3D part", op.name())));
    }
    let mut warnings = Vec::new();
    if part.dropped_degenerate > 0 {
        warnings.push(format!("{} degenerate triangles (zero area) were ignored", part.dropped_degenerate));
    }
    let stock = job.place(&mut part);
    let clearance_z = stock.max.z + job.stock.clearance;
    let mut paths = Vec::new();
    let count = job.operations.len().max(1) as f64;
    let share = if job.simulation.verify { 0.85 } else { 1.0 };
    for (k, op) in job.operations.iter().enumerate() {
        let (start, span) = (share * k as f64 / count, share / count);
        match op {
            Operation::FinishRaster(f) => {
                paths.push(finish_raster(job, f, &part, &stock, clearance_z, progress, start, span)?);
            }
            Operation::Profile2d(_) | Operation::Pocket2d(_) => return Err(Error::Job("2.5D operations need a drawing".into())),
        }
    }
    let finish = Finish { job, stock, clearance_z, share };
    finish.run(paths, part, None, warnings, progress, |part, moves, settings, progress| verify(part, &stock, moves, settings, &job.tolerances, progress))
}

/// The common end of every job: G-code, statistics, the program's moves, and verification by
/// simulation (seed 002).
pub(crate) struct Finish<'a> {
    pub job: &'a Job,
    pub stock: Aabb,
    pub clearance_z: f64,
    /// Share of the progress bar the operations took.
    pub share: f64,
}

impl Finish<'_> {
    pub fn run(
        self,
        paths: Vec<Toolpath>,
        part: Mesh,
        drawing: Option<Drawing>,
        warnings: Vec<String>,
        progress: &mut Progress,
        verify: impl FnOnce(&Mesh, &[ProgramMove], &VerifySettings, &mut Progress) -> Result<Verification>,
    ) -> Result<JobOutput> {
        let (job, stock, clearance_z, share) = (self.job, self.stock, self.clearance_z, self.share);
        let gcode = write_gcode(&job.name, &paths, &job.tools, clearance_z, &job.post);
        let stats = paths.iter().fold(PathStats::default(), |s, p| s + p.stats(job.post.rapid_rate));
        let moves = program_moves(&paths, &job.tools, job.post.rapid_rate)?;
        if moves.iter().all(|m| matches!(m.mv, crate::toolpath::Move::Rapid { .. })) {
            let why = if warnings.is_empty() { String::new() } else { format!(" ({})", warnings.join("; ")) };
            return Err(Error::Nothing(format!("the program has no cutting moves{why}")));
        }
        let verification = if job.simulation.verify {
            if !progress.stage("simulating the program", share, 1.0 - share) {
                return Err(Error::Cancelled);
            }
            Some(verify(&part, &moves, &VerifySettings::for_job(job, &stock, None), progress)?)
        } else {
            None
        };
        let problem = verification.as_ref().and_then(|v| v.report.problem());
        progress.stage("done", 1.0, 0.0);
        Ok(JobOutput { part, drawing, stock, clearance_z, paths, gcode, stats, moves, verification, warnings, problem })
    }
}

#[allow(clippy::too_many_arguments)]
fn finish_raster(job: &Job, op: &FinishRaster, part: &Mesh, stock: &Aabb, clearance_z: f64, progress: &mut Progress, start: f64, span: f64) -> Result<Toolpath> {
    let tool = job.tool(op.tool)?;
    let profile = tool.cutter.profile();
    let grid = Grid::checked(stock.min.truncate(), stock.max.truncate(), op.grid).map_err(|e| Error::Job(format!("{}: {e}", op.name)))?;
    let floor = op.floor.unwrap_or(stock.min.z);
    let tol = &job.tolerances;
    // The part's own heights, needed by the inverse offset and by the silhouette boundary.
    let cc = (op.builder == ClBuilder::InverseOffset || op.boundary == Boundary::Silhouette).then(|| cc_zmap(part, grid, floor, tol));
    let cc = || cc.as_ref().expect("built above for the uses that need it");
    if !progress.stage(&format!("{}: CL z-map", op.name), start, span * 0.2) {
        return Err(Error::Cancelled);
    }
    // Heights for the path come from the cutter grown by the program's resolution
    // (`PointDrop::grown`): no lower than the highest tip height within that distance, so that
    // rounding X and Y as the G-code is written cannot put a point below the surface, and Z is
    // written rounded up. The exact z-map is that grown cutter's, so its nodes stand in for the
    // drop where a pass crosses them.
    let drop = PointDrop::grown(part, &profile, job.post.resolution(), tol);
    let cl: HeightField = match op.builder {
        ClBuilder::Exact => drop.field(part, grid, floor, tol, progress)?,
        ClBuilder::InverseOffset => cl_inverse_offset(cc(), &profile, progress)?,
    };
    if !progress.stage(&format!("{}: passes", op.name), start + span * 0.2, span * 0.8) {
        return Err(Error::Cancelled);
    }
    let margin = op.margin.unwrap_or(profile.radius);
    let region = match op.boundary {
        Boundary::Stock => Region::Rect { min: stock.min.truncate(), max: stock.max.truncate() },
        Boundary::Silhouette => Region::silhouette(cc(), floor, margin),
    };
    let skip_floor = (op.boundary == Boundary::Silhouette && margin <= profile.radius).then_some(floor);
    let passes = RasterPasses { angle_deg: op.angle, stepover: op.stepover, pattern: op.pattern, allowance: op.allowance, tolerance: tol.chordal, skip_floor };
    let cl = ClSurface::new(cl, drop, floor, op.builder == ClBuilder::Exact, tol.interpolation);
    let runs = raster_runs(&cl, &region, &passes, progress).ok_or(Error::Cancelled)?;
    let settings = LinkSettings { clearance_z, stay_down_max: op.stay_down_max.unwrap_or(2.0 * op.stepover), stock_top: Some(stock.max.z), ..LinkSettings::default() };
    let floor_surface = Floor { cl: &cl, allowance: op.allowance, region: &region };
    let (path_start, moves) = link_runs(&runs, &floor_surface, &settings, Feeds { cut: tool.feed_rate, plunge: tool.plunge_rate }, tol);
    Ok(Toolpath { name: op.name.clone(), tool: tool.number, spindle_rpm: tool.spindle_rpm, start: path_start, moves })
}
