//! Bad input, as a new user types it: every case is refused with a message naming the
//! file's line or the flag that gave the value, never a panic, and nothing is written.
//!
//! Scene-file cases run in process through the library (`Scene::parse`,
//! `Scene::check_animation`, `Scene::prepare`: where the checks live); a sample of them,
//! and every case about flags, outputs and animations, run the `skyscape` binary in a
//! temporary folder of their own, asserting exit code 2 and an unchanged folder.

use std::path::Path;
use std::process::{Command, Stdio};

use rayon::prelude::*;
use render::scene::Scene;

/// An 8×8 scene on the closed form: each case changes one thing.
const BASE: &str = "\
[camera]
position = [0.0, 2.0, 0.0]
look_direction = [0.0, 0.3, -1.0]
vertical_fov_deg = 60.0
near = 0.5
far = 200000.0

[sun]
elevation_deg = 30.0
azimuth_deg = 180.0

[atmosphere]
rung = \"closed-form\"

[output]
width = 8
height = 8
exposure = 20.0
";

/// `[time]` in place of `[sun]`.
const TIME: &str = "[time]\nutc = \"2024-06-21T12:00:00Z\"\nlatitude_deg = 47.0\n\
                    longitude_deg = 8.0\n";

/// A small terrain.
const TERRAIN: &str = "[terrain.procedural]\nseed = 1\nsize = 16\ncell_size = 50.0\n\
                       relief = 100.0\n";

/// A small volume cloud.
const VOLUME: &str = "[clouds.volume]\nseed = 1\nsteps = 10\ngrid = [8, 8, 4]\n\
                      cell_size_m = 100.0\nbase_m = 1000.0\n";

/// A small cloud shell.
const SHELL: &str = "[clouds.shell]\nbottom_m = 1000.0\ntop_m = 1800.0\nview_steps = 4\n\
                     light_steps = 2\n";

/// A cloud layer (with `[time]`).
const LAYER: &str = "[[clouds.layers]]\nkind = \"cumulus\"\nbase_m = 2000.0\n\
                     thickness_m = 500.0\n";

/// BASE with the line `key = ...` (the first one) replaced by `key = value`.
fn set(key: &str, value: &str) -> String {
    with(BASE, key, value)
}

fn with(text: &str, key: &str, value: &str) -> String {
    let prefix = format!("{key} = ");
    let mut done = false;
    let lines: Vec<String> = text
        .lines()
        .map(|line| {
            if !done && line.starts_with(&prefix) {
                done = true;
                format!("{key} = {value}")
            } else {
                line.to_owned()
            }
        })
        .collect();
    assert!(done, "no `{key}` in the scene");
    lines.join("\n") + "\n"
}

/// BASE without the line of `key`.
fn without(text: &str, key: &str) -> String {
    let prefix = format!("{key} = ");
    text.lines()
        .filter(|line| !line.starts_with(&prefix))
        .map(|line| format!("{line}\n"))
        .collect()
}

/// BASE with `[sun]` replaced by `[time]`.
fn timed() -> String {
    BASE.replace("[sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n", TIME)
}

/// BASE plus `extra`.
fn plus(extra: &str) -> String {
    format!("{BASE}\n{extra}")
}

/// BASE with the camera 500 m up, over the small terrain.
fn over_terrain() -> String {
    format!("{}\n{TERRAIN}", set("position", "[0.0, 500.0, 0.0]"))
}

/// The scene-file cases: a name, the scene, and what the message must name besides
/// the line (the dotted key).
fn scene_cases() -> Vec<(String, String, &'static str)> {
    let mut cases: Vec<(String, String, &'static str)> = Vec::new();
    let mut add = |name: &str, scene: String, names: &'static str| {
        cases.push((name.to_owned(), scene, names));
    };
    // [camera]
    for v in ["0.0", "-10.0", "180.0", "200.0", "nan", "inf"] {
        add(
            &format!("fov {v}"),
            set("vertical_fov_deg", v),
            "camera.vertical_fov_deg",
        );
    }
    add(
        "fov string",
        set("vertical_fov_deg", "\"wide\""),
        "camera.vertical_fov_deg",
    );
    for v in ["-1.0", "nan", "inf", "-inf"] {
        add(&format!("near {v}"), set("near", v), "camera.near");
    }
    for v in ["0.1", "nan", "-5.0", "0.5"] {
        add(&format!("far {v}"), set("far", v), "camera.far");
    }
    for v in [
        "[0.0, nan, 0.0]",
        "[0.0, -1e7, 0.0]",
        "[inf, 2.0, 0.0]",
        "[1.0, 2.0]",
        "\"here\"",
    ] {
        add(
            &format!("position {v}"),
            set("position", v),
            "camera.position",
        );
    }
    for v in ["[0.0, 0.0, 0.0]", "[nan, 0.0, 0.0]", "[0.0, 0.3]"] {
        add(
            &format!("look_direction {v}"),
            set("look_direction", v),
            "camera.look_direction",
        );
    }
    add(
        "look_at and look_direction",
        set("position", "[0.0, 2.0, 0.0]\nlook_at = [0.0, 2.0, -10.0]"),
        "camera.look_at",
    );
    add(
        "look_at at the camera",
        with(
            &without(BASE, "look_direction"),
            "position",
            "[0.0, 2.0, 0.0]\nlook_at = [0.0, 2.0, 0.0]",
        ),
        "camera.look_at",
    );
    add(
        "no look",
        without(BASE, "look_direction"),
        "camera.position",
    );
    add(
        "misspelt camera key",
        set("vertical_fov_deg", "60.0\nvertical_fov = 50.0"),
        "camera.vertical_fov",
    );
    add("no position", without(BASE, "position"), "camera.position");
    // [sun]
    for v in ["91.0", "-91.0", "nan", "inf", "1e300"] {
        add(
            &format!("sun elevation {v}"),
            set("elevation_deg", v),
            "sun.elevation_deg",
        );
    }
    for v in ["nan", "inf", "-inf"] {
        add(
            &format!("sun azimuth {v}"),
            set("azimuth_deg", v),
            "sun.azimuth_deg",
        );
    }
    add(
        "sun without azimuth",
        without(BASE, "azimuth_deg"),
        "sun.azimuth_deg",
    );
    add(
        "sun elevation string",
        set("elevation_deg", "\"high\""),
        "sun.elevation_deg",
    );
    add("sun and time", plus(TIME), "time.utc");
    add(
        "sky objects with sun",
        plus("[sky_objects]\nenabled = true\n"),
        "sky_objects.enabled",
    );
    add(
        "misspelt sun key",
        set("azimuth_deg", "180.0\nazimut_deg = 10.0"),
        "sun.azimut_deg",
    );
    // [time]
    for (name, key, value, names) in [
        ("utc garbage", "utc", "\"noon\"", "time.utc"),
        ("utc 1800", "utc", "\"1800-01-01T00:00:00Z\"", "time.utc"),
        ("latitude 95", "latitude_deg", "95.0", "time.latitude_deg"),
        ("latitude nan", "latitude_deg", "nan", "time.latitude_deg"),
        (
            "longitude inf",
            "longitude_deg",
            "inf",
            "time.longitude_deg",
        ),
        ("utc number", "utc", "12", "time.utc"),
    ] {
        add(name, with(&timed(), key, value), names);
    }
    add(
        "offset nan",
        timed().replace(
            "longitude_deg = 8.0\n",
            "longitude_deg = 8.0\noffset_s = nan\n",
        ),
        "time.offset_s",
    );
    add(
        "star limit nan",
        format!("{}\n[sky_objects]\nstar_limit_magnitude = nan\n", timed()),
        "sky_objects.star_limit_magnitude",
    );
    // [atmosphere]
    for (key, value, names) in [
        ("rung", "\"precomputd\"", "atmosphere.rung"),
        ("rung", "3", "atmosphere.rung"),
        ("mie_scale", "-1.0", "atmosphere.mie_scale"),
        ("mie_scale", "nan", "atmosphere.mie_scale"),
        ("mie_g", "1.0", "atmosphere.mie_g"),
        ("mie_g", "-2.0", "atmosphere.mie_g"),
        (
            "rayleigh_scale_height",
            "0.0",
            "atmosphere.rayleigh_scale_height",
        ),
        (
            "rayleigh_scale_height",
            "-5.0",
            "atmosphere.rayleigh_scale_height",
        ),
        ("mie_scale_height", "0.0", "atmosphere.mie_scale_height"),
        ("ground_albedo", "2.0", "atmosphere.ground_albedo"),
        ("ground_albedo", "-0.5", "atmosphere.ground_albedo"),
        ("ground_albedo", "nan", "atmosphere.ground_albedo"),
    ] {
        let scene = if key == "rung" {
            set("rung", value)
        } else {
            set("rung", &format!("\"closed-form\"\n{key} = {value}"))
        };
        add(&format!("{key} {value}"), scene, names);
    }
    // [output]
    for (key, value, names) in [
        ("width", "0", "output.width"),
        ("width", "20000", "output.width"),
        ("width", "-8", "output.width"),
        ("width", "\"wide\"", "output.width"),
        ("width", "8.5", "output.width"),
        ("height", "0", "output.height"),
        ("height", "99999", "output.height"),
        ("exposure", "0.0", "output.exposure"),
        ("exposure", "-1.0", "output.exposure"),
        ("exposure", "nan", "output.exposure"),
        ("exposure", "inf", "output.exposure"),
    ] {
        add(&format!("{key} {value}"), set(key, value), names);
    }
    add(
        "16384 squared",
        with(&set("width", "16384"), "height", "16384"),
        "output.height",
    );
    add(
        "projection sphere",
        set("exposure", "20.0\nprojection = \"sphere\""),
        "output.projection",
    );
    add(
        "cubemap 8x8",
        set("exposure", "20.0\nprojection = \"cubemap\""),
        "output.width",
    );
    for v in ["0.0", "400.0", "nan"] {
        add(
            &format!("fisheye {v}"),
            set(
                "exposure",
                &format!("20.0\nprojection = \"fisheye\"\nfisheye_fov_deg = {v}"),
            ),
            "output.fisheye_fov_deg",
        );
    }
    add(
        "dither seed negative",
        set("exposure", "20.0\ndither_seed = -1"),
        "output.dither_seed",
    );
    add(
        "misspelt output key",
        set("exposure", "20.0\nexposur = 3.0"),
        "output.exposur",
    );
    // [terrain]
    let terrain = |key: &str, value: &str| with(&over_terrain(), key, value);
    for (key, value) in [
        ("size", "0"),
        ("size", "1"),
        ("cell_size", "0.0"),
        ("cell_size", "-1.0"),
        ("cell_size", "nan"),
        ("relief", "nan"),
        ("relief", "-10.0"),
        ("seed", "-1"),
    ] {
        add(
            &format!("terrain {key} {value}"),
            terrain(key, value),
            "terrain",
        );
    }
    add(
        "terrain wavelength 0",
        terrain("relief", "100.0\nwavelength = 0.0"),
        "terrain.procedural.wavelength",
    );
    add(
        "terrain octaves 0",
        terrain("relief", "100.0\noctaves = 0"),
        "terrain.procedural.octaves",
    );
    add(
        "terrain two sources",
        plus(&format!(
            "{TERRAIN}[terrain.raw_f32]\npath = \"h.raw\"\nwidth = 4\nheight = 4\ncell_size = 1.0\n"
        )),
        "terrain",
    );
    add(
        "terrain no source",
        plus("[terrain]\nhorizon = \"east-west\"\n"),
        "terrain",
    );
    add(
        "terrain png16 missing",
        plus("[terrain.png16]\npath = \"missing.png\"\ncell_size = 10.0\nheight_scale = 0.1\n"),
        "terrain.png16.path",
    );
    add(
        "terrain raw missing",
        plus("[terrain.raw_f32]\npath = \"missing.raw\"\nwidth = 4\nheight = 4\ncell_size = 1.0\n"),
        "terrain.raw_f32.path",
    );
    let terrain_table = |lines: &str| {
        format!(
            "{}\n[terrain]\n{lines}\n{TERRAIN}",
            set("position", "[0.0, 500.0, 0.0]")
        )
    };
    add(
        "horizon azimuths without N",
        terrain_table("horizon = \"azimuths\""),
        "terrain.horizon",
    );
    add(
        "horizon azimuths 2",
        terrain_table("horizon = \"azimuths\"\nhorizon_azimuths = 2"),
        "terrain.horizon_azimuths",
    );
    add(
        "horizon N with east-west",
        terrain_table("horizon_azimuths = 8"),
        "terrain.horizon_azimuths",
    );
    add(
        "horizon sideways",
        terrain_table("horizon = \"sideways\""),
        "terrain.horizon",
    );
    add(
        "aerial sometimes",
        terrain_table("aerial_perspective = \"sometimes\""),
        "terrain.aerial_perspective",
    );
    let albedo = |lines: &str| format!("{}[terrain.albedo]\n{lines}\n", over_terrain());
    let ramp = "heights = [0.0, 100.0]\ncolors = [[0.1, 0.1, 0.1], [0.2, 0.2, 0.2]]\n\
                steep_color = [0.2, 0.2, 0.2]\nsteep_slope_deg = 40.0";
    for (name, from, to, names) in [
        (
            "albedo decreasing",
            "[0.0, 100.0]",
            "[100.0, 0.0]",
            "terrain.albedo.heights",
        ),
        (
            "albedo mismatch",
            "[0.0, 100.0]",
            "[0.0, 100.0, 200.0]",
            "terrain.albedo",
        ),
        (
            "albedo colour 2",
            "[0.2, 0.2, 0.2]]",
            "[2.0, 0.2, 0.2]]",
            "terrain.albedo.colors",
        ),
        (
            "albedo slope nan",
            "40.0",
            "nan",
            "terrain.albedo.steep_slope_deg",
        ),
        (
            "albedo steep -1",
            "steep_color = [0.2",
            "steep_color = [-1.0",
            "terrain.albedo.steep_color",
        ),
    ] {
        add(name, albedo(&ramp.replacen(from, to, 1)), names);
    }
    add(
        "camera inside the terrain",
        with(&plus(TERRAIN), "position", "[0.0, -500.0, 0.0]"),
        "camera.position",
    );
    // [[clouds.layers]]
    add("layer with sun", plus(LAYER), "clouds.layers");
    let layer = |key: &str, value: &str| {
        let text = format!("{}\n{LAYER}", timed());
        if text.contains(&format!("\n{key} = ")) {
            with(&text, key, value)
        } else {
            format!("{text}{key} = {value}\n")
        }
    };
    for (key, value, names) in [
        ("kind", "\"nimbus\"", "nimbus"),
        ("coverage", "2.0", "clouds.layers.0.coverage"),
        ("coverage", "-1.0", "clouds.layers.0.coverage"),
        ("thickness_m", "0.0", "clouds.layers.0.thickness_m"),
        ("thickness_m", "-5.0", "clouds.layers.0.thickness_m"),
        ("base_m", "nan", "clouds.layers.0.base_m"),
        ("span_m", "0.0", "clouds.layers.0.span_m"),
        ("transition_m", "-1.0", "clouds.layers.0.transition_m"),
        ("coverage", "\"lots\"", "clouds.layers.0.coverage"),
        ("coverage", "\"Broken\"", "Broken"),
        ("coverage", "true", "clouds.layers.0.coverage"),
        ("wind_m_per_s", "[nan, 0.0]", "clouds.layers.0.wind_m_per_s"),
        (
            "wind_m_per_s",
            "[300.0, 0.0]",
            "clouds.layers.0.wind_m_per_s",
        ),
        (
            "wind_m_per_s",
            "[0.0, -inf]",
            "clouds.layers.0.wind_m_per_s",
        ),
        ("wind_m_per_s", "[1.0]", "clouds.layers.0.wind_m_per_s"),
    ] {
        add(&format!("layer {key} {value}"), layer(key, value), names);
    }
    // [visibility]
    for v in ["0.0", "-5.0", "nan", "inf", "2e6", "\"far\""] {
        add(
            &format!("visibility {v}"),
            plus(&format!("[visibility]\ndistance_m = {v}\n")),
            "visibility.distance_m",
        );
    }
    add(
        "visibility and mie_scale",
        plus("[visibility]\ndistance_m = 5000.0\n").replace(
            "rung = \"closed-form\"",
            "rung = \"closed-form\"\nmie_scale = 2.0",
        ),
        "visibility.distance_m",
    );
    add(
        "visibility from orbit",
        with(
            &plus("[visibility]\ndistance_m = 5000.0\n"),
            "position",
            "[0.0, 400000.0, 0.0]",
        ),
        "visibility.distance_m",
    );
    add(
        "visibility unknown key",
        plus("[visibility]\ndistance_m = 5000.0\nfog = true\n"),
        "fog",
    );
    // [clouds.volume]
    let volume = |key: &str, value: &str| {
        let text = plus(VOLUME);
        if text.contains(&format!("\n{key} = ")) {
            with(&text, key, value)
        } else {
            format!("{text}{key} = {value}\n")
        }
    };
    for (key, value, names) in [
        ("steps", "0", "clouds.volume.steps"),
        ("steps", "200000", "clouds.volume.steps"),
        ("grid", "[0, 4, 4]", "clouds.volume.grid"),
        ("grid", "[1000, 4, 4]", "clouds.volume.grid"),
        ("cell_size_m", "0.0", "clouds.volume.cell_size_m"),
        ("cell_size_m", "nan", "clouds.volume.cell_size_m"),
        (
            "sigma_t_per_density",
            "-1.0",
            "clouds.volume.sigma_t_per_density",
        ),
        ("view_steps", "0", "clouds.volume.view_steps"),
        ("view_steps", "5000", "clouds.volume.view_steps"),
        ("light_steps", "0", "clouds.volume.light_steps"),
        ("octaves", "0", "clouds.volume.octaves"),
        ("octaves", "9", "clouds.volume.octaves"),
        ("octave_a", "2.0", "clouds.volume.octave_a"),
        ("base_m", "nan", "clouds.volume.base_m"),
        ("draw", "\"splat\"", "clouds.volume.draw"),
    ] {
        add(&format!("volume {key} {value}"), volume(key, value), names);
    }
    add(
        "volume ellipsoid radius 0",
        format!(
            "{}\n[[clouds.volume.ellipsoids]]\ncentre = [4.0, 4.0, 2.0]\nradii = [0.0, 2.0, 2.0]\n",
            plus(VOLUME)
        ),
        "clouds.volume.ellipsoids.0.radii",
    );
    add(
        "volume billboards without draw",
        format!(
            "{}\n[clouds.volume.billboards]\nslices = \"physical\"\n",
            plus(VOLUME)
        ),
        "clouds.volume.billboards",
    );
    // [clouds.shell]
    let shell = |key: &str, value: &str| {
        let text = plus(SHELL);
        if text.contains(&format!("\n{key} = ")) {
            with(&text, key, value)
        } else {
            format!("{text}{key} = {value}\n")
        }
    };
    for (key, value, names) in [
        ("top_m", "500.0", "clouds.shell"),
        ("coverage", "2.0", "clouds.shell.coverage"),
        ("view_steps", "0", "clouds.shell.view_steps"),
        ("light_steps", "0", "clouds.shell.light_steps"),
        ("erosion", "1.0", "clouds.shell.erosion"),
        ("weather_cell_m", "100.0", "clouds.shell.weather"),
        ("octaves", "0", "clouds.shell.octaves"),
    ] {
        add(&format!("shell {key} {value}"), shell(key, value), names);
    }
    // [animation]
    let animation = |text: &str, lines: &str| format!("{text}\n[animation]\n{lines}\n");
    for (name, lines, names) in [
        ("frames 0", "frames = 0", "animation.frames"),
        ("frames 200000", "frames = 200000", "animation.frames"),
        ("frames 4e9", "frames = 4e9", "animation.frames"),
        (
            "elevation per frame nan",
            "frames = 4\nsun_elevation_deg_per_frame = nan",
            "animation.sun_elevation_deg_per_frame",
        ),
        (
            "sun past 90",
            "frames = 12\nsun_elevation_deg_per_frame = 20.0",
            "frame 4 of 12",
        ),
        (
            "azimuth per frame inf",
            "frames = 4\nsun_azimuth_deg_per_frame = inf",
            "animation.sun_azimuth_deg_per_frame",
        ),
        (
            "seconds with sun",
            "frames = 4\nseconds_per_frame = 60.0",
            "animation.seconds_per_frame",
        ),
        (
            "steps without volume",
            "frames = 4\nautomaton_steps_per_frame = 5",
            "animation.automaton_steps_per_frame",
        ),
        (
            "no frames",
            "sun_elevation_deg_per_frame = 1.0",
            "animation.frames",
        ),
    ] {
        add(name, animation(BASE, lines), names);
    }
    add(
        "elevation per frame with time",
        animation(&timed(), "frames = 4\nsun_elevation_deg_per_frame = 1.0"),
        "animation.sun_elevation_deg_per_frame",
    );
    add(
        "seconds past the ephemeris",
        animation(&timed(), "frames = 4\nseconds_per_frame = 1e10"),
        "animation.seconds_per_frame",
    );
    add(
        "cloud grown past its limit",
        animation(
            &plus(VOLUME),
            "frames = 10\nautomaton_steps_per_frame = 50000",
        ),
        "animation.automaton_steps_per_frame",
    );
    // [[animation.layers]] and the camera's travel
    let layered = format!("{}\n{LAYER}", timed());
    for (name, lines, names) in [
        (
            "layer change of a missing layer",
            "frames = 4\n[[animation.layers]]\nlayer = 3\ncoverage_per_frame = 0.1",
            "animation.layers.0.layer",
        ),
        (
            "layer coverage rate nan",
            "frames = 4\n[[animation.layers]]\nlayer = 0\ncoverage_per_frame = nan",
            "animation.layers.0.coverage_per_frame",
        ),
        (
            "layer coverage past 1",
            "frames = 10\n[[animation.layers]]\nlayer = 0\ncoverage_per_frame = 0.2",
            "animation.layers.0.coverage_per_frame",
        ),
        (
            "layer thinned to nothing",
            "frames = 10\n[[animation.layers]]\nlayer = 0\nthickness_m_per_frame = -100.0",
            "animation.layers.0.thickness_m_per_frame",
        ),
        (
            "layer base into space",
            "frames = 10\n[[animation.layers]]\nlayer = 0\nbase_m_per_frame = 50000.0",
            "animation.layers.0.base_m_per_frame",
        ),
        (
            "layer to_frame before from_frame",
            "frames = 10\n[[animation.layers]]\nlayer = 0\nfrom_frame = 5\nto_frame = 2",
            "animation.layers.0.to_frame",
        ),
        (
            "layer removed before it appears",
            "frames = 10\n[[animation.layers]]\nlayer = 0\nappear_at_frame = 5\n\
             remove_at_frame = 5",
            "animation.layers.0.remove_at_frame",
        ),
        (
            "layer change to an unknown kind",
            "frames = 4\n[[animation.layers]]\nlayer = 0\nkind = \"nimbus\"",
            "animation.layers.0.kind",
        ),
        (
            "layer change unknown key",
            "frames = 4\n[[animation.layers]]\nlayer = 0\nwind_per_frame = 1.0",
            "wind_per_frame",
        ),
        (
            "camera travel nan",
            "frames = 4\ncamera_m_per_frame = [0.0, nan, 0.0]",
            "animation.camera_m_per_frame",
        ),
        (
            "camera travel underground",
            "frames = 10\ncamera_m_per_frame = [0.0, -100.0, 0.0]",
            "animation.camera_m_per_frame",
        ),
    ] {
        add(name, animation(&layered, lines), names);
    }
    // Syntax
    add("unclosed array", set("position", "[0.0, 2.0, 0.0"), "");
    add(
        "duplicate key",
        set("near", "0.5\nnear = 1.0"),
        "duplicate key",
    );
    add("broken header", BASE.replace("[sun]", "[sun"), "");
    add(
        "table as value",
        set("rung", "{ name = 1 }"),
        "atmosphere.rung",
    );
    add("unknown table", plus("[weather]\nrain = true\n"), "weather");
    cases
}

/// Parses, checks the animation and prepares `text` (from a folder holding no files).
fn scene_error(text: &str) -> Option<String> {
    let scene = match Scene::parse(text, "/nonexistent-skyscape-folder") {
        Ok(scene) => scene,
        Err(e) => return Some(e.to_string()),
    };
    let frames = scene.file.animation.as_ref().map_or(1, |a| a.frames.max(1));
    if let Err(e) = scene.check_animation(0..frames) {
        return Some(e.to_string());
    }
    scene.prepare().err().map(|e| e.to_string())
}

#[test]
fn bad_scene_files_name_the_line_and_the_key() {
    let cases = scene_cases();
    eprintln!("{} scene-file cases", cases.len());
    let failures: Vec<String> = cases
        .par_iter()
        .filter_map(|(name, text, names)| {
            let result = std::panic::catch_unwind(|| scene_error(text));
            match result {
                Err(_) => Some(format!("{name}: panicked")),
                Ok(None) => Some(format!("{name}: accepted")),
                Ok(Some(message)) if !message.contains("line ") => {
                    Some(format!("{name}: no line in: {message}"))
                }
                Ok(Some(message)) if !message.contains(names) => {
                    Some(format!("{name}: `{names}` not in: {message}"))
                }
                Ok(Some(_)) => None,
            }
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A binary case: arguments after `render`, the scene text (`scene.toml` in the
/// case's folder), what the message must contain, and files to make first.
struct Case {
    args: Vec<String>,
    scene: String,
    names: String,
    setup: fn(&Path),
}

fn nothing(_: &Path) {}

fn case(args: &[&str], scene: &str, names: &str) -> Case {
    Case {
        args: args.iter().map(|a| (*a).to_owned()).collect(),
        scene: scene.to_owned(),
        names: names.to_owned(),
        setup: nothing,
    }
}

fn binary_cases() -> Vec<Case> {
    let animated = format!("{BASE}\n[animation]\nframes = 12\nsun_elevation_deg_per_frame = 1.0\n");
    let mut cases = Vec::new();
    for (args, names) in [
        (&["--width", "0"][..], "--width"),
        (&["--width", "-5"], "--width"),
        (&["--width", "99999"], "--width"),
        (&["--width", "abc"], "--width"),
        (&["--height", "0"], "--height"),
        (&["--height", "-1"], "--height"),
        (&["--width", "16384", "--height", "16384"], "--height"),
        (&["--exposure", "0"], "--exposure"),
        (&["--exposure", "-1"], "--exposure"),
        (&["--exposure", "nan"], "--exposure"),
        (&["--exposure", "inf"], "--exposure"),
        (&["--sun-elevation-deg", "nan"], "--sun-elevation-deg"),
        (&["--sun-elevation-deg", "91"], "--sun-elevation-deg"),
        (&["--sun-elevation-deg", "-91"], "--sun-elevation-deg"),
        (&["--sun-elevation-deg", "inf"], "--sun-elevation-deg"),
        (&["--sun-azimuth-deg", "nan"], "--sun-azimuth-deg"),
        (&["--sun-azimuth-deg", "-inf"], "--sun-azimuth-deg"),
        (&["--rung", "fast"], "--rung"),
        (&["--projection", "sphere"], "--projection"),
        (&["--projection", "cubemap"], "output.width"),
        (&["--frames", "3"], "--frames"),
        (&["--frame-range", "0..2"], "--frame-range"),
        (&["--frame-range", "-1..2"], "--frame-range"),
        (&["--frame-range", "2..1"], "--frame-range"),
        (&["--frame-range", "x"], "--frame-range"),
        (&["--format", "tiff"], "--format"),
        (&["--backend", "glide"], "--backend"),
        (&["-o", "out"], "is a directory"),
        (&["-o", "missing/x.png"], "-o"),
        (&["-o", "x.tif"], "-o"),
        (&["--format", "exr", "-o", "x.png"], "--format"),
        (&["--format", "png", "-o", "x.jpg"], "--format"),
        (
            &["--format", "png", "-o", "scene.toml"],
            "the scene file itself",
        ),
        (&["-o", "dangling.png"], "symbolic link"),
        (&["-o", "x_{frame}.png"], "{frame}"),
        (&["--compare"], "--compare"),
        (&["--rung", "reference", "--explain"], "--explain"),
    ] {
        let mut c = case(args, BASE, names);
        c.setup = |dir| {
            std::fs::create_dir(dir.join("out")).unwrap();
            #[cfg(unix)]
            std::os::unix::fs::symlink("nowhere.png", dir.join("dangling.png")).unwrap();
        };
        if args.contains(&"--compare") {
            c.args.push("--cpu".into());
        }
        cases.push(c);
    }
    for (args, names) in [
        (&["--frames", "0"][..], "--frames"),
        (&["--frames", "-1"], "--frames"),
        (&["--frames", "200000"], "--frames"),
        (&["--frames", "100"], "(--frames)"),
        (&["--frame-range", "0..13"], "--frame-range"),
        (&["-o", "x.png"], "{frame}"),
        (&["-o", "-"], "{frame}"),
        (&["--frames", "4", "--frame-range", "2..5"], "--frame-range"),
    ] {
        let mut args = args.to_vec();
        if !args.contains(&"-o") {
            args.extend(["-o", "f_{frame}.png"]);
        }
        cases.push(case(&args, &animated, names));
    }
    let timed_scene = timed();
    cases.push(case(
        &["--sun-elevation-deg", "10"],
        &timed_scene,
        "--sun-elevation-deg",
    ));
    let mut missing = case(&[], BASE, "nosuch.toml");
    missing.args = vec!["nosuch.toml".into()];
    cases.push(missing);
    let mut unknown = case(&[], BASE, "not a shipped scene");
    unknown.args = vec!["nosuch".into()];
    cases.push(unknown);
    // A sample of the scene-file cases through the binary: the exit code and the line.
    for (name, text, _) in scene_cases().into_iter().step_by(6) {
        let _ = name;
        cases.push(case(&[], &text, "line "));
    }
    cases
}

#[test]
fn bad_arguments_exit_2_name_the_flag_and_write_nothing() {
    let cases = binary_cases();
    let failures: Vec<String> = cases
        .par_iter()
        .filter_map(|c| {
            let dir = tempfile::tempdir().unwrap();
            std::fs::write(dir.path().join("scene.toml"), &c.scene).unwrap();
            (c.setup)(dir.path());
            let before = listing(dir.path());
            let mut args = vec!["render".to_owned()];
            if c.args.first().is_none_or(|a| a.starts_with('-')) {
                args.push("scene.toml".into());
            }
            args.extend(c.args.iter().cloned());
            if !args.iter().any(|a| a == "-o") {
                args.extend(["-o".into(), "image.png".into()]);
            }
            let output = Command::new(env!("CARGO_BIN_EXE_skyscape"))
                .current_dir(dir.path())
                .args(&args)
                .stdin(Stdio::null())
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            let what = format!("{args:?}: {stderr}");
            if output.status.code() != Some(2) {
                Some(format!("exit {:?}, not 2: {what}", output.status.code()))
            } else if stderr.contains("panicked") {
                Some(format!("panic: {what}"))
            } else if !stderr.contains(&c.names) {
                Some(format!("`{}` not named: {what}", c.names))
            } else if listing(dir.path()) != before {
                Some(format!("wrote {:?}: {what}", listing(dir.path())))
            } else {
                None
            }
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let total = scene_cases().len() + cases.len();
    assert!(total >= 150, "{total} cases in all");
    eprintln!("{} binary cases, {total} in all", cases.len());
}

fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}
