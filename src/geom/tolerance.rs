//! Every tolerance swarf uses, in one place. Algorithms take a `Tolerances` (or one of its
//! fields) as a parameter where a user could tune it; below those, the slack of float
//! arithmetic that no user tunes is named here once ([`FLOAT_ZERO`], [`FLOAT_SLACK`], [`HAIR`],
//! [`LEAST_STEP`]), each with its reason, and none keeps a stray epsilon of its own.

/// A length, angle or area this small is nothing: a degenerate segment, a zero divisor.
pub const FLOAT_ZERO: f64 = 1e-12;
/// Two heights, parameters or positions this close are the same: the rounding of sums of
/// millimetres, far below every tolerance a user sets.
pub const FLOAT_SLACK: f64 = 1e-9;
/// A hair (mm): past the float noise of geometry on parts a metre across, far below any
/// machine's resolution; what "above", "beyond" or "in material" leaves out as noise.
pub const HAIR: f64 = 1e-6;
/// The least step (mm) a setting is divided by or a path is sampled at, so that a zero or tiny
/// step-down, step-over or sampling cannot make an endless loop (settings are checked to be
/// positive; this keeps the arithmetic finite all the same).
pub const LEAST_STEP: f64 = 1e-3;

/// A line of a drawn chain shorter than this (mm) may be a piece of a curve drawn finely
/// divided (an exporter's flattening, a hole as thousands of segments): runs of three or more
/// are fitted with the arcs they trace, within the arc-fit tolerance (`drawing::chain::tidy`).
/// Longer lines are the drawing's own and stay as drawn.
pub const FINE_PIECE: f64 = 0.5;

use serde::{Deserialize, Serialize};

/// Distances in millimetres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Tolerances {
    /// Triangles with an area below `degenerate_area` (mm²) are dropped at import and counted.
    /// Default value: 1e-12.
    pub degenerate_area: f64,
    /// Largest distance a reduced tool path may lie above the points it replaces (chordal
    /// tolerance of point reduction, mm). It never lies below them. Default value: 0.002.
    pub chordal: f64,
    /// Heights closer than this are treated as equal when deciding whether a linking move
    /// may stay down (mm). Default value: 1e-6.
    pub height: f64,
    /// Largest distance of the exact CL surface from the straight line between two points of a
    /// path where the height was computed exactly, as tested at the midpoint by subdivision
    /// (mm). Where one feature decides both ends the rise between is at most twice this
    /// (`zmap/surface.rs` gives the argument). Default value: 0.0005.
    pub interpolation: f64,
    /// Horizontal components of a unit normal below this make a facet horizontal; normals
    /// with a vertical component below it make a facet vertical. Default value: 1e-12.
    pub normal: f64,
    /// Verification reports material below the part's surface plus allowance as a gouge only
    /// when it is deeper than this (mm); the same margin applies to the tool body's clearance.
    /// Default value: 0.02.
    pub gouge: f64,
    /// End points of drawn entities closer than this are joined into one chain (mm).
    /// Default value: 0.01.
    pub chain: f64,
    /// Curves (splines, ellipses, Béziers) are replaced by arcs that stay within this distance
    /// of them (mm). Default value: 0.002.
    pub arc_fit: f64,
    /// Entities of a loop shorter than this are merged into their neighbours before and after
    /// offsetting, as seed 003 does for spline-heavy parts (mm). Default value: 1e-4.
    pub micro_entity: f64,
    /// Points of the offsetter closer than this are one point, and an offset piece lying closer
    /// to the input than the distance less this is trimmed (mm). Default value: 1e-7.
    pub offset: f64,
}

/// A point closer to a z-map grid line than this fraction of the spacing is taken to lie on
/// it (so both cells beside the line count); it absorbs rounding in computed crossings.
pub const GRID_SNAP: f64 = 1e-9;

/// Material this little above a height counts as none there (mm): a cut to the height leaves
/// the stock's cells a rounding above it.
pub const MATERIAL_SLACK: f64 = 1e-6;

/// Added to a bound from above that one computation makes of another's result (the widened
/// cutter's drops bounding the exact surface along a grid edge, `zmap::contour::LevelMap`):
/// the two are computed apart and may round differently (mm).
pub const BOUND_SLACK: f64 = 1e-9;

/// A feed move whose tool comes this close to a fixture's clearance (mm) was stopped short by
/// it: its operation says so ([`crate::job::fixtures`]).
pub const FIXTURE_CONTACT: f64 = 0.25;

impl Tolerances {
    /// The chordal tolerance the simulation sweeps a helix (a ramp round an arc) with, as
    /// chords inside it: the job's, no coarser than a tenth of the gouge tolerance. The machine
    /// follows the helix itself; chords a coarse chordal tolerance apart would cut into the part
    /// past the gouge tolerance where the program does not (a disc profiled with a chordal
    /// tolerance of 0.05 mm was refused for gouges 3.5 mm deep: the ramp's chords cut into its
    /// edge all the way down).
    pub fn simulated_chordal(&self) -> f64 {
        self.chordal.min(0.1 * self.gouge)
    }

    /// Each tolerance outside its range ([`crate::limits::TOLERANCE_RANGES`]): the field as
    /// the job file names it, and why.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let values = [self.degenerate_area, self.chordal, self.height, self.interpolation, self.normal, self.gouge, self.chain, self.arc_fit, self.micro_entity, self.offset];
        crate::limits::TOLERANCE_RANGES
            .iter()
            .zip(values)
            .filter(|((_, least, most), v)| !(*v >= *least && *v <= *most))
            .map(|(&(field, least, most), v)| {
                let why =
                    if v > most { "a coarser one is no longer a tolerance of the part (it would pass what it should find)" } else { "a tolerance finer than that makes the work grow without bound" };
                (field, format!("must lie between {least:e} and {most:e} (got {}): {why}", crate::limits::shown(v)))
            })
            .collect()
    }

    pub const DEFAULT: Tolerances =
        Tolerances { degenerate_area: 1e-12, chordal: 0.002, height: 1e-6, interpolation: 0.0005, normal: 1e-12, gouge: 0.02, chain: 0.01, arc_fit: 0.002, micro_entity: 1e-4, offset: 1e-7 };
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances::DEFAULT
    }
}
