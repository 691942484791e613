//! What holds the part: whether the in-process stock still joins the part to material that the
//! workholding grips, and how much material a vise's jaws have to grip.
//!
//! The stock is the simulation's columns of spans ([`DexelStock`]). Two spans of neighbouring
//! columns (sharing a side) are one piece of material where they overlap in height by more
//! than [`JOIN`]; the pieces are the connected sets of spans. The part's material is the span
//! of each column over the part that holds the part's top there; it is held where its piece
//! holds a gripped span: one against a vise's jaw or a clamp's box within the fixture's height,
//! or, without fixtures, one in a column on the stock's sides (the stock held by its edges, as
//! a vise or clamps on its rim hold it). No peer checks this: a two-sided job that cut round
//! the part down to a thin web in its first setup and faced the web away in its second left
//! the part loose on the table without a word.

use crate::geom::{Aabb, DVec2};
use crate::sim::dexel::DexelStock;
use crate::zmap::HeightField;

/// Spans of neighbouring columns overlapping by more than this (mm) are one piece of material.
pub const JOIN: f64 = 0.01;

/// What grips the stock in a setup, as [`joined`] reads it.
#[derive(Clone, Debug)]
pub enum Grips {
    /// The fixtures' boxes (a vise's jaws, clamps, a plate): a span in a column within a cell
    /// of a box, overlapping its height, is gripped.
    Boxes(Vec<Aabb>),
    /// No fixture: the stock's sides (the columns of the grid's edge).
    Sides,
    /// No fixture, a stock that is not a box (a bar, a casting): the columns marked, its rim
    /// as it came ([`rim`]), row by row.
    Rim(Vec<bool>),
}

/// The columns of `stock` on its rim: holding material (more than [`JOIN`] of it) and beside
/// the grid's edge or a column without: a bar's round side seen from above, a casting's
/// outline, a box's four sides.
pub fn rim(stock: &DexelStock) -> Vec<bool> {
    let g = stock.grid();
    let solid: Vec<bool> = (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).map(|(i, j)| stock.spans(i, j).any(|(f, t)| t - f > JOIN)).collect();
    let at = |i: isize, j: isize| i >= 0 && j >= 0 && (i as usize) < g.nx && (j as usize) < g.ny && solid[j as usize * g.nx + i as usize];
    (0..g.ny)
        .flat_map(|j| (0..g.nx).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (i, j) = (i as isize, j as isize);
            at(i, j) && [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|(di, dj)| !at(i + di, j + dj))
        })
        .collect()
}

/// Whether the part is held.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Hold {
    Held,
    /// A piece of the part joined to nothing gripped, at a point of it (X, Y).
    Free(DVec2),
    /// No part over the stock's columns: nothing to judge.
    NoPart,
}

/// Whether `stock` joins every column's part material (the span holding `part`'s top there:
/// its heights on the stock's grid, not finite where there is no part) to a span `grips`
/// grips.
pub fn joined(stock: &DexelStock, part: &HeightField, grips: &Grips) -> Hold {
    let g = stock.grid();
    if part.nx != g.nx || part.ny != g.ny {
        return Hold::NoPart;
    }
    // Every span, numbered column by column.
    let mut first = Vec::with_capacity(g.nx * g.ny + 1);
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for j in 0..g.ny {
        for i in 0..g.nx {
            first.push(spans.len());
            spans.extend(stock.spans(i, j).filter(|(f, t)| t > f));
        }
    }
    first.push(spans.len());
    let column = |i: usize, j: usize| first[j * g.nx + i]..first[j * g.nx + i + 1];
    let mut sets = Sets::new(spans.len());
    for j in 0..g.ny {
        for i in 0..g.nx {
            for (di, dj) in [(1, 0), (0, 1)] {
                let (a, b) = (i + di, j + dj);
                if a >= g.nx || b >= g.ny {
                    continue;
                }
                for s in column(i, j) {
                    for t in column(a, b) {
                        let (lo, hi) = (spans[s].0.max(spans[t].0), spans[s].1.min(spans[t].1));
                        if hi - lo > JOIN {
                            sets.join(s, t);
                        }
                    }
                }
            }
        }
    }
    let mut gripped = vec![false; spans.len()];
    let cell = g.spacing;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            for s in column(i, j) {
                let (floor, top) = spans[s];
                let grip = match grips {
                    Grips::Sides => i == 0 || j == 0 || i + 1 == g.nx || j + 1 == g.ny,
                    Grips::Rim(rim) => rim[j * g.nx + i],
                    Grips::Boxes(boxes) => boxes
                        .iter()
                        .any(|b| p.x >= b.min.x - cell && p.x <= b.max.x + cell && p.y >= b.min.y - cell && p.y <= b.max.y + cell && top.min(b.max.z + cell) - floor.max(b.min.z - cell) > JOIN),
                };
                if grip {
                    let root = sets.find(s);
                    gripped[root] = true;
                }
            }
        }
    }
    let mut any = false;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let h = part.z[j * g.nx + i];
            if !h.is_finite() {
                continue;
            }
            // The span holding the part's top (or the material over it).
            let Some(s) = column(i, j).find(|&s| spans[s].0 < h - JOIN && spans[s].1 > h - JOIN) else { continue };
            any = true;
            let root = sets.find(s);
            if !gripped[root] {
                return Hold::Free(g.node(i, j));
            }
        }
    }
    if any {
        Hold::Held
    } else {
        Hold::NoPart
    }
}

/// How high the material of `stock` stands against a jaw's face: the most, over the columns
/// along the face (within `jaw`'s width, in the row or column of cells nearest the face at
/// `face` on the axis the jaw closes on, `x` or else `y`), of its overlap with the heights
/// `from`..`to` (the jaw's grip).
pub fn jaw_contact(stock: &DexelStock, along_x: bool, face: f64, width: (f64, f64), from: f64, to: f64) -> f64 {
    let g = stock.grid();
    let (n_across, o_across, n_along, o_along) = if along_x { (g.nx, g.origin.x, g.ny, g.origin.y) } else { (g.ny, g.origin.y, g.nx, g.origin.x) };
    let k = (((face - o_across) / g.spacing).round().max(0.0) as usize).min(n_across - 1);
    let mut most: f64 = 0.0;
    for m in 0..n_along {
        let along = o_along + m as f64 * g.spacing;
        if along < width.0 || along > width.1 {
            continue;
        }
        let (i, j) = if along_x { (k, m) } else { (m, k) };
        for (floor, top) in stock.spans(i, j) {
            most = most.max(top.min(to) - floor.max(from));
        }
    }
    most
}

/// Where the material of `stock` standing at least `least` high between the heights `from` and
/// `to` (a jaw's grip) reaches along X (`along_x`) or Y, over the columns within `width`
/// across: the least and greatest, each half a cell out from its column's centre; none
/// without such material.
pub fn band_extent(stock: &DexelStock, along_x: bool, width: (f64, f64), from: f64, to: f64, least: f64) -> Option<(f64, f64)> {
    let g = stock.grid();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for j in 0..g.ny {
        for i in 0..g.nx {
            let p = g.node(i, j);
            let (across, along) = if along_x { (p.x, p.y) } else { (p.y, p.x) };
            if along < width.0 || along > width.1 {
                continue;
            }
            if stock.spans(i, j).any(|(floor, top)| top.min(to) - floor.max(from) >= least) {
                lo = lo.min(across - g.spacing / 2.0);
                hi = hi.max(across + g.spacing / 2.0);
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// Disjoint sets, by index.
struct Sets {
    parent: Vec<usize>,
}

impl Sets {
    fn new(n: usize) -> Sets {
        Sets { parent: (0..n).collect() }
    }

    fn find(&mut self, mut k: usize) -> usize {
        while self.parent[k] != k {
            self.parent[k] = self.parent[self.parent[k]];
            k = self.parent[k];
        }
        k
    }

    fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;

    fn field(stock: &DexelStock, h: impl Fn(DVec2) -> f64) -> HeightField {
        let g = stock.grid();
        HeightField { origin: g.origin, spacing: g.spacing, nx: g.nx, ny: g.ny, z: (0..g.ny).flat_map(|j| (0..g.nx).map(move |i| (i, j))).map(|(i, j)| h(g.node(i, j))).collect() }
    }

    /// A block with a 10 mm square part in the middle: joined to the sides by a web, held;
    /// the web cut through all round, free; gripped by a box over the part itself, held again.
    #[test]
    fn a_part_cut_free_of_the_stocks_sides_is_found() {
        let raw = Aabb { min: DVec3::new(-20.0, -20.0, -10.0), max: DVec3::new(20.0, 20.0, 0.0) };
        let inside = |p: DVec2| p.x.abs() < 5.0 && p.y.abs() < 5.0;
        let part_at = |p: DVec2| if inside(p) { 0.0 } else { f64::NAN };
        let web = DexelStock::new(&raw, 0.5, 1).with_material(|p| if inside(p) { (-10.0, 0.0) } else { (-10.0, -9.7) });
        let part = field(&web, part_at);
        assert_eq!(joined(&web, &part, &Grips::Sides), Hold::Held);
        // A ring cut through round the part.
        let ring = |p: DVec2| !inside(p) && p.x.abs() < 8.0 && p.y.abs() < 8.0;
        let cut = DexelStock::new(&raw, 0.5, 1).with_material(|p| {
            if inside(p) {
                (-10.0, 0.0)
            } else if ring(p) {
                (-10.0, -10.0)
            } else {
                (-10.0, -9.7)
            }
        });
        let Hold::Free(at) = joined(&cut, &part, &Grips::Sides) else { panic!("held") };
        assert!(inside(at), "{at}");
        // A clamp's box pressing the part's top holds it.
        let clamp = Aabb { min: DVec3::new(-2.0, -2.0, 0.0), max: DVec3::new(2.0, 2.0, 5.0) };
        assert_eq!(joined(&cut, &part, &Grips::Boxes(vec![clamp])), Hold::Held);
        // Jaws on the sides of the cut block, up 6 mm: the outside is only 0.3 mm high.
        let jaw = Aabb { min: DVec3::new(-40.0, -30.0, -70.0), max: DVec3::new(40.0, -20.0, -4.0) };
        assert_eq!(joined(&cut, &part, &Grips::Boxes(vec![jaw])), Hold::Free(at));
        let contact = jaw_contact(&cut, false, -20.0, (-40.0, 40.0), -10.0, -4.0);
        assert!((contact - 0.3).abs() < 1e-9, "{contact}");
        // The material 6 mm up its sides is the part's alone: the jaws following it close on
        // the part's faces.
        let (lo, hi) = band_extent(&cut, false, (-40.0, 40.0), -10.0, -4.0, 3.0).unwrap();
        assert!((lo + 5.0).abs() < 0.26 && (hi - 5.0).abs() < 0.26, "{lo} {hi}");
    }
}
