//! Parity passes of `cloudlight`'s view march through a procedural cloud shell (Schneider 2015):
//! an image (64×48, 112×90) by `cloudlight::gpu::MarchShellPass` (`march_shell_pass.wgsl`, on
//! the stage its `new` chooses: `march_shell_fragment`, or `march_shell_main` where fragment
//! shaders cannot write storage), per pixel (radiance r, g, b, transmittance), of the cumulus layer
//! seen from the ground and of the shipped `stratocumulus` deck seen from above.
//! Reference: the generic march at f64 on the `CloudShell` (each pixel as
//! `march::render_image::<f64>` marches it: `march_view_at_pixel` along `pixel_direction`);
//! cpu: `render_image::<f32>` (the WGSL's twin); both then faded by the shell's horizon
//! fade at their depth, as the GPU pass does (`march::faded`). The bound re-marches each
//! pixel at f64 through two envelopes of the shell (four densities per sample), on two
//! threads.

use super::*;
use cloudlight::cone::ConeWeights;
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchResult, MarchSettings, Octaves, PinholeCamera,
    faded, march_view_at_pixel, pixel_direction, render_image,
};
use cloudlight::{CloudShell, DensityField, RaySpans, ShellSettings};

const U: f64 = super::super::compare::UNIT_ROUNDOFF;
/// Pixels of the cumulus image (3,072: 12,288 outputs; its raw cone's seven light samples
/// per step make each pixel's bound the dearest) and of the deck's (10,080).
const SIZES: [[u32; 2]; 2] = [[64, 48], [112, 90]];
/// The longest distance from a sample's ray origin to any sample (view or light), metres:
/// checked against every view span and the light chords of the case.
const T_MAX: f64 = 100_000.0;

/// The pass cases of this file, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "cloudlight::march_shell_pass (cumulus from the ground, sun 30°, raw cone 150 m \
                   spread 0.2, 2 octaves, Bayer, 6 steps, 64x48)",
            cpu: || march_shell_cpu(0),
            gpu: |gpu| march_shell_gpu(gpu, 0),
            audit: Audit::INDEPENDENT,
            tolerance: TOLERANCE_CUMULUS,
        },
        PassCase {
            name: "cloudlight::march_shell_pass (stratocumulus deck from above, sun 10°, full \
                   light march 4, 3 octaves, ambient 1, no jitter, 8 steps, 112x90)",
            cpu: || march_shell_cpu(1),
            gpu: |gpu| march_shell_gpu(gpu, 1),
            audit: Audit::INDEPENDENT,
            tolerance: TOLERANCE_DECK,
        },
    ]
}

/// The tolerance of both cases, with the case's measured figures in its `why`.
macro_rules! tolerance {
    ($measured:literal) => {
        Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: None,
            why: concat!(
                "per pixel, the march's forward error at Earth scale from the f64 march's own \
                 sensitivity (pass bounds are per output, so the tightness audit does not see \
                 them; lavapipe: ",
                $measured,
                "): twice the larger change of the f64 image under two envelopes of the \
                 shell, the view ray's densities moved up and the light and ambient rays' \
                 down, and the reverse (the sun and ambient terms fall as the light's optical \
                 depth grows; powder, which breaks that, is off): each density the extreme \
                 over the corners of ±δr radially, δr = 12u(|p| + t_max) (f32 positions at \
                 |p| ≈ 6.36e6 m, t_max 100 km: ~4.6 m of height fraction and noise \
                 coordinate), and ±e along its ray, e its span ends' f32 error (the sphere \
                 root's: |δD| ≤ 8u·b² + 4u·r² + 4u|c| through √D, plus 4u|b| + 12u·t; for a \
                 ray from a sample plus the root's change when the origin moves δr + e_view \
                 radially: |μ|δ and 2r(1 − μ²)δ through √D), scaled by 1 ± the step's \
                 relative error (2e/L on the view ray, e/exit on a full light march) and by \
                 1 ± 64u, ± 64u (the f32 noise and profile of O(1) values; the noise \
                 coordinates' rounding u|q| ≈ mm); plus (32N + 64)u of the value for N view \
                 steps' exp and the phase lobes (16 ULP each), and 4u on the transmittance \
                 for the fade's 1 − fade·(1 − T)"
            ),
        }
    };
}

const TOLERANCE_CUMULUS: Tolerance = tolerance!(
    "max |L32 − L64| 2.20e-2 over the four outputs, CPU and GPU alike; the worst output \
     uses 0.139 (1/7.2) of its bound"
);

const TOLERANCE_DECK: Tolerance = tolerance!(
    "max |L32 − L64| 1.75e-2 over the four outputs, CPU and GPU alike; the worst output \
     uses 0.081 (1/12) of its bound"
);

/// The scene of case `case`: shell, camera, settings, sun direction (planet-centred, the
/// camera's ground point at the pole, +z up).
struct Scene {
    size: [u32; 2],
    shell: CloudShell,
    camera: PinholeCamera,
    settings: MarchSettings,
    sun: [f64; 3],
}

fn scene(case: usize) -> Result<Scene, String> {
    let earth = atmos::Atmosphere::earth();
    let r = earth.planet_radius;
    let e = |s: &dyn std::fmt::Display| s.to_string();
    // Camera positions are f32-exact (6,360,002 and 6,363,000 m).
    let (settings, camera, config, elevation, azimuth) = match case {
        0 => (
            ShellSettings::cumulus_over(r),
            PinholeCamera::look_at(
                [0.0, 0.0, r + 2.0],
                [5000.0, 0.0, r + 5002.0],
                [0.0, 0.0, 1.0],
                1.0,
            ),
            MarchConfig {
                view_steps: 6,
                jitter: Jitter::Bayer4x4,
                transmittance_epsilon: 0.0,
                light: LightMarch::Cone {
                    step: 150.0,
                    spread: 0.2,
                    weights: ConeWeights::Raw,
                },
                octaves: Octaves {
                    count: 2,
                    a: 0.5,
                    b: 0.5,
                    c: 0.5,
                },
                ambient_steps: 0,
                ..MarchConfig::default()
            },
            30.0f64,
            40.0f64,
        ),
        _ => (
            ShellSettings::stratocumulus_deck(r),
            PinholeCamera::look_at(
                [0.0, 0.0, r + 3000.0],
                [4000.0, 1000.0, r],
                [0.0, 0.0, 1.0],
                1.0,
            ),
            MarchConfig {
                view_steps: 8,
                jitter: Jitter::None,
                transmittance_epsilon: 0.0,
                light: LightMarch::Full {
                    steps: std::num::NonZeroU32::new(4).ok_or("4 > 0")?,
                },
                octaves: Octaves {
                    count: 3,
                    a: 0.5,
                    b: 0.6,
                    c: 0.5,
                },
                ambient_steps: 1,
                ..MarchConfig::default()
            },
            10.0,
            200.0,
        ),
    };
    let shell = CloudShell::new(&earth, settings).map_err(|x| e(&x))?;
    let camera = camera.map_err(|x| e(&x))?;
    let settings = MarchSettings::new(config).map_err(|x| e(&x))?;
    let (el, az) = (elevation.to_radians(), azimuth.to_radians());
    let sun = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
    Ok(Scene {
        size: SIZES[case.min(1)],
        shell,
        camera,
        settings,
        sun,
    })
}

const SUN: [f64; 3] = [1.0, 0.95, 0.9];
const AMBIENT: [f64; 3] = [0.05, 0.08, 0.12];

fn lighting<F: atmos::real::Real>(sun: [f64; 3]) -> Result<Lighting<F>, String> {
    Lighting::new(sun, SUN, AMBIENT, [0.0, 0.0, 1.0]).map_err(|e| e.to_string())
}

/// A sphere root's f32 error (as the shell shadow map case's): the discriminant's error
/// through √D, `b`'s and a few roundings of `t`; with `shift` > 0 also the root's change
/// when the ray's origin moves `shift` metres radially (`b` by `μ·shift`, `D` by
/// `2r(1 − μ²)·shift`).
fn root_error(r: f64, mu: f64, radius: f64, shift: f64) -> f64 {
    let b = r * mu;
    let c = (r - radius) * (r + radius);
    let d = b * b - c;
    let delta_d =
        8.0 * U * b * b + 4.0 * U * r * r + 4.0 * U * c.abs() + 2.0 * r * (1.0 - mu * mu) * shift;
    let sqrt_error = if d > 0.0 {
        (delta_d / (2.0 * d.sqrt())).min(delta_d.sqrt())
    } else {
        delta_d.sqrt()
    };
    let roots = atmos::reference::ray_sphere_intersect(r, mu, radius);
    // Only roots ahead within T_MAX can be span ends (not the planet's far side).
    let t = roots
        .into_iter()
        .filter(|t| (0.0..=T_MAX).contains(t))
        .fold(0.0, f64::max);
    2.0 * sqrt_error + 4.0 * U * b.abs() + 12.0 * U * t + mu.abs() * shift
}

/// The shell moved to an envelope (see the tolerance's `why`): the view ray's densities toward
/// `sign` (+1 up, −1 down), the light and ambient rays' the other way, so that the changes
/// of the source and of the light reaching it add instead of cancelling. The spans are the
/// shell's; their ends' errors move and scale the densities of the ray they bound.
struct Envelope<'a> {
    shell: &'a CloudShell,
    sign: f64,
    /// The radial position error δr, metres.
    radial: f64,
    /// Whether the light march's sample positions scale with its exit distance (the full
    /// march and the partitioned cone; not the raw cone).
    light_scales: bool,
    /// The camera (rays from it are the view rays: their origin is f32-exact).
    camera: [f64; 3],
    /// The view direction of the pixel being marched.
    view: std::cell::Cell<[f64; 3]>,
    /// The view ray's and the last light or ambient ray's direction, span-end error
    /// (metres) and relative step-length error, set by `ray_spans`.
    view_error: std::cell::Cell<(f64, f64)>,
    ray: std::cell::Cell<([f64; 3], f64, f64)>,
}

impl Envelope<'_> {
    fn new(
        shell: &CloudShell,
        sign: f64,
        radial: f64,
        light_scales: bool,
        camera: [f64; 3],
    ) -> Envelope<'_> {
        Envelope {
            shell,
            sign,
            radial,
            light_scales,
            camera,
            view: std::cell::Cell::new([0.0; 3]),
            view_error: std::cell::Cell::new((0.0, 0.0)),
            ray: std::cell::Cell::new(([0.0; 3], 0.0, 0.0)),
        }
    }

    /// Whether `p` is on the current view ray.
    fn on_view_ray(&self, p: [f64; 3]) -> bool {
        let v: [f64; 3] = std::array::from_fn(|a| p[a] - self.camera[a]);
        let d = self.view.get();
        let cross = [
            v[1] * d[2] - v[2] * d[1],
            v[2] * d[0] - v[0] * d[2],
            v[0] * d[1] - v[1] * d[0],
        ];
        // View samples are `camera + t·d` in f64 (off by < 1e-8 m); light and ambient
        // samples leave the view ray at once (metres off at their first sample here).
        (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt() < 1e-3
    }
}

impl DensityField<f64> for Envelope<'_> {
    fn density(&self, p: [f64; 3]) -> f64 {
        let (sign, dir, shift, scale) = if self.on_view_ray(p) {
            let (shift, scale) = self.view_error.get();
            (self.sign, self.view.get(), shift, scale)
        } else {
            let (dir, shift, scale) = self.ray.get();
            (-self.sign, dir, shift, scale)
        };
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        // Over ±δr radially and ± the span ends' error along the ray the density is
        // smooth or has a convex kink (max(·, 0)): its extremes are at the corners.
        let corners = [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)].map(|(a, b)| {
            let q = std::array::from_fn(|k| p[k] + a * self.radial * p[k] / r + b * shift * dir[k]);
            DensityField::<f64>::density(self.shell, q)
        });
        if sign > 0.0 {
            let v = corners.into_iter().fold(0.0, f64::max);
            if v > 0.0 {
                v * (1.0 + scale) * (1.0 + 64.0 * U) + 64.0 * U
            } else {
                0.0
            }
        } else {
            let v = corners.into_iter().fold(f64::INFINITY, f64::min);
            (v * (1.0 - scale) * (1.0 - 64.0 * U) - 64.0 * U).max(0.0)
        }
    }

    fn extinction_per_density(&self) -> f64 {
        DensityField::<f64>::extinction_per_density(self.shell)
    }

    fn ray_spans(&self, origin: [f64; 3], direction: [f64; 3]) -> RaySpans<f64> {
        let spans: RaySpans<f64> = self.shell.ray_spans(origin, direction);
        let r = (origin[0] * origin[0] + origin[1] * origin[1] + origin[2] * origin[2]).sqrt();
        let mu = (0..3).map(|a| origin[a] * direction[a]).sum::<f64>() / r;
        let view = origin == self.camera;
        // A light or ambient ray starts at a view sample, off by δr and the view ends' error.
        let shift = if view {
            0.0
        } else {
            self.radial + self.view_error.get().0
        };
        let s = self.shell.settings();
        let error = [self.shell.planet_radius(), s.inner_radius, s.outer_radius]
            .map(|radius| root_error(r, mu, radius, shift))
            .into_iter()
            .fold(0.0, f64::max);
        let length = spans.length();
        if view {
            let scale = if length > 0.0 {
                2.0 * error / length
            } else {
                0.0
            };
            self.view_error.set((error, scale));
        } else {
            let exit = spans.as_slice().last().map_or(0.0, |&(_, b)| b);
            let scale = if self.light_scales && exit > 0.0 {
                error / exit
            } else {
                0.0
            };
            self.ray.set((direction, error, scale));
        }
        spans
    }
}

fn flatten<F: Into<f64> + Copy>(image: &[MarchResult<F>]) -> Vec<f64> {
    image
        .iter()
        .flat_map(|r| {
            [
                r.radiance[0].into(),
                r.radiance[1].into(),
                r.radiance[2].into(),
                r.transmittance.into(),
            ]
        })
        .collect()
}

/// The f64 march of rows `rows` through `field`, faded as the GPU pass fades.
fn rows_f64<D: DensityField<f64>>(
    field: &D,
    set_view: impl Fn(&D, [f64; 3]),
    scene: &Scene,
    lighting: &Lighting<f64>,
    rows: std::ops::Range<u32>,
) -> Vec<MarchResult<f64>> {
    let [forward, right, up] = scene.camera.basis();
    let tan_half = scene.camera.tan_half(scene.size);
    let origin = scene.camera.origin();
    rows.flat_map(|y| (0..scene.size[0]).map(move |x| [x, y]))
        .map(|pixel| {
            let d = pixel_direction(pixel, scene.size, forward, right, up, tan_half);
            set_view(field, d);
            let m = march_view_at_pixel(field, origin, d, &scene.settings, lighting, pixel);
            faded(m, scene.shell.horizon_fade(m.depth))
        })
        .collect()
}

fn march_shell_cpu(case: usize) -> Result<PassCpu, String> {
    let scene = scene(case)?;
    let l64 = lighting::<f64>(scene.sun)?;
    let l32 = lighting::<f32>(scene.sun)?;
    let s = scene.shell.settings();
    // The longest light chord: from the inner sphere toward the sun at the camera's
    // zenith angle (a few km away the angle differs by < 1e-3 rad).
    let chord =
        atmos::reference::ray_sphere_intersect(s.inner_radius, scene.sun[2], s.outer_radius)[1];
    let radial = 12.0 * U * (s.outer_radius + T_MAX);
    let light_scales = !matches!(
        scene.settings.config().light,
        LightMarch::Cone {
            weights: ConeWeights::Raw,
            ..
        }
    );
    let envelope = |sign: f64| {
        Envelope::new(
            &scene.shell,
            sign,
            radial,
            light_scales,
            scene.camera.origin(),
        )
    };
    let set = |e: &Envelope, d: [f64; 3]| e.view.set(d);
    // Two threads: the reference, the twin and 3/8 of the envelope rows on one, the rest
    // of the envelopes (four densities per sample) on the other.
    let split = scene.size[1] * 3 / 8;
    let (reference_image, cpu_image, up_image, down_image) = std::thread::scope(|scope| {
        let other = scope.spawn(|| {
            (
                rows_f64(&envelope(1.0), set, &scene, &l64, split..scene.size[1]),
                rows_f64(&envelope(-1.0), set, &scene, &l64, split..scene.size[1]),
            )
        });
        let reference = rows_f64(&scene.shell, |_, _| {}, &scene, &l64, 0..scene.size[1]);
        let cpu: Vec<MarchResult<f32>> = render_image::<f32>(
            &scene.shell,
            &scene.camera,
            scene.size,
            &scene.settings,
            &l32,
        )
        .into_iter()
        .map(|m| faded(m, scene.shell.horizon_fade(m.depth)))
        .collect();
        let mut up_image = rows_f64(&envelope(1.0), set, &scene, &l64, 0..split);
        let mut down_image = rows_f64(&envelope(-1.0), set, &scene, &l64, 0..split);
        let (u, d) = other.join().unwrap_or_default();
        up_image.extend(u);
        down_image.extend(d);
        (reference, cpu, up_image, down_image)
    });
    let pixels = scene.size[0] as usize * scene.size[1] as usize;
    if up_image.len() != pixels || down_image.len() != pixels {
        return Err("an envelope thread panicked".into());
    }
    let dense = reference_image
        .iter()
        .filter(|m| m.transmittance < 0.5)
        .count();
    if dense < pixels / 10 {
        return Err(format!(
            "{dense} of {pixels} pixels have transmittance below 0.5: the case would prove \
             little"
        ));
    }
    let far = reference_image.iter().map(|m| m.depth).fold(0.0, f64::max);
    if far >= s.horizon_fade_start || chord >= T_MAX {
        return Err(format!(
            "cloud depth {far} m (fade from {} m) or light chord {chord} m (t_max {T_MAX} m): \
             the bound assumes neither",
            s.horizon_fade_start
        ));
    }
    let reference = flatten(&reference_image);
    let (up_values, down_values) = (flatten(&up_image), flatten(&down_image));
    let steps = f64::from(scene.settings.config().view_steps);
    let bounds = reference
        .iter()
        .zip(up_values.iter().zip(&down_values))
        .enumerate()
        .map(|(i, (&r, (&hi, &lo)))| {
            // The fade's `1 − fade·(1 − T)`: two roundings of values ≤ 1.
            let fade = if i % 4 == 3 { 4.0 * U } else { 0.0 };
            2.0 * (hi - r).abs().max((lo - r).abs()) + (32.0 * steps + 64.0) * U * r.abs() + fade
        })
        .collect();
    Ok(PassCpu {
        inputs: pixels,
        reference,
        bounds: Some(bounds),
        cpu: flatten(&cpu_image).into_iter().map(|x| x as f32).collect(),
    })
}

fn march_shell_gpu(gpu: &skyscape_harness::GpuContext, case: usize) -> Result<Vec<f32>, String> {
    let scene = scene(case)?;
    let mut pass = cloudlight::gpu::MarchShellPass::new(&gpu.device).map_err(|e| e.to_string())?;
    pass.prepare(
        &gpu.device,
        &gpu.queue,
        &scene.shell,
        &scene.camera,
        scene.size,
        &scene.settings,
        &lighting::<f32>(scene.sun)?,
    )
    .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let buffer = pass.image_buffer().ok_or("no image buffer after prepare")?;
    let bytes =
        skyscape_harness::read_buffer(gpu, "cloudlight march shell", buffer, 0, pass.image_size())
            .map_err(|e| e.to_string())?;
    let image = pass.decode(&bytes).map_err(|e| e.to_string())?;
    Ok(flatten(&image).into_iter().map(|x| x as f32).collect())
}
