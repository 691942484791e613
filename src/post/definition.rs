//! A post-processor as data: what one controller accepts, as a JSON object the writer
//! ([`super::write_gcode`]) follows. The built-in posts are such files (`src/post/builtin/`),
//! and users load their own the same way; a post with an unknown field or an impossible
//! setting is refused with the field's name.
//!
//! Templates are G-code lines with placeholders in braces: `{tool}`, `{rpm}`, `{seconds}`,
//! `{millis}`, `{title}`, `{program}`, `{version}`, each allowed where it has a value.

use serde::{Deserialize, Serialize};

/// How comments are written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum CommentStyle {
    /// `(text)`.
    #[default]
    Parens,
    /// `; text`.
    Semicolon,
    /// No comments at all.
    None,
}

/// The characters a control reads in comments.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum CommentCharacters {
    /// Printable ASCII only: anything else is written as its nearest ASCII (`φ6` → `D6`,
    /// `×` → `x`, `é` → `e`), or `?`. What most controls (Fanuc, GRBL, Mach) read.
    #[default]
    Ascii,
    /// Any character (UTF-8), as LinuxCNC reads.
    Any,
}

/// How arcs are written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ArcFormat {
    /// G2/G3 with the centre as I and J, relative to the start (the program sets G91.1 where
    /// the control could be in absolute mode).
    #[default]
    Ij,
    /// G2/G3 with the radius R; arcs are split at the quadrants so that none needs a negative R
    /// or is a full circle.
    R,
    /// No arcs: chords within [`ARC_CHORD_ERROR`].
    Off,
}

/// The largest distance (mm) between an arc and the chords written instead of it, for a post
/// without arcs (or without helices).
pub const ARC_CHORD_ERROR: f64 = 0.0008;

/// Line numbers (N words). A number never comes back: a program with more lines than `start`
/// and `step` reach before `max` is numbered by ones, and one with more lines than that is
/// numbered up to `max` and goes on unnumbered (a control reads a line without an N word; one
/// that reads a number twice may jump to the wrong line).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
pub struct LineNumbers {
    pub start: u32,
    pub step: u32,
    /// The largest number the control reads.
    #[serde(default = "largest_line_number")]
    pub max: u32,
}

fn largest_line_number() -> u32 {
    99999
}

/// A post-processor. A field left out takes the generic post's value.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, deny_unknown_fields, rename_all = "camelCase")]
pub struct Post {
    /// Shown in the page and written in the program's head.
    pub name: String,
    /// The file extension its controllers expect (`ngc`, `tap`, `nc`).
    pub extension: String,
    /// Lines before everything else (`%`, a program number `O{program} ({title})`).
    pub header: Vec<String>,
    /// Modal setup lines, written after the units word (G20/G21).
    pub setup: Vec<String>,
    /// The work offset to select (`G54` … `G59`, and those of `workOffsets`), or none.
    pub work_offset: Option<String>,
    /// The work offsets the control has beyond `G54` to `G59`. Default value: none.
    pub work_offsets: WorkOffsets,
    /// Lines that change the tool (`T{tool} M6`, `G43 H{tool}`). Empty: the control has no tool
    /// changer, and the program stops the spindle, names the tool in a comment and pauses.
    pub tool_change: Vec<String>,
    /// The pause for a manual tool change (`M0`).
    pub pause: String,
    /// Starts the spindle clockwise (`S{rpm} M3`).
    pub spindle_on: String,
    pub spindle_off: String,
    /// Coolant words (`M8`, `M7`, `M9`); a tool asking for one the post lacks is refused.
    pub coolant_flood: Option<String>,
    pub coolant_mist: Option<String>,
    pub coolant_off: Option<String>,
    /// A dwell (`G4 P{seconds}`; Fanuc `G4 P{millis}`).
    pub dwell: Option<String>,
    /// Seconds to wait after starting the spindle (0: none). Needs `dwell`.
    pub spindle_dwell: f64,
    pub comments: CommentStyle,
    /// The characters its comments may hold; others are transliterated. Default value: ascii.
    pub comment_characters: CommentCharacters,
    pub line_numbers: Option<LineNumbers>,
    /// Digits after the point for lengths in millimetres and in inches, and for feeds.
    pub decimals_mm: usize,
    pub decimals_inch: usize,
    pub feed_decimals: usize,
    pub arcs: ArcFormat,
    /// Split arcs where they cross a quadrant (0°, 90°, 180°, 270°), for controls that want
    /// arcs of at most 90°.
    pub arc_quadrants: bool,
    /// Arcs may move Z (helices); without, a helix is written as chords.
    pub helix: bool,
    /// The largest radius written as an arc (mm); a larger one (a curve bowing a hair over its
    /// length) is written as chords within [`ARC_CHORD_ERROR`]. GRBL computes arcs in
    /// float32, which holds a centre 2.7 km off to a quarter of a millimetre: its posts set 2 m.
    /// Default value: 100,000 (100 m, for controls computing in double).
    pub max_arc_radius: f64,
    /// Leave out a motion word or coordinate that has not changed.
    pub modal: bool,
    /// The control runs the drilling cycles G81, G82, G83 and G73 (with R, Q, P, G98/G99 and
    /// G80): a drilling operation's holes are written as those; without (GRBL 1.1), as the
    /// moves they make.
    pub canned_cycles: bool,
    /// The longest line the control reads (characters), or none. Comments are shortened to
    /// fit; a motion that cannot fit is an error.
    pub max_line_length: Option<usize>,
    /// Lines after the program's last retract and spindle stop (`M2`, `M30`, `%`).
    pub footer: Vec<String>,
}

impl Default for Post {
    fn default() -> Self {
        Post {
            name: "custom".into(),
            extension: "nc".into(),
            header: Vec::new(),
            setup: vec!["G90 G94 G17".into()],
            work_offset: None,
            work_offsets: WorkOffsets::default(),
            tool_change: vec!["T{tool} M6".into()],
            pause: "M0".into(),
            spindle_on: "S{rpm} M3".into(),
            spindle_off: "M5".into(),
            coolant_flood: Some("M8".into()),
            coolant_mist: Some("M7".into()),
            coolant_off: Some("M9".into()),
            dwell: Some("G4 P{seconds}".into()),
            spindle_dwell: 0.0,
            comments: CommentStyle::Parens,
            comment_characters: CommentCharacters::Ascii,
            line_numbers: None,
            decimals_mm: 3,
            decimals_inch: 4,
            feed_decimals: 1,
            arcs: ArcFormat::Ij,
            arc_quadrants: false,
            helix: true,
            max_arc_radius: 100_000.0,
            modal: true,
            canned_cycles: false,
            max_line_length: None,
            footer: vec!["M30".into()],
        }
    }
}

/// The placeholders each template may use.
const PROGRAM_WORDS: &[&str] = &["title", "program", "version"];
const TOOL_WORDS: &[&str] = &["tool"];
const SPINDLE_WORDS: &[&str] = &["rpm"];
const DWELL_WORDS: &[&str] = &["seconds", "millis"];

/// The shortest line limit a post may set: a helix with every word at full width.
pub const MIN_LINE_LENGTH: usize = 48;

impl Post {
    /// Reads a post from JSON; errors name the field.
    pub fn from_json(text: &str) -> Result<Post, String> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
        let post: Post = crate::error::read_value(&value).map_err(|e| {
            let path = e.path().to_string();
            if path == "." {
                e.inner().to_string()
            } else {
                format!("{path}: {}", e.inner())
            }
        })?;
        post.validate()?;
        Ok(post)
    }

    /// Checks what serde cannot: placeholders, limits, words that need other words. Errors
    /// name the field.
    pub fn validate(&self) -> Result<(), String> {
        if self.extension.is_empty() || self.extension.len() > 8 || !self.extension.chars().all(|c| c.is_ascii_alphanumeric()) {
            return Err(format!("extension must be 1 to 8 letters or digits (got {:?})", self.extension));
        }
        let lists: [(&str, &[String], &[&str]); 5] = [
            ("header", &self.header, PROGRAM_WORDS),
            ("setup", &self.setup, &[]),
            ("toolChange", &self.tool_change, TOOL_WORDS),
            ("footer", &self.footer, &[]),
            ("spindleOn", std::slice::from_ref(&self.spindle_on), SPINDLE_WORDS),
        ];
        for (field, lines, allowed) in lists {
            for (k, line) in lines.iter().enumerate() {
                check_template(line, allowed).map_err(|e| format!("{field}[{k}]: {e}"))?;
            }
        }
        for (field, line, allowed) in [
            ("workOffset", &self.work_offset, &[][..]),
            ("coolantFlood", &self.coolant_flood, &[]),
            ("coolantMist", &self.coolant_mist, &[]),
            ("coolantOff", &self.coolant_off, &[]),
            ("dwell", &self.dwell, DWELL_WORDS),
        ] {
            if let Some(line) = line {
                check_template(line, allowed).map_err(|e| format!("{field}: {e}"))?;
            }
        }
        for (field, line) in [("spindleOff", &self.spindle_off), ("pause", &self.pause)] {
            check_template(line, &[]).map_err(|e| format!("{field}: {e}"))?;
        }
        if let Some(w) = &self.work_offset {
            if !self.has_work_offset(w) {
                return Err(format!("workOffset must be {} (got {w:?})", self.work_offsets_words()));
            }
        }
        if self.tool_change.is_empty() && self.pause.trim().is_empty() {
            return Err("pause must be set when toolChange is empty (a manual tool change stops the program)".into());
        }
        if self.spindle_on.trim().is_empty() || self.spindle_off.trim().is_empty() {
            return Err("spindleOn and spindleOff must be set".into());
        }
        if !(self.spindle_dwell >= 0.0 && self.spindle_dwell <= 600.0) {
            return Err(format!("spindleDwell must be 0 to 600 seconds (got {})", self.spindle_dwell));
        }
        if self.spindle_dwell > 0.0 && self.dwell.is_none() {
            return Err("spindleDwell needs a dwell word (dwell)".into());
        }
        if !(self.max_arc_radius >= 1.0 && self.max_arc_radius <= crate::limits::MAX_SIZE * 100.0) {
            return Err(format!("maxArcRadius must be 1 to {} mm (got {})", crate::limits::MAX_SIZE * 100.0, crate::limits::shown(self.max_arc_radius)));
        }
        if !(1..=6).contains(&self.decimals_mm) {
            return Err(format!("decimalsMm must be 1 to 6 (got {})", self.decimals_mm));
        }
        if !(2..=6).contains(&self.decimals_inch) {
            return Err(format!("decimalsInch must be 2 to 6 (got {})", self.decimals_inch));
        }
        if self.feed_decimals > 3 {
            return Err(format!("feedDecimals must be 0 to 3 (got {})", self.feed_decimals));
        }
        if let Some(n) = self.line_numbers {
            if n.step == 0 {
                return Err("lineNumbers.step must be at least 1".into());
            }
            if n.start > n.max || n.max - n.start < n.step {
                return Err(format!("lineNumbers.max ({}) must leave room for more than one number from start ({}) by step ({})", n.max, n.start, n.step));
            }
        }
        if let Some(max) = self.max_line_length {
            if max < MIN_LINE_LENGTH {
                return Err(format!("maxLineLength must be at least {MIN_LINE_LENGTH} characters, the width of a helical move (got {max})"));
            }
        }
        Ok(())
    }

    /// The comment lines for `text`, in the post's style: one line where it fits the control's
    /// line (`maxLineLength`, less a line number), else broken between words into lines that
    /// do; none for a post without comments.
    pub fn comment_lines(&self, text: &str) -> Vec<String> {
        let text = self.comment_text(text);
        let Some(line) = self.styled(&text) else { return Vec::new() };
        let Some(max) = self.max_line_length else { return vec![line] };
        let number = self.line_numbers.map_or(0, |n| format!("N{} ", n.max).len());
        let width = max.saturating_sub(number);
        if line.chars().count() <= width {
            return vec![line];
        }
        let marks = line.chars().count() - text.chars().count();
        wrap(&text, width.saturating_sub(marks)).iter().filter_map(|l| self.styled(l)).collect()
    }

    /// Whether the program is marked by `%` at its start or end (Fanuc's tape marks): a `%`
    /// elsewhere ends it, so its comments may not hold one.
    pub fn tape_marked(&self) -> bool {
        self.header.iter().chain(&self.footer).any(|l| l.trim() == "%")
    }

    /// The comment line for `text`, in the post's style (none for a post without comments).
    pub fn comment(&self, text: &str) -> Option<String> {
        self.styled(&self.comment_text(text))
    }

    /// `text`, already as its comments may hold it ([`Post::comment_text`]), in the post's
    /// comment style.
    fn styled(&self, text: &str) -> Option<String> {
        match self.comments {
            CommentStyle::Parens => Some(format!("({text})")),
            CommentStyle::Semicolon => Some(format!("; {text}")),
            CommentStyle::None => None,
        }
    }
}

/// `text` in printable ASCII: each other character as its nearest ASCII, or `?`.
pub fn ascii(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_ascii() && !c.is_ascii_control() {
            out.push(c);
            continue;
        }
        out.push_str(match c {
            'φ' | 'Φ' | 'ø' | 'Ø' | '⌀' | 'ϕ' => "D",
            '×' => "x",
            '°' => " deg",
            '²' => "2",
            '³' => "3",
            'µ' | 'μ' => "u",
            'δ' => "delta",
            'γ' => "gamma",
            '≤' => "<=",
            '≥' => ">=",
            '±' => "+/-",
            '–' | '—' | '−' => "-",
            '‘' | '’' => "'",
            '“' | '”' | '«' | '»' => "\"",
            '…' => "...",
            '·' | '•' => ".",
            '→' => "->",
            'ß' => "ss",
            'æ' => "ae",
            'Æ' => "AE",
            'œ' => "oe",
            'Œ' => "OE",
            'à' | 'á' | 'â' | 'ã' | 'ä' | 'å' | 'ā' => "a",
            'À' | 'Á' | 'Â' | 'Ã' | 'Ä' | 'Å' | 'Ā' => "A",
            'ç' | 'č' | 'ć' => "c",
            'Ç' | 'Č' | 'Ć' => "C",
            'è' | 'é' | 'ê' | 'ë' | 'ē' | 'ě' => "e",
            'È' | 'É' | 'Ê' | 'Ë' | 'Ē' | 'Ě' => "E",
            'ì' | 'í' | 'î' | 'ï' => "i",
            'Ì' | 'Í' | 'Î' | 'Ï' => "I",
            'ñ' | 'ń' => "n",
            'Ñ' | 'Ń' => "N",
            'ò' | 'ó' | 'ô' | 'õ' | 'ö' | 'ő' => "o",
            'Ò' | 'Ó' | 'Ô' | 'Õ' | 'Ö' | 'Ő' => "O",
            'ù' | 'ú' | 'û' | 'ü' | 'ů' | 'ű' => "u",
            'Ù' | 'Ú' | 'Û' | 'Ü' | 'Ů' | 'Ű' => "U",
            'ý' | 'ÿ' => "y",
            'Ý' => "Y",
            'š' | 'ś' => "s",
            'Š' | 'Ś' => "S",
            'ž' | 'ź' | 'ż' => "z",
            'Ž' | 'Ź' | 'Ż' => "Z",
            'ł' => "l",
            'Ł' => "L",
            'ř' => "r",
            'Ř' => "R",
            c if c.is_whitespace() => " ",
            _ => "?",
        });
    }
    out
}

impl Post {
    /// `text` as its comments may hold it: no parentheses (they would end the comment early),
    /// no `%` in a program marked by it (it would end the program), and in ASCII where the post
    /// says so.
    pub fn comment_text(&self, text: &str) -> String {
        let mut text = comment(text);
        if self.tape_marked() {
            text = text.replace('%', " percent");
        }
        match self.comment_characters {
            CommentCharacters::Ascii => ascii(&text),
            CommentCharacters::Any => text,
        }
    }
}

/// A template's placeholders are among `allowed`, its braces closed, and it is one line.
fn check_template(line: &str, allowed: &[&str]) -> Result<(), String> {
    if line.contains(['\n', '\r']) {
        return Err("a template is one line".into());
    }
    let mut rest = line;
    while let Some(open) = rest.find('{') {
        let Some(close) = rest[open..].find('}') else { return Err(format!("unclosed brace in {line:?}")) };
        let name = &rest[open + 1..open + close];
        if !allowed.contains(&name) {
            let known = if allowed.is_empty() { "none here".to_owned() } else { allowed.iter().map(|a| format!("{{{a}}}")).collect::<Vec<_>>().join(", ") };
            return Err(format!("unknown placeholder {{{name}}} in {line:?} (known: {known})"));
        }
        rest = &rest[open + close + 1..];
    }
    if rest.contains('}') {
        return Err(format!("unopened brace in {line:?}"));
    }
    Ok(())
}

/// Fills a template's placeholders.
pub(crate) fn fill(template: &str, values: &[(&str, String)]) -> String {
    let mut out = template.to_owned();
    for (name, value) in values {
        out = out.replace(&format!("{{{name}}}"), value);
    }
    out
}

/// `text` in lines of at most `width` characters, broken between words (a word longer than a
/// line is cut), no line empty.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let width = width.max(1);
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let mut word: Vec<char> = word.chars().collect();
        loop {
            let used = line.chars().count();
            let room = if used == 0 { width } else { width.saturating_sub(used + 1) };
            if word.len() <= room {
                if used > 0 {
                    line.push(' ');
                }
                line.extend(word);
                break;
            }
            if used > 0 {
                lines.push(std::mem::take(&mut line));
                continue;
            }
            let rest = word.split_off(width);
            lines.push(word.into_iter().collect());
            word = rest;
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Comments may not hold parentheses (they would end the comment early).
pub(crate) fn comment(text: &str) -> String {
    text.chars().map(|c| if c == '(' || c == ')' { '-' } else { c }).filter(|c| !c.is_control()).collect()
}

/// The work offsets a control has beyond `G54` to `G59`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, deny_unknown_fields, rename_all = "camelCase")]
pub struct WorkOffsets {
    /// `G59.1` to `G59.3` (LinuxCNC, grblHAL). Default value: false.
    pub g59_dot: bool,
    /// The largest `n` of the extended offsets `G54.1 Pn` (Fanuc's 48), 0 for none. Default
    /// value: 0.
    pub extended: u32,
}

impl Post {
    /// Whether the control has the work offset `w` (`G55`, `G59.2`, `G54.1 P12`).
    pub fn has_work_offset(&self, w: &str) -> bool {
        match w {
            "G54" | "G55" | "G56" | "G57" | "G58" | "G59" => true,
            "G59.1" | "G59.2" | "G59.3" => self.work_offsets.g59_dot,
            _ => w.strip_prefix("G54.1 P").and_then(|n| n.parse::<u32>().ok()).is_some_and(|n| n >= 1 && n <= self.work_offsets.extended),
        }
    }

    /// The work offsets the control has, in words ("G54 to G59, G59.1 to G59.3").
    pub fn work_offsets_words(&self) -> String {
        let mut words = vec!["G54 to G59".to_owned()];
        if self.work_offsets.g59_dot {
            words.push("G59.1 to G59.3".into());
        }
        if self.work_offsets.extended > 0 {
            words.push(format!("G54.1 P1 to G54.1 P{}", self.work_offsets.extended));
        }
        format!("one of {} ({})", words.join(", "), self.name)
    }
}

/// Whether the line `w` selects a work offset, on any control: `G54` to `G59`, `G59.1` to
/// `G59.3`, `G54.1 Pn`.
pub fn is_work_offset(w: &str) -> bool {
    matches!(w, "G54" | "G55" | "G56" | "G57" | "G58" | "G59" | "G59.1" | "G59.2" | "G59.3") || w.strip_prefix("G54.1 P").is_some_and(|n| n.parse::<u32>().is_ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapped_lines_keep_every_word_within_the_width() {
        let text = "2091 moves bury the tool deeper than its flute length: the first at X12.5 Y-3 Z-40 (T2 φ6 flat), abcdefghijklmnopqrstuvwxyz0123456789abcdefghij";
        for width in [10, 30, 68] {
            let lines = wrap(text, width);
            assert!(lines.iter().all(|l| !l.is_empty() && l.chars().count() <= width), "{width}: {lines:?}");
            // Nothing lost or added: the words (cut ones joined again) in order.
            let joined: String = lines.join(" ");
            let squeeze = |s: &str| s.split_whitespace().collect::<String>();
            assert_eq!(squeeze(&joined), squeeze(text), "{width}");
        }
        assert_eq!(wrap("a bc def", 4), ["a bc", "def"]);
        assert_eq!(wrap("abcdefghij", 4), ["abcd", "efgh", "ij"]);
        assert!(wrap("   ", 5).is_empty());
    }

    #[test]
    fn bad_posts_are_refused_naming_the_field() {
        for (json, needle) in [
            (r#"{"speed": 3}"#, "unknown field `speed`"),
            (r#"{"toolChange": ["T{tol} M6"]}"#, "toolChange[0]: unknown placeholder {tol}"),
            (r#"{"spindleOn": "S{rpm M3"}"#, "unclosed brace"),
            (r#"{"maxLineLength": 20}"#, "maxLineLength must be at least"),
            (r#"{"decimalsMm": 0}"#, "decimalsMm"),
            (r#"{"toolChange": [], "pause": ""}"#, "pause must be set"),
            (r#"{"spindleDwell": 2, "dwell": null}"#, "needs a dwell"),
            (r#"{"workOffset": "G92"}"#, "G54 to G59"),
            (r#"{"arcs": "spline"}"#, "arcs"),
            (r#"{"lineNumbers": {"start": 1}}"#, "step"),
            (r#"{"extension": "n c"}"#, "extension"),
        ] {
            let e = Post::from_json(json).unwrap_err();
            assert!(e.contains(needle), "{json}: {e}");
        }
        assert!(Post::from_json("{}").is_ok());
    }

    #[test]
    fn comments_are_ascii_unless_the_post_says_otherwise() {
        let fanuc = Post { comments: CommentStyle::Parens, ..Post::default() };
        assert_eq!(fanuc.comment("octree rough φ20 × 3 – δ 1.5 µm, café 30° ≤ 2²").unwrap(), "(octree rough D20 x 3 - delta 1.5 um, cafe 30 deg <= 22)");
        assert_eq!(fanuc.comment("漢字 (1)").unwrap(), "(?? -1-)");
        let linuxcnc = Post { comment_characters: CommentCharacters::Any, ..Post::default() };
        assert_eq!(linuxcnc.comment("φ20").unwrap(), "(φ20)");
    }

    #[test]
    fn templates_fill() {
        assert_eq!(fill("T{tool} M6", &[("tool", "3".into())]), "T3 M6");
        assert_eq!(fill("G4 P{millis}", &[("seconds", "2".into()), ("millis", "2000".into())]), "G4 P2000");
    }
}
