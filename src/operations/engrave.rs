//! Engraving along drawn lines: the tool's centre on the line itself (no offset), for text,
//! scribe lines and open chains a profile cannot cut. Each line is cut in passes no deeper than
//! the step-down; every pass descends along the line at the ramp angle, never straight down
//! into material. An open chain is cut back and forth (each pass runs the other way, so the
//! tool never travels back in the air), a closed loop in laps like a profile's; a last pass at
//! the full depth follows the whole line. Lines are taken nearest first.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geom::segment::Segment;
use crate::geom::tolerance::HAIR;
use crate::machining::path2d::{arc_lengths, cut_line, nearest_end, reversed};
use crate::machining::report::Groove;
use crate::machining::{named_operation, positive, sheet, Context, FieldError, Operate, Planned};
use crate::toolpath::Move;

/// Engraving on a drawing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Engrave {
    /// Default value: "engrave".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// Default value: 1.
    pub tool: u32,
    /// Depth below the sheet's top (mm). Default value: 0.5.
    pub depth: f64,
    /// Largest depth cut in one pass (mm). Default value: 0.5.
    pub stepdown: f64,
    /// Steepest descent along the line (degrees). Default value: 10.
    pub ramp_angle: f64,
    /// Layers to engrave (empty: all). Default value: empty.
    pub layers: Vec<String>,
    /// Engrave the open chains on those layers. Default value: true.
    pub chains: bool,
    /// Closed loops to engrave, by their index (as `swarf drawing` numbers them). Default value: none.
    pub loops: Vec<usize>,
    /// Engrave every closed loop on those layers too. Default value: false.
    pub all_loops: bool,
    /// Its own clearance (and retract) in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Moves,
}

impl Default for Engrave {
    fn default() -> Self {
        Engrave {
            name: "engrave".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            depth: 0.5,
            stepdown: 0.5,
            ramp_angle: 10.0,
            layers: Vec::new(),
            chains: true,
            loops: Vec::new(),
            all_loops: false,
        }
    }
}

/// A line to engrave.
struct Line {
    path: Vec<Segment>,
    closed: bool,
}

impl Operate for Engrave {
    named_operation!(OnDrawing);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm};
        let mut fields = F::sheet_cut();
        fields.extend([
            F::check("chains", "open chains on the layers"),
            F::check("allLoops", "every closed loop on the layers"),
            F::loops("Loops", "numbers with commas, or click them in the view", "none"),
            F::ramp_angle(),
        ]);
        fields.extend(crate::machining::settings::Moves::fields());
        OperationForm::new("engrave lines and text (2D)", fields)
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.stepdown)
    }

    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_all_but_thread_mills(cutter)
    }

    fn check_scale(&self, ctx: &Context) -> crate::error::Result<()> {
        sheet::check_levels(ctx, &self.name, Some(self.depth), self.stepdown)
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        positive("depth", self.depth)?;
        positive("stepdown", self.stepdown)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        // How far from the line the tool cuts at the top: its radius, or a V-bit's cone where
        // it crosses the top at the depth (a single-line font's stroke width).
        let reach = if tool.cutter.is_cone() { tool.cutter.profile().reach_squared(self.depth).sqrt().min(tool.cutter.radius()) } else { tool.cutter.radius() };
        let (drawing, thickness) = sheet::sheet(ctx, &self.name)?;
        if self.depth > thickness + sheet::BREAKTHROUGH {
            return Err(Error::operation(&self.name, format!("the depth {} mm is deeper than the {thickness} mm sheet", self.depth)));
        }
        let on = |layer: &String| self.layers.is_empty() || self.layers.contains(layer);
        let mut lines: Vec<Line> = Vec::new();
        if self.chains {
            lines.extend(drawing.open.iter().filter(|c| on(&c.layer) && !c.path.is_empty()).map(|c| Line { path: c.path.clone(), closed: false }));
        }
        for (i, l) in drawing.loops.iter().enumerate() {
            if on(&l.layer) && (self.all_loops || self.loops.contains(&i)) {
                lines.push(Line { path: l.path.segments().collect(), closed: true });
            }
        }
        if let Some(&k) = self.loops.iter().find(|&&k| k >= drawing.loops.len()) {
            return Err(Error::operation(&self.name, format!("the drawing has no loop {k} (it has {})", drawing.loops.len())));
        }
        if lines.is_empty() {
            let why = if self.chains { "no open chains on its layers; name loops to engrave, or set allLoops" } else { "nothing chosen: set chains, loops or allLoops" };
            return Err(Error::operation(&self.name, why));
        }
        let top = ctx.stock.max.z;
        let z_final = top - self.depth;
        let angle = self.ramp_angle.to_radians();
        let mut cursor = sheet::cursor(ctx, &tool);
        let mut out: Vec<Move> = Vec::new();
        let mut grooves = Vec::new();
        let mut in_air = 0;
        // Nearest line first, from its nearer end.
        let mut left: Vec<Line> = lines;
        while !left.is_empty() {
            let here = cursor.at.truncate();
            let (k, flip) = nearest_end(&left, here, |l| (l.path[0].a, (!l.closed).then(|| l.path[l.path.len() - 1].b)));
            let line = left.swap_remove(k);
            let path = if flip { reversed(&line.path) } else { line.path };
            let (_, total) = arc_lengths(&path);
            if total <= HAIR {
                continue;
            }
            grooves.push(Groove { path: path.clone(), radius: reach, depth: self.depth });
            let Some(start_z) = cursor.material_top(path.iter().copied(), top, z_final, ctx.tolerances.gouge) else {
                in_air += 1;
                continue;
            };
            cursor.safe = start_z + cursor.gap;
            cursor.reposition(path[0].a.extend(start_z), &mut out);
            cut_line(&path, line.closed, start_z, z_final, self.stepdown, angle, tool.feed_rate, &mut out);
            cursor.moved(&out);
        }
        if in_air > 0 {
            ctx.note(&self.name, format!("{in_air} lines have no material left along them and are not engraved"));
        }
        let paths = if out.is_empty() { Vec::new() } else { vec![sheet::toolpath(&self.name, &tool, out, ctx.heights.clearance)] };
        Ok(Planned { paths, grooves, ..Planned::default() })
    }
}
