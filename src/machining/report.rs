//! What an operation's plan gives back ([`Planned`]): its tool paths and its own report (the
//! regions a 2.5D operation cut and the grooves an engraving cut, for verifying the program;
//! the load along a zigzag roughing's path; octree roughing's stages and octants). The job
//! reads these whatever the operation; no operation's own type reaches it.

use serde::Serialize;

use crate::octree::OctantBox;
use crate::toolpath::Toolpath;

/// What an operation planned.
#[derive(Debug, Default)]
pub struct Planned {
    /// Its tool paths, each with its tool (an operation may use more than one).
    pub paths: Vec<Toolpath>,
    /// Where it cut a sheet: the regions, depths and wall allowances (2.5D operations).
    pub cuts: Vec<SheetCut>,
    /// The grooves it engraved.
    pub grooves: Vec<Groove>,
    /// The load along its path, where it measured one (seed 004).
    pub load: Option<LoadReport>,
    /// Its stages, where it chose its tools (seed 000).
    pub stages: Option<Vec<StageReport>>,
    /// Its stages' octants, for the view.
    pub octants: Vec<StageOctants>,
    /// The engagement it holds the tool to, where it holds one (adaptive clearing): the job
    /// measures the program's against it by the simulation.
    pub engagement: Option<EngagementTarget>,
}

/// The engagement an operation holds.
#[derive(Clone, Debug, PartialEq)]
pub struct EngagementTarget {
    /// The angle of the tool's circle in the material (radians).
    pub angle: f64,
    /// Climb milling (the material on the right of the way the tool goes, as a spindle turning
    /// clockwise from above, M3, cuts it), else conventional (on the left).
    pub climb: bool,
    /// Levels (height, angle) held at another angle: shallower than the load is set for, they
    /// cut wider ([`crate::machining::adaptive::Adaptive::shallow_step`]).
    pub levels: Vec<(f64, f64)>,
}

impl EngagementTarget {
    /// The angle held at height `z`.
    pub fn at(&self, z: f64) -> f64 {
        self.levels.iter().find(|l| (l.0 - z).abs() < 1e-6).map_or(self.angle, |l| l.1)
    }
}

impl From<Vec<Toolpath>> for Planned {
    fn from(paths: Vec<Toolpath>) -> Self {
        Planned { paths, ..Planned::default() }
    }
}

/// Where a 2.5D operation may cut, to what depth, leaving how much on the walls: the part a
/// drawing means, for verifying the program.
#[derive(Clone, Debug)]
pub struct SheetCut {
    pub region: crate::drawing::Shape,
    /// Cuts inside the region (else everywhere outside it).
    pub inside: bool,
    pub depth: f64,
    pub leave: f64,
    /// What the cut parts off beyond its kerf is scrap, not the part (a profile's: the sheet
    /// round the outline, a hole's slug): the verification judges neither what is left there
    /// nor a cut there, where no other cut asks for it.
    pub scrap: bool,
}

/// Where an engraving cuts: within `radius` of its line, to `depth`.
#[derive(Clone, Debug)]
pub struct Groove {
    pub path: Vec<crate::geom::segment::Segment>,
    pub radius: f64,
    pub depth: f64,
}

/// The load along one operation's path, before and after its correction, relative to the
/// reference (seed 004 Fig. 14): for reports and the page's plot.
#[derive(Clone, Debug, Default, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct LoadReport {
    /// The reference rate at the tool's feed (mm³/min per mm of depth: step-over × feed).
    pub reference: f64,
    /// The same at a full step-down (mm³/min): the reference line of the page's MRR plot.
    pub rate: f64,
    /// Δs (mm).
    pub sampling: f64,
    /// Per window of Δs along the cutting moves, the plain path's load over the reference.
    pub plain: Vec<f64>,
    /// The same for the path as cut (the tool's engagement).
    pub load: Vec<f64>,
    /// The path as cut, at its feeds: the removal rate over the reference rate.
    pub cut: Vec<f64>,
    /// The length of path (mm) that runs at a lowered feed because no extra path eases it.
    pub slowed: f64,
}

impl LoadReport {
    /// The highest load, and the spread (standard deviation), of a series.
    pub fn peak_and_spread(series: &[f64]) -> (f64, f64) {
        let n = series.len().max(1) as f64;
        let mean = series.iter().sum::<f64>() / n;
        let var = series.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
        (series.iter().copied().fold(0.0, f64::max), var.sqrt())
    }
}

/// Why a stage's tool was chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum StageRole {
    /// The largest tool whose octants it can enter (§3.2).
    First,
    /// Matched to the newly Full octants of one more subdivision (§3.2).
    Octants,
    /// Clears what is left at its own levels (§3.4).
    Profile,
    /// After the profile, goes only where the profiling tool cannot reach (a slot or corner
    /// narrower than it).
    Rest,
}

/// One stage of octree roughing: its tool, why, and what it did.
#[derive(Clone, Debug, PartialEq, Serialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub struct StageReport {
    pub tool: u32,
    pub diameter: f64,
    pub role: StageRole,
    /// Side of the octants matched to the tool (mm); none for profiling.
    pub side: Option<f64>,
    /// d / D.
    pub gamma: Option<f64>,
    /// Axial depth of cut (mm).
    pub depth: f64,
    /// Why this tool, for a person.
    pub why: String,
    /// Area of the XY plane where the stage removed material (mm²).
    pub area: f64,
    /// Volume it removed (mm³).
    pub removed: f64,
    /// Machine time at its feeds and the rapid rate (s).
    pub seconds: f64,
}

impl StageReport {
    pub fn describe(&self) -> String {
        format!(
            "T{} φ{:.1} ({}): {}; cut over {:.0} mm² seen from above, {:.0} mm³ removed, {:.0} s",
            self.tool,
            self.diameter,
            match self.role {
                StageRole::First => "first tool",
                StageRole::Octants => "octants",
                StageRole::Profile => "profile",
                StageRole::Rest => "rest",
            },
            self.why,
            self.area,
            self.removed,
            self.seconds
        )
    }
}

/// The octants of one stage, for the view.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct StageOctants {
    pub stage: usize,
    pub tool: u32,
    pub boxes: Vec<OctantBox>,
}
