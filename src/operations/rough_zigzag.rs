//! Zigzag roughing by the intersection-points graph, with the tool's load held at the
//! step-over's (seed 004; [`crate::zigzag`]). The levels, their regions (allowances, flats,
//! material left by earlier operations), entries and linking are the z-level strategy's
//! ([`LevelRoughing::levels_to_cut`], [`Context::link_quietly`]); at each level this strategy
//! clears the region with direction-parallel passes instead of rings:
//!
//! 1. the graph of the region and scan lines at the angle and step-over (§2.1), walked with a
//!    stack (§2.2) into runs the tool cuts staying down;
//! 2. the region's boundary last, so the wall left is the allowance;
//! 3. on a pixel map of the level (the in-process stock above it), each run cut in steps of
//!    Δs: where a step would remove more than the reference `(Δs / pixel) × (s / pixel)` by the
//!    tolerance, the tool eases off by extra path (§3.3, `load: path`), or the feed drops to
//!    hold the rate (`load: feed`, the usual feed-rate scheduling, for comparison); what no
//!    extra path can ease (a slot into a closed region) gets the lower feed in either case;
//! 4. runs joined staying down where the link stays in the region and within the load, else
//!    linked by the shared linker (retract, rapid down to just above the material, helix or
//!    ramp); the lines fitted with arcs.

use serde::{Deserialize, Serialize};

use crate::drawing::Shape;
use crate::error::{Error, Result};
use crate::geom::tolerance::LEAST_STEP;
use crate::geom::{DVec2, DVec3};
use crate::machining::air::Refeed;
use crate::machining::levels::{level_work, Level, LevelRoughing, Levels};
use crate::machining::path2d::start_nearest;
use crate::machining::report::LoadReport;
use crate::machining::rings::Inside;
use crate::machining::settings::{Direction, LoadControl, Roughing, Steps};
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::progress::Progress;
use crate::tool::Tool;
use crate::toolpath::entry::Entry;
use crate::toolpath::{arcfit, Move, Toolpath};
use crate::zigzag::graph::{along_boundary, Graph, Pattern};
use crate::zigzag::load::{self, Load, LoadProfile, PixelMap};

/// How spans are cut.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Passes {
    /// Back and forth (the paper's path): half the passes climb, half not.
    #[default]
    Zigzag,
    /// Every pass in the cutting direction, back along the pass just cut before the next.
    OneWay,
}

/// Zigzag roughing (seed 004).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct RoughZigzag {
    /// Default value: "zigzag rough".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// The tool that cuts the passes. Default value: 1.
    pub tool: u32,
    /// Direction of the passes (degrees from +X). Default value: 0.
    pub angle: f64,
    /// How deep the levels go and how far apart the passes are.
    #[serde(flatten)]
    #[ts(flatten)]
    pub steps: Steps,
    /// Default value: zigzag.
    pub passes: Passes,
    /// Default value: path.
    pub load: LoadControl,
    /// How far over the reference a stretch of Δs may load the tool (0.1: 10 %). Default value: 0.1.
    pub load_tolerance: f64,
    /// The sampling distance Δs (mm). Default value: half the step-over.
    pub sampling: Option<f64>,
    /// The pixel of the load's map (mm), at most an eighth of the step-over. Default value: the
    /// step-over / 24.
    pub pixel: Option<f64>,
    /// What it leaves, which way it cuts, its CL z-map's spacing and its entries' slope.
    #[serde(flatten)]
    #[ts(flatten)]
    pub roughing: Roughing,
    /// Cut every flat area of the part at its own height too. Default value: true.
    pub flats: bool,
}

impl Default for RoughZigzag {
    fn default() -> Self {
        RoughZigzag {
            name: "zigzag rough".into(),
            enabled: true,
            tool: 1,
            steps: Steps::default(),
            roughing: Roughing::default(),
            angle: 0.0,
            passes: Passes::Zigzag,
            load: LoadControl::Path,
            load_tolerance: 0.1,
            sampling: None,
            pixel: None,
            flats: true,
        }
    }
}

impl RoughZigzag {
    /// Refuses a pixel coarser than [`COARSEST_PIXEL`] of the step-over `step`: on such a map
    /// one pass's cut and the next's are a pixel or two apart, the load read off it swings by
    /// whole pixels, and the path held to it wanders (a φ3 at a 1.2 mm step-over on 0.3 mm
    /// pixels cut 13 m where 5 m clear the level, on 1 mm pixels 37 m in 13 s).
    fn pixel_fits(&self, step: f64) -> Result<()> {
        match self.pixel {
            Some(p) if p > step * COARSEST_PIXEL => Err(Error::operation(
                &self.name,
                format!(
                    "pixels of {} mm are coarser than an eighth of the step-over of {} mm: the load cannot be read off them; choose at most {} mm, or leave the pixel unset (the step-over / 24)",
                    crate::limits::shown(p),
                    crate::limits::shown((step * 1e4).round() / 1e4),
                    crate::limits::shown((step * COARSEST_PIXEL * 1e4).floor() / 1e4)
                ),
            )),
            _ => Ok(()),
        }
    }

    /// The sampling distance at a step-over of `step`: the set one, or half the step.
    fn sampling_at(&self, step: f64) -> f64 {
        self.sampling.unwrap_or(0.5 * step).max(LEAST_STEP)
    }

    /// The pixel of the load's map at a step-over of `step` (mm).
    fn pixel_at(&self, step: f64) -> f64 {
        self.pixel.unwrap_or_else(|| load::default_pixel(step)).max(LEAST_STEP)
    }

    /// Its levels' settings (its own loop cuts level by level).
    pub fn levels(&self) -> LevelRoughing {
        LevelRoughing { flats: self.flats, ..LevelRoughing::new(&self.name, self.tool, self.steps, &self.roughing) }
    }

    /// One level's tool path, its share of the load report, and what to warn of: the runs
    /// left out, the entries that plunged.
    fn level(&self, ctx: &Context, settings: &Settings, level: &Level) -> LevelCut {
        let Settings { tool, step, ds, px, load, pattern, entry, shortest } = *settings;
        let Level { z, z_prev, ref region } = *level;
        let r = tool.cutter.radius();
        let tol = ctx.tolerances;
        let (mut left_out, mut slowed) = (0, 0.0);
        // §2: the passes, then the boundary.
        let graph = Graph::new(region, self.angle.to_radians(), step);
        let mut runs = graph.walk(pattern, load.climb, tol.chordal);
        let end = runs.last().and_then(|r| r.last()).copied().unwrap_or(DVec2::ZERO);
        // The last contour finishes the wall: its load is held by the feed, never by moving
        // it off the boundary (a corrected path rounds the region's corners off).
        let contours_from = runs.len();
        runs.extend(boundary_runs(region, load.climb, tol.chordal, end));
        // §3: the load on the material at this level.
        let stock = ctx.sim.stock();
        let material = |p: DVec2| load::material_at(stock, p, z);
        let bounds = region.bounds();
        let px = load::pixel_for(bounds, r, px);
        let reference = load.reference(px);
        let limit = reference * (1.0 + self.load_tolerance);
        // The plain path's own map, for the report, only where the path is not the plain one.
        let mut map = PixelMap::new(bounds, px, r, material, region);
        let mut plain_map = (self.load == LoadControl::Path).then(|| map.clone());
        let inside = Inside(region);
        let (mut pts3, mut feeds): (Vec<Vec<DVec3>>, Vec<Vec<f64>>) = (Vec::new(), Vec::new());
        // Whether each run starts in material, as the map of this level knows.
        let mut starts = Vec::new();
        let mut plain = LoadProfile::default();
        let mut done = LoadProfile::default();
        let mut shares = Vec::new();
        for (i, run) in runs.iter().enumerate() {
            // The plain path's load, for the report (the path itself unless corrected).
            if let Some(m) = &mut plain_map {
                load::plain(m, run, &load, &mut plain);
            }
            // Joined to the run before when the straight link stays in the region and
            // within the load.
            let mut steps = LoadProfile::default();
            let mut pts = Vec::new();
            let from = pts3.last().and_then(|r: &Vec<DVec3>| r.last()).map(|p| p.truncate());
            // The link in steps of Δs, each within the load.
            let link = from.map(|a| load::densify(&[a, run[0]], ds / load::SUBSTEPS as f64)).unwrap_or_default();
            let joined = from.is_some_and(|a| {
                use crate::toolpath::entry::Keepout;
                inside.clears(a.extend(z), run[0].extend(z), 0.0) && load::link_keeps(&mut map, &link, limit, ds)
            });
            let in_material = map.count(run[0], run[0]) > 0;
            if !joined && too_short(run, shortest) && in_material {
                // Too short to ramp into the material at its start, in a place too narrow
                // for a helix: left, with a warning.
                left_out += 1;
                continue;
            }
            if joined {
                for w in link.windows(2) {
                    let n = map.cut(w[0], w[1]);
                    steps.counts.push((n as f64, w[0].distance(w[1])));
                }
                pts.extend(&link[..link.len() - 1]);
            }
            pts.extend(match self.load {
                LoadControl::Path if i < contours_from => load::corrected(&mut map, run, &load, &mut steps),
                _ => load::plain(&mut map, run, &load, &mut steps),
            });
            let mut fed = Vec::with_capacity(steps.counts.len());
            for &(n, len) in &steps.counts {
                let slow = if self.load == LoadControl::None { None } else { load::feed_share(n, len, limit, ds) };
                if slow.is_some() {
                    slowed += len;
                }
                let share = slow.unwrap_or(1.0);
                shares.push(share);
                fed.push(tool.feed_rate * share);
            }
            done.counts.extend(steps.counts);
            let run3: Vec<DVec3> = pts.iter().map(|p| p.extend(z)).collect();
            if joined {
                pts3.last_mut().unwrap().extend(run3.into_iter().skip(1));
                feeds.last_mut().unwrap().extend(fed);
            } else {
                pts3.push(run3);
                feeds.push(fed);
                starts.push(in_material);
            }
        }
        // Cut as it is (no plain path's map), the plain path's load is the path's own, links
        // included.
        let plain = if plain_map.is_some() { plain.ratios(reference, ds) } else { done.ratios(reference, ds) };
        let (linked, plunges) = ctx.link_quietly(&self.name, tool, &pts3, (Some(&feeds), Some(&starts)), z_prev, &inside, entry, 0.0, false);
        let moves = arcfit::fit(&linked.moves, linked.start, tol.chordal, &|p| region.contains(p));
        // Stretches over what the level cleared already at the air feed.
        let moves =
            Refeed { bounds: region.bounds().expand(r), z, stock: ctx.sim.stock(), profile: tool.cutter.profile(), feed: ctx.air_feed, cutting: tool.feed_rate, from: linked.start, moves }.run();
        LevelCut { path: Toolpath { moves, ..linked }, load: done.ratios(reference, ds), plain, cut: done.rates(Some(&shares), reference, ds), slowed, left_out, plunges }
    }
}

/// What every level of a zigzag roughing shares.
#[derive(Clone, Copy)]
struct Settings<'a> {
    tool: &'a Tool,
    step: f64,
    ds: f64,
    px: f64,
    load: Load,
    pattern: Pattern,
    entry: Entry,
    /// A run shorter than this that starts in material, where no helix fits, is left out.
    shortest: f64,
}

/// One level of a zigzag roughing ([`RoughZigzag::level`]).
struct LevelCut {
    path: Toolpath,
    load: Vec<f64>,
    plain: Vec<f64>,
    cut: Vec<f64>,
    slowed: f64,
    left_out: usize,
    plunges: Vec<DVec3>,
}

impl Operate for RoughZigzag {
    fn plans_round_fixtures(&self) -> bool {
        true
    }
    named_operation!(OnPart);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm};
        let mut fields = crate::machining::settings::roughing_form();
        fields.extend([
            F::number("angle", "Pass angle", U::Degrees),
            F::choice("passes", "Passes", &[("zigzag", "back and forth"), ("oneWay", "one way")]),
            F::load("Keep the load even by", "Where a pass would take a heavier cut than a full step-over at the step-down (into a corner, across a slot), the path adds a short detour to keep the chip load even, or the feed drops there."),
            F::number("loadTolerance", "Load allowed over the even one", U::None).note("fraction").range(0.0, None),
            F::length("sampling", "Load sampled along the passes every", 0.001).empty("half the step-over"),
            F::length("pixel", "Load map's pixel", 0.001).empty("the step-over / 24"),
        ]);
        OperationForm::new("rough by zigzag passes (even load)", fields).hint(crate::machining::settings::REST_HINT)
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.steps.stepdown)
    }

    fn allowance(&self) -> f64 {
        self.roughing.allowance()
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.levels().validate()?;
        crate::machining::angle("angle", self.angle, -360.0, 360.0)?;
        not_negative("loadTolerance", self.load_tolerance)?;
        if let Some(s) = self.sampling {
            positive("sampling", s)?;
        }
        if let Some(p) = self.pixel {
            positive("pixel", p)?;
        }
        Ok(())
    }

    level_work!();

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let levels = self.levels();
        // One level's work before the levels are found (a φ0.01 tool's are thousands).
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let step = levels.step(tool.cutter.radius());
        self.pixel_fits(step)?;
        self.weigh(ctx, &tool, step, self.sampling_at(step), self.pixel_at(step), 1)?;
        let Some(Levels { tool, levels: cut, .. }) = levels.levels_to_cut(ctx, progress)? else { return Ok(Planned::default()) };
        let r = tool.cutter.radius();
        let step = levels.step(r);
        let ds = self.sampling_at(step);
        let px = self.pixel_at(step);
        let load = Load { ds, step, tolerance: self.load_tolerance, climb: self.roughing.direction == Direction::Climb };
        let pattern = match self.passes {
            Passes::Zigzag => Pattern::Zigzag,
            Passes::OneWay => Pattern::OneWay,
        };
        self.weigh(ctx, &tool, step, ds, px, cut.len())?;
        let entry = Entry { ramp_angle: self.roughing.ramp_angle, ..Entry::default() };
        let mut report = LoadReport { reference: step * tool.feed_rate, rate: step * tool.feed_rate * self.steps.stepdown, sampling: ds, ..LoadReport::default() };
        let mut path: Option<Toolpath> = None;
        let mut left_out = 0;
        let count = cut.len();
        let shortest = crate::toolpath::entry::shortest_ramp(r);
        let settings = Settings { tool: &tool, step, ds, px, load, pattern, entry, shortest };
        // The levels on every core, a batch at a time (each level's material is the stock's
        // as the operation found it, below the levels before: they do not depend on each
        // other), joined in order; progress and cancel between batches.
        let batch = crate::parallel::threads();
        for first in (0..count).step_by(batch) {
            if !progress.report(first as f64 / count as f64) {
                return Err(Error::Cancelled);
            }
            let these = &cut[first..(first + batch).min(count)];
            let ctx_now = &*ctx;
            let made = crate::parallel::map_heavy(these.len(), |k| self.level(ctx_now, &settings, &these[k]));
            for level in made {
                report.load.extend(level.load);
                report.plain.extend(level.plain);
                report.cut.extend(level.cut);
                report.slowed += level.slowed;
                left_out += level.left_out;
                ctx.warn_plunges(&self.name, &level.plunges);
                match &mut path {
                    None => path = Some(level.path),
                    Some(p) => {
                        p.moves.push(Move::Rapid { to: level.path.start });
                        p.moves.extend(level.path.moves);
                    }
                }
            }
        }
        if left_out > 0 {
            let runs = if left_out == 1 { "run" } else { "runs" };
            ctx.warn(&self.name, format!("{left_out} {runs} shorter than {shortest:.2} mm start in material where no helix fits: left uncut"));
        }
        Ok(Planned { paths: path.into_iter().collect(), load: Some(report), ..Planned::default() })
    }
}

impl RoughZigzag {
    /// Refuses, before the work, passes every `step` over the stock's area sampled every `ds`
    /// on `levels` levels that weigh the load at more than [`crate::limits::MAX_LOAD_SAMPLES`]
    /// points, or sweep more than [`crate::limits::MAX_LOAD_ROWS`] rows of the levels' maps
    /// doing it (each point sweeps the tool's disk at the pixel `px`, no finer than a level's
    /// map holds) at a sampling or pixel finer than the defaults, naming the setting (the sampling, or the tool whose step-over it follows).
    fn weigh(&self, ctx: &Context, tool: &crate::tool::Tool, step: f64, ds: f64, px: f64, levels: usize) -> Result<()> {
        let size = ctx.stock.max - ctx.stock.min;
        let points = |ds: f64| levels as f64 * size.x * size.y / (step * ds);
        let samples = points(ds);
        // Each point sweeps the tool's disk over the level's map row by row.
        let finest = (size.x * size.y / load::MOST_PIXELS).sqrt();
        let rows = |px: f64| tool.cutter.diameter / px.max(finest);
        let work = samples * rows(px);
        // The defaults' own work grows with the part, which the levels' limits bound; only a
        // sampling or pixel set finer than theirs is held to this one.
        let plain = points(0.5 * step) * rows(load::default_pixel(step));
        if samples <= crate::limits::MAX_LOAD_SAMPLES && work <= crate::limits::MAX_LOAD_ROWS.max(plain) {
            return Ok(());
        }
        let why = match self.sampling {
            Some(s) => format!("a sampling of {} mm", crate::limits::shown(s)),
            None => format!("the φ{} tool's step-over of {} mm (sampled every {} mm)", tool.cutter.diameter, crate::limits::shown(step), crate::limits::shown(ds)),
        };
        let over = if levels == 1 { "a level".to_string() } else { format!("{levels} levels") };
        let most = if samples > crate::limits::MAX_LOAD_SAMPLES {
            format!("at most {:.0} million", crate::limits::MAX_LOAD_SAMPLES / 1e6)
        } else {
            format!("each sweeping the tool's {:.0} rows of {} mm pixels: at most {:.0} million rows in all", rows(px), (px.max(finest) * 1e4).round() / 1e4, crate::limits::MAX_LOAD_ROWS / 1e6)
        };
        Err(Error::operation(
            &self.name,
            format!(
                "{why} weighs the load at about {} million points over {over} of the {:.0} × {:.0} mm stock ({most}): choose a coarser sampling or pixel, or a larger tool, or check the part's units",
                crate::limits::shown((samples / 1e4).round() / 100.0),
                size.x,
                size.y,
            ),
        ))
    }
}

/// The coarsest pixel of the load's map, as a share of the step-over (the default's is 1/24).
const COARSEST_PIXEL: f64 = 1.0 / 8.0;

/// Whether a run is shorter than `least` (mm).
fn too_short(run: &[DVec2], least: f64) -> bool {
    run.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>() < least
}

/// The region's loops as closed runs (points within `chord` of them), climbing: outer loops
/// counter-clockwise, holes clockwise, as the region holds them; each starts at its point
/// nearest `near`.
fn boundary_runs(region: &Shape, climb: bool, chord: f64, near: DVec2) -> Vec<Vec<DVec2>> {
    region
        .loops
        .iter()
        .map(|l| {
            let l = if climb { l.clone() } else { l.reversed() };
            let mut pts = Vec::new();
            for seg in start_nearest(&l, near) {
                along_boundary(&seg, chord, &mut pts);
            }
            if let Some(&p) = pts.first() {
                pts.push(p);
            }
            pts
        })
        .collect()
}
