//! 2.5D profiling along drawn loops: the tool-centre path is the loop offset by the tool
//! radius plus leave-stock (seed 003), outside or inside, climb or conventional. Each loop is
//! entered by a lead-in arc from the waste side, cut in laps that ramp down along the contour
//! (no deeper than the step-down a lap, no steeper than the ramp angle) to the final depth,
//! where one full lap finishes the wall and a lead-out arc leaves it. Holding tabs lift the
//! last laps over short stretches so cut-through parts stay attached to the sheet.

use serde::{Deserialize, Serialize};

use crate::drawing::{Loop, Shape};
use crate::geom::segment::Segment;
use crate::geom::tolerance::{FLOAT_SLACK, HAIR, LEAST_STEP};
use crate::geom::{DVec2, Tolerances};
use crate::machining::path2d::{arc_lengths, does_not_fit, follow, point_at, start_nearest, Cursor, Heights};
use crate::machining::report::SheetCut;
use crate::machining::settings::Direction;
use crate::machining::walls::Walls;
use crate::machining::{named_operation, not_negative, positive, sheet, Context, FieldError, Operate, Planned};
use crate::offset::offset;
use crate::offset::trim::Original;
use crate::toolpath::Move;

/// Spacing of the points a lead arc is checked at (mm).
const LEAD_SAMPLE: f64 = 0.005;

/// Which side of a loop the tool runs on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Side {
    /// Outside outer loops, inside holes: the part as drawn is kept.
    #[default]
    Auto,
    Outside,
    Inside,
}

impl Side {
    /// Whether a loop is cut on its outside, given whether its nesting makes it an outline
    /// (counter-clockwise) rather than a hole.
    pub fn cuts_outside(self, outline: bool) -> bool {
        match self {
            Side::Auto => outline,
            Side::Outside => true,
            Side::Inside => false,
        }
    }
}

/// Holding tabs for parts cut through the sheet.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Tabs {
    /// Tabs per outside loop (0: none, unless `spacing` is set). Default value: 0.
    pub count: u32,
    /// Distance between tabs along the path (mm); used when `count` is 0. Default value: none.
    pub spacing: Option<f64>,
    /// Length of material left along the part's edge (mm). Default value: 4.
    pub width: f64,
    /// Height of the tab above the sheet's bottom (above the cut's floor where the cut stops
    /// inside the sheet), mm: the material that holds the part. Default value: 1.5.
    pub height: f64,
}

impl Tabs {
    /// Checks its numbers: a tab is wider than nothing and no taller than a sheet can be, and
    /// tabs are no closer than their own width, nor more on a loop than a part is held by.
    pub fn validate(&self) -> Result<(), FieldError> {
        positive("tabs.width", self.width)?;
        not_negative("tabs.height", self.height)?;
        if self.count > crate::limits::MAX_TABS {
            return Err(FieldError { field: "tabs.count", message: format!("must be at most {} tabs on a loop (got {})", crate::limits::MAX_TABS, self.count) });
        }
        if let Some(spacing) = self.spacing {
            positive("tabs.spacing", spacing)?;
            if spacing < self.width {
                return Err(FieldError {
                    field: "tabs.spacing",
                    message: format!("must be at least the tabs' width ({} mm), or the tabs run into each other (got {})", crate::limits::shown(self.width), crate::limits::shown(spacing)),
                });
            }
        }
        Ok(())
    }
}

impl Default for Tabs {
    fn default() -> Self {
        Tabs { count: 0, spacing: None, width: 4.0, height: 1.5 }
    }
}

/// Profile operation on a drawing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Profile2d {
    /// Default value: "profile".
    pub name: String,
    /// Whether the job runs it (a disabled operation stays in the job). Default value: true.
    pub enabled: bool,
    /// Default value: 1.
    pub tool: u32,
    /// Default value: auto.
    pub side: Side,
    /// Default value: climb.
    pub direction: Direction,
    /// Depth below the stock top (mm). Default value: the stock's thickness plus 0.2 (through).
    pub depth: Option<f64>,
    /// Largest depth cut in one lap (mm). Default value: 2.
    pub stepdown: f64,
    /// Material left on the walls (mm). Default value: 0.
    pub leave_stock: f64,
    /// Radius of the lead-in and lead-out arcs (mm; 0 for none). Default value: the tool radius.
    pub lead_radius: Option<f64>,
    /// Steepest descent along the contour (degrees). Default value: 3.
    pub ramp_angle: f64,
    pub tabs: Tabs,
    /// Layers to cut (empty: all). Default value: empty.
    pub layers: Vec<String>,
    /// Indices of the drawing's loops to cut (empty: all on the layers). Default value: empty.
    pub loops: Vec<usize>,
    /// Its own clearance (and retract) in place of the job's.
    #[serde(flatten)]
    #[ts(flatten)]
    pub moves: crate::machining::settings::Moves,
}

impl Default for Profile2d {
    fn default() -> Self {
        Profile2d {
            name: "profile".into(),
            enabled: true,
            moves: Default::default(),
            tool: 1,
            side: Side::Auto,
            direction: Direction::Climb,
            depth: None,
            stepdown: 2.0,
            leave_stock: 0.0,
            lead_radius: None,
            ramp_angle: 3.0,
            tabs: Tabs::default(),
            layers: Vec::new(),
            loops: Vec::new(),
        }
    }
}

/// What the profile needs besides its settings.
pub struct Setup<'a, 'm> {
    pub tool_radius: f64,
    pub top: f64,
    pub depth: f64,
    /// The sheet's bottom (z): a tab's height is measured from it.
    pub bottom: f64,
    pub feed: f64,
    pub cursor: &'a mut Cursor<'m>,
    pub tol: &'a Tolerances,
}

/// One closed tool-centre path to cut: where the part lies, whether it runs around the
/// outside of material (tabs go there), and what a lead arc must keep clear of.
struct Lap<'a> {
    path: Loop,
    part_left: bool,
    outside: bool,
    clear: Clear<'a>,
}

/// Whether each point within a radius of a point keeps off the walls.
type KeepsOffAround<'a> = Box<dyn Fn(DVec2, f64) -> Box<dyn Fn(DVec2) -> bool + 'a> + 'a>;

/// What a lead arc must keep clear of: every point of it at least `distance` from the walls
/// (`keeps_off`: given a point and a radius, the test for the points within it, the walls near
/// them looked up once), and on the waste side of them (`waste`, asked at one point: an arc
/// that keeps off every wall crosses none).
struct Clear<'a> {
    keeps_off: KeepsOffAround<'a>,
    waste: Box<dyn Fn(DVec2) -> bool + 'a>,
}

/// The moves of a profile around the loops `picked` (positions in `walls.shape`), and
/// warnings. Every loop on the operation's layers is a wall: the paths are the drawing's
/// material grown by the tool radius plus leave-stock as one shape ([`Walls::paths`]), so no
/// path comes closer than that to any part, and where two parts stand closer than the tool's
/// width one path runs around both and the gap is left, with a warning naming both loops and
/// where. A side forced against the nesting (the outside of a hole, the inside of a part) is
/// cut around that loop alone, as asked. Holes are cut first, so a part stays attached until
/// its outline is cut. A hole the tool does not fit in is left (with a warning saying where);
/// when nothing at all can be cut, that is an error.
pub fn profile_moves(walls: &Walls, picked: &[usize], op: &Profile2d, mut s: Setup) -> Result<(Vec<Move>, Vec<String>), String> {
    let mut warnings = Vec::new();
    // Loops the tool does not fit in: their index and extent, said once for all of them.
    let mut too_small: Vec<(usize, crate::geom::segment::Rect)> = Vec::new();
    let r = s.tool_radius;
    let d = r + op.leave_stock;
    let z_final = s.top - s.depth;
    let angle = op.ramp_angle.clamp(0.1, 90.0).to_radians();
    let n = walls.shape.loops.len();
    let mut grouped = vec![false; n];
    let mut alone = Vec::new();
    for &k in picked {
        let outline = walls.shape.loops[k].is_ccw();
        let outside = op.side.cuts_outside(outline);
        if outside == outline {
            grouped[k] = true;
        } else {
            alone.push((k, outside));
        }
    }
    let mut laps: Vec<Lap> = Vec::new();
    if grouped.iter().any(|&g| g) {
        let mut served = vec![false; n];
        let mut named = std::collections::HashSet::new();
        for wp in walls.paths(d, s.tol) {
            if !wp.along.iter().any(|&k| grouped[k]) {
                continue;
            }
            for &k in &wp.along {
                served[k] = true;
            }
            for (a, b) in walls.near_pairs(&wp.along, 2.0 * d) {
                let (a, b) = (a.min(b), a.max(b));
                // A merged group's outer path and the paths of the waste it encloses run
                // along the same loops: each pair is named once.
                if !named.insert((a, b)) {
                    continue;
                }
                // A path can run along loops that meet only through a third one.
                let (gap, at) = walls.closest_approach(a, b);
                if gap >= 2.0 * d {
                    continue;
                }
                warnings.push(format!(
                    "loops {} and {} are {gap:.3} mm apart near ({:.3}, {:.3}), less than the φ{:.3} tool needs ({:.3} mm); one path runs around both and the gap between them is left uncut",
                    walls.index[a],
                    walls.index[b],
                    at.x,
                    at.y,
                    2.0 * r,
                    2.0 * d
                ));
            }
            let outside = wp.path.is_ccw();
            let clear = Clear { keeps_off: Box::new(move |p, radius| Box::new(walls.keeps_off_around(p, radius, d))), waste: Box::new(|q| !walls.in_material(q)) };
            laps.push(Lap { path: wp.path, part_left: true, outside, clear });
        }
        for k in (0..n).filter(|&k| grouped[k] && !served[k]) {
            too_small.push((walls.index[k], walls.shape.loops[k].bounds()));
        }
    }
    for (k, outside) in alone {
        let region = Shape::from_oriented(vec![walls.shape.loops[k].counter_clockwise()]);
        let paths = offset(&region, if outside { d } else { -d }, s.tol);
        if paths.is_empty() {
            too_small.push((walls.index[k], region.bounds()));
        }
        let wall = std::rc::Rc::new(Original::new(&region));
        for path in paths.loops {
            let (wall, region) = (wall.clone(), region.clone());
            let keeps_off: KeepsOffAround = Box::new(move |p, radius| {
                let (wall, reach) = (wall.clone(), d - HAIR);
                let ids = wall.near(p, radius + reach);
                Box::new(move |q: DVec2| wall.distance_among(&ids, q, reach) >= reach)
            });
            let clear = Clear { keeps_off, waste: Box::new(move |q| region.contains(q) != outside) };
            // An outward offset has the part on its left, an inward one on its right.
            laps.push(Lap { path, part_left: outside, outside, clear });
        }
    }
    // Holes first.
    crate::geom::sort::sort_by_float(&mut laps, |l| f64::from(u8::from(l.outside)));
    let mut out = Vec::new();
    let mut in_air = 0;
    for lap in &laps {
        // Climb milling keeps the part on the tool's right.
        let climb = op.direction == Direction::Climb;
        let travel = if lap.part_left == climb { lap.path.reversed() } else { lap.path.clone() };
        let waste_left = climb;
        let longest = travel.segments().max_by(|a, b| a.length().total_cmp(&b.length())).unwrap();
        let segs = start_nearest(&travel, longest.midpoint());
        let tabbed = lap.outside && (op.tabs.count > 0 || op.tabs.spacing.is_some_and(|x| x > 0.0));
        let lead = op.lead_radius.unwrap_or(r).max(0.0);
        if !cut_loop(&segs, &lap.clear, waste_left, lead, tabbed.then_some(&op.tabs), op.stepdown, angle, z_final, &mut s, &mut out) {
            in_air += 1;
        }
        s.cursor.moved(&out);
    }
    crate::geom::sort::sort_by_float(&mut too_small, |t| t.0 as f64);
    match too_small.as_slice() {
        [] => {}
        [(k, b)] => warnings.push(format!("{}; it is not cut", does_not_fit(r, op.leave_stock, &format!("loop {k}"), b))),
        [(k, b), ..] => {
            let list: Vec<String> = too_small.iter().take(12).map(|(k, _)| k.to_string()).collect();
            let more = if too_small.len() > 12 { format!(" and {} more", too_small.len() - 12) } else { String::new() };
            warnings.push(format!(
                "{} loops are smaller than the φ{:.3} tool (plus {:.3} leave-stock) and are not cut: loops {}{more} ({})",
                too_small.len(),
                2.0 * r,
                op.leave_stock,
                list.join(", "),
                does_not_fit(r, op.leave_stock, &format!("loop {k}"), b).replace("the φ", "the first: the φ")
            ));
        }
    }
    // Nothing cut and nothing in the air: what was said (every loop too small) is the error.
    if out.is_empty() && in_air == 0 {
        return Err(if warnings.is_empty() { "no loop of the drawing gives a path to cut".into() } else { warnings.join("; ") });
    }
    if in_air > 0 {
        warnings.push(format!("{in_air} of {} paths have no material left along them (earlier operations cut it away) and are not cut", laps.len()));
    }
    Ok((out, warnings))
}

#[allow(clippy::too_many_arguments)]
fn cut_loop(segs: &[Segment], clear: &Clear, waste_left: bool, lead: f64, tabs: Option<&Tabs>, stepdown: f64, angle: f64, z_final: f64, s: &mut Setup, out: &mut Vec<Move>) -> bool {
    let (starts, total) = arc_lengths(segs);
    let start = segs[0].a;
    let t_in = segs[0].tangent_at(0.0);
    let lead_in = fitting_lead(start, t_in, waste_left, lead, clear, true);
    // The laps start where the in-process stock along the loop (and its lead) starts: not in
    // the air above what earlier operations cut away.
    let lead_arc = lead_in.map(|(l_start, (center, clockwise))| Segment::arc(l_start, start, center, !clockwise));
    let Some(top) = s.cursor.material_top(segs.iter().copied().chain(lead_arc), s.top, z_final, s.tol.gouge) else { return false };
    s.cursor.safe = top + s.cursor.gap;
    // Laps: each ramps down at most `stepdown` (and no steeper than the angle), then one full
    // lap at the final depth.
    let mut z = vec![(0.0, top)];
    let (mut at, mut current) = (0.0, top);
    while current > z_final + FLOAT_SLACK {
        let target = (current - stepdown.max(LEAST_STEP)).max(z_final);
        let run = (current - target) / angle.tan();
        if run <= total {
            z.push((at + run, target));
            current = target;
        } else {
            current -= total * angle.tan();
            z.push((at + total, current));
        }
        at += total;
    }
    let reached = z.last().unwrap().0;
    let end = reached + total;
    let mut heights = Heights(z);
    if let Some(tabs) = tabs {
        heights = heights.max(&tab_heights(tabs, total, end, z_final, z_final.max(s.bottom), s.tool_radius));
    }
    // Lead arcs from and to the waste side, if they keep clear of the part.
    let end_point = point_at(segs, &starts, total, end);
    let i_end = starts.partition_point(|&x| x <= end.rem_euclid(total)).saturating_sub(1);
    let seg_end = segs[i_end];
    let t_end = seg_end.tangent_at(seg_end.closest(end_point).1);
    let z_end = heights.at(end);
    match lead_in {
        Some((l_start, arc)) => {
            s.cursor.reposition(l_start.extend(top), out);
            out.push(Move::Arc { to: start.extend(top), center: arc.0, clockwise: arc.1, feed: s.feed });
        }
        None => s.cursor.reposition(start.extend(top), out),
    }
    follow(segs, 0.0, end, &heights, s.feed, out);
    if let Some((l_end, arc)) = fitting_lead(end_point, t_end, waste_left, lead, clear, false) {
        out.push(Move::Arc { to: l_end.extend(z_end), center: arc.0, clockwise: arc.1, feed: s.feed });
    }
    true
}

/// Tab heights over arc lengths [0, end): trapezoids with 45° sides over each tab, the tool's
/// width wider than the tab, standing `tabs.height` above `base` (the sheet's bottom, or the
/// cut's floor above it).
fn tab_heights(tabs: &Tabs, total: f64, end: f64, z_final: f64, base: f64, r: f64) -> Heights {
    // By spacing, as many as fit the loop, at most as many as a count may ask for.
    let count = if tabs.count > 0 { tabs.count as usize } else { (total / tabs.spacing.unwrap_or(total)).floor().clamp(1.0, f64::from(crate::limits::MAX_TABS)) as usize };
    let top = base + tabs.height.max(0.0);
    let low = z_final - 1.0;
    let half = tabs.width * 0.5 + r;
    let rise = top - low;
    let mut pts = vec![(0.0, low)];
    let laps = (end / total).ceil() as usize;
    for lap in 0..laps {
        for i in 0..count {
            let c = lap as f64 * total + (i as f64 + 0.5) * total / count as f64;
            pts.extend([(c - half - rise, low), (c - half, top), (c + half, top), (c + half + rise, low)]);
        }
    }
    Heights(pts)
}

/// A quarter-circle lead of radius `rho` tangent to the path at `p` (direction `t`), on the
/// waste side: returns the lead's far end and its (centre, clockwise). Halved until every
/// point of it is `clear`, and dropped below a tenth of a mm. Points 5 µm apart along the arc
/// (at most 4,096 of them, so 5 µm up to a radius of 13 mm) stand for all of it: a corner of
/// material between two of them can come closer than the samples by at most (spacing)² / (8 ×
/// its distance), a few millionths of a millimetre.
fn fitting_lead(p: DVec2, t: DVec2, waste_left: bool, rho: f64, clear: &Clear, into: bool) -> Option<(DVec2, (DVec2, bool))> {
    let n = if waste_left { t.perp() } else { -t.perp() };
    let mut rho = rho;
    while rho >= 0.1 {
        let c = p + n * rho;
        let far = if into { c - t * rho } else { c + t * rho };
        let sweep = (p - c).angle_to(far - c); // a quarter turn either way
        let samples = (rho * std::f64::consts::FRAC_PI_2 / LEAD_SAMPLE).ceil().clamp(16.0, 4096.0) as usize;
        let at = |k: usize| c + DVec2::from_angle(sweep * k as f64 / samples as f64).rotate(p - c);
        // Every sample lies within 2ρ of p.
        let keeps_off = (clear.keeps_off)(p, 2.0 * rho);
        let arc_fits = (clear.waste)(at(samples)) && (1..=samples).all(|k| keeps_off(at(k)));
        if arc_fits {
            // The arc turns towards the waste side going into the path: counter-clockwise when
            // the waste is on the left.
            return Some((far, (c, !waste_left)));
        }
        rho *= 0.5;
    }
    None
}

impl Operate for Profile2d {
    named_operation!(OnDrawing);

    fn form() -> crate::machining::form::OperationForm {
        use crate::machining::form::{FormField as F, OperationForm};
        let mut fields = F::name_and_tool().to_vec();
        fields.extend([
            F::words("layers", "Layers", "with commas").empty("all"),
            F::length("depth", "Depth", 0.01).empty("through, {throughDepth}"),
            F::length("stepdown", "Step-down per pass", 0.01),
            F::length("leaveStock", "Leave on walls", 0.0),
            F::choice("side", "Side", &[("auto", "outside outlines, inside holes"), ("outside", "outside"), ("inside", "inside")]),
            F::direction(),
            F::int("tabs.count", "Tabs per part", 0.0, None),
            F::length("tabs.spacing", "Tabs every", 0.01).note("along the path, with no tabs per part").empty("none"),
            F::length("tabs.width", "Tab width", 0.0),
            F::length("tabs.height", "Tab height above the sheet's bottom", 0.0),
            F::length("leadRadius", "Lead-in and lead-out arc radius", 0.0).empty("the tool's radius; 0: none"),
            F::loops("Loops", "numbers with commas, or click them in the view", "every loop on the layers"),
            F::ramp_angle(),
        ]);
        fields.extend(crate::machining::settings::Moves::fields());
        OperationForm::new("cut out along lines (2D)", fields)
    }

    fn stepdown(&self) -> Option<f64> {
        Some(self.stepdown)
    }

    fn check_scale(&self, ctx: &Context) -> crate::error::Result<()> {
        sheet::check_levels(ctx, &self.name, self.depth, self.stepdown)
    }

    fn validate(&self) -> Result<(), FieldError> {
        self.moves.validate()?;
        positive("stepdown", self.stepdown)?;
        crate::machining::angle("rampAngle", self.ramp_angle, 0.1, 90.0)?;
        not_negative("leaveStock", self.leave_stock)?;
        if let Some(d) = self.depth {
            positive("depth", d)?;
        }
        if let Some(r) = self.lead_radius {
            not_negative("leadRadius", r)?;
        }
        self.tabs.validate()
    }

    fn plan(&self, ctx: &mut Context, _progress: &mut crate::progress::Progress) -> crate::error::Result<Planned> {
        let tool = ctx.tool(&self.name, self.tool)?.clone();
        let (drawing, thickness) = sheet::sheet(ctx, &self.name)?;
        let (walls, picked) = sheet::selected(drawing, &self.name, &self.layers, &self.loops)?;
        let open = drawing.open_note(&self.layers);
        let depth = self.depth.unwrap_or(thickness + sheet::BREAKTHROUGH);
        // Tabs as tall as the sheet over the cut's floor would leave the tool in the air over
        // them: said, not cut.
        let floor = (ctx.stock.max.z - depth).max(ctx.stock.max.z - thickness);
        if (self.tabs.count > 0 || self.tabs.spacing.is_some()) && floor + self.tabs.height >= ctx.stock.max.z - 1e-9 {
            return Err(crate::error::Error::operation(
                &self.name,
                format!(
                    "tabs.height ({} mm) reaches the sheet's top from the cut's floor ({} mm below it): the tool would pass over the tabs in the air; make them lower",
                    crate::limits::shown(self.tabs.height),
                    crate::limits::shown(ctx.stock.max.z - floor)
                ),
            ));
        }
        let cuts = profile_cuts(&walls, &picked, self.side, depth, self.leave_stock);
        let mut cursor = sheet::cursor(ctx, &tool);
        let setup = Setup { tool_radius: tool.cutter.radius(), top: ctx.stock.max.z, depth, bottom: ctx.stock.max.z - thickness, feed: tool.feed_rate, cursor: &mut cursor, tol: &ctx.tolerances };
        let (moves, notes) = profile_moves(&walls, &picked, self, setup).map_err(|e| crate::error::Error::operation(&self.name, e))?;
        if let Some(note) = open {
            ctx.warn(&self.name, note);
        }
        for n in notes {
            ctx.warn(&self.name, n);
        }
        let paths = if moves.is_empty() { Vec::new() } else { vec![sheet::toolpath(&self.name, &tool, moves, ctx.heights.clearance)] };
        Ok(Planned { paths, cuts, ..Planned::default() })
    }
}

/// Where a profile cuts: outside the material of every loop on its layers (the walls), and
/// for a loop cut on the side its nesting does not give, outside or inside that loop alone.
pub fn profile_cuts(walls: &Walls, picked: &[usize], side: Side, depth: f64, leave: f64) -> Vec<SheetCut> {
    let mut cuts = vec![SheetCut { region: walls.shape.clone(), inside: false, depth, leave, scrap: true }];
    for &k in picked {
        let l = &walls.shape.loops[k];
        let outside = side.cuts_outside(l.is_ccw());
        if outside != l.is_ccw() {
            cuts.push(SheetCut { region: Shape::from_oriented(vec![l.counter_clockwise()]), inside: !outside, depth, leave, scrap: true });
        }
    }
    cuts
}
