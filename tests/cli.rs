//! The `swarf` command line, run as a user would.

use std::process::Command;

use swarf::cutter::Cutter;
use swarf::geom::{DVec2, Tolerances};
use swarf::mesh::import::read_mesh_auto;
use swarf::zmap::{cl_exact::cl_exact_at, io::from_raw};

fn swarf(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_swarf")).args(args).output().unwrap()
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn demo_then_run_then_zmap() {
    let dir = temp("demo");
    let out = swarf(&["demo", "-o", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for f in ["demo.stl", "demo.json", "demo.ngc"] {
        assert!(dir.join(f).metadata().unwrap().len() > 100, "{f}");
    }
    assert!(String::from_utf8_lossy(&out.stderr).contains("min on the machine"));

    // The job file drives `run` to the same program.
    let ngc = dir.join("again.ngc");
    let out = swarf(&["run", dir.join("demo.json").to_str().unwrap(), dir.join("demo.stl").to_str().unwrap(), "-o", ngc.to_str().unwrap(), "-q"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(std::fs::read(&ngc).unwrap() == std::fs::read(dir.join("demo.ngc")).unwrap(), "run and demo made different programs");

    // CL heights as CSV, point by point equal to the exact drop.
    let csv = dir.join("cl.csv");
    let stl = dir.join("demo.stl");
    let out = swarf(&["zmap", stl.to_str().unwrap(), "--shape", "bull-nose", "--diameter", "8", "--corner", "2", "--grid", "2", "-o", csv.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mesh = read_mesh_auto(&std::fs::read(&stl).unwrap(), Some("demo.stl"), &Tolerances::DEFAULT).unwrap();
    let profile = Cutter::bull_nose(8.0, 2.0).profile();
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z"));
    let rows: Vec<[f64; 3]> = lines.map(|l| {
        let v: Vec<f64> = l.split(',').map(|w| w.parse().unwrap()).collect();
        [v[0], v[1], v[2]]
    }).collect();
    assert!(rows.len() > 1000);
    for row in rows.iter().step_by(37) {
        let exact = cl_exact_at(&mesh, &profile, DVec2::new(row[0], row[1]), &Tolerances::DEFAULT).unwrap_or(mesh.bounds().min.z).max(mesh.bounds().min.z);
        assert!((row[2] - exact).abs() < 2e-6, "{row:?} vs {exact}"); // CSV keeps 6 decimals
    }

    // The raw format reads back to the same grid.
    let raw = dir.join("cl.zmap");
    assert!(swarf(&["zmap", stl.to_str().unwrap(), "--grid", "2", "--format", "raw", "-o", raw.to_str().unwrap()]).status.success());
    let field = from_raw(&std::fs::read(&raw).unwrap()).unwrap();
    assert_eq!(field.nx * field.ny, rows.len());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_gives_a_message_and_a_failure_code() {
    let dir = temp("bad");
    let broken = dir.join("broken.stl");
    std::fs::write(&broken, &swarf::mesh::sample::demo_part().to_binary_stl()[..3000]).unwrap();
    let out = swarf(&["zmap", broken.to_str().unwrap(), "-o", dir.join("x.csv").to_str().unwrap()]);
    assert!(!out.status.success());
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(message.contains("broken.stl") && message.contains("truncated"), "{message}");
    assert!(!message.contains("panicked"));

    let job = dir.join("job.json");
    std::fs::write(&job, r#"{"tools":[{"number":1,"shape":"ball","diameter":-3}]}"#).unwrap();
    let out = swarf(&["run", job.to_str().unwrap(), broken.to_str().unwrap()]);
    assert!(!out.status.success());
    let out = swarf(&["zmap", "/nonexistent/part.stl", "-o", "x.csv"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn verify_reads_a_program_and_reports_its_faults() {
    let dir = temp("verify");
    assert!(swarf(&["demo", "-o", dir.to_str().unwrap()]).status.success());
    let (job, part, program) = (dir.join("demo.json"), dir.join("demo.stl"), dir.join("demo.ngc"));
    let arg = |p: &std::path::Path| p.to_str().unwrap().to_owned();
    let ok = swarf(&["verify", &arg(&job), &arg(&part), &arg(&program), "--cell", "0.3"]);
    let text = String::from_utf8_lossy(&ok.stdout);
    assert!(ok.status.success(), "{text}\n{}", String::from_utf8_lossy(&ok.stderr));
    assert!(text.contains("gouges: 0") && text.contains("rapid moves through stock: 0"), "{text}");
    // Someone else's program: a rapid straight through the stock, in inches, then a cut 2 mm
    // into the part's top.
    let foreign = dir.join("foreign.nc");
    std::fs::write(&foreign, "G20 G90 G17\nG0 Z1\nG0 X-2 Y-0.5\nG0 Z-0.3\nG0 X2\nG21 G0 Z20\nG0 X0 Y0\nG1 Z-2 F200\nG0 Z20\nM30\n").unwrap();
    let bad = swarf(&["verify", &arg(&job), &arg(&part), &arg(&foreign), "--cell", "0.3", "--json"]);
    assert!(!bad.status.success());
    let report: serde_json::Value = serde_json::from_slice(&bad.stdout).unwrap();
    assert!(report["rapidCollisionCount"].as_u64().unwrap() >= 1, "{report}");
    assert!(report["gougeCount"].as_u64().unwrap() > 0, "{report}");
    // A program the reader cannot simulate is refused with its line.
    std::fs::write(&foreign, "G0 X0 Y0 Z5\nG81 X1 Y1 Z-1 R1\n").unwrap();
    let refused = swarf(&["verify", &arg(&job), &arg(&part), &arg(&foreign)]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("line 2"));
}
