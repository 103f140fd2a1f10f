//! `[clouds.volume]`: the scene keys' errors, the CPU composite of the shipped cumulus
//! scene (sunlit flank brighter than the sky behind, the hills in front hiding the
//! cloud's foot, no NaN), the march's pixel rays against atmos' frame rays, and the GPU
//! image against the CPU's on the shipped scene's 160×90 (lavapipe in CI).

mod common;

use common::{VALID, compare, cpu_pixels, gpu_pixels, luminance, parse_error, within_two_over};
use render::scene::Scene;
use render::volume_clouds::{march_pixel, pinhole_camera, world_to_enu};

const VOLUME: &str = "[clouds.volume]\nseed = 3\nsteps = 20\ngrid = [8, 8, 4]\n\
                      cell_size_m = 100.0\nbase_m = 800.0\nsigma_t_per_density = 0.03\n";

fn shipped(width: u32, height: u32) -> Scene {
    common::shipped("cumulus", width, height)
}

#[test]
fn volume_errors_name_the_key_and_its_line() {
    let prepared = Scene::parse(&format!("{VALID}{VOLUME}"), ".")
        .unwrap()
        .prepare()
        .unwrap();
    let cloud = prepared.volume_cloud.as_ref().unwrap();
    assert_eq!(cloud.volume.dims(), [8, 8, 4]);
    // The volume section starts on line 9: seed 10, steps 11, grid 12, cell size 13,
    // base 14, sigma 15.
    for (from, to, field, line, shown) in [
        ("steps = 20", "steps = 0", "clouds.volume.steps", 11, "0"),
        (
            "grid = [8, 8, 4]",
            "grid = [0, 8, 4]",
            "clouds.volume.grid",
            12,
            "[0, 8, 4]",
        ),
        (
            "cell_size_m = 100.0",
            "cell_size_m = -5.0",
            "clouds.volume.cell_size_m",
            13,
            "-5 m",
        ),
        (
            "base_m = 800.0",
            "base_m = nan",
            "clouds.volume.base_m",
            14,
            "NaN m",
        ),
        (
            "sigma_t_per_density = 0.03",
            "sigma_t_per_density = 0.0",
            "clouds.volume.sigma_t_per_density",
            15,
            "0 /m",
        ),
    ] {
        let e = parse_error(&format!("{VALID}{}", VOLUME.replace(from, to)));
        let message = e.to_string();
        assert_eq!(e.field(), Some(field), "{message}");
        assert_eq!(e.location().map(|l| l.line), Some(line), "{message}");
        assert!(message.contains(shown), "{message}");
    }
    let e = parse_error(&format!("{VALID}{VOLUME}octave_b = 1.5\n"));
    assert_eq!(e.field(), Some("clouds.volume.octave_b"), "{e}");
    assert_eq!(e.location().map(|l| l.line), Some(16), "{e}");
    // A seed that is not a u32 fails in the parser, located and named.
    let e = parse_error(&format!(
        "{VALID}{}",
        VOLUME.replace("seed = 3", "seed = -3")
    ));
    assert_eq!(e.location().map(|l| l.line), Some(10), "{e}");
    assert!(e.to_string().contains("seed"), "{e}");
    let e = parse_error(&format!(
        "{VALID}{}",
        VOLUME.replace("seed = 3", "sead = 3")
    ));
    assert!(e.to_string().contains("seed"), "{e}");
    // An ellipsoid with a zero radius.
    let e = parse_error(&format!(
        "{VALID}{VOLUME}[[clouds.volume.ellipsoids]]\ncentre = [4.0, 4.0, 2.0]\nradii = [3.0, 0.0, 2.0]\n"
    ));
    assert_eq!(e.field(), Some("clouds.volume.ellipsoids.0.radii"), "{e}");
}

#[test]
fn the_march_rays_are_the_scene_cameras_rays() {
    for (look, size) in [
        ("look_direction = [0.3, 0.2, -1.0]", [160, 90]),
        ("look_direction = [0.0, 1.0, 0.0]", [64, 48]), // straight up: north is the top
        ("look_direction = [-1.0, -0.4, 0.2]", [33, 91]),
    ] {
        let text = VALID
            .replace("look_direction = [0.0, 0.2, -1.0]", look)
            .replace(
                "position = [0.0, 2.0, 0.0]",
                "position = [-700.0, 1500.0, 2500.0]",
            );
        let mut scene = Scene::parse(&text, ".").unwrap();
        scene.file.output.width = size[0];
        scene.file.output.height = size[1];
        let prepared = scene.prepare().unwrap();
        let camera = &prepared.camera;
        let pinhole = pinhole_camera(camera, prepared.atmosphere.planet_radius).unwrap();
        let p = camera.position.map(f64::from);
        let origin = world_to_enu([p[0], p[1] - prepared.atmosphere.planet_radius, p[2]]);
        assert!(
            (0..3).all(|a| (pinhole.origin()[a] - origin[a]).abs() < 1e-6),
            "{:?} {origin:?}",
            pinhole.origin()
        );
        let [forward, right, up] = pinhole.basis().map(|v| v.map(|c| c as f32));
        let tan_half = pinhole.tan_half(size).map(|t| t as f32);
        let mut worst = 0.0f32;
        for y in 0..size[1] {
            for x in 0..size[0] {
                let march =
                    cloudlight::march::pixel_direction([x, y], size, forward, right, up, tan_half);
                let frame = atmos::frame::frame_view_direction([x, y], camera);
                let frame = world_to_enu(frame.map(f64::from));
                for a in 0..3 {
                    worst = worst.max((march[a] - frame[a] as f32).abs());
                }
            }
        }
        eprintln!("{look} {size:?}: largest component difference {worst:e}");
        assert!(worst < 1e-6, "{look}: {worst:e}");
    }
}

#[test]
fn the_shipped_cumulus_is_lit_hidden_by_the_hills_in_front_and_finite() {
    let (width, height) = (96, 54);
    let scene = shipped(width, height);
    let cloudy = scene.prepare().unwrap();
    let mut clear = scene.clone();
    clear.file.clouds = None;
    let clear = clear.prepare().unwrap();
    assert!(clear.volume_cloud.is_none());
    // Only the scene with the section plans the pass (`skyscape explain`).
    let volume_pass = |scene: &render::scene::PreparedScene| {
        render::passes::planned_passes(scene)
            .into_iter()
            .find(|(name, _)| *name == "volume clouds")
            .map(|(_, plan)| plan.is_ok())
    };
    assert_eq!(volume_pass(&cloudy), Some(true));
    assert_eq!(volume_pass(&clear), Some(false));
    let with = render::cpu_renderer::render_radiance(&cloudy).unwrap();
    let without = render::cpu_renderer::render_radiance(&clear).unwrap();
    let cloud = cloudy.volume_cloud.as_ref().unwrap();
    let pinhole = pinhole_camera(&cloudy.camera, cloudy.atmosphere.planet_radius).unwrap();
    let (mut sunlit, mut brighter, mut hidden, mut shown) = (0, 0, 0, 0);
    // The sun is high in the west-south-west: the cloud's west half (the image's left
    // half of its pixels) faces it.
    let mut columns = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            assert!(with[i].radiance.iter().all(|v| v.is_finite() && *v >= 0.0));
            let m = march_pixel(cloud, &pinhole, [width, height], [x, y], f32::INFINITY);
            if m.transmittance < 1.0 {
                columns.push(x);
            }
            match without[i].terrain_distance {
                Some(d) if m.transmittance < 0.5 => {
                    let limited = march_pixel(cloud, &pinhole, [width, height], [x, y], d);
                    if limited.transmittance == 1.0 {
                        // The hills in front of all of it: the cloud is not drawn.
                        hidden += 1;
                        assert_eq!(with[i].radiance, without[i].radiance, "pixel {x}, {y}");
                    } else {
                        // The terrain cuts the cloud: only the part in front is marched.
                        assert!(limited.transmittance >= m.transmittance, "pixel {x}, {y}");
                        shown += 1;
                    }
                }
                _ if m.transmittance < 0.5 => shown += 1,
                _ => {}
            }
        }
    }
    columns.sort_unstable();
    let middle = columns[columns.len() / 2];
    // Mean luminance of the opaque cloud pixels over the sky, west (sunlit) and east
    // halves, and how many of the west half's are brighter than the sky behind them.
    let mut halves = [(0.0f64, 0usize); 2];
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            let m = march_pixel(cloud, &pinhole, [width, height], [x, y], f32::INFINITY);
            if m.transmittance < 0.1 && without[i].terrain_distance.is_none() {
                let half = usize::from(x >= middle);
                halves[half].0 += f64::from(luminance(with[i].radiance));
                halves[half].1 += 1;
                if half == 0 {
                    sunlit += 1;
                    if luminance(with[i].radiance) > luminance(without[i].radiance) {
                        brighter += 1;
                    }
                }
            }
        }
    }
    let [west, east] = halves.map(|(sum, n)| sum / n.max(1) as f64);
    eprintln!(
        "cumulus {width}×{height}: {shown} cloud pixels drawn, {hidden} hidden by the hills; \
         opaque cloud over the sky: mean luminance west (sunlit) {west:.4}, east {east:.4}; \
         {brighter} of {sunlit} west pixels brighter than the sky behind"
    );
    assert!(shown > 50 && hidden > 5, "{shown} {hidden}");
    assert!(sunlit > 20 && west > 1.1 * east, "{west} {east}");
    assert!(
        brighter as f64 >= 0.8 * sunlit as f64,
        "{brighter} of {sunlit} brighter than the sky"
    );
}

#[test]
fn the_cumulus_agrees_on_the_gpu_and_the_cpu() {
    let Some(gpu) = common::gpu_or_skip("render::volume_clouds") else {
        return;
    };
    let (width, height) = (160, 90);
    let scene = shipped(width, height).prepare().unwrap();
    // The metric of tests/scene_gpu.rs (docs/scene-measurements.md), and the cloud's own pixels
    // (every one within 2 LSB on lavapipe: 402 of 402, worst 1).
    let (gpu_image, cpu_image, agreement) = compare(gpu, &scene);
    let cloud = scene.volume_cloud.as_ref().unwrap();
    let pinhole = pinhole_camera(&scene.camera, scene.atmosphere.planet_radius).unwrap();
    let mut drawn = Vec::new();
    for y in 0..height {
        for x in 0..width {
            if march_pixel(cloud, &pinhole, [width, height], [x, y], f32::INFINITY).transmittance
                < 1.0
            {
                drawn.push((y * width + x) as usize);
            }
        }
    }
    let (cloud_pixels, cloud_within, worst) = within_two_over(&gpu_image, &cpu_image, drawn);
    eprintln!(
        "cumulus 160×90 GPU vs CPU: {:.3} % of pixels within 2 LSB, {:.3} % within 8, \
         {:.3} % within 2 LSB of the other image's 3×3 neighbourhood; cloud pixels \
         {cloud_within} of {cloud_pixels} within 2 LSB, worst {worst} LSB",
        100.0 * agreement.two,
        100.0 * agreement.eight,
        100.0 * agreement.shifted,
    );
    assert!(agreement.close(), "{}", agreement.fractions());
    assert!(cloud_pixels > 100, "{cloud_pixels}");
    assert!(
        cloud_within as f64 >= 0.99 * cloud_pixels as f64,
        "{cloud_within} of {cloud_pixels}, worst {worst}"
    );
}

/// `[animation] automaton_steps_per_frame`: frame `k` is the cloud grown `k` more steps
/// from the same seed (the automaton is deterministic per step), so the frames are one
/// growth; a count past the steps limit is refused naming the key.
#[test]
fn animation_grows_the_cloud_between_frames() {
    let text = format!("{VALID}{VOLUME}[animation]\nframes = 3\nautomaton_steps_per_frame = 15\n");
    let scene = Scene::parse(&text, ".").unwrap();
    let animation = scene
        .file
        .animation
        .clone()
        .expect("the scene has [animation]");
    let steps_at = |frame: u32| {
        let mut frame_scene = scene.clone();
        animation.apply(&mut frame_scene.file, frame);
        let prepared = frame_scene.prepare().unwrap();
        let cloud = prepared.volume_cloud.expect("the scene has a volume");
        (cloud.steps, cloud.volume.density().to_vec())
    };
    let (first, d0) = steps_at(0);
    let (third, d2) = steps_at(2);
    assert_eq!((first, third), (20, 50));
    assert_ne!(d0, d2, "the cloud changes as it grows");
    // The same frame twice: the same cloud (frames can be rendered anywhere).
    assert_eq!(steps_at(2).1, d2);
    let mut huge = scene.clone();
    animation.apply(&mut huge.file, u32::MAX);
    let e = huge.prepare().unwrap_err();
    assert_eq!(e.field(), Some("clouds.volume.steps"), "{e}");
}

/// The cloud shades the terrain under it (cloudlight's shadow map, Hoffman and Preetham's
/// cloud_shadow term): with the map, no terrain pixel gets brighter and some are
/// clearly darker; without terrain, no map is computed.
#[test]
fn the_volume_cloud_shadows_the_terrain() {
    // Looking down at the cloud and the ground east of it (the sun is in the
    // west-south-west, 60° up: the shadow falls east-north-east of the cloud).
    let mut scene = shipped(96, 54);
    scene.file.camera.position = [4000.0, 7000.0, -3000.0];
    scene.file.camera.look_at = Some([1200.0, 300.0, -5400.0]);
    scene.file.camera.look_direction = None;
    scene.file.camera.vertical_fov_deg = 60.0;
    let mut prepared = scene.prepare().unwrap();
    let shadow = prepared
        .volume_cloud
        .as_ref()
        .and_then(|v| v.lights[0].shadow.as_ref())
        .expect("a sunlit cloud over terrain has a shadow map");
    let darkest = shadow.values.iter().fold(1.0f32, |m, &v| m.min(v));
    assert!(darkest < 0.5, "the map's darkest texel {darkest}");
    let shaded = render::cpu_renderer::render_radiance(&prepared).unwrap();
    prepared.volume_cloud.as_mut().unwrap().lights[0].shadow = None;
    let unshaded = render::cpu_renderer::render_radiance(&prepared).unwrap();
    let common::TerrainDarkening {
        terrain,
        darker,
        worst,
    } = common::terrain_darkening(&shaded, &unshaded);
    eprintln!(
        "{} of {terrain} terrain pixels over 10 % darker in the cloud's shadow (darkest ratio {worst})",
        darker.len()
    );
    assert!(!darker.is_empty(), "no terrain pixel in the cloud's shadow");
    // The GPU terrain pass reads the same map: its shadowed pixels agree with the CPU's.
    prepared = scene.prepare().unwrap();
    if let Some(gpu) = common::gpu_or_skip("render::volume_clouds shadow") {
        let gpu_image = gpu_pixels(gpu, &prepared);
        let cpu_image = cpu_pixels(&prepared);
        let (shadowed, agree, _) = within_two_over(&gpu_image, &cpu_image, darker);
        let everywhere = render::tonemap::fraction_within_lsb(&gpu_image, &cpu_image, 2).unwrap();
        eprintln!(
            "GPU vs CPU, looking down at the shadow: {agree} of {shadowed} shadowed pixels within 2 LSB; {:.3} % of all pixels",
            100.0 * everywhere
        );
        assert!(agree * 10 >= shadowed * 9, "{agree} of {shadowed}");
        assert!(everywhere >= 0.95, "{everywhere}");
    }
    // A scene without terrain computes no map.
    let mut no_terrain = shipped(32, 18);
    no_terrain.file.terrain = None;
    let prepared = no_terrain.prepare().unwrap();
    assert!(prepared.volume_cloud.unwrap().lights[0].shadow.is_none());
}

/// A cloud sunk into the hills (its base on the ground): where the terrain
/// stands inside it, the march stops at the ground (the GPU's from the terrain's depth,
/// the CPU's at the ray's hit), so only the cloud in front of a ridge is drawn; the two
/// renderers agree.
#[test]
fn the_terrain_cuts_the_cloud_where_it_stands() {
    let mut scene = shipped(160, 90);
    let volume = scene.file.clouds.as_mut().unwrap().volume.as_mut().unwrap();
    volume.base_m = 0.0;
    let prepared = scene.prepare().unwrap();
    let cloud = prepared.volume_cloud.as_ref().unwrap();
    let pinhole = pinhole_camera(&prepared.camera, prepared.atmosphere.planet_radius).unwrap();
    let (w, h) = (prepared.camera.width, prepared.camera.height);
    let radiance = render::cpu_renderer::render_radiance(&prepared).unwrap();
    let mut cut = 0;
    for (i, pixel) in radiance.iter().enumerate() {
        if let Some(d) = pixel.terrain_distance {
            let xy = [i as u32 % w, i as u32 / w];
            let whole = march_pixel(cloud, &pinhole, [w, h], xy, f32::INFINITY);
            let front = march_pixel(cloud, &pinhole, [w, h], xy, d);
            // (No strict order between the two: the limited march spreads its steps
            // over the shorter path, so its discretisation differs.)
            if front.transmittance > whole.transmittance + 0.01 {
                cut += 1;
            }
        }
    }
    eprintln!(
        "{cut} of {} pixels: the terrain hides part of the cloud",
        w * h
    );
    assert!(cut > 0, "no pixel where the terrain cuts the cloud");
    let Some(gpu) = common::gpu_or_skip("render::volume_clouds cut") else {
        return;
    };
    let gpu_image = gpu_pixels(gpu, &prepared);
    let cpu_image = cpu_pixels(&prepared);
    let two = render::tonemap::fraction_within_lsb(&gpu_image, &cpu_image, 2).unwrap();
    let eight = render::tonemap::fraction_within_lsb(&gpu_image, &cpu_image, 8).unwrap();
    eprintln!(
        "sunk cloud 160×90 GPU vs CPU: {:.3} % within 2 LSB, {:.3} % within 8",
        100.0 * two,
        100.0 * eight
    );
    assert!(two >= 0.96 && eight >= 0.985, "{two} {eight}");
}
