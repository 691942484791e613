fn main() {
    let m = swarf::mesh::sample::demo_part();
    let e = m.edges_with_faces();
    println!("boundary edges {} of {}, nonmanifold {}", e.iter().filter(|e| e.count==1).count(), e.len(), e.iter().filter(|e| e.count>2).count());
    let o = m.open_edges();
    println!("open {}: {:?} .. {:?}", o.len(), o.first(), o.last());
    let b = m.bounds(); println!("{:?}", b);
}
