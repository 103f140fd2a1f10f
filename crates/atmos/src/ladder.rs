//! The scattering ladder: every model of the sky answers the same question through
//! [`SkyModel`], so users can swap a cheap rung for an accurate one and
//! `cargo xtask tradeoff atmos` can measure each against the reference.
//!
//! The question: a viewer at `position` (planet-centred, metres) looks along `view`
//! with the sun along `sun` (unit vectors, pointing *away* from the viewer). Along the
//! view ray up to the ground, the top of the atmosphere or `max_distance` (whichever
//! comes first), what radiance is scattered toward the viewer, and what fraction of
//! light from the segment's far end arrives?
//!
//! * Radiance is in the unit of [`Atmosphere::sun_irradiance`](crate::Atmosphere) per
//!   steradian (per unit sun irradiance with the default irradiance of 1). It is the
//!   light scattered *in the air* only: it excludes the sun disc itself and the ground
//!   surface's own reflected radiance at the segment's end (the terrain shader adds that,
//!   times [`SkySample::transmittance`]); light the ground reflects *into the air* and
//!   the air scatters again is included by the rungs that model multiple scattering.
//! * The three channels are the atmosphere's three coefficient sets (≈ 680, 550, 440 nm,
//!   read as linear sRGB red, green, blue).
//! * A viewer outside the atmosphere sees the segment from where the ray enters the shell;
//!   a viewer below the ground (down to −10 m is accepted, rounding of terrain) is
//!   treated as on the ground.

use glam::DVec3;

use crate::AtmosError;

/// Rec. 709 / sRGB luminance weights, for the relative-luminance errors reported by
/// the trade-off study.
pub const LUMINANCE_WEIGHTS: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// Luminance of a linear-sRGB triple.
pub fn luminance(rgb: [f64; 3]) -> f64 {
    rgb.iter().zip(LUMINANCE_WEIGHTS).map(|(c, w)| c * w).sum()
}

/// How far below the ground a viewer may stand (m) before the query is rejected:
/// terrain meshes and height maps round a few metres either way.
pub const MAX_DEPTH_BELOW_GROUND: f64 = 10.0;

/// Directions may deviate from unit length by this much (and are renormalised);
/// anything further is a caller bug and is rejected.
pub const UNIT_LENGTH_TOLERANCE: f64 = 1e-3;

/// A validated question to a [`SkyModel`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyQuery {
    position: DVec3,
    view: DVec3,
    sun: DVec3,
    max_distance: f64,
}

fn invalid(field: &str, value: f64, reason: &'static str) -> AtmosError {
    AtmosError::InvalidCamera {
        field: field.to_owned(),
        value,
        reason,
    }
}

fn unit(field: &str, v: DVec3) -> Result<DVec3, AtmosError> {
    for (axis, c) in ["x", "y", "z"].iter().zip(v.to_array()) {
        if !c.is_finite() {
            return Err(invalid(&format!("{field}.{axis}"), c, "must be finite"));
        }
    }
    let length = v.length();
    if (length - 1.0).abs() > UNIT_LENGTH_TOLERANCE {
        return Err(invalid(
            &format!("|{field}|"),
            length,
            "must be a unit vector (within 1e-3)",
        ));
    }
    Ok(v / length)
}

impl SkyQuery {
    /// A query up to the ground or the top of the atmosphere.
    ///
    /// `planet_radius` is needed only to reject viewers more than
    /// [`MAX_DEPTH_BELOW_GROUND`] under the ground.
    pub fn new(
        planet_radius: f64,
        position: DVec3,
        view: DVec3,
        sun: DVec3,
    ) -> Result<Self, AtmosError> {
        Self::with_max_distance(planet_radius, position, view, sun, f64::INFINITY)
    }

    /// A query along a segment of at most `max_distance` metres (aerial perspective
    /// toward geometry at that distance). `f64::INFINITY` means "to the ground or space".
    pub fn with_max_distance(
        planet_radius: f64,
        position: DVec3,
        view: DVec3,
        sun: DVec3,
        max_distance: f64,
    ) -> Result<Self, AtmosError> {
        for (axis, c) in ["x", "y", "z"].iter().zip(position.to_array()) {
            if !c.is_finite() {
                return Err(invalid(&format!("position.{axis}"), c, "must be finite"));
            }
        }
        let altitude = position.length() - planet_radius;
        if altitude < -MAX_DEPTH_BELOW_GROUND {
            return Err(invalid(
                "position altitude",
                altitude,
                "viewer is more than 10 m below the ground",
            ));
        }
        if max_distance.is_nan() || max_distance < 0.0 {
            return Err(invalid(
                "max_distance",
                max_distance,
                "must be ≥ 0 (or infinite)",
            ));
        }
        Ok(Self {
            position,
            view: unit("view", view)?,
            sun: unit("sun", sun)?,
            max_distance,
        })
    }

    /// Viewer position, planet-centred (m).
    pub fn position(&self) -> DVec3 {
        self.position
    }
    /// Unit view direction.
    pub fn view(&self) -> DVec3 {
        self.view
    }
    /// Unit direction toward the sun.
    pub fn sun(&self) -> DVec3 {
        self.sun
    }
    /// Segment length limit (m), infinite for "to the ground or space".
    pub fn max_distance(&self) -> f64 {
        self.max_distance
    }
    /// Distance of the viewer from the planet centre (m).
    pub fn r(&self) -> f64 {
        self.position.length()
    }
    /// Cosine of the view zenith angle.
    pub fn mu(&self) -> f64 {
        self.view.dot(self.position.normalize())
    }
    /// Cosine of the sun zenith angle at the viewer.
    pub fn mu_s(&self) -> f64 {
        self.sun.dot(self.position.normalize())
    }
    /// Cosine of the view–sun angle.
    pub fn nu(&self) -> f64 {
        self.view.dot(self.sun)
    }
    /// `[r, μ, μ_s, ν]` at once (one square root and one division instead of one per
    /// accessor): what a per-pixel evaluation reads.
    pub fn cosines(&self) -> [f64; 4] {
        let r = self.position.length();
        let up = self.position * r.recip(); // = position.normalize(), as mu() and mu_s()
        [
            r,
            self.view.dot(up),
            self.sun.dot(up),
            self.view.dot(self.sun),
        ]
    }
}

/// What a rung answers.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SkySample {
    /// In-scattered radiance reaching the viewer per channel (see the module docs for
    /// the unit and what is included).
    pub radiance: [f64; 3],
    /// Transmittance of the segment per channel, in [0, 1].
    pub transmittance: [f64; 3],
}

/// One rung of the ladder: a model of the light scattered by the atmosphere.
pub trait SkyModel {
    /// A short description with its quality settings, e.g. `single scattering (32/8)`.
    fn label(&self) -> String;
    /// Radiance and transmittance along the query's segment.
    fn evaluate(&self, query: &SkyQuery) -> SkySample;
    /// [`SkyModel::evaluate`] of every query, in order: a frame's pixels. Models with
    /// per-viewpoint work (a per-frame LUT) look it up once for the queries that share
    /// the first query's viewer and sun, instead of once per query; the results are the
    /// same as one call per query.
    fn evaluate_batch(&self, queries: &[SkyQuery]) -> Vec<SkySample> {
        queries.iter().map(|query| self.evaluate(query)).collect()
    }
}

/// A model behind a reference, a `Box` or an `Arc` is the model: callers keep one
/// boxed or shared model and lend it to functions generic over `SkyModel`.
macro_rules! forward_sky_model {
    ($($pointer:ty),*) => {$(
        impl<M: SkyModel + ?Sized> SkyModel for $pointer {
            fn label(&self) -> String {
                (**self).label()
            }
            fn evaluate(&self, query: &SkyQuery) -> SkySample {
                (**self).evaluate(query)
            }
            fn evaluate_batch(&self, queries: &[SkyQuery]) -> Vec<SkySample> {
                (**self).evaluate_batch(queries)
            }
        }
    )*};
}
forward_sky_model!(&M, Box<M>, std::sync::Arc<M>);

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6_360_000.0;

    #[test]
    fn queries_reject_bad_input_naming_the_field() {
        let p = DVec3::new(0.0, 0.0, R + 1.0);
        let up = DVec3::Z;
        let err = |e: AtmosError| e.to_string();
        assert!(
            err(SkyQuery::new(R, p, DVec3::new(0.0, 0.0, 2.0), up).unwrap_err()).contains("|view|")
        );
        assert!(
            err(SkyQuery::new(R, p, up, DVec3::new(f64::NAN, 0.0, 1.0)).unwrap_err())
                .contains("sun.x")
        );
        assert!(
            err(SkyQuery::new(R, DVec3::new(0.0, 0.0, R - 11.0), up, up).unwrap_err())
                .contains("altitude")
        );
        assert!(
            err(SkyQuery::with_max_distance(R, p, up, up, -1.0).unwrap_err())
                .contains("max_distance")
        );
        assert!(SkyQuery::new(R, DVec3::new(0.0, 0.0, R - 9.0), up, up).is_ok());
    }

    #[test]
    fn nearly_unit_directions_are_renormalised_and_angles_follow() {
        let p = DVec3::new(0.0, 0.0, R + 100.0);
        let q = SkyQuery::new(R, p, DVec3::new(0.0, 0.0, 1.0005), DVec3::X).unwrap();
        assert!((q.view().length() - 1.0).abs() < 1e-15);
        assert!((q.mu() - 1.0).abs() < 1e-15);
        assert!(q.mu_s().abs() < 1e-15 && q.nu().abs() < 1e-15);
        assert_eq!(q.r(), R + 100.0);
    }

    #[test]
    fn luminance_weights_sum_to_one() {
        assert!((luminance([1.0; 3]) - 1.0).abs() < 1e-12);
        assert!(luminance([0.0, 1.0, 0.0]) > luminance([1.0, 0.0, 0.0]));
    }
}
