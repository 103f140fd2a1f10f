//! Physical parameters of an atmosphere, their validation, the f32 uniform block
//! shared with WGSL (`shaders/atmos/atmosphere.wgsl`) and the density profiles.

use crate::real::Real;

/// Everything atmos rejects, naming the field and its value; each variant says which
/// input it belongs to (the atmosphere, the camera, the LUT settings, another setting,
/// or a GPU resource), and wrapped errors keep their source.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AtmosError {
    /// An [`Atmosphere`] parameter is NaN, infinite or outside its physical range.
    #[error("invalid atmosphere: `{field}` = {value}: {reason}")]
    InvalidParameter {
        /// The field, as spelled in [`Atmosphere`] (with a channel index for colours).
        field: String,
        /// The offending value.
        value: f64,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// A camera or sky query ([`crate::frame::FrameCamera`], [`crate::SkyQuery`]) is
    /// invalid: a non-finite or non-unit vector, a position inside the planet, a bad
    /// field of view or frame size.
    #[error("invalid camera: `{field}` = {value}: {reason}")]
    InvalidCamera {
        /// The field, e.g. `position.x`, `vertical_fov`.
        field: String,
        /// The offending value.
        value: f64,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// A [`crate::lut::LutSettings`] size or count is out of range.
    #[error("invalid LUT settings: `{field}` = {value}: {reason}")]
    InvalidLutSettings {
        /// The field, as spelled in `LutSettings`.
        field: String,
        /// The offending value.
        value: f64,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// Another model setting (dome resolution, quadrature, sample counts, wavelengths,
    /// frame size) is out of range.
    #[error("invalid {setting}: `{field}` = {value}: {reason}")]
    InvalidSetting {
        /// Which settings, e.g. `dome resolution`, `reference settings`.
        setting: &'static str,
        /// The field.
        field: String,
        /// The offending value.
        value: f64,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// WGSL composition failed (a bug in skyscape's shaders, reported rather than panicking).
    #[error("WGSL composition: {0}")]
    Shader(#[from] skyscape_wgsl::ComposeError),
    /// A GPU pass cannot run: a resource the device cannot hold, or a call out of order.
    #[error("GPU: {0}")]
    Gpu(#[from] GpuError),
}

/// Why a GPU pass cannot run.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GpuError {
    /// A buffer larger than the device's storage-binding limit.
    #[error("{resource} needs a {bytes}-byte storage buffer; the device binds at most {limit}")]
    StorageBufferTooLarge {
        /// What the buffer holds, e.g. `a 4096×4096 frame`, `a LUT`.
        resource: String,
        /// Bytes it needs.
        bytes: u64,
        /// `max_storage_buffer_binding_size`.
        limit: u64,
    },
    /// A texture side larger than the device's limit.
    #[error("{resource} needs a texture side of {size} texels; the device allows at most {limit}")]
    TextureTooLarge {
        /// What the texture holds, e.g. `a 20000×10 frame (width)`, `the sky-view LUT`.
        resource: String,
        /// The side it needs.
        size: u32,
        /// `max_texture_dimension_2d` (or `_3d`).
        limit: u32,
    },
    /// The device cannot write `rgba32float` storage textures or read them unfiltered
    /// (every WebGPU adapter can; a downlevel GL adapter may not).
    #[error("the device cannot use {format} textures as {need}")]
    UnsupportedFormat {
        /// The texture format, e.g. `rgba32float`.
        format: &'static str,
        /// The usage it lacks, e.g. `write-only storage textures`.
        need: &'static str,
    },
    /// A wgpu backend that runs the bake but gives wrong tables: wgpu 30's GL backend
    /// binds a 3-D storage texture as its first slice only, so the aerial-perspective
    /// volume's other slices stay zero (`cargo test -p atmos --test storage_texture_3d`
    /// shows it), and its multiple-scattering table reads back zero.
    #[error("the {backend} backend cannot bake the LUTs: {reason}")]
    UnsupportedBackend {
        /// The backend, as `WGPU_BACKEND` spells it (e.g. `gl`).
        backend: String,
        /// What it gets wrong.
        reason: &'static str,
    },
    /// `encode` before `prepare`.
    #[error("{pass}: encode called before prepare")]
    NotPrepared {
        /// The renderer, e.g. `PrecomputedRenderer`.
        pass: &'static str,
    },
    /// The prepared camera's frame size differs from the output's.
    #[error(
        "camera frame {camera_width}×{camera_height} does not match the output's \
         {output_width}×{output_height}"
    )]
    OutputSizeMismatch {
        /// `FrameCamera::width`.
        camera_width: u32,
        /// `FrameCamera::height`.
        camera_height: u32,
        /// `FrameOutput::width`.
        output_width: u32,
        /// `FrameOutput::height`.
        output_height: u32,
    },
}

/// The sun's mean angular radius seen from the Earth (rad): the IAU nominal solar radius
/// over one astronomical unit, 695,700 km / 149,597,870.7 km = 959.2″ = 0.2664°. The
/// sun's true radius varies ±1.7 % over the year (`celestial` computes it for a date);
/// this is the default of [`Atmosphere::earth`] and of `terrain`'s soft shadows.
pub const SUN_ANGULAR_RADIUS: f64 = 695_700.0 / 149_597_870.7;

/// A planet's atmosphere. SI units: radii and heights in metres, coefficients in 1/m.
///
/// Radiance computed from it is in the unit of `sun_irradiance` per steradian; the
/// default irradiance of 1 per channel gives radiance per unit sun irradiance.
#[derive(Debug, Clone, PartialEq)]
pub struct Atmosphere {
    /// Ground radius (m).
    pub planet_radius: f64,
    /// Radius where the atmosphere is taken to end (m).
    pub top_radius: f64,
    /// Rayleigh scattering at the ground per channel (1/m); Rayleigh absorbs nothing.
    pub rayleigh_scattering: [f64; 3],
    /// Rayleigh scale height (m).
    pub rayleigh_scale_height: f64,
    /// Mie scattering at the ground per channel (1/m).
    pub mie_scattering: [f64; 3],
    /// Mie extinction at the ground per channel (1/m), ≥ scattering.
    pub mie_extinction: [f64; 3],
    /// Mie scale height (m).
    pub mie_scale_height: f64,
    /// Mie (Cornette–Shanks / Henyey–Greenstein) anisotropy, |g| < 1.
    pub mie_g: f64,
    /// Ozone absorption at the peak of its layer per channel (1/m).
    pub ozone_absorption: [f64; 3],
    /// Altitude of the ozone peak (m).
    pub ozone_center_altitude: f64,
    /// Half width of the ozone tent (m): density 0 at centre ± half width.
    pub ozone_half_width: f64,
    /// Lambertian ground albedo per channel, in [0, 1].
    pub ground_albedo: [f64; 3],
    /// Sun irradiance above the atmosphere per channel (sets the output unit).
    pub sun_irradiance: [f64; 3],
    /// Angular radius of the sun disc (rad).
    pub sun_angular_radius: f64,
}

impl Default for Atmosphere {
    fn default() -> Self {
        Self::earth()
    }
}

impl Atmosphere {
    /// Earth (Bruneton 2017 / Hillaire 2020 coefficients).
    ///
    /// The top is at 6,460 km (100 km up), as in Hillaire 2020: Rayleigh density there
    /// is e^{−12.5} ≈ 4e−6 of the ground's, so truncating the column costs < 1e−5 of
    /// its optical depth, where Bruneton's 6,420 km (60 km) costs 5.5e−4. It also keeps
    /// the LUT parameterisations comparable with Hillaire's published figures.
    pub fn earth() -> Self {
        Self {
            planet_radius: 6_360_000.0,
            top_radius: 6_460_000.0,
            rayleigh_scattering: [5.802e-6, 13.558e-6, 33.1e-6],
            rayleigh_scale_height: 8_000.0,
            mie_scattering: [3.996e-6; 3],
            mie_extinction: [4.40e-6; 3],
            mie_scale_height: 1_200.0,
            mie_g: 0.8,
            ozone_absorption: [0.650e-6, 1.881e-6, 0.085e-6],
            ozone_center_altitude: 25_000.0,
            ozone_half_width: 15_000.0,
            ground_albedo: [0.1; 3],
            sun_irradiance: [1.0; 3],
            sun_angular_radius: SUN_ANGULAR_RADIUS,
        }
    }

    /// Radiance of the sun's disc above the atmosphere, per channel: a uniform disc
    /// whose irradiance is `sun_irradiance`, `E / Ω` with the disc's solid angle
    /// `Ω = 2π(1 − cos α) = 4π sin²(α/2)` (the stable form; `E/(πα²)` is its small-angle
    /// limit). The one sun-disc formula of skyscape: renderers add it through the
    /// view ray's transmittance where the ray sees the disc.
    pub fn sun_disc_radiance(&self) -> [f64; 3] {
        let half = (0.5 * self.sun_angular_radius).sin();
        let solid_angle = 4.0 * std::f64::consts::PI * half * half;
        self.sun_irradiance
            .map(|irradiance| irradiance / solid_angle)
    }

    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), AtmosError> {
        fn check(
            field: &str,
            value: f64,
            ok: bool,
            reason: &'static str,
        ) -> Result<(), AtmosError> {
            if value.is_finite() && ok {
                Ok(())
            } else {
                Err(AtmosError::InvalidParameter {
                    field: field.to_owned(),
                    value,
                    reason,
                })
            }
        }
        fn check3(
            field: &str,
            values: [f64; 3],
            ok: impl Fn(f64) -> bool,
            reason: &'static str,
        ) -> Result<(), AtmosError> {
            for (i, &v) in values.iter().enumerate() {
                check(&format!("{field}[{i}]"), v, ok(v), reason)?;
            }
            Ok(())
        }
        let non_negative = |v: f64| v >= 0.0;
        check(
            "planet_radius",
            self.planet_radius,
            self.planet_radius > 0.0,
            "must be > 0 m",
        )?;
        check(
            "top_radius",
            self.top_radius,
            self.top_radius > self.planet_radius,
            "must exceed planet_radius",
        )?;
        check3(
            "rayleigh_scattering",
            self.rayleigh_scattering,
            non_negative,
            "must be ≥ 0 per metre",
        )?;
        check(
            "rayleigh_scale_height",
            self.rayleigh_scale_height,
            self.rayleigh_scale_height > 0.0,
            "must be > 0 m",
        )?;
        check3(
            "mie_scattering",
            self.mie_scattering,
            non_negative,
            "must be ≥ 0 per metre",
        )?;
        check3(
            "mie_extinction",
            self.mie_extinction,
            non_negative,
            "must be ≥ 0 per metre",
        )?;
        for i in 0..3 {
            check(
                &format!("mie_extinction[{i}]"),
                self.mie_extinction[i],
                self.mie_extinction[i] >= self.mie_scattering[i],
                "must be ≥ mie_scattering (absorption cannot be negative)",
            )?;
        }
        check(
            "mie_scale_height",
            self.mie_scale_height,
            self.mie_scale_height > 0.0,
            "must be > 0 m",
        )?;
        check(
            "mie_g",
            self.mie_g,
            self.mie_g.abs() < 1.0,
            "|g| must be < 1",
        )?;
        check3(
            "ozone_absorption",
            self.ozone_absorption,
            non_negative,
            "must be ≥ 0 per metre",
        )?;
        check(
            "ozone_center_altitude",
            self.ozone_center_altitude,
            true,
            "must be finite",
        )?;
        check(
            "ozone_half_width",
            self.ozone_half_width,
            self.ozone_half_width > 0.0,
            "must be > 0 m",
        )?;
        check3(
            "ground_albedo",
            self.ground_albedo,
            |v| (0.0..=1.0).contains(&v),
            "must be in [0, 1]",
        )?;
        check3(
            "sun_irradiance",
            self.sun_irradiance,
            non_negative,
            "must be ≥ 0",
        )?;
        check(
            "sun_angular_radius",
            self.sun_angular_radius,
            self.sun_angular_radius > 0.0 && self.sun_angular_radius < std::f64::consts::FRAC_PI_2,
            "must be in (0, π/2) rad",
        )?;
        Ok(())
    }

    /// Validates and converts to the f32 uniform block shared with WGSL.
    pub fn to_uniforms(&self) -> Result<AtmosphereParameters, AtmosError> {
        self.validate()?;
        let f = |v: [f64; 3]| v.map(|x| x as f32);
        Ok(AtmosphereParameters {
            rayleigh_scattering: f(self.rayleigh_scattering),
            rayleigh_scale_height: self.rayleigh_scale_height as f32,
            mie_scattering: f(self.mie_scattering),
            mie_scale_height: self.mie_scale_height as f32,
            mie_extinction: f(self.mie_extinction),
            mie_g: self.mie_g as f32,
            ozone_absorption: f(self.ozone_absorption),
            ozone_center_altitude: self.ozone_center_altitude as f32,
            ground_albedo: f(self.ground_albedo),
            ozone_half_width: self.ozone_half_width as f32,
            sun_irradiance: f(self.sun_irradiance),
            sun_angular_radius: self.sun_angular_radius as f32,
            planet_radius: self.planet_radius as f32,
            top_radius: self.top_radius as f32,
            padding: [0.0; 2],
        })
    }
}

/// The f32 uniform block, layout-identical to WGSL `AtmosphereParameters`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs)]
pub struct AtmosphereParameters {
    pub rayleigh_scattering: [f32; 3],
    pub rayleigh_scale_height: f32,
    pub mie_scattering: [f32; 3],
    pub mie_scale_height: f32,
    pub mie_extinction: [f32; 3],
    pub mie_g: f32,
    pub ozone_absorption: [f32; 3],
    pub ozone_center_altitude: f32,
    pub ground_albedo: [f32; 3],
    pub ozone_half_width: f32,
    pub sun_irradiance: [f32; 3],
    pub sun_angular_radius: f32,
    pub planet_radius: f32,
    pub top_radius: f32,
    pub padding: [f32; 2],
}

/// The atmosphere's parameters in one float type, for the formulas written once over
/// [`Real`]: the f32 uniform block [`AtmosphereParameters`] (what the WGSL reads; the
/// twin) and the f64 [`Atmosphere`] (the reference).
pub trait AtmosphereFields {
    /// The float type of the fields.
    type Real: Real;
    /// Rayleigh scattering at sea level per channel (1/m).
    fn rayleigh_scattering(&self) -> [Self::Real; 3];
    /// Rayleigh scale height (m).
    fn rayleigh_scale_height(&self) -> Self::Real;
    /// Mie scattering at sea level per channel (1/m).
    fn mie_scattering(&self) -> [Self::Real; 3];
    /// Mie extinction at sea level per channel (1/m).
    fn mie_extinction(&self) -> [Self::Real; 3];
    /// Mie scale height (m).
    fn mie_scale_height(&self) -> Self::Real;
    /// Mie asymmetry parameter g.
    fn mie_g(&self) -> Self::Real;
    /// Ozone absorption at the layer's peak per channel (1/m).
    fn ozone_absorption(&self) -> [Self::Real; 3];
    /// Altitude of the ozone layer's peak (m).
    fn ozone_center_altitude(&self) -> Self::Real;
    /// Half width of the ozone tent (m).
    fn ozone_half_width(&self) -> Self::Real;
    /// Sun irradiance at the top of the atmosphere per channel.
    fn sun_irradiance(&self) -> [Self::Real; 3];
    /// Planet radius (m).
    fn planet_radius(&self) -> Self::Real;
    /// Radius of the top of the atmosphere (m).
    fn top_radius(&self) -> Self::Real;
}

macro_rules! atmosphere_fields {
    ($type:ty, $real:ty) => {
        impl AtmosphereFields for $type {
            type Real = $real;
            fn rayleigh_scattering(&self) -> [$real; 3] {
                self.rayleigh_scattering
            }
            fn rayleigh_scale_height(&self) -> $real {
                self.rayleigh_scale_height
            }
            fn mie_scattering(&self) -> [$real; 3] {
                self.mie_scattering
            }
            fn mie_extinction(&self) -> [$real; 3] {
                self.mie_extinction
            }
            fn mie_scale_height(&self) -> $real {
                self.mie_scale_height
            }
            fn mie_g(&self) -> $real {
                self.mie_g
            }
            fn ozone_absorption(&self) -> [$real; 3] {
                self.ozone_absorption
            }
            fn ozone_center_altitude(&self) -> $real {
                self.ozone_center_altitude
            }
            fn ozone_half_width(&self) -> $real {
                self.ozone_half_width
            }
            fn sun_irradiance(&self) -> [$real; 3] {
                self.sun_irradiance
            }
            fn planet_radius(&self) -> $real {
                self.planet_radius
            }
            fn top_radius(&self) -> $real {
                self.top_radius
            }
        }
    };
}
atmosphere_fields!(AtmosphereParameters, f32);
atmosphere_fields!(Atmosphere, f64);

/// exp(−altitude/scale_height).
#[doc(hidden)]
pub fn exponential_density<F: Real>(altitude: F, scale_height: F) -> F {
    (-altitude / scale_height).exp()
}

/// 1 at `center`, linearly 0 at `center ± half_width`.
#[doc(hidden)]
pub fn tent_density<F: Real>(altitude: F, center: F, half_width: F) -> F {
    (F::one() - (altitude - center).abs() / half_width).max(F::zero())
}

/// Extinction (1/m) per channel at an altitude.
pub fn extinction_at_altitude<A: AtmosphereFields>(
    atmosphere: &A,
    altitude: A::Real,
) -> [A::Real; 3] {
    let rayleigh = exponential_density(altitude, atmosphere.rayleigh_scale_height());
    let mie = exponential_density(altitude, atmosphere.mie_scale_height());
    let ozone = tent_density(
        altitude,
        atmosphere.ozone_center_altitude(),
        atmosphere.ozone_half_width(),
    );
    let (rayleigh_scattering, mie_extinction, ozone_absorption) = (
        atmosphere.rayleigh_scattering(),
        atmosphere.mie_extinction(),
        atmosphere.ozone_absorption(),
    );
    std::array::from_fn(|i| {
        rayleigh_scattering[i] * rayleigh + mie_extinction[i] * mie + ozone_absorption[i] * ozone
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn earth_is_valid_and_matches_the_issue() {
        let earth = Atmosphere::earth();
        earth.validate().unwrap();
        let u = earth.to_uniforms().unwrap();
        assert_eq!(u.top_radius, 6_460_000.0);
        assert_eq!(std::mem::size_of::<AtmosphereParameters>(), 112);
    }

    #[test]
    fn invalid_fields_are_named_with_their_value() {
        let cases: Vec<(Atmosphere, &str)> = vec![
            (
                Atmosphere {
                    mie_g: 1.0,
                    ..Atmosphere::earth()
                },
                "mie_g",
            ),
            (
                Atmosphere {
                    top_radius: 6_360_000.0,
                    ..Atmosphere::earth()
                },
                "top_radius",
            ),
            (
                Atmosphere {
                    rayleigh_scattering: [5.8e-6, -1e-6, 3.3e-5],
                    ..Atmosphere::earth()
                },
                "rayleigh_scattering[1]",
            ),
            (
                Atmosphere {
                    planet_radius: f64::NAN,
                    ..Atmosphere::earth()
                },
                "planet_radius",
            ),
            (
                Atmosphere {
                    mie_extinction: [1e-6; 3],
                    ..Atmosphere::earth()
                },
                "mie_extinction[0]",
            ),
            (
                Atmosphere {
                    ozone_half_width: 0.0,
                    ..Atmosphere::earth()
                },
                "ozone_half_width",
            ),
        ];
        for (atmosphere, field) in cases {
            match atmosphere.validate() {
                Err(AtmosError::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        let message = Atmosphere {
            mie_g: -1.5,
            ..Atmosphere::earth()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(
            message.contains("mie_g") && message.contains("-1.5"),
            "{message}"
        );
    }

    #[test]
    fn profiles() {
        assert_eq!(exponential_density(0.0, 8000.0), 1.0);
        approx::assert_relative_eq!(exponential_density(8000.0, 8000.0), (-1.0f32).exp());
        assert_eq!(tent_density(25_000.0, 25_000.0, 15_000.0), 1.0);
        assert_eq!(tent_density(10_000.0, 25_000.0, 15_000.0), 0.0);
        assert_eq!(tent_density(0.0, 25_000.0, 15_000.0), 0.0);
        approx::assert_relative_eq!(tent_density(32_500.0, 25_000.0, 15_000.0), 0.5);
        let u = Atmosphere::earth().to_uniforms().unwrap();
        let ground = extinction_at_altitude(&u, 0.0);
        approx::assert_relative_eq!(ground[2], 33.1e-6 + 4.40e-6, max_relative = 1e-6);
    }
}
