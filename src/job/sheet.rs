//! The setup sheet: one printable HTML page that tells the machinist how to hold the part for
//! each setup and what each program does (`swarf sheet`), as Fusion's and FreeCAD's do: how the
//! part is turned from the setup before, the work offset and where its zero is, the stock's size,
//! a picture of the part and stock from above with the zero marked, each tool with its
//! stick-out, each operation with its tool, feed and time, and the cycle times.

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use super::run::JobOutput;
use super::schema::{Flip, Job, Up};
use crate::geom::Aabb;
use crate::post::{clock, TimeItem};

/// Longest side of the picture's grid of shades: the part's heights sampled this coarsely.
const PICTURE_CELLS: usize = 120;

/// What a setup sheet says of one setup's program: taken from its output as it is made
/// ([`SheetSetup::of`]), so that the page's worker keeps it beside the result it shows and the
/// sheet is written from the same figures in the page and by `swarf sheet`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SheetSetup {
    pub name: String,
    /// The work offset its program selects (`G55`), if any.
    pub work_offset: Option<String>,
    pub stock: Aabb,
    /// Where X0 Y0 Z0 lies, in words a machinist touches off by ([`zero_words`]): worked out
    /// from the program's own stock and part, so the sheet cannot say another zero than the
    /// program's.
    #[serde(default)]
    pub zero: String,
    pub moves: usize,
    pub cycle: f64,
    /// The tools in the order the program takes them.
    pub tools: Vec<u32>,
    pub operations: Vec<SheetOperation>,
    pub time: Vec<TimeItem>,
    /// The part and stock from above with the zero marked (SVG).
    pub picture: String,
}

/// One operation's line on the sheet.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SheetOperation {
    pub name: String,
    pub tools: Vec<u32>,
    pub seconds: f64,
    pub feed_length: f64,
    pub removed: Option<f64>,
}

impl SheetSetup {
    /// The sheet's figures of the program `out` of the setup named `name`.
    pub fn of(name: &str, out: &JobOutput) -> SheetSetup {
        let mut tools: Vec<u32> = Vec::new();
        for p in &out.paths {
            if !tools.contains(&p.tool) {
                tools.push(p.tool);
            }
        }
        SheetSetup {
            name: name.to_owned(),
            work_offset: out.gcode.lines().map(crate::post::without_number).find(|l| crate::post::definition::is_work_offset(l)).map(str::to_owned),
            stock: out.stock,
            zero: zero_words(&out.stock, part_box(out).as_ref(), zero_hole(out).as_ref()),
            moves: out.moves.len(),
            cycle: out.cycle.seconds,
            tools,
            operations: out.operations.iter().map(|o| SheetOperation { name: o.name.clone(), tools: o.tools.clone(), seconds: o.seconds, feed_length: o.feed_length, removed: o.removed }).collect(),
            time: out.time.clone(),
            picture: picture(name, out),
        }
    }
}

/// The setup sheet of `job`'s `setups` (each as [`SheetSetup::of`] took it from its program)
/// for the part named `part`, as a standalone HTML page.
pub fn setup_sheet(job: &Job, part: &str, setups: &[SheetSetup]) -> String {
    let mut h = String::new();
    let title = format!("{} — setup sheet", escape(&job.name));
    let total: f64 = setups.iter().map(|s| s.cycle).sum();
    let _ = write!(
        h,
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{title}</title><style>\
body{{font:14px system-ui,sans-serif;margin:2em;color:#111}}table{{border-collapse:collapse;margin:.5em 0 1em}}\
td,th{{border:1px solid #999;padding:.2em .6em;text-align:left}}th{{background:#eee}}section{{break-after:page;margin-bottom:2em}}\
svg{{border:1px solid #ccc;background:#fafafa}}.n{{text-align:right}}</style></head><body>\n\
<h1>{title}</h1>\n<p>Part: {}. {} setup{}, cycle time {} in all.</p>\n",
        escape(part),
        setups.len(),
        if setups.len() == 1 { "" } else { "s" },
        clock(total)
    );
    // Each tool with the speeds and feeds it cuts at, and where they come from.
    let cut: Vec<(&crate::tool::Tool, crate::cutting::CuttingData)> = job.tools.iter().zip(job.cutting_data()).collect();
    for (k, s) in setups.iter().enumerate() {
        let setup = job.setups.get(k);
        let _ = write!(h, "<section>\n<h2>{}: {}</h2>\n", k + 1, escape(&s.name));
        let hold = hold_words(job, k);
        let from = if k == 0 { "the raw stock".to_owned() } else { format!("the stock setup {} left", k) };
        let hold = if hold.is_empty() {
            format!("Hold {from} as {}.", if k == 0 { "the part is drawn, its top up" } else { "the setup before held it" })
        } else {
            format!("From {from}: {}.", hold.join(", then "))
        };
        let offset = s.work_offset.as_deref().unwrap_or("none (the machine's current)");
        let at_hole = setup.and_then(|s| s.zero).or(job.stock.zero).is_some_and(|z| z.at.is_some());
        // A point picked that is no hole's centre is said as picked.
        let zero = if at_hole && !s.zero.contains(" hole (its top at") { format!("{} (the point picked)", s.zero) } else { s.zero.clone() };
        let size = s.stock.size();
        let _ = write!(
            h,
            "<p>{hold}</p>\n<table><tr><th>Work offset</th><td>{}</td></tr><tr><th>Zero (X0 Y0 Z0)</th><td>{}</td></tr>\
<tr><th>Stock</th><td>{:.1} × {:.1} × {:.1} mm (X × Y × Z), from X{:.3} Y{:.3} Z{:.3} to X{:.3} Y{:.3} Z{:.3}</td></tr>\
<tr><th>Program</th><td>{} moves, cycle time {}</td></tr></table>\n",
            escape(offset),
            escape(&zero),
            size.x,
            size.y,
            size.z,
            s.stock.min.x,
            s.stock.min.y,
            s.stock.min.z,
            s.stock.max.x,
            s.stock.max.y,
            s.stock.max.z,
            s.moves,
            clock(s.cycle)
        );
        h.push_str(&s.picture);
        // Tools, in the order the program takes them.
        h.push_str("<h3>Tools</h3>\n<table><tr><th>Tool</th><th>Cutter</th><th>Stick-out</th><th>Holder</th><th class=n>Speed</th><th class=n>Feed</th><th>Speeds from</th></tr>\n");
        for (tool, data) in s.tools.iter().filter_map(|n| cut.iter().find(|(t, _)| t.number == *n)) {
            let _ = writeln!(
                h,
                "<tr><td>T{}</td><td>{}</td><td>{}</td><td>{}</td><td class=n>{:.0} rpm</td><td class=n>{:.0} mm/min</td><td>{}</td></tr>",
                tool.number,
                escape(&tool.describe()),
                tool.stick_out.map_or_else(|| format!("at least {:.1} mm (its flutes)", tool.cutter.flute_length), |s| format!("{s:.1} mm")),
                tool.holder.as_ref().map_or_else(|| "—".to_owned(), |h| escape(&h.name)),
                data.spindle_rpm,
                data.feed_rate,
                escape(&data.reason)
            );
        }
        h.push_str("</table>\n<h3>Operations</h3>\n<table><tr><th>#</th><th>Operation</th><th>Tool</th><th class=n>Time</th><th class=n>Cutting</th><th class=n>Removed</th></tr>\n");
        for (i, o) in s.operations.iter().enumerate() {
            let tools: Vec<String> = o.tools.iter().map(|t| format!("T{t}")).collect();
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td class=n>{}</td><td class=n>{:.0} mm</td><td class=n>{}</td></tr>",
                i + 1,
                escape(&o.name),
                tools.join(", "),
                clock(o.seconds),
                o.feed_length,
                o.removed.map_or_else(String::new, |v| format!("{:.1} cm³", v / 1000.0))
            );
        }
        h.push_str("</table>\n<h3>Cycle time</h3>\n<table>\n");
        for item in &s.time {
            let _ = writeln!(h, "<tr><td>{}</td><td class=n>{}</td></tr>", escape(&item.label), clock(item.seconds as f64));
        }
        let _ = writeln!(h, "<tr><th>In all</th><th class=n>{}</th></tr></table>\n</section>", clock(s.cycle));
    }
    h.push_str("</body></html>\n");
    h
}

/// How setup `k` holds the part, in a machinist's words ("turn the part over about X (front
/// edge to the back)", "turn it 90° counter-clockwise seen from above"); none where it holds it
/// as the setup before did.
pub fn hold_words(job: &Job, k: usize) -> Vec<String> {
    let setup = job.setups.get(k);
    let mut hold = Vec::new();
    match (setup.and_then(|s| s.up), setup.map(|s| s.flip)) {
        (Some(up), _) => hold.push(match up {
            Up::PlusZ => "hold the part its top up".to_owned(),
            Up::MinusZ => "hold the part its bottom up".to_owned(),
            side => format!(
                "stand the part on its side, its {} face up",
                match side {
                    Up::PlusX => "right (+X)",
                    Up::MinusX => "left (−X)",
                    Up::PlusY => "back (+Y)",
                    _ => "front (−Y)",
                }
            ),
        }),
        (None, Some(Flip::AboutX)) => hold.push("turn the part over about X (front edge to the back)".to_owned()),
        (None, Some(Flip::AboutY)) => hold.push("turn the part over about Y (left edge to the right)".to_owned()),
        _ => {}
    }
    if let Some(turn) = setup.map(|s| s.turn).filter(|&t| t != 0) {
        hold.push(format!("turn it {turn}° counter-clockwise seen from above"));
    }
    hold
}

/// The part's box in a program's frame; none for a drawing (its sheet is the stock) or an empty
/// part.
fn part_box(out: &JobOutput) -> Option<Aabb> {
    (out.drawing.is_none() && !out.part.faces.is_empty()).then(|| out.part.bounds())
}

/// Where X0 Y0 Z0 lies in a program whose stock box is `stock` and part box `part` (both in
/// the program's frame, as the setup holds them), in a machinist's words: what Z0 is on (the
/// part's top as held, the stock's top or bottom, or how far below the stock's top), what to
/// touch off and set, and where the stock's sides are from X0 Y0, so that the zero is found
/// on the stock in front of them whichever face is up.
/// The hole of the program `out`'s part whose centre is X0 Y0 (as the page's "X0 Y0 on the
/// picked hole" puts it), where its zero was put at a point and X0 Y0 is neither a corner nor
/// the centre of the stock or the part: the part's holes are not looked for on every run.
fn zero_hole(out: &JobOutput) -> Option<crate::holes::Hole> {
    const AT: f64 = 1e-3;
    if !out.zero_at {
        return None;
    }
    let (s, c) = (out.stock, out.stock.center());
    let plain = [(c.x, c.y), (s.min.x, s.min.y), (s.max.x, s.min.y), (s.min.x, s.max.y), (s.max.x, s.max.y)].iter().any(|(x, y)| x.abs() < AT && y.abs() < AT);
    let part_centre = part_box(out).is_some_and(|p| p.center().x.abs() < AT && p.center().y.abs() < AT);
    if plain || part_centre || out.drawing.is_some() || out.part.faces.is_empty() {
        return None;
    }
    crate::holes::mesh::find(&out.part).into_iter().find(|h| h.center.length() < AT)
}

pub fn zero_words(stock: &Aabb, part: Option<&Aabb>, hole: Option<&crate::holes::Hole>) -> String {
    const AT: f64 = 1e-6;
    let f = |v: f64| if v.abs() < 5e-4 { "0.000".to_owned() } else { format!("{v:+.3}") };
    let (top, bottom) = (stock.max.z, stock.min.z);
    let on = match part {
        Some(p) if p.max.z.abs() < AT && top.abs() < AT => "Z0 on the part's top as held, which is the stock's top".to_owned(),
        Some(p) if p.max.z.abs() < AT => format!("Z0 on the part's top as held, {:.3} mm below the stock's top", top),
        _ if top.abs() < AT => "Z0 on the stock's top".to_owned(),
        _ if bottom.abs() < AT => "Z0 on the stock's bottom".to_owned(),
        _ if top > 0.0 => format!("Z0 {top:.3} mm below the stock's top"),
        _ => format!("Z0 {:.3} mm above the stock's top", -top),
    };
    let touch = if top.abs() < AT { "touch off the stock's top as Z0".to_owned() } else { format!("touch off the stock's top and set it as Z{}", f(top)) };
    let c = stock.center();
    let corner = [
        ((c.x, c.y), "the centre of the stock seen from above"),
        ((stock.min.x, stock.min.y), "the stock's front left corner"),
        ((stock.max.x, stock.min.y), "the stock's front right corner"),
        ((stock.min.x, stock.max.y), "the stock's back left corner"),
        ((stock.max.x, stock.max.y), "the stock's back right corner"),
    ]
    .into_iter()
    .find(|((x, y), _)| x.abs() < AT && y.abs() < AT)
    .map(|(_, w)| w.to_owned());
    let xy = match (corner, part) {
        (Some(w), _) => w,
        (None, Some(p)) if p.center().x.abs() < AT && p.center().y.abs() < AT => "the centre of the part seen from above".to_owned(),
        (None, _) if hole.is_some() => {
            let h = hole.expect("a hole");
            format!(
                "the centre of the φ{} hole (its top at Z{}; {} from the centre of the stock seen from above)",
                crate::limits::shown((h.diameter * 1000.0).round() / 1000.0),
                f(h.top),
                format_args!("X{} Y{}", f(-c.x), f(-c.y))
            )
        }
        _ => format!("X{} Y{} from the centre of the stock seen from above", f(-c.x), f(-c.y)),
    };
    format!(
        "{on} ({touch}; the stock's bottom is Z{}); X0 Y0 at {xy}: the stock's left side at X{}, its right at X{}, its front at Y{}, its back at Y{}",
        f(bottom),
        f(stock.min.x),
        f(stock.max.x),
        f(stock.min.y),
        f(stock.max.y)
    )
}

/// The part and stock of one setup seen from above, as an SVG: the stock's outline, the part
/// shaded by height (darker lower) from the simulation's grid, and the zero's axes.
fn picture(name: &str, out: &JobOutput) -> String {
    let b = out.stock;
    let (w, d) = (b.size().x, b.size().y);
    let scale = 480.0 / w.max(d).max(1e-9);
    let (pw, ph) = (w * scale + 40.0, d * scale + 40.0);
    // Screen coordinates: X right, Y up, 20 px margin.
    let sx = |x: f64| 20.0 + (x - b.min.x) * scale;
    let sy = |y: f64| 20.0 + (b.max.y - y) * scale;
    let mut svg = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{pw:.0}\" height=\"{ph:.0}\" viewBox=\"0 0 {pw:.1} {ph:.1}\" role=\"img\" aria-label=\"{} from above\">\n", escape(name));
    let _ = writeln!(svg, "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#e8e2d0\" stroke=\"#555\"/>", sx(b.min.x), sy(b.max.y), w * scale, d * scale);
    if let Some(v) = &out.verification {
        let f = &v.part;
        let step = (f.nx.max(f.ny) as f64 / PICTURE_CELLS as f64).ceil().max(1.0) as usize;
        let (lo, hi) = f.z.iter().filter(|z| z.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &z| (lo.min(z), hi.max(z)));
        let span = (hi - lo).max(1e-9);
        let cell = f.spacing * step as f64;
        for j in (0..f.ny).step_by(step) {
            // Runs of cells of one shade along the row.
            let mut run: Option<(usize, u8)> = None;
            let shade_at = |i: usize| {
                let z = f.z[j * f.nx + i];
                z.is_finite().then(|| (60.0 + 160.0 * (z - lo) / span) as u8)
            };
            let flush = |from: usize, to: usize, shade: u8, svg: &mut String| {
                let (x0, y0) = (f.origin.x + from as f64 * f.spacing - f.spacing / 2.0, f.origin.y + j as f64 * f.spacing - f.spacing / 2.0);
                let _ = writeln!(
                    svg,
                    "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"rgb({shade},{shade},{})\"/>",
                    sx(x0),
                    sy(y0 + cell),
                    (to - from) as f64 * f.spacing * scale + 0.3,
                    cell * scale + 0.3,
                    shade.saturating_add(20)
                );
            };
            let mut i = 0;
            while i < f.nx {
                let shade = shade_at(i);
                if run.map(|r| r.1) != shade {
                    if let Some((from, s)) = run {
                        flush(from, i, s, &mut svg);
                    }
                    run = shade.map(|t| (i, t));
                }
                i += step;
            }
            if let Some((from, s)) = run {
                flush(from, f.nx, s, &mut svg);
            }
        }
    }
    // The zero: red X, green Y, as controls draw them.
    let (zx, zy) = (sx(0.0), sy(0.0));
    let arm = 40.0;
    let _ = write!(
        svg,
        "<line x1=\"{zx:.1}\" y1=\"{zy:.1}\" x2=\"{:.1}\" y2=\"{zy:.1}\" stroke=\"#c00\" stroke-width=\"2\"/><text x=\"{:.1}\" y=\"{:.1}\" fill=\"#c00\">X</text>\
<line x1=\"{zx:.1}\" y1=\"{zy:.1}\" x2=\"{zx:.1}\" y2=\"{:.1}\" stroke=\"#080\" stroke-width=\"2\"/><text x=\"{:.1}\" y=\"{:.1}\" fill=\"#080\">Y</text>\
<circle cx=\"{zx:.1}\" cy=\"{zy:.1}\" r=\"4\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/><text x=\"{:.1}\" y=\"{:.1}\">X0 Y0</text>\n</svg>\n",
        zx + arm,
        zx + arm + 3.0,
        zy + 4.0,
        zy - arm,
        zx - 4.0,
        zy - arm - 4.0,
        zx + 6.0,
        zy + 16.0
    );
    svg
}

/// `text` safe inside HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}
