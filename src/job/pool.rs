//! A job's heavy, independent work in pieces, for a pool of workers (issue 15, "every core in
//! the browser"). Wasm in a page has one thread, and sharing memory between workers needs a
//! cross-origin-isolated page, which a static host or `file://` cannot promise; so every worker
//! of the page's pool prepares its own copy of the job and part ([`super::prepare`]) and is
//! asked for pieces: bands of rows of the exact CL surfaces the operations name
//! ([`Prepared::surface_rows`]), then, on the surfaces joined from them, ranges of raster passes
//! ([`Prepared::raster_passes`]) and bands of the level maps z-level work contours
//! ([`Prepared::level_rows`]). The worker that plans keeps what the others made
//! ([`Prepared::keep_surface`], [`Prepared::keep_passes`], [`Prepared::keep_level_map`]) and plans as it would have alone:
//! the program is the same byte for byte. Natively the same bands and passes run on threads
//! ([`crate::zmap::cl_exact::ExactBuilder::field`], [`crate::machining::raster::raster_runs`]).

use std::ops::Range;

use super::run::{Prepared, Running};
use crate::drawing::Shape;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::machining::context::GivenRegion;
use crate::machining::context::SurfaceRequest;
use crate::machining::levels::{unpack, RegionWork};
use crate::machining::raster::{PassLayout, RasterPasses};
use crate::operations::FinishRaster;
use crate::operations::Operation;
use crate::progress::Progress;
use crate::zmap::contour::LevelMap;
use crate::zmap::region::Region;
use crate::zmap::ClBuilder;

/// A raster operation whose passes a pool can share out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct RasterWork {
    /// The operation's index in the job.
    pub operation: usize,
    /// Its surface's index in [`Prepared::surfaces`] (none for one the inverse offset makes:
    /// each worker makes that whole, quickly).
    pub surface: Option<usize>,
    /// How many passes it has.
    pub passes: usize,
}

impl Prepared {
    /// The exact CL surfaces the enabled operations will ask for, each once, in the order they
    /// ask.
    pub fn surfaces(&self) -> Result<Vec<SurfaceRequest>> {
        let mut out: Vec<SurfaceRequest> = Vec::new();
        for op in self.job.operations.iter().map(Operation::op).filter(|o| o.enabled()) {
            for r in op.surfaces(&self.ctx)? {
                if r.builder == ClBuilder::Exact && !out.contains(&r) {
                    out.push(r);
                }
            }
        }
        Ok(out)
    }

    /// Which of `surfaces` (the list [`Prepared::surfaces`] gave) the enabled operations want
    /// level maps of (z-level roughing, waterline finishing), as indices.
    pub fn level_maps(&self, surfaces: &[SurfaceRequest]) -> Result<Vec<usize>> {
        let mut out = Vec::new();
        for op in self.job.operations.iter().map(Operation::op).filter(|o| o.enabled()) {
            for r in op.level_maps(&self.ctx)? {
                if let Some(k) = surfaces.iter().position(|s| *s == r) {
                    if !out.contains(&k) {
                        out.push(k);
                    }
                }
            }
        }
        Ok(out)
    }

    /// Rows `rows` of the level map of surface `request` (kept, or made here): the bounds
    /// along the edges to the right, those along the edges up, and the widened cutter's
    /// heights at the rows' nodes (the node bounds).
    pub fn level_rows(&mut self, request: SurfaceRequest, rows: Range<usize>) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
        let cl = self.ctx.cl_surface(request, &mut Progress::none())?;
        let mut wide = self.ctx.widened_rows(request, rows.start..rows.end.saturating_add(1))?;
        let (right, up) = LevelMap::rows(&cl, &wide, &self.ctx.tolerances, rows.clone()).ok_or_else(|| Error::Input("the widened cutter's heights do not cover the band".into()))?;
        wide.truncate(right.len());
        Ok((right, up, wide))
    }

    /// Keeps the level map of surface `request` from its rows' heights (its bands joined),
    /// and its node bounds when `wide` holds them (not empty).
    pub fn keep_level_map(&mut self, request: SurfaceRequest, right: Vec<f64>, up: Vec<f64>, wide: Vec<f64>) -> Result<()> {
        let cl = self.ctx.cl_surface(request, &mut Progress::none())?;
        let map = LevelMap::from_rows(&cl, right, up).ok_or_else(|| Error::Input(format!("a level map of {} × {} nodes was given the wrong number of heights", request.grid.nx, request.grid.ny)))?;
        self.ctx.keep_level_map(request, map);
        if !wide.is_empty() {
            self.keep_node_bounds(request, wide)?;
        }
        Ok(())
    }

    /// Keeps the node bounds of surface `request` ([`crate::machining::Context::node_bounds`])
    /// from its rows' widened heights (its bands joined).
    pub fn keep_node_bounds(&mut self, request: SurfaceRequest, wide: Vec<f64>) -> Result<()> {
        if self.ctx.keep_node_bounds(request, wide) {
            Ok(())
        } else {
            Err(Error::Input(format!("the node bounds of {} × {} nodes were given the wrong number of heights", request.grid.nx, request.grid.ny)))
        }
    }

    /// Rows `rows` of the exact surface `request`, row after row.
    pub fn surface_rows(&mut self, request: SurfaceRequest, rows: Range<usize>, progress: &mut Progress) -> Result<Vec<f64>> {
        if request.builder != ClBuilder::Exact {
            return Err(Error::Input("only exact CL surfaces are made in bands".into()));
        }
        self.ctx.surface_rows(request, rows, progress)
    }

    /// Keeps `z`, the heights of `request` on its whole grid (its bands joined, row after row),
    /// as that surface.
    pub fn keep_surface(&mut self, request: SurfaceRequest, z: Vec<f64>) -> Result<()> {
        let grid = request.grid;
        if z.len() != grid.nx * grid.ny {
            return Err(Error::Input(format!("a CL surface of {} × {} nodes was given {} heights", grid.nx, grid.ny, z.len())));
        }
        let mut field = grid.filled(request.floor);
        field.z = z;
        self.ctx.keep_surface(request, field);
        Ok(())
    }

    /// The enabled raster operations, with their surfaces (indices in `surfaces`, the list
    /// [`Prepared::surfaces`] gave) and how many passes each has.
    pub fn rasters(&mut self, surfaces: &[SurfaceRequest]) -> Result<Vec<RasterWork>> {
        let mut out = Vec::new();
        for k in 0..self.job.operations.len() {
            if matches!(&self.job.operations[k], Operation::FinishRaster(r) if r.enabled) {
                let (r, region, passes) = self.raster_layout(k)?;
                let request = r.request(&self.ctx)?;
                out.push(RasterWork { operation: k, surface: surfaces.iter().position(|s| *s == request), passes: PassLayout::new(&region, &passes).count });
            }
        }
        Ok(out)
    }

    /// The enabled raster operation `operation`, where its passes run and how.
    fn raster_layout(&mut self, operation: usize) -> Result<(FinishRaster, Region, RasterPasses)> {
        let Some(Operation::FinishRaster(r)) = self.job.operations.get(operation).filter(|o| o.op().enabled()).cloned() else {
            return Err(Error::Input(format!("operation {operation} is not a raster finishing")));
        };
        let (region, passes) = r.layout(&mut self.ctx)?;
        Ok((r, region, passes))
    }

    /// The runs of passes `passes` of the raster operation `operation`, each pass's in its own
    /// direction, on its surface (kept, or made here).
    pub fn raster_passes(&mut self, operation: usize, passes: Range<usize>) -> Result<Vec<Vec<Vec<DVec3>>>> {
        let (r, region, settings) = self.raster_layout(operation)?;
        let cl = self.ctx.cl_surface(r.request(&self.ctx)?, &mut Progress::none())?;
        let layout = PassLayout::new(&region, &settings);
        let passes = passes.start.min(layout.count)..passes.end.min(layout.count);
        Ok(crate::parallel::map_heavy(passes.len(), |i| layout.pass(&cl, passes.start + i)))
    }

    /// Keeps passes of the raster operation `operation` made elsewhere, `first` the index of
    /// the first; once every pass is kept, the operation plans with them.
    pub fn keep_passes(&mut self, operation: usize, first: usize, passes: Vec<Vec<Vec<DVec3>>>) -> Result<()> {
        // The operation's pass count is looked up with its first passes.
        if !self.given.contains_key(&operation) {
            let (_, region, settings) = self.raster_layout(operation)?;
            self.given.insert(operation, vec![None; PassLayout::new(&region, &settings).count]);
        }
        let slots = self.given.get_mut(&operation).expect("inserted above");
        if first + passes.len() > slots.len() {
            return Err(Error::Input(format!("passes {first}..{} given of an operation with {}", first + passes.len(), slots.len())));
        }
        for (k, p) in passes.into_iter().enumerate() {
            slots[first + k] = Some(p);
        }
        Ok(())
    }

    /// Hands the context the raster operations whose every pass was given.
    pub(super) fn give_passes(&mut self) {
        for (op, slots) in self.given.drain() {
            if let Some(passes) = slots.into_iter().collect::<Option<Vec<_>>>() {
                self.ctx.given_passes.insert(op, passes);
            }
        }
    }
}

impl Prepared {
    /// The regions of `levels` (each the height it is contoured at and the nodes it keeps,
    /// packed: [`RegionWork::levels`]) on the surface `request` and its level map (kept, or
    /// made here), for the planner of a pool ([`Running::keep_regions`]).
    pub fn level_regions(&mut self, request: SurfaceRequest, levels: &[(f64, Vec<u8>)]) -> Result<Vec<Shape>> {
        level_regions(&mut self.ctx, request, levels)
    }
}

/// [`Prepared::level_regions`] in `ctx`.
fn level_regions(ctx: &mut crate::machining::Context, request: SurfaceRequest, levels: &[(f64, Vec<u8>)]) -> Result<Vec<Shape>> {
    let cl = ctx.cl_surface(request, &mut Progress::none())?;
    let map = ctx.level_map(request, &cl);
    let (grid, tol) = (cl.field.grid(), ctx.tolerances);
    Ok(crate::parallel::map_heavy(levels.len(), |k| {
        let keep = unpack(&levels[k].1, grid.nodes());
        map.region(&cl, levels[k].0, &|i, j| keep[j * grid.nx + i], &tol)
    }))
}

impl Running {
    /// The regions of the next operation's levels, as work for a pool, when it has levels
    /// ([`crate::machining::Operate::region_work`]); `None` once every operation is planned.
    pub fn region_work(&mut self, progress: &mut Progress) -> Result<Option<RegionWork>> {
        let Some(&k) = self.enabled.get(self.next) else { return Ok(None) };
        self.ctx.operation = k;
        let live = self.as_came_for(k);
        let work = self.job.operations[k].op().region_work(&mut self.ctx, progress);
        self.back_to(live);
        work
    }

    /// [`Prepared::level_regions`], by the planner of a pool as it plans.
    pub fn level_regions(&mut self, request: SurfaceRequest, levels: &[(f64, Vec<u8>)]) -> Result<Vec<Shape>> {
        level_regions(&mut self.ctx, request, levels)
    }

    /// Keeps `regions`, made by a pool for `work` (level by level), for the next operation to
    /// take as it plans.
    pub fn keep_regions(&mut self, work: &RegionWork, regions: Vec<Shape>) -> Result<()> {
        if regions.len() != work.levels.len() {
            return Err(Error::Input(format!("{} regions were given for {} levels", regions.len(), work.levels.len())));
        }
        for ((level, keep), region) in work.levels.iter().cloned().zip(regions) {
            self.ctx.given_regions.push(GivenRegion { request: work.request, level, keep, region });
        }
        Ok(())
    }
}
