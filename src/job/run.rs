//! Running a job: the context its operations plan in, prepared ([`prepare`]), then planned
//! operation by operation ([`Running`]) with each one's moves cutting the in-process stock
//! before the next, and the program written and verified ([`JobOutput`]); and verifying any
//! program against a job ([`verify_gcode`]).

use super::drawing;
use super::report::{self, OperationReport};
use super::schema::{Job, Retracts, Workpiece};
use crate::drawing::Drawing;
use crate::error::{Error, Result, Warning};
use crate::geom::{Aabb, DVec3};
use crate::machining::context::{CacheCounts, Caches, Context, SafeHeights, Sheet};
use crate::machining::report::{Groove, LoadReport, Planned, SheetCut, StageOctants, StageReport};
use crate::machining::Works;
use crate::mesh::Mesh;
use crate::operations::Operation;
use crate::post::{write_mapped, CycleTime, TimeItem};
use crate::progress::Progress;
use crate::sim::program::{program_moves, ProgramMove};
use crate::sim::verify::{BandCut, Simulator, Verification};
use crate::sim::DexelStock;
use crate::tool::Tool;
use crate::toolpath::{PathStats, Toolpath};
use crate::zmap::HeightField;

/// Raster passes a pool made, by operation: each pass's runs, as they came.
pub(super) type GivenPasses = std::collections::HashMap<usize, Vec<Option<Vec<Vec<crate::geom::DVec3>>>>>;

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
    /// What the feed optimisation did, where the job asked for it (`simulation.optimizeFeeds`).
    pub feeds: Option<report::FeedReport>,
    /// Whether its work zero's X0 Y0 was put at a point (`zero.at`: the page's "X0 Y0 on the
    /// picked hole"), the one way it lands on a hole's centre: the setup sheet looks for that
    /// hole only then ([`Job::zero_at`]).
    pub zero_at: bool,
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

/// The widest line of the warning at the head of a program written anyway: a control reads it
/// whole (rs274 refuses a line of 256 characters or more; GRBL keeps 80, some panels fewer).
pub const WARNING_WIDTH: usize = 70;

/// The warning comments at the head of a program written anyway, naming `problem`: ASCII, each
/// line at most [`WARNING_WIDTH`] characters, broken between words.
pub fn warning_lines(problem: &str) -> Vec<String> {
    let text = format!("WARNING: NOT SAFE TO RUN: {}", crate::post::ascii(&crate::post::comment(problem)));
    crate::post::wrap(&text, WARNING_WIDTH - 2).into_iter().map(|line| format!("({line})")).collect()
}

/// `gcode` with warning comments at its head naming `problem` ([`warning_lines`]), if there is
/// one.
pub fn marked(gcode: &str, problem: Option<&str>) -> String {
    match problem {
        Some(problem) => {
            let mut warning = warning_lines(problem).join("\n");
            warning.push('\n');
            // A program that starts with a tape mark (Fanuc) keeps it first.
            match gcode.strip_prefix("%\n") {
                Some(rest) => format!("%\n{warning}{rest}"),
                None => format!("{warning}{gcode}"),
            }
        }
        None => gcode.to_owned(),
    }
}

impl Job {
    /// The holes a drilling operation of this job finds in `workpiece` (placed as the job
    /// places it), in the order its `holes` field numbers them: a part's vertical round holes,
    /// or a drawing's circles (numbered as its loops).
    pub fn holes(&self, workpiece: impl Into<Workpiece>) -> Result<Vec<crate::holes::Hole>> {
        self.validate()?;
        Ok(crate::machining::holes::holes_of(&self.context(workpiece.into())?))
    }

    /// The part's round bosses as an external thread mill finds them, placed as this job places
    /// the part, numbered as its `holes` takes them.
    pub fn bosses(&self, mut part: Mesh) -> Result<Vec<crate::holes::Hole>> {
        self.validate()?;
        self.place(&mut part);
        Ok(crate::holes::mesh::bosses(&part))
    }

    /// The part's top edges as a chamfer finds them (`edges: partEdges`), placed as this job
    /// places the part, numbered as its `loops` takes them.
    pub fn top_edges(&self, mut part: Mesh) -> Result<Vec<crate::mesh::edges::TopEdge>> {
        self.validate()?;
        self.place(&mut part);
        Ok(crate::mesh::edges::top_edges(&part))
    }

    /// The context the operations plan in, with the part placed and the in-process stock
    /// fresh.
    fn context(&self, workpiece: Workpiece) -> Result<Context> {
        let resolution = self.post.planning_resolution();
        let (part, sheet, stock) = match workpiece {
            Workpiece::Mesh(mut part) => {
                let stock = self.place(&mut part);
                larger_than_any_machine("part", part.bounds().size(), "its unit (part.units) and part.scale")?;
                outside_the_stock(&part.bounds(), &stock)?;
                // A bar's own check below says it in the bar's words (a setup's box round it
                // would say a box's).
                if let Some(message) =
                    (self.stock.bar.is_none() && (self.stock.size_box.is_some() || self.stock.mesh.is_some())).then(|| super::schema::part_outside_error(&stock, &part.bounds())).flatten()
                {
                    return Err(Error::Input(message));
                }
                if let Some(bar) = self.stock.bar {
                    let reach = part.vertices.iter().map(|&v| bar.distance(&stock, v)).fold(0.0, f64::max);
                    if reach > bar.diameter / 2.0 + 1e-9 {
                        return Err(Error::Input(format!(
                            "stock.bar.diameter: the part reaches {:.3} mm from the bar's axis, outside a φ{} bar; choose a bar of at least φ{:.3}",
                            reach,
                            crate::limits::shown(bar.diameter),
                            2.0 * reach
                        )));
                    }
                }
                (part, None, stock)
            }
            Workpiece::Drawing(mut d) => {
                let (stock, thickness) = drawing::place(self, &mut d)?;
                (Mesh::default(), Some(Sheet { drawing: d, thickness }), stock)
            }
        };
        larger_than_any_machine("stock", stock.size(), "the stock's margins, size and the part's unit")?;
        // X0 Y0 on a point given from the stock's centre must be on the stock (a hole's centre).
        if self.stock.zero.and_then(|z| z.at).is_some() {
            super::schema::zero_on_stock(&stock, "stock.zero.at")?;
        }
        let cell = self.simulation.cell_for(&stock);
        if self.simulation.cell.is_some() {
            self.sees_with(cell, "simulation.cell")?;
        }
        let mut sim = Simulator::new(&stock, cell)?;
        if let Some(bar) = self.stock.bar.filter(|_| sheet.is_none()) {
            sim.carry([false; 2], crate::sim::dexel::one_span(bar.material(&stock)));
        } else if let Some(blank) = self.blank().filter(|_| sheet.is_none()) {
            // The blank moved to the work zero as the stock's box was.
            let to_zero = stock.min - self.stock_box(&stock).min;
            let mut blank = (*blank).clone();
            blank.transform(|v| v + to_zero);
            let columns = super::blank::Columns::new(&blank);
            if let Some(why) = columns.fault() {
                return Err(Error::Input(format!("stock.mesh: {why}")));
            }
            outside_the_blank(&part, &columns)?;
            sim.carry([false; 2], crate::sim::dexel::one_span(|p| columns.material(p)));
        }
        // What holds the stock joins the part in what the cutter is dropped onto, and rapids
        // across run above it.
        let keep_out = self.fixtures.keep_out(&stock);
        let solid = (sheet.is_none() && !keep_out.is_empty()).then(|| super::fixtures::solid(&part, &keep_out));
        let above_fixtures = keep_out.iter().map(|h| h.solid.max.z + self.stock.retract).fold(f64::NEG_INFINITY, f64::max);
        Ok(Context {
            part,
            sheet,
            stock,
            heights: SafeHeights { clearance: (stock.max.z + self.stock.clearance).max(above_fixtures), gap: self.stock.retract, full: self.stock.retracts == Retracts::Full },
            tools: self.tools.clone(),
            tolerances: self.tolerances,
            resolution,
            caches: Caches::default(),
            sim,
            warnings: Vec::new(),
            rapids: self.rapids(),
            air_feed: self.air_feed(),
            operation: 0,
            given_passes: Default::default(),
            given_regions: Vec::new(),
            keep_out,
            solid,
        })
    }
}

/// Refuses a part or stock larger than any machine ([`crate::limits::MAX_SIZE`]) before any
/// work, with its size and the settings to check.
fn larger_than_any_machine(what: &str, size: crate::geom::DVec3, check: &str) -> Result<()> {
    if size.is_finite() && size.max_element() <= crate::limits::MAX_SIZE {
        return Ok(());
    }
    let [x, y, z] = size.to_array().map(|v| crate::limits::shown((v * 100.0).round() / 100.0));
    Err(Error::Input(format!("the {what} is {x} × {y} × {z} mm, larger than any machine (at most 10 m): check {check}")))
}

impl Job {
    /// Refuses a simulation cell (`field`, as the job or the command names it) wider than the
    /// smallest tool's radius: its cuts, and a gouge by it, would fall between the cells, and a
    /// check that could not see them would say "clean" (a cell of 1e300 passed a program cutting
    /// 9 mm through the plate).
    pub fn sees_with(&self, cell: f64, field: &str) -> Result<()> {
        let Some(tool) = self.tools.iter().min_by(|a, b| a.cutter.diameter.total_cmp(&b.cutter.diameter)) else { return Ok(()) };
        let most = tool.cutter.radius();
        if cell <= most {
            return Ok(());
        }
        Err(Error::Input(format!(
            "{field}: cells of {} mm are wider than the radius of T{}, φ{} ({most} mm): the simulation could not see its cuts, nor a gouge by it; choose cells of at most {most} mm",
            crate::limits::shown(cell),
            tool.number,
            tool.cutter.diameter
        )))
    }
}

/// Verifies a G-code program (swarf's or another's) against a job's part, stock and tools:
/// the part is placed as the job says, the program read with [`crate::post::read::read_gcode`]
/// (after GRBL's word-set check, [`crate::post::grbl::check`], when the job's post is GRBL's)
/// (the job's first tool until the program picks one), and `cell` overrides the job's cell size.
/// Every move is checked against the job's fixtures too.
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
    let moves = program_moves(&paths, &job.tools, job.rapids(), job.air_feed())?;
    let settings = job.verify_settings(&stock, cell);
    if cell.is_some() || job.simulation.cell.is_some() {
        job.sees_with(settings.cell, if cell.is_some() { "the cell" } else { "simulation.cell" })?;
    }
    let mut v = crate::sim::verify::verify(&part, &stock, &moves, &settings, &job.tolerances, progress)?;
    // Every move against what holds the stock, as a job's own program is.
    let keep_out = job.fixtures.keep_out(&stock);
    v.report.fixtures(keep_out.len(), crate::sim::fixtures::collisions(&moves, &keep_out, job.tolerances.gouge));
    Ok(v)
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
    // What the machine does not suit, said of the tools as given (their feeds as typed).
    let unsuited = job.machine_warnings();
    // The tools' speeds and feeds from the stock's material, where they take them.
    let cut = job.with_cutting_data();
    let job: &Job = &cut;
    if !job.setups.is_empty() {
        return Err(Error::Input(format!("the job has {} setups, each a program of its own: run it with `swarf run` (the page makes one setup's program so far)", job.setups.len())));
    }
    let workpiece = workpiece.into();
    let on = match workpiece {
        Workpiece::Mesh(_) => Works::OnPart,
        Workpiece::Drawing(_) => Works::OnDrawing,
    };
    for op in job.operations.iter().filter(|o| o.op().enabled()) {
        let o = op.op();
        if o.works() != on && o.works() != Works::Either {
            let why = if on == Works::OnPart { "works on DXF or SVG drawings, not on a 3D part" } else { "works on 3D parts, not on drawings" };
            return Err(Error::operation(o.name(), why));
        }
    }
    let mut warnings = match &workpiece {
        Workpiece::Mesh(m) => surface_warnings(m),
        Workpiece::Drawing(d) => drawing_warnings(d),
    };
    warnings.extend(unsuited);
    let ctx = job.context(workpiece)?;
    // Its size in its unit, as placed.
    if ctx.sheet.is_none() {
        warnings.extend(unit_warning(&ctx.part));
    }
    // Work off by orders of magnitude is refused before any starts, naming the setting.
    for o in job.operations.iter().map(Operation::op).filter(|o| o.enabled()) {
        o.check_scale(&ctx)?;
    }
    if ctx.sheet.is_none() {
        if let Some((w, whole)) = tool_larger_than_part(job, &ctx.part) {
            // Every tool wider than the whole part, and no facing (a face mill wider than the
            // part is how a top is faced): nothing of the part is reached but its outside, and
            // the exact surface of so wide a tool costs minutes (a φ150 on the 90 mm sample:
            // 300 s to a program that leaves 10 mm). Refused at once.
            let facing = job.operations.iter().any(|o| o.op().enabled() && matches!(o, Operation::Face(_)));
            if whole && !facing {
                return Err(Error::Input(format!("{w}; choose a smaller tool")));
            }
            warnings.push(w);
        }
        if let Some(w) = super::schema::below_bottom(&ctx.stock, &ctx.part.bounds()) {
            warnings.push(Warning::job(w));
        }
    }
    if !job.operations.iter().any(|o| o.op().enabled()) {
        return Err(Error::Nothing("every operation of the job is disabled".into()));
    }
    // A changer the post cannot call: every change stops the program for the operator.
    let post = job.post.post();
    if job.machine.tool_changer == Some(true) && post.tool_change.is_empty() {
        warnings.push(Warning::job(format!(
            "the {} has a tool changer, but the post {} has no tool change word (M6): the program stops for each tool to be changed by hand; choose a post that calls the changer (grblHAL, LinuxCNC, Mach3/4, Fanuc)",
            job.machine.name, post.name
        )));
    }
    Ok(Prepared { job: job.clone(), ctx, warnings, given: Default::default(), last_setup: true })
}

/// A job with its part placed and its context made, ready to plan ([`Prepared::run`]); a pool
/// of workers can first make its CL surfaces and raster passes in pieces ([`super::pool`]).
pub struct Prepared {
    pub(super) job: Job,
    pub(super) ctx: Context,
    pub(super) warnings: Vec<Warning>,
    /// Raster passes a pool made, by operation.
    pub(super) given: GivenPasses,
    /// Whether no setup follows this one: its last operation may cut the part free (it comes
    /// off), which earlier ones may not where fixtures hold it ([`super::hold`]).
    pub(super) last_setup: bool,
}

impl Prepared {
    /// Starts from the stock earlier work left instead of the raw box (the setup before this
    /// one's, [`super::setups`]): each cell of the in-process stock holding the spans of
    /// material that `material` pushes for its centre, its cells laid as `at_max` says
    /// ([`crate::sim::DexelStock::laid_from`]).
    pub fn carry(&mut self, at_max: [bool; 2], material: impl FnMut(crate::geom::DVec2, &mut Vec<(f64, f64)>)) {
        self.ctx.sim.carry(at_max, material);
        // A vise closes on what the setup before left.
        super::hold::follow_jaws(&mut self.job, &mut self.ctx);
    }

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
        let Prepared { job, mut ctx, warnings, last_setup, .. } = self;
        let mut hold = super::hold::HoldWatch::default();
        hold.after(&job, &mut ctx, None);
        let enabled: Vec<usize> = (0..job.operations.len()).filter(|&k| job.operations[k].op().enabled()).collect();
        // The setup's stock as it came, kept for roughings with rest roughing off after others.
        let as_came = enabled.iter().skip(1).any(|&k| !job.operations[k].takes_what_is_left()).then(|| ctx.sim.clone());
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
            holders: Vec::new(),
            as_came,
            hold,
            last_setup,
            highest_clearance: f64::NEG_INFINITY,
        }
    }
}

/// A job being planned operation by operation ([`Prepared::start`]): each operation's moves cut
/// the in-process stock before the next operation plans (and the last one's too when the program
/// is verified). [`Running::simulate`] cuts them here; a pool of workers can cut them instead,
/// in bands of the stock ([`Running::take_bands`], [`crate::sim::verify::cut_bands`],
/// [`Running::absorb`]), with the same result.
pub struct Running {
    pub(super) job: Job,
    pub(super) ctx: Context,
    pub(super) warnings: Vec<Warning>,
    pub(super) enabled: Vec<usize>,
    /// How many of `enabled` are planned.
    pub(super) next: usize,
    pub(super) paths: Vec<Toolpath>,
    pub(super) path_operations: Vec<usize>,
    pub(super) move_ranges: Vec<std::ops::Range<usize>>,
    pub(super) all_moves: Vec<ProgramMove>,
    pub(super) snapshots: Vec<Option<HeightField>>,
    pub(super) loads: Vec<(Option<LoadReport>, Option<Vec<StageReport>>, Option<crate::machining::report::EngagementTarget>)>,
    /// Where the operations cut a sheet, and the grooves they engraved: what a drawing's
    /// program is verified against.
    pub(super) cuts: Vec<SheetCut>,
    pub(super) grooves: Vec<Groove>,
    /// Octree roughing's octants, for the view.
    pub(super) octants: Vec<StageOctants>,
    /// The last planned operation's moves, until they have cut the in-process stock.
    pub(super) pending: Vec<ProgramMove>,
    /// How many bands of the stock [`Running::take_bands`] handed out.
    pub(super) bands_out: usize,
    /// Each tool's holder's bound over the part, made as its paths ask ([`Running::keep_holders_out`]).
    pub(super) holders: Vec<(u32, bool, Option<crate::machining::holders::HolderBound>)>,
    /// The setup's stock as it came, before any operation cut it, where a roughing with rest
    /// roughing off plans against it.
    pub(super) as_came: Option<Simulator>,
    /// Whether the operations so far cut the part free of what holds it.
    pub(super) hold: super::hold::HoldWatch,
    /// Whether no setup follows ([`Prepared::last_setup`]).
    pub(super) last_setup: bool,
    /// The highest clearance an operation of its own moved at, where above the job's: the
    /// program starts and ends there.
    pub(super) highest_clearance: f64,
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
        if n == 0 {
            // The vise grips material before anything is cut.
            super::hold::jaws_grip(&self.job, &self.ctx)?;
        }
        self.next += 1;
        let (plan_share, _) = self.shares();
        let count = self.enabled.len() as f64;
        progress.frame(n as f64 / count, plan_share / count, Some(self.job.operations[k].name()));
        self.ctx.operation = k;
        let live = self.as_came_for(k);
        if live.is_some() {
            let name = self.job.operations[k].name().to_owned();
            self.ctx.note(&name, "rest roughing is off: it plans against the setup's stock as it came, so it cuts again through what the earlier operations cleared (air)");
        }
        // The operation's own clearance and retract, where it has them, for its planning alone.
        let job_heights = self.ctx.heights;
        if let Some(own) = self.job.operations[k].heights() {
            let lowest = self.ctx.keep_out.iter().map(|h| h.solid.max.z).fold(self.ctx.stock.max.z, f64::max);
            self.ctx.heights = own.safe(self.job.operations[k].name(), job_heights, lowest, &self.ctx.stock, &self.ctx.part)?;
            self.highest_clearance = self.highest_clearance.max(self.ctx.heights.clearance);
        }
        let o = self.job.operations[k].op();
        let planned = o.plan(&mut self.ctx, progress);
        self.ctx.heights = job_heights;
        let round = o.plans_round_fixtures();
        self.back_to(live);
        // Regions a pool made were for this operation only.
        self.ctx.given_regions.clear();
        let Planned { mut paths, cuts, grooves, load, stages, octants, engagement } = planned?;
        if !round {
            self.keep_clear(k, &mut paths);
        }
        self.keep_holders_out(k, &mut paths);
        self.loads.push((load, stages, engagement));
        self.cuts.extend(cuts);
        self.grooves.extend(grooves);
        self.octants.extend(octants);
        let first_path = self.paths.len();
        self.path_operations.extend(std::iter::repeat_n(k, paths.len()));
        self.paths.extend(paths);
        let moves = timed_moves(&self.paths, first_path, self.all_moves.last(), &self.job.tools, self.job.rapids(), self.job.air_feed())?;
        self.stopped_short(k, &moves);
        if !moves.is_empty() && (self.job.simulation.verify || self.next < self.enabled.len()) {
            self.pending = moves;
        } else {
            self.settle(moves);
        }
        Ok(true)
    }

    /// For operation `k` with rest roughing off after earlier operations: the in-process stock,
    /// taken out of the context, where the setup's stock as it came stands while it plans (or
    /// makes its regions for a pool); [`Running::back_to`] puts it back.
    pub(super) fn as_came_for(&mut self, k: usize) -> Option<Simulator> {
        let first = self.enabled.first() == Some(&k);
        let raw = self.as_came.as_ref().filter(|_| !first && !self.job.operations[k].takes_what_is_left())?.clone();
        Some(std::mem::replace(&mut self.ctx.sim, raw))
    }

    /// Puts the in-process stock [`Running::as_came_for`] took back into the context.
    pub(super) fn back_to(&mut self, live: Option<Simulator>) {
        if let Some(live) = live {
            self.ctx.sim = live;
        }
    }

    /// Keeps operation `k`'s `paths` clear of the fixtures where it planned without them
    /// ([`crate::machining::fixtures::keep_clear`]), and says which holes it left out.
    fn keep_clear(&mut self, k: usize, paths: &mut [Toolpath]) {
        if self.ctx.keep_out.is_empty() {
            return;
        }
        let name = self.job.operations[k].op().name().to_owned();
        let mut skipped: Vec<(String, crate::geom::DVec3)> = Vec::new();
        for path in paths.iter_mut() {
            let Some(tool) = self.job.tools.iter().find(|t| t.number == path.tool) else { continue };
            let over = crate::machining::fixtures::Over { clearance: self.ctx.heights.clearance, top: self.ctx.stock.max.z, gap: self.ctx.heights.gap, plunge: tool.plunge_rate };
            let cleared = crate::machining::fixtures::keep_clear(path, &tool.cutter, &self.ctx.keep_out, over);
            skipped.extend(cleared.skipped.into_iter().map(|(f, at)| (f, at.extend(self.ctx.stock.max.z))));
        }
        let names: Vec<String> = self.ctx.keep_out.iter().map(|h| h.name.clone()).collect();
        for fixture in names {
            let places: Vec<_> = skipped.iter().filter(|(f, _)| *f == fixture).map(|(_, at)| *at).collect();
            if !places.is_empty() {
                let what = format!("holes left out: drilling them would run into {fixture} ({} mm clear of it)", crate::limits::shown(self.job.fixtures.clearance));
                self.ctx.warn_at(&name, &what, &places);
            }
        }
    }

    /// Holds operation `k`'s `paths` on a part to their tools' holders' bounds
    /// ([`crate::machining::holders`]) over the part and over the stock the operation leaves,
    /// and says where the holder kept the tool above the path planned: material left there for
    /// a longer stick-out.
    fn keep_holders_out(&mut self, k: usize, paths: &mut [Toolpath]) {
        if self.ctx.sheet.is_some() {
            return;
        }
        let name = self.job.operations[k].op().name().to_owned();
        // A finishing keeps its tool's unfluted body (the shank above the flutes) out of the
        // part and the stock as it keeps the holder out: the roughings step down within the
        // flutes, but a finishing follows the part down walls deeper than them.
        let body = self.job.operations[k].is_finishing();
        // The stock the operation leaves, made once the first of its paths could bring a
        // holder down to the stock's top.
        let mut left: Option<crate::sim::DexelStock> = None;
        // The tools whose bounds are held to it for this operation already.
        let mut held: Vec<u32> = Vec::new();
        for n in 0..paths.len() {
            let Some(tool) = self.job.tools.iter().find(|t| t.number == paths[n].tool) else { continue };
            let mut rings: Vec<(f64, f64)> = tool.holder_rings().map(|r| r.to_vec()).unwrap_or_default();
            if body {
                rings.push((tool.cutter.shank_diameter.unwrap_or(tool.cutter.diameter) / 2.0, tool.cutter.flute_length));
            }
            if rings.is_empty() {
                continue;
            }
            let ctx = &self.ctx;
            let h = match self.holders.iter().position(|(n, b, _)| *n == tool.number && *b == body) {
                Some(h) => h,
                None => {
                    self.holders.push((tool.number, body, crate::machining::holders::HolderBound::new(ctx.solid.as_ref().unwrap_or(&ctx.part), &ctx.stock, &rings, &ctx.tolerances)));
                    self.holders.len() - 1
                }
            };
            let Some(bound) = self.holders[h].2.as_mut() else { continue };
            if !held.contains(&tool.number) {
                // Whether any of the tool's paths goes deep enough for its holder to reach
                // the stock's top.
                let top = ctx.stock.max.z + crate::machining::holders::HOLDER_CLEARANCE;
                let reaches = paths.iter().filter(|p| p.tool == tool.number).any(|p| p.moves.iter().any(|m| m.to().z + bound.lowest() <= top));
                if reaches && left.is_none() {
                    let tools = &self.job.tools;
                    left = Some(crate::machining::holders::stock_left(ctx.sim.stock(), paths, |t| tools.iter().find(|x| x.number == t).map(|x| x.cutter.profile()), self.job.tolerances.chordal));
                }
                bound.against(if reaches { left.clone() } else { None });
                held.push(tool.number);
            }
            let raised = crate::machining::holders::keep_holder_out(&mut paths[n], bound, self.job.tolerances.gouge, tool.feed_rate);
            // Only where the tool, planned lower, would have cut the stock there is material
            // left for a longer stick-out: not where it was raised in the air round the stock.
            let profile = tool.cutter.profile();
            let stock = ctx.sim.stock();
            let raised: Vec<_> = raised.into_iter().filter(|(p, planned)| stock.touch(p.truncate(), &profile, false) > planned + self.job.tolerances.gouge).map(|(p, _)| p).collect();
            if !raised.is_empty() {
                let stick_out = crate::limits::shown(tool.standing_out());
                let flutes = crate::limits::shown(tool.cutter.flute_length);
                let what = match (&tool.holder, body) {
                    (Some(holder), true) => format!(
                        "places held up so that T{}'s holder ({}, {stick_out} mm stick-out) keeps clear of the part and the stock, and its flutes ({flutes} mm) take all it cuts: material left there for a tool with longer flutes and stick-out",
                        tool.number, holder.name
                    ),
                    (Some(holder), false) => format!("places held up so that T{}'s holder ({}, {stick_out} mm stick-out) keeps clear of the part and the stock: material left there for a longer stick-out", tool.number, holder.name),
                    (None, _) => format!(
                        "places held up so that T{}'s flutes ({flutes} mm) take all it cuts, its shank above them clear of the part and the stock: material left there for a tool with longer flutes",
                        tool.number
                    ),
                };
                self.ctx.warn_at(&name, &what, &raised);
            }
        }
    }

    /// Says where operation `k`'s cutting `moves` were stopped short by a fixture (came to its
    /// clearance): material may be left beside it.
    fn stopped_short(&mut self, k: usize, moves: &[ProgramMove]) {
        if self.ctx.keep_out.is_empty() {
            return;
        }
        let near = crate::sim::fixtures::collisions(moves, &self.ctx.keep_out, -crate::geom::tolerance::FIXTURE_CONTACT);
        let clearance = crate::limits::shown(self.job.fixtures.clearance);
        // The cutting moves' places by fixture.
        let said: Vec<(String, Vec<crate::geom::DVec3>)> = self
            .ctx
            .keep_out
            .iter()
            .map(|h| {
                let places = near.iter().filter(|n| n.fixture == h.name && !moves[n.move_index].mv.is_rapid()).map(|n| n.at).collect();
                (format!("places stopped short of {} ({clearance} mm clear of it): material may be left beside it", h.name), places)
            })
            .filter(|(_, places): &(String, Vec<_>)| !places.is_empty())
            .collect();
        let name = self.job.operations[k].op().name().to_owned();
        for (what, places) in said {
            self.ctx.warn_at(&name, &what, &places);
        }
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
        if let Some(k) = cuts.iter().flat_map(|c| c.moves.last()).map(|c| c.index).find(|&k| k >= moves.len()) {
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
        let op = self.enabled.get(self.next.wrapping_sub(1)).copied();
        self.hold.after(&self.job, &mut self.ctx, op);
        self.move_ranges.push(self.all_moves.len()..self.all_moves.len() + moves.len());
        self.all_moves.extend(moves);
    }

    /// Writes the program once every operation is planned and has cut the stock, and judges it
    /// when the job verifies.
    pub fn finish(self, progress: &mut Progress) -> Result<JobOutput> {
        if self.next < self.enabled.len() || !self.pending.is_empty() {
            return Err(Error::Input("the job is not planned to its end yet".into()));
        }
        let Running {
            job, ctx, mut warnings, enabled, mut paths, path_operations, move_ranges, mut all_moves, snapshots, loads, cuts, grooves, octants, mut hold, last_setup, highest_clearance, ..
        } = self;
        let (freed_warning, freed) = hold.said(&job, enabled.last().copied(), last_setup);
        warnings.extend(freed_warning);
        warnings.extend(hold.parting_off(&job, last_setup, ctx.part.bounds().min.z));
        let job = &job;
        let verify = job.simulation.verify;
        let mut ctx = ctx;
        progress.frame(0.0, 1.0, None);
        warnings.append(&mut ctx.warnings);
        if all_moves.iter().all(|m| matches!(m.mv, crate::toolpath::Move::Rapid { .. })) {
            let why = if warnings.is_empty() { String::new() } else { format!(" ({})", warnings.iter().map(Warning::to_string).collect::<Vec<_>>().join("; ")) };
            return Err(Error::Nothing(format!("the program has no cutting moves{why}")));
        }
        let Context { part, sheet, stock, mut heights, caches, sim, keep_out, .. } = ctx;
        // The program starts and ends above every operation's clearance.
        heights.clearance = heights.clearance.max(highest_clearance);
        // The simulation that carried the in-process stock judges the whole program.
        let (mut verification, sim) = if verify {
            let settings = job.verify_settings(&stock, None);
            let tol = job.tolerances;
            let v = match &sheet {
                None => sim.finish_mesh_cut(&part, hold.take_part(), |field, grid| drawing::lower_in_grooves(field, &grooves, grid, tol.gouge, stock.max.z), settings.allowance, &tol),
                Some(sheet) => {
                    let mut v = sim.finish(|grid| drawing::surface(&cuts, &grooves, grid, tol.gouge, &tol), settings.allowance, &tol);
                    // The drawing's circles are its holes: a gouge on one's wall is said as a
                    // tool too wide for it (a φ6 drill in φ5 holes), not as cells.
                    v.holes = crate::holes::in_drawing(&sheet.drawing, stock.max.z, stock.max.z - sheet.thickness).into_iter().filter(|h| !h.mark).collect();
                    v
                }
            };
            (Some(v), None)
        } else {
            (None, Some(sim))
        };
        let (volumes, nearest, rates, cell) = match (&verification, &sim) {
            (Some(v), _) => (&v.volumes[..], &v.nearest[..], v.rates.clone(), Some(v.stock.grid().spacing)),
            (None, Some(sim)) => (sim.volumes(), sim.nearest(), sim.rates(), Some(sim.stock().grid().spacing)),
            (None, None) => (&[][..], &[][..], Vec::new(), None),
        };
        // Feeds raised for thin chips and air, where the job asks.
        let in_motion = |moves: &[ProgramMove]| moves.iter().map(|m| m.seconds).sum::<f64>();
        let plain = in_motion(&all_moves);
        let (mut rates, sped) = match (job.simulation.optimize_feeds, cell) {
            (true, Some(cell)) if volumes.len() == all_moves.len() && nearest.len() == all_moves.len() => {
                let sped = crate::sim::feeds::speed_up(&mut paths, &mut all_moves, volumes, nearest, cell, job.air_feed());
                let timings: Vec<_> = all_moves.iter().map(ProgramMove::timing).collect();
                (crate::sim::program::removal_rates(&timings, volumes, crate::sim::program::RATE_CELLS * cell), Some(sped))
            }
            _ => (rates, None),
        };
        // Feeds held where a cut would take more than the spindle has.
        let kc = job.stock.material.and_then(crate::cutting::Material::specific_cutting_force);
        let mut slowed = 0;
        if let (Some(limit), Some(cell)) = (crate::cutting::rate_limit(&job.machine, job.stock.material), cell) {
            if rates.iter().any(|&r| r > limit) {
                let before = rates.iter().copied().fold(0.0, f64::max);
                let held = crate::sim::feeds::hold_rate(&mut paths, &mut all_moves, volumes, cell, limit);
                let said = held_power(job, &path_operations, &all_moves, &held.slowed, before, kc.unwrap_or_default());
                warnings.extend(said);
                slowed = held.slowed.len();
                rates = held.rates;
            }
        }
        let refed = sped.is_some() || slowed > 0;
        let chips = cell.map(|cell| crate::sim::feeds::chips(&all_moves, volumes, nearest, cell, &job.tools));
        let crate::post::Written { gcode, cycle, move_lines } = write_mapped(&job.name, &paths, &job.tools, heights.clearance, &job.post_for_machine())?;
        let stats = paths.iter().fold(PathStats::default(), |s, p| s + p.stats(job.rapids()));
        let mut operations = report::per_operation(job, &enabled, &all_moves, &move_ranges, volumes, &rates, &snapshots, verification.as_ref());
        for ((o, (load, stages, engagement)), range) in operations.iter_mut().zip(loads).zip(&move_ranges) {
            o.load = load;
            o.stages = stages;
            o.engagement = engagement.zip(cell).filter(|_| nearest.len() == all_moves.len()).map(|(target, cell)| {
                let r = range.clone();
                report::EngagementReport::measure(target, &all_moves[r.clone()], &volumes[r.clone()], &nearest[r], cell)
            });
            // Its time as the program's head states it: its paths' as the post wrote them.
            o.seconds = path_operations.iter().zip(&cycle.paths).filter(|(&k, _)| k == o.index).map(|(_, s)| s).sum();
            o.power_max = o.mrr_max.zip(kc).map(|(m, kc)| crate::cutting::power(m, kc));
            o.chip_max = chips.as_ref().and_then(|c| c.get(range.clone())).map(|c| c.iter().copied().fold(0.0, f64::max));
        }
        let feeds = sped.map(|s| report::FeedReport { plain, seconds: in_motion(&all_moves), faster: s.faster, aired: s.aired, slowed });
        let time = cycle.items(&CycleTime::groups(&paths));
        if let Some(v) = verification.as_mut() {
            if refed {
                v.rates = rates;
                v.report.mrr_max = v.rates.iter().copied().fold(0.0, f64::max);
            }
            v.word_holes(&all_moves);
            // Every move against what holds the stock, by its name.
            v.report.fixtures(keep_out.len(), crate::sim::fixtures::collisions(&all_moves, &keep_out, job.tolerances.gouge));
        }
        let found = verification.as_ref().and_then(|v| {
            let found = v.report.problem()?;
            Some(match gouge_causes(sheet.as_ref().map(|s| &s.drawing), &v.report) {
                causes if causes.is_empty() => found,
                causes => format!("{}; {found}", causes.join("; ")),
            })
        });
        // A program the machine cannot reach is not safe to run, verified or not.
        // (The moves' extent only where the machine's travel is known.)
        let beyond = job.machine.travel.map_or_else(Vec::new, |_| {
            let (low, high) = move_extent(&all_moves);
            job.machine.beyond_travel(low, high)
        });
        let problem = match (found, beyond.is_empty()) {
            (found, true) => found,
            (None, false) => Some(beyond.join("; ")),
            (Some(found), false) => Some(format!("{}; {found}", beyond.join("; "))),
        };
        let problem = match (problem, freed) {
            (p, None) => p,
            (None, f) => f,
            (Some(p), Some(f)) => Some(format!("{f}; {p}")),
        };
        progress.stage("done", 1.0, 0.0);
        let drawing = sheet.map(|s| s.drawing);
        let (clearance_z, cache) = (heights.clearance, caches.counts);
        Ok(JobOutput {
            part,
            drawing,
            stock,
            clearance_z,
            paths,
            path_operations,
            gcode,
            move_lines,
            cycle,
            time,
            stats,
            moves: all_moves,
            operations,
            verification,
            warnings,
            problem,
            cache,
            octants,
            feeds,
            zero_at: job.zero_at(None),
        })
    }
}

/// Refuses a part that is not inside its blank (a casting): where a point of the part lies
/// above the blank's top or below its bottom over it by more than a hundredth of a millimetre,
/// the stock holds no material for that part of it (a blank 2 mm short under the part was
/// refused later as a gouge of 640 cells). A part beside the blank is the stock box's check.
fn outside_the_blank(part: &Mesh, blank: &super::blank::Columns) -> Result<()> {
    const SLACK: f64 = 0.01;
    let step = (part.vertices.len() / 20_000).max(1);
    let mut worst: Option<(f64, DVec3, f64, bool)> = None;
    for &v in part.vertices.iter().step_by(step) {
        let (lo, hi) = blank.material(v.truncate());
        let (by, edge, below) = if hi <= lo {
            continue;
        } else if v.z < lo - SLACK {
            (lo - v.z, lo, true)
        } else if v.z > hi + SLACK {
            (v.z - hi, hi, false)
        } else {
            continue;
        };
        if worst.is_none_or(|w| by > w.0) {
            worst = Some((by, v, edge, below));
        }
    }
    let Some((by, at, edge, below)) = worst else { return Ok(()) };
    Err(Error::Input(format!(
        "stock.mesh: the part is not inside the blank: at X{:.3} Y{:.3} it reaches Z{:.3}, {:.3} mm {} the blank's {} (Z{edge:.3}); the stock holds no material there: check that the part and the blank come from the same model",
        at.x,
        at.y,
        at.z,
        by,
        if below { "below" } else { "above" },
        if below { "bottom" } else { "top" }
    )))
}

/// The least and greatest tip position of `moves` in each axis ([`crate::toolpath::Move::bounds`]).
fn move_extent(moves: &[ProgramMove]) -> ([f64; 3], [f64; 3]) {
    if moves.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    let (lo, hi) = moves.iter().map(|m| m.mv.bounds(m.from)).fold((crate::geom::DVec3::INFINITY, crate::geom::DVec3::NEG_INFINITY), |(lo, hi), (a, b)| (lo.min(a), hi.max(b)));
    (lo.to_array(), hi.to_array())
}

/// Why a program gouges, where the drawing says it before the simulation's cells do: its loops
/// cross (they draw no one part, and the cut round each goes into the other). A tool too wide
/// for a hole is said by [`crate::sim::verify::hole_overcuts`].
fn gouge_causes(drawing: Option<&Drawing>, report: &crate::sim::verify::Report) -> Vec<String> {
    let mut out = Vec::new();
    if report.gouge_count == 0 {
        return out;
    }
    if let Some((a, b, at)) = drawing.and_then(Drawing::crossing_loops) {
        out.push(format!(
            "the drawing's loops {a} and {b} cross (at X{:.3} Y{:.3}): they draw no one part, and the cut round each goes into the other; join them into one outline, or choose the loops to cut",
            at.x, at.y
        ));
    }
    out
}

/// What the user should know of a drawing as read: what it left out (text, dimensions, and
/// elements that draw nothing: a circle of radius 0, a line to a coordinate that is not a
/// number), by kind, with counts.
pub fn drawing_warnings(d: &Drawing) -> Vec<Warning> {
    let mut out: Vec<Warning> = drawing_unit_warning(d).into_iter().collect();
    if !d.ignored.is_empty() {
        let list: Vec<String> = d.ignored.iter().map(|(k, n)| format!("{n} {k}")).collect();
        out.push(Warning::job(format!("the drawing left out: {}", list.join("; "))));
    }
    out
}

/// A drawing under 5 mm or over 3 m across as read ([`crate::mesh::placement::LIKELY_ACROSS`]),
/// where the other unit a drawing can be read in (inch or mm) would make it a part: that unit,
/// and its size then.
pub fn drawing_unit_warning(d: &Drawing) -> Option<Warning> {
    let size = d.bounds().size();
    let across = size.x.max(size.y);
    let [low, high] = crate::mesh::placement::LIKELY_ACROSS;
    let inches = d.scale == 25.4;
    let (unit, choice, mm) = if across < low && !inches {
        ("inches", "inch", across * 25.4)
    } else if across > high && inches {
        ("millimetres", "mm", across / 25.4)
    } else {
        return None;
    };
    if !(2.0 * low..=high).contains(&mm) {
        return None;
    }
    Some(Warning::job(format!(
        "the drawing is {} × {} mm, {}: is the file in another unit? {} (Units of the file: {choice}; drawing.units in a job file)",
        size_shown(size.x),
        size_shown(size.y),
        outside_likely(across),
        read_in(unit, mm)
    )))
}

/// What the user should know of a part as read and placed: triangles dropped, holes in its
/// surface, and a size that says it was read in the wrong unit (under 5 mm or over 3 m
/// across).
pub fn part_warnings(mesh: &Mesh) -> Vec<Warning> {
    let mut out = surface_warnings(mesh);
    out.extend(unit_warning(mesh));
    out
}

/// A part under 5 mm or over 3 m across as placed ([`crate::mesh::placement::LIKELY_ACROSS`]):
/// the unit that would make it a part, and its size then.
fn unit_warning(mesh: &Mesh) -> Option<Warning> {
    let size = mesh.bounds().size();
    let across = size.x.max(size.y).max(size.z);
    let (read_in, choice) = likely_unit(across)?;
    Some(Warning::job(format!(
        "the part is {} × {} × {} mm, {}: is the file in another unit? {read_in} (Units of the file: {choice}; part.units in a job file)",
        size_shown(size.x),
        size_shown(size.y),
        size_shown(size.z),
        outside_likely(across)
    )))
}

/// For a part `across` mm wide, the unit that would make it a part, in the words both its
/// warnings use ([`read_in`]), and the page's choice for it.
fn likely_unit(across: f64) -> Option<(String, &'static str)> {
    let (unit, choice, mm) = crate::mesh::placement::PartUnits::likely(across)?;
    Some((read_in(unit, mm), choice))
}

/// What a part or drawing read in `unit` would be: "Read in inches it would be 90 mm across".
fn read_in(unit: &str, mm: f64) -> String {
    format!("Read in {unit} it would be {} mm across", size_shown(mm))
}

/// Which side of [`crate::mesh::placement::LIKELY_ACROSS`] a size `across` falls: "under 5 mm
/// across", "over 3000 mm across".
fn outside_likely(across: f64) -> String {
    let [low, high] = crate::mesh::placement::LIKELY_ACROSS;
    if across < low {
        format!("under {low} mm across")
    } else {
        format!("over {high} mm across")
    }
}

/// Triangles dropped as a part was read, and holes in its surface (edges bordering one
/// triangle, off the rim of its outline; [`Mesh::open_edges`]).
fn surface_warnings(mesh: &Mesh) -> Vec<Warning> {
    let mut out = Vec::new();
    if mesh.dropped_duplicates > 0 {
        out.push(Warning::job(format!("{} triangles were copies of others (the same three corners) and were ignored", mesh.dropped_duplicates)).note());
    }
    if mesh.dropped_degenerate > 0 {
        out.push(Warning::job(format!("{} degenerate triangles (zero area) were ignored", mesh.dropped_degenerate)).note());
    }
    let open = mesh.open_edges();
    if !open.is_empty() {
        out.push(Warning::counted(None, "edges of the part's surface border one triangle only: it has holes, and a cutter goes down through them (a file cut short or a bad export?)", &open));
    }
    out
}

/// A size as a warning says it: three significant figures, at most three decimals.
fn size_shown(mm: f64) -> String {
    let decimals = (2 - mm.abs().max(1e-3).log10().floor() as i32).clamp(0, 3) as usize;
    let text = format!("{mm:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

/// A warning when the smallest tool the job uses is wider than the placed part is in X or Y:
/// most often a part read in the wrong unit (a glTF in metres read as millimetres is a thousand
/// times too small).
fn tool_larger_than_part(job: &Job, part: &Mesh) -> Option<(Warning, bool)> {
    let used: Vec<u32> = job.operations.iter().filter(|o| o.op().enabled()).flat_map(|o| o.op().tools()).collect();
    let smallest = job.tools.iter().filter(|t| used.is_empty() || used.contains(&t.number)).min_by(|a, b| a.cutter.diameter.total_cmp(&b.cutter.diameter))?;
    let size = part.bounds().size();
    let d = smallest.cutter.diameter;
    let across = size.x.max(size.y).max(size.z);
    let setting = format!("in a job file part.units: {:?}, part.scale: {}", job.part.units, job.part.scale);
    let unit = match likely_unit(across) {
        Some((read_in, choice)) => format!("is its unit right? {read_in} (Units of the file: {choice}; {setting})"),
        None => format!("is its unit right? (Units of the file; {setting})"),
    };
    if d > size.x.max(size.y) {
        Some((Warning::job(format!("the part is {:.2} × {:.2} × {:.2} mm, smaller than the φ{d} tool T{}: {unit}", size.x, size.y, size.z, smallest.number)), true))
    } else if d > size.x.min(size.y) {
        Some((
            Warning::job(format!(
                "the part is {:.2} × {:.2} × {:.2} mm, narrower across than the φ{d} tool T{}: the tool fits in none of its pockets or gaps and cuts only around it; {unit}",
                size.x, size.y, size.z, smallest.number
            )),
            false,
        ))
    } else {
        None
    }
}

/// The moves of `paths[first..]`, timed on from the program's last move so far.
fn timed_moves(paths: &[Toolpath], first: usize, last: Option<&ProgramMove>, tools: &[Tool], rapids: crate::toolpath::Rapids, air_feed: f64) -> Result<Vec<ProgramMove>> {
    let clock = last.map_or(0.0, |m| m.start + m.seconds);
    let mut moves = program_moves(&paths[first..], tools, rapids, air_feed)?;
    for m in &mut moves {
        m.path += first;
        m.start += clock;
    }
    Ok(moves)
}

/// The error for a part the stock does not hold: wholly below its bottom (the whole stock would
/// be milled away down to the bottom), above its top (nothing to cut), or beside it.
fn outside_the_stock(part: &Aabb, stock: &Aabb) -> Result<()> {
    let why = if part.max.z <= stock.min.z {
        format!("the part lies wholly below the stock's bottom (its top at Z{:.3}, the stock's bottom at Z{:.3}): every operation would mill the whole stock away", part.max.z, stock.min.z)
    } else if part.min.z >= stock.max.z {
        format!("the part lies wholly above the stock's top (its bottom at Z{:.3}, the stock's top at Z{:.3}): there is nothing to cut", part.min.z, stock.max.z)
    } else if part.max.x <= stock.min.x || part.min.x >= stock.max.x || part.max.y <= stock.min.y || part.min.y >= stock.max.y {
        "the part lies wholly beside the stock, not in it".to_owned()
    } else {
        return Ok(());
    };
    Err(Error::Input(format!("{why}; check stock.sizeBox, stock.zero and the part's placement")))
}

/// What holding the feeds to the spindle's power did, a warning for each operation whose
/// moves were slowed: how many, the spindle, and the most the cuts took at the feeds as
/// planned (`before`, mm³/min; `kc` the material's specific cutting force).
fn held_power(job: &Job, path_operations: &[usize], moves: &[ProgramMove], slowed: &[usize], before: f64, kc: f64) -> Vec<Warning> {
    let mut out: Vec<Warning> = Vec::new();
    let material = job.stock.material.map_or("", crate::cutting::Material::words);
    let spindle = job.machine.power.map(crate::limits::shown).unwrap_or_default();
    let what = format!(
        "feeds held down so that no cut takes more than the {}'s {spindle} kW spindle in {material} (Kc {kc:.0} N/mm²; the program as planned took up to {:.2} kW)",
        job.machine.name,
        crate::cutting::power(before, kc)
    );
    for &k in slowed {
        let op = job.operations[path_operations[moves[k].path]].name();
        let at = [moves[k].mv.to()];
        match out.iter_mut().find(|w| w.operation.as_deref() == Some(op)) {
            Some(w) => w.add(&at),
            None => out.push(Warning::counted(Some(op), &what, &at)),
        }
    }
    out
}
