//! Prints the stages octree roughing chooses on the generated mould (seed 000's case): `cargo
//! run --release --example octree_stages`.

#[path = "../benches/support/mod.rs"]
mod support;
fn main() {
    let (_, job) = support::job::octree_jobs(0.25, 0.5, 0.5, 0.25).remove(0);
    let out = swarf::job::run(&job, swarf::mesh::sample::octree_mould(1.0), &mut swarf::progress::Progress::none()).expect("the mould roughs");
    for o in &out.operations {
        println!("{}", o.describe());
    }
}
