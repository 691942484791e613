//! The one strict reader of jobs: the CLI, the page (`readJob`, and every run it asks for),
//! embedding pages (`engine.run`) and project files all read a job through [`Job::from_value`].
//! A value that does not fit is named by its path and said in plain words
//! (`stock.marginXy: expected a number, got "5"`), and so is every field this version does not
//! know (`operations[0].stepOver (did you mean stepover?)`): a misspelt setting must never fall
//! back to its default unseen. Files of an older version are read as they were written.

use super::schema::{DrawingSetup, Job, JOB_VERSION};
use crate::error::{plain, Error, Result};
use crate::operations::Operation;

/// The fields that changed name, by version: `(version that renamed it, operation kinds, old
/// name, new name)`. A file of an older version is read with its old names.
const RENAMED: &[(u32, &[&str], &str, &str)] = &[(2, &["roughZlevel", "roughZigzag", "roughOctree", "pocket2d"], "stepover", "stepoverFraction")];

/// A job's machine given by the name of a built-in one takes that one's limits where the file
/// gives none of its own (`"machine": {"name": "small VMC"}` once kept the hobby router's); a
/// name of no built-in machine with none of the limits is refused, naming them.
fn machine_by_name(value: &serde_json::Value) -> Result<serde_json::Value> {
    let mut value = value.clone();
    let Some(machine) = value.get_mut("machine").and_then(serde_json::Value::as_object_mut) else { return Ok(value) };
    let Some(name) = machine.get("name").and_then(serde_json::Value::as_str).map(str::to_owned) else { return Ok(value) };
    let builtin = crate::cutting::Machine::builtin();
    match builtin.iter().find(|m| m.name.eq_ignore_ascii_case(name.trim())) {
        Some(m) => {
            let whole = serde_json::to_value(m).map_err(|e| Error::Internal(e.to_string()))?;
            for (k, v) in whole.as_object().into_iter().flatten() {
                machine.entry(k.clone()).or_insert_with(|| v.clone());
            }
        }
        None if !["spindleMin", "spindleMax", "maxFeed"].iter().any(|k| machine.contains_key(*k)) => {
            let names: Vec<String> = builtin.iter().map(|m| format!("{:?}", m.name)).collect();
            return Err(Error::Input(format!(
                "machine.name: {name:?} is none of the built-in machines ({}), and the machine gives none of its limits: give its spindleMin, spindleMax and maxFeed, or name a built-in one",
                names.join(", ")
            )));
        }
        None => {}
    }
    Ok(value)
}

impl Job {
    /// Reads a job file (JSON text), see [`Job::from_value`].
    pub fn from_json(text: &str) -> Result<Job> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Input(format!("the job is not JSON: {e}")))?;
        // A parsed value keeps the last of two keys of the same name: the first (two
        // `"operations"`, one edited and one pasted) would be dropped without a word.
        serde_json::from_str::<NoDuplicateKeys>(text).map_err(|e| Error::Input(format!("the job {}", plain(&e.to_string()))))?;
        Job::from_value(&value)
    }

    /// Reads a job from JSON already parsed. A value that does not fit is named by its path
    /// and what was expected; every field this version does not know is named, with the known
    /// field it may mean. A file without a `version` is read as version 1; one from a newer
    /// swarf is refused. The job comes back in this version's form (`version` too).
    pub fn from_value(value: &serde_json::Value) -> Result<Job> {
        // A job is an object of settings: serde reads a struct from an array too (its fields in
        // order), and an empty array would be the default job without a word.
        if !value.is_object() {
            let what = match value {
                serde_json::Value::Array(_) => "a list",
                serde_json::Value::String(_) => "a string",
                serde_json::Value::Number(_) => "a number",
                serde_json::Value::Bool(_) => "true or false",
                _ => "null",
            };
            return Err(Error::Input(format!("the job is {what}, not an object of settings ({{ \"operations\": […], \"tools\": […], … }}, as `swarf job` prints it)")));
        }
        let version = value.get("version").and_then(serde_json::Value::as_u64).unwrap_or(1);
        if version > JOB_VERSION as u64 {
            return Err(Error::Input(format!("the job has version {version}; this swarf reads versions up to {JOB_VERSION} (a newer swarf wrote it)")));
        }
        let value = &machine_by_name(&upgrade(value, version as u32))?;
        let mut job: Job = crate::error::read_value(value).map_err(|e| {
            let path = e.path().to_string();
            // An operation is read whole (its `kind` picks the type), so the path stops at it:
            // read it again as its kind's type to name the field.
            let op = value.get("operations").and_then(|ops| path.strip_prefix("operations[")?.strip_suffix(']')?.parse::<usize>().ok().and_then(|i| ops.get(i)));
            // A tool is read whole too (its cutter's fields flattened in): each of its fields
            // is tried on a default tool to find the one that does not fit.
            let tool = value.get("tools").and_then(|tools| path.strip_prefix("tools[")?.strip_suffix(']')?.parse::<usize>().ok().and_then(|i| tools.get(i)));
            match op.and_then(Operation::field_error).or_else(|| tool.and_then(tool_field_error)) {
                Some(inner) => Error::Input(format!("{path}.{inner}")),
                None if path == "." => Error::Input(plain(&e.into_inner().to_string())),
                None => Error::Input(format!("{path}: {}", plain(&e.into_inner().to_string()))),
            }
        })?;
        let canonical = serde_json::to_value(&job).map_err(|e| Error::Internal(e.to_string()))?;
        if let Some(path) = list_for_object(value, &canonical, "") {
            return Err(Error::Input(format!("{path}: a list, where its settings belong in an object ({{ … }})")));
        }
        let mut unknown = Vec::new();
        unknown_fields(value, &canonical, "", &mut unknown);
        if !unknown.is_empty() {
            return Err(Error::Input(format!("unknown field{}: {}", if unknown.len() == 1 { "" } else { "s" }, unknown.join("; "))));
        }
        // A job of setups lists each setup's operations in it: operations beside them would
        // belong to none.
        if !job.setups.is_empty() {
            if value.get("operations").and_then(serde_json::Value::as_array).is_some_and(|ops| !ops.is_empty()) {
                return Err(Error::Input("operations: a job with setups lists its operations in each setup (setups[0].operations, …), not beside them".into()));
            }
            job.operations = Vec::new();
        }
        job.version = JOB_VERSION;
        Ok(job)
    }
}

/// `value`, a job of `version`, with the fields renamed since then under their new names and
/// the values whose meaning changed carried over.
fn upgrade(value: &serde_json::Value, version: u32) -> serde_json::Value {
    let mut value = value.clone();
    if version < 2 {
        tabs_from_the_bottom(&mut value);
    }
    for &(_, kinds, old, new) in RENAMED.iter().filter(|r| r.0 > version) {
        for op in value.get_mut("operations").and_then(serde_json::Value::as_array_mut).into_iter().flatten() {
            let ours = op.get("kind").and_then(serde_json::Value::as_str).is_some_and(|k| kinds.contains(&k));
            if let Some(object) = op.as_object_mut().filter(|_| ours) {
                if !object.contains_key(new) {
                    if let Some(v) = object.remove(old) {
                        object.insert(new.to_owned(), v);
                    }
                }
            }
        }
    }
    value
}

/// Version 1 measured a profile's tab height from the cut's final depth; version 2 measures it
/// from the sheet's bottom (or the cut's floor, where the cut stops inside the sheet): a
/// version-1 height over a cut through the sheet loses the cut's depth past the bottom.
fn tabs_from_the_bottom(value: &mut serde_json::Value) {
    let thickness = value.pointer("/drawing/thickness").and_then(serde_json::Value::as_f64).unwrap_or(DrawingSetup::default().thickness);
    for op in value.get_mut("operations").and_then(serde_json::Value::as_array_mut).into_iter().flatten() {
        if op.get("kind").and_then(serde_json::Value::as_str) != Some("profile2d") {
            continue;
        }
        let depth = op.get("depth").and_then(serde_json::Value::as_f64).unwrap_or(thickness + crate::machining::sheet::BREAKTHROUGH);
        let past = (depth - thickness).max(0.0);
        let height = op.pointer("/tabs/height").and_then(serde_json::Value::as_f64).unwrap_or(crate::operations::Tabs::default().height);
        if past > 0.0 && op.get("tabs").is_some_and(serde_json::Value::is_object) {
            op["tabs"]["height"] = serde_json::json!(height - past);
        }
    }
}

/// The fields of `input` that reading it did not use: those absent from the job it made,
/// written back (`canonical`), with a known field of the same object that differs only in case
/// or by underscores, as a hint.
fn unknown_fields(input: &serde_json::Value, canonical: &serde_json::Value, path: &str, out: &mut Vec<String>) {
    use serde_json::Value;
    match (input, canonical) {
        (Value::Object(given), Value::Object(known)) => {
            for (k, v) in given {
                let here = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                match known.get(k) {
                    Some(w) => unknown_fields(v, w, &here, out),
                    None => match likely(k, known.keys()) {
                        Some(n) => out.push(format!("{here} (did you mean {n}?)")),
                        None => out.push(here),
                    },
                }
            }
        }
        (Value::Array(given), Value::Array(known)) => {
            for (i, (v, w)) in given.iter().zip(known).enumerate() {
                unknown_fields(v, w, &format!("{path}[{i}]"), out);
            }
        }
        _ => {}
    }
}

/// The first place in `input` where a list stands for an object of settings (serde reads a
/// struct from a list of its fields in order, an empty one as the defaults, without a word).
fn list_for_object(input: &serde_json::Value, canonical: &serde_json::Value, path: &str) -> Option<String> {
    use serde_json::Value;
    match (input, canonical) {
        (Value::Array(_), Value::Object(_)) => Some(path.to_string()),
        (Value::Object(given), Value::Object(known)) => {
            given.iter().find_map(|(k, v)| known.get(k).and_then(|w| list_for_object(v, w, &if path.is_empty() { k.clone() } else { format!("{path}.{k}") })))
        }
        (Value::Array(given), Value::Array(known)) => given.iter().zip(known).enumerate().find_map(|(i, (v, w))| list_for_object(v, w, &format!("{path}[{i}]"))),
        _ => None,
    }
}

/// Where a tool's JSON does not fit: `field: what is wrong`, the first field that, put alone on
/// a default tool, does not read.
fn tool_field_error(value: &serde_json::Value) -> Option<String> {
    let base = serde_json::to_value(super::Tool::default()).ok()?;
    for (key, v) in value.as_object()? {
        let mut one = base.clone();
        one[key] = v.clone();
        if let Err(e) = crate::error::read_value::<super::Tool>(&one) {
            return Some(format!("{key}: {}", plain(&e.inner().to_string())));
        }
    }
    None
}

/// How many single-character edits (insert, delete, change, swap two neighbours) make `a` into
/// `b`, case aside.
fn edits(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.to_lowercase().chars().collect(), b.to_lowercase().chars().collect());
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for j in 0..=b.len() {
        d[0][j] = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let change = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + change);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

/// The known field a misspelt `given` most likely means: one that differs by case or
/// underscores, an old name, or one within two edits (one for short names).
fn likely<'a>(given: &str, known: impl Iterator<Item = &'a String> + Clone) -> Option<&'a String> {
    let squash = |k: &str| k.to_lowercase().replace(['_', '-'], "");
    if let Some(n) = known.clone().find(|n| squash(n) == squash(given)) {
        return Some(n);
    }
    if let Some(n) = renamed(given).and_then(|n| known.clone().find(|m| *m == n)) {
        return Some(n);
    }
    let most = if given.chars().count() <= 4 { 1 } else { 2 };
    known.map(|n| (edits(&squash(n), &squash(given)), n)).filter(|(d, _)| *d <= most).min_by_key(|(d, _)| *d).map(|(_, n)| n)
}

/// The field an old name became, if it became one.
fn renamed(old: &str) -> Option<&'static str> {
    RENAMED.iter().find(|r| r.2.eq_ignore_ascii_case(old)).map(|r| r.3)
}

/// A JSON text read only to refuse an object that names a key twice ([`Job::from_json`]).
struct NoDuplicateKeys;

impl<'de> serde::Deserialize<'de> for NoDuplicateKeys {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Visit;
        impl<'de> serde::de::Visitor<'de> for Visit {
            type Value = NoDuplicateKeys;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("any JSON value")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> std::result::Result<Self::Value, A::Error> {
                let mut seen = std::collections::HashSet::new();
                while let Some(key) = map.next_key::<String>()? {
                    if !seen.insert(key.clone()) {
                        return Err(serde::de::Error::custom(format!("names the key \"{key}\" twice in one object: only one can be meant; remove the other")));
                    }
                    map.next_value::<NoDuplicateKeys>()?;
                }
                Ok(NoDuplicateKeys)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> std::result::Result<Self::Value, A::Error> {
                while seq.next_element::<NoDuplicateKeys>()?.is_some() {}
                Ok(NoDuplicateKeys)
            }
            fn visit_bool<E>(self, _: bool) -> std::result::Result<Self::Value, E> {
                Ok(NoDuplicateKeys)
            }
            fn visit_i64<E>(self, _: i64) -> std::result::Result<Self::Value, E> {
                Ok(NoDuplicateKeys)
            }
            fn visit_u64<E>(self, _: u64) -> std::result::Result<Self::Value, E> {
                Ok(NoDuplicateKeys)
            }
            fn visit_f64<E>(self, _: f64) -> std::result::Result<Self::Value, E> {
                Ok(NoDuplicateKeys)
            }
            fn visit_str<E>(self, _: &str) -> std::result::Result<Self::Value, E> {
                Ok(NoDuplicateKeys)
            }
            fn visit_unit<E>(self) -> std::result::Result<Self::Value, E> {
                Ok(NoDuplicateKeys)
            }
        }
        d.deserialize_any(Visit)
    }
}
