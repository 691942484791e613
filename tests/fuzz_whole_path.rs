//! The fuzz target `job` (file → part or drawing → a small job with fuzzed settings →
//! program, `fuzz/fuzz_targets/whole_path.rs`) on every input it kept in
//! `tests/fuzz_regressions/job-*.bin`, and on valid files of every format under each operation
//! kind and each of its settings drawn absurd: a program or an error, never a panic.

#[path = "../fuzz/fuzz_targets/whole_path.rs"]
mod whole_path;

#[test]
fn kept_whole_path_inputs_give_a_program_or_an_error() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with("job-") && n.ends_with(".bin")) {
            whole_path::check(&std::fs::read(&path).unwrap());
        }
    }
}

#[test]
fn every_kind_under_every_drawn_setting_gives_a_program_or_an_error() {
    // A small part keeps the runs short: a 20 mm plate with a bump.
    let stl = swarf::mesh::sample::height_field_solid(swarf::geom::DVec2::new(0.0, 0.0), swarf::geom::DVec2::new(20.0, 20.0), 20, 20, 0.0, |x, y| {
        if (x - 10.0).abs() < 4.0 && (y - 10.0).abs() < 4.0 {
            8.0
        } else {
            5.0
        }
    })
    .to_binary_stl();
    let dxf = b"0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n8\n0\n10\n20\n20\n20\n40\n15\n0\nCIRCLE\n8\n0\n10\n20\n20\n20\n40\n4\n0\nCIRCLE\n8\n0\n10\n10\n20\n20\n40\n2.5\n0\nENDSEC\n0\nEOF\n".to_vec();
    let svg = b"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"50mm\" height=\"50mm\" viewBox=\"0 0 50 50\"><rect x=\"5\" y=\"5\" width=\"40\" height=\"30\"/><circle cx=\"25\" cy=\"20\" r=\"5\"/><circle cx=\"12\" cy=\"20\" r=\"2.5\"/></svg>".to_vec();
    // The absurd values, and an ordinary one (indices into `VALUES`).
    let values: Vec<u8> = [1.0, 0.0, -1.0, 1e-9, 1e9, 1e308, f64::NAN, 0.001].iter().map(|v| whole_path::VALUES.iter().position(|w| w.to_bits() == v.to_bits()).unwrap() as u8).collect();
    let mut runs: Vec<Vec<u8>> = Vec::new();
    for (format, file) in [(0u8, &stl), (4, &dxf), (5, &svg)] {
        let drawing = format >= 4;
        let kinds = whole_path::kinds(drawing);
        assert!(kinds.len() >= if drawing { 9 } else { 6 }, "{} kinds work on the {}", kinds.len(), if drawing { "drawing" } else { "part" });
        let run = |head: [u8; whole_path::HEAD]| head.iter().copied().chain(file.iter().copied()).collect::<Vec<u8>>();
        for (kind, op) in kinds.iter().enumerate() {
            let settings = whole_path::settings(op).len();
            assert!(settings > 0, "{op}: no settings found");
            // Each setting in turn drawn absurd, the tool and the job's ordinary (a φ3 tool,
            // margins and sheet of 1 mm); then the tool's diameter and the job's own.
            for field in 0..settings as u8 {
                for &v in &values {
                    runs.push(run([format, kind as u8, 3, field, v, 1, 1]));
                }
            }
            for k in [2, 5, 6] {
                for &v in &values {
                    let mut head = [format, kind as u8, 3, 0, 1, 1, 1];
                    head[k] = v;
                    runs.push(run(head));
                }
            }
        }
    }
    assert!(runs.len() > 1000, "{} runs", runs.len());
    let next = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                while let Some(data) = runs.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed)) {
                    whole_path::check(data);
                }
            });
        }
    });
}
