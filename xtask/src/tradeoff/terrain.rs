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
//! the measured bake time and the bytes per texel. Then every azimuth `k · 22.5°` on
//! its own against the ray cast (mean, max, bias, wrong shadows at a 20° sun; for
//! the sampling of `terrain::horizon` and a digital-line sampling), and the 16-direction bake of a 1024² map with and
//! without a maximum distance against GRASS `r.horizon`'s march (full run only).

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

/// Azimuth counts; 2 stands for the east/west pair.
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
}

impl Setup {
    fn new(quick: bool) -> Self {
        if quick {
            Self {
                side: 192,
                suns: 64,
                texels_per_sun: 1024,
                min_timing_s: 0.05,
            }
        } else {
            Self {
                side: 512,
                suns: 128,
                texels_per_sun: 8192,
                min_timing_s: 1.0,
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
    heightfield_at(side, SPACING)
}

/// The same texel heights at another spacing (the per-azimuth study's steep map uses
/// [`STEEP_SPACING`]: the same relief three times steeper).
fn heightfield_at(side: usize, spacing: f64) -> Result<Heightfield, String> {
    generate(&GeneratorParams {
        amplitude: RELIEF,
        wavelength: WAVELENGTH * spacing / SPACING,
        octaves: OCTAVES,
        ..GeneratorParams::new(side, side, spacing, SEED)
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

/// The per-azimuth and speed studies of a run.
struct Studies {
    azimuths: Vec<AzimuthRow>,
    speed: Vec<SpeedRow>,
    load_before_speed: String,
}

/// Entry point.
pub fn run(options: &super::Options) -> Result<(), String> {
    let setup = Setup::new(options.quick);
    if std::env::var("SKYSCAPE_TERRAIN_STUDY").as_deref() == Ok("azimuths") {
        // Only the per-azimuth and speed studies (the "before" file is made this way
        // on the commit before a change): rows to target/tradeoff/terrain-azimuths.json.
        let rows = azimuth_studies(&setup)?;
        let speed = speed_study(setup.min_timing_s, !options.quick)?;
        let path = super::write_output(
            "target/tradeoff/terrain-azimuths.json",
            &azimuth_json(&rows, &speed),
        )?;
        eprintln!("wrote {}", path.display());
        return Ok(());
    }
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
    eprintln!("tradeoff terrain: per-azimuth study (20° sun)…");
    let azimuth_rows = azimuth_studies(&setup)?;
    let load_before_speed = load_average();
    eprintln!("tradeoff terrain: {SPEED_SIDE}² speed study (the march runs once each)…");
    let speed = speed_study(setup.min_timing_s, !options.quick)?;
    let load_at_end = load_average();
    let studies = Studies {
        azimuths: azimuth_rows,
        speed,
        load_before_speed,
    };

    let context = Context {
        setup: &setup,
        truth_seconds,
        samples: samples.len(),
        load_at_start,
        load_at_end,
        quick: options.quick,
    };
    let report = markdown(&rows, &studies, &context);
    let prefix = if options.quick {
        "target/tradeoff/terrain-quick"
    } else {
        "docs/tradeoffs/terrain"
    };
    let md_path = super::write_output(&format!("{prefix}.md"), &report)?;
    super::write_output(&format!("{prefix}.svg"), &plot(&rows).to_svg())?;
    super::write_output("target/tradeoff/terrain.json", &json(&rows, &context))?;
    super::write_output(
        "target/tradeoff/terrain-azimuths.json",
        &azimuth_json(&studies.azimuths, &studies.speed),
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

fn markdown(rows: &[Row], studies: &Studies, c: &Context<'_>) -> String {
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
         sampling of `terrain::horizon` (the axes and diagonals read texels; other azimuths \
         interpolate across the grid lines, see the per-azimuth section). *E/W*: the east/west pair; a sun azimuth \
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
    study_markdown(&mut md, studies, c);
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

fn json(rows: &[Row], c: &Context<'_>) -> String {
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
    out.push_str("]}\n");
    out
}

// ---------------------------------------------------------------------------
// Per-azimuth accuracy and the 1024² speed study.

/// Azimuths of the per-azimuth study: `k · 22.5°`, `k = 0..16` (the axes, the
/// diagonals and the odd multiples of 22.5° in between).
const STUDY_AZIMUTHS: usize = 16;
/// The sun elevation of the per-azimuth hard-shadow rate, degrees.
const STUDY_SUN_DEG: f64 = 20.0;
/// Spacing of the per-azimuth study's steep map, metres (same texel heights as the
/// main map: slopes three times steeper, where a 20° sun casts many shadows).
const STEEP_SPACING: f64 = 10.0;
/// Side of the speed study's map.
const SPEED_SIDE: usize = 1024;
/// Maximum distances of the speed study.
const SPEED_DISTANCES: [Option<f64>; 3] = [None, Some(6_000.0), Some(2_000.0)];

/// One azimuth's accuracy: the map baked at exactly this azimuth against the ray cast.
pub(super) struct AzimuthRow {
    terrain: &'static str,
    azimuth_deg: f64,
    mean_error_deg: f64,
    /// Largest error where both the map and the truth see terrain (as the main table's
    /// last column).
    max_error_deg: f64,
    /// Mean of `stored − truth`, degrees (positive: more shadow).
    bias_deg: f64,
    /// Wrong hard shadows at a 20° sun on this azimuth.
    wrong: f64,
}

/// The speed study on the 1024² map.
pub(super) struct SpeedRow {
    max_distance: Option<f64>,
    sweep_seconds: f64,
    /// r.horizon-style march, 16 directions, all texels, once.
    march_seconds: Option<f64>,
}

/// The bilinear height at texel position `(x, y)` (clamped to the map).
fn bilinear(hf: &Heightfield, e: &[f64], x: f64, y: f64) -> f64 {
    let (w, h) = (hf.width(), hf.height());
    let i = (x.floor().max(0.0) as usize).min(w - 2);
    let j = (y.floor().max(0.0) as usize).min(h - 2);
    let (fx, fy) = (x - i as f64, y - j as f64);
    let at = |i: usize, j: usize| e[j * w + i];
    let top = at(i, j) + (at(i + 1, j) - at(i, j)) * fx;
    let bottom = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fx;
    top + (bottom - top) * fy
}

/// GRASS `r.horizon`'s method for one texel and azimuth: march along the exact ray
/// one texel spacing at a time, bilinear heights, curvature, stop at the map edge, at
/// the maximum distance, or when even the map's highest point could not rise above
/// the horizon found so far (r.horizon's `zmax` exit). Returns the tangent.
#[allow(clippy::too_many_arguments)]
fn march_tangent(
    hf: &Heightfield,
    e: &[f64],
    zmax: f64,
    x: usize,
    y: usize,
    azimuth: f64,
    inv_two_r: f64,
    max_distance: f64,
) -> f64 {
    let (dx, dy) = (azimuth.sin(), -azimuth.cos());
    let (wmax, hmax) = ((hf.width() - 1) as f64, (hf.height() - 1) as f64);
    let hp = e[y * hf.width() + x];
    let mut best = f64::NEG_INFINITY;
    let mut k = 1.0f64;
    loop {
        let (px, py) = (x as f64 + k * dx, y as f64 + k * dy);
        let d = k * hf.spacing();
        if px < -1e-9 || py < -1e-9 || px > wmax + 1e-9 || py > hmax + 1e-9 || d > max_distance {
            break;
        }
        if (zmax - hp) / d <= best {
            break;
        }
        let t =
            (bilinear(hf, e, px.clamp(0.0, wmax), py.clamp(0.0, hmax)) - hp - d * d * inv_two_r)
                / d;
        best = best.max(t);
        k += 1.0;
    }
    best
}

/// The r.horizon-style march over every texel for `count` azimuths, on all threads.
fn march_bake(hf: &Heightfield, count: usize, options: &HorizonOptions) -> f64 {
    let e = hf.elevations();
    let zmax = e.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let inv_two_r = options.effective_radius.map_or(0.0, |r| 0.5 / r);
    let max_distance = options.max_distance.unwrap_or(f64::INFINITY);
    let rows = std::sync::atomic::AtomicUsize::new(0);
    let checksum = std::sync::Mutex::new(0.0f64);
    std::thread::scope(|scope| {
        for _ in 0..threads() {
            scope.spawn(|| {
                let mut sum = 0.0;
                loop {
                    let y = rows.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    if y >= hf.height() {
                        break;
                    }
                    for k in 0..count {
                        let azimuth = k as f64 * std::f64::consts::TAU / count as f64;
                        for x in 0..hf.width() {
                            let t =
                                march_tangent(hf, &e, zmax, x, y, azimuth, inv_two_r, max_distance);
                            if t.is_finite() {
                                sum += t.atan();
                            }
                        }
                    }
                }
                if let Ok(mut c) = checksum.lock() {
                    *c += sum;
                }
            });
        }
    });
    checksum.into_inner().unwrap_or(0.0)
}

/// Per-azimuth accuracy on the study map: each azimuth `k · 22.5°` baked on its own
/// (no interpolation between layers), against the ray cast at the same azimuth.
fn azimuth_study(
    terrain: &'static str,
    hf: &Heightfield,
    texels: usize,
) -> Result<Vec<AzimuthRow>, String> {
    let mut rng = Rng(SEED ^ 0xa21);
    let points: Vec<(usize, usize)> = (0..texels)
        .map(|_| (rng.below(hf.width()), rng.below(hf.height())))
        .collect();
    let options = HorizonOptions::default();
    let sun = STUDY_SUN_DEG.to_radians();
    let mut rows = Vec::new();
    for k in 0..STUDY_AZIMUTHS {
        let azimuth = k as f64 * std::f64::consts::TAU / STUDY_AZIMUTHS as f64;
        let map = terrain::bake_horizon(hf, azimuth, &options, Algorithm::HullSweep)
            .map_err(|e| e.to_string())?;
        let chunk = points.len().div_ceil(threads());
        let truths: Vec<f64> = std::thread::scope(|scope| {
            let handles: Vec<_> = points
                .chunks(chunk)
                .map(|part| {
                    scope.spawn(move || {
                        part.iter()
                            .map(|&(x, y)| {
                                ray_cast_horizon_angle(hf, x, y, azimuth, &options)
                                    .map_err(|e| e.to_string())
                            })
                            .collect::<Result<Vec<f64>, String>>()
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| {
                    h.join()
                        .map_err(|_| "ray-cast worker panicked".to_string())?
                })
                .collect::<Result<Vec<Vec<f64>>, String>>()
        })?
        .concat();
        let (mut sum, mut signed, mut max, mut wrong) = (0.0f64, 0.0f64, 0.0f64, 0usize);
        for (&(x, y), &truth) in points.iter().zip(&truths) {
            let stored = f64::from(map.angle(x, y).map_err(|e| e.to_string())?);
            let error = stored - truth;
            sum += error.abs();
            signed += error;
            let nothing = -std::f64::consts::FRAC_PI_2 + 1e-6;
            if stored > nothing && truth > nothing {
                max = max.max(error.abs());
            }
            if (sun > stored) != (sun > truth) {
                wrong += 1;
            }
        }
        let n = points.len() as f64;
        let row = AzimuthRow {
            terrain,
            azimuth_deg: azimuth.to_degrees(),
            mean_error_deg: (sum / n).to_degrees(),
            max_error_deg: max.to_degrees(),
            bias_deg: (signed / n).to_degrees(),
            wrong: wrong as f64 / n,
        };
        eprintln!(
            "  {terrain} azimuth {:>6.2}°: mean {:.3}°  max {:.2}°  bias {:+.3}°  wrong {:.3} %",
            row.azimuth_deg,
            row.mean_error_deg,
            row.max_error_deg,
            row.bias_deg,
            100.0 * row.wrong
        );
        rows.push(row);
    }
    Ok(rows)
}

/// One row of [`BEFORE_AZIMUTHS`].
type BeforeRow = (&'static str, f64, f64, f64, f64, f64);

/// The per-azimuth study on the earlier digital-line sampling (the same study run on
/// it; raw rows in `docs/tradeoffs/terrain_before.json`): map, azimuth (°),
/// mean error (°), max error where both see terrain (°), bias (°), wrong hard shadows at
/// a 20° sun (fraction).
const BEFORE_AZIMUTHS: [BeforeRow; 32] = [
    ("30 m", 0.0, 0.0000, 0.000, -0.0000, 0.000000),
    #[allow(clippy::approx_constant)] // a measured error, not π/6
    ("30 m", 22.5, 0.5236, 7.134, 0.2798, 0.000000),
    ("30 m", 45.0, 0.1116, 2.749, -0.1116, 0.000000),
    ("30 m", 67.5, 0.5961, 8.679, 0.3542, 0.000244),
    ("30 m", 90.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("30 m", 112.5, 0.5991, 8.836, 0.3550, 0.000000),
    ("30 m", 135.0, 0.1044, 2.623, -0.1044, 0.000000),
    ("30 m", 157.5, 0.5291, 6.754, 0.3191, 0.000122),
    ("30 m", 180.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("30 m", 202.5, 0.4971, 9.365, 0.2734, 0.000488),
    ("30 m", 225.0, 0.1067, 2.923, -0.1067, 0.000000),
    ("30 m", 247.5, 0.6033, 9.305, 0.3613, 0.000732),
    ("30 m", 270.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("30 m", 292.5, 0.5500, 7.650, 0.3040, 0.000122),
    ("30 m", 315.0, 0.1064, 3.404, -0.1064, 0.000000),
    ("30 m", 337.5, 0.5138, 7.728, 0.3037, 0.000000),
    ("10 m", 0.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("10 m", 22.5, 1.2552, 18.376, 0.5808, 0.035278),
    ("10 m", 45.0, 0.3097, 7.720, -0.3097, 0.010010),
    ("10 m", 67.5, 1.4746, 19.862, 0.8018, 0.044800),
    ("10 m", 90.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("10 m", 112.5, 1.5209, 22.053, 0.8405, 0.048706),
    ("10 m", 135.0, 0.2882, 7.474, -0.2882, 0.008423),
    ("10 m", 157.5, 1.2671, 17.979, 0.6898, 0.031616),
    ("10 m", 180.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("10 m", 202.5, 1.2324, 20.581, 0.6139, 0.035889),
    ("10 m", 225.0, 0.2958, 8.674, -0.2958, 0.010010),
    ("10 m", 247.5, 1.4699, 22.302, 0.7949, 0.045166),
    ("10 m", 270.0, 0.0000, 0.000, -0.0000, 0.000000),
    ("10 m", 292.5, 1.4403, 17.694, 0.7493, 0.038818),
    ("10 m", 315.0, 0.2976, 9.358, -0.2976, 0.007324),
    ("10 m", 337.5, 1.2881, 22.151, 0.7038, 0.041016),
];
/// The speed study on the earlier digital-line sampling: maximum distance, 16-direction hull sweep (s),
/// r.horizon-style march (s), on this machine under other work.
const BEFORE_SPEED: [(Option<f64>, f64, f64); 3] = [
    (None, 1.566, 219.65),
    (Some(6000.0), 3.639, 136.05),
    (Some(2000.0), 4.110, 52.48),
];

/// The per-azimuth study on the main map and on the steep one.
fn azimuth_studies(setup: &Setup) -> Result<Vec<AzimuthRow>, String> {
    let mut rows = azimuth_study("30 m", &heightfield(setup.side)?, setup.texels_per_sun)?;
    rows.extend(azimuth_study(
        "10 m",
        &heightfield_at(setup.side, STEEP_SPACING)?,
        setup.texels_per_sun,
    )?);
    Ok(rows)
}

/// 16 directions on the 1024² map: the hull sweep with and without a maximum distance,
/// and (once each, `with_march`) the r.horizon-style march.
fn speed_study(min_seconds: f64, with_march: bool) -> Result<Vec<SpeedRow>, String> {
    let hf = heightfield(SPEED_SIDE)?;
    let mut rows = Vec::new();
    for max_distance in SPEED_DISTANCES {
        let options = HorizonOptions {
            max_distance,
            ..HorizonOptions::default()
        };
        let mut error = None;
        let sweep_seconds = super::time_per_call(min_seconds, || {
            if let Err(e) = bake_azimuths(&hf, STUDY_AZIMUTHS, &options, Algorithm::HullSweep) {
                error = Some(e.to_string());
            }
        });
        if let Some(e) = error {
            return Err(e);
        }
        let march_seconds = with_march.then(|| {
            let started = Instant::now();
            std::hint::black_box(march_bake(&hf, STUDY_AZIMUTHS, &options));
            started.elapsed().as_secs_f64()
        });
        eprintln!(
            "  {SPEED_SIDE}², 16 directions, {}: sweep {} march {}",
            distance_label(max_distance),
            seconds(sweep_seconds),
            march_seconds.map_or("-".into(), seconds)
        );
        rows.push(SpeedRow {
            max_distance,
            sweep_seconds,
            march_seconds,
        });
    }
    Ok(rows)
}

fn study_markdown(md: &mut String, studies: &Studies, c: &Context<'_>) {
    let s = c.setup;
    let _ = writeln!(
        md,
        "## Every azimuth against the ray cast\n\n\
         Each azimuth `k · 22.5°` baked on its own (`bake_horizon`, hull sweep, default \
         options: curvature on, no maximum distance) and read at {0} texels drawn uniformly \
         (the same texels for every azimuth), against `ray_cast_horizon_angle` along the same \
         azimuth. Two {1}×{1} maps of the generator above: *30 m* (the main table's map) and \
         *10 m* (the same texel heights at {STEEP_SPACING} m: three times steeper, where a 20° \
         sun casts many shadows). *mean*, *max* (over pairs where both see terrain) and *bias* \
         (mean of stored − truth; positive: more shadow) in degrees; *wrong*: the hard shadow \
         of a sun at {STUDY_SUN_DEG}° on that azimuth differs. **Before**: the digital-line \
         sampling up to commit bf74ace (texels up to one texel beside the ray, at the distance \
         along the line), measured by the same study there (`docs/tradeoffs/terrain_before.json`). \
         **After**: `terrain::horizon`'s sampling now (the texel's own ray for `NEAR_STEPS` = \
         {2} steps, then its line's samples interpolated across the grid line at their distance \
         along the azimuth). The axes sample the grid lines exactly (error only from the ray \
         cast's in-cell extrema: none here); the diagonals are unchanged.\n",
        s.texels_per_sun,
        s.side,
        terrain::horizon::NEAR_STEPS
    );
    let _ = writeln!(
        md,
        "| map | azimuth | mean before | mean after | max before | max after | bias before | bias after | wrong before | wrong after |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in &studies.azimuths {
        let before = BEFORE_AZIMUTHS
            .iter()
            .find(|b| b.0 == r.terrain && (b.1 - r.azimuth_deg).abs() < 1e-6);
        let cell = |f: fn(&BeforeRow) -> String| before.map_or("–".into(), f);
        let _ = writeln!(
            md,
            "| {} | {:.1}° | {} | {:.3}° | {} | {:.2}° | {} | {:+.3}° | {} | {:.2} % |",
            r.terrain,
            r.azimuth_deg,
            cell(|b| format!("{:.3}°", b.2)),
            r.mean_error_deg,
            cell(|b| format!("{:.2}°", b.3)),
            r.max_error_deg,
            cell(|b| format!("{:+.3}°", b.4)),
            r.bias_deg,
            cell(|b| format!("{:.2} %", 100.0 * b.5)),
            100.0 * r.wrong
        );
    }
    let _ = writeln!(
        md,
        "\n## Bake speed: 16 directions on {SPEED_SIDE}²\n\n\
         `bake_azimuths(…, 16, …, HullSweep)` on a {SPEED_SIDE}×{SPEED_SIDE} map of the 30 m \
         generator, {} threads, `time_per_call` over at least {} s. **March**: GRASS \
         `r.horizon`'s method written here (this machine has no GRASS): per texel and \
         direction, steps of one texel along the exact ray, bilinear heights, curvature, stop \
         at the map edge, the maximum distance, or when the map's highest point can no longer \
         rise above the horizon found (r.horizon's `zmax` exit); one wall-clock run on all \
         threads. Load average {} before, {} after (other work was running: times are noisy). \
         **Before**: the same study on commit bf74ace.\n",
        threads(),
        s.min_timing_s,
        studies.load_before_speed,
        c.load_at_end
    );
    let _ = writeln!(
        md,
        "| max distance | sweep before | sweep after | march | march / sweep after |\n|---|---:|---:|---:|---:|"
    );
    for r in &studies.speed {
        let before = BEFORE_SPEED.iter().find(|b| b.0 == r.max_distance);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} |",
            distance_label(r.max_distance),
            before.map_or("–".into(), |b| seconds(b.1)),
            seconds(r.sweep_seconds),
            r.march_seconds.map_or("not run (--quick)".into(), seconds),
            r.march_seconds
                .map_or("–".into(), |m| format!("{:.0}×", m / r.sweep_seconds))
        );
    }
    let _ = writeln!(
        md,
        "\nEach maximum distance's method, and a 1-thread comparison of each against none: \
         [`terrain_max_distance.md`](terrain_max_distance.md) (written by hand, not by this \
         command)."
    );
}

fn azimuth_json(rows: &[AzimuthRow], speed: &[SpeedRow]) -> String {
    let mut out = String::from("{\"azimuths\":[");
    for (i, r) in rows.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(
            out,
            "{{\"terrain\":\"{}\",\"azimuth_deg\":{},\"mean_error_deg\":{:e},\"max_error_deg\":{:e},\"bias_deg\":{:e},\"wrong\":{:e}}}",
            r.terrain, r.azimuth_deg, r.mean_error_deg, r.max_error_deg, r.bias_deg, r.wrong
        );
    }
    out.push_str("],\"speed\":[");
    for (i, r) in speed.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(
            out,
            "{{\"max_distance_m\":{},\"sweep_s\":{:e},\"march_s\":{}}}",
            r.max_distance.map_or("null".into(), |d| format!("{d}")),
            r.sweep_seconds,
            r.march_seconds.map_or("null".into(), |s| format!("{s:e}"))
        );
    }
    out.push_str("]}\n");
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
