//! What the page draws and shows of a part, a drawing and a job's result, as plain data: the
//! wasm boundary (`wasm.rs`) only hands these to JavaScript, so everything here is native and
//! covered by `cargo test`. Large arrays stay flat (xyz after xyz) for typed arrays; the rest
//! is serde data whose TypeScript types are generated (`www/types/`).

use serde::Serialize;

use crate::drawing::Drawing;
use crate::error::{Error, Result, Warning};
use crate::geom::{Aabb, DVec2, DVec3};
use crate::job::{self, Job, JobOutput, OperationReport};
use crate::mesh::Mesh;
use crate::post::{CycleTime, PostSettings, TimeItem};
use crate::sim::playback::Playback;
use crate::sim::verify::{Report, Verification};
use crate::sim::DexelStock;
use crate::tool::Tool;
use crate::toolpath::{arc_sweep, Move, PathStats, Toolpath};

/// Chord angle (radians) of the arcs drawn as line segments.
const ARC_STEP: f64 = 0.1;

/// A part read and placed, ready to draw: triangle corners and facet normals (xyz per vertex,
/// three vertices per triangle), its bounds, and what the user should know of it.
#[derive(Clone, Debug)]
pub struct PartData {
    pub positions: Vec<f32>,
    pub normals: Vec<f32>,
    pub bounds: Aabb,
    pub triangles: usize,
    /// Degenerate triangles dropped at import.
    pub dropped: usize,
    /// Holes in its surface, triangles dropped ([`job::part_warnings`]).
    pub warnings: Vec<Warning>,
    /// The placed triangles' identity ([`PartData::hash_of`]): two parts are the same to the
    /// page (kept, not uploaded again) only when this is the same.
    pub hash: String,
}

impl PartData {
    pub fn of(mesh: &Mesh) -> PartData {
        let mut positions = Vec::with_capacity(mesh.faces.len() * 9);
        let mut normals = Vec::with_capacity(mesh.faces.len() * 9);
        for t in mesh.triangles() {
            let n = t.normal().unwrap_or(DVec3::Z);
            for v in t.vertices() {
                positions.extend([v.x as f32, v.y as f32, v.z as f32]);
                normals.extend([n.x as f32, n.y as f32, n.z as f32]);
            }
        }
        let hash = PartData::hash_of(&positions);
        PartData { positions, normals, bounds: mesh.bounds(), triangles: mesh.faces.len(), dropped: mesh.dropped_degenerate, warnings: job::part_warnings(mesh), hash }
    }

    /// A part with no triangles (what a result holds once its part is taken).
    pub fn empty() -> PartData {
        PartData { positions: vec![], normals: vec![], bounds: Aabb::EMPTY, triangles: 0, dropped: 0, warnings: vec![], hash: PartData::hash_of(&[]) }
    }

    /// 64-bit FNV-1a over every coordinate's bits, in hex: any placement that moves a single
    /// vertex (a flip, a turn, a scale) gives another hash; the normals follow the positions.
    pub fn hash_of(positions: &[f32]) -> String {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for v in positions {
            for b in v.to_bits().to_le_bytes() {
                h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
        format!("{:016x}-{}", h, positions.len())
    }

    /// `[minX, minY, minZ, maxX, maxY, maxZ]` (mm).
    pub fn bounds_array(&self) -> Vec<f64> {
        let b = self.bounds;
        vec![b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z]
    }
}

/// A drawing for the page's view: outer loops, holes and open chains as line segments at Z0
/// (xyz pairs), and a list of its loops and layers.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct DrawingView {
    pub outer: Vec<f32>,
    pub holes: Vec<f32>,
    pub open: Vec<f32>,
    pub bounds: [f64; 6],
    pub loops: Vec<LoopInfo>,
    pub layers: Vec<String>,
    pub units: String,
    /// What the reader left out, by kind, with how many.
    pub ignored: Vec<(String, usize)>,
    pub open_chains: Vec<crate::drawing::OpenChain>,
    /// A size that says the drawing was read in the wrong unit ([`job::drawing_unit_warning`]).
    pub warnings: Vec<Warning>,
}

/// A part's top edge as the page lists and draws it (`swarf edges`): numbered as the chamfer's
/// `loops` takes them (its place in the list).
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct EdgeView {
    /// The height of the face it bounds (mm).
    pub z: f64,
    /// It drops down a steep wall all round: a chamfer can break it.
    pub sharp: bool,
    /// Its length (mm).
    pub length: f64,
    /// The loop's corners in plan (mm), closed back to the first.
    pub points: Vec<[f64; 2]>,
}

impl EdgeView {
    pub fn of(e: &crate::mesh::edges::TopEdge) -> EdgeView {
        EdgeView { z: e.z, sharp: e.sharp, length: e.outline.length(), points: e.outline.vertices.iter().map(|v| v.p.to_array()).collect() }
    }
}

/// One closed loop of a drawing, as the page lists it.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct LoopInfo {
    pub index: usize,
    pub layer: String,
    pub hole: bool,
    pub entities: usize,
    pub min: [f64; 2],
    pub max: [f64; 2],
    /// Its line segments: vertices `lines[0]..lines[1]` (in pairs) of `holes` or `outer`.
    pub lines: [usize; 2],
}

impl DrawingView {
    pub fn of(d: &Drawing) -> DrawingView {
        let nesting = crate::drawing::Shape::new(d.loops.iter().map(|l| l.path.clone()).collect());
        let (mut outer, mut holes, mut loops) = (Vec::new(), Vec::new(), Vec::new());
        for (index, (l, o)) in d.loops.iter().zip(&nesting.loops).enumerate() {
            let target = if o.is_ccw() { &mut outer } else { &mut holes };
            let first = target.len() / 3;
            for seg in l.path.segments() {
                let n = seg.arc_geom().map_or(1, |g| ((g.sweep().abs() / (ARC_STEP / 2.0)).ceil() as usize).max(1));
                for k in 0..n {
                    let (a, b) = (seg.point_at(k as f64 / n as f64), seg.point_at((k + 1) as f64 / n as f64));
                    target.extend([a.x as f32, a.y as f32, 0.0, b.x as f32, b.y as f32, 0.0]);
                }
            }
            let b = l.path.bounds();
            loops.push(LoopInfo { index, layer: l.layer.clone(), hole: !o.is_ccw(), entities: l.path.len(), min: [b.min.x, b.min.y], max: [b.max.x, b.max.y], lines: [first, target.len() / 3] });
        }
        let mut open = Vec::new();
        for o in &d.open {
            open.extend([o.start.x as f32, o.start.y as f32, 0.0, o.end.x as f32, o.end.y as f32, 0.0]);
        }
        let b = d.bounds();
        DrawingView {
            outer,
            holes,
            open,
            bounds: [b.min.x, b.min.y, 0.0, b.max.x, b.max.y, 0.0],
            loops,
            layers: d.layers.clone(),
            units: d.units.clone(),
            ignored: d.ignored.clone(),
            open_chains: d.open.clone(),
            warnings: job::drawing_unit_warning(d).into_iter().collect(),
        }
    }
}

/// What the page shows of a job's result beside the drawing: figures, warnings, the problem if
/// any, the per-operation reports and the cycle time's breakdown.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Summary {
    #[serde(flatten)]
    pub stats: PathStats,
    pub warnings: Vec<Warning>,
    /// Per operation: name, tools, time, lengths, volume removed, peak MRR, what it left.
    pub operations: Vec<OperationReport>,
    /// The index of each operation's first move in the program (for the scrubber's marks).
    pub operation_starts: Vec<usize>,
    /// Lookups of the CL z-map cache that found a z-map made for an earlier operation.
    pub cache_hits: usize,
    /// What makes the program unsafe to run, if verification found anything.
    pub problem: Option<String>,
    pub stock: [f64; 6],
    /// What holds the stock (a vise's jaws, clamps): each box's least and greatest corner.
    pub fixtures: Vec<[f64; 6]>,
    pub clearance_z: f64,
    /// The extension the post's controllers expect of the program's file.
    pub extension: String,
    /// The post's name, for the program's file name.
    pub post: String,
    /// The program's cycle time as its head states it (tool changes included).
    pub cycle: CycleTime,
    /// The cycle time by operation, tool changes and the rest, in whole seconds summing to the
    /// whole, as the program's head and the CLI give it.
    pub time: Vec<TimeItem>,
    /// What the feed optimisation did, where the job asked for it.
    pub feeds: Option<crate::job::report::FeedReport>,
}

/// A job's paths as line segments for drawing (xyz of both ends per segment), with the
/// operation, tool and program move of each cutting segment and the move of each rapid one.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Segments {
    pub feeds: Vec<f32>,
    pub feed_ops: Vec<f32>,
    pub feed_tools: Vec<f32>,
    /// The index in the program of the move each cutting segment belongs to.
    pub feed_moves: Vec<u32>,
    pub rapids: Vec<f32>,
    pub rapid_moves: Vec<u32>,
}

impl Segments {
    /// The segments of `paths` (the operation of each in `operations`), arcs as chords.
    pub fn of(paths: &[Toolpath], operations: &[usize]) -> Segments {
        let mut s = Segments::default();
        let mut index = 0u32;
        for (path, &op) in paths.iter().zip(operations) {
            let mut at = path.start;
            for m in &path.moves {
                let rapid = m.is_rapid();
                let mut push = |a: DVec3, b: DVec3| {
                    let target = if rapid { &mut s.rapids } else { &mut s.feeds };
                    target.extend([a.x as f32, a.y as f32, a.z as f32, b.x as f32, b.y as f32, b.z as f32]);
                    if rapid {
                        s.rapid_moves.push(index);
                    } else {
                        s.feed_ops.push(op as f32);
                        s.feed_tools.push(path.tool as f32);
                        s.feed_moves.push(index);
                    }
                };
                match *m {
                    Move::Arc { to, center, clockwise, .. } => {
                        let steps = ((arc_sweep(at, to, center, clockwise).abs() / ARC_STEP).ceil() as usize).max(1);
                        let mut prev = at;
                        for k in 1..=steps {
                            let p = if k == steps { to } else { along(at, m, k as f64 / steps as f64) };
                            push(prev, p);
                            prev = p;
                        }
                    }
                    _ => push(at, m.to()),
                }
                at = m.to();
                index += 1;
            }
        }
        s
    }
}

/// The point a fraction `f` of the way along the move `m` from `from`.
pub fn along(from: DVec3, m: &Move, f: f64) -> DVec3 {
    match *m {
        Move::Rapid { to } | Move::Line { to, .. } => from.lerp(to, f),
        Move::Arc { to, center, clockwise, .. } => {
            let a = from.truncate() - center;
            let th = a.y.atan2(a.x) + arc_sweep(from, to, center, clockwise) * f;
            (center + DVec2::new(th.cos(), th.sin()) * a.length()).extend(from.z + (to.z - from.z) * f)
        }
    }
}

/// The verification report with a text for people.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
pub struct ReportView {
    #[serde(flatten)]
    pub report: Report,
    pub text: String,
}

/// The simulated program, for the page's scrubber: the stock after any move, the part's surface
/// on the same cells, the moves' times and removal rates, and what verification found.
pub struct SimulationData {
    pub playback: Playback,
    /// `[originX, originY, spacing, nx, ny, stockBottom, stockTop, gougeTolerance]`.
    pub grid: Vec<f64>,
    /// The part's surface plus allowance at each cell centre (NaN off the part).
    pub part: Vec<f32>,
    /// When each move starts in the program (s, tool changes and the way down to each path
    /// included), and at the end the program's cycle time.
    pub times: Vec<f64>,
    /// Each move's removal rate (mm³/min).
    pub mrr: Vec<f32>,
    /// Places of gouges and collisions: x, y, z, kind (0 gouge, 1 rapid, 2 tool body).
    pub findings: Vec<f32>,
    pub report: ReportView,
}

impl SimulationData {
    fn of(job: &Job, out: &JobOutput, mut v: Verification) -> SimulationData {
        let g = v.stock.grid();
        let grid = vec![g.origin.x, g.origin.y, g.spacing, g.nx as f64, g.ny as f64, out.stock.min.z, out.stock.max.z, job.tolerances.gouge];
        let part = v.part.z.iter().map(|&z| z as f32).collect();
        let mrr = v.rates.iter().map(|&r| r as f32).collect();
        let r = &v.report;
        let mut findings = Vec::new();
        for (kind, list) in [(0.0, &r.gouges), (1.0, &r.rapid_collisions), (2.0, &r.body_collisions), (2.0, &r.holder_collisions)] {
            for f in list {
                findings.extend([f.at.x as f32, f.at.y as f32, f.at.z as f32, kind]);
            }
        }
        let report = ReportView { report: r.clone(), text: r.describe() };
        // The playback starts where the program did: the raw box, or the bar or the stock the
        // setup before left.
        let fresh = v.start.take().unwrap_or_else(|| DexelStock::new(&out.stock, g.spacing, 1));
        let playback = Playback::at_end(fresh, v.stock, out.moves.clone(), job.tolerances.simulated_chordal());
        SimulationData { playback, grid, part, times: program_times(out), mrr, findings, report }
    }
}

/// When each move of `out` starts on the machine: its path's start as the post timed it (tool
/// changes and the way down from the clearance height before it), plus its time into the
/// path; and the cycle time at the end. The scrubber's clock is the program head's.
fn program_times(out: &JobOutput) -> Vec<f64> {
    let mut times = Vec::with_capacity(out.moves.len() + 1);
    let mut first: Option<(usize, f64)> = None;
    for m in &out.moves {
        let path_start = match first {
            Some((p, s)) if p == m.path => s,
            _ => {
                first = Some((m.path, m.start));
                m.start
            }
        };
        let begins = out.cycle.starts.get(m.path).copied().unwrap_or(path_start);
        let t = begins + (m.start - path_start);
        // Never back in time (the post's timing of a path may differ by a hair).
        times.push(times.last().map_or(t, |&last: &f64| t.max(last)));
    }
    let end = out.cycle.seconds.max(times.last().copied().unwrap_or(0.0));
    times.push(end);
    times
}

/// The paths of a job and what writing them needs, to write them again for another post.
#[derive(Clone, Debug)]
pub struct Program {
    pub title: String,
    pub paths: Vec<Toolpath>,
    pub tools: Vec<Tool>,
    pub clearance: f64,
    pub post: PostSettings,
    pub problem: Option<String>,
}

/// A program written again for another post.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Reposted {
    pub gcode: String,
    pub extension: String,
    pub post: String,
    pub cycle: CycleTime,
    pub time: Vec<TimeItem>,
    /// The line each move ended on ([`crate::post::Written::move_lines`]).
    #[serde(skip)]
    #[ts(skip)]
    pub move_lines: Vec<u32>,
}

impl Program {
    /// The same paths written by another post, without planning again. A post that rounds
    /// coarser than the resolution the paths were planned for is refused: the paths keep their
    /// clearance from the part only at that resolution.
    pub fn repost(&self, settings: &PostSettings) -> Result<Reposted> {
        if settings.resolution() > self.post.planning_resolution() * (1.0 + 1e-9) {
            return Err(Error::Input("this post rounds coarser than the one the paths were made for: generate again".into()));
        }
        let w = crate::post::write_mapped(&self.title, &self.paths, &self.tools, self.clearance, settings)?;
        let time = w.cycle.items(&CycleTime::groups(&self.paths));
        let (gcode, move_lines) = marked(w.gcode, w.move_lines, self.problem.as_deref());
        Ok(Reposted { gcode, extension: settings.extension(), post: settings.post().name, cycle: w.cycle, time, move_lines })
    }
}

/// The program with a warning at its head naming `problem`, if there is one, and its move
/// lines shifted past the warning's lines.
fn marked(gcode: String, lines: Vec<u32>, problem: Option<&str>) -> (String, Vec<u32>) {
    match problem {
        Some(p) => {
            let added = job::warning_lines(p).len() as u32;
            (job::marked(&gcode, problem), lines.into_iter().map(|l| l + added).collect())
        }
        None => (gcode, lines),
    }
}

/// Where a setup holds the part, for the view and a portal: a point `p` of the part as the job
/// places it is at `rotation · (p − centre) + centre + shift` in the setup (the rotation by
/// quarter turns, column after column); `stock` is the raw stock's box there.
#[derive(Clone, Debug, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct SetupView {
    pub index: usize,
    pub name: String,
    pub rotation: [f64; 9],
    pub centre: [f64; 3],
    pub shift: [f64; 3],
    pub stock: Aabb,
    /// What holds the stock in it (a vise's jaws, clamps, fixtures as meshes by their boxes):
    /// each box's least and greatest corner.
    pub fixtures: Vec<[f64; 6]>,
}

/// The boxes of `held`, as the view draws them.
fn fixture_boxes(held: &[job::fixtures::Held]) -> Vec<[f64; 6]> {
    held.iter()
        .map(|h| {
            let (a, b) = (h.solid.min, h.solid.max);
            [a.x, a.y, a.z, b.x, b.y, b.z]
        })
        .collect()
}

impl SetupView {
    pub fn of(index: usize, name: &str, orientation: &job::setups::Orientation, stock: Aabb) -> SetupView {
        SetupView {
            index,
            name: name.to_owned(),
            rotation: orientation.rotation.to_cols_array(),
            centre: orientation.centre.to_array(),
            shift: orientation.shift.to_array(),
            stock,
            fixtures: Vec::new(),
        }
    }

    /// How the view shows a job before it runs, on a part whose bounds (placed as the job
    /// places it, before any work zero) are `part`: each setup as [`SetupView::frames`] holds
    /// it, or a job without setups as its one, the part moved to the work zero; each with its
    /// stock's box and its fixtures, in the program's coordinates (the zero at the origin).
    pub fn stage(job: &Job, part: &Aabb) -> Vec<SetupView> {
        if job.setups.is_empty() {
            let (stock, shift) = job.stock_at_zero(part);
            let orientation = job::setups::Orientation { rotation: glam::DMat3::IDENTITY, centre: crate::geom::DVec3::ZERO, shift };
            return vec![SetupView { fixtures: fixture_boxes(&job.fixtures.held(&stock)), ..SetupView::of(0, &job.name, &orientation, stock) }];
        }
        let mut frames = SetupView::frames(job, part);
        for (frame, setup) in frames.iter_mut().zip(&job.setups) {
            frame.fixtures = fixture_boxes(&setup.fixtures.as_ref().unwrap_or(&job.fixtures).held(&frame.stock));
        }
        frames
    }

    /// Every setup of `job` on a part whose bounds (placed as the job places it) are `part`
    /// ([`job::setups::setup_frames`]); none for a job without setups.
    pub fn frames(job: &Job, part: &Aabb) -> Vec<SetupView> {
        let names = job.setup_names();
        job::setups::setup_frames(job, part).iter().enumerate().map(|(k, (o, stock))| SetupView::of(k, &names[k], o, *stock)).collect()
    }
}

/// Everything the page takes of a job's result.
pub struct ResultView {
    pub gcode: String,
    /// The line of `gcode` each move ended on.
    pub move_lines: Vec<u32>,
    pub segments: Segments,
    /// The octants of each stage of octree roughing: per box `stage, tool, full, minX, minY,
    /// minZ, maxX, maxY, maxZ`.
    pub octants: Vec<f32>,
    pub summary: Summary,
    pub part: PartData,
    pub drawing: Option<DrawingView>,
    pub simulation: Option<SimulationData>,
    pub program: Program,
}

impl ResultView {
    pub fn of(job: &Job, mut out: JobOutput) -> ResultView {
        let simulation = out.verification.take().map(|v| SimulationData::of(job, &out, v));
        let segments = Segments::of(&out.paths, &out.path_operations);
        let mut operation_starts = Vec::new();
        let mut at = 0;
        for r in &out.operations {
            operation_starts.push(at);
            at += r.moves;
        }
        let s = out.stock;
        let summary = Summary {
            stats: out.stats,
            warnings: out.warnings.clone(),
            operations: out.operations.clone(),
            operation_starts,
            cache_hits: out.cache.hits,
            problem: out.problem.clone(),
            stock: [s.min.x, s.min.y, s.min.z, s.max.x, s.max.y, s.max.z],
            fixtures: fixture_boxes(&job.fixtures.held(&s)),
            clearance_z: out.clearance_z,
            extension: job.post.extension(),
            post: job.post.post().name,
            cycle: out.cycle.clone(),
            time: out.time.clone(),
            feeds: out.feeds.clone(),
        };
        let octants = out
            .octants
            .iter()
            .flat_map(|s| s.boxes.iter().map(move |b| (s, b)))
            .flat_map(|(s, b)| [s.stage as f64, s.tool as f64, if b.full { 1.0 } else { 0.0 }, b.min[0], b.min[1], b.min[2], b.max[0], b.max[1], b.max[2]])
            .map(|v| v as f32)
            .collect();
        let (gcode, move_lines) = marked(std::mem::take(&mut out.gcode), std::mem::take(&mut out.move_lines), out.problem.as_deref());
        let program = Program {
            title: job.name.clone(),
            paths: std::mem::take(&mut out.paths),
            tools: job.tools.clone(),
            clearance: out.clearance_z,
            post: job.post_for_machine(),
            problem: out.problem.clone(),
        };
        ResultView { gcode, move_lines, segments, octants, summary, part: PartData::of(&out.part), drawing: out.drawing.as_ref().map(DrawingView::of), simulation, program }
    }

    /// Where the tool is a fraction `f` of the way through move `k` of the program: `[x, y,
    /// z, tool number]` (the last move's end past the end; nothing without a simulation).
    pub fn tool_at(&self, k: usize, f: f64) -> Option<[f64; 4]> {
        let moves = self.simulation.as_ref()?.playback.moves();
        let m = moves.get(k.min(moves.len().checked_sub(1)?))?;
        let f = if k >= moves.len() { 1.0 } else { f.clamp(0.0, 1.0) };
        let p = along(m.from, &m.mv, f);
        Some([p.x, p.y, p.z, m.tool as f64])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::Progress;

    /// Issue 55: the page keeps a part's triangles when a run gives back the same part, and
    /// only then. Every up axis and turn of a part without symmetry is another hash (a flip
    /// keeps a centred part's bounds: a sample of coordinates once took −Z for the same part),
    /// and the same placement the same hash.
    #[test]
    fn every_placement_is_another_part_and_the_same_one_the_same() {
        use crate::mesh::placement::{PartSetup, UpAxis};
        let mut seen = std::collections::HashMap::new();
        for up in [UpAxis::Z, UpAxis::Y, UpAxis::X, UpAxis::MinusZ, UpAxis::MinusY, UpAxis::MinusX] {
            for rotation in [0, 90, 180, 270] {
                let setup = PartSetup { up_axis: up, rotation, ..PartSetup::default() };
                let mut mesh = crate::mesh::sample::demo_part();
                setup.apply(&mut mesh);
                let data = PartData::of(&mesh);
                let mut again = crate::mesh::sample::demo_part();
                setup.apply(&mut again);
                assert_eq!(PartData::of(&again).hash, data.hash, "{up:?} {rotation}");
                if let Some(other) = seen.insert(data.hash.clone(), (up, rotation)) {
                    panic!("{up:?} turned {rotation} has the hash of {other:?}");
                }
            }
        }
        // One coordinate moved by its last bit is another part.
        let data = PartData::of(&crate::mesh::sample::demo_part());
        let mut moved = data.positions.clone();
        moved[4] = f32::from_bits(moved[4].to_bits() + 1);
        assert_ne!(PartData::hash_of(&moved), data.hash);
        assert_ne!(PartData::empty().hash, data.hash);
    }

    #[test]
    fn segments_name_their_moves_and_the_scrubbers_clock_is_the_programs() {
        let job = Job::demo();
        let out = job::run(&job, crate::mesh::sample::demo_part(), &mut Progress::none()).unwrap();
        let moves = out.moves.len();
        let view = ResultView::of(&job, out);
        let s = &view.segments;
        assert_eq!(s.feeds.len() / 6, s.feed_moves.len());
        assert_eq!(s.rapids.len() / 6, s.rapid_moves.len());
        assert!(s.feed_moves.windows(2).all(|w| w[0] <= w[1]) && *s.feed_moves.last().unwrap() < moves as u32);
        let sim = view.simulation.as_ref().unwrap();
        assert_eq!(sim.times.len(), moves + 1);
        assert!(sim.times.windows(2).all(|w| w[0] <= w[1]));
        assert!((sim.times[moves] - view.summary.cycle.seconds).abs() < 1e-9);
        // Every move's line is a motion line of the program, in order.
        let lines: Vec<&str> = view.gcode.lines().collect();
        assert_eq!(view.move_lines.len(), moves);
        assert!(view.move_lines.windows(2).all(|w| w[0] <= w[1]));
        for &l in view.move_lines.iter().step_by(97) {
            let line = lines[l as usize];
            assert!(line.starts_with(['G', 'X', 'Y', 'Z']), "line {l}: {line}");
        }
        // The tool's place along a move, in its tool.
        let [x, y, z, tool] = view.tool_at(10, 0.5).unwrap();
        let m = &sim.playback.moves()[10];
        assert_eq!(DVec3::new(x, y, z), along(m.from, &m.mv, 0.5));
        assert_eq!(tool as u32, m.tool);
    }
}
