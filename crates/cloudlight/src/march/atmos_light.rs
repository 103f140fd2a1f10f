//! The sun and the sky from `atmos`, and the air in front of the cloud.

use atmos::{Atmosphere, SkyModel, SkyQuery};
use glam::DVec3;

use super::*;

/// Sun irradiance and ambient sky radiance at a point of a planet's atmosphere, from
/// `atmos` ([`atmos_light`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmosLight {
    /// The sun's irradiance on a surface facing it at the point: `sun_irradiance` times
    /// the model's transmittance toward the sun; zero behind the planet.
    pub sun_irradiance: [f64; 3],
    /// The uniform sky radiance with the sky's irradiance on a horizontal surface at the
    /// point (`atmos` [`ground_irradiance`](atmos::ground_irradiance::ground_irradiance)`.sky / π`).
    pub ambient_radiance: [f64; 3],
}

/// The sun light and the ambient sky at `point` (planet-centred, metres) with the sun
/// along unit `sun` (planet-centred frame), from any `atmos` [`SkyModel`] of
/// `atmosphere`: `quadrature` is the hemisphere integral of the sky irradiance. Build a
/// [`Lighting`] from it with the sun and up directions expressed in the field's frame.
pub fn atmos_light(
    model: &impl SkyModel,
    atmosphere: &Atmosphere,
    point: DVec3,
    sun: DVec3,
    quadrature: atmos::ground_irradiance::HemisphereQuadrature,
) -> Result<AtmosLight, MarchError> {
    let irradiance =
        atmos::ground_irradiance::ground_irradiance(model, atmosphere, point, sun, quadrature)?;
    let query = SkyQuery::new(atmosphere.planet_radius, point, sun, sun)?;
    let r = query.r().max(atmosphere.planet_radius);
    let mu_s = query.mu_s();
    let behind_planet = mu_s < 0.0
        && atmos::reference::ray_sphere_intersect(r, mu_s, atmosphere.planet_radius)[1] > 0.0;
    let sun_irradiance = if behind_planet {
        [0.0; 3]
    } else {
        let t = model.evaluate(&query).transmittance;
        std::array::from_fn(|k| t[k] * atmosphere.sun_irradiance[k])
    };
    Ok(AtmosLight {
        sun_irradiance,
        ambient_radiance: irradiance.sky.map(|e| e / std::f64::consts::PI),
    })
}

/// The cloud seen through the air in front of it: `cloud.radiance · T_air + L_air ·
/// (1 − cloud.transmittance)`, where `(L_air, T_air)` are `model`'s in-scattered radiance
/// and transmittance from `camera` (planet-centred, m) along unit `view` to the cloud's
/// [`depth`](MarchResult::depth), sun along unit `sun`. The air's own light in front of
/// the cloud replaces, in proportion to the cloud's opacity, what the sky behind would
/// have added (the sky behind is composited by the caller with `cloud.transmittance`).
pub fn apply_aerial_perspective(
    model: &impl SkyModel,
    atmosphere: &Atmosphere,
    camera: DVec3,
    view: DVec3,
    sun: DVec3,
    cloud: &MarchResult<f64>,
) -> Result<[f64; 3], MarchError> {
    let query =
        SkyQuery::with_max_distance(atmosphere.planet_radius, camera, view, sun, cloud.depth)?;
    let air = model.evaluate(&query);
    let opacity = 1.0 - cloud.transmittance;
    Ok(std::array::from_fn(|k| {
        cloud.radiance[k] * air.transmittance[k] + air.radiance[k] * opacity
    }))
}
