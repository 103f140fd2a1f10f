//! The precomputed rung for scattered queries: every segment marched through the
//! static tables, no per-viewpoint sky-view table.
//!
//! [`PrecomputedSky`] answers an unlimited view ray from inside the atmosphere by
//! reading a sky-view table baked for the viewer's radius and the sun's zenith cosine
//! (Hillaire 2020), as the GPU's sky pass does: worth it for a frame's pixels, which
//! share the viewpoint. A handful of directions — a sky dome's vertices, a hemisphere
//! quadrature for a surface's irradiance, the light at a cloud layer's altitude — would
//! pay for a whole table per viewpoint and sun. [`MarchedPrecomputedSky`] marches each
//! such ray instead, with the same transmittance and multiple-scattering tables
//! ([`super::raymarch::march_view_segment`], `pixel_samples` steps: the path the rung already takes for
//! viewers above the atmosphere and for finite segments), so its answers carry no
//! sky-view interpolation error and cost nothing per viewpoint.

use super::precomputed_sky::PrecomputedSky;
use crate::ladder::{SkyModel, SkyQuery, SkySample};

/// [`PrecomputedSky`]'s tables read by a per-ray march (module documentation).
#[derive(Debug, Clone, Copy)]
pub struct MarchedPrecomputedSky<'a> {
    sky: &'a PrecomputedSky,
}

impl<'a> MarchedPrecomputedSky<'a> {
    /// The march over `sky`'s static tables.
    pub fn new(sky: &'a PrecomputedSky) -> Self {
        Self { sky }
    }
}

impl SkyModel for MarchedPrecomputedSky<'_> {
    fn label(&self) -> String {
        format!("{}, marched per ray", self.sky.label())
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        self.sky
            .marched_sample(query.cosines(), query.max_distance())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn sky() -> PrecomputedSky {
        PrecomputedSky::new(&crate::Atmosphere::earth(), &Default::default()).unwrap()
    }

    fn query(view: DVec3, sun: DVec3, altitude: f64) -> SkyQuery {
        let planet = crate::Atmosphere::earth().planet_radius;
        SkyQuery::new(
            planet,
            DVec3::new(0.0, planet + altitude, 0.0),
            view.normalize(),
            sun.normalize(),
        )
        .unwrap()
    }

    #[test]
    fn marched_rays_agree_with_the_sky_view_table() {
        let sky = sky();
        let marched = MarchedPrecomputedSky::new(&sky);
        let sun = DVec3::new(0.6, 0.5, 0.2);
        let mut worst: f64 = 0.0;
        for (i, view) in [
            DVec3::Y,
            DVec3::new(1.0, 0.3, 0.0),
            DVec3::new(-1.0, 0.05, 0.4),
            DVec3::new(0.2, 0.8, -0.5),
        ]
        .into_iter()
        .enumerate()
        {
            let q = query(view, sun, 1000.0 * i as f64);
            let a = marched.evaluate(&q);
            let b = sky.evaluate(&q);
            for k in 0..3 {
                assert!(a.radiance[k].is_finite() && a.radiance[k] > 0.0);
                worst = worst.max((a.radiance[k] / b.radiance[k] - 1.0).abs());
            }
        }
        // Both integrate the same tables; they differ by the sky-view table's
        // interpolation and its 30-step march against 64 uniform steps.
        assert!(worst < 0.05, "worst relative difference {worst}");
        // And a wrong answer would show: the sun at the nadir darkens the zenith.
        let night = marched.evaluate(&query(DVec3::Y, -DVec3::Y, 0.0));
        let day = marched.evaluate(&query(DVec3::Y, sun, 0.0));
        assert!(night.radiance[2] < 1e-3 * day.radiance[2]);
    }
}
