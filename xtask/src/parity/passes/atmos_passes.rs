//! Parity passes of `atmos::lut` (the precomputed rung): each LUT baked by the CPU
//! f32 twin and by the GPU compute pass, at the small test sizes (lavapipe).
//!
//! There is no separate f64 bake: the "reference" column is the CPU f32 bake itself
//! (its discretisation error against the f64 reference rung is measured by the
//! trade-off study and `crates/atmos/tests/luts.rs`, not here), so these cases measure
//! GPU-vs-CPU drift only: they are `Audit::CPU_IS_REFERENCE`, their CPU rows are
//! reported as "reference = this side", never as a pass. The
//! tolerances come from what each texel accumulates: tens to hundreds of exp/sqrt
//! evaluations (16 ULP measured on lavapipe) and bilinear lookups whose weights move
//! with the coordinates' rounding (the parameterisation cases bound those).

use super::*;
use atmos::Atmosphere;
use atmos::frame::FrameCamera;
use atmos::lut::{FrameLuts, LutSettings, StaticLuts, ViewTransmittance};

fn settings() -> LutSettings {
    LutSettings::small()
}

/// The small settings with a radiance-only sky view (transmittance per pixel).
fn radiance_only_settings() -> LutSettings {
    LutSettings {
        view_transmittance: ViewTransmittance::TransmittanceLut,
        ..LutSettings::small()
    }
}

fn camera() -> FrameCamera {
    FrameCamera::look_at(
        glam::DVec3::new(0.0, 0.0, 6_360_000.0 + 500.0),
        glam::DVec3::new(1.0, 0.2, 0.05),
        glam::DVec3::Z,
        1.2,
        16,
        12,
        glam::DVec3::new(0.6, 0.3, 0.35),
        Some(10_000.0),
    )
    .expect("a valid camera")
}

fn cpu_luts() -> Result<(StaticLuts, FrameLuts), String> {
    cpu_luts_with(&settings())
}

fn cpu_luts_with(settings: &LutSettings) -> Result<(StaticLuts, FrameLuts), String> {
    let luts = StaticLuts::bake(&Atmosphere::earth(), settings).map_err(|e| e.to_string())?;
    let frame = FrameLuts::bake(&luts, &camera());
    Ok((luts, frame))
}

fn as_pass(texels: &[[f32; 4]]) -> PassCpu {
    let values: Vec<f32> = bytemuck::cast_slice(texels).to_vec();
    PassCpu {
        inputs: texels.len(),
        reference: values.iter().map(|&v| f64::from(v)).collect(),
        bounds: None,
        cpu: values,
    }
}

/// The multiple-scattering table (six planar layers: Ψ, then five moments) with a
/// bound of `MOMENT_RELATIVE` × the same texel's Ψ on the moment layers, whose values
/// cancel (their error scales with Ψ, not with themselves).
fn moments_pass(texels: &[[f32; 4]]) -> PassCpu {
    const MOMENT_RELATIVE: f64 = 2e-4;
    let layer =
        texels.len() / atmos::lut::multiple_scattering_moments::MULTIPLE_SCATTERING_LAYERS as usize;
    let mut pass = as_pass(texels);
    let bounds = texels
        .iter()
        .enumerate()
        .flat_map(|(i, _)| {
            let mean = texels[i % layer];
            (0..4).map(move |c| {
                if i < layer || c == 3 {
                    0.0
                } else {
                    MOMENT_RELATIVE * f64::from(mean[c]).abs()
                }
            })
        })
        .collect();
    pass.bounds = Some(bounds);
    pass
}

#[derive(Clone, Copy)]
enum Which {
    Transmittance,
    MultipleScattering,
    SkyView,
    AerialPerspective,
}

fn gpu_bake(gpu: &skyscape_harness::GpuContext, which: Which) -> Result<Vec<f32>, String> {
    gpu_bake_with(gpu, which, &settings())
}

fn gpu_bake_with(
    gpu: &skyscape_harness::GpuContext,
    which: Which,
    settings: &LutSettings,
) -> Result<Vec<f32>, String> {
    let luts = atmos::gpu::AtmosphereLuts::new(&gpu.device, &Atmosphere::earth(), settings)
        .map_err(|e| e.to_string())?;
    luts.prepare(&gpu.queue, &camera());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    luts.encode_static_luts(&mut encoder, None);
    luts.encode_frame_luts(&mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    // Texture readbacks are layer-major, the CPU twin's planar layout.
    let textures = match which {
        Which::Transmittance => vec![luts.transmittance_texture()],
        Which::MultipleScattering => vec![luts.multiple_scattering_texture()],
        Which::SkyView => vec![luts.sky_view_texture()],
        Which::AerialPerspective => vec![
            luts.aerial_perspective_radiance_texture(),
            luts.aerial_perspective_transmittance_texture(),
        ],
    };
    let mut values = Vec::new();
    for texture in textures {
        let bytes =
            skyscape_harness::read_texture(gpu, "atmos LUT", texture).map_err(|e| e.to_string())?;
        values.extend_from_slice(bytemuck::cast_slice::<u8, f32>(&bytes));
    }
    Ok(values)
}

/// A 20×12 frame from 300 m looking at the horizon (sky and ground rows), with no
/// distance limit: every pixel goes through the sky-view lookup.
fn frame_camera() -> FrameCamera {
    FrameCamera::look_at(
        glam::DVec3::new(0.0, 0.0, 6_360_000.0 + 300.0),
        glam::DVec3::new(0.3, 1.0, 0.02),
        glam::DVec3::Z,
        1.4,
        20,
        12,
        glam::DVec3::new(0.2, 0.5, 0.3),
        None,
    )
    .expect("a valid camera")
}

/// `shade_pixel` over the frame: radiance, then transmittance (RGBA each).
fn frame_cpu(settings: &LutSettings) -> Result<PassCpu, String> {
    let luts = StaticLuts::bake(&Atmosphere::earth(), settings).map_err(|e| e.to_string())?;
    let camera = frame_camera();
    let frame = FrameLuts::bake(&luts, &camera);
    let pixels: Vec<_> = (0..camera.height)
        .flat_map(|y| (0..camera.width).map(move |x| [x, y]))
        .map(|pixel| atmos::lut::precomputed_sky::shade_pixel(&luts, &frame, pixel))
        .collect();
    let texels: Vec<[f32; 4]> = pixels
        .iter()
        .map(|s| s.radiance)
        .chain(pixels.iter().map(|s| s.transmittance))
        .map(|[r, g, b]| [r, g, b, 1.0])
        .collect();
    Ok(as_pass(&texels))
}

/// The precomputed renderer's whole frame (LUT bakes and the per-pixel pass).
fn frame_gpu(
    gpu: &skyscape_harness::GpuContext,
    settings: LutSettings,
) -> Result<Vec<f32>, String> {
    let camera = frame_camera();
    let mut renderer = atmos::gpu::precomputed::PrecomputedRenderer::new(
        &gpu.device,
        &Atmosphere::earth(),
        settings,
    )
    .map_err(|e| e.to_string())?;
    let output = atmos::gpu::FrameOutput::new(&gpu.device, camera.width, camera.height)
        .map_err(|e| e.to_string())?;
    renderer
        .prepare(&gpu.queue, &camera, &output)
        .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    renderer
        .encode(&mut encoder, None)
        .map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let mut values = Vec::new();
    for texture in [output.radiance(), output.transmittance()] {
        let read = skyscape_harness::read_texture(gpu, "atmos frame", texture)
            .map_err(|e| e.to_string())?;
        values.extend_from_slice(bytemuck::cast_slice::<u8, f32>(&read));
    }
    Ok(values)
}

/// The pass cases of the precomputed rung, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "atmos::lut transmittance bake (64x16)",
            cpu: || {
                let mut pass = as_pass(&cpu_luts()?.0.transmittance.texels);
                pass.bounds = Some(transmittance_texel_bounds(&settings()));
                Ok(pass)
            },
            gpu: |gpu| gpu_bake(gpu, Which::Transmittance),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-6,
                rel: 2e-5,
                ulp: 0.0,
                bound: None,
                why: "40 log-linear steps (3 exp each, 16 ULP) summed, then exp of an \
                      optical depth ≤ ~40 (3 + 2τ ULP → ≤ 1e-5 relative); 2e-5 relative, \
                      1e-6 absolute where the grazing texels underflow towards 0; plus the \
                      texel's (r, μ) moved by twice transmittance_lut_r_mu's forward bound \
                      (either side may err by it: WGSL's sqrt, division and fused \
                      multiply-adds round differently), through the f64 column's slope, \
                      steep at the grazing texels (H100: 9.0e-4 relative there)",
            },
        },
        PassCase {
            name: "atmos::lut multiple-scattering bake (16x16)",
            cpu: || Ok(moments_pass(&cpu_luts()?.0.multiple_scattering.texels)),
            gpu: |gpu| gpu_bake(gpu, Which::MultipleScattering),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-9,
                rel: 2e-4,
                ulp: 0.0,
                bound: None,
                why: "orders 1…4's field summed; each 64 directions × 20 steps with a LUT \
                      lookup (transmittance, then the previous order) whose bilinear weights \
                      move with the uv rounding (≤ 1e-6 of a texel), the phase functions of \
                      ν (cos of the azimuth, order 2) and the planet-shadow test, which may \
                      flip for a sample on the terminator: 2e-4 relative on sums of ~1300 \
                      positive terms per order. The moment layers (d, A) are differences of \
                      such sums: 2e-4 of the texel's mean Ψ (a per-element bound)",
            },
        },
        PassCase {
            name: "atmos::lut sky-view bake (48x28)",
            cpu: || {
                let (luts, frame) = cpu_luts()?;
                let mut pass = as_pass(&frame.sky_view.texels);
                pass.bounds = Some(sky_view_transmittance_bounds(&luts, &frame));
                Ok(pass)
            },
            gpu: |gpu| gpu_bake(gpu, Which::SkyView),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "texel directions through cos/atan2 (sky_view_lut_direction case), 30 \
                      steps each reading two LUTs and the phase functions; near the horizon \
                      the path length changes fast with μ: 5e-4 relative. The transmittance \
                      layer (transmittance_to_boundary: one lookup, or for ground rays the \
                      ratio of two at the ground point d(μ) away) also moves with the \
                      texel's μ, whose slope is unbounded at the ground's tangent: plus the \
                      CPU twin's spread over μ ± 2× the sky_view_lut_direction bound and \
                      the viewer's r ± 1 ULP (H100 without it: 3.6e-2 relative)",
            },
        },
        PassCase {
            name: "atmos::lut sky-view radiance (48x28)",
            cpu: || {
                Ok(as_pass(
                    &cpu_luts_with(&radiance_only_settings())?.1.sky_view.texels,
                ))
            },
            gpu: |gpu| gpu_bake_with(gpu, Which::SkyView, &radiance_only_settings()),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "ViewTransmittance::TransmittanceLut: one entry per texel, the same \
                      radiance march as the full sky view (its budget)",
            },
        },
        PassCase {
            name: "atmos::lut precomputed frame (20x12)",
            cpu: || frame_cpu(&settings()),
            gpu: |gpu| frame_gpu(gpu, settings()),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "shade_pixel: the frame's view directions (normalize, dot), then a \
                      bilinear sky-view lookup of the bakes above (their 5e-4 budget) whose \
                      weights move with the uv rounding (sky_view_lut_uv case)",
            },
        },
        PassCase {
            name: "atmos::lut frame, T per pixel (20x12)",
            cpu: || frame_cpu(&radiance_only_settings()),
            gpu: |gpu| frame_gpu(gpu, radiance_only_settings()),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "ViewTransmittance::TransmittanceLut: the same radiance lookup; the \
                      transmittance per pixel from one or two transmittance lookups and \
                      their ratio (the transmittance bake's 2e-5 each)",
            },
        },
        PassCase {
            name: "atmos::lut aerial-perspective bake (8x8x16)",
            cpu: || Ok(as_pass(&cpu_luts()?.1.aerial_perspective.texels)),
            gpu: |gpu| gpu_bake(gpu, Which::AerialPerspective),
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "froxel directions (normalize, dot) then 32 steps per column reading two \
                      LUTs: the sky-view budget",
            },
        },
    ]
}

/// exp(−τ) per channel of the f64 column from (r, μ) to the top: the bake's scheme
/// (`transmittance_samples` uniform steps, log-linear exponentials, trapezoid ozone)
/// in f64, for the bake's sensitivity to its texel coordinates.
fn transmittance_column_f64(atmosphere: &Atmosphere, samples: u32, r: f64, mu: f64) -> [f64; 3] {
    use atmos::geometry::{altitude_along_ray, ray_sphere_intersect};
    use atmos::lut::reference::exponential_step_integral;
    use atmos::twins::tent_density;
    let a = atmosphere;
    let length = ray_sphere_intersect(r, mu, a.top_radius)[1].max(0.0);
    let dt = length / f64::from(samples);
    let (mut rayleigh, mut mie, mut ozone) = (0.0, 0.0, 0.0);
    let mut previous = altitude_along_ray(r, mu, 0.0, a.planet_radius);
    for i in 0..samples {
        let altitude = altitude_along_ray(r, mu, f64::from(i + 1) * dt, a.planet_radius);
        rayleigh += exponential_step_integral(
            previous / a.rayleigh_scale_height,
            altitude / a.rayleigh_scale_height,
            dt,
        );
        mie += exponential_step_integral(
            previous / a.mie_scale_height,
            altitude / a.mie_scale_height,
            dt,
        );
        ozone += 0.5
            * dt
            * (tent_density(previous, a.ozone_center_altitude, a.ozone_half_width)
                + tent_density(altitude, a.ozone_center_altitude, a.ozone_half_width));
        previous = altitude;
    }
    std::array::from_fn(|c| {
        (-(a.rayleigh_scattering[c] * rayleigh
            + a.mie_extinction[c] * mie
            + a.ozone_absorption[c] * ozone))
            .exp()
    })
}

/// Per texel and channel: how far the transmittance moves when the texel's (r, μ)
/// move by twice `transmittance_lut_r_mu`'s forward bound (the CPU twin and the GPU
/// may each err by it, in opposite directions). Alpha (1) gets 0.
fn transmittance_texel_bounds(settings: &LutSettings) -> Vec<f64> {
    let [width, height] = settings.transmittance_size;
    let earth = Atmosphere::earth();
    let samples = settings.transmittance_samples;
    let mut bounds = Vec::with_capacity((width * height * 4) as usize);
    for y in 0..height {
        for x in 0..width {
            let uv = [
                (f64::from(x) + 0.5) / f64::from(width),
                (f64::from(y) + 0.5) / f64::from(height),
            ];
            let [r, mu] = atmos::lut::reference::transmittance_lut_r_mu(
                uv,
                earth.planet_radius,
                earth.top_radius,
                width,
                height,
            );
            let [dr, dmu] = crate::parity::cases::transmittance_r_mu_error(uv, width, height);
            let centre = transmittance_column_f64(&earth, samples, r, mu);
            let mut spread = [0.0f64; 3];
            for (sr, smu) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                let moved = transmittance_column_f64(
                    &earth,
                    samples,
                    r + sr * 2.0 * dr,
                    (mu + smu * 2.0 * dmu).clamp(-1.0, 1.0),
                );
                for c in 0..3 {
                    spread[c] = spread[c].max((moved[c] - centre[c]).abs());
                }
            }
            bounds.extend([spread[0], spread[1], spread[2], 0.0]);
        }
    }
    bounds
}

/// Per element of the sky-view bake: 0 on the radiance layer (its 5e-4 budget), and on
/// the transmittance layer the CPU twin's spread of `transmittance_to_boundary` when
/// the texel's direction moves by twice the `sky_view_lut_direction` case's bound
/// (512 ULP of the horizon angle and 64 ULP of π through the mapping, whose slope is
/// ≤ 1) and the viewer's radius by one ULP (its √ rounds either way). Near the ground's
/// tangent the ground distance d(μ) has an unbounded slope: a shift within rounding
/// moves the ground point by kilometres (or switches sky ↔ ground), which the ratio of
/// two lookups turns into a relative change of percent.
fn sky_view_transmittance_bounds(luts: &StaticLuts, frame: &FrameLuts) -> Vec<f64> {
    use atmos::lut::parameterization::sky_view_lut_direction;
    use atmos::lut::reference::horizon_zenith_angle;
    use atmos::lut::transmittance_lut::transmittance_to_boundary;
    let bindings = luts.bindings();
    let settings = &luts.settings;
    let (width, height) = (settings.sky_view_width, settings.sky_view_height);
    let planet_radius = luts.atmosphere.planet_radius;
    let [r, _] = frame.sky_view_r_mu_s;
    let layer = (width * height) as usize;
    let mut bounds = vec![0.0; frame.sky_view.texels.len() * 4];
    if frame.sky_view.texels.len() < 2 * layer {
        return bounds;
    }
    let horizon = horizon_zenith_angle(f64::from(r), f64::from(planet_radius));
    let ulp = crate::parity::compare::ulp_f32;
    let d_theta = 512.0 * ulp(horizon) + 64.0 * ulp(std::f64::consts::PI);
    let radii = [
        f32::from_bits(r.to_bits() - 1),
        r,
        f32::from_bits(r.to_bits() + 1),
    ];
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            let centre = frame.sky_view.texels[layer + i];
            let uv = [
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / height as f32,
            ];
            let mut spread = [0.0f64; 3];
            for radius in radii {
                let [mu, _] = sky_view_lut_direction(uv, radius, planet_radius, width, height);
                // sin θ·δθ moves μ by at most δθ.
                for k in -8..=8 {
                    let moved = (f64::from(mu) + 2.0 * d_theta * f64::from(k) / 8.0)
                        .clamp(-1.0, 1.0) as f32;
                    let t = transmittance_to_boundary(&bindings, radius, moved);
                    for c in 0..3 {
                        spread[c] = spread[c].max((f64::from(t[c]) - f64::from(centre[c])).abs());
                    }
                }
            }
            for c in 0..3 {
                bounds[(layer + i) * 4 + c] = spread[c];
            }
        }
    }
    bounds
}
