//! The fuzz target `job` (file → part or drawing → a small job with fuzzed settings →
//! program, `fuzz/fuzz_targets/whole_path.rs`) on every input it kept in
//! `tests/fuzz_regressions/job-*.bin`, and on valid files of every format under each setting
//! it draws from: a program or an error, never a panic.

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
fn every_format_under_every_drawn_setting_gives_a_program_or_an_error() {
    // A small part keeps the 576 runs short: a 20 mm plate with a bump.
    let stl = swarf::mesh::sample::height_field_solid(swarf::geom::DVec2::new(0.0, 0.0), swarf::geom::DVec2::new(20.0, 20.0), 20, 20, 0.0, |x, y| {
        if (x - 10.0).abs() < 4.0 && (y - 10.0).abs() < 4.0 {
            8.0
        } else {
            5.0
        }
    })
    .to_binary_stl();
    let dxf = b"0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n8\n0\n10\n20\n20\n20\n40\n15\n0\nENDSEC\n0\nEOF\n".to_vec();
    let svg = b"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"50mm\" height=\"50mm\" viewBox=\"0 0 50 50\"><rect x=\"5\" y=\"5\" width=\"40\" height=\"30\"/></svg>".to_vec();
    for (format, file) in [(0u8, &stl), (4, &dxf), (5, &svg)] {
        for kind in 0..3u8 {
            for setting in 0..16u8 {
                // Each setting in turn absurd, the others ordinary (a φ3 tool, steps of 1).
                for k in 2..6 {
                    let mut head = [format, kind, 3, 1, 1, 1];
                    head[k] = setting;
                    let data: Vec<u8> = head.iter().copied().chain(file.iter().copied()).collect();
                    whole_path::check(&data);
                }
            }
        }
    }
}
