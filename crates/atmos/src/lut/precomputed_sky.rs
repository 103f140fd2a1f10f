//! The precomputed rung as a [`SkyModel`], and the CPU twin of the GPU renderer's
//! per-pixel pass.
//!
//! Cost is split the way the GPU splits it, so each part can be timed:
//! * [`StaticLuts::bake`] — per atmosphere: transmittance and multiple-scattering LUTs;
//! * [`PrecomputedSky::prepare`] / [`FrameLuts::bake`] — per frame (viewer altitude and
//!   sun): the sky-view LUT (and, for a frame camera, the aerial-perspective volume);
//! * [`PrecomputedSky::evaluate_prepared`] / [`shade_pixel`] — per pixel: lookups.
//!
//! What a query gets:
//! * unlimited segment, viewer inside the atmosphere: sky-view lookup for the radiance;
//!   the transmittance (Bruneton's ratio for ground rays) from the same footprint or
//!   from the transmittance LUT, as [`super::ViewTransmittance`] chose;
//! * unlimited segment, viewer above the atmosphere: the sky-view LUT does not apply
//!   (each ray enters the shell at a different zenith); the ray is marched from its
//!   entry point with the LUTs ([`march_view_segment`], `pixel_samples` steps);
//! * limited segment (`max_distance`): on the GPU, the aerial-perspective volume when
//!   `max_distance` ≤ its range, else a march with the LUTs; on the CPU
//!   ([`SkyModel::evaluate`], arbitrary directions with no frustum) always the march
//!   with the LUTs. [`shade_pixel`] reproduces the GPU's choice exactly.

use std::sync::{Arc, Mutex};

use glam::DVec3;

use crate::frame::{FrameCamera, UNLIMITED_DISTANCE, frame_view_direction};
use crate::ladder::{SkyModel, SkyQuery, SkySample};
use crate::{AtmosError, Atmosphere, AtmosphereParameters};

use super::aerial_perspective::{
    AerialPerspectiveVolume, bake_aerial_perspective, lookup_aerial_perspective, view_cosines,
};
use super::multiple_scattering_lut::bake_multiple_scattering_lut;
use super::parameterization::view_sun_cos_azimuth;
use super::raymarch::{
    LutBindings, ScatteringSegment, march_view_segment, ray_segment_in_atmosphere,
};
use super::sky_view_lut::{bake_sky_view_lut, lookup_sky_view, sky_view_r_mu_s};
use super::transmittance_lut::bake_transmittance_lut;
use super::{Lut2d, LutSettings, LutSettingsUniform};

/// The first bytes of [`StaticLuts::to_bytes`]: the format's name and version, then 1
/// as a `u32` in the writer's byte order.
pub const CACHE_MAGIC: [u8; 12] = {
    let mut magic = *b"skyLUT01\0\0\0\0";
    let one = 1u32.to_ne_bytes();
    magic[8] = one[0];
    magic[9] = one[1];
    magic[10] = one[2];
    magic[11] = one[3];
    magic
};

/// An atmosphere with its light zeroed: the air alone, what the static tables depend on.
fn unlit(atmosphere: &AtmosphereParameters) -> AtmosphereParameters {
    AtmosphereParameters {
        sun_irradiance: [0.0; 3],
        sun_angular_radius: 0.0,
        ..*atmosphere
    }
}

/// The per-atmosphere tables.
#[derive(Debug, Clone)]
pub struct StaticLuts {
    /// The f32 atmosphere they were baked for.
    pub atmosphere: AtmosphereParameters,
    /// Sizes and sample counts.
    pub settings: LutSettingsUniform,
    /// Orders of scattering the multiple-scattering table sums
    /// ([`LutSettings::multiple_scattering_orders`]).
    pub multiple_scattering_orders: u32,
    /// Transmittance LUT.
    pub transmittance: Lut2d,
    /// Multiple-scattering LUT.
    pub multiple_scattering: Lut2d,
}

impl StaticLuts {
    /// Validates and bakes both tables on the CPU (threaded).
    pub fn bake(atmosphere: &Atmosphere, settings: &LutSettings) -> Result<Self, AtmosError> {
        let atmosphere = atmosphere.to_uniforms()?;
        let uniforms = settings.to_uniforms()?;
        let transmittance = bake_transmittance_lut(&atmosphere, &uniforms);
        let unused = Lut2d {
            width: 0,
            height: 0,
            texels: Vec::new(),
        };
        let orders = settings.multiple_scattering_orders;
        let multiple_scattering = bake_multiple_scattering_lut(
            &LutBindings {
                atmosphere: &atmosphere,
                settings: &uniforms,
                transmittance: &transmittance,
                multiple_scattering: &unused,
            },
            orders,
        );
        Ok(Self {
            atmosphere,
            settings: uniforms,
            multiple_scattering_orders: orders,
            transmittance,
            multiple_scattering,
        })
    }

    /// The tables for `atmosphere` when it differs from theirs in its light alone (the
    /// sun's irradiance and angular radius: the moon as a light, celestial's
    /// `MoonLight::atmosphere`, or another sun): the same transmittance and
    /// multiple-scattering tables, which hold the air's response per unit irradiance
    /// and are applied to the light only where radiance is formed, with the new
    /// atmosphere. `None` when anything else differs (then [`StaticLuts::bake`]).
    pub fn relit(&self, atmosphere: &Atmosphere) -> Result<Option<Self>, AtmosError> {
        let lit = atmosphere.to_uniforms()?;
        if bytemuck::bytes_of(&unlit(&lit)) != bytemuck::bytes_of(&unlit(&self.atmosphere)) {
            return Ok(None);
        }
        Ok(Some(Self {
            atmosphere: lit,
            ..self.clone()
        }))
    }

    /// The tables as the bytes of a cache file: [`CACHE_MAGIC`], the atmosphere (its
    /// light zeroed: [`StaticLuts::relit`] gives any light), settings and orders they
    /// were baked for, each table's size, then the texels, all in this machine's byte
    /// order.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut bytes = CACHE_MAGIC.to_vec();
        bytes.extend_from_slice(bytemuck::bytes_of(&unlit(&self.atmosphere)));
        bytes.extend_from_slice(bytemuck::bytes_of(&self.settings));
        bytes.extend_from_slice(&self.multiple_scattering_orders.to_ne_bytes());
        for table in [&self.transmittance, &self.multiple_scattering] {
            bytes.extend_from_slice(&table.width.to_ne_bytes());
            bytes.extend_from_slice(&table.height.to_ne_bytes());
            bytes.extend_from_slice(&(table.texels.len() as u64).to_ne_bytes());
            bytes.extend_from_slice(bytemuck::cast_slice(&table.texels));
        }
        bytes
    }

    /// Tables read back from [`StaticLuts::to_bytes`] for `atmosphere` with `settings`:
    /// `None` unless the bytes are a whole set baked for this air and these settings by
    /// this format (another atmosphere, other settings or sizes, a truncated or foreign
    /// file, the other byte order); an error only for an invalid `atmosphere` or
    /// `settings`.
    pub fn from_bytes(
        bytes: &[u8],
        atmosphere: &Atmosphere,
        settings: &LutSettings,
    ) -> Result<Option<Self>, AtmosError> {
        let lit = atmosphere.to_uniforms()?;
        let uniforms = settings.to_uniforms()?;
        let Some(rest) = bytes.strip_prefix(CACHE_MAGIC.as_slice()) else {
            return Ok(None);
        };
        let air = unlit(&lit);
        let Some(rest) = rest.strip_prefix(bytemuck::bytes_of(&air)) else {
            return Ok(None);
        };
        let Some(rest) = rest.strip_prefix(bytemuck::bytes_of(&uniforms)) else {
            return Ok(None);
        };
        let orders = settings.multiple_scattering_orders;
        let Some(mut rest) = rest.strip_prefix(orders.to_ne_bytes().as_slice()) else {
            return Ok(None);
        };
        // Two tables, each its width, height and texel count, then the texels (their
        // sizes follow from the settings compared above and this format's version).
        let mut tables = Vec::with_capacity(2);
        for _ in 0..2 {
            let u32_at = |at: usize| -> Option<u32> {
                Some(u32::from_ne_bytes(rest.get(at..at + 4)?.try_into().ok()?))
            };
            let count = rest
                .get(8..16)
                .and_then(|b| b.try_into().ok())
                .map(u64::from_ne_bytes);
            let (Some(width), Some(height), Some(count)) = (u32_at(0), u32_at(4), count) else {
                return Ok(None);
            };
            if u64::from(width) * u64::from(height) != count {
                return Ok(None);
            }
            let Some(texels) = usize::try_from(count)
                .ok()
                .and_then(|n| n.checked_mul(16))
                .and_then(|bytes| rest.get(16..16 + bytes))
            else {
                return Ok(None);
            };
            tables.push(Lut2d {
                width,
                height,
                texels: bytemuck::pod_collect_to_vec(texels),
            });
            rest = &rest[16 + texels.len()..];
        }
        if !rest.is_empty() {
            return Ok(None);
        }
        let multiple_scattering = tables.pop().unwrap_or_default();
        let transmittance = tables.pop().unwrap_or_default();
        Ok(Some(Self {
            atmosphere: lit,
            settings: uniforms,
            multiple_scattering_orders: orders,
            transmittance,
            multiple_scattering,
        }))
    }

    /// The tables as the raymarch functions read them.
    pub fn bindings(&self) -> LutBindings<'_> {
        LutBindings {
            atmosphere: &self.atmosphere,
            settings: &self.settings,
            transmittance: &self.transmittance,
            multiple_scattering: &self.multiple_scattering,
        }
    }
}

/// The per-frame tables of a frame camera.
#[derive(Debug, Clone)]
pub struct FrameLuts {
    /// The camera they were baked for.
    pub camera: FrameCamera,
    /// Viewer radius (clamped to the atmosphere) and sun zenith cosine of the sky view.
    pub sky_view_r_mu_s: [f32; 2],
    /// Sky-view LUT.
    pub sky_view: Lut2d,
    /// Aerial-perspective volume.
    pub aerial_perspective: AerialPerspectiveVolume,
}

impl FrameLuts {
    /// Bakes the sky view and the aerial-perspective volume for `camera`.
    pub fn bake(luts: &StaticLuts, camera: &FrameCamera) -> Self {
        let bindings = luts.bindings();
        let r_mu_s = sky_view_r_mu_s(
            camera,
            luts.atmosphere.planet_radius,
            luts.atmosphere.top_radius,
        );
        Self {
            camera: *camera,
            sky_view_r_mu_s: r_mu_s,
            sky_view: bake_sky_view_lut(&bindings, r_mu_s[0], r_mu_s[1]),
            aerial_perspective: bake_aerial_perspective(&bindings, camera),
        }
    }
}

/// Radiance and transmittance of one pixel of `frame.camera`: the CPU twin of
/// `shade_pixel` in `shaders/atmos/lut_render.wgsl`.
pub fn shade_pixel(luts: &StaticLuts, frame: &FrameLuts, pixel: [u32; 2]) -> ScatteringSegment {
    let bindings = luts.bindings();
    let atmosphere = &luts.atmosphere;
    let settings = &luts.settings;
    let camera = &frame.camera;
    let direction = frame_view_direction(pixel, camera);
    let [r, mu, mu_s, nu] = view_cosines(camera, direction, atmosphere.planet_radius);
    if camera.max_distance >= UNLIMITED_DISTANCE {
        return unlimited_view_segment(&bindings, &frame.sky_view, r, mu, mu_s, nu);
    }
    // The segment ends at the ground if the ray meets it first (the volume's columns go
    // on through the ground, for the lookups' blend between columns).
    let segment = ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
    let distance = if segment[2] > 0.5 {
        camera.max_distance.min(segment[1])
    } else {
        camera.max_distance
    };
    if distance <= settings.aerial_perspective_range {
        let uv = [
            (pixel[0] as f32 + 0.5) / camera.width as f32,
            (pixel[1] as f32 + 0.5) / camera.height as f32,
        ];
        let [radiance, transmittance] =
            lookup_aerial_perspective(&frame.aerial_perspective, settings, uv, distance);
        return ScatteringSegment {
            radiance,
            transmittance,
        };
    }
    march_view_segment(
        &bindings,
        r,
        mu,
        mu_s,
        nu,
        camera.max_distance,
        settings.pixel_samples,
    )
}

/// Below the top of the atmosphere, within this band (m), the sky-view lookup is blended
/// linearly into the LUT march that takes over above the top, so radiance is continuous
/// as a camera crosses the top (the "painted shell" jump of a shell-entry march). Without it the step is
/// the sky-view LUT's interpolation error, 3.7 % mean (8.2 % max) for ±1 m. Only
/// viewers in the band (the top kilometre of a 100 km atmosphere) pay for both.
pub const TOP_BLEND_BAND: f32 = 1_000.0;

/// The whole view ray (no distance limit) seen from radius `r`: the sky-view lookup
/// inside the atmosphere, the LUT march above it, blended over [`TOP_BLEND_BAND`].
#[allow(clippy::too_many_arguments)]
pub fn unlimited_view_segment(
    bindings: &LutBindings<'_>,
    sky_view: &Lut2d,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
) -> ScatteringSegment {
    let atmosphere = bindings.atmosphere;
    let settings = bindings.settings;
    let march = || {
        march_view_segment(
            bindings,
            r,
            mu,
            mu_s,
            nu,
            UNLIMITED_DISTANCE,
            settings.pixel_samples,
        )
    };
    if r > atmosphere.top_radius {
        return march();
    }
    let lookup = lookup_sky_view(
        bindings,
        sky_view,
        r,
        mu,
        view_sun_cos_azimuth(mu, mu_s, nu),
    );
    let blend = (r - (atmosphere.top_radius - TOP_BLEND_BAND)) / TOP_BLEND_BAND;
    if blend <= 0.0 {
        return lookup;
    }
    let marched = march();
    let mix = |a: [f32; 3], b: [f32; 3]| std::array::from_fn(|i| a[i] + (b[i] - a[i]) * blend);
    ScatteringSegment {
        radiance: mix(lookup.radiance, marched.radiance),
        transmittance: mix(lookup.transmittance, marched.transmittance),
    }
}

/// How many sky-view LUTs [`PrecomputedSky`] keeps (one per viewer radius and sun
/// zenith cosine); the oldest is dropped beyond this.
pub const SKY_VIEW_CACHE_CAPACITY: usize = 64;

type SkyViewCache = Vec<([u32; 2], Arc<Lut2d>)>;

/// Rung 3 on the CPU: static LUTs baked at construction, sky-view LUTs baked by
/// [`PrecomputedSky::prepare`] (or on demand by [`SkyModel::evaluate`]) and cached per
/// (viewer radius, sun zenith cosine). For a few scattered queries from many viewpoints
/// (a dome, a hemisphere), [`super::MarchedPrecomputedSky`] reads the same tables
/// without baking a sky-view table.
#[derive(Debug)]
pub struct PrecomputedSky {
    luts: StaticLuts,
    sky_views: Mutex<SkyViewCache>,
}

impl PrecomputedSky {
    /// Validates and bakes the static tables.
    pub fn new(atmosphere: &Atmosphere, settings: &LutSettings) -> Result<Self, AtmosError> {
        Ok(Self {
            luts: StaticLuts::bake(atmosphere, settings)?,
            sky_views: Mutex::new(Vec::new()),
        })
    }

    /// The rung over tables already baked (e.g. [`StaticLuts::relit`] of another
    /// light's): no bake here.
    pub fn from_static_luts(luts: StaticLuts) -> Self {
        Self {
            luts,
            sky_views: Mutex::new(Vec::new()),
        }
    }

    /// The static tables.
    pub fn static_luts(&self) -> &StaticLuts {
        &self.luts
    }

    /// The per-frame part: the sky-view LUT for a viewer at `position` with the sun
    /// along `sun` (baked, or taken from the cache). Directions need not be unit.
    pub fn prepare(&self, position: DVec3, sun: DVec3) -> Arc<Lut2d> {
        let r = position.length();
        let mu_s = sun.normalize_or_zero().dot(position / r);
        self.sky_view_for(r as f32, mu_s as f32)
    }

    fn sky_view_for(&self, r: f32, mu_s: f32) -> Arc<Lut2d> {
        let a = &self.luts.atmosphere;
        let key_r = r.clamp(a.planet_radius, a.top_radius);
        let key_mu_s = mu_s.clamp(-1.0, 1.0);
        let key = [key_r.to_bits(), key_mu_s.to_bits()];
        if let Some((_, lut)) = self.lock_cache().iter().find(|(cached, _)| *cached == key) {
            return Arc::clone(lut);
        }
        let lut = Arc::new(bake_sky_view_lut(&self.luts.bindings(), key_r, key_mu_s));
        let mut cache = self.lock_cache();
        if cache.len() >= SKY_VIEW_CACHE_CAPACITY {
            cache.remove(0);
        }
        cache.push((key, Arc::clone(&lut)));
        lut
    }

    fn lock_cache(&self) -> std::sync::MutexGuard<'_, SkyViewCache> {
        // A panic while holding the lock leaves a valid Vec: keep using it.
        self.sky_views
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Whether `query` reads a sky-view LUT (an unlimited segment seen from inside the
    /// atmosphere).
    fn needs_sky_view(&self, query: &SkyQuery) -> bool {
        self.needs_sky_view_at(query, query.r())
    }

    fn needs_sky_view_at(&self, query: &SkyQuery, r: f64) -> bool {
        query.max_distance().is_infinite() && r as f32 <= self.luts.atmosphere.top_radius
    }

    /// The per-pixel part: a query answered with a sky-view LUT from
    /// [`PrecomputedSky::prepare`] for the query's viewer and sun (it is read only for
    /// unlimited segments seen from inside the atmosphere).
    pub fn evaluate_prepared(&self, sky_view: &Lut2d, query: &SkyQuery) -> SkySample {
        self.evaluate_prepared_at(sky_view, query, query.cosines())
    }

    /// [`Self::evaluate_prepared`] with the query's `[r, μ, μ_s, ν]` already computed.
    fn evaluate_prepared_at(
        &self,
        sky_view: &Lut2d,
        query: &SkyQuery,
        cosines: [f64; 4],
    ) -> SkySample {
        if !query.max_distance().is_infinite() {
            return self.marched_sample(cosines, query.max_distance());
        }
        let [r, mu, mu_s, nu] = cosines.map(|c| c as f32);
        let r = r.max(self.luts.atmosphere.planet_radius);
        sample(unlimited_view_segment(
            &self.luts.bindings(),
            sky_view,
            r,
            mu,
            mu_s,
            nu,
        ))
    }

    /// The segment of `[r, μ, μ_s, ν]` up to `max_distance` (m; infinite: the whole
    /// ray) marched through the static tables ([`march_view_segment`], `pixel_samples`
    /// steps), no sky-view table: this rung's answer for a finite segment, and
    /// [`super::MarchedPrecomputedSky`]'s for every query.
    pub(crate) fn marched_sample(&self, cosines: [f64; 4], max_distance: f64) -> SkySample {
        let [r, mu, mu_s, nu] = cosines.map(|c| c as f32);
        let r = r.max(self.luts.atmosphere.planet_radius);
        sample(march_view_segment(
            &self.luts.bindings(),
            r,
            mu,
            mu_s,
            nu,
            max_distance.min(f64::from(UNLIMITED_DISTANCE)) as f32,
            self.luts.settings.pixel_samples,
        ))
    }
}

/// A segment's f32 radiance and transmittance as a [`SkySample`].
fn sample(segment: ScatteringSegment) -> SkySample {
    SkySample {
        radiance: segment.radiance.map(f64::from),
        transmittance: segment.transmittance.map(f64::from),
    }
}

impl SkyModel for PrecomputedSky {
    fn label(&self) -> String {
        let s = &self.luts.settings;
        format!(
            "precomputed (T {}x{}, MS {}x{}, sky view {}x{}/{})",
            s.transmittance_width,
            s.transmittance_height,
            s.multiple_scattering_width,
            s.multiple_scattering_height,
            s.sky_view_width,
            s.sky_view_height,
            s.sky_view_samples
        )
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        if self.needs_sky_view(query) {
            let lut = self.sky_view_for(query.r() as f32, query.mu_s() as f32);
            self.evaluate_prepared(&lut, query)
        } else {
            self.evaluate_prepared(&Lut2d::default(), query)
        }
    }

    fn evaluate_batch(&self, queries: &[SkyQuery]) -> Vec<SkySample> {
        let Some(first) = queries.first() else {
            return Vec::new();
        };
        // one cache lookup for the queries seen from the first one's viewpoint (the
        // sky-view LUT depends only on the viewer's radius and the sun's zenith cosine)
        let key = |c: &[f64; 4]| [(c[0] as f32).to_bits(), (c[2] as f32).to_bits()];
        let first_cosines = first.cosines();
        let shared_key = key(&first_cosines);
        let shared = self.sky_view_for(first_cosines[0] as f32, first_cosines[2] as f32);
        queries
            .iter()
            .map(|query| {
                let cosines = query.cosines();
                if !self.needs_sky_view_at(query, cosines[0]) {
                    self.evaluate_prepared_at(&Lut2d::default(), query, cosines)
                } else if key(&cosines) == shared_key {
                    self.evaluate_prepared_at(&shared, query, cosines)
                } else {
                    self.evaluate(query)
                }
            })
            .collect()
    }
}
