//! How the page asks for an operation's settings: each operation's file says, next to its
//! options, the fields of its form ([`crate::machining::Operate::form`]): the key each edits in
//! the operation's JSON, the words it is asked in, its unit, its range and what an empty field
//! means. The page builds the operation's form from these (`operationForms` at the wasm
//! boundary), and the defaults it fills them with are the options' own `Default`: a new
//! operation is its one Rust file. A test holds every form to its options: each field's key is
//! one of theirs, each choice reads, each default lies in the field's range, and no setting is
//! left without a field unless the form names it as kept out.

use serde::Serialize;

/// What a field holds, for its label and the page's units: a length and a feed follow the
/// page's mm or inches; the others are said as they are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum FieldUnit {
    /// A count, a fraction, a word.
    #[default]
    None,
    /// mm (or inches in the page).
    Length,
    /// mm/min (or in/min).
    Feed,
    /// Degrees.
    Degrees,
    /// Seconds.
    Seconds,
}

/// How a field is typed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum FieldInput {
    /// A number (empty where the field says what empty means).
    Number,
    /// A whole number.
    Int,
    /// One of the field's choices.
    Choice,
    /// Yes or no.
    Check,
    /// Words with commas (layers).
    Words,
    /// Whole numbers with commas (holes, loops, tools).
    Ints,
    /// Free text (a name, a thread).
    Text,
    /// One of the library's tools, by its number.
    Tool,
}

/// One choice of a [`FieldInput::Choice`] field: its value in the job file and its words.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, ts_rs::TS)]
pub struct FieldChoice {
    pub value: &'static str,
    pub label: &'static str,
}

/// One field of an operation's form.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct FormField {
    /// The setting it edits, dotted into objects (`tabs.count`).
    pub key: &'static str,
    /// Its words, without the unit ("Step-down").
    pub label: &'static str,
    pub input: FieldInput,
    pub unit: FieldUnit,
    /// What the number means beyond its unit ("fraction of the tool's diameter").
    pub note: Option<&'static str>,
    /// What an empty field means ("down to the part's top"); none: it must be filled.
    pub empty: Option<&'static str>,
    /// The least and the most it takes (in mm for a length).
    pub min: Option<f64>,
    pub max: Option<f64>,
    /// The choices of a [`FieldInput::Choice`].
    pub choices: Vec<FieldChoice>,
    /// A longer word on what it does (the field's tooltip).
    pub help: Option<&'static str>,
    /// Shown for a part, a drawing or either.
    pub applies: Applies,
}

/// What a form or a field is for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Applies {
    Part,
    Drawing,
    #[default]
    Either,
}

/// What the page finds for an operation to pick from, shown above its fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Picks {
    /// The holes of the part or drawing (bosses for an external thread, top edges for a
    /// chamfer of a part's edges), listed and clicked in the view.
    Holes,
}

/// An operation's form.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct OperationForm {
    /// The kind, as the job file names it.
    pub kind: &'static str,
    /// Its name in the list of operations to add ("face the stock's top").
    pub title: &'static str,
    /// A paragraph shown over its fields.
    pub hint: Option<&'static str>,
    pub applies: Applies,
    pub picks: Option<Picks>,
    pub fields: Vec<FormField>,
    /// Settings of the job file the form leaves out (set in the file only).
    pub kept_out: Vec<&'static str>,
}

impl OperationForm {
    /// A form titled `title` with `fields` (its kind and what it applies to filled in from the
    /// operation's list).
    /// A kind with the heights ([`super::settings::Heights::fields`], or a 2D or hole
    /// kind's clearance) leaves out their picked point: the page picks it under its heights.
    pub fn new(title: &'static str, fields: Vec<FormField>) -> Self {
        let kept_out = if fields.iter().any(|f| f.key == "clearanceFrom") { vec!["point"] } else { Vec::new() };
        OperationForm { kind: "", title, hint: None, applies: Applies::Either, picks: None, fields, kept_out }
    }

    pub fn hint(mut self, hint: &'static str) -> Self {
        self.hint = Some(hint);
        self
    }

    pub fn picks(mut self, picks: Picks) -> Self {
        self.picks = Some(picks);
        self
    }

    /// Settings left to the job file.
    pub fn kept_out(mut self, keys: &[&'static str]) -> Self {
        self.kept_out.extend_from_slice(keys);
        self
    }
}

impl FormField {
    fn new(key: &'static str, label: &'static str, input: FieldInput, unit: FieldUnit) -> Self {
        FormField { key, label, input, unit, note: None, empty: None, min: None, max: None, choices: Vec::new(), help: None, applies: Applies::Either }
    }

    /// A length (mm), at least `min`.
    pub fn length(key: &'static str, label: &'static str, min: f64) -> Self {
        FormField::new(key, label, FieldInput::Number, FieldUnit::Length).range(min, None)
    }

    /// A number of `unit`.
    pub fn number(key: &'static str, label: &'static str, unit: FieldUnit) -> Self {
        FormField::new(key, label, FieldInput::Number, unit)
    }

    /// An angle in degrees from `min` to `max`.
    pub fn degrees(key: &'static str, label: &'static str, min: f64, max: f64) -> Self {
        FormField::new(key, label, FieldInput::Number, FieldUnit::Degrees).range(min, Some(max))
    }

    /// A fraction of the tool's diameter, from 0.01 to `max`.
    pub fn fraction(key: &'static str, label: &'static str, note: &'static str, max: f64) -> Self {
        FormField::new(key, label, FieldInput::Number, FieldUnit::None).range(0.01, Some(max)).note(note)
    }

    /// A whole number from `min`.
    pub fn int(key: &'static str, label: &'static str, min: f64, max: Option<f64>) -> Self {
        FormField::new(key, label, FieldInput::Int, FieldUnit::None).range(min, max)
    }

    /// One of `choices` (`(value, words)`).
    pub fn choice(key: &'static str, label: &'static str, choices: &[(&'static str, &'static str)]) -> Self {
        let mut f = FormField::new(key, label, FieldInput::Choice, FieldUnit::None);
        f.choices = choices.iter().map(|&(value, label)| FieldChoice { value, label }).collect();
        f
    }

    /// Yes or no, said as what a tick means.
    pub fn check(key: &'static str, label: &'static str) -> Self {
        FormField::new(key, label, FieldInput::Check, FieldUnit::None)
    }

    /// Whole numbers with commas: `note` says which.
    pub fn ints(key: &'static str, label: &'static str, note: &'static str) -> Self {
        FormField::new(key, label, FieldInput::Ints, FieldUnit::None).note(note)
    }

    /// Words with commas.
    pub fn words(key: &'static str, label: &'static str, note: &'static str) -> Self {
        FormField::new(key, label, FieldInput::Words, FieldUnit::None).note(note)
    }

    /// Free text.
    pub fn text(key: &'static str, label: &'static str) -> Self {
        FormField::new(key, label, FieldInput::Text, FieldUnit::None)
    }

    /// The operation's name and tool: the first fields of every form that has one tool.
    pub fn name_and_tool() -> [Self; 2] {
        [FormField::text("name", "Name"), FormField::new("tool", "Tool", FieldInput::Tool, FieldUnit::None)]
    }

    /// Where a finish on a part cuts (`boundary`): within the part's outline grown by the tool's
    /// radius, or over the whole stock.
    pub fn area() -> Self {
        FormField::choice("boundary", "Area", &[("silhouette", "the part's outline + the tool's radius"), ("stock", "the whole stock")])
    }

    /// How far the outline [`FormField::area`] names is grown (`margin`).
    pub fn outline_growth() -> Self {
        FormField::number("margin", "Outline grown by", FieldUnit::Length).note("less than 0: shrunk").empty("the tool's radius")
    }

    /// The first fields of a 2D cut to a depth in steps: its name and tool, the drawing's layers,
    /// the depth and the step-down.
    pub fn sheet_cut() -> Vec<Self> {
        let mut fields = FormField::name_and_tool().to_vec();
        fields.extend([FormField::words("layers", "Layers", "with commas").empty("all"), FormField::length("depth", "Depth", 0.01), FormField::length("stepdown", "Step-down per pass", 0.01)]);
        fields
    }

    /// Only the name (an operation that picks its tools).
    pub fn name() -> Self {
        FormField::text("name", "Name")
    }

    pub fn note(mut self, note: &'static str) -> Self {
        self.note = Some(note);
        self
    }

    /// May be left empty, meaning `what`.
    pub fn empty(mut self, what: &'static str) -> Self {
        self.empty = Some(what);
        self
    }

    pub fn range(mut self, min: f64, max: Option<f64>) -> Self {
        self.min = Some(min);
        self.max = max;
        self
    }

    pub fn help(mut self, help: &'static str) -> Self {
        self.help = Some(help);
        self
    }

    pub fn applies(mut self, applies: Applies) -> Self {
        self.applies = applies;
        self
    }

    // ---- fields several operations share, in the same words --------------------------------

    /// `direction`: climb or conventional.
    pub fn direction() -> Self {
        FormField::choice("direction", "Direction", &[("climb", "climb"), ("conventional", "conventional")])
    }

    /// `grid`: the spacing of the CL z-map.
    pub fn grid() -> Self {
        FormField::length("grid", "Surface grid", 0.01)
            .help("How finely the part's surface is sampled under the tool: its lowest safe height is worked out at points this far apart. Finer: slower to compute, closer into narrow places.")
    }

    /// `rampAngle`: the steepest descent of ramps and helices.
    pub fn ramp_angle() -> Self {
        FormField::degrees("rampAngle", "Ramp angle", 0.1, 89.0)
    }

    /// `load`: how a zigzag keeps the chip load even.
    pub fn load(label: &'static str, help: &'static str) -> Self {
        FormField::choice("load", label, &[("path", "adding path"), ("feed", "slowing the feed"), ("none", "nothing")]).help(help)
    }

    /// `holes`, `minDiameter` and `maxDiameter`: which holes a hole operation makes.
    pub fn which_holes() -> [Self; 3] {
        [
            FormField::ints("holes", "Holes", "numbers with commas, as the part's or drawing's holes are listed").empty("all"),
            FormField::length("minDiameter", "Only holes at least this wide", 0.01).empty("any"),
            FormField::length("maxDiameter", "Only holes at most this wide", 0.01).empty("any"),
        ]
    }

    /// `loops`: a drawing's loops, typed or clicked in the view; `empty` says what none means.
    pub fn loops(label: &'static str, note: &'static str, empty: &'static str) -> Self {
        FormField::ints("loops", label, note).empty(empty)
    }

    /// `entry`: how a finishing pass enters material ([`crate::toolpath::entry::Entry`]).
    pub fn entry() -> [Self; 3] {
        [
            FormField::degrees("entry.rampAngle", "Entry ramp angle", 0.1, 89.0),
            FormField::number("entry.helixMin", "Smallest entry helix", FieldUnit::None).range(0.0, Some(1.0)).note("fraction of the tool's diameter; 0: no helix"),
            FormField::number("entry.helixMax", "Largest entry helix", FieldUnit::None).range(0.0, Some(1.0)).note("fraction of the tool's diameter"),
        ]
    }

    /// `retract`: the height over the material a hole's cycle starts from.
    pub fn start_above() -> Self {
        FormField::length("retract", "Start above the material", 0.01)
    }

    /// `marks`: a drawing's drill marks taken with "all the holes".
    pub fn marks() -> Self {
        FormField::check("marks", "a drawing's drill marks (its points) too, with all the holes").applies(Applies::Drawing)
    }
}
