//! The sky with seed 000's closed-form model: scene description, per-frame uniforms,
//! and the per-pixel CPU twin of `shaders/render/sky_closed_form.wgsl`.

use crate::error::{RenderError, check};
use crate::tonemap::{pack_rgba8, quantize_srgb8, tonemap_exposure};
use atmos::closed_form::closed_form_extinction;
use atmos::closed_form_sky::{
    ClosedFormSkyParameters, closed_form_sky_radiance, closed_form_sky_transmittance,
    closed_form_sunlight,
};
use atmos::frame::UNLIMITED_DISTANCE;
use atmos::geometry::ray_sphere_intersect;
use glam::Vec3;
use skyscape_wgsl::common::INV_PI;

/// Physical parameters of the closed-form (homogeneous) atmosphere.
///
/// The closed form assumes constant density. skyscape maps Earth's exponential layers
/// onto one homogeneous shell of thickness `rayleigh_scale_height` above the ground,
/// with the Mie coefficient scaled by `mie_scale_height / rayleigh_scale_height`, so
/// that both constituents keep their true vertical optical depth.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormAtmosphere {
    /// Planet radius (m).
    pub planet_radius: f32,
    /// Rayleigh scattering at sea level per channel (1/m).
    pub rayleigh_scattering: [f32; 3],
    /// Rayleigh scale height (m); also the thickness of the homogeneous shell.
    pub rayleigh_scale_height: f32,
    /// Mie scattering at sea level (1/m), grey.
    pub mie_scattering: f32,
    /// Mie scale height (m).
    pub mie_scale_height: f32,
    /// Mie (Henyey–Greenstein) anisotropy, |g| < 1.
    pub mie_g: f32,
    /// Lambertian ground albedo in [0, 1].
    pub ground_albedo: f32,
    /// Sun irradiance above the atmosphere per channel (any unit; the image is in it).
    pub sun_irradiance: [f32; 3],
    /// Angular radius of the sun disc (rad).
    pub sun_angular_radius: f32,
}

impl Default for ClosedFormAtmosphere {
    fn default() -> Self {
        Self {
            planet_radius: 6_360_000.0,
            rayleigh_scattering: [5.802e-6, 13.558e-6, 33.1e-6],
            rayleigh_scale_height: 8_000.0,
            mie_scattering: 3.996e-6,
            mie_scale_height: 1_200.0,
            mie_g: 0.8,
            ground_albedo: 0.1,
            sun_irradiance: [1.0; 3],
            sun_angular_radius: 0.004_675,
        }
    }
}

/// A camera and a sun over the closed-form atmosphere.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyScene {
    /// Image width in pixels (1…16384).
    pub width: u32,
    /// Image height in pixels (1…16384).
    pub height: u32,
    /// Camera altitude above the ground (m, ≥ 0).
    pub camera_altitude: f32,
    /// View azimuth (rad), from north (−z) towards east (+x).
    pub camera_azimuth: f32,
    /// View elevation (rad), in (−π/2, π/2).
    pub camera_elevation: f32,
    /// Vertical field of view (rad), in (0, 3].
    pub vertical_fov: f32,
    /// Sun elevation above the horizon (rad), in [−π/2, π/2].
    pub sun_elevation: f32,
    /// Sun azimuth (rad), from north towards east.
    pub sun_azimuth: f32,
    /// Exposure multiplying radiance before the tone map (> 0).
    pub exposure: f32,
    /// Seed of the dither pattern.
    pub dither_seed: u32,
    /// The atmosphere.
    pub atmosphere: ClosedFormAtmosphere,
}

impl Default for SkyScene {
    /// A clear afternoon seen from 2 m above the ground, looking 35° to the side of the
    /// sun: blue zenith, bright horizon haze, the sun and its glow in frame.
    fn default() -> Self {
        Self {
            width: 960,
            height: 540,
            camera_altitude: 2.0,
            camera_azimuth: 0.0,
            camera_elevation: 0.35,
            vertical_fov: 1.4,
            sun_elevation: 0.35,
            sun_azimuth: 0.6,
            exposure: 20.0,
            dither_seed: 0,
            atmosphere: ClosedFormAtmosphere::default(),
        }
    }
}

/// Unit direction from an elevation and an azimuth (from north −z towards east +x).
pub fn direction_from_angles(elevation: f32, azimuth: f32) -> Vec3 {
    let (sin_e, cos_e) = elevation.sin_cos();
    let (sin_a, cos_a) = azimuth.sin_cos();
    Vec3::new(cos_e * sin_a, sin_e, -cos_e * cos_a)
}

impl SkyScene {
    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), RenderError> {
        let size_ok = |v: u32| (1..=16_384).contains(&v);
        if !size_ok(self.width) {
            return Err(RenderError::InvalidParameter {
                field: "width",
                value: self.width.to_string(),
                reason: "must be in 1..=16384 pixels",
            });
        }
        if !size_ok(self.height) {
            return Err(RenderError::InvalidParameter {
                field: "height",
                value: self.height.to_string(),
                reason: "must be in 1..=16384 pixels",
            });
        }
        let half_pi = std::f32::consts::FRAC_PI_2;
        check(
            "camera_altitude",
            self.camera_altitude,
            self.camera_altitude >= 0.0,
            "must be ≥ 0 m",
        )?;
        check(
            "camera_azimuth",
            self.camera_azimuth,
            true,
            "must be finite",
        )?;
        check(
            "camera_elevation",
            self.camera_elevation,
            self.camera_elevation.abs() < half_pi,
            "must be in (−π/2, π/2) rad",
        )?;
        check(
            "vertical_fov",
            self.vertical_fov,
            self.vertical_fov > 0.0 && self.vertical_fov <= 3.0,
            "must be in (0, 3] rad",
        )?;
        check(
            "sun_elevation",
            self.sun_elevation,
            self.sun_elevation.abs() <= half_pi,
            "must be in [−π/2, π/2] rad",
        )?;
        check("sun_azimuth", self.sun_azimuth, true, "must be finite")?;
        check(
            "exposure",
            self.exposure,
            self.exposure > 0.0,
            "must be > 0",
        )?;
        let a = &self.atmosphere;
        check(
            "atmosphere.planet_radius",
            a.planet_radius,
            a.planet_radius > 0.0,
            "must be > 0 m",
        )?;
        for &beta in &a.rayleigh_scattering {
            check(
                "atmosphere.rayleigh_scattering",
                beta,
                beta >= 0.0,
                "must be ≥ 0 per metre",
            )?;
        }
        check(
            "atmosphere.rayleigh_scale_height",
            a.rayleigh_scale_height,
            a.rayleigh_scale_height > 0.0,
            "must be > 0 m",
        )?;
        check(
            "atmosphere.mie_scattering",
            a.mie_scattering,
            a.mie_scattering >= 0.0,
            "must be ≥ 0 per metre",
        )?;
        check(
            "atmosphere.mie_scale_height",
            a.mie_scale_height,
            a.mie_scale_height > 0.0,
            "must be > 0 m",
        )?;
        check(
            "atmosphere.mie_g",
            a.mie_g,
            a.mie_g.abs() < 1.0,
            "|g| must be < 1",
        )?;
        check(
            "atmosphere.ground_albedo",
            a.ground_albedo,
            (0.0..=1.0).contains(&a.ground_albedo),
            "must be in [0, 1]",
        )?;
        for &e in &a.sun_irradiance {
            check("atmosphere.sun_irradiance", e, e >= 0.0, "must be ≥ 0")?;
        }
        check(
            "atmosphere.sun_angular_radius",
            a.sun_angular_radius,
            a.sun_angular_radius > 0.0 && a.sun_angular_radius < 0.5,
            "must be in (0, 0.5) rad",
        )?;
        Ok(())
    }
}

/// Per-frame constants of the sky pass; layout identical to WGSL `SkyUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SkyUniforms {
    /// xyz right, w tan(horizontal half fov).
    pub camera_right: [f32; 4],
    /// xyz up, w tan(vertical half fov).
    pub camera_up: [f32; 4],
    /// xyz forward, w camera distance from the planet centre (m).
    pub camera_forward: [f32; 4],
    /// xyz towards the sun, w cos(sun angular radius).
    pub sun_direction: [f32; 4],
    /// xyz Rayleigh scattering (1/m), w Mie g.
    pub beta_rayleigh: [f32; 4],
    /// xyz homogeneous-equivalent Mie scattering (1/m), w planet radius (m).
    pub beta_mie: [f32; 4],
    /// xyz sun irradiance at the camera, w homogeneous shell top radius (m).
    pub sun_irradiance_at_camera: [f32; 4],
    /// xyz sun disc radiance above the atmosphere, w ground albedo.
    pub sun_disc_radiance: [f32; 4],
    /// xyz sunlight driving in-scatter (irradiance × column-averaged transmittance).
    pub sunlight_in_scatter: [f32; 4],
    /// x exposure.
    pub display: [f32; 4],
    /// x width, y height, z dither seed.
    pub image: [u32; 4],
}

impl SkyUniforms {
    /// Validates the scene and derives the per-frame constants (the `prepare` step,
    /// done once per frame on the CPU for both the CPU and GPU paths).
    pub fn from_scene(scene: &SkyScene) -> Result<Self, RenderError> {
        scene.validate()?;
        let a = &scene.atmosphere;
        let forward = direction_from_angles(scene.camera_elevation, scene.camera_azimuth);
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        let tan_half_v = (0.5 * scene.vertical_fov).tan();
        let tan_half_h = tan_half_v * scene.width as f32 / scene.height as f32;
        let sun = direction_from_angles(scene.sun_elevation, scene.sun_azimuth);
        let r = a.planet_radius + scene.camera_altitude;
        let shell_radius = a.planet_radius + a.rayleigh_scale_height;
        let beta_rayleigh = a.rayleigh_scattering;
        let beta_mie = [a.mie_scattering * a.mie_scale_height / a.rayleigh_scale_height; 3];
        // Sunlight reaching the camera: blocked by the planet, else attenuated along
        // the sun path through the shell (the closed form evaluates it once, here).
        let sun_ground = ray_sphere_intersect(r, sun.y, a.planet_radius);
        let sun_path = if sun_ground[0] >= 0.0 {
            None
        } else {
            let sun_shell = ray_sphere_intersect(r, sun.y, shell_radius);
            Some((sun_shell[1] - sun_shell[0].max(0.0)).max(0.0))
        };
        let sun_transmittance = sun_path.map_or([0.0; 3], |path| {
            closed_form_extinction(beta_rayleigh, beta_mie, path)
        });
        let sun_at_camera: [f32; 3] =
            std::array::from_fn(|i| a.sun_irradiance[i] * sun_transmittance[i]);
        // In-scatter happens all along the view path, mostly above the camera where
        // the sun is less attenuated; the closed form needs one value: atmos's
        // column-averaged sunlight, E·(1 − e^{−τs})/τs (0 when the planet hides the sun).
        let shell = ClosedFormSkyParameters {
            beta_rayleigh,
            mie_g: a.mie_g,
            beta_mie,
            planet_radius: a.planet_radius,
            sun_irradiance: a.sun_irradiance,
            shell_radius,
        };
        let sunlight_in_scatter = closed_form_sunlight(r, sun.y, &shell);
        let disc_solid_angle = std::f32::consts::PI * a.sun_angular_radius * a.sun_angular_radius;
        let disc = a.sun_irradiance.map(|e| e / disc_solid_angle);
        Ok(Self {
            camera_right: [right.x, right.y, right.z, tan_half_h],
            camera_up: [up.x, up.y, up.z, tan_half_v],
            camera_forward: [forward.x, forward.y, forward.z, r],
            sun_direction: [sun.x, sun.y, sun.z, a.sun_angular_radius.cos()],
            beta_rayleigh: [
                beta_rayleigh[0],
                beta_rayleigh[1],
                beta_rayleigh[2],
                a.mie_g,
            ],
            beta_mie: [beta_mie[0], beta_mie[1], beta_mie[2], a.planet_radius],
            sun_irradiance_at_camera: [
                sun_at_camera[0],
                sun_at_camera[1],
                sun_at_camera[2],
                shell_radius,
            ],
            sun_disc_radiance: [disc[0], disc[1], disc[2], a.ground_albedo],
            sunlight_in_scatter: [
                sunlight_in_scatter[0],
                sunlight_in_scatter[1],
                sunlight_in_scatter[2],
                0.0,
            ],
            display: [scene.exposure, 0.0, 0.0, 0.0],
            image: [scene.width, scene.height, scene.dither_seed, 0],
        })
    }
}

fn xyz(v: [f32; 4]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

fn scale(a: [f32; 3], s: f32) -> [f32; 3] {
    a.map(|x| x * s)
}

fn mul(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|i| a[i] * b[i])
}

fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    std::array::from_fn(|i| a[i] + b[i])
}

/// The homogeneous shell of `atmos::closed_form_sky` held in the uniforms.
fn shell_parameters(uniforms: &SkyUniforms) -> ClosedFormSkyParameters {
    ClosedFormSkyParameters {
        beta_rayleigh: [
            uniforms.beta_rayleigh[0],
            uniforms.beta_rayleigh[1],
            uniforms.beta_rayleigh[2],
        ],
        mie_g: uniforms.beta_rayleigh[3],
        beta_mie: [
            uniforms.beta_mie[0],
            uniforms.beta_mie[1],
            uniforms.beta_mie[2],
        ],
        planet_radius: uniforms.beta_mie[3],
        sun_irradiance: [
            uniforms.sun_irradiance_at_camera[0],
            uniforms.sun_irradiance_at_camera[1],
            uniforms.sun_irradiance_at_camera[2],
        ],
        shell_radius: uniforms.sun_irradiance_at_camera[3],
    }
}

/// Unit view direction through the centre of `pixel` (y down). Twin of the WGSL.
pub fn sky_view_direction(pixel: [u32; 2], uniforms: &SkyUniforms) -> Vec3 {
    let ndc_x = (pixel[0] as f32 + 0.5) / uniforms.image[0] as f32 * 2.0 - 1.0;
    let ndc_y = (pixel[1] as f32 + 0.5) / uniforms.image[1] as f32 * 2.0 - 1.0;
    let direction = xyz(uniforms.camera_forward)
        + ndc_x * uniforms.camera_right[3] * xyz(uniforms.camera_right)
        - ndc_y * uniforms.camera_up[3] * xyz(uniforms.camera_up);
    direction.normalize()
}

/// Radiance arriving from `view_direction` (in-scatter + lit ground or sun disc,
/// attenuated). Twin of `shade_sky_pixel` in WGSL.
pub fn shade_sky_pixel(view_direction: Vec3, uniforms: &SkyUniforms) -> [f32; 3] {
    let r = uniforms.camera_forward[3];
    let mu = view_direction.y;
    let planet_radius = uniforms.beta_mie[3];
    // The shell, coefficients and path are atmos's rung 1 (closed_form_sky); this pass
    // only adds the lit ground or the sun disc behind the path.
    let params = shell_parameters(uniforms);
    let hits_ground = ray_sphere_intersect(r, mu, planet_radius)[0] >= 0.0;
    let sun = xyz(uniforms.sun_direction);
    let cos_theta = view_direction.dot(sun);
    let sunlight = [
        uniforms.sun_irradiance_at_camera[0],
        uniforms.sun_irradiance_at_camera[1],
        uniforms.sun_irradiance_at_camera[2],
    ];
    let in_scatter_light = [
        uniforms.sunlight_in_scatter[0],
        uniforms.sunlight_in_scatter[1],
        uniforms.sunlight_in_scatter[2],
    ];
    let mut radiance = closed_form_sky_radiance(
        r,
        mu,
        cos_theta,
        UNLIMITED_DISTANCE,
        in_scatter_light,
        &params,
    );
    let extinction = closed_form_sky_transmittance(r, mu, UNLIMITED_DISTANCE, &params);
    if hits_ground {
        let cos_sun_zenith = uniforms.sun_direction[1].max(0.0);
        let lit = scale(
            sunlight,
            uniforms.sun_disc_radiance[3] * INV_PI * cos_sun_zenith,
        );
        radiance = add(radiance, mul(extinction, lit));
    } else if cos_theta >= uniforms.sun_direction[3] {
        let disc = [
            uniforms.sun_disc_radiance[0],
            uniforms.sun_disc_radiance[1],
            uniforms.sun_disc_radiance[2],
        ];
        radiance = add(radiance, mul(extinction, disc));
    }
    radiance
}

/// Linear radiance of every pixel, row-major (for analysis; not tone-mapped).
pub fn render_sky_radiance_cpu(scene: &SkyScene) -> Result<Vec<[f32; 3]>, RenderError> {
    let uniforms = SkyUniforms::from_scene(scene)?;
    Ok(per_pixel(&uniforms, |pixel| {
        shade_sky_pixel(sky_view_direction(pixel, &uniforms), &uniforms)
    }))
}

/// The tone-mapped, dithered RGBA8 image on the CPU (the GPU pass's twin),
/// row-major, R in the low byte of each `u32`. Uses every core.
pub fn render_sky_cpu(scene: &SkyScene) -> Result<Vec<u32>, RenderError> {
    let uniforms = SkyUniforms::from_scene(scene)?;
    Ok(per_pixel(&uniforms, |pixel| {
        let radiance = shade_sky_pixel(sky_view_direction(pixel, &uniforms), &uniforms);
        let display = tonemap_exposure(radiance, uniforms.display[0]);
        pack_rgba8(quantize_srgb8(display, pixel, uniforms.image[2]))
    }))
}

fn per_pixel<T: Send + Copy + Default>(
    uniforms: &SkyUniforms,
    shade: impl Fn([u32; 2]) -> T + Sync,
) -> Vec<T> {
    let (width, height) = (uniforms.image[0] as usize, uniforms.image[1] as usize);
    let mut out = vec![T::default(); width * height];
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let rows_per_chunk = height.div_ceil(threads).max(1);
    std::thread::scope(|scope| {
        for (chunk_index, chunk) in out.chunks_mut(rows_per_chunk * width).enumerate() {
            let shade = &shade;
            scope.spawn(move || {
                for (i, value) in chunk.iter_mut().enumerate() {
                    let row = chunk_index * rows_per_chunk + i / width;
                    *value = shade([(i % width) as u32, row as u32]);
                }
            });
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn luminance(c: [f32; 3]) -> f32 {
        0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    }

    fn uniforms() -> SkyUniforms {
        SkyUniforms::from_scene(&SkyScene::default()).unwrap()
    }

    #[test]
    fn zenith_is_blue_and_horizon_is_brighter() {
        let u = uniforms();
        let zenith = shade_sky_pixel(Vec3::Y, &u);
        assert!(zenith[2] > zenith[1] && zenith[1] > zenith[0], "{zenith:?}");
        // Horizon away from the sun (opposite azimuth), 1° up.
        let sun = xyz(u.sun_direction);
        let away = Vec3::new(-sun.x, 0.0, -sun.z).normalize();
        let horizon = shade_sky_pixel((away + Vec3::Y * 0.017).normalize(), &u);
        assert!(
            luminance(horizon) > 1.5 * luminance(zenith),
            "{horizon:?} vs {zenith:?}"
        );
    }

    #[test]
    fn sun_glow_brightens_towards_the_sun() {
        let u = uniforms();
        let sun = xyz(u.sun_direction);
        let near_sun = shade_sky_pixel((sun + Vec3::X * 0.05).normalize(), &u);
        let far = shade_sky_pixel((sun + Vec3::X * 1.0).normalize(), &u);
        assert!(luminance(near_sun) > 1.2 * luminance(far));
        let disc = shade_sky_pixel(sun, &u);
        assert!(luminance(disc) > 100.0 * luminance(near_sun));
    }

    #[test]
    fn bad_input_names_the_field() {
        let mut scene = SkyScene::default();
        scene.atmosphere.mie_g = 1.0;
        let err = SkyUniforms::from_scene(&scene).unwrap_err();
        assert!(err.to_string().contains("atmosphere.mie_g"), "{err}");
        let scene = SkyScene {
            exposure: f32::NAN,
            ..SkyScene::default()
        };
        assert!(matches!(
            SkyUniforms::from_scene(&scene),
            Err(RenderError::InvalidParameter {
                field: "exposure",
                ..
            })
        ));
        let scene = SkyScene {
            width: 0,
            ..SkyScene::default()
        };
        assert!(matches!(
            SkyUniforms::from_scene(&scene),
            Err(RenderError::InvalidParameter { field: "width", .. })
        ));
    }

    #[test]
    fn no_nan_anywhere_over_extreme_scenes() {
        use std::f32::consts::FRAC_PI_2;
        for altitude in [0.0, 1.0, 7_999.0, 8_000.0, 8_001.0, 1e5, 1e7] {
            for sun_elevation in [-FRAC_PI_2, -0.1, 0.0, 0.02, FRAC_PI_2] {
                let scene = SkyScene {
                    width: 48,
                    height: 27,
                    camera_altitude: altitude,
                    sun_elevation,
                    camera_elevation: -0.5,
                    vertical_fov: 3.0,
                    ..SkyScene::default()
                };
                for c in render_sky_radiance_cpu(&scene).unwrap() {
                    assert!(
                        c.iter().all(|v| v.is_finite() && *v >= 0.0),
                        "{altitude} {sun_elevation}: {c:?}"
                    );
                }
            }
        }
    }
}

/// Seed 000's observations, as tests of the closed-form sky.
#[cfg(test)]
mod seed_000_observations {
    use super::*;

    fn sky(sun_elevation: f32, mie_scattering: f32) -> SkyUniforms {
        SkyUniforms::from_scene(&SkyScene {
            sun_elevation,
            atmosphere: ClosedFormAtmosphere {
                mie_scattering,
                ..ClosedFormAtmosphere::default()
            },
            ..SkyScene::default()
        })
        .unwrap()
    }

    /// Chroma relative to brightness: (max − min)/max of the channels.
    fn saturation(c: [f32; 3]) -> f32 {
        let max = c.iter().copied().fold(0.0, f32::max);
        let min = c.iter().copied().fold(f32::INFINITY, f32::min);
        (max - min) / max
    }

    #[test]
    fn clear_blue_sky_without_mie() {
        let u = sky(std::f32::consts::FRAC_PI_2 - 0.01, 0.0);
        let zenith = shade_sky_pixel(Vec3::Y, &u);
        assert!(zenith[2] > zenith[1] && zenith[1] > zenith[0], "{zenith:?}");
    }

    #[test]
    fn strong_mie_with_high_sun_is_hazy() {
        // 30° from a high sun, with 25× Earth's haze: brighter and much less
        // saturated than the clear sky in the same direction.
        let clear = sky(1.3, 3.996e-6);
        let hazy = sky(1.3, 1e-4);
        let direction = direction_from_angles(1.3 - 0.52, 0.6);
        let (c, h) = (
            shade_sky_pixel(direction, &clear),
            shade_sky_pixel(direction, &hazy),
        );
        assert!(
            saturation(h) < 0.6 * saturation(c),
            "hazy {h:?} vs clear {c:?}"
        );
        assert!(h.iter().sum::<f32>() > c.iter().sum::<f32>());
    }

    #[test]
    fn low_sun_turns_the_sky_towards_it_yellow_orange() {
        let u = sky(0.03, 3.996e-6);
        let towards_sun = direction_from_angles(0.05, 0.6);
        let c = shade_sky_pixel(towards_sun, &u);
        assert!(c[0] > c[1] && c[1] > c[2], "towards a low sun: {c:?}");
        // …while at noon the same elevation and azimuth is not.
        let noon = shade_sky_pixel(towards_sun, &sky(1.2, 3.996e-6));
        assert!(noon[2] > noon[0], "{noon:?}");
    }
}
