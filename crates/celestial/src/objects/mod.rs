//! The per-frame description of the sky objects, built on the CPU from where they are
//! (the ephemerides) and from any atmos [`SkyModel`] (how the air dims them and how
//! bright the sky behind them is), and drawn by the CPU twin here
//! ([`render_sky_objects_cpu`]) or by the GPU pass (`celestial::gpu::SkyObjectsPass`)
//! from the same [`SkyObjectsFrame`].
//!
//! Frame: the viewer's east/north/up frame (x east, y north, z up), the planet's centre
//! at `(0, 0, −(planet_radius + altitude))`: the atmos query's planet-centred position
//! is `(0, 0, planet_radius + altitude)` with these axes, so directions pass unchanged.

use atmos::Atmosphere;
use atmos::dome::{DomeInterpolated, DomeResolution};
use atmos::frame::FrameCamera;
use atmos::ladder::{SkyModel, SkyQuery, SkySample};
use glam::DVec3;

use crate::draw::{
    self, DISC_MOON, DISC_SUN, DiscObject, MIN_SPRITE_SIGMA_PX, PointSource, SPRITE_CUTOFF_SIGMAS,
};
use crate::error::{CelestialError, Result};
use crate::light::{LuminanceScale, MoonLight};
use crate::photometry::{NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2, luminance_from_surface_brightness};

/// A borrowed model as a [`SkyModel`] (so a dome can wrap it for one frame).
#[derive(Clone, Copy)]
pub struct ModelRef<'a>(pub &'a dyn SkyModel);

impl std::fmt::Debug for ModelRef<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ModelRef({})", self.0.label())
    }
}

impl SkyModel for ModelRef<'_> {
    fn label(&self) -> String {
        self.0.label()
    }
    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        self.0.evaluate(query)
    }
}

/// How the sky behind the stars is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BackgroundSampling {
    /// Every star queries the model (exact; costly with the expensive rungs).
    PerObject,
    /// The model is evaluated at the vertices of an atmos dome per light source and
    /// interpolated per star ([`atmos::dome`]; its error is the dome's, measured by
    /// `cargo xtask tradeoff atmos`).
    Dome(DomeResolution),
}

impl Default for BackgroundSampling {
    /// A 32 × 48 dome: 1,666 model evaluations per light source and frame.
    fn default() -> Self {
        BackgroundSampling::Dome(DomeResolution {
            rings: 32,
            segments: 48,
        })
    }
}

/// Builds [`DiscObject`]s and [`PointSource`]s for one viewer, one frame.
pub struct SkyObjectsBuilder<'a> {
    atmosphere: &'a Atmosphere,
    model: &'a dyn SkyModel,
    altitude_m: f64,
    scale: LuminanceScale,
    sun_direction: DVec3,
    moon: Option<MoonLight>,
    background_floor: f64,
    sun_dome: Option<DomeInterpolated<ModelRef<'a>>>,
    moon_dome: Option<DomeInterpolated<ModelRef<'a>>>,
}

impl std::fmt::Debug for SkyObjectsBuilder<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SkyObjectsBuilder")
            .field("model", &self.model.label())
            .field("altitude_m", &self.altitude_m)
            .field("scale", &self.scale)
            .finish_non_exhaustive()
    }
}

pub(crate) fn unit_direction(field: &'static str, v: [f64; 3]) -> Result<DVec3> {
    for c in v {
        if !c.is_finite() {
            return Err(CelestialError::NotFinite { field, value: c });
        }
    }
    let d = DVec3::from_array(v);
    let length = d.length();
    if (length - 1.0).abs() > 1e-3 {
        return Err(CelestialError::OutOfRange {
            field,
            value: length,
            min: 0.999,
            max: 1.001,
            unit: "(length of a unit vector)",
        });
    }
    Ok(d / length)
}

fn atmos_error(field: &'static str) -> impl Fn(atmos::AtmosError) -> CelestialError {
    move |source| CelestialError::Atmos { field, source }
}

/// Whether a view ray (unit, east/north/up) from a viewer `altitude_m` up hits the
/// ground (docs/architecture.md, "Rays at the ground").
pub(crate) fn ray_hits_ground(atmosphere: &Atmosphere, altitude_m: f64, view: DVec3) -> bool {
    let r = atmosphere.planet_radius + altitude_m;
    let mu = view.z;
    mu < 0.0 && atmos::reference::ray_sphere_intersect(r, mu, atmosphere.planet_radius)[0] >= 0.0
}

impl<'a> SkyObjectsBuilder<'a> {
    /// A builder for a viewer `altitude_m` above the ground of `atmosphere`, whose sky
    /// is `model` (built from the same `atmosphere`: its radiance is in the unit of
    /// `atmosphere.sun_irradiance`), with the sun along `sun_direction` (east/north/up)
    /// at `sun_distance_m`, the moon's light `moon` if it is to be drawn, and the sky
    /// behind stars sampled as `background`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        atmosphere: &'a Atmosphere,
        model: &'a dyn SkyModel,
        altitude_m: f64,
        sun_direction: [f64; 3],
        sun_distance_m: f64,
        moon: Option<MoonLight>,
        background: BackgroundSampling,
    ) -> Result<Self> {
        atmosphere.validate().map_err(atmos_error("atmosphere"))?;
        let top = atmosphere.top_radius - atmosphere.planet_radius;
        crate::error::check_range(
            "altitude_m",
            altitude_m,
            -atmos::ladder::MAX_DEPTH_BELOW_GROUND,
            10.0 * top,
            "m",
        )?;
        let sun_direction = unit_direction("sun_direction", sun_direction)?;
        let scale = LuminanceScale::new(atmosphere, sun_distance_m)?;
        let (sun_dome, moon_dome) = match background {
            BackgroundSampling::PerObject => (None, None),
            BackgroundSampling::Dome(resolution) => (
                Some(
                    DomeInterpolated::new(ModelRef(model), resolution, atmosphere)
                        .map_err(atmos_error("background dome"))?,
                ),
                Some(
                    DomeInterpolated::new(ModelRef(model), resolution, atmosphere)
                        .map_err(atmos_error("background dome"))?,
                ),
            ),
        };
        Ok(Self {
            atmosphere,
            model,
            altitude_m,
            scale,
            sun_direction,
            moon,
            background_floor: luminance_from_surface_brightness(
                NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2,
            ),
            sun_dome,
            moon_dome,
        })
    }

    /// The photometric scale of the atmosphere's unit.
    pub fn scale(&self) -> &LuminanceScale {
        &self.scale
    }

    /// The viewer's planet-centred position (m) in the east/north/up axes.
    pub fn position(&self) -> DVec3 {
        DVec3::new(0.0, 0.0, self.atmosphere.planet_radius + self.altitude_m)
    }

    fn query(&self, view: DVec3, light: DVec3) -> Result<SkyQuery> {
        SkyQuery::new(self.atmosphere.planet_radius, self.position(), view, light)
            .map_err(atmos_error("sky query"))
    }

    fn hits_ground(&self, view: DVec3) -> bool {
        ray_hits_ground(self.atmosphere, self.altitude_m, view)
    }

    /// The atmosphere's transmittance from the viewer toward `direction` to space
    /// (per channel); 0 where the ray meets the ground.
    pub fn transmittance(&self, direction: [f64; 3]) -> Result<[f64; 3]> {
        let view = unit_direction("direction", direction)?;
        if self.hits_ground(view) {
            return Ok([0.0; 3]);
        }
        Ok(self
            .model
            .evaluate(&self.query(view, self.sun_direction)?)
            .transmittance)
    }

    /// ln T at three points across a disc of angular radius `radius` centred on
    /// `centre` (its lowest point, centre and highest point, kept above the geometric
    /// horizon where the ray would end on the ground) fitted as ln T₀ + b·Δμ + c·Δμ².
    fn transmittance_fit(&self, centre: DVec3, radius: f64) -> Result<TransmittanceFit> {
        let r = self.atmosphere.planet_radius + self.altitude_m;
        let horizon = -((r - self.atmosphere.planet_radius).max(0.0)
            * (r + self.atmosphere.planet_radius))
            .sqrt()
            / r;
        let horizon_elevation = horizon.asin() + 1e-6;
        let elevation = centre.z.clamp(-1.0, 1.0).asin();
        let azimuth = centre.x.atan2(centre.y);
        let at = |e: f64| {
            let e = e.clamp(horizon_elevation, std::f64::consts::FRAC_PI_2);
            DVec3::new(e.cos() * azimuth.sin(), e.cos() * azimuth.cos(), e.sin())
        };
        let points = [
            at(elevation - radius),
            at(elevation),
            at(elevation + radius),
        ];
        let mut log_t = [[0.0f64; 3]; 3];
        for (k, p) in points.iter().enumerate() {
            let t = self
                .model
                .evaluate(&self.query(*p, self.sun_direction)?)
                .transmittance;
            log_t[k] = t.map(|v| v.max(1e-30).ln());
        }
        let mu: [f64; 3] = points.map(|p| p.z);
        let mu0 = centre.z;
        let (d1, d2) = (mu[0] - mu0, mu[2] - mu0);
        let mut a = [0.0f32; 3];
        let mut b = [0.0f32; 3];
        let mut c = [0.0f32; 3];
        for ch in 0..3 {
            // Lagrange through (d1, y0), (dc, y1), (d2, y2) with dc = mu[1] − mu0.
            let dc = mu[1] - mu0;
            let (y0, y1, y2) = (log_t[0][ch], log_t[1][ch], log_t[2][ch]);
            let distinct =
                (d1 - dc).abs() > 1e-12 && (d2 - dc).abs() > 1e-12 && (d2 - d1).abs() > 1e-12;
            if distinct {
                // y(d) = y1 + s1 (d − dc) + s2 (d − dc)(d − d1) in Newton form.
                let s01 = (y1 - y0) / (dc - d1);
                let s12 = (y2 - y1) / (d2 - dc);
                let s2 = (s12 - s01) / (d2 - d1);
                // Expand around d = 0: y(0) etc.
                let value = y1 + s01 * (0.0 - dc) + s2 * (0.0 - dc) * (0.0 - d1);
                let slope = s01 + s2 * ((0.0 - dc) + (0.0 - d1));
                a[ch] = value as f32;
                b[ch] = slope as f32;
                c[ch] = s2 as f32;
            } else {
                a[ch] = y1 as f32;
            }
        }
        Ok(TransmittanceFit {
            log_transmittance: a,
            slope: b,
            curvature: c,
            mu_centre: mu0 as f32,
        })
    }

    /// The sun's disc: the atmosphere's angular radius and irradiance, limb-darkened per
    /// channel, through the transmittance fitted across the disc.
    pub fn sun_disc(&self) -> Result<DiscObject> {
        self.sun_disc_towards(self.sun_direction.to_array())
    }

    /// [`Self::sun_disc`] drawn along `direction` (the apparent, refracted place) while
    /// the air stays lit from the builder's sun.
    pub fn sun_disc_towards(&self, direction: [f64; 3]) -> Result<DiscObject> {
        let direction = unit_direction("sun disc direction", direction)?;
        let fit = self.transmittance_fit(direction, self.atmosphere.sun_angular_radius)?;
        Ok(sun_disc_object(self.atmosphere, direction, fit))
    }

    /// The moon's disc (if the builder has the moon): Lommel–Seeliger shading lit from
    /// the sun as seen from the moon, scaled so the disc delivers the moon's irradiance,
    /// through the transmittance fitted across the disc.
    pub fn moon_disc(&self) -> Result<DiscObject> {
        match &self.moon {
            Some(moon) => self.moon_disc_towards(moon.direction),
            None => Ok(DiscObject::NONE),
        }
    }

    /// [`Self::moon_disc`] drawn along `direction` (the apparent place).
    pub fn moon_disc_towards(&self, direction: [f64; 3]) -> Result<DiscObject> {
        let Some(moon) = &self.moon else {
            return Ok(DiscObject::NONE);
        };
        let direction = unit_direction("moon disc direction", direction)?;
        moon_disc_object(moon, direction, |radius| {
            self.transmittance_fit(direction, radius)
        })
    }

    /// The sky toward `view`: in-scattered radiance (sunlit plus moonlit, in the
    /// atmosphere's unit) and transmittance, from the model or its domes.
    pub fn sky(&self, view: [f64; 3]) -> Result<SkySample> {
        let view = unit_direction("view", view)?;
        let sun_query = self.query(view, self.sun_direction)?;
        let mut sample = match &self.sun_dome {
            Some(dome) => dome.evaluate(&sun_query),
            None => self.model.evaluate(&sun_query),
        };
        if let Some(moon) = &self.moon {
            let moon_query = self.query(view, DVec3::from_array(moon.direction))?;
            let lit = match &self.moon_dome {
                Some(dome) => dome.evaluate(&moon_query),
                None => self.model.evaluate(&moon_query),
            };
            let scale = moon.sky_scale(self.atmosphere);
            for ((total, moonlit), s) in sample.radiance.iter_mut().zip(lit.radiance).zip(scale) {
                *total += moonlit * s;
            }
        }
        Ok(sample)
    }

    /// The sky toward `view` from the model itself (one query per light source), whatever
    /// the background sampling: what the dome's vertices take.
    pub fn sky_exact(&self, view: [f64; 3]) -> Result<SkySample> {
        let view = unit_direction("view", view)?;
        let mut sample = self.model.evaluate(&self.query(view, self.sun_direction)?);
        if let Some(moon) = &self.moon {
            let lit = self
                .model
                .evaluate(&self.query(view, DVec3::from_array(moon.direction))?);
            let scale = moon.sky_scale(self.atmosphere);
            for ((total, moonlit), s) in sample.radiance.iter_mut().zip(lit.radiance).zip(scale) {
                *total += moonlit * s;
            }
        }
        Ok(sample)
    }

    /// A star or planet along `direction` with illuminance `illuminance_lx` above the
    /// atmosphere and unit-luminance `colour`: the transmittance toward it and the
    /// luminance of the sky behind it (natural night-sky floor included); hidden (zero
    /// transmittance) below the horizon.
    pub fn point_source(
        &self,
        direction: [f64; 3],
        illuminance_lx: f64,
        colour: [f64; 3],
    ) -> Result<PointSource> {
        crate::error::check_range("illuminance_lx", illuminance_lx, 0.0, 1e6, "lx")?;
        let view = unit_direction("direction", direction)?;
        let sky = self.sky(direction)?;
        let transmittance = if self.hits_ground(view) {
            [0.0; 3]
        } else {
            sky.transmittance
        };
        Ok(PointSource {
            direction: view.as_vec3().to_array(),
            illuminance_lux: illuminance_lx as f32,
            colour: colour.map(|c| c as f32),
            background_luminance: (self.scale.luminance(sky.radiance) + self.background_floor)
                as f32,
            transmittance: transmittance.map(|t| t as f32),
            scintillation: 1.0,
        })
    }

    /// The aureole's inputs along the sun: transmittance and Mie scattering optical
    /// depth of the viewer's path to space toward the sun (0 when the planet hides it).
    pub fn aureole(&self) -> Result<Aureole> {
        self.aureole_towards(self.sun_direction.to_array())
    }

    /// [`Self::aureole`] around the sun drawn along `direction`.
    pub fn aureole_towards(&self, direction: [f64; 3]) -> Result<Aureole> {
        let direction = unit_direction("aureole direction", direction)?;
        Ok(Aureole::along(
            self.atmosphere,
            self.altitude_m,
            direction,
            self.transmittance(direction.to_array())?,
        ))
    }
}

/// The sun's disc along `direction` (unit): the atmosphere's angular radius and
/// irradiance, limb-darkened per channel, through `fit`.
pub(crate) fn sun_disc_object(
    atmosphere: &Atmosphere,
    direction: DVec3,
    fit: TransmittanceFit,
) -> DiscObject {
    let radius = atmosphere.sun_angular_radius;
    let solid_angle = std::f64::consts::TAU * (1.0 - radius.cos());
    DiscObject {
        direction: direction.as_vec3().to_array(),
        sin_radius: radius.sin() as f32,
        radiance: atmosphere.sun_irradiance.map(|e| (e / solid_angle) as f32),
        kind: DISC_SUN,
        shading: draw::solar_limb_darkening_exponents().map(|a| a as f32),
        mu_centre: fit.mu_centre,
        log_transmittance: fit.log_transmittance,
        padding0: 0.0,
        log_transmittance_slope: fit.slope,
        padding1: 0.0,
        log_transmittance_curvature: fit.curvature,
        padding2: 0.0,
    }
}

/// The moon's disc along `direction` (unit): Lommel–Seeliger shading lit from the sun
/// as seen from the moon, scaled so the disc delivers the moon's irradiance, through
/// `fit(angular radius)`; [`DiscObject::NONE`] when no lit part faces the viewer.
pub(crate) fn moon_disc_object(
    moon: &MoonLight,
    direction: DVec3,
    fit: impl FnOnce(f64) -> Result<TransmittanceFit>,
) -> Result<DiscObject> {
    let radius = moon.angular_radius.radians();
    let solid_angle = std::f64::consts::TAU * (1.0 - radius.cos());
    let mean = draw::lommel_seeliger_disc_mean(moon.phase_angle);
    if mean <= 0.0 {
        return Ok(DiscObject::NONE);
    }
    let fit = fit(radius)?;
    Ok(DiscObject {
        direction: direction.as_vec3().to_array(),
        sin_radius: radius.sin() as f32,
        radiance: moon.irradiance.map(|e| (e / (solid_angle * mean)) as f32),
        kind: DISC_MOON,
        shading: moon.toward_sun.map(|c| c as f32),
        mu_centre: fit.mu_centre,
        log_transmittance: fit.log_transmittance,
        padding0: 0.0,
        log_transmittance_slope: fit.slope,
        padding1: 0.0,
        log_transmittance_curvature: fit.curvature,
        padding2: 0.0,
    })
}

/// ln T ≈ `log_transmittance` + `slope`·Δμ + `curvature`·Δμ² around `mu_centre`.
pub(crate) struct TransmittanceFit {
    log_transmittance: [f32; 3],
    slope: [f32; 3],
    curvature: [f32; 3],
    mu_centre: f32,
}

impl TransmittanceFit {
    /// One transmittance across the disc (slope and curvature zero) centred at
    /// zenith cosine `mu_centre`; ln T as the fit takes it (T ≥ 10⁻³⁰).
    pub(crate) fn flat(transmittance: [f64; 3], mu_centre: f64) -> Self {
        Self {
            log_transmittance: transmittance.map(|t| t.max(1e-30).ln() as f32),
            slope: [0.0; 3],
            curvature: [0.0; 3],
            mu_centre: mu_centre as f32,
        }
    }
}

/// What [`draw::sun_aureole_radiance`] needs along the sun.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aureole {
    /// The sun's irradiance above the atmosphere per channel.
    pub irradiance: [f64; 3],
    /// Transmittance toward the sun per channel.
    pub transmittance: [f64; 3],
    /// Mie scattering optical depth of the same path per channel.
    pub mie_optical_depth: [f64; 3],
    /// Mie anisotropy.
    pub mie_g: f64,
    /// Unit direction of the sun.
    pub direction: [f64; 3],
}

impl Aureole {
    /// The aureole around the sun along `direction` (unit) for a viewer `altitude_m`
    /// up, seen through `transmittance`: the Mie scattering optical depth of the
    /// viewer's path to space that way; transmittance and optical depth 0 when the
    /// planet hides the sun.
    pub fn along(
        atmosphere: &Atmosphere,
        altitude_m: f64,
        direction: DVec3,
        transmittance: [f64; 3],
    ) -> Self {
        if ray_hits_ground(atmosphere, altitude_m, direction) {
            return Aureole {
                irradiance: atmosphere.sun_irradiance,
                transmittance: [0.0; 3],
                mie_optical_depth: [0.0; 3],
                mie_g: atmosphere.mie_g,
                direction: direction.to_array(),
            };
        }
        let r = atmosphere.planet_radius + altitude_m.max(0.0);
        let mu = direction.z;
        let exit = atmos::reference::ray_sphere_intersect(r, mu, atmosphere.top_radius)[1].max(0.0);
        let path = atmos::closed_form_sky::closed_form_segment_path(
            r,
            mu,
            exit,
            atmosphere.planet_radius,
            atmosphere.mie_scale_height,
        );
        Aureole {
            irradiance: atmosphere.sun_irradiance,
            transmittance,
            mie_optical_depth: atmosphere.mie_scattering.map(|b| b * path),
            mie_g: atmosphere.mie_g,
            direction: direction.to_array(),
        }
    }

    /// The aureole's radiance along `view` (unit).
    pub fn radiance(&self, view: [f32; 3]) -> [f32; 3] {
        let d = self.direction.map(|c| c as f32);
        let cos = view[0] * d[0] + view[1] * d[1] + view[2] * d[2];
        std::array::from_fn(|i| {
            draw::sun_aureole_radiance(
                cos,
                self.mie_g as f32,
                self.irradiance[i] as f32,
                self.transmittance[i] as f32,
                self.mie_optical_depth[i] as f32,
            )
        })
    }
}

/// The frame uniform of the sky-objects pass; layout identical to WGSL
/// `SkyObjectsUniforms` (shaders/celestial/sky_objects.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SkyObjectsUniforms {
    /// The camera (its `sun` field is not used).
    pub camera: FrameCamera,
    /// Ground radius (m).
    pub planet_radius: f32,
    /// Lux per unit of the atmosphere's irradiance.
    pub lux_per_unit: f32,
    /// Point-sprite σ (pixels).
    pub sprite_sigma_px: f32,
    /// Depth written for the objects (the far plane of the caller's convention).
    pub far_depth: f32,
}

/// Everything the sky objects need for one frame, on the CPU or the GPU.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyObjectsFrame {
    /// Camera and constants.
    pub uniforms: SkyObjectsUniforms,
    /// The sun and the moon ([`DiscObject::NONE`] for absent ones).
    pub discs: [DiscObject; 2],
    /// Stars and planets.
    pub points: Vec<PointSource>,
}

impl SkyObjectsFrame {
    /// A frame for `camera` (east/north/up axes, planet-centred position on +z) above a
    /// ground of `planet_radius`, with sprites of `sprite_sigma_px` (≥
    /// [`MIN_SPRITE_SIGMA_PX`]), checked.
    pub fn new(
        camera: FrameCamera,
        planet_radius: f64,
        scale: &LuminanceScale,
        sprite_sigma_px: f32,
        discs: [DiscObject; 2],
        points: Vec<PointSource>,
    ) -> Result<Self> {
        crate::error::check_range(
            "sprite_sigma_px",
            f64::from(sprite_sigma_px),
            f64::from(MIN_SPRITE_SIGMA_PX),
            64.0,
            "px",
        )?;
        crate::error::check_range("planet_radius", planet_radius, 1.0, 1e9, "m")?;
        Ok(Self {
            uniforms: SkyObjectsUniforms {
                camera,
                planet_radius: planet_radius as f32,
                lux_per_unit: scale.lux_per_unit() as f32,
                sprite_sigma_px,
                far_depth: 1.0,
            },
            discs,
            points,
        })
    }
}

/// Adds the sky objects' radiance to `radiance` (row-major, `camera.width ×
/// camera.height`, in the atmosphere's unit): per pixel the discs, then each point
/// source splatted over the pixels within [`SPRITE_CUTOFF_SIGMAS`]·σ of its projected
/// centre. The CPU twin of the GPU pass, pixel for pixel.
pub fn render_sky_objects_cpu(frame: &SkyObjectsFrame, radiance: &mut [[f32; 3]]) -> Result<()> {
    let u = &frame.uniforms;
    let camera = &u.camera;
    let (width, height) = (camera.width as usize, camera.height as usize);
    if radiance.len() != width * height {
        return Err(CelestialError::OutOfRange {
            field: "radiance.len()",
            value: radiance.len() as f64,
            min: (width * height) as f64,
            max: (width * height) as f64,
            unit: "pixels",
        });
    }
    let p = camera.position;
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let zenith = p.map(|c| c / r);
    if frame.discs.iter().any(|d| d.kind != draw::DISC_NONE) {
        for y in 0..height {
            for x in 0..width {
                let view = atmos::frame::frame_view_direction([x as u32, y as u32], camera);
                let out = &mut radiance[y * width + x];
                for disc in &frame.discs {
                    let l = draw::disc_object_radiance(view, disc, zenith, r, u.planet_radius);
                    for i in 0..3 {
                        out[i] += l[i];
                    }
                }
            }
        }
    }
    let cutoff = SPRITE_CUTOFF_SIGMAS * u.sprite_sigma_px;
    for point in &frame.points {
        let [cx, cy, cos_forward] = draw::project_direction(point.direction, camera);
        if cos_forward <= 0.0 {
            continue;
        }
        let irradiance = draw::point_source_irradiance(
            point.illuminance_lux,
            point.colour,
            point.transmittance,
            point.background_luminance,
            point.scintillation,
            u.lux_per_unit,
        );
        if irradiance == [0.0; 3] {
            continue;
        }
        let solid_angle =
            draw::pixel_solid_angle(camera.tan_half_fov_y, camera.height, cos_forward);
        let x0 = (cx - cutoff).floor().max(0.0) as usize;
        let y0 = (cy - cutoff).floor().max(0.0) as usize;
        let x1 = ((cx + cutoff).ceil().max(0.0) as usize).min(width);
        let y1 = ((cy + cutoff).ceil().max(0.0) as usize).min(height);
        for y in y0..y1 {
            for x in x0..x1 {
                let dx = x as f32 + 0.5 - cx;
                let dy = y as f32 + 0.5 - cy;
                let r2 = dx * dx + dy * dy;
                if r2 > cutoff * cutoff {
                    continue;
                }
                let w = draw::point_sprite_weight(r2, u.sprite_sigma_px) / solid_angle;
                let out = &mut radiance[y * width + x];
                for i in 0..3 {
                    out[i] += irradiance[i] * w;
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
