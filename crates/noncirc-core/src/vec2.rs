//! A point or a vector of the plane (mm, or mm per radian for derivatives): a small
//! copyable type with the arithmetic the mechanism needs, in the spirit of kurbo's `Vec2`.
//! Serialised as `[x, y]`.

use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// A point or vector `(x, y)`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(from = "[f64; 2]", into = "[f64; 2]")]
pub struct Vec2 {
    pub x: f64,
    pub y: f64,
}

impl Vec2 {
    pub const ZERO: Vec2 = Vec2 { x: 0.0, y: 0.0 };

    #[inline]
    pub const fn new(x: f64, y: f64) -> Self {
        Vec2 { x, y }
    }

    /// Dot product.
    #[inline]
    pub fn dot(self, other: Vec2) -> f64 {
        self.x * other.x + self.y * other.y
    }

    /// Cross product `x·y' − y·x'` (positive when `other` is counter-clockwise of `self`).
    #[inline]
    pub fn cross(self, other: Vec2) -> f64 {
        self.x * other.y - self.y * other.x
    }

    /// Length.
    #[inline]
    pub fn hypot(self) -> f64 {
        self.x.hypot(self.y)
    }

    /// Squared length.
    #[inline]
    pub fn hypot2(self) -> f64 {
        self.dot(self)
    }

    /// Turned a quarter turn counter-clockwise: `(−y, x)`.
    #[inline]
    pub fn turn_90(self) -> Vec2 {
        Vec2::new(-self.y, self.x)
    }

    /// Turned by the angle of the unit vector `by` (a complex product).
    #[inline]
    pub fn rotated(self, by: Vec2) -> Vec2 {
        Vec2::new(self.x * by.x - self.y * by.y, self.x * by.y + self.y * by.x)
    }

    /// Whether both coordinates are finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl From<[f64; 2]> for Vec2 {
    #[inline]
    fn from([x, y]: [f64; 2]) -> Self {
        Vec2 { x, y }
    }
}

impl From<Vec2> for [f64; 2] {
    #[inline]
    fn from(v: Vec2) -> Self {
        [v.x, v.y]
    }
}

impl From<Vec2> for (f64, f64) {
    #[inline]
    fn from(v: Vec2) -> Self {
        (v.x, v.y)
    }
}

impl Add for Vec2 {
    type Output = Vec2;
    #[inline]
    fn add(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x + o.x, self.y + o.y)
    }
}

impl AddAssign for Vec2 {
    #[inline]
    fn add_assign(&mut self, o: Vec2) {
        *self = *self + o;
    }
}

impl Sub for Vec2 {
    type Output = Vec2;
    #[inline]
    fn sub(self, o: Vec2) -> Vec2 {
        Vec2::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<f64> for Vec2 {
    type Output = Vec2;
    #[inline]
    fn mul(self, k: f64) -> Vec2 {
        Vec2::new(self.x * k, self.y * k)
    }
}

impl Neg for Vec2 {
    type Output = Vec2;
    #[inline]
    fn neg(self) -> Vec2 {
        Vec2::new(-self.x, -self.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_and_turns() {
        let (a, b) = (Vec2::new(3.0, 4.0), Vec2::new(-2.0, 1.0));
        assert_eq!(a.hypot(), 5.0);
        assert_eq!(a.dot(b), -2.0);
        assert_eq!(a.cross(b), 11.0);
        assert_eq!(a.turn_90(), Vec2::new(-4.0, 3.0));
        assert_eq!(a.rotated(Vec2::new(0.0, 1.0)), a.turn_90());
        assert_eq!((a - b) * 2.0 + b, Vec2::new(8.0, 7.0));
        assert_eq!(serde_json::to_string(&a).unwrap(), "[3.0,4.0]");
        assert_eq!(serde_json::from_str::<Vec2>("[3.0,4.0]").unwrap(), a);
    }
}
