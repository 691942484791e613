//! A static packed R-tree over rectangles (16 children a node): built once, queried many times.
//! The offsetter finds candidate pairs of crossing segments and segments near a point with it.
//!
//! The rectangles are packed in the order given, without sorting: the offsetter's segments come
//! loop by loop, each the neighbour of the one before, so sixteen in a row make a compact node
//! (as a space-filling-curve order would, and for free).

use super::segment::Rect;
use super::DVec2;

const FANOUT: usize = 16;

/// Up to this many rectangles are kept as one flat level (every query tests them all, which
/// beats sorting them into a tree).
const FLAT: usize = 64;

/// Rectangles by index, packed level by level.
pub struct RectIndex {
    /// Per level, from the leaves up: node rectangles; the leaves are the rectangles themselves,
    /// by index.
    levels: Vec<Vec<Rect>>,
}

impl RectIndex {
    pub fn new(rects: &[Rect]) -> RectIndex {
        let mut levels = vec![rects.to_vec()];
        if rects.len() > FLAT {
            while levels.last().unwrap().len() > FANOUT {
                let below = levels.last().unwrap();
                let up = below.chunks(FANOUT).map(|c| c.iter().fold(Rect::EMPTY, |a, r| a.union(*r))).collect();
                levels.push(up);
            }
        }
        RectIndex { levels }
    }

    /// Calls `visit` with the index of every rectangle that overlaps `query`.
    pub fn query(&self, query: &Rect, mut visit: impl FnMut(usize)) {
        self.walk(
            0,
            |r| r.overlaps(query),
            |i| {
                visit(i);
                false
            },
        );
    }

    /// Calls `visit` once with every pair of overlapping rectangles `(i, j)`, `i < j`. Each
    /// rectangle is looked up only among those after it, so whole subtrees before it are
    /// skipped.
    pub fn pairs(&self, mut visit: impl FnMut(usize, usize)) {
        for (i, r) in self.levels[0].iter().enumerate() {
            self.walk(
                i + 1,
                |node| node.overlaps(r),
                |j| {
                    visit(i, j);
                    false
                },
            );
        }
    }

    /// Depth-first over the nodes that `enter` accepts, calling `visit` on accepted items from
    /// item `from` on until it returns true. The tree is implicit (children of node `i` are
    /// `16i..16i+16` one level down, so node `k` of level `l` holds items `k·16^l..(k+1)·16^l`),
    /// and the walk keeps only a cursor per level: nothing to allocate or clear.
    fn walk(&self, from: usize, enter: impl Fn(&Rect) -> bool, mut visit: impl FnMut(usize) -> bool) -> bool {
        let top = self.levels.len() - 1;
        // The first node of each level that holds an item from `from` on.
        let mut first = [0usize; MAX_DEPTH];
        let mut f = from;
        for l in first.iter_mut().take(top + 1) {
            *l = f;
            f /= FANOUT;
        }
        let (mut at, mut end) = ([0usize; MAX_DEPTH], [0usize; MAX_DEPTH]);
        at[top] = first[top];
        end[top] = self.levels[top].len();
        let mut level = top;
        loop {
            if at[level] == end[level] {
                if level == top {
                    return false;
                }
                level += 1;
                continue;
            }
            let i = at[level];
            at[level] += 1;
            if !enter(&self.levels[level][i]) {
                continue;
            }
            if level == 0 {
                if visit(i) {
                    return true;
                }
            } else {
                level -= 1;
                at[level] = (i * FANOUT).max(first[level]);
                end[level] = ((i + 1) * FANOUT).min(self.levels[level].len());
            }
        }
    }
}

/// Levels a tree of up to 16^12 items needs.
const MAX_DEPTH: usize = 12;

impl RectIndex {
    /// Calls `visit` with the index of every rectangle closer than `radius` to `q` until
    /// `visit` returns true (then returns true).
    pub fn any_within(&self, q: DVec2, radius: f64, visit: impl FnMut(usize) -> bool) -> bool {
        let r2 = radius * radius;
        self.walk(0, |r| distance_squared(r, q) < r2, visit)
    }
}

/// Squared distance from `q` to the rectangle (0 inside).
fn distance_squared(r: &Rect, q: DVec2) -> f64 {
    let dx = (r.min.x - q.x).max(q.x - r.max.x).max(0.0);
    let dy = (r.min.y - q.y).max(q.y - r.max.y).max(0.0);
    dx * dx + dy * dy
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_overlapping_rectangles() {
        let rects: Vec<Rect> = (0..1000)
            .map(|k| {
                let p = DVec2::new((k * 37 % 101) as f64, (k * 53 % 97) as f64);
                Rect { min: p, max: p + DVec2::new((k % 7) as f64, (k % 5) as f64) }
            })
            .collect();
        let index = RectIndex::new(&rects);
        let q = Rect { min: DVec2::new(20.0, 30.0), max: DVec2::new(40.0, 45.0) };
        let mut found = Vec::new();
        index.query(&q, |i| found.push(i));
        found.sort();
        let expected: Vec<usize> = (0..rects.len()).filter(|&i| rects[i].overlaps(&q)).collect();
        assert_eq!(found, expected);
    }

    #[test]
    fn finds_every_overlapping_pair_once() {
        for n in [10, 64, 65, 300, 1000] {
            let rects: Vec<Rect> = (0..n)
                .map(|k| {
                    let p = DVec2::new((k * 37 % 101) as f64, (k * 53 % 97) as f64);
                    Rect { min: p, max: p + DVec2::new((k % 7) as f64, (k % 5) as f64) }
                })
                .collect();
            let mut found = Vec::new();
            RectIndex::new(&rects).pairs(|i, j| found.push((i, j)));
            found.sort();
            let expected: Vec<(usize, usize)> = (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).filter(|&(i, j)| rects[i].overlaps(&rects[j])).collect();
            assert_eq!(found, expected, "{n} rectangles");
        }
    }
}
