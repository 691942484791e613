//! Seed 000: octree multi-tool roughing against z-level roughing with each tool of its library
//! alone (and the best of them named) and with the largest then the smallest, on the generated
//! mould and the shared parts, the rocker arm of issue 38 among them (`support::job::octree_rows`).
//!
//! Run: `cargo bench --bench octree` (native). The wasm figures: `bash scripts/bench-wasm.sh`.

mod support;

fn main() {
    let origin = std::time::Instant::now();
    let clock = || origin.elapsed().as_secs_f64();
    for row in support::job::octree_rows("mould", &swarf::mesh::sample::octree_mould(1.0), "native", &clock) {
        println!("{row}");
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/meshes");
    // (file, scale, Y up)
    for (file, scale, y_up) in
        [("ocl_mount_rush.stl", 1.0, false), ("ocl_wheel_in_box.stl", 1.0, false), ("tm_featuretype.stl", 25.4, false), ("kiri_pocket-test.stl", 1.0, false), ("c3d_rocker-arm.obj", 100.0, true)]
    {
        let part = file.split('.').next().unwrap_or(file);
        if let Ok(bytes) = std::fs::read(dir.join(file)) {
            let mut mesh = swarf::mesh::import::read_mesh_auto(&bytes, Some(file), &swarf::geom::Tolerances::default()).expect("the part reads");
            mesh.transform(|p| if y_up { swarf::geom::DVec3::new(p.x, -p.z, p.y) * scale } else { p * scale });
            for row in support::job::octree_rows(part, &mesh, "native", &clock) {
                println!("{row}");
            }
        }
    }
}
