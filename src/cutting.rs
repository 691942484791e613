//! Speeds and feeds from the stock's material (issue 58): the cutting speed and the chip load a
//! tooth of a tool of its diameter takes, from published tables, each row with its source;
//! from them the spindle speed `n = 1000·vc / (π·D)` and the feed `f = fz·z·n`, capped by the
//! machine's spindle range and feed. A tool takes them unless it says its own are as typed
//! (`speeds: asTyped`): the program, its cycle time and the setup sheet all read the tools as
//! they come out of `Job::with_cutting_data`.
//!
//! The chip loads are for a cut as deep as the tool is wide at full width (the tables'
//! condition); what the operations do with lighter cuts is theirs.

use serde::{Deserialize, Serialize};

use crate::cutter::Shape;
use crate::tool::{Speeds, Tool, ToolMaterial};

/// The stock's material.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Material {
    /// Wrought aluminium (6061-T6, 2024, 7075).
    Aluminium6061,
    /// Low-carbon and low-alloy steel (1018, 1045).
    MildSteel,
    /// Austenitic stainless (304, 316).
    Stainless304,
    /// Yellow, free-cutting and red brass.
    Brass,
    /// Cast or extruded acrylic (PMMA).
    Acrylic,
    /// HDPE and other soft plastics.
    Hdpe,
    /// Hardwood (oak, maple, walnut).
    Hardwood,
    /// MDF and particle board.
    Mdf,
    /// Plywood.
    Plywood,
}

/// The machine's limits the speeds and feeds keep to.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Machine {
    /// Shown in the page and on the setup sheet. Default value: "hobby router".
    pub name: String,
    /// The spindle's slowest and fastest speeds (rpm). Default value: 8000 and 24000.
    pub spindle_min: f64,
    pub spindle_max: f64,
    /// The fastest cutting feed (mm/min). Default value: 5000.
    pub max_feed: f64,
    /// How far the machine travels in X, Y and Z (mm): a program that spans more in any axis
    /// cannot run on it, and is marked not safe to run, naming where. Default value: none (not
    /// known: not checked; each built-in machine has its own).
    pub travel: Option<[f64; 3]>,
    /// Rapid rates in X, Y and Z (mm/min): a rapid takes as long as its slowest axis needs,
    /// in the cycle time and the setup sheet. Default value: none (not known: rapids are timed
    /// along the move at the post's `rapidRate`; each built-in machine has its own).
    pub rapids: Option<[f64; 3]>,
    /// The spindle's power (kW): where the stock's material has a specific cutting force
    /// (the metals), the feeds are held down wherever the simulation finds a cut taking more
    /// ([`MACHINE_COEFFICIENT`] of it reaching the cut). Default value: none (not known: not
    /// held; each built-in machine has its own).
    pub power: Option<f64>,
    /// Whether it changes tools itself (`T… M6` fetches the tool). Without one the operator
    /// changes each tool by hand where the program stops, told which to put in. Default value:
    /// none (not known: the program as the post writes it; each built-in machine says).
    pub tool_changer: Option<bool>,
    /// Whether it has a tool length sensor (a tool setter): after a change by hand the new
    /// tool's length is measured on it (the control's or the sender's tool change routine),
    /// instead of the operator touching off Z again. Default value: none (not known; each
    /// built-in machine says).
    pub length_sensor: Option<bool>,
}

/// The share of the spindle's power that reaches the cut (Mitsubishi Materials' "machine
/// coefficient" η in its cutting-power formula for milling).
pub const MACHINE_COEFFICIENT: f64 = 0.8;

impl Default for Machine {
    fn default() -> Self {
        // The hobby router's limits, its travel and rapids not known until a machine is chosen.
        let mut router = Machine::builtin().swap_remove(0);
        router.travel = None;
        router.rapids = None;
        router.power = None;
        router.tool_changer = None;
        router.length_sensor = None;
        router
    }
}

impl Machine {
    /// The built-in machines: a hobby router, a benchtop mill and a small VMC.
    pub fn builtin() -> Vec<Machine> {
        // Name, spindle range (rpm), fastest feed (mm/min), travel (mm), rapids (mm/min), power (kW).
        let machine = |name: &str, [spindle_min, spindle_max]: [f64; 2], max_feed, travel, rapids, power| Machine {
            name: name.into(),
            spindle_min,
            spindle_max,
            max_feed,
            travel: Some(travel),
            rapids: Some(rapids),
            power: Some(power),
            tool_changer: Some(false),
            length_sensor: Some(false),
        };
        vec![
            // A 4 × 4 ft class router's gantry (838 × 838 × 95 mm on the largest hobby kits), a
            // 1.5 kW spindle.
            machine("hobby router", [8000.0, 24000.0], 5000.0, [800.0, 800.0, 100.0], [10000.0, 10000.0, 5000.0], 1.5),
            // A square-column benchtop mill's table and quill (X 300, Y 150, Z 250), a 1 hp
            // (0.75 kW) motor.
            machine("benchtop mill", [100.0, 10000.0], 2500.0, [300.0, 150.0, 250.0], [3000.0, 3000.0, 2000.0], 0.75),
            // A small VMC's 16 × 12 × 10 inch envelope, a 7.5 hp (5.6 kW) spindle,
            // with an umbrella changer and a tool setter.
            Machine { tool_changer: Some(true), length_sensor: Some(true), ..machine("small VMC", [100.0, 12000.0], 10000.0, [406.0, 305.0, 254.0], [15000.0, 15000.0, 15000.0], 5.6) },
        ]
    }

    /// What is wrong with the limits, if anything: `(field, message)`.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        if !(self.spindle_min.is_finite() && self.spindle_min >= 0.0) {
            out.push(("spindleMin", format!("must be zero or more rpm (got {})", crate::limits::shown(self.spindle_min))));
        }
        if !(self.spindle_max.is_finite() && self.spindle_max > 0.0 && self.spindle_max >= self.spindle_min && self.spindle_max <= crate::limits::MAX_RPM) {
            out.push(("spindleMax", format!("must be more than 0 rpm, at least spindleMin and at most {} (got {})", crate::limits::MAX_RPM, crate::limits::shown(self.spindle_max))));
        }
        if !(self.max_feed.is_finite() && self.max_feed >= 1.0 && self.max_feed <= crate::limits::MAX_FEED) {
            out.push(("maxFeed", format!("must be at least 1 mm/min, at most {} (got {})", crate::limits::MAX_FEED, crate::limits::shown(self.max_feed))));
        }
        if let Some(t) = self.travel.filter(|t| !t.iter().all(|v| v.is_finite() && *v > 0.0 && *v <= crate::limits::MAX_SIZE)) {
            out.push(("travel", format!("must be three lengths of more than 0 mm, at most {} (got {t:?})", crate::limits::MAX_SIZE)));
        }
        if let Some(r) = self.rapids.filter(|r| !r.iter().all(|v| v.is_finite() && *v > 0.0 && *v <= crate::limits::MAX_FEED)) {
            out.push(("rapids", format!("must be three rates of more than 0 mm/min, at most {} (got {r:?})", crate::limits::MAX_FEED)));
        }
        if let Some(p) = self.power.filter(|p| !(p.is_finite() && *p > 0.0 && *p <= MAX_POWER)) {
            out.push(("power", format!("must be more than 0 kW, at most {MAX_POWER} (got {})", crate::limits::shown(p))));
        }
        out
    }

    /// Where a program whose tip reaches from `low` to `high` in each axis (its coordinates)
    /// spans more than this machine travels: for each such axis, its words.
    pub fn beyond_travel(&self, low: [f64; 3], high: [f64; 3]) -> Vec<String> {
        let Some(travel) = self.travel else { return Vec::new() };
        (0..3)
            .filter(|&i| high[i] - low[i] > travel[i] + 1e-9)
            .map(|i| {
                let mm = |v: f64| crate::limits::shown((v * 1000.0).round() / 1000.0);
                format!(
                    "the program spans {} mm in {} (from {} to {}), more than the {}'s {} mm of travel",
                    mm(high[i] - low[i]),
                    ["X", "Y", "Z"][i],
                    mm(low[i]),
                    mm(high[i]),
                    self.name,
                    mm(travel[i])
                )
            })
            .collect()
    }
}

/// A material as the page lists it.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
pub struct MaterialChoice {
    pub value: Material,
    pub words: &'static str,
    pub source: &'static str,
}

impl Material {
    /// Every material of the table, in its order.
    pub fn choices() -> Vec<MaterialChoice> {
        TABLE.iter().map(|r| MaterialChoice { value: r.material, words: r.words, source: r.source }).collect()
    }
}

/// One material's row: its cutting speeds (SFM) for carbide (the chart's range; none: as fast
/// as the spindle goes, as router bits in wood run) and for HSS, and its chip load a tooth (mm)
/// at the tool diameters `DIAMETERS`, with where the figures come from.
struct Row {
    material: Material,
    words: &'static str,
    /// The carbide chart's range of surface speeds (SFM): a tool runs at its middle.
    sfm_carbide: Option<(f64, f64)>,
    /// HSS's surface speed (SFM), from [`HSS`].
    sfm_hss: Option<f64>,
    chip: [f64; 4],
    source: &'static str,
    /// Specific cutting force (N/mm², MPa; [`POWER`]); none where the tables give none.
    kc: Option<f64>,
}

/// The largest spindle power a machine may be given (kW).
const MAX_POWER: f64 = 1000.0;

/// Where the specific cutting forces come from.
pub const POWER: &str = "Mitsubishi Materials, Formulae for cutting power in milling (mitsubishicarbide.com, technical information): the specific cutting force Kc at 0.1 mm a tooth, the table's thinnest chip (thinner chips take more); aluminium at its hardest alloy (Al-Zn-Mg-Cu, 7075), stainless at its austenitic row; none for plastics and wood";

/// The diameters the chip loads are given at (mm): 1/8", 1/4", 3/8", 1/2"; between them the
/// chip load is interpolated, below the first and above the last it is in proportion to the
/// diameter and held at the last.
const DIAMETERS: [f64; 4] = [3.175, 6.35, 9.525, 12.7];

const IN: f64 = 25.4;
/// Surface feet a minute in metres a minute.
const SFM: f64 = 0.3048;

const METALS: &str = "Torbide Tooling, Feeds & Speeds chart for carbide end mills (torbidetooling.com/feeds-speeds): the middle of the SFM range, inch a tooth by diameter";
const ROUTER: &str =
    "AST Tooling, Recommended Feeds & Speeds for Solid Carbide Router Bits (asttooling.com/pages/speeds-and-feeds-charts): the middle of each chip-load range, the spindle at its top speed";
const PLASTICS: &str = "chip load: AST Tooling's router-bit chart (asttooling.com/pages/speeds-and-feeds-charts), the middle of each range; cutting speed: Torbide Tooling's plastics row (200–500 SFM), kept low so the plastic does not melt";
/// Where HSS's and coated carbide's surface speeds come from.
pub const HSS: &str = "HSS: Newson Tool's end-mill chart (newsontool.com, Table A, roughing SFPM: aluminium 600, low-carbon steel 75, stainless 304 55), brass as aluminium (the chart has none; free-cutting brass runs 600+ SFM with HSS, MMTO's machining notes), plastics at half carbide's; coated carbide (TiN, TiAlN, AlTiN) a quarter faster than carbide in the metals (Newson Tool: \"Titanium Nitride Coated +25 percent\"), as carbide in plastics and wood";

/// How much faster a coated carbide tool runs than an uncoated one in the metals ([`HSS`]).
pub const COATED: f64 = 1.25;

const TABLE: [Row; 9] = [
    Row {
        material: Material::Aluminium6061,
        words: "aluminium 6061",
        sfm_carbide: Some((800.0, 1500.0)),
        sfm_hss: Some(600.0),
        chip: [0.001 * IN, 0.002 * IN, 0.003 * IN, 0.004 * IN],
        source: METALS,
        kc: Some(880.0),
    },
    Row {
        material: Material::MildSteel,
        words: "mild steel",
        sfm_carbide: Some((100.0, 300.0)),
        sfm_hss: Some(75.0),
        chip: [0.0005 * IN, 0.0015 * IN, 0.002 * IN, 0.003 * IN],
        source: METALS,
        kc: Some(2200.0),
    },
    Row {
        material: Material::Stainless304,
        words: "stainless 304",
        sfm_carbide: Some((100.0, 250.0)),
        sfm_hss: Some(55.0),
        chip: [0.0001 * IN, 0.0005 * IN, 0.001 * IN, 0.0015 * IN],
        source: METALS,
        kc: Some(2030.0),
    },
    Row {
        material: Material::Brass,
        words: "brass",
        sfm_carbide: Some((800.0, 1500.0)),
        sfm_hss: Some(600.0),
        chip: [0.001 * IN, 0.002 * IN, 0.0025 * IN, 0.003 * IN],
        source: METALS,
        kc: Some(1150.0),
    },
    Row {
        material: Material::Acrylic,
        words: "acrylic",
        sfm_carbide: Some((350.0, 350.0)),
        sfm_hss: Some(175.0),
        chip: [0.003 * IN, 0.0065 * IN, 0.009 * IN, 0.0115 * IN],
        source: PLASTICS,
        kc: None,
    },
    Row { material: Material::Hdpe, words: "HDPE", sfm_carbide: Some((500.0, 500.0)), sfm_hss: Some(250.0), chip: [0.004 * IN, 0.0075 * IN, 0.010 * IN, 0.0125 * IN], source: PLASTICS, kc: None },
    Row { material: Material::Hardwood, words: "hardwood", sfm_carbide: None, sfm_hss: None, chip: [0.003 * IN, 0.006 * IN, 0.014 * IN, 0.018 * IN], source: ROUTER, kc: None },
    Row { material: Material::Mdf, words: "MDF", sfm_carbide: None, sfm_hss: None, chip: [0.0055 * IN, 0.0135 * IN, 0.018 * IN, 0.0225 * IN], source: ROUTER, kc: None },
    Row { material: Material::Plywood, words: "plywood", sfm_carbide: None, sfm_hss: None, chip: [0.004 * IN, 0.0075 * IN, 0.0165 * IN, 0.0195 * IN], source: ROUTER, kc: None },
];

fn row(material: Material) -> &'static Row {
    TABLE.iter().find(|r| r.material == material).expect("every material has a row")
}

impl Material {
    /// Its name in a machinist's words.
    pub fn words(self) -> &'static str {
        row(self).words
    }

    /// Where its figures come from.
    pub fn source(self) -> &'static str {
        row(self).source
    }

    /// Its specific cutting force (N/mm², [`POWER`]): the spindle power a cut takes is its
    /// material removal rate times this.
    pub fn specific_cutting_force(self) -> Option<f64> {
        row(self).kc
    }

    /// The cutting speed for a tool of `tool` material (m/min), or none: the spindle's top.
    pub fn cutting_speed(self, tool: ToolMaterial) -> Option<f64> {
        let r = row(self);
        let carbide = r.sfm_carbide.map(|(lo, hi)| 0.5 * (lo + hi) * SFM);
        match tool {
            ToolMaterial::Carbide => carbide,
            ToolMaterial::Coated => carbide.map(|v| if r.kc.is_some() { v * COATED } else { v }),
            ToolMaterial::Hss => r.sfm_hss.map(|v| v * SFM),
        }
    }

    /// The carbide chart's range of surface speeds (m/min), where it gives one.
    pub fn carbide_range(self) -> Option<(f64, f64)> {
        row(self).sfm_carbide.map(|(lo, hi)| (lo * SFM, hi * SFM))
    }

    /// The chip load a tooth of a tool `diameter` wide takes (mm).
    pub fn chip_load(self, diameter: f64) -> f64 {
        let c = row(self).chip;
        if diameter <= DIAMETERS[0] {
            return c[0] * diameter / DIAMETERS[0];
        }
        for k in 1..DIAMETERS.len() {
            if diameter <= DIAMETERS[k] {
                let t = (diameter - DIAMETERS[k - 1]) / (DIAMETERS[k] - DIAMETERS[k - 1]);
                return c[k - 1] + t * (c[k] - c[k - 1]);
            }
        }
        c[DIAMETERS.len() - 1]
    }
}

/// A tool's speeds and feeds as worked out, with the reasons in words.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct CuttingData {
    pub tool: u32,
    pub spindle_rpm: f64,
    pub feed_rate: f64,
    pub plunge_rate: f64,
    /// Whether they come from the material (false: as typed).
    pub from_material: bool,
    /// How they were worked out ("φ6 carbide, 2 flutes, in aluminium 6061: 244 m/min → …").
    pub reason: String,
    /// Where the material's figures come from.
    pub source: Option<String>,
}

/// `tool`'s speeds and feeds cutting `material` on `machine` (as typed where the tool says so
/// or the job names no material), at a cut as deep as its diameter.
pub fn cutting_data(tool: &Tool, material: Option<Material>, machine: &Machine) -> CuttingData {
    cutting_data_at(tool, material, machine, None)
}

/// The diameter a tool cuts at when its cut is `depth` deep (mm): a ball's or a bull nose's
/// corner cuts at a smaller circle than its diameter near its tip, `2·√(d·(2r − d))` across the
/// corner of radius `r` (the flat between added), so its spindle runs faster for the same
/// surface speed; the whole diameter at or beyond the corner, and for every other shape.
pub fn effective_diameter(cutter: &crate::cutter::Cutter, depth: f64) -> f64 {
    let d = cutter.diameter;
    let r = match cutter.shape {
        Shape::Ball => d / 2.0,
        Shape::BullNose => cutter.corner_radius,
        _ => return d,
    };
    if !(depth > 0.0) || depth >= r || r <= 0.0 {
        return d;
    }
    d - 2.0 * r + 2.0 * (depth * (2.0 * r - depth)).sqrt()
}

/// [`cutting_data`] where the deepest cut the tool takes is `depth` (mm; none: as deep as its
/// diameter): a ball or bull nose takes its speed from its [`effective_diameter`] there, its
/// chip load from its whole diameter. Where the machine's slowest spindle speed is faster than
/// the surface speed wants, the feed stays what the chart's speed gives (a thinner chip a
/// tooth), said in the reason.
pub fn cutting_data_at(tool: &Tool, material: Option<Material>, machine: &Machine, depth: Option<f64>) -> CuttingData {
    // Feeds as typed, no faster than the machine goes.
    let typed = |why: &str| {
        let held = tool.feed_rate > machine.max_feed || tool.plunge_rate > machine.max_feed;
        CuttingData {
            tool: tool.number,
            spindle_rpm: tool.spindle_rpm,
            feed_rate: tool.feed_rate.min(machine.max_feed),
            plunge_rate: tool.plunge_rate.min(machine.max_feed),
            from_material: false,
            reason: if held { format!("{why}, held at the machine's fastest feed ({} mm/min)", crate::limits::shown(machine.max_feed)) } else { why.to_owned() },
            source: None,
        }
    };
    let Some(material) = material else { return typed("as typed: the stock's material is not set") };
    if tool.speeds == Speeds::AsTyped {
        return typed("as typed (the tool's own)");
    }
    let c = &tool.cutter;
    let d = c.diameter;
    let cut_at = depth.map_or(d, |depth| effective_diameter(c, depth));
    // A drill's two lips, a thread mill's single form, an end mill's flutes.
    let teeth = match c.shape {
        Shape::Drill | Shape::SpotDrill => 2,
        _ => tool.flutes.max(1),
    } as f64;
    let shown = crate::limits::shown;
    let mut why = format!(
        "φ{} {}, {} {}, in {}: ",
        shown(d),
        tool.tool_material.words(),
        teeth,
        if matches!(c.shape, Shape::Drill | Shape::SpotDrill) {
            "lips"
        } else if teeth == 1.0 {
            "flute"
        } else {
            "flutes"
        },
        material.words()
    );
    let wanted = match material.cutting_speed(tool.tool_material) {
        Some(vc) => {
            let n = 1000.0 * vc / (std::f64::consts::PI * cut_at);
            why += &format!("{} m/min", shown((vc * 10.0).round() / 10.0));
            if cut_at < d - 1e-9 {
                why += &format!(" at φ{} (where its corner cuts {} mm deep)", shown((cut_at * 100.0).round() / 100.0), shown(depth.unwrap_or(0.0)));
            }
            why += &format!(" → {} rpm", shown(n.round()));
            n
        }
        None => {
            why += "the spindle's top speed";
            machine.spindle_max
        }
    };
    let rpm = wanted.clamp(machine.spindle_min, machine.spindle_max).round();
    // Thread mills take a light chip: half the table's.
    let mut fz = material.chip_load(d) * if c.shape == Shape::ThreadMill { 0.5 } else { 1.0 };
    if rpm < wanted.round() {
        why += &format!(" (held at the machine's {} rpm)", shown(rpm));
    } else if rpm > wanted.round() {
        why += &format!(" (the machine's slowest, {} rpm", shown(rpm));
        if let Some(over) = surface_too_fast(tool, material, machine) {
            why += &format!(": {over}");
        }
        // The feed the chart's speed gives, spread over the faster turns.
        let thinner = fz * wanted / rpm;
        why += &format!("; the chip a tooth thinned from {} to {} mm to keep the chart's feed)", shown((fz * 10000.0).round() / 10000.0), shown((thinner * 10000.0).round() / 10000.0));
        fz = thinner;
    }
    let wanted_feed = fz * teeth * rpm;
    let feed = wanted_feed.min(machine.max_feed).max(1.0);
    why += &format!("; {} mm a tooth × {} × {} rpm = {} mm/min", shown((fz * 10000.0).round() / 10000.0), teeth, shown(rpm), shown(wanted_feed.round()));
    if feed < wanted_feed {
        why += &format!(" (held at the machine's {} mm/min)", shown(machine.max_feed));
    }
    // A drill feeds at its feed; an end mill plunges at half its feed.
    let plunge = if matches!(c.shape, Shape::Drill | Shape::SpotDrill) { feed } else { feed / 2.0 };
    CuttingData {
        tool: tool.number,
        spindle_rpm: rpm,
        feed_rate: feed.round(),
        plunge_rate: plunge.round().max(1.0),
        from_material: true,
        reason: why,
        source: Some(format!("{}; {}", material.source(), HSS)),
    }
}

/// Where `machine`'s slowest spindle speed runs `tool` in `material` at more than half as fast
/// again as the chart's surface speed: what it comes to, in words (a φ12 in mild steel on a
/// router's 8000 rpm floor runs at several times the chart's speed, and burns).
pub fn surface_too_fast(tool: &Tool, material: Material, machine: &Machine) -> Option<String> {
    let vc = material.cutting_speed(tool.tool_material)?;
    let d = tool.cutter.diameter;
    let at = std::f64::consts::PI * d * machine.spindle_min / 1000.0;
    (at > 1.5 * vc).then(|| {
        format!(
            "{} m/min at the surface, {:.1} × the chart's {} m/min for {} in {}: too fast for it; a machine that turns slower suits it",
            crate::limits::shown(at.round()),
            at / vc,
            crate::limits::shown((vc * 10.0).round() / 10.0),
            tool.tool_material.words(),
            material.words()
        )
    })
}

/// The spindle power (kW) a cut removing `rate` mm³/min of a material of specific cutting
/// force `kc` (N/mm²) takes: `rate · kc / (60·10⁶ · η)`, η the [`MACHINE_COEFFICIENT`].
pub fn power(rate: f64, kc: f64) -> f64 {
    rate * kc / (60e6 * MACHINE_COEFFICIENT)
}

/// The largest material removal rate (mm³/min) `machine`'s spindle can take in `material`,
/// where both are known ([`power`] turned round).
pub fn rate_limit(machine: &Machine, material: Option<Material>) -> Option<f64> {
    Some(machine.power? * 60e6 * MACHINE_COEFFICIENT / material?.specific_cutting_force()?)
}
