//! What one worker of a pool holds, and the flat form its pieces travel in between workers
//! (numbers in typed arrays, no shared memory): the native half of the page's pool
//! (`www/swarf.js`), so that `cargo test` runs the same wire format the browser does
//! (`tests/pool.rs`). `wasm.rs` only converts these to and from JavaScript.
//!
//! Each worker prepares its own copy of the job and part ([`PoolWorker::prepare`]); the helpers
//! make bands of rows of the CL surfaces and level maps and ranges of raster passes, the planner
//! keeps them ([`crate::job::pool`]); then the planner plans operation by operation, the regions
//! of a z-level operation's levels made on every worker first, and each operation's moves cut
//! the in-process stock in groups of bands of rows on every worker.

use super::pool::RasterWork;
use super::run::{JobOutput, Prepared, Running};
use super::schema::{Job, Workpiece};
use super::setups::{carried, laid_like, setup_error, Orientation};
use crate::drawing::Shape;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::machining::context::SurfaceRequest;
use crate::machining::levels::RegionWork;
use crate::progress::Progress;
use crate::sim::program::{decode, encode, ProgramMove};
use crate::sim::verify::{cut_bands, BandCut};
use crate::sim::DexelStock;

/// What a pool can share of a prepared job: the surfaces' sizes, the raster operations'
/// passes, and the surfaces whose level maps are wanted.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "camelCase")]
pub struct PlanNeeds {
    /// Per CL surface, its nodes across and up (`nx`, `ny`).
    pub surfaces: Vec<SurfaceSize>,
    pub rasters: Vec<RasterWork>,
    /// Indices in `surfaces`.
    pub level_maps: Vec<usize>,
}

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SurfaceSize {
    pub nx: usize,
    pub ny: usize,
}

/// The regions of the next operation's levels as work for the pool: its surface's index in
/// [`PlanNeeds::surfaces`], the height each level is contoured at, and the nodes each keeps
/// (packed eight to a byte, level after level).
#[derive(Clone, Debug, PartialEq)]
pub struct LevelWork {
    pub surface: usize,
    pub levels: Vec<f64>,
    pub keep: Vec<u8>,
}

/// One worker's job in a pool (the planner's or a helper's).
pub struct PoolWorker {
    job: Job,
    prepared: Option<Prepared>,
    surfaces: Vec<SurfaceRequest>,
    /// The planner's job once it plans operation by operation ([`PoolWorker::start`]).
    running: Option<Running>,
    /// A helper's copy of the moves it cuts its bands of the stock with.
    moves: Vec<ProgramMove>,
    /// The regions the planner asked the pool for ([`PoolWorker::region_work`]).
    regions: Option<RegionWork>,
    /// The setup this worker plans, for a job with setups ([`PoolWorker::prepare_setup`]).
    setup: Option<SetupPlace>,
}

/// Which setup of a job with setups a worker plans and where it holds the part.
#[derive(Clone, Debug, PartialEq)]
pub struct SetupPlace {
    pub index: usize,
    pub name: String,
    pub orientation: Orientation,
    /// Whether a setup follows it (its stock is carried on).
    pub more: bool,
    /// Whether its work zero puts X0 Y0 at a point ([`Job::zero_at`]).
    pub zero_at: bool,
}

impl PoolWorker {
    /// Prepares `job` on `workpiece`.
    pub fn prepare(job: Job, workpiece: Workpiece) -> Result<PoolWorker> {
        let prepared = super::run::prepare(&job, workpiece)?;
        let surfaces = prepared.surfaces()?;
        Ok(PoolWorker { job, prepared: Some(prepared), surfaces, running: None, moves: Vec::new(), regions: None, setup: None })
    }

    /// Prepares setup `k` of `job` (a job with setups) on `workpiece`: the part held as that
    /// setup holds it ([`super::setups`]), its stock the raw box until
    /// [`PoolWorker::carry_from`] carries in what the setup before left.
    pub fn prepare_setup(job: &Job, workpiece: Workpiece, k: usize) -> Result<PoolWorker> {
        let Workpiece::Mesh(part) = workpiece else {
            return Err(Error::Input("setups turn a 3D part over; a drawing is cut from one side (a job without setups)".into()));
        };
        let (sub, held, orientation) = job.for_setup(k, part)?;
        let names = job.setup_names();
        let name = names[k].clone();
        let mut worker = PoolWorker::prepare(sub, Workpiece::Mesh(held)).map_err(|e| setup_error(k, &name, e))?;
        worker.setup = Some(SetupPlace { index: k, name, orientation, more: k + 1 < names.len(), zero_at: job.zero_at(Some(k)) });
        if let Some(p) = worker.prepared.as_mut() {
            p.last_setup = k + 1 == names.len();
        }
        Ok(worker)
    }

    /// The setup this worker plans, if the job has setups.
    pub fn setup(&self) -> Option<&SetupPlace> {
        self.setup.as_ref()
    }

    /// Starts from the stock `left` that the setup before (holding the part as `from`) left,
    /// turned into this setup's frame. Before planning.
    pub fn carry_from(&mut self, left: &DexelStock, from: &Orientation) -> Result<()> {
        let to = self.setup.as_ref().map(|s| s.orientation).ok_or_else(|| Error::Input("only a setup's plan carries a stock in".into()))?;
        self.prepared()?.carry(laid_like(left, from, &to), |p, spans| carried(left, from, &to, p, spans));
        Ok(())
    }

    /// `e` said with this worker's setup, if any.
    fn named(&self, e: Error) -> Error {
        match &self.setup {
            Some(s) => setup_error(s.index, &s.name, e),
            None => e,
        }
    }

    pub fn job(&self) -> &Job {
        &self.job
    }

    fn prepared(&mut self) -> Result<&mut Prepared> {
        self.prepared.as_mut().ok_or_else(|| Error::Input("this plan has run".into()))
    }

    fn surface(&self, k: usize) -> Result<SurfaceRequest> {
        self.surfaces.get(k).copied().ok_or_else(|| Error::Input(format!("no surface {k}")))
    }

    fn running(&mut self) -> Result<&mut Running> {
        self.running.as_mut().ok_or_else(|| Error::Input("this plan has not started".into()))
    }

    /// What can be shared ([`PlanNeeds`]).
    pub fn needs(&mut self) -> Result<PlanNeeds> {
        let surfaces = self.surfaces.clone();
        let rasters = self.prepared()?.rasters(&surfaces)?;
        let level_maps = self.prepared()?.level_maps(&surfaces)?;
        Ok(PlanNeeds { surfaces: surfaces.iter().map(|s| SurfaceSize { nx: s.grid.nx, ny: s.grid.ny }).collect(), rasters, level_maps })
    }

    /// Rows `j0..j1` of the level map of surface `k`: the heights along the edges to the
    /// right, those along the edges up, then the node bounds (as many of each).
    pub fn level_rows(&mut self, k: usize, j0: usize, j1: usize) -> Result<Vec<f64>> {
        let s = self.surface(k)?;
        let (mut right, up, wide) = self.prepared()?.level_rows(s, j0..j1)?;
        right.extend(up);
        right.extend(wide);
        Ok(right)
    }

    /// Keeps the level map of surface `k`: `right` and `up` for every node, row after row, and
    /// its node bounds `wide` unless empty.
    pub fn keep_level_map(&mut self, k: usize, right: Vec<f64>, up: Vec<f64>, wide: Vec<f64>) -> Result<()> {
        let s = self.surface(k)?;
        self.prepared()?.keep_level_map(s, right, up, wide)
    }

    /// Rows `j0..j1` of surface `k`, row after row.
    pub fn surface_rows(&mut self, k: usize, j0: usize, j1: usize) -> Result<Vec<f64>> {
        let s = self.surface(k)?;
        self.prepared()?.surface_rows(s, j0..j1, &mut Progress::none())
    }

    /// Keeps the whole of surface `k` (`nx × ny` heights, row after row).
    pub fn keep_surface(&mut self, k: usize, z: Vec<f64>) -> Result<()> {
        let s = self.surface(k)?;
        self.prepared()?.keep_surface(s, z)
    }

    /// Passes `i0..i1` of the raster operation `operation`, flat: per pass its number of runs,
    /// per run its number of points, then the points' x, y, z.
    pub fn raster_passes(&mut self, operation: usize, i0: usize, i1: usize) -> Result<Vec<f64>> {
        let passes = self.prepared()?.raster_passes(operation, i0..i1)?;
        let mut out = Vec::new();
        for runs in &passes {
            out.push(runs.len() as f64);
            for run in runs {
                out.push(run.len() as f64);
                out.extend(run.iter().flat_map(|p| [p.x, p.y, p.z]));
            }
        }
        Ok(out)
    }

    /// Keeps passes `first..` of the raster operation `operation`, as
    /// [`PoolWorker::raster_passes`] wrote them (`count` passes).
    pub fn keep_passes(&mut self, operation: usize, first: usize, count: usize, flat: &[f64]) -> Result<()> {
        let mut at = 0;
        let mut next = || -> Result<f64> {
            let v = *flat.get(at).ok_or_else(|| Error::Input("the passes end early".into()))?;
            at += 1;
            Ok(v)
        };
        let mut passes = Vec::with_capacity(count);
        for _ in 0..count {
            let runs = next()? as usize;
            let mut pass = Vec::with_capacity(runs);
            for _ in 0..runs {
                let points = next()? as usize;
                let mut run = Vec::with_capacity(points);
                for _ in 0..points {
                    run.push(DVec3::new(next()?, next()?, next()?));
                }
                pass.push(run);
            }
            passes.push(pass);
        }
        self.prepared()?.keep_passes(operation, first, passes)
    }

    /// Lets go of the prepared part and surfaces, keeping the job: a helper of the pool then
    /// only cuts bands of the stock, for which the job's tools and tolerances are enough.
    pub fn release(&mut self) {
        self.prepared = None;
    }

    /// Starts planning operation by operation.
    pub fn start(&mut self) -> Result<()> {
        let prepared = self.prepared.take().ok_or_else(|| Error::Input("this plan has run".into()))?;
        self.running = Some(prepared.start());
        Ok(())
    }

    /// Plans the next operation: `None` once all are planned, else how many moves wait to cut
    /// the in-process stock (0 when none do).
    pub fn plan_next(&mut self, progress: &mut Progress) -> Result<Option<usize>> {
        let running = self.running()?;
        match running.plan_next(progress) {
            Ok(more) => Ok(more.then(|| running.pending().len())),
            Err(e) => Err(self.named(e)),
        }
    }

    /// The regions of the next operation's levels as work for the pool, when it has levels on
    /// one of the shared surfaces. The planner keeps the work until [`PoolWorker::keep_regions`].
    pub fn region_work(&mut self) -> Result<Option<LevelWork>> {
        let Some(work) = self.running()?.region_work(&mut Progress::none())? else { return Ok(None) };
        let Some(surface) = self.surfaces.iter().position(|s| *s == work.request) else { return Ok(None) };
        let levels = work.levels.iter().map(|l| l.0).collect();
        let keep = work.levels.iter().flat_map(|l| l.1.iter().copied()).collect();
        self.regions = Some(work);
        Ok(Some(LevelWork { surface, levels, keep }))
    }

    /// The regions of levels `levels` of surface `k`, each keeping the nodes of `keep` (packed,
    /// level after level), flat ([`Shape::to_flat`]).
    pub fn level_regions(&mut self, k: usize, levels: &[f64], keep: &[u8]) -> Result<Vec<f64>> {
        let s = self.surface(k)?;
        let per = s.grid.nodes().div_ceil(8);
        if keep.len() != per * levels.len() {
            return Err(Error::Input(format!("{} bytes are not the kept nodes of {} levels", keep.len(), levels.len())));
        }
        let work: Vec<(f64, Vec<u8>)> = levels.iter().zip(keep.chunks(per.max(1))).map(|(&z, k)| (z, k.to_vec())).collect();
        let shapes = match &mut self.running {
            Some(r) => r.level_regions(s, &work),
            None => self.prepared()?.level_regions(s, &work),
        }?;
        let mut out = Vec::new();
        shapes.iter().for_each(|s| s.to_flat(&mut out));
        Ok(out)
    }

    /// Keeps the regions of every level of the last [`PoolWorker::region_work`] (flat, level
    /// after level), for the next operation to take as it plans.
    pub fn keep_regions(&mut self, flat: &[f64]) -> Result<()> {
        let work = self.regions.take().ok_or_else(|| Error::Input("no regions were asked for".into()))?;
        let shapes = Shape::all_from_flat(flat).ok_or_else(|| Error::Input("the regions end early".into()))?;
        self.running()?.keep_regions(&work, shapes)
    }

    /// The moves waiting to cut the stock, flat, for the pool's helpers ([`encode`]).
    pub fn pending_moves(&mut self) -> Result<Vec<f64>> {
        Ok(encode(self.running()?.pending()))
    }

    /// The in-process stock, taken out in `groups` groups of consecutive bands of rows (each
    /// flat, [`DexelStock::to_flat`]) for the pool to cut with the pending moves;
    /// [`PoolWorker::absorb`] takes them back.
    pub fn take_bands(&mut self, groups: usize) -> Result<Vec<Vec<f64>>> {
        let bands = self.running()?.take_bands();
        let size = bands.len().div_ceil(groups.max(1)).max(1);
        Ok(bands.chunks(size).map(DexelStock::all_to_flat).collect())
    }

    /// Keeps `flat` ([`PoolWorker::pending_moves`] of the planner) as the moves this helper
    /// cuts its bands with.
    pub fn keep_moves(&mut self, flat: &[f64]) -> Result<()> {
        self.moves = decode(flat, &self.job.tools)?;
        Ok(())
    }

    /// Cuts a group of bands of the stock (flat, from [`PoolWorker::take_bands`]) with the
    /// pending moves (the planner) or the kept ones (a helper): the bands and their cuts, flat.
    pub fn cut_bands(&mut self, group: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        let mut bands = DexelStock::all_from_flat(group).ok_or_else(|| Error::Input("a group of bands of the stock ends early".into()))?;
        let tolerances = self.job.tolerances;
        let moves = match &self.running {
            Some(r) => r.pending(),
            None => &self.moves[..],
        };
        let cuts = cut_bands(&mut bands, moves, &tolerances, &mut Progress::none(), 1.0)?;
        Ok((DexelStock::all_to_flat(&bands), cuts.iter().flat_map(|c| c.to_flat()).collect()))
    }

    /// Takes back the stock's groups of bands (all of them, in order, as
    /// [`PoolWorker::cut_bands`] returned them) with their cuts, flat.
    pub fn absorb(&mut self, groups: &[Vec<f64>], cuts: &[Vec<f64>]) -> Result<()> {
        let (mut bands, mut all) = (Vec::new(), Vec::new());
        for (g, c) in groups.iter().zip(cuts) {
            bands.extend(DexelStock::all_from_flat(g).ok_or_else(|| Error::Input("a group of bands of the stock ends early".into()))?);
            all.extend(BandCut::all_from_flat(c)?);
        }
        self.running()?.absorb(bands, &all)
    }

    /// Writes the program once every operation is planned and has cut the stock.
    pub fn finish(&mut self, progress: &mut Progress) -> Result<JobOutput> {
        let running = self.running.take().ok_or_else(|| Error::Input("this plan has not started".into()))?;
        running.finish(progress).map_err(|e| self.named(e))
    }

    /// Plans the job with what was kept and writes its program, on this worker alone.
    pub fn run(&mut self, progress: &mut Progress) -> Result<JobOutput> {
        let prepared = self.prepared.take().ok_or_else(|| Error::Input("this plan has run".into()))?;
        prepared.run(progress).map_err(|e| self.named(e))
    }
}
