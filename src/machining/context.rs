//! The context every operation of a job plans in (DESIGN.md ideas 5 and 6): the placed part or
//! drawing, the stock, the safe heights, the tool library and the tolerances, built once per
//! job; caches, so that a second operation on the same part and cutter gets its z-map for
//! nothing; and the in-process stock, the material the earlier operations left, which later
//! operations enter and link over.

use std::sync::Arc;

use crate::cutter::Profile;
use crate::drawing::Drawing;
use crate::error::{Error, Result, Warning};
use crate::geom::{Aabb, DVec2, DVec3, Tolerances};
use crate::mesh::Mesh;
use crate::progress::Progress;
use crate::sim::verify::Simulator;
use crate::tool::Tool;
use crate::toolpath::entry::{Entry, Keepout};
use crate::toolpath::link::{Feeds, LinkSettings, Linker};
use crate::toolpath::Toolpath;
use crate::zmap::bounds::NodeBounds;
use crate::zmap::cc::cc_zmap;
use crate::zmap::cl_exact::ExactBuilder;
use crate::zmap::cl_inverse::cl_inverse_offset;
use crate::zmap::contour::LevelMap;
use crate::zmap::drop::PointDrop;
use crate::zmap::surface::ClSurface;
use crate::zmap::{ClBuilder, Grid, HeightField};

/// Heights of moves between cuts (mm, absolute).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SafeHeights {
    /// Rapids across the part run here: above the stock's top by the job's clearance.
    pub clearance: f64,
    /// A rapid descent stops this far above the material under the tool (the short retract
    /// used between nearby cuts); the rest is fed.
    pub gap: f64,
    /// Retracts across material go to the clearance height (not the gap above the material
    /// on the way).
    pub full: bool,
}

/// A drawing as a sheet on the machine: its top at Z0, `thickness` below.
#[derive(Clone, Debug)]
pub struct Sheet {
    pub drawing: Drawing,
    pub thickness: f64,
}

/// Lookups of the caches, for reports and benchmarks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CacheCounts {
    pub hits: usize,
    pub misses: usize,
}

/// What operations of one job share: the part's CC z-map per grid, the exact builder's
/// preparation of the mesh per cutter (its drop index), and the CL surface per cutter, grid
/// and builder.
#[derive(Default)]
pub struct Caches {
    cc: Vec<((Grid, u64), Arc<HeightField>)>,
    drops: Vec<((Profile, u64), Arc<PointDrop>)>,
    cl: Vec<(SurfaceKey, Arc<ClSurface>)>,
    builders: Vec<((Profile, u64), Arc<ExactBuilder>)>,
    /// The builders of widened cutters ([`PointDrop::widened`]), by the cutter they widen.
    widened: Vec<((Profile, u64, u64), Arc<ExactBuilder>)>,
    levels: Vec<(SurfaceKey, Arc<LevelMap>)>,
    /// The widened cutters' heights at the nodes of a surface's grid ([`Context::node_bounds`]).
    bounds: Vec<(SurfaceKey, Arc<NodeBounds>)>,
    pub counts: CacheCounts,
}

/// A CL surface an operation asks the context for: its cutter, grid, floor (the height where
/// no part is under the cutter) and builder. Operations name theirs before planning
/// ([`crate::machining::Operate::surfaces`]), so that a pool of workers can make them first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceRequest {
    pub profile: Profile,
    pub grid: Grid,
    pub floor: f64,
    pub builder: ClBuilder,
}

/// A region made elsewhere for a level: the surface, the height and the kept nodes it was
/// contoured with.
#[derive(Clone, Debug)]
pub struct GivenRegion {
    pub request: SurfaceRequest,
    pub level: f64,
    pub keep: Vec<u8>,
    pub region: crate::drawing::Shape,
}

/// A request with the program's resolution, as the cache keys it.
type SurfaceKey = (Profile, u64, Grid, u64, ClBuilder);

/// The job's context, as each operation sees it.
pub struct Context {
    /// The part as placed (mm, Z up); empty for a drawing.
    pub part: Mesh,
    pub sheet: Option<Sheet>,
    /// The raw stock's box.
    pub stock: Aabb,
    pub heights: SafeHeights,
    pub tools: Vec<Tool>,
    pub tolerances: Tolerances,
    /// How far the program's rounding may move a point sideways (mm), see
    /// [`crate::post::PostSettings::planning_resolution`].
    pub resolution: f64,
    pub caches: Caches,
    /// The in-process stock: the raw box cut by every operation planned so far.
    pub sim: Simulator,
    pub warnings: Vec<Warning>,
    /// How the machine's rapids are timed, for timing what an operation plans.
    pub rapids: crate::toolpath::Rapids,
    /// The feed of level moves an operation knows cut nothing (the job's `stock.airFeed`, at
    /// most the rapid rate; [`super::air`]).
    pub air_feed: f64,
    /// The index in the job of the operation being planned.
    pub operation: usize,
    /// Raster passes a pool of workers made before planning ([`crate::job::pool`]), by the
    /// index of their operation: each pass's runs, in pass order.
    pub given_passes: std::collections::HashMap<usize, Vec<Vec<Vec<DVec3>>>>,
    /// Regions of levels a pool of workers made for the operation about to plan
    /// ([`crate::machining::levels::LevelRoughing::region_work`]): a level contoured on the
    /// same surface, at the same height, keeping the same nodes takes its region from here.
    pub given_regions: Vec<GivenRegion>,
    /// What holds the stock, each grown by its clearance ([`crate::job::fixtures`]).
    pub keep_out: Vec<crate::job::fixtures::Held>,
    /// The part with `keep_out`'s boxes, where there are any: what the cutter is dropped onto,
    /// so that every CL surface, and every strategy above one, stays out of them.
    pub solid: Option<Mesh>,
}

impl Context {
    /// The tool `number` of the library, for the operation `op`.
    pub fn tool(&self, op: &str, number: u32) -> Result<&Tool> {
        self.tools.iter().find(|t| t.number == number).ok_or_else(|| Error::operation(op, format!("no tool number {number} in the tool library")))
    }

    /// The CL surface the finishing operation `op` cuts on: tool `tool`'s profile on a grid of
    /// `spacing` over the stock's plan, the floor `floor` (the stock's bottom when none).
    pub fn stock_surface(&self, op: &str, tool: u32, spacing: f64, floor: Option<f64>, builder: ClBuilder) -> Result<SurfaceRequest> {
        let profile = self.tool(op, tool)?.cutter.profile();
        let grid = Grid::checked(self.stock.min.truncate(), self.stock.max.truncate(), spacing).map_err(|e| Error::operation(op, e))?;
        Ok(SurfaceRequest { profile, grid, floor: floor.unwrap_or(self.stock.min.z), builder })
    }

    pub fn warn(&mut self, op: &str, message: impl Into<String>) {
        self.warnings.push(Warning::of(op, message));
    }

    /// A note of the operation `op`, for the record.
    pub fn note(&mut self, op: &str, message: impl Into<String>) {
        self.warnings.push(Warning::of(op, message).note());
    }

    /// Counts `places` of `what` for the operation `op`, adding to its warning of the same
    /// thing if it has one.
    pub fn warn_at(&mut self, op: &str, what: &str, places: &[DVec3]) {
        let w = Warning::counted(Some(op), what, places);
        match self.warnings.iter_mut().find(|v| v.counts_as(&w)) {
            Some(v) => v.add(places),
            None => self.warnings.push(w),
        }
    }

    /// The highest tip height at which a cutter of `profile` at `p` touches the in-process
    /// stock (`-inf` where it touches none), as the stock's z-map samples it at its cells'
    /// centres: an estimate, for deciding what is left to cut.
    pub fn material_estimate(&self, p: DVec2, profile: &Profile) -> f64 {
        self.sim.stock().touch(p, profile, false)
    }

    /// Joins `runs` of the operation `op` into one tool path with the shared linker
    /// ([`Linker`]): stay-down links and entries kept clear by `keep`, rapid descents stopping
    /// the retract gap above the in-process stock, entries by `entry`. Entries that found no
    /// room for a helix or a ramp are warned of.
    pub fn link(&mut self, op: &str, tool: &Tool, runs: &[Vec<DVec3>], keep: &dyn Keepout, entry: Entry, stay_down_max: f64) -> Toolpath {
        let (path, plunges) = self.link_quietly(op, tool, runs, (None, None), f64::INFINITY, keep, entry, stay_down_max, true);
        self.warn_plunges(op, &plunges);
        path
    }

    /// [`Context::link`] without the warning (planning that runs on several threads warns
    /// afterwards, in order, by [`Context::warn_plunges`]): the tool path and where its
    /// entries feed straight down into material. Where given, a feed for each move along the
    /// runs and whether each run starts in material (`known`, see [`Linker::link_fed`]), and
    /// the in-process stock taken no higher than `ceiling` (what the operation itself has cut
    /// down to before these runs). `side_first`: [`Linker::side_first`] (finishing; roughing
    /// meets whole levels of material beside its starts, and goes in by a helix).
    #[allow(clippy::too_many_arguments)]
    pub fn link_quietly(
        &self,
        op: &str,
        tool: &Tool,
        runs: &[Vec<DVec3>],
        known: (Option<&[Vec<f64>]>, Option<&[bool]>),
        ceiling: f64,
        keep: &dyn Keepout,
        entry: Entry,
        stay_down_max: f64,
        side_first: bool,
    ) -> (Toolpath, Vec<DVec3>) {
        let profile = tool.cutter.profile();
        let stock = self.sim.stock();
        let material = |p: DVec2| stock.touch(p, &profile, true).min(ceiling);
        let material_above = |p: DVec2, h: f64| ceiling > h && stock.touches_above(p, p, &profile, true, h);
        let estimate = |p: DVec2| stock.touch(p, &profile, false).min(ceiling);
        let along = |a: DVec2, b: DVec2| stock.touch_along(a, b, &profile, true);
        let core = Profile::new(profile.radius / 2.0, 0.0);
        let core_along = |a: DVec2, b: DVec2| stock.touch_along(a, b, &core, true);
        let settings = LinkSettings { clearance_z: self.heights.clearance, rapid_gap: self.heights.gap, stay_down_max, full_retract: self.heights.full };
        let rates = Feeds { cut: tool.feed_rate, plunge: tool.plunge_rate };
        let linker = Linker {
            settings,
            keep,
            material: &material,
            material_above: &material_above,
            material_along: &along,
            estimate: &estimate,
            threshold: self.tolerances.gouge,
            entry,
            radius: profile.radius,
            feeds: rates,
            side_first: side_first.then_some(&core_along),
        };
        let (start, moves, entries) = linker.link_fed(runs, known.0, known.1, &self.tolerances);
        (Toolpath { name: op.to_string(), tool: tool.number, spindle_rpm: tool.spindle_rpm, start, moves, cycles: Vec::new() }, entries.plunges)
    }

    /// Warns of entries of `op` at `plunges` that found no room for a helix or a ramp.
    pub fn warn_plunges(&mut self, op: &str, plunges: &[DVec3]) {
        if !plunges.is_empty() {
            self.warn_at(op, "entries found no room for a helix or a ramp and feed straight down into material", plunges);
        }
    }

    /// The part's heights on `grid` (`floor` where it is not): its CC z-map, made once.
    pub fn cc_zmap(&mut self, grid: Grid, floor: f64) -> Arc<HeightField> {
        let (part, tol) = (&self.part, &self.tolerances);
        cached(&mut self.caches.cc, (grid, floor.to_bits()), || cc_zmap(part, grid, floor, tol))
    }

    /// The part indexed for exact drops of `profile` grown by the program's resolution
    /// ([`PointDrop::grown`]), made once per cutter.
    pub fn drop(&mut self, profile: &Profile) -> Arc<PointDrop> {
        let (part, resolution, tol) = (self.solid.as_ref().unwrap_or(&self.part), self.resolution, &self.tolerances);
        cached(&mut self.caches.drops, (*profile, resolution.to_bits()), || PointDrop::grown(part, profile, resolution, tol))
    }

    /// The CL surface `request` names: its cutter over the part on its grid, its floor where
    /// no part is under the cutter, made by its builder; made once per request. Heights come
    /// from the cutter grown by the program's resolution: no lower than the highest tip height
    /// within that distance, so that rounding X and Y as the G-code is written cannot put a
    /// point below the surface (Z is written rounded up).
    pub fn cl_surface(&mut self, request: SurfaceRequest, progress: &mut Progress) -> Result<Arc<ClSurface>> {
        if let Some(s) = self.cached_surface(&request) {
            self.caches.counts.hits += 1;
            return Ok(s);
        }
        self.caches.counts.misses += 1;
        let SurfaceRequest { profile, grid, floor, builder } = request;
        let drop = self.drop(&profile);
        let field = match builder {
            // The exact z-map is the grown cutter's, so its nodes stand in for the drop where
            // a pass crosses them.
            ClBuilder::Exact => drop.field(self.solid.as_ref().unwrap_or(&self.part), grid, floor, &self.tolerances, progress)?,
            ClBuilder::InverseOffset => {
                // The part's heights with the fixtures' (not kept: the part's own outline is
                // what the cached one gives).
                let cc = match &self.solid {
                    Some(solid) => Arc::new(cc_zmap(solid, grid, floor, &self.tolerances)),
                    None => self.cc_zmap(grid, floor),
                };
                cl_inverse_offset(&cc, &profile, progress)?
            }
        };
        Ok(self.keep_surface(request, field))
    }

    fn cached_surface(&self, request: &SurfaceRequest) -> Option<Arc<ClSurface>> {
        let key = self.surface_key(request);
        self.caches.cl.iter().find(|(k, _)| *k == key).map(|(_, s)| s.clone())
    }

    fn surface_key(&self, r: &SurfaceRequest) -> SurfaceKey {
        (r.profile, self.resolution.to_bits(), r.grid, r.floor.to_bits(), r.builder)
    }

    /// Keeps `field`, the heights `request` names (made here or by a worker of a pool, band by
    /// band), as that request's CL surface.
    pub fn keep_surface(&mut self, request: SurfaceRequest, field: HeightField) -> Arc<ClSurface> {
        let drop = self.drop(&request.profile);
        let s = Arc::new(ClSurface::new(field, drop, request.floor, request.builder == ClBuilder::Exact, self.tolerances.interpolation));
        let key = self.surface_key(&request);
        self.caches.cl.retain(|(k, _)| *k != key);
        self.caches.cl.push((key, s.clone()));
        s
    }

    /// The level map ([`LevelMap`]) of `cl`, the CL surface `request` names, made once per
    /// request.
    pub fn level_map(&mut self, request: SurfaceRequest, cl: &ClSurface) -> Arc<LevelMap> {
        let key = self.surface_key(&request);
        if let Some((_, m)) = self.caches.levels.iter().find(|(k, _)| *k == key) {
            return m.clone();
        }
        // The widened heights at every node, kept as the surface's node bounds too.
        let wide = LevelMap::widened_heights(cl, &self.widened(request));
        let map = Arc::new(LevelMap::new(cl, &wide, &self.tolerances).expect("the widened heights cover the grid"));
        self.caches.levels.push((key, map.clone()));
        self.keep_node_bounds(request, wide);
        map
    }

    /// The heights of the cutter of `request` widened by its grid's spacing at the nodes of
    /// its grid (`Context::widened`), each a bound from above of the surface within a spacing
    /// of its node: those its level map took, else made in bands of rows as they are asked for.
    pub fn node_bounds(&mut self, request: SurfaceRequest) -> Arc<NodeBounds> {
        let key = self.surface_key(&request);
        if let Some((_, b)) = self.caches.bounds.iter().find(|(k, _)| *k == key) {
            return b.clone();
        }
        let (builder, drop) = (self.widened(request), self.drop(&request.profile));
        let (grid, floor) = (request.grid, request.floor);
        let bounds = Arc::new(NodeBounds::lazy(grid.nx, grid.ny, move |rows| drop.rows(&builder, grid, floor, rows, &mut Progress::none()).unwrap_or_default()));
        self.caches.bounds.push((key, bounds.clone()));
        bounds
    }

    /// The exact builder of the cutter of `request` widened by its grid's spacing
    /// ([`PointDrop::widened`]): what [`LevelMap`] bounds its edges by. Made once per cutter
    /// and spacing.
    fn widened(&mut self, request: SurfaceRequest) -> Arc<ExactBuilder> {
        let drop = self.drop(&request.profile);
        let (part, tol, h) = (self.solid.as_ref().unwrap_or(&self.part), &self.tolerances, request.grid.spacing);
        cached(&mut self.caches.widened, (request.profile, self.resolution.to_bits(), h.to_bits()), || drop.widened(part, h, tol))
    }

    /// The widened cutter's heights (`Context::widened`) at the nodes of rows `rows` of
    /// `request`'s grid: a band of a level map's bounds, as a worker of a pool makes it.
    pub fn widened_rows(&mut self, request: SurfaceRequest, rows: std::ops::Range<usize>) -> Result<Vec<f64>> {
        let builder = self.widened(request);
        self.drop(&request.profile).rows(&builder, request.grid, request.floor, rows, &mut Progress::none())
    }

    /// Keeps `wide` (made by a pool, band by band) as the node bounds of `request`'s surface
    /// ([`Context::node_bounds`]); `false` when it holds another number of heights.
    pub fn keep_node_bounds(&mut self, request: SurfaceRequest, wide: Vec<f64>) -> bool {
        let Some(bounds) = NodeBounds::whole(request.grid.nx, request.grid.ny, wide) else { return false };
        let key = self.surface_key(&request);
        self.caches.bounds.retain(|(k, _)| *k != key);
        self.caches.bounds.push((key, Arc::new(bounds)));
        true
    }

    /// Keeps `map` (made by a pool, band by band) as the level map of `request`'s surface.
    pub fn keep_level_map(&mut self, request: SurfaceRequest, map: LevelMap) {
        let key = self.surface_key(&request);
        self.caches.levels.retain(|(k, _)| *k != key);
        self.caches.levels.push((key, Arc::new(map)));
    }

    /// Rows `rows` of the exact CL surface `request` names (its builder must be the exact
    /// one): a band of it, as a worker of a pool makes it; the mesh's features are prepared once
    /// per cutter.
    pub fn surface_rows(&mut self, request: SurfaceRequest, rows: std::ops::Range<usize>, progress: &mut Progress) -> Result<Vec<f64>> {
        debug_assert!(request.builder == ClBuilder::Exact);
        let drop = self.drop(&request.profile);
        let (part, tol) = (self.solid.as_ref().unwrap_or(&self.part), &self.tolerances);
        let builder = cached(&mut self.caches.builders, (request.profile, self.resolution.to_bits()), || drop.builder(part, tol));
        drop.rows(&builder, request.grid, request.floor, rows, progress)
    }
}

/// The value `list` keeps under `key`, made by `make` and kept the first time.
fn cached<K: PartialEq, V>(list: &mut Vec<(K, Arc<V>)>, key: K, make: impl FnOnce() -> V) -> Arc<V> {
    if let Some((_, v)) = list.iter().find(|(k, _)| *k == key) {
        return v.clone();
    }
    let v = Arc::new(make());
    list.push((key, v.clone()));
    v
}
