fn main() {
    let tol = swarf::geom::Tolerances::default();
    println!("demo: {}", swarf::mesh::sample::demo_part().open_edges().len());
    for f in std::fs::read_dir("/work/shared/data/meshes").unwrap() {
        let p = f.unwrap().path();
        let mut m = swarf::mesh::import::read_mesh_auto(&std::fs::read(&p).unwrap(), p.file_name().and_then(|n| n.to_str()), &tol).unwrap();
        swarf::mesh::placement::PartSetup::default().apply(&mut m);
        let t = std::time::Instant::now();
        let o = m.open_edges();
        println!("{}: open {} ({:?}) {:?}", p.display(), o.len(), t.elapsed(), o.first());
    }
}
