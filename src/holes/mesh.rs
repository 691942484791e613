//! Vertical round holes found in a part's triangles (axis parallel to Z): the walls
//! (triangles whose normal is horizontal) joined edge to edge into pieces; a piece whose
//! vertices lie on one circle all round, its normals pointing in to the axis, is a hole. Its
//! top and bottom are the wall's; what meets the wall's lower rim says whether it goes
//! through (a face outside the circle: the part's bottom) or ends in a floor (inside: flat
//! when level, a cone when it slopes, as a drill leaves it). A counterbore is two holes on one
//! axis, each found on its own. A piece whose normals point out from the axis is a boss (a
//! stud an external thread is milled on).

use std::collections::HashMap;

use super::{Bottom, Hole};
use crate::geom::{DVec2, DVec3};
use crate::mesh::{union_root, Mesh};

/// A wall's normal may lean this far from horizontal (its z component).
const VERTICAL: f64 = 1e-3;

/// How far from the fitted circle a wall's vertex may lie (mm, or this share of the radius
/// if larger): a tessellated cylinder has its vertices on the circle.
const ON_CIRCLE: f64 = 1e-3;

/// The widest angle round the axis a hole's wall may leave without a vertex (radians): a
/// wall that does not go all round (a slot's end, a fillet) is no hole.
const LARGEST_GAP: f64 = std::f64::consts::FRAC_PI_3;

/// Every vertical round hole of `mesh`, largest first where two share an axis (a
/// counterbore above its hole), otherwise in order of their centres (x, then y).
pub fn find(mesh: &Mesh) -> Vec<Hole> {
    cylinders(mesh, false)
}

/// Every vertical round boss (a stud, for an external thread) of `mesh`: a wall whose normals
/// point out from its axis, its top and bottom the wall's; in the order of [`find`].
pub fn bosses(mesh: &Mesh) -> Vec<Hole> {
    cylinders(mesh, true)
}

/// The vertical round walls of `mesh` facing their axis (holes) or away from it (`outward`:
/// bosses).
fn cylinders(mesh: &Mesh, outward: bool) -> Vec<Hole> {
    let ids = welded(mesh);
    let faces: Vec<[usize; 3]> = mesh.faces.iter().map(|f| f.map(|v| ids[v as usize])).collect();
    let normal = |f: &[usize; 3]| {
        let [a, b, c] = f.map(|v| mesh.vertices[v]);
        (b - a).cross(c - a).try_normalize()
    };
    let normals: Vec<Option<DVec3>> = faces.iter().map(normal).collect();
    let wall: Vec<bool> = normals.iter().map(|n| n.is_some_and(|n| n.z.abs() < VERTICAL)).collect();
    // Edges to their faces.
    let mut edges: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (k, f) in faces.iter().enumerate() {
        for [a, b] in [[f[0], f[1]], [f[1], f[2]], [f[2], f[0]]] {
            if a != b {
                edges.entry((a.min(b), a.max(b))).or_default().push(k);
            }
        }
    }
    // Walls joined along shared edges (union-find).
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    for list in edges.values() {
        let walls: Vec<usize> = list.iter().copied().filter(|&k| wall[k]).collect();
        for w in walls.windows(2) {
            let (a, b) = (union_root(&mut parent, w[0]), union_root(&mut parent, w[1]));
            parent[a] = b;
        }
    }
    let mut pieces: HashMap<usize, Vec<usize>> = HashMap::new();
    for k in (0..faces.len()).filter(|&k| wall[k]) {
        let r = union_root(&mut parent, k);
        pieces.entry(r).or_default().push(k);
    }
    let mut holes = Vec::new();
    for piece in pieces.values() {
        let mut verts: Vec<usize> = piece.iter().flat_map(|&k| faces[k]).collect();
        verts.sort_unstable();
        verts.dedup();
        let points: Vec<DVec2> = verts.iter().map(|&v| mesh.vertices[v].truncate()).collect();
        let Some((center, radius)) = fit_circle(&points) else { continue };
        let within = ON_CIRCLE.max(ON_CIRCLE * radius);
        if points.iter().any(|p| (p.distance(center) - radius).abs() > within) || !all_round(&points, center) {
            continue;
        }
        // The normals point in to the axis: a hole, not a boss.
        let inward: f64 = piece
            .iter()
            .map(|&k| {
                let [a, b, c] = faces[k].map(|v| mesh.vertices[v]);
                let mid = ((a + b + c) / 3.0).truncate();
                normals[k].map_or(0.0, |n| n.truncate().dot(center - mid))
            })
            .sum();
        if (inward > 0.0) == outward || inward == 0.0 {
            continue;
        }
        let zs = verts.iter().map(|&v| mesh.vertices[v].z);
        let (bottom, top) = zs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| (lo.min(z), hi.max(z)));
        if outward {
            holes.push(Hole { center, diameter: 2.0 * radius, top, bottom, through: false, bottom_shape: Bottom::Flat, loop_index: None, layer: None, mark: false });
            continue;
        }
        // What meets each rim: the faces (not walls of this piece) on its edges there, inside
        // the circle or out, and of those inside how many slope.
        let in_piece: std::collections::HashSet<usize> = piece.iter().copied().collect();
        let meets = |z: f64| {
            let (mut inside, mut outside, mut sloped) = (0, 0, 0);
            for &k in piece {
                let f = faces[k];
                for [a, b] in [[f[0], f[1]], [f[1], f[2]], [f[2], f[0]]] {
                    let (pa, pb) = (mesh.vertices[a], mesh.vertices[b]);
                    if (pa.z - z).abs() > within || (pb.z - z).abs() > within {
                        continue;
                    }
                    for &other in edges.get(&(a.min(b), a.max(b))).into_iter().flatten() {
                        if in_piece.contains(&other) {
                            continue;
                        }
                        let [x, y, z] = faces[other].map(|v| mesh.vertices[v]);
                        let mid = ((x + y + z) / 3.0).truncate();
                        if mid.distance(center) < radius {
                            inside += 1;
                            if normals[other].is_some_and(|n| n.z.abs() < 1.0 - 1e-6) {
                                sloped += 1;
                            }
                        } else {
                            outside += 1;
                        }
                    }
                }
            }
            (inside, outside, sloped)
        };
        // A wall closed above (a floor or a drill's point over it) opens downwards: a hole to
        // drill from below, once the part is turned over, not from this side.
        let (over, open, _) = meets(top);
        if over > open {
            continue;
        }
        let (inside, outside, sloped) = meets(bottom);
        let (through, bottom_shape) = if inside == 0 && outside == 0 || outside > inside {
            (true, Bottom::Open)
        } else if sloped * 2 > inside {
            (false, Bottom::Cone)
        } else {
            (false, Bottom::Flat)
        };
        holes.push(Hole { center, diameter: 2.0 * radius, top, bottom, through, bottom_shape, loop_index: None, layer: None, mark: false });
    }
    // By centre to a ten-thousandth of a millimetre (a counterbore's centre and its hole's
    // differ in the last bits), the higher first on one axis.
    let key = |v: f64| (v * 1e4).round() as i64;
    // The last key first: each stable pass keeps the order of the one before among its ties.
    crate::geom::sort::sort_by_float(&mut holes, |h| -h.top);
    crate::geom::sort::sort_by_float(&mut holes, |h| key(h.center.y) as f64);
    crate::geom::sort::sort_by_float(&mut holes, |h| key(h.center.x) as f64);
    holes
}

/// Vertex ids with coincident vertices (within a millionth of the part's size) made one.
fn welded(mesh: &Mesh) -> Vec<usize> {
    let b = mesh.bounds();
    let size = (b.max - b.min).max_element().max(1e-9);
    let q = 1e-6 * size;
    let mut seen: HashMap<[i64; 3], usize> = HashMap::new();
    mesh.vertices
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let key = [(v.x / q).round() as i64, (v.y / q).round() as i64, (v.z / q).round() as i64];
            *seen.entry(key).or_insert(k)
        })
        .collect()
}

/// The circle nearest `points` in the least-squares sense of `x² + y² + a x + b y + c = 0`
/// (Kåsa's fit), about their mean for conditioning.
fn fit_circle(points: &[DVec2]) -> Option<(DVec2, f64)> {
    if points.len() < 6 {
        return None;
    }
    let mean = points.iter().copied().sum::<DVec2>() / points.len() as f64;
    let (mut sxx, mut sxy, mut syy, mut sxz, mut syz, mut sz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let n = points.len() as f64;
    for p in points {
        let d = *p - mean;
        let z = d.length_squared();
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
        sxz += d.x * z;
        syz += d.y * z;
        sz += z;
    }
    // With the mean at the origin: [sxx sxy; sxy syy] [a b]ᵀ = -[sxz syz]ᵀ, c = -sz / n.
    let det = sxx * syy - sxy * sxy;
    if det.abs() <= 1e-12 * (sxx * syy).max(1e-300) {
        return None;
    }
    let a = -(sxz * syy - syz * sxy) / det;
    let b = -(syz * sxx - sxz * sxy) / det;
    let c = -sz / n;
    let center = DVec2::new(-a / 2.0, -b / 2.0);
    let r2 = center.length_squared() - c;
    (r2 > 0.0).then(|| (mean + center, r2.sqrt()))
}

/// Whether the points go all round `center`, no gap wider than [`LARGEST_GAP`].
fn all_round(points: &[DVec2], center: DVec2) -> bool {
    let mut angles: Vec<f64> = points.iter().map(|p| (*p - center).to_angle()).collect();
    crate::geom::sort::sort_floats(&mut angles);
    let wrap = angles.first().map_or(0.0, |a| a + std::f64::consts::TAU) - angles.last().copied().unwrap_or(0.0);
    angles.windows(2).map(|w| w[1] - w[0]).chain([wrap]).all(|gap| gap <= LARGEST_GAP)
}
