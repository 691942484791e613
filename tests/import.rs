//! Importers: good files of every format, and bad files that must give clear errors.

mod common;

use base64::Engine;
use swarf::geom::{DVec3, Tolerances};
use swarf::mesh::import::{read_mesh, read_mesh_auto, ImportError, MeshFormat};
use swarf::mesh::placement::{PartSetup, Placement, UpAxis};
use swarf::mesh::sample::demo_part;

const TOL: Tolerances = Tolerances::DEFAULT;

fn ascii_stl(tris: &[[[f32; 3]; 3]]) -> String {
    let mut s = String::from("solid test\n");
    for t in tris {
        s.push_str("facet normal 0 0 1\nouter loop\n");
        for v in t {
            s.push_str(&format!("vertex {} {} {}\n", v[0], v[1], v[2]));
        }
        s.push_str("endloop\nendfacet\n");
    }
    s.push_str("endsolid test\n");
    s
}

#[test]
fn binary_stl_round_trip_welds_vertices() {
    let part = demo_part();
    let bytes = part.to_binary_stl();
    let back = read_mesh_auto(&bytes, Some("demo.stl"), &TOL).unwrap();
    assert_eq!(back.faces.len(), part.faces.len());
    assert_eq!(back.vertices.len(), part.vertices.len(), "shared vertices are welded");
    let (a, b) = (part.bounds(), back.bounds());
    assert!((a.min - b.min).abs().max_element() < 1e-4 && (a.max - b.max).abs().max_element() < 1e-4);
}

#[test]
fn ascii_stl_is_read() {
    let text = ascii_stl(&[[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]], [[1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]]);
    let mesh = read_mesh_auto(text.as_bytes(), Some("a.stl"), &TOL).unwrap();
    assert_eq!((mesh.faces.len(), mesh.vertices.len()), (2, 4));
}

#[test]
fn truncated_binary_stl_says_so() {
    let bytes = demo_part().to_binary_stl();
    let cut = &bytes[..bytes.len() - 17];
    match read_mesh_auto(cut, Some("part.stl"), &TOL) {
        Err(ImportError::StlSizeMismatch { announced, actual, .. }) => {
            assert_eq!(announced as usize, demo_part().faces.len());
            assert_eq!(actual as usize, cut.len());
        }
        other => panic!("expected a size mismatch, got {other:?}"),
    }
    let message = read_mesh_auto(cut, Some("part.stl"), &TOL).unwrap_err().to_string();
    assert!(message.contains("truncated"), "{message}");
    // Shorter than a header.
    assert!(matches!(read_mesh_auto(&bytes[..40], Some("p.stl"), &TOL), Err(ImportError::StlSizeMismatch { .. })));
}

#[test]
fn triangle_count_that_does_not_match_the_size_is_refused() {
    let mut bytes = demo_part().to_binary_stl();
    bytes[80..84].copy_from_slice(&7u32.to_le_bytes());
    assert!(matches!(read_mesh_auto(&bytes, Some("p.stl"), &TOL), Err(ImportError::StlSizeMismatch { announced: 7, .. })));
}

#[test]
fn empty_files_and_unknown_formats() {
    assert_eq!(read_mesh_auto(b"", Some("p.stl"), &TOL).unwrap_err(), ImportError::Empty);
    assert_eq!(read_mesh_auto(b"hello", None, &TOL).unwrap_err(), ImportError::UnknownFormat);
    // An STL with a zero triangle count.
    let mut bytes = vec![0u8; 84];
    bytes[..5].copy_from_slice(b"model");
    assert_eq!(read_mesh_auto(&bytes, Some("p.stl"), &TOL).unwrap_err(), ImportError::NoTriangles);
}

#[test]
fn nan_and_infinite_coordinates_are_refused() {
    for bad in ["nan", "inf", "-inf"] {
        let text = ascii_stl(&[[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]]]).replacen("vertex 1 0 0", &format!("vertex 1 {bad} 0"), 1);
        let err = read_mesh_auto(text.as_bytes(), Some("p.stl"), &TOL).unwrap_err();
        assert!(matches!(err, ImportError::NonFinite { triangle: 0, .. }), "{bad}: {err:?}");
    }
    let mut bytes = demo_part().to_binary_stl();
    bytes[84 + 50 * 3 + 16..84 + 50 * 3 + 20].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(matches!(read_mesh_auto(&bytes, Some("p.stl"), &TOL), Err(ImportError::NonFinite { triangle: 3, .. })));
}

#[test]
fn degenerate_triangles_are_dropped_and_counted() {
    let text = ascii_stl(&[
        [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]],
        [[0., 0., 0.], [1., 1., 1.], [2., 2., 2.]], // collinear
        [[5., 5., 5.], [5., 5., 5.], [5., 5., 5.]], // a point
    ]);
    let mesh = read_mesh_auto(text.as_bytes(), Some("p.stl"), &TOL).unwrap();
    assert_eq!((mesh.faces.len(), mesh.dropped_degenerate), (1, 2));
    let all_bad = ascii_stl(&[[[0., 0., 0.], [1., 1., 1.], [2., 2., 2.]]]);
    assert_eq!(read_mesh_auto(all_bad.as_bytes(), Some("p.stl"), &TOL).unwrap_err(), ImportError::AllDegenerate { count: 1 });
}

/// A glTF with one triangle in an embedded buffer, its node translated by (10, 20, 30).
fn gltf_json(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
        "nodes":[{{"mesh":0,"translation":[10,20,30]}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "buffers":[{{"byteLength":36,"uri":"{uri}"}}]}}"#
    )
}

fn triangle_bytes() -> Vec<u8> {
    [0f32, 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|f| f.to_le_bytes()).collect()
}

#[test]
fn gltf_with_a_data_uri_applies_node_transforms() {
    let uri = format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(triangle_bytes()));
    let mesh = read_mesh_auto(gltf_json(&uri).as_bytes(), Some("t.gltf"), &TOL).unwrap();
    assert_eq!(mesh.faces.len(), 1);
    assert_eq!(mesh.bounds().min, DVec3::new(10.0, 20.0, 30.0));
    assert_eq!(mesh.bounds().max, DVec3::new(11.0, 21.0, 30.0));
}

#[test]
fn gltf_pointing_at_an_external_uri_is_refused_and_nothing_is_fetched() {
    for uri in ["https://example.com/evil.bin", "triangle.bin", "file:///etc/passwd"] {
        let err = read_mesh_auto(gltf_json(uri).as_bytes(), Some("t.gltf"), &TOL).unwrap_err();
        assert_eq!(err, ImportError::ExternalUri(uri.into()));
        assert!(err.to_string().contains("never fetches"));
    }
}

/// A GLB of `json` with `bin` as its binary chunk.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let pad = |mut v: Vec<u8>, fill: u8| {
        while v.len() % 4 != 0 {
            v.push(fill);
        }
        v
    };
    let (j, b) = (pad(json.as_bytes().to_vec(), b' '), pad(bin.to_vec(), 0));
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((12 + 8 + j.len() + 8 + b.len()) as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(j);
    out.extend((b.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(b);
    out
}

#[test]
fn glb_is_read_and_lying_accessors_are_refused() {
    let json = gltf_json("").replace(r#","uri":"""#, "");
    let mesh = read_mesh_auto(&glb(&json, &triangle_bytes()), Some("t.glb"), &TOL).unwrap();
    assert_eq!(mesh.faces.len(), 1);
    // An accessor claiming more vertices than its view holds.
    let lying = json.replace(r#""count":3"#, r#""count":300"#);
    let err = read_mesh_auto(&glb(&lying, &triangle_bytes()), Some("t.glb"), &TOL).unwrap_err();
    assert!(matches!(err, ImportError::Gltf(_)), "{err:?}");
    // A truncated GLB.
    let whole = glb(&json, &triangle_bytes());
    assert!(read_mesh_auto(&whole[..whole.len() - 20], Some("t.glb"), &TOL).is_err());
}

#[test]
fn obj_is_triangulated() {
    let text = "# a quad\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n";
    let mesh = read_mesh_auto(text.as_bytes(), Some("q.obj"), &TOL).unwrap();
    assert_eq!(mesh.faces.len(), 2);
    let bad = "v 0 0 0\nf 1 2 3\n";
    assert!(matches!(read_mesh_auto(bad.as_bytes(), Some("q.obj"), &TOL), Err(ImportError::Truncated(m)) if m.contains("line 2 names vertex 2")));
    assert!(matches!(MeshFormat::detect(None, text.as_bytes()), Some(MeshFormat::Obj)));
}

#[test]
fn inches_and_y_up_are_converted_and_the_part_is_placed() {
    let text = ascii_stl(&[[[0., 0., 0.], [1., 0., 0.], [0., 2., 1.]]]);
    let mut mesh = read_mesh(text.as_bytes(), MeshFormat::Stl, &TOL).unwrap();
    PartSetup { units: swarf::mesh::placement::PartUnits::Inch, up_axis: UpAxis::Y, placement: Placement::Keep, scale: 1.0, rotation: 0 }.apply(&mut mesh);
    let b = mesh.bounds();
    // File Y (0..2 in) becomes Z (0..50.8 mm); file Z (0..1 in) becomes -Y.
    assert!((b.max.z - 50.8).abs() < 1e-9 && (b.min.y + 25.4).abs() < 1e-9 && (b.max.x - 25.4).abs() < 1e-9);
    PartSetup { placement: Placement::CenterTop, ..PartSetup::default() }.apply(&mut mesh);
    let b = mesh.bounds();
    assert!(b.max.z.abs() < 1e-12 && b.center().truncate().length() < 1e-12);
}

#[test]
fn shared_real_parts_load() {
    let cases: &[(&str, usize)] = &[
        ("meshes/ocl_mount_rush.stl", 15_592),
        ("meshes/kiri_pocket-test.stl", 28),
        ("meshes/tm_featuretype.stl", 3_476),
        ("meshes/tm_Duck.glb", 4_212),
        ("meshes/Box.gltf", 12),
        ("meshes/pycam_textbox.stl", 1_444),
        ("meshes/ocl_wheel_in_box.stl", 6_102),
        ("meshes/c3d_rocker-arm.obj", 20_088),
    ];
    for (rel, triangles) in cases {
        let Some(path) = common::shared_data(rel) else { return };
        let bytes = std::fs::read(&path).unwrap();
        let mesh = read_mesh_auto(&bytes, path.file_name().and_then(|n| n.to_str()), &TOL).unwrap_or_else(|e| panic!("{rel}: {e}"));
        assert_eq!(mesh.faces.len() + mesh.dropped_degenerate + mesh.dropped_duplicates, *triangles, "{rel}");
    }
}

#[test]
fn gltf_is_read_in_metres_unless_the_user_says_otherwise_and_any_part_takes_a_scale() {
    use swarf::mesh::placement::{PartSetup, PartUnits, Placement};
    let uri = format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(triangle_bytes()));
    let gltf = read_mesh_auto(gltf_json(&uri).as_bytes(), Some("t.gltf"), &TOL).unwrap();
    assert!(gltf.in_metres);
    let size = |setup: PartSetup, mut mesh: swarf::mesh::Mesh| {
        setup.apply(&mut mesh);
        assert!(!mesh.in_metres, "applied once");
        mesh.bounds().size().x
    };
    let keep = PartSetup { placement: Placement::Keep, ..PartSetup::default() };
    // A 1 m triangle by the specification: 1000 mm.
    assert_eq!(size(keep, gltf.clone()), 1000.0);
    assert_eq!(size(PartSetup { units: PartUnits::Mm, ..keep }, gltf.clone()), 1.0);
    assert_eq!(size(PartSetup { units: PartUnits::Mm, scale: 2.5, ..keep }, gltf.clone()), 2.5);
    // An STL says nothing: millimetres, or metres and a factor when the user says so.
    let stl = read_mesh_auto(ascii_stl(&[[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]]]).as_bytes(), Some("t.stl"), &TOL).unwrap();
    assert!(!stl.in_metres);
    assert_eq!(size(keep, stl.clone()), 1.0);
    assert_eq!(size(PartSetup { units: PartUnits::Metre, scale: 0.5, ..keep }, stl.clone()), 500.0);
    assert_eq!(size(PartSetup { units: PartUnits::Inch, ..keep }, stl), 25.4);
    // Job files name the units as users write them.
    let setup: PartSetup = serde_json::from_str(r#"{"units": "m", "scale": 2}"#).unwrap();
    assert_eq!((setup.units, setup.scale), (PartUnits::Metre, 2.0));
}

#[test]
fn a_part_smaller_than_the_tool_is_named_in_a_warning_and_a_bad_scale_is_refused() {
    use swarf::job::{self, Job};
    use swarf::mesh::placement::PartUnits;
    use swarf::progress::Progress;
    // The sample part read as if its file were in metres and then scaled down a million
    // times: 0.1 mm across, under the φ6 tool.
    let mut job = Job::default();
    job.part.units = PartUnits::Metre;
    job.part.scale = 1e-6;
    let warned = match job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()) {
        Ok(out) => out.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n"),
        Err(e) => e.to_string(),
    };
    assert!(warned.contains("smaller than the φ6 tool T1: is its unit right?"), "{warned}");
    // A part wider than the tool one way and narrower the other is not called smaller (issue
    // 38: "228.60 × 164.71 × 15.88 mm, smaller than the φ180 tool"): the warning says what the
    // tool can do on it. The sample is 90 × 60 mm: a φ70 tool.
    let mut wide = Job::default();
    wide.tools[0].cutter = swarf::cutter::Cutter { flute_length: 80.0, ..swarf::cutter::Cutter::flat(70.0) };
    wide.simulation.verify = false;
    wide.operations.truncate(1);
    let warned = match job::run(&wide, swarf::mesh::sample::demo_part(), &mut Progress::none()) {
        Ok(out) => out.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n"),
        Err(e) => e.to_string(),
    };
    assert!(warned.contains("narrower across than the φ70 tool T1: the tool fits in none of its pockets") && !warned.contains("smaller than"), "{warned}");
    job.part.scale = 0.0;
    let e = job::run(&job, swarf::mesh::sample::demo_part(), &mut Progress::none()).unwrap_err().to_string();
    assert!(e.contains("part.scale must be a positive number"), "{e}");
}

#[test]
fn the_khronos_duck_is_read_in_metres() {
    let Some(path) = common::shared_data("meshes/tm_Duck.glb") else { return };
    let mut mesh = read_mesh_auto(&std::fs::read(&path).unwrap(), Some("tm_Duck.glb"), &TOL).unwrap();
    PartSetup::default().apply(&mut mesh);
    let size = mesh.bounds().size();
    // The Duck is 1.7 units long in its file: 1.7 m by glTF's specification.
    assert!(size.x > 1000.0 && size.x < 2500.0, "{size}");
}

/// A file that ends early is an error in every format, naming where it ends: an ASCII STL cut
/// inside a facet or after its last facet (no endsolid), an OBJ cut mid-number (its last line
/// still parses) or cut and joined (a face naming a vertex not yet read), a glTF whose JSON or
/// buffer stops short, a GLB shorter than its header says. Cut in half with `head -c`, an ASCII
/// STL once loaded as half its triangles and was machined without a word.
#[test]
fn a_file_that_ends_early_is_refused_in_every_format_with_where_it_ends() {
    let truncated = |bytes: &[u8], name: &str| match read_mesh_auto(bytes, Some(name), &TOL) {
        Err(ImportError::Truncated(m)) => m,
        other => panic!("{name} cut at {} bytes: {other:?}", bytes.len()),
    };
    let tris: Vec<[[f32; 3]; 3]> = (0..40).map(|k| [[k as f32, 0., 0.], [k as f32 + 1., 0., 0.], [k as f32, 1., 0.5]]).collect();
    let stl = ascii_stl(&tris);
    // Cut anywhere before its last line: inside a facet, or between facets.
    for cut in [stl.len() / 2, stl.len() / 3 + 7, stl.rfind("endfacet").unwrap() + 9, stl.rfind("endsolid").unwrap()] {
        let m = truncated(&stl.as_bytes()[..cut], "half.stl");
        assert!(m.contains("ASCII STL ends") && m.contains("line"), "{m}");
    }
    assert!(read_mesh_auto(stl.as_bytes(), Some("whole.stl"), &TOL).is_ok());

    let mut obj = String::new();
    for k in 0..30 {
        obj += &format!("v {k}.125 0.5 1.75\nv {k}.5 1.25 0.5\nv {k}.75 0.25 2.5\n");
    }
    for k in 0..30 {
        obj += &format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3);
    }
    assert!(read_mesh_auto(obj.as_bytes(), Some("whole.obj"), &TOL).is_ok());
    // Cut mid-number in a vertex and in a face: the last line still parses.
    for cut in [obj.find("v 12.5 1.2").unwrap() + 10, obj.len() - 2] {
        let m = truncated(&obj.as_bytes()[..cut], "cut.obj");
        assert!(m.contains("has no line end"), "{m}");
    }
    // Cut and joined: the faces name vertices that never came.
    let joined = format!("{}{}", &obj[..obj.find("v 20.").unwrap()], &obj[obj.find("f 1 2 3").unwrap()..]);
    let m = truncated(joined.as_bytes(), "joined.obj");
    assert!(m.contains("names vertex 61") && m.contains("60 vertices"), "{m}");

    let gltf = gltf_json(&format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(triangle_bytes())));
    assert!(read_mesh_auto(gltf.as_bytes(), Some("whole.gltf"), &TOL).is_ok());
    let m = truncated(&gltf.as_bytes()[..gltf.len() * 2 / 3], "cut.gltf");
    assert!(m.contains("JSON ends at line"), "{m}");
}

/// A part whose surface has holes is named in a warning with how many open edges and where:
/// a cutter goes down through a hole. A closed part, a relief open only along its sides, and a
/// part exported with its seams as coincident rings (as tm_featuretype is) get none.
#[test]
fn a_part_with_holes_in_its_surface_is_warned_of() {
    use swarf::job::part_warnings;
    let whole = demo_part();
    assert!(part_warnings(&whole).is_empty());
    // Three triangles of the dome taken out.
    let mut holed = whole.clone();
    let top: Vec<usize> = (0..holed.faces.len()).filter(|&f| holed.triangle(f).normal().is_some_and(|n| n.z > 0.5)).collect();
    for f in [top[2000], top[2001], top[4000]].into_iter().rev() {
        holed.faces.remove(f);
    }
    let w = part_warnings(&holed);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].count, 7, "{w:?}"); // 4 edges around the two neighbours, 3 around the lone one
    assert!(w[0].message.starts_with("7 edges of the part's surface border one triangle only") && w[0].message.contains("at X"), "{}", w[0].message);
    assert_eq!(w[0].places.len(), 7);
    // The same part says the same, places and order, every time it is read.
    for _ in 0..4 {
        assert_eq!(part_warnings(&holed)[0].places, w[0].places);
    }
    // A box with one triangle of its top missing: every corner of the hole lies on the
    // outline's rim, and it is a hole all the same.
    let v = |i: usize| DVec3::new((i & 1) as f64 * 30.0, ((i >> 1) & 1) as f64 * 20.0, ((i >> 2) & 1) as f64 * 10.0);
    let faces = [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]];
    let boxed = |skip: usize| common::mesh(faces.iter().enumerate().filter(|&(k, _)| k != skip).map(|(_, f)| f.map(v)).collect());
    assert!(part_warnings(&boxed(99)).is_empty());
    assert_eq!(part_warnings(&boxed(2))[0].count, 3);
    // A relief (a surface open along its sides) is not holed.
    assert!(part_warnings(&common::plane(10.0, 0.0, 0.1, 0.2)).is_empty());
    assert!(part_warnings(&common::faceted_terrain(7, 2.0, 0.3)).is_empty());
    if let Some(path) = common::shared_data("meshes/tm_featuretype.stl") {
        let mesh = read_mesh_auto(&std::fs::read(path).unwrap(), Some("featuretype.stl"), &TOL).unwrap();
        assert!(part_warnings(&mesh).is_empty());
    }
    // OpenCAMLib's Mount Rushmore has gaps around the heads and open eyes (trimesh counts 862
    // open edges too), and 407 triangles that repeat another, corners and orientation (trimesh
    // finds the same 407): read once, with a note.
    if let Some(path) = common::shared_data("meshes/ocl_mount_rush.stl") {
        let mesh = read_mesh_auto(&std::fs::read(path).unwrap(), Some("mount_rush.stl"), &TOL).unwrap();
        assert_eq!(mesh.dropped_duplicates, 407);
        let w = part_warnings(&mesh);
        assert!(w.len() == 2 && w[0].message.starts_with("407 triangles were copies") && w[1].count > 500, "{w:?}");
        // Hundreds of holes: the places named are the same every time.
        for _ in 0..4 {
            assert_eq!(part_warnings(&mesh)[1].message, w[1].message);
        }
    }
}

/// Any of ±X, ±Y, ±Z can be the file's up axis, and the part turns about Z in quarter turns:
/// each a turn, never a mirror (a part drawn Y-up with its cavity facing −Y is machined from the
/// cavity's side, not its back).
#[test]
fn any_axis_can_point_up_and_the_part_turns_about_z() {
    use swarf::mesh::placement::PartUnits;
    let part = demo_part();
    let volume = |m: &swarf::mesh::Mesh| m.triangles().map(|t| t.a.dot(t.b.cross(t.c))).sum::<f64>() / 6.0;
    let v0 = volume(&part);
    for (up, file_up) in [(UpAxis::Z, DVec3::Z), (UpAxis::Y, DVec3::Y), (UpAxis::X, DVec3::X), (UpAxis::MinusZ, -DVec3::Z), (UpAxis::MinusY, -DVec3::Y), (UpAxis::MinusX, -DVec3::X)] {
        for rotation in [0, 90, 180, 270] {
            let setup = PartSetup { units: PartUnits::Mm, up_axis: up, rotation, placement: Placement::Keep, scale: 1.0 };
            let mut m = part.clone();
            setup.apply(&mut m);
            // The file's up direction points along +Z, and nothing is mirrored.
            let turned = {
                let mut probe = swarf::mesh::Mesh { vertices: vec![file_up], ..Default::default() };
                setup.apply(&mut probe);
                probe.vertices[0]
            };
            assert!((turned - DVec3::Z).length() < 1e-12, "{up:?} {rotation}: {turned}");
            assert!((volume(&m) - v0).abs() < 1e-6 * v0.abs(), "{up:?} {rotation}: mirrored");
        }
    }
    // A quarter turn takes +X to +Y.
    let mut probe = swarf::mesh::Mesh { vertices: vec![DVec3::X], ..Default::default() };
    PartSetup { rotation: 90, placement: Placement::Keep, ..PartSetup::default() }.apply(&mut probe);
    assert!((probe.vertices[0] - DVec3::Y).length() < 1e-12);
    // Up axes read from job files by their names.
    let setup: PartSetup = serde_json::from_str(r#"{"upAxis": "-y", "rotation": 270}"#).unwrap();
    assert_eq!((setup.up_axis, setup.rotation), (UpAxis::MinusY, 270));
}

/// Issue 56: a scene that places its nodes over and over (20 nodes, each listing the next twice:
/// 2^20 instances, which once asked 5.4 GB) is refused at once, saying so; a few such levels read.
#[test]
fn a_gltf_scene_placing_its_nodes_a_million_times_is_refused() {
    let uri = format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(triangle_bytes()));
    let chain = |levels: usize| {
        let nodes: Vec<String> = (0..levels).map(|k| if k + 1 < levels { format!(r#"{{"children":[{},{}],"translation":[{k},0,0]}}"#, k + 1, k + 1) } else { r#"{"mesh":0}"#.to_string() }).collect();
        gltf_json(&uri).replace(r#""nodes":[{"mesh":0,"translation":[10,20,30]}]"#, &format!(r#""nodes":[{}]"#, nodes.join(",")))
    };
    let (e, took) = common::cpu_timed(|| read_mesh_auto(chain(21).as_bytes(), Some("t.gltf"), &TOL).unwrap_err().to_string());
    assert!(e.contains("places its nodes more than 100000 times"), "{e}");
    assert!(took < 5.0, "{took:.2} s of CPU");
    // Two levels: the triangle placed twice over (four instances, one place) reads.
    assert!(read_mesh_auto(chain(3).as_bytes(), Some("t.gltf"), &TOL).is_ok());
}

/// Issue 56: an OBJ face of 100,000 corners (a disc's cap) is triangulated as a strip across it,
/// not a fan of slivers from one corner (with which every node of a z-map met every triangle):
/// the triangles cover the cap once, turn as the face does, and none spans more than a sliver of
/// it in both directions.
#[test]
fn an_obj_face_of_100000_corners_is_a_strip_of_thin_bands() {
    let n = 100_000;
    let mut obj = String::new();
    for k in 0..n {
        let t = std::f64::consts::TAU * k as f64 / n as f64;
        obj += &format!("v {:.9} {:.9} 0\n", 40.0 * t.cos(), 40.0 * t.sin());
    }
    obj += "v 0 0 -5\nf";
    for k in 0..n {
        obj += &format!(" {}", k + 1);
    }
    obj += "\nf 1 2 100001\n";
    let mesh = read_mesh_auto(obj.as_bytes(), Some("cap.obj"), &TOL).unwrap();
    let cap: Vec<[DVec3; 3]> = mesh.faces.iter().map(|f| f.map(|i| mesh.vertices[i as usize])).filter(|t| t.iter().all(|p| p.z == 0.0)).collect();
    assert_eq!(cap.len() + mesh.dropped_degenerate, n - 2);
    let area: f64 = cap.iter().map(|[a, b, c]| (*b - *a).cross(*c - *a).z * 0.5).sum();
    let polygon = 0.5 * n as f64 * 1600.0 * (std::f64::consts::TAU / n as f64).sin();
    assert!((area - polygon).abs() < 1e-6 * polygon, "{area} vs {polygon}");
    assert!(cap.iter().all(|[a, b, c]| (*b - *a).cross(*c - *a).z >= 0.0), "every triangle turns as the face");
    // Thin bands: no triangle's box is more than a few percent of the cap's in both directions.
    let fat = cap.iter().filter(|t| {
        let (lo, hi) = t.iter().fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        (hi.x - lo.x).min(hi.y - lo.y) > 4.0
    });
    assert_eq!(fat.count(), 0);
    // A face of four corners is still the fan tobj makes (two triangles from its first).
    let quad = read_mesh_auto(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 2 5\n", Some("q.obj"), &TOL).unwrap();
    assert_eq!(quad.faces.len(), 3);
}

/// Issue 56: a glTF triangle fan over a flat convex polygon of 100,000 corners (a disc's cap,
/// from a corner of it or from its centre) is cut as a strip of thin bands, as an OBJ face is,
/// covering the same area; a fan over any other shape (a star round its hub, a cone) is kept
/// triangle for triangle as the file gives it.
#[test]
fn a_gltf_fan_over_a_flat_convex_polygon_is_a_strip_and_any_other_fan_is_kept() {
    let read_fan = |corners: &[[f32; 3]]| {
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
            "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"mode":6}}]}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3"}}],
            "bufferViews":[{{"buffer":0,"byteLength":{len}}}],"buffers":[{{"byteLength":{len}}}]}}"#,
            n = corners.len(),
            len = corners.len() * 12
        );
        let bin: Vec<u8> = corners.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        let mut mesh = read_mesh_auto(&glb(&json, &bin), Some("fan.glb"), &TOL).unwrap();
        // In the file's own numbers (metres: scaling comes with the part's setup).
        let triangles: Vec<[DVec3; 3]> = mesh.faces.drain(..).map(|f| f.map(|i| mesh.vertices[i as usize])).collect();
        triangles
    };
    let area = |ts: &[[DVec3; 3]]| ts.iter().map(|[a, b, c]| (*b - *a).cross(*c - *a).length() * 0.5).sum::<f64>();
    let widest = |ts: &[[DVec3; 3]]| {
        ts.iter()
            .map(|t| {
                let (lo, hi) = t.iter().fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
                (hi.x - lo.x).min(hi.y - lo.y)
            })
            .fold(0.0, f64::max)
    };
    let n = 100_000;
    let rim: Vec<[f32; 3]> = (0..n).map(|k| std::f64::consts::TAU * k as f64 / n as f64).map(|t| [(0.04 * t.cos()) as f32, (0.04 * t.sin()) as f32, 0.01]).collect();
    let polygon = 0.5 * n as f64 * 0.04f64.powi(2) * (std::f64::consts::TAU / n as f64).sin();
    // From a corner (f32 corners wobble off the circle by more than its turn between them).
    let from_corner = read_fan(&rim);
    // From the centre, the rim closed on its first corner.
    let hub: Vec<[f32; 3]> = std::iter::once([0.0, 0.0, 0.01]).chain(rim.iter().copied()).chain(std::iter::once(rim[0])).collect();
    let from_hub = read_fan(&hub);
    for (what, ts) in [("corner", &from_corner), ("hub", &from_hub)] {
        assert!((area(ts) - polygon).abs() < 1e-6 * polygon, "{what}: {} vs {polygon}", area(ts));
        assert!(ts.len() <= n - 2, "{what}: {} triangles", ts.len());
        assert!(widest(ts) < 0.004, "{what}: a triangle {} m wide both ways", widest(ts));
        assert!(ts.iter().all(|[a, b, c]| (*b - *a).cross(*c - *a).z >= 0.0), "{what}: every triangle turns as the fan");
    }
    // A star of 40 points round its hub, and a cone: each triangle as given.
    let star: Vec<[f32; 3]> = std::iter::once([0.0, 0.0, 0.0])
        .chain((0..=80).map(|k| {
            let (t, r) = (std::f64::consts::TAU * k as f64 / 80.0, if k % 2 == 0 { 0.04 } else { 0.02 });
            [(r * t.cos()) as f32, (r * t.sin()) as f32, 0.0]
        }))
        .collect();
    let cone: Vec<[f32; 3]> = std::iter::once([0.0, 0.0, 0.03]).chain(rim.iter().step_by(1000).copied()).collect();
    for (what, fan) in [("star", &star), ("cone", &cone)] {
        let ts = read_fan(fan);
        let given: Vec<[DVec3; 3]> = fan[1..].windows(2).map(|w| [fan[0], w[0], w[1]].map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))).collect();
        assert_eq!(ts.len(), given.len(), "{what}");
        assert!((area(&ts) - area(&given)).abs() < 1e-9 * area(&given), "{what}");
        assert!(widest(&ts) > 0.01, "{what}: the file's own triangles reach across");
    }
}

/// Issue 62: a part read in the wrong unit is said at load, beside its size, with the unit
/// that would make it a part: the sample drawn in inches (3.5 mm across as millimetres), in
/// metres (0.09 mm), and at its own size nothing.
#[test]
fn a_part_in_the_wrong_unit_is_said_at_load_with_its_likely_unit() {
    use swarf::mesh::placement::PartUnits;
    let part = swarf::mesh::sample::demo_part();
    let across = |m: &swarf::mesh::Mesh| {
        let s = m.bounds().size();
        s.x.max(s.y).max(s.z)
    };
    let full = across(&part);
    let said = |k: f64| {
        let mut m = part.clone();
        for v in &mut m.vertices {
            *v /= k;
        }
        swarf::job::part_warnings(&m).iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n")
    };
    let inch = said(25.4);
    assert!(inch.contains(&format!("Read in inches it would be {} mm across (Units of the file: inch", full.round())), "{inch}");
    let metre = said(1000.0);
    assert!(metre.contains(&format!("Read in metres it would be {} mm across (Units of the file: metres", full.round())), "{metre}");
    assert!(!said(1.0).contains("Units of the file"));
    // A job says it of the part as it places it: read in inches as the file is, nothing; read
    // as millimetres, the same words.
    let mut small = part.clone();
    for v in &mut small.vertices {
        *v /= 25.4;
    }
    let ran = |units: PartUnits| {
        let mut job = swarf::job::Job::default();
        job.part.units = units;
        job.operations.retain(|o| matches!(o, swarf::job::Operation::FinishRaster(_)));
        job.simulation.verify = false;
        match swarf::job::run(&job, small.clone(), &mut swarf::progress::Progress::none()) {
            Ok(out) => out.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>().join("\n"),
            Err(e) => e.to_string(),
        }
    };
    assert!(!ran(PartUnits::Inch).contains("Units of the file"), "{}", ran(PartUnits::Inch));
    assert!(ran(PartUnits::Auto).contains("Read in inches it would be"), "{}", ran(PartUnits::Auto));
    // The unit that makes it a part, or none where none does.
    assert_eq!(PartUnits::likely(1.69).map(|(u, _, mm)| (u, (mm * 10.0).round() / 10.0)), Some(("inches", 42.9)));
    assert_eq!(PartUnits::likely(0.23).map(|(u, _, mm)| (u, mm.round())), Some(("metres", 230.0)));
    assert_eq!(PartUnits::likely(50.0), None);
    assert_eq!(PartUnits::likely(0.0001), None);
    assert_eq!(PartUnits::likely(100_000.0).map(|(u, c, mm)| (u, c, mm.round())), Some(("millimetres", "mm", 100.0)));
}
