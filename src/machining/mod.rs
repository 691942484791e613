//! The machinery operations share, owned by none of them: the contract every operation kind
//! follows ([`Operate`]), the context they plan in ([`Context`]: inputs, caches and the
//! in-process stock), what a plan gives back ([`Planned`]), the settings they share
//! ([`settings`]), and the ways of cutting they are built from: levels and their order
//! (`levels.rs`), ring clearing (`rings.rs`), raster passes (`raster.rs`), the 2D cursor
//! (`path2d.rs`), the air feed (`air.rs`), walls (`walls.rs`) and sheets (`sheet.rs`).
//!
//! Every path keeps the tool tip on or above the CL surface plus its allowance, so none can
//! gouge (DESIGN.md, idea 1). The operations themselves are in [`crate::operations`], one file
//! each, importing only from here and the geometry below.

pub mod adaptive;
pub mod air;
pub mod context;
pub mod fixtures;
pub mod form;
pub mod holders;
pub mod holes;
pub mod levels;
pub mod path2d;
pub mod pencil;
pub mod raster;
pub mod report;
pub mod rings;
pub mod scallop;
pub mod settings;
pub mod sheet;
pub mod threads;
pub mod walls;
pub mod waterline;

pub use context::Context;
pub use report::Planned;

/// The most levels an operation may cut ([`crate::limits`]): more is a setting off by orders
/// of magnitude (a 100 mm stock at a 0.1 mm step-down is 1000 levels); and the most raster
/// passes (a 1 m stock at 0.1 mm is 10,000 passes).
pub use crate::limits::{MAX_LEVELS, MAX_PASSES};

/// The error for `count` of `what` (levels, passes) made by `field` = `value` over `span` mm,
/// when it passes `most`.
pub fn too_many(op: &str, what: &str, count: f64, most: f64, field: &str, value: f64, span: f64) -> Result<()> {
    if count <= most {
        return Ok(());
    }
    Err(crate::error::Error::operation(op, format!("{field} {} mm makes {count:.0} {what} over {span:.1} mm (at most {most:.0}): check the setting and the part's units", crate::limits::shown(value))))
}

/// Refuses, before the work, levels `stepdown` apart down `stock` past [`MAX_LEVELS`], or
/// reading more level-map nodes on a `grid` mm grid than [`level_work`] allows.
pub fn check_levels(op: &str, stock: crate::geom::Aabb, stepdown: f64, grid: f64) -> Result<()> {
    let size = stock.max - stock.min;
    too_many(op, "levels", size.z / stepdown, MAX_LEVELS, "a step-down of", stepdown, size.z)?;
    level_work(op, (size.z / stepdown).ceil().max(1.0), &format!("a step-down of {} mm", crate::limits::shown(stepdown)), grid, size)
}

/// Refuses, before the work, `levels` levels that each read a level map on a `grid` mm grid
/// over a stock of `size`, when they read more than [`crate::limits::MAX_LEVEL_NODES`] nodes
/// in all; `why` names what makes the levels ("a step-down of 0.05 mm").
pub fn level_work(op: &str, levels: f64, why: &str, grid: f64, size: crate::geom::DVec3) -> Result<()> {
    let work = levels * (size.x / grid + 1.0) * (size.y / grid + 1.0);
    if work <= crate::limits::MAX_LEVEL_NODES {
        return Ok(());
    }
    Err(crate::error::Error::operation(
        op,
        format!(
            "{levels:.0} levels ({why}) on a {} mm grid over the {:.0} × {:.0} × {:.0} mm stock read about {} million level-map nodes (at most {:.0} million): choose fewer levels or a coarser grid, or check the part's units",
            crate::limits::shown(grid),
            size.x,
            size.y,
            size.z,
            crate::limits::shown((work / 1e6).round().max(1.0)),
            crate::limits::MAX_LEVEL_NODES / 1e6
        ),
    ))
}

use crate::error::Result;
use crate::progress::Progress;

/// A setting of an operation that does not fit: the field (as the job file names it) and why.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldError {
    pub field: &'static str,
    pub message: String,
}

/// `Ok` when `value` is a positive number no larger than [`crate::limits::MAX_SIZE`] (every
/// length of an operation: a depth, a step, an allowance, a radius), else the error naming
/// `field`.
pub fn positive(field: &'static str, value: f64) -> Result<(), FieldError> {
    if value > 0.0 && value <= crate::limits::MAX_SIZE {
        Ok(())
    } else {
        Err(FieldError { field, message: format!("must be a positive number, at most {} (got {})", crate::limits::MAX_SIZE, crate::limits::shown(value)) })
    }
}

/// `Ok` when `value` is zero or a positive number no larger than [`crate::limits::MAX_SIZE`].
pub fn not_negative(field: &'static str, value: f64) -> Result<(), FieldError> {
    if (0.0..=crate::limits::MAX_SIZE).contains(&value) {
        Ok(())
    } else {
        Err(FieldError { field, message: format!("must be zero or more, at most {} (got {})", crate::limits::MAX_SIZE, crate::limits::shown(value)) })
    }
}

/// `Ok` when `value` is a number no farther from zero than [`crate::limits::MAX_SIZE`].
pub fn finite(field: &'static str, value: f64) -> Result<(), FieldError> {
    if crate::limits::in_size(value) {
        Ok(())
    } else {
        Err(FieldError { field, message: format!("must be a number from -{0} to {0} (got {1})", crate::limits::MAX_SIZE, crate::limits::shown(value)) })
    }
}

/// `Ok` when `value` is a share of the tool's diameter above 0 and at most 1 (a step-over).
pub fn fraction(field: &'static str, value: f64) -> Result<(), FieldError> {
    if value > 0.0 && value <= 1.0 {
        Ok(())
    } else {
        Err(FieldError { field, message: format!("must be a share of the tool's diameter above 0 and at most 1 (got {})", crate::limits::shown(value)) })
    }
}

/// `Ok` when `value` is an angle in degrees from `least` to `most`.
pub fn angle(field: &'static str, value: f64, least: f64, most: f64) -> Result<(), FieldError> {
    if (least..=most).contains(&value) {
        Ok(())
    } else {
        Err(FieldError { field, message: format!("must be an angle from {least}° to {most}° (got {})", crate::limits::shown(value)) })
    }
}

/// What a part or drawing needs to be for an operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Works {
    /// A part (mesh): 3D operations on its CL z-map.
    OnPart,
    /// A drawing (DXF, SVG) as a sheet: 2.5D operations.
    OnDrawing,
    /// Either (drilling: a drawing's circles or a part's holes).
    Either,
}

impl From<Works> for form::Applies {
    fn from(w: Works) -> Self {
        match w {
            Works::OnPart => form::Applies::Part,
            Works::OnDrawing => form::Applies::Drawing,
            Works::Either => form::Applies::Either,
        }
    }
}

/// The [`Operate`] methods every operation's options answer from their `name`, `tool` and
/// `enabled` fields, and what it works on (`OnPart` or `OnDrawing`).
macro_rules! named_operation {
    ($works:ident) => {
        fn name(&self) -> &str {
            &self.name
        }

        fn tool(&self) -> u32 {
            self.tool
        }

        fn enabled(&self) -> bool {
            self.enabled
        }

        fn works(&self) -> $crate::machining::Works {
            $crate::machining::Works::$works
        }
    };
}
pub(crate) use named_operation;

/// What the finishing operations cut with: the torus family and the cones that cut on their
/// side (V-bits, chamfer mills and spot drills: a V-bit's 3D carving); a twist drill cuts at
/// its point only, a thread mill only its thread.
pub fn takes_end_mills_and_v_bits(cutter: &crate::cutter::Cutter) -> Result<(), &'static str> {
    use crate::cutter::Shape;
    match cutter.shape {
        Shape::Drill | Shape::ThreadMill => Err("flat, ball and bull-nose end mills, V-bits and spot drills"),
        _ => Ok(()),
    }
}

/// What the finishing by a cusp height cuts with: ball and bull-nose end mills, whose rounded
/// corner sets the cusp between passes.
pub fn takes_rounded_corners(cutter: &crate::cutter::Cutter) -> Result<(), &'static str> {
    if cutter.profile().corner > 0.0 {
        Ok(())
    } else {
        Err("ball and bull-nose end mills (the cusp follows their rounded corner)")
    }
}

/// [`Operate::takes`] for the operations that cut with any tool but a thread mill (drilling,
/// chamfering, engraving).
pub fn takes_all_but_thread_mills(cutter: &crate::cutter::Cutter) -> Result<(), &'static str> {
    if cutter.shape == crate::cutter::Shape::ThreadMill {
        Err("end mills, drills and V-bits")
    } else {
        Ok(())
    }
}

/// One kind of operation.
pub trait Operate {
    /// Shown in progress, warnings and the program's comments.
    fn name(&self) -> &str;
    /// The number of the tool it asks for (an operation that picks its own tools names the
    /// first it may use).
    fn tool(&self) -> u32;
    /// Every tool it names (an operation that chooses its own tools names those it may choose
    /// from, or none for the whole library); the job checks each is in the library.
    fn tools(&self) -> Vec<u32> {
        vec![self.tool()]
    }
    /// Whether the job runs it (a disabled operation stays in the job file).
    fn enabled(&self) -> bool;
    /// Whether it cuts with `cutter`, and if not, what it cuts with (for the message): roughing
    /// takes the torus family (flat, ball, bull nose) and refuses a cone (drill, spot drill,
    /// V-bit) or a thread mill by name; finishing takes V-bits too
    /// ([`takes_end_mills_and_v_bits`]); drilling, chamfering and engraving take cones, thread
    /// milling only thread mills.
    fn takes(&self, cutter: &crate::cutter::Cutter) -> Result<(), &'static str> {
        if cutter.is_cone() || cutter.shape == crate::cutter::Shape::ThreadMill {
            Err("flat, ball and bull-nose tools")
        } else {
            Ok(())
        }
    }
    fn works(&self) -> Works;
    /// Material it leaves on the part's surface (mm); 2.5D operations leave theirs on the walls
    /// (their verification keeps it in the regions they cut) and have none.
    fn allowance(&self) -> f64 {
        0.0
    }
    /// How deep it steps into material at its tool's full width, a level at a time (mm), for the
    /// kinds that do: the step-down the tool's flutes must reach (`Job::problems`).
    fn stepdown(&self) -> Option<f64> {
        None
    }
    /// What does not fit between its settings, its tool and the holes it takes of `holes` (every
    /// hole found in the workpiece, as the page lists them): `(field, message)`, said as the
    /// settings are typed (`Job::problems_with`) rather than after the plan: a hole deeper
    /// than the flutes, a peck deeper than the hole.
    fn hole_problems(&self, _holes: &[crate::holes::Hole], _tool: &crate::tool::Tool) -> Vec<(&'static str, String)> {
        Vec::new()
    }
    /// Checks its settings before any work.
    fn validate(&self) -> Result<(), FieldError>;
    /// Whether it plans round the fixtures itself (the 3D operations, dropped onto the part
    /// with the fixtures joined: [`Context::solid`]); the others' paths are kept clear of them
    /// after they plan ([`fixtures::keep_clear`]).
    fn plans_round_fixtures(&self) -> bool {
        false
    }

    /// The page's form for these options ([`form`]): their fields, in the words a machinist
    /// uses, with units and ranges.
    fn form() -> form::OperationForm
    where
        Self: Sized;
    /// Whether the work its settings ask for on this stock is within reason (levels, passes),
    /// checked before any work starts: an error naming the setting where it is not (a step-down
    /// of 0.001 mm over an 18 mm stock is 18,000 levels, minutes of silence).
    fn check_scale(&self, _ctx: &Context) -> Result<()> {
        Ok(())
    }
    /// The CL surfaces it will ask the context for, named before it plans, so that a pool of
    /// workers can make them first, band by band (none by default: it makes what it needs as
    /// it plans).
    fn surfaces(&self, _ctx: &Context) -> Result<Vec<context::SurfaceRequest>> {
        Ok(Vec::new())
    }
    /// The CL surfaces whose level maps ([`crate::zmap::contour::LevelMap`]) it will ask for
    /// (z-level work), named before it plans like [`Operate::surfaces`].
    fn level_maps(&self, _ctx: &Context) -> Result<Vec<context::SurfaceRequest>> {
        Ok(Vec::new())
    }
    /// The regions of its levels, as work a pool of workers can share out just before it
    /// plans, on the in-process stock as it is then (z-level roughing and what clears the same
    /// levels another way; none by default).
    fn region_work(&self, _ctx: &mut Context, _progress: &mut Progress) -> Result<Option<levels::RegionWork>> {
        Ok(None)
    }
    /// Its tool paths, each with its tool, planned in the job's context, with its own report
    /// ([`Planned`]). `progress` is this operation's own: stages run from 0 to 1.
    fn plan(&self, ctx: &mut Context, progress: &mut Progress) -> Result<Planned>;
}
