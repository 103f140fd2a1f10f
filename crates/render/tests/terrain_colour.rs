//! The terrain's colour: `[terrain.colour]`'s texture reaches the terrain's pixels on
//! both renderers, bad colour and material keys are refused by name, and the procedural
//! materials agree between the GPU and the CPU as well as the ramp does.

mod common;

use std::path::Path;

use render::scene::{MaterialsModel, Scene};

/// Writes a `width`×`height` 8-bit RGB PNG: `west` left of the middle column, `east`
/// right of it.
fn write_split_png(path: &Path, width: u32, height: u32, west: [u8; 3], east: [u8; 3]) {
    let image = image::RgbImage::from_fn(width, height, |x, _| {
        image::Rgb(if 2 * x < width { west } else { east })
    });
    image.save(path).unwrap();
}

const RED: [u8; 3] = [200, 40, 40];
const BLUE: [u8; 3] = [40, 60, 200];

/// A gentle 6.3 km square terrain (64 cells of 100 m) seen from 9 km up, 3 km south of
/// its centre, looking north and down at it (image left = west), with `colour` (TOML
/// lines of `[terrain.colour]`) and `extra` lines under `[terrain]`.
fn colour_scene(colour: &str, extra: &str) -> String {
    format!(
        "[camera]\nposition = [0.0, 9000.0, 3000.0]\nlook_at = [0.0, 0.0, 0.0]\n\
         vertical_fov_deg = 50.0\nnear = 1.0\nfar = 120000.0\n\
         [sun]\nelevation_deg = 60.0\nazimuth_deg = 180.0\n\
         [atmosphere]\nrung = \"closed-form\"\n\
         [terrain]\n{extra}\n\
         [terrain.procedural]\nseed = 3\nsize = 65\ncell_size = 100.0\nrelief = 150.0\n\
         [terrain.colour]\n{colour}\n\
         [output]\nwidth = 96\nheight = 64\nexposure = 8.0\n"
    )
}

fn channels(pixel: u32) -> [i32; 3] {
    [0, 1, 2].map(|c| common::code(pixel, c) as i32)
}

/// Terrain pixels (those the two swapped textures change) left and right of the middle
/// band: how many, and how many take their side's hue in both images.
fn sides(west_red: &[u32], west_blue: &[u32], width: usize) -> [[usize; 2]; 2] {
    let mut counts = [[0; 2]; 2];
    for (index, (&a, &b)) in west_red.iter().zip(west_blue).enumerate() {
        let column = index % width;
        let side = if column * 10 < width * 4 {
            0
        } else if column * 10 >= width * 6 {
            1
        } else {
            continue;
        };
        let (a, b) = (channels(a), channels(b));
        let changed = (0..3).map(|c| (a[c] - b[c]).abs()).max().unwrap() > 12;
        if !changed {
            continue;
        }
        counts[side][0] += 1;
        let red_then_blue = a[0] > a[2] && b[2] > b[0];
        let blue_then_red = a[2] > a[0] && b[0] > b[2];
        if (side == 0 && red_then_blue) || (side == 1 && blue_then_red) {
            counts[side][1] += 1;
        }
    }
    counts
}

#[test]
fn a_split_texture_colours_each_side_of_the_terrain_on_both_renderers() {
    let folder = tempfile::tempdir().unwrap();
    // 33×33 pixels of 200 m: the heightfield's 6.4 km extent.
    write_split_png(&folder.path().join("west_red.png"), 33, 33, RED, BLUE);
    write_split_png(&folder.path().join("west_blue.png"), 33, 33, BLUE, RED);
    let prepared = |file: &str| {
        let text = colour_scene(&format!("path = \"{file}\"\ncell_size = 200.0"), "");
        Scene::parse(&text, folder.path())
            .unwrap()
            .prepare()
            .unwrap()
    };
    let (west_red, west_blue) = (prepared("west_red.png"), prepared("west_blue.png"));
    let width = west_red.camera.width as usize;
    let mut images = vec![(
        "cpu",
        common::cpu_pixels(&west_red),
        common::cpu_pixels(&west_blue),
    )];
    if let Some(gpu) = common::gpu_or_skip("render::terrain_colour") {
        images.push((
            "gpu",
            common::gpu_pixels(gpu, &west_red),
            common::gpu_pixels(gpu, &west_blue),
        ));
    }
    for (renderer, a, b) in images {
        let counts = sides(&a, &b, width);
        eprintln!(
            "{renderer}: west {} of {} terrain pixels take the west's hue, east {} of {}",
            counts[0][1], counts[0][0], counts[1][1], counts[1][0]
        );
        for (side, [terrain, hued]) in ["west", "east"].iter().zip(counts) {
            assert!(terrain > 300, "{renderer} {side}: {terrain} terrain pixels");
            assert_eq!(hued, terrain, "{renderer} {side}");
        }
    }
}

#[test]
fn bad_colour_and_material_keys_are_refused_by_name() {
    let folder = tempfile::tempdir().unwrap();
    write_split_png(&folder.path().join("ok.png"), 33, 33, RED, BLUE);
    write_split_png(&folder.path().join("wide.png"), 40, 33, RED, BLUE);
    image::GrayImage::new(33, 33)
        .save(folder.path().join("grey.png"))
        .unwrap();
    std::fs::write(folder.path().join("text.png"), "not an image").unwrap();
    let ok = "path = \"ok.png\"\ncell_size = 200.0";
    let cases = [
        (
            "path = \"missing.png\"\ncell_size = 200.0",
            "",
            "terrain.colour.path",
            "missing.png",
        ),
        (
            "path = \"grey.png\"\ncell_size = 200.0",
            "",
            "terrain.colour.path",
            "grey.png",
        ),
        (
            "path = \"text.png\"\ncell_size = 200.0",
            "",
            "terrain.colour.path",
            "text.png",
        ),
        (
            "path = \"wide.png\"\ncell_size = 200.0",
            "",
            "terrain.colour.cell_size",
            "200 m",
        ),
        (
            "path = \"ok.png\"\ncell_size = 150.0",
            "",
            "terrain.colour.cell_size",
            "150 m",
        ),
        (
            "path = \"ok.png\"\ncell_size = -1.0",
            "",
            "terrain.colour.cell_size",
            "-1 m",
        ),
        (
            ok,
            "materials = \"procedural\"\n[terrain.procedural_materials]\nsnow_slope_deg = 5.0",
            "terrain.procedural_materials.snow_slope_deg",
            "5°",
        ),
        (
            ok,
            "materials = \"procedural\"\n[terrain.procedural_materials]\ntransition_m = 0.0",
            "terrain.procedural_materials.transition_m",
            "0 m",
        ),
        (
            ok,
            "materials = \"procedural\"\n[terrain.procedural_materials]\nsnow_albedo = [1.2, 0.9, 0.9]",
            "terrain.procedural_materials.snow_albedo",
            "1.2",
        ),
        (
            ok,
            "[terrain.procedural_materials]\nseed = 2",
            "terrain.procedural_materials",
            "materials = \"procedural\"",
        ),
        (
            ok,
            "materials = \"painted\"",
            "terrain.materials",
            "painted",
        ),
    ];
    for (colour, extra, key, value) in cases {
        let text = colour_scene(colour, extra);
        let message = match Scene::parse(&text, folder.path()) {
            Err(e) => e.to_string(),
            Ok(scene) => match scene.prepare() {
                Err(e) => e.to_string(),
                Ok(_) => panic!("accepted {key} in\n{text}"),
            },
        };
        assert!(
            message.contains(key) && message.contains(value),
            "{key} {value}: {message}"
        );
    }
}

/// The default scene with the procedural materials: GPU and CPU agree as well as on the
/// default scene with its ramp (`scene_gpu`'s metric and thresholds).
#[test]
fn the_procedural_materials_agree_on_the_gpu_and_the_cpu() {
    let Some(gpu) = common::gpu_or_skip("render::terrain_colour") else {
        return;
    };
    let ramp = common::shipped("default", 160, 90);
    let mut procedural = ramp.clone();
    procedural.file.terrain.as_mut().unwrap().materials = MaterialsModel::Procedural;
    let mut fractions = Vec::new();
    for (name, scene) in [("ramp", ramp), ("procedural", procedural)] {
        let (_, _, agreement) = common::compare(gpu, &scene.prepare().unwrap());
        eprintln!(
            "default ({name}) 160×90: {:.3} % of pixels within 2 LSB, {:.3} % within 8, \
             {:.3} % within 2 LSB of a pixel in the other image's 3×3 neighbourhood; mean \
             difference (GPU − CPU) {:.3?} LSB, mean |difference| {:.3?} LSB",
            100.0 * agreement.two,
            100.0 * agreement.eight,
            100.0 * agreement.shifted,
            agreement.signed,
            agreement.absolute,
        );
        assert!(agreement.close(), "{name}: {}", agreement.fractions());
        assert!(agreement.unbiased(1.0), "{name}: {}", agreement.biases());
        fractions.push([agreement.two, agreement.eight, agreement.shifted]);
    }
    // Per pixel, within one pixel in 160×90 of the ramp's figures. The neighbourhood
    // fraction may lose a few more: the procedural snow on the foreground ridge is
    // brighter against its shadowed valley than the ramp's scree, so the pixels where
    // the rasterised and ray-cast silhouettes differ (scene_gpu's note) differ by more.
    let pixel = 1.0 / (160.0 * 90.0);
    let allowed = [pixel, pixel, 10.0 * pixel];
    for k in 0..3 {
        assert!(
            fractions[1][k] >= fractions[0][k] - allowed[k],
            "procedural {:?} vs ramp {:?}",
            fractions[1],
            fractions[0]
        );
    }
}

/// The procedural materials on the CPU (the default scene lies at 46.5° N: the pole is
/// north): snow on the summits above the snow line, rock
/// on the steepest slopes, grass in the gentle valleys.
#[test]
fn snow_lies_above_the_snow_line_and_rock_on_steep_slopes() {
    use render::terrain_materials::material_weights;
    let mut scene = common::shipped("default", 8, 8);
    scene.file.terrain.as_mut().unwrap().materials = MaterialsModel::Procedural;
    let prepared = scene.prepare().unwrap();
    let terrain = prepared.terrain.as_ref().unwrap();
    let params = terrain.materials.unwrap();
    let hf = &terrain.heightfield;
    let normals = terrain.normals.normals();
    let (mut snow_high, mut high, mut rock_steep, mut steep, mut grass_gentle_low, mut low) =
        (0, 0, 0, 0, 0, 0);
    for (&elevation, normal) in hf.elevations().iter().zip(normals) {
        let elevation = elevation as f32;
        let [rock, grass, snow] = material_weights(*normal, elevation, 0.0, &params);
        let slope_deg = normal[2].acos().to_degrees();
        // The snow line where this texel faces (lower toward the pole).
        let snow_line = params.snow_line - params.snow_line_aspect * normal[1];
        if elevation > snow_line + params.transition && slope_deg < 35.0 {
            high += 1;
            snow_high += usize::from(snow > 0.99);
        }
        if slope_deg > 42.0
            && elevation < params.snow_line - params.snow_line_aspect - params.transition
        {
            steep += 1;
            rock_steep += usize::from(rock > 0.99);
        }
        if elevation < params.grass_line - params.transition && slope_deg < 25.0 {
            low += 1;
            grass_gentle_low += usize::from(grass > 0.99);
        }
    }
    eprintln!(
        "snow on {snow_high} of {high} gentle texels above the snow line, rock on \
         {rock_steep} of {steep} texels below it steeper than 42°, grass on {grass_gentle_low} of \
         {low} gentle texels below the grass line"
    );
    assert!(
        high > 100 && steep > 100 && low > 100,
        "{high} {steep} {low}"
    );
    assert_eq!(snow_high, high);
    assert_eq!(rock_steep, steep);
    assert_eq!(grass_gentle_low, low);
}
