//! `cargo xtask tradeoff terrain`: how many azimuths, how many bits per angle and how
//! far to search, against the exact ray-cast shadow.
//!
//! On a generated mountainous heightfield, every combination of
//! {east/west (2), 4, 8, 16, 32, 64 azimuths} × {u8, u16, f32} × {unlimited, 6 km,
//! 2 km maximum distance} is baked with the hull sweep and queried at random texels
//! under random suns (elevation uniform in 2°–30°, azimuth uniform). The truth is
//! [`terrain::raycast::ray_cast_horizon_angle`] along the sun's exact azimuth over the
//! bilinear surface, with the same curvature and **no** distance limit. Reported: the
//! fraction of (texel, sun) pairs whose hard shadow is wrong, the horizon-angle error,
//! the measured bake time and the bytes per texel. The full run also measures the
//! 4096² east/west bake, hull sweep against brute force (once each, wall clock, output
//! compared) and the sweep's two-thread scaling.

use std::fmt::Write as _;
use std::num::NonZeroUsize;
use std::time::Instant;

use terrain::generate::{GeneratorParams, generate};
use terrain::horizon::EFFECTIVE_EARTH_RADIUS;
use terrain::raycast::ray_cast_horizon_angle;
use terrain::{
    Algorithm, Heightfield, HorizonEncoding, HorizonMap, HorizonOptions, bake_azimuths,
    bake_east_west,
};

use super::plot::{Plot, Point, Series};

/// Azimuth counts; 2 stands for seed 000's east/west pair.
const AZIMUTH_COUNTS: [usize; 6] = [2, 4, 8, 16, 32, 64];
/// Maximum search distances, metres (`None`: up to the map edge).
const MAX_DISTANCES: [Option<f64>; 3] = [None, Some(6_000.0), Some(2_000.0)];
/// Sun elevations are uniform in this range, degrees.
const SUN_ELEVATION_DEG: (f64, f64) = (2.0, 30.0);
/// Map spacing, metres per texel, relief (peak to peak), metres, the first octave's
/// wavelength, metres, and the octave count (finest wavelength 120 m, 4 texels): a
/// mountain range like a 30 m DEM of the Alps, whatever the map size.
const SPACING: f64 = 30.0;
const RELIEF: f64 = 2_000.0;
const WAVELENGTH: f64 = 7_680.0;
const OCTAVES: u32 = 7;
const SEED: u64 = 2010;

/// The problem size of one run.
struct Setup {
    side: usize,
    suns: usize,
    texels_per_sun: usize,
    min_timing_s: f64,
    /// Side of the sweep-vs-brute comparison map.
    large_side: usize,
}

impl Setup {
    fn new(quick: bool) -> Self {
        if quick {
            Self {
                side: 192,
                suns: 64,
                texels_per_sun: 1024,
                min_timing_s: 0.05,
                large_side: 512,
            }
        } else {
            Self {
                side: 512,
                suns: 128,
                texels_per_sun: 8192,
                min_timing_s: 1.0,
                large_side: 4096,
            }
        }
    }
}

/// SplitMix64: a small seeded generator for sun positions and texels.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        (self.unit() * n as f64) as usize
    }
}

/// One (texel, sun) query and its truth.
struct Sample {
    x: usize,
    y: usize,
    azimuth: f64,
    elevation: f64,
    /// The ray-cast horizon along `azimuth` (radians).
    truth: f64,
}

/// A baked configuration: its layers and how a sun azimuth picks among them.
struct Baked {
    count: usize,
    max_distance: Option<f64>,
    layers: Vec<HorizonMap>,
    bake_seconds: f64,
}

impl Baked {
    /// The stored horizon for a sun azimuth after `encoding`'s round trip: the east map
    /// while the sun is east of the meridian (`sin(azimuth) ≥ 0`, as
    /// `self_shadow_east_west` selects), the west map otherwise; `N` layers interpolate
    /// linearly between neighbours (`azimuth_layers`).
    fn horizon(&self, x: usize, y: usize, azimuth: f64, encoding: HorizonEncoding) -> f64 {
        // The samples lie inside the maps and the bakes' angles in [-π/2, π/2].
        let stored = |layer: &HorizonMap| {
            let angle = layer.angle(x, y).expect("sample inside the map");
            encoding
                .round_trip(angle)
                .expect("baked angles are encodable")
        };
        if self.count == 2 {
            let side = if azimuth.sin() >= 0.0 { 0 } else { 1 };
            return f64::from(stored(&self.layers[side]));
        }
        let l = terrain::shadow::azimuth_layers(azimuth as f32, self.count as u32)
            .expect("count >= 4 and a finite azimuth");
        let a = stored(&self.layers[l.lower as usize]);
        let b = stored(&self.layers[l.upper as usize]);
        f64::from(a + (b - a) * l.weight)
    }
}

struct Row {
    count: usize,
    encoding: HorizonEncoding,
    max_distance: Option<f64>,
    bake_seconds: f64,
    wrong: f64,
    false_shadow: f64,
    false_light: f64,
    mean_error: f64,
    p99_error: f64,
    max_error: f64,
    /// Largest error over pairs where both the map and the truth see some terrain
    /// (neither is `−π/2`): leaves out the map-edge pairs where one line leaves the map
    /// and the other does not.
    max_error_seen: f64,
}

impl Row {
    fn bytes_per_texel(&self) -> usize {
        self.count * self.encoding.bytes()
    }
    fn label(&self) -> String {
        format!(
            "{} {} {}",
            azimuths_label(self.count),
            self.encoding.name(),
            distance_label(self.max_distance)
        )
    }
}

fn azimuths_label(count: usize) -> String {
    if count == 2 {
        "E/W".into()
    } else {
        format!("N={count}")
    }
}

fn distance_label(d: Option<f64>) -> String {
    d.map_or("unlimited".into(), |d| format!("{:.0} km", d / 1000.0))
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into())
}

fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, NonZeroUsize::get)
}

fn heightfield(side: usize) -> Result<Heightfield, String> {
    generate(&GeneratorParams {
        amplitude: RELIEF,
        wavelength: WAVELENGTH,
        octaves: OCTAVES,
        ..GeneratorParams::new(side, side, SPACING, SEED)
    })
    .map_err(|e| e.to_string())
}

/// Random suns and texels, and the ray-cast truth for each (on all cores).
fn samples(hf: &Heightfield, setup: &Setup) -> Result<Vec<Sample>, String> {
    let mut rng = Rng(SEED ^ 0x5eed);
    let (lo, hi) = SUN_ELEVATION_DEG;
    let mut samples = Vec::with_capacity(setup.suns * setup.texels_per_sun);
    for _ in 0..setup.suns {
        let azimuth = rng.unit() * std::f64::consts::TAU;
        let elevation = (lo + (hi - lo) * rng.unit()).to_radians();
        for _ in 0..setup.texels_per_sun {
            samples.push(Sample {
                x: rng.below(hf.width()),
                y: rng.below(hf.height()),
                azimuth,
                elevation,
                truth: f64::NAN,
            });
        }
    }
    let truth_options = HorizonOptions::default();
    let chunk = samples.len().div_ceil(threads());
    std::thread::scope(|scope| {
        let handles: Vec<_> = samples
            .chunks_mut(chunk)
            .map(|part| {
                scope.spawn(move || -> Result<(), String> {
                    for s in part {
                        s.truth = ray_cast_horizon_angle(hf, s.x, s.y, s.azimuth, &truth_options)
                            .map_err(|e| e.to_string())?;
                    }
                    Ok(())
                })
            })
            .collect();
        handles.into_iter().try_for_each(|h| {
            h.join()
                .map_err(|_| "ray-cast worker panicked".to_string())?
        })
    })?;
    Ok(samples)
}

fn bake(
    hf: &Heightfield,
    count: usize,
    options: &HorizonOptions,
) -> Result<Vec<HorizonMap>, String> {
    if count == 2 {
        let maps = bake_east_west(hf, options, Algorithm::HullSweep).map_err(|e| e.to_string())?;
        Ok(vec![maps.east, maps.west])
    } else {
        let maps =
            bake_azimuths(hf, count, options, Algorithm::HullSweep).map_err(|e| e.to_string())?;
        Ok(maps.layers().to_vec())
    }
}

fn evaluate(baked: &Baked, encoding: HorizonEncoding, samples: &[Sample]) -> Row {
    let (mut false_shadow, mut false_light) = (0usize, 0usize);
    let mut errors: Vec<f64> = Vec::with_capacity(samples.len());
    let mut max_error_seen = 0.0f64;
    let nothing = -std::f64::consts::FRAC_PI_2 + 1e-6;
    for s in samples {
        let stored = baked.horizon(s.x, s.y, s.azimuth, encoding);
        let lit_map = s.elevation > stored;
        let lit_truth = s.elevation > s.truth;
        match (lit_map, lit_truth) {
            (false, true) => false_shadow += 1,
            (true, false) => false_light += 1,
            _ => {}
        }
        let error = (stored - s.truth).abs();
        if stored > nothing && s.truth > nothing {
            max_error_seen = max_error_seen.max(error);
        }
        errors.push(error);
    }
    let n = samples.len() as f64;
    let mean_error = errors.iter().sum::<f64>() / n;
    let max_error = errors.iter().copied().fold(0.0, f64::max);
    let p99_index = ((errors.len() as f64 * 0.99) as usize).min(errors.len() - 1);
    let p99_error = *errors
        .select_nth_unstable_by(p99_index, |a, b| a.total_cmp(b))
        .1;
    Row {
        count: baked.count,
        encoding,
        max_distance: baked.max_distance,
        bake_seconds: baked.bake_seconds,
        wrong: (false_shadow + false_light) as f64 / n,
        false_shadow: false_shadow as f64 / n,
        false_light: false_light as f64 / n,
        mean_error,
        p99_error,
        max_error,
        max_error_seen,
    }
}

/// The 4096² (quick: 512²) east/west bake, sweep against brute force.
struct LargeBake {
    side: usize,
    sweep_1_thread: f64,
    sweep_2_threads: f64,
    brute_2_threads: f64,
    max_difference: f32,
    load_before: String,
    load_after: String,
}

fn large_bake(setup: &Setup) -> Result<LargeBake, String> {
    let hf = heightfield(setup.large_side)?;
    let with_threads = |n: usize| HorizonOptions {
        threads: NonZeroUsize::new(n),
        ..HorizonOptions::default()
    };
    let load_before = load_average();
    let mut sweep = None;
    let mut time_sweep = |n: usize| -> Result<f64, String> {
        let options = with_threads(n);
        let mut error = None;
        let seconds = super::time_per_call(3.0 * setup.min_timing_s, || {
            match bake_east_west(&hf, &options, Algorithm::HullSweep) {
                Ok(maps) => sweep = Some(maps),
                Err(e) => error = Some(e.to_string()),
            }
        });
        error.map_or(Ok(seconds), Err)
    };
    let sweep_1_thread = time_sweep(1)?;
    let sweep_2_threads = time_sweep(2)?;
    let sweep = sweep.ok_or("the sweep produced no maps")?;
    eprintln!(
        "tradeoff terrain: {0}² sweep {sweep_1_thread:.3} s (1 thread), {sweep_2_threads:.3} s (2 threads); brute force (once)…",
        setup.large_side
    );
    let started = Instant::now();
    let brute =
        bake_east_west(&hf, &with_threads(2), Algorithm::BruteForce).map_err(|e| e.to_string())?;
    let brute_2_threads = started.elapsed().as_secs_f64();
    let max_difference = sweep
        .east
        .angles()
        .iter()
        .chain(sweep.west.angles())
        .zip(brute.east.angles().iter().chain(brute.west.angles()))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    Ok(LargeBake {
        side: setup.large_side,
        sweep_1_thread,
        sweep_2_threads,
        brute_2_threads,
        max_difference,
        load_before,
        load_after: load_average(),
    })
}

/// Entry point.
pub fn run(options: &super::Options) -> Result<(), String> {
    let setup = Setup::new(options.quick);
    let load_at_start = load_average();
    let hf = heightfield(setup.side)?;
    eprintln!(
        "tradeoff terrain: {0}×{0} map, {1} suns × {2} texels; ray-casting the truth…",
        setup.side, setup.suns, setup.texels_per_sun
    );
    let started = Instant::now();
    let samples = samples(&hf, &setup)?;
    let truth_seconds = started.elapsed().as_secs_f64();

    let mut rows = Vec::new();
    for max_distance in MAX_DISTANCES {
        for count in AZIMUTH_COUNTS {
            let bake_options = HorizonOptions {
                max_distance,
                ..HorizonOptions::default()
            };
            let mut layers = None;
            let mut error = None;
            let bake_seconds = super::time_per_call(setup.min_timing_s, || {
                match bake(&hf, count, &bake_options) {
                    Ok(l) => layers = Some(l),
                    Err(e) => error = Some(e),
                }
            });
            if let Some(e) = error {
                return Err(e);
            }
            let baked = Baked {
                count,
                max_distance,
                layers: layers.ok_or("no layers baked")?,
                bake_seconds,
            };
            for encoding in HorizonEncoding::ALL {
                let row = evaluate(&baked, encoding, &samples);
                eprintln!(
                    "  {:<22} wrong {:>7.3} %  max error {:.4} rad  bake {:.3} s",
                    row.label(),
                    100.0 * row.wrong,
                    row.max_error,
                    row.bake_seconds
                );
                rows.push(row);
            }
        }
    }
    let large = large_bake(&setup)?;
    let load_at_end = load_average();

    let context = Context {
        setup: &setup,
        truth_seconds,
        samples: samples.len(),
        load_at_start,
        load_at_end,
        quick: options.quick,
    };
    let report = markdown(&rows, &large, &context);
    let prefix = if options.quick {
        "target/tradeoff/terrain-quick"
    } else {
        "docs/tradeoffs/terrain"
    };
    let md_path = super::write_output(&format!("{prefix}.md"), &report)?;
    super::write_output(&format!("{prefix}.svg"), &plot(&rows).to_svg())?;
    super::write_output(
        "target/tradeoff/terrain.json",
        &json(&rows, &large, &context),
    )?;
    println!("{report}");
    eprintln!("wrote {}", md_path.display());
    Ok(())
}

struct Context<'a> {
    setup: &'a Setup,
    truth_seconds: f64,
    samples: usize,
    load_at_start: String,
    load_at_end: String,
    quick: bool,
}

fn seconds(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.2} s")
    } else {
        format!("{:.1} ms", s * 1e3)
    }
}

fn markdown(rows: &[Row], large: &LargeBake, c: &Context<'_>) -> String {
    let s = c.setup;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# terrain: horizon-map accuracy against storage and bake cost\n"
    );
    let _ = writeln!(
        md,
        "Generated by `WGPU_BACKEND=vulkan cargo run --release -p xtask -- tradeoff terrain{}` \
         (raw rows: `target/tradeoff/terrain.json`). Machine: {} ({} threads available), load \
         average {} at the start and {} at the end (other work was running on the machine: \
         times are wall clock and noisy).\n",
        if c.quick { " --quick" } else { "" },
        cpu_model(),
        threads(),
        c.load_at_start,
        c.load_at_end
    );
    let _ = writeln!(
        md,
        "**Terrain.** `terrain::generate` (gradient fBm, {OCTAVES} octaves from a {WAVELENGTH} m \
         wavelength, gain ½, seed {SEED}), {0}×{0} texels at {SPACING} m ({1:.1} km square), \
         {RELIEF} m relief. Curvature on (effective radius {2:.0} m = 4/3 × 6,371 km: the \
         default `terrain::EFFECTIVE_EARTH_RADIUS`, standard atmospheric refraction) in the \
         bakes and in the truth.\n",
        s.side,
        s.side as f64 * SPACING / 1000.0,
        EFFECTIVE_EARTH_RADIUS
    );
    let _ = writeln!(
        md,
        "**Queries.** {} suns, azimuth uniform in [0, 2π), elevation uniform in {}°–{}°, each \
         at {} texels drawn uniformly: {} (texel, sun) pairs. **Truth:** \
         `terrain::raycast::ray_cast_horizon_angle` along the sun's exact azimuth over the \
         bilinear surface, no distance limit (f64, exact per cell; {:.1} s for all pairs on all \
         threads). A pair's hard shadow is wrong when `elevation > horizon` differs between \
         the stored horizon and the truth (*false shadow*: the map darkens a lit texel; \
         *false light*: the reverse).\n",
        s.suns,
        SUN_ELEVATION_DEG.0,
        SUN_ELEVATION_DEG.1,
        s.texels_per_sun,
        c.samples,
        c.truth_seconds
    );
    let _ = writeln!(
        md,
        "**Maps.** Hull-sweep bakes (`Algorithm::HullSweep`, identical to brute force) on the \
         digital-line sampling of `terrain::horizon`. *E/W*: seed 000's pair; a sun azimuth \
         with `sin(azimuth) ≥ 0` reads the east map, otherwise the west map (as \
         `shadow::self_shadow_east_west`). *N*: layers at `k·2π/N`, linear interpolation \
         between the two neighbours (`shadow::azimuth_layers`). Encodings (`HorizonEncoding`): \
         u8/u16 unorm `round((a + π/2)/π·(2^b − 1))`, decoded `q/(2^b − 1)·π − π/2` (half-step \
         error 6.2e−3 / 2.4e−5 rad); f32 unquantised. **Bake** is the wall-clock time of one \
         bake of all layers on {} threads (`HorizonOptions::default()` threads), repeated for \
         at least {} s; **bytes/texel** counts the horizon angles only. Angle errors are \
         `|stored − truth|` in radians over all pairs.\n",
        threads(),
        s.min_timing_s
    );
    let _ = writeln!(
        md,
        "| azimuths | encoding | max distance | bytes/texel | bake | wrong shadow | false shadow | false light | mean error (rad) | p99 error (rad) | max error (rad) | max error, both see terrain (rad) |"
    );
    let _ = writeln!(
        md,
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {:.3} % | {:.3} % | {:.3} % | {:.2e} | {:.2e} | {:.3} | {:.3} |",
            azimuths_label(r.count),
            r.encoding.name(),
            distance_label(r.max_distance),
            r.bytes_per_texel(),
            seconds(r.bake_seconds),
            100.0 * r.wrong,
            100.0 * r.false_shadow,
            100.0 * r.false_light,
            r.mean_error,
            r.p99_error,
            r.max_error,
            r.max_error_seen
        );
    }
    let _ = writeln!(
        md,
        "\n![wrong-shadow fraction vs bake cost](terrain.svg)\n\nThe plot shows the wrong \
         hard-shadow fraction against the bake time, one series per encoding and maximum \
         distance, points labelled by azimuth count.\n"
    );
    let _ = writeln!(md, "## Sweep against brute force, {0}×{0}\n", large.side);
    let _ = writeln!(
        md,
        "East + west bake of a {0}×{0} map of the same generator ({SPACING} m, {RELIEF} m \
         relief, curvature on). Hull sweep: `time_per_call` over at least {1:.2} s; brute force: \
         **one** wall-clock run on 2 threads (criterion's 10 samples would take tens of \
         minutes). Load average {2} before, {3} after.\n",
        large.side,
        3.0 * s.min_timing_s,
        large.load_before,
        large.load_after
    );
    let _ = writeln!(md, "| bake | threads | time |\n|---|---:|---:|");
    let _ = writeln!(md, "| hull sweep | 1 | {} |", seconds(large.sweep_1_thread));
    let _ = writeln!(
        md,
        "| hull sweep | 2 | {} |",
        seconds(large.sweep_2_threads)
    );
    let _ = writeln!(
        md,
        "| brute force | 2 | {} |",
        seconds(large.brute_2_threads)
    );
    let _ = writeln!(
        md,
        "\nRatio brute / sweep (2 threads each): **{:.0}×**; two-thread scaling of the sweep: \
         {:.2}× (1 thread / 2 threads); largest |sweep − brute| over all {} angles: {:e} rad.",
        large.brute_2_threads / large.sweep_2_threads,
        large.sweep_1_thread / large.sweep_2_threads,
        2 * large.side * large.side,
        large.max_difference
    );
    md
}

fn plot(rows: &[Row]) -> Plot {
    let mut series = Vec::new();
    for encoding in HorizonEncoding::ALL {
        for max_distance in MAX_DISTANCES {
            let points = rows
                .iter()
                .filter(|r| r.encoding == encoding && r.max_distance == max_distance)
                .map(|r| Point {
                    x: r.bake_seconds,
                    y: r.wrong,
                    label: azimuths_label(r.count),
                })
                .collect();
            series.push(Series {
                name: format!("{}, {}", encoding.name(), distance_label(max_distance)),
                points,
            });
        }
    }
    Plot {
        title: "terrain: wrong hard-shadow fraction vs bake cost".into(),
        x_label: "bake time of all layers (s, CPU wall clock)".into(),
        y_label: "fraction of (texel, sun) pairs with a wrong hard shadow".into(),
        series,
    }
}

fn json(rows: &[Row], large: &LargeBake, c: &Context<'_>) -> String {
    let mut out = format!(
        "{{\"quick\":{},\"side\":{},\"spacing_m\":{SPACING},\"relief_m\":{RELIEF},\"suns\":{},\"samples\":{},\"truth_s\":{:e},\"rows\":[",
        c.quick, c.setup.side, c.setup.suns, c.samples, c.truth_seconds
    );
    for (i, r) in rows.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(
            out,
            "{{\"azimuths\":{},\"encoding\":\"{}\",\"max_distance_m\":{},\"bytes_per_texel\":{},\"bake_s\":{:e},\"wrong\":{:e},\"false_shadow\":{:e},\"false_light\":{:e},\"mean_error_rad\":{:e},\"p99_error_rad\":{:e},\"max_error_rad\":{:e},\"max_error_seen_rad\":{:e}}}",
            r.count,
            r.encoding.name(),
            r.max_distance.map_or("null".into(), |d| format!("{d}")),
            r.bytes_per_texel(),
            r.bake_seconds,
            r.wrong,
            r.false_shadow,
            r.false_light,
            r.mean_error,
            r.p99_error,
            r.max_error,
            r.max_error_seen
        );
    }
    let _ = writeln!(
        out,
        "],\"large\":{{\"side\":{},\"sweep_1_thread_s\":{:e},\"sweep_2_threads_s\":{:e},\"brute_2_threads_s\":{:e},\"max_difference_rad\":{:e}}}}}",
        large.side,
        large.sweep_1_thread,
        large.sweep_2_threads,
        large.brute_2_threads,
        large.max_difference
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn east_west_maps_answer_by_the_side_of_the_meridian() {
        let hf = Heightfield::from_fn(8, 4, 1.0, |x, _| x as f32).unwrap();
        let layers = bake(&hf, 2, &HorizonOptions::flat()).unwrap();
        let baked = Baked {
            count: 2,
            max_distance: None,
            layers,
            bake_seconds: 0.0,
        };
        // Rising east: the east horizon is 45°, the west one is −45°.
        let east = baked.horizon(3, 1, 1.0, HorizonEncoding::F32);
        let west = baked.horizon(3, 1, 4.0, HorizonEncoding::F32);
        assert!((east - std::f64::consts::FRAC_PI_4).abs() < 1e-6);
        assert!((west + std::f64::consts::FRAC_PI_4).abs() < 1e-6);
    }

    #[test]
    fn rng_is_uniform_enough() {
        // The stream the trade-off draws: mean within 5σ (σ = 0.0009 for 1e5 draws),
        // and `below` stays in range and reaches both ends.
        let mut rng = Rng(SEED ^ 0x5eed);
        let mean = (0..100_000).map(|_| rng.unit()).sum::<f64>() / 100_000.0;
        assert!((mean - 0.5).abs() < 0.0045, "{mean}");
        let draws: Vec<usize> = (0..10_000).map(|_| rng.below(7)).collect();
        assert!(draws.iter().all(|&d| d < 7));
        assert!(draws.contains(&0) && draws.contains(&6));
    }
}
