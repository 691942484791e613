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
    let text = std::str::from_utf8(bytes).map_err(|_| Error::Input(format!("{name}: not text (a tool library is JSON or a LinuxCNC tool table)")))?;
    let lower = name.to_lowercase();
    if lower.ends_with(".tbl") {
        return Ok(linuxcnc(text, if inches { INCH } else { 1.0 }));
    }
    let value: Value = serde_json::from_str(text).map_err(|e| Error::Input(format!("{name}: not a tool library: {}", crate::error::plain(&e.to_string()))))?;
    if lower.ends_with(".fctl") || value.get("tools").and_then(Value::as_array).is_some_and(|t| t.iter().any(|x| x.get("path").is_some())) {
        return freecad_library(&value, name, bits);
    }
    if lower.ends_with(".fctb") || value.get("shape").is_some() {
        let mut out = Imported::default();
        if let Some(t) = freecad_bit(&value, 1, name, &mut out.notes) {
            out.tools.push(t);
        }
        return Ok(out);
    }
    if value.get("data").is_some_and(Value::is_array) {
        return Ok(fusion(&value));
    }
    Err(Error::Input(format!("{name}: not a tool library swarf reads (Fusion's JSON with `data`, a LinuxCNC .tbl, a FreeCAD .fctb or .fctl)")))
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

/// A cutter's shape from words in a name or a type ("ball end mill", "6 mm V-bit 60°").
fn shape_in(words: &str) -> Option<Shape> {
    let w = words.to_lowercase();
    [
        ("bull", Shape::BullNose),
        ("torus", Shape::BullNose),
        ("radius", Shape::BullNose),
        ("ball", Shape::Ball),
        ("spot", Shape::SpotDrill),
        ("center drill", Shape::SpotDrill),
        ("centre drill", Shape::SpotDrill),
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
    ]
    .iter()
    .find(|(k, _)| w.contains(k))
    .map(|&(_, s)| s)
}

/// Fusion's tool library.
fn fusion(value: &Value) -> Imported {
    let mut notes = Notes::default();
    let mut tools = Vec::new();
    let mut unknown: Vec<String> = Vec::new();
    const TAKEN: &[&str] = &["type", "unit", "description", "product-id", "vendor", "geometry", "post-process", "start-values", "guid", "holder", "BMC", "GRADE"];
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
        let scale = if entry.get("unit").and_then(Value::as_str) == Some("inches") { INCH } else { 1.0 };
        let g = entry.get("geometry").cloned().unwrap_or(json!({}));
        let num = |key: &str| g.get(key).and_then(Value::as_f64);
        let d = num("DC").unwrap_or(0.0) * scale;
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
        let mut tool = Tool { number, name: description.clone(), cutter, ..Tool::default() };
        if let Some(z) = num("NOF") {
            tool.flutes = z.round().max(1.0) as u32;
        }
        if let Some(lb) = num("LB") {
            tool.stick_out = Some((lb * scale).max(tool.cutter.flute_length));
        }
        let presets = entry.pointer("/start-values/presets").and_then(Value::as_array).cloned().unwrap_or_default();
        if let Some(p) = presets.first() {
            let rate = |key: &str| p.get(key).and_then(Value::as_f64).filter(|v| *v > 0.0);
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
            let hs = if h.get("unit").and_then(Value::as_str) == Some("inches") { INCH } else { 1.0 };
            // Its segments from the tool up: each as high as it is, from its lower to its upper
            // diameter.
            let sections: Vec<HolderSection> = h
                .get("segments")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
                .filter_map(|seg| {
                    let v = |k: &str| seg.get(k).and_then(Value::as_f64).map(|x| x * hs);
                    let (d, l) = (v("lower-diameter")?, v("height")?);
                    let top = v("upper-diameter").filter(|u| (u - d).abs() > 1e-9);
                    Some(HolderSection { diameter: d, length: l, top_diameter: top })
                })
                .collect();
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
    Imported { tools, notes: notes.0 }
}

/// LinuxCNC's tool table: `T<n> P<pocket> D<diameter> Z<length> ;comment`, lengths in
/// `scale` mm; the shape from the comment's words (a flat end mill where they say none).
fn linuxcnc(text: &str, scale: f64) -> Imported {
    let mut notes = Notes::default();
    let mut tools = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let (words, comment) = line.split_once(';').unwrap_or((line, ""));
        if words.trim().is_empty() {
            continue;
        }
        let mut number = None;
        let mut diameter = None;
        for w in words.split_whitespace() {
            let (letter, rest) = w.split_at(1);
            let v = rest.parse::<f64>();
            match (letter.to_ascii_uppercase().as_str(), v) {
                ("T", Ok(v)) => number = Some(v as u32),
                ("D", Ok(v)) => diameter = Some(v.abs() * scale),
                ("P", Ok(_)) => {}
                (l, Ok(_)) if "XYZABCUVWIJQ".contains(l) => notes.say("the tool offsets and orientations (X Y Z A B C U V W I J Q) are the machine's: not taken".to_owned()),
                _ => notes.say(format!("line {}: {w:?} is no tool table word: not taken", i + 1)),
            }
        }
        let (Some(number), Some(d)) = (number, diameter.filter(|&d| d > 0.0)) else {
            notes.say(format!("line {}: a tool needs its T number and a diameter D: not taken", i + 1));
            continue;
        };
        let comment = comment.trim();
        let shape = shape_in(comment).unwrap_or(Shape::Flat);
        if shape_in(comment).is_none() {
            notes.say(format!("T{number}: the comment names no shape: taken as a flat end mill"));
        }
        let angle = comment.split_whitespace().find_map(|w| w.trim_end_matches(['°', ',']).strip_suffix("deg").or(w.strip_suffix('°')).and_then(|a| a.parse::<f64>().ok()));
        let cutter = Cutter { shape, diameter: d, angle: angle.filter(|_| matches!(shape, Shape::Drill | Shape::SpotDrill | Shape::VBit)), ..Cutter::default() };
        tools.push(Tool { number, name: comment.to_owned(), cutter, ..Tool::default() });
    }
    Imported { tools, notes: notes.0 }
}

/// A FreeCAD quantity ("5.00 mm", "118.00 °", "0.25 in", or a bare number) in mm or degrees.
fn quantity(v: &Value) -> Option<f64> {
    match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => {
            let s = s.trim();
            let split = s.find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E')).unwrap_or(s.len());
            let (n, unit) = s.split_at(split);
            let n: f64 = n.trim().parse().ok()?;
            Some(match unit.trim() {
                "in" | "\"" => n * INCH,
                "cm" => n * 10.0,
                "m" => n * 1000.0,
                _ => n,
            })
        }
        _ => None,
    }
}

/// A FreeCAD tool bit numbered `number`.
fn freecad_bit(value: &Value, number: u32, name: &str, notes: &mut Vec<String>) -> Option<Tool> {
    let shape_file = value.get("shape").and_then(Value::as_str).unwrap_or("");
    let bit = value.get("name").and_then(Value::as_str).unwrap_or(name).to_owned();
    let say = |notes: &mut Vec<String>, n: String| {
        if !notes.contains(&n) {
            notes.push(n)
        }
    };
    let shape = match shape_file.trim_end_matches(".fcstd").to_lowercase().as_str() {
        "endmill" | "slittingsaw" => Shape::Flat,
        "ballend" => Shape::Ball,
        "bullnose" | "torus" => Shape::BullNose,
        "drill" => Shape::Drill,
        "v-bit" | "vbit" | "chamfer" => Shape::VBit,
        "threadmill" => Shape::ThreadMill,
        other => match shape_in(other) {
            Some(s) => s,
            None => {
                say(notes, format!("{bit}: its shape {shape_file:?} has none in swarf: not taken"));
                return None;
            }
        },
    };
    let p = value.get("parameter").cloned().unwrap_or(json!({}));
    let q = |key: &str| p.get(key).and_then(quantity);
    let Some(d) = q("Diameter").filter(|&d| d > 0.0) else {
        say(notes, format!("{bit}: no Diameter: not taken"));
        return None;
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
            cutter.tip_diameter = q("TipDiameter").unwrap_or(0.0);
        }
        _ => {}
    }
    let mut tool = Tool { number, name: bit.clone(), cutter, ..Tool::default() };
    if let Some(z) = q("Flutes") {
        tool.flutes = z.round().max(1.0) as u32;
    }
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
    let unknown: Vec<&String> = p.as_object().map(Map::keys).into_iter().flatten().filter(|k| !TAKEN.contains(&k.as_str())).collect();
    if !unknown.is_empty() {
        say(notes, format!("{bit}: not taken, as swarf does not model them: {}", unknown.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")));
    }
    Some(tool)
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
        if let Some(t) = freecad_bit(&bit, number, file, &mut out.notes) {
            out.tools.push(t);
        }
    }
    Ok(out)
}

/// `tools` as a FreeCAD library named `library`: its `.fctl` (each tool's number and its bit's
/// file) and one `.fctb` bit a tool, each with its shape's file and its parameters in mm and
/// degrees, as `(file name, text)`, the library first. A bit holds no speeds or holder (in
/// FreeCAD those are the tool controller's): they are not written.
pub fn write_freecad(tools: &[Tool], library: &str) -> Vec<(String, String)> {
    let mm = |v: f64| format!("{v:.4} mm");
    let deg = |v: f64| format!("{v:.4} °");
    let mut bits = Vec::new();
    let mut entries = Vec::new();
    for t in tools {
        let c = &t.cutter;
        let shape = match c.shape {
            Shape::Flat => "endmill",
            Shape::Ball => "ballend",
            Shape::BullNose => "bullnose",
            Shape::Drill | Shape::SpotDrill => "drill",
            Shape::VBit => "v-bit",
            Shape::ThreadMill => "threadmill",
        };
        let mut p = Map::new();
        p.insert("Diameter".into(), json!(mm(c.diameter)));
        p.insert("ShankDiameter".into(), json!(mm(c.shank_diameter.unwrap_or(c.diameter))));
        p.insert("CuttingEdgeHeight".into(), json!(mm(c.flute_length)));
        p.insert("Length".into(), json!(mm(t.stick_out.unwrap_or(c.flute_length).max(c.flute_length))));
        p.insert("Flutes".into(), json!(t.flutes.to_string()));
        match c.shape {
            Shape::BullNose => {
                p.insert("TorusRadius".into(), json!(mm(c.corner_radius)));
            }
            Shape::Drill | Shape::SpotDrill => {
                p.insert("TipAngle".into(), json!(deg(c.point_angle())));
            }
            Shape::VBit => {
                p.insert("CuttingEdgeAngle".into(), json!(deg(c.point_angle())));
                p.insert("TipDiameter".into(), json!(mm(c.tip_diameter)));
            }
            _ => {}
        }
        let name = if t.name.is_empty() { c.describe() } else { t.name.clone() };
        let slug: String = name.chars().map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '_' }).collect();
        let file = format!("T{}_{}.fctb", t.number, slug.trim_matches('_'));
        let bit = json!({ "version": 2, "name": name, "shape": format!("{shape}.fcstd"), "parameter": p, "attribute": {} });
        entries.push(json!({ "nr": t.number, "path": file }));
        bits.push((file, serde_json::to_string_pretty(&bit).expect("JSON")));
    }
    let mut out = vec![(format!("{library}.fctl"), serde_json::to_string_pretty(&json!({ "version": 1, "tools": entries })).expect("JSON"))];
    out.extend(bits);
    out
}

/// `tools` as a library of `format`.
pub fn write_library(tools: &[Tool], format: LibraryFormat) -> String {
    match format {
        LibraryFormat::LinuxCnc => {
            let mut out = String::new();
            for t in tools {
                let angle = t.cutter.angle.map(|a| format!(" {}°", crate::limits::shown(a))).unwrap_or_default();
                out += &format!("T{0} P{0} D{1} ;{2}{angle}\n", t.number, crate::post::number(t.cutter.diameter, 4), super::super::post::ascii(&t.describe()));
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
