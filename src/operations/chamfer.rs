//! Chamfering (countersinking) holes' top edges, or a drawing's loops (outside its outlines,
//! inside its holes), with a V-bit, chamfer mill or spot drill: the user gives the chamfer's
//! width at the top; the tool's angle gives its depth. The cone's side, not its tip, cuts the
//! edge: the tip goes `extraDepth` below the chamfer's foot, the cone's axis at the distance
//! from the edge where its side lies on the chamfer. A hole: one circle (climb), in from the
//! hole's axis and back to it. A drawing's loops: the sheet's parts grown by that distance (so
//! the axis keeps it from every edge, and the cone's reach into the material is the chamfer's
//! width and no more, corners included), each loop entered along a ramp.

use serde::{Deserialize, Serialize};

use crate::drawing::Loop;
use crate::error::{Error, Result};
use crate::geom::segment::Segment;
use crate::machining::holes::{circle, entry_height, hole_path, point, HolePick};
use crate::machining::path2d::{cut_line, start_nearest};
use crate::machining::report::Groove;
use crate::machining::settings::Direction;
use crate::machining::sheet;
use crate::machining::{named_operation, not_negative, positive, Context, FieldError, Operate, Planned};
use crate::offset::offset;
use crate::tool::Tool;
use crate::toolpath::Move;

/// Chamfering holes' edges.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Chamfer {
    /// Default value: "chamfer".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// A V-bit, chamfer mill or spot drill. Default value: 1.
    pub tool: u32,
    /// The holes whose edges to chamfer.
    #[serde(flatten)]
    #[ts(flatten)]
    pub pick: HolePick,
    /// The chamfer's width at the top (mm, measured out from the hole's edge). Default value: 0.5.
    pub width: f64,
    /// How far below the chamfer's foot the tip goes, so the cone's side cuts the edge (mm).
    /// Default value: 0.2.
    pub extra_depth: f64,
    /// Height above the material over the hole where feeding starts (mm). Default value: 1.
    pub retract: f64,
    /// Default value: climb.
    pub direction: Direction,
    /// Which edges: the holes' (picked as above), or a drawing's loops (on `layers`, or those
    /// named in `loops`). Default value: holes.
    pub edges: ChamferEdges,
    /// A drawing's layers whose loops to chamfer (edges: loops). Default value: all.
    pub layers: Vec<String>,
    /// The drawing's loops to chamfer, by index as `swarf drawing` lists them (edges: loops).
    /// Default value: all on the layers.
    pub loops: Vec<usize>,
    /// The angle a loop's chamfer is entered at, along the loop (degrees). Default value: 10.
    pub ramp_angle: f64,
    /// Its own clearance in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Clearance,
}

/// The edges a chamfer breaks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ChamferEdges {
    /// The top edges of holes.
    #[default]
    Holes,
    /// A drawing's loops: outside its outlines, inside its holes.
    Loops,
    /// A part's sharp top edges: where a horizontal face meets a steep wall falling away from
    /// it, round every such outline of the face (`loops` picks them by the number `swarf
    /// edges` lists them by; all by default).
    PartEdges,
}

impl Default for Chamfer {
    fn default() -> Self {
        Chamfer {
            name: "chamfer".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            pick: HolePick::default(),
            width: 0.5,
            extra_depth: 0.2,
            retract: 1.0,
            direction: Direction::Climb,
            edges: ChamferEdges::Holes,
            layers: Vec::new(),
            loops: Vec::new(),
            ramp_angle: 10.0,
        }
    }
}

impl Operate for Chamfer {
    named_operation!(Either);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm, Picks};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend(F::which_holes());
        fields.extend([
            F::choice("edges", "Edges", &[("holes", "the holes' edges"), ("loops", "a drawing's loops (holes inside)"), ("partEdges", "a part's sharp top edges")]),
            F::words("layers", "Loops on layers", "edges: loops; with commas").empty("all"),
            F::loops("Loops", "edges: loops, or a part's top edges as swarf edges lists them; numbers with commas, or click them", "all on the layers, every sharp edge"),
            F::length("width", "Chamfer width at the top", 0.01),
            F::length("extraDepth", "Tip below the chamfer", 0.0),
            F::start_above(),
            F::direction(),
            F::degrees("rampAngle", "Ramp angle along a loop", 0.1, 89.0),
            F::marks(),
        ]);
        fields.extend(crate::machining::settings::Clearance::fields());
        OperationForm::new("chamfer edges (holes, loops, a part's top)", fields).picks(Picks::Holes)
    }

    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        crate::machining::takes_all_but_thread_mills(cutter)
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        self.pick.validate()?;
        positive("width", self.width)?;
        not_negative("extraDepth", self.extra_depth)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)?;
        positive("retract", self.retract)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cutter = &tool.cutter;
        if !cutter.is_cone() {
            return Err(Error::operation(&self.name, format!("a chamfer needs a V-bit, chamfer mill or spot drill; T{} is a {}", tool.number, cutter.describe())));
        }
        // The chamfer's depth at the cone's angle, and the cone's radius where it meets the top.
        let depth = self.width / (cutter.point_angle().to_radians() / 2.0).tan();
        let at_top = self.at_top(&tool, depth);
        if at_top > cutter.radius() + 1e-9 {
            return Err(Error::operation(
                &self.name,
                format!(
                    "a {} mm chamfer with the tip {} mm below it needs a cone {:.3} mm across at the top; T{} is {} mm across",
                    self.width,
                    self.extra_depth,
                    2.0 * at_top,
                    tool.number,
                    cutter.diameter
                ),
            ));
        }
        match self.edges {
            ChamferEdges::Loops => return self.plan_loops(ctx, &tool, depth, at_top),
            ChamferEdges::PartEdges => return self.plan_part_edges(ctx, &tool, depth, at_top),
            ChamferEdges::Holes => {}
        }
        let holes = self.pick.sized(ctx, &self.name)?;
        let clearance = ctx.heights.clearance;
        let ccw = self.direction == Direction::Climb;
        let profile = cutter.profile();
        let mut moves = Vec::new();
        let mut grooves = Vec::new();
        let mut below = 0;
        for h in &holes {
            let r_hole = h.diameter / 2.0;
            let rho = r_hole + self.width - at_top;
            if rho < 0.0 {
                return Err(Error::operation(
                    &self.name,
                    format!(
                        "the φ{} hole at X{:.3} Y{:.3} is too small for this chamfer with T{}: its cone is {:.3} mm across at the top",
                        crate::limits::shown((h.diameter * 1000.0).round() / 1000.0),
                        h.center.x,
                        h.center.y,
                        tool.number,
                        2.0 * at_top
                    ),
                ));
            }
            let tip = h.top - depth - self.extra_depth;
            if !h.through && h.bottom > tip {
                return Err(Error::operation(
                    &self.name,
                    format!("the hole at X{:.3} Y{:.3} is {:.3} mm deep: the tip would reach its floor ({:.3} mm needed)", h.center.x, h.center.y, h.depth(), depth + self.extra_depth),
                ));
            }
            let c = h.center;
            // On a part, nothing within the tool's reach may stand above the hole's rim (a hole
            // in a counterbore's floor): the tool's full width stands there.
            if ctx.sheet.is_none() {
                let reach = rho + cutter.radius();
                let highest = crate::zmap::drop::PointDrop::new(&ctx.part, &crate::cutter::Profile::new(reach, 0.0), &ctx.tolerances).at(c, f64::NEG_INFINITY);
                if highest > h.top + ctx.tolerances.gouge {
                    below += 1;
                    continue;
                }
            }
            let start = entry_height(ctx, h, &profile, self.retract);
            moves.push(Move::Rapid { to: c.extend(clearance) });
            moves.push(Move::Rapid { to: c.extend(start) });
            moves.push(Move::Line { to: c.extend(tip), feed: tool.plunge_rate });
            moves.push(Move::Line { to: point(c, rho, 0.0, tip), feed: tool.feed_rate });
            if rho > 1e-6 {
                circle(c, rho, 0.0, tip, ccw, tool.feed_rate, &mut moves);
            }
            moves.push(Move::Line { to: c.extend(tip), feed: tool.feed_rate });
            moves.push(Move::Rapid { to: c.extend(clearance) });
            // What the chamfer takes: within the cone's reach at the top of its circle.
            let path: Vec<Segment> = if rho > 1e-6 { Loop::circle(c, rho).segments().collect() } else { vec![Segment::line(c, c)] };
            grooves.push(Groove { path, radius: at_top, depth: ctx.stock.max.z - tip });
        }
        if below > 0 {
            ctx.warn(
                &self.name,
                format!("{below} holes lie below the part around them (in a counterbore's floor, a pocket's): not chamfered, T{}'s full width would meet the walls above", tool.number),
            );
        }
        if moves.is_empty() {
            return Err(Error::operation(&self.name, "no hole's edge is clear for the tool to chamfer"));
        }
        Ok(Planned { paths: vec![hole_path(&self.name, &tool, moves, Vec::new(), clearance)], grooves, ..Planned::default() })
    }
}

impl Chamfer {
    /// The cone's radius at the top of a chamfer `depth` deep, its tip the extra depth below.
    fn at_top(&self, tool: &Tool, depth: f64) -> f64 {
        tool.cutter.tip_radius() + (depth + self.extra_depth) * (tool.cutter.point_angle().to_radians() / 2.0).tan()
    }

    /// A drawing's loops chamfered: the sheet's parts (the loops on the layers) grown by the
    /// axis's distance from the edge, `at_top - width`; each grown loop that keeps that distance
    /// from a chosen loop is cut at the tip's depth, entered along the loop at the ramp angle.
    fn plan_loops(&self, ctx: &mut Context, tool: &Tool, depth: f64, at_top: f64) -> Result<Planned> {
        let (drawing, _) = sheet::sheet(ctx, &self.name)?;
        let shape = drawing.shape(&self.layers).map_err(|e| Error::operation(&self.name, e.to_string()))?;
        if let Some(&k) = self.loops.iter().find(|&&k| k >= drawing.loops.len()) {
            return Err(Error::operation(&self.name, format!("the drawing has no loop {k} (it has {})", drawing.loops.len())));
        }
        let chosen: Vec<&Loop> = drawing
            .loops
            .iter()
            .enumerate()
            .filter(|(i, l)| (self.layers.is_empty() || self.layers.contains(&l.layer)) && (self.loops.is_empty() || self.loops.contains(i)))
            .map(|(_, l)| &l.path)
            .collect();
        if chosen.is_empty() {
            return Err(Error::operation(&self.name, "none of the chosen loops is on the chosen layers"));
        }
        let away = at_top - self.width;
        let grown = offset(&shape, away, &ctx.tolerances);
        // A grown loop follows a chosen one where it keeps the axis's distance from it.
        let near = away + ctx.tolerances.chain.max(1e-6);
        let follows = |l: &Loop, c: &Loop| l.vertices.iter().any(|v| c.distance_to(v.p) <= near);
        let rings: Vec<&Loop> = grown.loops.iter().filter(|l| chosen.iter().any(|c| follows(l, c))).collect();
        let lost = chosen.iter().filter(|c| !grown.loops.iter().any(|l| follows(l, c))).count();
        if lost > 0 {
            ctx.warn(&self.name, format!("{lost} loops are too small inside for T{}'s cone at this chamfer: not chamfered", tool.number));
        }
        if rings.is_empty() {
            return Err(Error::operation(&self.name, format!("no chosen loop leaves room for T{}'s cone at this chamfer", tool.number)));
        }
        let top = ctx.stock.max.z;
        let rings = rings.into_iter().map(|r| (r.clone(), top)).collect();
        self.cut_rings(ctx, tool, rings, depth)
    }

    /// A part's sharp top edges chamfered: each flat's region grown by the axis's distance from
    /// the edge, as a drawing's loops are, cut at the tip's depth below the flat; a ring along
    /// which the exact drop of the cone onto the part stands higher than the edge itself would
    /// hold it (another face within the cone's reach: it would cut more than the chamfer) is
    /// left, named.
    fn plan_part_edges(&self, ctx: &mut Context, tool: &Tool, depth: f64, at_top: f64) -> Result<Planned> {
        if ctx.sheet.is_some() {
            return Err(Error::operation(&self.name, "a part's edges: this is a drawing (chamfer its loops instead)"));
        }
        let edges = crate::mesh::edges::top_edges(&ctx.part);
        if let Some(&k) = self.loops.iter().find(|&&k| k >= edges.len()) {
            return Err(Error::operation(&self.name, format!("the part has no top edge {k} (it has {}; swarf edges lists them)", edges.len())));
        }
        let chosen: Vec<usize> = (0..edges.len()).filter(|&k| if self.loops.is_empty() { edges[k].sharp } else { self.loops.contains(&k) }).collect();
        if let Some(&k) = chosen.iter().find(|&&k| !edges[k].sharp) {
            return Err(Error::operation(&self.name, format!("the part's top edge {k} is not sharp all round (a rounded or bevelled edge, or a step up): a chamfer cannot follow it")));
        }
        if chosen.is_empty() {
            return Err(Error::operation(&self.name, "the part has no sharp top edge (a horizontal face falling away down a steep wall) to chamfer"));
        }
        let away = at_top - self.width;
        let near = away + ctx.tolerances.chain.max(1e-6);
        let profile = tool.cutter.profile();
        let drop = crate::zmap::drop::PointDrop::new(&ctx.part, &profile, &ctx.tolerances);
        // Where the cone stands on the edge alone, its axis `away` from it.
        let on_edge = profile.height(away);
        let mut rings = Vec::new();
        let mut refused = Vec::new();
        let mut flats: Vec<usize> = chosen.iter().map(|&k| edges[k].flat).collect();
        flats.dedup();
        for flat in flats {
            let group: Vec<&crate::mesh::edges::TopEdge> = edges.iter().filter(|e| e.flat == flat).collect();
            let z = group[0].z;
            let shape = crate::drawing::Shape::new(group.iter().map(|e| e.outline.clone()).collect());
            let grown = offset(&shape, away, &ctx.tolerances);
            let mine: Vec<&Loop> = chosen.iter().filter(|&&k| edges[k].flat == flat).map(|&k| &edges[k].outline).collect();
            for ring in grown.loops.iter().filter(|l| mine.iter().any(|c| l.vertices.iter().any(|v| c.distance_to(v.p) <= near))) {
                // The cone's drop along the ring, every tenth of a millimetre.
                let worst = ring.segments().flat_map(|s| {
                    let n = (s.length() / 0.1).ceil().max(1.0) as usize;
                    (0..n).map(move |i| s.point_at(i as f64 / n as f64))
                });
                match worst.map(|p| (p, drop.at(p, f64::NEG_INFINITY))).find(|&(_, h)| h > z - on_edge + ctx.tolerances.gouge) {
                    Some((p, _)) => refused.push(p),
                    None => rings.push((ring.clone(), z)),
                }
            }
        }
        if !refused.is_empty() {
            let at: Vec<String> = refused.iter().take(3).map(|p| format!("X{:.3} Y{:.3}", p.x, p.y)).collect();
            ctx.warn(&self.name, format!("{} edges not chamfered: T{}'s cone would cut the part beyond the chamfer (another face within its reach, at {})", refused.len(), tool.number, at.join(", ")));
        }
        if rings.is_empty() {
            return Err(Error::operation(&self.name, format!("no sharp top edge leaves room for T{}'s cone at this chamfer", tool.number)));
        }
        self.cut_rings(ctx, tool, rings, depth)
    }

    /// Cuts `rings` (each with the height of the edge it breaks) with the tip `depth` and the
    /// extra depth below it, the nearest next, each entered along a ramp.
    fn cut_rings(&self, ctx: &mut Context, tool: &Tool, rings: Vec<(Loop, f64)>, depth: f64) -> Result<Planned> {
        let angle = self.ramp_angle.to_radians();
        let mut cursor = sheet::cursor(ctx, tool);
        let mut out: Vec<Move> = Vec::new();
        let mut grooves = Vec::new();
        let mut left = rings;
        while !left.is_empty() {
            // The nearest loop next, from its point nearest the tool.
            let here = cursor.at.truncate();
            let k = (0..left.len()).min_by(|&a, &b| left[a].0.distance_to(here).total_cmp(&left[b].0.distance_to(here))).expect("loops left");
            let (ring, top) = left.swap_remove(k);
            let tip = top - depth - self.extra_depth;
            // Grown outlines run counter-clockwise and holes clockwise: the material on the
            // left, a conventional cut; climb runs them the other way.
            let ring = if self.direction == Direction::Climb { ring.reversed() } else { ring };
            let path = start_nearest(&ring, here);
            grooves.push(Groove { path: path.clone(), radius: self.at_top(tool, depth), depth: ctx.stock.max.z - tip });
            let start_z = cursor.material_top(path.iter().copied(), ctx.stock.max.z, tip, ctx.tolerances.gouge).unwrap_or(tip);
            cursor.safe = start_z.max(tip) + cursor.gap;
            cursor.reposition(path[0].a.extend(start_z), &mut out);
            cut_line(&path, true, start_z, tip, depth + self.extra_depth, angle, tool.feed_rate, &mut out);
            cursor.moved(&out);
        }
        Ok(Planned { paths: vec![sheet::toolpath(&self.name, tool, out, ctx.heights.clearance)], grooves, ..Planned::default() })
    }
}
