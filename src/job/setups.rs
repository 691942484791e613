//! Setups: one part machined from more than one side, from one stock.
//!
//! Every setup is the part and its stock turned by a rigid motion of the first setup's frame
//! (the part as the job places it, the stock around it): a flip about X or Y and a turn about
//! the spindle, each about the stock's centre, so the box stays a box and the part keeps its
//! place in it as it does in the vise; then moved so that the setup's zero is the origin. Each
//! setup is then a job of its own (its operations, its work offset, the stock box as it holds
//! it), planned, written and verified as any job is, except that its in-process stock starts as
//! the setup before left it, turned into its frame ([`carried`]).
//!
//! The carried stock is the simulation's z-map with a floor in each cell: the material of a
//! column runs from its floor to its top, so a stock turned over is carried exactly as far as
//! its columns go (a flip about X or Y turns columns into columns): its top is the raw face
//! the setup before never cut, its floor what that setup cut from above, and a cut reaching a
//! floor empties the column. What one column cannot hold (material above a cavity in it) no
//! 3-axis setup from above or below makes.

use glam::DMat3;

use super::run::{prepare, JobOutput};
use super::schema::{Bar, BarAxis, Flip, Job, Up, WorkZero, Workpiece};
use crate::error::{Error, Result};
use crate::geom::{Aabb, DVec2, DVec3};
use crate::mesh::placement::{PartSetup, Placement};
use crate::mesh::Mesh;
use crate::progress::Progress;
use crate::sim::DexelStock;

/// Where a setup holds the part: `p ↦ rotation · (p − centre) + centre + shift` from the first
/// setup's frame (the part as the job places it, before any work zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orientation {
    /// A rotation by quarter turns (a signed permutation of the axes).
    pub rotation: DMat3,
    /// The raw stock's centre in the first setup's frame.
    pub centre: DVec3,
    pub shift: DVec3,
}

impl Orientation {
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.rotation * (p - self.centre) + self.centre + self.shift
    }

    /// The point of the first setup's frame that this one puts at `p`.
    pub fn unapply(&self, p: DVec3) -> DVec3 {
        self.rotation.transpose() * (p - self.centre - self.shift) + self.centre
    }

    /// The box `b` as this setup holds it (a box again: the rotation is by quarter turns).
    pub fn apply_box(&self, b: &Aabb) -> Aabb {
        let (p, q) = (self.apply(b.min), self.apply(b.max));
        Aabb { min: p.min(q), max: p.max(q) }
    }
}

/// What one setup made.
#[derive(Clone, Debug)]
pub struct SetupOutput {
    /// The setup's name (its `name`, or "Setup N").
    pub name: String,
    /// Where it holds the part.
    pub orientation: Orientation,
    /// Its program, as any job's (its part, stock and moves in its own frame).
    pub output: JobOutput,
}

/// The rotation of a flip.
fn flip_rotation(flip: Flip) -> DMat3 {
    match flip {
        Flip::None => DMat3::IDENTITY,
        Flip::AboutX => DMat3::from_diagonal(DVec3::new(1.0, -1.0, -1.0)),
        Flip::AboutY => DMat3::from_diagonal(DVec3::new(-1.0, 1.0, -1.0)),
    }
}

/// The rotation that holds face `up` of the part up.
fn up_rotation(up: Up) -> DMat3 {
    match up {
        Up::PlusZ => DMat3::IDENTITY,
        Up::MinusZ => flip_rotation(Flip::AboutX),
        // About Y by -90°: X up, Z to -X.
        Up::PlusX => DMat3::from_cols(DVec3::Z, DVec3::Y, -DVec3::X),
        Up::MinusX => DMat3::from_cols(-DVec3::Z, DVec3::Y, DVec3::X),
        // About X by 90°: Y up, Z to -Y.
        Up::PlusY => DMat3::from_cols(DVec3::X, DVec3::Z, -DVec3::Y),
        Up::MinusY => DMat3::from_cols(DVec3::X, -DVec3::Z, DVec3::Y),
    }
}

/// The rotation of a turn about Z by `degrees` (a multiple of 90).
fn turn_rotation(degrees: u32) -> DMat3 {
    match (degrees / 90) % 4 {
        1 => DMat3::from_cols(DVec3::Y, -DVec3::X, DVec3::Z),
        2 => DMat3::from_diagonal(DVec3::new(-1.0, -1.0, 1.0)),
        3 => DMat3::from_cols(-DVec3::Y, DVec3::X, DVec3::Z),
        _ => DMat3::IDENTITY,
    }
}

impl Job {
    /// The setups' names: each one's own, or "Setup N".
    pub fn setup_names(&self) -> Vec<String> {
        self.setups.iter().enumerate().map(|(k, s)| if s.name.trim().is_empty() { format!("Setup {}", k + 1) } else { s.name.clone() }).collect()
    }

    /// The job setup `k` is on its own: its operations and work offset, the part already in
    /// its frame (kept where it is given), its stock the box `stock` as it holds it.
    pub(super) fn setup_job(&self, k: usize, stock: Aabb, rotation: DMat3) -> Job {
        let setup = &self.setups[k];
        let mut job = self.clone();
        job.setups = Vec::new();
        job.operations = setup.operations.clone();
        job.name = format!("{} - {}", self.name, self.setup_names()[k]);
        job.part = PartSetup { placement: Placement::Keep, ..PartSetup::default() };
        job.stock.size_box = Some(stock);
        job.stock.margin_sides = None;
        job.stock.zero = None;
        // Bar stock fills the first setup's box along its axis as turned; later setups start
        // from what the one before left.
        job.stock.bar = self.stock.bar.filter(|_| k == 0).map(|bar| Bar { axis: BarAxis::along(rotation * bar.axis.unit()), ..bar });
        // So does a mesh stock (turned as the setup holds it: [`setup_stage`]).
        job.stock.mesh = None;
        if setup.work_offset.is_some() {
            job.post.work_offset = setup.work_offset.clone();
        }
        if let Some(fixtures) = &setup.fixtures {
            job.fixtures = fixtures.clone();
        }
        // The next setup starts from what the simulation left.
        if k + 1 < self.setups.len() {
            job.simulation.verify = true;
        }
        job
    }
}

/// Where each setup of `job` holds a part whose bounds (as the job places it) are `part`, and
/// the raw stock's box in that setup's frame: the frames [`run_setups`] runs the setups in,
/// for a view that shows a setup before it is run.
pub fn setup_frames(job: &Job, part: &Aabb) -> Vec<(Orientation, Aabb)> {
    let raw = job.stock_box(part);
    let mut rotation = DMat3::IDENTITY;
    job.setups
        .iter()
        .enumerate()
        .map(|(k, setup)| {
            rotation = match setup.up {
                Some(up) => turn_rotation(setup.turn) * up_rotation(up),
                None => turn_rotation(setup.turn) * flip_rotation(setup.flip) * rotation,
            };
            let turned = Orientation { rotation, centre: raw.center(), shift: DVec3::ZERO };
            let stock = turned.apply_box(&raw);
            // A quarter-turned box of the part is the turned part's box.
            let held = turned.apply_box(part);
            let shift = match setup.zero.or(job.stock.zero) {
                Some(zero) => -zero.point(&stock, held.max.z),
                // Without a zero, the first setup's is where the part's placement puts it
                // (the centre of its top); a later setup's is the same point of the part as
                // that setup holds it (the face turned up), not wherever the turn about the
                // stock's centre took the first one's: the sheet says the part's top, and an
                // operator touching it off would cut the difference too deep.
                None if k > 0 => job.part.shift(&held),
                None => DVec3::ZERO,
            };
            let orientation = Orientation { shift, ..turned };
            (orientation, orientation.apply_box(&raw))
        })
        .collect()
}

/// Setup `k` of `job` as a job of its own on `part` (placed as the job places it), held as
/// `frame` ([`setup_frames`]) holds it: ready to prepare. Errors it meets are to be named
/// with [`setup_error`].
pub fn setup_stage(job: &Job, k: usize, part: &Mesh, frame: &(Orientation, Aabb)) -> (Job, Mesh) {
    let (orientation, stock) = *frame;
    let mut held = part.clone();
    held.transform(|v| orientation.apply(v));
    let mut setup = job.setup_job(k, stock, orientation.rotation);
    if let Some(blank) = job.blank().filter(|_| k == 0) {
        let mut turned = (*blank).clone();
        turned.transform(|v| orientation.apply(v));
        let name = job.stock.mesh.as_ref().map_or(String::new(), |f| f.name.clone());
        setup.stock.mesh = Some(super::blank::MeshFile::given(&name, turned));
    }
    (setup, held)
}

impl Job {
    /// The work zero with X0 Y0 on the point `p` (X and Y where the job, or its setup `setup`,
    /// holds the part now: a hole's centre as its holes are found), its height kept: the job's
    /// `stock.zero` or the setup's `zero`. `part` is the part's box as the job places it.
    pub fn zero_on(&self, part: &Aabb, setup: Option<usize>, p: DVec2) -> Result<WorkZero> {
        let (stock, zero) = match setup {
            Some(k) => {
                let frame = setup_frames(self, part).get(k).copied().ok_or_else(|| Error::Input(format!("setup {k}: the job has {} setups", self.setups.len())))?;
                (frame.1, self.setups[k].zero.or(self.stock.zero))
            }
            None => (self.stock_at_zero(part).0, self.stock.zero),
        };
        let c = stock.center();
        Ok(WorkZero { at: Some([p.x - c.x, p.y - c.y]), ..zero.unwrap_or_default() })
    }

    /// Setup `k` of this job (one with setups) on its own: its job, `part` (as read) held as
    /// the setup holds it, and where that is; what [`crate::job::wire::PoolWorker::prepare_setup`]
    /// plans, and what finds the holes, bosses and edges that setup's operations pick from.
    pub fn for_setup(&self, k: usize, mut part: Mesh) -> Result<(Job, Mesh, Orientation)> {
        self.validate()?;
        if k >= self.setups.len() {
            return Err(Error::Input(format!("setup {k}: the job has {} setups", self.setups.len())));
        }
        self.place_part(&mut part);
        let frame = setup_frames(self, &part.bounds())[k];
        let (job, held) = setup_stage(self, k, &part, &frame);
        Ok((job, held, frame.0))
    }
}

/// An error of setup `k`, named `name`, said with the setup's place and name.
pub fn setup_error(k: usize, name: &str, e: Error) -> Error {
    match e {
        // A setup's stock is a box made from the job's (its margins, bar or blank, turned as
        // the setup holds it): a message on that box names it so, not a field the user may
        // never have set.
        Error::Input(m) => Error::Input(format!("setups[{k}] ({name}): {}", m.replacen("stock.sizeBox", "the stock as this setup holds it (the job's stock, turned over)", 1))),
        Error::Operation { operation, why } => Error::Operation { operation: format!("{operation} ({name})"), why },
        e => e,
    }
}

/// Runs every setup of `job` on `part` in turn, each from the stock the one before left: one
/// program each. A job without setups is its one setup.
pub fn run_setups(job: &Job, mut part: Mesh, progress: &mut Progress) -> Result<Vec<SetupOutput>> {
    job.validate()?;
    if job.setups.is_empty() {
        let output = super::run(job, part, progress)?;
        let orientation = Orientation { rotation: DMat3::IDENTITY, centre: DVec3::ZERO, shift: DVec3::ZERO };
        return Ok(vec![SetupOutput { name: job.name.clone(), orientation, output }]);
    }
    job.place_part(&mut part);
    let frames = setup_frames(job, &part.bounds());
    let names = job.setup_names();
    let n = job.setups.len();
    let mut out: Vec<SetupOutput> = Vec::with_capacity(n);
    for (k, frame) in frames.iter().enumerate() {
        if job.setups[k].zero.or(job.stock.zero).is_some() {
            super::schema::zero_on_stock(&frame.1, if job.setups[k].zero.is_some() { "zero.at" } else { "stock.zero.at" }).map_err(|e| setup_error(k, &names[k], e))?;
        }
        let (sub, held) = setup_stage(job, k, &part, frame);
        let mut prepared = prepare(&sub, Workpiece::Mesh(held)).map_err(|e| setup_error(k, &names[k], e))?;
        prepared.last_setup = k + 1 == n;
        if let Some(before) = out.last() {
            let left = before.output.verification.as_ref().map(|v| &v.stock).ok_or_else(|| Error::Internal("a setup before another was not simulated".into()))?;
            let (from, to) = (before.orientation, frame.0);
            prepared.carry(laid_like(left, &from, &to), |p, spans| carried(left, &from, &to, p, spans));
        }
        let mut output = progress.within(k as f64 / n as f64, 1.0 / n as f64, &names[k], |p| prepared.run(p)).map_err(|e| setup_error(k, &names[k], e))?;
        output.zero_at = job.zero_at(Some(k));
        out.push(SetupOutput { name: names[k].clone(), orientation: frame.0, output });
    }
    Ok(out)
}

/// The setups' programs as one (`post.oneProgram`, [`crate::post::join_setups`]): `programs`
/// are each setup's sheet figures, program text (unmarked) and why it is not safe to run, if
/// it is not, in order; between two setups the control stops with a message saying how to hold
/// the part, where to set the zero and (without a tool changer) which tool to put in. A setup
/// not safe to run puts its warning, named for it, at the joined program's head.
pub fn one_program(job: &Job, programs: &[(&super::sheet::SheetSetup, &str, Option<&str>)]) -> Result<String> {
    let post = job.post.post();
    let joined: Vec<crate::post::SetupProgram> = programs
        .iter()
        .enumerate()
        .map(|(k, (sheet, gcode, _))| {
            let hold = super::sheet::hold_words(job, k);
            crate::post::SetupProgram {
                name: &sheet.name,
                held: if hold.is_empty() { "hold the part as the setup before did".to_owned() } else { hold.join(", then ") },
                work_offset: sheet.work_offset.clone().unwrap_or_else(|| "the work offset".to_owned()),
                first_tool: if post.tool_change.is_empty() {
                    sheet.tools.first().map(|n| job.tools.iter().find(|t| t.number == *n).map_or_else(|| format!("T{n}"), |t| format!("T{n}, {}", t.describe())))
                } else {
                    None
                },
                gcode,
                seconds: sheet.cycle,
            }
        })
        .collect();
    let joined = crate::post::join_setups(&job.post, &joined)?;
    let problems: Vec<String> = programs.iter().filter_map(|(sheet, _, problem)| problem.map(|p| format!("{}: {p}", sheet.name))).collect();
    Ok(super::run::marked(&joined, (!problems.is_empty()).then(|| problems.join("; ")).as_deref()))
}

/// The material over `p` (in the frame `to`) of the stock `left` in the frame `from`, pushed
/// onto `spans` as `(floor, top)`, lowest first: the column over `p` is a column there too (the
/// frames differ by quarter turns and a shift), its spans turned over when the frames are; an
/// emptied column stays empty. Where this setup stands the part on a side of that one, the
/// column is a line across the columns there, each run of material through it a span.
pub fn carried(left: &DexelStock, from: &Orientation, to: &Orientation, p: DVec2, spans: &mut Vec<(f64, f64)>) {
    let to_before = |z: f64| from.apply(to.unapply(p.extend(z)));
    let (a, b) = (to_before(0.0), to_before(1.0));
    if (b.z - a.z).abs() < 0.5 {
        return carried_across(left, a, b - a, spans);
    }
    let q = a.truncate();
    let g = left.grid();
    let cell = |v: f64, o: f64, n: usize| (((v - o) / g.spacing).round().max(0.0) as usize).min(n - 1);
    let (i, j) = (cell(q.x, g.origin.x, g.nx), cell(q.y, g.origin.y, g.ny));
    // A height there is `a.z + (b.z - a.z) z` of a height z here (b.z - a.z is 1 or -1).
    let here = |z_before: f64| (z_before - a.z) / (b.z - a.z);
    let start = spans.len();
    spans.extend(left.spans(i, j).map(|(floor, top)| {
        let (u, v) = (here(floor), here(top));
        (u.min(v), u.max(v))
    }));
    if b.z < a.z {
        spans[start..].reverse();
    }
}

/// How a setup's cells are laid ([`crate::sim::DexelStock::laid_from`]) so that their centres
/// are the images of the cells' centres of the stock `left` the setup before left, in its
/// orientation `from` (this setup's is `to`): along each axis here that is an axis there, laid
/// from the side the one there is laid from, or the other where the axis turned round. An
/// axis that was vertical there (a part stood on its side) is laid from its minimum.
pub fn laid_like(left: &DexelStock, from: &Orientation, to: &Orientation) -> [bool; 2] {
    let before = |v: DVec3| from.apply(to.unapply(v));
    let there = left.laid_from_max();
    [DVec3::X, DVec3::Y].map(|axis| {
        let d = before(axis) - before(DVec3::ZERO);
        if d.x.abs() > 0.5 {
            there[0] != (d.x < 0.0)
        } else if d.y.abs() > 0.5 {
            there[1] != (d.y < 0.0)
        } else {
            false
        }
    })
}

/// [`carried`] for a setup that stands the part on a side of the one before: the column here
/// is a line across the columns there, `a + dir t` (`dir` along X or Y there), at the height
/// `a.z`. Its material is where that line runs through material there (in the rows within a
/// cell of it, within half a cell of its height, in any of a column's spans): each run of such
/// cells one span, half a cell out each way, the cavities between them (a pocket the setup
/// before cut, now seen from its side) air. A span may only err towards more material.
fn carried_across(left: &DexelStock, a: DVec3, dir: DVec3, spans: &mut Vec<(f64, f64)>) {
    let g = left.grid();
    let along_x = dir.x.abs() > 0.5;
    let (fixed, o_fixed, n_fixed) = if along_x { (a.y, g.origin.y, g.ny) } else { (a.x, g.origin.x, g.nx) };
    // The rows within a cell of the line, and material within half a cell of its height: the
    // line's place rounds to no one row.
    let at = (fixed - o_fixed) / g.spacing;
    let (k0, k1) = ((at - 1.0).ceil().max(0.0), (at + 1.0).floor().min(n_fixed as f64 - 1.0));
    if k1 < k0 {
        return;
    }
    let (n, o, start, sign) = if along_x { (g.nx, g.origin.x, a.x, dir.x) } else { (g.ny, g.origin.y, a.y, dir.y) };
    let slack = g.spacing / 2.0;
    let solid = |c: usize| {
        (k0 as usize..=k1 as usize).any(|k| {
            let (i, j) = if along_x { (c, k) } else { (k, c) };
            left.spans(i, j).any(|(floor, top)| floor - slack <= a.z && a.z <= top + slack)
        })
    };
    // Runs of solid cells, as t (the height here) ranges, lowest first.
    let t_of = |c: usize| (o + c as f64 * g.spacing - start) / sign;
    let first = spans.len();
    let mut run: Option<(usize, usize)> = None;
    for c in 0..=n {
        match (c < n && solid(c), run) {
            (true, None) => run = Some((c, c)),
            (true, Some((c0, _))) => run = Some((c0, c)),
            (false, Some((c0, c1))) => {
                let (u, v) = (t_of(c0), t_of(c1));
                spans.push((u.min(v) - g.spacing / 2.0, u.max(v) + g.spacing / 2.0));
                run = None;
            }
            (false, None) => {}
        }
    }
    if sign < 0.0 {
        spans[first..].reverse();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::StockModel;

    /// A part stood on its side: the column over a point is a line across the columns the
    /// setup before left, and it carries their runs of material as spans, half a cell out each
    /// way, a cavity between them air.
    #[test]
    fn a_stock_stood_on_its_side_carries_the_spans_its_columns_cross() {
        let raw = Aabb { min: DVec3::new(0.0, 0.0, 0.0), max: DVec3::new(10.0, 10.0, 10.0) };
        // Material in the columns whose centres are at x = 1.5 to 2.5 and 5.5 to 7.5, up to
        // z = 5, and between them (x = 3.5 and 4.5) up to 2: a pocket's floor.
        let left = DexelStock::new(&raw, 1.0, 1).with_material(|p| match p.x {
            x if (1.0..3.0).contains(&x) || (5.0..8.0).contains(&x) => (0.0, 5.0),
            x if (3.0..5.0).contains(&x) => (0.0, 2.0),
            _ => (0.0, 0.0),
        });
        let first = Orientation { rotation: DMat3::IDENTITY, centre: raw.center(), shift: DVec3::ZERO };
        // Its -X face up: the old X runs down the new Z (x = 5 + z here, about the centre).
        let side = Orientation { rotation: up_rotation(Up::MinusX), centre: raw.center(), shift: DVec3::ZERO };
        let x_at = |p: DVec2, z: f64| first.apply(side.unapply(p.extend(z))).x;
        let mut spans = Vec::new();
        // A column at the old height 3: the old x from 1 to 3 and from 5 to 8, those cells'
        // edges, the pocket between them air.
        let p = side.apply(DVec3::new(0.0, 4.0, 3.0)).truncate();
        carried(&left, &first, &side, p, &mut spans);
        let xs: Vec<(f64, f64)> = spans.iter().map(|&(f, t)| (x_at(p, t), x_at(p, f))).collect();
        assert_eq!(xs.len(), 2, "{xs:?}");
        assert!(spans[0].1 < spans[1].0, "lowest first: {spans:?}");
        let near = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9;
        assert!(near(xs[0], (5.0, 8.0)) && near(xs[1], (1.0, 3.0)), "{xs:?}");
        // At the old height 1.5 the pocket's floor joins them: one span from x = 1 to 8.
        spans.clear();
        let p = side.apply(DVec3::new(0.0, 4.0, 1.5)).truncate();
        carried(&left, &first, &side, p, &mut spans);
        assert_eq!(spans.len(), 1, "{spans:?}");
        // Above the material there (the old height 7): nothing.
        spans.clear();
        let q = side.apply(DVec3::new(0.0, 4.0, 7.0)).truncate();
        carried(&left, &first, &side, q, &mut spans);
        assert!(spans.is_empty());
        // Each face up is a rotation by quarter turns that holds that face up.
        for (up, face) in [(Up::PlusX, DVec3::X), (Up::MinusX, -DVec3::X), (Up::PlusY, DVec3::Y), (Up::MinusY, -DVec3::Y), (Up::MinusZ, -DVec3::Z), (Up::PlusZ, DVec3::Z)] {
            let r = up_rotation(up);
            assert!((r * face - DVec3::Z).length() < 1e-12 && (r.determinant() - 1.0).abs() < 1e-12, "{up:?}");
        }
    }

    /// A stock turned over about X, and then a quarter about Z: its cells are laid so that
    /// their centres are the images of the centres before, and what the setup before left
    /// carries cell for cell, on a box no whole number of cells wide (a drilled cell stays one
    /// cell, the material adds up exactly).
    #[test]
    fn a_stock_turned_over_carries_cell_for_cell() {
        let raw = Aabb { min: DVec3::new(-5.3, -3.85, -4.0), max: DVec3::new(5.3, 3.85, 4.0) };
        let hole = DVec2::new(-4.8, 3.4);
        let cut = |p: DVec2| if p.distance(hole) < 0.3 { (0.0, 0.0) } else { (-4.0, 4.0) };
        let left = DexelStock::new(&raw, 0.5, 1).with_material(cut);
        let first = Orientation { rotation: DMat3::IDENTITY, centre: DVec3::ZERO, shift: DVec3::ZERO };
        let over = Orientation { rotation: flip_rotation(Flip::AboutX), centre: DVec3::ZERO, shift: DVec3::new(0.7, -0.2, 1.0) };
        let turned = Orientation { rotation: DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2) * over.rotation, centre: DVec3::ZERO, shift: DVec3::ZERO };
        let empties = |s: &DexelStock| {
            let g = s.grid();
            (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).filter(|&(i, j)| s.top(i, j) <= s.floor(i, j)).count()
        };
        assert_eq!(empties(&left), 2, "the drilled cells");
        let mut before = (left, first);
        for to in [over, turned] {
            let lay = laid_like(&before.0, &before.1, &to);
            let boxed = to.apply_box(&raw);
            let carried_stock = DexelStock::new(&boxed, 0.5, 1).laid_from(lay).with_spans(|p, spans| carried(&before.0, &before.1, &to, p, spans));
            let g = carried_stock.grid();
            for j in 0..g.ny {
                for i in 0..g.nx {
                    // Each centre here is a centre there.
                    let there = before.1.apply(to.unapply(g.node(i, j).extend(0.0))).truncate();
                    let h = before.0.grid();
                    let f = (there - h.origin) / h.spacing;
                    assert!((f - f.round()).abs().max_element() < 1e-9, "{lay:?}: ({i}, {j}) is {f} there");
                }
            }
            assert_eq!(empties(&carried_stock), 2, "{lay:?}");
            assert!((carried_stock.volume() - before.0.volume()).abs() < 1e-9, "{} {}", carried_stock.volume(), before.0.volume());
            before = (carried_stock, to);
        }
    }
}
