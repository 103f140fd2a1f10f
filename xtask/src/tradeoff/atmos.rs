//! `cargo xtask tradeoff atmos`: every rung of the scattering ladder and its quality
//! settings against the f64 Reference (rung 4) on a fixed set of viewers, suns and
//! directions: relative luminance error, CPU cost, and GPU cost per 1280×720 frame on
//! the adapter in use (labelled with its type); then every rung and the Reference
//! against the Monte Carlo path tracer, with standard errors.

use std::fmt::Write as _;
use std::time::Instant;

use atmos::Atmosphere;
use atmos::closed_form_sky::ClosedFormSky;
use atmos::dome::{DomeInterpolated, DomeResolution};
use atmos::frame::FrameCamera;
use atmos::gpu::precomputed::PrecomputedRenderer;
use atmos::gpu::{ClosedFormRenderer, EvaluationFrequency, FrameOutput};
use atmos::ladder::{SkyModel, SkyQuery, SkySample, luminance};
use atmos::lut::{LutSettings, PrecomputedSky};
use atmos::reference::{
    PathTracedSky, PathTracerSettings, ReferenceSettings, ReferenceSky, SpectralReferenceSky,
};
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use celestial::dome::DomeColouring;
use celestial::dome_sky::SgskyDomeSky;
use celestial::gpu::SkyDomeRenderer;
use glam::DVec3;

use super::plot::{Plot, Point, Series};

/// Sun elevations of the fixed set (degrees).
const SUN_ELEVATIONS_DEG: [f64; 7] = [-6.0, 0.0, 2.0, 10.0, 30.0, 60.0, 90.0];
/// Camera altitudes of the fixed set (m).
const ALTITUDES: [f64; 5] = [0.0, 1_000.0, 10_000.0, 100_000.0, 1_000_000.0];
/// Sun elevations at or above this count as "day" for the 1 % goal; below, twilight.
const DAY_THRESHOLD_DEG: f64 = 5.0;
/// Reference luminances below this (per unit sun irradiance per sr) are "dark" (space
/// above the limb, the night side): relative errors there are meaningless, so they are
/// reported as a count and an absolute error instead.
const DARK_LUMINANCE: f64 = 1e-6;
/// The frame the GPU cost is quoted for.
const FRAME: (u32, u32) = (1280, 720);

struct Viewpoint {
    sun_elevation_deg: f64,
    altitude: f64,
    queries: Vec<SkyQuery>,
}

/// The path-traced truth: a smaller set (`PT_DIRECTIONS` directions per
/// viewpoint of the fixed set's suns and altitudes), each view path traced with
/// `PT_SAMPLES` samples, luminance and its standard error.
const PT_DIRECTIONS: usize = 24;
const PT_SAMPLES: u32 = 1024;

struct PathTracedSet {
    /// (is day, query, traced luminance, its standard error).
    views: Vec<(bool, SkyQuery, f64, f64)>,
    seconds: f64,
    samples: u32,
}

fn path_traced_set(atmosphere: &Atmosphere, quick: bool) -> Result<PathTracedSet, String> {
    let samples = if quick { 128 } else { PT_SAMPLES };
    let tracer = PathTracedSky::new(
        atmosphere,
        PathTracerSettings {
            samples,
            ..PathTracerSettings::default()
        },
    )
    .map_err(|e| e.to_string())?;
    let set = fixed_set(atmosphere, PT_DIRECTIONS)?;
    let started = Instant::now();
    let mut views = Vec::new();
    for viewpoint in &set {
        let is_day = viewpoint.sun_elevation_deg >= DAY_THRESHOLD_DEG;
        for (q, pt) in viewpoint
            .queries
            .iter()
            .zip(tracer.estimate_batch(&viewpoint.queries))
        {
            if pt.total.luminance >= DARK_LUMINANCE {
                views.push((
                    is_day,
                    *q,
                    pt.total.luminance,
                    pt.total.luminance_standard_error,
                ));
            }
        }
    }
    Ok(PathTracedSet {
        views,
        seconds: started.elapsed().as_secs_f64(),
        samples,
    })
}

/// One model against the path-traced set: per day / twilight, (mean |e|, mean e, its
/// standard error, max |e|, the standard error of that view, mean σ), e relative.
fn against_path_tracer(model: &dyn SkyModel, traced: &PathTracedSet) -> [[f64; 6]; 2] {
    let mut out = [[0.0; 6]; 2];
    for (k, day) in [true, false].into_iter().enumerate() {
        let errors: Vec<(f64, f64)> = traced
            .views
            .iter()
            .filter(|v| v.0 == day)
            .map(|(_, q, want, sigma)| {
                let got = luminance(model.evaluate(q).radiance);
                ((got - want) / want, sigma * got / (want * want))
            })
            .collect();
        let n = errors.len().max(1) as f64;
        let (max, max_sigma) = errors.iter().fold((0.0f64, 0.0), |m, e| {
            if e.0.abs() > m.0 { (e.0.abs(), e.1) } else { m }
        });
        out[k] = [
            errors.iter().map(|e| e.0.abs()).sum::<f64>() / n,
            errors.iter().map(|e| e.0).sum::<f64>() / n,
            errors.iter().map(|e| e.1 * e.1).sum::<f64>().sqrt() / n,
            max,
            max_sigma,
            errors.iter().map(|e| e.1).sum::<f64>() / n,
        ];
    }
    out
}

fn path_tracer_markdown(traced: &PathTracedSet, rows: &[(String, [[f64; 6]; 2])]) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n## Against the path tracer\n\nThe truth above is the iterated-orders Reference; \
         here every rung and the Reference itself are measured against the unbiased Monte \
         Carlo path tracer (`atmos::reference::PathTracedSky`): the fixed set's \
         suns and altitudes with {PT_DIRECTIONS} directions each, {} samples per view \
         ({} views brighter than {DARK_LUMINANCE:e}, {:.0} s). e = (model − path tracer) / \
         path tracer in luminance; ± is the Monte Carlo standard error of the mean, σ the \
         standard error of one view.\n",
        traced.samples,
        traced.views.len(),
        traced.seconds
    );
    let _ = writeln!(
        md,
        "| model | day mean abs | day mean signed | day max abs (σ of that view) | twilight mean abs | twilight mean signed | twilight max abs (σ) | mean σ day / twilight |"
    );
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|");
    for (label, [d, t]) in rows {
        let _ = writeln!(
            md,
            "| {label} | {:.2} % | {:+.2} ± {:.2} % | {:.1} % ({:.1} %) | {:.2} % | {:+.2} ± {:.2} % | {:.1} % ({:.1} %) | {:.2} / {:.2} % |",
            100.0 * d[0],
            100.0 * d[1],
            100.0 * d[2],
            100.0 * d[3],
            100.0 * d[4],
            100.0 * t[0],
            100.0 * t[1],
            100.0 * t[2],
            100.0 * t[3],
            100.0 * t[4],
            100.0 * d[5],
            100.0 * t[5],
        );
    }
    md
}

/// Directions covering the sphere evenly (a Fibonacci lattice).
fn sphere_directions(count: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let radius = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            DVec3::new(radius * phi.cos(), radius * phi.sin(), z)
        })
        .collect()
}

fn fixed_set(atmosphere: &Atmosphere, directions: usize) -> Result<Vec<Viewpoint>, String> {
    let views = sphere_directions(directions);
    let mut set = Vec::new();
    for &sun_elevation_deg in &SUN_ELEVATIONS_DEG {
        let e = sun_elevation_deg.to_radians();
        // The viewer stands on +z; the sun lies in the x–z plane.
        let sun = DVec3::new(e.cos(), 0.0, e.sin());
        for &altitude in &ALTITUDES {
            let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + altitude);
            let queries = views
                .iter()
                .map(|&view| SkyQuery::new(atmosphere.planet_radius, position, view, sun))
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| e.to_string())?;
            set.push(Viewpoint {
                sun_elevation_deg,
                altitude,
                queries,
            });
        }
    }
    Ok(set)
}

/// How a rung runs on the GPU (for the frame cost).
enum GpuVariant {
    /// SGSky's dome painted from the closed form (celestial's pass).
    SgskyDome(DomeColouring),
    ClosedForm(EvaluationFrequency),
    SingleScattering(SingleScatteringSettings),
    Precomputed(LutSettings),
}

struct Rung {
    rung: &'static str,
    model: Box<dyn SkyModel + Sync>,
    gpu: Option<GpuVariant>,
}

fn rungs(atmosphere: &Atmosphere, quick: bool) -> Result<Vec<Rung>, String> {
    let e = |e: atmos::AtmosError| e.to_string();
    let mut rungs = Vec::new();
    // SGSky's 12-sided dome (celestial), painted from the closed form: SGSky's weights
    // (13 queries) and every vertex from the model (49).
    for colouring in [DomeColouring::SeedWeights, DomeColouring::Model] {
        rungs.push(Rung {
            rung: "0 SGSky dome",
            model: Box::new(
                SgskyDomeSky::new(
                    ClosedFormSky::new(atmosphere).map_err(e)?,
                    atmosphere,
                    colouring,
                )
                .map_err(|e| e.to_string())?,
            ),
            gpu: Some(GpuVariant::SgskyDome(colouring)),
        });
    }
    rungs.push(Rung {
        rung: "1 closed form",
        model: Box::new(ClosedFormSky::new(atmosphere).map_err(e)?),
        gpu: Some(GpuVariant::ClosedForm(EvaluationFrequency::PerPixel)),
    });
    let domes: &[(u32, u32)] = if quick {
        &[(8, 16)]
    } else {
        &[(8, 16), (16, 32), (32, 64)]
    };
    for &(rings, segments) in domes {
        let resolution = DomeResolution { rings, segments };
        rungs.push(Rung {
            rung: "1 closed form",
            model: Box::new(
                DomeInterpolated::new(
                    ClosedFormSky::new(atmosphere).map_err(e)?,
                    resolution,
                    atmosphere,
                )
                .map_err(e)?,
            ),
            gpu: Some(GpuVariant::ClosedForm(EvaluationFrequency::PerVertex(
                resolution,
            ))),
        });
    }
    let samples: &[(u32, u32)] = if quick {
        &[(32, 8)]
    } else {
        &[(8, 4), (16, 4), (32, 8), (64, 16), (128, 32)]
    };
    for &(view_samples, light_samples) in samples {
        let settings = SingleScatteringSettings {
            view_samples,
            light_samples,
        };
        rungs.push(Rung {
            rung: "2 single scattering",
            model: Box::new(SingleScatteringSky::new(atmosphere, settings).map_err(e)?),
            gpu: Some(GpuVariant::SingleScattering(settings)),
        });
    }
    let luts: Vec<(&str, LutSettings)> = if quick {
        vec![("default", LutSettings::default())]
    } else {
        let default = LutSettings::default();
        vec![
            (
                "small",
                LutSettings {
                    transmittance_size: [64, 16],
                    multiple_scattering_size: [16, 16],
                    sky_view_size: [96, 54],
                    sky_view_samples: 16,
                    ..default
                },
            ),
            ("default", default),
            (
                "large",
                LutSettings {
                    transmittance_size: [512, 128],
                    multiple_scattering_size: [256, 64],
                    sky_view_size: [384, 216],
                    sky_view_samples: 60,
                    ..default
                },
            ),
        ]
    };
    for (_name, settings) in luts {
        rungs.push(Rung {
            rung: "3 precomputed",
            model: Box::new(PrecomputedSky::new(atmosphere, &settings).map_err(e)?),
            gpu: Some(GpuVariant::Precomputed(settings)),
        });
    }
    Ok(rungs)
}

/// Evaluates `model` over the set; returns the samples and the CPU seconds per
/// evaluation split into per-viewpoint setup (e.g. a dome's vertices, a per-frame LUT)
/// and per-query cost, from wall-clock timing on one thread (the setup figure is
/// reported; the per-query cost is re-measured by criterion).
fn evaluate_all(model: &dyn SkyModel, set: &[Viewpoint]) -> (Vec<Vec<SkySample>>, f64, f64) {
    let mut all = Vec::with_capacity(set.len());
    let mut first_calls = Vec::new();
    let mut later_calls = Vec::new();
    for viewpoint in set {
        let mut samples = Vec::with_capacity(viewpoint.queries.len());
        for (i, query) in viewpoint.queries.iter().enumerate() {
            let start = Instant::now();
            samples.push(model.evaluate(query));
            let seconds = start.elapsed().as_secs_f64();
            if i == 0 {
                first_calls.push(seconds);
            } else {
                later_calls.push(seconds);
            }
        }
        all.push(samples);
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    };
    let per_query = median(&mut later_calls);
    let setup = (median(&mut first_calls) - per_query).max(0.0);
    (all, setup, per_query)
}

/// Where the per-query criterion measurements write their raw estimates.
const CRITERION_DIR: &str = "target/tradeoff/criterion";

/// The viewpoint whose queries criterion times for every rung: camera 1 km up, sun
/// 30°, the 96 directions over the sphere (the GPU frame's viewpoint too).
const TIMED_ALTITUDE: f64 = 1_000.0;
const TIMED_SUN_DEG: f64 = 30.0;

/// Seconds per query of `model` on the CPU, measured by criterion (used as a library):
/// one iteration evaluates all of `queries` as a frame's pixels
/// ([`SkyModel::evaluate_batch`]: a per-frame LUT is looked up once per batch, not per
/// query) after a first call that does the viewpoint's setup, and the result is
/// criterion's median per iteration divided by the number of queries. The estimates
/// criterion writes under `target/tradeoff/criterion/<slug>/new/estimates.json` are
/// read back.
fn criterion_seconds_per_query(
    model: &dyn SkyModel,
    queries: &[SkyQuery],
    slug: &str,
    quick: bool,
) -> Result<f64, String> {
    let (warm_up, measurement) = if quick { (100, 500) } else { (500, 2_000) };
    let mut criterion = criterion::Criterion::default()
        .output_directory(std::path::Path::new(CRITERION_DIR))
        .sample_size(10)
        .warm_up_time(std::time::Duration::from_millis(warm_up))
        .measurement_time(std::time::Duration::from_millis(measurement))
        .without_plots();
    // the viewpoint's setup happens here, outside the timing
    std::hint::black_box(model.evaluate_batch(queries));
    criterion.bench_function(slug, |b| {
        b.iter(|| std::hint::black_box(model.evaluate_batch(std::hint::black_box(queries))))
    });
    let path = std::path::Path::new(CRITERION_DIR)
        .join(slug)
        .join("new")
        .join("estimates.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("criterion estimates {}: {e}", path.display()))?;
    let nanoseconds = median_point_estimate(&text)
        .ok_or_else(|| format!("no median point estimate in {}", path.display()))?;
    Ok(nanoseconds * 1e-9 / queries.len().max(1) as f64)
}

/// `median.point_estimate` of a criterion `estimates.json` (nanoseconds).
pub(super) fn median_point_estimate(json: &str) -> Option<f64> {
    let median = &json[json.find("\"median\"")?..];
    let value = &median[median.find("\"point_estimate\":")? + "\"point_estimate\":".len()..];
    let end = value.find([',', '}'])?;
    value[..end].trim().parse().ok()
}

/// Evaluates `model` over the set on all cores (for the slow reference).
fn evaluate_parallel(model: &(dyn SkyModel + Sync), set: &[Viewpoint]) -> Vec<Vec<SkySample>> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut out: Vec<Vec<SkySample>> = vec![Vec::new(); set.len()];
    std::thread::scope(|scope| {
        let chunk = set.len().div_ceil(threads);
        for (viewpoints, outputs) in set.chunks(chunk).zip(out.chunks_mut(chunk)) {
            scope.spawn(move || {
                for (viewpoint, output) in viewpoints.iter().zip(outputs.iter_mut()) {
                    *output = viewpoint
                        .queries
                        .iter()
                        .map(|q| model.evaluate(q))
                        .collect();
                }
            });
        }
    });
    out
}

#[derive(Debug, Default, Clone)]
struct ErrorStats {
    relative: Vec<f64>,
    dark: usize,
    dark_max_abs: f64,
    non_finite: usize,
}

impl ErrorStats {
    fn add(&mut self, reference: f64, model: f64) {
        if !model.is_finite() {
            self.non_finite += 1;
        } else if reference < DARK_LUMINANCE {
            self.dark += 1;
            self.dark_max_abs = self.dark_max_abs.max((model - reference).abs());
        } else {
            self.relative.push((model - reference).abs() / reference);
        }
    }
    fn mean(&self) -> f64 {
        self.relative.iter().sum::<f64>() / self.relative.len().max(1) as f64
    }
    fn max(&self) -> f64 {
        self.relative.iter().copied().fold(0.0, f64::max)
    }
}

/// The RGB Reference measured against the spectral Reference: the error of rendering
/// the atmosphere in three channels, which no RGB rung can be more accurate than.
struct SpectralComparison {
    label: String,
    seconds: f64,
    day: ErrorStats,
    twilight: ErrorStats,
    by_sun: Vec<ErrorStats>,
    /// Distance between the two chromaticities (r, g, b)/(r + g + b), day queries.
    day_chromaticity: Vec<f64>,
}

fn spectral_comparison(
    atmosphere: &Atmosphere,
    set: &[Viewpoint],
    truth: &[Vec<SkySample>],
    quick: bool,
) -> Result<SpectralComparison, String> {
    let started = Instant::now();
    let spectral = SpectralReferenceSky::new(atmosphere, reference_settings(quick))
        .map_err(|e| e.to_string())?;
    let label = spectral.label();
    let samples = evaluate_parallel(&spectral, set);
    let seconds = started.elapsed().as_secs_f64();
    let mut day = ErrorStats::default();
    let mut twilight = ErrorStats::default();
    let mut by_sun = vec![ErrorStats::default(); SUN_ELEVATIONS_DEG.len()];
    let mut day_chromaticity = Vec::new();
    let chromaticity = |c: [f64; 3]| c.map(|v| v / (c[0] + c[1] + c[2]));
    for ((viewpoint, rgb), spectral) in set.iter().zip(truth).zip(&samples) {
        let sun_index = SUN_ELEVATIONS_DEG
            .iter()
            .position(|&e| e == viewpoint.sun_elevation_deg)
            .expect("viewpoints use the fixed sun elevations");
        let is_day = viewpoint.sun_elevation_deg >= DAY_THRESHOLD_DEG;
        for (spectral, rgb) in spectral.iter().zip(rgb) {
            let (want, got) = (luminance(spectral.radiance), luminance(rgb.radiance));
            by_sun[sun_index].add(want, got);
            if is_day {
                day.add(want, got);
                if want >= DARK_LUMINANCE {
                    let (a, b) = (chromaticity(spectral.radiance), chromaticity(rgb.radiance));
                    let distance = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
                    day_chromaticity.push(distance);
                }
            } else {
                twilight.add(want, got);
            }
        }
    }
    eprintln!(
        "RGB reference vs `{label}`: day mean {:.2} %, twilight mean {:.2} % ({seconds:.1} s)",
        100.0 * day.mean(),
        100.0 * twilight.mean()
    );
    Ok(SpectralComparison {
        label,
        seconds,
        day,
        twilight,
        by_sun,
        day_chromaticity,
    })
}

struct Row {
    rung: &'static str,
    label: String,
    day: ErrorStats,
    twilight: ErrorStats,
    /// Day errors per camera altitude (same order as `ALTITUDES`).
    day_by_altitude: Vec<ErrorStats>,
    /// Errors per sun elevation, all altitudes (same order as `SUN_ELEVATIONS_DEG`).
    by_sun: Vec<ErrorStats>,
    cpu_setup: f64,
    cpu_query: f64,
    gpu_frame: Option<f64>,
}

fn gpu_frame_seconds(
    ctx: &skyscape_harness::GpuContext,
    atmosphere: &Atmosphere,
    variant: &GpuVariant,
) -> Result<f64, String> {
    let e = |e: atmos::AtmosError| e.to_string();
    let camera = FrameCamera::look_at(
        DVec3::new(0.0, 0.0, atmosphere.planet_radius + 1_000.0),
        DVec3::new(1.0, 0.0, 0.1),
        DVec3::Z,
        1.0,
        FRAME.0,
        FRAME.1,
        DVec3::new(30f64.to_radians().cos(), 0.3, 30f64.to_radians().sin()),
        None,
    )
    .map_err(e)?;
    let output = FrameOutput::new(&ctx.device, FRAME.0, FRAME.1).map_err(e)?;
    let seconds = match variant {
        GpuVariant::SgskyDome(colouring) => {
            let c = |e: celestial::CelestialError| e.to_string();
            let sky = SgskyDomeSky::new(
                ClosedFormSky::new(atmosphere).map_err(e)?,
                atmosphere,
                *colouring,
            )
            .map_err(c)?;
            let position = glam::Vec3::from_array(camera.position).as_dvec3();
            let sun = glam::Vec3::from_array(camera.sun).as_dvec3().normalize();
            let dome = sky.uniforms(position, sun).map_err(c)?;
            let mut renderer = SkyDomeRenderer::new(&ctx.device).map_err(c)?;
            renderer
                .prepare(&ctx.queue, &camera, &dome, &output)
                .map_err(c)?;
            skyscape_harness::median_pass_seconds(ctx, 5, |encoder, timer, span| {
                renderer
                    .encode(encoder, Some(timer.compute_writes(span)))
                    .expect("prepared above");
            })
        }
        GpuVariant::ClosedForm(frequency) => {
            let mut renderer =
                ClosedFormRenderer::new(&ctx.device, atmosphere, *frequency).map_err(e)?;
            renderer.prepare(&ctx.queue, &camera, &output).map_err(e)?;
            // Frames at high sample counts take seconds on a CPU adapter: 2 timed frames.
            skyscape_harness::median_pass_seconds(ctx, 2, |encoder, timer, span| {
                renderer
                    .encode(encoder, Some(timer.compute_writes(span)))
                    .expect("prepared above");
            })
        }
        GpuVariant::SingleScattering(settings) => {
            let mut renderer =
                atmos::gpu::SingleScatteringRenderer::new(&ctx.device, atmosphere, *settings)
                    .map_err(e)?;
            renderer.prepare(&ctx.queue, &camera, &output).map_err(e)?;
            // Frames at high sample counts take seconds on a CPU adapter: 2 timed frames.
            skyscape_harness::median_pass_seconds(ctx, 2, |encoder, timer, span| {
                renderer
                    .encode(encoder, Some(timer.compute_writes(span)))
                    .expect("prepared above");
            })
        }
        GpuVariant::Precomputed(settings) => {
            return precomputed_frame_seconds(ctx, atmosphere, *settings, &camera, &output);
        }
    };
    seconds.map_err(|e| e.to_string())
}

/// The precomputed rung's frame: per-frame LUT bakes (sky view, aerial perspective)
/// and the per-pixel lookups, each its own timed pass; the static LUTs (per atmosphere)
/// are baked once beforehand and not counted. Median of 5 frames after a warm-up.
fn precomputed_frame_seconds(
    ctx: &skyscape_harness::GpuContext,
    atmosphere: &Atmosphere,
    settings: LutSettings,
    camera: &FrameCamera,
    output: &FrameOutput,
) -> Result<f64, String> {
    let e = |e: atmos::AtmosError| e.to_string();
    let mut renderer = PrecomputedRenderer::new(&ctx.device, atmosphere, settings).map_err(e)?;
    renderer.prepare(&ctx.queue, camera, output).map_err(e)?;
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    renderer.encode_static_luts(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    const FRAMES: u32 = 6;
    let timer = skyscape_harness::PassTimer::new(ctx, 2 * FRAMES).map_err(|e| e.to_string())?;
    for frame in 0..FRAMES {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        renderer.encode_frame_luts(&mut encoder, Some(timer.compute_writes(2 * frame)));
        renderer
            .encode_pixels(&mut encoder, Some(timer.compute_writes(2 * frame + 1)))
            .map_err(e)?;
        if frame + 1 == FRAMES {
            timer.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
    }
    let spans = timer.read_seconds(ctx).map_err(|e| e.to_string())?;
    let mut frames: Vec<f64> = spans.chunks_exact(2).skip(1).map(|p| p[0] + p[1]).collect();
    frames.sort_by(f64::total_cmp);
    Ok(frames[frames.len() / 2])
}

/// Runs the study and writes the report.
pub fn run(options: &super::Options) -> Result<(), String> {
    let atmosphere = Atmosphere::earth();
    let directions = if options.quick { 24 } else { 96 };
    let set = fixed_set(&atmosphere, directions)?;
    let query_count: usize = set.iter().map(|v| v.queries.len()).sum();
    eprintln!(
        "tradeoff atmos: {} viewpoints × {directions} directions = {query_count} queries",
        set.len()
    );

    let reference_started = Instant::now();
    let reference = reference_model(&atmosphere, options.quick)?;
    let reference_label = reference.label();
    let truth = evaluate_parallel(reference.as_ref(), &set);
    let reference_seconds = reference_started.elapsed().as_secs_f64();
    eprintln!(
        "reference `{reference_label}`: {reference_seconds:.1} s (precomputation + {query_count} queries)"
    );

    let spectral = spectral_comparison(&atmosphere, &set, &truth, options.quick)?;

    let traced = path_traced_set(&atmosphere, options.quick)?;
    eprintln!(
        "path tracer: {} views, {} samples each, {:.1} s",
        traced.views.len(),
        traced.samples,
        traced.seconds
    );
    let mut traced_rows = vec![(
        reference_label.clone(),
        against_path_tracer(reference.as_ref(), &traced),
    )];

    let gpu = match skyscape_harness::context() {
        Ok(ctx) => Some(ctx),
        Err(e) if skyscape_harness::gpu_required() => return Err(e.to_string()),
        Err(e) => {
            eprintln!("SKIPPED GPU frame costs: {e}");
            None
        }
    };

    let mut rows = Vec::new();
    for rung in rungs(&atmosphere, options.quick)? {
        let label = rung.model.label();
        traced_rows.push((
            label.clone(),
            against_path_tracer(rung.model.as_ref(), &traced),
        ));
        let (samples, cpu_setup, _) = evaluate_all(rung.model.as_ref(), &set);
        let timed = set
            .iter()
            .find(|v| {
                (v.altitude - TIMED_ALTITUDE).abs() < 0.5
                    && (v.sun_elevation_deg - TIMED_SUN_DEG).abs() < 1e-9
            })
            .ok_or("the set lacks the timed viewpoint")?;
        let cpu_query = criterion_seconds_per_query(
            rung.model.as_ref(),
            &timed.queries,
            &super::slug(&label),
            options.quick,
        )?;
        let mut day = ErrorStats::default();
        let mut twilight = ErrorStats::default();
        let mut day_by_altitude = vec![ErrorStats::default(); ALTITUDES.len()];
        let mut by_sun = vec![ErrorStats::default(); SUN_ELEVATIONS_DEG.len()];
        for ((viewpoint, reference), model) in set.iter().zip(&truth).zip(&samples) {
            let sun_index = SUN_ELEVATIONS_DEG
                .iter()
                .position(|&e| e == viewpoint.sun_elevation_deg)
                .expect("viewpoints use the fixed sun elevations");
            let is_day = viewpoint.sun_elevation_deg >= DAY_THRESHOLD_DEG;
            let altitude_index = ALTITUDES
                .iter()
                .position(|&a| a == viewpoint.altitude)
                .expect("viewpoints use the fixed altitudes");
            for (r, m) in reference.iter().zip(model) {
                let (r, m) = (luminance(r.radiance), luminance(m.radiance));
                by_sun[sun_index].add(r, m);
                if is_day {
                    day.add(r, m);
                    day_by_altitude[altitude_index].add(r, m);
                } else {
                    twilight.add(r, m);
                }
            }
        }
        let gpu_frame = match (&gpu, &rung.gpu) {
            (Some(ctx), Some(variant)) => match gpu_frame_seconds(ctx, &atmosphere, variant) {
                Ok(s) => Some(s),
                Err(message) => {
                    eprintln!("{label}: no GPU frame cost: {message}");
                    None
                }
            },
            _ => None,
        };
        eprintln!(
            "{label}: day mean {:.3} % max {:.2} %, twilight mean {:.2} %, cpu {:.0} ns/query",
            100.0 * day.mean(),
            100.0 * day.max(),
            100.0 * twilight.mean(),
            cpu_query * 1e9
        );
        rows.push(Row {
            rung: rung.rung,
            label,
            day,
            twilight,
            day_by_altitude,
            by_sun,
            cpu_setup,
            cpu_query,
            gpu_frame,
        });
    }

    let adapter = gpu.map(|ctx| {
        let kind = if ctx.is_cpu_adapter() {
            "a CPU adapter (software rasteriser): these are CPU timings, not GPU speed"
        } else {
            "a hardware GPU"
        };
        format!("{} — {kind}", skyscape_harness::describe_adapter(&ctx.info))
    });
    let report = markdown(
        &rows,
        &reference_label,
        reference_seconds,
        query_count,
        directions,
        adapter.as_deref(),
        &spectral,
        options.quick,
    );
    let report = report + &path_tracer_markdown(&traced, &traced_rows);
    let json = json(&rows, &reference_label);
    let plot = error_plot(&rows, adapter.is_some());
    let prefix = if options.quick {
        "target/tradeoff/atmos-quick"
    } else {
        "docs/tradeoffs/atmos"
    };
    let md_path = super::write_output(&format!("{prefix}.md"), &report)?;
    super::write_output(&format!("{prefix}.svg"), &plot.to_svg())?;
    super::write_output("target/tradeoff/atmos.json", &json)?;
    println!("{report}");
    eprintln!("wrote {}", md_path.display());
    Ok(())
}

fn reference_settings(quick: bool) -> ReferenceSettings {
    if quick {
        ReferenceSettings::low()
    } else {
        ReferenceSettings::default()
    }
}

fn reference_model(
    atmosphere: &Atmosphere,
    quick: bool,
) -> Result<Box<dyn SkyModel + Sync>, String> {
    Ok(Box::new(
        ReferenceSky::new(atmosphere, reference_settings(quick)).map_err(|e| e.to_string())?,
    ))
}

fn frame_pixels() -> f64 {
    f64::from(FRAME.0) * f64::from(FRAME.1)
}

/// CPU seconds for a 1280×720 frame derived from the measured setup and per-query costs.
fn cpu_frame(row: &Row) -> f64 {
    row.cpu_setup + row.cpu_query * frame_pixels()
}

#[allow(clippy::too_many_arguments)]
fn markdown(
    rows: &[Row],
    reference_label: &str,
    reference_seconds: f64,
    query_count: usize,
    directions: usize,
    adapter: Option<&str>,
    spectral: &SpectralComparison,
    quick: bool,
) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# atmos: speed against accuracy\n");
    let _ = writeln!(
        md,
        "Generated by `cargo xtask tradeoff atmos`{} (release build: `cargo run --release -p xtask -- tradeoff atmos`). \
         Raw rows: `target/tradeoff/atmos.json`.\n",
        if quick { " --quick" } else { "" }
    );
    let _ = writeln!(
        md,
        "**Set.** Sun elevations {:?}°; camera altitudes {:?} m; {directions} view directions \
         covering the sphere (Fibonacci lattice) per viewpoint: {query_count} queries. Earth \
         defaults (`Atmosphere::earth()`). **Truth:** {reference_label} ({reference_seconds:.1} s \
         for its precomputation and all queries on all cores).\n",
        SUN_ELEVATIONS_DEG, ALTITUDES
    );
    let _ = writeln!(
        md,
        "**Error** is the relative error of luminance (Rec. 709 weights) of the in-scattered \
         radiance, `|Y − Y_ref| / Y_ref`, over queries whose reference luminance is ≥ {DARK_LUMINANCE:e} \
         per unit sun irradiance per sr; darker queries (space above the limb, the night side) \
         are counted apart with their largest absolute error. *Day*: sun ≥ {DAY_THRESHOLD_DEG}°; \
         *twilight*: −6°, 0°, 2°.\n"
    );
    let _ = writeln!(
        md,
        "**CPU cost**, one thread: *query* is the per-pixel evaluation measured by **criterion** \
         (median over 10 samples of evaluating the 96 directions of the viewpoint 1 km up as one batch, `SkyModel::evaluate_batch`, \
         sun 30°, after the viewpoint's setup; raw estimates in `target/tradeoff/criterion/`); \
         *setup* is the per-viewpoint work a frame does once (a dome's vertices, per-frame \
         LUTs), by wall clock inside this command (median over the set of the first query \
         minus the later ones); *CPU frame* = setup + 1280·720 × query. \
         **GPU frame** is the median of 5 (single scattering: 2) timestamp-query measurements of a 1280×720 frame \
         (camera 1 km up, sun 30°) on: {}.\n",
        adapter.unwrap_or("no adapter (GPU costs skipped)")
    );
    let _ = writeln!(
        md,
        "| rung | setting | day mean | day max | twilight mean | twilight max | dark (max abs) | CPU setup | CPU query | CPU frame | GPU frame |"
    );
    let _ = writeln!(md, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for row in rows {
        let dark = row.day.dark + row.twilight.dark;
        let dark_abs = row.day.dark_max_abs.max(row.twilight.dark_max_abs);
        let _ = writeln!(
            md,
            "| {} | {} | {:.2} % | {:.1} % | {:.1} % | {:.0} % | {dark} ({dark_abs:.1e}) | {} | {} | {} | {} |",
            row.rung,
            row.label,
            100.0 * row.day.mean(),
            100.0 * row.day.max(),
            100.0 * row.twilight.mean(),
            100.0 * row.twilight.max(),
            seconds(row.cpu_setup),
            seconds(row.cpu_query),
            seconds(cpu_frame(row)),
            row.gpu_frame.map_or("—".into(), seconds),
        );
        if row.day.non_finite + row.twilight.non_finite > 0 {
            let _ = writeln!(
                md,
                "|  | **{} non-finite results** |  |  |  |  |  |  |  |  |  |",
                row.day.non_finite + row.twilight.non_finite
            );
        }
    }
    md.push_str(
        "\n*SGSky's dome* paints the sky above the horizon and, below it, SimGear's skirt in \
         the horizon's (fog) colour, which the scene's terrain covers: rays that end on the \
         ground, most of the sphere seen from altitude, take that colour where the truth is \
         the dim air in front of the ground. The 0 km column (below) is the sky the dome is \
         for; above the horizon alone against rung 3: `docs/tradeoffs/sky_dome.md`.\n",
    );
    md.push_str(&goals(rows));
    let _ = writeln!(
        md,
        "\n**Day mean error by camera altitude** (sun ≥ {DAY_THRESHOLD_DEG}°):\n"
    );
    let _ = write!(md, "| rung | setting |");
    for altitude in ALTITUDES {
        let _ = write!(md, " {} km |", altitude / 1000.0);
    }
    let _ = writeln!(md, "\n|---|---|{}", "---:|".repeat(ALTITUDES.len()));
    for row in rows {
        let _ = write!(md, "| {} | {} |", row.rung, row.label);
        for stats in &row.day_by_altitude {
            let _ = write!(md, " {:.2} % |", 100.0 * stats.mean());
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(
        md,
        "\n**Mean error by sun elevation** (all camera altitudes; below \
         {DAY_THRESHOLD_DEG}° is twilight):\n"
    );
    let _ = write!(md, "| rung | setting |");
    for elevation in SUN_ELEVATIONS_DEG {
        let _ = write!(md, " {elevation}° |");
    }
    let _ = writeln!(
        md,
        "\n|---|---|{}",
        "---:|".repeat(SUN_ELEVATIONS_DEG.len())
    );
    for row in rows {
        let _ = write!(md, "| {} | {} |", row.rung, row.label);
        for stats in &row.by_sun {
            let _ = write!(md, " {:.2} % |", 100.0 * stats.mean());
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(
        md,
        "\n![error vs cost](atmos.svg)\n\nThe plot shows day mean error against the CPU cost \
         per query (and the GPU frame cost where measured)."
    );
    md.push_str(&spectral_markdown(spectral));
    md
}

/// The RGB Reference against the spectral one.
fn spectral_markdown(spectral: &SpectralComparison) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n## Three channels against a spectrum\n\nEvery rung above renders in three channels \
         (the atmosphere's coefficients at ≈ 680, 550, 440 nm read as linear sRGB). The truth \
         itself was measured against **{}**: the same Reference at 18 wavelengths \
         (390–730 nm), through the CIE 1931 observer to linear sRGB, white-balanced to a \
         5,778 K black-body sun (`atmos::reference::spectral`; {:.1} s for its six \
         precomputations and all queries). Same set, same luminance error, the RGB \
         Reference as the model:\n",
        spectral.label, spectral.seconds
    );
    let mut chromaticity = spectral.day_chromaticity.clone();
    chromaticity.sort_by(f64::total_cmp);
    let mean_chromaticity = chromaticity.iter().sum::<f64>() / chromaticity.len().max(1) as f64;
    let p95 = chromaticity
        .get((chromaticity.len() * 95 / 100).min(chromaticity.len().saturating_sub(1)))
        .copied()
        .unwrap_or(0.0);
    let _ = writeln!(
        md,
        "| | day mean | day max | twilight mean | twilight max | day chromaticity distance, mean / p95 |"
    );
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|");
    let _ = writeln!(
        md,
        "| RGB Reference vs spectral | {:.2} % | {:.1} % | {:.1} % | {:.0} % | {mean_chromaticity:.4} / {p95:.4} |",
        100.0 * spectral.day.mean(),
        100.0 * spectral.day.max(),
        100.0 * spectral.twilight.mean(),
        100.0 * spectral.twilight.max(),
    );
    let _ = write!(md, "\nBy sun elevation (mean):");
    for (elevation, stats) in SUN_ELEVATIONS_DEG.iter().zip(&spectral.by_sun) {
        let _ = write!(md, " {elevation}°: {:.2} %;", 100.0 * stats.mean());
    }
    let _ = writeln!(
        md,
        "\n\nThe chromaticity distance is the Euclidean distance between (r, g, b)/(r + g + b) \
         of the two results. A rung's error against the RGB truth well below this row is \
         smaller than the error of rendering the atmosphere in three channels at all."
    );
    md
}

/// The two goals, checked against the rows of the default settings.
fn goals(rows: &[Row]) -> String {
    let default_lut = LutSettings::default();
    let find = |prefix: &str| rows.iter().find(|r| r.label.starts_with(prefix));
    let precomputed = find(&format!(
        "precomputed (T {}x{}",
        default_lut.transmittance_size[0], default_lut.transmittance_size[1]
    ));
    let default_single = SingleScatteringSettings::default();
    let single = find(&format!(
        "single scattering ({}/{})",
        default_single.view_samples, default_single.light_samples
    ));
    let mut md = String::from("\n**Goals** (default settings of rungs 2 and 3):\n\n");
    if let Some(p) = precomputed {
        let _ = writeln!(
            md,
            "* Precomputed within 1 % mean relative luminance error of the reference for sun ≥ \
             {DAY_THRESHOLD_DEG}°: **{:.2} %** — {} (twilight, reported apart: {:.1} %).",
            100.0 * p.day.mean(),
            if p.day.mean() <= 0.01 {
                "met"
            } else {
                "**not met**"
            },
            100.0 * p.twilight.mean()
        );
    }
    if let (Some(p), Some(s)) = (precomputed, single) {
        let cpu = s.cpu_query / p.cpu_query;
        let _ = write!(
            md,
            "* Precomputed ≥ 50× cheaper per pixel than single scattering at its default: CPU \
             per query (criterion) **{cpu:.0}×**"
        );
        if let (Some(pg), Some(sg)) = (p.gpu_frame, s.gpu_frame) {
            let _ = write!(
                md,
                ", GPU frame (per-frame LUT bakes + per-pixel pass) **{:.1}×**",
                sg / pg
            );
        }
        let _ = writeln!(
            md,
            " — {}.",
            if cpu >= 50.0 {
                "met on the CPU"
            } else {
                "**not met** here"
            }
        );
    }
    md
}

fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.2} s")
    } else if s >= 1e-3 {
        format!("{:.2} ms", s * 1e3)
    } else if s >= 1e-6 {
        format!("{:.2} µs", s * 1e6)
    } else {
        format!("{:.0} ns", s * 1e9)
    }
}

fn error_plot(rows: &[Row], with_gpu: bool) -> Plot {
    let mut series: Vec<Series> = Vec::new();
    for row in rows {
        let name = format!("{} (CPU per query)", row.rung);
        let point = Point {
            x: row.cpu_query,
            y: row.day.mean(),
            label: row.label.clone(),
        };
        match series.iter_mut().find(|s| s.name == name) {
            Some(s) => s.points.push(point),
            None => series.push(Series {
                name,
                points: vec![point],
            }),
        }
        if let (true, Some(frame)) = (with_gpu, row.gpu_frame) {
            let name = format!("{} (GPU per pixel)", row.rung);
            let point = Point {
                x: frame / frame_pixels(),
                y: row.day.mean(),
                label: String::new(),
            };
            match series.iter_mut().find(|s| s.name == name) {
                Some(s) => s.points.push(point),
                None => series.push(Series {
                    name,
                    points: vec![point],
                }),
            }
        }
    }
    Plot {
        title: "atmos ladder: day mean relative luminance error vs cost".into(),
        x_label: "seconds per evaluation (CPU query, or GPU frame / pixels)".into(),
        y_label: "mean relative luminance error (sun ≥ 5°)".into(),
        series,
    }
}

fn json(rows: &[Row], reference_label: &str) -> String {
    let mut out = format!("{{\"reference\":\"{reference_label}\",\"rows\":[");
    for (i, row) in rows.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(
            out,
            "{{\"rung\":\"{}\",\"setting\":\"{}\",\"slug\":\"{}\",\"day_mean\":{:e},\"day_max\":{:e},\"twilight_mean\":{:e},\"twilight_max\":{:e},\"dark\":{},\"non_finite\":{},\"cpu_setup_s\":{:e},\"cpu_query_s\":{:e},\"gpu_frame_s\":{}}}",
            row.rung,
            row.label,
            super::slug(&row.label),
            row.day.mean(),
            row.day.max(),
            row.twilight.mean(),
            row.twilight.max(),
            row.day.dark + row.twilight.dark,
            row.day.non_finite + row.twilight.non_finite,
            row.cpu_setup,
            row.cpu_query,
            row.gpu_frame.map_or("null".into(), |s| format!("{s:e}")),
        );
    }
    out.push_str("]}\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fibonacci_directions_are_unit_and_balanced() {
        let d = sphere_directions(96);
        assert!(d.iter().all(|v| (v.length() - 1.0).abs() < 1e-12));
        let mean = d.iter().copied().sum::<DVec3>() / 96.0;
        assert!(mean.length() < 0.02, "{mean}");
        assert_eq!(d.iter().filter(|v| v.z > 0.0).count(), 48);
    }

    #[test]
    fn error_stats_separate_dark_queries_and_count_non_finite() {
        let mut s = ErrorStats::default();
        s.add(1.0, 1.01);
        s.add(1e-9, 1e-7);
        s.add(1.0, f64::NAN);
        assert!((s.mean() - 0.01).abs() < 1e-12);
        assert_eq!((s.dark, s.non_finite), (1, 1));
        // An injected 10 % error shows up as 10 %.
        s.add(2.0, 2.2);
        assert!((s.max() - 0.1).abs() < 1e-12);
    }
}
