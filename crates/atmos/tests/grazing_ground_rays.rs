//! The convention for tangent and grazing rays at the ground (docs/architecture.md,
//! "Rays at the ground"): a ray that starts on the ground and points along or above the
//! tangent plane sees the sky; only a ray pointing strictly below it hits the ground.
//! Every rung must agree, at altitudes 0, 1 mm and 1 m and view elevations −0.01°, 0°
//! and +0.01° (at altitude exactly 0 and elevation exactly 0° a ground test that is not
//! strict returns radiance 0 and transmittance 1).

use atmos::closed_form_sky::ClosedFormSky;
use atmos::ladder::luminance;
use atmos::lut::LutSettings;
use atmos::lut::precomputed_sky::PrecomputedSky;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{Atmosphere, SkyModel, SkyQuery, SkySample};
use glam::DVec3;

const ALTITUDES: [f64; 3] = [0.0, 1e-3, 1.0];
const ELEVATIONS_DEG: [f64; 3] = [-0.01, 0.0, 0.01];

fn sample(model: &dyn SkyModel, altitude: f64, elevation_deg: f64) -> SkySample {
    let atmosphere = Atmosphere::earth();
    let e = elevation_deg.to_radians();
    // The sun 20° up and 30° off the view's azimuth: a lit horizon.
    let sun = DVec3::new(
        20f64.to_radians().cos() * 30f64.to_radians().cos(),
        20f64.to_radians().cos() * 30f64.to_radians().sin(),
        20f64.to_radians().sin(),
    );
    let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + altitude);
    let view = DVec3::new(e.cos(), 0.0, e.sin());
    model.evaluate(&SkyQuery::new(atmosphere.planet_radius, position, view, sun).unwrap())
}

/// For every (altitude, elevation) of the grid: a ray at or above the tangent plane is
/// a sky ray, as bright as the sky ray 1 m up at +0.01° (within `tolerance`, relative
/// luminance) and mostly extinguished along its path through the atmosphere; a ray
/// below the tangent plane from the ground (or 1 mm above it) hits the ground within a
/// few metres: no light, transmittance ≈ 1.
fn check_rung(name: &str, model: &dyn SkyModel, tolerance: f64) {
    let sky = sample(model, 1.0, 0.01);
    let sky_luminance = luminance(sky.radiance);
    assert!(
        sky_luminance > 0.0,
        "{name}: the reference sky ray is black"
    );
    for altitude in ALTITUDES {
        for elevation in ELEVATIONS_DEG {
            let s = sample(model, altitude, elevation);
            let lum = luminance(s.radiance);
            // From 1 m, −0.01° is above the geometric horizon (dip ≈ 0.032°): sky.
            let sees_sky = elevation >= 0.0 || altitude >= 1.0;
            if sees_sky {
                let error = (lum / sky_luminance - 1.0).abs();
                assert!(
                    error < tolerance && s.transmittance[2] < 0.5,
                    "{name}: altitude {altitude} m, elevation {elevation}° should see the sky: \
                     luminance {lum:e} vs {sky_luminance:e} ({error:.3} off), \
                     transmittance {:?}",
                    s.transmittance
                );
            } else {
                assert!(
                    lum < 1e-3 * sky_luminance && s.transmittance.iter().all(|&t| t > 0.999),
                    "{name}: altitude {altitude} m, elevation {elevation}° should hit the \
                     ground at once: luminance {lum:e}, transmittance {:?}",
                    s.transmittance
                );
            }
        }
    }
}

// Tolerances: the sky rays of the grid differ from the 1 m, +0.01° ray by ≤ 1 m of
// altitude and ≤ 0.02° of elevation; the closed form and single scattering vary
// smoothly there (a few per mille); the precomputed rung reads a sky-view table whose
// rows at the horizon are split by the horizon's own zenith angle, so it is given 5 %.

#[test]
fn closed_form_sees_the_sky_along_the_tangent_plane() {
    let model = ClosedFormSky::new(&Atmosphere::earth()).unwrap();
    check_rung("closed form", &model, 0.01);
}

#[test]
fn single_scattering_sees_the_sky_along_the_tangent_plane() {
    let model = SingleScatteringSky::new(
        &Atmosphere::earth(),
        SingleScatteringSettings {
            view_samples: 64,
            light_samples: 16,
        },
    )
    .unwrap();
    check_rung("single scattering", &model, 0.01);
}

#[test]
fn precomputed_sees_the_sky_along_the_tangent_plane() {
    let model = PrecomputedSky::new(&Atmosphere::earth(), &LutSettings::small()).unwrap();
    check_rung("precomputed", &model, 0.05);
}
