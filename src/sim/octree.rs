//! The octree stock of seed 002 (§2.2), and the octree with supersampling (§3.3).
//!
//! A root cube around the stock is split into octants, recursively, only where an octant is
//! Partial: Full (black) and Empty (white) octants stay whole. Splitting stops at the leaf size.
//! A move classifies each octant against the sweep's envelope with bounds over the octant's
//! footprint ([`Sweep::bounds_over`]): untouched when the envelope stays above the octant's top,
//! emptied when it stays below its bottom, otherwise split further.
//!
//! * Classical (`k = 1`): a Partial leaf is decided by its centre, like a pixel (§3.1).
//! * With supersampling (`k > 1`): only boundary leaves get more sample points, `k × k` columns
//!   each holding the height of material above the leaf's floor at its own point (§3.3). The
//!   paper counts sample points inside the object; in 3-axis milling the material over a point is
//!   always one interval from the floor up, so a column's height is that count taken to the
//!   limit in z. The floors of cuts are then exact and only the walls are sampled, at
//!   `leaf / k`.

use super::sweep::Sweep;
use super::StockModel;
use crate::geom::{Aabb, DVec2, DVec3};

#[derive(Clone, Copy, Debug, PartialEq)]
enum Node {
    Empty,
    Full,
    /// Eight children at consecutive indices from this one (bit 0: +x, bit 1: +y, bit 2: +z).
    Split(u32),
    /// A supersampled leaf: `k * k` column heights above its floor, from this index.
    Columns(u32),
}

/// An octree stock.
#[derive(Clone, Debug)]
pub struct OctreeStock {
    origin: DVec3,
    side: f64,
    levels: u32,
    k: usize,
    nodes: Vec<Node>,
    columns: Vec<f64>,
    volume: f64,
}

impl OctreeStock {
    /// A box stock with leaves no larger than `leaf`; `k` columns per side in boundary leaves (1:
    /// the classical octree).
    pub fn new(stock: &Aabb, leaf: f64, k: usize) -> OctreeStock {
        let extent = stock.size().max_element().max(leaf);
        let levels = (extent / leaf).log2().ceil().max(0.0) as u32;
        let side = leaf * (1u64 << levels) as f64;
        let mut tree = OctreeStock { origin: stock.min, side, levels, k: k.max(1), nodes: vec![Node::Empty], columns: Vec::new(), volume: 0.0 };
        tree.nodes[0] = tree.build(stock, stock.min, side, 0);
        tree.volume = tree.node_volume(0, stock.min, side);
        tree
    }

    /// Leaf edge length.
    pub fn leaf(&self) -> f64 {
        self.side / (1u64 << self.levels) as f64
    }

    /// Nodes in the tree (including ones emptied since, which are not reclaimed).
    pub fn nodes(&self) -> usize {
        self.nodes.len()
    }

    fn build(&mut self, stock: &Aabb, lo: DVec3, size: f64, level: u32) -> Node {
        let hi = lo + DVec3::splat(size);
        if hi.cmple(stock.min).any() || lo.cmpge(stock.max).any() {
            return Node::Empty;
        }
        if lo.cmpge(stock.min).all() && hi.cmple(stock.max).all() {
            return Node::Full;
        }
        if level == self.levels {
            if self.k == 1 {
                let c = lo + DVec3::splat(size * 0.5);
                return if c.cmpge(stock.min).all() && c.cmple(stock.max).all() { Node::Full } else { Node::Empty };
            }
            let first = self.columns.len();
            let step = size / self.k as f64;
            for b in 0..self.k {
                for a in 0..self.k {
                    let q = lo.truncate() + DVec2::new((a as f64 + 0.5) * step, (b as f64 + 0.5) * step);
                    let inside = q.cmpge(stock.min.truncate()).all() && q.cmple(stock.max.truncate()).all();
                    self.columns.push(if inside { (stock.max.z.min(hi.z) - lo.z).max(0.0) } else { 0.0 });
                }
            }
            return Node::Columns(first as u32);
        }
        let first = self.nodes.len();
        self.nodes.extend([Node::Empty; 8]);
        let half = size * 0.5;
        for c in 0..8 {
            let child = self.build(stock, lo + child_offset(c, half), half, level + 1);
            self.nodes[first + c] = child;
        }
        Node::Split(first as u32)
    }

    fn node_volume(&self, n: usize, lo: DVec3, size: f64) -> f64 {
        match self.nodes[n] {
            Node::Empty => 0.0,
            Node::Full => size * size * size,
            Node::Split(first) => (0..8).map(|c| self.node_volume(first as usize + c, lo + child_offset(c, size * 0.5), size * 0.5)).sum(),
            Node::Columns(first) => {
                let k2 = self.k * self.k;
                let area = size * size / k2 as f64;
                self.columns[first as usize..first as usize + k2].iter().sum::<f64>() * area
            }
        }
    }

    fn cut(&mut self, n: usize, lo: DVec3, size: f64, level: u32, sweep: &Sweep) -> f64 {
        let node = self.nodes[n];
        if node == Node::Empty {
            return 0.0;
        }
        let hi = lo + DVec3::splat(size);
        let (lower, upper) = sweep.bounds_over(lo.truncate(), hi.truncate());
        if lower >= hi.z {
            return 0.0;
        }
        if upper <= lo.z {
            let removed = self.node_volume(n, lo, size);
            self.nodes[n] = Node::Empty;
            return removed;
        }
        match node {
            Node::Empty => 0.0,
            Node::Full if level == self.levels => {
                if self.k == 1 {
                    let c = lo + DVec3::splat(size * 0.5);
                    if sweep.lowest(c.truncate()) <= c.z {
                        self.nodes[n] = Node::Empty;
                        return size * size * size;
                    }
                    return 0.0;
                }
                let first = self.columns.len();
                self.columns.extend(std::iter::repeat_n(size, self.k * self.k));
                self.nodes[n] = Node::Columns(first as u32);
                self.cut_columns(n, first, lo, size, sweep)
            }
            Node::Full => {
                let first = self.nodes.len();
                self.nodes.extend([Node::Full; 8]);
                self.nodes[n] = Node::Split(first as u32);
                self.cut_children(n, first, lo, size, level, sweep)
            }
            Node::Split(first) => self.cut_children(n, first as usize, lo, size, level, sweep),
            Node::Columns(first) => self.cut_columns(n, first as usize, lo, size, sweep),
        }
    }

    fn cut_children(&mut self, n: usize, first: usize, lo: DVec3, size: f64, level: u32, sweep: &Sweep) -> f64 {
        let half = size * 0.5;
        let removed = (0..8).map(|c| self.cut(first + c, lo + child_offset(c, half), half, level + 1, sweep)).sum();
        if self.nodes[first..first + 8].iter().all(|c| *c == Node::Empty) {
            self.nodes[n] = Node::Empty;
        }
        removed
    }

    fn cut_columns(&mut self, n: usize, first: usize, lo: DVec3, size: f64, sweep: &Sweep) -> f64 {
        let k = self.k;
        let step = size / k as f64;
        let area = step * step;
        let mut removed = 0.0;
        let mut left = 0.0;
        for b in 0..k {
            for a in 0..k {
                let h = &mut self.columns[first + b * k + a];
                if *h > 0.0 && lo.z + *h > sweep.lowest_tip {
                    let e = sweep.lowest(lo.truncate() + DVec2::new((a as f64 + 0.5) * step, (b as f64 + 0.5) * step));
                    let new = (e - lo.z).max(0.0);
                    if new < *h {
                        removed += (*h - new) * area;
                        *h = new;
                    }
                }
                left += *h;
            }
        }
        if left == 0.0 {
            self.nodes[n] = Node::Empty;
        }
        removed
    }
}

fn child_offset(c: usize, half: f64) -> DVec3 {
    DVec3::new((c & 1) as f64, ((c >> 1) & 1) as f64, ((c >> 2) & 1) as f64) * half
}

impl StockModel for OctreeStock {
    fn apply(&mut self, sweep: &Sweep) -> f64 {
        let removed = self.cut(0, self.origin, self.side, 0, sweep);
        self.volume -= removed;
        removed
    }

    fn volume(&self) -> f64 {
        self.volume
    }
}
