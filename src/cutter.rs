//! Milling cutters and the drop of a cutter onto a vertex, an edge and a facet.
//!
//! A cutter is described by its profile: radius `R` and corner radius `a` (seed 001, Fig. 1 and
//! eq. 2: flat end `a = 0`, ball end `a = R`, bull nose `0 < a < R`). `profile_height(r)` is the
//! height of the cutter's lower surface above its tip at horizontal distance `r` from the axis.
//! The drop of a cutter standing over a point `c` onto a feature is the lowest tip height at
//! which it touches the feature and nowhere cuts into it; the CL height over `c` is the largest
//! drop over all vertices, edges and facets (the "offset facet" model of seed 001 §3.3, and the
//! same fixed vertex + facet + edge decomposition that OpenCAMLib's drop-cutter uses).
//!
//! A cone (drill, spot drill, V-bit or chamfer mill) has a flat tip of radius `f` (zero for a
//! point) and a side rising `k = cot(half the included angle)` per millimetre out to `R`: its
//! height above the tip is `(r - f) k`. Its drops are closed forms: the same cases as the
//! torus's with the corner's arc replaced by a line (OpenCAMLib's `ConeCutter`).

use serde::{Deserialize, Serialize};

use crate::geom::{orient2d, DVec2, DVec3};

/// The shape of a cutter's end.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, ts_rs::TS)]
#[serde(rename_all = "camelCase")]
pub enum Shape {
    Flat,
    Ball,
    BullNose,
    /// A twist drill: a cone of its point angle (118° by default).
    Drill,
    /// A spot (centre) drill: a cone of its point angle (90° by default).
    SpotDrill,
    /// A V-bit or chamfer mill: a cone of its included angle (90° by default) from a tip of
    /// `tipDiameter` (0: a point).
    VBit,
    /// A single-form thread mill: a disc of the cutting diameter at the tip (its form's angle
    /// 60° by default) on a neck `fluteLength` long; simulated as a flat end of its diameter.
    ThreadMill,
}

/// A milling cutter's geometry, in millimetres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, ts_rs::TS)]
#[serde(default, rename_all = "camelCase")]
pub struct Cutter {
    /// End shape. Default value: ball.
    pub shape: Shape,
    /// Cutting diameter (mm). Default value: 6.
    pub diameter: f64,
    /// Corner radius of a bull nose (mm), between 0 and half the diameter; ignored for flat and
    /// ball cutters. Default value: 1.
    pub corner_radius: f64,
    /// Shank diameter (mm), kept for collision checks. Default value: the cutting diameter.
    pub shank_diameter: Option<f64>,
    /// Length of the fluted part (mm), kept for collision checks. Default value: 20.
    pub flute_length: f64,
    /// Included angle of a drill's point or a V-bit's cone (degrees, more than 0 and less than
    /// 180); ignored for the other shapes. Default value: 118 for a drill, 90 for a spot drill
    /// and a V-bit.
    pub angle: Option<f64>,
    /// Diameter of a V-bit's or chamfer mill's flat tip (mm, less than the diameter); ignored
    /// for the other shapes. Default value: 0.
    pub tip_diameter: f64,
}

impl Default for Cutter {
    fn default() -> Self {
        Cutter { shape: Shape::Ball, diameter: 6.0, corner_radius: 1.0, shank_diameter: None, flute_length: 20.0, angle: None, tip_diameter: 0.0 }
    }
}

/// What is wrong with a cutter's description.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum CutterError {
    #[error("the cutter diameter must lie between {min} and {max} mm (got {})", crate::limits::shown(*.0), min = crate::limits::MIN_TOOL_DIAMETER, max = crate::limits::MAX_TOOL_DIAMETER)]
    Diameter(f64),
    #[error("the corner radius must lie between 0 and half the diameter (got {corner} for diameter {diameter})")]
    CornerRadius { corner: f64, diameter: f64 },
    #[error("the flute length must be positive, in millimetres, at most 10 m (got {})", crate::limits::shown(*.0))]
    FluteLength(f64),
    #[error("the point or included angle must lie between 1 and 179 degrees (got {})", crate::limits::shown(*.0))]
    Angle(f64),
    #[error("the tip diameter must lie from 0 to less than the diameter (got {tip} for diameter {diameter})")]
    TipDiameter { tip: f64, diameter: f64 },
}

impl Cutter {
    pub fn flat(diameter: f64) -> Cutter {
        Cutter { shape: Shape::Flat, diameter, ..Cutter::default() }
    }
    pub fn ball(diameter: f64) -> Cutter {
        Cutter { shape: Shape::Ball, diameter, ..Cutter::default() }
    }
    pub fn bull_nose(diameter: f64, corner_radius: f64) -> Cutter {
        Cutter { shape: Shape::BullNose, diameter, corner_radius, ..Cutter::default() }
    }
    pub fn drill(diameter: f64, angle: f64) -> Cutter {
        Cutter { shape: Shape::Drill, diameter, angle: Some(angle), ..Cutter::default() }
    }
    pub fn v_bit(diameter: f64, angle: f64, tip_diameter: f64) -> Cutter {
        Cutter { shape: Shape::VBit, diameter, angle: Some(angle), tip_diameter, ..Cutter::default() }
    }

    /// Whether its end is a cone (a drill, a spot drill, a V-bit).
    pub fn is_cone(&self) -> bool {
        matches!(self.shape, Shape::Drill | Shape::SpotDrill | Shape::VBit)
    }

    /// The included angle of a cone's point (degrees; 180 for the other shapes, which end flat
    /// or round).
    pub fn point_angle(&self) -> f64 {
        match self.shape {
            Shape::Drill => self.angle.unwrap_or(118.0),
            Shape::SpotDrill | Shape::VBit => self.angle.unwrap_or(90.0),
            _ => 180.0,
        }
    }

    /// The radius of a cone's flat tip (0 for a drill's point).
    pub fn tip_radius(&self) -> f64 {
        if self.shape == Shape::VBit {
            self.tip_diameter / 2.0
        } else {
            0.0
        }
    }

    /// How far a cone's full diameter stands above its tip (0 for the other shapes): what a
    /// through hole's depth adds so that the drill's full diameter breaks through.
    pub fn tip_length(&self) -> f64 {
        if self.is_cone() {
            (self.radius() - self.tip_radius()) / (self.point_angle().to_radians() / 2.0).tan()
        } else {
            0.0
        }
    }

    pub fn validate(&self) -> Result<(), CutterError> {
        if !(crate::limits::MIN_TOOL_DIAMETER..=crate::limits::MAX_TOOL_DIAMETER).contains(&self.diameter) {
            return Err(CutterError::Diameter(self.diameter));
        }
        // Only a bull nose uses it, but a negative one is a mistake on any.
        if !(self.corner_radius >= 0.0 && (self.shape != Shape::BullNose || self.corner_radius <= self.diameter / 2.0)) {
            return Err(CutterError::CornerRadius { corner: self.corner_radius, diameter: self.diameter });
        }
        if !(self.flute_length > 0.0 && self.flute_length <= crate::limits::MAX_SIZE) {
            return Err(CutterError::FluteLength(self.flute_length));
        }
        if let Some(angle) = self.angle {
            if !(1.0..=179.0).contains(&angle) {
                return Err(CutterError::Angle(angle));
            }
        }
        if !(self.tip_diameter >= 0.0 && (self.shape != Shape::VBit || self.tip_diameter < self.diameter)) {
            return Err(CutterError::TipDiameter { tip: self.tip_diameter, diameter: self.diameter });
        }
        Ok(())
    }

    pub fn radius(&self) -> f64 {
        self.diameter / 2.0
    }

    /// The corner radius `a` of seed 001's eq. 2.
    pub fn corner(&self) -> f64 {
        match self.shape {
            Shape::Flat => 0.0,
            Shape::Ball => self.radius(),
            Shape::BullNose => self.corner_radius.clamp(0.0, self.radius()),
            Shape::Drill | Shape::SpotDrill | Shape::VBit | Shape::ThreadMill => 0.0,
        }
    }

    /// A short human name ("6 mm ball").
    pub fn describe(&self) -> String {
        match self.shape {
            Shape::Flat => format!("{} mm flat end", self.diameter),
            Shape::Ball => format!("{} mm ball end", self.diameter),
            Shape::BullNose => format!("{} mm bull nose r{}", self.diameter, self.corner_radius),
            Shape::Drill => format!("{} mm drill {}°", self.diameter, self.point_angle()),
            Shape::SpotDrill => format!("{} mm spot drill {}°", self.diameter, self.point_angle()),
            Shape::VBit if self.tip_diameter > 0.0 => format!("{} mm V-bit {}° tip {}", self.diameter, self.point_angle(), self.tip_diameter),
            Shape::VBit => format!("{} mm V-bit {}°", self.diameter, self.point_angle()),
            Shape::ThreadMill => format!("{} mm thread mill", self.diameter),
        }
    }

    pub fn profile(&self) -> Profile {
        if self.is_cone() {
            Profile::cone(self.radius(), self.tip_radius(), self.point_angle().to_radians() / 2.0)
        } else {
            Profile::new(self.radius(), self.corner())
        }
    }
}

/// The lower surface of a cutter as heights above the tip, with the drop computations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    /// Cutter radius R.
    pub radius: f64,
    /// Corner radius a.
    pub corner: f64,
    /// R - a: radius of the flat bottom, and of the circle the corner's centres lie on; a
    /// cone's flat tip.
    flat: f64,
    /// A cone's rise per millimetre out from its tip (cot of half its included angle); 0 for
    /// the torus family.
    taper: f64,
}

/// The search for a bull nose's contact with a line stops when its bracket in the corner's
/// radial coordinate is narrower than this (mm), or at [`CONTACT_LAST_STEP`]. It finds the top
/// of a concave function, so the height it gives is off by about the square of the error times
/// the curvature.
const CONTACT_STEP: f64 = 1e-13;

/// A Newton step of the contact search no longer than this (mm) is its last: near the root
/// Newton converges quadratically, so the step taken leaves an error of about its square times
/// `|P'' / 2 P'|`, of the order of [`CONTACT_STEP`] (the search used to take one more step to
/// see that).
const CONTACT_LAST_STEP: f64 = 1e-8;

/// Within this share of the corner radius from the rim, the contact found is checked against
/// the chord's ends (see [`Profile::contact_along`]).
const RIM: f64 = 1e-4;

impl Profile {
    pub fn new(radius: f64, corner: f64) -> Profile {
        Profile { radius, corner, flat: radius - corner, taper: 0.0 }
    }

    /// A cone of radius `radius` from a flat tip of radius `tip`, its side at `half_angle`
    /// (radians) from the axis.
    pub fn cone(radius: f64, tip: f64, half_angle: f64) -> Profile {
        Profile { radius, corner: 0.0, flat: tip.clamp(0.0, radius), taper: 1.0 / half_angle.tan() }
    }

    /// Whether it is a cone's.
    #[inline]
    pub fn is_cone(&self) -> bool {
        self.taper > 0.0
    }

    /// Whether it is a flat end's (a level bottom to its rim).
    #[inline]
    pub fn is_flat(&self) -> bool {
        self.corner == 0.0 && self.taper == 0.0
    }

    /// Whether it is a ball's (a round end with no flat: not a pointed cone).
    #[inline]
    pub fn is_ball(&self) -> bool {
        self.flat <= 0.0 && self.taper == 0.0
    }

    /// Its Minkowski sum with a horizontal disk of radius `h`: the same shape with a flat (or a
    /// cone's tip) wider by `h` (a ball becomes a bull nose of its radius).
    pub fn widened(&self, h: f64) -> Profile {
        Profile { radius: self.radius + h, flat: self.flat + h, ..*self }
    }

    /// The horizontal distance from the tip's axis to where the cutter touches a plane whose
    /// upward unit normal has horizontal length `slope_sin` and height `n_z`, towards the
    /// plane's uphill side: a torus's `R - a + a |n_xy|`; a cone's tip rim where the plane is
    /// flatter than its side, else its rim.
    #[inline]
    pub fn plane_contact(&self, slope_sin: f64, n_z: f64) -> f64 {
        if self.taper > 0.0 {
            if slope_sin / n_z < self.taper {
                self.flat
            } else {
                self.radius
            }
        } else {
            self.flat + self.corner * slope_sin
        }
    }

    /// A cone's rise per millimetre (0 for the torus family).
    #[inline]
    pub fn taper(&self) -> f64 {
        self.taper
    }

    /// R - a: the radius of the flat bottom.
    #[inline]
    pub fn flat_radius(&self) -> f64 {
        self.flat
    }

    /// Height of the cutter's lower surface above the tip at horizontal distance `r <= R`.
    #[inline]
    pub fn height(&self, r: f64) -> f64 {
        if r <= self.flat {
            0.0
        } else if self.taper > 0.0 {
            (r.min(self.radius) - self.flat) * self.taper
        } else {
            let d = r - self.flat;
            self.corner - (self.corner * self.corner - d * d).max(0.0).sqrt()
        }
    }

    /// The squared horizontal distance from the axis beyond which the lower surface stands at
    /// least `rise` above the tip (infinite where it never does within the radius).
    #[inline]
    pub fn reach_squared(&self, rise: f64) -> f64 {
        if rise <= 0.0 {
            0.0
        } else if self.taper > 0.0 {
            let r = self.flat + rise / self.taper;
            if r > self.radius {
                f64::INFINITY
            } else {
                r * r
            }
        } else if rise > self.corner {
            f64::INFINITY
        } else {
            let r = self.flat + (rise * (2.0 * self.corner - rise)).sqrt();
            r * r
        }
    }

    /// Drop onto a point: `None` when the point is outside the cutter's reach.
    #[inline]
    pub fn drop_vertex(&self, c: DVec2, v: DVec3) -> Option<f64> {
        let r2 = (v.truncate() - c).length_squared();
        (r2 <= self.radius * self.radius).then(|| v.z - self.height(r2.sqrt()))
    }

    /// Drop onto the plane of a facet, valid only when the contact point lies in the facet.
    /// `n` is the facet's unit normal with `n.z > 0` (vertical facets are left to their edges).
    /// With `h = |n_xy|`, the contact lies at `c + (R - a + a h) u` (u the uphill direction) and
    /// the tip at `plane(c) + ((R - a) h + a) / n.z - a` (seed 001 eq. 2 solved for the tip).
    #[inline]
    pub fn drop_facet(&self, c: DVec2, facet: &FacetPlane) -> Option<f64> {
        let n = facet.normal;
        let plane_z = facet.point.z - ((c.x - facet.point.x) * n.x + (c.y - facet.point.y) * n.y) / n.z;
        let r = self.plane_contact(facet.slope_sin, n.z);
        let contact = c + facet.uphill * r;
        if self.taper > 0.0 {
            // A cone on a plane rising `t` per mm: the top of `t r - height(r)` is at the tip's
            // rim where the plane is flatter than the side, else at the cone's rim.
            let t = facet.slope_sin / n.z;
            return facet.contains(contact).then(|| plane_z + t * r - self.height(r));
        }
        facet.contains(contact).then(|| plane_z + (self.flat * facet.slope_sin + self.corner) / n.z - self.corner)
    }

    /// Drop onto the segment `p`–`q`.
    #[inline]
    pub fn drop_edge(&self, c: DVec2, p: DVec3, q: DVec3) -> Option<f64> {
        self.drop_edge_above(c, p, q, f64::NEG_INFINITY)
    }

    /// Drop onto the segment `p`–`q`, or `None` when it cannot rise above `current` (the height
    /// already known over `c`): the edge's higher end minus the cutter's height at the edge's
    /// perpendicular distance bounds the drop from above, and is cheap.
    #[inline]
    pub fn drop_edge_above(&self, c: DVec2, p: DVec3, q: DVec3, current: f64) -> Option<f64> {
        let d = (q - p).truncate();
        let len2 = d.length_squared();
        if len2 <= 0.0 {
            return None; // a vertical edge: its top vertex decides
        }
        let t_c = (c - p.truncate()).dot(d) / len2;
        let foot = p.truncate() + d * t_c;
        let dist2 = (c - foot).length_squared();
        let r2 = self.radius * self.radius;
        // Bound: the drop is at most the higher end minus the cutter's height at the edge's
        // perpendicular distance; it cannot beat `current` when that distance reaches past
        // where the cutter has risen by the difference.
        if dist2 > r2 || dist2 >= self.reach_squared(p.z.max(q.z) - current) {
            return None;
        }
        let len = len2.sqrt();
        let half = (r2 - dist2).sqrt() / len; // half chord in parameter units
        let lo = (t_c - half).max(0.0);
        let hi = (t_c + half).min(1.0);
        if lo > hi {
            return None;
        }
        let dz = q.z - p.z;
        let z_at = |t: f64| p.z + dz * t;
        if self.taper > 0.0 {
            let (m, s_lo, s_hi) = (dz / len, (lo - t_c) * len, (hi - t_c) * len);
            let s = self.cone_top(m, dist2, s_lo, s_hi);
            return Some(z_at(t_c) + m * s - self.height((dist2 + s * s).sqrt()));
        }
        if self.corner <= 0.0 {
            // Flat end: the disk meets the edge along [lo, hi]; the higher end decides.
            return Some(z_at(lo).max(z_at(hi)));
        }
        if self.flat <= 0.0 {
            // Ball end: in the vertical plane of the edge the ball is a circle of radius
            // rho = sqrt(R² - dist²) resting on a line of slope m; it touches at
            // s = s_c + rho m / k with k = sqrt(1 + m²), its centre at z(s_c) + rho k.
            let m = dz / len;
            let k = (1.0 + m * m).sqrt();
            let rho = (r2 - dist2).sqrt();
            let t_contact = t_c + rho * m / k / len;
            if !(0.0..=1.0).contains(&t_contact) {
                return None; // the end vertex decides
            }
            return Some(z_at(t_c) + rho * k - self.radius);
        }
        // The part of the edge under the cutter rises no higher than its higher end, and the
        // cutter stands at least its height at the edge's perpendicular distance: a bound that
        // spares the search below most of a long edge (the end-based bound above cannot prune
        // a bull nose once the edge's top is more than the corner radius above `current`).
        if z_at(lo).max(z_at(hi)) - self.height(dist2.sqrt()) <= current {
            return None;
        }
        let (m, s_lo, s_hi) = (dz / len, (lo - t_c) * len, (hi - t_c) * len);
        if z_at(t_c) + self.cone_bound(m, dist2, s_lo, s_hi) <= current {
            return None;
        }
        let s = self.contact_along(m, dist2, s_lo, s_hi);
        Some(p.z + dz * (t_c + s / len) - self.height((dist2 + s * s).sqrt().min(self.radius)))
    }

    /// At `s` along a line of slope `m` whose foot lies `sqrt(dist2)` from the axis: a number
    /// with the sign of `F'(s)` (see [`Profile::contact_along`]; infinite at the rim, where the
    /// wall is vertical), and the cutter's height there (`height(min(r, R))`), from one
    /// evaluation with no division.
    #[inline]
    pub fn slope_and_height(&self, m: f64, dist2: f64, s: f64) -> (f64, f64) {
        let r = (dist2 + s * s).sqrt();
        let u = r - self.flat;
        if u <= 0.0 {
            return (m, 0.0); // on the flat bottom
        }
        if self.taper > 0.0 {
            // F' = m - k s / r.
            return (m * r - self.taper * s, self.height(r));
        }
        let w2 = self.corner * self.corner - u * u;
        if w2 <= 0.0 {
            return (if s < 0.0 { f64::INFINITY } else { f64::NEG_INFINITY }, self.corner);
        }
        // F' = m - u s / (w r), with w r > 0.
        let w = w2.sqrt();
        (m * w * r - u * s, self.corner - w)
    }

    /// Where this cone meets a line of slope `m` at horizontal distance `sqrt(dist2)` from its
    /// axis: the `s` in `[lo, hi]` that maximises `F(s) = m s - height(sqrt(dist2 + s²))` (see
    /// `cone_peak`: towards the chord's end, where F' = 0 on the side, or where the side meets the tip).
    pub fn cone_top(&self, m: f64, dist2: f64, lo: f64, hi: f64) -> f64 {
        cone_peak(m, dist2, self.taper, self.flat, lo, hi)
    }

    /// An upper bound of `F(s) = m s - height(sqrt(dist2 + s²))` over `[lo, hi]` in closed form
    /// (see [`Profile::contact_along`]): the corner's height is convex, so it stands above its
    /// tangent at 45°, `r - (R - a) - a (√2 - 1)`, and above zero; with that cone for the corner
    /// F is bounded by a concave function whose top is a square root away. It lets the edge drop
    /// skip the search where even this bound cannot rise above the height already found.
    fn cone_bound(&self, m: f64, dist2: f64, lo: f64, hi: f64) -> f64 {
        let r1 = self.flat + self.corner * (std::f64::consts::SQRT_2 - 1.0);
        let g = |s: f64| m * s - ((dist2 + s * s).sqrt() - r1).max(0.0);
        g(cone_peak(m, dist2, 1.0, r1, lo, hi))
    }

    /// Where a bull nose meets a line of slope `m` at horizontal distance `sqrt(dist2)` from its
    /// axis: the `s` in `[lo, hi]` (along the line, from the foot of the axis) that maximises
    /// `F(s) = m s - height(sqrt(dist2 + s²))`. F is concave (height is convex and
    /// non-decreasing in r, r is convex in s), so the maximum is where F' = 0, or an end. The
    /// edge drop asks it of a mesh edge under the cutter; the simulation's sweep asks it of the
    /// cutter's own path (the lowest point of a sloped move over a point is the same problem
    /// upside down).
    ///
    /// F' = 0 has its root on the side of the foot the line rises to, in the corner (the flat
    /// bottom alone never stops a sloped line). With `u = r - (R - a)` the corner's height has
    /// slope `u / sqrt(a² - u²)`, so F' = 0 reads `|m| sqrt(a² - u²) r = u sqrt(r² - dist2)`;
    /// squared (both sides are at least zero), it is the quartic
    /// `P(u) = (r² - dist2) u² - m² (a² - u²) r² = 0`, negative where the corner starts and
    /// positive at the rim, with its one root there. A safeguarded Newton iteration on P needs
    /// no square roots and stays smooth at the rim, where F's own slope is infinite.
    pub fn contact_along(&self, m: f64, dist2: f64, lo: f64, hi: f64) -> f64 {
        if self.taper > 0.0 {
            return self.cone_top(m, dist2, lo, hi);
        }
        let slope = |s: f64| {
            let r = (dist2 + s * s).sqrt();
            let u = r - self.flat;
            if u <= 0.0 {
                return m; // on the flat bottom
            }
            let w2 = self.corner * self.corner - u * u;
            if w2 <= 0.0 {
                // At the rim the wall is vertical: F rises steeply towards the foot.
                return if s < 0.0 { f64::INFINITY } else { f64::NEG_INFINITY };
            }
            m - u / w2.sqrt() * s / r
        };
        if slope(lo) <= 0.0 {
            return lo; // falling all along: the near end is highest
        }
        if slope(hi) >= 0.0 {
            return hi; // rising all along: the far end is highest
        }
        self.contact_between(m, dist2, lo, hi)
    }

    /// [`Profile::contact_along`] where F rises at `lo` and falls at `hi` (the caller has
    /// looked): the root of F' between.
    pub fn contact_between(&self, m: f64, dist2: f64, lo: f64, hi: f64) -> f64 {
        if self.taper > 0.0 {
            return self.cone_top(m, dist2, lo, hi);
        }
        if m == 0.0 {
            return 0.0; // a level line: the foot (between lo and hi, where the slope changes sign)
        }
        // Mirror a falling line onto a rising one: the root lies at s > 0, in (lo', hi').
        let (sign, m2) = (m.signum(), m * m);
        let (lo_m, hi_m) = if m > 0.0 { (lo, hi) } else { (-hi, -lo) };
        let (a, f) = (self.corner, self.flat);
        let u_of = |s: f64| ((dist2 + s * s).sqrt() - f).clamp(0.0, a);
        let (mut u_lo, mut u_hi) = (u_of(lo_m.max(0.0)), u_of(hi_m));
        // P and its derivative.
        let p = |u: f64| {
            let r = f + u;
            let (r2, u2) = (r * r, u * u);
            let value = (r2 - dist2) * u2 - m2 * (a * a - u2) * r2;
            let rate = 2.0 * r * u2 + 2.0 * u * (r2 - dist2) - m2 * (2.0 * r * (a * a - u2) - 2.0 * u * r2);
            (value, rate)
        };
        // P = 0 reads u = |m| a r / sqrt(r² (1 + m²) - dist2): exact at u0 = |m| a / sqrt(1 + m²)
        // for a line through the axis (dist2 = 0); one step of that from u0 starts the search.
        let k2 = 1.0 + m2;
        let r0 = f + m.abs() * a / k2.sqrt();
        let den = r0 * r0 * k2 - dist2;
        let guess = if den > 0.0 { m.abs() * a * r0 / den.sqrt() } else { -1.0 };
        let mut u = if guess > u_lo && guess < u_hi { guess } else { 0.5 * (u_lo + u_hi) };
        for _ in 0..100 {
            let (value, rate) = p(u);
            if value < 0.0 {
                u_lo = u;
            } else {
                u_hi = u;
            }
            let newton = u - value / rate;
            if rate > 0.0 && (newton - u).abs() <= CONTACT_LAST_STEP {
                u = newton.clamp(u_lo, u_hi);
                break;
            }
            u = if rate > 0.0 && newton > u_lo && newton < u_hi { newton } else { 0.5 * (u_lo + u_hi) };
            if u_hi - u_lo <= CONTACT_STEP {
                break;
            }
        }
        let r = f + u;
        let s = (sign * (r * r - dist2).max(0.0).sqrt()).clamp(lo, hi);
        // Near the rim the corner's wall is all but vertical: a root found to the last bits of u
        // can still stand a hair from the chord's end that is really highest there.
        if a - u > RIM * a {
            return s;
        }
        let value = |s: f64| m * s - self.height((dist2 + s * s).sqrt().min(self.radius));
        [lo, hi].into_iter().fold(s, |best, end| if value(end) > value(best) { end } else { best })
    }
}

/// The `s` in `[lo, hi]` that maximises the concave `F(s) = m s - k max(0, sqrt(dist2 + s²) - f)`
/// (a line of slope `m` at horizontal distance `sqrt(dist2)` from the axis of a cone rising `k`
/// per mm from a flat of radius `f`): towards the chord's end where the line rises at least as
/// fast as the side (`|m| >= k`), else where F' = 0, `s = m sqrt(dist2 / (k² - m²))`, if that lies
/// on the side, else where the side meets the flat.
fn cone_peak(m: f64, dist2: f64, k: f64, f: f64, lo: f64, hi: f64) -> f64 {
    let top = if m.abs() >= k {
        m.signum() * f64::INFINITY
    } else {
        let s_side = m * (dist2 / (k * k - m * m)).sqrt();
        if dist2 + s_side * s_side >= f * f {
            s_side
        } else {
            m.signum() * (f * f - dist2).max(0.0).sqrt()
        }
    };
    top.clamp(lo, hi)
}

/// A facet prepared for repeated drops: its plane, its projected corners, and the direction of
/// steepest ascent.
#[derive(Clone, Copy, Debug)]
pub struct FacetPlane {
    pub point: DVec3,
    /// Unit normal with a positive z component.
    pub normal: DVec3,
    /// Unit horizontal uphill direction (zero for a horizontal facet).
    pub uphill: DVec2,
    /// |n_xy|, the sine of the facet's slope.
    pub slope_sin: f64,
    corners: [DVec2; 3],
}

impl FacetPlane {
    /// `None` for degenerate and vertical facets (`|n.z|` at most `normal_tolerance`).
    pub fn new(a: DVec3, b: DVec3, c: DVec3, normal_tolerance: f64) -> Option<FacetPlane> {
        let mut n = (b - a).cross(c - a).try_normalize()?;
        if n.z < 0.0 {
            n = -n;
        }
        if n.z <= normal_tolerance {
            return None;
        }
        let h = n.truncate().length();
        let uphill = if h > normal_tolerance { -n.truncate() / h } else { DVec2::ZERO };
        let mut corners = [a.truncate(), b.truncate(), c.truncate()];
        if orient2d(corners[0], corners[1], corners[2]) < 0.0 {
            corners.swap(1, 2);
        }
        Some(FacetPlane { point: a, normal: n, uphill, slope_sin: h, corners })
    }

    /// Whether the projected facet contains `p` (boundary included).
    #[inline]
    pub fn contains(&self, p: DVec2) -> bool {
        let [a, b, c] = self.corners;
        orient2d(a, b, p) >= 0.0 && orient2d(b, c, p) >= 0.0 && orient2d(c, a, p) >= 0.0
    }

    /// Height of the facet's plane over `p`.
    #[inline]
    pub fn z_at(&self, p: DVec2) -> f64 {
        self.point.z - ((p.x - self.point.x) * self.normal.x + (p.y - self.point.y) * self.normal.y) / self.normal.z
    }
}

#[cfg(test)]
mod edge_tests {
    use super::*;

    /// The contact search against a long ternary search of the concave F(s), on lines of every
    /// slope (level to near vertical, rising and falling) at every distance (over the flat,
    /// across the corner, near the rim) and chords cut short at either end. (The Newton search
    /// on F' it replaced stopped up to 2.4e-5 mm short on near-vertical lines.)
    #[test]
    fn contact_along_finds_the_top_of_f() {
        let mut seed = 777u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for (radius, corner) in [(3.0, 1.0), (5.0, 2.5), (3.0, 0.2), (3.0, 2.9)] {
            let p = Profile::new(radius, corner);
            for k in 0..20_000 {
                let d = radius * [rnd(), 1.0 - rnd() * 1e-6, (radius - corner) / radius][k % 3];
                let m = (rnd() - 0.5) * [0.01, 1.0, 20.0, 1e4][k % 4];
                let half = (radius * radius - d * d).max(0.0).sqrt();
                let (lo, hi) = if k % 5 == 0 { (-half * rnd(), half * rnd()) } else { (-half, half) };
                let f = |s: f64| m * s - p.height((d * d + s * s).sqrt().min(radius));
                let (mut a, mut b) = (lo, hi);
                for _ in 0..300 {
                    let (x, y) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
                    if f(x) < f(y) {
                        a = x;
                    } else {
                        b = y;
                    }
                }
                let best = f(lo).max(f(hi)).max(f(0.5 * (a + b)));
                let s = p.contact_along(m, d * d, lo, hi);
                let bound = p.cone_bound(m, d * d, lo, hi);
                assert!(bound >= best - 1e-9 * (1.0 + m.abs()), "R{radius} a{corner} d {d} m {m} [{lo}, {hi}]: bound {bound} below {best}");
                assert!((lo..=hi).contains(&s), "R{radius} a{corner} d {d} m {m}: {s} outside [{lo}, {hi}]");
                assert!(f(s) >= best - 1e-8 * (1.0 + m.abs()), "R{radius} a{corner} d {d} m {m} [{lo}, {hi}]: F({s}) = {} below {best}", f(s));
            }
        }
    }

    /// The cone's edge drop (a drill's point, a V-bit with a flat tip, a shallow and a steep
    /// cone) against a dense scan along the edge, and its facet drop against a dense scan over
    /// the facet's points under the cutter.
    #[test]
    fn cone_drops_match_dense_scans() {
        for cutter in [Cutter::drill(6.0, 118.0), Cutter::v_bit(10.0, 90.0, 2.0), Cutter::v_bit(6.0, 30.0, 0.0), Cutter::v_bit(8.0, 160.0, 1.0)] {
            edge_drop_matches_a_dense_scan(&cutter, 1500);
            let p = cutter.profile();
            let mut seed = 99u64;
            let mut rnd = || {
                seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (seed >> 11) as f64 / (1u64 << 53) as f64
            };
            for _ in 0..300 {
                let corners = [0, 1, 2].map(|_| DVec3::new(rnd() * 20.0 - 10.0, rnd() * 20.0 - 10.0, rnd() * 12.0 - 6.0));
                let Some(facet) = FacetPlane::new(corners[0], corners[1], corners[2], 1e-9) else { continue };
                let c = DVec2::new(rnd() * 8.0 - 4.0, rnd() * 8.0 - 4.0);
                let Some(got) = p.drop_facet(c, &facet) else { continue };
                // The plane's points under the cutter: the drop is the highest of theirs.
                let mut best = f64::NEG_INFINITY;
                for i in 0..=400 {
                    for j in 0..=40 {
                        let (r, a) = (p.radius * i as f64 / 400.0, std::f64::consts::TAU * j as f64 / 40.0);
                        let q = c + DVec2::from_angle(a) * r;
                        best = best.max(facet.z_at(q) - p.height(r));
                    }
                }
                let along = c + facet.uphill * p.radius;
                best = best.max(facet.z_at(along) - p.height(p.radius)).max(facet.z_at(c + facet.uphill * p.flat_radius()));
                assert!(got >= best - 1e-9 && got <= best + 1e-3, "{cutter:?} {c}: facet drop {got} against a scan's {best}");
            }
        }
    }

    fn edge_drop_matches_a_dense_scan(cutter: &Cutter, count: usize) {
        let p = cutter.profile();
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..count {
            let a = DVec3::new(rnd() * 10.0 - 5.0, rnd() * 10.0 - 5.0, rnd() * 6.0 - 3.0);
            let b = DVec3::new(rnd() * 10.0 - 5.0, rnd() * 10.0 - 5.0, rnd() * 6.0 - 3.0);
            let c = DVec2::new(rnd() * 4.0 - 2.0, rnd() * 4.0 - 2.0);
            let got = p.drop_edge(c, a, b);
            let mut best: Option<f64> = None;
            let n = 200_000;
            for k in 0..=n {
                let q = a.lerp(b, k as f64 / n as f64);
                if let Some(z) = p.drop_vertex(c, q) {
                    best = Some(best.map_or(z, |v: f64| v.max(z)));
                }
            }
            match (got, best) {
                (Some(g), Some(w)) => assert!(g >= w - 1e-6 && g <= w + 1e-3, "{cutter:?} {a} {b} {c}: {g} vs scan {w}"),
                (None, Some(w)) => panic!("{cutter:?} {a} {b} {c}: none vs scan {w}"),
                _ => {}
            }
        }
    }

    /// The bull nose's edge drop against a dense scan along the edge.
    #[test]
    fn bull_nose_edge_drop_matches_a_dense_scan() {
        edge_drop_matches_a_dense_scan(&Cutter::bull_nose(6.0, 1.0), 2000);
    }
}
