//! Aerial-perspective volume (Hillaire 2020 §5.4): in-scattered radiance and
//! transmittance from the camera to each froxel of its view frustum, for geometry at a
//! finite distance. Slice k (of D) ends at (k + 1)·range/D; a virtual slice at distance 0
//! holds (0 radiance, transmittance 1), so lookups are exact at the camera. Each
//! froxel column is marched once, front to back, `steps_per_slice` uniform steps per
//! slice, from where it enters the atmosphere to where it leaves the top: a column
//! that meets the ground goes on through it in air at ground density, so the lookup's
//! blend of neighbouring columns stays right at a low camera's horizon (see
//! [`aerial_perspective_column`]).
//!
//! Layout: planar like the GPU's two 3-D textures — froxel k = x + W·(y + H·z) holds
//! its radiance (rgb, 1) at index k and its transmittance (rgb, 1) at W·H·D + k. Twin of
//! `shaders/atmos/lut_aerial_perspective.wgsl` (bake) and `lut_sampling.wgsl` (lookup).

use crate::frame::FrameCamera;
use crate::geometry::ray_sphere_intersect;
use crate::phase::{cornette_shanks_phase, rayleigh_phase};

use super::parameterization::bilinear_footprint;
use super::raymarch::{
    LutBindings, empty_march, integrate_scattering_step, medium_at_altitude, point_along_ray,
    ray_segment_in_atmosphere, scattering_source,
};
use super::{LutSettingsUniform, blend_footprint};

/// The baked volume.
#[derive(Debug, Clone, PartialEq)]
pub struct AerialPerspectiveVolume {
    /// Froxels (x, y, depth).
    pub size: [u32; 3],
    /// The radiance volume, then the transmittance volume (`W·H·D` texels each).
    pub texels: Vec<[f32; 4]>,
}

/// Unit view direction through screen coordinate `uv` ∈ [0, 1]² (x right, y down),
/// the continuous form of [`crate::frame::frame_view_direction`].
pub fn froxel_view_direction(uv: [f32; 2], camera: &FrameCamera) -> [f32; 3] {
    let aspect = camera.width as f32 / camera.height as f32;
    let ndc_x = (2.0 * uv[0] - 1.0) * camera.tan_half_fov_y * aspect;
    let ndc_y = (1.0 - 2.0 * uv[1]) * camera.tan_half_fov_y;
    let d: [f32; 3] =
        std::array::from_fn(|i| camera.forward[i] + ndc_x * camera.right[i] + ndc_y * camera.up[i]);
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|c| c / length)
}

/// (r, μ, μ_s, ν) of a view direction from the camera (r clamped to ≥ planet_radius).
pub fn view_cosines(camera: &FrameCamera, direction: [f32; 3], planet_radius: f32) -> [f32; 4] {
    let p = camera.position;
    let length = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let up = p.map(|c| c / length);
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    [
        length.max(planet_radius),
        dot(direction, up).clamp(-1.0, 1.0),
        dot(camera.sun, up).clamp(-1.0, 1.0),
        dot(direction, camera.sun).clamp(-1.0, 1.0),
    ]
}

/// Marches one froxel column (x, y) and returns its `2·depth` texels, front to back.
pub fn aerial_perspective_column(
    bindings: &LutBindings<'_>,
    camera: &FrameCamera,
    x: u32,
    y: u32,
) -> Vec<[f32; 4]> {
    let atmosphere = bindings.atmosphere;
    let s = bindings.settings;
    let uv = [
        (x as f32 + 0.5) / s.aerial_perspective_width as f32,
        (y as f32 + 0.5) / s.aerial_perspective_height as f32,
    ];
    let direction = froxel_view_direction(uv, camera);
    let [r, mu, mu_s, nu] = view_cosines(camera, direction, atmosphere.planet_radius);
    let segment = ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
    // A column that meets the ground goes on through it (in air at ground density) to
    // the top. Nothing behind the ground is looked up for its own sake, but a lookup
    // blends neighbouring columns: near the horizon of a low camera, one column meets
    // the ground a few kilometres out while its neighbour sees a distant mountain, and
    // a column stopped at the ground would hold that mountain's haze at a few km's.
    let end = if segment[2] > 0.5 {
        ray_sphere_intersect(r, mu, atmosphere.top_radius)[1]
    } else {
        segment[1]
    };
    let rayleigh_phase_value = rayleigh_phase(nu);
    let mie_phase_value = cornette_shanks_phase(nu, atmosphere.mie_g);
    let depth = s.aerial_perspective_depth;
    let steps = s.aerial_perspective_steps_per_slice;
    let step_length = s.aerial_perspective_range / (depth * steps) as f32;
    let mut march = empty_march();
    let mut out = Vec::with_capacity(2 * depth as usize);
    for slice in 0..depth {
        for step in 0..steps {
            let a = (slice * steps + step) as f32 * step_length;
            let lo = a.max(segment[0]);
            let hi = (a + step_length).min(end);
            if hi > lo {
                let dt = hi - lo;
                let [r_below, mu_t, mu_s_t] = point_along_ray(r, mu, mu_s, nu, lo + 0.5 * dt);
                let r_t = r_below.max(atmosphere.planet_radius);
                let medium = medium_at_altitude(atmosphere, r_t - atmosphere.planet_radius);
                let source = scattering_source(
                    bindings,
                    &medium,
                    r_t,
                    mu_t,
                    mu_s_t,
                    nu,
                    rayleigh_phase_value,
                    mie_phase_value,
                );
                march = integrate_scattering_step(march, source, medium.extinction, dt);
            }
        }
        let [radiance, throughput] = [march.radiance, march.transmittance];
        out.push([
            radiance[0] * atmosphere.sun_irradiance[0],
            radiance[1] * atmosphere.sun_irradiance[1],
            radiance[2] * atmosphere.sun_irradiance[2],
            1.0,
        ]);
        out.push([throughput[0], throughput[1], throughput[2], 1.0]);
    }
    out
}

/// Bakes the volume for a frame camera (threaded over columns).
pub fn bake_aerial_perspective(
    bindings: &LutBindings<'_>,
    camera: &FrameCamera,
) -> AerialPerspectiveVolume {
    let s = bindings.settings;
    let (w, h, d) = (
        s.aerial_perspective_width,
        s.aerial_perspective_height,
        s.aerial_perspective_depth,
    );
    let columns = (w * h) as usize;
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(columns);
    let chunk = columns.div_ceil(threads);
    let mut per_column: Vec<Vec<[f32; 4]>> = vec![Vec::new(); columns];
    std::thread::scope(|scope| {
        for (c, slot) in per_column.chunks_mut(chunk).enumerate() {
            scope.spawn(move || {
                for (i, column) in slot.iter_mut().enumerate() {
                    let index = (c * chunk + i) as u32;
                    *column = aerial_perspective_column(bindings, camera, index % w, index / w);
                }
            });
        }
    });
    let volume = columns * d as usize;
    let mut texels = vec![[0.0f32; 4]; 2 * volume];
    for (column, values) in per_column.iter().enumerate() {
        for z in 0..d as usize {
            let k = column + columns * z;
            texels[k] = values[2 * z];
            texels[volume + k] = values[2 * z + 1];
        }
    }
    AerialPerspectiveVolume {
        size: [w, h, d],
        texels,
    }
}

/// Trilinear lookup at screen coordinate `uv` and `distance` (m, ≤ the range):
/// `[radiance, transmittance]`.
pub fn lookup_aerial_perspective(
    volume: &AerialPerspectiveVolume,
    settings: &LutSettingsUniform,
    uv: [f32; 2],
    distance: f32,
) -> [[f32; 3]; 2] {
    let [w, h, d] = volume.size;
    let f = bilinear_footprint(uv, w, h, 0, h - 1);
    let slice =
        (distance / settings.aerial_perspective_range * d as f32 - 1.0).clamp(-1.0, (d - 1) as f32);
    let z0 = slice.floor();
    let fz = slice - z0;
    let read = |z: f32, which: usize| -> [f32; 3] {
        if z < 0.0 {
            // The virtual slice at the camera.
            return if which == 0 { [0.0; 3] } else { [1.0; 3] };
        }
        let z = z as u32;
        let offset = which * (w * h * d) as usize;
        blend_footprint(&volume.texels, &f, |x, y| {
            offset + (x + w * (y + h * z)) as usize
        })
    };
    let z1 = (z0 + 1.0).min((d - 1) as f32);
    std::array::from_fn(|which| {
        let near = read(z0, which);
        let far = read(z1, which);
        std::array::from_fn(|i| near[i] * (1.0 - fz) + far[i] * fz)
    })
}
