//! G-code writing. One writer walks the program; a [`Post`] (data, [`definition`]) says what
//! the controller accepts: its header and footer, tool changes, spindle, coolant and dwell
//! words, comments, line numbers, decimals, arcs by I/J or R or none, helices, modal words and
//! line length. The built-in posts ([`Dialect`]) are such data. The writer times the program as
//! it writes it and puts the cycle time in its head. Millimetres inside; inches only here.

pub mod definition;
pub mod grbl;
pub mod read;

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

pub use self::definition::{ArcFormat, CommentCharacters, CommentStyle, Post};

use self::definition::ARC_CHORD_ERROR;
use crate::error::Error;
use crate::geom::{DVec2, DVec3};
use crate::mesh::placement::Units;
use crate::tool::{Coolant, Tool};
use crate::toolpath::cycle::{same_moves, Cycle, CycleKind};
use crate::toolpath::{arc_sweep, Move, Rapids, Toolpath};

/// The built-in posts, by the controller family they are written for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Dialect {
    #[default]
    LinuxCnc,
    /// GRBL 1.1: no tool changer (the program pauses with `M0` naming the tool), only the words
    /// GRBL accepts, lines of at most 80 characters.
    Grbl,
    /// grblHAL: GRBL's words with `T… M6` tool changes.
    GrblHal,
    /// Mach3 and Mach4: `.tap`, arcs split at the quadrants, incremental I and J set explicitly.
    Mach3,
    /// Fanuc: `%`, a program number, line numbers, arcs by R.
    Fanuc,
    /// Plain RS-274: arcs split at the quadrants, helices as chords, every word on every line.
    Generic,
}

impl Dialect {
    /// Every built-in post.
    pub const ALL: [Dialect; 6] = [Dialect::LinuxCnc, Dialect::Grbl, Dialect::GrblHal, Dialect::Mach3, Dialect::Fanuc, Dialect::Generic];

    /// The built-in post's data (`src/post/builtin/*.json`), read once.
    pub fn post(self) -> Post {
        static POSTS: std::sync::OnceLock<Vec<Post>> = std::sync::OnceLock::new();
        let posts = POSTS.get_or_init(|| {
            Dialect::ALL
                .iter()
                .map(|d| {
                    let json = match d {
                        Dialect::LinuxCnc => include_str!("builtin/linuxcnc.json"),
                        Dialect::Grbl => include_str!("builtin/grbl.json"),
                        Dialect::GrblHal => include_str!("builtin/grblhal.json"),
                        Dialect::Mach3 => include_str!("builtin/mach3.json"),
                        Dialect::Fanuc => include_str!("builtin/fanuc.json"),
                        Dialect::Generic => include_str!("builtin/generic.json"),
                    };
                    // The built-in files are read by a test of their own.
                    Post::from_json(json).unwrap_or_else(|e| panic!("built-in post {d:?}: {e}"))
                })
                .collect()
        });
        posts[Dialect::ALL.iter().position(|&d| d == self).expect("every dialect is in ALL")].clone()
    }

    /// The file extension its controllers expect: `ngc` for LinuxCNC, `tap` for Mach3/Mach4,
    /// `nc` for the others.
    pub fn extension(self) -> String {
        self.post().extension
    }
}

/// How G-code is written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct PostSettings {
    /// The built-in post. Default value: linuxCnc.
    pub dialect: Dialect,
    /// A post of the user's own (the fields of [`Post`]), used instead of the built-in one.
    /// Default value: none.
    pub custom: Option<Post>,
    /// Units of the program. Default value: mm.
    pub units: Units,
    /// Digits after the decimal point, instead of the post's. Default value: the post's (3
    /// for mm, 4 for inches in the built-in posts).
    pub decimals: Option<usize>,
    /// Rapid rate of the machine (mm/min), for the cycle-time estimate. Default value: 3000.
    pub rapid_rate: f64,
    /// The machine's rapid rates per axis (`machine.rapids`), which time rapids instead of
    /// `rapidRate` where known: set from the job's machine as its programs are written.
    #[serde(skip)]
    #[ts(skip)]
    pub rapid_axes: Option<[f64; 3]>,
    /// Whether the machine changes tools itself and measures them (`machine.toolChanger`,
    /// `machine.lengthSensor`): set from the job's machine as its programs are written; none
    /// where not known.
    #[serde(skip)]
    #[ts(skip)]
    pub tool_changer: Option<bool>,
    #[serde(skip)]
    #[ts(skip)]
    pub length_sensor: Option<bool>,
    /// Time a tool change takes (seconds), for the cycle-time estimate. Default value: 15.
    pub tool_change_seconds: f64,
    /// Program number (O word) for posts that write one. Default value: 1.
    pub program_number: u32,
    /// The work offset the program selects (`G54` to `G59`), instead of the post's: each
    /// setup of a part holds its own zero. Default value: the post's (G54 in the built-in
    /// posts).
    pub work_offset: Option<String>,
    /// With setups: every setup in one program, the control stopping (the post's pause, `M0`)
    /// between them with a message on how to hold the part next, instead of a program per
    /// setup. Default value: false.
    pub one_program: bool,
}

impl PostSettings {
    /// How rapids are timed: the machine's rates per axis where known, else `rapidRate`.
    pub fn rapids(&self) -> Rapids {
        Rapids { rate: self.rapid_rate, axes: self.rapid_axes }
    }

    /// The post in use: the user's own, else the built-in one.
    pub fn post(&self) -> Post {
        let mut post = self.custom.clone().unwrap_or_else(|| self.dialect.post());
        if let Some(w) = &self.work_offset {
            post.work_offset = Some(w.clone());
        }
        post
    }

    /// The file extension of the program.
    pub fn extension(&self) -> String {
        self.post().extension
    }

    fn decimals_for(&self, post: &Post) -> usize {
        self.decimals.unwrap_or(match self.units {
            Units::Mm => post.decimals_mm,
            Units::Inch => post.decimals_inch,
        })
    }

    /// How far rounding to the program's decimals can move a point sideways (mm): half a unit
    /// of the last digit in X and in Y.
    pub fn resolution(&self) -> f64 {
        self.resolution_in(self.units)
    }

    fn resolution_in(&self, units: Units) -> f64 {
        let decimals = self.decimals.unwrap_or(match units {
            Units::Mm => self.post().decimals_mm,
            Units::Inch => self.post().decimals_inch,
        });
        0.5 * 10f64.powi(-(decimals as i32)) * units.mm() * std::f64::consts::SQRT_2
    }

    /// The resolution paths are planned for (mm): the coarser of the post's in millimetres and
    /// in inches. Strategies that follow a surface take their heights as the highest within
    /// this distance, so that the written points stay above it whichever unit the program is
    /// written in: a job is planned once, in millimetres, and the post only writes it (a
    /// program in inches follows the same path as one in millimetres, to the inch's
    /// resolution, and the page writes it again in the other unit without planning again).
    pub fn planning_resolution(&self) -> f64 {
        self.resolution_in(Units::Mm).max(self.resolution_in(Units::Inch))
    }

    /// Checks the settings and the post; errors name the field.
    pub fn validate(&self, tools: &[Tool]) -> Result<(), String> {
        if let Some(custom) = &self.custom {
            custom.validate().map_err(|e| format!("post.custom.{e}"))?;
        }
        if let Some(w) = &self.work_offset {
            let post = self.post();
            if !post.has_work_offset(w) {
                return Err(format!("post.workOffset must be {} (got {w:?})", post.work_offsets_words()));
            }
        }
        if let Some(d) = self.decimals {
            if !(1..=6).contains(&d) {
                return Err(format!("post.decimals must be 1 to 6 (got {d})"));
            }
        }
        if !(self.rapid_rate > 0.0 && self.rapid_rate <= crate::limits::MAX_FEED) {
            return Err(format!("post.rapidRate must be a positive number of mm/min, at most {} (got {})", crate::limits::MAX_FEED, crate::limits::shown(self.rapid_rate)));
        }
        if !(self.tool_change_seconds >= 0.0 && self.tool_change_seconds <= crate::limits::MAX_TOOL_CHANGE) {
            return Err(format!("post.toolChangeSeconds must be zero or more seconds, at most a day (got {})", crate::limits::shown(self.tool_change_seconds)));
        }
        let post = self.post();
        for t in tools {
            let (word, field) = match t.coolant {
                Coolant::Off => continue,
                Coolant::Flood => (&post.coolant_flood, "coolantFlood"),
                Coolant::Mist => (&post.coolant_mist, "coolantMist"),
            };
            if word.is_none() || post.coolant_off.is_none() {
                let missing = if word.is_none() { field } else { "coolantOff" };
                return Err(format!("tool {} asks for {:?} coolant, but the post {} has no {missing} word", t.number, t.coolant, post.name));
            }
        }
        Ok(())
    }
}

impl Default for PostSettings {
    fn default() -> Self {
        PostSettings {
            dialect: Dialect::LinuxCnc,
            custom: None,
            units: Units::Mm,
            decimals: None,
            rapid_rate: 3000.0,
            rapid_axes: None,
            tool_changer: None,
            length_sensor: None,
            tool_change_seconds: 15.0,
            program_number: 1,
            work_offset: None,
            one_program: false,
        }
    }
}

/// What a program takes on the machine, part by part: each tool path's motion (its way down
/// from the clearance height included), the tool changes, and the rest (the spindle's start
/// dwells and the retracts to the clearance height at tool changes and at the end). The parts
/// sum to the whole, and [`CycleTime::items`] rounds them so that they still do.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct CycleTime {
    /// Seconds of motion of each tool path, in the program's order.
    pub paths: Vec<f64>,
    /// When each tool path's own moves begin (s from the program's start), after its tool
    /// change and its way down from the clearance height.
    pub starts: Vec<f64>,
    pub tool_changes: usize,
    /// Seconds of the tool changes (`post.toolChangeSeconds` each).
    pub tool_change_seconds: f64,
    /// Seconds of the rest: the spindle's start dwells and the retracts to the clearance
    /// height at tool changes and at the program's end.
    pub other_seconds: f64,
    /// The whole program (seconds): the sum of the parts.
    pub seconds: f64,
}

/// One part of a program's cycle time, for people: what it is and how long it takes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct TimeItem {
    pub label: String,
    /// Whole seconds.
    pub seconds: u64,
}

impl CycleTime {
    /// The paths of `paths` by operation, as the cycle time is broken down: consecutive paths
    /// of one name (an operation's, one path per tool) with their tools, `rough with T1, T3`.
    pub fn groups(paths: &[Toolpath]) -> Vec<(String, Vec<usize>)> {
        let mut groups: Vec<(String, Vec<usize>, Vec<u32>)> = Vec::new();
        for (k, p) in paths.iter().enumerate() {
            match groups.last_mut() {
                Some((name, ks, tools)) if *name == p.name => {
                    ks.push(k);
                    if !tools.contains(&p.tool) {
                        tools.push(p.tool);
                    }
                }
                _ => groups.push((p.name.clone(), vec![k], vec![p.tool])),
            }
        }
        groups.into_iter().map(|(name, ks, tools)| (format!("{name} with {}", tools.iter().map(|t| format!("T{t}")).collect::<Vec<_>>().join(", ")), ks)).collect()
    }

    /// The parts of the cycle time in whole seconds that sum to the whole rounded to a second:
    /// `groups` names the paths' parts (each a label and the indices of its paths, in order:
    /// an operation's), then the tool changes and the rest follow. Each part is the rounded
    /// running total less the one before it, so no rounding is lost or counted twice.
    pub fn items(&self, groups: &[(String, Vec<usize>)]) -> Vec<TimeItem> {
        let mut parts: Vec<(String, f64)> = groups.iter().map(|(label, paths)| (label.clone(), paths.iter().filter_map(|&k| self.paths.get(k)).sum())).collect();
        if self.tool_changes > 0 {
            let s = if self.tool_changes == 1 { "" } else { "s" };
            parts.push((format!("{} tool change{s}", self.tool_changes), self.tool_change_seconds));
        }
        if self.other_seconds > 0.0 {
            parts.push(("retracts and spindle starts".into(), self.other_seconds));
        }
        let (mut total, mut shown) = (0.0, 0u64);
        parts
            .into_iter()
            .map(|(label, seconds)| {
                total += seconds;
                let upto = total.max(0.0).round() as u64;
                let item = TimeItem { label, seconds: upto.saturating_sub(shown) };
                shown = upto.max(shown);
                item
            })
            .collect()
    }
}

/// What [`clock`] writes `seconds` as: `h:mm:ss` or `m:ss`.
pub fn clock_format(seconds: f64) -> &'static str {
    if seconds.max(0.0).round() >= 3600.0 {
        "h:mm:ss"
    } else {
        "m:ss"
    }
}

/// `seconds` as h:mm:ss or m:ss.
pub fn clock(seconds: f64) -> String {
    let s = seconds.max(0.0).round() as u64;
    if s >= 3600 {
        format!("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
    } else {
        format!("{}:{:02}", s / 60, s % 60)
    }
}

/// Writes the program. `clearance_z` is the safe height (mm) the program starts and ends at.
pub fn write_gcode(title: &str, paths: &[Toolpath], tools: &[Tool], clearance_z: f64, settings: &PostSettings) -> Result<String, Error> {
    Ok(write_program(title, paths, tools, clearance_z, settings)?.0)
}

/// Writes the program and times it.
pub fn write_program(title: &str, paths: &[Toolpath], tools: &[Tool], clearance_z: f64, settings: &PostSettings) -> Result<(String, CycleTime), Error> {
    write_mapped(title, paths, tools, clearance_z, settings).map(|w| (w.gcode, w.cycle))
}

/// A program as written: its text, its cycle time, and where each move went.
#[derive(Clone, Debug, PartialEq)]
pub struct Written {
    pub gcode: String,
    pub cycle: CycleTime,
    /// The line (0 first) of the program each move of the paths ended on, the paths' moves
    /// one after another (a move written as several lines, an arc split at the quadrants or a
    /// helix as chords, ends on its last; one too short to write, on the line before it).
    pub move_lines: Vec<u32>,
}

/// Writes the program, times it, and maps its moves to its lines ([`Written`]).
pub fn write_mapped(title: &str, paths: &[Toolpath], tools: &[Tool], clearance_z: f64, settings: &PostSettings) -> Result<Written, Error> {
    settings.validate(tools).map_err(Error::Input)?;
    let post = settings.post();
    let mut w = Writer::new(settings, &post);
    w.line(match settings.units {
        Units::Mm => "G21",
        Units::Inch => "G20",
    });
    for l in &post.setup {
        w.line(l);
    }
    if let Some(offset) = &post.work_offset {
        w.line(offset);
    }
    let mut current: Option<&Tool> = None;
    let mut started = false;
    let mut time = CycleTime::default();
    let mut move_lines = Vec::new();
    for path in paths {
        let tool = tools.iter().find(|t| t.number == path.tool);
        w.comment(&path.name);
        if !started || current.map(|t| t.number) != Some(path.tool) {
            if started {
                w.coolant_off();
                w.line(&post.spindle_off);
            }
            w.rapid_z(clearance_z);
            let describe = tool.map(Tool::describe).unwrap_or_default();
            // By hand, the new tool's length is measured on the sensor, else touched off again.
            let measure = if settings.length_sensor == Some(true) { "measure it on the tool length sensor" } else { "set Z zero again with the new tool (touch off)" };
            if !post.tool_change.is_empty() {
                // A machine without a changer stops at M6 for the operator (LinuxCNC's manual
                // tool change, Mach's M6 macro): the comment says what to put in.
                if settings.tool_changer == Some(false) {
                    w.comment(&format!("change to tool {} by hand: {describe}; {measure}", path.tool));
                }
                for l in &post.tool_change {
                    w.line(&definition::fill(l, &[("tool", path.tool.to_string())]));
                }
            } else if started {
                // Without a changer the operator changes the tool by hand, and its length is
                // the new tool's: Z must be measured again before the program goes on.
                w.comment(&format!("change to tool {}: {describe}; then {measure} and resume", path.tool));
                w.line(&post.pause);
            }
            if started {
                time.tool_changes += 1;
            }
            started = true;
            current = tool;
            let rpm = number(path.spindle_rpm, 0);
            w.line(&definition::fill(&post.spindle_on, &[("rpm", rpm)]));
            if post.spindle_dwell > 0.0 {
                if let Some(dwell) = &post.dwell {
                    let values = [("seconds", number(post.spindle_dwell, 3)), ("millis", number(post.spindle_dwell * 1000.0, 0))];
                    w.line(&definition::fill(dwell, &values));
                    w.seconds += post.spindle_dwell;
                }
            }
            w.coolant_on(tool);
        }
        let before = w.seconds;
        w.motion(&Move::Rapid { to: path.start.truncate().extend(clearance_z) });
        w.motion(&Move::Rapid { to: path.start });
        time.starts.push(w.seconds + time.tool_changes as f64 * settings.tool_change_seconds);
        // Drilling cycles by their first move; a run of canned blocks ends with G80.
        let cycles: std::collections::HashMap<usize, &Cycle> = path.cycles.iter().map(|c| (c.first, c)).collect();
        let mut dwell_after = None;
        let mut canned = false;
        let mut k = 0;
        while k < path.moves.len() {
            if let Some(c) = cycles.get(&k) {
                let moves = &path.moves[k..(k + c.count).min(path.moves.len())];
                if w.canned(c, moves) {
                    canned = true;
                    move_lines.extend(std::iter::repeat_n(w.lines.len().saturating_sub(1) as u32, moves.len()));
                    k += moves.len();
                    continue;
                }
                dwell_after = (c.kind == CycleKind::Dwell).then(|| (c.bottom_move(), c.dwell));
            }
            if std::mem::take(&mut canned) {
                w.line("G80");
            }
            w.motion(&path.moves[k]);
            move_lines.push(w.lines.len().saturating_sub(1) as u32);
            if let Some((_, seconds)) = dwell_after.filter(|&(at, _)| at == k) {
                w.dwell(seconds)?;
                dwell_after = None;
            }
            k += 1;
        }
        if canned {
            w.line("G80");
        }
        time.paths.push(w.seconds - before);
    }
    w.coolant_off();
    w.line(&post.spindle_off);
    w.rapid_z(clearance_z);
    for l in &post.footer {
        w.line(l);
    }
    time.tool_change_seconds = time.tool_changes as f64 * settings.tool_change_seconds;
    time.other_seconds = w.seconds - time.paths.iter().sum::<f64>();
    time.seconds = time.paths.iter().sum::<f64>() + time.tool_change_seconds + time.other_seconds;

    // The head, now that the program is timed.
    let mut head = Writer::new(settings, &post);
    let values = [("title", post.comment_text(title)), ("program", format!("{:04}", settings.program_number)), ("version", env!("CARGO_PKG_VERSION").to_owned())];
    for l in &post.header {
        head.line(&definition::fill(l, &values));
    }
    head.comment(title);
    head.comment(&format!("generated by swarf {} for {}", env!("CARGO_PKG_VERSION"), post.name));
    head.comment(&format!("cycle time {} {}, {}:", clock(time.seconds), clock_format(time.seconds), settings.rapids().describe(settings.units.mm(), settings.units.short())));
    for item in time.items(&CycleTime::groups(paths)) {
        head.comment(&format!("  {}: {}", item.label, clock(item.seconds as f64)));
    }
    let mut listed = Vec::new();
    for path in paths {
        if !listed.contains(&path.tool) {
            listed.push(path.tool);
            if let Some(tool) = tools.iter().find(|t| t.number == path.tool) {
                head.comment(&format!("T{} {}", tool.number, tool.describe()));
            }
        }
    }
    let head_lines = head.lines.len() as u32;
    let mut lines = head.lines;
    lines.extend(w.lines);
    Ok(Written { gcode: finish(lines, &post)?, cycle: time, move_lines: move_lines.into_iter().map(|l| l + head_lines).collect() })
}

/// One setup's program, for [`join_setups`].
#[derive(Clone, Debug)]
pub struct SetupProgram<'a> {
    /// The setup's name.
    pub name: &'a str,
    /// How the part is held: "turned over about X", "left side (-X) up".
    pub held: String,
    /// The work offset its zero is set in (`G55`).
    pub work_offset: String,
    /// Its first tool, where the control has no changer and the operator puts it in.
    pub first_tool: Option<String>,
    /// The program as [`write_program`] wrote it.
    pub gcode: &'a str,
    pub seconds: f64,
}

/// The setups' programs as one (`post.oneProgram`): the first one's head, then each setup's
/// program without the tape marks and program number of its head nor the end of program of its
/// foot, an operator stop (the post's pause, `M0`) between them with a message saying how to
/// hold the part, where to set the zero and which tool to put in; one end of program. Each
/// setup's own lines select its units, modes and work offset again, so nothing carries over
/// but the machine's state the stop leaves (the spindle and coolant off, the tool up). The
/// lines are numbered anew as the post numbers them.
pub fn join_setups(settings: &PostSettings, programs: &[SetupProgram]) -> Result<String, Error> {
    let post = settings.post();
    if post.pause.trim().is_empty() {
        return Err(Error::Input(format!("the post {} has no pause (M0) to stop between setups: write a program per setup", post.name)));
    }
    let (head, foot) = (post.header.len(), post.footer.len());
    let n = programs.len();
    let total: f64 = programs.iter().map(|p| p.seconds).sum();
    let mut lines: Vec<String> = Vec::new();
    for (k, p) in programs.iter().enumerate() {
        let own: Vec<String> = p.gcode.lines().map(|l| without_number(l).to_owned()).collect();
        let end = if k + 1 < n { own.len().saturating_sub(foot) } else { own.len() };
        let body = head.min(end);
        if k == 0 {
            lines.extend(own[..body].iter().cloned());
            lines.extend(post.comment(&format!("{n} setups in one program, cycle time {} {} without the stops between them", clock(total), clock_format(total))));
        } else {
            let tool = p.first_tool.as_ref().map(|t| format!("; put in {t}")).unwrap_or_default();
            let say = format!("setup {} of {n}, {}: {}; clamp it, set the zero of {}{tool}; then resume", k + 1, p.name, p.held, p.work_offset);
            // Said in lines the control keeps whole (GRBL reads 80 characters).
            let width = post.max_line_length.map_or(76, |m| m.saturating_sub(12)).clamp(20, 76);
            lines.extend(wrap(&post.comment_text(&say), width).iter().filter_map(|l| post.comment(l)));
            lines.push(post.pause.clone());
        }
        lines.extend(own[body..end].iter().cloned());
    }
    finish(lines, &post)
}

/// `line` without its line number (`N120 G1 X5` → `G1 X5`).
pub fn without_number(line: &str) -> &str {
    let line = line.trim();
    match line.split_once(' ') {
        Some((n, rest)) if n.len() > 1 && n.starts_with('N') && n[1..].chars().all(|c| c.is_ascii_digit()) => rest.trim(),
        _ => line,
    }
}

/// Numbers the lines and holds them to the post's length. Numbers never come back (see
/// [`definition::LineNumbers`]): the post's step where the program fits under its largest
/// number, else by ones, and past that no more numbers.
fn finish(lines: Vec<String>, post: &Post) -> Result<String, Error> {
    let numbered = |line: &String| line != "%" && !line.starts_with('O');
    let mut n = post.line_numbers.map(|l| {
        let count = lines.iter().filter(|l| numbered(l)).count() as u64;
        let fits = |step: u32| (l.start as u64) + (count.saturating_sub(1)) * step as u64 <= l.max as u64;
        (l.start as u64, if fits(l.step) { l.step } else { 1 }, l.max as u64)
    });
    let mut out = String::with_capacity(lines.iter().map(|l| l.len() + 1).sum::<usize>() + if n.is_some() { 8 * lines.len() } else { 0 });
    for line in lines {
        let mut line = match n.as_mut() {
            // The tape marks and the program number stand unnumbered.
            Some((k, step, max)) if numbered(&line) && *k <= *max => {
                let numbered = format!("N{k} {line}");
                *k += *step as u64;
                numbered
            }
            _ => line,
        };
        if let Some(max) = post.max_line_length {
            if line.chars().count() > max {
                line = fit(&line, max).ok_or_else(|| Error::Input(format!("the line {line:?} is longer than the post's maxLineLength ({max})")))?;
            }
        }
        out.push_str(&line);
        out.push('\n');
    }
    Ok(out)
}

/// A line shortened to `max` characters: its comment cut, then its spaces dropped.
fn fit(line: &str, max: usize) -> Option<String> {
    let (code, note) = match line.find(['(', ';']) {
        Some(k) => (&line[..k], &line[k..]),
        None => (line, ""),
    };
    let code = if code.trim_end().chars().count() > max { code.replace(' ', "") } else { code.to_owned() };
    let room = max.checked_sub(code.chars().count())?;
    if note.is_empty() {
        return Some(code);
    }
    // Cut between words where a space leaves more than half the room, else within the word.
    let cut = |text: &str, room: usize| -> String {
        let head: String = text.chars().take(room).collect();
        if head.chars().count() == text.chars().count() {
            return head;
        }
        match head.rfind(' ') {
            Some(k) if k > room / 2 => head[..k].trim_end().to_owned(),
            _ => head,
        }
    };
    let note = if note.starts_with('(') {
        // Keep the parenthesis that closes it.
        if room < 2 {
            String::new()
        } else {
            format!("({})", cut(&note[1..note.len() - 1], room - 2))
        }
    } else {
        cut(note, room)
    };
    Some(format!("{code}{note}").trim_end().to_owned())
}

pub(crate) use definition::comment;
pub use definition::{ascii, wrap};

struct Writer<'a> {
    post: &'a Post,
    lines: Vec<String>,
    scale: f64,
    decimals: usize,
    rapids: Rapids,
    position: [Option<f64>; 3],
    /// The words last written for X, Y and Z.
    written: [Option<Word>; 3],
    feed: Option<f64>,
    mode: Option<&'static str>,
    coolant: bool,
    /// Motion and dwell time so far.
    seconds: f64,
}

impl<'a> Writer<'a> {
    fn new(settings: &PostSettings, post: &'a Post) -> Writer<'a> {
        let scale = 1.0 / settings.units.mm();
        let decimals = settings.decimals_for(post);
        Writer { post, lines: Vec::new(), scale, decimals, rapids: settings.rapids(), position: [None; 3], written: [None, None, None], feed: None, mode: None, coolant: false, seconds: 0.0 }
    }

    /// A line that is not a motion: the next motion states its G word again.
    fn line(&mut self, text: &str) {
        if !text.trim().is_empty() {
            self.lines.push(text.to_owned());
        }
        self.mode = None;
    }

    fn comment(&mut self, text: &str) {
        self.lines.extend(self.post.comment_lines(text));
    }

    fn coolant_on(&mut self, tool: Option<&Tool>) {
        let word = match tool.map(|t| t.coolant) {
            Some(Coolant::Flood) => self.post.coolant_flood.clone(),
            Some(Coolant::Mist) => self.post.coolant_mist.clone(),
            _ => None,
        };
        if let Some(word) = word {
            self.line(&word);
            self.coolant = true;
        }
    }

    fn coolant_off(&mut self) {
        if self.coolant {
            if let Some(word) = self.post.coolant_off.clone() {
                self.line(&word);
            }
            self.coolant = false;
        }
    }

    fn length(&self, mm: f64) -> Word {
        Word::number(mm * self.scale, self.decimals)
    }

    /// The length rounded up to the program's resolution, never down (a value a millionth of
    /// a unit above a digit, as a float's error leaves −10.2 in millimetres, takes that digit).
    fn length_up(&self, mm: f64) -> Word {
        let unit = 10f64.powi(-(self.decimals as i32));
        let v = mm * self.scale;
        let up = (v / unit - 1e-6).ceil() * unit;
        // Rounding in the division may land a hair short: one more step (a millionth of a unit
        // short is the digit itself).
        Word::number(if up < v - 2e-6 * unit { up + unit } else { up }, self.decimals)
    }

    /// A dwell of `seconds` in the post's words (G4 P…).
    fn dwell(&mut self, seconds: f64) -> Result<(), Error> {
        let dwell = self.post.dwell.clone().ok_or_else(|| Error::Input(format!("the post '{}' has no dwell word (dwell), which a drilling cycle's dwell needs", self.post.name)))?;
        let values = [("seconds", number(seconds, 3)), ("millis", number(seconds * 1000.0, 0))];
        self.line(&definition::fill(&dwell, &values));
        self.seconds += seconds;
        Ok(())
    }

    /// A value as the program writes it, read back in millimetres.
    fn as_written(&self, mm: f64, up: bool) -> f64 {
        let text = if up { self.length_up(mm) } else { self.length(mm) };
        text.as_str().parse::<f64>().unwrap_or(mm * self.scale) / self.scale
    }

    /// The drilling cycle `c`, whose moves are `moves`, written as one canned block where the
    /// post has them and the control would make the same moves of the values as written (its
    /// pecks counted on the rounded R, Z and Q; the tool standing at the cycle's starting
    /// height); false where it is not, and the moves are to be written as they are.
    fn canned(&mut self, c: &Cycle, moves: &[Move]) -> bool {
        if !self.post.canned_cycles || moves.len() != c.count {
            return false;
        }
        let written = Cycle {
            at: DVec2::new(self.as_written(c.at.x, false), self.as_written(c.at.y, false)),
            initial: self.as_written(c.initial, false),
            r: self.as_written(c.r, false),
            bottom: self.as_written(c.bottom, true),
            peck: self.as_written(c.peck, false),
            ..*c
        };
        let unit = 10f64.powi(-(self.decimals as i32)) / self.scale;
        let standing = self.position[2].is_some_and(|z| self.length(z) == self.length(c.initial));
        // (The cheap checks first: a peck of 0 would never reach the bottom.)
        if !standing || written.r < written.bottom || written.initial < written.r || written.peck <= 0.0 {
            return false;
        }
        let Some(from) = self.at() else { return false };
        let expanded = written.moves();
        if !same_moves(&expanded, moves, 1.01 * unit) {
            return false;
        }
        let mut at = from;
        for m in &expanded {
            self.seconds += if m.is_rapid() { self.rapids.seconds(at, m.to()) } else { m.length(at) / c.feed * 60.0 };
            at = m.to();
        }
        let mut words = format!("{} {} X{} Y{} Z{} R{}", if c.to_initial { "G98" } else { "G99" }, c.kind.code(), self.length(c.at.x), self.length(c.at.y), self.length_up(c.bottom), self.length(c.r));
        if matches!(c.kind, CycleKind::Peck | CycleKind::ChipBreak) {
            let _ = write!(words, " Q{}", self.length(c.peck));
        }
        if c.kind == CycleKind::Dwell {
            // The dwell in the unit the post's own dwell word uses (Fanuc's P counts ms).
            let millis = self.post.dwell.as_deref().is_some_and(|d| d.contains("{millis}"));
            let _ = write!(words, " P{}", if millis { number(c.dwell * 1000.0, 0) } else { number(c.dwell, 3) });
            self.seconds += c.dwell;
        }
        let _ = write!(words, " F{}", number(c.feed * self.scale, self.post.feed_decimals));
        self.line(&words);
        self.feed = Some(c.feed);
        let end = written.at.extend(written.clear());
        self.position = [Some(end.x), Some(end.y), Some(end.z)];
        self.written = [Some(self.length(end.x)), Some(self.length(end.y)), Some(self.length(end.z))];
        true
    }

    fn rapid_z(&mut self, z: f64) {
        if let Some(from) = self.position[2] {
            let at = DVec3::new(self.position[0].unwrap_or(0.0), self.position[1].unwrap_or(0.0), from);
            self.seconds += self.rapids.seconds(at, DVec3::new(at.x, at.y, z));
        }
        let text = format!("G0 Z{}", self.length(z));
        self.line(&text);
        self.mode = Some("G0");
        self.position[2] = Some(z);
        self.written[2] = Some(self.length(z));
    }

    fn at(&self) -> Option<DVec3> {
        match self.position {
            [Some(x), Some(y), Some(z)] => Some(DVec3::new(x, y, z)),
            _ => None,
        }
    }

    /// Writes a move as the post wants it: arcs as they are, split at the quadrants, or as
    /// chords.
    fn motion(&mut self, m: &Move) {
        let Move::Arc { to, center, clockwise, feed } = *m else { return self.emit(m) };
        let Some(from) = self.at() else { return self.emit(m) };
        let radius = (from.truncate() - center).length();
        let sweep = arc_sweep(from, to, center, clockwise);
        let a0 = (from.truncate() - center).to_angle();
        let point = |angle: f64| {
            let t = (angle - a0) / sweep;
            (center + DVec2::from_angle(angle) * radius).extend(from.z + (to.z - from.z) * t)
        };
        let helix = to.z != from.z;
        if self.post.arcs == ArcFormat::Off || (helix && !self.post.helix) || radius > self.post.max_arc_radius {
            let step = crate::geom::segment::chord_step(radius, ARC_CHORD_ERROR).unwrap_or(std::f64::consts::PI);
            let n = ((sweep.abs() / step).ceil() as usize).max(1);
            for k in 1..n {
                self.emit(&Move::Line { to: point(a0 + sweep * k as f64 / n as f64), feed });
            }
            return self.emit(&Move::Line { to, feed });
        }
        if self.post.arc_quadrants || self.post.arcs == ArcFormat::R {
            let quarter = std::f64::consts::FRAC_PI_2;
            let end = a0 + sweep;
            // The quadrant boundaries strictly inside the sweep (a hair's margin at the ends).
            let mut k = if sweep > 0.0 { (a0 / quarter).floor() + 1.0 } else { (a0 / quarter).ceil() - 1.0 };
            let margin = 1e-7;
            while (sweep > 0.0 && k * quarter < end - margin) || (sweep < 0.0 && k * quarter > end + margin) {
                let angle = k * quarter;
                if (angle - a0).abs() > margin {
                    self.emit(&Move::Arc { to: point(angle), center, clockwise, feed });
                }
                k += sweep.signum();
            }
        }
        self.emit(m)
    }

    fn emit(&mut self, m: &Move) {
        let to = m.to();
        if let Some(from) = self.at() {
            self.seconds += match *m {
                Move::Rapid { to } => self.rapids.seconds(from, to),
                Move::Line { feed, .. } | Move::Arc { feed, .. } => m.length(from) / feed * 60.0,
            };
        }
        let (code, feed) = match *m {
            Move::Rapid { .. } => ("G0", None),
            Move::Line { feed, .. } => ("G1", Some(feed)),
            Move::Arc { clockwise: true, feed, .. } => ("G2", Some(feed)),
            Move::Arc { clockwise: false, feed, .. } => ("G3", Some(feed)),
        };
        let texts = [self.length(to.x), self.length(to.y), if feed.is_some() { self.length_up(to.z) } else { self.length(to.z) }];
        // An arc whose ends round to one point would read as a full circle: write it as a line.
        // (What was written for X and Y is the position's own rounding.)
        let rounds_shut = |axis: usize| self.position[axis].is_some() && self.written[axis].as_ref() == Some(&texts[axis]);
        let short_arc = matches!(m, Move::Arc { .. }) && rounds_shut(0) && rounds_shut(1) && !(self.position[0] == Some(to.x) && self.position[1] == Some(to.y));
        let code = if short_arc { "G1" } else { code };
        let is_arc = matches!(m, Move::Arc { .. }) && !short_arc;
        let modal = self.post.modal;
        let mut words: Vec<u8> = Vec::with_capacity(48);
        let mut moved = false;
        if self.mode != Some(code) || is_arc || !modal {
            words.extend_from_slice(code.as_bytes());
        }
        let word = |words: &mut Vec<u8>, name: &str, text: &[u8]| {
            if !words.is_empty() {
                words.push(b' ');
            }
            words.extend_from_slice(name.as_bytes());
            words.extend_from_slice(text);
        };
        // A feed's Z is rounded up, an arc's too: the path was made for the resolution (see
        // `PostSettings::resolution`), and rounding Z down would lower it (and a level arc
        // between two lines would come out a hair-thin helix).
        for (axis, (name, text)) in ["X", "Y", "Z"].into_iter().zip(texts).enumerate() {
            let changed = self.written[axis].as_ref() != Some(&text);
            moved |= changed;
            if changed || (is_arc && axis < 2) || !modal {
                word(&mut words, name, text.bytes());
                self.written[axis] = Some(text);
            }
        }
        if !moved && (!is_arc || self.position[0] != Some(to.x) || self.position[1] != Some(to.y)) {
            return; // no motion at the program's resolution
        }
        if let (Move::Arc { center, .. }, true) = (*m, is_arc) {
            let from = DVec3::new(self.position[0].unwrap_or(to.x), self.position[1].unwrap_or(to.y), 0.0);
            if self.post.arcs == ArcFormat::R {
                word(&mut words, "R", self.length((from.truncate() - center).length()).bytes());
            } else {
                word(&mut words, "I", self.length(center.x - from.x).bytes());
                word(&mut words, "J", self.length(center.y - from.y).bytes());
            }
        }
        if let Some(feed) = feed {
            if self.feed != Some(feed) || !modal {
                word(&mut words, "F", Word::number(feed * self.scale, self.post.feed_decimals).bytes());
                self.feed = Some(feed);
            }
        }
        if !words.is_empty() {
            self.lines.push(String::from_utf8(words).expect("a motion's words are ASCII"));
        }
        self.mode = Some(code);
        self.position = [Some(to.x), Some(to.y), Some(to.z)];
    }
}

/// `value` with at most `decimals` digits, rounded as `format!("{value:.decimals$}")` rounds
/// it (the exact binary value, halves to even), without trailing zeros or a negative zero.
///
/// Programs hold a number for every word, so the common case skips the formatter: below 2⁵²
/// units of the last digit every half unit is a float, and the product `value × 10^decimals`
/// is rounded to the nearest float, so it lands on the same side of each half as the exact
/// product does and rounding it to an integer gives the formatter's digits. A product that
/// is exactly a half (the formatter rounds those to even), or larger, is formatted.
pub(crate) fn number(value: f64, decimals: usize) -> String {
    Word::number(value, decimals).as_str().to_owned()
}

/// A number as the program writes it ([`number`]), held without a heap allocation when short
/// (every coordinate and feed a program writes; a program of millions of moves writes millions
/// of them).
#[derive(Clone, Debug)]
enum Word {
    Short { len: u8, bytes: [u8; 30] },
    Long(String),
}

impl PartialEq for Word {
    fn eq(&self, other: &Word) -> bool {
        self.bytes() == other.bytes()
    }
}

impl Word {
    /// `value` rounded to `decimals`, trailing zeros dropped (as `format!("{value:.decimals$}")`
    /// trimmed writes it, with no "-0").
    fn number(value: f64, decimals: usize) -> Word {
        const POWERS: [u64; 7] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000];
        const HALVES_EXACT: f64 = (1u64 << 52) as f64;
        if let Some(&unit) = POWERS.get(decimals) {
            let y = value * unit as f64;
            if y.abs() < HALVES_EXACT && y.fract().abs() != 0.5 {
                let units = y.round() as i64;
                let (whole, mut part) = (units.unsigned_abs() / unit, units.unsigned_abs() % unit);
                let mut bytes = [0u8; 30];
                let mut len = 0;
                if units < 0 {
                    bytes[0] = b'-';
                    len = 1;
                }
                len += digits(whole, 1, &mut bytes[len..]);
                if part != 0 {
                    let mut places = decimals;
                    while part % 10 == 0 {
                        part /= 10;
                        places -= 1;
                    }
                    bytes[len] = b'.';
                    len += 1 + digits(part, places, &mut bytes[len + 1..]);
                }
                return Word::Short { len: len as u8, bytes };
            }
        }
        let mut s = format!("{value:.decimals$}");
        if s.contains('.') {
            s = s.trim_end_matches('0').trim_end_matches('.').to_owned();
        }
        if s == "-0" {
            s = "0".to_owned();
        }
        Word::Long(s)
    }

    fn bytes(&self) -> &[u8] {
        match self {
            Word::Short { len, bytes } => &bytes[..*len as usize],
            Word::Long(s) => s.as_bytes(),
        }
    }

    fn as_str(&self) -> &str {
        match self {
            Word::Short { len, bytes } => std::str::from_utf8(&bytes[..*len as usize]).expect("digits are ASCII"),
            Word::Long(s) => s,
        }
    }
}

impl std::fmt::Display for Word {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Writes `value`'s decimal digits, at least `width` of them (zeros in front), at the start of
/// `out`; returns how many.
fn digits(mut value: u64, width: usize, out: &mut [u8]) -> usize {
    let mut held = [0u8; 20];
    let mut n = 0;
    while value > 0 || n < width {
        held[n] = b'0' + (value % 10) as u8;
        value /= 10;
        n += 1;
    }
    for (k, d) in held[..n].iter().rev().enumerate() {
        out[k] = *d;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::number;

    /// What [`number`] stands for: the standard formatting, trimmed.
    fn formatted(value: f64, decimals: usize) -> String {
        let mut s = format!("{value:.decimals$}");
        if s.contains('.') {
            s = s.trim_end_matches('0').trim_end_matches('.').to_owned();
        }
        if s == "-0" {
            s = "0".to_owned();
        }
        s
    }

    #[test]
    fn numbers_are_written_as_the_standard_formatting_writes_them() {
        // Halves and near halves (written exactly, and a float's error off them), round
        // values and their neighbours, tiny and huge values, signs, every count of decimals.
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            0.0005,
            -0.0005,
            0.0015,
            1e-12,
            -1e-12,
            1e9,
            1e12,
            -3.7e15,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            999.9995,
            999.9994999,
            -10.2,
            10.2 - 1e-15,
            0.1 + 0.2,
        ];
        let mut rng = crate::offset::check::Rng::new(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200_000 {
            // Values from a millionth to thousands, some at halves of a last digit.
            let x = rng.next_u64();
            let v = (x % 4_000_000_000) as f64 / 1000.0 - 2_000_000.0;
            let scale = [1.0, 0.001, 0.0001, 1e-6, 0.37][(x >> 40) as usize % 5];
            values.push(v * scale);
            values.push((v * scale * 2000.0).round() / 2000.0 + 0.00025);
            values.push(f64::from_bits(x >> 2));
            // Large values whose last digits fall near and beyond 2^52 units.
            let large = (x % 10_000_000_000_000) as f64 * [1e-6, 1e-5, 1e-4, 1e-3, 0.0125][(x >> 50) as usize % 5];
            values.push(large);
            values.push(large + 0.0000005);
        }
        for &v in &values {
            for decimals in 0..9 {
                assert_eq!(number(v, decimals), formatted(v, decimals), "{v:e} to {decimals} decimals");
            }
        }
    }
}
