//! A scene with both the `[clouds.shell]` deck and the `[clouds.volume]` cloud: the two
//! composited by depth per pixel (`render::cloud_order`). Four views of one deck
//! (1,000–1,800 m) and a volume cloud 3 km north: from above the deck, a volume above
//! it (the volume in front) and one below it (the deck in front); from below the deck,
//! a low volume (the volume in front) and one above the deck (the deck in front). Where
//! the nearer cloud is opaque the image is that cloud's alone (lit as in the scene: the
//! other's shadow on it kept, `render::mutual_shadow`), not the farther's; GPU vs CPU on
//! the cloud pixels, each cloud lit through the other's shadow map on both (lavapipe in
//! CI).

mod common;

use common::{gpu_or_skip, gpu_pixels, lsb, within_two_over};
use render::cpu_renderer::render_cpu;
use render::mutual_shadow;
use render::scene::{PreparedScene, Scene};
use render::shell_clouds::{march_shell_pixel, shell_camera};
use render::volume_clouds::{march_pixel, pinhole_camera};

const WIDTH: u32 = 80;
const HEIGHT: u32 = 45;

/// Which cloud a view sees in front where both are along a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Front {
    Volume,
    Shell,
}

/// One view: its name, the camera's height and look-at point (m), the volume's base
/// above the ground (m, its grid 600 m tall) and the cloud in front.
struct View {
    name: &'static str,
    camera_m: f64,
    look_at: [f64; 3],
    volume_base_m: f64,
    front: Front,
}

const VIEWS: [View; 4] = [
    View {
        name: "above the deck, volume above it",
        camera_m: 3200.0,
        look_at: [0.0, 2000.0, -4000.0],
        volume_base_m: 2000.0,
        front: Front::Volume,
    },
    View {
        name: "below the deck, low volume",
        camera_m: 200.0,
        look_at: [0.0, 1200.0, -4000.0],
        volume_base_m: 300.0,
        front: Front::Volume,
    },
    View {
        name: "below the deck, volume above it",
        camera_m: 200.0,
        look_at: [0.0, 3000.0, -4000.0],
        volume_base_m: 2000.0,
        front: Front::Shell,
    },
    View {
        name: "above the deck, low volume",
        camera_m: 3200.0,
        look_at: [0.0, -200.0, -4000.0],
        volume_base_m: 300.0,
        front: Front::Shell,
    },
];

/// The view's scene: the shipped stratocumulus deck (no terrain) and a small cumulus
/// grown by the automaton, on the precomputed rung (the GPU's marched clouds need its
/// tables).
fn scene(view: &View) -> PreparedScene {
    scene_on(view, "precomputed")
}

/// [`scene`] on the atmosphere rung `rung`.
fn scene_on(view: &View, rung: &str) -> PreparedScene {
    Scene::parse(&scene_text(view, rung), ".")
        .unwrap()
        .prepare()
        .unwrap()
}

/// [`scene_on`]'s scene file.
fn scene_text(view: &View, rung: &str) -> String {
    let [x, y, z] = view.look_at;
    format!(
        "[camera]\nposition = [0.0, {camera}, 0.0]\nlook_at = [{x}, {y}, {z}]\n\
         vertical_fov_deg = 60.0\nnear = 1.0\nfar = 100000.0\n\
         [sun]\nelevation_deg = 40.0\nazimuth_deg = 230.0\n\
         [atmosphere]\nrung = \"{rung}\"\n\
         [clouds.shell]\nbottom_m = 1000.0\ntop_m = 1800.0\ncoverage = 0.5\n\
         coverage_contrast = 0.25\ncloud_type = 0.5\ncloud_type_contrast = 0.0\n\
         shape_period_m = 6000.0\ndetail_period_m = 800.0\nsigma_t_per_density = 0.04\n\
         seed = 3\nview_steps = 16\nlight_steps = 3\nambient_steps = 1\noctaves = 4\n\
         [clouds.volume]\nseed = 2026\nsteps = 250\ngrid = [24, 24, 6]\ncell_size_m = 100.0\n\
         base_m = {base}\ncentre_m = [0.0, -3000.0]\nsigma_t_per_density = 0.03\n\
         view_steps = 24\nlight_steps = 4\n\
         [output]\nwidth = {WIDTH}\nheight = {HEIGHT}\nexposure = 12.0\n",
        camera = view.camera_m,
        base = view.volume_base_m,
    )
}

/// Per pixel, each cloud's march alone (transmittance, depth): the volume's, then the
/// deck's (unlit: the same transmittance and depth at a fraction of the cost).
fn marches(scene: &PreparedScene) -> Vec<[(f32, f32); 2]> {
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let volume = scene.volume_cloud.as_ref().unwrap();
    let mut shell = scene.shell_cloud.clone().unwrap();
    shell.lights[0].lighting =
        cloudlight::march::Lighting::new([0.0, 0.0, 1.0], [0.0; 3], [0.0; 3], [0.0, 0.0, 1.0])
            .unwrap();
    shell.lights.truncate(1);
    let volume_camera = pinhole_camera(camera, scene.atmosphere.planet_radius).unwrap();
    let deck_camera = shell_camera(camera).unwrap();
    (0..size[1])
        .flat_map(|y| (0..size[0]).map(move |x| [x, y]))
        .map(|xy| {
            let v = march_pixel(volume, &volume_camera, size, xy, f32::INFINITY);
            let s = march_shell_pixel(&shell, &deck_camera, size, xy, f32::INFINITY);
            [(v.transmittance, v.depth), (s.transmittance, s.depth)]
        })
        .collect()
}

/// The scene on the CPU with only the volume cloud and with only the deck, each lit as
/// in the scene: the other cloud emptied (no density: the deck's coverage 0, the
/// volume's grid zero) but its shadow map on this one kept (`render::mutual_shadow`).
fn alone(scene: &mut PreparedScene) -> (Vec<u32>, Vec<u32>) {
    let shell = scene.shell_cloud.clone();
    let deck = &mut scene.shell_cloud.as_mut().unwrap().shell;
    let mut settings = deck.settings().clone();
    let cloudlight::shell::WeatherMap::Procedural(weather) = &mut settings.weather else {
        panic!("the deck's weather is procedural");
    };
    (weather.coverage_mean, weather.coverage_contrast) = (0.0, 0.0);
    *deck = cloudlight::CloudShell::new(&scene.atmosphere, settings).unwrap();
    let volume_only = render_cpu(scene).unwrap().pixels;
    scene.shell_cloud = shell;
    let volume = scene.volume_cloud.clone();
    let grid = &mut scene.volume_cloud.as_mut().unwrap().volume;
    let cells = grid.density().len();
    *grid = cloudlight::CloudVolume::new(
        grid.dims(),
        grid.origin(),
        grid.voxel_size(),
        grid.extinction_per_density(),
        vec![0.0; cells],
    )
    .unwrap();
    let shell_only = render_cpu(scene).unwrap().pixels;
    scene.volume_cloud = volume;
    (volume_only, shell_only)
}

/// Each view on the CPU: where both clouds are along a ray the expected one is nearer,
/// and where it is opaque the image is its alone, not the other's; then on the GPU (when
/// an adapter is found): its image against the CPU's on the cloud pixels.
#[test]
fn the_nearer_cloud_goes_over_the_farther_on_the_cpu_and_the_gpu() {
    let gpu = gpu_or_skip("both marched clouds by depth on the GPU");
    let (mut count, mut within, mut crossing, mut crossing_within) = (0, 0, 0, 0);
    for view in &VIEWS {
        let mut scene = scene(view);
        // Each cloud's shadow on the other: the volume's map on the deck always (the sun
        // at 40°), the deck's on the volume where the volume reaches below its top.
        let (volume, shell) = (&scene.volume_cloud, &scene.shell_cloud);
        assert!(mutual_shadow::volume_on_deck(volume.as_ref().unwrap(), 0).is_some());
        let deck_on_volume = mutual_shadow::deck_on_volume(shell.as_ref().unwrap(), 0);
        assert_eq!(deck_on_volume.is_some(), view.volume_base_m < 1800.0);
        let both = render_cpu(&scene).unwrap().pixels;
        let (volume_only, shell_only) = alone(&mut scene);
        let (front_only, back_only) = match view.front {
            Front::Volume => (&volume_only, &shell_only),
            Front::Shell => (&shell_only, &volume_only),
        };
        let marches = marches(&scene);
        let (mut crossed, mut in_order, mut opaque, mut as_front, mut order_shows) =
            (vec![], 0, 0, 0, 0);
        let mut worst = 0;
        for (i, &[(t_v, d_v), (t_s, d_s)]) in marches.iter().enumerate() {
            // Both clouds along the ray, each with some opacity.
            if !(t_v < 0.9 && t_s < 0.9) {
                continue;
            }
            crossed.push(i);
            let (t_front, t_back) = match view.front {
                Front::Volume => (t_v, t_s),
                Front::Shell => (t_s, t_v),
            };
            in_order += usize::from(match view.front {
                Front::Volume => d_v < d_s,
                Front::Shell => d_s < d_v,
            });
            // The front cloud opaque, the back one dense: the front cloud's image alone,
            // not the back one's.
            if t_front < 0.01 && t_back < 0.5 {
                opaque += 1;
                let d = lsb(both[i], front_only[i]);
                worst = worst.max(d);
                as_front += usize::from(d <= 2);
                order_shows += usize::from(lsb(front_only[i], back_only[i]) > 2);
            }
        }
        println!(
            "{} ({WIDTH}×{HEIGHT}): {} pixels cross both clouds (T < 0.9 each), the {:?} \
             nearer in {in_order}; {opaque} where it is opaque (T < 0.01) and the other \
             dense (T < 0.5): {as_front} within 2 LSB of the {:?} alone (worst {worst}), \
             {order_shows} of them > 2 LSB from the other cloud alone",
            view.name,
            crossed.len(),
            view.front,
            view.front
        );
        assert!(crossed.len() >= 50, "{}", view.name);
        assert_eq!(in_order, crossed.len(), "{}", view.name);
        assert!(opaque >= 20 && as_front == opaque, "{}", view.name);
        assert!(order_shows * 2 >= opaque, "{}", view.name);

        let Some(gpu) = gpu else {
            continue;
        };
        let gpu_image = gpu_pixels(gpu, &scene);
        let cloudy = marches
            .iter()
            .enumerate()
            .filter(|(_, [(t_v, _), (t_s, _)])| *t_v < 1.0 || *t_s < 1.0)
            .map(|(i, _)| i);
        let (n, ok, worst) = within_two_over(&gpu_image, &both, cloudy);
        let (m, crossed_ok, crossed_worst) =
            within_two_over(&gpu_image, &both, crossed.iter().copied());
        let all = render::tonemap::fraction_within_lsb(&gpu_image, &both, 2).unwrap();
        println!(
            "{} GPU vs CPU: cloud pixels {ok} of {n} within 2 LSB (worst {worst}), those \
             crossing both {crossed_ok} of {m} (worst {crossed_worst}); {:.3} % of all pixels",
            view.name,
            100.0 * all
        );
        count += n;
        within += ok;
        crossing += m;
        crossing_within += crossed_ok;
    }
    if gpu.is_some() {
        println!(
            "four views GPU vs CPU: {within} of {count} cloud pixels within 2 LSB ({:.3} %), \
             {crossing_within} of {crossing} crossing both",
            100.0 * within as f64 / count as f64
        );
        assert!(within as f64 >= 0.999 * count as f64);
        assert!(crossing_within as f64 >= 0.999 * crossing as f64);
    }
}

/// `skyscape explain`'s plan: with both clouds "clouds by depth" runs in place of their
/// two composites; with one, that cloud's composite runs and "clouds by depth" is skipped.
#[test]
fn explain_plans_one_composite_by_depth() {
    let planned = |scene: &PreparedScene, pass: &str| {
        render::passes::planned_passes(scene)
            .into_iter()
            .find(|(name, _)| *name == pass)
            .map(|(_, plan)| plan.is_ok())
    };
    let mut scene = scene(&VIEWS[0]);
    assert_eq!(planned(&scene, "clouds by depth"), Some(true));
    // The volume above the deck: the volume's map shades the deck, the deck's is empty.
    assert_eq!(planned(&scene, "mutual cloud shadows"), Some(true));
    for pass in ["volume clouds", "shell clouds"] {
        assert_eq!(planned(&scene, pass), Some(false), "{pass}");
    }
    for pass in ["volume cloud march", "shell cloud march"] {
        assert_eq!(planned(&scene, pass), Some(true), "{pass}");
    }
    scene.shell_cloud = None;
    assert_eq!(planned(&scene, "clouds by depth"), Some(false));
    assert_eq!(planned(&scene, "mutual cloud shadows"), Some(false));
    assert_eq!(planned(&scene, "volume clouds"), Some(true));
}

/// Under the GPU's other rungs (the clouds' air from the rung's functions instead of the
/// tables): the view where the deck hides the cumulus, GPU vs CPU on its cloud pixels.
#[test]
fn both_clouds_agree_under_the_other_gpu_rungs() {
    let Some(gpu) = gpu_or_skip("both marched clouds by depth under every GPU rung") else {
        return;
    };
    for rung in ["closed-form", "single"] {
        let scene = scene_on(&VIEWS[2], rung);
        let gpu_image = gpu_pixels(gpu, &scene);
        let cpu_image = render_cpu(&scene).unwrap().pixels;
        let cloudy = marches(&scene)
            .into_iter()
            .enumerate()
            .filter(|(_, [(t_v, _), (t_s, _)])| *t_v < 1.0 || *t_s < 1.0)
            .map(|(i, _)| i);
        let (n, ok, worst) = within_two_over(&gpu_image, &cpu_image, cloudy);
        println!(
            "{} under {rung} GPU vs CPU: cloud pixels {ok} of {n} within 2 LSB (worst {worst})",
            VIEWS[2].name
        );
        assert!(ok as f64 >= 0.999 * n as f64, "{rung}");
    }
}

/// At night both clouds are marched a second time lit by the moon, each through the
/// other's shadow map toward the moon (the sun, 53° down, has none). Two views from
/// below the deck at 48×27: a volume at 700–1,300 m, its top in the deck (the deck's
/// map shades it), and one at 1,400–2,000 m (its map shades the deck). In each, taking
/// the moon's map out changes the CPU image (the march is told it is the moon's and
/// reads that light's map), and the GPU agrees with the CPU on the pixels it changes
/// (its march hooks told the same).
#[test]
fn the_moons_marches_read_the_moons_maps() {
    let gpu = gpu_or_skip("the moon's marches on the GPU");
    for (base, look_up, deck_map) in [(700.0, 1000.0, true), (1400.0, 1600.0, false)] {
        let view = View {
            name: "night, below the deck",
            camera_m: 200.0,
            look_at: [0.0, look_up, -4000.0],
            volume_base_m: base,
            front: Front::Volume,
        };
        // The closed form: no tables to build (the light a march reads does not depend
        // on the rung), which keeps this test to a few seconds per view.
        let text = scene_text(&view, "closed-form")
            .replace(
                "[sun]\nelevation_deg = 40.0\nazimuth_deg = 230.0\n",
                "[time]\nutc = \"2024-12-15T21:00:00Z\"\nlatitude_deg = 46.5\n\
                 longitude_deg = 8.0\n",
            )
            .replace("exposure = 12.0", "exposure = 3.0e5")
            .replace(
                &format!("width = {WIDTH}\nheight = {HEIGHT}"),
                "width = 48\nheight = 27",
            );
        assert!(text.contains("[time]") && text.contains("width = 48"));
        let mut scene = Scene::parse(&text, ".").unwrap().prepare().unwrap();
        let (volume, shell) = (
            scene.volume_cloud.as_ref().unwrap(),
            scene.shell_cloud.as_ref().unwrap(),
        );
        assert!(
            volume.lights.len() == 2 && shell.lights.len() == 2,
            "both moonlit"
        );
        for (light, some) in [(0, false), (1, true)] {
            assert_eq!(mutual_shadow::deck_on_volume(shell, light).is_some(), some);
            assert_eq!(mutual_shadow::volume_on_deck(volume, light).is_some(), some);
        }
        let full = render_cpu(&scene).unwrap().pixels;
        // The moon's map on the one cloud taken out, the scene rendered, the map put back.
        let without = if deck_map {
            let map = &mut scene.shell_cloud.as_mut().unwrap().over_volume[1];
            let kept = map.take();
            let without = render_cpu(&scene).unwrap().pixels;
            scene.shell_cloud.as_mut().unwrap().over_volume[1] = kept;
            without
        } else {
            let moonlit = &mut scene.volume_cloud.as_mut().unwrap().lights[1];
            let kept = moonlit.shadow.take();
            let without = render_cpu(&scene).unwrap().pixels;
            scene.volume_cloud.as_mut().unwrap().lights[1].shadow = kept;
            without
        };
        let changed: Vec<usize> = (0..full.len())
            .filter(|&i| lsb(full[i], without[i]) > 2)
            .collect();
        let which = if deck_map {
            "the deck's moon map on the volume"
        } else {
            "the volume's moon map on the deck"
        };
        println!(
            "{}, volume at {base} m (48×27): {} pixels > 2 LSB changed by {which}",
            view.name,
            changed.len()
        );
        assert!(changed.len() >= 10, "{which}");

        let Some(gpu) = gpu else {
            continue;
        };
        let gpu_image = gpu_pixels(gpu, &scene);
        let (n, ok, worst) = within_two_over(&gpu_image, &full, changed.iter().copied());
        let all = render::tonemap::fraction_within_lsb(&gpu_image, &full, 2).unwrap();
        println!(
            "{}, volume at {base} m GPU vs CPU: {ok} of {n} pixels {which} changes within \
             2 LSB (worst {worst}); {:.3} % of all pixels",
            view.name,
            100.0 * all
        );
        assert!(ok as f64 >= 0.99 * n as f64, "{which}");
    }
}
