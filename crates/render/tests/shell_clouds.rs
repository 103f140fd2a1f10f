//! `[clouds.shell]`: Schneider's (GPU Pro 7) ray-marched cloud shell in a scene. The scene keys'
//! errors (cloudlight's validation, named by key and line), nothing planned without
//! the section, the shipped `stratocumulus` scene on the CPU (hills in front of the
//! deck hide it, the deck in front of hills covers them, every value finite), an
//! overcast deck hiding the sun, and the GPU image against the CPU's (lavapipe in CI).

mod common;

use common::{VALID, cpu_pixels, gpu_pixels, lsb, parse_error, within_two_over};
use render::scene::{PreparedScene, Scene, SceneError};
use render::shell_clouds::{PreparedShell, march_shell_pixel, shell_camera};

/// The deck unlit: its march gives the same transmittance and depth (they do not depend
/// on the light) without the light and ambient marches, which the march skips for a
/// black sun and sky — the tests classify pixels with it at a fifth of the cost.
fn unlit(cloud: &PreparedShell) -> PreparedShell {
    let mut cloud = cloud.clone();
    cloud.lights[0].lighting =
        cloudlight::march::Lighting::new([0.0, 0.0, 1.0], [0.0; 3], [0.0; 3], [0.0, 0.0, 1.0])
            .unwrap();
    cloud.lights.truncate(1);
    cloud
}

// Lines 9 to 15.
const SHELL: &str = "[clouds.shell]\nbottom_m = 1000.0\ntop_m = 1800.0\ncoverage = 0.4\n\
                     cloud_type = 0.5\nsigma_t_per_density = 0.04\nview_steps = 8\n";

fn shipped(width: u32, height: u32) -> Scene {
    common::shipped("stratocumulus", width, height)
}

/// The shipped deck is cloudlight's `ShellSettings::stratocumulus_deck`, the deck of
/// cloudlight's shell-shadow GPU test and of the parity's shell shadow-map passes.
#[test]
fn the_shipped_deck_is_cloudlights_stratocumulus_deck() {
    let prepared = shipped(8, 8).prepare().unwrap();
    let shell = prepared.shell_cloud.as_ref().unwrap();
    assert_eq!(
        shell.shell.settings(),
        &cloudlight::ShellSettings::stratocumulus_deck(prepared.atmosphere.planet_radius)
    );
}

#[test]
fn shell_errors_name_the_key_and_its_line() {
    let prepared = Scene::parse(&format!("{VALID}{SHELL}"), ".")
        .unwrap()
        .prepare()
        .unwrap();
    let shell = prepared.shell_cloud.as_ref().unwrap();
    let r = prepared.atmosphere.planet_radius;
    assert_eq!(shell.shell.settings().inner_radius, r + 1000.0);
    assert_eq!(shell.settings.config().view_steps, 8);
    for (from, to, key, line, shown) in [
        // cloudlight's ShellError::InnerBelowGround.
        (
            "bottom_m = 1000.0",
            "bottom_m = -100.0",
            "bottom_m",
            10,
            "-100 m",
        ),
        // RadiiOrder.
        ("top_m = 1800.0", "top_m = 900.0", "top_m", 11, "900 m"),
        // OutOfRange (the weather's coverage_mean).
        ("coverage = 0.4", "coverage = 1.5", "coverage", 12, "1.5"),
        (
            "cloud_type = 0.5",
            "cloud_type = nan",
            "cloud_type",
            13,
            "NaN",
        ),
        // NotPositive.
        (
            "sigma_t_per_density = 0.04",
            "sigma_t_per_density = 0.0",
            "sigma_t_per_density",
            14,
            "0 /m",
        ),
        // render's own bound on the cost.
        (
            "view_steps = 8",
            "view_steps = 5000",
            "view_steps",
            15,
            "5000",
        ),
    ] {
        let e = parse_error(&format!("{VALID}{}", SHELL.replace(from, to)));
        let message = e.to_string();
        assert_eq!(
            e.field(),
            Some(format!("clouds.shell.{key}").as_str()),
            "{message}"
        );
        assert_eq!(e.location().map(|l| l.line), Some(line), "{message}");
        assert!(message.contains(shown), "{message}");
    }
    // cloudlight's typed errors are kept as the source.
    let e = parse_error(&format!(
        "{VALID}{}",
        SHELL.replace("coverage = 0.4", "coverage = 1.5")
    ));
    assert!(matches!(e, SceneError::Cloudlight { .. }), "{e}");
    let source = std::error::Error::source(&e).expect("cloudlight's error is the source");
    assert!(source.to_string().contains("coverage_mean"), "{source}");
    for (extra, key) in [
        ("erosion = 1.0\n", "erosion"),
        ("weather_cells = 0\n", "weather_cells"),
        ("octave_b = 2.0\n", "octave_b"),
        ("light_steps = 0\n", "light_steps"),
        (
            "horizon_fade_start_m = 5000.0\nhorizon_fade_end_m = 4000.0\n",
            "horizon_fade_end_m",
        ),
    ] {
        let e = parse_error(&format!("{VALID}{SHELL}{extra}"));
        assert_eq!(
            e.field(),
            Some(format!("clouds.shell.{key}").as_str()),
            "{e}"
        );
        assert!(e.location().is_some(), "{e}");
    }
    // A misspelt key: the nearest one is suggested.
    let e = parse_error(&format!("{VALID}{SHELL}coverge_contrast = 0.1\n"));
    assert!(e.to_string().contains("coverage_contrast"), "{e}");
}

/// Whether `skyscape explain` plans the pass called `name`.
fn planned(scene: &PreparedScene, name: &str) -> Option<bool> {
    render::passes::planned_passes(scene)
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, plan)| plan.is_ok())
}

/// The deck over `scene`'s terrain at its size on the CPU, against the same scene without
/// it: `(hidden, covering, sky)` = hill pixels nearer than the deck's bottom sphere (each
/// exactly the deck-less render's), hill pixels behind deck cloud of transmittance < 0.9
/// (each changed: the deck covers them) and sky pixels behind deck cloud of
/// transmittance < 0.5 (each changed). Every value finite and ≥ 0.
fn hidden_covering_sky(scene: &Scene) -> (usize, usize, usize) {
    let (width, height) = (scene.file.output.width, scene.file.output.height);
    let mut cloudy = scene.prepare().unwrap();
    // The deck's composite only: its shadow on the terrain is the_deck_shadows_the_terrain's.
    cloudy.shell_cloud.as_mut().unwrap().lights[0].shadow = None;
    let mut clear = scene.clone();
    clear.file.clouds = None;
    let clear = clear.prepare().unwrap();
    assert!(clear.shell_cloud.is_none());
    for name in ["shell cloud march", "shell clouds"] {
        assert_eq!(planned(&cloudy, name), Some(true), "{name}");
        assert_eq!(planned(&clear, name), Some(false), "{name}");
    }
    let with = render::cpu_renderer::render_radiance(&cloudy).unwrap();
    let without = render::cpu_renderer::render_radiance(&clear).unwrap();
    let cloud = &unlit(cloudy.shell_cloud.as_ref().unwrap());
    let camera = shell_camera(&cloudy.camera).unwrap();
    let settings = cloud.shell.settings();
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half([width, height]);
    let (mut hidden, mut covering, mut sky) = (0, 0, 0);
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            assert!(
                with[i].radiance.iter().all(|v| v.is_finite() && *v >= 0.0),
                "pixel {x}, {y}: {:?}",
                with[i].radiance
            );
            let direction = cloudlight::march::pixel_direction(
                [x, y],
                [width, height],
                forward,
                right,
                up,
                tan_half,
            );
            // Where the ray enters the shell (f64, cloudlight's spans).
            let spans = cloudlight::shell::shell_ray_spans(
                camera.origin(),
                direction,
                cloudy.atmosphere.planet_radius,
                settings.inner_radius,
                settings.outer_radius,
            );
            let enter = if spans.count > 0 {
                spans.spans[0].0
            } else {
                f64::INFINITY
            };
            let pixel = [x, y];
            match without[i].terrain_distance {
                Some(d) if f64::from(d) < enter - 1.0 => {
                    // The hill is in front of the whole deck: not drawn.
                    hidden += 1;
                    assert_eq!(with[i].radiance, without[i].radiance, "pixel {x}, {y}");
                }
                Some(d) => {
                    let m = march_shell_pixel(cloud, &camera, [width, height], pixel, d);
                    if m.transmittance < 0.9 {
                        // The deck in front of the hill covers it.
                        covering += 1;
                        assert_ne!(with[i].radiance, without[i].radiance, "pixel {x}, {y}");
                    }
                }
                None => {
                    let m =
                        march_shell_pixel(cloud, &camera, [width, height], pixel, f32::INFINITY);
                    if m.transmittance < 0.5 {
                        sky += 1;
                        assert_ne!(with[i].radiance, without[i].radiance, "pixel {x}, {y}");
                    }
                }
            }
        }
    }
    (hidden, covering, sky)
}

/// The shipped deck at 64×36 seen from the valley: the hills in front of it hide it, it
/// covers the sky; and from 2.6 km up, above it, looking down at the hills: it covers
/// the hills behind it.
#[test]
fn hills_in_front_hide_the_deck_and_the_deck_covers_hills_behind() {
    let (hidden, _, sky) = hidden_covering_sky(&shipped(64, 36));
    let mut above = shipped(64, 36);
    above.file.camera.position = [0.0, 2600.0, 9000.0];
    above.file.camera.look_at = Some([0.0, 600.0, 0.0]);
    let (_, covering, _) = hidden_covering_sky(&above);
    eprintln!(
        "stratocumulus 64×36 from the valley: {hidden} hill pixels in front of the deck \
         (unchanged), {sky} sky pixels behind deck cloud (T < 0.5); from 2.6 km up: \
         {covering} hill pixels behind deck cloud (T < 0.9, covered)"
    );
    assert!(
        hidden > 50 && sky > 50 && covering > 50,
        "{hidden} {sky} {covering}"
    );
}

/// An overcast deck (coverage 1) between the viewer and the sun hides the sun's disc:
/// the brightest pixel of a view centred on the sun drops by orders of magnitude.
#[test]
fn an_overcast_deck_hides_the_sun() {
    let text = "[camera]\nposition = [0.0, 2.0, 0.0]\n\
                look_direction = [0.0, 0.8391, -1.0]\nvertical_fov_deg = 4.0\n\
                [sun]\nelevation_deg = 40.0\nazimuth_deg = 0.0\n\
                [output]\nwidth = 24\nheight = 16\n";
    let deck = "[clouds.shell]\nbottom_m = 1000.0\ntop_m = 1800.0\ncoverage = 1.0\n\
                coverage_contrast = 0.0\ncloud_type = 0.5\ncloud_type_contrast = 0.0\n\
                view_steps = 8\nlight_steps = 2\nambient_steps = 1\noctaves = 2\n";
    let brightest = |text: &str| {
        let scene = Scene::parse(text, ".").unwrap().prepare().unwrap();
        render::cpu_renderer::render_radiance(&scene)
            .unwrap()
            .iter()
            .map(|p| p.radiance[1])
            .fold(0.0f32, f32::max)
    };
    let clear = brightest(text);
    let overcast = brightest(&format!("{text}{deck}"));
    eprintln!("brightest pixel toward the sun: clear {clear:.3e}, under the deck {overcast:.3e}");
    assert!(overcast < 1e-2 * clear, "{overcast} vs {clear}");
}

/// The shipped deck at 96×54 on the GPU (`cloudlight::gpu::MarchShellPass` limited by
/// the terrain's depth, the volume cloud's air and composite passes) and on the CPU.
#[test]
fn the_deck_agrees_on_the_gpu_and_the_cpu() {
    let Some(gpu) = common::gpu_or_skip("render::shell_clouds") else {
        return;
    };
    let (width, height) = (96, 54);
    let scene = shipped(width, height).prepare().unwrap();
    let gpu_image = gpu_pixels(gpu, &scene);
    let cpu_image = cpu_pixels(&scene);
    let within = |lsb| render::tonemap::fraction_within_lsb(&gpu_image, &cpu_image, lsb).unwrap();
    let cloud = &unlit(scene.shell_cloud.as_ref().unwrap());
    let camera = shell_camera(&scene.camera).unwrap();
    let mut deck = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let m = march_shell_pixel(cloud, &camera, [width, height], [x, y], f32::INFINITY);
            if m.transmittance < 1.0 {
                deck.push((y * width + x) as usize);
            }
        }
    }
    let (cloud_pixels, cloud_within, worst) = within_two_over(&gpu_image, &cpu_image, deck);
    let (two, eight) = (within(2), within(8));
    eprintln!(
        "stratocumulus {width}×{height} GPU vs CPU: {:.3} % of pixels within 2 LSB, {:.3} % \
         within 8; deck pixels {cloud_within} of {cloud_pixels} within 2 LSB, worst {worst} LSB",
        100.0 * two,
        100.0 * eight
    );
    assert!(cloud_pixels > 500, "{cloud_pixels}");
    assert!(two >= 0.999 && eight >= 0.9995, "{two} {eight}");
}

/// At night (the shipped night scene, the moon up) the moon lights the deck: its second
/// march, added through the moonlit air, makes the deck's pixels brighter than the sun's
/// march alone (the sun is down: only its twilight sky lights it then); the GPU agrees.
#[test]
fn the_moon_lights_the_deck_at_night() {
    let (width, height) = (64, 36);
    let night = std::fs::read_to_string(common::scene_path("night")).unwrap();
    let deck = "[clouds.shell]\nbottom_m = 3500.0\ntop_m = 4300.0\ncoverage = 0.35\n\
                coverage_contrast = 0.25\ncloud_type = 0.5\ncloud_type_contrast = 0.0\n\
                shape_period_m = 6000.0\ndetail_period_m = 800.0\nview_steps = 12\n\
                light_steps = 3\nambient_steps = 1\noctaves = 4\n";
    let mut scene = Scene::parse(&format!("{night}{deck}"), ".").unwrap();
    scene.file.output.width = width;
    scene.file.output.height = height;
    let mut prepared = scene.prepare().unwrap();
    assert!(prepared.shell_cloud.as_ref().unwrap().lights.len() > 1);
    assert_eq!(planned(&prepared, "moonlit shell march"), Some(true));
    // The deck's shadow on the moonlit terrain: toward the moon only (the sun is down).
    let shell = prepared.shell_cloud.as_ref().unwrap();
    let moon_map = shell.lights[1]
        .shadow
        .as_ref()
        .expect("a shadow map toward the moon");
    assert!(shell.lights[0].shadow.is_none());
    eprintln!(
        "night deck's shadow toward the moon: {}×{} texels, {} < 1, baked in {:.3} s",
        moon_map.resolution[0],
        moon_map.resolution[1],
        moon_map.values.iter().filter(|&&t| t < 1.0).count(),
        shell.shadow_seconds
    );
    let gpu = common::gpu_or_skip("render::shell_clouds night").map(|gpu| {
        let image = gpu_pixels(gpu, &prepared);
        let cpu = cpu_pixels(&prepared);
        (image, cpu)
    });
    let moonlit = render::cpu_renderer::render_radiance(&prepared).unwrap();
    let cloud = &unlit(prepared.shell_cloud.as_ref().unwrap());
    let camera = shell_camera(&prepared.camera).unwrap();
    let deck: Vec<usize> = (0..width * height)
        .filter(|&i| {
            let m = march_shell_pixel(
                cloud,
                &camera,
                [width, height],
                [i % width, i / width],
                moonlit[i as usize]
                    .terrain_distance
                    .unwrap_or(f32::INFINITY),
            );
            m.transmittance < 0.5
        })
        .map(|i| i as usize)
        .collect();
    prepared.shell_cloud.as_mut().unwrap().lights.truncate(1);
    let sunlit_only = render::cpu_renderer::render_radiance(&prepared).unwrap();
    let mean = |image: &[render::cpu_renderer::PixelRadiance]| {
        deck.iter()
            .map(|&i| f64::from(image[i].radiance[1]))
            .sum::<f64>()
            / deck.len() as f64
    };
    let (with, without) = (mean(&moonlit), mean(&sunlit_only));
    eprintln!(
        "night deck 64×36: {} opaque deck pixels, mean green radiance {with:.3e} with the \
         moon's march, {without:.3e} without",
        deck.len()
    );
    assert!(
        deck.len() > 100 && with > 2.0 * without,
        "{} {with} {without}",
        deck.len()
    );
    if let Some((gpu_image, cpu_image)) = gpu {
        let two = render::tonemap::fraction_within_lsb(&gpu_image, &cpu_image, 2).unwrap();
        let deck_within = deck
            .iter()
            .filter(|&&i| lsb(gpu_image[i], cpu_image[i]) <= 2)
            .count();
        eprintln!(
            "night deck 64×36 GPU vs CPU: {:.3} % of pixels within 2 LSB, deck pixels \
             {deck_within} of {} within 2 LSB",
            100.0 * two,
            deck.len()
        );
        assert!(two >= 0.99, "{two}");
        assert!(
            deck_within * 1000 >= deck.len() * 999,
            "{deck_within} of {}",
            deck.len()
        );
    }
}

/// The deck's shadow on the terrain (cloudlight's shadow map of the shell, baked over the
/// heightfield): the shipped deck at 96×54 from the valley against the same scene
/// without it. Over terrain pixels the deck is not in front of (its march leaves them
/// untouched), a pixel is darker only where the map toward the sun is < 1 there, and
/// many are; nowhere is one brighter.
#[test]
fn the_deck_shadows_the_terrain() {
    let (width, height) = (96, 54);
    let scene = shipped(width, height);
    let cloudy = scene.prepare().unwrap();
    let cloud = cloudy.shell_cloud.as_ref().unwrap();
    let map = cloud.lights[0]
        .shadow
        .as_ref()
        .expect("a shadow map over the terrain");
    assert_eq!(cloud.lights.len(), 1, "the sun alone lights the day");
    assert_eq!(planned(&cloudy, "shell cloud shadow"), Some(true));
    let shadowed_texels = map.values.iter().filter(|&&t| t < 1.0).count();
    let darkest = map.values.iter().copied().fold(1.0f32, f32::min);
    eprintln!(
        "stratocumulus shadow map: {}×{} texels of {:.1} m on the plane at {} m, baked in \
         {:.3} s; {shadowed_texels} texels < 1, darkest {darkest:.3e}",
        map.resolution[0], map.resolution[1], map.cell_size, map.plane, cloud.shadow_seconds
    );
    assert!(map.values.iter().all(|t| (0.0..=1.0).contains(t)));
    let mut clear = scene.clone();
    clear.file.clouds = None;
    let clear = clear.prepare().unwrap();
    assert_eq!(planned(&clear, "shell cloud shadow"), Some(false));
    let with = render::cpu_renderer::render_radiance(&cloudy).unwrap();
    let without = render::cpu_renderer::render_radiance(&clear).unwrap();
    let unlit = &unlit(cloud);
    let camera = shell_camera(&cloudy.camera).unwrap();
    let r = cloudy.atmosphere.planet_radius;
    let eye = cloudy.camera_position - glam::DVec3::new(0.0, r, 0.0);
    let (mut terrain, mut darker, mut lit_darker, mut brighter) = (0, 0, 0, 0);
    let mut unchanged_under = 0;
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            let Some(d) = without[i].terrain_distance else {
                continue;
            };
            let m = march_shell_pixel(unlit, &camera, [width, height], [x, y], d);
            if m.transmittance < 1.0 {
                continue; // the deck in front: its composite changes the pixel too
            }
            terrain += 1;
            let view = atmos::frame::frame_view_direction([x, y], &cloudy.camera);
            let p: [f32; 3] = std::array::from_fn(|a| eye.to_array()[a] as f32 + view[a] * d);
            let shadow = map.at([p[0], -p[2], p[1]]);
            let (a, b) = (with[i].radiance, without[i].radiance);
            if a.iter().zip(b).any(|(a, b)| *a > b) {
                brighter += 1;
            }
            if a.iter().zip(b).any(|(a, b)| *a < b) {
                darker += 1;
                if shadow == 1.0 {
                    lit_darker += 1;
                }
            } else if shadow < 0.9 {
                // Unlit by the sun anyway (facing away, or in the terrain's own shadow).
                unchanged_under += 1;
            }
        }
    }
    eprintln!(
        "stratocumulus 96×54: {terrain} terrain pixels not behind the deck, {darker} darker \
         under its shadow ({lit_darker} of them where the map reads 1), {brighter} brighter; \
         {unchanged_under} unchanged where the map is < 0.9 (no direct sun there anyway)"
    );
    assert_eq!(brighter, 0);
    assert_eq!(lit_darker, 0);
    assert!(darker > 100, "{darker} of {terrain}");
}
