//! The region a cutter's centre may occupy at a level (DESIGN.md idea 3): where the CL surface
//! stands at or below the level, as closed loops of lines that the seed 003 offsetter takes.
//!
//! Steps:
//! 1. once per CL surface ([`LevelMap::new`]): a bound from above of the highest height along
//!    every grid edge (the cutter widened by the grid's spacing, at the edge's lower end), and
//!    at a level, along the edges that bound leaves in doubt, the highest exact height
//!    ([`ClSurface::along`], which probes every peak in reach);
//! 2. at a level, marching squares on the nodes' exact heights; of two nodes inside whose edge
//!    rises above the level between them (a ridge between nodes, seed 001's blind spot, or a
//!    convex surface bulging between them) the higher is left out, and so is a node a `keep`
//!    mask refuses (outside the stock, no
//!    material near); the grid's border is outside. The crossing on an edge from an inside
//!    node is where the exact surface along the edge first rises above the level (found on the
//!    edge's exact profile, kept for the map's other levels, then checked at the point itself);
//! 3. every piece between two crossings is checked along its length and, where the surface
//!    rises above the level (a peak inside the cell), bent in towards the cell's inside node;
//! 4. loops are simplified within the chordal tolerance where the chord itself clears, and the
//!    corners the cells' diagonals chamfered are put back where the two edges to the corner
//!    clear the level (a pocket's corner is cleared as far as the tool reaches).
//!
//! So a boundary may lie inside the safe region, never past it by more than twice
//! [`Tolerances::interpolation`] (the exact surface's rise between two samples of
//! [`ClSurface::along`] that both clear the level, 0.001 mm); inside, a peak standing in the middle of a cell may rise above the
//! level by the cutter's rise at half a grid spacing from its axis (0 for a flat end's flat,
//! 0.003 mm for a φ6 ball on a 0.25 mm grid).

use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use crate::drawing::{Loop, Shape};
use crate::geom::{tolerance::BOUND_SLACK, DVec2, Tolerances};
use crate::mesh::Mesh;
use crate::parallel;
use crate::progress::Progress;
use crate::zmap::cl_exact::ExactBuilder;
use crate::zmap::surface::ClSurface;

/// Depth of the bending of one piece towards its inside node.
const BEND_DEPTH: usize = 6;
/// Halvings when pulling a point towards an inside node.
const PULL_STEPS: usize = 40;

/// A CL surface's grid with, along each of its edges, a bound from above of the surface's
/// highest there, and the exact highest where a level needs it.
///
/// The bound is the widened cutter's height ([`crate::zmap::drop::PointDrop::widened`], grown
/// by the grid's spacing) at the lower of the edge's two ends: every point of the edge is
/// within a spacing of either end. It takes one more z-map; the exact profile along an edge
/// ([`ClSurface::along`], a dozen drops) is taken only for an edge whose ends both stand at or
/// below a level its bound rises above, which on most parts is a few edges in a hundred.
pub struct LevelMap {
    /// Per node, the bound along the edge to its right and the edge up (`-inf` past the grid).
    right: Vec<f64>,
    up: Vec<f64>,
    /// The exact highest (with the interpolation allowance) along edges a level asked about,
    /// by node × 2 + direction (0 right, 1 up).
    exact: Mutex<HashMap<usize, f64>>,
    /// The exact profile along the grid edges levels found a crossing on, from the inside node
    /// to the outside one, as far as the first point above the level that asked
    /// ([`ClSurface::along_until`]): a wall's foot is the same crossing at every level below its
    /// top, and finding it takes a search down to [`crate::zmap::surface::MIN_PIECE`].
    profiles: Profiles,
    /// How many edge profiles levels have had to take (not found kept).
    taken: AtomicUsize,
}

/// Exact profiles along grid edges, by the edge's two nodes (from, to): whether it is the whole
/// profile (no point above the level that took it), and its points.
type Profiles = Mutex<HashMap<((isize, isize), (isize, isize)), (bool, Arc<[(f64, f64)]>)>>;

impl LevelMap {
    /// The map of `cl` from `wide`, the widened cutter's heights at every node of its grid.
    pub fn new(cl: &ClSurface, wide: &[f64], tol: &Tolerances) -> Option<LevelMap> {
        let (right, up) = LevelMap::rows(cl, wide, tol, 0..cl.field.ny)?;
        LevelMap::from_rows(cl, right, up)
    }

    /// The map of `cl` over `mesh`, the part its drops are of (the widened cutter's builder
    /// made here).
    pub fn of_part(cl: &ClSurface, mesh: &Mesh, tol: &Tolerances) -> LevelMap {
        LevelMap::widened_by(cl, &cl.drop().widened(mesh, cl.field.spacing, tol), tol)
    }

    /// The map of `cl` from `builder`, its drop's [`crate::zmap::drop::PointDrop::widened`]
    /// by the grid's spacing: its z-map made here, on every core natively.
    pub fn widened_by(cl: &ClSurface, builder: &ExactBuilder, tol: &Tolerances) -> LevelMap {
        LevelMap::new(cl, &LevelMap::widened_heights(cl, builder), tol).expect("the widened heights cover the grid")
    }

    /// The heights of `builder`'s cutter (`cl`'s drop widened, [`crate::zmap::drop::PointDrop::widened`])
    /// at every node of `cl`'s grid, on every core natively: what a map is made from, and the
    /// surface's node bounds ([`crate::zmap::bounds::NodeBounds`]).
    pub fn widened_heights(cl: &ClSurface, builder: &ExactBuilder) -> Vec<f64> {
        let f = &cl.field;
        // Without a way to cancel it cannot fail; were it to, bounds of +inf still hold.
        cl.drop().field_by(builder, f.grid(), cl.floor(), &mut Progress::none()).map(|w| w.z).unwrap_or_else(|_| vec![f64::INFINITY; f.nx * f.ny])
    }

    /// Rows `rows` of the map (each row's bounds along the edges to the right, then those
    /// along the edges up), from `wide`, the widened cutter's heights at the nodes of rows
    /// `rows.start..rows.end + 1` (those of the grid): a band, as a worker of a pool makes it.
    /// `None` when `wide` holds another number of heights.
    pub fn rows(cl: &ClSurface, wide: &[f64], tol: &Tolerances, rows: std::ops::Range<usize>) -> Option<(Vec<f64>, Vec<f64>)> {
        let f = &cl.field;
        let (nx, ny) = (f.nx, f.ny);
        let rows = rows.start.min(ny)..rows.end.min(ny);
        let held = rows.start..(rows.end + 1).min(ny);
        if wide.len() != held.len() * nx {
            return None;
        }
        let allowance = 2.0 * tol.interpolation + BOUND_SLACK;
        let at = |i: usize, j: usize| wide[(j - held.start) * nx + i];
        let (mut right, mut up) = (Vec::with_capacity(rows.len() * nx), Vec::with_capacity(rows.len() * nx));
        for j in rows {
            right.extend((0..nx).map(|i| if i + 1 < nx { at(i, j).min(at(i + 1, j)) + allowance } else { f64::NEG_INFINITY }));
            up.extend((0..nx).map(|i| if j + 1 < ny { at(i, j).min(at(i, j + 1)) + allowance } else { f64::NEG_INFINITY }));
        }
        Some((right, up))
    }

    /// The map of `cl` from its rows' bounds along the edges to the right and up (its bands
    /// joined); `None` when their number is not the grid's.
    pub fn from_rows(cl: &ClSurface, right: Vec<f64>, up: Vec<f64>) -> Option<LevelMap> {
        let n = cl.field.nx * cl.field.ny;
        (right.len() == n && up.len() == n).then(|| LevelMap { right, up, exact: Mutex::new(HashMap::new()), profiles: Mutex::new(HashMap::new()), taken: AtomicUsize::new(0) })
    }

    /// How many exact profiles along grid edges the regions asked of this map have taken: a
    /// crossing's profile is kept and serves every level it reaches above.
    pub fn profiles_taken(&self) -> usize {
        self.taken.load(Ordering::Relaxed)
    }

    /// The bounds along the edges to the right of every node, then those along the edges up
    /// (with the interpolation allowance the exact heights get).
    pub fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.right, &self.up)
    }

    /// The highest of the surface along each edge of `edges` (node × 2 + direction) with the
    /// interpolation allowance: from its exact profile, taken once per edge.
    fn exact_tops(&self, cl: &ClSurface, edges: &[usize], tol: &Tolerances) -> Vec<f64> {
        let f = &cl.field;
        let node = |c: usize| f.origin + DVec2::new((c % f.nx) as f64, (c / f.nx) as f64) * f.spacing;
        let missing: Vec<usize> = {
            let known = self.exact.lock().expect("the level map's cache");
            edges.iter().copied().filter(|e| !known.contains_key(e)).collect()
        };
        let tops = parallel::map_heavy(missing.len(), |k| {
            let (c, dir) = (missing[k] / 2, missing[k] % 2);
            let other = if dir == 0 { c + 1 } else { c + f.nx };
            cl.along(node(c), node(other)).into_iter().fold(f64::NEG_INFINITY, |m, (_, z)| m.max(z)) + 2.0 * tol.interpolation
        });
        let mut cache = self.exact.lock().expect("the level map's cache");
        cache.extend(missing.into_iter().zip(tops));
        edges.iter().map(|e| cache[e]).collect()
    }

    /// The region at `level`: where the cutter's centre stands at or below it, among the nodes
    /// `keep` accepts.
    pub fn region(&self, cl: &ClSurface, level: f64, keep: &dyn Fn(usize, usize) -> bool, tol: &Tolerances) -> Shape {
        let f = &cl.field;
        let (nx, ny) = (f.nx, f.ny);
        let low: Vec<bool> = (0..nx * ny).map(|c| f.z[c] <= level && keep(c % nx, c / nx)).collect();
        // Nodes out only because `keep` refuses them: no corner is put back towards one.
        let refused: Vec<bool> = (0..nx * ny).map(|c| f.z[c] <= level && !low[c]).collect();
        // A ridge between two low nodes (or a convex surface bulging above the level between
        // them) leaves the higher of the two out: the edge from the other then gets its
        // crossing from the exact profile along it, where the surface first rises above the
        // level. Only edges whose bound rises above the level are looked at exactly.
        let mut asked = Vec::new();
        for c in (0..nx * ny).filter(|&c| low[c]) {
            let (i, j) = (c % nx, c / nx);
            if i + 1 < nx && low[c + 1] && self.right[c] > level + tol.height {
                asked.push(2 * c);
            }
            if j + 1 < ny && low[c + nx] && self.up[c] > level + tol.height {
                asked.push(2 * c + 1);
            }
        }
        let tops = self.exact_tops(cl, &asked, tol);
        let mut inside = low.clone();
        for (&e, &top) in asked.iter().zip(&tops) {
            let (c, dir) = (e / 2, e % 2);
            let other = if dir == 0 { c + 1 } else { c + nx };
            if top > level + tol.height {
                let higher = if f.z[other] >= f.z[c] { other } else { c };
                inside[higher] = false;
            }
        }
        // A node inside stands at least the back-off from the level's edge along the grid's
        // four directions: one just short of a cliff would make the boundary pass along the
        // cliff's foot, where a chord between two of its points can clip the cliff. Only a
        // cutter with a flat bottom makes cliffs (a ball's surface is smooth, and its level
        // curves, a waterline's path, stay where the crossings put them). A node beside a
        // ridge along one of its edges has a neighbour out already (the ridge's higher end).
        if cl.profile().is_ball() {
            return level_region(cl, &inside, &refused, level, self, tol);
        }
        let margin = back_off(cl, tol);
        let node = |i: usize, j: usize| f.origin + DVec2::new(i as f64, j as f64) * f.spacing;
        let edge_of = |c: usize| {
            let (i, j) = (c % nx, c / nx);
            (i > 0 && !inside[c - 1]) || (i + 1 < nx && !inside[c + 1]) || (j > 0 && !inside[c - nx]) || (j + 1 < ny && !inside[c + nx])
        };
        let near_edge: Vec<usize> = (0..nx * ny).filter(|&c| inside[c] && edge_of(c)).collect();
        for c in near_edge {
            let (i, j) = (c % nx, c / nx);
            let p = node(i, j);
            let steps = [(i + 1 < nx, DVec2::X), (i > 0, DVec2::NEG_X), (j + 1 < ny, DVec2::Y), (j > 0, DVec2::NEG_Y)];
            if steps.iter().any(|&(within, d)| within && cl.height(p + d * margin) > level + tol.height) {
                inside[c] = false;
            }
        }
        level_region(cl, &inside, &refused, level, self, tol)
    }
}

fn level_region(cl: &ClSurface, nodes_inside: &[bool], refused: &[bool], level: f64, map: &LevelMap, tol: &Tolerances) -> Shape {
    let f = &cl.field;
    let (nx, ny) = (f.nx, f.ny);
    let inside = |i: isize, j: isize| i >= 0 && j >= 0 && (i as usize) < nx && (j as usize) < ny && nodes_inside[j as usize * nx + i as usize];
    let node = |i: isize, j: isize| f.origin + DVec2::new(i as f64, j as f64) * f.spacing;
    let safe = |p: DVec2| cl.height(p) <= level + tol.height;
    let margin = back_off(cl, tol);
    // The crossing on the edge from inside node a to outside node b: where the exact profile
    // along the edge first rises above the level, checked at the point (and pulled back towards
    // a until safe). The profile is kept for other levels: up to its first point above a level
    // it is the same for every level, so a kept one that reaches above this level serves it
    // (a wall's foot is the same crossing at every level below its top), and so does a whole
    // one (an edge out past the grid's border).
    let crossing = |a: (isize, isize), b: (isize, isize)| -> DVec2 {
        let (pa, pb) = (node(a.0, a.1), node(b.0, b.1));
        let known = map.profiles.lock().expect("the level map's profiles").get(&(a, b)).cloned();
        let (_, profile) = known.filter(|(whole, p)| *whole || p.iter().any(|&(_, z)| z > level)).unwrap_or_else(|| {
            let profile: Arc<[(f64, f64)]> = cl.along_until(pa, pb, level).into();
            // Nothing above the level: the whole profile, which serves every level.
            let kept = (profile.iter().all(|&(_, z)| z <= level), profile);
            map.taken.fetch_add(1, Ordering::Relaxed);
            map.profiles.lock().expect("the level map's profiles").insert((a, b), kept.clone());
            kept
        });
        let mut t = 1.0;
        for w in profile.windows(2) {
            let ((t0, z0), (t1, z1)) = (w[0], w[1]);
            if z1 > level {
                t = if z1 > z0 { t0 + (t1 - t0) * ((level - z0) / (z1 - z0)).clamp(0.0, 1.0) } else { t0 };
                break;
            }
        }
        // Back off: at a cliff (a flat end's rim standing on an edge or a vertex) the safe side
        // ends sharply, and a piece between two points on it, a chord of the rim's circle
        // (radius at least the flat's), must not dip into it.
        t = (t - margin / f.spacing).max(0.0);
        if !safe(pa + (pb - pa) * t) {
            let (mut lo, mut hi) = (0.0, t);
            for _ in 0..PULL_STEPS {
                let mid = 0.5 * (lo + hi);
                if safe(pa + (pb - pa) * mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            t = lo;
        }
        pa + (pb - pa) * t
    };
    let value = |i: isize, j: isize| if inside(i, j) { f.at(i as usize, j as usize) - level } else { f.spacing };
    // Marching squares over the cells, padded by one so the border closes the loops. Each
    // directed piece has the inside on its left; pieces are keyed by the grid edges they join.
    // Edge key: (i, j, dir) with dir 0 the edge from node (i, j) to (i+1, j), 1 to (i, j+1).
    type Key = (isize, isize, u8);
    let mut pieces: std::collections::HashMap<Key, (Key, (isize, isize), Vec<(isize, isize)>)> = std::collections::HashMap::new();
    let mut points: std::collections::HashMap<Key, DVec2> = std::collections::HashMap::new();
    let mut point = |k: Key| -> DVec2 {
        *points.entry(k).or_insert_with(|| {
            let (a, b) = if k.2 == 0 { ((k.0, k.1), (k.0 + 1, k.1)) } else { ((k.0, k.1), (k.0, k.1 + 1)) };
            if inside(a.0, a.1) {
                crossing(a, b)
            } else {
                crossing(b, a)
            }
        })
    };
    for j in -1..ny as isize {
        for i in -1..nx as isize {
            // Corners counter-clockwise: 0 (i, j), 1 (i+1, j), 2 (i+1, j+1), 3 (i, j+1).
            let c = [inside(i, j), inside(i + 1, j), inside(i + 1, j + 1), inside(i, j + 1)];
            let case = c.iter().enumerate().fold(0u8, |m, (k, &b)| m | ((b as u8) << k));
            if case == 0 || case == 15 {
                continue;
            }
            // Edges: 0 bottom (i,j)-(i+1,j), 1 right (i+1,j)-(i+1,j+1), 2 top (i,j+1)-(i+1,j+1), 3 left (i,j)-(i,j+1).
            let edge = |e: u8| -> Key {
                match e {
                    0 => (i, j, 0),
                    1 => (i + 1, j, 1),
                    2 => (i, j + 1, 0),
                    _ => (i, j, 1),
                }
            };
            let centre_inside = || (value(i, j) + value(i + 1, j) + value(i + 1, j + 1) + value(i, j + 1)) <= 0.0;
            // Pieces (from edge, to edge) with the inside on the left, walking counter-clockwise
            // around inside corners.
            let list: &[(u8, u8)] = match case {
                1 => &[(3, 0)],
                2 => &[(0, 1)],
                3 => &[(3, 1)],
                4 => &[(1, 2)],
                5 => {
                    if centre_inside() {
                        &[(3, 2), (1, 0)]
                    } else {
                        &[(3, 0), (1, 2)]
                    }
                }
                6 => &[(0, 2)],
                7 => &[(3, 2)],
                8 => &[(2, 3)],
                9 => &[(2, 0)],
                10 => {
                    if centre_inside() {
                        &[(0, 3), (2, 1)]
                    } else {
                        &[(0, 1), (2, 3)]
                    }
                }
                11 => &[(2, 1)],
                12 => &[(1, 3)],
                13 => &[(1, 0)],
                14 => &[(0, 3)],
                _ => &[],
            };
            let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            // The corner (its index) at the inside end of an edge.
            let end_of = |e: u8| -> usize {
                let ends = [[0usize, 1], [1, 2], [3, 2], [0, 3]][e as usize];
                if inside(corners[ends[0]].0, corners[ends[0]].1) {
                    ends[0]
                } else {
                    ends[1]
                }
            };
            // The inside corner to bend a piece towards: the one farthest from the outside
            // corners (the diagonal one when three are inside), on the piece's side in a saddle.
            let corner = |e: u8| -> (isize, isize) {
                let own = corners[end_of(e)];
                if case == 5 || case == 10 {
                    return own;
                }
                let outside: Vec<(isize, isize)> = corners.iter().copied().filter(|c| !inside(c.0, c.1)).collect();
                let far = |c: (isize, isize)| outside.iter().map(|o| (o.0 - c.0).abs() + (o.1 - c.1).abs()).min().unwrap_or(0);
                corners.iter().copied().filter(|c| inside(c.0, c.1)).max_by_key(|&c| far(c)).unwrap_or(own)
            };
            // The inside ends of two edges joined through inside corners only, along the cell's
            // sides (each safe from end to end): the way round a piece that will not clear.
            let stairs = |from: u8, to: u8| -> Vec<(isize, isize)> {
                let (s0, s1) = (end_of(from), end_of(to));
                for dir in [1usize, 3] {
                    let mut path = vec![corners[s0]];
                    let mut k = s0;
                    while k != s1 {
                        k = (k + dir) % 4;
                        if !inside(corners[k].0, corners[k].1) {
                            break;
                        }
                        path.push(corners[k]);
                    }
                    if k == s1 && inside(corners[k].0, corners[k].1) {
                        return path;
                    }
                }
                vec![corners[s0]]
            };
            for &(from, to) in list {
                let (ka, kb) = (edge(from), edge(to));
                point(ka);
                point(kb);
                pieces.insert(ka, (kb, corner(from), stairs(from, to)));
            }
        }
    }
    // Chain the pieces into loops.
    let mut loops = Vec::new();
    let keys: Vec<Key> = {
        let mut k: Vec<Key> = pieces.keys().copied().collect();
        k.sort();
        k
    };
    let mut used = std::collections::HashSet::new();
    for start in keys {
        if used.contains(&start) {
            continue;
        }
        let mut ring: Vec<Piece> = Vec::new();
        let mut k = start;
        while used.insert(k) {
            let Some((next, corner, stairs)) = pieces.get(&k) else { break };
            ring.push(Piece { from: points[&k], corner: *corner, stairs: stairs.clone() });
            k = *next;
        }
        if ring.len() >= 3 {
            loops.push(ring);
        }
    }
    let shape_loops: Vec<Loop> = loops
        .into_iter()
        .filter_map(|ring| {
            let pts = bend(cl, level, &ring, &node, tol);
            let pts = sharpen(cl, level, &simplify(cl, level, &pts, tol), refused, tol);
            (pts.len() >= 3).then(|| Loop::polygon(&pts))
        })
        .filter(|l| l.area().abs() > 1e-12)
        .collect();
    Shape::new(shape_loops)
}

/// How far boundary points stay in from the level's edge: the chordal tolerance, plus twice the
/// sag of a chord a cell's diagonal long on the tightest rim a cliff can have (a circle of the
/// flat's radius about a vertex or a vertical edge; a ball's surface has no cliff, its radius
/// stands in).
pub fn back_off(cl: &ClSurface, tol: &Tolerances) -> f64 {
    let p = cl.profile();
    let rim = if p.flat_radius() > 0.0 { p.flat_radius() } else { p.radius };
    let diagonal = cl.field.spacing * std::f64::consts::SQRT_2;
    tol.chordal + 2.0 * diagonal * diagonal / (8.0 * rim.max(1e-3))
}

/// The ring's points with every piece between two of them checked along its length and, where
/// the surface rises above the level, bent in towards the piece's inside node.
/// A piece of a marching-squares loop: where it starts (on a grid edge), the inside corner to
/// bend it towards, and the inside nodes that lead from its start's edge to its end's.
struct Piece {
    from: DVec2,
    corner: (isize, isize),
    stairs: Vec<(isize, isize)>,
}

/// The ring's points with every piece between two of them checked along its length and, where
/// the surface rises above the level, bent in towards the piece's inside corner; a piece that
/// will not bend clear goes round by the inside nodes, along the cell's sides.
fn bend(cl: &ClSurface, level: f64, ring: &[Piece], node: &dyn Fn(isize, isize) -> DVec2, tol: &Tolerances) -> Vec<DVec2> {
    // The highest point of the surface along a piece above the level, if any (between two
    // samples `along` lets the surface rise up to twice the interpolation tolerance above
    // their chord: that is how far past the level a boundary may go).
    let worst = |a: DVec2, b: DVec2| -> Option<f64> { cl.along(a, b).into_iter().filter(|&(_, z)| z > level + tol.height).max_by(|p, q| p.1.total_cmp(&q.1)).map(|(t, _)| t) };
    let clears = |a: DVec2, b: DVec2| clears_level(cl, level, a, b, tol);
    let safe = |p: DVec2| cl.height(p) <= level + tol.height;
    #[allow(clippy::too_many_arguments)]
    fn towards(
        a: DVec2,
        b: DVec2,
        c: DVec2,
        depth: usize,
        worst: &dyn Fn(DVec2, DVec2) -> Option<f64>,
        clears: &dyn Fn(DVec2, DVec2) -> bool,
        safe: &dyn Fn(DVec2) -> bool,
        out: &mut Vec<DVec2>,
    ) -> bool {
        let Some(t) = worst(a, b) else {
            out.push(b);
            return true;
        };
        if depth == 0 {
            // Through the inside node itself, when that clears.
            if clears(a, c) && clears(c, b) {
                out.push(c);
                out.push(b);
                return true;
            }
            return false;
        }
        // The highest point along it, pulled towards the inside node c until safe, and a
        // quarter further, so the pieces from there clear a cliff's rim.
        let m = a + (b - a) * t.clamp(0.05, 0.95);
        let (mut lo, mut hi) = (0.0, 1.0);
        if safe(m) {
            hi = 0.0;
        } else {
            for _ in 0..PULL_STEPS {
                let u = 0.5 * (lo + hi);
                if safe(m + (c - m) * u) {
                    hi = u;
                } else {
                    lo = u;
                }
            }
        }
        let q = m + (c - m) * (hi + 0.25 * (1.0 - hi));
        towards(a, q, c, depth - 1, worst, clears, safe, out) && towards(q, b, c, depth - 1, worst, clears, safe, out)
    }
    let n = ring.len();
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let (a, b) = (ring[k].from, ring[(k + 1) % n].from);
        let c = node(ring[k].corner.0, ring[k].corner.1);
        let mark = out.len();
        if !towards(a, b, c, BEND_DEPTH, &worst, &clears, &safe, &mut out) {
            // Round by the inside nodes: from the start along its edge to the edge's inside
            // end, along the cell's sides, and out along the end's edge.
            out.truncate(mark);
            out.extend(ring[k].stairs.iter().map(|&(i, j)| node(i, j)));
            out.push(b);
        }
    }
    out
}

/// Drops points whose neighbours' chord stays within the chordal tolerance of them and clears
/// the level along its length (Douglas–Peucker on the closed ring, greedy).
fn simplify(cl: &ClSurface, level: f64, pts: &[DVec2], tol: &Tolerances) -> Vec<DVec2> {
    let clears = |a: DVec2, b: DVec2| clears_level(cl, level, a, b, tol);
    let mut out: Vec<DVec2> = Vec::with_capacity(pts.len());
    let n = pts.len();
    if n < 4 {
        return pts.to_vec();
    }
    let mut anchor = 0;
    out.push(pts[0]);
    let mut k = 1;
    while k < n {
        // Extend the chord from the anchor as far as every skipped point stays near it, and
        // take the farthest end within that whose chord clears the level (tried farthest
        // first: on a smooth boundary the first try is the one).
        let a = pts[anchor];
        let mut m = k + 1;
        while m <= n && m - anchor <= 64 && (anchor + 1..m).all(|q| distance_to_segment(pts[q], a, pts[m % n]) <= tol.chordal) {
            m += 1;
        }
        let best = (k + 1..m).rev().find(|&m| clears(a, pts[m % n])).unwrap_or(k);
        if best >= n {
            break;
        }
        out.push(pts[best]);
        anchor = best;
        k = best + 1;
    }
    out
}

/// Puts back the corners marching squares cut off. Where a short edge (at most two cells'
/// diagonal) joins two edges that turn by 60° or more round it, their lines meet just beyond
/// it: a convex corner of the region, such as the one a pocket's inside corner
/// makes of where the tool's centre may go, which the cells' diagonal chamfered (leaving
/// material in the pocket's corner). The meeting point replaces the short edge when the two
/// new edges clear the level along their length, so the boundary still never passes the safe
/// region; and only where the meeting point's cell has no node a keep mask refused (`refused`:
/// low enough, but out): there the boundary is no corner of the part's but where the region
/// was told to end (no material within reach, another tool's octants), and a corner put back
/// past it takes the tool where its levels above did not go.
fn sharpen(cl: &ClSurface, level: f64, pts: &[DVec2], refused: &[bool], tol: &Tolerances) -> Vec<DVec2> {
    let n = pts.len();
    if n < 4 {
        return pts.to_vec();
    }
    let clears = |a: DVec2, b: DVec2| clears_level(cl, level, a, b, tol);
    let ring = Loop::polygon(pts);
    let short = 2.0 * std::f64::consts::SQRT_2 * cl.field.spacing;
    let f = &cl.field;
    let near_refused = |x: DVec2| {
        let g = (x - f.origin) / f.spacing;
        let (i, j) = (g.x.floor() as isize, g.y.floor() as isize);
        [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)].into_iter().any(|(a, b)| a >= 0 && b >= 0 && (a as usize) < f.nx && (b as usize) < f.ny && refused[b as usize * f.nx + a as usize])
    };
    let mut out = Vec::with_capacity(n + 4);
    for i in 0..n {
        let (a, b, c, d) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n], pts[(i + 2) % n]);
        out.push(b);
        let (u, e, w) = (b - a, c - b, d - c);
        // A corner: the edges either side turn by 60° or more (a curve's small turns are left).
        let half = 0.5 * cl.field.spacing;
        if e.length() > short || u.length() < half || w.length() < half || u.normalize().dot(w.normalize()) > 0.5 {
            continue;
        }
        // b + u s = c + w t: forward from b along a→b, back from c along c→d.
        let cross = u.perp_dot(w);
        if cross.abs() <= 1e-12 * u.length() * w.length() {
            continue;
        }
        let (s, t) = (e.perp_dot(w) / cross, e.perp_dot(u) / cross);
        let x = b + u * s;
        // A convex corner: between the chamfer and the meeting point lies what the ring left
        // out (at a reflex one, what it holds).
        let between = (b + c) * 0.25 + x * 0.5;
        if s > 0.0 && t < 0.0 && x.distance(b) <= short && x.distance(c) <= short && !ring.contains(between) && !near_refused(x) && clears(b, x) && clears(x, c) {
            out.push(x);
        }
    }
    out
}

/// Whether the exact surface stays at or below `level` all along the segment from `a` to `b`.
fn clears_level(cl: &ClSurface, level: f64, a: DVec2, b: DVec2, tol: &Tolerances) -> bool {
    cl.stays_below(a, b, level + tol.height)
}

fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let t = if d.length_squared() > 0.0 { ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
    p.distance(a + d * t)
}
