//! `cargo xtask tradeoff sky-dome`: SimGear's 12-sided dome (SGSky's cheap sky,
//! `celestial::dome`) against the per-pixel sky it stands in for. For each sun
//! elevation from high day to deep twilight, the dome is painted from atmos' rung 3 in
//! both colourings — SGSky's 70/30 and 10/90 sky/fog weights (13 model queries) and
//! every vertex from the model (49 queries) — with the aureole per pixel over it, and
//! compared with rung 3 per pixel over a Fibonacci set of sky directions. Writes
//! `docs/tradeoffs/sky_dome.md` and `target/tradeoff/sky_dome.json`.

use atmos::Atmosphere;
use atmos::ladder::{LUMINANCE_WEIGHTS, SkyModel};
use atmos::lut::{LutSettings, PrecomputedSky};
use celestial::Angle;
use celestial::dome::{DomeColouring, SkyDome, spin_from_azimuth};
use celestial::objects::{BackgroundSampling, SkyObjectsBuilder};

use super::{Options, time_per_call, write_output};

/// Directions over the sky above 0.5° elevation (a Fibonacci lattice on the upper
/// hemisphere, in east/north/up).
fn sky_directions(count: usize) -> Vec<[f64; 3]> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let z_min = 0.5f64.to_radians().sin();
    (0..count)
        .map(|i| {
            let z = z_min + (1.0 - z_min) * (i as f64 + 0.5) / count as f64;
            let radius = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            [radius * phi.cos(), radius * phi.sin(), z]
        })
        .collect()
}

fn luminance(c: [f64; 3]) -> f64 {
    (0..3).map(|i| c[i] * LUMINANCE_WEIGHTS[i]).sum()
}

#[derive(Debug, Clone)]
struct Row {
    sun_elevation: f64,
    colouring: &'static str,
    queries: usize,
    mean: f64,
    p95: f64,
    max: f64,
    paint_seconds: f64,
    dome_seconds_per_direction: f64,
    model_seconds_per_direction: f64,
    model_frame_seconds: f64,
}

/// Runs the comparison.
pub fn run(options: &Options) -> Result<(), String> {
    let atmosphere = Atmosphere::earth();
    let settings = if options.quick {
        LutSettings::small()
    } else {
        LutSettings::default()
    };
    let model = PrecomputedSky::new(&atmosphere, &settings).map_err(|e| e.to_string())?;
    let directions = sky_directions(if options.quick { 400 } else { 4000 });
    let au = celestial::sun::ASTRONOMICAL_UNIT_M;
    let sun_azimuth = Angle::from_degrees(200.0);
    let mut rows = Vec::new();
    for sun_elevation in [60.0, 30.0, 10.0, 5.0, 2.0, 0.0, -3.0, -6.0] {
        let (e, a) = (f64::to_radians(sun_elevation), sun_azimuth.radians());
        let sun = [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()];
        let builder = SkyObjectsBuilder::new(
            &atmosphere,
            &model,
            2.0,
            sun,
            au,
            None,
            BackgroundSampling::PerObject,
        )
        .map_err(|e| e.to_string())?;
        let aureole = builder.aureole().map_err(|e| e.to_string())?;
        let spin = spin_from_azimuth(sun_azimuth);
        let reference: Vec<f64> = directions
            .iter()
            .map(|&d| builder.sky_exact(d).map(|s| luminance(s.radiance)))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
        // Rung 3's per-frame work: a sky-view table for this viewer and sun (a new
        // altitude each call, a metre apart — past f32 rounding of the radius — so each
        // call bakes one).
        let mut bake = 0u32;
        let model_frame_seconds = time_per_call(0.5, || {
            bake += 1;
            let position =
                glam::DVec3::new(0.0, 0.0, atmosphere.planet_radius + 2.0 + f64::from(bake));
            std::hint::black_box(model.prepare(position, glam::DVec3::from_array(sun)));
        });
        let model_seconds = time_per_call(0.2, || {
            for &d in &directions {
                std::hint::black_box(builder.sky_exact(d).expect("valid direction"));
            }
        }) / directions.len() as f64;
        for (colouring, name, queries) in [
            (DomeColouring::SeedWeights, "SGSky weights", 13),
            (DomeColouring::Model, "model per vertex", 49),
        ] {
            let paint = || {
                SkyDome::paint(
                    colouring,
                    spin,
                    |d| Ok(builder.sky_exact(d)?.radiance),
                    |d| aureole.radiance(d.map(|c| c as f32)).map(f64::from),
                )
            };
            let painted = paint().map_err(|e| e.to_string())?;
            let paint_seconds = time_per_call(0.2, || {
                std::hint::black_box(paint().expect("painted once already"));
            });
            let estimate = |d: [f64; 3]| {
                let dome = painted.dome.radiance(d);
                let a = aureole.radiance(d.map(|c| c as f32));
                luminance(std::array::from_fn(|i| dome[i] + f64::from(a[i])))
            };
            let mut errors: Vec<f64> = directions
                .iter()
                .zip(&reference)
                .filter(|(_, r)| **r > 0.0)
                .map(|(&d, &r)| (estimate(d) - r).abs() / r)
                .collect();
            errors.sort_by(f64::total_cmp);
            let dome_seconds = time_per_call(0.2, || {
                for &d in &directions {
                    std::hint::black_box(estimate(d));
                }
            }) / directions.len() as f64;
            let row = Row {
                sun_elevation,
                colouring: name,
                queries,
                mean: errors.iter().sum::<f64>() / errors.len().max(1) as f64,
                p95: errors
                    .get(errors.len() * 95 / 100)
                    .copied()
                    .unwrap_or(f64::NAN),
                max: errors.last().copied().unwrap_or(f64::NAN),
                paint_seconds,
                dome_seconds_per_direction: dome_seconds,
                model_seconds_per_direction: model_seconds,
                model_frame_seconds,
            };
            eprintln!(
                "sun {:5.1}°  {:18} mean {:7.1} %  p95 {:7.1} %  max {:8.1} %",
                row.sun_elevation,
                row.colouring,
                100.0 * row.mean,
                100.0 * row.p95,
                100.0 * row.max
            );
            rows.push(row);
        }
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let markdown = markdown(
        &rows,
        &model.label(),
        directions.len(),
        options.quick,
        load.trim(),
    );
    if !options.quick {
        let path = write_output("docs/tradeoffs/sky_dome.md", &markdown)?;
        println!("wrote {}", path.display());
    } else {
        println!("{markdown}");
    }
    let json = json(&rows);
    let path = write_output("target/tradeoff/sky_dome.json", &json)?;
    println!("wrote {}", path.display());
    Ok(())
}

fn markdown(rows: &[Row], reference: &str, directions: usize, quick: bool, load: &str) -> String {
    let mut out = String::new();
    out.push_str("# SGSky's 12-sided dome against the per-pixel sky\n\n");
    out.push_str(&format!(
        "Generated by `cargo xtask tradeoff sky-dome`{}. The cheap sky of SGSky (`celestial::dome`: a \
         centre fan and inner, middle and outer rings of 12 vertices, SimGear's geometry, rotated so \
         vertex 0 faces the sun) painted two ways from the same atmos rung — SGSky's weights \
         (centre = the zenith's radiance, inner ring 70 % sky + 30 % fog, middle ring 10 % + 90 %, outer \
         ring the fog = the horizon's radiance in that vertex's azimuth; 13 model queries) and every \
         vertex from the model (49 queries) — each vertex minus the sun's aureole, which is drawn per \
         pixel over the dome (`celestial::draw::sun_aureole_radiance`). Reference: **{reference}** per \
         pixel, sunlit sky only, viewer 2 m up, sun at azimuth 200°. Error: relative luminance error \
         over {directions} directions above 0.5° elevation (a Fibonacci lattice).\n\n",
        if quick { " --quick" } else { "" }
    ));
    out.push_str("| sun elevation | dome colouring | model queries per frame | mean error | p95 | max | dome paint per frame (ms) | dome per direction (µs) | rung 3 sky-view bake per frame (ms) | rung 3 per direction (µs) |\n");
    out.push_str("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for r in rows {
        out.push_str(&format!(
            "| {:.0}° | {} | {} | {:.1} % | {:.1} % | {:.0} % | {:.3} | {:.2} | {:.1} | {:.2} |\n",
            r.sun_elevation,
            r.colouring,
            r.queries,
            100.0 * r.mean,
            100.0 * r.p95,
            100.0 * r.max,
            1e3 * r.paint_seconds,
            1e6 * r.dome_seconds_per_direction,
            1e3 * r.model_frame_seconds,
            1e6 * r.model_seconds_per_direction
        ));
    }
    out.push_str(&format!(
        "\nTimes are CPU wall time in the dev profile (celestial, atmos and the dependencies at \
         opt-level 2), one thread, measured with `time_per_call` while other builds shared the \
         machine (load average {load}): read them as ratios. Rung 3 bakes a sky-view table per \
         viewer and sun each frame, then answers each direction from it; the dome queries the model \
         13 or 49 times per frame and then finds each direction's triangle (a sector by azimuth, up \
         to 21 ray–triangle tests here) and adds the aureole — on the CPU that per-direction work \
         costs more than rung 3's table lookup.\n\n\
         Reading: SGSky's weights carry the horizon's colour 70 % of the way to 21.8° and 90 % to \
         6.5°; with an atmos horizon (bright toward a low sun, dark away from it) that is the \
         scheme's error, measured here, not a bug — SGSky's hand-picked fog colour was a mild haze. \
         Colouring every vertex from the model removes the weights' bias and leaves the \
         interpolation's error across 30° sectors. The dome as a scene rung (`rung = \"dome\"`, \
         celestial's `SkyDomeRenderer` on the GPU) is measured beside the other rungs in \
         `docs/tradeoffs/atmos.md`.\n"
    ));
    out
}

fn json(rows: &[Row]) -> String {
    let items: Vec<String> = rows
        .iter()
        .map(|r| {
            format!(
                "  {{\"sun_elevation_deg\": {}, \"colouring\": \"{}\", \"queries\": {}, \"mean\": {:e}, \"p95\": {:e}, \"max\": {:e}, \"paint_s\": {:e}, \"dome_s_per_direction\": {:e}, \"model_frame_s\": {:e}, \"model_s_per_direction\": {:e}}}",
                r.sun_elevation,
                r.colouring,
                r.queries,
                r.mean,
                r.p95,
                r.max,
                r.paint_seconds,
                r.dome_seconds_per_direction,
                r.model_frame_seconds,
                r.model_seconds_per_direction
            )
        })
        .collect();
    format!("[\n{}\n]\n", items.join(",\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_cover_the_sky_above_the_horizon() {
        let d = sky_directions(1000);
        assert!(
            d.iter().all(|v| v[2] > 0.0087
                && ((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0).abs() < 1e-12)
        );
        // Area-uniform: half the directions above 30°·… the z midpoint.
        let above = d.iter().filter(|v| v[2] > 0.5 + 0.5 * 0.0087).count();
        assert!((above as f64 / 1000.0 - 0.5).abs() < 0.01);
    }

    #[test]
    fn luminance_of_white_is_one() {
        assert!((luminance([1.0; 3]) - 1.0).abs() < 1e-12);
        let _: &dyn SkyModel =
            &atmos::closed_form_sky::ClosedFormSky::new(&Atmosphere::earth()).unwrap();
    }
}
