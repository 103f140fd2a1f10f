//! The volume cloud at night and far away: the moon lights `[clouds.volume]`
//! (a second march with the moon's light, as the terrain's second draw), its shadow map
//! along the moon shades the moonlit terrain, and a cloud beyond the aerial-perspective
//! volume's range (32 km) is seen through the same air on the GPU as on the CPU.
//! GPU parts run on whatever adapter the harness finds (lavapipe in CI).

mod common;

use common::{lsb, luminance};
use render::cpu_renderer::{display_pixels, render_cpu, render_radiance};
use render::scene::{PreparedScene, Scene};
use render::volume_clouds::{march_pixel, pinhole_camera};

/// The shipped night with the camera `camera` and a cumulus `volume` ([`common::night_with`]).
fn night(camera: &str, volume: &str, width: u32, height: u32) -> Scene {
    common::night_with(camera, volume, width, height)
}

/// A 3.2 × 3.2 × 1.6 km cumulus (the shipped `cumulus`' automaton) centred at world
/// `[x, z]`, its base `base` metres up.
fn cumulus(centre: [f64; 2], base: f64, cell: f64) -> String {
    format!(
        "seed = 2026\nsteps = 300\ngrid = [32, 32, 16]\ncell_size_m = {cell:?}\n\
         base_m = {base:?}\ncentre_m = [{:?}, {:?}]\nsigma_t_per_density = 0.03\n\
         view_steps = 48\nlight_steps = 8\noctaves = 8\noctave_b = 0.65\n",
        centre[0], centre[1]
    )
}

/// The scene on the GPU (the harness's adapter), RGBA8; `None` when skipped.
fn gpu_image(scene: &PreparedScene, what: &str) -> Option<Vec<u32>> {
    let gpu = common::gpu_or_skip(what)?;
    Some(common::gpu_pixels(gpu, scene))
}

/// Indices of the pixels where the cloud has opacity (`T < limit`) and is drawn.
fn cloud_pixels(scene: &PreparedScene, limit: f32) -> Vec<usize> {
    let cloud = scene.volume_cloud.as_ref().unwrap();
    let camera = &scene.camera;
    let pinhole = pinhole_camera(camera, scene.atmosphere.planet_radius).unwrap();
    let size = [camera.width, camera.height];
    (0..camera.width * camera.height)
        .filter(|&i| {
            let xy = [i % camera.width, i / camera.width];
            march_pixel(cloud, &pinhole, size, xy, f32::INFINITY).transmittance < limit
        })
        .map(|i| i as usize)
        .collect()
}

/// Looking west-north-west from the night scene's camera, away from the moon (51° up
/// behind the camera): the cloud's moonlit face over the night sky.
const WEST_CAMERA: &str = "position = [-14000.0, 2500.0, 0.0]\n\
                           look_direction = [-0.852, 0.423, -0.310]\n\
                           vertical_fov_deg = 40.0\nnear = 1.0\nfar = 120000.0";

#[test]
fn the_moon_lights_the_volume_cloud() {
    // The cloud 10 km west-north-west, 3.8 km up.
    let scene = night(
        WEST_CAMERA,
        &cumulus([-23400.0, -3420.0], 3800.0, 100.0),
        160,
        90,
    );
    let lit = scene.prepare().unwrap();
    let moon = lit.volume_cloud.as_ref().unwrap().lights.get(1);
    assert!(moon.is_some(), "the moon lights the night's cloud");
    // `skyscape explain` lists the moonlit march and why.
    let plan = render::passes::planned_passes(&lit);
    let moonlit = plan.iter().find(|(name, _)| *name == "moonlit cloud march");
    assert!(
        matches!(moonlit, Some((_, Ok(_)))),
        "explain lists the moonlit march: {moonlit:?}"
    );
    let mut dark = scene.clone().prepare().unwrap();
    dark.volume_cloud.as_mut().unwrap().lights.truncate(1);
    let mut clear_scene = scene.clone();
    clear_scene.file.clouds = None;
    let clear = clear_scene.prepare().unwrap();
    let with = render_radiance(&lit).unwrap();
    let without_moon = render_radiance(&dark).unwrap();
    let sky = render_radiance(&clear).unwrap();
    let opaque = cloud_pixels(&lit, 0.1);
    let (mut lit_sum, mut dark_sum, mut sky_sum, mut brighter) = (0.0f64, 0.0f64, 0.0f64, 0);
    for &i in &opaque {
        let (l, d, s) = (
            luminance(with[i].radiance),
            luminance(without_moon[i].radiance),
            luminance(sky[i].radiance),
        );
        assert!(
            l.is_finite() && l >= d,
            "pixel {i}: {l} vs {d} without the moon"
        );
        lit_sum += f64::from(l);
        dark_sum += f64::from(d);
        sky_sum += f64::from(s);
        brighter += usize::from(l > s);
    }
    let n = opaque.len().max(1) as f64;
    eprintln!(
        "night cloud 160×90: {} opaque pixels (T < 0.1); mean luminance moonlit {:.4e}, \
         without the moon {:.4e}, the sky behind {:.4e}; {brighter} of {} brighter than the sky",
        opaque.len(),
        lit_sum / n,
        dark_sum / n,
        sky_sum / n,
        opaque.len()
    );
    assert!(opaque.len() > 50, "{}", opaque.len());
    assert!(lit_sum > 3.0 * dark_sum, "moonlit {lit_sum} vs {dark_sum}");
    assert!(
        brighter * 10 >= opaque.len() * 8,
        "{brighter} of {}",
        opaque.len()
    );

    // GPU vs CPU.
    let Some(gpu) = gpu_image(&lit, "render::volume_night moon") else {
        return;
    };
    let cpu = render_cpu(&lit).unwrap().pixels;
    let two = render::tonemap::fraction_within_lsb(&gpu, &cpu, 2).unwrap();
    let cloudy = cloud_pixels(&lit, 1.0);
    let within = cloudy.iter().filter(|&&i| lsb(gpu[i], cpu[i]) <= 2).count();
    let worst = cloudy
        .iter()
        .map(|&i| lsb(gpu[i], cpu[i]))
        .max()
        .unwrap_or(0);
    eprintln!(
        "night cloud 160×90 GPU vs CPU: {:.3} % of pixels within 2 LSB; cloud pixels \
         {within} of {} within 2 LSB, worst {worst}",
        100.0 * two,
        cloudy.len()
    );
    assert!(two >= 0.999, "{two}");
    assert!(
        within * 1000 >= cloudy.len() * 999,
        "{within} of {}",
        cloudy.len()
    );
}

#[test]
fn the_volume_cloud_shadows_the_moonlit_terrain() {
    // A cloud 3 km up over the range's middle; its moon shadow falls west-north-west.
    let volume = cumulus([0.0, 0.0], 3000.0, 100.0);
    let probe = night(WEST_CAMERA, &volume, 32, 18).prepare().unwrap();
    let moon = probe.other_lights[0].direction;
    let shadow = &probe.volume_cloud.as_ref().unwrap().lights[1];
    let map = shadow
        .shadow
        .as_ref()
        .expect("a moonlit cloud over terrain has a shadow map");
    let darkest = map.values.iter().fold(1.0f32, |m, &v| m.min(v));
    assert!(darkest < 0.5, "the moon map's darkest texel {darkest}");
    // Looking down at where the shadow falls: from the cloud's middle (3.8 km) along
    // −moon to 1.2 km.
    let reach = (3800.0 - 1200.0) / moon.y;
    let camera = common::camera_looking_down_at([-moon.x * reach, 1200.0, -moon.z * reach]);
    let scene = night(&camera, &volume, 96, 54);
    let mut prepared = scene.prepare().unwrap();
    let shaded = render_radiance(&prepared).unwrap();
    let kept = prepared.volume_cloud.as_mut().unwrap().lights[1]
        .shadow
        .take();
    assert!(kept.is_some());
    let unshaded = render_radiance(&prepared).unwrap();
    let common::TerrainDarkening {
        terrain,
        darker,
        worst,
    } = common::terrain_darkening(&shaded, &unshaded);
    let mean = |pixels: &[usize]| {
        let sum: f64 = pixels
            .iter()
            .map(|&i| f64::from(luminance(shaded[i].radiance)))
            .sum();
        sum / pixels.len().max(1) as f64
    };
    let beside: Vec<usize> = (0..shaded.len())
        .filter(|i| shaded[*i].terrain_distance.is_some() && !darker.contains(i))
        .collect();
    eprintln!(
        "moonlit terrain: {} of {terrain} pixels over 10 % darker in the cloud's moon \
         shadow (darkest ratio {worst:.3}); mean luminance in it {:.3e}, beside it {:.3e}",
        darker.len(),
        mean(&darker),
        mean(&beside)
    );
    assert!(
        darker.len() >= 20,
        "{} terrain pixels in the moon shadow",
        darker.len()
    );
    assert!(worst < 0.5, "darkest ratio {worst}");
    // The GPU's moonlit terrain draw reads the same map.
    let prepared = scene.prepare().unwrap();
    let Some(gpu) = gpu_image(&prepared, "render::volume_night shadow") else {
        return;
    };
    let cpu = render_cpu(&prepared).unwrap().pixels;
    let (shadowed, agree, _) = common::within_two_over(&gpu, &cpu, darker);
    let everywhere = render::tonemap::fraction_within_lsb(&gpu, &cpu, 2).unwrap();
    eprintln!(
        "GPU vs CPU over the moon shadow: {agree} of {shadowed} shadowed pixels within 2 LSB; \
         {:.3} % of all pixels",
        100.0 * everywhere
    );
    assert!(agree * 10 >= shadowed * 9, "{agree} of {shadowed}");
}

#[test]
fn a_cloud_beyond_the_aerial_perspective_range_agrees() {
    // The shipped cumulus' sun and hills; an 8 km cloud 45–55 km north, 1.5 km up.
    let mut scene = common::shipped("cumulus", 160, 90);
    scene.file.camera.position = [0.0, 1500.0, 6500.0];
    scene.file.camera.look_at = Some([0.0, 3500.0, -45000.0]);
    let volume = scene.file.clouds.as_mut().unwrap().volume.as_mut().unwrap();
    volume.cell_size_m = 250.0;
    volume.base_m = 1500.0;
    volume.centre_m = [0.0, -45000.0];
    let prepared = scene.prepare().unwrap();
    let range = prepared
        .precomputed
        .as_ref()
        .unwrap()
        .static_luts()
        .settings
        .aerial_perspective_range;
    // Where the cloud is drawn, its depth is past the table's range.
    let radiance = render_radiance(&prepared).unwrap();
    let cloud = prepared.volume_cloud.as_ref().unwrap();
    let camera = &prepared.camera;
    let size = [camera.width, camera.height];
    let pinhole = pinhole_camera(camera, prepared.atmosphere.planet_radius).unwrap();
    let (mut drawn, mut nearest) = (Vec::new(), f32::INFINITY);
    // The air the old composite read: the table's last slice (clamped), per drawn pixel.
    let luts = prepared.precomputed.as_ref().unwrap().static_luts();
    let frame = atmos::lut::FrameLuts::bake(luts, camera);
    let mut clamped = radiance.iter().map(|p| p.radiance).collect::<Vec<_>>();
    for (i, pixel) in radiance.iter().enumerate() {
        let xy = [i as u32 % size[0], i as u32 / size[0]];
        let behind = pixel.terrain_distance.unwrap_or(f32::INFINITY);
        let m = march_pixel(cloud, &pinhole, size, xy, behind);
        if !render::marched_cloud::cloud_in_front(&m, behind) {
            continue;
        }
        drawn.push(i);
        nearest = nearest.min(m.depth);
        let view = atmos::frame::frame_view_direction(xy, camera);
        let offset = view.map(|v| v * m.depth);
        let exact = atmos::lut::drop_in::aerial_perspective(luts, &frame, offset);
        let [u, v, _] = atmos::lut::drop_in::frame_screen_position(camera, view);
        let [l_old, t_old] = atmos::lut::aerial_perspective::lookup_aerial_perspective(
            &frame.aerial_perspective,
            &luts.settings,
            [u, v],
            m.depth.max(1.0),
        );
        for k in 0..3 {
            clamped[i][k] += m.radiance[k] * (t_old[k] - exact.transmittance[k])
                + (l_old[k] - exact.radiance[k]) * (1.0 - m.transmittance);
        }
    }
    assert!(drawn.len() > 100, "{} cloud pixels", drawn.len());
    assert!(
        nearest > range,
        "the cloud's nearest depth {nearest} m, range {range} m"
    );
    let cpu = render_cpu(&prepared).unwrap().pixels;
    let old = display_pixels(&clamped, size[0], &prepared.present);
    let old_within = drawn.iter().filter(|&&i| lsb(old[i], cpu[i]) <= 2).count();
    let old_worst = drawn.iter().map(|&i| lsb(old[i], cpu[i])).max().unwrap();
    eprintln!(
        "far cloud 160×90: {} cloud pixels drawn, depths from {nearest:.0} m (range {range} m); \
         the table's clamped last slice would put {old_within} of them within 2 LSB of the \
         CPU, worst {old_worst}",
        drawn.len()
    );
    let Some(gpu) = gpu_image(&prepared, "render::volume_night far") else {
        return;
    };
    let within = drawn.iter().filter(|&&i| lsb(gpu[i], cpu[i]) <= 2).count();
    let worst = drawn.iter().map(|&i| lsb(gpu[i], cpu[i])).max().unwrap();
    let two = render::tonemap::fraction_within_lsb(&gpu, &cpu, 2).unwrap();
    eprintln!(
        "far cloud 160×90 GPU vs CPU: cloud pixels {within} of {} within 2 LSB, worst {worst}; \
         {:.3} % of all pixels",
        drawn.len(),
        100.0 * two
    );
    assert!(
        within * 1000 >= drawn.len() * 999,
        "{within} of {}",
        drawn.len()
    );
}

/// The moon lights the cloud through any rung: with the closed form the CPU renderer
/// takes the moon's air from the moonlit segment model (no tables).
#[test]
fn the_moon_lights_the_cloud_through_the_closed_form() {
    let mut scene = night(
        WEST_CAMERA,
        &cumulus([-23400.0, -3420.0], 3800.0, 100.0),
        48,
        27,
    );
    scene.file.atmosphere.rung = render::scene::Rung::ClosedForm;
    let lit = scene.prepare().unwrap();
    assert!(lit.precomputed.is_none());
    let mut dark = scene.prepare().unwrap();
    dark.volume_cloud.as_mut().unwrap().lights.truncate(1);
    let with = render_radiance(&lit).unwrap();
    let without = render_radiance(&dark).unwrap();
    let opaque = cloud_pixels(&lit, 0.1);
    let mean = |image: &[render::cpu_renderer::PixelRadiance]| {
        opaque
            .iter()
            .map(|&i| f64::from(luminance(image[i].radiance)))
            .sum::<f64>()
            / opaque.len().max(1) as f64
    };
    let (l, d) = (mean(&with), mean(&without));
    eprintln!(
        "closed form, 48×27: {} opaque cloud pixels, mean luminance moonlit {l:.4e}, without \
         the moon {d:.4e}",
        opaque.len()
    );
    assert!(
        opaque.len() > 10
            && with
                .iter()
                .all(|p| p.radiance.iter().all(|v| v.is_finite()))
    );
    assert!(l > 3.0 * d, "{l} vs {d}");
}

/// The lights are a list: a third light is the same passes run once more. The night
/// (sky, terrain with the cloud's shadow, the marched cloud) rendered by the CPU with
/// the sun alone (`R₁`), with the sun and the moon (`R₂`, as prepared) and with the moon
/// listed twice (`R₃`: the same `LightSky` and the cloud's same `CloudLight` appended)
/// is linear in the lights: `R₃ − R₂ = R₂ − R₁` per pixel, within f32 rounding of the
/// sums. The GPU renderer draws at most `render::gpu::MAX_LIGHTS` and refuses the third
/// with an error naming the count.
#[test]
fn a_third_light_is_the_same_passes_run_again() {
    let volume = cumulus([-23400.0, -3420.0], 3800.0, 100.0);
    let scene = night(WEST_CAMERA, &volume, 48, 27);
    let two = scene.prepare().unwrap();
    assert_eq!(two.lights().len(), 2, "the night's sun and moon");
    let mut one = scene.prepare().unwrap();
    one.other_lights.clear();
    one.volume_cloud.as_mut().unwrap().lights.truncate(1);
    let mut three = scene.prepare().unwrap();
    let again = scene.prepare().unwrap().other_lights.remove(0);
    three.other_lights.push(again);
    let cloud = three.volume_cloud.as_mut().unwrap();
    let moonlit = cloud.lights[1].clone();
    cloud.lights.push(moonlit);
    assert_eq!(three.lights().len(), 3);
    let [r1, r2, r3] = [&one, &two, &three].map(|s| render_radiance(s).unwrap());
    let (mut worst, mut scale, mut moonlit) = (0f32, 0f32, 0usize);
    for ((a, b), c) in r1.iter().zip(&r2).zip(&r3) {
        for k in 0..3 {
            let (added, again) = (b.radiance[k] - a.radiance[k], c.radiance[k] - b.radiance[k]);
            worst = worst.max((again - added).abs());
            scale = scale.max(c.radiance[k].abs());
        }
        moonlit += usize::from(b.radiance[1] > a.radiance[1]);
    }
    eprintln!(
        "a third light (the moon twice), 48×27 on the CPU: the moon adds to {moonlit} of {} \
         pixels; |(R3 − R2) − (R2 − R1)| ≤ {worst:.3e} (largest radiance {scale:.3e})",
        r1.len()
    );
    assert!(moonlit > r1.len() / 2, "the moon lights {moonlit} pixels");
    assert!(worst <= 1e-5 * scale, "{worst:e} against {scale:e}");
    if let Some(gpu) = common::gpu_or_skip("render::volume_night third light on the GPU") {
        let error =
            render::gpu::SceneRenderer::new(&gpu.device, &gpu.queue, &three, Default::default())
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
        assert!(error.contains("3 lights"), "{error}");
    }
}
