//! Threads by name: ISO metric coarse (`M8`) and fine (`M8x1`), Unified coarse and fine
//! (`1/4-20`, `#10-32`, `1/4 UNC`, `#10 UNF`), as major diameter and pitch in millimetres; and
//! the basic 60° profile's depths (ISO 68-1, ASME B1.1).

/// ISO metric coarse pitches (ISO 261): (major diameter, pitch), mm.
const METRIC_COARSE: &[(f64, f64)] = &[
    (1.0, 0.25),
    (1.2, 0.25),
    (1.6, 0.35),
    (2.0, 0.4),
    (2.5, 0.45),
    (3.0, 0.5),
    (3.5, 0.6),
    (4.0, 0.7),
    (5.0, 0.8),
    (6.0, 1.0),
    (8.0, 1.25),
    (10.0, 1.5),
    (12.0, 1.75),
    (14.0, 2.0),
    (16.0, 2.0),
    (18.0, 2.5),
    (20.0, 2.5),
    (22.0, 2.5),
    (24.0, 3.0),
    (27.0, 3.0),
    (30.0, 3.5),
    (36.0, 4.0),
    (42.0, 4.5),
    (48.0, 5.0),
];

/// Unified sizes: (size as written, major diameter in inches, threads per inch UNC, UNF).
const UNIFIED: &[(&str, f64, Option<u32>, Option<u32>)] = &[
    ("#0", 0.060, None, Some(80)),
    ("#1", 0.073, Some(64), Some(72)),
    ("#2", 0.086, Some(56), Some(64)),
    ("#3", 0.099, Some(48), Some(56)),
    ("#4", 0.112, Some(40), Some(48)),
    ("#5", 0.125, Some(40), Some(44)),
    ("#6", 0.138, Some(32), Some(40)),
    ("#8", 0.164, Some(32), Some(36)),
    ("#10", 0.190, Some(24), Some(32)),
    ("#12", 0.216, Some(24), Some(28)),
    ("1/4", 0.25, Some(20), Some(28)),
    ("5/16", 0.3125, Some(18), Some(24)),
    ("3/8", 0.375, Some(16), Some(24)),
    ("7/16", 0.4375, Some(14), Some(20)),
    ("1/2", 0.5, Some(13), Some(20)),
    ("9/16", 0.5625, Some(12), Some(18)),
    ("5/8", 0.625, Some(11), Some(18)),
    ("3/4", 0.75, Some(10), Some(16)),
    ("7/8", 0.875, Some(9), Some(14)),
    ("1", 1.0, Some(8), Some(12)),
];

/// A thread's major diameter and pitch (mm) from its name, or what is wrong with the name.
pub fn lookup(name: &str) -> Result<(f64, f64), String> {
    let text = name.trim().to_ascii_uppercase().replace(' ', "");
    let bad = || format!("'{name}' is not a thread swarf knows: write M8 or M8x1 (ISO metric), 1/4-20, #10-32, 1/4UNC or #10UNF (Unified), or give majorDiameter and pitch");
    if let Some(rest) = text.strip_prefix('M') {
        let (d, p) = match rest.split_once(['X', '×']) {
            Some((d, p)) => (d.parse::<f64>().map_err(|_| bad())?, Some(p.parse::<f64>().map_err(|_| bad())?)),
            None => (rest.parse::<f64>().map_err(|_| bad())?, None),
        };
        let pitch = match p {
            Some(p) => p,
            None => METRIC_COARSE.iter().find(|(m, _)| (m - d).abs() < 1e-9).map(|&(_, p)| p).ok_or_else(|| format!("M{d} has no coarse pitch in swarf's table: write it with its pitch, M{d}x1.5"))?,
        };
        return (d > 0.0 && pitch > 0.0 && pitch < d).then_some((d, pitch)).ok_or_else(bad);
    }
    // Unified: size-tpi, or size with UNC / UNF.
    let (size, tpi) = if let Some(size) = text.strip_suffix("UNC").or_else(|| text.strip_suffix("-UNC")) {
        let size = size.trim_end_matches('-');
        let row = UNIFIED.iter().find(|r| r.0 == size).ok_or_else(bad)?;
        (row.1, row.2.ok_or_else(|| format!("{size} has no UNC thread"))?)
    } else if let Some(size) = text.strip_suffix("UNF").or_else(|| text.strip_suffix("-UNF")) {
        let size = size.trim_end_matches('-');
        let row = UNIFIED.iter().find(|r| r.0 == size).ok_or_else(bad)?;
        (row.1, row.3.ok_or_else(|| format!("{size} has no UNF thread"))?)
    } else {
        let (size, tpi) = text.split_once('-').ok_or_else(bad)?;
        let major = match UNIFIED.iter().find(|r| r.0 == size) {
            Some(r) => r.1,
            None => size.parse::<f64>().map_err(|_| bad())?,
        };
        (major, tpi.parse::<u32>().map_err(|_| bad())?)
    };
    if tpi == 0 {
        return Err(bad());
    }
    Ok((size * 25.4, 25.4 / tpi as f64))
}

/// The basic profile's radial depth of an internal thread, from its minor diameter to its
/// major (5/8 of the fundamental triangle's height H = √3/2 P).
pub fn internal_depth(pitch: f64) -> f64 {
    5.0 / 8.0 * 3f64.sqrt() / 2.0 * pitch
}

/// How deep an external thread is cut (mm): ISO 68-1's h3 = 17/24 H, to the bolt's minor
/// diameter d3 with its rounded root's clearance.
pub fn external_depth(pitch: f64) -> f64 {
    17.0 / 24.0 * 3f64.sqrt() / 2.0 * pitch
}

/// An internal thread's basic minor diameter: the tap drill's size.
pub fn minor_diameter(major: f64, pitch: f64) -> f64 {
    major - 2.0 * internal_depth(pitch)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_are_read_by_their_names() {
        assert_eq!(lookup("M8").unwrap(), (8.0, 1.25));
        assert_eq!(lookup("m10 x 1").unwrap(), (10.0, 1.0));
        let (d, p) = lookup("1/4-20").unwrap();
        assert!((d - 6.35).abs() < 1e-12 && (p - 1.27).abs() < 1e-12);
        let (d, p) = lookup("#10-32").unwrap();
        assert!((d - 4.826).abs() < 1e-9 && (p - 25.4 / 32.0).abs() < 1e-12);
        assert_eq!(lookup("1/4 UNC").unwrap(), lookup("1/4-20").unwrap());
        assert_eq!(lookup("#10UNF").unwrap(), lookup("#10-32").unwrap());
        assert!(lookup("M7").unwrap_err().contains("no coarse pitch"));
        assert!(lookup("banana").is_err() && lookup("1/4-0").is_err());
        // M8's tap drill: 6.647 mm basic minor (6.8 drilled in practice).
        assert!((minor_diameter(8.0, 1.25) - 6.647).abs() < 1e-3);
    }
}
