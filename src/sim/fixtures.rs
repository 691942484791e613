//! Every move checked against what holds the stock ([`crate::job::fixtures`]): the tool, its
//! cutter and the shank above it (the holder is not modelled), against each fixture grown by
//! its clearance. The tool stands on its tip and rises without end, so at a point of its move
//! it runs into a box where the box's footprint comes within the tool's radius of its axis and
//! the tool's lower surface there (the cutter's profile within the cutter's radius, the
//! flutes' top under a wider shank) stands below the box's top. The moves are judged at points
//! no farther apart than a fiftieth of the tool's radius (and 0.05 mm), never only at their
//! ends.

use crate::cutter::Cutter;
use crate::geom::{Aabb, DVec2, DVec3};
use crate::job::fixtures::Held;
use crate::toolpath::{arc_sweep, Move};

use super::program::ProgramMove;

/// A move that runs into a fixture.
#[derive(Clone, Debug, PartialEq)]
pub struct FixtureHit {
    /// The fixture, by name ("the vise's front jaw").
    pub fixture: String,
    pub move_index: usize,
    pub tool: u32,
    /// The tool's tip where it is deepest in the fixture's clearance.
    pub at: DVec3,
    /// How far into the clearance it goes (mm): past the clearance into the fixture itself
    /// once it exceeds it.
    pub depth: f64,
}

/// The height above the tip of the tool's lower surface at `d` from its axis (`None` beyond
/// the tool's widest radius).
fn body_height(c: &Cutter, d: f64) -> Option<f64> {
    let r = c.diameter / 2.0;
    let shank = c.shank_diameter.unwrap_or(c.diameter) / 2.0;
    if d <= r {
        Some(c.profile().height(d))
    } else if d <= shank {
        Some(c.flute_length)
    } else {
        None
    }
}

/// The distance in XY from `p` to the rectangle of `b`.
fn to_rectangle(p: DVec2, b: &Aabb) -> f64 {
    let dx = (b.min.x - p.x).max(p.x - b.max.x).max(0.0);
    let dy = (b.min.y - p.y).max(p.y - b.max.y).max(0.0);
    dx.hypot(dy)
}

/// How far the tool at tip `p` is into `b`: the lesser of how far its lower surface stands
/// below the box's top and how far the box's side comes inside its widest radius (a tool
/// touching the box's side or top is not in it); below 0, how far it keeps clear of the box
/// in the nearer of the two senses.
pub fn depth_into(c: &Cutter, p: DVec3, b: &Aabb) -> f64 {
    let d = to_rectangle(p.truncate(), b);
    let reach = c.diameter.max(c.shank_diameter.unwrap_or(0.0)) / 2.0;
    let h = body_height(c, d.min(reach)).unwrap_or(c.flute_length);
    (b.max.z - (p.z + h)).min(reach - d)
}

/// The tip's place a fraction `t` along move `m` from `from`.
pub fn along(from: DVec3, m: &Move, t: f64) -> DVec3 {
    match *m {
        Move::Rapid { to } | Move::Line { to, .. } => from.lerp(to, t),
        Move::Arc { to, center, clockwise, .. } => {
            let sweep = arc_sweep(from, to, center, clockwise);
            let a = from.truncate() - center;
            let (s, c) = (sweep * t).sin_cos();
            let p = center + DVec2::new(a.x * c - a.y * s, a.x * s + a.y * c);
            p.extend(from.z + (to.z - from.z) * t)
        }
    }
}

/// A mesh fixture as one tool meets it: the lowest tip heights at which the cutter, and a
/// shank wider than it, keep the clearance from the mesh.
struct MeshDrops {
    cutter: crate::zmap::drop::PointDrop,
    /// The drop of the cutter grown by a horizontal disk of the clearance is raised by it too
    /// (a ball grown about its centre keeps it every way already).
    lift: f64,
    /// A shank wider than the cutter: its drop, and how far above the tip it starts less the
    /// clearance it is raised by.
    shank: Option<(crate::zmap::drop::PointDrop, f64)>,
}

impl MeshDrops {
    fn new(mesh: &crate::mesh::Mesh, c: &Cutter, clearance: f64) -> MeshDrops {
        use crate::cutter::Profile;
        use crate::zmap::drop::PointDrop;
        let tol = crate::geom::Tolerances::default();
        let profile = c.profile();
        let cutter = PointDrop::grown(mesh, &profile, clearance, &tol);
        let lift = if profile.is_ball() || clearance <= 0.0 { 0.0 } else { clearance };
        // A flat shank grown by a disk is raised by the clearance too.
        let shank = c.shank_diameter.filter(|&d| d > c.diameter).map(|d| (PointDrop::grown(mesh, &Profile::new(d / 2.0, 0.0), clearance, &tol), c.flute_length - clearance.max(0.0)));
        MeshDrops { cutter, lift, shank }
    }

    /// How far the tool with its tip at `p` is into the clearance (below 0: clear of it).
    fn depth(&self, p: DVec3) -> f64 {
        let at = p.truncate();
        let mut lowest = self.cutter.at(at, f64::NEG_INFINITY) + self.lift;
        if let Some((shank, rise)) = &self.shank {
            lowest = lowest.max(shank.at(at, f64::NEG_INFINITY) - rise);
        }
        lowest - p.z
    }
}

/// How far apart along a move the tool is judged against the fixtures (mm).
pub fn sample_step(c: &Cutter) -> f64 {
    (c.diameter / 100.0).clamp(1e-3, 0.05)
}

/// The moves of `moves` that run into a fixture of `keep_out` (each grown by its clearance)
/// by more than `tolerance` (below 0: that come within `-tolerance` of one): the deepest
/// point of each such move and fixture.
pub fn collisions(moves: &[ProgramMove], keep_out: &[Held], tolerance: f64) -> Vec<FixtureHit> {
    let mut out = Vec::new();
    if keep_out.is_empty() {
        return out;
    }
    // Each mesh fixture's drops for each tool that comes into its box, made once.
    let mut drops: Vec<((usize, u32), MeshDrops)> = Vec::new();
    for (k, m) in moves.iter().enumerate() {
        let reach = (m.cutter.diameter.max(m.cutter.shank_diameter.unwrap_or(0.0))) / 2.0;
        // Points along the move this far apart, when one comes near a fixture.
        let step = sample_step(&m.cutter);
        let n = (m.mv.length(m.from) / step).ceil().max(1.0) as usize;
        let (lo, hi) = m.mv.bounds(m.from);
        for (f, h) in keep_out.iter().enumerate() {
            let b = &h.solid;
            let near = -tolerance.min(0.0);
            if lo.z >= b.max.z + near || lo.x > b.max.x + reach + near || hi.x < b.min.x - reach - near || lo.y > b.max.y + reach + near || hi.y < b.min.y - reach - near {
                continue;
            }
            let mut worst: Option<(f64, DVec3)> = None;
            for i in 0..=n {
                let p = along(m.from, &m.mv, i as f64 / n as f64);
                let mut d = depth_into(&m.cutter, p, b);
                // Within a mesh fixture's box: how far into the clearance of the mesh itself.
                if let (Some(mesh), true) = (&h.mesh, d > tolerance) {
                    let key = (f, m.tool);
                    let at = match drops.iter().position(|(k, _)| *k == key) {
                        Some(at) => at,
                        None => {
                            drops.push((key, MeshDrops::new(mesh, &m.cutter, h.grown)));
                            drops.len() - 1
                        }
                    };
                    d = drops[at].1.depth(p);
                }
                if d > tolerance && worst.is_none_or(|(w, _)| d > w) {
                    worst = Some((d, p));
                }
            }
            if let Some((depth, at)) = worst {
                out.push(FixtureHit { fixture: h.name.clone(), move_index: k, tool: m.tool, at, depth });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::Move;

    fn moving(cutter: &Cutter, from: DVec3, to: DVec3) -> ProgramMove {
        ProgramMove { path: 0, tool: 1, cutter: cutter.clone(), from, mv: Move::Line { to, feed: 1000.0 }, start: 0.0, seconds: 1.0, air: false, holder: None }
    }

    #[test]
    fn a_tool_beside_a_jaw_clears_it_by_its_profile_and_one_over_it_runs_in() {
        let jaw = Held::solid("the vise's front jaw", Aabb { min: DVec3::new(-50.0, -40.0, -60.0), max: DVec3::new(50.0, -25.0, -10.0) });
        let ball = Cutter { shape: crate::cutter::Shape::Ball, diameter: 6.0, corner_radius: 3.0, shank_diameter: None, flute_length: 20.0, angle: None, tip_diameter: 0.0 };
        // Along the jaw's face, 3 mm off: the ball's side just touches it, no more.
        let beside = moving(&ball, DVec3::new(-30.0, -22.0, -15.0), DVec3::new(30.0, -22.0, -15.0));
        assert!(collisions(std::slice::from_ref(&beside), std::slice::from_ref(&jaw), 1e-9).is_empty());
        // 1 mm closer: 1 mm into its side (the tip 5 mm below the jaw's top).
        let closer = moving(&ball, DVec3::new(-30.0, -23.0, -15.0), DVec3::new(30.0, -23.0, -15.0));
        let hits = collisions(&[closer], std::slice::from_ref(&jaw), 1e-9);
        assert_eq!(hits.len(), 1);
        assert!((hits[0].depth - 1.0).abs() < 1e-9, "{}", hits[0].depth);
        // Across the jaw's end 1 mm off it, the tip 1 mm under its top: the ball's side
        // 0.83 mm into it, found between the move's ends (both well clear of the jaw).
        let over = moving(&ball, DVec3::new(-51.0, -10.0, -11.0), DVec3::new(-51.0, -55.0, -11.0));
        let hits = collisions(&[over], std::slice::from_ref(&jaw), 1e-9);
        assert_eq!(hits.len(), 1);
        assert_eq!(hits[0].fixture, "the vise's front jaw");
        assert!((hits[0].depth - (1.0 - (3.0 - 8.0f64.sqrt()))).abs() < 1e-9, "{}", hits[0].depth);
        assert!((-40.0..=-25.0).contains(&hits[0].at.y), "{}", hits[0].at);
        // 0.2 mm off its side: clear, but within 0.25 of it.
        let near = moving(&ball, DVec3::new(-30.0, -21.8, -15.0), DVec3::new(30.0, -21.8, -15.0));
        assert!(collisions(std::slice::from_ref(&near), std::slice::from_ref(&jaw), 1e-9).is_empty());
        let touching = collisions(&[near], std::slice::from_ref(&jaw), -0.25);
        assert_eq!(touching.len(), 1);
        assert!((touching[0].depth + 0.2).abs() < 1e-9, "{}", touching[0].depth);
        // Above it: clear.
        let high = moving(&ball, DVec3::new(0.0, -60.0, -9.99), DVec3::new(0.0, 0.0, -9.99));
        assert!(collisions(&[high], &[jaw], 1e-9).is_empty());
    }

    /// A stepped block as a mesh fixture: a tool over its low step, inside the block's box but
    /// clear of the mesh, is clear; one too low over the step, or into the tall part, is not.
    #[test]
    fn a_mesh_fixture_is_judged_by_its_mesh_within_its_box() {
        let mesh = crate::mesh::sample::height_field_solid(DVec2::new(0.0, 0.0), DVec2::new(20.0, 10.0), 200, 100, 0.0, |x, _| if x < 10.0 { 10.0 } else { 2.0 });
        let held = Held { name: "the step block".into(), solid: Aabb { min: mesh.bounds().min - DVec3::ONE, max: mesh.bounds().max + DVec3::ONE }, mesh: Some(std::sync::Arc::new(mesh)), grown: 1.0 };
        let flat = Cutter { flute_length: 20.0, ..Cutter::flat(4.0) };
        let at = |p: DVec3| {
            let m =
                ProgramMove { path: 0, tool: 1, cutter: flat.clone(), from: p, mv: Move::Line { to: p + DVec3::new(0.0, 0.5, 0.0), feed: 100.0 }, start: 0.0, seconds: 0.0, air: false, holder: None };
            collisions(&[m], std::slice::from_ref(&held), 0.0)
        };
        assert!(at(DVec3::new(15.0, 5.0, 5.0)).is_empty(), "over the low step, 3 mm clear of it and of the tall part");
        let low = at(DVec3::new(15.0, 5.0, 2.5));
        assert!(low.len() == 1 && (low[0].depth - 0.5).abs() < 1e-6, "{low:?}");
        let into = at(DVec3::new(11.5, 5.0, 5.0));
        assert!(into.len() == 1 && (into[0].depth - 6.0).abs() < 1e-6, "{into:?}");
    }
}
