//! Drilling: spot, drill (G81), drill with a dwell (G82), peck with full retract (G83) and
//! chip-break pecking (G73), at a drawing's circles or a part's vertical holes
//! ([`crate::holes`]), picked by index or by a diameter range. Holes are taken in a short
//! order (nearest neighbour, then 2-opt); each is drilled from the R plane just above the
//! material over it to the hole's bottom, or for a through hole past it by the drill's point
//! and a breakthrough. Each hole's moves are marked as a [`Cycle`], so a control with canned
//! cycles gets one `G8x` block per hole and GRBL the same moves written out.

use serde::{Deserialize, Serialize};

use crate::cutter::Cutter;
use crate::error::{Error, Result};
use crate::geom::segment::Segment;
use crate::holes::{Bottom, Hole};
use crate::machining::holes::{entry_height, hole_path, HolePick};
use crate::machining::report::Groove;
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::tool::Tool;
use crate::toolpath::cycle::{Cycle, CycleKind};
use crate::toolpath::Move;

/// Which drilling cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum DrillCycle {
    /// A spot (centre) drill or a V-bit marks each hole: a cone `spotDiameter` across at the
    /// top (G81, or G82 with a dwell).
    Spot,
    /// Straight to the bottom and out (G81).
    #[default]
    Drill,
    /// To the bottom, a dwell, out (G82).
    Dwell,
    /// Pecks, out of the hole after each to clear the chips (G83).
    Peck,
    /// Pecks, backing off a little after each to break the chip (G73).
    ChipBreak,
}

/// Where the tool goes between holes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ReturnLevel {
    /// Back to the clearance height (G98): over clamps and the part's high places.
    #[default]
    Initial,
    /// To the R plane (G99): shorter, where nothing stands between the holes.
    Retract,
}

/// Drilling holes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Drill {
    /// Default value: "drill".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// Default value: 1.
    pub tool: u32,
    /// Default value: drill.
    pub cycle: DrillCycle,
    /// The holes to drill.
    #[serde(flatten)]
    #[ts(flatten)]
    pub pick: HolePick,
    /// Depth below each hole's top (mm). Default value: the hole's own (through: past its
    /// bottom by the drill's point and the breakthrough; a spot: the depth of a cone
    /// `spotDiameter` across).
    pub depth: Option<f64>,
    /// How far the drill's full diameter goes past a through hole's bottom (mm). Default value: 0.5.
    pub breakthrough: f64,
    /// The spot's diameter at the top (mm). Default value: the hole's diameter, at most the tool's.
    pub spot_diameter: Option<f64>,
    /// Depth of each peck (mm; peck and chip break). Default value: 2.
    pub peck: f64,
    /// Seconds at the bottom (dwell). Default value: 0.5.
    pub dwell: f64,
    /// The R plane's height above the material over the hole (mm). Default value: 1.
    pub retract: f64,
    /// Default value: initial.
    pub return_to: ReturnLevel,
    /// Its own clearance in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Clearance,
}

impl Default for Drill {
    fn default() -> Self {
        Drill {
            name: "drill".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            cycle: DrillCycle::Drill,
            pick: HolePick::default(),
            depth: None,
            breakthrough: 0.5,
            spot_diameter: None,
            peck: 2.0,
            dwell: 0.5,
            retract: 1.0,
            return_to: ReturnLevel::Initial,
        }
    }
}

impl Drill {
    /// A drill mark (a drawing's POINT) drilled with `cutter`: as wide as the drill.
    fn sized(h: Hole, cutter: &Cutter) -> Hole {
        if h.mark {
            Hole { diameter: cutter.diameter, ..h }
        } else {
            h
        }
    }

    /// How deep it drills `h` with `cutter`: to its depth where one is set; a spot to the depth
    /// of a cone `spotDiameter` across; else the hole's own (a through hole past its bottom by
    /// the drill's point and the breakthrough, a cone-bottomed one by the point).
    fn bottom(&self, h: &Hole, cutter: &Cutter) -> f64 {
        match (self.depth, self.cycle == DrillCycle::Spot) {
            (Some(d), _) => h.top - d,
            (None, true) => {
                let across = self.spot_diameter.unwrap_or(h.diameter).min(cutter.diameter);
                h.top - (across / 2.0 - cutter.tip_radius()).max(0.0) / (cutter.point_angle().to_radians() / 2.0).tan()
            }
            (None, false) if h.through => h.bottom - cutter.tip_length() - self.breakthrough,
            (None, false) if h.bottom_shape == Bottom::Cone => h.bottom - cutter.tip_length(),
            (None, false) => h.bottom,
        }
    }

    /// The setting that does not fit drilling `h` to `bottom` with `tool`, with its field: a
    /// peck deeper than the hole or so shallow it pecks past [`crate::limits::MAX_PECKS`], a
    /// hole deeper than the flutes.
    fn misfit(&self, h: &Hole, bottom: f64, tool: &Tool) -> Option<(&'static str, String)> {
        let depth = h.top - bottom;
        if matches!(self.cycle, DrillCycle::Peck | DrillCycle::ChipBreak) && self.peck > depth + self.retract {
            return Some((
                "peck",
                format!("the peck ({} mm) is deeper than the hole at X{:.3} Y{:.3} ({depth:.3} mm from its top): drill it without pecking, or peck less", self.peck, h.center.x, h.center.y),
            ));
        }
        let pecks = depth / self.peck;
        if matches!(self.cycle, DrillCycle::Peck | DrillCycle::ChipBreak) && pecks > crate::limits::MAX_PECKS {
            return Some((
                "peck",
                format!(
                    "a peck of {} mm makes {pecks:.0} pecks in the hole at X{:.3} Y{:.3} ({depth:.3} mm deep; at most {:.0}): peck deeper, or check the setting's unit",
                    crate::limits::shown(self.peck),
                    h.center.x,
                    h.center.y,
                    crate::limits::MAX_PECKS
                ),
            ));
        }
        (depth > tool.cutter.flute_length + 1e-9).then(|| {
            (
                if self.depth.is_some() { "depth" } else { "tool" },
                format!("the hole at X{:.3} Y{:.3} is {depth:.2} mm deep, deeper than T{}'s flutes ({} mm)", h.center.x, h.center.y, tool.number, tool.cutter.flute_length),
            )
        })
    }
}

impl Operate for Drill {
    named_operation!(Either);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FieldUnit as U, FormField as F, OperationForm, Picks};
        let mut fields = F::name_and_tool().to_vec();
        fields.push(F::choice(
            "cycle",
            "Cycle",
            &[
                ("drill", "drill (G81)"),
                ("peck", "peck, out of the hole after each (G83)"),
                ("chipBreak", "peck, breaking the chip (G73)"),
                ("dwell", "drill, dwell at the bottom (G82)"),
                ("spot", "spot (a spot drill or V-bit)"),
            ],
        ));
        fields.extend(F::which_holes());
        fields.extend([
            F::length("depth", "Depth below the hole's top", 0.01).empty("the hole's, through holes past the bottom by the point and the breakthrough"),
            F::length("breakthrough", "Breakthrough", 0.0),
            F::length("peck", "Peck depth", 0.01),
            F::number("dwell", "Dwell at the bottom", U::Seconds).range(0.0, None),
            F::length("spotDiameter", "Spot diameter", 0.01).empty("the hole's"),
            F::length("retract", "R plane above the material", 0.01),
            F::choice("returnTo", "Between holes", &[("initial", "back to the clearance height (G98)"), ("retract", "to the R plane (G99)")]),
            F::marks(),
        ]);
        fields.extend(crate::machining::settings::Clearance::fields());
        OperationForm::new("drill holes (spot, drill, peck)", fields).picks(Picks::Holes)
    }

    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_all_but_thread_mills(cutter)
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        if let Some(d) = self.depth {
            positive("depth", d)?;
        }
        self.pick.validate()?;
        if let Some(v) = self.spot_diameter {
            positive("spotDiameter", v)?;
        }
        not_negative("breakthrough", self.breakthrough)?;
        positive("peck", self.peck)?;
        not_negative("dwell", self.dwell)?;
        if self.dwell > 600.0 {
            return Err(FieldError { field: "dwell", message: format!("must be at most 600 seconds (got {})", self.dwell) });
        }
        positive("retract", self.retract)
    }

    fn hole_problems(&self, holes: &[Hole], tool: &Tool) -> Vec<(&'static str, String)> {
        // The first hole that does not fit says it (as the plan would).
        self.pick.chosen(holes).into_iter().map(|h| Self::sized(h, &tool.cutter)).find_map(|h| self.misfit(&h, self.bottom(&h, &tool.cutter), tool)).into_iter().collect()
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cutter = &tool.cutter;
        let spot = self.cycle == DrillCycle::Spot;
        if spot && !cutter.is_cone() {
            return Err(Error::operation(&self.name, format!("spotting needs a spot drill, a drill or a V-bit; T{} is a {}", tool.number, cutter.describe())));
        }
        // A drill mark is drilled as wide as its drill.
        let picked: Vec<_> = self.pick.pick(ctx, &self.name)?.into_iter().map(|h| Self::sized(h, cutter)).collect();
        let profile = cutter.profile();
        let tip = cutter.tip_length();
        let initial = ctx.heights.clearance;
        let kind = match self.cycle {
            DrillCycle::Spot | DrillCycle::Drill => CycleKind::Drill,
            DrillCycle::Dwell => CycleKind::Dwell,
            DrillCycle::Peck => CycleKind::Peck,
            DrillCycle::ChipBreak => CycleKind::ChipBreak,
        };
        let mut moves: Vec<Move> = Vec::new();
        let mut cycles = Vec::new();
        // On a sheet, what each hole may lose: its circle, to the drill's depth (the sheet's
        // verification holds everything else to the sheet's top).
        let mut grooves = Vec::new();
        let (mut flat_floors, mut wider, mut narrower) = (0, 0, 0);
        for h in &picked {
            let bottom = self.bottom(h, cutter);
            if self.depth.is_none() && !spot && !h.through && h.bottom_shape == Bottom::Flat && cutter.is_cone() {
                flat_floors += 1;
            }
            if let Some((_, message)) = self.misfit(h, bottom, &tool) {
                return Err(Error::operation(&self.name, message));
            }
            if !spot {
                if cutter.diameter > h.diameter + 1e-6 {
                    wider += 1;
                } else if cutter.diameter < h.diameter - 0.01 {
                    narrower += 1;
                }
            }
            // R just above what stands over the hole now (the part's top there, or stock not
            // yet cut).
            let r = entry_height(ctx, h, &profile, self.retract);
            if r > initial {
                return Err(Error::operation(
                    &self.name,
                    format!(
                        "the R plane ({r:.3}) lies above the clearance height ({initial:.3}): raise its 'Clearance height' (Heights), or 'Safe height above the stock' (Stock tab; stock.clearance)"
                    ),
                ));
            }
            let from_initial = cycles.is_empty() || self.return_to == ReturnLevel::Initial;
            // Under G99 the tool stands at the last hole's R plane: the next hole starts there
            // when that is no lower than its own R, else from the clearance height.
            let standing = moves.last().map_or(initial, |m: &Move| m.to().z);
            let begin = if from_initial || standing < r { initial } else { standing };
            if begin != standing {
                moves.push(Move::Rapid { to: moves.last().map_or(h.center, |m| m.to().truncate()).extend(begin) });
            }
            let mut c = Cycle {
                kind,
                first: moves.len(),
                count: 0,
                at: h.center,
                initial: begin,
                r,
                bottom,
                to_initial: self.return_to == ReturnLevel::Initial,
                peck: self.peck,
                dwell: if kind == CycleKind::Dwell { self.dwell } else { 0.0 },
                feed: tool.plunge_rate,
            };
            if ctx.sheet.is_some() {
                grooves.push(Groove { path: vec![Segment::line(h.center, h.center)], radius: h.diameter / 2.0, depth: ctx.stock.max.z - bottom });
            }
            let m = c.moves();
            c.count = m.len();
            moves.extend(m);
            cycles.push(c);
        }
        if flat_floors > 0 {
            ctx.warn(
                &self.name,
                format!("{flat_floors} blind holes have flat floors: the drill's point leaves a cone below them and their full diameter {tip:.2} mm short; finish the floors with a flat end mill"),
            );
        }
        if wider > 0 {
            ctx.warn(&self.name, format!("{wider} holes are narrower than T{} ({} mm): the drill makes them wider", tool.number, cutter.diameter));
        }
        if narrower > 0 {
            ctx.note(&self.name, format!("{narrower} holes are wider than T{} ({} mm): bore them to size after drilling", tool.number, cutter.diameter));
        }
        if moves.last().is_some_and(|m| m.to().z < initial) {
            moves.push(Move::Rapid { to: moves.last().expect("a move").to().truncate().extend(initial) });
        }
        // The first cycle's first move is the rapid to its centre at the clearance height, where
        // the path starts: kept (a move of no length), so the cycles' indices hold.
        Ok(Planned { paths: vec![hole_path(&self.name, &tool, moves, cycles, initial)], grooves, ..Planned::default() })
    }
}
