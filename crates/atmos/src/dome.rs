//! Per-vertex evaluation: any [`SkyModel`] evaluated at the vertices of a dome mesh
//! around the viewer and interpolated across its faces, as a vertex shader over a sky
//! dome does (seed 000's dome). Cost moves from per pixel to per vertex; the error is
//! the interpolation's, measured by `cargo xtask tradeoff atmos`.
//!
//! The dome is a latitude–longitude sphere in the viewer's local frame: `rings`
//! elevation bands from −π/2 to π/2 and `segments` azimuth sectors, azimuth measured
//! from the sun's vertical plane (so the sun's glow is centred on a meridian). Values are
//! interpolated bilinearly in (elevation, azimuth) — Gouraud shading of the quads.

use std::sync::Mutex;

use glam::DVec3;

use crate::AtmosError;
use crate::ladder::{SkyModel, SkyQuery, SkySample};

/// Mesh resolution of a [`DomeInterpolated`] sky.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DomeResolution {
    /// Elevation bands from nadir to zenith (≥ 2).
    pub rings: u32,
    /// Azimuth sectors (≥ 3).
    pub segments: u32,
}

impl DomeResolution {
    /// Number of vertices evaluated per (viewer, sun).
    pub fn vertex_count(&self) -> usize {
        (self.rings as usize + 1) * (self.segments as usize + 1)
    }
}

#[derive(Debug)]
struct DomeGrid {
    key: (DVec3, DVec3, u64),
    samples: Vec<SkySample>,
}

/// A model evaluated per vertex of a dome and interpolated per query.
#[derive(Debug)]
pub struct DomeInterpolated<M> {
    model: M,
    resolution: DomeResolution,
    planet_radius: f64,
    grid: Mutex<Option<DomeGrid>>,
}

/// The viewer's local frame: zenith, and the horizontal direction of the sun (any
/// horizontal direction when the sun is at the zenith or nadir).
fn local_frame(position: DVec3, sun: DVec3) -> (DVec3, DVec3, DVec3) {
    let zenith = position.normalize();
    let horizontal_sun = sun - zenith * sun.dot(zenith);
    let east = horizontal_sun
        .try_normalize()
        .unwrap_or_else(|| zenith.any_orthonormal_vector());
    let north = zenith.cross(east);
    (zenith, east, north)
}

impl<M: SkyModel> DomeInterpolated<M> {
    /// Wraps `model`; `planet_radius` (m) is needed to build the vertex queries.
    pub fn new(
        model: M,
        resolution: DomeResolution,
        planet_radius: f64,
    ) -> Result<Self, AtmosError> {
        if resolution.rings < 2 {
            return Err(AtmosError::InvalidParameter {
                field: "rings".into(),
                value: f64::from(resolution.rings),
                reason: "a dome needs ≥ 2 elevation bands",
            });
        }
        if resolution.segments < 3 {
            return Err(AtmosError::InvalidParameter {
                field: "segments".into(),
                value: f64::from(resolution.segments),
                reason: "a dome needs ≥ 3 azimuth sectors",
            });
        }
        Ok(Self {
            model,
            resolution,
            planet_radius,
            grid: Mutex::new(None),
        })
    }

    /// The mesh resolution.
    pub fn resolution(&self) -> DomeResolution {
        self.resolution
    }

    /// The wrapped model.
    pub fn model(&self) -> &M {
        &self.model
    }

    fn vertex_direction(&self, ring: u32, segment: u32, frame: (DVec3, DVec3, DVec3)) -> DVec3 {
        let (zenith, east, north) = frame;
        let elevation = -std::f64::consts::FRAC_PI_2
            + std::f64::consts::PI * f64::from(ring) / f64::from(self.resolution.rings);
        let azimuth =
            std::f64::consts::TAU * f64::from(segment) / f64::from(self.resolution.segments);
        let (sin_e, cos_e) = elevation.sin_cos();
        let (sin_a, cos_a) = azimuth.sin_cos();
        (zenith * sin_e + cos_e * (east * cos_a + north * sin_a)).normalize()
    }

    /// Evaluates every vertex for this viewer and sun (the per-frame "vertex shader").
    fn build(&self, query: &SkyQuery) -> DomeGrid {
        let frame = local_frame(query.position(), query.sun());
        let mut samples = Vec::with_capacity(self.resolution.vertex_count());
        for ring in 0..=self.resolution.rings {
            for segment in 0..=self.resolution.segments {
                let view = self.vertex_direction(ring, segment, frame);
                let vertex = SkyQuery::with_max_distance(
                    self.planet_radius,
                    query.position(),
                    view,
                    query.sun(),
                    query.max_distance(),
                )
                .expect("vertex queries reuse a validated query's position, sun and distance");
                samples.push(self.model.evaluate(&vertex));
            }
        }
        DomeGrid {
            key: (
                query.position(),
                query.sun(),
                query.max_distance().to_bits(),
            ),
            samples,
        }
    }
}

impl<M: SkyModel> SkyModel for DomeInterpolated<M> {
    fn label(&self) -> String {
        format!(
            "{} per vertex ({}×{} dome)",
            self.model.label().trim_end_matches(", per pixel"),
            self.resolution.rings,
            self.resolution.segments
        )
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        let key = (
            query.position(),
            query.sun(),
            query.max_distance().to_bits(),
        );
        let mut guard = self
            .grid
            .lock()
            .unwrap_or_else(|poison| poison.into_inner());
        if guard.as_ref().is_none_or(|g| g.key != key) {
            *guard = Some(self.build(query));
        }
        let grid = guard.as_ref().expect("built above");
        let (zenith, east, north) = local_frame(query.position(), query.sun());
        let view = query.view();
        let elevation = view.dot(zenith).clamp(-1.0, 1.0).asin();
        let azimuth = view
            .dot(north)
            .atan2(view.dot(east))
            .rem_euclid(std::f64::consts::TAU);
        let rings = f64::from(self.resolution.rings);
        let segments = f64::from(self.resolution.segments);
        let v = ((elevation + std::f64::consts::FRAC_PI_2) / std::f64::consts::PI * rings)
            .clamp(0.0, rings);
        let u = (azimuth / std::f64::consts::TAU * segments).clamp(0.0, segments);
        let (i0, j0) = (
            (v.floor() as u32).min(self.resolution.rings - 1),
            (u.floor() as u32).min(self.resolution.segments - 1),
        );
        let (fv, fu) = (v - f64::from(i0), u - f64::from(j0));
        let stride = self.resolution.segments as usize + 1;
        let at = |i: u32, j: u32| &grid.samples[i as usize * stride + j as usize];
        let weights = [
            (at(i0, j0), (1.0 - fv) * (1.0 - fu)),
            (at(i0, j0 + 1), (1.0 - fv) * fu),
            (at(i0 + 1, j0), fv * (1.0 - fu)),
            (at(i0 + 1, j0 + 1), fv * fu),
        ];
        let mut out = SkySample::default();
        for (sample, w) in weights {
            for c in 0..3 {
                out.radiance[c] += w * sample.radiance[c];
                out.transmittance[c] += w * sample.transmittance[c];
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Atmosphere;
    use crate::closed_form_sky::ClosedFormSky;

    #[test]
    fn vertices_reproduce_the_model_and_between_them_values_are_bounded() {
        let earth = Atmosphere::earth();
        let model = ClosedFormSky::new(&earth).unwrap();
        let dome = DomeInterpolated::new(
            ClosedFormSky::new(&earth).unwrap(),
            DomeResolution {
                rings: 8,
                segments: 16,
            },
            earth.planet_radius,
        )
        .unwrap();
        let position = DVec3::new(0.0, 0.0, earth.planet_radius + 100.0);
        let sun = DVec3::new(0.6, 0.0, 0.8);
        // A vertex direction: elevation −π/2 + π·5/8 = π/8 in the sun's plane (azimuth 0).
        let e = std::f64::consts::FRAC_PI_8;
        let at_vertex = DVec3::new(e.cos(), 0.0, e.sin());
        let q = SkyQuery::new(earth.planet_radius, position, at_vertex, sun).unwrap();
        let (a, b) = (dome.evaluate(&q), model.evaluate(&q));
        for c in 0..3 {
            assert!((a.radiance[c] - b.radiance[c]).abs() <= 1e-9 * b.radiance[c].abs().max(1e-12));
        }
        // Between vertices, the interpolation stays within the neighbouring values.
        let between = DVec3::new(0.9, 0.3, 0.3).normalize();
        let q = SkyQuery::new(earth.planet_radius, position, between, sun).unwrap();
        let s = dome.evaluate(&q);
        assert!(s.radiance.iter().all(|v| v.is_finite() && *v >= 0.0));
        assert!(s.transmittance.iter().all(|t| (0.0..=1.0).contains(t)));
    }

    #[test]
    fn too_coarse_domes_are_rejected() {
        let earth = Atmosphere::earth();
        let m = || ClosedFormSky::new(&earth).unwrap();
        let r = earth.planet_radius;
        assert!(
            DomeInterpolated::new(
                m(),
                DomeResolution {
                    rings: 1,
                    segments: 8
                },
                r
            )
            .unwrap_err()
            .to_string()
            .contains("rings")
        );
        assert!(
            DomeInterpolated::new(
                m(),
                DomeResolution {
                    rings: 4,
                    segments: 2
                },
                r
            )
            .unwrap_err()
            .to_string()
            .contains("segments")
        );
    }
}
