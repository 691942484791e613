//! The DXF and SVG readers on any bytes: a drawing or an error, never a panic; a drawing has
//! only finite coordinates.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf::geom::Tolerances;
use swarf::drawing::import::read_drawing;

fuzz_target!(|data: &[u8]| {
    for name in ["x.dxf", "x.svg"] {
        if let Ok(d) = read_drawing(data, Some(name), &Tolerances::DEFAULT) {
            assert!(d.loops.iter().flat_map(|l| &l.path.vertices).all(|v| v.p.is_finite() && v.bulge.is_finite()));
        }
    }
});
