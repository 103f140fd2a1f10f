//! `cargo xtask tradeoff cloudlight`: what each way of lighting a cloud costs and how
//! wrong it is against `cloudlight::reference`, which approximates nothing it can
//! compute: the exact optical depth of the trilinear density, single scattering with
//! the exact light path at every point of an adaptive view quadrature, and a Monte Carlo
//! path tracer for every scattering order.
//!
//! Three studies on cloudsim's cumulus (seed 2026, 64×64×24 cells of 50 m at 1.5 km,
//! 600 steps, σ_t = 0.03 /m per unit density), suns at 60° and 10° (azimuth 30°):
//!
//! * **Light transmittance** toward the sun at every cell with density > 0 — Dobashi et al.
//!   2000's slice propagation (physical, both resamplings; faithful), Schneider's 6 + 1 cone (raw
//!   and partitioned) and the full light march of N steps — RMSE and max error against
//!   the exact transmittance, CPU cost per cloudy cell by criterion (f32 twins, the
//!   arithmetic the WGSL mirrors).
//! * **View march** (single scattering): view steps, light estimate, jitter; the mean
//!   relative radiance error per pixel and the error of the image's mean radiance
//!   against the single-scattering reference, from a camera below the cloud and one
//!   above it; CPU cost per pixel by criterion.
//! * **Multiple-scattering octaves** against the path tracer's every-order mean
//!   radiance (with its standard error).
//!
//! GPU: the slice pass's time by timestamp queries on the adapter found (labelled; on
//! lavapipe a CPU adapter's time).

use std::fmt::Write as _;
use std::num::NonZeroU32;

use cloudlight::CloudVolume;
use cloudlight::cone::{ConeWeights, box_exit_distance, cone_optical_depth, march_optical_depth};
use cloudlight::density::DensityField;
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchSettings, Octaves, PinholeCamera, render_image,
};
use cloudlight::propagate::{Resampling, SliceMode, SlicePlan, propagate};
use cloudlight::reference::path_tracer::{PathTracerSettings, RaySample, estimate};
use cloudlight::reference::single_scattering::{SingleScatteringSettings, single_scattering};
use cloudlight::reference::{Phase, Sun, transmittance};

use super::plot::{Plot, Point, Series};

/// Where criterion writes its raw estimates for this study.
const CRITERION_DIR: &str = "target/tradeoff/criterion-cloudlight";

/// The march's default phase (dual-lobe Henyey–Greenstein on atmos' lobe).
const G_FORWARD: f64 = 0.8;
const G_BACK: f64 = -0.3;
const BACK_WEIGHT: f64 = 0.2;
/// Extinction per unit density (1/m): a physical cumulus (0.02–0.1 /m).
const SIGMA_T: f64 = 0.03;
const SUNS_DEG: [f64; 2] = [60.0, 10.0];
const SUN_AZIMUTH_DEG: f64 = 30.0;

/// cloudsim's cumulus (the `light_accuracy` example's and the octave test's).
fn cumulus(quick: bool) -> Result<CloudVolume, String> {
    let (n, nz, steps) = if quick { (32, 12, 300) } else { (64, 24, 600) };
    let size = cloudsim::GridSize::new(n, n, nz);
    let mut config = cloudsim::Config::new(size);
    config.seed = 2026;
    let s = n as f32 / 64.0;
    let sz = nz as f32 / 24.0;
    config.ellipsoids = vec![
        cloudsim::Ellipsoid {
            center: [28.0 * s, 32.0 * s, 9.0 * sz],
            radii: [20.0 * s, 18.0 * s, 8.0 * sz],
        },
        cloudsim::Ellipsoid {
            center: [40.0 * s, 30.0 * s, 13.0 * sz],
            radii: [16.0 * s, 20.0 * s, 9.0 * sz],
        },
    ];
    let e = |e: cloudsim::Error| e.to_string();
    let model = cloudsim::Model::new(config).map_err(e)?;
    let mut sim = cloudsim::Simulation::new(model).map_err(e)?;
    sim.advance(steps).map_err(e)?;
    let density = sim.density().map_err(e)?;
    let cell = 50.0 * 64.0 / f64::from(n);
    CloudVolume::new([n, n, nz], [0.0, 0.0, 1500.0], cell, SIGMA_T, density)
        .map_err(|e| e.to_string())
}

fn to_sun(elevation_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), SUN_AZIMUTH_DEG.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// Criterion's median seconds per call of `f` (criterion used as a library, its
/// estimates read back from `CRITERION_DIR`).
fn criterion_seconds(slug: &str, quick: bool, mut f: impl FnMut()) -> Result<f64, String> {
    let (warm_up, measurement) = if quick { (50, 200) } else { (300, 1_500) };
    let mut criterion = criterion::Criterion::default()
        .output_directory(std::path::Path::new(CRITERION_DIR))
        .sample_size(10)
        .warm_up_time(std::time::Duration::from_millis(warm_up))
        .measurement_time(std::time::Duration::from_millis(measurement))
        .without_plots();
    criterion.bench_function(slug, |b| b.iter(&mut f));
    let path = std::path::Path::new(CRITERION_DIR)
        .join(slug)
        .join("new")
        .join("estimates.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("criterion estimates {}: {e}", path.display()))?;
    let nanoseconds = super::atmos::median_point_estimate(&text)
        .ok_or_else(|| format!("no median point estimate in {}", path.display()))?;
    Ok(nanoseconds * 1e-9)
}

fn slug(parts: &[&str]) -> String {
    super::slug(&parts.join(" "))
}

/// Runs `f` over `items` on every core, keeping the order.
fn parallel_map<T: Sync, R: Send + Default + Clone>(
    items: &[T],
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut out = vec![R::default(); items.len()];
    let chunk = items.len().div_ceil(threads).max(1);
    std::thread::scope(|scope| {
        for (inputs, outputs) in items.chunks(chunk).zip(out.chunks_mut(chunk)) {
            let f = &f;
            scope.spawn(move || {
                for (input, output) in inputs.iter().zip(outputs.iter_mut()) {
                    *output = f(input);
                }
            });
        }
    });
    out
}

// ---------------------------------------------------------------------------------------
// Light transmittance

struct LightRow {
    sun_deg: f64,
    method: String,
    samples: String,
    rmse: f64,
    max: f64,
    ns_per_cell: f64,
}

/// One light estimate: the f32 transmittance at each cloudy cell.
enum LightMethod {
    Slices(SliceMode, Resampling),
    Cone {
        weights: ConeWeights,
        spread: f64,
        /// Step in cells (`None`: the path's length over 7).
        step_cells: Option<f64>,
    },
    March(u32),
}

fn light_methods() -> Vec<(String, String, LightMethod)> {
    let mut v = vec![
        (
            "slices, physical, Catmull–Rom".into(),
            "1 sweep".into(),
            LightMethod::Slices(SliceMode::Physical, Resampling::CatmullRom),
        ),
        (
            "slices, physical, bilinear".into(),
            "1 sweep".into(),
            LightMethod::Slices(SliceMode::Physical, Resampling::Bilinear),
        ),
        (
            "slices, faithful (Dobashi et al. 2000, ratio e^−σ_t·Δ)".into(),
            "1 sweep".into(),
            // Filled per volume: a slice of density 1 passes e^{−σ_t Δ}.
            LightMethod::Slices(
                SliceMode::Faithful {
                    attenuation_ratio: f64::NAN,
                },
                Resampling::Bilinear,
            ),
        ),
        (
            "cone 6+1, raw (Schneider), spread 0.2, Δ = 1 cell".into(),
            "7".into(),
            LightMethod::Cone {
                weights: ConeWeights::Raw,
                spread: 0.2,
                step_cells: Some(1.0),
            },
        ),
        (
            "cone 6+1, partitioned, Δ = 1 cell".into(),
            "7".into(),
            LightMethod::Cone {
                weights: ConeWeights::Partitioned,
                spread: 0.0,
                step_cells: Some(1.0),
            },
        ),
        (
            "cone 6+1, partitioned, Δ = L/7".into(),
            "7".into(),
            LightMethod::Cone {
                weights: ConeWeights::Partitioned,
                spread: 0.0,
                step_cells: None,
            },
        ),
    ];
    for steps in [8u32, 16, 32, 64] {
        v.push((
            format!("full light march, {steps} steps"),
            steps.to_string(),
            LightMethod::March(steps),
        ));
    }
    v
}

fn light_study(volume: &CloudVolume, quick: bool) -> Result<Vec<LightRow>, String> {
    let [nx, ny, nz] = volume.dims();
    let h = volume.voxel_size();
    let o = volume.origin();
    let hi = [0, 1, 2].map(|a| o[a] + f64::from(volume.dims()[a]) * h);
    let cells = (nx * ny * nz) as usize;
    let inside: Vec<usize> = (0..cells).filter(|&c| volume.density()[c] > 0.0).collect();
    let point = |c: usize| {
        let (x, y, z) = (
            c % nx as usize,
            (c / nx as usize) % ny as usize,
            c / (nx * ny) as usize,
        );
        let local = [x, y, z].map(|v| (v as f64 + 0.5) * h);
        [local[0] + o[0], local[1] + o[1], local[2] + o[2]]
    };
    let sigma = volume.extinction_per_density();
    let mut rows = Vec::new();
    for sun_deg in SUNS_DEG {
        let l = to_sun(sun_deg);
        let exact: Vec<f64> = parallel_map(&inside, |&c| {
            transmittance(volume, point(c), l, f64::INFINITY).unwrap_or(f64::NAN)
        });
        if exact.iter().any(|t| !t.is_finite()) {
            return Err("the exact transmittance failed at a cell".into());
        }
        for (method, samples, estimate_kind) in light_methods() {
            let l32 = l.map(|c| c as f32);
            let lo32 = o.map(|c| c as f32);
            let hi32 = hi.map(|c| c as f32);
            let density = |q: [f32; 3]| DensityField::<f32>::density(volume, q);
            let light_at = |c: usize| -> f32 {
                let p = point(c).map(|v| v as f32);
                let exit = box_exit_distance(p, l32, lo32, hi32);
                let tau = match &estimate_kind {
                    LightMethod::Cone {
                        weights,
                        spread,
                        step_cells,
                    } => {
                        let step = step_cells.map_or(f32::MAX, |s| (s * h) as f32);
                        cone_optical_depth(
                            density,
                            sigma as f32,
                            p,
                            l32,
                            step,
                            exit,
                            *spread as f32,
                            *weights,
                        )
                    }
                    LightMethod::March(steps) => march_optical_depth(
                        density,
                        sigma as f32,
                        p,
                        l32,
                        exit,
                        NonZeroU32::new(*steps).expect("steps > 0"),
                    ),
                    LightMethod::Slices(..) => unreachable!("slices light the whole volume"),
                };
                (-tau).exp()
            };
            let (light, seconds): (Vec<f64>, f64) = match &estimate_kind {
                LightMethod::Slices(mode, resampling) => {
                    let mode = match mode {
                        SliceMode::Faithful { .. } => SliceMode::Faithful {
                            attenuation_ratio: (-sigma * h).exp(),
                        },
                        physical => *physical,
                    };
                    let plan = SlicePlan::new(volume, l, mode)
                        .map_err(|e| e.to_string())?
                        .with_resampling(*resampling);
                    let all = propagate::<f32>(volume, &plan).map_err(|e| e.to_string())?;
                    let seconds = criterion_seconds(
                        &slug(&["light", &sun_deg.to_string(), &method]),
                        quick,
                        || {
                            let _ = std::hint::black_box(propagate::<f32>(
                                std::hint::black_box(volume),
                                &plan,
                            ));
                        },
                    )?;
                    (inside.iter().map(|&c| f64::from(all[c])).collect(), seconds)
                }
                _ => {
                    let light: Vec<f64> = inside.iter().map(|&c| f64::from(light_at(c))).collect();
                    let seconds = criterion_seconds(
                        &slug(&["light", &sun_deg.to_string(), &method]),
                        quick,
                        || {
                            let mut sum = 0.0f32;
                            for &c in &inside {
                                sum += light_at(c);
                            }
                            std::hint::black_box(sum);
                        },
                    )?;
                    (light, seconds)
                }
            };
            let (mut sum, mut max) = (0.0, 0.0f64);
            for (a, b) in light.iter().zip(&exact) {
                sum += (a - b) * (a - b);
                max = max.max((a - b).abs());
            }
            rows.push(LightRow {
                sun_deg,
                method,
                samples,
                rmse: (sum / light.len() as f64).sqrt(),
                max,
                ns_per_cell: seconds * 1e9 / inside.len() as f64,
            });
        }
    }
    Ok(rows)
}

// ---------------------------------------------------------------------------------------
// Slices against a per-voxel light march at up to 128³

struct VolumeCost {
    n: u32,
    method: String,
    ms: f64,
}

/// A paraboloid blob `n³` (density 1 − r²/c², cells of 1280/n m, σ_t 0.01 /m): every cell
/// lit, by one sweep or by a march per cell (f32 twins), criterion's median.
fn volume_cost(quick: bool) -> Result<Vec<VolumeCost>, String> {
    let n: u32 = if quick { 48 } else { 128 };
    let c = (f64::from(n) - 1.0) / 2.0;
    let mut density = Vec::with_capacity((n * n * n) as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let r2: f64 = [x, y, z].iter().map(|&v| (f64::from(v) - c).powi(2)).sum();
                density.push((1.0 - r2 / (c * c)).max(0.0) as f32);
            }
        }
    }
    let cell = 1280.0 / f64::from(n);
    let volume =
        CloudVolume::new([n; 3], [0.0; 3], cell, 0.01, density).map_err(|e| e.to_string())?;
    let l = to_sun(60.0);
    let l32 = l.map(|v| v as f32);
    let hi = [(f64::from(n) * cell) as f32; 3];
    let mut rows = Vec::new();
    let plan = SlicePlan::new(&volume, l, SliceMode::Physical).map_err(|e| e.to_string())?;
    let seconds = criterion_seconds(&format!("volume_{n}_slices"), quick, || {
        let _ = std::hint::black_box(propagate::<f32>(std::hint::black_box(&volume), &plan));
    })?;
    rows.push(VolumeCost {
        n,
        method: "slices, physical, Catmull–Rom (one sweep)".into(),
        ms: seconds * 1e3,
    });
    let cells = (n * n * n) as usize;
    let density = |q: [f32; 3]| DensityField::<f32>::density(&volume, q);
    for steps in [32u32, 128] {
        let steps_nz = NonZeroU32::new(steps).expect("steps > 0");
        let seconds = criterion_seconds(&format!("volume_{n}_march_{steps}"), quick, || {
            let mut sum = 0.0f32;
            for index in 0..cells {
                let (x, y, z) = (
                    index % n as usize,
                    (index / n as usize) % n as usize,
                    index / (n * n) as usize,
                );
                let p = [x, y, z].map(|v| ((v as f64 + 0.5) * cell) as f32);
                let exit = box_exit_distance(p, l32, [0.0; 3], hi);
                sum += march_optical_depth(density, 0.01, p, l32, exit, steps_nz);
            }
            std::hint::black_box(sum);
        })?;
        rows.push(VolumeCost {
            n,
            method: format!("full light march per voxel, {steps} steps"),
            ms: seconds * 1e3,
        });
    }
    Ok(rows)
}

// ---------------------------------------------------------------------------------------
// View march (single scattering)

struct ViewRow {
    camera: &'static str,
    sun_deg: f64,
    setting: String,
    mean_relative: f64,
    image_mean: f64,
    transmittance_rmse: f64,
    ns_per_pixel: f64,
}

/// A camera below the cloud (under its base, looking up across it) or above it.
fn camera(volume: &CloudVolume, below: bool) -> Result<PinholeCamera, String> {
    let o = volume.origin();
    let extent = volume.dims().map(|d| f64::from(d) * volume.voxel_size());
    let centre = [0, 1, 2].map(|i| o[i] + 0.5 * extent[i]);
    let eye = if below {
        [
            centre[0] - 1.2 * extent[0],
            centre[1] - 0.3 * extent[1],
            300.0,
        ]
    } else {
        [
            centre[0] - 1.0 * extent[0],
            centre[1] - 0.6 * extent[1],
            o[2] + 2.5 * extent[0],
        ]
    };
    PinholeCamera::look_at(eye, centre, [0.0, 0.0, 1.0], 60f64.to_radians())
        .map_err(|e| e.to_string())
}

fn settings(view_steps: u32, light: LightMarch, jitter: Jitter, octaves: Octaves) -> MarchSettings {
    MarchSettings::new(MarchConfig {
        view_steps,
        jitter,
        transmittance_epsilon: 0.0,
        light,
        albedo: 1.0,
        g_forward: G_FORWARD,
        g_back: G_BACK,
        back_weight: BACK_WEIGHT,
        octaves,
        powder: false,
        ambient_steps: 0,
    })
    .expect("the study's settings are valid")
}

fn full(steps: u32) -> LightMarch {
    LightMarch::Full {
        steps: NonZeroU32::new(steps).expect("steps > 0"),
    }
}

fn view_settings(cell: f64) -> Vec<(String, MarchSettings)> {
    let mut v = Vec::new();
    for steps in [16u32, 32, 64, 128] {
        v.push((
            format!("{steps} view steps, full light march 16"),
            settings(steps, full(16), Jitter::None, Octaves::SINGLE),
        ));
    }
    for (label, weights, spread) in [
        ("cone 6+1 raw (spread 0.2)", ConeWeights::Raw, 0.2),
        ("cone 6+1 partitioned", ConeWeights::Partitioned, 0.0),
    ] {
        v.push((
            format!("64 view steps, {label}, Δ = 1 cell"),
            settings(
                64,
                LightMarch::Cone {
                    weights,
                    step: cell,
                    spread,
                },
                Jitter::None,
                Octaves::SINGLE,
            ),
        ));
    }
    v.push((
        "64 view steps, cone 6+1 partitioned, Δ = L/7".into(),
        settings(
            64,
            LightMarch::cone_sevenths(),
            Jitter::None,
            Octaves::SINGLE,
        ),
    ));
    for steps in [4u32, 64] {
        v.push((
            format!("64 view steps, full light march {steps}"),
            settings(64, full(steps), Jitter::None, Octaves::SINGLE),
        ));
    }
    for (label, jitter) in [
        ("Bayer 4×4", Jitter::Bayer4x4),
        ("interleaved gradient noise", Jitter::InterleavedGradient),
    ] {
        v.push((
            format!("32 view steps, full light march 16, {label} jitter"),
            settings(32, full(16), jitter, Octaves::SINGLE),
        ));
    }
    v
}

fn view_study(volume: &CloudVolume, quick: bool) -> Result<Vec<ViewRow>, String> {
    let size = if quick { [16, 12] } else { [40, 30] };
    let phase = Phase::DualLobe {
        g_forward: G_FORWARD,
        g_back: G_BACK,
        back_weight: BACK_WEIGHT,
    };
    let reference_settings = SingleScatteringSettings {
        relative_tolerance: 1e-5,
        ..Default::default()
    };
    let mut rows = Vec::new();
    for (name, below) in [("below", true), ("above", false)] {
        let cam = camera(volume, below)?;
        let [forward, right, up] = cam.basis();
        let tan_half = cam.tan_half(size);
        let pixels: Vec<[u32; 2]> = (0..size[1])
            .flat_map(|y| (0..size[0]).map(move |x| [x, y]))
            .collect();
        for sun_deg in SUNS_DEG {
            let l = to_sun(sun_deg);
            let sun = Sun::new(l, [1.0; 3]).map_err(|e| e.to_string())?;
            let reference: Vec<(f64, f64)> = parallel_map(&pixels, |&pixel| {
                let d =
                    cloudlight::march::pixel_direction(pixel, size, forward, right, up, tan_half);
                single_scattering(volume, cam.origin(), d, &sun, &phase, &reference_settings)
                    .map_or((f64::NAN, f64::NAN), |s| (s.radiance[0], s.transmittance))
            });
            if reference.iter().any(|r| !r.0.is_finite()) {
                return Err("the single-scattering reference failed at a pixel".into());
            }
            let peak = reference.iter().fold(0.0f64, |m, r| m.max(r.0));
            let reference_mean = reference.iter().map(|r| r.0).sum::<f64>() / pixels.len() as f64;
            let lighting = Lighting::<f32>::white_sun(l).map_err(|e| e.to_string())?;
            for (setting, march) in view_settings(volume.voxel_size()) {
                let image = render_image::<f32>(volume, &cam, size, &march, &lighting);
                let (mut relative, mut counted, mut t2, mut sum) = (0.0, 0usize, 0.0, 0.0);
                for (got, (want, t)) in image.iter().zip(&reference) {
                    let value = f64::from(got.radiance[0]);
                    sum += value;
                    let dt = f64::from(got.transmittance) - t;
                    t2 += dt * dt;
                    if *want > 1e-3 * peak {
                        relative += (value - want).abs() / want;
                        counted += 1;
                    }
                }
                let seconds = criterion_seconds(
                    &slug(&["view", name, &sun_deg.to_string(), &setting]),
                    quick,
                    || {
                        std::hint::black_box(render_image::<f32>(
                            std::hint::black_box(volume),
                            &cam,
                            size,
                            &march,
                            &lighting,
                        ));
                    },
                )?;
                rows.push(ViewRow {
                    camera: name,
                    sun_deg,
                    setting,
                    mean_relative: relative / counted.max(1) as f64,
                    image_mean: sum / pixels.len() as f64 / reference_mean - 1.0,
                    transmittance_rmse: (t2 / pixels.len() as f64).sqrt(),
                    ns_per_pixel: seconds * 1e9 / pixels.len() as f64,
                });
            }
        }
    }
    Ok(rows)
}

// ---------------------------------------------------------------------------------------
// Octaves against the path tracer

struct OctaveRow {
    sun_deg: f64,
    setting: String,
    relative: f64,
    /// The path tracer's standard error over its mean.
    mc_relative_error: f64,
    single_share: f64,
}

fn octave_study(volume: &CloudVolume, quick: bool) -> Result<(Vec<OctaveRow>, u64), String> {
    let size = if quick { [16u32, 12] } else { [32, 24] };
    let paths: u64 = if quick { 40_000 } else { 400_000 };
    let o = volume.origin();
    let extent = volume.dims().map(|d| f64::from(d) * volume.voxel_size());
    let centre = [0, 1, 2].map(|i| o[i] + 0.5 * extent[i]);
    // The octave test's goal camera: 8 km from the centre, 20° above it, azimuth 150°.
    let (e, a) = (20f64.to_radians(), 150f64.to_radians());
    let distance = 8000.0 * extent[0] / 3200.0;
    let eye = [
        centre[0] + distance * e.cos() * a.cos(),
        centre[1] + distance * e.cos() * a.sin(),
        centre[2] + distance * e.sin(),
    ];
    let cam = PinholeCamera::look_at(eye, centre, [0.0, 0.0, 1.0], 30f64.to_radians())
        .map_err(|e| e.to_string())?;
    let [forward, right, up] = cam.basis();
    let tan_half = cam.tan_half(size);
    let rays: Vec<[f64; 3]> = (0..size[1])
        .flat_map(|y| (0..size[0]).map(move |x| [x, y]))
        .map(|pixel| cloudlight::march::pixel_direction(pixel, size, forward, right, up, tan_half))
        .collect();
    let phase = Phase::DualLobe {
        g_forward: G_FORWARD,
        g_back: G_BACK,
        back_weight: BACK_WEIGHT,
    };
    let mut rows = Vec::new();
    for sun_deg in SUNS_DEG {
        let l = to_sun(sun_deg);
        let sun = Sun::new(l, [1.0; 3]).map_err(|e| e.to_string())?;
        let mc = estimate(
            volume,
            &sun,
            &phase,
            &PathTracerSettings {
                samples: paths,
                ..Default::default()
            },
            |[u, _]| {
                let k = ((u * rays.len() as f64) as usize).min(rays.len() - 1);
                RaySample {
                    origin: eye,
                    direction: rays[k],
                    weight: 1.0,
                }
            },
        )
        .map_err(|e| e.to_string())?;
        let (mean, se) = (mc.total.mean[0], mc.total.standard_error[0]);
        let lighting = Lighting::<f32>::white_sun(l).map_err(|e| e.to_string())?;
        for (label, octaves) in [
            ("single scattering (1 octave)", Octaves::SINGLE),
            ("2 octaves, a = b = c = 0.5", oct(2, 0.5, 0.5, 0.5)),
            ("4 octaves, a = b = c = 0.5", oct(4, 0.5, 0.5, 0.5)),
            ("8 octaves, a = b = c = 0.5", oct(8, 0.5, 0.5, 0.5)),
            (
                "8 octaves, a = 0.5, b = 0.65, c = 0.5",
                oct(8, 0.5, 0.65, 0.5),
            ),
        ] {
            let march = settings(128, full(32), Jitter::None, octaves);
            let image = render_image::<f32>(volume, &cam, size, &march, &lighting);
            let m =
                image.iter().map(|r| f64::from(r.radiance[0])).sum::<f64>() / image.len() as f64;
            rows.push(OctaveRow {
                sun_deg,
                setting: label.into(),
                relative: m / mean - 1.0,
                mc_relative_error: se / mean,
                single_share: mc.single.mean[0] / mean,
            });
        }
    }
    Ok((rows, paths))
}

fn oct(count: u32, a: f64, b: f64, c: f64) -> Octaves {
    Octaves { count, a, b, c }
}

// ---------------------------------------------------------------------------------------
// GPU

fn gpu_slices(volume: &CloudVolume) -> Result<Option<(String, f64)>, String> {
    let ctx = match skyscape_harness::context() {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("tradeoff cloudlight: no GPU adapter ({e}): no GPU timing");
            return Ok(None);
        }
    };
    if !ctx
        .device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY)
    {
        eprintln!("tradeoff cloudlight: the adapter has no timestamp queries: no GPU timing");
        return Ok(None);
    }
    let plan =
        SlicePlan::new(volume, to_sun(60.0), SliceMode::Physical).map_err(|e| e.to_string())?;
    let mut pass =
        cloudlight::gpu::SlicePropagation::new(&ctx.device).map_err(|e| e.to_string())?;
    pass.prepare(&ctx.device, &ctx.queue, volume, &plan)
        .map_err(|e| e.to_string())?;
    let seconds = skyscape_harness::median_pass_seconds(ctx, 5, |encoder, timer, span| {
        pass.encode_timed(encoder, Some(timer.compute_writes(span)))
            .expect("prepared above");
    })
    .map_err(|e| e.to_string())?;
    Ok(Some((
        skyscape_harness::describe_adapter(&ctx.info),
        seconds,
    )))
}

// ---------------------------------------------------------------------------------------
// Report

/// Runs the study and writes `docs/tradeoffs/cloudlight.md` and `.svg`.
pub fn run(options: &super::Options) -> Result<(), String> {
    let started = std::time::Instant::now();
    let volume = cumulus(options.quick)?;
    let cloudy = volume.density().iter().filter(|&&d| d > 0.0).count();
    eprintln!(
        "tradeoff cloudlight: cumulus {:?} cells, {cloudy} cloudy; light study…",
        volume.dims()
    );
    let light = light_study(&volume, options.quick)?;
    eprintln!("tradeoff cloudlight: view study…");
    let view = view_study(&volume, options.quick)?;
    eprintln!("tradeoff cloudlight: octaves against the path tracer…");
    let (octaves, paths) = octave_study(&volume, options.quick)?;
    eprintln!("tradeoff cloudlight: slices against per-voxel marches…");
    let volume_costs = volume_cost(options.quick)?;
    let gpu = gpu_slices(&volume)?;
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();

    let mut md = String::new();
    let w = &mut md;
    let [nx, ny, nz] = volume.dims();
    let _ = writeln!(w, "# cloudlight: speed against accuracy\n");
    let _ = writeln!(
        w,
        "Generated by `cargo xtask tradeoff cloudlight` (release build: `cargo run --release -p xtask -- tradeoff cloudlight`{}) in {:.0} s. \
         **Case:** cloudsim's cumulus (seed 2026, {nx}×{ny}×{nz} cells of {} m at 1.5 km, two ellipsoids, grown {} steps, smoothed density), \
         σ_t = {SIGMA_T} /m per unit density, {cloudy} cloudy cells; suns at 60° and 10° elevation, azimuth 30°; white sun of irradiance 1; \
         the march's dual-lobe Henyey–Greenstein (0.8, −0.3, back weight 0.2); albedo 1; no ambient, no ground. \
         **Reference:** `cloudlight::reference` — the exact optical depth of the trilinear density (Simpson on each cubic piece), \
         single scattering with that exact light path at every point of an adaptive view quadrature (relative tolerance 1e-5), \
         and the Monte Carlo path tracer (delta tracking, every order) with its standard error. \
         **CPU cost** by criterion (median of 10 samples), one thread, the f32 twins (the arithmetic the WGSL mirrors); \
         this machine's load average at the end: {}.",
        if options.quick { ", `--quick`" } else { "" },
        started.elapsed().as_secs_f64(),
        volume.voxel_size(),
        if options.quick { 300 } else { 600 },
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    );
    let _ = writeln!(w, "\n## Light transmittance toward the sun\n");
    let _ = writeln!(
        w,
        "At the centre of every cloudy cell; error against the exact transmittance. Cost per cloudy cell (the slices light every cell of the volume in one sweep; the per-cell estimates only the cloudy ones).\n"
    );
    let _ = writeln!(
        w,
        "| sun | method | density samples per cell | RMSE | max error | CPU ns per cloudy cell |"
    );
    let _ = writeln!(w, "|---:|---|---:|---:|---:|---:|");
    for r in &light {
        let _ = writeln!(
            w,
            "| {}° | {} | {} | {:.4} | {:.3} | {:.0} |",
            r.sun_deg, r.method, r.samples, r.rmse, r.max, r.ns_per_cell
        );
    }
    if let Some((adapter, seconds)) = &gpu {
        let _ = writeln!(
            w,
            "\nGPU: `gpu::SlicePropagation` (physical, sun 60°) over the {nx}×{ny}×{nz} volume takes **{:.3} ms** (median of 5 timestamp-query measurements) on {adapter}{}.",
            seconds * 1e3,
            if adapter.contains("CPU") {
                " — a CPU adapter: CPU timings, not GPU speed"
            } else {
                ""
            }
        );
    }
    let _ = writeln!(
        w,
        "\n### Every cell of a volume: slices against a march per voxel\n"
    );
    let _ = writeln!(
        w,
        "A paraboloid blob of {n}³ cells (σ_t 0.01 /m, sun 60°), every cell lit; criterion's median of one call, f32, one thread (the target: slices ≥ 20× cheaper than a per-voxel march at 128³).\n",
        n = volume_costs.first().map_or(0, |r| r.n)
    );
    let _ = writeln!(w, "| method | CPU ms | slices are cheaper by |");
    let _ = writeln!(w, "|---|---:|---:|");
    let slices_ms = volume_costs.first().map_or(f64::NAN, |r| r.ms);
    for r in &volume_costs {
        let _ = writeln!(
            w,
            "| {} | {:.0} | {:.1}× |",
            r.method,
            r.ms,
            r.ms / slices_ms
        );
    }
    let _ = writeln!(w, "\n## The view march (single scattering)\n");
    let _ = writeln!(
        w,
        "`march::render_image::<f32>` of a {}-pixel image against the single-scattering reference per pixel. *Mean relative error*: over pixels whose reference radiance is above 10⁻³ of the image's peak; *image mean*: the relative error of the image's mean radiance (what jitter is meant to fix); *T RMSE*: the view transmittance's. Cameras: *below* (300 m up, under and beside the cloud, looking up at its centre), *above* (above and beside it, looking down); horizontal field of view 60°.\n",
        if options.quick { "16×12" } else { "40×30" }
    );
    let _ = writeln!(
        w,
        "| camera | sun | setting | mean relative error | image mean | T RMSE | CPU ns per pixel |"
    );
    let _ = writeln!(w, "|---|---:|---|---:|---:|---:|---:|");
    for r in &view {
        let _ = writeln!(
            w,
            "| {} | {}° | {} | {:.2} % | {:+.2} % | {:.4} | {:.0} |",
            r.camera,
            r.sun_deg,
            r.setting,
            100.0 * r.mean_relative,
            100.0 * r.image_mean,
            r.transmittance_rmse,
            r.ns_per_pixel
        );
    }
    let _ = writeln!(
        w,
        "\n## Multiple scattering: octaves against the path tracer\n"
    );
    let _ = writeln!(
        w,
        "Mean radiance of a {} image (camera 20° above the cloud's centre at azimuth 150°, the octave test's goal view) by the march (128 view steps, full light march of 32) against the path tracer's every-order mean ({paths} paths). *Single share*: the path tracer's order 1 over its total.\n",
        if options.quick { "16×12" } else { "32×24" }
    );
    let _ = writeln!(
        w,
        "| sun | octave setting | march − MC (relative) | MC standard error | single share |"
    );
    let _ = writeln!(w, "|---:|---|---:|---:|---:|");
    for r in &octaves {
        let _ = writeln!(
            w,
            "| {}° | {} | {:+.1} % | {:.1} % | {:.1} % |",
            r.sun_deg,
            r.setting,
            100.0 * r.relative,
            100.0 * r.mc_relative_error,
            100.0 * r.single_share
        );
    }
    let _ = writeln!(
        w,
        "\n![error against cost](cloudlight.svg)\n\nThe plot: light-transmittance RMSE against CPU ns per cloudy cell, one series per sun."
    );

    let series = SUNS_DEG
        .iter()
        .map(|&sun| Series {
            name: format!("light transmittance, sun {sun}°"),
            points: light
                .iter()
                .filter(|r| r.sun_deg == sun)
                .map(|r| Point {
                    x: r.ns_per_cell,
                    y: r.rmse,
                    label: r.method.chars().take(24).collect(),
                })
                .collect(),
        })
        .collect();
    let plot = Plot {
        title: "cloudlight: light transmittance error against CPU cost".into(),
        x_label: "CPU ns per cloudy cell (f32, one thread)".into(),
        y_label: "RMSE of the transmittance".into(),
        series,
    };
    let md_path = super::write_output("docs/tradeoffs/cloudlight.md", &md)?;
    super::write_output("docs/tradeoffs/cloudlight.svg", &plot.to_svg())?;
    let mut json = String::from("{\"light\":[");
    for (i, r) in light.iter().enumerate() {
        let _ = write!(
            json,
            "{}{{\"sun_deg\":{},\"method\":{:?},\"rmse\":{},\"max\":{},\"ns_per_cell\":{}}}",
            if i > 0 { "," } else { "" },
            r.sun_deg,
            r.method,
            r.rmse,
            r.max,
            r.ns_per_cell
        );
    }
    json.push_str("]}\n");
    super::write_output("target/tradeoff/cloudlight.json", &json)?;
    eprintln!("tradeoff cloudlight: wrote {}", md_path.display());
    Ok(())
}
