//! Tool libraries machinists already keep (issue 58), read into swarf's tools and written back:
//! Fusion's tool library (JSON: `data`, each tool's `type`, `geometry`, `post-process` and
//! `start-values`), LinuxCNC's tool table (`.tbl`: `T1 P1 D6 ;comment`), FreeCAD's tool bits
//! (`.fctb`: `shape` and `parameter` with units) and its libraries (`.fctl`: numbered paths to
//! bits). What a file holds that swarf does not take (a holder, a second preset, a field it does
//! not model, a kind of tool it has no shape for) is named in the notes, never dropped silently.

use serde_json::{json, Map, Value};

use super::{HolderSection, Speeds, Tool};
use crate::cutter::{Cutter, Shape};
use crate::error::{Error, Result};

/// The tools read from a library, and what of it was not taken.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, ts_rs::TS)]
pub struct Imported {
    pub tools: Vec<Tool>,
    /// What the file holds that swarf did not take, each said once.
    pub notes: Vec<String>,
}

/// The formats a library is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum LibraryFormat {
    /// Fusion's tool library JSON.
    Fusion,
    /// LinuxCNC's tool table.
    LinuxCnc,
}

const INCH: f64 = 25.4;

/// Reads the library `bytes` of the file `name` (its extension and its content tell the
/// format). A LinuxCNC tool table says no unit: `inches` reads it in inches. A FreeCAD library
/// (`.fctl`) names its bits' files: `bits` holds them by file name.
pub fn read_library(bytes: &[u8], name: &str, inches: bool, bits: &[(String, Vec<u8>)]) -> Result<Imported> {
    if bytes.starts_with(b"PK\x03\x04") {
        // Fusion's `.tools`: a ZIP holding the library's JSON.
        let json = zip_json(bytes).map_err(|why| Error::Input(format!("{name}: a ZIP (as Fusion's .tools is), but {why}")))?;
        return read_library(&json, &format!("{name} (its tools.json)"), inches, bits);
    }
    let text = std::str::from_utf8(bytes).map_err(|_| Error::Input(format!("{name}: not text (a tool library is JSON or a LinuxCNC tool table)")))?;
    let lower = name.to_lowercase();
    if lower.ends_with(".tbl") {
        return linuxcnc(text, if inches { INCH } else { 1.0 });
    }
    let value: Value = serde_json::from_str(text).map_err(|e| Error::Input(format!("{name}: not a tool library: {}", crate::error::plain(&e.to_string()))))?;
    if lower.ends_with(".fctl") || value.get("tools").and_then(Value::as_array).is_some_and(|t| t.iter().any(|x| x.get("path").is_some())) {
        return freecad_library(&value, name, bits);
    }
    if lower.ends_with(".fctb") || value.get("shape").is_some() {
        let mut out = Imported::default();
        if let Some(t) = freecad_bit(&value, 1, name, &mut out.notes)? {
            out.tools.push(t);
        }
        return Ok(out);
    }
    if value.get("data").is_some_and(Value::is_array) {
        return fusion(&value);
    }
    Err(Error::Input(format!("{name}: not a tool library swarf reads (Fusion's JSON with `data`, a LinuxCNC .tbl, a FreeCAD .fctb or .fctl)")))
}

/// The first `.json` file a ZIP holds (Fusion's `.tools` holds `tools.json`), from its central
/// directory: stored or deflated; what is wrong with the ZIP otherwise.
fn zip_json(zip: &[u8]) -> std::result::Result<Vec<u8>, String> {
    const MOST: usize = 64 << 20;
    let u16_at = |at: usize| zip.get(at..at + 2).map(|b| u16::from_le_bytes([b[0], b[1]]) as usize);
    let u32_at = |at: usize| zip.get(at..at + 4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let end = (0..zip.len().saturating_sub(21)).rev().take(65_557).find(|&at| u32_at(at) == Some(0x0605_4b50)).ok_or("its end (the central directory's record) is missing: the file is cut short")?;
    let (count, mut at) = (u16_at(end + 10).ok_or("its end is cut short")?, u32_at(end + 16).ok_or("its end is cut short")?);
    for _ in 0..count {
        if u32_at(at) != Some(0x0201_4b50) {
            return Err("its directory is damaged".into());
        }
        let field = |off: usize| u16_at(at + off).ok_or("its directory is cut short");
        let (method, packed, size) = (field(10)?, u32_at(at + 20).ok_or("its directory is cut short")?, u32_at(at + 24).ok_or("its directory is cut short")?);
        let (name_len, extra, comment, local) = (field(28)?, field(30)?, field(32)?, u32_at(at + 42).ok_or("its directory is cut short")?);
        let name = zip.get(at + 46..at + 46 + name_len).ok_or("its directory is cut short")?;
        at += 46 + name_len + extra + comment;
        if !String::from_utf8_lossy(name).to_lowercase().ends_with(".json") {
            continue;
        }
        let start = local + 30 + u16_at(local + 26).ok_or("a file's header is cut short")? + u16_at(local + 28).ok_or("a file's header is cut short")?;
        let data = zip.get(start..start + packed).ok_or("its JSON is cut short")?;
        return match method {
            0 => Ok(data.to_vec()),
            8 => miniz_oxide::inflate::decompress_to_vec_with_limit(data, size.min(MOST)).map_err(|_| "its JSON does not inflate (damaged)".into()),
            m => Err(format!("its JSON is packed by method {m}, which swarf does not unpack (stored or deflated)")),
        };
    }
    Err("it holds no .json library (Fusion's .tools holds tools.json)".into())
}

/// Notes said once each, in the order first met.
#[derive(Default)]
struct Notes(Vec<String>);

impl Notes {
    fn say(&mut self, note: String) {
        if !self.0.contains(&note) {
            self.0.push(note);
        }
    }
}

/// A cutter's shape from words in a name or a type ("ball end mill", "6 mm V-bit 60°"): the
/// word that comes first names it (the longer where two start together), so that "slot drill"
/// (a two-flute end mill) is a flat end mill, "drill mill" a chamfer mill, and a name the
/// shape's words lead ("6 mm flat end (roughing drill)") its shape.
fn shape_in(words: &str) -> Option<Shape> {
    let w = words.to_lowercase();
    const WORDS: &[(&str, Shape)] = &[
        ("bull", Shape::BullNose),
        ("torus", Shape::BullNose),
        ("corner radius", Shape::BullNose),
        ("radius", Shape::BullNose),
        ("ball", Shape::Ball),
        ("spot", Shape::SpotDrill),
        ("center drill", Shape::SpotDrill),
        ("centre drill", Shape::SpotDrill),
        ("slot drill", Shape::Flat),
        ("drill mill", Shape::VBit),
        ("drill", Shape::Drill),
        ("thread", Shape::ThreadMill),
        ("v-bit", Shape::VBit),
        ("vbit", Shape::VBit),
        ("v bit", Shape::VBit),
        ("chamfer", Shape::VBit),
        ("engrav", Shape::VBit),
        ("countersink", Shape::VBit),
        ("counter sink", Shape::VBit),
        ("flat", Shape::Flat),
        ("end mill", Shape::Flat),
        ("endmill", Shape::Flat),
        ("face mill", Shape::Flat),
        ("slot", Shape::Flat),
    ];
    WORDS.iter().filter_map(|&(k, shape)| w.find(k).map(|at| (at, std::cmp::Reverse(k.len()), shape))).min_by_key(|&(at, len, _)| (at, len)).map(|(_, _, shape)| shape)
}

/// A shape's name, as a note says it.
fn shape_name(shape: Shape) -> &'static str {
    match shape {
        Shape::Flat => "flat end mill",
        Shape::Ball => "ball end mill",
        Shape::BullNose => "bull nose end mill",
        Shape::Drill => "drill",
        Shape::SpotDrill => "spot drill",
        Shape::VBit => "V-bit or chamfer mill",
        Shape::ThreadMill => "thread mill",
    }
}

/// A number of a library's field: JSON's own, or one written as text ("44", read as Fusion
/// reads it); `None` where absent or null; an error naming `field` of `what` where it is
/// neither, not finite, or (for a size, `size`) negative.
fn number_of(v: Option<&Value>, what: &str, field: &str, size: bool) -> Result<Option<f64>> {
    let n = match v {
        None | Some(Value::Null) => return Ok(None),
        Some(Value::Number(n)) => n.as_f64(),
        Some(Value::String(t)) => t.trim().parse::<f64>().ok(),
        Some(_) => None,
    };
    match n {
        Some(n) if n.is_finite() && !(size && n < 0.0) => Ok(Some(n)),
        Some(n) if n.is_finite() => Err(Error::Input(format!("{what}: {field} is {}: a size is not negative; the library is not read", crate::limits::shown(n)))),
        _ => Err(Error::Input(format!("{what}: {field} is {}, not a number; the library is not read", v.map(Value::to_string).unwrap_or_default()))),
    }
}

/// The scale to mm of a Fusion entry's `unit` ("millimeters" or "inches", as Fusion writes
/// them); none is read in millimeters, and said; any other is refused naming it (a size read
/// in the wrong unit is a crash).
fn fusion_unit(entry: &Value, what: &str, notes: &mut Notes) -> Result<f64> {
    match entry.get("unit") {
        Some(Value::String(u)) if u == "millimeters" => Ok(1.0),
        Some(Value::String(u)) if u == "inches" => Ok(INCH),
        None => {
            notes.say(format!("{what}: no unit given: read in millimeters"));
            Ok(1.0)
        }
        Some(other) => Err(Error::Input(format!("{what}: its unit {other} is not one Fusion writes (\"millimeters\" or \"inches\"): the library is not read, as its sizes would be wrong"))),
    }
}

/// A Fusion tool's material (`BMC`) as swarf's charts have it: carbide, or HSS (cobalt HSS
/// too); another is taken as carbide, and said.
fn fusion_material(entry: &Value, what: &str, notes: &mut Notes) -> super::ToolMaterial {
    match entry.get("BMC").and_then(Value::as_str).map(str::to_lowercase).as_deref() {
        None | Some("carbide") => super::ToolMaterial::Carbide,
        Some("hss") | Some("cobalt") => super::ToolMaterial::Hss,
        Some("ti coated") => super::ToolMaterial::Coated,
        Some(other) => {
            notes.say(format!("{what}: its material (BMC) {other:?} is none of carbide, ti coated and HSS, the three swarf's charts have: taken as carbide"));
            super::ToolMaterial::Carbide
        }
    }
}

/// Fusion's tool library.
fn fusion(value: &Value) -> Result<Imported> {
    let mut notes = Notes::default();
    let mut tools = Vec::new();
    let mut unknown: Vec<String> = Vec::new();
    const TAKEN: &[&str] = &["type", "unit", "description", "product-id", "vendor", "geometry", "post-process", "start-values", "guid", "holder", "BMC"];
    let mut numbers: Vec<(u32, String)> = Vec::new();
    const GEOMETRY: &[&str] = &["DC", "SFDM", "NOF", "LCF", "RE", "SIG", "TA", "tip-diameter", "LB"];
    for (k, entry) in value["data"].as_array().into_iter().flatten().enumerate() {
        let kind = entry.get("type").and_then(Value::as_str).unwrap_or("");
        let number = entry.pointer("/post-process/number").and_then(Value::as_u64).map_or(k as u32 + 1, |n| n as u32);
        let description = entry.get("description").and_then(Value::as_str).unwrap_or("").to_owned();
        if matches!(kind, "holder" | "probe") {
            notes.say(format!("a {kind} ({}) is not a cutting tool: not taken", if description.is_empty() { "no description" } else { &description }));
            continue;
        }
        let Some(shape) = shape_in(kind).filter(|_| !kind.contains("tap") && !kind.contains("boring") && !kind.contains("reamer") && !kind.contains("lollipop") && !kind.contains("dovetail")) else {
            notes.say(format!("T{number} ({}): a {kind:?} has no shape in swarf: not taken", if description.is_empty() { kind } else { &description }));
            continue;
        };
        let what = format!("T{number} ({})", if description.is_empty() { kind } else { &description });
        if let Some((_, other)) = numbers.iter().find(|(n, _)| *n == number) {
            return Err(Error::Input(format!("{what}: T{number} is also {other}: two tools of one number; the library is not read")));
        }
        numbers.push((number, description.clone()));
        let scale = fusion_unit(entry, &what, &mut notes)?;
        let g = entry.get("geometry").cloned().unwrap_or(json!({}));
        let mut sizes = std::collections::BTreeMap::new();
        for key in GEOMETRY {
            // Angles and the flute count are no sizes in the unit, but none is negative either.
            if let Some(v) = number_of(g.get(*key), &what, &format!("geometry.{key}"), true)? {
                sizes.insert(*key, v);
            }
        }
        let num = |key: &str| sizes.get(key).copied();
        let Some(d) = num("DC").filter(|&d| d > 0.0).map(|d| d * scale) else {
            notes.say(format!("{what}: no diameter (geometry.DC): not taken"));
            continue;
        };
        let mut cutter = Cutter { shape, diameter: d, ..Cutter::default() };
        cutter.shank_diameter = num("SFDM").map(|v| v * scale).filter(|&s| (s - d).abs() > 1e-9);
        if let Some(l) = num("LCF") {
            cutter.flute_length = l * scale;
        }
        cutter.corner_radius = if shape == Shape::BullNose { num("RE").unwrap_or(0.0) * scale } else { Cutter::default().corner_radius };
        cutter.angle = match shape {
            Shape::Drill | Shape::SpotDrill => num("SIG"),
            // A chamfer mill's taper angle is half its included angle.
            Shape::VBit => num("TA").map(|a| 2.0 * a).filter(|&a| a > 0.0).or(num("SIG")),
            _ => None,
        };
        if shape == Shape::VBit {
            cutter.tip_diameter = num("tip-diameter").unwrap_or(0.0) * scale;
        }
        let mut tool = Tool { number, name: description.clone(), cutter, tool_material: fusion_material(entry, &what, &mut notes), ..Tool::default() };
        if let Some(z) = num("NOF") {
            tool.flutes = z.round().max(1.0) as u32;
        }
        if let Some(lb) = num("LB") {
            tool.stick_out = Some((lb * scale).max(tool.cutter.flute_length));
        }
        let presets = match entry.get("start-values") {
            Some(v) if v.get("presets").is_some() => v["presets"].as_array().cloned().unwrap_or_default(),
            // Older libraries: a map from a material (or "*", any) to one set of values.
            Some(Value::Object(by)) => {
                let sets: Vec<Value> = by
                    .iter()
                    .filter(|(_, v)| v.get("n").is_some() || v.get("v_f").is_some())
                    .map(|(k, v)| {
                        let mut v = v.clone();
                        if v.get("name").is_none() {
                            v["name"] = json!(k);
                        }
                        v
                    })
                    .collect();
                sets
            }
            _ => Vec::new(),
        };
        if let Some(p) = presets.first() {
            let rate = |key: &str| number_of(p.get(key), &what, &format!("start-values.{key}"), true).ok().flatten().filter(|v| *v > 0.0);
            if let (Some(n), Some(f)) = (rate("n"), rate("v_f")) {
                tool.spindle_rpm = n;
                tool.feed_rate = f * scale;
                tool.plunge_rate = rate("v_f_plunge").map_or(f * scale / 2.0, |v| v * scale);
                tool.speeds = Speeds::AsTyped;
            }
            if presets.len() > 1 {
                let name = p.get("name").and_then(Value::as_str).unwrap_or("the first");
                notes.say(format!("T{number}: {} presets: the first ('{name}') taken for its speeds and feeds", presets.len()));
            }
        }
        if let Some(h) = entry.get("holder").filter(|h| !h.is_null()) {
            let what = h.get("description").and_then(Value::as_str).unwrap_or("a holder");
            let hs = fusion_unit(h, &format!("{what}'s holder ({what_holder})", what_holder = what_h(h)), &mut notes)?;
            // Its segments from the tool up: each as high as it is, from its lower to its upper
            // diameter.
            let mut sections: Vec<HolderSection> = Vec::new();
            for (i, seg) in h.get("segments").and_then(Value::as_array).into_iter().flatten().enumerate() {
                let field = |k: &str| format!("holder.segments[{i}].{k}");
                let v = |k: &str| number_of(seg.get(k), what, &field(k), true).map(|x| x.map(|x| x * hs));
                let (Some(d), Some(l)) = (v("lower-diameter")?, v("height")?) else {
                    notes.say(format!("{what}: its holder's segment {i} gives no height or lower diameter: the holder not taken"));
                    sections.clear();
                    break;
                };
                let top = v("upper-diameter")?.filter(|u| (u - d).abs() > 1e-9);
                sections.push(HolderSection { diameter: d, length: l, top_diameter: top });
            }
            if sections.is_empty() {
                notes.say(format!("T{number}: its holder ({what}) gives no segments (height, lower and upper diameter): not taken"));
            } else {
                tool.holder = Some(super::Holder { name: what.to_owned(), sections });
            }
        }
        for key in entry.as_object().map(Map::keys).into_iter().flatten().filter(|k| !TAKEN.contains(&k.as_str())) {
            if !unknown.contains(key) {
                unknown.push(key.clone());
            }
        }
        let post = entry.get("post-process").cloned().unwrap_or(json!({}));
        let geometry = g.as_object().map(Map::keys).into_iter().flatten().filter(|k| !GEOMETRY.contains(&k.as_str())).map(|k| format!("geometry.{k}"));
        let posting = post.as_object().map(Map::keys).into_iter().flatten().filter(|k| *k != "number").map(|k| format!("post-process.{k}"));
        for key in geometry.chain(posting) {
            if !unknown.contains(&key) {
                unknown.push(key);
            }
        }
        tools.push(tool);
    }
    if !unknown.is_empty() {
        notes.say(format!("not taken, as swarf does not model them: {}", unknown.join(", ")));
    }
    Ok(Imported { tools, notes: notes.0 })
}

/// A holder's description, for what is said of it.
fn what_h(h: &Value) -> String {
    h.get("description").and_then(Value::as_str).unwrap_or("no description").to_owned()
}

/// LinuxCNC's tool table: `T<n> P<pocket> D<diameter> Z<length> ;comment`, lengths in
/// `scale` mm. The table has no shape: it is taken from the comment's words (a flat end mill
/// where they say none), a guess said for each tool, with a bull nose's corner (`r0.5`) and a
/// V-bit's tip (`tip 0.2`) from them too. A repeated number, a negative or unreadable diameter,
/// or one under the least swarf cuts with, is refused at its line.
fn linuxcnc(text: &str, scale: f64) -> Result<Imported> {
    let mut notes = Notes::default();
    let mut tools: Vec<Tool> = Vec::new();
    let refuse = |line: usize, why: String| Err(Error::Input(format!("line {line}: {why}; the table is not read")));
    for (i, line) in text.lines().enumerate() {
        let (words, comment) = line.split_once(';').unwrap_or((line, ""));
        if words.trim().is_empty() {
            continue;
        }
        let mut number = None;
        let mut diameter = None;
        for w in words.split_whitespace() {
            let (letter, rest) = w.split_at(w.chars().next().map_or(0, char::len_utf8));
            let v = rest.parse::<f64>().ok().filter(|v| v.is_finite());
            match (letter.to_ascii_uppercase().as_str(), v) {
                ("T", Some(v)) if v >= 0.0 && v.fract() == 0.0 => number = Some(v as u32),
                ("T", _) => return refuse(i + 1, format!("{w:?} is no tool number")),
                ("D", Some(v)) if v >= 0.0 => diameter = Some(v * scale),
                ("D", _) => return refuse(i + 1, format!("{w:?} is no diameter (a positive number)")),
                ("P", Some(_)) => {}
                (l, Some(_)) if "XYZABCUVWIJQ".contains(l) => notes.say("the tool offsets and orientations (X Y Z A B C U V W I J Q) are the machine's: not taken".to_owned()),
                _ => notes.say(format!("line {}: {w:?} is no tool table word: not taken", i + 1)),
            }
        }
        let (Some(number), Some(d)) = (number, diameter.filter(|&d| d > 0.0)) else {
            notes.say(format!("line {}: a tool needs its T number and a diameter D: not taken", i + 1));
            continue;
        };
        if d < crate::limits::MIN_TOOL_DIAMETER {
            return refuse(
                i + 1,
                format!(
                    "T{number}'s diameter {} mm is under the least swarf cuts with ({} mm){}",
                    crate::limits::shown(d),
                    crate::limits::MIN_TOOL_DIAMETER,
                    if scale == 1.0 { ": a table in inches is read with inches" } else { "" }
                ),
            );
        }
        if tools.iter().any(|t| t.number == number) {
            return refuse(i + 1, format!("T{number} is given twice"));
        }
        let comment = comment.trim();
        let shape = shape_in(comment).unwrap_or(Shape::Flat);
        notes.say(match shape_in(comment) {
            None => format!("T{number}: the table gives no shape and its comment names none: taken as a flat end mill"),
            Some(s) => format!("T{number}: the table gives no shape: taken from its comment as a {}", shape_name(s)),
        });
        if scale == 1.0 && d < 0.5 && (comment.contains('"') || comment.contains("/") || comment.to_lowercase().contains("inch")) {
            notes.say(format!("T{number}: a diameter of {} mm with a comment in inches ({comment:?}): if the table is in inches, read it with inches", crate::limits::shown(d)));
        }
        let lower = comment.to_lowercase();
        let words: Vec<&str> = lower.split_whitespace().collect();
        // An angle: "118°", "90deg", or "90 deg" (as swarf's own table writes it, in ASCII).
        let angle = words.iter().enumerate().find_map(|(k, w)| {
            let w = w.trim_end_matches(',');
            let unit_next = words.get(k + 1).is_some_and(|n| n.trim_end_matches(',').starts_with("deg"));
            w.strip_suffix("deg").or(w.strip_suffix('°')).or(unit_next.then_some(w)).and_then(|a| a.parse::<f64>().ok())
        });
        let after = |key: &str| words.iter().position(|w| *w == key).and_then(|k| words.get(k + 1)).and_then(|w| w.trim_end_matches(',').parse::<f64>().ok());
        let corner = words.iter().find_map(|w| w.strip_prefix('r').and_then(|r| r.trim_end_matches(',').parse::<f64>().ok()));
        let mut cutter = Cutter { shape, diameter: d, angle: angle.filter(|_| matches!(shape, Shape::Drill | Shape::SpotDrill | Shape::VBit)), ..Cutter::default() };
        if shape == Shape::BullNose {
            if let Some(r) = corner {
                cutter.corner_radius = r * scale;
            }
        }
        if shape == Shape::VBit {
            cutter.tip_diameter = after("tip").map_or(0.0, |t| t * scale);
        }
        tools.push(Tool { number, name: comment.to_owned(), cutter, ..Tool::default() });
    }
    Ok(Imported { tools, notes: notes.0 })
}

/// A FreeCAD quantity in mm (a length) or degrees (an angle), read as FreeCAD's own parser
/// reads it: a number ("5.00", "5,00" as a comma-decimal locale writes it, a fraction
/// "1/4"), then its unit: mm, µm (um), nm, cm, dm, m, km, in ("), ft ('), thou (mil), yd,
/// °, deg, rad; none is the base unit (mm, °). What it is not is said (`Err`): a unit FreeCAD
/// does not have, or no number.
fn quantity(v: &Value) -> std::result::Result<f64, String> {
    let s = match v {
        Value::Number(n) => return n.as_f64().ok_or_else(|| format!("{n} is no number")),
        Value::String(s) => s.trim(),
        other => return Err(format!("{other} is no quantity")),
    };
    let split = s.find(|c: char| !(c.is_ascii_digit() || ".,-+eE/ ".contains(c))).unwrap_or(s.len());
    // An exponent's `e` is the number's only where a digit or sign follows it.
    let (mut n, mut unit) = s.split_at(split);
    if let Some(e) = n.rfind(['e', 'E']).filter(|&e| !n[e + 1..].trim_start_matches(['-', '+']).starts_with(|c: char| c.is_ascii_digit())) {
        (n, unit) = s.split_at(e);
    }
    let n = n.trim();
    let number = |t: &str| -> Option<f64> {
        let t = t.trim();
        if t.contains(',') && !t.contains('.') {
            t.replace(',', ".").parse().ok()
        } else {
            t.parse().ok()
        }
    };
    let value = match n.split_once('/') {
        Some((a, b)) => number(a).zip(number(b)).filter(|(_, b)| *b != 0.0).map(|(a, b)| a / b),
        None => number(n),
    }
    .filter(|v: &f64| v.is_finite())
    .ok_or_else(|| format!("{s:?} is no number"))?;
    let scale = match unit.trim() {
        "" | "mm" | "°" | "deg" => 1.0,
        "µm" | "um" => 1e-3,
        "nm" => 1e-6,
        "cm" => 10.0,
        "dm" => 100.0,
        "m" => 1000.0,
        "km" => 1e6,
        "in" | "\"" => INCH,
        "ft" | "'" => 12.0 * INCH,
        "thou" | "mil" => INCH / 1000.0,
        "yd" => 36.0 * INCH,
        "rad" => 180.0 / std::f64::consts::PI,
        other => return Err(format!("{s:?}: {other:?} is no unit FreeCAD has")),
    };
    Ok(value * scale)
}

/// A FreeCAD tool bit numbered `number`: `None` (said) where swarf has no shape for it or it
/// gives no diameter; an error naming the parameter where a size does not read.
fn freecad_bit(value: &Value, number: u32, name: &str, notes: &mut Vec<String>) -> Result<Option<Tool>> {
    let shape_file = value.get("shape").and_then(Value::as_str).unwrap_or("");
    let bit = value.get("name").and_then(Value::as_str).unwrap_or(name).to_owned();
    let say = |notes: &mut Vec<String>, n: String| {
        if !notes.contains(&n) {
            notes.push(n)
        }
    };
    let Some(shape) = shape_of_file(shape_file) else {
        say(notes, format!("{bit}: its shape {shape_file:?} has none in swarf: not taken"));
        return Ok(None);
    };
    const TAKEN: &[&str] = &[
        "Diameter",
        "ShankDiameter",
        "CuttingEdgeHeight",
        "Length",
        "TorusRadius",
        "CornerRadius",
        "FlatRadius",
        "TipAngle",
        "CuttingEdgeAngle",
        "TipDiameter",
        "Flutes",
        "Chipload",
        "Material",
        "SpindleDirection",
    ];
    let mut p = value.get("parameter").cloned().unwrap_or(json!({}));
    // FreeCAD keeps the flutes, chip load, material and spindle direction among a bit's
    // attributes (older bits among its parameters): read from either.
    if let (Some(attributes), Some(params)) = (value.get("attribute").and_then(Value::as_object), p.as_object_mut()) {
        for key in ["Flutes", "Chipload", "Material", "SpindleDirection"] {
            if let Some(v) = attributes.get(key).filter(|_| !params.contains_key(key)) {
                params.insert(key.to_owned(), v.clone());
            }
        }
    }
    // Every quantity read as FreeCAD reads it, one that does not refused naming it.
    let mut read = std::collections::BTreeMap::new();
    for key in TAKEN.iter().filter(|k| !matches!(**k, "Material" | "SpindleDirection")) {
        if let Some(v) = p.get(*key).filter(|v| !v.is_null()) {
            let q = quantity(v).map_err(|why| Error::Input(format!("{bit}: {key} {why}; the bit is not read")))?;
            if q < 0.0 {
                return Err(Error::Input(format!("{bit}: {key} is {}: a size is not negative; the bit is not read", crate::limits::shown(q))));
            }
            read.insert(*key, q);
        }
    }
    let q = |key: &str| read.get(key).copied();
    let Some(d) = q("Diameter").filter(|&d| d > 0.0) else {
        say(notes, format!("{bit}: no Diameter: not taken"));
        return Ok(None);
    };
    let mut cutter = Cutter { shape, diameter: d, ..Cutter::default() };
    cutter.shank_diameter = q("ShankDiameter").filter(|&s| (s - d).abs() > 1e-9);
    if let Some(l) = q("CuttingEdgeHeight").or(q("Length")) {
        cutter.flute_length = l;
    }
    match shape {
        Shape::BullNose => cutter.corner_radius = q("TorusRadius").or(q("CornerRadius")).or(q("FlatRadius").map(|f| d / 2.0 - f)).unwrap_or(0.0),
        Shape::Drill => cutter.angle = q("TipAngle"),
        Shape::VBit => {
            cutter.angle = q("CuttingEdgeAngle").or(q("TipAngle"));
            // A chamfer mill's flat is given by its radius.
            cutter.tip_diameter = q("TipDiameter").or(q("FlatRadius").map(|r| 2.0 * r)).unwrap_or(0.0);
        }
        _ => {}
    }
    let mut tool = Tool { number, name: bit.clone(), cutter, ..Tool::default() };
    if let Some(z) = q("Flutes") {
        tool.flutes = z.round().max(1.0) as u32;
    }
    match p.get("Material").and_then(Value::as_str).map(str::to_lowercase).as_deref() {
        None | Some("carbide") => {}
        Some("hss") => tool.tool_material = super::ToolMaterial::Hss,
        Some("coated carbide") => tool.tool_material = super::ToolMaterial::Coated,
        Some(other) => say(notes, format!("{bit}: its Material {other:?} is none of Carbide, Coated carbide and HSS, the three swarf's charts have: taken as carbide")),
    }
    // `Units` is how FreeCAD shows the bit (every quantity carries its own unit).
    let unknown: Vec<&String> = p.as_object().map(Map::keys).into_iter().flatten().filter(|k| !TAKEN.contains(&k.as_str()) && *k != "Units").collect();
    if !unknown.is_empty() {
        say(notes, format!("{bit}: not taken, as swarf does not model them: {} (kept, to be written back to FreeCAD)", unknown.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")));
    }
    tool.library_fields = freecad_fields(value);
    Ok(Some(tool))
}

/// Every field of a FreeCAD bit as it is written, by place (`freecad:shape`,
/// `freecad:parameter.Length`, `freecad:attribute.Flutes`), its value as JSON text: what
/// [`write_freecad`] writes back.
fn freecad_fields(bit: &Value) -> std::collections::BTreeMap<String, String> {
    let mut out = std::collections::BTreeMap::new();
    for (key, v) in bit.as_object().into_iter().flatten() {
        match (key.as_str(), v.as_object()) {
            ("version" | "name", _) => {}
            ("parameter" | "attribute", Some(fields)) => {
                out.insert(format!("freecad:{key}"), "{}".to_owned());
                for (k, v) in fields {
                    out.insert(format!("freecad:{key}.{k}"), v.to_string());
                }
            }
            _ => {
                out.insert(format!("freecad:{key}"), v.to_string());
            }
        }
    }
    out
}

/// A FreeCAD library: its tools' numbers and the bits' files they name, read from `bits`.
fn freecad_library(value: &Value, name: &str, bits: &[(String, Vec<u8>)]) -> Result<Imported> {
    let mut out = Imported::default();
    for entry in value.get("tools").and_then(Value::as_array).into_iter().flatten() {
        let number = entry.get("nr").and_then(Value::as_u64).unwrap_or(out.tools.len() as u64 + 1) as u32;
        let path = entry.get("path").and_then(Value::as_str).unwrap_or("");
        let file = path.rsplit(['/', '\\']).next().unwrap_or(path);
        let Some((_, bytes)) = bits.iter().find(|(n, _)| n.rsplit(['/', '\\']).next() == Some(file)) else {
            out.notes.push(format!("T{number}: its bit {file} was not given with {name}: not taken"));
            continue;
        };
        let bit: Value = serde_json::from_slice(bytes).map_err(|e| Error::Input(format!("{file}: not a FreeCAD tool bit: {}", crate::error::plain(&e.to_string()))))?;
        if let Some(t) = freecad_bit(&bit, number, file, &mut out.notes)? {
            out.tools.push(t);
        }
    }
    Ok(out)
}

/// `tools` as a FreeCAD library named `library`: its `.fctl` (each tool's number and its bit's
/// file) and one `.fctb` bit a tool, each with its shape's file and its parameters in mm and
/// degrees, as `(file name, text)`, the library first. A bit holds no speeds or holder (in
/// FreeCAD those are the tool controller's): they are not written. A tool read from a FreeCAD
/// bit is written as that bit was, field for field and in its own words, but for what has
/// changed since: a round trip gives the bit back.
pub fn write_freecad(tools: &[Tool], library: &str) -> Vec<(String, String)> {
    let mut bits = Vec::new();
    let mut entries = Vec::new();
    for t in tools {
        let name = if t.name.is_empty() { t.cutter.describe() } else { t.name.clone() };
        let slug: String = name.chars().map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '_' }).collect();
        let file = format!("T{}_{}.fctb", t.number, slug.trim_matches('_'));
        entries.push(json!({ "nr": t.number, "path": file }));
        bits.push((file, serde_json::to_string_pretty(&freecad_bit_of(t, &name)).expect("JSON")));
    }
    let mut out = vec![(format!("{library}.fctl"), serde_json::to_string_pretty(&json!({ "version": 1, "tools": entries })).expect("JSON"))];
    out.extend(bits);
    out
}

/// The FreeCAD shape file of a cutter's shape.
fn freecad_shape(shape: Shape) -> &'static str {
    match shape {
        Shape::Flat => "endmill.fcstd",
        Shape::Ball => "ballend.fcstd",
        Shape::BullNose => "bullnose.fcstd",
        Shape::Drill | Shape::SpotDrill => "drill.fcstd",
        Shape::VBit => "v-bit.fcstd",
        Shape::ThreadMill => "threadmill.fcstd",
    }
}

/// A tool's FreeCAD bit named `name`. What swarf models, `(place, key, value)`, goes over the
/// fields the tool was read with (`Tool::library_fields`), keeping a field's own text where it
/// still reads the same; a modelled field the bit did not have is added only where the bit
/// would not read back as the tool without it.
fn freecad_bit_of(t: &Tool, name: &str) -> Value {
    let mm = |v: f64| json!(format!("{v:.4} mm"));
    let deg = |v: f64| json!(format!("{v:.4} °"));
    let c = &t.cutter;
    let kept: Vec<(&str, Value)> = t.library_fields.iter().filter_map(|(k, v)| Some((k.strip_prefix("freecad:")?, serde_json::from_str(v).ok()?))).collect();
    let mut modelled: Vec<(&str, &str, Value)> =
        vec![("parameter", "Diameter", mm(c.diameter)), ("parameter", "ShankDiameter", mm(c.shank_diameter.unwrap_or(c.diameter))), ("parameter", "CuttingEdgeHeight", mm(c.flute_length))];
    let length = t.stick_out.unwrap_or(c.flute_length).max(c.flute_length);
    if kept.is_empty() || t.stick_out.is_some() {
        modelled.push(("parameter", "Length", mm(length)));
    }
    match c.shape {
        Shape::BullNose => modelled.push(("parameter", "TorusRadius|CornerRadius", mm(c.corner_radius))),
        Shape::Drill | Shape::SpotDrill => modelled.push(("parameter", "TipAngle", deg(c.point_angle()))),
        Shape::VBit => {
            modelled.push(("parameter", "CuttingEdgeAngle|TipAngle", deg(c.point_angle())));
            modelled.push(("parameter", "TipDiameter", mm(c.tip_diameter)));
        }
        _ => {}
    }
    let material = match t.tool_material {
        super::ToolMaterial::Carbide => "Carbide",
        super::ToolMaterial::Hss => "HSS",
        super::ToolMaterial::Coated => "Coated carbide",
    };
    modelled.push(("attribute", "Flutes", json!(t.flutes)));
    modelled.push(("attribute", "Material", json!(material)));
    // A key names its aliases after a `|`: the first is what swarf writes.
    let first = |key: &str| key.split('|').next().unwrap_or(key).to_owned();
    let fresh = || {
        let mut bit = json!({ "version": 2, "name": name, "shape": freecad_shape(c.shape), "parameter": {}, "attribute": {} });
        for (place, key, v) in &modelled {
            bit[*place][first(key)] = v.clone();
        }
        bit
    };
    if kept.is_empty() {
        return fresh();
    }
    // The bit as it was read, its fields in their places.
    let mut bit = json!({ "version": 2, "name": name });
    for (key, v) in &kept {
        match key.split_once('.') {
            Some((place, k)) => {
                if !bit[place].is_object() {
                    bit[place] = json!({});
                }
                bit[place][k] = v.clone();
            }
            None => bit[*key] = v.clone(),
        }
    }
    // Whether `bit` reads back as the tool (its cutter, flutes and material).
    let reads_back = |bit: &Value| {
        let mut notes = Vec::new();
        matches!(freecad_bit(bit, t.number, name, &mut notes), Ok(Some(b)) if b.cutter == t.cutter && b.flutes == t.flutes && b.tool_material == t.tool_material)
    };
    // Its shape file where it still names the tool's shape ("chamfer.fcstd" for a V-bit).
    if bit.get("shape").and_then(Value::as_str).is_none_or(|s| shape_of_file(s) != Some(c.shape)) {
        bit["shape"] = json!(freecad_shape(c.shape));
    }
    // Where the bit has a field (by any of its names, in either place), and where.
    let find = |bit: &Value, key: &str| -> Option<(&'static str, String)> {
        key.split('|').find_map(|k| ["parameter", "attribute"].into_iter().find(|place| bit[*place].get(k).is_some()).map(|place| (place, k.to_owned())))
    };
    // A field the bit has takes the tool's value where it no longer reads the same.
    let reads = |a: &Value, b: &Value| a == b || matches!((quantity(a), quantity(b)), (Ok(x), Ok(y)) if (x - y).abs() < 1e-9);
    for (_, key, v) in &modelled {
        if let Some((place, k)) = find(&bit, key) {
            let o = &bit[place][&k];
            if !(reads(o, v) || (*key == "Material" && o.as_str().is_some_and(|o| o.eq_ignore_ascii_case(material)))) {
                bit[place][k] = v.clone();
            }
        }
    }
    // A field it lacks is added where the bit does not read back as the tool without it.
    if !reads_back(&bit) {
        for (place, key, v) in &modelled {
            if find(&bit, key).is_none() {
                bit[*place][first(key)] = v.clone();
            }
        }
    }
    if !reads_back(&bit) {
        return fresh();
    }
    bit
}

/// The shape a FreeCAD shape file names, as [`freecad_bit`] takes it.
fn shape_of_file(file: &str) -> Option<Shape> {
    match file.trim_end_matches(".fcstd").to_lowercase().as_str() {
        "endmill" => Some(Shape::Flat),
        "ballend" => Some(Shape::Ball),
        "bullnose" | "torus" => Some(Shape::BullNose),
        "drill" => Some(Shape::Drill),
        "v-bit" | "vbit" | "chamfer" => Some(Shape::VBit),
        "threadmill" => Some(Shape::ThreadMill),
        // A saw cuts with its rim, not its end: no shape swarf plans for.
        other => shape_in(other).filter(|_| !other.contains("saw")),
    }
}

/// `tools` as a library of `format`.
pub fn write_library(tools: &[Tool], format: LibraryFormat) -> String {
    match format {
        LibraryFormat::LinuxCnc => {
            let mut out = String::new();
            for t in tools {
                // The cutter's words first (its shape, corner, angle and tip, as the reader
                // takes them), then the tool's name.
                let name = if t.name.is_empty() { String::new() } else { format!(" ({})", t.name) };
                out += &format!("T{0} P{0} D{1} ;{2}{name}\n", t.number, crate::post::number(t.cutter.diameter, 4), super::super::post::ascii(&t.cutter.describe()));
            }
            out
        }
        LibraryFormat::Fusion => {
            let data: Vec<Value> = tools
                .iter()
                .map(|t| {
                    let c = &t.cutter;
                    let kind = match c.shape {
                        Shape::Flat => "flat end mill",
                        Shape::Ball => "ball end mill",
                        Shape::BullNose => "bull nose end mill",
                        Shape::Drill => "drill",
                        Shape::SpotDrill => "spot drill",
                        Shape::VBit => "chamfer mill",
                        Shape::ThreadMill => "thread mill",
                    };
                    let mut g = json!({ "DC": c.diameter, "SFDM": c.shank_diameter.unwrap_or(c.diameter), "LCF": c.flute_length, "NOF": t.flutes });
                    match c.shape {
                        Shape::BullNose => g["RE"] = json!(c.corner_radius),
                        Shape::Drill | Shape::SpotDrill => g["SIG"] = json!(c.point_angle()),
                        Shape::VBit => {
                            g["TA"] = json!(c.point_angle() / 2.0);
                            g["tip-diameter"] = json!(c.tip_diameter);
                        }
                        _ => {}
                    }
                    if let Some(s) = t.stick_out {
                        g["LB"] = json!(s);
                    }
                    let holder = t.holder.as_ref().map(|h| {
                        let segments: Vec<Value> =
                            h.sections.iter().map(|s| json!({ "height": s.length, "lower-diameter": s.diameter, "upper-diameter": s.top_diameter.unwrap_or(s.diameter) })).collect();
                        json!({ "description": h.name, "type": "holder", "unit": "millimeters", "segments": segments })
                    });
                    json!({
                        "holder": holder,
                        "type": kind,
                        "BMC": match t.tool_material { super::ToolMaterial::Carbide => "carbide", super::ToolMaterial::Hss => "hss", super::ToolMaterial::Coated => "ti coated" },
                        "unit": "millimeters",
                        "description": if t.name.is_empty() { c.describe() } else { t.name.clone() },
                        "geometry": g,
                        "post-process": { "number": t.number },
                        "start-values": { "presets": [{ "name": "swarf", "n": t.spindle_rpm, "v_f": t.feed_rate, "v_f_plunge": t.plunge_rate }] },
                    })
                })
                .collect();
            serde_json::to_string_pretty(&json!({ "data": data, "version": 2 })).expect("JSON")
        }
    }
}
