//! The TypeScript definitions of the job and the other data the page and portals exchange with
//! swarf (`www/types/swarf-types.d.ts`) are generated from the Rust serde types by ts-rs, never
//! written by hand: this test makes them and fails when the file in the tree differs. Run it
//! with `UPDATE_TYPES=1` to write the file anew.

use std::any::TypeId;
use std::collections::BTreeMap;
use std::path::Path;

use swarf::cutting::{CuttingData, MaterialChoice};
use swarf::holes::Hole;
use swarf::job::project::Project;
use swarf::job::Problem;
use swarf::machining::form::OperationForm;
use swarf::post::{CycleTime, Post};
use swarf::tool::library::{Imported, LibraryFormat};
use swarf::view::{DrawingView, EdgeView, ReportView, Reposted, SetupView, Summary};
use ts_rs::{Config, TypeVisitor, TS};

const HEAD: &str = "// Generated from swarf's Rust types by ts-rs (tests/typescript.rs): do not edit.\n// UPDATE_TYPES=1 cargo test --test typescript writes it anew.\n\n";

fn generate() -> String {
    let dir = std::env::temp_dir().join(format!("swarf-ts-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let cfg = Config::new().with_large_int("number").with_out_dir(&dir);
    Project::export_all(&cfg).unwrap();
    Post::export_all(&cfg).unwrap();
    CycleTime::export_all(&cfg).unwrap();
    Summary::export_all(&cfg).unwrap();
    DrawingView::export_all(&cfg).unwrap();
    ReportView::export_all(&cfg).unwrap();
    Reposted::export_all(&cfg).unwrap();
    Problem::export_all(&cfg).unwrap();
    Hole::export_all(&cfg).unwrap();
    EdgeView::export_all(&cfg).unwrap();
    SetupView::export_all(&cfg).unwrap();
    OperationForm::export_all(&cfg).unwrap();
    CuttingData::export_all(&cfg).unwrap();
    MaterialChoice::export_all(&cfg).unwrap();
    Imported::export_all(&cfg).unwrap();
    LibraryFormat::export_all(&cfg).unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let mut out = HEAD.to_owned();
    for f in files {
        // One file: the imports between the generated files are not needed.
        let text = std::fs::read_to_string(&f).unwrap();
        for line in text.lines().filter(|l| !l.starts_with("import type") && !l.starts_with("// This file was generated")) {
            out.push_str(line);
            out.push('\n');
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    out.replace("\n\n\n", "\n\n")
}

/// Every Rust type behind the exported ones, by the name it takes in TypeScript.
#[derive(Default)]
struct Names(BTreeMap<String, Vec<(TypeId, &'static str)>>);

impl TypeVisitor for Names {
    fn visit<T: TS + 'static + ?Sized>(&mut self) {
        if T::output_path().is_none() {
            return;
        }
        let rust = (TypeId::of::<T>(), std::any::type_name::<T>());
        let seen = self.0.entry(T::ident(&Config::new())).or_default();
        if !seen.contains(&rust) {
            seen.push(rust);
            T::visit_dependencies(self);
        }
    }
}

#[test]
fn no_two_rust_types_share_a_typescript_name() {
    // Two types of one name are written to one file, and which is kept depends on the order
    // ts-rs happens to visit them in: the generated file would change from run to run.
    let mut names = Names::default();
    names.visit::<Project>();
    names.visit::<Post>();
    names.visit::<CycleTime>();
    names.visit::<Summary>();
    names.visit::<DrawingView>();
    names.visit::<ReportView>();
    names.visit::<Reposted>();
    names.visit::<Problem>();
    names.visit::<Hole>();
    names.visit::<EdgeView>();
    names.visit::<SetupView>();
    names.visit::<OperationForm>();
    names.visit::<CuttingData>();
    names.visit::<MaterialChoice>();
    names.visit::<Imported>();
    names.visit::<LibraryFormat>();
    assert!(names.0.len() > 20, "{:?}", names.0.keys());
    let twice: Vec<_> = names.0.values().filter(|v| v.len() > 1).collect();
    assert!(twice.is_empty(), "types sharing a TypeScript name (give one #[ts(rename)]): {twice:?}");
}

#[test]
fn the_typescript_definitions_match_the_rust_types() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("www/types/swarf-types.d.ts");
    let made = generate();
    for name in [
        "export type Job = ",
        "export type Operation = ",
        "export type Post = ",
        "export type Tool = ",
        "export type Project = ",
        "export type Summary = ",
        "export type OperationReport = ",
        "export type Warning = ",
    ] {
        assert!(made.contains(name), "{name} missing");
    }
    // Fields as the JSON has them: camelCase, the operation's kind as its tag.
    assert!(made.contains("spindleRpm: number") && made.contains("\"kind\": \"roughOctree\""), "{made}");
    // The per-operation results are typed (their seconds once came out `unknown`).
    assert!(!made.contains("unknown"), "{made}");
    if std::env::var_os("UPDATE_TYPES").is_some() {
        std::fs::write(&path, &made).unwrap();
    }
    let kept = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(kept == made, "www/types/swarf-types.d.ts is out of date: run UPDATE_TYPES=1 cargo test --test typescript");
}
