//! What holds the part while a job runs ([`crate::sim::hold`]): a vise's jaws close on the
//! material the setup starts from, each must grip at least its least grip of it, and after
//! every operation the in-process stock must still join the part to what the fixtures grip (or,
//! without fixtures, to the stock's sides). An operation that cuts the part free is an error
//! where fixtures are given (unless the part is marked held otherwise, or it is the last
//! operation of the last setup: the part coming off), and a warning where none are.

use super::fixtures::ViseAxis;
use super::schema::Job;
use crate::error::{Error, Result, Warning};
use crate::geom::DVec2;
use crate::machining::context::Context;
use crate::sim::hold::{band_extent, jaw_contact, joined, Grips, Hold};
use crate::zmap::HeightField;

/// Whether, and where, the operations so far cut the part free.
#[derive(Clone, Debug, Default)]
pub struct HoldWatch {
    /// The part's heights on the in-process stock's grid, made at the first check.
    part: Option<HeightField>,
    /// The first operation (its index in the job) after which a piece of the part was joined to
    /// nothing gripped, and a point of that piece.
    pub freed: Option<(usize, DVec2)>,
    /// Whether the part was held before any operation (no check is said where it was not).
    held_at_start: Option<bool>,
    /// The stock's rim as the setup came, where it is no box (a bar, a casting): what holds
    /// it without fixtures.
    rim: Option<Vec<bool>>,
    /// Whether the part was joined to gripped material after the last check.
    pub held_now: bool,
}

/// Whether the job's part can be judged: a mesh part, verified, cut from a box, a bar or a
/// casting (a drawing's sheet has its own tabs).
fn judged(job: &Job, ctx: &Context) -> bool {
    job.simulation.verify && ctx.sheet.is_none() && !ctx.part.faces.is_empty()
}

/// What grips the stock in `ctx`: its fixtures' boxes as they stand, or its sides (a bar's or
/// a casting's rim as it came, `rim`).
fn grips(ctx: &Context, rim: Option<&Vec<bool>>) -> Grips {
    if ctx.keep_out.is_empty() {
        rim.map_or(Grips::Sides, |r| Grips::Rim(r.clone()))
    } else {
        // The fixtures themselves, not grown by their clearance.
        Grips::Boxes(ctx.keep_out.iter().map(|h| crate::geom::Aabb { min: h.solid.min + h.grown, max: h.solid.max - h.grown }).collect())
    }
}

/// A vise's jaws close on the material within their grip as the setup starts: where a setup
/// before cut round the part, on what it left (the part's own faces), not on the stock's box;
/// the fixtures the planning keeps out of are made again.
pub fn follow_jaws(job: &mut Job, ctx: &mut Context) {
    let Some(mut vise) = job.fixtures.vise else { return };
    if ctx.sheet.is_some() {
        return;
    }
    let stock = ctx.stock;
    let along_x = vise.closes == ViseAxis::X;
    let Some((lo, hi)) = band_extent(ctx.sim.stock(), along_x, vise.span_on(&stock), stock.min.z, stock.min.z + vise.grip, vise.least()) else { return };
    let (box_lo, box_hi) = super::fixtures::Vise { faces: None, ..vise }.faces_on(&stock);
    let (lo, hi) = (lo.max(box_lo), hi.min(box_hi));
    if lo <= box_lo + 1e-9 && hi >= box_hi - 1e-9 {
        return;
    }
    vise.faces = Some((lo, hi));
    job.fixtures.vise = Some(vise);
    ctx.keep_out = job.fixtures.keep_out(&stock);
    ctx.solid = (!ctx.keep_out.is_empty()).then(|| super::fixtures::solid(&ctx.part, &ctx.keep_out));
}

/// Each of a vise's jaws grips at least its least grip of material as the setup starts: an
/// error naming the jaw otherwise.
pub fn jaws_grip(job: &Job, ctx: &Context) -> Result<()> {
    let Some(vise) = job.fixtures.vise else { return Ok(()) };
    if ctx.sheet.is_some() {
        return Ok(());
    }
    let stock = ctx.stock;
    let along_x = vise.closes == ViseAxis::X;
    let (from, to) = (stock.min.z, stock.min.z + vise.grip);
    // The jaws (the first two fixtures held: the low face's, then the high face's), each judged
    // at the cells just inside its face.
    let (lo, hi) = vise.faces_on(&stock);
    for (held, inside) in job.fixtures.held(&stock).iter().zip([lo + 1e-6, hi - 1e-6]) {
        let contact = jaw_contact(ctx.sim.stock(), along_x, inside, vise.span_on(&stock), from, to);
        if contact < vise.least() - 1e-9 {
            return Err(Error::Input(format!(
                "{} grips {contact:.3} mm of material (it reaches {:.3} mm up the stock's side), less than its least grip of {:.3} mm: the stock as this setup starts has {} there; hold the part by what is left (a lower grip, soft jaws, a fixture), or leave more in the setup before (a 'Bottom height' above the parting line)",
                held.name,
                vise.grip,
                vise.least(),
                if contact <= 0.0 { "no material".to_owned() } else { format!("only {contact:.3} mm") }
            )));
        }
    }
    Ok(())
}

impl HoldWatch {
    /// Judges the in-process stock of `ctx` after operation `op` of `job` has cut it.
    pub fn after(&mut self, job: &Job, ctx: &mut Context, op: Option<usize>) {
        if self.freed.is_some() || !judged(job, ctx) {
            return;
        }
        let stock = ctx.sim.stock();
        let grid = stock.grid();
        let part = self.part.get_or_insert_with(|| crate::zmap::cc::cc_zmap(&ctx.part, grid, f64::NEG_INFINITY, &job.tolerances));
        if self.rim.is_none() && (job.stock.bar.is_some() || job.stock.mesh.is_some()) {
            self.rim = Some(crate::sim::hold::rim(stock));
        }
        let hold = joined(stock, part, &grips(ctx, self.rim.as_ref()));
        self.held_now = hold == Hold::Held;
        match (op, hold) {
            (None, h) => self.held_at_start = Some(h != Hold::NoPart && !matches!(h, Hold::Free(_))),
            (Some(k), Hold::Free(at)) if self.held_at_start == Some(true) => self.freed = Some((k, at)),
            _ => {}
        }
    }

    /// What the job says of a part still joined to its bar as the last setup ends: that it is
    /// to be parted off below the part's bottom (`bottom`, the part's lowest Z in the setup's
    /// program), as a lathe's cut-off or a saw does, the cut faced after.
    pub fn parting_off(&self, job: &Job, last_setup: bool, bottom: f64) -> Option<Warning> {
        let bar = job.stock.bar?;
        (last_setup && self.held_now && self.held_at_start == Some(true)).then(|| {
            Warning::of(
                "stock",
                format!(
                    "the part is still joined to the φ{} bar as the job ends: part it off below its bottom (Z{bottom:.3} in this setup's program) with a saw or a cut-off tool, and face the cut (a setup turned over with a face, or by hand)",
                    crate::limits::shown(bar.diameter)
                ),
            )
            .note()
        })
    }

    /// The part's heights on the stock's grid, as the checks made them (for the verification).
    pub fn take_part(&mut self) -> Option<HeightField> {
        self.part.take()
    }

    /// What the job says of a part cut free: a warning, or the problem that makes the program
    /// not safe to run (fixtures given, the part not marked held otherwise, and not the last
    /// operation of the last setup).
    pub fn said(&self, job: &Job, last_op: Option<usize>, last_setup: bool) -> (Option<Warning>, Option<String>) {
        let Some((k, at)) = self.freed else { return (None, None) };
        let name = job.operations[k].name();
        let place = format!("X{:.3} Y{:.3}", at.x, at.y);
        if job.fixtures.held_otherwise {
            let w = format!("it cuts the part free at {place} of the stock {}; the part is held otherwise, as the job says", if job.fixtures.is_empty() { "round it" } else { "the fixtures grip" });
            return (Some(Warning::of(name, w).note()), None);
        }
        if job.fixtures.is_empty() {
            let w = format!("it cuts the part free at {place}: after it nothing joins the part to the stock's sides; hold the part by its bottom (a plate, screws or tape), stop the cut above the parting line (a 'Bottom height'), or leave tabs");
            return (Some(Warning::of(name, w)), None);
        }
        if last_setup && last_op == Some(k) {
            let w = format!("it cuts the part free at {place} as the job ends: the part comes off loose; catch it, or leave a skin to break off");
            return (Some(Warning::of(name, w)), None);
        }
        (None, Some(format!("{name} cuts the part free at {place}: after it nothing joins the part to what the fixtures grip; stop the cut above the parting line (a 'Bottom height'), leave tabs, or mark the part as held otherwise (fixtures.heldOtherwise)")))
    }
}
