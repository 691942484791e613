//! Seed 002's accuracy experiment (§4, Table 1 and 2, Fig. 6–9): a φ4 flat and a φ4 ball end
//! mill cutting a groove and a side cut through a block, simulated by the four stock models at
//! cells of 0.5, 0.3 and 0.1 mm. The paper's figure of the set-up is lost from our copy, so the
//! cuts are laid out here and their exact removed volumes derived in closed form: the tool
//! crosses the whole block on a straight line, so the volume is the block's length times the
//! area of the cutter's cross-section inside the block.
//!
//! The cuts sit off the cell grid on purpose (a groove centred at y = 10.37, a depth of 1.83 mm,
//! a radial engagement of 0.73 mm), so no model is helped by walls or floors that fall on cell
//! boundaries. Shared by the tests, the native benchmark and the wasm benchmark.

use super::{Model, Sweep};
use crate::cutter::Profile;
use crate::geom::{Aabb, DVec3};

/// Tool radius (mm): φ4.
pub const RADIUS: f64 = 2.0;
/// Depth of cut below the block's top (mm).
pub const DEPTH: f64 = 1.83;
/// Radial engagement of the side cut (mm).
pub const ENGAGEMENT: f64 = 0.73;
/// Centre line of the groove (mm).
pub const GROOVE_Y: f64 = 10.37;
/// The cell sizes of Table 2 (mm).
pub const CELLS: [f64; 3] = [0.5, 0.3, 0.1];
/// Length of each programmed move (mm), as a program's short moves would be.
pub const STEP: f64 = 1.0;

/// Which cut.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cut {
    Groove,
    Side,
}

/// One of the four cases: flat or ball, groove or side cut.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    pub ball: bool,
    pub cut: Cut,
}

impl Case {
    pub const ALL: [Case; 4] = [Case { ball: false, cut: Cut::Groove }, Case { ball: false, cut: Cut::Side }, Case { ball: true, cut: Cut::Groove }, Case { ball: true, cut: Cut::Side }];

    pub fn label(&self) -> String {
        format!("φ4 {} {}", if self.ball { "ball" } else { "flat" }, if self.cut == Cut::Groove { "groove" } else { "side cut" })
    }

    /// The block: 30 × 20 × 10 mm, top at z = 0.
    pub fn stock() -> Aabb {
        Aabb { min: DVec3::new(0.0, 0.0, -10.0), max: DVec3::new(30.0, 20.0, 0.0) }
    }

    pub fn profile(&self) -> Profile {
        Profile::new(RADIUS, if self.ball { RADIUS } else { 0.0 })
    }

    /// The tool's centre line in Y.
    pub fn y(&self) -> f64 {
        match self.cut {
            Cut::Groove => GROOVE_Y,
            Cut::Side => Case::stock().max.y + RADIUS - ENGAGEMENT,
        }
    }

    /// The tip's way through the block in moves of [`STEP`]: from x = -3 (clear of the block) to
    /// x = 33 (clear again).
    pub fn moves(&self) -> Vec<(DVec3, DVec3)> {
        let (start, end) = (-3.0, 33.0);
        let count = ((end - start) / STEP).round() as usize;
        let at = |k: usize| DVec3::new(start + k as f64 * STEP, self.y(), -DEPTH);
        (0..count).map(|k| (at(k), at(k + 1))).collect()
    }

    /// The cross-section of the cut in a plane across the path (mm²).
    pub fn section(&self) -> f64 {
        let stock = Case::stock();
        // Extent of the block across the path, relative to the tool's axis.
        let (side_lo, side_hi) = (stock.min.y - self.y(), stock.max.y - self.y());
        if !self.ball {
            let width = side_hi.min(RADIUS) - side_lo.max(-RADIUS);
            return width * DEPTH;
        }
        // The ball's centre stands RADIUS above the tip; the block's top is 0.
        let top = stock.max.z - (-DEPTH + RADIUS);
        disk_clip_area(RADIUS, side_hi, top) - disk_clip_area(RADIUS, side_lo, top)
    }

    /// The exact volume the whole cut removes (mm³).
    pub fn exact_volume(&self) -> f64 {
        let stock = Case::stock();
        (stock.max.x - stock.min.x) * self.section()
    }
}

/// The paper's Table 2 (φ4 flat and ball, octree without and with supersampling): for cells of
/// 0.5, 0.3 and 0.1 mm, (time in ms, error in the paper's unstated unit).
pub const PAPER_TABLE_2: [(&str, [(f64, f64); 3]); 4] = [
    ("flat, octree", [(351.0, 8.59), (3107.0, 5.018), (22979.0, 0.034)]),
    ("flat, octree + supersampling", [(380.0, 0.221), (2823.0, 0.473), (2164.0, 0.016)]),
    ("ball, octree", [(531.0, 15.88), (4844.0, 3.43), (39570.0, 1.33)]),
    ("ball, octree + supersampling", [(656.0, 1.626), (5365.0, 1.064), (39635.0, 0.918)]),
];

/// One simulation of one case by one model at one cell size.
#[derive(Clone, Copy, Debug)]
pub struct Row {
    pub case: Case,
    pub model: Model,
    pub cell: f64,
    /// Wall time of one run: building the stock and applying every move (s).
    pub seconds: f64,
    pub volume: f64,
    pub exact: f64,
}

impl Row {
    /// Relative error of the removed volume (%).
    pub fn error_percent(&self) -> f64 {
        (self.volume - self.exact) / self.exact * 100.0
    }

    pub fn line(&self, platform: &str) -> String {
        format!(
            "{platform:<8} {:<20} {:<24} cell {:.1} mm: {:>9.2} ms, removed {:>8.3} mm³ (exact {:.3}), error {:+.4} %",
            self.case.label(),
            self.model.label(),
            self.cell,
            self.seconds * 1e3,
            self.volume,
            self.exact,
            self.error_percent()
        )
    }
}

impl Case {
    /// Simulates this case with `model` at `cell` and returns the volume removed.
    pub fn simulate(&self, model: Model, cell: f64) -> f64 {
        self.per_move(model, cell).iter().sum()
    }

    /// The removed volume per move (mm³): the MRR per unit length of the paper's Fig. 7 and 8.
    pub fn per_move(&self, model: Model, cell: f64) -> Vec<f64> {
        let mut stock = model.stock(&Case::stock(), cell);
        let profile = self.profile();
        self.moves().iter().map(|&(a, b)| stock.apply(&Sweep::line(profile, a, b))).collect()
    }
}

/// Every case, model and cell size, each timed over `repeats` runs with `clock` (seconds).
pub fn table(clock: &dyn Fn() -> f64, repeats: usize) -> Vec<Row> {
    let mut rows = Vec::new();
    for case in Case::ALL {
        for model in Model::ALL {
            for cell in CELLS {
                let start = clock();
                let mut volume = 0.0;
                for _ in 0..repeats.max(1) {
                    volume = case.simulate(model, cell);
                }
                let seconds = (clock() - start) / repeats.max(1) as f64;
                rows.push(Row { case, model, cell, seconds, volume, exact: case.exact_volume() });
            }
        }
    }
    rows
}

/// Area of the disk of radius `r` about the origin where `u <= a` and `v <= b`.
pub fn disk_clip_area(r: f64, a: f64, b: f64) -> f64 {
    if b <= -r || a <= -r {
        return 0.0;
    }
    let a = a.min(r);
    // ∫ sqrt(r² - u²) du
    let f = |u: f64| {
        let u = u.clamp(-r, r);
        0.5 * (u * (r * r - u * u).max(0.0).sqrt() + r * r * (u / r).asin())
    };
    // Over u, the chord's length below v = b: (b + s) where s > |b|'s level is cut, else 2s
    // (b >= 0) or nothing (b < 0), with s = sqrt(r² - u²).
    let c = if b >= r { 0.0 } else { (r * r - b * b).sqrt() };
    let piece = |lo: f64, hi: f64| -> (f64, f64) { (lo, hi.min(a)) };
    let mut area = 0.0;
    let (lo, hi) = piece(-c, c);
    if hi > lo && b < r {
        area += b * (hi - lo) + f(hi) - f(lo);
    }
    for (lo, hi) in [piece(-r, -c), piece(c, r)] {
        if hi > lo && b >= 0.0 {
            area += 2.0 * (f(hi) - f(lo));
        }
    }
    area
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn disk_clip_area_closed_forms() {
        let r = 2.0;
        let close = |x: f64, y: f64| assert!((x - y).abs() < 1e-12, "{x} vs {y}");
        close(disk_clip_area(r, 5.0, 5.0), PI * r * r);
        close(disk_clip_area(r, 5.0, 0.0), PI * r * r / 2.0);
        close(disk_clip_area(r, 0.0, 0.0), PI * r * r / 4.0);
        close(disk_clip_area(r, 0.0, 5.0), PI * r * r / 2.0);
        // A circular segment of height h = r - d: r² acos(d / r) - d sqrt(r² - d²).
        let d = 0.6;
        let segment = r * r * (d / r).acos() - d * (r * r - d * d).sqrt();
        close(disk_clip_area(r, 5.0, -d), segment);
        close(disk_clip_area(r, 5.0, d), PI * r * r - segment);
        close(disk_clip_area(r, -d, 5.0), segment);
        // By numeric integration, an off-centre quadrant.
        let (a, b): (f64, f64) = (0.7, -0.4);
        let n = 200_000;
        let numeric: f64 = (0..n)
            .map(|k| {
                let u = -r + (k as f64 + 0.5) * (a + r) / n as f64;
                let s = (r * r - u * u).sqrt();
                (b.min(s) + s).max(0.0) * (a + r) / n as f64
            })
            .sum();
        assert!((disk_clip_area(r, a, b) - numeric).abs() < 1e-6);
    }

    #[test]
    fn the_cases_sections() {
        let flat_groove = Case { ball: false, cut: Cut::Groove };
        assert!((flat_groove.section() - 4.0 * DEPTH).abs() < 1e-12);
        let flat_side = Case { ball: false, cut: Cut::Side };
        assert!((flat_side.section() - ENGAGEMENT * DEPTH).abs() < 1e-12);
        let ball_groove = Case { ball: true, cut: Cut::Groove };
        let d = RADIUS - DEPTH;
        let segment = RADIUS * RADIUS * (d / RADIUS).acos() - d * (RADIUS * RADIUS - d * d).sqrt();
        assert!((ball_groove.section() - segment).abs() < 1e-12);
    }
}
