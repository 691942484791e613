//! The importers on hostile bytes: random data, truncations and byte flips of valid files, and
//! every input the fuzzers (`fuzz/`, `cargo fuzz run stl|gltf|obj`) ever shrank to a failure,
//! kept in `tests/fuzz_regressions/`. Each gives a mesh or an error, never a panic.

mod common;

use proptest::prelude::*;
use swarf::geom::Tolerances;
use swarf::mesh::import::{read_mesh, read_mesh_auto, MeshFormat};
use swarf::mesh::sample::demo_part;

const FORMATS: [MeshFormat; 4] = [MeshFormat::Stl, MeshFormat::Gltf, MeshFormat::Glb, MeshFormat::Obj];

fn check(bytes: &[u8]) {
    for format in FORMATS {
        if let Ok(mesh) = read_mesh(bytes, format, &Tolerances::DEFAULT) {
            assert!(mesh.vertices.iter().all(|v| v.is_finite()));
            assert!(mesh.faces.iter().flatten().all(|&i| (i as usize) < mesh.vertices.len()));
        }
    }
    let _ = read_mesh_auto(bytes, None, &Tolerances::DEFAULT);
}

fn valid_files() -> Vec<Vec<u8>> {
    let stl = demo_part().to_binary_stl();
    let ascii = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n".to_vec();
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\nf 2 4 3\n".to_vec();
    let gltf = br#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}"#.to_vec();
    vec![stl[..84 + 50 * 40].to_vec(), ascii, obj, gltf]
}

/// The inputs kept in `tests/fuzz_regressions/` whose names start with `prefix`.
fn kept(prefix: &str) -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let named = |p: &std::path::Path| p.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with(prefix) && n.ends_with(".bin"));
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).filter(|p| named(p)).collect()
}

#[test]
fn kept_fuzz_failures_do_not_panic() {
    let paths = kept("");
    for path in &paths {
        check(&std::fs::read(path).unwrap());
    }
    assert!(!paths.is_empty(), "the regression corpus is empty");
}

#[test]
fn every_truncation_of_valid_files_is_handled() {
    for file in valid_files() {
        for len in 0..file.len() {
            check(&file[..len]);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]
    #[test]
    fn random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        check(&bytes);
    }

    #[test]
    fn flipped_bytes_of_valid_files(which in 0usize..4, flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8)) {
        let mut file = valid_files().swap_remove(which);
        for (at, value) in flips {
            let i = at.index(file.len());
            file[i] = value;
        }
        check(&file);
    }
}

/// The drawing readers (DXF, SVG) on hostile bytes: every truncation and random byte flips of
/// valid drawings give a drawing with finite coordinates or an error, never a panic. The
/// `drawing` fuzz target (`cargo fuzz run drawing`) does the same at length.
fn check_drawing(bytes: &[u8]) {
    use swarf::drawing::import::read_drawing;
    for name in ["x.dxf", "x.svg"] {
        if let Ok(d) = read_drawing(bytes, Some(name), &Tolerances::DEFAULT) {
            assert!(d.loops.iter().flat_map(|l| &l.path.vertices).all(|v| v.p.is_finite() && v.bulge.is_finite()));
        }
    }
}

fn valid_drawings() -> Vec<Vec<u8>> {
    let svg = br#"<svg xmlns="http://www.w3.org/2000/svg" width="50mm" height="50mm" viewBox="0 0 50 50"><g transform="rotate(10)"><rect x="1" y="1" width="20" height="10" rx="2"/><path d="M30 30 c 5 0 5 5 0 5 q -3 -2 0 -5 a 4 4 0 1 1 -2 2 z"/><ellipse cx="10" cy="30" rx="4" ry="2"/></g></svg>"#;
    vec![swarf::drawing::sample::plate_dxf().into_bytes(), svg.to_vec()]
}

/// What the `drawing` fuzz target kept (`tests/fuzz_regressions/drawing-*.bin`: an SVG whose
/// viewBox puts an ellipse 1e117 mm out, which once fitted arcs for minutes) is answered at
/// once, never with a panic.
#[test]
fn kept_drawing_fuzz_failures_are_answered_at_once() {
    let paths = kept("drawing-");
    for path in &paths {
        let ((), took) = common::cpu_timed(|| check_drawing(&std::fs::read(path).unwrap()));
        assert!(took < 5.0, "{}: {took:.2} s of CPU", path.display());
    }
    assert!(paths.len() >= 2);
}

#[test]
fn every_truncation_of_valid_drawings_is_handled() {
    for file in valid_drawings() {
        for len in (0..file.len()).step_by(3) {
            check_drawing(&file[..len]);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]
    #[test]
    fn flipped_bytes_of_valid_drawings(which in 0usize..2, flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8)) {
        let mut file = valid_drawings().swap_remove(which);
        for (at, value) in flips {
            let i = at.index(file.len());
            file[i] = value;
        }
        check_drawing(&file);
    }
}
