//! What holds the stock: a vise's jaws gripping its sides, and boxes for clamps, a plate or
//! anything else on the table. Every operation keeps out of them, tool and shank, by a
//! clearance: they join the part in what the cutter is dropped onto ([`solid`]), so
//! each strategy, being above its exact CL surface, stays above them too and stops short of
//! them; and the verification checks every move against them
//! ([`crate::sim::fixtures::collisions`]), naming the fixture a move runs into.

use serde::{Deserialize, Serialize};

use crate::geom::{Aabb, DVec3};
use crate::mesh::Mesh;

/// What holds the stock in a setup.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Fixtures {
    /// A vise gripping the stock's sides; its jaws follow the stock. Default value: none.
    pub vise: Option<Vise>,
    /// Clamps, a plate, anything else: boxes in the program's coordinates (mm from the work
    /// zero). Default value: none.
    pub boxes: Vec<FixtureBox>,
    /// Fixtures as meshes (a vise's model, a strap clamp, a soft jaw), in the program's
    /// coordinates (mm from the work zero): the operations keep out of the box round each,
    /// the verification out of the mesh itself. Default value: none.
    pub meshes: Vec<FixtureMesh>,
    /// How far every tool keeps from each of them (mm). Default value: 1.
    pub clearance: f64,
    /// The part is held by something the fixtures do not show (screws, tape, a vacuum table,
    /// soft jaws on its finished faces): an operation that cuts it free of what the fixtures
    /// grip (or, without fixtures, of the stock round it) is then noted, not refused or warned
    /// of. Default value: false.
    pub held_otherwise: bool,
}

impl Default for Fixtures {
    fn default() -> Self {
        Fixtures { vise: None, boxes: Vec::new(), meshes: Vec::new(), clearance: 1.0, held_otherwise: false }
    }
}

/// A machine vise: two jaws gripping the stock's sides from its bottom up.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Vise {
    /// How far up the stock's sides the jaws reach, from its bottom (mm). Default value: 6.
    pub grip: f64,
    /// The jaws' width along the stock's side (mm). Default value: 150.
    pub jaw_width: f64,
    /// The jaws' thickness, out from the stock (mm). Default value: 20.
    pub jaw_thickness: f64,
    /// Which way the jaws close: `y` grips the front and back of the stock, `x` its left and
    /// right. Default value: y.
    pub closes: ViseAxis,
    /// The least height of material each jaw must grip when its setup starts (mm): a jaw on
    /// air or on a thin web is an error naming the setup and the jaw. Default value: half the
    /// grip.
    pub least_grip: Option<f64>,
    /// Where the jaws' faces stand along the axis they close on, where they close on less than
    /// the stock's box (a later setup's stock, cut round the part by the setup before): set as
    /// the setup starts, from the material within the grip ([`crate::sim::hold::band_extent`]).
    #[serde(skip)]
    #[ts(skip)]
    pub faces: Option<(f64, f64)>,
}

impl Default for Vise {
    fn default() -> Self {
        Vise { grip: 6.0, jaw_width: 150.0, jaw_thickness: 20.0, closes: ViseAxis::Y, least_grip: None, faces: None }
    }
}

impl Vise {
    /// The least height of material a jaw must grip (mm): `leastGrip`, or half the grip.
    pub fn least(&self) -> f64 {
        self.least_grip.unwrap_or(self.grip / 2.0)
    }

    /// Where its jaws' faces stand along the axis they close on, round `stock`: `faces` where
    /// set, else the stock's sides.
    pub fn faces_on(&self, stock: &Aabb) -> (f64, f64) {
        self.faces.unwrap_or(match self.closes {
            ViseAxis::Y => (stock.min.y, stock.max.y),
            ViseAxis::X => (stock.min.x, stock.max.x),
        })
    }

    /// How far its jaws reach along the stock's side (across the axis they close on), centred
    /// on `stock`.
    pub fn span_on(&self, stock: &Aabb) -> (f64, f64) {
        let c = stock.center();
        let centre = if self.closes == ViseAxis::X { c.y } else { c.x };
        (centre - self.jaw_width / 2.0, centre + self.jaw_width / 2.0)
    }
}

/// Which way a vise's jaws close.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum ViseAxis {
    X,
    #[default]
    Y,
}

/// A box no tool may enter: a clamp, a plate, a stop.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FixtureBox {
    /// Its name, in the messages. Default value: "fixture N".
    pub name: String,
    /// Its least corner (mm, in the program's coordinates). Default value: [0, 0, 0].
    pub min: [f64; 3],
    /// Its greatest corner. Default value: [0, 0, 0].
    pub max: [f64; 3],
}

impl Default for FixtureBox {
    fn default() -> Self {
        FixtureBox { name: String::new(), min: [0.0; 3], max: [0.0; 3] }
    }
}

/// A fixture as a mesh.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct FixtureMesh {
    /// Its name, in the messages. Default value: its file's name.
    pub name: String,
    /// Its file (STL, OBJ, glTF), in the program's coordinates (mm).
    pub file: super::blank::MeshFile,
}

/// How far below the stock's bottom a vise's jaws reach: far enough that no tool reaches
/// under them.
const JAW_DEPTH: f64 = 60.0;

/// One fixture as the planning and the verification see it: its name and its box, and for a
/// mesh fixture the mesh (the box is then the mesh's, which the planning keeps out of and the
/// verification looks inside for the mesh itself).
#[derive(Clone, Debug)]
pub struct Held {
    pub name: String,
    pub solid: Aabb,
    pub mesh: Option<std::sync::Arc<Mesh>>,
    /// How far the box was grown round the fixture (its clearance, in [`Fixtures::keep_out`]).
    pub grown: f64,
}

impl PartialEq for Held {
    fn eq(&self, other: &Held) -> bool {
        self.name == other.name && self.solid == other.solid && self.grown == other.grown && self.mesh.is_some() == other.mesh.is_some()
    }
}

impl Held {
    /// A box fixture.
    pub fn solid(name: &str, solid: Aabb) -> Held {
        Held { name: name.to_owned(), solid, mesh: None, grown: 0.0 }
    }
}

impl Fixtures {
    pub fn is_empty(&self) -> bool {
        self.vise.is_none() && self.boxes.is_empty() && self.meshes.is_empty()
    }

    /// Every fixture round `stock` (the program's coordinates), each box as it stands.
    pub fn held(&self, stock: &Aabb) -> Vec<Held> {
        let mut out = Vec::new();
        if let Some(v) = &self.vise {
            let (mut lo, mut hi, c) = (stock.min, stock.max, stock.center());
            match (v.closes, v.faces_on(stock)) {
                (ViseAxis::Y, faces) => (lo.y, hi.y) = faces,
                (ViseAxis::X, faces) => (lo.x, hi.x) = faces,
            }
            let (z0, z1) = (lo.z - JAW_DEPTH, lo.z + v.grip);
            let half = v.jaw_width / 2.0;
            let jaw = |min: DVec3, max: DVec3| Aabb { min, max };
            let jaws = match v.closes {
                ViseAxis::Y => [
                    ("the vise's front jaw", jaw(DVec3::new(c.x - half, lo.y - v.jaw_thickness, z0), DVec3::new(c.x + half, lo.y, z1))),
                    ("the vise's back jaw", jaw(DVec3::new(c.x - half, hi.y, z0), DVec3::new(c.x + half, hi.y + v.jaw_thickness, z1))),
                ],
                ViseAxis::X => [
                    ("the vise's left jaw", jaw(DVec3::new(lo.x - v.jaw_thickness, c.y - half, z0), DVec3::new(lo.x, c.y + half, z1))),
                    ("the vise's right jaw", jaw(DVec3::new(hi.x, c.y - half, z0), DVec3::new(hi.x + v.jaw_thickness, c.y + half, z1))),
                ],
            };
            out.extend(jaws.into_iter().map(|(name, solid)| Held::solid(name, solid)));
        }
        for (k, b) in self.boxes.iter().enumerate() {
            let name = if b.name.trim().is_empty() { format!("fixture {}", k + 1) } else { b.name.clone() };
            out.push(Held::solid(&name, Aabb { min: DVec3::from_array(b.min), max: DVec3::from_array(b.max) }));
        }
        for (k, m) in self.meshes.iter().enumerate() {
            // One that cannot be read is named by `problems`.
            let Ok(mesh) = m.file.mesh() else { continue };
            let name = [&m.name, &m.file.name].into_iter().find(|n| !n.trim().is_empty()).cloned().unwrap_or_else(|| format!("fixture mesh {}", k + 1));
            out.push(Held { name, solid: mesh.bounds(), mesh: Some(mesh), grown: 0.0 });
        }
        out
    }

    /// What no tool may enter round `stock`: each fixture grown by the clearance.
    pub fn keep_out(&self, stock: &Aabb) -> Vec<Held> {
        let c = DVec3::splat(self.clearance.max(0.0));
        self.held(stock).into_iter().map(|h| Held { solid: Aabb { min: h.solid.min - c, max: h.solid.max + c }, grown: c.x, ..h }).collect()
    }

    /// The settings that do not fit, as `(field, message)` under `at` (`fixtures`, or a
    /// setup's).
    pub fn problems(&self, at: &str) -> Vec<(String, String)> {
        let mut out = Vec::new();
        let mut say = |field: String, message: String| out.push((field, message));
        if !(self.clearance >= 0.0 && self.clearance.is_finite()) {
            say(format!("{at}.clearance"), format!("{at}.clearance: the clearance round the fixtures must be 0 or more millimetres (got {})", self.clearance));
        }
        if let Some(v) = &self.vise {
            for (field, value, what) in
                [("grip", v.grip, "how far up the stock the jaws reach"), ("jawWidth", v.jaw_width, "the jaws' width"), ("jawThickness", v.jaw_thickness, "the jaws' thickness")]
            {
                if !(value > 0.0 && value.is_finite()) {
                    say(format!("{at}.vise.{field}"), format!("{at}.vise.{field}: {what} must be more than 0 mm (got {value})"));
                }
            }
            if let Some(least) = v.least_grip.filter(|&l| !(l > 0.0 && l <= v.grip)) {
                say(format!("{at}.vise.leastGrip"), format!("{at}.vise.leastGrip: the least material a jaw grips must be more than 0 mm and at most the grip ({} mm; got {least})", v.grip));
            }
        }
        for (k, b) in self.boxes.iter().enumerate() {
            if !(0..3).all(|i| b.min[i].is_finite() && b.max[i].is_finite() && b.min[i] < b.max[i]) {
                say(format!("{at}.boxes[{k}]"), format!("{at}.boxes[{k}]: a fixture's least corner must be below its greatest in X, Y and Z (got {:?} to {:?})", b.min, b.max));
            }
        }
        for (k, m) in self.meshes.iter().enumerate() {
            if let Err(e) = m.file.mesh() {
                say(format!("{at}.meshes[{k}]"), format!("{at}.meshes[{k}]: the fixture's mesh cannot be read: {e}"));
            }
        }
        out
    }
}

/// `part` with the boxes of `keep_out` added, as one mesh to drop the cutter onto.
pub fn solid(part: &Mesh, keep_out: &[Held]) -> Mesh {
    let mut mesh = part.clone();
    for h in keep_out {
        let (a, b) = (h.solid.min, h.solid.max);
        let base = mesh.vertices.len() as u32;
        for k in 0..8 {
            mesh.vertices.push(DVec3::new(if k & 1 == 0 { a.x } else { b.x }, if k & 2 == 0 { a.y } else { b.y }, if k & 4 == 0 { a.z } else { b.z }));
        }
        // Outward, counter-clockwise seen from outside: bottom, top, then the four sides.
        let faces: [[u32; 3]; 12] = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]];
        mesh.faces.extend(faces.iter().map(|f| f.map(|v| base + v)));
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vises_jaws_grip_the_stocks_sides_and_a_box_is_outward() {
        let stock = Aabb { min: DVec3::new(-40.0, -25.0, -20.0), max: DVec3::new(40.0, 25.0, 1.0) };
        let f = Fixtures { vise: Some(Vise::default()), ..Fixtures::default() };
        let held = f.held(&stock);
        assert_eq!(held.len(), 2);
        assert_eq!(held[0].solid.max.y, -25.0);
        assert_eq!(held[1].solid.min.y, 25.0);
        assert_eq!(held[0].solid.max.z, -14.0);
        let out = f.keep_out(&stock);
        assert_eq!(out[0].solid.max.y, -24.0);
        assert_eq!(out[0].solid.max.z, -13.0);
        // The box's facets face out: its volume by the divergence theorem is positive.
        let m = solid(&Mesh::default(), &out[..1]);
        let volume: f64 = m.faces.iter().map(|f| m.vertices[f[0] as usize].dot(m.vertices[f[1] as usize].cross(m.vertices[f[2] as usize])) / 6.0).sum();
        let size = out[0].solid.size();
        assert!((volume - size.x * size.y * size.z).abs() < 1e-6, "{volume}");
        let bad = Fixtures {
            vise: Some(Vise { grip: 0.0, ..Vise::default() }),
            boxes: vec![FixtureBox { min: [0.0, 0.0, 1.0], max: [1.0, 1.0, 0.0], ..FixtureBox::default() }],
            clearance: -1.0,
            ..Fixtures::default()
        };
        let fields: Vec<String> = bad.problems("fixtures").into_iter().map(|p| p.0).collect();
        assert_eq!(fields, ["fixtures.clearance", "fixtures.vise.grip", "fixtures.boxes[0]"]);
    }
}
