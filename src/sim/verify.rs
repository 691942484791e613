//! Verification of a program by simulating it on a z-map stock (seed 002's conventional model,
//! whose cell centres are sampled exactly, so a gouge it reports is a real one at that point).
//!
//! * **Gouge**: after the program, no cell's material lies below the part's own surface (its CC
//!   z-map at the cell centre, not the CL surface) plus the allowance the operations promised,
//!   by more than [`Tolerances::gouge`].
//! * **Rapid collision**: a rapid move that removes material, or a feed move at the air feed
//!   (faster than its tool's feed: its operation knew it to cut nothing) that does.
//! * **Body collision**: a feed move with material standing higher above the tip than the
//!   cutter's flute length within the shank's radius: the unfluted body would rub it.
//! * **Holder collision**: a feed move with material within a section of the tool's holder
//!   ([`crate::tool::Holder::rings`]) above that section's bottom.
//! * **Residual**: material left above part + allowance, as a map, its largest and mean value.

use serde::Serialize;

use super::dexel::DexelStock;
use super::program::{removal_rates, ProgramMove, Timing, RATE_CELLS};
use super::sweep::Sweep;
use super::StockModel;
use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec2, DVec3, Tolerances};
use crate::mesh::Mesh;
use crate::progress::Progress;
use crate::zmap::{cc::cc_zmap, Grid, HeightField, MAX_NODES};
use std::sync::atomic::{AtomicBool, Ordering};

/// Rapid moves removing less than this (mm³) only grazed the stock's surface.
const GRAZE: f64 = 1e-6;
/// Problems of each kind kept with their place (the rest are counted).
const KEPT: usize = 50;

/// How to verify.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VerifySettings {
    /// Cell size of the simulated stock (mm).
    pub cell: f64,
    /// Material the program promised to leave on the part (mm).
    pub allowance: f64,
}

/// A place where something went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Finding {
    /// Index of the move (in program order), when a move is to blame.
    pub move_index: Option<usize>,
    #[ts(type = "[number, number, number]")]
    pub at: DVec3,
    /// Gouge depth, collision depth (mm), or the volume a rapid cut (mm³).
    pub amount: f64,
}

/// A move into a fixture's clearance: which fixture, which tool, where and how deep.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct FixtureCollision {
    pub fixture: String,
    pub tool: u32,
    pub finding: Finding,
}

impl Report {
    /// Takes in the moves found running into fixtures (`checked` of them named), the deepest
    /// first.
    pub fn fixtures(&mut self, checked: usize, mut hits: Vec<super::fixtures::FixtureHit>) {
        crate::geom::sort::sort_by_float(&mut hits, |a| -a.depth);
        self.fixtures_checked = checked;
        self.fixture_collision_count = hits.len();
        self.fixture_collisions =
            hits.into_iter().take(KEPT).map(|h| FixtureCollision { fixture: h.fixture, tool: h.tool, finding: Finding { move_index: Some(h.move_index), at: h.at, amount: h.depth } }).collect();
    }
}

/// What verification found.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Report {
    pub cells: usize,
    pub moves: usize,
    /// Volume removed by the whole program (mm³).
    pub removed: f64,
    pub gouge_count: usize,
    /// Deepest gouge (mm), 0 when none.
    pub gouge_max: f64,
    pub gouges: Vec<Finding>,
    pub rapid_collision_count: usize,
    pub rapid_collisions: Vec<Finding>,
    pub body_collision_count: usize,
    pub body_collisions: Vec<Finding>,
    /// Moves that drive the tool's holder into material (how deep past its face), where the
    /// tool has a holder.
    pub holder_collision_count: usize,
    pub holder_collisions: Vec<Finding>,
    /// Moves into what holds the stock, grown by its clearance ([`super::fixtures`]); none
    /// checked where the job names no fixtures (`fixtures_checked`).
    pub fixtures_checked: usize,
    pub fixture_collision_count: usize,
    pub fixture_collisions: Vec<FixtureCollision>,
    /// Largest and mean material above part + allowance where the part is (mm).
    pub residual_max: f64,
    pub residual_mean: f64,
    /// Largest material removal rate of the feed moves (mm³/min), each measured over
    /// [`RATE_CELLS`] cells of path ([`removal_rates`]).
    pub mrr_max: f64,
    /// The gouges on the walls of the part's round holes in a machinist's words
    /// ([`hole_overcuts`]: "φ6.4 drill (T2) in φ6.35 holes: 0.025 mm oversize on the radius").
    pub overcuts: Vec<String>,
}

impl Report {
    pub fn is_clean(&self) -> bool {
        self.gouge_count == 0 && self.rapid_collision_count == 0 && self.body_collision_count == 0 && self.holder_collision_count == 0 && self.fixture_collision_count == 0
    }

    /// What makes the program unsafe to run, in one message that says where and how deep, or
    /// `None` when verification found nothing: a gouge, a rapid move through stock, or the tool's
    /// body in material is a problem, never a note.
    pub fn problem(&self) -> Option<String> {
        let place = |f: &Finding| format!("at X{:.3} Y{:.3} Z{:.3}{}", f.at.x, f.at.y, f.at.z, f.move_index.map(|m| format!(" (move {})", m + 1)).unwrap_or_default());
        let deepest = |list: &[Finding]| list.iter().copied().max_by(|a, b| a.amount.total_cmp(&b.amount));
        let mut parts = Vec::new();
        if self.gouge_count > 0 {
            let at = deepest(&self.gouges).map(|f| format!(", deepest {}", place(&f))).unwrap_or_default();
            parts.push(format!("it gouges the part in {} cells, {:.3} mm deep at most{at}", self.gouge_count, self.gouge_max));
        }
        if self.rapid_collision_count > 0 {
            let at = self.rapid_collisions.first().map(|f| format!(", the first {}", place(f))).unwrap_or_default();
            parts.push(format!("{} rapid moves (or moves at the air feed) pass through stock{at}", self.rapid_collision_count));
        }
        if self.body_collision_count > 0 {
            let at = deepest(&self.body_collisions).map(|f| format!(", {:.3} mm past the flutes at most, {}", f.amount, place(&f))).unwrap_or_default();
            parts.push(format!("{} moves bury the tool deeper than its flute length{at}", self.body_collision_count));
        }
        if self.holder_collision_count > 0 {
            let at = deepest(&self.holder_collisions).map(|f| format!(", {:.3} mm into material at most, {}", f.amount, place(&f))).unwrap_or_default();
            parts.push(format!("{} moves drive the tool's holder into material (a longer stick-out or a slimmer holder reaches){at}", self.holder_collision_count));
        }
        if let Some(c) = self.fixture_collisions.first() {
            let inside = if c.finding.amount > 0.0 { format!("{:.3} mm into its clearance", c.finding.amount) } else { String::new() };
            parts.push(format!("{} moves run into what holds the stock: T{} into {}, {inside}, {}", self.fixture_collision_count, c.tool, c.fixture, place(&c.finding)));
        }
        // Gouges on holes' walls said as a machinist says them, before the cells.
        (!parts.is_empty()).then(|| {
            let found = format!("the simulation found problems: {}", parts.join("; "));
            if self.overcuts.is_empty() {
                found
            } else {
                format!("{}; {found}", self.overcuts.join("; "))
            }
        })
    }

    /// A few lines for a person.
    pub fn describe(&self) -> String {
        let mut s = format!("simulated {} moves on {} cells; removed {:.1} mm³, peak MRR {:.0} mm³/min\n", self.moves, self.cells, self.removed, self.mrr_max);
        let first = |list: &[Finding]| {
            list.first().map(|f| format!(", first at ({:.3}, {:.3}, {:.3}){}", f.at.x, f.at.y, f.at.z, f.move_index.map(|m| format!(" in move {}", m + 1)).unwrap_or_default())).unwrap_or_default()
        };
        s += &format!("gouges: {} (deepest {:.4} mm){}\n", self.gouge_count, self.gouge_max, first(&self.gouges));
        for o in &self.overcuts {
            s += &format!("  {o}\n");
        }
        s += &format!("rapid moves through stock: {}{}\n", self.rapid_collision_count, first(&self.rapid_collisions));
        s += &format!("tool body (above the flutes) in material: {}{}\n", self.body_collision_count, first(&self.body_collisions));
        if self.holder_collision_count > 0 {
            s += &format!("holder in material: {}{}\n", self.holder_collision_count, first(&self.holder_collisions));
        }
        if self.fixtures_checked > 0 {
            let at = self
                .fixture_collisions
                .first()
                .map(|c| format!(", the deepest into {} by {:.3} mm at ({:.3}, {:.3}, {:.3})", c.fixture, c.finding.amount, c.finding.at.x, c.finding.at.y, c.finding.at.z))
                .unwrap_or_default();
            s += &format!("moves into the {} fixtures' clearance: {}{at}\n", self.fixtures_checked, self.fixture_collision_count);
        }
        s += &format!("material left on the part: max {:.3} mm, mean {:.3} mm\n", self.residual_max, self.residual_mean);
        s
    }
}

/// Everything verification produced: the report, the per-move volumes and the maps.
#[derive(Clone, Debug)]
pub struct Verification {
    pub report: Report,
    /// Volume removed by each move (mm³).
    pub volumes: Vec<f64>,
    /// Material removal rate of each move (mm³/min, 0 for rapids; [`removal_rates`]).
    pub rates: Vec<f64>,
    /// How near each move's path came to a cell it cut ([`DexelStock::take_nearest`]; ∞ for
    /// none): what its chip's thickness follows ([`crate::sim::feeds`]).
    pub nearest: Vec<f64>,
    pub stock: DexelStock,
    /// The stock the program started from where that was not the raw box (a bar, what the
    /// setup before left: [`Simulator::carry`]); a playback starts from it.
    pub start: Option<DexelStock>,
    /// The part's surface plus the allowance at the stock's cell centres, no higher than the raw
    /// stock's top (NaN where the part is not).
    pub part: HeightField,
    /// The part's round holes, judged as their circles (none for a drawing's sheet).
    pub holes: Vec<crate::holes::Hole>,
}

impl Verification {
    /// Says the gouges on the walls of the part's round holes in a machinist's words
    /// ([`Report::overcuts`]), with the program's `moves` (whose tool went too far out).
    pub fn word_holes(&mut self, moves: &[ProgramMove]) {
        self.report.overcuts = hole_overcuts(&self.report, &self.holes, moves);
    }

    /// Material above part + allowance per cell: negative where gouged, NaN off the part.
    pub fn residual(&self) -> HeightField {
        let mut field = self.stock.heights();
        for (z, part) in field.z.iter_mut().zip(&self.part.z) {
            *z -= part;
        }
        field
    }
}

/// The stock grid for a cell size, refused when it would not fit in memory.
pub fn stock_for(stock: &Aabb, cell: f64) -> Result<DexelStock> {
    if !(cell > 0.0 && cell.is_finite()) {
        return Err(Error::Input(format!("simulation.cell: the simulation cell must be a positive number of millimetres (got {cell})")));
    }
    let size = stock.size();
    let cells = (size.x / cell).ceil() * (size.y / cell).ceil();
    if cells > MAX_NODES as f64 {
        return Err(Error::Input(format!("simulation.cell: {cell} mm cells over this stock make {:.0} million cells; choose larger cells", cells / 1e6)));
    }
    Ok(DexelStock::new(stock, cell, 1))
}

/// Cells found cut below the part that [`Simulator::finish_near`] judges again by the part's
/// heights beside them.
pub const WALL_RECHECKS: usize = 20_000;

/// The part's lowest height (−∞ where it is absent) at `p` and at sixteen points round it at
/// the gouge tolerance: what [`Simulator::finish_near`] judges a cell beside a wall by.
pub fn lowest_near(drop: &crate::zmap::drop::PointDrop, p: DVec2, reach: f64) -> f64 {
    (0..16).map(|k| p + DVec2::from_angle(k as f64 * std::f64::consts::TAU / 16.0) * reach).chain([p]).map(|q| drop.at(q, f64::NEG_INFINITY)).fold(f64::INFINITY, f64::min)
}

/// The widest sliver between a hole's facets and its circle, as a share of its radius: the
/// sagitta of the widest gap the hole finder lets a wall leave between vertices (60°).
const SLIVER: f64 = 0.134;
/// How near the hole's top a cell of the sliver stands (mm): the sliver is the top face around
/// the hole, never other geometry inside it (a boss in a moat stands higher or lower).
const SLIVER_HEIGHT: f64 = 1e-3;

/// Whether `p` lies on the wall of hole `h`: between the widest sliver inside its circle and
/// `beyond` outside it.
fn on_wall(h: &crate::holes::Hole, p: DVec2, beyond: f64) -> bool {
    let (r, d) = (h.diameter / 2.0, p.distance(h.center));
    d >= r * (1.0 - SLIVER) && d < r + beyond
}

/// The part's heights lowered to each round hole's bottom in the sliver of top face between its
/// facets and its circle (the facets of a tessellated hole lie inside the circle): only cells
/// near the wall standing at the hole's top, so whatever stands inside the hole (a boss in a
/// moat) is judged as the mesh has it.
fn lower_in_holes(field: &mut HeightField, grid: Grid, holes: &[crate::holes::Hole]) {
    for h in holes {
        let r = h.diameter / 2.0;
        let (Some((i0, i1)), Some((j0, j1))) = (grid.columns(h.center.x - r, h.center.x + r), grid.rows(h.center.y - r, h.center.y + r)) else { continue };
        for j in j0..=j1 {
            for i in i0..=i1 {
                let c = j * grid.nx + i;
                if on_wall(h, grid.node(i, j), 0.0) && (field.z[c] - h.top).abs() <= SLIVER_HEIGHT {
                    field.z[c] = field.z[c].min(h.bottom);
                }
            }
        }
    }
}

/// Gouges on the walls of a part's round holes, in a machinist's words: the tool that reaches
/// farthest into each hole's wall where a gouge lies, its diameter, the holes' and how far over
/// on the radius ("φ6.4 drill (T2) in φ6.35 holes: 0.025 mm oversize on the radius").
pub fn hole_overcuts(report: &Report, holes: &[crate::holes::Hole], moves: &[ProgramMove]) -> Vec<String> {
    // Per hole with a gouge on its wall: the feed move inside it reaching farthest out.
    let mut walls: Vec<usize> = Vec::new();
    for g in &report.gouges {
        let p = g.at.truncate();
        let near = holes.iter().enumerate().filter(|(_, h)| h.center.distance(p) < h.diameter / 2.0 + 2.0 && g.at.z >= h.bottom - 1e-6);
        if let Some((k, _)) = near.min_by(|a, b| a.1.center.distance(p).total_cmp(&b.1.center.distance(p))) {
            if !walls.contains(&k) {
                walls.push(k);
            }
        }
    }
    // (tool number, tool diameter, hole diameter) → the worst overcut, the first hole's place.
    let mut found: Vec<((u32, u64, u64), f64, DVec2, &'static str)> = Vec::new();
    for k in walls {
        let h = &holes[k];
        let r = h.diameter / 2.0;
        let reach = |m: &ProgramMove| m.mv.to().truncate().distance(h.center) + m.cutter.diameter / 2.0;
        let inside = moves.iter().filter(|m| !m.mv.is_rapid() && m.mv.to().z < h.top && m.mv.to().truncate().distance(h.center) < r);
        let Some(m) = inside.max_by(|a, b| reach(a).total_cmp(&reach(b))) else { continue };
        let over = reach(m) - r;
        if over <= 0.0 {
            continue;
        }
        let kind = match m.cutter.shape {
            crate::cutter::Shape::Drill => "drill",
            crate::cutter::Shape::SpotDrill => "spot drill",
            crate::cutter::Shape::VBit => "V-bit",
            crate::cutter::Shape::ThreadMill => "thread mill",
            _ => "end mill",
        };
        let key = (m.tool, m.cutter.diameter.to_bits(), h.diameter.to_bits());
        match found.iter_mut().find(|f| f.0 == key) {
            Some(f) => f.1 = f.1.max(over),
            None => found.push((key, over, h.center, kind)),
        }
    }
    let mm = |v: f64| format!("{v:.3}").trim_end_matches('0').trim_end_matches('.').to_owned();
    found
        .into_iter()
        .map(|((tool, d, hole), over, at, kind)| {
            format!("φ{} {kind} (T{tool}) in φ{} holes: {over:.3} mm oversize on the radius (the first at X{:.3} Y{:.3})", mm(f64::from_bits(d)), mm(f64::from_bits(hole)), at.x, at.y)
        })
        .collect()
}

/// Simulates `moves` on the box `stock` and checks them against `part`.
pub fn verify(part: &Mesh, stock: &Aabb, moves: &[ProgramMove], settings: &VerifySettings, tolerances: &Tolerances, progress: &mut Progress) -> Result<Verification> {
    let mut sim = Simulator::new(stock, settings.cell)?;
    sim.run(moves, tolerances, progress, 0.9)?;
    progress.report(0.9);
    let mut v = sim.finish_mesh(part, settings.allowance, tolerances);
    v.word_holes(moves);
    Ok(v)
}

/// Simulates `moves` on the box `stock` and checks them against the part's heights on the
/// simulation's grid, as `surface` gives them (−∞ where there is no part).
pub fn verify_against(
    surface: impl FnOnce(Grid) -> HeightField,
    stock: &Aabb,
    moves: &[ProgramMove],
    settings: &VerifySettings,
    tolerances: &Tolerances,
    progress: &mut Progress,
) -> Result<Verification> {
    let mut sim = Simulator::new(stock, settings.cell)?;
    sim.run(moves, tolerances, progress, 0.9)?;
    progress.report(0.9);
    Ok(sim.finish(surface, settings.allowance, tolerances))
}

/// Bands of rows the stock is cut in (a fixed number, so volumes are summed alike on any
/// number of cores).
const BANDS: usize = 64;
/// Moves simulated between two progress reports.
const CHUNK: usize = 4096;

/// What one band of the stock made of a program's moves: per move whose sweeps reached it (in
/// program order), the move's index, the volume its sweeps removed from the band (summed in
/// sweep order), and the worst place its tool's body met the band before them (where, at the
/// body's lowest point, and how deep).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BandCut {
    pub moves: Vec<MoveCut>,
}

/// What one move did to one band ([`BandCut`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveCut {
    /// The move's index in the program.
    pub index: usize,
    /// The volume its sweeps removed from the band (mm³).
    pub volume: f64,
    /// The nearest its path came to a cell it cut ([`DexelStock::take_nearest`]; ∞ for none).
    pub nearest: f64,
    /// The worst place its tool's body met the band.
    pub body: Option<BodyPlace>,
}

/// Where a tool's body met material (at the body's lowest point), how deep (mm), and whether
/// it was the holder (else the shank above the flutes).
pub type BodyPlace = (DVec3, f64, bool);

/// Numbers per move in [`BandCut::to_flat`].
const CUT_FLAT: usize = 8;

impl BandCut {
    /// As flat numbers (for a worker of the page's pool): per move its index, volume, nearest
    /// cut, and the body's place and depth (NaN for none).
    pub fn to_flat(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(1 + self.moves.len() * CUT_FLAT);
        out.push(self.moves.len() as f64);
        for m in &self.moves {
            let (at, depth, holder) = m.body.unwrap_or((DVec3::NAN, f64::NAN, false));
            out.extend([m.index as f64, m.volume, m.nearest, at.x, at.y, at.z, depth, if holder { 1.0 } else { 0.0 }]);
        }
        out
    }

    /// The band cuts [`BandCut::to_flat`] wrote one after another in `flat`.
    pub fn all_from_flat(flat: &[f64]) -> Result<Vec<BandCut>> {
        let short = || Error::Input("a band's cut ends early".into());
        let mut out = Vec::new();
        let mut rest = flat;
        while let Some((&count, tail)) = rest.split_first() {
            let len = count as usize * CUT_FLAT;
            let (mine, tail) = (tail.get(..len).ok_or_else(short)?, &tail[len..]);
            let moves = mine
                .chunks_exact(CUT_FLAT)
                .map(|v| MoveCut { index: v[0] as usize, volume: v[1], nearest: v[2], body: (!v[6].is_nan()).then(|| (DVec3::new(v[3], v[4], v[5]), v[6], v[7] == 1.0)) })
                .collect();
            out.push(BandCut { moves });
            rest = tail;
        }
        Ok(out)
    }
}

/// A band of the stock at work on a run of sweeps.
struct Band<'a> {
    stock: &'a mut DexelStock,
    /// The sweeps (their indices in the run) whose footprint, grown to the tool's body, may
    /// reach the band's rows.
    sweeps: Vec<usize>,
    cut: BandCut,
}

impl Band<'_> {
    /// Cuts the band with its sweeps of `run` (each with its move's index in `moves`).
    fn run(&mut self, moves: &[ProgramMove], run: &[(usize, Sweep)], gouge: f64) {
        for &s in &self.sweeps {
            let (k, sweep) = &run[s];
            let m = &moves[*k];
            let body = if m.mv.is_rapid() {
                None
            } else {
                // The holder first: in material, it is the worse of the two.
                let rings = m.holder.as_deref().map(Vec::as_slice).unwrap_or_default();
                let holder = rings
                    .iter()
                    .filter_map(|&(r, rise)| self.stock.above_body(sweep, r, rise + gouge).map(|(at, depth)| (at.extend(sweep.nearest(at).1 + rise), depth, true)))
                    .max_by(|a, b| a.1.total_cmp(&b.1));
                holder.or_else(|| self.stock.above_body(sweep, body_radius(m), m.cutter.flute_length + gouge).map(|(at, depth)| (at.extend(sweep.nearest(at).1 + m.cutter.flute_length), depth, false)))
            };
            let volume = self.stock.apply(sweep);
            let nearest = self.stock.take_nearest();
            match self.cut.moves.last_mut() {
                Some(last) if last.index == *k => {
                    last.volume += volume;
                    last.nearest = last.nearest.min(nearest);
                    keep_deeper(&mut last.body, body);
                }
                _ => self.cut.moves.push(MoveCut { index: *k, volume, nearest, body }),
            }
        }
    }
}

/// Cuts `bands` (bands of rows of a stock in order, [`DexelStock::split_rows`]) with `moves`,
/// a few thousand moves at a time, reporting up to `share` of the progress stage; what each
/// band made of them, in the bands' order. A band's cut depends only on the band and the
/// moves, so bands can be cut in groups anywhere (the page's pool) and their cuts gathered by
/// [`Simulator::absorb`]. Natively the bands are dealt to the cores in turn (band k to core k
/// mod n), each core running through the whole program for its bands: a program cuts one
/// region at a time, and every core then has its share of each region's bands.
pub fn cut_bands(bands: &mut [DexelStock], moves: &[ProgramMove], tolerances: &Tolerances, progress: &mut Progress, share: f64) -> Result<Vec<BandCut>> {
    let threads = crate::parallel::threads().min(bands.len());
    let stop = AtomicBool::new(false);
    if threads <= 1 {
        return cut_group(bands.iter_mut().collect(), moves, tolerances, progress, share, &stop);
    }
    let mut groups: Vec<Vec<&mut DexelStock>> = (0..threads).map(|_| Vec::new()).collect();
    for (b, band) in bands.iter_mut().enumerate() {
        groups[b % threads].push(band);
    }
    let mut groups = groups.into_iter();
    let first = groups.next().expect("two groups or more");
    let stop = &stop;
    let made: Vec<Result<Vec<BandCut>>> = std::thread::scope(|scope| {
        let others: Vec<_> = groups.map(|g| scope.spawn(move || cut_group(g, moves, tolerances, &mut Progress::none(), share, stop))).collect();
        // This thread's group reports the progress, and a cancel stops the others too.
        let mine = cut_group(first, moves, tolerances, progress, share, stop);
        if mine.is_err() {
            stop.store(true, Ordering::Relaxed);
        }
        std::iter::once(mine).chain(others.into_iter().map(|h| h.join().expect("a simulating thread panicked"))).collect()
    });
    // Back in the bands' order: band k is the (k / n)th of group k mod n.
    let mut dealt: Vec<std::vec::IntoIter<BandCut>> = made.into_iter().map(|m| m.map(Vec::into_iter)).collect::<Result<_>>()?;
    Ok((0..bands.len()).map(|k| dealt[k % threads].next().expect("every band has its cut")).collect())
}

/// [`cut_bands`] on one thread, for `bands` in order (not necessarily next to one another);
/// stops, cancelled, when `progress` says so or another thread sets `stop`.
fn cut_group(bands: Vec<&mut DexelStock>, moves: &[ProgramMove], tolerances: &Tolerances, progress: &mut Progress, share: f64, stop: &AtomicBool) -> Result<Vec<BandCut>> {
    let rows: Vec<(f64, f64)> = bands.iter().map(|b| b.rows()).collect();
    if rows.is_empty() {
        return Ok(Vec::new());
    }
    // The bands whose rows `[lo, hi]` meets: from the first not wholly below it.
    let reaching = |lo: f64, hi: f64| {
        let first = rows.partition_point(|r| r.1 < lo);
        rows.iter().enumerate().skip(first).take_while(move |(_, r)| r.0 <= hi).map(|(b, _)| b)
    };
    let mut work: Vec<Band> = bands.into_iter().map(|stock| Band { stock, sweeps: Vec::new(), cut: BandCut::default() }).collect();
    for (c, chunk) in moves.chunks(CHUNK).enumerate() {
        if stop.load(Ordering::Relaxed) || !progress.report(share * (c * CHUNK) as f64 / moves.len().max(1) as f64) {
            stop.store(true, Ordering::Relaxed);
            return Err(Error::Cancelled);
        }
        // The sweeps of the moves that may reach these bands, each handed to the bands its
        // footprint (grown to the body) spans.
        let first = c * CHUNK;
        let run: Vec<(usize, Sweep)> = chunk
            .iter()
            .enumerate()
            .filter(|(_, m)| {
                let (lo, hi) = m.y_span();
                reaching(lo, hi).next().is_some()
            })
            .flat_map(|(i, m)| m.sweeps(tolerances.simulated_chordal()).into_iter().map(move |s| (first + i, s)))
            .collect();
        for band in &mut work {
            band.sweeps.clear();
        }
        for (s, (k, sweep)) in run.iter().enumerate() {
            let grow = (reach_radius(&moves[*k]) - sweep.profile.radius).max(0.0);
            for b in reaching(sweep.min.y - grow, sweep.max.y + grow) {
                work[b].sweeps.push(s);
            }
        }
        for band in &mut work {
            band.run(moves, &run, tolerances.gouge);
        }
    }
    Ok(work.into_iter().map(|b| b.cut).collect())
}

/// `found` in `worst` where it is deeper (the first kept where equal).
fn keep_deeper(worst: &mut Option<BodyPlace>, found: Option<BodyPlace>) {
    if let Some(f) = found {
        if worst.is_none_or(|w| f.1 > w.1) {
            *worst = Some(f);
        }
    }
}

/// The radius of the tool's body above its flutes.
fn body_radius(m: &ProgramMove) -> f64 {
    m.cutter.shank_diameter.unwrap_or(m.cutter.diameter) * 0.5
}

/// How far from its axis the tool meets material: its body, or its holder's widest section.
fn reach_radius(m: &ProgramMove) -> f64 {
    m.holder.iter().flat_map(|rings| rings.iter().map(|r| r.0)).fold(body_radius(m), f64::max)
}

/// A program simulated piece by piece on a z-map stock: a job applies each operation's moves as
/// it is made, so the next operation sees the stock the earlier ones left (the in-process
/// stock), and the findings of the whole program are gathered on the way.
#[derive(Clone, Debug)]
pub struct Simulator {
    stock: DexelStock,
    /// The raw stock's top: a cell the program never cut stands here, whatever the part.
    raw_top: f64,
    volumes: Vec<f64>,
    /// Each move's nearest cut ([`Verification::nearest`]).
    nearest: Vec<f64>,
    /// Each move's length, time and kind, for its removal rate.
    timings: Vec<Timing>,
    rapid: (usize, Vec<Finding>),
    body: (usize, Vec<Finding>),
    holder: (usize, Vec<Finding>),
    /// The stock carried in, as it was before the first move.
    start: Option<DexelStock>,
}

impl Simulator {
    /// The untouched box `stock` on cells of side `cell`.
    pub fn new(stock: &Aabb, cell: f64) -> Result<Simulator> {
        Ok(Simulator {
            stock: stock_for(stock, cell)?,
            raw_top: stock.max.z,
            volumes: Vec::new(),
            nearest: Vec::new(),
            timings: Vec::new(),
            rapid: (0, Vec::new()),
            body: (0, Vec::new()),
            holder: (0, Vec::new()),
            start: None,
        })
    }

    /// Starts from the stock earlier work left instead of the raw box: each cell's spans of
    /// material as `material` pushes them for its centre ([`DexelStock::with_spans`]), the
    /// cells laid from the box's maximum side along the axes `at_max` marks
    /// ([`DexelStock::laid_from`]). Before any move.
    pub fn carry(&mut self, at_max: [bool; 2], material: impl FnMut(DVec2, &mut Vec<(f64, f64)>)) {
        self.stock = self.stock.take().laid_from(at_max).with_spans(material);
        self.start = Some(self.stock.clone());
    }

    /// The stock as the moves so far left it.
    pub fn stock(&self) -> &DexelStock {
        &self.stock
    }

    /// Volume removed by each move so far (mm³).
    pub fn volumes(&self) -> &[f64] {
        &self.volumes
    }

    /// How near each move so far came to a cell it cut ([`Verification::nearest`]).
    pub fn nearest(&self) -> &[f64] {
        &self.nearest
    }

    /// The material removal rate of each move so far (mm³/min, [`removal_rates`] over
    /// [`RATE_CELLS`] cells of path).
    pub fn rates(&self) -> Vec<f64> {
        removal_rates(&self.timings, &self.volumes, RATE_CELLS * self.stock.grid().spacing)
    }

    /// Applies the next `moves` of the program (move indices continue from the earlier ones),
    /// reporting up to `share` of the progress stage: the stock is cut in bands of rows
    /// ([`Simulator::take_bands`], [`cut_bands`]) and their cuts gathered
    /// ([`Simulator::absorb`]).
    pub fn run(&mut self, moves: &[ProgramMove], tolerances: &Tolerances, progress: &mut Progress, share: f64) -> Result<()> {
        let mut bands = self.take_bands();
        match cut_bands(&mut bands, moves, tolerances, progress, share) {
            Ok(cuts) => {
                self.absorb(bands, &cuts, moves);
                Ok(())
            }
            // A cancelled run leaves the stock as far as it was cut, and no figures.
            Err(e) => {
                self.stock = DexelStock::join(bands);
                Err(e)
            }
        }
    }

    /// The stock cut into the bands of rows it is simulated in (a fixed number, so the figures
    /// are the same on any number of cores or workers), leaving none here until
    /// [`Simulator::absorb`] gives them back.
    pub fn take_bands(&mut self) -> Vec<DexelStock> {
        self.stock.take().split_rows(BANDS)
    }

    /// Takes back the stock's `bands` (all of them, in order) after `moves` cut them, with what
    /// each band made of them (`cuts`, in the bands' order): a move's volume is its bands'
    /// summed in band order, and its body collision the deepest of its bands' (the first
    /// band's where equal), so the findings depend neither on the cores nor on the workers.
    pub fn absorb(&mut self, bands: Vec<DexelStock>, cuts: &[BandCut], moves: &[ProgramMove]) {
        let note = |list: &mut (usize, Vec<Finding>), f: Finding| {
            list.0 += 1;
            if list.1.len() < KEPT {
                list.1.push(f);
            }
        };
        self.stock = DexelStock::join(bands);
        let mut removed = vec![0.0; moves.len()];
        let mut nearest = vec![f64::INFINITY; moves.len()];
        let mut body: Vec<Option<BodyPlace>> = vec![None; moves.len()];
        for cut in cuts {
            for m in &cut.moves {
                removed[m.index] += m.volume;
                nearest[m.index] = nearest[m.index].min(m.nearest);
                keep_deeper(&mut body[m.index], m.body);
            }
        }
        let first = self.nearest.len();
        self.nearest.extend(nearest);
        let grain = self.stock.grid().spacing * std::f64::consts::FRAC_1_SQRT_2;
        for (((m, volume), body), near) in moves.iter().zip(removed).zip(body).zip(&self.nearest[first..]) {
            let index = self.volumes.len();
            if let Some((at, depth, holder)) = body {
                note(if holder { &mut self.holder } else { &mut self.body }, Finding { move_index: Some(index), at, amount: depth });
            }
            self.timings.push(m.timing());
            // A feed move in air meets material when it cuts into it past its rim by more than
            // the cells can tell (half a cell's diagonal): a rim grazing one cell's centre, or
            // a floor skimmed by rounding, is no collision at a feed.
            let through = volume > GRAZE && (m.mv.is_rapid() || (m.air && *near < m.cutter.diameter * 0.5 - grain));
            if through {
                note(&mut self.rapid, Finding { move_index: Some(index), at: m.mv.to(), amount: volume });
            }
            self.volumes.push(volume);
        }
    }

    /// [`Simulator::finish_near`] against a mesh: its heights at the cells' centres, and beside
    /// them within the gouge tolerance.
    pub fn finish_mesh(self, part: &Mesh, allowance: f64, tolerances: &Tolerances) -> Verification {
        self.finish_mesh_cut(part, None, |_, _| {}, allowance, tolerances)
    }

    /// [`Simulator::finish_mesh`], the part's heights first lowered by `cut` where operations
    /// may take more than the mesh has (a chamfer on its edges, a thread in its holes).
    ///
    /// The part's round holes are judged as the circles their facets approximate (the hole
    /// finder's, [`crate::holes::mesh::find`]), not as the polygons inscribed in them: a bore to
    /// a tessellated hole's size or a clearance drill a hair over it cuts past the facets by
    /// their sagitta (0.029 mm for a φ12 hole of 32 sides) without cutting the part as drawn.
    ///
    /// `heights`, where given, are the part's heights on the simulation's grid as
    /// [`cc_zmap`] makes them (a check made them already: [`crate::job::hold`]).
    pub fn finish_mesh_cut(self, part: &Mesh, heights: Option<HeightField>, cut: impl FnOnce(&mut HeightField, Grid), allowance: f64, tolerances: &Tolerances) -> Verification {
        let point = crate::zmap::drop::PointDrop::new(part, &crate::cutter::Profile::new(1e-9, 0.0), tolerances);
        let holes = crate::holes::mesh::find(part);
        let surface = |grid: Grid| {
            let mut field =
                heights.filter(|h| h.nx == grid.nx && h.ny == grid.ny && h.origin == grid.origin && h.spacing == grid.spacing).unwrap_or_else(|| cc_zmap(part, grid, f64::NEG_INFINITY, tolerances));
            cut(&mut field, grid);
            lower_in_holes(&mut field, grid, &holes);
            field
        };
        let lowest = |p: DVec2| {
            // Beside a hole's wall, within the gouge tolerance of its circle (the sliver of top
            // face between its facets and the circle included): the hole's bottom.
            let top = point.at(p, f64::NEG_INFINITY);
            let beside = holes.iter().filter(|h| on_wall(h, p, tolerances.gouge) && (top - h.top).abs() <= SLIVER_HEIGHT).map(|h| h.bottom).fold(f64::INFINITY, f64::min);
            Some(lowest_near(&point, p, tolerances.gouge).min(beside))
        };
        let mut v = self.finish_near(surface, lowest, allowance, tolerances);
        v.holes = holes;
        v
    }

    /// Judges the stock against the part's heights (`surface` on the simulation's grid, −∞ where
    /// there is no part) plus `allowance`, and ends the simulation. A gouge is material the
    /// program removed below the part plus the allowance: where the raw stock itself stands
    /// lower than that (a part whose top is the stock's top), the program is held to the raw
    /// top, not to a height the stock never had.
    pub fn finish(self, surface: impl FnOnce(Grid) -> HeightField, allowance: f64, tolerances: &Tolerances) -> Verification {
        self.finish_near(surface, |_| None, allowance, tolerances)
    }

    /// [`Simulator::finish`], with a cell found cut below the part judged again by `lowest_near`
    /// (the part's lowest height within the gouge tolerance of a point, sideways; `None`: not
    /// known): a cell beside a vertical wall, cut within the tolerance of the wall (a drill of
    /// the hole's own diameter in a hole tessellated inside its circle), is no gouge, though
    /// its centre stands on the part, a wall's height above the cut. At most
    /// [`WALL_RECHECKS`] cells are judged again; beyond, a program gouges anyway.
    pub fn finish_near(self, surface: impl FnOnce(Grid) -> HeightField, lowest_near: impl Fn(DVec2) -> Option<f64>, allowance: f64, tolerances: &Tolerances) -> Verification {
        let rates = self.rates();
        let Simulator { stock: sim, raw_top, volumes, nearest, rapid, body, holder, start, .. } = self;
        let grid = sim.grid();
        let mut surface = surface(grid);
        let mut gouges = Vec::new();
        let mut rechecked = 0;
        let (mut residual_max, mut residual_sum, mut covered) = (0.0f64, 0.0, 0usize);
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let c = j * grid.nx + i;
                if surface.z[c] == f64::NEG_INFINITY {
                    surface.z[c] = f64::NAN;
                    continue;
                }
                surface.z[c] = (surface.z[c] + allowance).min(raw_top);
                let left = sim.top(i, j) - surface.z[c];
                let mut beside_wall = || {
                    rechecked += 1;
                    rechecked <= WALL_RECHECKS && lowest_near(grid.node(i, j)).is_some_and(|low| sim.top(i, j) - (low + allowance).min(raw_top) >= -tolerances.gouge)
                };
                if left < -tolerances.gouge && !beside_wall() {
                    gouges.push(Finding { move_index: None, at: grid.node(i, j).extend(sim.top(i, j)), amount: -left });
                }
                residual_max = residual_max.max(left);
                residual_sum += left.max(0.0);
                covered += 1;
            }
        }
        // The deepest gouges first.
        crate::geom::sort::sort_by_float(&mut gouges, |a| -a.amount);
        let gouge_count = gouges.len();
        gouges.truncate(KEPT);
        let report = Report {
            cells: sim.cells(),
            moves: volumes.len(),
            removed: volumes.iter().sum(),
            gouge_count,
            gouge_max: gouges.first().map_or(0.0, |g| g.amount),
            gouges,
            rapid_collision_count: rapid.0,
            rapid_collisions: rapid.1,
            body_collision_count: body.0,
            body_collisions: body.1,
            holder_collision_count: holder.0,
            holder_collisions: holder.1,
            fixtures_checked: 0,
            fixture_collision_count: 0,
            fixture_collisions: Vec::new(),
            residual_max,
            residual_mean: if covered > 0 { residual_sum / covered as f64 } else { 0.0 },
            mrr_max: rates.iter().copied().fold(0.0, f64::max),
            overcuts: Vec::new(),
        };
        Verification { report, volumes, rates, nearest, stock: sim, start, part: surface, holes: Vec::new() }
    }
}
