//! The octree of the volume to remove (seed 000 §3, DESIGN.md idea 4), kept as a quadtree over
//! layers of heights: for 3-axis work the volume is `{(x, y, z) in stock : z > part(x, y) +
//! allowance}`, and every octant over a square F of the XY plane and heights `[z, top]` is
//! Full, Partial or Empty.
//!
//! 1. **The root** (§3.2 (2)): a square of side `d · 2^n` from the stock's corner, the smallest
//!    that holds the stock's footprint, with `d = γ · D` for the candidate tool. Subdividing it
//!    `n` times gives squares of side `d` ([`Squares::root`]); one more subdivision halves them
//!    ([`Squares::halved`]), so the squares of every later tool nest in the ones before.
//! 2. **Heights** (§3.2, Fig. 9): an octant taller than the axial depth `h = δ · D` is split in
//!    Z with its upper part taking the full `h`, so a tool's octants lie in layers
//!    `[z_i, z_{i-1}]`, `z_i = z_{i-1} − h` from the stock's top, the short remainder at the
//!    bottom; the layers' bottoms are the cutting planes (§3.3, Fig. 11).
//! 3. **Classification** ([`Octree::classify`]): an octant is **Full** when the candidate tool
//!    clears all of F at the octant's bottom without gouging (every node over F lies within the
//!    tool's radius of a centre it may take at `z`: where the CL z-map of the tool, grown by the
//!    wall allowance, plus the floor allowance, is at or below `z`) and the in-process stock
//!    still holds material to remove in it (any: a square the earlier tools left partly cut,
//!    the round tools' corners of the paper's Fig. 21, is the next matched tool's to clear
//!    rather than the last tool's; counting only octants wholly of material left three times
//!    as much to the smallest tool on the generated mould, and slowed the program by 60 %);
//!    **Empty** when it holds none (the stock is gone down to `z`
//!    there, or the part plus its allowance fills it); **Partial** otherwise. Material removed
//!    earlier, or never there, is not cut again; a round tool's leftovers in the corners of
//!    square octants (the paper's Fig. 21) are material like any other, as the stock was
//!    simulated.
//! 4. **The entry test** (§3.2 (3), Fig. 10): the Full octants of a layer form 4-connected
//!    components; the tool can enter a component that lies beside the air (an octant with no
//!    stock above its bottom, or the root's edge), where it comes in from outside, or that holds
//!    at least the area of 2 × 2 octants (side `2γD >= D`: room for the tool, Fig. 10 (c)), where
//!    it goes down by the shared helix or a ramp along its first ring.
//! 5. **What is cut**: the Full octants of the components the tool can enter, at a layer only
//!    where the layer above was cut too (or holds no material), so the tool never meets
//!    material deeper than its axial depth.
//!
//! [`Octree::boxes`] merges each layer's squares back into the quadtree's largest uniform
//! nodes, for the page's view of the stages.

use serde::Serialize;

use crate::geom::DVec2;
use crate::zmap::distance::{distance_to, distance_within};
use crate::zmap::{Grid, HeightField};

/// γ = d / D for the first tool (§3.2 (2)): the largest radial depth of cut.
pub const GAMMA_FIRST: f64 = 0.85;
/// The range of γ = d / D a later tool must match (§3.1: from the smallest tool that clears a
/// square of side d, `D = d / (1/2 + cos 45°/2)`, to `D = 2d`).
pub const GAMMA_RANGE: (f64, f64) = (0.5, 0.95);

/// The squares of one subdivision: side `side`, `nx × ny` of them from `origin`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Squares {
    pub origin: DVec2,
    pub side: f64,
    pub nx: usize,
    pub ny: usize,
    /// Subdivisions from the root (the root is `2^depth` squares a side).
    pub depth: u32,
}

impl Squares {
    /// The squares of side `side` that the smallest root of side `side · 2^n` from `min` holds
    /// when it covers `[min, max]`.
    pub fn root(min: DVec2, max: DVec2, side: f64) -> Squares {
        let extent = (max - min).max_element().max(side);
        let depth = (extent / side).log2().ceil().max(0.0) as u32;
        let n = |e: f64| ((e / side).ceil() as usize).clamp(1, 1 << depth);
        Squares { origin: min, side, nx: n(max.x - min.x), ny: n(max.y - min.y), depth }
    }

    /// One more subdivision: squares of half the side.
    pub fn halved(&self) -> Squares {
        Squares { origin: self.origin, side: self.side / 2.0, nx: self.nx * 2, ny: self.ny * 2, depth: self.depth + 1 }
    }

    pub fn count(&self) -> usize {
        self.nx * self.ny
    }

    /// The corners of square (i, j).
    pub fn rect(&self, i: usize, j: usize) -> (DVec2, DVec2) {
        let lo = self.origin + DVec2::new(i as f64, j as f64) * self.side;
        (lo, lo + DVec2::splat(self.side))
    }

    /// Indices (`lo..=hi` on each axis) of `grid`'s nodes in the closed square (i, j).
    fn nodes_in(&self, grid: Grid, i: usize, j: usize) -> Option<((usize, usize), (usize, usize))> {
        let (lo, hi) = self.rect(i, j);
        Some((grid.columns(lo.x, hi.x)?, grid.rows(lo.y, hi.y)?))
    }
}

/// What an octant holds of the volume to remove.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
pub enum State {
    Empty,
    Partial,
    Full,
}

/// One layer of octants: heights `[z, top]`, per square its state, whether it is air (no
/// stock above `z`) and whether it is cut.
#[derive(Clone, Debug)]
pub struct Layer {
    pub z: f64,
    pub top: f64,
    pub state: Vec<State>,
    pub air: Vec<bool>,
    /// Whether the stock holds material above `top` in the square.
    pub above: Vec<bool>,
    pub cut: Vec<bool>,
}

/// The volume to remove: the in-process stock's heights and the part's, on the stock's cells.
pub struct Volume<'a> {
    /// The stock's top over each cell's centre.
    pub stock: &'a HeightField,
    /// The part's height over each cell's centre (−∞ where there is none), on the same grid.
    pub part: &'a HeightField,
    /// Material on floors (mm).
    pub allowance: f64,
    /// Material thinner than this is not material (mm).
    pub tolerance: f64,
}

/// A tool's octants over its layers.
#[derive(Clone, Debug)]
pub struct Octree {
    pub squares: Squares,
    pub layers: Vec<Layer>,
}

/// An octant (or a merged node of the quadtree) for the view.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct OctantBox {
    pub min: [f64; 3],
    pub max: [f64; 3],
    /// Full and cut by the stage's tool (else Partial: material the tool cannot clear whole).
    pub full: bool,
}

impl Octree {
    /// Classifies the octants of `squares` over `layers` (`(z, top)` from the top down) for a
    /// tool whose CL z-map (grown by the wall allowance) is `cl`, against `volume`; then marks
    /// what the tool cuts (steps 3 to 5 of the module's docs).
    pub fn classify(squares: Squares, layers: &[(f64, f64)], cl: &HeightField, radius: f64, volume: &Volume) -> Octree {
        let (a, tol) = (volume.allowance, volume.tolerance);
        let cl_grid = cl.grid();
        let nodes: Vec<Option<((usize, usize), (usize, usize))>> = (0..squares.count()).map(|s| squares.nodes_in(cl_grid, s % squares.nx, s / squares.nx)).collect();
        // Per square at `z`: the farthest of its nodes from a centre the tool may take (+∞
        // where the CL z-map does not reach).
        let farthest = |z: f64| -> Vec<f64> {
            let safe: Vec<bool> = cl.z.iter().map(|&h| h + a <= z).collect();
            let d = distance_to(&safe, cl.nx, cl.ny, cl.spacing);
            nodes
                .iter()
                .map(|n| match *n {
                    Some(((i0, i1), (j0, j1))) => (j0..=j1).flat_map(|j| (i0..=i1).map(move |i| (i, j))).map(|(i, j)| d[j * cl.nx + i]).fold(f64::NEG_INFINITY, f64::max),
                    None => f64::INFINITY,
                })
                .collect()
        };
        // Per square, the stock's cells in it (half-open, so each cell counts once).
        let sg = volume.stock.grid();
        let cells: Vec<Option<((usize, usize), (usize, usize))>> = (0..squares.count())
            .map(|s| {
                let (lo, hi) = squares.rect(s % squares.nx, s / squares.nx);
                let (lo, hi) = (lo, hi - DVec2::splat(1e-9 * squares.side));
                Some((sg.columns(lo.x, hi.x)?, sg.rows(lo.y, hi.y)?))
            })
            .collect();
        let top_of = |s: usize| match cells[s] {
            Some(((i0, i1), (j0, j1))) => (j0..=j1).flat_map(|j| (i0..=i1).map(move |i| (i, j))).map(|(i, j)| volume.stock.at(i, j)).fold(f64::NEG_INFINITY, f64::max),
            None => f64::NEG_INFINITY,
        };
        let stock_top: Vec<f64> = (0..squares.count()).map(top_of).collect();

        let removable = |s: usize, z: f64| match cells[s] {
            Some(((i0, i1), (j0, j1))) => (j0..=j1).any(|j| (i0..=i1).any(|i| volume.stock.at(i, j) - z.max(volume.part.at(i, j) + a) > tol)),
            None => false,
        };
        let mut out = Vec::with_capacity(layers.len());
        for &(z, top) in layers {
            let far = farthest(z);
            let mut state = Vec::with_capacity(squares.count());
            let (mut air, mut above) = (Vec::with_capacity(squares.count()), Vec::with_capacity(squares.count()));
            for s in 0..squares.count() {
                air.push(stock_top[s] <= z + tol);
                above.push(stock_top[s] > top + tol);
                state.push(if stock_top[s] <= z + tol || !removable(s, z) {
                    State::Empty
                } else if far[s] <= radius {
                    State::Full
                } else {
                    State::Partial
                });
            }
            out.push(Layer { z, top, state, air, above, cut: vec![false; squares.count()] });
        }
        let mut tree = Octree { squares, layers: out };
        tree.mark_cuts();
        tree
    }

    /// Steps 4 and 5: the Full octants of the components the tool can enter, under octants cut
    /// (or without material) at the layer above.
    fn mark_cuts(&mut self) {
        let (nx, ny) = (self.squares.nx, self.squares.ny);
        for k in 0..self.layers.len() {
            let (before, rest) = self.layers.split_at_mut(k);
            let layer = &mut rest[0];
            let allowed = |s: usize| before.last().is_none_or(|up| up.cut[s] || !layer.above[s]);
            let full: Vec<bool> = (0..nx * ny).map(|s| layer.state[s] == State::Full && allowed(s)).collect();
            let mut seen = vec![false; nx * ny];
            for start in 0..nx * ny {
                if !full[start] || seen[start] {
                    continue;
                }
                let mut component = vec![start];
                seen[start] = true;
                let mut k = 0;
                let mut enterable = false;
                let mut area = 0usize;
                while k < component.len() {
                    let s = component[k];
                    k += 1;
                    let (i, j) = (s % nx, s / nx);
                    area += 1;
                    for (di, dj) in [(-1isize, 0isize), (1, 0), (0, -1), (0, 1)] {
                        let (a, b) = (i as isize + di, j as isize + dj);
                        if a < 0 || b < 0 || a >= nx as isize || b >= ny as isize {
                            enterable = true;
                            continue;
                        }
                        let t = b as usize * nx + a as usize;
                        if layer.air[t] {
                            enterable = true;
                        }
                        if full[t] && !seen[t] {
                            seen[t] = true;
                            component.push(t);
                        }
                    }
                }
                if enterable || area >= 4 {
                    for s in component {
                        layer.cut[s] = true;
                    }
                }
            }
        }
    }

    /// Whether the tool cuts any octant.
    pub fn cuts(&self) -> bool {
        self.layers.iter().any(|l| l.cut.iter().any(|&c| c))
    }

    /// The index of the layer whose bottom is `z` (within `same`).
    pub fn layer_at(&self, z: f64, same: f64) -> Option<usize> {
        self.layers.iter().position(|l| (l.z - z).abs() <= same)
    }

    /// Per node of `grid`, whether it lies in a square `layer` cuts (closed squares).
    pub fn mask(&self, layer: &Layer, grid: Grid) -> Vec<bool> {
        let mut mask = vec![false; grid.nodes()];
        for s in (0..self.squares.count()).filter(|&s| layer.cut[s]) {
            if let Some(((i0, i1), (j0, j1))) = self.squares.nodes_in(grid, s % self.squares.nx, s / self.squares.nx) {
                for j in j0..=j1 {
                    mask[j * grid.nx + i0..=j * grid.nx + i1].fill(true);
                }
            }
        }
        mask
    }

    /// Per layer, the centres (nodes of `grid`) from which the tool of `radius` clears the
    /// squares cut there: within its radius (and a node's spacing) of them. Below the first
    /// layer only centres taken at the layer above too, or with no material of `stock` above
    /// the layer within the radius (and two spacings), so the tool never meets material deeper
    /// than its axial depth, and above every centre the material stands no higher than the
    /// layer above (where rapids may come down to).
    pub fn centres(&self, grid: Grid, radius: f64, stock: &HeightField, tolerance: f64) -> Vec<Vec<bool>> {
        let sg = stock.grid();
        // The stock's cell nearest each node (none off the stock).
        let cell: Vec<Option<usize>> = (0..grid.nodes()).map(|c| sg.nearest(grid.node(c % grid.nx, c / grid.nx))).collect();
        let mut out: Vec<Vec<bool>> = Vec::with_capacity(self.layers.len());
        for layer in &self.layers {
            let d = distance_within(&self.mask(layer, grid), grid.nx, grid.ny, grid.spacing, radius + grid.spacing);
            let mut keep: Vec<bool> = d.iter().map(|&d| d <= radius + grid.spacing).collect();
            if let Some(above) = out.last() {
                let high: Vec<bool> = cell.iter().map(|c| c.is_some_and(|c| stock.z[c] > layer.top + tolerance)).collect();
                let near = distance_within(&high, grid.nx, grid.ny, grid.spacing, radius + 2.0 * grid.spacing);
                for (c, k) in keep.iter_mut().enumerate() {
                    *k = *k && (above[c] || near[c] > radius + 2.0 * grid.spacing);
                }
            }
            out.push(keep);
        }
        out
    }

    /// The area of the squares cut at each layer, summed (mm²).
    pub fn cut_area(&self) -> f64 {
        let side2 = self.squares.side * self.squares.side;
        self.layers.iter().map(|l| l.cut.iter().filter(|&&c| c).count() as f64 * side2).sum()
    }

    /// The octants cut (Full) and the Partial ones, each layer's merged into the largest
    /// uniform nodes of the quadtree; at most `limit` boxes (the Full ones first when there
    /// are more).
    pub fn boxes(&self, limit: usize) -> Vec<OctantBox> {
        let mut full = Vec::new();
        let mut partial = Vec::new();
        for layer in &self.layers {
            let class = |s: usize| {
                if layer.cut[s] {
                    1u8
                } else if layer.state[s] == State::Partial {
                    2
                } else {
                    0
                }
            };
            let mut emit = |lo: DVec2, hi: DVec2, c: u8| {
                let b = OctantBox { min: [lo.x, lo.y, layer.z], max: [hi.x, hi.y, layer.top], full: c == 1 };
                if c == 1 {
                    full.push(b)
                } else {
                    partial.push(b)
                }
            };
            if let Node::Uniform(c) = self.merge(0, 0, self.squares.depth, &class, &mut emit) {
                self.emit(0, 0, self.squares.depth, c, &mut emit);
            }
        }
        full.truncate(limit);
        partial.truncate(limit - full.len());
        full.extend(partial);
        full
    }

    /// The quadtree node at `level` (`2^level` squares a side) with lower left square (i, j):
    /// uniform, or mixed after emitting its uniform children of a class other than 0.
    fn merge(&self, i: usize, j: usize, level: u32, class: &dyn Fn(usize) -> u8, emit: &mut dyn FnMut(DVec2, DVec2, u8)) -> Node {
        let (nx, ny) = (self.squares.nx, self.squares.ny);
        if i >= nx || j >= ny {
            return Node::Outside;
        }
        if level == 0 {
            return Node::Uniform(class(j * nx + i));
        }
        let half = 1usize << (level - 1);
        let children = [(i, j), (i + half, j), (i, j + half), (i + half, j + half)];
        let kinds: Vec<Node> = children.iter().map(|&(a, b)| self.merge(a, b, level - 1, class, emit)).collect();
        let mut inside = kinds.iter().filter(|k| **k != Node::Outside);
        let first = *inside.next().expect("the first child is inside");
        if first != Node::Mixed && inside.all(|k| *k == first) {
            return first;
        }
        for (&(a, b), k) in children.iter().zip(&kinds) {
            if let Node::Uniform(c) = *k {
                self.emit(a, b, level - 1, c, emit);
            }
        }
        Node::Mixed
    }

    /// Emits the node at `level` from square (i, j), clipped to the squares, unless `c` is 0.
    fn emit(&self, i: usize, j: usize, level: u32, c: u8, emit: &mut dyn FnMut(DVec2, DVec2, u8)) {
        if c == 0 {
            return;
        }
        let side = 1usize << level;
        let lo = self.squares.rect(i, j).0;
        let hi = self.squares.rect((i + side).min(self.squares.nx) - 1, (j + side).min(self.squares.ny) - 1).1;
        emit(lo, hi, c);
    }
}

/// A quadtree node while merging.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Node {
    /// Wholly past the squares.
    Outside,
    Uniform(u8),
    Mixed,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_root_holds_the_stock_in_powers_of_two() {
        let s = Squares::root(DVec2::ZERO, DVec2::new(100.0, 60.0), 17.0);
        assert_eq!(s.depth, 3, "17 · 2³ = 136 holds 100; 17 · 2² = 68 does not");
        assert_eq!((s.nx, s.ny), (6, 4));
        let h = s.halved();
        assert_eq!((h.nx, h.ny, h.depth, h.side), (12, 8, 4, 8.5));
    }

    /// A flat plate of stock 10 mm above a part that is a floor with one pillar: squares over the
    /// pillar's reach are Partial, the others Full; a lone Full square walled in is not entered.
    #[test]
    fn squares_are_classified_and_entered() {
        let grid = Grid { origin: DVec2::ZERO, spacing: 1.0, nx: 41, ny: 41 };
        // CL: 0 everywhere except a 10 mm high block over x, y in [10, 20].
        let mut cl = grid.filled(0.0);
        for j in 0..41 {
            for i in 0..41 {
                if (10..=20).contains(&i) && (10..=20).contains(&j) {
                    cl.z[j * 41 + i] = 10.0;
                }
            }
        }
        let stock_grid = Grid { origin: DVec2::splat(0.5), spacing: 1.0, nx: 40, ny: 40 };
        let stock = stock_grid.filled(10.0);
        let part = stock_grid.filled(0.0);
        let volume = Volume { stock: &stock, part: &part, allowance: 0.0, tolerance: 1e-6 };
        let squares = Squares::root(DVec2::ZERO, DVec2::splat(40.0), 5.0);
        let tree = Octree::classify(squares, &[(5.0, 10.0), (0.0, 5.0)], &cl, 2.0, &volume);
        let l = &tree.layers[0];
        // Square (2, 2) spans [10, 15]²: over the block, Partial.
        assert_eq!(l.state[2 * 8 + 2], State::Partial);
        // Square (1, 1) spans [5, 10]²: its corner node (10, 10) is on the block, 1 mm from
        // a centre the tool may take, within its radius of 2.
        assert_eq!(l.state[8 + 1], State::Full);
        // Square (2, 1) spans [10, 15] × [5, 10]: its row at y = 10 is on the block, 1 mm
        // from the centres below it.
        assert_eq!(l.state[8 + 2], State::Full);
        assert_eq!(l.state[0], State::Full);
        assert!(l.cut[0], "open to the root's edge");
        assert!(tree.cuts());
        assert!(!tree.layers[1].cut[2 * 8 + 2]);
        let area = tree.cut_area();
        assert!(area > 0.0 && area < 2.0 * 1600.0);
        let boxes = tree.boxes(10_000);
        assert!(boxes.iter().any(|b| b.full) && boxes.iter().any(|b| !b.full));
        // Merged: fewer boxes than squares cut.
        assert!(boxes.iter().filter(|b| b.full).count() < tree.layers.iter().map(|l| l.cut.iter().filter(|&&c| c).count()).sum::<usize>());
    }
}
