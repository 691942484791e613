//! Octree multi-tool roughing (seed 000, DESIGN.md idea 4): the machine chooses the roughing
//! tools from the library, biggest first, by subdividing the volume to remove
//! ([`crate::octree`]) and matching tools to the octants.
//!
//! 1. **The first tool** (§3.2 (1)–(4)): the tools sorted by diameter, the largest whose octree
//!    (squares of side `d = 0.85 D` from the smallest root `d · 2^n` over the stock, layers of
//!    the axial depth `h = δ D`) has Full octants it can enter.
//! 2. **A stage** (§3.3): at each layer from the top, the octants the tool cuts (the Full ones
//!    it can enter, under octants cut above) limit the region its centre may occupy there
//!    (the exact region of [`crate::zmap::contour`]: the squares are where the tool may go,
//!    the region's boundary where it may go exactly), which is cleared by rings inside-out,
//!    entered by the shared helix or ramp or from the air beside it, at the step-over (the
//!    paper's `0.85 D`, the widest step that leaves no island where boundaries meet at 90°,
//!    Fig. 13), with the level machinery ([`LevelRoughing::clear`]). Its moves then
//!    cut the in-process stock, so the next stage classifies against the stock as simulated
//!    (the paper's open problem of Fig. 21: a round tool leaves the square octants' corners,
//!    and the next tool meets them as material, not as a surprise).
//! 3. **Later tools** (§3.2, last paragraph): one more subdivision halves the squares; the tool
//!    matched to them is the largest smaller one with `0.5 <= γ = d / D <= 0.95` whose newly
//!    Full octants it can enter; where none matches, the squares are halved again.
//! 4. **The stop test** (§3.4): subdividing stops when the current tool reaches, at every level,
//!    all the material that the smallest tool could remove (the paper offsets the part's slices
//!    by the tool's radius and looks for self-intersection: a tool that fits every slice leaves
//!    nothing a smaller one could reach); where the subdivision runs out of tools first, the
//!    largest tool that passes the test is taken.
//! 5. **Profiling** (§3.4): that tool clears what is left at its own levels (every step-down and
//!    every flat, z-level rest roughing), so the material left is the allowance plus the
//!    stair-step between its levels.
//! 6. **The rest** (not in the paper): where the stop test hands the profile to a tool smaller
//!    than the last stage's, that tool would follow the whole part again at its own fine levels
//!    to reach a few slots and corners (issue 38: the smallest tool's profile took 60–90 % of
//!    the time for 1–14 % of the volume). Instead the largest tool between them whose levels
//!    leave steps no higher than 2 mm (`TERRACES`, or than the smaller's would) profiles, and the
//!    smaller goes, at its own levels, only where the material left is out of that one's reach
//!    and within its own. A tool matched to halved octants whose levels are that fine profiles
//!    at once, its octants being part of what it profiles.
//!
//! One program with a tool change per stage; the report says which tools were chosen and why
//! (octant side, γ, the entry test), and per stage the area cleared, the volume removed and the
//! machine time; the page draws each stage's octants.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::cutter::Shape;
use crate::error::{Error, Result};
use crate::geom::tolerance::FLOAT_SLACK;
use crate::machining::levels::LevelRoughing;
use crate::machining::report::{StageOctants, StageReport, StageRole};
use crate::machining::settings::{Order, Roughing, Steps};
use crate::machining::{positive, too_many, Context, FieldError, Operate, Planned, Works, MAX_LEVELS};
use crate::octree::{Octree, Squares, Volume, GAMMA_FIRST, GAMMA_RANGE};
use crate::progress::Progress;
use crate::sim::program::{program_moves, ProgramMove};
use crate::tool::Tool;
use crate::toolpath::Toolpath;
use crate::zmap::distance::{distance_within, near_any};
use crate::zmap::surface::ClSurface;
use crate::zmap::HeightField;

/// The thinnest axial depth of cut, as a fraction of the diameter (δ): a hundredth.
const LEAST_DELTA: f64 = 0.01;
/// Octree multi-tool roughing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct RoughOctree {
    /// Default value: "octree rough".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// The tools it may choose from, by number. Default value: empty, meaning every flat and
    /// bull-nose end in the job's library.
    pub tools: Vec<u32>,
    /// Axial depth of cut as a fraction of each tool's diameter (seed 000's δ = h / D), at least
    /// 0.01 and never more than the tool's flute length. Default value: 0.25.
    pub delta: f64,
    /// Distance between rings after the first as a fraction of the tool's diameter, at most
    /// 0.85 (seed 000 §3.3: wider steps leave islands where boundaries meet at 90°). The paper's
    /// regions are unions of square octants; here they follow the part, and rings more than
    /// the tool's radius apart can leave strips where a region narrows
    /// ([`crate::machining::rings::rings`]), so the default is the widest that never does. Default
    /// value: 0.5.
    pub stepover_fraction: f64,
    #[serde(flatten)]
    #[ts(flatten)]
    pub roughing: Roughing,
}

impl Default for RoughOctree {
    fn default() -> Self {
        RoughOctree { name: "octree rough".into(), enabled: true, tools: Vec::new(), delta: 0.25, stepover_fraction: 0.5, roughing: Roughing::default() }
    }
}

/// Steps higher than this (mm) that the last stage leaves on slopes are warned of: a finishing
/// ball meeting more than 2 mm of stock at a step is a finishing pass doing roughing's work.
const TERRACES: f64 = 2.0;

/// Boxes kept per stage for the view.
const VIEW_BOXES: usize = 20_000;
/// Levels sampled by the stop test at most.
const REACH_LEVELS: usize = 24;

impl Operate for RoughOctree {
    fn plans_round_fixtures(&self) -> bool {
        true
    }
    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm};
        let mut fields = vec![
            F::name(),
            F::ints("tools", "Tools it may use", "numbers, with commas").empty("every flat and bull-nose end"),
            F::number("delta", "Step-down", U::None)
                .note("× each tool's diameter")
                .range(0.01, None)
                .help("Each tool steps down this many times its own diameter (0.5: a φ10 steps 5 mm, a φ4 steps 2 mm)."),
            F::fraction("stepoverFraction", "Step-over", "fraction of the diameter, at most 0.85", 0.85),
        ];
        fields.extend(Roughing::fields());
        OperationForm::new("rough with several tools (picks them)", fields)
            .hint("Picks its tools from the library: the largest that gets into the material goes first, smaller ones clear what it left, and the last takes what remains around the part. After a larger tool of another operation, with rest roughing on (the default), it cuts only what that tool left.")
    }

    fn name(&self) -> &str {
        &self.name
    }

    /// The first tool listed (0 when it may choose from the whole library).
    fn tool(&self) -> u32 {
        self.tools.first().copied().unwrap_or(0)
    }

    fn tools(&self) -> Vec<u32> {
        self.tools.clone()
    }

    fn enabled(&self) -> bool {
        self.enabled
    }

    fn works(&self) -> Works {
        Works::OnPart
    }

    fn allowance(&self) -> f64 {
        self.roughing.allowance()
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("delta", self.delta)?;
        if self.delta < LEAST_DELTA {
            return Err(FieldError {
                field: "delta",
                message: format!("is at least {LEAST_DELTA} of the diameter: a thinner cut rubs rather than cuts, and takes thousands of levels (got {})", crate::limits::shown(self.delta)),
            });
        }
        crate::machining::fraction("stepoverFraction", self.stepover_fraction)?;
        if self.stepover_fraction > 0.85 {
            return Err(FieldError { field: "stepoverFraction", message: format!("is at most 0.85 of the diameter: wider steps leave islands between rings (got {})", self.stepover_fraction) });
        }
        self.roughing.validate()
    }

    fn check_scale(&self, ctx: &Context) -> Result<()> {
        // The smallest tool's layers are the most.
        let height = ctx.stock.max.z - ctx.stock.min.z;
        let candidates = self.candidates(ctx)?;
        if let Some(t) = candidates.last() {
            too_many(&self.name, "levels", height / self.depth(t), MAX_LEVELS, &format!("δ = {}: the φ{} tool's depth of cut of", self.delta, t.cutter.diameter), self.depth(t), height)?;
        }
        // Each tool's levels read the level map; their rings are weighed as they are cut.
        candidates.iter().try_for_each(|t| self.zlevel(t, false).check_scale(ctx))
    }

    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned> {
        let candidates = self.candidates(ctx)?;
        // The stages cut a copy of the in-process stock as they go; the job then cuts the real
        // one with the whole operation, as it does for every operation.
        let before = ctx.sim.clone();
        let result = self.stages(ctx, &candidates, progress);
        progress.leave();
        ctx.sim = before;
        let (paths, stages, octants) = result?;
        Ok(Planned { paths, stages: Some(stages), octants, ..Planned::default() })
    }
}

/// The stages' paths, reports and octants.
type Stages = (Vec<Toolpath>, Vec<StageReport>, Vec<StageOctants>);

impl RoughOctree {
    /// The tools it may choose from, largest first.
    fn candidates(&self, ctx: &Context) -> Result<Vec<Tool>> {
        let mut tools: Vec<Tool> = if self.tools.is_empty() {
            ctx.tools.iter().filter(|t| matches!(t.cutter.shape, Shape::Flat | Shape::BullNose)).cloned().collect()
        } else {
            self.tools.iter().map(|&n| ctx.tool(&self.name, n).cloned()).collect::<Result<_>>()?
        };
        if tools.is_empty() {
            return Err(Error::operation(&self.name, "the tool library has no flat or bull-nose end to rough with"));
        }
        crate::geom::sort::sort_by_float(&mut tools, |a| -a.cutter.diameter);
        tools.dedup_by(|a, b| a.cutter.diameter == b.cutter.diameter);
        Ok(tools)
    }

    /// The z-level settings a stage of `tool` cuts with: its axial depth, this operation's
    /// allowances and step-over; `flats` for profiling.
    fn zlevel(&self, tool: &Tool, flats: bool) -> LevelRoughing {
        // The profiling stage (`flats`) cuts what is left region by region, each down to its
        // floor before the next, so the tool travels between the rest regions once rather than
        // once per level; the octant stages cut layer by layer, as seed 000 does.
        let order = if flats { Order::Regions } else { Order::Levels };
        LevelRoughing { flats, order, ..LevelRoughing::new(&self.name, tool.number, Steps { stepdown: self.depth(tool), stepover_fraction: self.stepover_fraction }, &self.roughing) }
    }

    /// The axial depth of cut for `tool` (mm).
    pub fn depth(&self, tool: &Tool) -> f64 {
        (self.delta * tool.cutter.diameter).min(tool.cutter.flute_length)
    }

    /// The octree of `tool` over `squares`, classified against the in-process stock.
    fn octree(&self, ctx: &mut Context, tool: &Tool, squares: Squares, progress: &mut Progress) -> Result<Octree> {
        let zl = self.zlevel(tool, true);
        let (_, cl) = zl.surface(ctx, progress)?;
        let heights = zl.heights(ctx, &cl, tool.cutter.radius());
        let tops = std::iter::once(ctx.stock.max.z).chain(heights.iter().copied());
        let layers: Vec<(f64, f64)> = heights.iter().copied().zip(tops).collect();
        let stock = ctx.sim.stock().heights();
        let part = ctx.cc_zmap(stock.grid(), f64::NEG_INFINITY);
        let volume = Volume { stock: &stock, part: &part, allowance: self.roughing.allowance, tolerance: ctx.tolerances.gouge };
        Ok(Octree::classify(squares, &layers, &cl.field, tool.cutter.radius(), &volume))
    }

    /// Cuts the octants `tree` marks with `tool` (one stage), then cuts the in-process stock
    /// with it; `None` where no level holds them.
    fn cut(&self, ctx: &mut Context, tool: &Tool, tree: &Octree, progress: &mut Progress) -> Result<Option<(Toolpath, Cut)>> {
        let zl = self.zlevel(tool, true);
        let (stock, tol) = (ctx.sim.stock().heights(), ctx.tolerances.gouge);
        let r = tool.cutter.radius();
        let centres: std::sync::OnceLock<Vec<Vec<bool>>> = std::sync::OnceLock::new();
        let within = |z: f64, grid: crate::zmap::Grid| {
            let all = centres.get_or_init(|| tree.centres(grid, r, &stock, tol));
            Some(tree.layer_at(z, FLOAT_SLACK).map_or_else(|| vec![false; grid.nodes()], |k| all[k].clone()))
        };
        let Some(levels) = zl.levels_within(ctx, progress, r, false, &within)? else { return Ok(None) };
        let path = zl.clear(ctx, levels, progress)?;
        let cut = advance(ctx, &path, progress)?;
        Ok(Some((path, cut)))
    }

    /// Every stage, in order: the paths, their reports and their octants.
    fn stages(&self, ctx: &mut Context, candidates: &[Tool], progress: &mut Progress) -> Result<Stages> {
        let (lo, hi) = (ctx.stock.min.truncate(), ctx.stock.max.truncate());
        let mut paths = Vec::new();
        let mut reports = Vec::new();
        let mut views = Vec::new();
        let count = candidates.len() as f64 + 1.0;
        let stage_progress = |progress: &mut Progress, k: f64, name: &str| progress.enter(name, (k / count).min(0.95), 1.0 / count);

        // §3.2: the first tool.
        let mut first = None;
        let mut empty = true;
        for (k, tool) in candidates.iter().enumerate() {
            if !stage_progress(progress, k as f64 * 0.2, &format!("octree φ{}", tool.cutter.diameter)) {
                return Err(Error::Cancelled);
            }
            let squares = Squares::root(lo, hi, GAMMA_FIRST * tool.cutter.diameter);
            let tree = self.octree(ctx, tool, squares, progress)?;
            empty &= tree.layers.iter().all(|l| l.state.iter().all(|&s| s == crate::octree::State::Empty));
            if tree.cuts() {
                first = Some((k, tree));
                break;
            }
        }
        let Some((mut current, tree)) = first else {
            if empty {
                ctx.note(&self.name, "no material is left to rough");
                return Ok((paths, reports, views));
            }
            // No tool can clear a whole block anywhere (the blocks are partly part wherever
            // there is material, as on a shallow mould insert): the largest tool that reaches
            // all the smallest would takes what it can in levels, as z-level roughing would,
            // rather than nothing at all.
            let mut k = 0;
            while k + 1 < candidates.len() && !self.reaches_all(ctx, &candidates[k], &candidates[k + 1..], progress)? {
                k += 1;
            }
            let why = format!(
                "no tool clears a whole block of the material anywhere (blocks of {:.2} mm and less are partly part everywhere), so the largest tool that reaches all the smallest would takes it in {:.2} mm levels",
                GAMMA_FIRST * candidates[k].cutter.diameter,
                self.depth(&candidates[k])
            );
            self.profile(ctx, &candidates[k], why, count, &mut paths, &mut reports, progress)?;
            if paths.is_empty() {
                return Err(self.nothing_enters(ctx, candidates, progress));
            }
            return Ok((paths, reports, views));
        };
        let tool = &candidates[current];
        let mut squares = tree.squares;
        views.push(StageOctants { stage: 0, tool: tool.number, boxes: tree.boxes(VIEW_BOXES) });
        // (§3.1: octants of side γ D, the octree's root that side times 2^depth.)
        let why = format!(
            "the largest tool that gets into the material to remove: it clears blocks of {1:.2} mm, {0:.0} mm² of them summed over its {2} levels, going in from the air or by a helix",
            tree.cut_area(),
            squares.side,
            tree.layers.iter().filter(|l| l.cut.iter().any(|&c| c)).count(),
        );
        if let Some((path, cut)) = self.cut(ctx, tool, &tree, progress)? {
            paths.push(path);
            reports.push(self.report(tool, StageRole::First, Some((squares.side, GAMMA_FIRST)), why, cut));
        }

        // §3.2 and §3.4: later tools, until one reaches everything the smallest would.
        let mut profiler = None;
        while profiler.is_none() {
            let tool = &candidates[current];
            if !stage_progress(progress, current as f64 + 0.5, &format!("stop test φ{}", tool.cutter.diameter)) {
                return Err(Error::Cancelled);
            }
            if self.reaches_all(ctx, tool, &candidates[current + 1..], progress)? {
                profiler = Some((current, format!("it reaches at every level all the material a smaller tool would, so it takes what is left around the part in {:.2} mm levels", self.depth(tool))));
                break;
            }
            squares = squares.halved();
            let smallest = candidates.last().expect("at least one candidate").cutter.diameter;
            if squares.side / smallest < GAMMA_RANGE.0 {
                // No tool matches smaller octants: the largest tool that reaches what the
                // smallest would profiles.
                let mut k = current + 1;
                while k + 1 < candidates.len() && !self.reaches_all(ctx, &candidates[k], &candidates[k + 1..], progress)? {
                    k += 1;
                }
                let k = k.min(candidates.len() - 1);
                profiler = Some((
                    k,
                    format!(
                        "no smaller tool fits the blocks left; it reaches all the material the smallest would, and takes what is left around the part in {:.2} mm levels",
                        self.depth(&candidates[k])
                    ),
                ));
                break;
            }
            for k in current + 1..candidates.len() {
                let t = &candidates[k];
                let gamma = squares.side / t.cutter.diameter;
                if !(GAMMA_RANGE.0..=GAMMA_RANGE.1).contains(&gamma) {
                    continue;
                }
                if k + 1 == candidates.len() || self.depth(t) <= TERRACES {
                    // The smallest tool passes the stop test by itself, and a tool whose levels
                    // leave no steps to speak of will profile whatever the stop test says (see
                    // below): it profiles at once (its octants would be cut again by the
                    // profiling).
                    let which = if k + 1 == candidates.len() { "the smallest tool" } else { "a tool fine enough to take the steps between levels" };
                    profiler = Some((
                        k,
                        format!(
                            "{which}, sized for the {:.2} mm blocks the larger tools left ({:.0} % of its diameter): it takes everything left that it can reach around the part in {:.2} mm levels",
                            squares.side,
                            gamma * 100.0,
                            self.depth(t)
                        ),
                    ));
                    break;
                }
                if !stage_progress(progress, k as f64, &format!("octree φ{}", t.cutter.diameter)) {
                    return Err(Error::Cancelled);
                }
                let tree = self.octree(ctx, t, squares, progress)?;
                if !tree.cuts() {
                    continue;
                }
                // (§3.2: the newly Full octants of the subdivision, γ = side / D within 0.5 to 0.95.)
                let why = format!(
                    "sized for the {:.2} mm blocks the larger tools left ({:.0} % of its diameter): it clears {:.0} mm² of them summed over its levels",
                    squares.side,
                    gamma * 100.0,
                    tree.cut_area()
                );
                views.push(StageOctants { stage: reports.len(), tool: t.number, boxes: tree.boxes(VIEW_BOXES) });
                if let Some((path, cut)) = self.cut(ctx, t, &tree, progress)? {
                    paths.push(path);
                    reports.push(self.report(t, StageRole::Octants, Some((squares.side, gamma)), why, cut));
                }
                current = k;
                break;
            }
        }

        // §3.4: profiling. Where the stop test hands it to a smaller tool than the last stage's,
        // that tool would follow the whole part again at its own fine levels to reach a few
        // slots and corners: the largest tool between them that leaves steps no higher than it
        // would (or than [`TERRACES`]) profiles, and the smaller tools go only where that one
        // cannot reach.
        let (k, why) = profiler.expect("the loop ends with a profiling tool");
        let fine = TERRACES.max(self.depth(&candidates[k]));
        let p = (current..k).find(|&p| self.depth(&candidates[p]) <= fine).unwrap_or(k);
        let why =
            if p == k { why } else { format!("it takes everything left that it can reach around the part in {:.2} mm levels; the smaller tools go only where it cannot", self.depth(&candidates[p])) };
        let (from, before) = (reports.len(), ctx.sim.clone());
        self.profile(ctx, &candidates[p], why, count, &mut paths, &mut reports, progress)?;
        let Some(r) = self.rest(ctx, candidates, p, count, &mut paths, &mut reports, progress)? else { return Ok((paths, reports, views)) };
        // The paper's way too, the quicker kept: where little is left but corners (a square
        // pocket after one large tool), the small tool round everything beats the larger one
        // and then the small one corner by corner.
        let seconds = |stages: &[StageReport]| stages.iter().map(|s| s.seconds).sum::<f64>();
        let (with_rest, with_rest_paths, with_rest_sim) = (reports.split_off(from), paths.split_off(from), std::mem::replace(&mut ctx.sim, before));
        let small = &candidates[r];
        // Its path's time first: the stock is cut with it only where it is the quicker.
        let round = self.profile_path(ctx, small, count, progress)?;
        let moves = round.as_ref().map(|path| moves_of(ctx, path)).transpose()?;
        let (a, b) = (seconds(&with_rest), moves.as_ref().map_or(f64::INFINITY, |moves| moves.iter().map(|m| m.seconds).sum()));
        let (p_d, r_d) = (candidates[p].cutter.diameter, small.cutter.diameter);
        if let (Some(path), Some(moves), true) = (round, moves, a >= b) {
            let cut = cut_with(ctx, &moves, progress)?;
            paths.push(path);
            let why = format!(
                "it takes everything left around the part in {:.2} mm levels (quicker than the φ{p_d} round everything and then the φ{r_d} only where it cannot reach: {b:.0} s against {a:.0} s)",
                self.depth(small)
            );
            reports.push(self.report(small, StageRole::Profile, None, why, cut));
        } else {
            reports.extend(with_rest);
            paths.extend(with_rest_paths);
            ctx.sim = with_rest_sim;
            // (Said of the rest's first stage, where it made one.)
            if let Some(first) = reports.get_mut(from).filter(|_| b.is_finite()) {
                first.why += &format!(" (it and then the φ{r_d} only where it cannot reach: {a:.0} s, against {b:.0} s for the φ{r_d} round everything)");
            }
        }
        Ok((paths, reports, views))
    }

    /// The profiling stage (§3.4): `tool` takes what is left at its own levels (every
    /// step-down and every flat).
    fn profile(&self, ctx: &mut Context, tool: &Tool, why: String, count: f64, paths: &mut Vec<Toolpath>, reports: &mut Vec<StageReport>, progress: &mut Progress) -> Result<()> {
        if let Some(path) = self.profile_path(ctx, tool, count, progress)? {
            let cut = advance(ctx, &path, progress)?;
            paths.push(path);
            reports.push(self.report(tool, StageRole::Profile, None, why, cut));
        }
        Ok(())
    }

    /// The profiling stage's path, before it cuts the stock (none where no level holds
    /// anything to cut).
    fn profile_path(&self, ctx: &mut Context, tool: &Tool, count: f64, progress: &mut Progress) -> Result<Option<Toolpath>> {
        if !progress.enter(&format!("profile φ{}", tool.cutter.diameter), ((count - 1.0) / count).min(0.95), 1.0 / count) {
            return Err(Error::Cancelled);
        }
        let zl = self.zlevel(tool, true);
        // Every centre whose cutter touches what is left: rest material reachable only by the
        // cutter's side (a round tool's corner left by a bigger one) is cut from its top down
        // like the rest, never met by the side of a deeper pass.
        let path = match zl.levels_within(ctx, progress, tool.cutter.radius(), false, &|_, _| None)? {
            Some(levels) => Some(zl.clear(ctx, levels, progress)?),
            None => None,
        };
        let depth = self.depth(tool);
        if depth > TERRACES {
            ctx.warn(
                &self.name,
                format!("its last tool, φ{}, cuts levels {depth:.2} mm apart: on slopes it leaves steps up to that high for the next operation to meet (a smaller δ, or a z-level roughing at a smaller step-down before finishing, takes them)", tool.cutter.diameter),
            );
        }
        Ok(path)
    }

    fn report(&self, tool: &Tool, role: StageRole, octants: Option<(f64, f64)>, why: String, cut: Cut) -> StageReport {
        StageReport {
            tool: tool.number,
            diameter: tool.cutter.diameter,
            role,
            side: octants.map(|o| o.0),
            gamma: octants.map(|o| o.1),
            depth: self.depth(tool),
            why,
            area: cut.area,
            removed: cut.removed,
            seconds: cut.seconds,
        }
    }

    /// The stop test (§3.4): whether `tool` reaches, at the smallest tool's levels, all the
    /// material left that the smallest of `smaller` would (no more than four stock cells at
    /// any level, for the grids' rounding).
    fn reaches_all(&self, ctx: &mut Context, tool: &Tool, smaller: &[Tool], progress: &mut Progress) -> Result<bool> {
        let Some(small) = smaller.last() else { return Ok(true) };
        let reach = Reach::new(self, ctx, tool, small, progress)?;
        let mut levels = self.zlevel(small, false).heights(ctx, &reach.cl_small, small.cutter.radius());
        if levels.len() > REACH_LEVELS {
            let n = levels.len();
            levels = (0..REACH_LEVELS).map(|k| levels[k * (n - 1) / (REACH_LEVELS - 1)]).collect();
        }
        let cell = reach.stock.spacing * reach.stock.spacing;
        // More than a few cells: grid rounding aside, material the smaller tool would remove.
        let limit = 4.0 * cell;
        Ok(levels.into_iter().all(|z| reach.missed(z).len() as f64 * cell <= limit))
    }

    /// The rest after `candidates[p]` profiled: the largest smaller tool that reaches what the
    /// smallest would goes, at its own levels, only where the material left is out of
    /// `candidates[p]`'s reach and within its own (a slot or a corner narrower than it); none
    /// when nothing is. Which tool, when one is needed.
    #[allow(clippy::too_many_arguments)]
    fn rest(&self, ctx: &mut Context, candidates: &[Tool], p: usize, count: f64, paths: &mut Vec<Toolpath>, reports: &mut Vec<StageReport>, progress: &mut Progress) -> Result<Option<usize>> {
        if p + 1 >= candidates.len() || self.reaches_all(ctx, &candidates[p], &candidates[p + 1..], progress)? {
            return Ok(None);
        }
        let mut r = p + 1;
        while r + 1 < candidates.len() && !self.reaches_all(ctx, &candidates[r], &candidates[r + 1..], progress)? {
            r += 1;
        }
        let (big, small) = (&candidates[p], &candidates[r]);
        if !progress.stage(&format!("rest φ{}", small.cutter.diameter), ((count - 0.5) / count).min(0.97), 0.5 / count) {
            return Err(Error::Cancelled);
        }
        let reach = Reach::new(self, ctx, big, small, progress)?;
        let sg = reach.stock.grid();
        let radius = small.cutter.radius();
        // Centres within the small tool's radius (and a cell, for the grids' rounding) of
        // material only it reaches: a few cells of the stock's, whose discs are marked (none
        // at most levels).
        let within = |z: f64, grid: crate::zmap::Grid| {
            let missed = reach.missed(z);
            if missed.is_empty() {
                return Some(vec![false; grid.nodes()]);
            }
            let near = near_any(&missed, sg.nx, sg.ny, sg.spacing, radius + sg.spacing);
            Some((0..grid.nodes()).map(|n| sg.nearest(grid.node(n % grid.nx, n / grid.nx)).is_some_and(|c| near[c])).collect())
        };
        let zl = self.zlevel(small, true);
        if let Some(levels) = zl.levels_within(ctx, progress, radius, false, &within)? {
            let path = zl.clear(ctx, levels, progress)?;
            let cut = advance(ctx, &path, progress)?;
            paths.push(path);
            let why = format!("only where the material left is out of the φ{}'s reach (slots and corners narrower than it), in {:.2} mm levels", big.cutter.diameter, self.depth(small));
            reports.push(self.report(small, StageRole::Rest, None, why, cut));
        }
        Ok(Some(r))
    }

    /// The error when no tool of the library can enter the volume anywhere: names the largest
    /// flat end, halving from the smallest in the library, that would.
    fn nothing_enters(&self, ctx: &mut Context, candidates: &[Tool], progress: &mut Progress) -> Error {
        let smallest = candidates.last().expect("at least one candidate");
        let (lo, hi) = (ctx.stock.min.truncate(), ctx.stock.max.truncate());
        let mut d = smallest.cutter.diameter / 2.0;
        let number = ctx.tools.iter().map(|t| t.number).max().unwrap_or(0) + 1;
        let mut would = None;
        while d >= 0.5 && would.is_none() {
            let mut t = smallest.clone();
            t.number = number;
            t.cutter = crate::cutter::Cutter { shape: Shape::Flat, diameter: d, ..smallest.cutter.clone() };
            ctx.tools.push(t.clone());
            let tree = self.octree(ctx, &t, Squares::root(lo, hi, GAMMA_FIRST * d), progress);
            ctx.tools.pop();
            if tree.is_ok_and(|tree| tree.cuts()) {
                would = Some(d);
            }
            d /= 2.0;
        }
        let why = match would {
            Some(d) => format!(
                "no tool of the library can enter the volume to remove anywhere (the smallest, φ{}, finds no octants of {:.2} mm it can clear and reach); a φ{d} flat end would",
                smallest.cutter.diameter,
                GAMMA_FIRST * smallest.cutter.diameter
            ),
            None => format!("no tool of the library can enter the volume to remove anywhere (the smallest is φ{}); not even a φ0.5 flat end would", smallest.cutter.diameter),
        };
        Error::operation(&self.name, why)
    }
}

/// What one stage's moves did to the in-process stock.
struct Cut {
    area: f64,
    removed: f64,
    seconds: f64,
}

/// Cuts the in-process stock with `path` and says what it did.
fn advance(ctx: &mut Context, path: &Toolpath, progress: &mut Progress) -> Result<Cut> {
    let moves = moves_of(ctx, path)?;
    cut_with(ctx, &moves, progress)
}

/// One stage's `path` as the program's moves, timed.
fn moves_of(ctx: &Context, path: &Toolpath) -> Result<Vec<ProgramMove>> {
    program_moves(std::slice::from_ref(path), &ctx.tools, ctx.rapids, ctx.air_feed)
}

/// Cuts the in-process stock with a path's `moves` and says what they did.
fn cut_with(ctx: &mut Context, moves: &[ProgramMove], progress: &mut Progress) -> Result<Cut> {
    let before = ctx.sim.stock().heights();
    let first = ctx.sim.volumes().len();
    ctx.sim.run(moves, &ctx.tolerances, progress, 1.0)?;
    let removed = ctx.sim.volumes()[first..].iter().sum();
    let after = ctx.sim.stock().heights();
    let lowered = before.z.iter().zip(&after.z).filter(|(b, a)| *b - *a > ctx.tolerances.gouge).count();
    Ok(Cut { area: lowered as f64 * before.spacing * before.spacing, removed, seconds: moves.iter().map(|m| m.seconds).sum() })
}

/// What a larger and a smaller tool reach of the material left: the stop test's and the rest
/// stage's question.
struct Reach {
    cl_big: Arc<ClSurface>,
    cl_small: Arc<ClSurface>,
    r_big: f64,
    r_small: f64,
    stock: HeightField,
    part: Arc<HeightField>,
    allowance: f64,
    tolerance: f64,
}

impl Reach {
    fn new(op: &RoughOctree, ctx: &mut Context, big: &Tool, small: &Tool, progress: &mut Progress) -> Result<Reach> {
        let (_, cl_big) = op.zlevel(big, false).surface(ctx, progress)?;
        let (_, cl_small) = op.zlevel(small, false).surface(ctx, progress)?;
        let stock = ctx.sim.stock().heights();
        let part = ctx.cc_zmap(stock.grid(), f64::NEG_INFINITY);
        let r_big = big.cutter.radius() + cl_big.field.spacing;
        Ok(Reach { cl_big, cl_small, r_big, r_small: small.cutter.radius(), stock, part, allowance: op.roughing.allowance, tolerance: ctx.tolerances.gouge })
    }

    /// The stock's cells that hold material at level `z` the small tool reaches and the big one
    /// does not, in order.
    fn missed(&self, z: f64) -> Vec<usize> {
        let (a, tol) = (self.allowance, self.tolerance);
        // Per node of a CL z-map, the distance to the nearest centre the tool may take at `z`.
        // (Only whether it is within the tool's radius is asked: no farther is worked out.)
        let reach = |cl: &ClSurface, radius: f64| {
            let f = &cl.field;
            let safe: Vec<bool> = f.z.iter().map(|&h| h + a <= z).collect();
            distance_within(&safe, f.nx, f.ny, f.spacing, radius)
        };
        let sg = self.stock.grid();
        let material: Vec<usize> = (0..sg.nodes()).filter(|&c| self.stock.z[c] - z.max(self.part.z[c] + a) > tol).collect();
        if material.is_empty() {
            return material;
        }
        let (big, little) = (reach(&self.cl_big, self.r_big), reach(&self.cl_small, self.r_small));
        material
            .into_iter()
            .filter(|&c| {
                let p = sg.node(c % sg.nx, c / sg.nx);
                at(self.cl_small.field.grid(), &little, p) <= self.r_small && at(self.cl_big.field.grid(), &big, p) > self.r_big
            })
            .collect()
    }
}

/// A grid's value `d` at its node nearest `p` (+∞ off the grid).
fn at(g: crate::zmap::Grid, d: &[f64], p: crate::geom::DVec2) -> f64 {
    g.nearest(p).map_or(f64::INFINITY, |c| d[c])
}
