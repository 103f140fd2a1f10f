//! Hoffman and Preetham 2002's terrain shading, composed: the surface term `(N·L) · albedo ·
//! self_shadow · cloud_shadow` is `terrain::shadow::terrain_shading` (the same
//! function the WGSL twin mirrors), lit by the sun through the atmosphere's
//! transmittance and by the sky's irradiance from `atmos::ground_irradiance`. What
//! lives here is only what a scene adds: the albedo ramp and the sum of the two lights.

use glam::Vec3;

use crate::scene::AlbedoSection;

/// Albedo by elevation (piecewise linear between stops) and slope (a steep-rock
/// colour blended in over the 10° below `steep_slope`).
#[derive(Debug, Clone, PartialEq)]
pub struct AlbedoRamp {
    heights: Vec<f32>,
    colors: Vec<Vec3>,
    steep_color: Vec3,
    /// cos(steep_slope): normals whose up component is below this are rock.
    cos_steep: f32,
    /// cos(steep_slope − 10°): above this, no rock.
    cos_gentle: f32,
}

/// The width of the slope blend, degrees.
const SLOPE_BLEND_DEG: f64 = 10.0;

/// The most stops a ramp may have (the GPU's uniform holds this many).
pub const MAX_ALBEDO_STOPS: usize = 8;

/// The ramp as the GPU's uniform (layout identical to WGSL `AlbedoRamp` in
/// `shaders/render/terrain_shading.wgsl`): heights packed four to a vec4.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct AlbedoRampUniform {
    /// Stop elevations (m), `heights[k / 4][k % 4]`.
    pub heights: [[f32; 4]; 2],
    /// Stop colours (rgb, 0).
    pub colors: [[f32; 4]; MAX_ALBEDO_STOPS],
    /// Rock colour.
    pub steep_color: [f32; 3],
    /// Number of stops (1..=8).
    pub stop_count: u32,
    /// cos(steep slope).
    pub cos_steep: f32,
    /// cos(steep slope − 10°).
    pub cos_gentle: f32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding: [f32; 2],
}

impl AlbedoRamp {
    /// Checks and converts `[terrain.albedo]`; the error is (key, value as typed, rule).
    pub fn new(section: &AlbedoSection) -> Result<Self, (&'static str, String, String)> {
        if section.heights.len() > MAX_ALBEDO_STOPS {
            return Err((
                "heights",
                format!("{} stops", section.heights.len()),
                format!("at most {MAX_ALBEDO_STOPS} stops"),
            ));
        }
        if section.heights.is_empty() || section.heights.len() != section.colors.len() {
            return Err((
                "colors",
                format!(
                    "{} colours for {} heights",
                    section.colors.len(),
                    section.heights.len()
                ),
                "needs one colour per height, at least one".into(),
            ));
        }
        for pair in section.heights.windows(2) {
            if pair[1].is_nan() || pair[1] <= pair[0] {
                return Err((
                    "heights",
                    format!("{} m after {} m", pair[1], pair[0]),
                    "must increase strictly".into(),
                ));
            }
        }
        if let Some(h) = section.heights.iter().find(|h| !h.is_finite()) {
            return Err(("heights", format!("{h} m"), "must be finite".into()));
        }
        let unit = |c: &[f64; 3]| c.iter().all(|v| (0.0..=1.0).contains(v));
        if let Some(c) = section.colors.iter().find(|c| !unit(c)) {
            return Err((
                "colors",
                format!("{c:?}"),
                "each channel must be an albedo in [0, 1]".into(),
            ));
        }
        if !unit(&section.steep_color) {
            return Err((
                "steep_color",
                format!("{:?}", section.steep_color),
                "each channel must be an albedo in [0, 1]".into(),
            ));
        }
        let slope = section.steep_slope_deg;
        if !(slope > SLOPE_BLEND_DEG && slope <= 90.0) {
            return Err((
                "steep_slope_deg",
                format!("{slope}°"),
                format!("must be in ({SLOPE_BLEND_DEG}°, 90°]"),
            ));
        }
        let colour = |c: &[f64; 3]| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32);
        Ok(Self {
            heights: section.heights.iter().map(|&h| h as f32).collect(),
            colors: section.colors.iter().map(colour).collect(),
            steep_color: colour(&section.steep_color),
            cos_steep: slope.to_radians().cos() as f32,
            cos_gentle: (slope - SLOPE_BLEND_DEG).to_radians().cos() as f32,
        })
    }

    /// The GPU uniform of this ramp.
    pub fn uniform(&self) -> AlbedoRampUniform {
        let mut uniform = AlbedoRampUniform {
            heights: [[0.0; 4]; 2],
            colors: [[0.0; 4]; MAX_ALBEDO_STOPS],
            steep_color: self.steep_color.to_array(),
            stop_count: self.heights.len() as u32,
            cos_steep: self.cos_steep,
            cos_gentle: self.cos_gentle,
            padding: [0.0; 2],
        };
        for (k, (&h, c)) in self.heights.iter().zip(&self.colors).enumerate() {
            uniform.heights[k / 4][k % 4] = h;
            uniform.colors[k] = [c.x, c.y, c.z, 0.0];
        }
        uniform
    }

    /// Albedo at `elevation` (m) on a surface whose unit normal has up component `up`.
    /// Twin of WGSL `terrain_albedo`.
    pub fn albedo(&self, elevation: f32, up: f32) -> Vec3 {
        let n = self.heights.len();
        let by_height = if elevation <= self.heights[0] {
            self.colors[0]
        } else if elevation >= self.heights[n - 1] {
            self.colors[n - 1]
        } else {
            let k = self.heights.partition_point(|&h| h <= elevation) - 1;
            let t = (elevation - self.heights[k]) / (self.heights[k + 1] - self.heights[k]);
            self.colors[k].lerp(self.colors[k + 1], t)
        };
        let rock = ((self.cos_gentle - up) / (self.cos_gentle - self.cos_steep)).clamp(0.0, 1.0);
        by_height.lerp(self.steep_color, rock)
    }
}

/// Outgoing radiance of a Lambertian terrain point (unit of the sun irradiance, per
/// steradian): `[terrain_shading(N, L, albedo, self_shadow, cloud_shadow) · E_sun ·
/// T_sun + albedo · E_sky · (1 + N·up)/2] / π`.
///
/// * `sun_irradiance_at_point`: the sun's irradiance above the atmosphere times its
///   transmittance to the point (`atmos`), per channel;
/// * `sky_irradiance`: `atmos::ground_irradiance`'s sky term on a horizontal surface;
///   a surface tilted by `θ` sees the fraction `(1 + cos θ)/2` of an isotropic sky
///   (the view factor of a tilted plane to the upper hemisphere) — the sky's
///   anisotropy and the terrain's occlusion of it are not modelled;
/// * `normal`, `sun`: unit, one frame; `up` is `normal`'s up component;
/// * `cloud_shadow`: the sun's transmittance through the clouds above the point (1: none).
///
/// Twin of WGSL `surface_radiance` (`shaders/render/terrain_shading.wgsl`).
#[allow(clippy::too_many_arguments)] // mirrors the WGSL signature
pub fn surface_radiance(
    normal: Vec3,
    up: f32,
    sun: Vec3,
    albedo: Vec3,
    self_shadow: f32,
    cloud_shadow: f32,
    sun_irradiance_at_point: Vec3,
    sky_irradiance: Vec3,
) -> Vec3 {
    let direct = terrain::shadow::terrain_shading(normal, sun, albedo, self_shadow, cloud_shadow)
        * sun_irradiance_at_point;
    let ambient = albedo * sky_irradiance * (0.5 * (1.0 + up));
    (direct + ambient) * std::f32::consts::FRAC_1_PI
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_interpolates_by_height_and_turns_to_rock_on_steep_slopes() {
        let ramp = AlbedoRamp::new(&AlbedoSection {
            heights: vec![0.0, 100.0],
            colors: vec![[0.0; 3], [1.0; 3]],
            steep_color: [0.5, 0.0, 0.0],
            steep_slope_deg: 40.0,
        })
        .unwrap();
        assert_eq!(ramp.albedo(-5.0, 1.0), Vec3::ZERO);
        assert!((ramp.albedo(25.0, 1.0) - Vec3::splat(0.25)).length() < 1e-6);
        assert_eq!(ramp.albedo(500.0, 1.0), Vec3::ONE);
        // Slope 45° > 40°: all rock; 20° < 30°: none.
        let steep = 45f32.to_radians().cos();
        assert_eq!(ramp.albedo(50.0, steep), Vec3::new(0.5, 0.0, 0.0));
        let gentle = 20f32.to_radians().cos();
        assert!((ramp.albedo(50.0, gentle) - Vec3::splat(0.5)).length() < 1e-6);
    }

    #[test]
    fn bad_ramps_name_the_key_and_value() {
        let mut section = AlbedoSection::default();
        section.heights[2] = 100.0;
        assert_eq!(AlbedoRamp::new(&section).unwrap_err().0, "heights");
        let mut section = AlbedoSection::default();
        section.colors[1][0] = 1.5;
        assert_eq!(AlbedoRamp::new(&section).unwrap_err().0, "colors");
        let section = AlbedoSection {
            steep_slope_deg: f64::NAN,
            ..AlbedoSection::default()
        };
        let (key, value, _) = AlbedoRamp::new(&section).unwrap_err();
        assert_eq!((key, value.as_str()), ("steep_slope_deg", "NaN°"));
    }

    #[test]
    fn a_shadowed_surface_keeps_only_the_sky_light() {
        let n = Vec3::Y;
        let sun = Vec3::new(0.0, 0.5, -0.75f32.sqrt());
        let lit = surface_radiance(
            n,
            1.0,
            sun,
            Vec3::ONE,
            1.0,
            1.0,
            Vec3::ONE,
            Vec3::splat(0.2),
        );
        let dark = surface_radiance(
            n,
            1.0,
            sun,
            Vec3::ONE,
            0.0,
            1.0,
            Vec3::ONE,
            Vec3::splat(0.2),
        );
        assert!((dark - Vec3::splat(0.2 / std::f32::consts::PI)).length() < 1e-6);
        assert!((lit - dark - Vec3::splat(0.5 / std::f32::consts::PI)).length() < 1e-6);
    }
}
