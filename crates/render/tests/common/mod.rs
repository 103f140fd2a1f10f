//! Shared by the render integration tests (`mod common;` in each): the GPU adapter
//! policy, the shipped scenes, the GPU and CPU renders and scene_gpu's agreement metric
//! of a GPU image against the CPU's. Not every test binary uses every helper.
//!
//! GPU policy: an adapter found → run; none and `SKYSCAPE_REQUIRE_GPU=1` → fail; none →
//! skip with a visible line (`skyscape_harness::gpu_or_skip`, which also creates the
//! device once per test binary).

#![allow(dead_code)]

use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::scene::{PreparedScene, Scene, SceneError};
use skyscape_harness::GpuContext;

/// The harness's device when an adapter is found; `None` (after a visible `SKIPPED`
/// line) when none is and `SKYSCAPE_REQUIRE_GPU` is not `1`; a panic when it is.
pub fn gpu_or_skip(what: &str) -> Option<&'static GpuContext> {
    skyscape_harness::gpu_or_skip(what)
}

/// The path of the shipped scene `name` (`scenes/<name>.toml`).
pub fn scene_path(name: &str) -> String {
    format!("{}/../../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// The smallest valid scene on the closed-form rung (8 lines: a section appended to it
/// starts on line 9).
pub const VALID: &str = "[camera]\nposition = [0.0, 2.0, 0.0]\nlook_direction = [0.0, 0.2, -1.0]\n\
                         [sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n\
                         [atmosphere]\nrung = \"closed-form\"\n";

/// The shipped scene `name` drawn at `width`×`height`.
pub fn shipped(name: &str, width: u32, height: u32) -> Scene {
    let mut scene = Scene::open(scene_path(name)).unwrap();
    scene.file.output.width = width;
    scene.file.output.height = height;
    scene
}

/// The shipped night (2024-12-15 21:00 UTC, 46.5° N 8° E: the sun 53° down, the full
/// moon 51° up in the east-south-east) with its camera replaced by `camera` (TOML lines
/// of `[camera]`) and a `[clouds.volume]` of `volume`'s lines, drawn at `width`×`height`.
pub fn night_with(camera: &str, volume: &str, width: u32, height: u32) -> Scene {
    let text = std::fs::read_to_string(scene_path("night")).unwrap();
    let start = text.find("[camera]").unwrap();
    let end = text.find("[time]").unwrap();
    let text = format!(
        "{}[camera]\n{camera}\n{}\n[clouds.volume]\n{volume}\n",
        &text[..start],
        &text[end..]
    );
    let mut scene = Scene::parse(&text, ".").unwrap();
    scene.file.output.width = width;
    scene.file.output.height = height;
    scene
}

/// Relative luminance (Rec. 709 weights) of linear RGB radiance.
pub fn luminance(rgb: [f32; 3]) -> f32 {
    0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
}

/// The shipped scene `name` at `width × height` prepared with its clouds and without
/// them, and the CPU reference renderer's luminance of each (Rec. 709, per pixel).
pub fn luminance_with_and_without_clouds(
    name: &str,
    width: u32,
    height: u32,
) -> (render::scene::PreparedScene, Vec<f64>, Vec<f64>) {
    let scene = shipped(name, width, height).prepare().unwrap();
    let mut cloudless = shipped(name, width, height);
    cloudless.file.clouds = None;
    let cloudless = cloudless.prepare().unwrap();
    let luminance_of = |scene: &render::scene::PreparedScene| -> Vec<f64> {
        render::cpu_renderer::render_radiance(scene)
            .unwrap()
            .iter()
            .map(|p| f64::from(luminance(p.radiance)))
            .collect()
    };
    let (with_clouds, without) = (luminance_of(&scene), luminance_of(&cloudless));
    (scene, with_clouds, without)
}

/// A cloud's shadow on the terrain: the same view drawn with its map and without.
#[derive(Debug)]
pub struct TerrainDarkening {
    /// Terrain pixels.
    pub terrain: usize,
    /// The terrain pixels over 10 % darker with the map.
    pub darker: Vec<usize>,
    /// The smallest luminance ratio, with the map over without.
    pub worst: f32,
}

/// Compares the terrain pixels of `shaded` (drawn with a cloud's shadow map) with
/// `unshaded` (without it); panics where the map brightens one.
pub fn terrain_darkening(
    shaded: &[render::cpu_renderer::PixelRadiance],
    unshaded: &[render::cpu_renderer::PixelRadiance],
) -> TerrainDarkening {
    let mut out = TerrainDarkening {
        terrain: 0,
        darker: Vec::new(),
        worst: 1.0,
    };
    for (i, (a, b)) in shaded.iter().zip(unshaded).enumerate() {
        if a.terrain_distance.is_some() {
            out.terrain += 1;
            let (la, lb) = (luminance(a.radiance), luminance(b.radiance));
            assert!(
                la <= lb * (1.0 + 1e-6) + 1e-12,
                "pixel {i} brighter in shadow: {la} vs {lb}"
            );
            if la < 0.9 * lb {
                out.darker.push(i);
            }
            out.worst = out.worst.min(la / lb.max(1e-30));
        }
    }
    out
}

/// `[camera]` lines 9 km up, 3 km west and 2 km south of `at` (x east, y up, z south),
/// looking down at it: where a cloud's shadow falls.
pub fn camera_looking_down_at(at: [f64; 3]) -> String {
    format!(
        "position = [{:.1}, 9000.0, {:.1}]\nlook_at = [{:.1}, {:.1}, {:.1}]\n\
         vertical_fov_deg = 60.0\nnear = 1.0\nfar = 120000.0",
        at[0] - 3000.0,
        at[2] + 2000.0,
        at[0],
        at[1],
        at[2]
    )
}

/// The error of parsing `text`, or else of preparing it.
pub fn parse_error(text: &str) -> SceneError {
    match Scene::parse(text, ".") {
        Err(e) => e,
        Ok(scene) => scene.prepare().unwrap_err(),
    }
}

/// The renderer's settings the CPU comparisons use: every terrain tile at full
/// resolution (the CPU ray casts the full heightfield), no timestamps, every cloud
/// pixel marched every frame.
pub fn exact_settings() -> SceneRendererSettings {
    SceneRendererSettings {
        terrain_error_px: 0.0,
        timestamps: false,
        temporal_clouds: false,
    }
}

/// `scene` on the GPU with `settings`, RGBA8 packed as `u32`.
pub fn gpu_pixels_with(
    gpu: &GpuContext,
    scene: &PreparedScene,
    settings: SceneRendererSettings,
) -> Vec<u32> {
    let mut renderer = SceneRenderer::new(&gpu.device, &gpu.queue, scene, settings).unwrap();
    draw(gpu, &mut renderer, scene)
}

/// One frame of `scene` drawn by `renderer` (prepared, encoded, submitted), RGBA8
/// packed as `u32`.
pub fn draw(gpu: &GpuContext, renderer: &mut SceneRenderer, scene: &PreparedScene) -> Vec<u32> {
    renderer.prepare(&gpu.queue, scene).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    renderer.encode(&mut encoder).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let buffer = renderer.pixel_buffer();
    let bytes =
        skyscape_harness::read_buffer(gpu, "scene pixels", buffer, 0, buffer.size()).unwrap();
    bytemuck::cast_slice(&bytes).to_vec()
}

/// `scene` on the GPU with [`exact_settings`], RGBA8 packed as `u32`.
pub fn gpu_pixels(gpu: &GpuContext, scene: &PreparedScene) -> Vec<u32> {
    gpu_pixels_with(gpu, scene, exact_settings())
}

/// `scene` on the CPU reference renderer, RGBA8 packed as `u32`.
pub fn cpu_pixels(scene: &PreparedScene) -> Vec<u32> {
    render::cpu_renderer::render_cpu(scene).unwrap().pixels
}

/// `scene` on the GPU ([`gpu_pixels`]) and on the CPU, and their [`Agreement`].
pub fn compare(gpu: &GpuContext, scene: &PreparedScene) -> (Vec<u32>, Vec<u32>, Agreement) {
    let gpu_image = gpu_pixels(gpu, scene);
    let cpu_image = cpu_pixels(scene);
    let agreement = Agreement::of(&gpu_image, &cpu_image, scene.camera.width as usize);
    (gpu_image, cpu_image, agreement)
}

/// Channel `channel` (0 R, 1 G, 2 B) of a packed RGBA8 pixel.
pub fn code(pixel: u32, channel: usize) -> u32 {
    (pixel >> (8 * channel)) & 255
}

/// The largest difference of two packed RGBA8 pixels over R, G, B (LSB).
pub fn lsb(a: u32, b: u32) -> u32 {
    (0..3)
        .map(|c| code(a, c).abs_diff(code(b, c)))
        .max()
        .unwrap()
}

/// The pixels `indices` of two images: how many, how many within 2 LSB ([`lsb`]) and
/// the worst difference.
pub fn within_two_over(
    gpu_image: &[u32],
    cpu_image: &[u32],
    indices: impl IntoIterator<Item = usize>,
) -> (usize, usize, u32) {
    let (mut count, mut within, mut worst) = (0usize, 0usize, 0u32);
    for i in indices {
        let d = lsb(gpu_image[i], cpu_image[i]);
        count += 1;
        within += usize::from(d <= 2);
        worst = worst.max(d);
    }
    (count, within, worst)
}

/// scene_gpu's metric of a GPU image against the CPU's: the fractions of pixels within
/// 2 and 8 LSB, within 2 LSB of the other image's 3×3 neighbourhood, and the mean
/// signed (GPU − CPU) and absolute differences per channel (LSB).
pub struct Agreement {
    pub two: f64,
    pub eight: f64,
    pub shifted: f64,
    pub signed: [f64; 3],
    pub absolute: [f64; 3],
}

impl Agreement {
    /// The metric of `gpu_image` against `cpu_image`, `width` pixels a row.
    pub fn of(gpu_image: &[u32], cpu_image: &[u32], width: usize) -> Self {
        let within = |n| render::tonemap::fraction_within_lsb(gpu_image, cpu_image, n).unwrap();
        let shifted = render::tonemap::fraction_within_lsb_of_neighbourhood(
            gpu_image, cpu_image, width, 2, 1,
        )
        .unwrap();
        let mut signed = [0.0f64; 3];
        let mut absolute = [0.0f64; 3];
        for (a, b) in gpu_image.iter().zip(cpu_image) {
            for channel in 0..3 {
                let difference = f64::from(code(*a, channel)) - f64::from(code(*b, channel));
                signed[channel] += difference / gpu_image.len() as f64;
                absolute[channel] += difference.abs() / gpu_image.len() as f64;
            }
        }
        Self {
            two: within(2),
            eight: within(8),
            shifted,
            signed,
            absolute,
        }
    }

    /// Most pixels within 2 LSB, nearly all within 8 (scene_gpu's thresholds).
    pub fn close(&self) -> bool {
        self.two >= 0.96 && self.eight >= 0.985 && self.shifted >= 0.975
    }

    /// The three fractions as the assertions print them: `two eight shifted`.
    pub fn fractions(&self) -> String {
        format!("{} {} {}", self.two, self.eight, self.shifted)
    }

    /// The mean differences as the assertions print them: `signed absolute`.
    pub fn biases(&self) -> String {
        format!("{:?} {:?}", self.signed, self.absolute)
    }

    /// No bias: every channel's mean signed difference within ±0.5 LSB and its mean
    /// absolute difference at most `absolute` LSB.
    pub fn unbiased(&self, absolute: f64) -> bool {
        (0..3).all(|c| self.signed[c].abs() <= 0.5 && self.absolute[c] <= absolute)
    }
}

impl std::fmt::Display for Agreement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:.3} % within 2 LSB, {:.3} % within 8, {:.3} % within 2 LSB of the other \
             image's 3×3 neighbourhood; mean (GPU − CPU) {:.3?} LSB, mean |difference| {:.3?} LSB",
            100.0 * self.two,
            100.0 * self.eight,
            100.0 * self.shifted,
            self.signed,
            self.absolute
        )
    }
}
