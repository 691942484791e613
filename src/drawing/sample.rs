//! A built-in sample drawing, as ASCII DXF text (so that it goes through the importer like a
//! dropped file): a 120 × 80 mm plate with rounded corners on layer CUT, with a round hole, a
//! square hole of four lines and a slot; on layer POCKET, a 40 × 24 mm pocket with a round
//! island.

/// The sample drawing's DXF text.
pub fn plate_dxf() -> String {
    let mut e = String::new();
    let mut add = |s: String| e.push_str(&s);
    let k = (std::f64::consts::PI / 8.0).tan(); // bulge of a quarter circle
    let r = 6.0;
    // Outline: rounded rectangle 0..120 × 0..80, counter-clockwise.
    let outline = [(r, 0.0, 0.0), (120.0 - r, 0.0, k), (120.0, r, 0.0), (120.0, 80.0 - r, k), (120.0 - r, 80.0, 0.0), (r, 80.0, k), (0.0, 80.0 - r, 0.0), (0.0, r, k)];
    add(lwpolyline("CUT", &outline, true));
    add("0\nCIRCLE\n8\nCUT\n10\n20.0\n20\n20.0\n30\n0.0\n40\n8.0\n".to_string());
    for (a, b) in [((92.0, 12.0), (108.0, 12.0)), ((108.0, 12.0), (108.0, 28.0)), ((108.0, 28.0), (92.0, 28.0)), ((92.0, 28.0), (92.0, 12.0))] {
        add(format!("0\nLINE\n8\nCUT\n10\n{}\n20\n{}\n30\n0.0\n11\n{}\n21\n{}\n31\n0.0\n", a.0, a.1, b.0, b.1));
    }
    // A slot 30 long, 8 wide: two half circles.
    add(lwpolyline("CUT", &[(15.0, 56.0, 0.0), (45.0, 56.0, 1.0), (45.0, 64.0, 0.0), (15.0, 64.0, 1.0)], true));
    // The pocket and its island.
    add(lwpolyline("POCKET", &[(60.0, 44.0, 0.0), (100.0, 44.0, 0.0), (100.0, 68.0, 0.0), (60.0, 68.0, 0.0)], true));
    add("0\nCIRCLE\n8\nPOCKET\n10\n80.0\n20\n56.0\n30\n0.0\n40\n4.0\n".to_string());
    format!("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{e}0\nENDSEC\n0\nEOF\n")
}

fn lwpolyline(layer: &str, vertices: &[(f64, f64, f64)], closed: bool) -> String {
    let mut s = format!("0\nLWPOLYLINE\n8\n{layer}\n90\n{}\n70\n{}\n", vertices.len(), closed as i32);
    for (x, y, bulge) in vertices {
        s.push_str(&format!("10\n{x}\n20\n{y}\n"));
        if *bulge != 0.0 {
            s.push_str(&format!("42\n{bulge}\n"));
        }
    }
    s
}
