//! Presents a frame of sky radiance from any rung of the atmos ladder: adds the sun
//! disc seen through the atmosphere, tone-maps and encodes RGBA8. Twin of
//! `shaders/render/present.wgsl`. The ground surface's own radiance is terrain
//! shading's job; here the ground shows the atmosphere between it and the camera.

use atmos::Atmosphere;
use atmos::frame::{FrameCamera, frame_view_direction};
use atmos::geometry::ray_sphere_intersect;
use atmos::ladder::{SkyModel, SkyQuery};

use crate::RenderError;
use crate::tonemap::{DisplayTransform, display_transform, pack_rgba8, quantize_srgb8};

/// Per-frame display constants; layout identical to WGSL `PresentParameters`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PresentParameters {
    /// Radiance of the sun disc above the atmosphere (irradiance / solid angle).
    pub sun_disc_radiance: [f32; 3],
    /// cos(sun angular radius).
    pub cos_sun_radius: f32,
    /// Planet radius (m).
    pub planet_radius: f32,
    /// Exposure before the display transform.
    pub exposure: f32,
    /// Dither seed.
    pub dither_seed: u32,
    /// [`DisplayTransform::code`].
    pub display_transform: u32,
}

impl PresentParameters {
    /// Display constants for `atmosphere` (validated) with `exposure` > 0, displayed
    /// by the default [`DisplayTransform`] ([`Self::with_display_transform`] chooses).
    pub fn new(
        atmosphere: &Atmosphere,
        exposure: f32,
        dither_seed: u32,
    ) -> Result<Self, RenderError> {
        atmosphere.validate().map_err(RenderError::Atmosphere)?;
        crate::error::check("exposure", exposure, exposure > 0.0, "must be > 0")?;
        let radius = atmosphere.sun_angular_radius;
        let solid_angle = 2.0 * std::f64::consts::PI * (1.0 - radius.cos());
        Ok(Self {
            sun_disc_radiance: atmosphere.sun_irradiance.map(|e| (e / solid_angle) as f32),
            cos_sun_radius: radius.cos() as f32,
            planet_radius: atmosphere.planet_radius as f32,
            exposure,
            dither_seed,
            display_transform: DisplayTransform::default().code(),
        })
    }

    /// The same constants displayed by `transform`.
    pub fn with_display_transform(self, transform: DisplayTransform) -> Self {
        Self {
            display_transform: transform.code(),
            ..self
        }
    }
}

/// Radiance reaching the pixel: the atmosphere's in-scatter, plus the sun disc through
/// the segment's transmittance where the view ray sees the disc and not the ground.
pub fn present_radiance(
    view: [f32; 3],
    radiance: [f32; 3],
    transmittance: [f32; 3],
    camera: &FrameCamera,
    present: &PresentParameters,
) -> [f32; 3] {
    let p = camera.position;
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let mu = (view[0] * p[0] + view[1] * p[1] + view[2] * p[2]) / r;
    let ground = ray_sphere_intersect(r, mu, present.planet_radius);
    let s = camera.sun;
    let cos_sun = view[0] * s[0] + view[1] * s[1] + view[2] * s[2];
    if ground[0] < 0.0 && cos_sun >= present.cos_sun_radius {
        return std::array::from_fn(|i| {
            radiance[i] + transmittance[i] * present.sun_disc_radiance[i]
        });
    }
    radiance
}

/// One presented pixel, packed RGBA8 (the CPU twin of `present_main`).
pub fn present_pixel(
    pixel: [u32; 2],
    radiance: [f32; 3],
    transmittance: [f32; 3],
    camera: &FrameCamera,
    present: &PresentParameters,
) -> u32 {
    let view = frame_view_direction(pixel, camera);
    let light = present_radiance(view, radiance, transmittance, camera, present);
    let transform = DisplayTransform::from_code(present.display_transform);
    let display = display_transform(light, present.exposure, transform);
    pack_rgba8(quantize_srgb8(display, pixel, present.dither_seed))
}

/// Renders a frame with any [`SkyModel`] on the CPU (all cores), presented as RGBA8.
/// Returns the pixels and the linear radiance/transmittance per pixel.
pub fn render_model_cpu(
    model: &(dyn SkyModel + Sync),
    planet_radius: f64,
    camera: &FrameCamera,
    present: &PresentParameters,
) -> Result<Vec<u32>, RenderError> {
    let (width, height) = (camera.width, camera.height);
    let position = glam::DVec3::from_array(camera.position.map(f64::from));
    let sun = glam::DVec3::from_array(camera.sun.map(f64::from)).normalize();
    let max_distance = if camera.max_distance >= atmos::frame::UNLIMITED_DISTANCE {
        f64::INFINITY
    } else {
        f64::from(camera.max_distance)
    };
    let mut pixels = vec![0u32; camera.pixel_count()];
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let rows_per_thread = (height as usize).div_ceil(threads).max(1);
    let failure = std::sync::Mutex::new(None);
    std::thread::scope(|scope| {
        for (chunk_index, chunk) in pixels
            .chunks_mut(rows_per_thread * width as usize)
            .enumerate()
        {
            let failure = &failure;
            scope.spawn(move || {
                for (i, out) in chunk.iter_mut().enumerate() {
                    let index = chunk_index * rows_per_thread * width as usize + i;
                    let pixel = [
                        (index % width as usize) as u32,
                        (index / width as usize) as u32,
                    ];
                    let view =
                        glam::DVec3::from_array(frame_view_direction(pixel, camera).map(f64::from));
                    let query = match SkyQuery::with_max_distance(
                        planet_radius,
                        position,
                        view.normalize(),
                        sun,
                        max_distance,
                    ) {
                        Ok(q) => q,
                        Err(e) => {
                            *failure.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                            return;
                        }
                    };
                    let sample = model.evaluate(&query);
                    *out = present_pixel(
                        pixel,
                        sample.radiance.map(|v| v as f32),
                        sample.transmittance.map(|v| v as f32),
                        camera,
                        present,
                    );
                }
            });
        }
    });
    match failure.into_inner().unwrap_or_else(|p| p.into_inner()) {
        Some(error) => Err(RenderError::Atmosphere(error)),
        None => Ok(pixels),
    }
}
