//! Prints what swarf reads from a drawing: `cargo run --example drawing_info -- file.dxf`.
fn main() {
    for path in std::env::args().skip(1) {
        let bytes = std::fs::read(&path).expect("readable file");
        match swarf::drawing::import::read_drawing(&bytes, Some(&path), &swarf::geom::Tolerances::default()) {
            Ok(d) => {
                let b = d.bounds();
                println!("{path}: {} loops, {} open chains, layers {:?}, units {}, ignored {:?}, bounds {:.2?}..{:.2?}", d.loops.len(), d.open.len(), d.layers, d.units, d.ignored, b.min, b.max);
                for o in d.open.iter().take(3) {
                    println!("  open: {o:?}");
                }
                match d.shape(&[]) {
                    Ok(s) => println!("  shape: {} loops, area {:.2} mm², {} outer", s.loops.len(), s.area(), s.loops.iter().filter(|l| l.is_ccw()).count()),
                    Err(e) => println!("  {e}"),
                }
            }
            Err(e) => println!("{path}: {e}"),
        }
    }
}
