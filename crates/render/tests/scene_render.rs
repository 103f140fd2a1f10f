//! Golden properties (not golden images) of scenes rendered by the CPU reference
//! renderer, and the scene file's errors. Small sizes: these run in debug builds.

mod common;

use common::parse_error;
use glam::DVec3;
use render::cpu_renderer::{PixelRadiance, render_cpu, render_radiance};
use render::scene::{Scene, SceneError};

fn default_scene(width: u32, height: u32) -> Scene {
    common::shipped("default", width, height)
}

fn luminance(rgb: [f32; 3]) -> f64 {
    atmos::ladder::luminance(rgb.map(f64::from))
}

/// The world position (camera-relative, metres) of a terrain pixel.
fn hit_offset(scene: &render::scene::PreparedScene, pixel: [u32; 2], distance: f32) -> DVec3 {
    let view = atmos::frame::frame_view_direction(pixel, &scene.camera);
    DVec3::from_array(view.map(f64::from)) * f64::from(distance)
}

#[test]
fn the_default_scene_renders_terrain_under_a_sky() {
    let scene = default_scene(48, 27).prepare().unwrap();
    let frame = render_cpu(&scene).unwrap();
    assert_eq!(frame.pixels.len(), 48 * 27);
    let radiance = render_radiance(&scene).unwrap();
    let terrain = radiance
        .iter()
        .filter(|p| p.terrain_distance.is_some())
        .count();
    // The mountains fill the lower part of the frame, the sky the upper.
    assert!(
        terrain > 48 * 27 / 4 && terrain < 48 * 27 * 3 / 4,
        "{terrain} terrain pixels"
    );
    for p in &radiance {
        assert!(
            p.radiance.iter().all(|c| c.is_finite() && *c >= 0.0),
            "{p:?}"
        );
    }
    // A sunlit slope is brighter than black: the ground is lit, not dark.
    let brightest = radiance
        .iter()
        .filter(|p| p.terrain_distance.is_some())
        .map(|p| luminance(p.radiance))
        .fold(0.0, f64::max);
    assert!(brightest > 0.01, "brightest terrain luminance {brightest}");
}

#[test]
fn the_default_scenes_zenith_is_blue() {
    let mut scene = default_scene(8, 8);
    scene.file.camera.look_at = None;
    scene.file.camera.look_direction = Some([0.0, 1.0, -0.01]);
    scene.file.clouds = None; // the clear sky between the cumulus
    let prepared = scene.prepare().unwrap();
    let radiance = render_radiance(&prepared).unwrap();
    let [r, g, b] = radiance[4 * 8 + 4].radiance;
    assert!(b > g && g > r, "zenith rgb {r} {g} {b}");
}

#[test]
fn distant_mountains_take_the_skys_colour() {
    let prepared = default_scene(96, 54).prepare().unwrap();
    let radiance = render_radiance(&prepared).unwrap();
    let width = 96usize;
    // The horizon sky: the lowest sky pixel of each column, averaged.
    let mut horizon = [0.0f64; 3];
    let mut horizon_count = 0.0;
    for x in 0..width {
        if let Some(p) = (0..54)
            .map(|y| radiance[y * width + x])
            .take_while(|p| p.terrain_distance.is_none())
            .last()
        {
            for (sum, c) in horizon.iter_mut().zip(p.radiance) {
                *sum += f64::from(c);
            }
            horizon_count += 1.0;
        }
    }
    let horizon = horizon.map(|c| c / horizon_count);
    let mean_distance_to_sky = |keep: &dyn Fn(f32) -> bool| {
        let pixels: Vec<&PixelRadiance> = radiance
            .iter()
            .filter(|p| p.terrain_distance.is_some_and(keep))
            .collect();
        assert!(pixels.len() > 20, "{} pixels", pixels.len());
        pixels
            .iter()
            .map(|p| {
                (0..3)
                    .map(|k| (f64::from(p.radiance[k]) - horizon[k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .sum::<f64>()
            / pixels.len() as f64
    };
    let near = mean_distance_to_sky(&|d| d < 5_000.0);
    let far = mean_distance_to_sky(&|d| d > 20_000.0);
    eprintln!("distance to the horizon sky: near {near:.4}, far {far:.4}");
    assert!(
        far < 0.75 * near,
        "distant terrain is {far:.4} from the horizon sky, near terrain {near:.4}"
    );
}

/// A north–south ridge with 25° flanks on a 64×64 map at 50 m, as raw f32.
fn write_ridge(folder: &std::path::Path) {
    let drop_per_texel = 50.0 * 25f32.to_radians().tan();
    let bytes: Vec<u8> = (0..64 * 64)
        .flat_map(|i| {
            let x = (i % 64) as f32;
            (800.0 - drop_per_texel * (x - 31.5).abs())
                .max(0.0)
                .to_le_bytes()
        })
        .collect();
    std::fs::write(folder.join("ridge.f32"), bytes).unwrap();
}

#[test]
fn at_sunset_east_faces_are_darker_than_west_faces() {
    let folder = std::env::temp_dir().join(format!("render-ridge-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    write_ridge(&folder);
    for horizon in [
        "horizon = \"east-west\"",
        "horizon = \"azimuths\"\nhorizon_azimuths = 8",
    ] {
        let text = format!(
            "[camera]\nposition = [0.0, 700.0, 4500.0]\nlook_at = [0.0, 300.0, 0.0]\n\
             vertical_fov_deg = 40.0\n\
             [sun]\nelevation_deg = 3.0\nazimuth_deg = 270.0\n\
             [atmosphere]\nrung = \"closed-form\"\n\
             [terrain]\n{horizon}\n\
             [terrain.raw_f32]\npath = \"ridge.f32\"\nwidth = 64\nheight = 64\ncell_size = 50.0\n\
             [output]\nwidth = 40\nheight = 24\n"
        );
        let prepared = Scene::parse(&text, &folder).unwrap().prepare().unwrap();
        let radiance = render_radiance(&prepared).unwrap();
        let (mut west, mut east) = (Vec::new(), Vec::new());
        for (i, p) in radiance.iter().enumerate() {
            let Some(distance) = p.terrain_distance else {
                continue;
            };
            let pixel = [(i % 40) as u32, (i / 40) as u32];
            let point = prepared.camera_position + hit_offset(&prepared, pixel, distance);
            // The crest runs along x = 0; keep clear of it and of the flat ground.
            let elevation = point.y - prepared.atmosphere.planet_radius;
            if elevation < 100.0 || point.x.abs() < 80.0 {
                continue;
            }
            let l = luminance(p.radiance);
            if point.x < 0.0 {
                west.push(l)
            } else {
                east.push(l)
            }
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        assert!(
            west.len() > 10 && east.len() > 10,
            "{} west, {} east",
            west.len(),
            east.len()
        );
        let (w, e) = (mean(&west), mean(&east));
        eprintln!("{horizon}: west faces {w:.5}, east faces {e:.5}");
        assert!(
            w > 2.0 * e,
            "{horizon}: west faces {w:.5}, east faces {e:.5}"
        );
    }
    let _ = std::fs::remove_dir_all(&folder);
}

const VALID: &str = "[camera]\nposition = [0.0, 2.0, 0.0]\nlook_direction = [0.0, 0.2, -1.0]\n\
                     [sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n";

#[test]
fn a_misspelt_key_names_its_line_column_and_the_right_key() {
    let text = VALID.replace("[sun]\n", "[sun]\nelevaton_deg = 3.0\n");
    let e = parse_error(&text);
    let message = e.to_string();
    assert_eq!(
        e.location().map(|l| (l.line, l.column)),
        Some((5, 1)),
        "{message}"
    );
    assert!(message.contains("line 5, column 1"), "{message}");
    assert!(
        message.contains("did you mean `elevation_deg`"),
        "{message}"
    );
    assert!(message.contains("`sun.elevaton_deg`"), "{message}");
}

#[test]
fn an_unknown_rung_is_rejected_with_the_nearest_name() {
    let text = format!("{VALID}[atmosphere]\nrung = \"precomputd\"\n");
    let e = parse_error(&text);
    let message = e.to_string();
    assert_eq!(e.location().map(|l| l.line), Some(8), "{message}");
    assert!(message.contains("did you mean `precomputed`"), "{message}");
}

#[test]
fn nan_and_out_of_range_values_name_the_field_in_the_unit_typed() {
    let e = parse_error(&VALID.replace("[sun]", "vertical_fov_deg = nan\n[sun]"));
    let message = e.to_string();
    assert_eq!(e.field(), Some("camera.vertical_fov_deg"), "{message}");
    assert_eq!(
        e.location().map(|l| (l.line, l.column)),
        Some((4, 20)),
        "{message}"
    );
    assert!(message.contains("NaN°"), "{message}");
    assert!(matches!(e, SceneError::Atmosphere { .. }), "{e:?}");

    let e = parse_error(&VALID.replace("elevation_deg = 30.0", "elevation_deg = 120.0"));
    assert_eq!(e.field(), Some("sun.elevation_deg"));
    assert!(e.to_string().contains("120°"), "{e}");

    let e = parse_error(&format!("{VALID}[atmosphere]\nmie_g = 1.5\n"));
    assert_eq!(e.field(), Some("atmosphere.mie_g"));
    assert_eq!(e.location().map(|l| l.line), Some(8), "{e}");
}

#[test]
fn negative_and_zero_sizes_are_rejected_before_anything_is_built() {
    let terrain = "[terrain.procedural]\nseed = 1\nsize = -5\ncell_size = 10.0\n";
    let e = parse_error(&format!("{VALID}{terrain}"));
    assert_eq!(e.location().map(|l| l.line), Some(9), "{e}");
    assert!(e.to_string().contains("-5"), "{e}");

    let terrain = "[terrain.procedural]\nseed = 1\nsize = 32\ncell_size = -10.0\n";
    let e = parse_error(&format!("{VALID}{terrain}"));
    assert_eq!(e.field(), Some("terrain.procedural.cell_size"), "{e}");
    assert_eq!(e.location().map(|l| l.line), Some(10), "{e}");
    assert!(e.to_string().contains("-10 m"), "{e}");
    assert!(matches!(e, SceneError::Terrain { .. }), "{e:?}");

    let e = parse_error(&format!("{VALID}[output]\nwidth = 16384\nheight = 16384\n"));
    assert_eq!(e.field(), Some("output.height"), "{e}");
    assert!(e.to_string().contains("268435456 pixels"), "{e}");

    let e = parse_error(&format!("{VALID}[output]\nwidth = 0\n"));
    assert_eq!(e.field(), Some("output.width"), "{e}");
    assert_eq!(e.location().map(|l| l.line), Some(8), "{e}");
}

#[test]
fn a_missing_heightfield_file_names_the_path() {
    let terrain =
        "[terrain.png16]\npath = \"no-such-map.png\"\ncell_size = 30.0\nheight_scale = 0.1\n";
    let e = parse_error(&format!("{VALID}{terrain}"));
    assert_eq!(e.field(), Some("terrain.png16.path"), "{e}");
    assert!(e.to_string().contains("no-such-map.png"), "{e}");
    assert!(std::error::Error::source(&e).is_some());
}

/// Renders the ridge in a 30° afternoon sun with each rung and checks that the
/// sunlit flank is lit (not black ground, as a sky-only rung would draw).
fn rungs_draw_lit_terrain(rungs: &[&str]) {
    let folder =
        std::env::temp_dir().join(format!("render-rungs-{}-{}", std::process::id(), rungs[0]));
    std::fs::create_dir_all(&folder).unwrap();
    write_ridge(&folder);
    for rung in rungs {
        let text = format!(
            "[camera]\nposition = [0.0, 700.0, 4500.0]\nlook_at = [0.0, 300.0, 0.0]\n\
             vertical_fov_deg = 40.0\n\
             [sun]\nelevation_deg = 30.0\nazimuth_deg = 240.0\n\
             [atmosphere]\nrung = \"{rung}\"\n\
             [terrain.raw_f32]\npath = \"ridge.f32\"\nwidth = 64\nheight = 64\ncell_size = 50.0\n\
             [output]\nwidth = 16\nheight = 10\n"
        );
        let start = std::time::Instant::now();
        let prepared = Scene::parse(&text, &folder).unwrap().prepare().unwrap();
        let radiance = render_radiance(&prepared).unwrap();
        let terrain: Vec<f64> = radiance
            .iter()
            .filter(|p| p.terrain_distance.is_some())
            .map(|p| luminance(p.radiance))
            .collect();
        let brightest = terrain.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "{rung}: {} terrain pixels, brightest {brightest:.4} ({:.1} s)",
            terrain.len(),
            start.elapsed().as_secs_f64()
        );
        // A sunlit 25° slope of albedo ~0.1 under a 30° sun: ~0.02 per unit irradiance.
        assert!(
            terrain.len() > 10,
            "{rung}: {} terrain pixels",
            terrain.len()
        );
        assert!(brightest > 0.01, "{rung}: brightest terrain {brightest}");
    }
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn every_real_time_rung_draws_lit_terrain() {
    rungs_draw_lit_terrain(&[
        "dome",
        "closed-form",
        "closed-form-vertex",
        "single",
        "precomputed",
    ]);
}

/// The f64 reference rungs take 10 s and 53 s in a debug build:
/// `cargo test -p render --test scene_render -- --ignored`.
#[test]
#[ignore = "slow in debug builds (about a minute)"]
fn the_reference_rungs_draw_lit_terrain() {
    rungs_draw_lit_terrain(&["reference", "reference-spectral"]);
}

#[test]
fn a_missing_key_or_section_is_named() {
    let e =
        parse_error("[camera]\nposition = [0.0, 2.0, 0.0]\nlook_direction = [0.0, 0.2, -1.0]\n");
    assert_eq!(e.field(), Some("sun"), "{e}");
    let e = parse_error(&VALID.replace("position = [0.0, 2.0, 0.0]\n", ""));
    assert_eq!(e.field(), Some("camera.position"), "{e}");
    assert_eq!(e.location().map(|l| l.line), Some(1), "{e}");
}

#[test]
fn a_png16_heightfield_loads_with_its_cell_size_and_height_scale() {
    let folder = std::env::temp_dir().join(format!("render-png16-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let source =
        terrain::Heightfield::from_fn(20, 10, 1.0, |x, y| (100 + 7 * x + 3 * y) as f32).unwrap();
    std::fs::write(folder.join("map.png"), source.to_png16(0.5, 50.0).unwrap()).unwrap();
    // The camera above the map's 100 to 250 m (under it is an error).
    let above = VALID.replace("position = [0.0, 2.0, 0.0]", "position = [0.0, 500.0, 0.0]");
    let text = format!(
        "{above}[terrain.png16]\npath = \"map.png\"\ncell_size = 30.0\nheight_scale = 0.5\n\
         height_offset = 50.0\n[output]\nwidth = 8\nheight = 6\n"
    );
    let prepared = Scene::parse(&text, &folder).unwrap().prepare().unwrap();
    let terrain = prepared.terrain.as_ref().unwrap();
    let hf = &terrain.heightfield;
    assert_eq!((hf.width(), hf.height(), hf.spacing()), (20, 10, 30.0));
    for (loaded, expected) in hf.elevations().iter().zip(source.elevations()) {
        assert!((loaded - expected).abs() <= 0.25, "{loaded} vs {expected}");
    }
    render_cpu(&prepared).unwrap();
    let _ = std::fs::remove_dir_all(&folder);
}

const NIGHT_SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/night.toml");

#[test]
fn a_full_moon_night_is_a_dim_blue_sky_with_the_moon_and_stars() {
    let mut scene = Scene::open(NIGHT_SCENE).unwrap();
    scene.file.output.width = 160;
    scene.file.output.height = 90;
    let prepared = scene.prepare().unwrap();
    assert!(
        prepared.sun_elevation_deg() < -18.0,
        "{}",
        prepared.sun_elevation_deg()
    );
    let objects = prepared
        .sky_objects
        .as_ref()
        .expect("[time] places the sky objects");
    assert!(
        objects.points.len() > 100,
        "{} point sources",
        objects.points.len()
    );
    let radiance = render_radiance(&prepared).unwrap();
    let mut values: Vec<f64> = radiance.iter().map(|p| luminance(p.radiance)).collect();
    values.sort_by(f64::total_cmp);
    let median = values[values.len() / 2];
    // The sky and the ridges are dark (the sun is 53° down); the moon and the stars
    // stand out by orders of magnitude.
    let day = default_scene(16, 9).prepare().unwrap();
    let day_median = {
        let mut v: Vec<f64> = render_radiance(&day)
            .unwrap()
            .iter()
            .map(|p| luminance(p.radiance))
            .collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    // A full moon's sky: of the order of 10⁻⁶ of the day's (the moon's irradiance is
    // ~1/400,000 of the sun's), and blue like it (the same scattering).
    assert!(
        median > 1e-7 * day_median && median < 1e-5 * day_median,
        "night median {median:e}, day {day_median:e}"
    );
    let sky_pixel = radiance
        .iter()
        .filter(|p| p.terrain_distance.is_none())
        .min_by(|a, b| {
            (luminance(a.radiance) - median)
                .abs()
                .total_cmp(&(luminance(b.radiance) - median).abs())
        })
        .unwrap();
    let [r, _, b] = sky_pixel.radiance;
    assert!(b > r, "the moonlit sky is blue: {:?}", sky_pixel.radiance);
    // The moon, 0.5° across, is smaller than this frame's pixels: a 4° view of it.
    let moon = prepared
        .other_lights
        .first()
        .expect("the moon is up")
        .direction;
    let mut close = Scene::open(NIGHT_SCENE).unwrap();
    close.file.output.width = 32;
    close.file.output.height = 18;
    close.file.camera.vertical_fov_deg = 4.0;
    close.file.camera.look_direction = Some(moon.to_array());
    let close = render_radiance(&close.prepare().unwrap()).unwrap();
    let brightest = close
        .iter()
        .map(|p| luminance(p.radiance))
        .fold(0.0, f64::max);
    assert!(
        brightest > 1e4 * median,
        "the moon: {brightest:e} against the night sky's {median:e}"
    );
    // Terrain hides the objects behind it.
    assert!(
        radiance
            .iter()
            .filter(|p| p.terrain_distance.is_some())
            .all(|p| luminance(p.radiance) < 10.0 * median.max(1e-12) + 1e-9),
        "a star drawn over terrain"
    );
}

/// The moon lights the terrain through the same shading as the sun — N·L, the
/// horizon maps' self-shadow, the sky it lights, the aerial perspective — scaled by its
/// irradiance: the night scene's terrain equals, per channel, the same view lit by a
/// sun standing where the moon stands, times the moon's irradiance over the sun's (the
/// sun 53° down adds nothing). Only the light's angular radius differs (the soft
/// shadow's edge).
#[test]
fn the_moon_lights_the_terrain_as_a_sun_of_its_irradiance_would() {
    let small = |mut scene: Scene| {
        scene.file.output.width = 160;
        scene.file.output.height = 90;
        scene
    };
    let night = small(Scene::open(NIGHT_SCENE).unwrap()).prepare().unwrap();
    let moon = night.other_lights.first().expect("the moon is up");
    let scale: [f64; 3] = std::array::from_fn(|c| {
        moon.atmosphere.sun_irradiance[c] / night.atmosphere.sun_irradiance[c]
    });
    let d = moon.direction; // x east, y up, z south
    let mut equivalent = small(Scene::open(NIGHT_SCENE).unwrap());
    equivalent.file.time = None;
    equivalent.file.sky_objects = None;
    equivalent.file.sun = Some(render::scene::SunSection {
        elevation_deg: d.y.asin().to_degrees(),
        azimuth_deg: d.x.atan2(-d.z).to_degrees(),
    });
    let lit = render_radiance(&night).unwrap();
    let sunlit = render_radiance(&equivalent.prepare().unwrap()).unwrap();
    let mut differences: Vec<f64> = lit
        .iter()
        .zip(&sunlit)
        .filter(|(a, b)| a.terrain_distance.is_some() && b.terrain_distance.is_some())
        .flat_map(|(a, b)| {
            (0..3).map(move |c| {
                let expected = f64::from(b.radiance[c]) * scale[c];
                (f64::from(a.radiance[c]) - expected).abs() / expected.max(1e-30)
            })
        })
        .collect();
    assert!(
        differences.len() > 3 * 1000,
        "{} terrain values",
        differences.len()
    );
    differences.sort_by(f64::total_cmp);
    let median = differences[differences.len() / 2];
    let p95 = differences[differences.len() * 95 / 100];
    eprintln!("moonlit terrain vs the scaled sunlit one: median {median:.2e}, p95 {p95:.2e}");
    assert!(
        median < 1e-5 && p95 < 1e-3,
        "median {median:e}, p95 {p95:e}"
    );
    // And it is lit: the terrain's median is of the order of the moonlit sky's.
    let mut terrain: Vec<f64> = lit
        .iter()
        .filter(|p| p.terrain_distance.is_some())
        .map(|p| luminance(p.radiance))
        .collect();
    terrain.sort_by(f64::total_cmp);
    assert!(terrain[terrain.len() / 2] > 0.0);
}

#[test]
fn time_and_place_errors_name_the_key() {
    let timed = VALID.replace(
        "[sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n",
        "[time]\nutc = \"2024-12-15T21:00:00Z\"\nlatitude_deg = 46.5\nlongitude_deg = 8.0\n",
    );
    let prepared = Scene::parse(&timed, ".").unwrap().prepare().unwrap();
    assert!(prepared.sky_objects.is_some());
    let both = format!("{VALID}{}", &timed[timed.find("[time]").unwrap()..]);
    let e = parse_error(&both);
    assert_eq!(e.field(), Some("time.utc"), "{e}");
    let e = parse_error(&timed.replace("2024-12-15T21:00:00Z", "2024-13-15T21:00:00Z"));
    assert_eq!(e.field(), Some("time.utc"), "{e}");
    assert!(e.to_string().contains("2024-13-15"), "{e}");
    let e = parse_error(&timed.replace("latitude_deg = 46.5", "latitude_deg = 96.5"));
    assert_eq!(e.field(), Some("time.latitude_deg"), "{e}");
    assert!(e.to_string().contains("96.5"), "{e}");
    let e = parse_error(&format!("{VALID}[sky_objects]\nenabled = true\n"));
    assert_eq!(e.field(), Some("sky_objects.enabled"), "{e}");
}

const ABOVE_CLOUDS_SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenes/above_clouds.toml"
);

#[test]
fn a_cloud_deck_covers_the_valleys_and_not_the_peaks_above_it() {
    let mut scene = Scene::open(ABOVE_CLOUDS_SCENE).unwrap();
    scene.file.output.width = 96;
    scene.file.output.height = 54;
    // The stratus deck alone (the cirrus at 9 km would shade the peaks too: its
    // shadow, not the deck, would change them).
    if let Some(clouds) = scene.file.clouds.as_mut() {
        clouds.layers.truncate(1);
    }
    let cloudy = scene.prepare().unwrap();
    assert_eq!(cloudy.cloud_layers.len(), 1);
    let clouded = render_radiance(&cloudy).unwrap();
    scene.file.clouds = None;
    let clear = render_radiance(&scene.prepare().unwrap()).unwrap();
    let (mut peaks, mut peaks_changed, mut valleys, mut valleys_changed) = (0, 0, 0, 0);
    for (pixel, (with, without)) in clouded.iter().zip(&clear).enumerate() {
        let Some(distance) = without.terrain_distance else {
            continue;
        };
        let pixel = [(pixel % 96) as u32, (pixel / 96) as u32];
        let elevation = cloudy.camera_position.y - cloudy.atmosphere.planet_radius
            + hit_offset(&cloudy, pixel, distance).y;
        let changed = with.radiance != without.radiance;
        // The stratus deck is 2,000–2,300 m: above it the terrain is in front of the
        // deck and out of its shadow.
        if elevation > 2300.0 {
            peaks += 1;
            peaks_changed += usize::from(changed);
        } else if elevation < 2000.0 {
            valleys += 1;
            valleys_changed += usize::from(changed);
        }
    }
    assert!(
        peaks > 20 && valleys > 20,
        "{peaks} peak and {valleys} valley pixels"
    );
    assert_eq!(peaks_changed, 0, "terrain above the deck is in front of it");
    assert!(
        valleys_changed * 2 > valleys,
        "{valleys_changed} of {valleys} valley pixels under the deck"
    );
}

#[test]
fn cloud_layers_need_time_and_name_bad_values() {
    let layer = "[[clouds.layers]]\nkind = \"cumulus\"\nbase_m = 1500.0\nthickness_m = 300.0\n";
    let e = parse_error(&format!("{VALID}{layer}"));
    assert_eq!(e.field(), Some("clouds.layers"), "{e}");
    let timed = VALID.replace(
        "[sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n",
        "[time]\nutc = \"2024-06-21T12:00:00Z\"\nlatitude_deg = 46.5\nlongitude_deg = 8.0\n",
    );
    let prepared = Scene::parse(&format!("{timed}{layer}"), ".")
        .unwrap()
        .prepare()
        .unwrap();
    assert_eq!(prepared.cloud_layers.len(), 1);
    let e = parse_error(&format!("{timed}{}", layer.replace("300.0", "-300.0")));
    assert_eq!(e.field(), Some("clouds.layers.0.thickness_m"), "{e}");
    assert!(e.to_string().contains("-300"), "{e}");
    let e = parse_error(&format!(
        "{timed}{}",
        layer.replace("cumulus", "cumulonimbus")
    ));
    assert!(e.to_string().contains("cumulonimbus"), "{e}");
}

#[test]
fn cloud_shadows_darken_the_ground_beneath_and_nowhere_else() {
    let mut scene = default_scene(96, 54);
    let cloudy = scene.prepare().unwrap();
    assert!(!cloudy.cloud_layers.is_empty());
    let with = render_radiance(&cloudy).unwrap();
    scene.file.clouds = None;
    let without = render_radiance(&scene.prepare().unwrap()).unwrap();
    let (mut shadowed, mut darker, mut sunlit, mut unchanged) = (0, 0, 0, 0);
    let mut brighter = 0;
    for (pixel, (a, b)) in with.iter().zip(&without).enumerate() {
        let Some(distance) = b.terrain_distance else {
            continue;
        };
        let pixel = [(pixel % 96) as u32, (pixel / 96) as u32];
        let offset = hit_offset(&cloudy, pixel, distance).as_vec3().to_array();
        let shadow = render::clouds::cloud_shadow_at(
            offset,
            cloudy.viewer_radius as f32,
            &cloudy.cloud_layers,
        );
        if shadow < 0.3 {
            shadowed += 1;
            darker += usize::from(luminance(a.radiance) < 0.8 * luminance(b.radiance));
            brighter += usize::from(luminance(a.radiance) > luminance(b.radiance));
        } else if shadow == 1.0 {
            sunlit += 1;
            unchanged += usize::from(a.radiance == b.radiance);
        }
    }
    assert!(
        shadowed > 50 && sunlit > 50,
        "{shadowed} shadowed, {sunlit} sunlit pixels"
    );
    // Faces already in the terrain's own shadow (or turned from the sun) have no direct
    // sun to lose; every other shadowed pixel is darker by over a fifth.
    assert_eq!(brighter, 0, "a pixel under a cloud's shadow got brighter");
    assert!(
        darker * 4 >= shadowed * 3,
        "{darker} of {shadowed} shadowed pixels darker"
    );
    assert_eq!(unchanged, sunlit, "a pixel outside every shadow changed");
}

#[test]
fn the_camera_looks_straight_up_and_straight_down() {
    for (direction, expect_terrain) in [([0.0, 1.0, 0.0], false), ([0.0, -1.0, 0.0], true)] {
        let mut scene = default_scene(16, 9);
        scene.file.camera.look_at = None;
        scene.file.camera.look_direction = Some(direction);
        let prepared = scene.prepare().unwrap();
        let radiance = render_radiance(&prepared).unwrap();
        let terrain = radiance
            .iter()
            .filter(|p| p.terrain_distance.is_some())
            .count();
        assert_eq!(
            terrain == radiance.len(),
            expect_terrain,
            "{direction:?}: {terrain}"
        );
        assert!(
            radiance
                .iter()
                .all(|p| p.radiance.iter().all(|v| v.is_finite()))
        );
    }
}

#[test]
fn a_panorama_from_cube_faces_sees_what_the_camera_sees() {
    use render::projection::{CUBE_FACES, Face, Projection, assemble, face_scene};
    // The default sky without terrain, clouds or the ephemeris, in the closed form
    // (cheap to prepare eight times in a debug build).
    let mut scene = default_scene(64, 32);
    scene.file.terrain = None;
    scene.file.clouds = None;
    scene.file.time = None;
    scene.file.sun = Some(render::scene::SunSection {
        elevation_deg: 34.0,
        azimuth_deg: 228.0,
    });
    scene.file.atmosphere.rung = render::scene::Rung::ClosedForm;
    scene.file.output.projection = Projection::Equirectangular;
    let view = scene.prepare().unwrap();
    let faces: Vec<Face> = CUBE_FACES
        .iter()
        .map(|&forward| {
            let prepared = face_scene(&scene, forward, 16).prepare().unwrap();
            let radiance = render_radiance(&prepared)
                .unwrap()
                .iter()
                .map(|p| p.radiance)
                .collect();
            Face {
                camera: prepared.camera,
                radiance,
            }
        })
        .collect();
    let pano = assemble(
        Projection::Equirectangular,
        &faces,
        64,
        32,
        &view.camera,
        0.0,
    )
    .unwrap();
    // A direct camera looking where panorama pixel (48, 12) looks (azimuth 272.8°,
    // elevation 22.5°: west, above the horizon) sees the same radiance.
    let (x, y) = (48usize, 12usize);
    let azimuth = (x as f64 + 0.5) / 64.0 * std::f64::consts::TAU;
    let elevation = std::f64::consts::FRAC_PI_2 - (y as f64 + 0.5) / 32.0 * std::f64::consts::PI;
    let direction = render::scene::prepare::world_direction(elevation, azimuth);
    let mut direct = scene.clone();
    direct.file.output.projection = Projection::Rectilinear;
    direct.file.output.width = 1;
    direct.file.output.height = 1;
    direct.file.camera.look_at = None;
    direct.file.camera.look_direction = Some(direction.to_array());
    let truth = render_radiance(&direct.prepare().unwrap()).unwrap()[0].radiance;
    let got = pano[y * 64 + x];
    for k in 0..3 {
        assert!(
            (got[k] - truth[k]).abs() <= 0.02 * truth[k],
            "{got:?} vs {truth:?}"
        );
    }
    // A cubemap strip is six faces wide, or an error naming output.width.
    scene.file.output.projection = Projection::Cubemap;
    let e = scene.prepare().unwrap_err();
    assert_eq!(e.field(), Some("output.width"), "{e}");
}

/// A cubemap's faces share one preparation: `PreparedScene::look_along` gives the same
/// image as preparing the face's own scene (camera, sky objects and all), bit for bit.
#[test]
fn look_along_is_the_face_scene_prepared_again() {
    let scene = default_scene(48, 27);
    let forward = [0.6, 0.1, -0.79];
    let face = render::projection::face_scene(&scene, forward, 24);
    let expected = render_radiance(&face.prepare().unwrap()).unwrap();
    let mut prepared = scene.prepare().unwrap();
    prepared
        .look_along(
            DVec3::from_array(forward),
            std::f64::consts::FRAC_PI_2,
            24,
            24,
        )
        .unwrap();
    let got = render_radiance(&prepared).unwrap();
    assert_eq!(got.len(), expected.len());
    for (i, (a, b)) in got.iter().zip(&expected).enumerate() {
        assert_eq!(a, b, "pixel {i}");
    }
}

/// A preparation cache changes what is built, not what is drawn: the night (sun and
/// moon, precomputed rung, procedural terrain) prepared through one cache three times
/// renders bit for bit the image of a plain `prepare`; the first preparation bakes the
/// static tables once (the moon's are the sun's relit) and builds the terrain and
/// celestial's sky, the later ones take all four. A heightfield file replaced between
/// two preparations is read again.
#[test]
fn a_preparation_cache_keeps_what_did_not_change() {
    let mut scene = Scene::open(NIGHT_SCENE).unwrap();
    scene.file.output.width = 32;
    scene.file.output.height = 18;
    let plain = render_radiance(&scene.prepare().unwrap()).unwrap();
    let cache = render::scene::PrepareCache::new();
    let first = scene.prepare_cached(&cache).unwrap();
    assert_eq!(first.lights().len(), 2, "the night's sun and moon");
    assert_eq!(
        cache.counts(),
        [3, 1],
        "tables, terrain and celestial's sky built, the moon's tables relit"
    );
    for _ in 0..2 {
        let again = scene.prepare_cached(&cache).unwrap();
        assert_eq!(render_radiance(&again).unwrap(), plain);
    }
    assert_eq!(cache.counts(), [3, 9], "every later product taken");
    assert_eq!(render_radiance(&first).unwrap(), plain);

    // Kept in a folder, the tables outlive the cache: a new cache in the same folder
    // (a second run) reads them back and draws the same image; a damaged file is baked
    // again and replaced whole.
    let folder = std::env::temp_dir().join(format!("skyscape-tables-{}", std::process::id()));
    let run = || {
        let cache = render::scene::PrepareCache::in_folder(&folder);
        let image = render_radiance(&scene.prepare_cached(&cache).unwrap()).unwrap();
        (cache.counts(), image)
    };
    let (counts, image) = run();
    assert_eq!(
        (counts, image == plain),
        ([3, 1], true),
        "the first run bakes"
    );
    let files: Vec<_> = std::fs::read_dir(&folder).unwrap().flatten().collect();
    assert_eq!(files.len(), 1, "one file for the night's air: {files:?}");
    let (counts, image) = run();
    assert_eq!(
        (counts, image == plain),
        ([2, 2], true),
        "the second run reads them"
    );
    let path = files[0].path();
    let whole = std::fs::read(&path).unwrap();
    std::fs::write(&path, &whole[..whole.len() / 2]).unwrap();
    let (counts, image) = run();
    assert_eq!(
        (counts, image == plain),
        ([3, 1], true),
        "a damaged file is baked again"
    );
    assert_eq!(std::fs::read(&path).unwrap(), whole, "and replaced whole");
    std::fs::remove_dir_all(&folder).ok();

    // A heightfield file replaced between preparations is read again.
    let folder = std::env::temp_dir().join(format!("skyscape-cache-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    write_ridge(&folder);
    let source = "[camera]\nposition = [0.0, 1500.0, 300.0]\nlook_direction = [0.0, -0.3, -1.0]\n\
         [sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n\
         [atmosphere]\nrung = \"closed-form\"\n\
         [output]\nwidth = 16\nheight = 9\n\
         [terrain.raw_f32]\npath = \"ridge.f32\"\nwidth = 64\nheight = 64\ncell_size = 30.0\n";
    let ridge = Scene::parse(source, &folder).unwrap();
    let cache = render::scene::PrepareCache::new();
    let before = ridge.prepare_cached(&cache).unwrap();
    ridge.prepare_cached(&cache).unwrap();
    assert_eq!(cache.counts(), [1, 1]);
    let file = folder.join("ridge.f32");
    let heights: Vec<u8> = std::fs::read(&file)
        .unwrap()
        .chunks(4)
        .flat_map(|h| (f32::from_le_bytes(h.try_into().unwrap()) + 100.0).to_le_bytes())
        .collect();
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&file, heights).unwrap();
    let after = ridge.prepare_cached(&cache).unwrap();
    assert_eq!(cache.counts(), [2, 1], "the replaced file is read again");
    let [low, high] = [&before, &after].map(|p| {
        let hf = &p.terrain.as_ref().unwrap().heightfield;
        hf.elevations().into_iter().fold(f64::MIN, f64::max)
    });
    assert!((high - low - 100.0).abs() < 1e-3, "{low} → {high}");
    std::fs::remove_dir_all(&folder).ok();
}
