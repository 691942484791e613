//! A tool's holder (issue 58): the collet nut and chuck round the shank above the stick-out, as a
//! stack of cylinders and cones from the nut's face up. The verification finds it in material
//! ([`crate::sim::verify`]): every cutting move's holder, section by section, against the stock
//! the program has left there, which holds the part.

use serde::{Deserialize, Serialize};

/// One section of a holder: a cylinder, or a cone whose top is `topDiameter` wide.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct HolderSection {
    /// Its diameter at its bottom (mm). Default value: 30.
    pub diameter: f64,
    /// Its length up the tool's axis (mm). Default value: 20.
    pub length: f64,
    /// A cone's diameter at its top (mm). Default value: as at its bottom (a cylinder).
    pub top_diameter: Option<f64>,
}

impl Default for HolderSection {
    fn default() -> Self {
        HolderSection { diameter: 30.0, length: 20.0, top_diameter: None }
    }
}

/// A holder: its sections from the face the tool stands out of (the collet nut's) upward.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Holder {
    /// Shown in the library and on the setup sheet. Default value: "holder".
    pub name: String,
    /// From the nut's face up. Default value: one section 30 mm wide and 20 mm long.
    pub sections: Vec<HolderSection>,
}

impl Default for Holder {
    fn default() -> Self {
        Holder { name: "holder".into(), sections: vec![HolderSection::default()] }
    }
}

/// Steps a cone is checked in: each at its wider end, so the check never misses it (a cone 20
/// mm long that widens by 10 mm is met up to 1.25 mm early at most).
const CONE_STEPS: usize = 4;

/// The most a holder's section may be, wide or long (mm).
const MOST: f64 = 1000.0;

impl Holder {
    /// The holders swarf knows: ER collet chucks with their standard nuts (ER11, ER16, ER20,
    /// ER32; nut and chuck sizes as the common DIN 6499 ones are, to be measured against yours)
    /// and a router's collet nut.
    pub fn builtin() -> Vec<Holder> {
        let er = |name: &str, nut: (f64, f64), body: (f64, f64)| Holder {
            name: name.into(),
            sections: vec![HolderSection { diameter: nut.0, length: nut.1, top_diameter: None }, HolderSection { diameter: body.0, length: body.1, top_diameter: None }],
        };
        vec![
            er("ER11 collet chuck", (16.0, 11.5), (20.0, 30.0)),
            er("ER16 collet chuck", (28.0, 18.0), (32.0, 40.0)),
            er("ER20 collet chuck", (34.0, 19.5), (40.0, 40.0)),
            er("ER32 collet chuck", (50.0, 22.5), (56.0, 45.0)),
            Holder {
                name: "router collet nut".into(),
                sections: vec![HolderSection { diameter: 24.0, length: 18.0, top_diameter: None }, HolderSection { diameter: 43.0, length: 30.0, top_diameter: None }],
            },
        ]
    }

    /// The rings its sections are checked as: `(radius, rise)`, a cylinder of that radius from
    /// `rise` above the tool's tip up, for a tool standing `stick_out` out of it (a cone in
    /// steps, each as wide as its wider end).
    pub fn rings(&self, stick_out: f64) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        let mut at = stick_out;
        for s in &self.sections {
            let top = s.top_diameter.unwrap_or(s.diameter);
            let steps = if (top - s.diameter).abs() > 1e-9 { CONE_STEPS } else { 1 };
            for k in 0..steps {
                let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
                let wider = (s.diameter + (top - s.diameter) * a).max(s.diameter + (top - s.diameter) * b);
                out.push((wider / 2.0, at + s.length * a));
            }
            at += s.length;
        }
        out
    }

    /// What is wrong with it: `(field, message)`, the field under the holder.
    pub fn problems(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        if self.sections.is_empty() {
            out.push(("sections".to_owned(), "a holder needs at least one section".to_owned()));
        }
        let fits = |v: f64| v.is_finite() && v > 0.0 && v <= MOST;
        for (k, s) in self.sections.iter().enumerate() {
            for (field, v) in [("diameter", Some(s.diameter)), ("length", Some(s.length)), ("topDiameter", s.top_diameter)] {
                if let Some(v) = v.filter(|&v| !fits(v)) {
                    out.push((format!("sections[{k}].{field}"), format!("must be more than 0 and at most {MOST} mm (got {})", crate::limits::shown(v))));
                }
            }
        }
        out
    }
}
