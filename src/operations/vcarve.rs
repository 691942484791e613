//! V-carving a drawing's regions (letters, logos, inlays; islands inside) with a V-bit: the
//! tool's axis runs along the region's medial axis ([`crate::drawing::medial`]), at each point
//! as deep as the point's clearance allows, so the cone's side touches the boundary on both
//! sides: depth = (clearance − tip radius) / tan(half angle). Sharp corners get their spikes
//! (the axis runs into them as its clearance falls to 0).
//!
//! With a maximum depth, the region is flat-bottomed there (Vectric's "flat depth"): the V-bit
//! cuts the walls down to it along the region shrunk by the clearance at that depth, and a
//! second, flat tool clears the floor inside by pocketing at that depth (when one is named).

use serde::{Deserialize, Serialize};

use crate::drawing::medial::{medial_axis, Branch};
use crate::drawing::{Loop, Shape};
use crate::error::{Error, Result, Warning};
use crate::machining::path2d::{arc_lengths, follow, nearest_end, start_nearest, Heights};
use crate::machining::report::SheetCut;
use crate::machining::rings::{clear_down, Clearing, RingSetup};
use crate::machining::settings::PocketPattern;
use crate::machining::{named_operation, positive, sheet, Context, FieldError, Operate, Planned};
use crate::offset::offset;
use crate::toolpath::Move;

/// V-carving a drawing's regions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct VCarve {
    /// Default value: "V-carve".
    pub name: String,
    /// Whether the job runs it. Default value: true.
    pub enabled: bool,
    /// A V-bit (or a spot drill). Default value: 1.
    pub tool: u32,
    /// The layers whose loops make the regions. Default value: all.
    pub layers: Vec<String>,
    /// The loops to carve, by index as `swarf drawing` lists them (each with the loops inside
    /// it as islands). Default value: all on the layers.
    pub loops: Vec<usize>,
    /// The deepest the V-bit goes (mm); deeper, the region is flat-bottomed at this depth.
    /// Default value: none (as deep as the region is wide).
    pub max_depth: Option<f64>,
    /// A flat end mill that clears the flat floor below `maxDepth`. Default value: none (the
    /// V-bit cuts the walls down to the floor; the floor is left with a warning).
    pub flat_tool: Option<u32>,
    /// The flat tool's step-over (fraction of its diameter). Default value: 0.4.
    pub stepover_fraction: f64,
    /// The flat tool's step-down (mm). Default value: 2.
    pub stepdown: f64,
    /// Its own clearance (and retract) in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Moves,
}

impl Default for VCarve {
    fn default() -> Self {
        VCarve {
            name: "V-carve".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            layers: Vec::new(),
            loops: Vec::new(),
            max_depth: None,
            flat_tool: None,
            stepover_fraction: 0.4,
            stepdown: 2.0,
        }
    }
}

/// Points along the medial axis closer than this (mm) are not taken apart.
const STEP: f64 = 0.1;

impl Operate for VCarve {
    named_operation!(OnDrawing);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::words("layers", "Layers", "with commas").empty("all"),
            F::loops("Loops", "numbers with commas, or click them in the view", "every loop on the layers"),
            F::length("maxDepth", "Flat depth", 0.01).empty("as deep as the letters are wide"),
            F::int("flatTool", "Flat tool for the floor", 1.0, None).note("its number").empty("none"),
            F::length("stepdown", "Flat tool's step-down", 0.01),
            F::fraction("stepoverFraction", "Flat tool's step-over", "fraction of its diameter", 1.0),
        ]);
        fields.extend(crate::machining::settings::Moves::fields());
        OperationForm::new("V-carve letters and shapes (2D)", fields)
    }

    fn tools(&self) -> Vec<u32> {
        std::iter::once(self.tool).chain(self.flat_tool).collect()
    }

    /// A V-bit carves; a flat end mill may clear the floor.
    fn takes(&self, cutter: &crate::cutter::Cutter) -> std::result::Result<(), &'static str> {
        if cutter.is_cone() || cutter.shape == crate::cutter::Shape::Flat {
            Ok(())
        } else {
            Err("V-bits, chamfer mills and spot drills (and a flat end mill for the floor)")
        }
    }

    fn validate(&self) -> std::result::Result<(), FieldError> {
        self.moves.validate()?;
        if let Some(d) = self.max_depth {
            positive("maxDepth", d)?;
        }
        crate::machining::fraction("stepoverFraction", self.stepover_fraction)?;
        positive("stepdown", self.stepdown)
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let cutter = &tool.cutter;
        if !cutter.is_cone() {
            return Err(Error::operation(&self.name, format!("V-carving needs a V-bit, chamfer mill or spot drill; T{} is a {}", tool.number, cutter.describe())));
        }
        let (drawing, thickness) = sheet::sheet(ctx, &self.name)?;
        let (walls, picked) = sheet::selected(drawing, &self.name, &self.layers, &self.loops)?;
        let picked: Vec<Loop> = picked.iter().map(|&k| walls.shape.loops[k].clone()).collect();
        let tan = (cutter.point_angle().to_radians() / 2.0).tan();
        let tip = cutter.tip_radius();
        // The clearance at which the cone is as deep as it may go: its own height, the sheet,
        // the maximum depth.
        let cone_depth = (cutter.radius() - tip) / tan;
        let deepest = self.max_depth.unwrap_or(f64::INFINITY).min(cone_depth).min(thickness);
        let c_max = tip + deepest * tan;
        let region = if self.loops.is_empty() && self.max_depth.is_none() {
            let reach = format!("wider than T{}'s cone reaches at {deepest:.3} mm", tool.number);
            let (region, carved, note) = carvable(&walls.shape, &walls.index, c_max, &reach, ctx);
            if let Some(note) = note {
                let said = format!("no loops picked: {note}; pick loops (Loops) to carve such regions, flat with maxDepth and a flatTool");
                ctx.warnings.push(Warning::of(&self.name, said).offering(carved));
            }
            region
        } else {
            sheet::pocket_region(&walls.shape, &picked, self.loops.is_empty())
        };
        let top = ctx.stock.max.z;
        let z_at = |c: f64| top - ((c.min(c_max) - tip).max(0.0) / tan);
        let axis = medial_axis(&region, ctx.tolerances.arc_fit, STEP, c_max).map_err(|e| Error::operation(&self.name, e))?;
        if axis.is_empty() {
            return Err(Error::operation(&self.name, "the regions have no inside to carve"));
        }
        let widest = axis.iter().flat_map(|b| b.clearance.iter().copied()).fold(0.0f64, f64::max);
        let flat = widest > c_max + 1e-6;
        if flat && self.max_depth.is_none() {
            let why = if deepest == thickness { format!("the {thickness} mm sheet") } else { format!("T{}'s cone ({} mm across)", tool.number, cutter.diameter) };
            ctx.warn(
                &self.name,
                format!(
                    "the regions are up to {:.3} mm wide, deeper than {why} lets the V-bit go: they are carved flat at {deepest:.3} mm; give it a deepest cut and a flat tool to clear the floor (maxDepth, flatTool)",
                    2.0 * widest
                ),
            );
        }
        let mut out: Vec<Move> = Vec::new();
        let mut paths = Vec::new();
        // The flat floor: cleared by the flat tool, then its walls cut by the V-bit.
        let floor = if flat { offset(&region, -c_max, &ctx.tolerances) } else { Shape::new(Vec::new()) };
        if flat && !floor.is_empty() {
            match self.flat_tool {
                Some(n) => {
                    let flat_tool = ctx.tool(&self.name, n)?.clone();
                    if flat_tool.cutter.shape != crate::cutter::Shape::Flat {
                        return Err(Error::operation(&self.name, format!("the flat tool T{n} is a {}: the floor needs a flat end mill", flat_tool.cutter.describe())));
                    }
                    let r = flat_tool.cutter.radius();
                    let mut cursor = sheet::cursor(ctx, &flat_tool);
                    let setup = RingSetup { tool_radius: r, top, feed: flat_tool.feed_rate, cursor: &mut cursor, tol: &ctx.tolerances, unfinished: false };
                    let moves = flat_floor(&floor, r, self, deepest, setup);
                    if moves.is_empty() {
                        ctx.warn(&self.name, format!("the flat tool T{n} fits nowhere on the floor: the floor is left"));
                    } else {
                        paths.push(sheet::toolpath(&self.name, &flat_tool, moves, ctx.heights.clearance));
                    }
                }
                None if self.max_depth.is_some() => {
                    ctx.warn(&self.name, format!("the flat floor at {deepest:.3} mm ({:.0} mm²) is left: name a flatTool to clear it", floor.area().abs()));
                }
                None => {}
            }
        }
        let mut cursor = sheet::cursor(ctx, &tool);
        // The floor's walls at the full depth, each loop from its point nearest the tool.
        let z_floor = z_at(c_max);
        for l in &floor.loops {
            let path = start_nearest(l, cursor.at.truncate());
            cursor.reposition(path[0].a.extend(z_floor), &mut out);
            let (_, total) = arc_lengths(&path);
            follow(&path, 0.0, total, &Heights::constant(z_floor), tool.feed_rate, &mut out);
            cursor.moved(&out);
        }
        // The medial axis, nearest branch first, from its nearer end.
        let mut left: Vec<Branch> = axis;
        while !left.is_empty() {
            let here = cursor.at.truncate();
            let (k, flip) = nearest_end(&left, here, |b| (b.points[0], b.points.last().copied()));
            let branch = left.swap_remove(k);
            let branch = if flip { branch.reversed() } else { branch };
            let first = branch.points[0].extend(z_at(branch.clearance[0]));
            cursor.reposition(first, &mut out);
            for k in 1..branch.points.len() {
                let (p0, c0, p1, c1) = (branch.points[k - 1], branch.clearance[k - 1], branch.points[k], branch.clearance[k]);
                // Where the clearance crosses the flat depth's, the depth stops (or starts) falling.
                if (c0 - c_max) * (c1 - c_max) < 0.0 {
                    let t = (c_max - c0) / (c1 - c0);
                    out.push(Move::Line { to: p0.lerp(p1, t).extend(z_at(c_max)), feed: tool.feed_rate });
                }
                out.push(Move::Line { to: p1.extend(z_at(c1)), feed: tool.feed_rate });
            }
            cursor.moved(&out);
        }
        paths.push(sheet::toolpath(&self.name, &tool, out, ctx.heights.clearance));
        let cuts = vec![SheetCut { region, inside: true, depth: deepest, leave: 0.0, scrap: false }];
        Ok(Planned { paths, cuts, ..Planned::default() })
    }
}

/// With no loops picked, the regions a V-bit carves: of the drawing's regions as its loops
/// nest (each loop with the loops just inside it as holes), those at even depths (what the
/// file fills) or, where those hold a region wider than the cone reaches (`c_max`, its
/// clearance at the deepest it may go) and the odd ones leave less such area, those at odd
/// depths: on a sign of letters drawn on a background rectangle, the letters. Of the chosen
/// regions only those the cone reaches across are kept, and the note names the rest by their
/// drawing index (`index`) and size, and why (`reach`); the kept regions' outer loops come
/// with it by drawing index (picked, they carve the same). Where no region is narrow enough,
/// the drawing as it is (carved flat, with the operation's own warning).
fn carvable(shape: &Shape, index: &[usize], c_max: f64, reach: &str, ctx: &Context) -> (Shape, Vec<usize>, Option<String>) {
    let parents = shape.parents();
    let mut depth = vec![0usize; parents.len()];
    for (i, d) in depth.iter_mut().enumerate() {
        let mut at = parents[i];
        while let Some(p) = at {
            *d += 1;
            at = parents[p];
        }
    }
    let regions: Vec<Shape> = (0..shape.loops.len())
        .map(|i| {
            let mut loops = vec![shape.loops[i].counter_clockwise()];
            loops.extend((0..parents.len()).filter(|&j| parents[j] == Some(i)).map(|j| shape.loops[j].counter_clockwise().reversed()));
            Shape::from_oriented(loops)
        })
        .collect();
    let reached: Vec<bool> = regions.iter().map(|r| offset(r, -(c_max + 1e-6), &ctx.tolerances).is_empty()).collect();
    let wide = |parity: usize| -> f64 { (0..regions.len()).filter(|&i| depth[i] % 2 == parity && !reached[i]).map(|i| regions[i].area().abs()).sum() };
    let (even, odd) = (wide(0), wide(1));
    if even == 0.0 {
        return (shape.clone(), Vec::new(), None);
    }
    let parity = usize::from(odd < even);
    let kept: Vec<usize> = (0..regions.len()).filter(|&i| depth[i] % 2 == parity && reached[i]).collect();
    if kept.is_empty() {
        return (shape.clone(), Vec::new(), None);
    }
    let named = |want: usize| -> String {
        let list: Vec<String> = (0..regions.len())
            .filter(|&i| depth[i] % 2 == want && !reached[i])
            .map(|i| {
                let size = shape.loops[i].bounds().size();
                format!("loop {} ({:.1} × {:.1} mm)", index[i], size.x, size.y)
            })
            .collect();
        list.join(", ")
    };
    let note = if parity == 1 {
        let also = if odd > 0.0 { format!("; left {} too", named(1)) } else { String::new() };
        format!("carved the {} regions inside {}, not that background (letters on a background): it is {reach}{also}", kept.len(), named(0))
    } else {
        format!("carved the {} regions the V-bit reaches across; left {}: {reach}", kept.len(), named(0))
    };
    let loops: Vec<Loop> = kept.iter().flat_map(|&i| regions[i].loops.clone()).collect();
    (Shape::from_oriented(loops), kept.iter().map(|&i| index[i]).collect(), Some(note))
}

/// The flat floor's moves: the floor (the region shrunk by the clearance at the full depth)
/// pocketed by the flat tool of radius `r`, in levels of the step-down down to `depth`, as a
/// pocket clears by default: rings from the wall in, entered on a helix.
fn flat_floor(floor: &Shape, r: f64, op: &VCarve, depth: f64, mut s: RingSetup) -> Vec<Move> {
    let step = op.stepover_fraction * 2.0 * r;
    let clearing = Clearing::plain(step, r, PocketPattern::Offset);
    clear_down(floor, r, &clearing, depth, op.stepdown, &mut s).unwrap_or_default()
}
