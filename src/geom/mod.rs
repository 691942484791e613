//! Small shared geometry on glam's f64 vectors: bounding boxes, triangles, and the one place
//! where swarf's tolerances live.

pub mod index;
pub mod segment;
pub mod sort;
pub mod tolerance;

pub use glam::{DVec2, DVec3};
pub use tolerance::Tolerances;

/// An axis-aligned box in millimetres.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize, ts_rs::TS)]
pub struct Aabb {
    #[ts(type = "[number, number, number]")]
    pub min: DVec3,
    #[ts(type = "[number, number, number]")]
    pub max: DVec3,
}

impl Aabb {
    /// The empty box: any point grows it.
    pub const EMPTY: Aabb = Aabb { min: DVec3::splat(f64::INFINITY), max: DVec3::splat(f64::NEG_INFINITY) };

    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| b.grow(*p))
    }

    pub fn grow(self, p: DVec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }

    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }
}

/// A triangle of a part, in millimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub a: DVec3,
    pub b: DVec3,
    pub c: DVec3,
}

impl Triangle {
    pub fn new(a: DVec3, b: DVec3, c: DVec3) -> Triangle {
        Triangle { a, b, c }
    }

    pub fn vertices(&self) -> [DVec3; 3] {
        [self.a, self.b, self.c]
    }

    /// Twice the area vector (not normalised).
    pub fn cross(&self) -> DVec3 {
        (self.b - self.a).cross(self.c - self.a)
    }

    /// Unit normal, or `None` for a degenerate triangle.
    pub fn normal(&self) -> Option<DVec3> {
        let n = self.cross();
        let len = n.length();
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&[self.a, self.b, self.c])
    }
}

/// Signed doubled area of the 2D triangle (a, b, c): positive when counter-clockwise.
#[inline]
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}
