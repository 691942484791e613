//! Seed 000: octree multi-tool roughing against z-level roughing with the smallest tool alone
//! and with the largest then the smallest, on the generated mould and the shared parts
//! (`job::bench::octree_rows`).
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
    for (part, scale) in [("ocl_mount_rush", 1.0), ("ocl_wheel_in_box", 1.0), ("tm_featuretype", 25.4), ("kiri_pocket-test", 1.0)] {
        if let Ok(stl) = std::fs::read(dir.join(format!("{part}.stl"))) {
            let mut mesh = swarf::mesh::import::read_mesh_auto(&stl, Some("part.stl"), &swarf::geom::Tolerances::default()).expect("the part reads");
            mesh.transform(|p| p * scale);
            for row in support::job::octree_rows(part, &mesh, "native", &clock) {
                println!("{row}");
            }
        }
    }
}
