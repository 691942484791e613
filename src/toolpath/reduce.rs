//! Point reduction within a chordal tolerance that never lets the path sink: a run of sampled
//! points is replaced by a straight segment only if the segment lies on or above every point it
//! replaces and at most `tolerance` above any of them. So a reduced path stays above the CL
//! surface the samples were taken from.

use crate::geom::DVec3;

/// Longest run of samples one segment may replace: bounds the quadratic cost on long flats.
const MAX_RUN: usize = 400;

/// Keeps the first and last point and as few between as the rule above allows (greedy: each
/// kept point reaches as far ahead as it can).
pub fn reduce(points: &[DVec3], tolerance: f64) -> Vec<DVec3> {
    if points.len() <= 2 {
        return points.to_vec();
    }
    let mut kept = vec![points[0]];
    let mut anchor = 0;
    while anchor < points.len() - 1 {
        let mut reach = anchor + 1;
        let mut candidate = anchor + 2;
        while candidate < points.len() && candidate - anchor <= MAX_RUN && spans(&points[anchor..=candidate], tolerance) {
            reach = candidate;
            candidate += 1;
        }
        kept.push(points[reach]);
        anchor = reach;
    }
    kept
}

/// Whether the segment from the first to the last point stays within `[0, tolerance]` above
/// every point between, measured vertically at each point's position along the segment.
fn spans(run: &[DVec3], tolerance: f64) -> bool {
    let (a, b) = (run[0], run[run.len() - 1]);
    let d = (b - a).truncate();
    let len2 = d.length_squared();
    run[1..run.len() - 1].iter().all(|p| {
        let t = if len2 > 0.0 { ((p.truncate() - a.truncate()).dot(d) / len2).clamp(0.0, 1.0) } else { 0.0 };
        let along = a + (b - a) * t;
        // The samples lie on the segment's vertical plane (raster passes are straight lines),
        // so the vertical gap is the distance that matters.
        let gap = along.z - p.z;
        (0.0..=tolerance).contains(&gap) && (along.truncate() - p.truncate()).length_squared() <= tolerance * tolerance
    })
}
