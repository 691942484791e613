//! Issue 56: a DXF means what its file says, as the CAD readers people check drawings in read it.
//! Each generated drawing (and each shared one) is read by swarf and by ezdxf, the Python DXF
//! library (`tests/oracles/ezdxf_read.py`, installed into `.venv` by `scripts/setup.sh`); the
//! two must agree on the drawing's bounds, the length of its lines and curves and the areas of
//! its closed loops, in millimetres. The cases cover every entity swarf reads, the units of
//! `$INSUNITS`, entities drawn in a mirrored plane (extrusion 0, 0, −1: their own coordinates
//! mirrored, a LINE's or POINT's not), an ELLIPSE facing −Z, any line ends and a byte-order
//! mark. Entities standing out of the XY plane are left out by both (and said by swarf); an
//! ARC whose angle is no angle is refused.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use swarf::drawing::import::read_drawing;
use swarf::drawing::Drawing;
use swarf::geom::Tolerances;

/// A DXF of `entities` (group-code lines) in `$INSUNITS` `units`.
fn dxf(units: u32, entities: &str) -> String {
    format!("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n{units}\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n")
}

fn line(a: (f64, f64), b: (f64, f64), extra: &str) -> String {
    format!("0\nLINE\n8\n0\n10\n{}\n20\n{}\n30\n0\n11\n{}\n21\n{}\n31\n0\n{extra}", a.0, a.1, b.0, b.1)
}

fn circle(c: (f64, f64), r: f64, extra: &str) -> String {
    format!("0\nCIRCLE\n8\n0\n10\n{}\n20\n{}\n30\n0\n40\n{r}\n{extra}", c.0, c.1)
}

fn arc(c: (f64, f64), r: f64, a0: f64, a1: f64, extra: &str) -> String {
    format!("0\nARC\n8\n0\n10\n{}\n20\n{}\n30\n0\n40\n{r}\n50\n{a0}\n51\n{a1}\n{extra}", c.0, c.1)
}

/// A closed LWPOLYLINE through `(x, y, bulge)`.
fn lwpolyline(vertices: &[(f64, f64, f64)], extra: &str) -> String {
    let mut s = format!("0\nLWPOLYLINE\n100\nAcDbEntity\n8\n0\n100\nAcDbPolyline\n90\n{}\n70\n1\n{extra}", vertices.len());
    for (x, y, b) in vertices {
        s += &format!("10\n{x}\n20\n{y}\n42\n{b}\n");
    }
    s
}

/// A closed 2D POLYLINE (VERTEX … SEQEND) through `(x, y, bulge)`.
fn polyline(vertices: &[(f64, f64, f64)], extra: &str) -> String {
    let mut s = format!("0\nPOLYLINE\n8\n0\n66\n1\n10\n0\n20\n0\n30\n0\n70\n1\n{extra}");
    for (x, y, b) in vertices {
        s += &format!("0\nVERTEX\n8\n0\n10\n{x}\n20\n{y}\n30\n0\n42\n{b}\n");
    }
    s + "0\nSEQEND\n8\n0\n"
}

const FACING_DOWN: &str = "210\n0\n220\n0\n230\n-1\n";

fn square(x: f64, y: f64, side: f64) -> String {
    let p = [(x, y), (x + side, y), (x + side, y + side), (x, y + side)];
    (0..4).map(|k| line(p[k], p[(k + 1) % 4], "")).collect()
}

/// The generated cases: a name and the file's bytes.
fn cases() -> Vec<(&'static str, Vec<u8>)> {
    let plate = dxf(4, &(square(10.0, 0.0, 60.0) + &circle((40.0, 30.0), 8.0, "")));
    let rounded = [(0.0, 0.0, 0.0), (2.0, 0.0, 0.41421356), (2.5, 0.5, 0.0), (2.5, 1.5, 1.0), (0.0, 1.5, 0.3)];
    // A D: an arc from −90° to 90° written as −90 and 450 (the same arc, a writer's choice).
    let d_shape = arc((50.0, 20.0), 20.0, -90.0, 450.0, "") + &line((50.0, 40.0), (20.0, 40.0), "") + &line((20.0, 40.0), (20.0, 0.0), "") + &line((20.0, 0.0), (50.0, 0.0), "");
    let ellipse = "0\nELLIPSE\n100\nAcDbEntity\n8\n0\n100\nAcDbEllipse\n10\n30\n20\n20\n30\n0\n11\n25\n21\n5\n31\n0\n40\n0.4\n41\n0\n42\n6.283185307179586\n";
    // Half an ellipse facing −Z (it sweeps the other way: its upper half is the lower one) closed
    // by its major axis.
    let half = format!(
        "0\nELLIPSE\n100\nAcDbEntity\n8\n0\n100\nAcDbEllipse\n10\n100\n20\n0\n30\n0\n11\n30\n21\n0\n31\n0\n210\n0\n220\n0\n230\n-1\n40\n0.5\n41\n0\n42\n3.141592653589793\n{}",
        line((70.0, 0.0), (130.0, 0.0), "")
    );
    // A cubic B-spline from (0, 0) to (40, 0) bulging up, closed by a line.
    let spline = format!(
        "0\nSPLINE\n100\nAcDbEntity\n8\n0\n100\nAcDbSpline\n70\n8\n71\n3\n72\n8\n73\n4\n40\n0\n40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n40\n1\n40\n1\n10\n0\n20\n0\n30\n0\n10\n10\n20\n30\n30\n0\n10\n30\n20\n30\n30\n0\n10\n40\n20\n0\n30\n0\n{}",
        line((40.0, 0.0), (0.0, 0.0), "")
    );
    // Mirrored planes: a CIRCLE, an ARC and an LWPOLYLINE whose extrusion faces −Z are drawn at
    // −x; a LINE's and a POINT's coordinates are the world's whatever their extrusion.
    let mirrored = square(10.0, 0.0, 60.0).replace("31\n0\n", &format!("31\n0\n{FACING_DOWN}"))
        + &circle((-40.0, 25.0), 5.0, FACING_DOWN)
        + &arc((-50.0, 45.0), 10.0, 0.0, 180.0, FACING_DOWN)
        + &line((40.0, 45.0), (60.0, 45.0), "")
        + &lwpolyline(&[(-20.0, 5.0, 0.0), (-30.0, 5.0, 0.5), (-30.0, 15.0, 0.0), (-20.0, 15.0, 0.0)], FACING_DOWN)
        + "0\nPOINT\n8\n0\n10\n20\n20\n10\n30\n0\n210\n0\n220\n0\n230\n-1\n";
    let mut out = vec![
        ("lines and a circle, mm", plate.clone().into_bytes()),
        ("a rounded LWPOLYLINE, inches", dxf(1, &lwpolyline(&rounded, "")).into_bytes()),
        ("a rounded POLYLINE, cm", dxf(5, &polyline(&rounded, "")).into_bytes()),
        ("an ARC past 360°", dxf(4, &d_shape).into_bytes()),
        ("ELLIPSEs, one facing −Z", dxf(4, &format!("{ellipse}{half}")).into_bytes()),
        ("a SPLINE", dxf(4, &spline).into_bytes()),
        ("mirrored planes", dxf(4, &mirrored).into_bytes()),
        ("CR LF line ends", plate.replace('\n', "\r\n").into_bytes()),
        ("old Mac CR line ends", plate.replace('\n', "\r").into_bytes()),
        ("a byte-order mark", [b"\xEF\xBB\xBF".as_slice(), plate.as_bytes()].concat()),
        ("a circle standing in YZ", dxf(4, &(square(0.0, 0.0, 60.0) + &circle((0.0, 30.0), 8.0, "210\n1\n220\n0\n230\n0\n"))).into_bytes()),
    ];
    out.push(("a POLYLINE tilted out of XY", dxf(4, &(square(0.0, 0.0, 60.0) + &polyline(&rounded, "210\n0\n220\n0.6\n230\n0.8\n"))).into_bytes()));
    out
}

/// ezdxf's reading of each file: bounds [x0, x1, y0, y1], length, loop areas (sorted), left out.
struct Oracle {
    bounds: Option<[f64; 4]>,
    length: f64,
    loops: Vec<f64>,
    left_out: u64,
}

fn python() -> PathBuf {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python");
    assert!(p.exists(), "{} is absent: scripts/setup.sh installs ezdxf, the DXF tests' oracle", p.display());
    p
}

fn ezdxf(files: &[PathBuf], gap: f64) -> Vec<Oracle> {
    let out = Command::new(python()).arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/oracles/ezdxf_read.py")).arg(gap.to_string()).args(files).output().expect("python runs");
    assert!(out.status.success(), "ezdxf failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            let nums = |x: &serde_json::Value| x.as_array().unwrap().iter().map(|n| n.as_f64().unwrap()).collect::<Vec<f64>>();
            Oracle {
                bounds: (!v["bounds"].is_null()).then(|| nums(&v["bounds"]).try_into().unwrap()),
                length: v["length"].as_f64().unwrap(),
                loops: nums(&v["loops"]),
                left_out: v["leftOut"].as_u64().unwrap(),
            }
        })
        .collect()
}

/// swarf's reading in the oracle's terms.
fn ours(d: &Drawing) -> ([f64; 4], f64, Vec<f64>) {
    let segments = d.loops.iter().flat_map(|l| l.path.segments().collect::<Vec<_>>()).chain(d.open.iter().flat_map(|o| o.path.clone()));
    let (mut b, mut length) = ([f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY], 0.0);
    for s in segments {
        let r = s.bounds();
        b = [b[0].min(r.min.x), b[1].max(r.max.x), b[2].min(r.min.y), b[3].max(r.max.y)];
        length += s.length();
    }
    let mut areas: Vec<f64> = d.loops.iter().map(|l| l.path.area().abs()).collect();
    areas.sort_by(f64::total_cmp);
    (b, length, areas)
}

/// swarf and ezdxf agree on `name`'s drawing; returns swarf's.
fn agree(name: &str, bytes: &[u8], file: &Path, o: &Oracle) -> Option<Drawing> {
    let tol = Tolerances::default();
    let read = read_drawing(bytes, Some(&format!("{name}.dxf")), &tol);
    let Some(ob) = o.bounds else {
        // Nothing ezdxf would draw in XY: swarf refuses the drawing, naming what it left out.
        let e = read.expect_err(name).to_string();
        assert!(o.left_out == 0 || e.contains("out of the XY plane"), "{name}: {e}");
        return None;
    };
    let d = read.unwrap_or_else(|e| panic!("{name} ({}): {e}", file.display()));
    let (b, length, areas) = ours(&d);
    // swarf fits curves with arcs within its arc-fit tolerance; ezdxf's flattening is finer.
    let slack = 2.0 * tol.arc_fit + 1e-6;
    for k in 0..4 {
        assert!((b[k] - ob[k]).abs() <= slack, "{name}: bounds {b:?}, ezdxf {ob:?}");
    }
    assert!((length - o.length).abs() <= 1e-4 * o.length + slack, "{name}: length {length}, ezdxf {}", o.length);
    assert_eq!(areas.len(), o.loops.len(), "{name}: loops {areas:?}, ezdxf {:?}", o.loops);
    for (a, e) in areas.iter().zip(&o.loops) {
        assert!((a - e).abs() <= 1e-4 * e + slack * length, "{name}: loop areas {areas:?}, ezdxf {:?}", o.loops);
    }
    let said: usize = d.ignored.iter().filter(|(k, _)| k.contains("out of the XY plane")).map(|(_, n)| n).sum();
    assert_eq!(said as u64, o.left_out, "{name}: left out {:?}", d.ignored);
    Some(d)
}

#[test]
fn swarf_reads_every_dxf_as_ezdxf_does() {
    let dir = std::env::temp_dir().join(format!("swarf-dxf-spec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = cases();
    let mut files: Vec<(String, Vec<u8>, PathBuf)> = cases
        .iter()
        .enumerate()
        .map(|(k, (name, bytes))| {
            let p = dir.join(format!("case{k}.dxf"));
            std::fs::write(&p, bytes).unwrap();
            (name.to_string(), bytes.clone(), p)
        })
        .collect();
    for shared in ["profiles/tm_1002_tray_bottom.dxf", "profiles/tm_LM2.dxf", "profiles/ezdxf_POLI-ALL210_12.dxf"] {
        if let Some(p) = common::shared_data(shared) {
            files.push((shared.to_string(), std::fs::read(&p).unwrap(), p));
        }
    }
    let oracle = ezdxf(&files.iter().map(|f| f.2.clone()).collect::<Vec<_>>(), Tolerances::default().chain);
    assert_eq!(oracle.len(), files.len());
    let mut drawings = Vec::new();
    for ((name, bytes, path), o) in files.iter().zip(&oracle) {
        drawings.push(agree(name, bytes, path, o));
    }
    // The checks above hold swarf to ezdxf; these hold the cases to what they were made for.
    let d = |name: &str| drawings[files.iter().position(|f| f.0 == name).unwrap()].clone().unwrap();
    // Line ends and a byte-order mark change nothing.
    for name in ["CR LF line ends", "old Mac CR line ends", "a byte-order mark"] {
        assert_eq!(ours(&d(name)), ours(&d("lines and a circle, mm")), "{name}");
    }
    // A mirrored plane: the circle at x = +40, the LINEs' square where it was drawn, the POINT too.
    let m = d("mirrored planes");
    assert!(m.loops.iter().any(|l| (l.path.bounds().min.x - 35.0).abs() < 1e-9), "{:?}", m.loops.iter().map(|l| l.path.bounds()).collect::<Vec<_>>());
    assert_eq!(m.points.iter().map(|p| (p.at.x, p.at.y)).collect::<Vec<_>>(), vec![(20.0, 10.0)]);
    // Out of the plane: left out, and said.
    for name in ["a circle standing in YZ", "a POLYLINE tilted out of XY"] {
        let o = d(name);
        assert_eq!(o.loops.len(), 1, "{name}");
        assert!(o.ignored.iter().any(|(k, n)| k.contains("out of the XY plane") && *n == 1), "{name}: {:?}", o.ignored);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_arc_whose_angle_is_no_angle_is_refused() {
    for (a0, a1) in [(0.0, 1e300), (-1e20, 90.0), (0.0, 3601.0)] {
        let e = read_drawing(dxf(4, &arc((0.0, 0.0), 10.0, a0, a1, "")).as_bytes(), Some("arc.dxf"), &Tolerances::default()).expect_err("refused").to_string();
        assert!(e.contains("is not an angle"), "{e}");
    }
    // Within ten turns: read as the arc it is (−90° to 450° is a full turn and a half: 180°).
    let d = read_drawing(dxf(4, &(arc((0.0, 0.0), 10.0, -90.0, 450.0, "") + &line((0.0, 10.0), (0.0, -10.0), ""))).as_bytes(), Some("arc.dxf"), &Tolerances::default()).unwrap();
    assert!((d.loops[0].path.area().abs() - std::f64::consts::PI * 50.0).abs() < 1e-9);
}

/// A drawing whose size says it was read in the wrong unit is said as it loads (issue 62): a
/// 3 × 3 square in a file that names no unit is 3 mm read as millimetres, 76.2 mm read in
/// inches; a 200-inch square in a file that says inches is 5 m, 200 mm as millimetres. Read in
/// the unit that makes it a part, nothing is said; a drawing the other unit would make no part
/// (0.01 mm, 0.25 mm in inches) gets no guess.
#[test]
fn a_drawing_in_the_wrong_unit_is_said_at_load_with_the_unit_that_makes_it_a_part() {
    use swarf::job::{drawing_unit_warning, DrawingSetup, DrawingUnits};
    let said = |units: u32, side: f64, setup: DrawingUnits| {
        let mut d = read_drawing(dxf(units, &square(0.0, 0.0, side)).as_bytes(), Some("plate.dxf"), &Tolerances::default()).unwrap();
        DrawingSetup { units: setup, ..DrawingSetup::default() }.apply(&mut d);
        drawing_unit_warning(&d).map(|w| w.to_string())
    };
    let small = said(0, 3.0, DrawingUnits::File).expect("a 3 mm drawing is said");
    assert!(
        small.contains("the drawing is 3 × 3 mm, under 5 mm across") && small.contains("Read in inches it would be 76.2 mm across (Units of the file: inch; drawing.units in a job file)"),
        "{small}"
    );
    assert_eq!(said(0, 3.0, DrawingUnits::Inch), None);
    let large = said(1, 200.0, DrawingUnits::File).expect("a 5 m drawing is said");
    assert!(large.contains("over 3000 mm across") && large.contains("Read in millimetres it would be 200 mm across (Units of the file: mm;"), "{large}");
    assert_eq!(said(1, 200.0, DrawingUnits::Mm), None);
    assert_eq!(said(0, 0.01, DrawingUnits::File), None);
    assert_eq!(said(4, 60.0, DrawingUnits::File), None);
    // A job run on it says it too, beside what the drawing left out.
    let mut d = read_drawing(dxf(0, &square(0.0, 0.0, 3.0)).as_bytes(), Some("plate.dxf"), &Tolerances::default()).unwrap();
    DrawingSetup::default().apply(&mut d);
    assert!(swarf::job::run::drawing_warnings(&d).iter().any(|w| w.to_string().contains("Read in inches")));
}
