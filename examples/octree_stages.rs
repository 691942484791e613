//! Prints the stages octree roughing chooses on the generated mould (seed 000's case): `cargo
//! run --release --example octree_stages`.
fn main() {
    let [(_, job), ..] = swarf::job::bench::octree_jobs(0.25, 0.5, 0.5, 0.25);
    let out = swarf::job::run(&job, swarf::mesh::sample::octree_mould(1.0), &mut swarf::progress::Progress::none()).expect("the mould roughs");
    for o in &out.operations {
        println!("{}", o.describe());
    }
}
