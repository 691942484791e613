//! Stock from a mesh (`stock.mesh`): a casting, a forging or a near-net blank, read from its
//! own file (STL, OBJ, glTF), drawn in the same CAD model as the part and so in the part's own
//! coordinates. The file travels inside the job (its bytes in base64), so that a job, a
//! project and the page's workers all carry it; the CLI embeds a file a job only names. The
//! blank is placed with the part (its units, up axis and turn), and `centerTop` centres the
//! blank's top, the part keeping its place in it; the stock's box is the blank's. The
//! simulation starts from the material inside the blank, column by column (its lowest and
//! highest crossing of each vertical line: a 3-axis machine sees no undercut of a blank), so the
//! operations, the air-cut skipping and the verification see the air round it.

use std::sync::{Arc, OnceLock};

use base64::Engine as _;
use serde::{Deserialize, Serialize};

use crate::geom::segment::Rect;
use crate::geom::{index::RectIndex, DVec2, Tolerances};
use crate::mesh::Mesh;

/// A mesh file in the job: its name (the extension tells the format) and its bytes.
#[derive(Clone, Debug, Default, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct MeshFile {
    /// The file's name, with its extension. Default value: "".
    pub name: String,
    /// Its bytes in base64; none: the file lies beside the job file under `name` (the CLI
    /// reads it). Default value: none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub data: Option<String>,
    /// The mesh itself where it is given already placed in the job's frame (a setup's blank
    /// as that setup holds it), instead of the file.
    #[serde(skip)]
    #[ts(skip)]
    pub given: Option<Arc<Mesh>>,
    /// The file read, once.
    #[serde(skip)]
    #[ts(skip)]
    read: OnceLock<Result<Arc<Mesh>, String>>,
}

impl PartialEq for MeshFile {
    fn eq(&self, other: &MeshFile) -> bool {
        let same_given = match (&self.given, &other.given) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        self.name == other.name && self.data == other.data && same_given
    }
}

impl MeshFile {
    /// A file with its bytes.
    pub fn embedded(name: &str, bytes: &[u8]) -> MeshFile {
        MeshFile { name: name.into(), data: Some(base64::engine::general_purpose::STANDARD.encode(bytes)), ..MeshFile::default() }
    }

    /// A mesh given in the job's frame.
    pub fn given(name: &str, mesh: Mesh) -> MeshFile {
        MeshFile { name: name.into(), given: Some(Arc::new(mesh)), ..MeshFile::default() }
    }

    /// The file's mesh as read (in the file's units and axes), or why it cannot be read.
    pub fn mesh(&self) -> Result<Arc<Mesh>, String> {
        self.read
            .get_or_init(|| {
                let Some(data) = &self.data else {
                    return Err(format!("{} is named but its bytes are not in the job: run the job where the file lies beside it, or load the file", self.name));
                };
                let bytes = base64::engine::general_purpose::STANDARD.decode(data.trim()).map_err(|e| format!("{}: its data is not base64: {e}", self.name))?;
                let mesh = crate::mesh::import::read_mesh_auto(&bytes, Some(&self.name), &Tolerances::default()).map_err(|e| format!("{}: {e}", self.name))?;
                if mesh.faces.is_empty() {
                    return Err(format!("{}: no triangles", self.name));
                }
                Ok(Arc::new(mesh))
            })
            .clone()
    }
}

/// A blank's columns: the vertical lines through it, each crossing its surface, found through
/// an index of its faces seen from above (made once, asked at every cell of the stock).
pub struct Columns<'a> {
    blank: &'a Mesh,
    index: RectIndex,
}

impl<'a> Columns<'a> {
    pub fn new(blank: &'a Mesh) -> Columns<'a> {
        let rects: Vec<Rect> = blank
            .faces
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|v| blank.vertices[v as usize].truncate());
                Rect { min: a.min(b).min(c), max: a.max(b).max(c) }
            })
            .collect();
        Columns { blank, index: RectIndex::new(&rects) }
    }

    /// The material over `p`: `(floor, top)`, the lowest and highest crossing of the vertical
    /// line there (empty where the line misses the blank, or crosses it once).
    pub fn material(&self, p: DVec2) -> (f64, f64) {
        let (n, lo, hi) = self.crossings(p);
        if n >= 2 && hi > lo {
            (lo, hi)
        } else {
            (f64::NEG_INFINITY, f64::NEG_INFINITY)
        }
    }

    /// What is wrong with the blank as stock, in words, if anything: open (a vertical line
    /// through it crosses its surface once over part of it: a bottom or top missing), so that
    /// it holds no material there.
    pub fn fault(&self) -> Option<String> {
        const N: usize = 48;
        let b = self.blank.bounds();
        let (mut hit, mut once) = (0usize, 0usize);
        for i in 0..N {
            for j in 0..N {
                let p = DVec2::new(b.min.x + (i as f64 + 0.5) / N as f64 * (b.max.x - b.min.x), b.min.y + (j as f64 + 0.5) / N as f64 * (b.max.y - b.min.y));
                match self.crossings(p).0 {
                    0 => {}
                    1 => {
                        hit += 1;
                        once += 1;
                    }
                    _ => hit += 1,
                }
            }
        }
        (hit > 0 && once * 20 > hit).then(|| {
            format!(
                "the blank is open: over {:.0} % of it a vertical line crosses its surface once (its bottom or its top is missing), so it holds no material there; export it as a closed solid",
                100.0 * once as f64 / hit as f64
            )
        })
    }

    /// How many times the vertical line over `p` crosses the blank's surface, and its lowest
    /// and highest crossing.
    fn crossings(&self, p: DVec2) -> (usize, f64, f64) {
        let (mut n, mut lo, mut hi) = (0, f64::INFINITY, f64::NEG_INFINITY);
        self.index.query(&Rect { min: p, max: p }, |k| {
            let [a, b, c] = self.blank.faces[k].map(|v| self.blank.vertices[v as usize]);
            // Barycentric coordinates of p in the triangle seen from above.
            let (e1, e2, d) = ((b - a).truncate(), (c - a).truncate(), p - a.truncate());
            let det = e1.perp_dot(e2);
            if det.abs() < 1e-12 {
                return;
            }
            let (u, v) = (d.perp_dot(e2) / det, e1.perp_dot(d) / det);
            const EDGE: f64 = 1e-9;
            if u >= -EDGE && v >= -EDGE && u + v <= 1.0 + EDGE {
                let z = a.z + u * (b.z - a.z) + v * (c.z - a.z);
                n += 1;
                lo = lo.min(z);
                hi = hi.max(z);
            }
        });
        (n, lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;

    #[test]
    fn a_blanks_columns_run_from_its_bottom_to_its_top() {
        // A tetrahedron: over (0.2, 0.2) its bottom face z = 0 and its slanted top face.
        let tris = vec![
            [DVec3::ZERO, DVec3::new(0.0, 1.0, 0.0), DVec3::new(1.0, 0.0, 0.0)],
            [DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, 0.0, 1.0)],
            [DVec3::ZERO, DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 1.0, 0.0)],
            [DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 0.0, 1.0)],
        ];
        let mesh = Mesh::from_triangles(tris, &Tolerances::DEFAULT).unwrap();
        let m = Columns::new(&mesh);
        let (lo, hi) = m.material(DVec2::new(0.2, 0.3));
        assert!(lo.abs() < 1e-12 && (hi - 0.5).abs() < 1e-12, "{lo} {hi}");
        assert_eq!(m.material(DVec2::new(0.8, 0.8)).1, f64::NEG_INFINITY);
        let file = MeshFile { name: "x.stl".into(), data: Some("***".into()), ..MeshFile::default() };
        assert!(file.mesh().unwrap_err().contains("not base64"));
        assert!(MeshFile { name: "x.stl".into(), ..MeshFile::default() }.mesh().unwrap_err().contains("named but"));
    }
}
