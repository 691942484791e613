//! One error type for the whole pipeline, in three kinds (as lyon sorts its errors): bad input
//! (a file that does not read, a job setting that does not fit, named by its path), an operation
//! that cannot be done (named, with why), and a fault of swarf's own. Cancelling, a program that
//! would cut nothing and one the simulation found unsafe are told apart so that the CLI and the
//! page can say each plainly.

use thiserror::Error;

pub use crate::mesh::import::ImportError;

/// Anything that can go wrong between a dropped file and G-code.
#[derive(Debug, Error)]
pub enum Error {
    #[error(transparent)]
    Import(#[from] ImportError),
    #[error(transparent)]
    Program(#[from] crate::post::read::ReadError),
    /// A job setting that does not fit (from a file, the page or a portal): the message names
    /// the field by its path (`operations[1].stepover must be a positive number`), and says
    /// nothing of a file, which there may not be.
    #[error("{0}")]
    Input(String),
    /// A project file that does not fit (its job's errors are named under `job.`).
    #[error("invalid project file: {0}")]
    Project(String),
    /// An operation that cannot be done on this part or drawing: a tool that does not fit, an
    /// empty region, a 3D operation on a drawing.
    #[error("{operation}: {why}")]
    Operation { operation: String, why: String },
    /// A fault of swarf's own, never the user's.
    #[error("internal error (please report it): {0}")]
    Internal(String),
    #[error("cancelled")]
    Cancelled,
    /// The job would make a program that cuts nothing.
    #[error("nothing to cut: {0}")]
    Nothing(String),
    /// Verification found a gouge, a rapid through stock or the tool's body in material.
    #[error("the program is not safe to run: {0}")]
    Unsafe(String),
}

/// Which of the three kinds an error is (cancelling is the user's choice, not a fault).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// The input is wrong: fix the file or the setting the message names.
    Input,
    /// The input is fine but the operation cannot be done as set up.
    Operation,
    /// swarf's own fault.
    Internal,
    Cancelled,
}

impl Error {
    /// An operation that cannot be done.
    pub fn operation(operation: &str, why: impl Into<String>) -> Error {
        Error::Operation { operation: operation.to_string(), why: why.into() }
    }

    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::Import(_) | Error::Program(_) | Error::Input(_) | Error::Project(_) => ErrorKind::Input,
            Error::Operation { .. } | Error::Nothing(_) | Error::Unsafe(_) => ErrorKind::Operation,
            Error::Internal(_) => ErrorKind::Internal,
            Error::Cancelled => ErrorKind::Cancelled,
        }
    }
}

/// Something the user should know that did not stop the job, with the operation it belongs to
/// (none for the job as a whole: the part, the stock): a warning (something may not be as the
/// user means: look) or a note (for the record). A counted warning says how many places and
/// keeps the first of them, for the page to mark.
#[derive(Clone, Debug, PartialEq, serde::Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Warning {
    pub operation: Option<String>,
    pub message: String,
    pub level: Level,
    /// How many places it counts (0: it counts none).
    pub count: usize,
    /// The first of them (x, y, z in mm, as placed), at most [`Warning::KEPT`].
    pub places: Vec<[f64; 3]>,
    /// Loops of the drawing (by index) the operation offers to pick, where it chose what to
    /// cut by itself (a V-carve with none picked: the regions it carved), for the user to make
    /// the choice their own and change it.
    pub loops: Vec<usize>,
    /// What is counted, for [`Warning::counted`] to add to.
    #[serde(skip)]
    #[ts(skip)]
    what: String,
}

/// How much a [`Warning`] asks of the user.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Level {
    /// Something may not be as the user means: a plunge into material, a part that may be in
    /// the wrong unit, a loop left uncut. The page shows it in amber.
    #[default]
    Warning,
    /// For the record: triangles dropped, a rest operation with nothing left to cut.
    Note,
}

impl Warning {
    /// Places a counted warning keeps.
    pub const KEPT: usize = 20;

    pub fn job(message: impl Into<String>) -> Warning {
        Warning { operation: None, message: message.into(), level: Level::Warning, count: 0, places: Vec::new(), loops: Vec::new(), what: String::new() }
    }

    pub fn of(operation: &str, message: impl Into<String>) -> Warning {
        Warning { operation: Some(operation.to_string()), ..Warning::job(message) }
    }

    /// The same, offering `loops` to pick ([`Warning::loops`]).
    pub fn offering(self, loops: Vec<usize>) -> Warning {
        Warning { loops, ..self }
    }

    /// A note rather than a warning.
    pub fn note(self) -> Warning {
        Warning { level: Level::Note, ..self }
    }

    /// A warning of `operation` (none: the job's) that counts `places` of `what`
    /// (`entries feed straight down into material`): "3 entries … (at X1.000 Y2.000 Z-3.000, …)".
    pub fn counted(operation: Option<&str>, what: &str, places: &[crate::geom::DVec3]) -> Warning {
        let mut w = Warning { operation: operation.map(str::to_owned), what: what.to_owned(), ..Warning::job("") };
        w.add(places);
        w
    }

    /// Whether `other` counts the same thing of the same operation, so that it adds to this.
    pub fn counts_as(&self, other: &Warning) -> bool {
        !self.what.is_empty() && self.what == other.what && self.operation == other.operation
    }

    /// Adds `places` to a counted warning.
    pub fn add(&mut self, places: &[crate::geom::DVec3]) {
        self.count += places.len();
        let room = Warning::KEPT.saturating_sub(self.places.len());
        self.places.extend(places.iter().take(room).map(|p| p.to_array()));
        let at: Vec<String> = self.places.iter().take(3).map(|p| format!("X{:.3} Y{:.3} Z{:.3}", p[0], p[1], p[2])).collect();
        let more = if self.count > at.len() { ", …" } else { "" };
        self.message = format!("{} {} (at {}{more})", self.count, self.what, at.join("; "));
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.operation {
            Some(op) => write!(f, "{op}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

/// `T` read from JSON already parsed, what does not fit named by its path. Every reader of
/// settings (a job, a post, a tool, what the page hands the engine) goes through this one, so
/// serde's readers of swarf's types are built once in the page's wasm, for `&Value`, instead of
/// once more for each source (a JS object, a JSON text, an owned value).
pub(crate) fn read_value<T: serde::de::DeserializeOwned>(value: &serde_json::Value) -> std::result::Result<T, serde_path_to_error::Error<serde_json::Error>> {
    serde_path_to_error::deserialize(value)
}

/// A message of serde's said in a user's words: `invalid type: string "5", expected f64` is
/// `expected a number, got "5"`.
pub(crate) fn plain(message: &str) -> String {
    let what = |expected: &str| -> String {
        let e = expected.trim();
        match e {
            "f64" | "f32" => "a number".into(),
            "u8" | "u16" | "u32" | "u64" | "usize" => "a whole number, 0 or more".into(),
            "i32" | "i64" | "isize" => "a whole number".into(),
            "a boolean" | "bool" => "true or false".into(),
            "a string" => "text".into(),
            "a sequence" => "a list".into(),
            "unit" => "null".into(),
            _ if e.starts_with("struct ") || e.starts_with("a map") => "an object".into(),
            _ if e.starts_with("a sequence of ") || e.starts_with("an array of length") => format!("a list ({e})"),
            _ if e.starts_with("internally tagged enum") => "an object with a kind".into(),
            _ => e.to_owned(),
        }
    };
    let got = |unexpected: &str| -> String {
        let u = unexpected.trim();
        let quoted = |prefix: &str| u.strip_prefix(prefix).map(|v| v.trim_matches('`').to_owned());
        if let Some(v) = u.strip_prefix("string ") {
            return v.to_owned();
        }
        for prefix in ["integer ", "floating point ", "boolean "] {
            if let Some(v) = quoted(prefix) {
                return v;
            }
        }
        match u {
            "map" => "an object".into(),
            "sequence" => "a list".into(),
            "unit value" | "null" => "null".into(),
            _ => u.to_owned(),
        }
    };
    for rest in [message.strip_prefix("invalid type: "), message.strip_prefix("invalid value: ")] {
        if let Some((unexpected, expected)) = rest.and_then(|r| r.rsplit_once(", expected ")) {
            return format!("expected {}, got {}", what(expected), got(unexpected));
        }
    }
    if let Some(rest) = message.strip_prefix("unknown variant ") {
        if let Some((variant, expected)) = rest.split_once(", expected ") {
            let options = expected.trim_start_matches("one of ").replace('`', "\"");
            return format!("{} is not one of {options}", variant.replace('`', "\""));
        }
    }
    if let Some(field) = message.strip_prefix("missing field ") {
        return format!("{} is missing", field.trim_matches('`'));
    }
    message.to_owned()
}

#[cfg(test)]
mod tests {
    use super::plain;

    #[test]
    fn serde_s_messages_in_a_users_words() {
        assert_eq!(plain(r#"invalid type: string "5", expected f64"#), r#"expected a number, got "5""#);
        assert_eq!(plain("invalid type: floating point `1.5`, expected u32"), "expected a whole number, 0 or more, got 1.5");
        assert_eq!(plain("invalid value: integer `-1`, expected u32"), "expected a whole number, 0 or more, got -1");
        assert_eq!(plain("invalid type: map, expected f64"), "expected a number, got an object");
        assert_eq!(plain("invalid type: integer `3`, expected a boolean"), "expected true or false, got 3");
        assert_eq!(plain("unknown variant `spline`, expected one of `ij`, `r`, `off`"), r#""spline" is not one of "ij", "r", "off""#);
        assert_eq!(plain("missing field `start`"), "start is missing");
        assert_eq!(plain("something else"), "something else");
    }
}
