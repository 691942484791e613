//! Project files (`.swarf.json`): a job and the part or drawing it works on, in one file the
//! page saves and opens and the CLI runs (`swarf run project.swarf.json -o out.nc`). The part
//! is embedded (base64) or named, to be found beside the project file. Versioned; a field this
//! swarf does not know is named and refused, as in job files.

use base64::Engine as _;
use serde::{Deserialize, Serialize};

use super::schema::Job;
use crate::error::{Error, Result};

/// The value of a project file's `format` field.
pub const PROJECT_FORMAT: &str = "swarf project";

/// The project file format this swarf writes and reads (files from a newer one are refused).
pub const PROJECT_VERSION: u32 = 1;

/// The part or drawing of a project.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
pub struct ProjectFile {
    /// The file's name, with its extension (it tells the format).
    pub name: String,
    /// The file's bytes in base64; none: the file lies beside the project under `name`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub data: Option<String>,
}

/// A project: a job and its part or drawing.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct Project {
    pub format: String,
    pub version: u32,
    pub job: Job,
    pub workpiece: ProjectFile,
}

impl Project {
    /// A project with the part or drawing embedded.
    pub fn embedded(job: Job, name: &str, bytes: &[u8]) -> Project {
        let data = Some(base64::engine::general_purpose::STANDARD.encode(bytes));
        Project { format: PROJECT_FORMAT.into(), version: PROJECT_VERSION, job, workpiece: ProjectFile { name: name.into(), data } }
    }

    /// A project naming its part or drawing, which stays a file of its own.
    pub fn referencing(job: Job, name: &str) -> Project {
        Project { format: PROJECT_FORMAT.into(), version: PROJECT_VERSION, job, workpiece: ProjectFile { name: name.into(), data: None } }
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a project is plain data")
    }

    /// Whether `text` looks like a project file rather than a job file.
    pub fn is_project(text: &str) -> bool {
        serde_json::from_str::<serde_json::Value>(text).ok().and_then(|v| v.get("format").and_then(|f| f.as_str().map(|f| f == PROJECT_FORMAT))).unwrap_or(false)
    }

    /// Reads a project; errors name the field (`job.operations[0].stepover`, `workpiece.data`).
    pub fn from_json(text: &str) -> Result<Project> {
        let bad = Error::Project;
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| bad(format!("not JSON: {e}")))?;
        let Some(object) = value.as_object() else { return Err(bad("not a JSON object".into())) };
        const FIELDS: [&str; 4] = ["format", "version", "job", "workpiece"];
        let unknown: Vec<&str> = object.keys().map(String::as_str).filter(|k| !FIELDS.contains(k)).collect();
        if !unknown.is_empty() {
            return Err(bad(format!("unknown field{}: {} (a project has {})", if unknown.len() == 1 { "" } else { "s" }, unknown.join(", "), FIELDS.join(", "))));
        }
        if object.get("format").and_then(|f| f.as_str()) != Some(PROJECT_FORMAT) {
            return Err(bad(format!("format must be \"{PROJECT_FORMAT}\" (is this a job file? `swarf run job.json part.stl` runs those)")));
        }
        let version = object.get("version").and_then(|v| v.as_u64()).ok_or_else(|| bad("version must be a whole number".into()))?;
        if version > PROJECT_VERSION as u64 {
            return Err(bad(format!("version {version}; this swarf reads versions up to {PROJECT_VERSION} (a newer swarf wrote it)")));
        }
        let job = Job::from_value(object.get("job").ok_or_else(|| bad("job is missing".into()))?).map_err(|e| match e {
            Error::Input(m) => bad(format!("job.{m}")),
            other => other,
        })?;
        let workpiece: ProjectFile =
            crate::error::read_value(object.get("workpiece").ok_or_else(|| bad("workpiece is missing".into()))?).map_err(|e| bad(format!("workpiece.{}: {}", e.path(), e.inner())))?;
        if workpiece.name.trim().is_empty() {
            return Err(bad("workpiece.name must name the part's or drawing's file".into()));
        }
        Ok(Project { format: PROJECT_FORMAT.into(), version: version as u32, job, workpiece })
    }

    /// The part's or drawing's bytes: embedded, else read by `read_beside` (given the name).
    pub fn workpiece_bytes(&self, read_beside: impl FnOnce(&str) -> std::io::Result<Vec<u8>>) -> Result<Vec<u8>> {
        match &self.workpiece.data {
            Some(data) => base64::engine::general_purpose::STANDARD.decode(data.trim()).map_err(|e| Error::Project(format!("workpiece.data is not base64: {e}"))),
            None => read_beside(&self.workpiece.name).map_err(|e| Error::Project(format!("its part {} (named, not embedded) could not be read: {e}", self.workpiece.name))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projects_read_back_and_bad_ones_are_named() {
        let p = Project::embedded(Job::default(), "demo.stl", b"solid x\nendsolid x\n");
        let text = p.to_json();
        assert!(Project::is_project(&text) && !Project::is_project(&serde_json::to_string(&Job::default()).unwrap()));
        let back = Project::from_json(&text).unwrap();
        assert_eq!(back, p);
        assert_eq!(back.workpiece_bytes(|_| unreachable!()).unwrap(), b"solid x\nendsolid x\n");
        let named = Project::referencing(Job::default(), "demo.stl");
        assert_eq!(Project::from_json(&named.to_json()).unwrap().workpiece_bytes(|n| Ok(n.as_bytes().to_vec())).unwrap(), b"demo.stl");
        let edit = |f: &dyn Fn(&mut serde_json::Value)| {
            let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
            f(&mut v);
            Project::from_json(&v.to_string()).unwrap_err().to_string()
        };
        assert!(edit(&|v| v["workpeice"] = 1.into()).contains("unknown field: workpeice"));
        assert!(edit(&|v| v["version"] = 9.into()).contains("version 9"));
        assert!(edit(&|v| v["format"] = "x".into()).contains("format must be"));
        assert!(edit(&|v| v["job"]["operations"][0]["stepOver"] = 1.into()).contains("job.unknown field: operations[0].stepOver"));
        assert!(edit(&|v| v["workpiece"]["size"] = 3.into()).contains("workpiece."));
        let e =
            Project::from_json(&Project { workpiece: ProjectFile { name: "x.stl".into(), data: Some("***".into()) }, ..p.clone() }.to_json()).unwrap().workpiece_bytes(|_| unreachable!()).unwrap_err();
        assert!(e.to_string().contains("not base64"), "{e}");
    }
}
