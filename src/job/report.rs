//! What each operation of a job did: its time and length at the programmed feeds, the volume it
//! removed from the in-process stock and its peak material removal rate, and what it left
//! above the part (plus the job's allowance).

use serde::Serialize;

use super::schema::Job;
use crate::machining::report::{EngagementTarget, LoadReport, StageReport};
use crate::operations::Operation;
use crate::sim::program::ProgramMove;
use crate::sim::verify::Verification;
use crate::toolpath::Move;
use crate::zmap::HeightField;

/// One operation's figures.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct OperationReport {
    /// Its index in the job's operations.
    pub index: usize,
    pub name: String,
    /// The tools it used, in order.
    pub tools: Vec<u32>,
    pub moves: usize,
    /// Time at the programmed feeds and the rapid rate (s).
    pub seconds: f64,
    pub feed_length: f64,
    pub rapid_length: f64,
    /// Volume removed (mm³), when its moves were simulated.
    pub removed: Option<f64>,
    /// Largest material removal rate of its feed moves (mm³/min), when simulated.
    pub mrr_max: Option<f64>,
    /// The spindle power its heaviest cut takes (kW: [`crate::cutting::power`] of `mrrMax`),
    /// where the stock's material has a specific cutting force.
    pub power_max: Option<f64>,
    /// The thickest chip a tooth cut (mm per tooth, measured: [`crate::sim::feeds::chips`]),
    /// when simulated.
    pub chip_max: Option<f64>,
    /// Material left above the part plus the allowance after it, largest and mean over the
    /// part (mm), when the program was verified.
    pub left_max: Option<f64>,
    pub left_mean: Option<f64>,
    /// The load along its path against the reference, before and after seed 004's correction,
    /// where the operation measured it.
    pub load: Option<LoadReport>,
    /// The stages of an operation that chose its tools (seed 000): each tool, why, and what it did.
    pub stages: Option<Vec<StageReport>>,
    /// The engagement along its cut as the simulation measured it, where it holds one
    /// (adaptive clearing).
    pub engagement: Option<EngagementReport>,
    /// For a roughing after earlier work with larger tools (rest roughing: it cuts only what
    /// they left, the in-process stock), those tools, largest first; `removed` is what it took
    /// of their leftovers.
    pub rest_after: Vec<u32>,
}

impl OperationReport {
    /// One line for a person.
    pub fn describe(&self) -> String {
        let mut s = format!("{}: {:.0} s, {:.0} mm fed, {:.0} mm rapid", self.name, self.seconds, self.feed_length, self.rapid_length);
        if !self.rest_after.is_empty() {
            let after: Vec<String> = self.rest_after.iter().map(|t| format!("T{t}")).collect();
            s += &format!(", rest roughing after {}", after.join(", "));
        }
        if let (Some(v), Some(m)) = (self.removed, self.mrr_max) {
            s += &format!(", removed {v:.0} mm³, peak MRR {m:.0} mm³/min");
            if let Some(p) = self.power_max {
                s += &format!(" ({p:.2} kW)");
            }
        }
        if let Some(c) = self.chip_max.filter(|&c| c > 0.0) {
            s += &format!(", thickest chip {c:.4} mm/tooth");
        }
        if let (Some(a), Some(b)) = (self.left_max, self.left_mean) {
            s += &format!(", left up to {a:.3} mm (mean {b:.3} mm)");
        }
        if let Some(l) = &self.load {
            let ((p, ps), (e, es), (c, cs)) = (LoadReport::peak_and_spread(&l.plain), LoadReport::peak_and_spread(&l.load), LoadReport::peak_and_spread(&l.cut));
            s += &format!(
                "; per {:.2} mm over the reference ({:.0} mm³/min per mm of depth): the plain path's load peaks at {p:.2} (spread {ps:.2}), the path's at {e:.2} (spread {es:.2}), its removal rate at its feeds at {c:.2} (spread {cs:.2}), {:.0} mm at a lowered feed",
                l.sampling, l.reference, l.slowed
            );
        }
        if let Some(e) = &self.engagement {
            s += &format!("; {}", e.describe());
        }
        for stage in self.stages.iter().flatten() {
            s += &format!("\n  {}", stage.describe());
        }
        s
    }
}

/// The engagement angle of an operation's level cutting moves (those at one height that cut
/// more than a cell deep), as the simulation measured it, weighed by the moves' lengths: the
/// angle of the tool's circle inside the material, from the material's nearest edge `e` from
/// the move's path ([`crate::sim::verify::Verification::nearest`]: the nearest cut cell's
/// centre, less half a cell), the edge taken as parallel to the path on the side the material
/// lies (climb milling: the right). Along a line, `arccos(e / r)` (a straight cut `ae` into a
/// wall: `arccos(1 − ae/r)`); along an arc of radius ρ, where the edge is a circle about the
/// arc's centre, `arccos(e/r + (e² − r²)/(2ρr))` with the material outside it, ρ negative
/// with the material inside. A move whose nearest cut lies on its path (a slot, or more than
/// half the tool in the material) reads 90° or more: 90°.
#[derive(Clone, Debug, Default, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct EngagementReport {
    /// The angle the operation holds (degrees).
    pub target: f64,
    /// The share of the cutting length within ±10 % of the target, and above 1.3× it.
    pub within: f64,
    pub over: f64,
    /// The largest, the mean and the spread (standard deviation) by length (degrees).
    pub peak: f64,
    pub mean: f64,
    pub spread: f64,
    /// Each of the operation's moves' engagement (degrees; `null` where the move does not
    /// count: rapids, ramps and helices, moves that cut a cell deep or less), for the plot.
    pub moves: Vec<Option<f32>>,
}

impl EngagementReport {
    /// The engagement of `moves` (what the simulation measured of each: the volume it removed
    /// and the nearest its path came to a cell it cut, on cells of side `cell`) against
    /// `target`.
    pub fn measure(target: EngagementTarget, moves: &[ProgramMove], volumes: &[f64], nearest: &[f64], cell: f64) -> EngagementReport {
        let angles: Vec<Option<(f64, f64, f64)>> = moves
            .iter()
            .zip(volumes.iter().zip(nearest))
            .map(|(m, (&volume, &near))| {
                let r = 0.5 * m.cutter.diameter;
                let level = !m.mv.is_rapid() && (m.mv.to().z - m.from.z).abs() < 1e-9;
                let e = (near - 0.5 * cell).max(0.0);
                if !(level && volume > 0.0 && near.is_finite() && e < r - cell) {
                    return None;
                }
                let cos = match m.mv {
                    // The material outside the arc where it lies on the side away from its
                    // centre: the centre is on the right of a clockwise arc.
                    Move::Arc { center, clockwise, .. } => {
                        let rho = m.from.truncate().distance(center);
                        let rho = if clockwise == target.climb { -rho } else { rho };
                        e / r + (e * e - r * r) / (2.0 * rho * r)
                    }
                    _ => e / r,
                };
                Some((cos.clamp(0.0, 1.0).acos(), m.mv.length(m.from), target.at(m.mv.to().z)))
            })
            .collect();
        let counted: Vec<(f64, f64, f64)> = angles.iter().flatten().copied().collect();
        let total = counted.iter().map(|c| c.1).sum::<f64>().max(1e-12);
        // (+ 0.0: an empty sum is −0.)
        let share = |keep: &dyn Fn(f64, f64) -> bool| counted.iter().filter(|c| keep(c.0, c.2)).map(|c| c.1).sum::<f64>() / total + 0.0;
        let mean = counted.iter().map(|c| c.0 * c.1).sum::<f64>() / total;
        let var = counted.iter().map(|c| (c.0 - mean).powi(2) * c.1).sum::<f64>() / total;
        EngagementReport {
            target: target.angle.to_degrees(),
            within: share(&|a, t| (a - t).abs() <= 0.1 * t),
            over: share(&|a, t| a > 1.3 * t),
            peak: counted.iter().map(|c| c.0).fold(0.0, f64::max).to_degrees(),
            mean: mean.to_degrees(),
            spread: var.sqrt().to_degrees(),
            moves: angles.iter().map(|a| a.map(|(a, _, _)| a.to_degrees() as f32)).collect(),
        }
    }

    /// One phrase for a person.
    pub fn describe(&self) -> String {
        format!(
            "engagement {:.0} % of the cut within ±10 % of {:.1}°, {:.0} % above 1.3×, peak {:.1}°, mean {:.1}° (spread {:.1}°)",
            100.0 * self.within,
            self.target,
            100.0 * self.over,
            self.peak,
            self.mean,
            self.spread
        )
    }
}

/// What the feed optimisation did (a job's `simulation.optimizeFeeds`, [`crate::sim::feeds`]).
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct FeedReport {
    /// The program's time in motion at the feeds as planned, and as optimised (s; tool changes
    /// apart).
    pub plain: f64,
    pub seconds: f64,
    /// Cuts run faster for their thinner chips, moves that removed nothing run at the air feed,
    /// and moves slowed after for the spindle's power.
    pub faster: usize,
    pub aired: usize,
    pub slowed: usize,
}

impl FeedReport {
    /// One line for a person.
    pub fn describe(&self) -> String {
        format!(
            "feeds optimised: {} cuts faster for their thinner chips, {} moves in air at the air feed{}; {} in motion, {} as planned ({:.0} % saved)",
            self.faster,
            self.aired,
            if self.slowed > 0 { format!(", {} slowed for the spindle", self.slowed) } else { String::new() },
            crate::post::clock(self.seconds),
            crate::post::clock(self.plain),
            if self.plain > 0.0 { 100.0 * (1.0 - self.seconds / self.plain) } else { 0.0 }
        )
    }
}

/// The reports of a job's `enabled` operations: `ranges[k]` are the k-th one's moves, `volumes` what the
/// simulation removed per move (as many as it ran), `snapshots[k]` the stock's heights after
/// operation k when the program is verified, `rates` each simulated move's removal rate.
pub fn per_operation(
    job: &Job,
    enabled: &[usize],
    moves: &[ProgramMove],
    ranges: &[std::ops::Range<usize>],
    volumes: &[f64],
    rates: &[f64],
    snapshots: &[Option<HeightField>],
    verification: Option<&Verification>,
) -> Vec<OperationReport> {
    let mut reports: Vec<OperationReport> = enabled
        .iter()
        .map(|&i| (i, &job.operations[i]))
        .zip(ranges)
        .zip(snapshots)
        .map(|(((index, op), range), snapshot)| {
            let mine = &moves[range.clone()];
            let mut tools: Vec<u32> = Vec::new();
            let (mut seconds, mut feed_length, mut rapid_length) = (0.0, 0.0, 0.0);
            for m in mine {
                if tools.last() != Some(&m.tool) {
                    tools.push(m.tool);
                }
                seconds += m.seconds;
                let len = m.mv.length(m.from);
                if m.mv.is_rapid() {
                    rapid_length += len;
                } else {
                    feed_length += len;
                }
            }
            let simulated = range.end <= volumes.len();
            let (removed, mrr_max) = if simulated {
                let v = &volumes[range.clone()];
                let peak = rates[range.clone()].iter().copied().fold(0.0, f64::max);
                (Some(v.iter().sum()), Some(peak))
            } else {
                (None, None)
            };
            let (left_max, left_mean) = match (snapshot, verification) {
                (Some(h), Some(v)) => {
                    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
                    for (top, part) in h.z.iter().zip(&v.part.z) {
                        if part.is_nan() {
                            continue;
                        }
                        let left = top - part;
                        max = max.max(left);
                        sum += left.max(0.0);
                        n += 1;
                    }
                    (Some(max), Some(if n > 0 { sum / n as f64 } else { 0.0 }))
                }
                _ => (None, None),
            };
            OperationReport {
                rest_after: Vec::new(),
                index,
                name: op.name().to_string(),
                tools,
                moves: mine.len(),
                seconds,
                feed_length,
                rapid_length,
                removed,
                mrr_max,
                power_max: None,
                chip_max: None,
                left_max,
                left_mean,
                load: None,
                stages: None,
                engagement: None,
            }
        })
        .collect();
    // Rest roughing: a roughing after operations that removed material with larger tools, that
    // plans against what they left.
    let diameter = |t: u32| job.tools.iter().find(|x| x.number == t).map_or(0.0, |x| x.cutter.diameter);
    for n in 0..reports.len() {
        if !job.operations[reports[n].index].roughing().is_some_and(|r| r.rest) {
            continue;
        }
        let mine = reports[n].tools.iter().map(|&t| diameter(t)).fold(f64::INFINITY, f64::min);
        let mut after: Vec<u32> = Vec::new();
        for earlier in reports[..n].iter().filter(|r| r.removed.is_some_and(|v| v > 0.0) && !matches!(job.operations[r.index], Operation::Face(_))) {
            for &t in &earlier.tools {
                if diameter(t) > mine + 1e-9 && !after.contains(&t) {
                    after.push(t);
                }
            }
        }
        crate::geom::sort::sort_by_float(&mut after, |a| -diameter(*a));
        reports[n].rest_after = after;
    }
    reports
}
