//! SGSky's 12-sided dome as an atmos rung: [`SgskyDomeSky`] answers every sky ray from
//! the painted dome (SimGear's SGSky: a few model queries per frame on the CPU, vertex
//! colours blended across the dome's triangles) plus the sun's Mie aureole per pixel,
//! and every finite segment (terrain, clouds) from the model it wraps.
//!
//! **Frame.** A query's viewer defines the dome's frame: up is the viewer's
//! planet-centred position, "east" the sun's horizontal direction, so the dome is
//! rotated toward the sun as SGSky rotates it ([`SKY_DOME_SPIN`]: vertex 0 on the sun's
//! azimuth). The WGSL pass (`celestial::gpu::SkyDomeRenderer`) builds the same frame
//! from a `FrameCamera` ([`dome_local_frame`]).
//!
//! **Transmittance.** The dome carries colours only. Every sky ray gets the
//! transmittance toward the sun: what draws the sun's disc through the air (the only
//! use of a sky ray's transmittance in a frame: elsewhere the disc's radiance is zero).
//!
//! **Range.** SGSky's dome is a sky seen from inside the atmosphere; the painting
//! accepts viewers up to ten times the atmosphere's height
//! ([`crate::objects::SkyObjectsBuilder`]'s range). Beyond it, or where a painting
//! fails, [`SgskyDomeSky::painting`] says why and `evaluate` answers from the model.

use std::sync::Mutex;

use atmos::Atmosphere;
use atmos::ladder::{SkyModel, SkyQuery, SkySample};
use glam::DVec3;

use crate::angle::Angle;
use crate::dome::{DOME_VERTICES, DomeColouring, SkyDome};
use crate::error::Result;
use crate::objects::{Aureole, BackgroundSampling, SkyObjectsBuilder};

/// The dome's rotation in its local frame: vertex 0 along +x, the sun's horizontal
/// direction (azimuth 90° from north, 90° from south toward east).
pub const SKY_DOME_SPIN: Angle = Angle::from_radians(std::f64::consts::FRAC_PI_2);

/// The dome's frame for a viewer at planet-centred `position` lit along `sun`: (x,
/// y, up) with x the sun's horizontal direction, y = up × x. With the sun at the zenith
/// or nadir, x = normalize((1, 0, 0) × up) (or (0, 1, 0) × up when |up.x| > 0.9), as
/// the WGSL pass does.
pub fn dome_local_frame(position: DVec3, sun: DVec3) -> [DVec3; 3] {
    let up = position.normalize();
    let horizontal = sun - up * sun.dot(up);
    let x = if horizontal.length_squared() > 1e-12 {
        horizontal.normalize()
    } else {
        let helper = if up.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
        helper.cross(up).normalize()
    };
    [x, up.cross(x), up]
}

/// What the GPU pass needs of one painted dome (`shaders/celestial/sky_dome_pass.wgsl`'s
/// `SkyDomeUniforms`): the vertex colours, the rotation and the aureole's inputs.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SkyDomeUniforms {
    /// Vertex colours (rgb, 1) in [`SkyDome::vertex_colours`]' order.
    pub colours: [[f32; 4]; DOME_VERTICES],
    /// The sun's irradiance above the atmosphere per channel.
    pub sun_irradiance: [f32; 3],
    /// The dome's rotation (radians, vertex 0 from south toward east).
    pub spin: f32,
    /// Transmittance toward the sun per channel.
    pub sun_transmittance: [f32; 3],
    /// Mie anisotropy.
    pub mie_g: f32,
    /// Mie optical depth toward the sun per channel.
    pub mie_optical_depth: [f32; 3],
    /// Keeps 16-byte rows.
    pub padding: f32,
}

impl SkyDomeUniforms {
    /// The uniforms of `dome` and `aureole`.
    pub fn new(dome: &SkyDome, aureole: &Aureole) -> Self {
        let colours = dome.vertex_colours();
        Self {
            colours: std::array::from_fn(|k| {
                let c = colours[k];
                [c[0] as f32, c[1] as f32, c[2] as f32, 1.0]
            }),
            sun_irradiance: aureole.irradiance.map(|v| v as f32),
            spin: dome.spin().radians() as f32,
            sun_transmittance: aureole.transmittance.map(|v| v as f32),
            mie_g: aureole.mie_g as f32,
            mie_optical_depth: aureole.mie_optical_depth.map(|v| v as f32),
            padding: 0.0,
        }
    }
}

/// One painting: the dome and the aureole for a viewer and a sun.
#[derive(Debug, Clone)]
pub struct PaintedSky {
    /// The viewer (planet-centred, m) and the sun (unit) it was painted for.
    pub key: (DVec3, DVec3),
    /// The dome, in the local frame of [`dome_local_frame`].
    pub dome: SkyDome,
    /// The sun's aureole, in the same frame.
    pub aureole: Aureole,
}

/// SGSky's dome painted from `model` (see the module docs).
pub struct SgskyDomeSky<M> {
    model: M,
    atmosphere: Atmosphere,
    colouring: DomeColouring,
    painted: Mutex<Option<PaintedSky>>,
}

impl<M> std::fmt::Debug for SgskyDomeSky<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SgskyDomeSky")
            .field("colouring", &self.colouring)
            .finish_non_exhaustive()
    }
}

impl<M: SkyModel> SgskyDomeSky<M> {
    /// The dome painted from `model` (built from `atmosphere`: its radiance in the unit
    /// of `atmosphere.sun_irradiance`) as `colouring` says: SGSky's weights (13 model
    /// queries per painting) or every vertex from the model (49).
    pub fn new(model: M, atmosphere: &Atmosphere, colouring: DomeColouring) -> Result<Self> {
        atmosphere
            .validate()
            .map_err(|source| crate::CelestialError::Atmos {
                field: "atmosphere",
                source,
            })?;
        Ok(Self {
            model,
            atmosphere: atmosphere.clone(),
            colouring,
            painted: Mutex::new(None),
        })
    }

    /// The wrapped model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The colouring.
    pub fn colouring(&self) -> DomeColouring {
        self.colouring
    }

    /// The painting for a viewer at planet-centred `position` (m) lit along `sun` (unit):
    /// the last one if it was for the same viewer and sun, else a new one.
    pub fn painting(&self, position: DVec3, sun: DVec3) -> Result<PaintedSky> {
        let mut guard = self
            .painted
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(painted) = guard.as_ref().filter(|p| p.key == (position, sun)) {
            return Ok(painted.clone());
        }
        let painted = self.paint(position, sun)?;
        *guard = Some(painted.clone());
        Ok(painted)
    }

    /// The GPU pass's uniforms for a viewer at `position` lit along `sun`.
    pub fn uniforms(&self, position: DVec3, sun: DVec3) -> Result<SkyDomeUniforms> {
        let painted = self.painting(position, sun)?;
        Ok(SkyDomeUniforms::new(&painted.dome, &painted.aureole))
    }

    fn paint(&self, position: DVec3, sun: DVec3) -> Result<PaintedSky> {
        let [x, y, up] = dome_local_frame(position, sun);
        let local_sun = [sun.dot(x), sun.dot(y), sun.dot(up)];
        let builder = SkyObjectsBuilder::new(
            &self.atmosphere,
            &self.model,
            position.length() - self.atmosphere.planet_radius,
            local_sun,
            crate::sun::ASTRONOMICAL_UNIT_M,
            None,
            BackgroundSampling::PerObject,
        )?;
        let aureole = builder.aureole_towards(local_sun)?;
        let painted = SkyDome::paint(
            self.colouring,
            SKY_DOME_SPIN,
            |direction| Ok(builder.sky_exact(direction)?.radiance),
            |direction| aureole.radiance(direction.map(|c| c as f32)).map(f64::from),
        )?;
        Ok(PaintedSky {
            key: (position, sun),
            dome: painted.dome,
            aureole,
        })
    }
}

impl<M: SkyModel> SkyModel for SgskyDomeSky<M> {
    fn label(&self) -> String {
        let colouring = match self.colouring {
            DomeColouring::SeedWeights => "SGSky weights",
            DomeColouring::Model => "model per vertex",
        };
        format!(
            "SGSky dome ({colouring}) of {}",
            self.model.label().trim_end_matches(", per pixel")
        )
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        if query.max_distance().is_finite() {
            return self.model.evaluate(query);
        }
        let Ok(painted) = self.painting(query.position(), query.sun()) else {
            return self.model.evaluate(query);
        };
        let [x, y, up] = dome_local_frame(query.position(), query.sun());
        let view = query.view();
        let local = [view.dot(x), view.dot(y), view.dot(up)];
        let dome = painted.dome.radiance(local);
        let aureole = painted.aureole.radiance(local.map(|c| c as f32));
        SkySample {
            radiance: std::array::from_fn(|c| dome[c] + f64::from(aureole[c])),
            transmittance: painted.aureole.transmittance,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmos::closed_form_sky::ClosedFormSky;

    fn sky() -> (SgskyDomeSky<ClosedFormSky>, Atmosphere) {
        let atmosphere = Atmosphere::earth();
        let model = ClosedFormSky::new(&atmosphere).unwrap();
        (
            SgskyDomeSky::new(model, &atmosphere, DomeColouring::SeedWeights).unwrap(),
            atmosphere,
        )
    }

    /// The dome's zenith is the model's zenith less the aureole there, and its horizon
    /// toward the sun the model's horizon there (SGSky's weights put the fog colour on
    /// the outer ring), whatever frame the viewer is given in.
    #[test]
    fn the_dome_reproduces_the_model_at_its_vertices_in_any_frame() {
        let (dome, atmosphere) = sky();
        let r = atmosphere.planet_radius + 500.0;
        for (up, sun) in [
            (DVec3::Z, DVec3::new(0.6, 0.0, 0.8)),
            (DVec3::Y, DVec3::new(0.3, 0.2, -0.4).normalize()),
            (
                DVec3::new(1.0, 1.0, 1.0).normalize(),
                DVec3::new(0.2, -0.9, 0.4).normalize(),
            ),
        ] {
            let position = up * r;
            let [x, _, _] = dome_local_frame(position, sun);
            let zenith_query = SkyQuery::new(atmosphere.planet_radius, position, up, sun).unwrap();
            let sample = dome.evaluate(&zenith_query);
            let exact = dome.model().evaluate(&zenith_query);
            let painted = dome.painting(position, sun).unwrap();
            let aureole_at_zenith = painted.aureole.radiance([0.0, 0.0, 1.0]);
            for ((got, expected), aureole) in sample
                .radiance
                .iter()
                .zip(exact.radiance)
                .zip(aureole_at_zenith)
            {
                // The pixel adds the aureole back: the model's zenith (f32 aureole).
                assert!(
                    (got - expected).abs() <= 1e-6 * expected.max(1e-9),
                    "{got} vs {expected} (aureole {aureole})"
                );
            }
            let horizon = SkyQuery::new(atmosphere.planet_radius, position, x, sun).unwrap();
            let sample = dome.evaluate(&horizon);
            let exact = dome.model().evaluate(&horizon);
            for c in 0..3 {
                let expected = exact.radiance[c];
                assert!(
                    (sample.radiance[c] - expected).abs() <= 1e-6 * expected.max(1e-9),
                    "horizon {c}: {} vs {expected}",
                    sample.radiance[c]
                );
            }
            // Every sky ray carries the transmittance toward the sun: the aureole's
            // (atmos' optical depth), within 2 % of the model's where the sun is up
            // (the closed form's own transmittance is a fit), zero where it is set.
            assert_eq!(sample.transmittance, painted.aureole.transmittance);
            let toward_sun = dome
                .model()
                .evaluate(&SkyQuery::new(atmosphere.planet_radius, position, sun, sun).unwrap());
            for c in 0..3 {
                let (t, model) = (sample.transmittance[c], toward_sun.transmittance[c]);
                if sun.dot(up) > 0.0 {
                    assert!((t - model).abs() <= 0.02 * model, "{c}: {t} vs {model}");
                } else {
                    assert_eq!(t, 0.0);
                }
            }
        }
    }

    /// Finite segments are the model's; a painting is reused for the same viewer and
    /// sun and made again for another.
    #[test]
    fn segments_are_the_models_and_paintings_are_cached_per_viewer_and_sun() {
        let (dome, atmosphere) = sky();
        let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + 10.0);
        let sun = DVec3::new(0.0, 0.6, 0.8);
        let view = DVec3::new(0.8, 0.0, -0.6);
        let segment =
            SkyQuery::with_max_distance(atmosphere.planet_radius, position, view, sun, 2_000.0)
                .unwrap();
        assert_eq!(
            dome.evaluate(&segment).radiance,
            dome.model().evaluate(&segment).radiance
        );
        let first = dome.uniforms(position, sun).unwrap();
        assert_eq!(first, dome.uniforms(position, sun).unwrap());
        let lower = dome
            .uniforms(position, DVec3::new(0.0, 0.9, 0.1).normalize())
            .unwrap();
        assert_ne!(first.colours, lower.colours);
        assert!(
            first
                .colours
                .iter()
                .flatten()
                .all(|c| c.is_finite() && *c >= 0.0)
        );
    }

    #[test]
    fn uniforms_match_their_wgsl_layout() {
        let composer = crate::composer();
        let source = composer.compose_module("celestial::sky_dome_pass").unwrap();
        let parsed = skyscape_wgsl::validate("celestial::sky_dome_pass", &source).unwrap();
        skyscape_wgsl::rust_layout!(SkyDomeUniforms {
            colours,
            sun_irradiance,
            spin,
            sun_transmittance,
            mie_g,
            mie_optical_depth,
            padding
        })
        .check_twin_of(&skyscape_wgsl::struct_layout(&parsed, "SkyDomeUniforms").unwrap())
        .unwrap_or_else(|e| panic!("{e}"));
    }
}
