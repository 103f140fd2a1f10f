//! A typed plane angle: the API never takes a bare `f64` for an angle, so passing
//! degrees where radians are expected (or the reverse) does not compile.

use std::f64::consts::{PI, TAU};
use std::ops::{Add, Neg, Sub};

/// A plane angle, stored in radians; build it with [`Angle::from_degrees`] or
/// [`Angle::from_radians`] and read it with [`Angle::degrees`] or [`Angle::radians`].
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct Angle {
    radians: f64,
}

impl Angle {
    /// Zero.
    pub const ZERO: Angle = Angle { radians: 0.0 };

    /// An angle of `radians` radians.
    pub const fn from_radians(radians: f64) -> Self {
        Angle { radians }
    }

    /// An angle of `degrees` degrees.
    pub fn from_degrees(degrees: f64) -> Self {
        Angle {
            radians: degrees.to_radians(),
        }
    }

    /// An angle given in arcseconds (nutation and obliquity terms are published so).
    pub fn from_arcseconds(arcseconds: f64) -> Self {
        Self::from_degrees(arcseconds / 3600.0)
    }

    /// An angle given in hours of right ascension or sidereal time (1 h = 15°).
    pub fn from_hours(hours: f64) -> Self {
        Self::from_degrees(hours * 15.0)
    }

    /// The angle in radians.
    pub const fn radians(self) -> f64 {
        self.radians
    }

    /// The angle in degrees.
    pub fn degrees(self) -> f64 {
        self.radians.to_degrees()
    }

    /// The angle in hours (15° per hour).
    pub fn hours(self) -> f64 {
        self.degrees() / 15.0
    }

    /// The same direction in [0, 2π).
    pub fn wrapped_positive(self) -> Self {
        let wrapped = self.radians.rem_euclid(TAU);
        // rem_euclid can round up to exactly TAU for tiny negative inputs.
        Angle::from_radians(if wrapped >= TAU { 0.0 } else { wrapped })
    }

    /// The same direction in [−π, π).
    pub fn wrapped_signed(self) -> Self {
        Angle::from_radians((self.radians + PI).rem_euclid(TAU) - PI)
    }

    /// Sine.
    pub fn sin(self) -> f64 {
        self.radians.sin()
    }

    /// Cosine.
    pub fn cos(self) -> f64 {
        self.radians.cos()
    }

    /// Whether the value is finite (not NaN or infinite).
    pub fn is_finite(self) -> bool {
        self.radians.is_finite()
    }
}

impl Add for Angle {
    type Output = Angle;
    fn add(self, rhs: Angle) -> Angle {
        Angle::from_radians(self.radians + rhs.radians)
    }
}

impl Sub for Angle {
    type Output = Angle;
    fn sub(self, rhs: Angle) -> Angle {
        Angle::from_radians(self.radians - rhs.radians)
    }
}

impl Neg for Angle {
    type Output = Angle;
    fn neg(self) -> Angle {
        Angle::from_radians(-self.radians)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_round_trip() {
        let a = Angle::from_degrees(180.0);
        assert!((a.radians() - PI).abs() < 1e-15);
        assert!((Angle::from_hours(13.0).degrees() - 195.0).abs() < 1e-12);
        assert!((Angle::from_arcseconds(3600.0).degrees() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn wrapping() {
        assert!((Angle::from_degrees(-90.0).wrapped_positive().degrees() - 270.0).abs() < 1e-12);
        assert!((Angle::from_degrees(270.0).wrapped_signed().degrees() + 90.0).abs() < 1e-12);
        let tiny = Angle::from_radians(-1e-300).wrapped_positive();
        assert!(tiny.radians() >= 0.0 && tiny.radians() < TAU);
    }
}
