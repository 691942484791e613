//! Level-by-level roughing on the CL z-map (DESIGN.md ideas 1 and 3), the machinery z-level,
//! zigzag and octree roughing share (and waterline finishing's regions): at each level, the region the
//! cutter's centre may occupy there ([`crate::zmap::contour`]) is cleared by rings, repeated
//! seed 003 offsets inwards at the step-over, inner rings first (each region entered by the
//! shared helix, else a ramp), and the region's own boundary last, so the wall left is the
//! allowance and not a ring's scallop.
//!
//! * **Allowances.** The radial one (`leaveStock`, on walls) grows the cutter by it before its
//!   CL z-map is made, so walls keep it at every height; the axial one (`allowance`, on floors)
//!   raises the surface: at level z the centre goes where `CL + allowance <= z`.
//! * **Levels** run from the stock's top down by the step-down to the stock's bottom (plus the
//!   allowance), and every flat area of the part is a level of its own (at its height plus the
//!   allowance), so no shallow feature is skipped for lying between two levels. A flat's level
//!   is cut only where the level below it cannot go (the flat and the slopes between the two
//!   heights): everywhere else the level below takes the material down further, in a slab no
//!   deeper than the step-down from the step-down level above, so cutting it there too would
//!   be a second, thin pass over the same area.
//! * **Never in air.** At each level only where the in-process stock still has material within
//!   the cutter's reach: after another roughing, this is rest machining.
//! * **Order.** Each level's region falls apart into connected regions, each under the region
//!   of the level above that holds it; by default a region is cut and then the regions under it,
//!   down to their floors (nearest first), before the next region of its level ([`Order`]), so
//!   the tool goes from pocket to pocket once, not once per level. Each region's material starts
//!   at the level above, which its parent cut; retracts and entries know what has been cut, in
//!   whatever order (the lowest cut region that holds a point or a way).
//! * **Traverses** between pieces cross at the gap over the lowest level whose cut regions
//!   together hold the straight way (the air beside the stock needs none), or over what still
//!   stands on the way by the operation's own cuts so far, whichever is lower (issue 38: on a
//!   terrain the tool crosses a ridge at the ridge, not at the stock's top).

use super::air::Refeed;
use super::context::SurfaceRequest;
use super::path2d::Cursor;
use super::rings::{clear_rings_at_feed, rings, way_out, Clearing, RingSetup};
use super::settings::{Direction, EntryKind, LoadControl, Order, PocketPattern, Roughing, Steps};
use super::{positive, sheet, Context, FieldError};
use crate::cutter::Profile;
use crate::drawing::Shape;
use crate::error::{Error, Result};
use crate::geom::segment::{Rect, Segment};
use crate::geom::tolerance::{FLOAT_SLACK, HAIR, LEAST_STEP};
use crate::geom::{DVec2, DVec3};
use crate::progress::Progress;
use crate::sim::sweep::Sweep;
use crate::sim::{DexelStock, StockModel};
use crate::tool::Tool;
use crate::toolpath::{Move, Toolpath};
use crate::zmap::region::Region;
use crate::zmap::surface::ClSurface;
use crate::zmap::{ClBuilder, Grid, HeightField};
use std::cell::RefCell;
use std::rc::Rc;
use std::sync::{Arc, OnceLock};

/// Which nodes of a level's grid its region may keep, by the level's height (`None`: all), as
/// [`LevelRoughing::levels_within`] asks each level on whichever core is free.
pub type Within<'a> = dyn Fn(f64, Grid) -> Option<Vec<bool>> + Sync + 'a;

/// Nodes of equal height covering at least this many times the cutter's area make a flat (a level): more than the plateau a flat end leaves over a peak (its own disk).
const FLAT_AREA: f64 = 2.0;
/// Heights within this are one flat (mm).
const FLAT_SAME: f64 = 1e-4;
/// Levels closer than this are one (mm).
const LEVEL_SAME: f64 = 0.01;
/// A flat's level reaches this many node spacings past where the level below cannot go.
const FLAT_BAND: f64 = 1.5;

/// The settings of a level-by-level roughing, as each roughing kind gives them: its name (for
/// warnings), tool, step-down, step-over and the shared [`Roughing`] settings, the helix's
/// radius, whether flats get levels of their own, and the order regions are cut in.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelRoughing {
    pub name: String,
    pub tool: u32,
    pub steps: Steps,
    pub roughing: Roughing,
    pub helix_radius: Option<f64>,
    pub flats: bool,
    pub order: Order,
    /// How each level's region is cleared: rings, or adaptive clearing.
    pub pattern: PocketPattern,
    /// The range of adaptive clearing's step length.
    pub adaptive_steps: super::adaptive::StepRange,
}

impl LevelRoughing {
    /// Level-by-level roughing with `roughing`'s settings (helix radius by default, flats and
    /// each level everywhere before the next: [`Order::Levels`]; set the fields to change them).
    pub fn new(name: &str, tool: u32, steps: Steps, roughing: &Roughing) -> LevelRoughing {
        LevelRoughing {
            name: name.to_owned(),
            tool,
            steps,
            roughing: *roughing,
            helix_radius: None,
            flats: true,
            order: Order::Levels,
            pattern: PocketPattern::Offset,
            adaptive_steps: Default::default(),
        }
    }

    /// The levels this stock's height makes at the step-down, within [`super::MAX_LEVELS`], and
    /// the level-map nodes they read, within [`crate::limits::MAX_LEVEL_NODES`] (each level's
    /// region is found over the whole grid: a step-down of 0.01 mm inside the levels' limit ran
    /// for minutes). The rings the levels' regions ask are weighed once the regions are known
    /// ([`LevelRoughing::check_rings`]).
    pub fn check_scale(&self, ctx: &Context) -> Result<()> {
        super::check_levels(&self.name, ctx.stock, self.steps.stepdown, self.roughing.grid)
    }

    /// Refuses, before any ring is made, regions that would take more than
    /// [`crate::limits::MAX_RINGS`] rings `step` apart in all (each region's rings from its
    /// middle out: its inradius, about twice its area over its perimeter, over the step), or
    /// more than [`crate::limits::MAX_CUT_LENGTH`] mm of cut (their area over the step): a
    /// step-over of 1% of the tool, or a step-down of 0.05 mm, on the sample ran for minutes.
    /// The regions are those the levels really cut, so rest roughing after a larger tool, and
    /// octree roughing's octants, are weighed by what they leave, not by the whole stock.
    pub fn check_rings(&self, tool: &Tool, regions: &[Arc<Shape>], step: f64) -> Result<()> {
        let (mut rings, mut length) = (0.0, 0.0);
        for region in regions {
            let (area, perimeter) = (region.area().abs(), region.length());
            if perimeter > 0.0 {
                let b = region.bounds();
                let across = (2.0 * area / perimeter).min(0.5 * (b.max - b.min).min_element());
                rings += across / step + 1.0;
                length += area / step + perimeter;
            }
        }
        let shown_step = crate::limits::shown((step * 1e6).round() / 1e6);
        let most = crate::limits::MAX_RINGS;
        if rings > most {
            return Err(Error::operation(
                &self.name,
                format!(
                    "the φ{} tool's step-over of {shown_step} mm makes about {rings:.0} rings over the {} regions of its levels (at most {most:.0}): choose a larger step-over or step-down, or check the part's units",
                    tool.cutter.diameter,
                    regions.len(),
                ),
            ));
        }
        if length > crate::limits::MAX_CUT_LENGTH {
            return Err(Error::operation(
                &self.name,
                format!(
                    "the φ{} tool's step-over of {shown_step} mm over the {} regions of its levels (a step-down of {} mm) cuts about {} km ({} hours at {} mm/min; at most {} km planned at once): choose a larger step-over or step-down, or check the part's units",
                    tool.cutter.diameter,
                    regions.len(),
                    crate::limits::shown(self.steps.stepdown),
                    crate::limits::shown((length / 1e5).round() / 10.0),
                    crate::limits::shown((length / tool.feed_rate.max(1.0) / 60.0).round()),
                    crate::limits::shown(tool.feed_rate),
                    crate::limits::shown(crate::limits::MAX_CUT_LENGTH / 1e6)
                ),
            ));
        }
        Ok(())
    }

    /// Checks the settings of a roughing that names its step-down and step-over (z-level and
    /// zigzag roughing), each named as the job file names it.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.steps.validate()?;
        self.roughing.validate()?;
        if let Some(r) = self.helix_radius {
            positive("helixRadius", r)?;
        }
        self.adaptive_steps.validate()
    }
}

/// The [`super::Operate`] methods of an operation that cuts the levels its `levels()` gives
/// ([`LevelRoughing`]): the CL surface and level map it asks for, the regions of its levels as
/// work a pool can share out, and the number of its levels checked before any work.
macro_rules! level_work {
    () => {
        fn surfaces(&self, ctx: &$crate::machining::Context) -> $crate::error::Result<Vec<$crate::machining::context::SurfaceRequest>> {
            Ok(vec![self.levels().request(ctx)?])
        }

        fn level_maps(&self, ctx: &$crate::machining::Context) -> $crate::error::Result<Vec<$crate::machining::context::SurfaceRequest>> {
            self.surfaces(ctx)
        }

        fn region_work(&self, ctx: &mut $crate::machining::Context, progress: &mut $crate::progress::Progress) -> $crate::error::Result<Option<$crate::machining::levels::RegionWork>> {
            self.levels().region_work(ctx, progress).map(Some)
        }

        fn check_scale(&self, ctx: &$crate::machining::Context) -> $crate::error::Result<()> {
            self.levels().check_scale(ctx)
        }
    };
}
pub(crate) use level_work;

/// What a level-by-level roughing cuts: its tool, the CL surface of the tool grown by the
/// radial allowance, and the levels with material left, from the top down.
pub struct Levels {
    pub tool: Tool,
    pub cl: Arc<ClSurface>,
    pub levels: Vec<Level>,
}

/// One level to cut: its height, the height down to which material was cut before over its
/// whole region (the step-down level above it, or the stock's top), and the region the tool's
/// centre may occupy there, within reach of material (at a flat's level, only where the level
/// below cannot go).
pub struct Level {
    pub z: f64,
    pub z_prev: f64,
    pub region: Shape,
}

impl LevelRoughing {
    /// The step-over (mm) for a tool of radius `r`.
    pub fn step(&self, r: f64) -> f64 {
        (self.steps.stepover_fraction * 2.0 * r).max(LEAST_STEP)
    }

    /// Clears `levels` (from [`LevelRoughing::levels_to_cut`] or [`LevelRoughing::levels_within`])
    /// in the roughing's [`Order`]: rings inside-out from the helix or ramp (or in from the air
    /// beside the region), the region's boundary last; one tool path.
    pub fn clear(&self, ctx: &mut Context, levels: Levels, progress: &mut Progress) -> Result<Toolpath> {
        let Levels { tool, cl, levels } = levels;
        let r = tool.cutter.radius();
        let tol = ctx.tolerances;
        let step = self.step(r);
        let clearing = Clearing {
            step,
            climb: self.roughing.direction == Direction::Climb,
            pattern: self.pattern,
            angle: 0.0,
            load: LoadControl::None,
            load_tolerance: 0.0,
            entry: EntryKind::Helix,
            ramp_angle: self.roughing.ramp_angle.clamp(0.1, 89.0).to_radians(),
            helix_r: self.helix_radius.unwrap_or(0.4 * 2.0 * r).min(0.95 * r),
            depth: (self.pattern == PocketPattern::Adaptive).then_some(self.steps.stepdown),
            adaptive_steps: self.adaptive_steps,
        };
        clearing.check_helix(&self.name, self.steps.stepdown)?;
        let clearance = ctx.heights.clearance;
        // (Where adaptive clearing stopped at a budget with material left: warned once the
        // pieces are cut, with the context no longer shared.)
        let ((cancelled, fed), unfinished) = {
            let ctx = &*ctx;
            let mut run = Run {
                unfinished: Vec::new(),
                clearing,
                cursor: sheet::cursor(ctx, &tool),
                // The in-process stock as this roughing's pieces so far left it, brought up to date
                // where a traverse asks: it crosses just over what still stands on its way.
                standing: Rc::new(RefCell::new(Standing::new(ctx.sim.stock(), tool.cutter.profile()))),
                // What was cut so far: each piece's height and region. Beyond the stock's sides by
                // more than the cutter's radius, no height holds material. (A ring's start lies on
                // its region's boundary: a point a chordal tolerance from a region counts as in it.)
                cleared: Cleared { slack: tol.chordal, air: Rect { min: ctx.stock.min.truncate(), max: ctx.stock.max.truncate() }.expand(r + tol.chordal), cut: Vec::new() },
            };
            let mut pieces = Pieces::new(levels, self.order, tol.chordal, r);
            let count = pieces.list.len();
            // The region is the set of centres: its rings start on it. Each piece's rings are made
            // ahead of the clearing on a second thread, and each piece's stretches of air judged
            // behind it (the rings depend only on the region, the air only on the stock the
            // operation starts from): the same program, sooner.
            // Piece k's rings are made from region k: every piece is still in the list.
            let regions: Vec<Arc<Shape>> = pieces.list.iter().map(|p| p.as_ref().expect("no piece is cut yet").region.clone()).collect();
            self.check_rings(&tool, &regions, step)?;
            // (Adaptive clearing needs only the region's own boundary.)
            let make = |k: usize| if self.pattern == PocketPattern::Adaptive { vec![(*regions[k]).clone()] } else { rings(&regions[k], 0.0, step, r, &tol) };
            let cut = crate::parallel::ahead(count, make, |rings_of| {
                crate::parallel::behind(Refeed::run, |send| {
                    for n in 0..count {
                        if !progress.report(n as f64 / count as f64) {
                            return true;
                        }
                        let Some((k, Piece { z, z_prev, region })) = pieces.next(run.cursor.at.truncate()) else { break };
                        send(self.clear_piece(ctx, &tool, &cl, &mut run, (z, z_prev), &rings_of(k)));
                        run.cleared.add(z, region);
                    }
                    false
                })
            });
            (cut, run.unfinished)
        };
        if cancelled {
            return Err(Error::Cancelled);
        }
        if !unfinished.is_empty() {
            ctx.warn(&self.name, super::adaptive::unfinished(&unfinished));
        }
        Ok(sheet::toolpath(&self.name, &tool, fed.into_iter().flatten().collect(), clearance))
    }

    /// One piece of [`LevelRoughing::clear`], cleared by `rings` from `z_prev` down to `z`
    /// with the cursor, the stock and the regions cleared as the pieces before left them.
    fn clear_piece<'m>(&self, ctx: &'m Context, tool: &Tool, cl: &Arc<ClSurface>, run: &mut Run<'m>, (z, z_prev): (f64, f64), rings: &[Shape]) -> Refeed<'m> {
        let (r, tol) = (tool.cutter.radius(), ctx.tolerances);
        // Material above this level was cleared by the level before within this region
        // (which lies inside what that level cut): rapids stop the gap above it.
        run.cursor.safe = (z_prev + ctx.heights.gap).min(ctx.heights.clearance);
        // Rapids come down to the gap above the level before (the step-down level above:
        // a flat's level between cut only its band) only over what it cleared, and lower
        // where a flat's band was cut since: elsewhere (rest roughing beside what an earlier
        // tool left) above the stock.
        let done = Arc::new(run.cleared.clone());
        let levelled = done.cut.iter().any(|e| e.z == z_prev);
        let before = done.clone();
        run.cursor.safe_at = Some(Box::new(move |p: DVec2| before.lowest_holding(p).map_or(!levelled, |level| level == z_prev)));
        // Past it (the cursor asks only where `safe_at` does not hold): the lowest level cut
        // so far whose region holds the point.
        let earlier = done.clone();
        run.cursor.cleared_to = Some(Box::new(move |p: DVec2| earlier.lowest_holding(p)));
        // The short retract: a traverse just above the lowest level cut so far whose
        // region holds the straight move (what that level cleared), over the part there;
        // above the stock's top before the first level.
        let (surface, allowance, gap, tol_z) = (cl.clone(), self.roughing.allowance, ctx.heights.gap, tol.height + 2.0 * tol.interpolation);
        let across = done;
        let stands = run.standing.clone();
        run.cursor.traverse = Some(Box::new(move |a: DVec2, b: DVec2| {
            let over = |level: f64| surface.stays_below(a, b, level - allowance - tol_z);
            if across.cut.is_empty() {
                return over(z_prev).then_some(z_prev + gap);
            }
            // Over what this roughing cut (no lower than the level above: the cursor keeps
            // its rapids there), else just over what stands on the way.
            let by_regions = across.lowest_covering(a, b, &over);
            if by_regions.is_some_and(|level| level <= z_prev) {
                return by_regions.map(|level| level + gap);
            }
            let by_stock = stands.borrow_mut().along(a, b);
            // Over the part too: by the nodes' bound (or the exact surface, where the nodes
            // are not the exact drop), the exact surface only where the bound stands much
            // higher (beside a wall the bound counts, half a node off the cutter's reach).
            let bound = surface.bound_along(a, b).map(|top| top + allowance + tol_z);
            let by_stock = match bound {
                Some(b) if b <= by_stock + gap => Some(b.max(by_stock)),
                _ if over(by_stock) => Some(by_stock),
                _ => bound,
            };
            let by_stock = by_stock.filter(|&level| by_regions.is_none_or(|r| level < r));
            by_regions.into_iter().chain(by_stock).reduce(f64::min).map(|level| level + gap)
        }));
        let from = run.cursor.at;
        let mut setup = RingSetup { tool_radius: r, top: z_prev, feed: tool.feed_rate, cursor: &mut run.cursor, tol: &tol, unfinished: false };
        let air = self.air(ctx, cl, r, z);
        let cut = clear_rings_at_feed(rings, &run.clearing, z_prev, z, &mut setup, Some(&air));
        if setup.unfinished {
            run.unfinished.push(z);
        }
        // (The stock as it stands: the same whatever the feeds.)
        run.standing.borrow_mut().cut(from, &cut.moves, tol.chordal);
        cut
    }

    /// The levels this roughing cuts (the z-level strategy's and every strategy that clears
    /// the same levels another way): the CL z-map, the levels by step-down and flats, and at
    /// each the region with material left within reach. `None`, with a warning, where no
    /// level has material left.
    pub fn levels_to_cut(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Option<Levels>> {
        // Centres whose cutter reaches at least half a step into material (the outermost ring
        // then cuts that much of the stock's edge, the next a full step).
        let r = ctx.tool(&self.name, self.tool)?.cutter.radius();
        let levels = self.levels_within(ctx, progress, self.reach(r), true, &|_, _| None)?;
        if levels.is_none() {
            ctx.note(&self.name, "no level has material left to cut");
        }
        Ok(levels)
    }

    /// How far from material above a level a centre of a tool of radius `r` is kept: its
    /// cutter reaches at least half a step into it.
    fn reach(&self, r: f64) -> f64 {
        (r - 0.5 * self.step(r)).max(0.0)
    }

    /// How far from material a centre is kept beside the stock (outside its box): adaptive
    /// clearing's passes start there in the air, clear of the material
    /// ([`super::rings::adaptive_reach`]), instead of helixing down into a region along the
    /// stock's edge; the other patterns', as inside.
    fn air_reach(&self, r: f64) -> f64 {
        if self.pattern == PocketPattern::Adaptive {
            super::rings::adaptive_reach(r, self.adaptive_steps.fractions(r).0)
        } else {
            self.reach(r)
        }
    }

    /// The tool and its CL surface: the cutter grown by the radial allowance (the Minkowski sum
    /// with a disk: a ball's becomes a bull nose of its own corner), over the stock and the
    /// cutter's reach beyond it, down to the stock's bottom. Made once per job for the same
    /// tool, allowance and grid (the context's cache).
    pub fn surface(&self, ctx: &mut Context, progress: &mut Progress) -> Result<(Tool, Arc<ClSurface>)> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cl = ctx.cl_surface(self.request(ctx)?, progress)?;
        Ok((tool, cl))
    }

    /// The CL surface of [`LevelRoughing::surface`].
    pub fn request(&self, ctx: &Context) -> Result<SurfaceRequest> {
        let profile = ctx.tool(&self.name, self.tool)?.cutter.profile();
        let r = profile.radius;
        let grown = Profile::new(r + self.roughing.leave_stock, if profile.flat_radius() <= 0.0 { r } else { profile.corner });
        let stock = ctx.stock;
        // (Adaptive clearing's regions reach farther beside the stock: the grid as far.)
        let reach = self.air_reach(r).max(r) + self.roughing.leave_stock + 2.0 * self.roughing.grid;
        let grid = Grid::checked(stock.min.truncate() - DVec2::splat(reach), stock.max.truncate() + DVec2::splat(reach), self.roughing.grid).map_err(|e| Error::operation(&self.name, e))?;
        Ok(SurfaceRequest { profile: grown, grid, floor: stock.min.z, builder: ClBuilder::Exact })
    }

    /// The heights of the levels on `cl` for a tool of radius `r`, from the top down (see
    /// [`LevelRoughing`]).
    pub fn heights(&self, ctx: &Context, cl: &ClSurface, r: f64) -> Vec<f64> {
        self.levels_and_kinds(ctx, cl, r).into_iter().map(|(z, _)| z).collect()
    }

    /// [`LevelRoughing::heights`], each with whether it is a flat's level alone.
    fn levels_and_kinds(&self, ctx: &Context, cl: &ClSurface, r: f64) -> Vec<(f64, bool)> {
        // Floors are cut a hair above their height plus the allowance: the region at a level
        // counts a surface as clear when the exact profile stands below it by the interpolation
        // margin (`zmap/contour.rs`).
        let clear = 2.0 * ctx.tolerances.interpolation + ctx.tolerances.height;
        let heights = &self.roughing.heights;
        let (lowest, top) = (heights.bottom_z(&ctx.stock, &ctx.part), heights.top_z(&ctx.stock, &ctx.part));
        self.levels(&cl.field, top.map_or(ctx.stock.max.z, |t| t.min(ctx.stock.max.z)), ctx.stock.min.z, lowest, r, clear)
    }

    /// [`LevelRoughing::levels_to_cut`] with centres kept within `reach` of material above each
    /// level, each level's region limited further to the nodes of the CL z-map's grid that
    /// `within(z, grid)` accepts, where it gives a mask (seed 000's octants a tool cuts);
    /// `None`, without a warning, where no level has material left.
    ///
    /// With `bands`, a flat's level is cut only where the level below cannot go (see
    /// [`LevelRoughing`]); without (seed 000's layers, each its own octants), over its whole region.
    pub fn levels_within(&self, ctx: &mut Context, progress: &mut Progress, reach: f64, bands: bool, within: &Within) -> Result<Option<Levels>> {
        self.roughing.heights.window(&self.name, &ctx.stock, &ctx.part)?;
        if !progress.stage("CL z-map", 0.0, 0.3) {
            return Err(Error::Cancelled);
        }
        let (tool, cl) = self.surface(ctx, progress)?;
        let stock = ctx.stock;
        if !progress.stage("levels", 0.3, 0.2) {
            return Err(Error::Cancelled);
        }
        let tol = ctx.tolerances;
        let request = self.request(ctx)?;
        let map = ctx.level_map(request, &cl);
        let mut levels = Vec::new();
        let mut z_prev = stock.max.z;
        let inputs = self.level_inputs(ctx, &tool, &cl, reach, bands, within);
        // Each level's region on whichever core is free (they do not depend on each other),
        // unless a pool made it already.
        let given = &ctx.given_regions;
        let keeps = inputs.keeps();
        let regions = crate::parallel::map_uneven(inputs.heights.len(), |k| {
            let (packed, level) = (&keeps[k], inputs.level(k));
            let made = given.iter().find(|g| g.request == request && g.level == level && &g.keep == packed);
            made.map_or_else(
                || {
                    let keep = unpack(packed, inputs.grid.nodes());
                    map.region(&cl, level, &|i, j| keep[j * inputs.grid.nx + i], &tol)
                },
                |g| g.region.clone(),
            )
        });
        for ((z, flat), region) in inputs.heights.into_iter().zip(regions) {
            if region.is_empty() {
                continue;
            }
            levels.push(Level { z, z_prev, region });
            // Over a flat's band only: the levels after it start from the step-down level above.
            if !(flat && bands) {
                z_prev = z;
            }
        }
        if !progress.stage("rings", 0.5, 0.5) {
            return Err(Error::Cancelled);
        }
        if levels.is_empty() {
            return Ok(None);
        }
        Ok(Some(Levels { tool, cl, levels }))
    }

    /// What each level's region is made of (see [`LevelRoughing::levels_within`]): the levels,
    /// and per level the nodes its region keeps, on the stock as it is now.
    fn level_inputs<'a>(&'a self, ctx: &'a Context, tool: &Tool, cl: &'a ClSurface, reach: f64, bands: bool, within: &Within) -> LevelInputs<'a> {
        let r = tool.cutter.radius();
        let grid = cl.field.grid();
        let heights = self.levels_and_kinds(ctx, cl, r);
        // Each level's mask on whichever core is free (a rest stage's takes distance maps).
        let limits = crate::parallel::map_heavy(heights.len(), |k| within(heights[k].0, grid));
        let tops = (0..grid.nodes()).map(|_| OnceLock::new()).collect();
        let beside = Rect { min: ctx.stock.min.truncate(), max: ctx.stock.max.truncate() };
        let air_reach = (self.air_reach(r) > reach).then_some((self.air_reach(r), beside));
        LevelInputs { zl: self, cl, stock: ctx.sim.stock(), grid, r, reach, air_reach, bands, heights, limits, tops, nearest: OnceLock::new() }
    }

    /// The regions [`LevelRoughing::levels_to_cut`] would make, as work a pool can share out
    /// before the operation plans: its CL surface, and per level the height its region is
    /// contoured at and the nodes it keeps (packed eight to a byte).
    pub fn region_work(&self, ctx: &mut Context, progress: &mut Progress) -> Result<RegionWork> {
        let (tool, cl) = self.surface(ctx, progress)?;
        let request = self.request(ctx)?;
        let r = tool.cutter.radius();
        let inputs = self.level_inputs(ctx, &tool, &cl, self.reach(r), true, &|_, _| None);
        let levels = inputs.keeps().into_iter().enumerate().map(|(k, keep)| (inputs.level(k), keep)).collect();
        Ok(RegionWork { request, levels })
    }

    /// In the air beside a region at level `z`: a step out from a boundary point, the way out
    /// ([`way_out`]) asked, where the cutter touches nothing the earlier operations left (beside the
    /// stock, or where another operation cleared it), and the way in from there to the point
    /// stays clear of the part all along (a region cut short by a mask, octree roughing's
    /// octants, can end beside a thin wall of the part that the step out would cross).
    pub fn air<'a>(&'a self, ctx: &'a Context, cl: &'a ClSurface, r: f64, z: f64) -> impl Fn(DVec2, usize) -> Option<DVec2> + 'a {
        let stock_now = ctx.sim.stock();
        let middle = ctx.stock.center().truncate();
        let flat = Profile::new(r, 0.0);
        let (step, height) = (self.step(r), ctx.tolerances.height);
        let floor = z - self.roughing.allowance;
        move |p: DVec2, k: usize| {
            let q = p + way_out(k, p, middle) * step;
            (stock_now.touch(q, &flat, true) <= z + height && cl.height(q) <= floor && cl.stays_below(q, p, floor + height)).then_some(q)
        }
    }
    /// The levels, from the top down: every step-down from `top` to `floor` plus the
    /// allowance (or to the operation's bottom height `lowest`, where that is higher), and the
    /// flats of the surface (plus the allowance) between, each with whether it is a flat's
    /// alone (cut only where the level below cannot go). None where the bottom height is at
    /// or above the top.
    fn levels(&self, cl: &HeightField, top: f64, floor: f64, lowest: Option<f64>, radius: f64, clear: f64) -> Vec<(f64, bool)> {
        let bottom = (floor + self.roughing.allowance + clear).max(lowest.unwrap_or(f64::NEG_INFINITY));
        let mut levels = Vec::new();
        if bottom >= top - LEVEL_SAME {
            return levels;
        }
        let mut z = top - self.steps.stepdown;
        while z > bottom + LEVEL_SAME {
            levels.push((z, false));
            z -= self.steps.stepdown;
        }
        levels.push((bottom, false));
        if self.flats {
            let mut heights: Vec<f64> = cl.z.iter().copied().filter(|&h| h > floor + FLAT_SAME && h < top).collect();
            crate::geom::sort::sort_floats(&mut heights);
            let cell = cl.spacing * cl.spacing;
            let least = FLAT_AREA * std::f64::consts::PI * radius * radius / cell;
            let mut k = 0;
            while k < heights.len() {
                let mut e = k;
                while e < heights.len() && heights[e] - heights[k] <= FLAT_SAME {
                    e += 1;
                }
                if (e - k) as f64 >= least {
                    let level = heights[e - 1] + self.roughing.allowance + clear;
                    if level < top - LEVEL_SAME && level > bottom {
                        levels.push((level, true));
                    }
                }
                k = e;
            }
        }
        crate::geom::sort::sort_by_float(&mut levels, |a| -a.0);
        // Levels closer than LEVEL_SAME are one, at the higher height; a step-down level among
        // them makes it a whole level.
        levels.dedup_by(|a, b| {
            let same = (a.0 - b.0).abs() < LEVEL_SAME;
            if same {
                b.1 &= a.1;
            }
            same
        });
        levels
    }
}

/// One connected region of a level (or a whole level).
struct Piece {
    z: f64,
    z_prev: f64,
    region: Arc<Shape>,
}

/// How clearing cuts each piece, and what it carries from one piece to the next: where the
/// tool is and how it moves, the stock as the pieces so far left it, and the regions they
/// cleared.
struct Run<'m> {
    /// The heights where adaptive clearing stopped at a budget with material left.
    unfinished: Vec<f64>,
    clearing: Clearing,
    cursor: Cursor<'m>,
    standing: Rc<RefCell<Standing>>,
    cleared: Cleared,
}

/// The pieces a roughing cuts, handed out in its order.
struct Pieces {
    list: Vec<Option<Piece>>,
    children: Vec<Vec<usize>>,
    /// Every piece by level (from the top down).
    levels: Vec<Vec<usize>>,
    /// Per piece, the pieces of higher levels within the tool's reach of it: cut before it,
    /// so that the tool never works a level beside material a level above it left standing
    /// (a piece can lie beside, not under, a region of a higher level: the region of the
    /// level just above that holds it need not be the only one within reach).
    above: Vec<Vec<usize>>,
    /// The pieces cut so far whose children are not all cut, the latest last.
    open: Vec<usize>,
}

impl Pieces {
    /// `levels` as pieces: whole levels for [`Order::Levels`], each level's connected regions
    /// (each under the piece of the level before that holds it) for [`Order::Regions`], for a
    /// tool of radius `reach`.
    fn new(levels: Vec<Level>, order: Order, slack: f64, reach: f64) -> Pieces {
        let mut list: Vec<Option<Piece>> = Vec::new();
        let mut children: Vec<Vec<usize>> = Vec::new();
        let mut by_level: Vec<Vec<usize>> = Vec::new();
        for Level { z, z_prev, region } in levels {
            let parts = match order {
                Order::Levels => vec![region],
                Order::Regions => region.regions(),
            };
            let mut level = Vec::new();
            for part in parts {
                let probe = part.loops[0].probe_point();
                let parent = match order {
                    Order::Levels => None,
                    Order::Regions => list.iter().position(|p| p.as_ref().is_some_and(|p| p.z == z_prev && holds(&p.region, probe, slack))),
                };
                let k = list.len();
                if let Some(p) = parent {
                    children[p].push(k);
                }
                level.push(k);
                list.push(Some(Piece { z, z_prev, region: Arc::new(part) }));
                children.push(Vec::new());
            }
            by_level.push(level);
        }
        let above = match order {
            Order::Levels => vec![Vec::new(); list.len()],
            Order::Regions => within_reach(&list, reach),
        };
        Pieces { list, children, levels: by_level, above, open: Vec::new() }
    }

    /// The next piece to cut with the tool at `at`: the nearest uncut piece under the latest
    /// open one, else the nearest uncut piece of the highest level that has one; either only
    /// once the pieces above within reach of it are cut.
    fn next(&mut self, at: DVec2) -> Option<(usize, Piece)> {
        let nearest = |list: &[Option<Piece>], above: &[Vec<usize>], candidates: &[usize]| {
            candidates
                .iter()
                .filter(|&&k| above[k].iter().all(|&a| list[a].is_none()))
                .filter_map(|&k| list[k].as_ref().map(|p| (k, if p.region.contains(at) { 0.0 } else { p.region.distance_to(at) })))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(k, _)| k)
        };
        let k = loop {
            match self.open.last() {
                Some(&o) => match nearest(&self.list, &self.above, &self.children[o]) {
                    Some(k) => break k,
                    None => {
                        self.open.pop();
                    }
                },
                None => break self.levels.iter().find_map(|level| nearest(&self.list, &self.above, level))?,
            }
        };
        self.open.push(k);
        self.list[k].take().map(|p| (k, p))
    }
}

/// Per piece, the pieces of higher levels that come within `reach` of it, by the cells of a
/// coarse grid each region meets (sampled along three rows a cell; the lower piece's grown by
/// the reach and a cell).
fn within_reach(list: &[Option<Piece>], reach: f64) -> Vec<Vec<usize>> {
    let bounds = list.iter().flatten().fold(Rect::EMPTY, |b, p| b.union(p.region.bounds()));
    if bounds.is_empty() {
        return vec![Vec::new(); list.len()];
    }
    let cell = (0.25 * reach).max(0.25);
    let origin = bounds.min;
    let grow = (reach / cell).ceil() as isize + 1;
    // The cells a region meets, grown by `by` cells: its first row, and per row from there the
    // ranges of columns.
    let cells = |region: &Shape, by: isize| {
        let b = region.bounds();
        let (j0, j1) = (((b.min.y - origin.y) / cell).floor() as isize, ((b.max.y - origin.y) / cell).floor() as isize);
        let mut rows: Vec<Vec<(isize, isize)>> = vec![Vec::new(); (j1 - j0 + 1 + 2 * by) as usize];
        // Three heights a row: its bottom, middle and top.
        let heights: Vec<f64> = (j0..=j1).flat_map(|j| [0.0, 0.5, 1.0].map(|t| origin.y + (j as f64 + t) * cell)).collect();
        for (k, spans) in region.spans_on_rows(&heights).into_iter().enumerate() {
            let j = j0 + (k / 3) as isize;
            for (x0, x1) in spans {
                let (i0, i1) = (((x0 - origin.x) / cell).floor() as isize - by, ((x1 - origin.x) / cell).floor() as isize + by);
                for row in &mut rows[(j - j0) as usize..=(j - j0 + 2 * by) as usize] {
                    row.push((i0, i1));
                }
            }
        }
        (j0 - by, rows)
    };
    // Whether two such sets share a cell: along the rows both have.
    let meets = |(ja, a): &(isize, Vec<Vec<(isize, isize)>>), (jb, b): &(isize, Vec<Vec<(isize, isize)>>)| {
        let skip = |from: isize| (ja.max(jb) - from) as usize;
        a.iter().skip(skip(*ja)).zip(b.iter().skip(skip(*jb))).any(|(ra, rb)| ra.iter().any(|&(a0, a1)| rb.iter().any(|&(b0, b1)| a0 <= b1 && b0 <= a1)))
    };
    // Each piece on whichever core is free (a later piece has more pieces before it to try).
    let own = crate::parallel::map_uneven(list.len(), |k| list[k].as_ref().map(|p| cells(&p.region, 0)));
    crate::parallel::map_uneven(list.len(), |k| {
        let Some(p) = &list[k] else { return Vec::new() };
        let near = p.region.bounds().expand(reach + 2.0 * cell);
        let mut grown = None;
        let mut above = Vec::new();
        for (j, q) in list.iter().enumerate().take(k) {
            let (Some(q), Some(theirs)) = (q, &own[j]) else { continue };
            if q.z > p.z && q.region.bounds().overlaps(&near) && meets(grown.get_or_insert_with(|| cells(&p.region, 1 + grow)), theirs) {
                above.push(j);
            }
        }
        above
    })
}

/// Whether `region` holds `p`, counting points `slack` from it.
fn holds(region: &Shape, p: DVec2, slack: f64) -> bool {
    region.contains(p) || region.distance_to(p) <= slack
}

/// The in-process stock as an operation's cuts so far left it, for its traverses: the cuts'
/// sweeps are kept and taken off the stock only where a traverse asks what stands on its way
/// (a stock of one height a cell is cut the same in any order), on cells of about an eighth
/// of the cutter's radius. Each coarse cell stands as high as the highest of the simulation's
/// cells it holds, and is cut by a cutter narrower by the reach of its corners from its centre
/// (and its answers raised as much): it never stands lower than the simulation's cells would.
struct Standing {
    stock: DexelStock,
    /// The cutter the coarse cells are cut by, and how much higher it stands than it cuts.
    narrower: Profile,
    raise: f64,
    profile: Profile,
    waiting: Vec<Sweep>,
}

impl Standing {
    fn new(stock: &DexelStock, profile: Profile) -> Standing {
        let fine = stock.grid().spacing;
        let factor = ((profile.radius / 8.0 / fine).floor() as usize).max(1);
        // The simulation's cells' centres in a coarse cell lie this near its own (at most an
        // eighth of the radius: the narrower cutter stays a cutter).
        let raise = (factor - 1) as f64 * fine * std::f64::consts::FRAC_1_SQRT_2;
        let radius = profile.radius - raise;
        let narrower = Profile::new(radius, profile.corner.min(radius));
        Standing { stock: stock.coarsened(factor), narrower, raise, profile, waiting: Vec::new() }
    }

    /// Keeps the sweeps of `moves`, made from `from`.
    fn cut(&mut self, mut from: DVec3, moves: &[Move], chordal: f64) {
        for m in moves {
            if !m.is_rapid() {
                self.waiting.extend(Sweep::of_move(self.narrower, from, m, chordal));
            }
            from = m.to();
        }
    }

    /// The highest tip height at which the cutter touches what stands anywhere along the
    /// straight way from `a` to `b`, each cell as a column over its whole square (`-inf` where
    /// nothing stands).
    fn along(&mut self, a: DVec2, b: DVec2) -> f64 {
        let reach = self.profile.radius + 2.0 * self.stock.grid().spacing;
        let stock = &mut self.stock;
        // The cuts whose footprints come within the cutter's reach of the way.
        self.waiting.retain(|s| {
            let meets = Rect { min: s.min, max: s.max }.expand(reach).clip_fractions(a, b).is_some();
            if meets {
                stock.apply(s);
            }
            !meets
        });
        self.stock.touch_along(a, b, &self.profile, true) + self.raise
    }
}

/// The pieces cut so far, from the lowest up.
#[derive(Clone)]
struct Cleared {
    slack: f64,
    /// Centres outside it meet no stock at any height.
    air: Rect,
    cut: Vec<ClearedPiece>,
}

#[derive(Clone)]
struct ClearedPiece {
    z: f64,
    region: Arc<Shape>,
    bounds: Rect,
}

impl Cleared {
    fn add(&mut self, z: f64, region: Arc<Shape>) {
        let bounds = region.bounds().expand(self.slack);
        let at = self.cut.partition_point(|e| e.z <= z);
        self.cut.insert(at, ClearedPiece { z, region, bounds });
    }

    /// The lowest level cut so far whose region holds `p`.
    fn lowest_holding(&self, p: DVec2) -> Option<f64> {
        let inside = |r: &Rect| p.cmpge(r.min).all() && p.cmple(r.max).all();
        self.cut.iter().find(|e| inside(&e.bounds) && holds(&e.region, p, self.slack)).map(|e| e.z)
    }

    /// The lowest height from which the straight move from `a` to `b` lies over what was cut:
    /// the lowest level such that the regions cut at it and below it together hold the whole
    /// move (a traverse over a ridge between two pockets goes at the ridge's level, not the
    /// stock's top), where `over` the part stands below it. Where the move passes outside the
    /// stock's sides (by the cutter's radius) it needs no region.
    fn lowest_covering(&self, a: DVec2, b: DVec2, over: &dyn Fn(f64) -> bool) -> Option<f64> {
        let (lo, hi) = (a.min(b), a.max(b));
        let meets = |r: &Rect| lo.cmple(r.max).all() && hi.cmpge(r.min).all();
        let length = a.distance(b);
        if length <= self.slack {
            return self.lowest_holding(a).into_iter().chain(self.lowest_holding(b)).reduce(f64::max).filter(|&z| over(z));
        }
        // Each end under a piece or in the air beside the stock, first (a quick answer where not).
        let aired = |p: DVec2| !(p.cmpge(self.air.min).all() && p.cmple(self.air.max).all());
        let held = |p: DVec2| if aired(p) { Some(f64::NEG_INFINITY) } else { self.lowest_holding(p) };
        let lowest = held(a)?.max(held(b)?);
        // The parts of the move (as fractions of it) in the air beside the stock and under the
        // pieces cut so far, level by level from the lowest up, until they join from end to end.
        let link = Segment::line(a, b);
        let mut under: Vec<(f64, f64)> = outside(&self.air, a, b);
        let gap = self.slack / length;
        for (k, e) in self.cut.iter().enumerate() {
            if meets(&e.bounds) {
                under.extend(spans_inside(&e.region, &link, self.slack));
            }
            if self.cut.get(k + 1).is_some_and(|n| n.z == e.z) || e.z < lowest {
                continue;
            }
            crate::geom::sort::sort_by_float(&mut under, |p| p.0);
            let mut reach = 0.0;
            for &(t0, t1) in &under {
                if t0 > reach + gap {
                    break;
                }
                reach = f64::max(reach, t1);
            }
            if reach >= 1.0 - gap {
                return over(e.z).then_some(e.z);
            }
        }
        None
    }
}

/// The parts of the straight move from `a` to `b` (as fractions of it) outside `rect`.
fn outside(rect: &Rect, a: DVec2, b: DVec2) -> Vec<(f64, f64)> {
    match rect.clip_fractions(a, b) {
        None => vec![(0.0, 1.0)],
        Some((t0, t1)) => [(0.0, t0), (t1, 1.0)].into_iter().filter(|s| s.1 > s.0).collect(),
    }
}

/// The parts of `link` (as fractions of it, from its start) that lie in `region` or within
/// `slack` of it.
fn spans_inside(region: &Shape, link: &Segment, slack: f64) -> Vec<(f64, f64)> {
    let mut ts = vec![0.0, 1.0];
    let g = link.arc_geom();
    for s in region.segments() {
        ts.extend(s.crossings_with(s.arc_geom().as_ref(), link, g.as_ref(), FLOAT_SLACK).iter().map(|c| c.u.clamp(0.0, 1.0)));
    }
    crate::geom::sort::sort_floats(&mut ts);
    ts.dedup();
    ts.windows(2).filter(|w| holds(region, link.point_at(0.5 * (w[0] + w[1])), slack)).map(|w| (w[0], w[1])).collect()
}

/// What each level's region is made of ([`LevelRoughing::level_inputs`]).
struct LevelInputs<'a> {
    zl: &'a LevelRoughing,
    cl: &'a ClSurface,
    stock: &'a DexelStock,
    grid: Grid,
    r: f64,
    reach: f64,
    /// A farther reach outside the stock's box (`(reach, box)`), where it is farther.
    air_reach: Option<(f64, Rect)>,
    bands: bool,
    /// The levels from the top down, each with whether it is a flat's alone.
    heights: Vec<(f64, bool)>,
    /// Per level, the nodes `within` limits it to, where it does.
    limits: Vec<Option<Vec<bool>>>,
    /// Per node, the stock's highest around it, once a level asked ([`material_above`]).
    tops: Vec<OnceLock<f64>>,
    /// Per node, the stock's height at the cell nearest it, once a level asked.
    nearest: OnceLock<Vec<Option<f64>>>,
}

impl LevelInputs<'_> {
    /// The height level `k`'s region is contoured at: its own less the axial allowance.
    fn level(&self, k: usize) -> f64 {
        self.heights[k].0 - self.zl.roughing.allowance
    }

    /// The nodes every level's region keeps ([`LevelInputs::keep`]), a step-down level's
    /// widened by the nodes of lower levels' regions (within its limit) whose cutter touches
    /// material above it. A node a level keeps for the material it reaches half a step into
    /// may also touch, by a sliver, material beside it (in a crevice) that no level above came
    /// that near: cut only from below, that material would stand over the tool's flutes up to
    /// the top it was left at, the shank buried beside it. Kept at every step-down level above
    /// where the cutter touches that material, the node takes it down a step at a time.
    /// Packed ([`pack`]): every level's are held at once.
    fn keeps(&self) -> Vec<Vec<u8>> {
        let touching = self.r + self.grid.spacing * std::f64::consts::FRAC_1_SQRT_2;
        let count = self.heights.len();
        let nodes = self.grid.nodes();
        // The material above each level decides how near it a centre is: a level with no top of
        // the stock between it and the level before (a fresh stock's whole depth) shares that
        // level's distance map.
        let above = crate::parallel::map_heavy(count, |k| pack(&self.above(k)));
        let mut owner: Vec<usize> = (0..count).collect();
        for k in 1..count {
            if above[k] == above[k - 1] {
                owner[k] = owner[k - 1];
            }
        }
        let (air, beside) = self.air_reach.unwrap_or((self.reach, Rect::EMPTY));
        let reached = crate::parallel::map_heavy(count, |k| (owner[k] == k).then(|| within_reach_of(&unpack(&above[k], nodes), self.grid, [self.reach, touching, air]).map(|m| pack(&m))));
        let made = crate::parallel::map_heavy(count, |k| {
            let [keep, near, far] = reached[owner[k]].as_ref().expect("every shared level's reach is made");
            let mut keep = unpack(keep, nodes);
            if self.air_reach.is_some() {
                // Beside the stock, out to the farther reach.
                let far = unpack(far, nodes);
                for (n, kept) in keep.iter_mut().enumerate() {
                    let p = self.grid.node(n % self.grid.nx, n / self.grid.nx);
                    *kept |= far[n] && !(p.cmpge(beside.min).all() && p.cmple(beside.max).all());
                }
            }
            (pack(&self.keep(k, keep)), near.clone())
        });
        // From the bottom up: the nodes of the regions of the levels below.
        let mut below = vec![false; nodes];
        let mut keeps = vec![Vec::new(); made.len()];
        for (k, (keep, near)) in made.into_iter().enumerate().rev() {
            let (mut keep, near) = (unpack(&keep, nodes), unpack(&near, nodes));
            let band = self.heights[k].1 && self.bands;
            let limit = self.limits[k].as_deref();
            if !band {
                for (n, kept) in keep.iter_mut().enumerate() {
                    *kept |= below[n] && near[n] && limit.is_none_or(|l| l[n]);
                }
            }
            let level = self.level(k);
            for (n, &kept) in keep.iter().enumerate() {
                below[n] |= kept && self.cl.field.z[n] <= level;
            }
            keeps[k] = pack(&keep);
        }
        keeps
    }

    /// The nodes of the stock's grid with material above level `k` ([`material_above`]), at
    /// full reach (rest roughing: every centre whose cutter touches what is left) only material
    /// the cutter can reach from a centre it may take (within its radius of one, less half a
    /// node's spacing), not the part's walls and their leave-stock beside the region, which
    /// every level would otherwise follow.
    fn above(&self, k: usize) -> Vec<bool> {
        let (zl, grid, r) = (self.zl, self.grid, self.r);
        let z = self.heights[k].0;
        let removable = (self.reach >= r).then(|| {
            let safe: Vec<bool> = self.cl.field.z.iter().map(|&h| h + zl.roughing.allowance <= z).collect();
            let within = r - 0.5 * grid.spacing;
            let d = crate::zmap::distance::distance_within(&safe, grid.nx, grid.ny, grid.spacing, within);
            d.into_iter().map(|d| d <= within).collect::<Vec<bool>>()
        });
        match removable {
            Some(counts) => material_above(self.stock, grid, z, &counts, &self.tops),
            // Else the stock's cell nearest each node.
            None => {
                let nearest = self.nearest.get_or_init(|| (0..grid.nodes()).map(|n| self.stock.top_near(grid.node(n % grid.nx, n / grid.nx))).collect());
                nearest.iter().map(|top| top.is_some_and(|top| top > z + HAIR)).collect()
            }
        }
    }

    /// The nodes level `k`'s region keeps of `near`, those within reach of material above it:
    /// within its limit, and for a flat's level alone, where the level below cannot go.
    fn keep(&self, k: usize, mut keep: Vec<bool>) -> Vec<bool> {
        let (zl, grid) = (self.zl, self.grid);
        let flat = self.heights[k].1;
        if let Some(limit) = &self.limits[k] {
            keep.iter_mut().zip(limit).for_each(|(k, &l)| *k &= l);
        }
        // A flat's level only where the level below cannot go (a node further than a node's
        // spacing from every centre that level refuses is left to it).
        if flat && self.bands {
            let below = self.heights.get(k + 1).map_or(f64::NEG_INFINITY, |&(q, _)| q);
            let refused: Vec<bool> = self.cl.field.z.iter().map(|&h| h + zl.roughing.allowance > below).collect();
            let band = FLAT_BAND * grid.spacing;
            let d = crate::zmap::distance::distance_within(&refused, grid.nx, grid.ny, grid.spacing, band);
            keep.iter_mut().zip(d).for_each(|(k, d)| *k &= d <= band);
        }
        keep
    }
}

/// The regions an operation's levels will be contoured into, as work for a pool
/// ([`LevelRoughing::region_work`]): made elsewhere and given to the context
/// ([`Context::given_regions`]), they are taken instead of made.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionWork {
    /// The CL surface (and its level map) the regions are contoured on.
    pub request: SurfaceRequest,
    /// Per level, the height its region is contoured at and the nodes it keeps ([`pack`]).
    pub levels: Vec<(f64, Vec<u8>)>,
}

/// Booleans packed eight to a byte, the first in the lowest bit.
pub fn pack(bits: &[bool]) -> Vec<u8> {
    bits.chunks(8).map(|c| c.iter().enumerate().fold(0u8, |b, (k, &v)| b | ((v as u8) << k))).collect()
}

/// The first `count` booleans [`pack`] packed.
pub fn unpack(bytes: &[u8], count: usize) -> Vec<bool> {
    (0..count).map(|k| bytes.get(k / 8).is_some_and(|b| b >> (k % 8) & 1 == 1)).collect()
}

/// Per node of `grid`, whether material stands above `z` in the stock there, at the nodes
/// `counts` accepts: the highest of the stock's cells around the node (within half a diagonal
/// of the grid), so no cell between nodes goes unseen.
///
/// `tops` holds per node the highest of the cells around it once a level has asked (the same
/// for every level of one stock): `material_above` fills it as it goes.
fn material_above(stock: &DexelStock, grid: Grid, z: f64, counts: &[bool], tops: &[OnceLock<f64>]) -> Vec<bool> {
    let around = crate::cutter::Profile::new(grid.spacing * std::f64::consts::FRAC_1_SQRT_2, 0.0);
    let top = |n: usize| *tops[n].get_or_init(|| stock.touch(grid.node(n % grid.nx, n / grid.nx), &around, false));
    (0..grid.nodes()).map(|n| counts[n] && top(n) > z + HAIR).collect()
}

/// Per distance in `reach`, the nodes of `grid` within it of a node of `above`
/// ([`Region::silhouettes`]; every node where every node is above).
fn within_reach_of<const N: usize>(above: &[bool], grid: Grid, reach: [f64; N]) -> [Vec<bool>; N] {
    if above.iter().all(|&a| a) {
        return reach.map(|_| vec![true; grid.nodes()]);
    }
    let mut mask = grid.filled(0.0);
    mask.z.iter_mut().zip(above).for_each(|(m, &a)| *m = if a { 1.0 } else { 0.0 });
    Region::silhouettes(&mask, 0.5, reach).map(|region| match region {
        Region::Mask(m) => m.z.iter().map(|&v| v >= 0.5).collect(),
        Region::Rect { .. } => vec![true; grid.nodes()],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::Loop;

    /// A thin pin (0.2 mm square, 20 mm tall) on nothing, in a stock 60 mm across.
    fn pin_context() -> Context {
        use crate::geom::{Aabb, DVec3, Tolerances};
        let v = DVec3::new;
        let (a, h) = (0.1, 20.0);
        let c = [v(-a, -a, 0.0), v(a, -a, 0.0), v(a, a, 0.0), v(-a, a, 0.0), v(-a, -a, h), v(a, -a, h), v(a, a, h), v(-a, a, h)];
        let quads = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]];
        let tris = quads.iter().flat_map(|q| [[c[q[0]], c[q[1]], c[q[2]]], [c[q[0]], c[q[2]], c[q[3]]]]);
        let tolerances = Tolerances::default();
        let part = crate::mesh::Mesh::from_triangles(tris, &tolerances).unwrap();
        let stock = Aabb { min: v(-30.0, -30.0, -1.0), max: v(30.0, 30.0, h) };
        let tool = Tool { number: 1, cutter: crate::cutter::Cutter::flat(6.0), ..Tool::default() };
        Context {
            part,
            sheet: None,
            stock,
            heights: crate::machining::context::SafeHeights { clearance: h + 5.0, gap: 1.0, full: false },
            tools: vec![tool],
            tolerances,
            resolution: 0.001,
            caches: Default::default(),
            // The in-process stock already cut down to 5 mm: the air over it.
            sim: crate::sim::verify::Simulator::new(&Aabb { min: stock.min, max: v(30.0, 30.0, 5.0) }, 0.5).unwrap(),
            warnings: Vec::new(),
            rapids: crate::toolpath::Rapids::at(5000.0),
            air_feed: 5000.0,
            operation: 0,
            given_passes: Default::default(),
            given_regions: Vec::new(),
            keep_out: Vec::new(),
            solid: None,
        }
    }

    #[test]
    fn rings_are_weighed_by_the_regions_they_clear() {
        // Square regions of side a, a step s: about a / 2s rings and a² / s mm of cut each.
        let roughing = LevelRoughing::new("rough", 1, Steps { stepdown: 2.0, stepover_fraction: 0.4 }, &Roughing::default());
        let tool = Tool { number: 1, cutter: crate::cutter::Cutter::flat(6.0), feed_rate: 1000.0, ..Tool::default() };
        let square = |a: f64| Arc::new(Shape::new(vec![Loop::rect(DVec2::ZERO, DVec2::splat(a))]));
        // Two 500 mm squares at 2.4 mm: 210 rings, 212 m of cut (area and outline); ten, 1.06 km.
        assert!(roughing.check_rings(&tool, &vec![square(500.0); 2], 2.4).is_ok());
        let e = roughing.check_rings(&tool, &vec![square(500.0); 10], 2.4).unwrap_err().to_string();
        assert!(e.contains("cuts about 1.1 km (18 hours at 1000 mm/min"), "{e}");
        // A 20 mm square at 0.006 mm: 1,668 rings (its inradius over the step, and one); three of them are more than the limit allows.
        assert!(roughing.check_rings(&tool, &vec![square(20.0); 2], 0.006).is_ok());
        let e = roughing.check_rings(&tool, &vec![square(20.0); 3], 0.006).unwrap_err().to_string();
        assert!(e.contains("step-over of 0.006 mm makes about 5003 rings over the 3 regions"), "{e}");
    }

    #[test]
    fn the_way_in_from_the_air_never_crosses_the_part() {
        // A region cut short by a mask (octree roughing's octants) can end at a point whose
        // step out, away from the stock's middle, passes the side of a pin: both ends stand
        // clear of it (the φ6 flat end's centre 3.1 mm from its side), the way
        // between does not. The rocker arm's φ6 and φ3 stages fed through it, deeper at every
        // level (issue 38).
        let mut ctx = pin_context();
        let roughing = LevelRoughing::new("rough", 1, Steps { stepdown: 2.0, stepover_fraction: 0.4 }, &Roughing { allowance: 0.0, leave_stock: 0.0, ..Roughing::default() });
        let (tool, cl) = roughing.surface(&mut ctx, &mut Progress::none()).unwrap();
        let r = tool.cutter.radius();
        let z = 10.0;
        // Two points level with each other beside the pin's axis, a step apart: the step out
        // from the first (the stock's middle put behind it) lands on the second.
        let step = roughing.step(r);
        let (p, q) = (DVec2::new(-0.5 * step, 3.0), DVec2::new(0.5 * step, 3.0));
        assert!(cl.height(p) <= z && cl.height(q) <= z, "both ends clear of the pin");
        assert!(!cl.stays_below(p, q, z), "the way between passes over the pin's shadow");
        let middle_behind = |from: DVec2| {
            let m = from - (q - p) * 10.0;
            crate::geom::Aabb { min: (m - DVec2::splat(1.0)).extend(-1.0), max: (m + DVec2::splat(1.0)).extend(20.0) }
        };
        ctx.stock = middle_behind(p);
        {
            let air = roughing.air(&ctx, &cl, r, z);
            assert_eq!(air(p, 0), None, "no way in from the air across the pin");
            // Another way out may be taken (the compass directions after it), never across the pin.
            for k in 1..crate::machining::rings::WAYS_OUT {
                assert!(air(p, k).is_none_or(|a| cl.stays_below(a, p, z)), "way {k} crosses the pin: {:?}", air(p, k));
            }
        }
        // Farther from the pin, with nothing in the way, the way in stays.
        let far = DVec2::new(-0.5 * step, 9.0);
        ctx.stock = middle_behind(far);
        let air = roughing.air(&ctx, &cl, r, z);
        assert!(air(far, 0).is_some_and(|a| a.distance(far + (q - p)) < 1e-9), "{:?}", air(far, 0));
    }

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::new(vec![Loop::rect(DVec2::new(x0, y0), DVec2::new(x1, y1))])
    }

    #[test]
    fn a_region_beside_a_higher_one_waits_for_it() {
        // Level 0: a region on the left and one on the right, 20 mm apart. Level −1: a region
        // under the left one that reaches to within 1 mm of the right one (a tool of radius 3
        // there would work beside the material the right one has still to take down).
        let levels = |gap: f64| {
            vec![
                Level { z: 0.0, z_prev: 1.0, region: Shape::new(rect(0.0, 0.0, 10.0, 10.0).loops.into_iter().chain(rect(30.0, 0.0, 40.0, 10.0).loops).collect()) },
                // Counter-clockwise from the left side's foot: its first side (its probe) lies under the left region.
                Level { z: -1.0, z_prev: 0.0, region: Shape::new(vec![Loop::polygon(&[DVec2::new(1.0, 9.0), DVec2::new(1.0, 1.0), DVec2::new(29.0 - gap, 1.0), DVec2::new(29.0 - gap, 9.0)])]) },
            ]
        };
        let order = |gap: f64, reach: f64| {
            let mut pieces = Pieces::new(levels(gap), Order::Regions, 1e-6, reach);
            let mut at = DVec2::ZERO;
            std::iter::from_fn(|| {
                let (_, p) = pieces.next(at)?;
                at = p.region.bounds().center();
                Some((p.z, p.region.bounds().min.x))
            })
            .collect::<Vec<_>>()
        };
        // Left, right, then the region below: not the region below before the right one.
        assert_eq!(order(0.0, 3.0), vec![(0.0, 0.0), (0.0, 30.0), (-1.0, 1.0)]);
        // Out of the tool's reach of the right one (7 mm from it, a radius of 3), it goes down
        // first.
        assert_eq!(order(6.0, 3.0), vec![(0.0, 0.0), (-1.0, 1.0), (0.0, 30.0)]);
    }
}
