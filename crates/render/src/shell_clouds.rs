//! Seed 003's ray-marched cloud shell in a scene (`[clouds.shell]`): `cloudlight`'s
//! procedural shell (two spheres about the planet centre, tileable Perlin–Worley noise,
//! procedural weather, height profiles per cloud type) marched per pixel with seed 003's
//! lighting and composited over the opaque scene, depth-aware, exactly as the volume
//! cloud is (`crate::volume_clouds`): the march stops at the terrain, so a ridge in front
//! of the deck hides it and the deck in front of a ridge covers it, and the cloud is seen
//! through the air up to its transmittance-weighted depth. This module owns only the
//! section, the frame and the lighting point; the shell, its density and validation are
//! `cloudlight::CloudShell`'s, the march is `cloudlight::march` (CPU, the f32 twin) and
//! `cloudlight::gpu::MarchShellPass` (GPU), the air and the composite are the volume
//! cloud's (`shaders/render/volume_air.wgsl`, `shaders/render/volume_clouds.wgsl` with
//! its moonlit march off; `render::volume_clouds::cloud_through_air` on the CPU).
//!
//! # Frame
//!
//! cloudlight's shell is planet-centred with the viewer near the +z pole; the render
//! world is `x` east, `y` up, `z` south with the planet centre at `(0, −R, 0)`, so a
//! world point's planet-centred position `(x, y + R, z)` becomes the shell's
//! `(x, −z, y + R)` ([`crate::volume_clouds::world_to_enu`] without removing the
//! radius): [`shell_camera`] is the scene camera there. The weather and the noise are
//! sampled at the shell frame's `x` (east) and `y` (north).
//!
//! # Lighting
//!
//! Once per scene, at the middle of the shell straight above the camera: the sun's
//! irradiance through the scene's rung and the ambient sky (`cloudlight::march::atmos_light`,
//! as the volume cloud). At night (a scene with a moonlit sky: the sun down, the moon
//! up, when the terrain gets its moonlit draw) the deck is marched a second time lit by
//! the moon (`atmos_light` of celestial's moonlit atmosphere along the moon, as the
//! volume cloud's [`crate::volume_clouds::MoonlitVolume`]) and added through the moonlit
//! air. The deck's shadow on the terrain is not modelled.
//!
//! # What it costs
//!
//! Nothing without the section: no shell, no march pipeline, no buffer. The GPU pass
//! evaluates the noise procedurally per sample (cloudlight's `MarchShellPass` has no
//! baked-noise variant), so there is no noise bake either.

use glam::DVec3;
use serde::Deserialize;

use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchError, MarchResult, MarchSettings, Octaves,
    PinholeCamera,
};
use cloudlight::shell::{ProceduralWeather, WeatherMap};
use cloudlight::{CloudShell, ShellError, ShellSettings};

use crate::scene::{Scene, SceneError};
use crate::volume_clouds::{ModelRef, world_to_enu};

/// The most view-march steps per pixel.
pub const MAX_VIEW_STEPS: u32 = 1024;
/// The most light-march steps per sample.
pub const MAX_LIGHT_STEPS: u32 = 256;
/// The most ambient-visibility steps per sample.
pub const MAX_AMBIENT_STEPS: u32 = 64;
/// The most multiple-scattering octaves.
pub const MAX_OCTAVES: u32 = 8;

/// `[clouds.shell]`: seed 003's procedural cloud shell (`cloudlight::CloudShell`)
/// between two altitudes, its coverage and cloud type from cloudlight's procedural
/// weather, marched by `cloudlight` (seed 003's lighting). Defaults not given here are
/// cloudlight's (`ShellSettings::cumulus_over`, `ProceduralWeather::default`,
/// `MarchConfig::default`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudShellSection {
    /// Altitude of the shell's bottom (its inner sphere) above the planet's surface
    /// (world `y = 0`), metres.
    pub bottom_m: f64,
    /// Altitude of the shell's top (its outer sphere), metres.
    pub top_m: f64,
    /// Mean coverage of the weather, in [0, 1].
    #[serde(default = "default_coverage")]
    pub coverage: f64,
    /// Coverage contrast (≥ 0): coverage `clamp(mean + contrast·(2n − 1), 0, 1)`.
    #[serde(default = "default_coverage_contrast")]
    pub coverage_contrast: f64,
    /// Mean cloud type, in [0, 1]: the height profile, 0 stratus, ½ stratocumulus,
    /// 1 cumulus (blended between).
    #[serde(default = "default_cloud_type")]
    pub cloud_type: f64,
    /// Cloud type contrast, ≥ 0.
    #[serde(default = "default_cloud_type_contrast")]
    pub cloud_type_contrast: f64,
    /// The weather map's horizontal period, metres.
    #[serde(default = "default_weather_period")]
    pub weather_period_m: f64,
    /// Lattice cells of the weather's lowest octave per period (≥ 1).
    #[serde(default = "default_weather_cells")]
    pub weather_cells: u32,
    /// Seed of the weather map.
    #[serde(default = "default_weather_seed")]
    pub weather_seed: u32,
    /// Period of the shape noise (one 128³ tile), metres.
    #[serde(default = "default_shape_period")]
    pub shape_period_m: f64,
    /// Period of the detail noise (one 32³ tile), metres.
    #[serde(default = "default_detail_period")]
    pub detail_period_m: f64,
    /// Detail erosion strength, in [0, 1).
    #[serde(default = "default_erosion")]
    pub erosion: f64,
    /// Extinction per unit density σ_t, 1/m.
    #[serde(default = "default_sigma_t")]
    pub sigma_t_per_density: f64,
    /// Seed of the shape and detail noise.
    #[serde(default = "default_seed")]
    pub seed: u32,
    /// Distance along a view ray where the horizon fade begins, metres.
    #[serde(default = "default_fade_start")]
    pub horizon_fade_start_m: f64,
    /// Distance where the clouds have faded out, metres.
    #[serde(default = "default_fade_end")]
    pub horizon_fade_end_m: f64,
    /// View-march steps per pixel (1..=1024).
    #[serde(default = "default_view_steps")]
    pub view_steps: u32,
    /// Light-march steps toward the sun per sample (1..=256).
    #[serde(default = "default_light_steps")]
    pub light_steps: u32,
    /// Ambient-visibility steps along up per sample (0..=64; 0: visibility 1).
    #[serde(default = "default_ambient_steps")]
    pub ambient_steps: u32,
    /// Multiple-scattering octaves (1: single scattering; 1..=8).
    #[serde(default = "default_octaves")]
    pub octaves: u32,
    /// The octaves' extinction factor `a` in [0, 1].
    #[serde(default = "half")]
    pub octave_a: f64,
    /// The octaves' contribution factor `b` in [0, 1].
    #[serde(default = "half")]
    pub octave_b: f64,
    /// The octaves' phase eccentricity factor `c` in [0, 1].
    #[serde(default = "half")]
    pub octave_c: f64,
}

fn default_shell() -> ShellSettings {
    ShellSettings::cumulus_over(0.0)
}
fn default_coverage() -> f64 {
    ProceduralWeather::default().coverage_mean
}
fn default_coverage_contrast() -> f64 {
    ProceduralWeather::default().coverage_contrast
}
fn default_cloud_type() -> f64 {
    ProceduralWeather::default().cloud_type_mean
}
fn default_cloud_type_contrast() -> f64 {
    ProceduralWeather::default().cloud_type_contrast
}
fn default_weather_period() -> f64 {
    ProceduralWeather::default().period
}
fn default_weather_cells() -> u32 {
    ProceduralWeather::default().cells
}
fn default_weather_seed() -> u32 {
    ProceduralWeather::default().seed
}
fn default_shape_period() -> f64 {
    default_shell().shape_period
}
fn default_detail_period() -> f64 {
    default_shell().detail_period
}
fn default_erosion() -> f64 {
    default_shell().erosion
}
fn default_sigma_t() -> f64 {
    default_shell().extinction_per_density
}
fn default_seed() -> u32 {
    default_shell().seed
}
fn default_fade_start() -> f64 {
    default_shell().horizon_fade_start
}
fn default_fade_end() -> f64 {
    default_shell().horizon_fade_end
}
fn default_view_steps() -> u32 {
    48
}
fn default_light_steps() -> u32 {
    8
}
fn default_ambient_steps() -> u32 {
    MarchConfig::default().ambient_steps
}
fn default_octaves() -> u32 {
    8
}
fn half() -> f64 {
    0.5
}

/// The scene's cloud shell, built once per scene.
#[derive(Debug, Clone)]
pub struct PreparedShell {
    /// The shell about the scene's planet (planet-centred, the camera near +z).
    pub shell: CloudShell,
    /// The march's settings (midpoint samples, a full light march).
    pub settings: MarchSettings,
    /// The sun and ambient sky at the middle of the shell above the camera, in the
    /// shell's frame.
    pub lighting: Lighting<f32>,
    /// The moon and the moonlit ambient sky there: only in scenes with a moonlit sky
    /// (`PreparedScene::moonlit`), else `None` and no second march runs.
    pub moon: Option<Lighting<f32>>,
}

/// The `[clouds.shell]` key a cloudlight `ShellError` is about.
fn shell_key(error: &ShellError) -> &'static str {
    let field: &str = match error {
        ShellError::NotFinite { field, .. }
        | ShellError::NotPositive { field, .. }
        | ShellError::OutOfRange { field, .. }
        | ShellError::GridSize { field, .. }
        | ShellError::GridValue { field, .. }
        | ShellError::ZeroCount { field } => field,
        ShellError::RadiiOrder { .. } => "outer_radius",
        ShellError::InnerBelowGround { .. } => "inner_radius",
        ShellError::FadeOrder { .. } => "horizon_fade_end",
    };
    match field {
        "outer_radius" => "top_m",
        "shape_period" => "shape_period_m",
        "detail_period" => "detail_period_m",
        "extinction_per_density" => "sigma_t_per_density",
        "erosion" => "erosion",
        "horizon_fade_start" => "horizon_fade_start_m",
        "horizon_fade_end" => "horizon_fade_end_m",
        "weather.period" => "weather_period_m",
        "weather.cells" => "weather_cells",
        "weather.coverage_mean" => "coverage",
        "weather.coverage_contrast" => "coverage_contrast",
        "weather.cloud_type_mean" => "cloud_type",
        "weather.cloud_type_contrast" => "cloud_type_contrast",
        // inner_radius, and the planet's radius it is checked against.
        _ => "bottom_m",
    }
}

/// The `[clouds.shell]` key a cloudlight `MarchError` is about.
fn march_key(error: &MarchError) -> &'static str {
    match error {
        MarchError::Invalid { field, .. } => match *field {
            "octaves.count" => "octaves",
            "octaves.a" => "octave_a",
            "octaves.b" => "octave_b",
            "octaves.c" => "octave_c",
            _ => "view_steps",
        },
        MarchError::Atmos(_) => "bottom_m",
    }
}

impl CloudShellSection {
    /// The value of key `key` as typed, with its unit.
    fn value_of(&self, key: &str) -> String {
        let metres = |v: f64| format!("{v} m");
        match key {
            "bottom_m" => metres(self.bottom_m),
            "top_m" => metres(self.top_m),
            "coverage" => self.coverage.to_string(),
            "coverage_contrast" => self.coverage_contrast.to_string(),
            "cloud_type" => self.cloud_type.to_string(),
            "cloud_type_contrast" => self.cloud_type_contrast.to_string(),
            "weather_period_m" => metres(self.weather_period_m),
            "weather_cells" => self.weather_cells.to_string(),
            "shape_period_m" => metres(self.shape_period_m),
            "detail_period_m" => metres(self.detail_period_m),
            "erosion" => self.erosion.to_string(),
            "sigma_t_per_density" => format!("{} /m", self.sigma_t_per_density),
            "horizon_fade_start_m" => metres(self.horizon_fade_start_m),
            "horizon_fade_end_m" => metres(self.horizon_fade_end_m),
            "view_steps" => self.view_steps.to_string(),
            "light_steps" => self.light_steps.to_string(),
            "ambient_steps" => self.ambient_steps.to_string(),
            "octaves" => self.octaves.to_string(),
            "octave_a" => self.octave_a.to_string(),
            "octave_b" => self.octave_b.to_string(),
            "octave_c" => self.octave_c.to_string(),
            _ => String::new(),
        }
    }

    /// cloudlight's shell settings about a planet of `planet_radius` metres.
    fn shell_settings(&self, planet_radius: f64) -> ShellSettings {
        ShellSettings {
            inner_radius: planet_radius + self.bottom_m,
            outer_radius: planet_radius + self.top_m,
            weather: WeatherMap::Procedural(ProceduralWeather {
                seed: self.weather_seed,
                period: self.weather_period_m,
                cells: self.weather_cells,
                coverage_mean: self.coverage,
                coverage_contrast: self.coverage_contrast,
                cloud_type_mean: self.cloud_type,
                cloud_type_contrast: self.cloud_type_contrast,
            }),
            shape_period: self.shape_period_m,
            detail_period: self.detail_period_m,
            erosion: self.erosion,
            extinction_per_density: self.sigma_t_per_density,
            seed: self.seed,
            horizon_fade_start: self.horizon_fade_start_m,
            horizon_fade_end: self.horizon_fade_end_m,
        }
    }
}

impl Scene {
    /// An error cloudlight raised about `[clouds.shell]`'s key `key`.
    fn shell_error(
        &self,
        section: &CloudShellSection,
        key: &str,
        source: Box<dyn std::error::Error + Send + Sync>,
    ) -> SceneError {
        let path = ["clouds", "shell", key];
        SceneError::Cloudlight {
            location: self.location(&path),
            field: path.join("."),
            value: section.value_of(key),
            source,
        }
    }

    /// Checks `[clouds.shell]` (cheap: cloudlight validates the shell and the march's
    /// settings; nothing is evaluated), every error naming its key: the shell and the
    /// settings.
    pub(crate) fn check_shell_cloud(
        &self,
        section: &CloudShellSection,
        atmosphere: &atmos::Atmosphere,
    ) -> Result<(CloudShell, MarchSettings), SceneError> {
        let s = section;
        // The counts' upper bounds are render's (the cost of a frame); the rest is
        // cloudlight's validation.
        for (key, value, lowest, highest) in [
            ("view_steps", s.view_steps, 1, MAX_VIEW_STEPS),
            ("light_steps", s.light_steps, 1, MAX_LIGHT_STEPS),
            ("ambient_steps", s.ambient_steps, 0, MAX_AMBIENT_STEPS),
            ("octaves", s.octaves, 1, MAX_OCTAVES),
        ] {
            if !(lowest..=highest).contains(&value) {
                return Err(self.invalid(
                    &["clouds", "shell", key],
                    value.to_string(),
                    format!("must be in {lowest}..={highest}"),
                ));
            }
        }
        let shell = CloudShell::new(atmosphere, s.shell_settings(atmosphere.planet_radius))
            .map_err(|e| self.shell_error(s, shell_key(&e), Box::new(e)))?;
        let settings = MarchSettings::new(MarchConfig {
            view_steps: s.view_steps,
            jitter: Jitter::None,
            light: LightMarch::Full {
                steps: std::num::NonZeroU32::new(s.light_steps).expect("checked ≥ 1 above"),
            },
            octaves: Octaves {
                count: s.octaves,
                a: s.octave_a,
                b: s.octave_b,
                c: s.octave_c,
            },
            ambient_steps: s.ambient_steps,
            ..MarchConfig::default()
        })
        .map_err(|e| self.shell_error(s, march_key(&e), Box::new(e)))?;
        Ok((shell, settings))
    }

    /// Builds and lights `[clouds.shell]` for a camera at planet-centred
    /// `camera_position` (m) and the sun along unit `sun` (world frame); at night
    /// (`moonlit`) lit by the moon too.
    pub(crate) fn shell_cloud(
        &self,
        section: &CloudShellSection,
        atmosphere: &atmos::Atmosphere,
        model: &(dyn atmos::SkyModel + Send + Sync),
        camera_position: DVec3,
        sun: DVec3,
        moonlit: Option<&crate::scene::prepare::MoonlitSky>,
    ) -> Result<PreparedShell, SceneError> {
        let (shell, settings) = self.check_shell_cloud(section, atmosphere)?;
        // The middle of the shell straight above the camera.
        let middle = atmosphere.planet_radius + 0.5 * (section.bottom_m + section.top_m);
        let point = camera_position.try_normalize().unwrap_or(DVec3::Y) * middle;
        // One light (the sun, or the moon through the moonlit atmosphere) there.
        let light_at = |model: &(dyn atmos::SkyModel + Send + Sync),
                        atmosphere: &atmos::Atmosphere,
                        toward: DVec3| {
            let light_error = |e: MarchError| self.shell_error(section, "bottom_m", Box::new(e));
            let light = cloudlight::march::atmos_light(
                &ModelRef(model),
                atmosphere,
                point,
                toward,
                atmos::ground_irradiance::HemisphereQuadrature::default(),
            )
            .map_err(light_error)?;
            Lighting::new(
                world_to_enu(toward.to_array()),
                light.sun_irradiance,
                light.ambient_radiance,
                [0.0, 0.0, 1.0],
            )
            .map_err(light_error)
        };
        let lighting = light_at(model, atmosphere, sun)?;
        let moon = match moonlit {
            Some(moon) => Some(light_at(
                moon.sky_model.as_ref(),
                &moon.atmosphere,
                moon.direction,
            )?),
            None => None,
        };
        Ok(PreparedShell {
            shell,
            settings,
            lighting,
            moon,
        })
    }
}

/// The scene camera as a pinhole camera in the shell's planet-centred frame (module
/// documentation): [`crate::volume_clouds::pinhole_camera`] with the planet centre as
/// the origin, so [`cloudlight::march::pixel_direction`] gives the scene's pixel rays.
pub fn shell_camera(camera: &atmos::frame::FrameCamera) -> Result<PinholeCamera, MarchError> {
    crate::volume_clouds::pinhole_camera(camera, 0.0)
}

/// The march of pixel `pixel` through the shell (f32, the twin of `MarchShellPass`'s
/// pixel): along [`cloudlight::march::pixel_direction`] of `camera` from its origin, up
/// to `max_distance` metres (the terrain's hit; infinite for the sky), then faded by the
/// shell's horizon fade at the result's depth.
pub fn march_shell_pixel(
    cloud: &PreparedShell,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    march_shell_pixel_lit(cloud, &cloud.lighting, camera, size, pixel, max_distance)
}

/// [`march_shell_pixel`] lit by `lighting` (the sun's, [`PreparedShell::lighting`], or
/// the moon's, [`PreparedShell::moon`]).
pub fn march_shell_pixel_lit(
    cloud: &PreparedShell,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    let [forward, right, up] = camera.basis().map(|v| v.map(|c| c as f32));
    let tan_half = camera.tan_half(size).map(|t| t as f32);
    let origin = camera.origin().map(|c| c as f32);
    let direction = cloudlight::march::pixel_direction(pixel, size, forward, right, up, tan_half);
    let result = cloudlight::march::march_view_at_pixel_limited(
        &cloud.shell,
        origin,
        direction,
        &cloud.settings,
        lighting,
        pixel,
        max_distance,
    );
    cloudlight::march::faded(result, cloud.shell.horizon_fade(result.depth))
}

/// The air between the camera and `depth` metres along unit world `view` lit by `light`
/// (the sun, or the moon at night): its transmittance and in-scattered radiance, from
/// the precomputed rung's aerial-perspective tables of that light when `tables` is given
/// (`atmos::lut::drop_in::aerial_perspective`, the twin of the GPU's air pass), else
/// from the light's segment model.
pub fn air_in_front(
    scene: &crate::scene::PreparedScene,
    light: &crate::scene::Illuminant<'_>,
    tables: Option<(&atmos::lut::StaticLuts, &atmos::lut::FrameLuts)>,
    view: [f32; 3],
    depth: f32,
) -> Result<([f32; 3], [f32; 3]), crate::RenderError> {
    Ok(match tables {
        Some((luts, frame)) => {
            let offset = view.map(|v| v * depth);
            let segment = atmos::lut::drop_in::aerial_perspective(luts, frame, offset);
            (segment.transmittance, segment.radiance)
        }
        None => {
            let view = DVec3::from_array(view.map(f64::from)).normalize();
            let query = atmos::SkyQuery::with_max_distance(
                scene.atmosphere.planet_radius,
                scene.camera_position,
                view,
                light.direction,
                f64::from(depth),
            )?;
            let air = light.segment_model.evaluate(&query);
            (
                air.transmittance.map(|t| t as f32),
                air.radiance.map(|l| l as f32),
            )
        }
    })
}

/// The CPU twin of the GPU's shell march and composite: per pixel, the f32 march through
/// the shell up to the terrain's hit (`PixelRadiance::terrain_distance`; the sky: no
/// limit), faded toward the horizon, drawn where it has opacity in front of the scene
/// (`crate::volume_clouds::cloud_in_front`) as `L_c·T_air + L_air·(1 − T_c) + T_c·L`
/// (`crate::volume_clouds::cloud_through_air`, the air from [`air_in_front`] with the
/// sun's `tables`). At night (`moon`: the moon's light and its tables) the deck's march
/// lit by the moon, seen through the moonlit air, is added.
#[allow(clippy::type_complexity)] // the tables as the CPU renderer holds them
pub fn composite_shell_cloud(
    scene: &crate::scene::PreparedScene,
    cloud: &PreparedShell,
    tables: Option<(&atmos::lut::StaticLuts, &atmos::lut::FrameLuts)>,
    moon: Option<(
        &crate::scene::Illuminant<'_>,
        Option<(&atmos::lut::StaticLuts, &atmos::lut::FrameLuts)>,
    )>,
    out: &mut [crate::cpu_renderer::PixelRadiance],
) -> Result<(), crate::RenderError> {
    use crate::volume_clouds::{cloud_in_front, cloud_through_air};
    use rayon::prelude::*;
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let pinhole = shell_camera(camera)?;
    let sun = scene.sun_light();
    let moon = match (&cloud.moon, moon) {
        (Some(lighting), Some((light, moon_tables))) => Some((lighting, light, moon_tables)),
        _ => None,
    };
    out.par_chunks_mut(camera.width as usize)
        .enumerate()
        .try_for_each(|(row, pixels)| {
            for (column, pixel) in pixels.iter_mut().enumerate() {
                let xy = [column as u32, row as u32];
                let behind = pixel.terrain_distance.unwrap_or(f32::INFINITY);
                let result = march_shell_pixel(cloud, &pinhole, size, xy, behind);
                if !cloud_in_front(&result, behind) {
                    continue;
                }
                let view = atmos::frame::frame_view_direction(xy, camera);
                let (transmittance, radiance) =
                    air_in_front(scene, &sun, tables, view, result.depth)?;
                let mut seen = cloud_through_air(&result, transmittance, radiance);
                if let Some((lighting, light, moon_tables)) = &moon {
                    let lit = march_shell_pixel_lit(cloud, lighting, &pinhole, size, xy, behind);
                    let (transmittance, radiance) =
                        air_in_front(scene, light, *moon_tables, view, lit.depth)?;
                    let added = cloud_through_air(&lit, transmittance, radiance);
                    for (value, a) in seen.iter_mut().zip(added) {
                        *value += a;
                    }
                }
                for (value, s) in pixel.radiance.iter_mut().zip(seen) {
                    *value = s + result.transmittance * *value;
                }
            }
            Ok::<(), crate::RenderError>(())
        })
}

/// The GPU side, the volume cloud's passes over the shell's march: the terrain's depth
/// as a distance per pixel (`shaders/render/volume_distance.wgsl`),
/// `cloudlight::gpu::MarchShellPass` over the scene's pixels limited by it (prepared per
/// frame with [`shell_camera`]; at night a second one lit by the moon), the air in front
/// of the deck per pixel and light (`shaders/render/volume_air.wgsl`: atmos'
/// `aerial_perspective`, the CPU's function) and the composite render pass
/// (`shaders/render/volume_clouds.wgsl`). Built only for scenes with `[clouds.shell]`.
#[cfg(feature = "gpu")]
#[derive(Debug)]
pub(crate) struct ShellCloudPass {
    sun: ShellLit,
    moon: Option<ShellLit>,
    distance_pipeline: wgpu::ComputePipeline,
    distance_layout: wgpu::BindGroupLayout,
    distance_uniform: wgpu::Buffer,
    /// The distance buffer, its bind group and the dispatch size (after `prepare`).
    distance: Option<(wgpu::Buffer, wgpu::BindGroup, [u32; 2])>,
    air_layout: wgpu::BindGroupLayout,
    air_uniform: wgpu::Buffer,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    bind_group: Option<wgpu::BindGroup>,
}

/// One light's march of the shell and its air pass (the sun's; at night the moon's).
#[cfg(feature = "gpu")]
#[derive(Debug)]
struct ShellLit {
    march: cloudlight::gpu::MarchShellPass,
    /// `shaders/render/volume_air.wgsl` with this light's tables' layouts.
    air_pipeline: wgpu::ComputePipeline,
    /// The air per pixel and its bind group (after `prepare`).
    air: Option<(wgpu::Buffer, wgpu::BindGroup)>,
}

#[cfg(feature = "gpu")]
impl ShellCloudPass {
    /// The march, distance, air and composite pipelines (each light's tables' layouts
    /// in its air pass's groups 0 and 1; `moon_luts`: the moonlit tables when the deck is
    /// lit by the moon too, [`PreparedShell::moon`]).
    pub(crate) fn new(
        device: &wgpu::Device,
        luts: &atmos::gpu::AtmosphereLuts,
        moon_luts: Option<&atmos::gpu::AtmosphereLuts>,
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        use crate::volume_clouds::{
            VolumeAirParams, VolumeComposite, VolumeDistanceParams, buffer_entry, compute_pipeline,
            depth_entry,
        };
        use wgpu::BufferBindingType::{Storage, Uniform};
        let compute = wgpu::ShaderStages::COMPUTE;
        let module = |name: &str| -> Result<wgpu::ShaderModule, crate::RenderError> {
            let source = crate::composer().compose_module(name)?;
            Ok(device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(name),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            }))
        };
        let uniform_buffer = |label: &str, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let distance_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render shell distance"),
            entries: &[
                buffer_entry(0, compute, Uniform),
                depth_entry(1, compute),
                buffer_entry(2, compute, Storage { read_only: false }),
            ],
        });
        let distance_pipeline = compute_pipeline(
            device,
            "render shell distance",
            &module("render::volume_distance")?,
            "volume_distance_main",
            &[Some(&distance_layout)],
        );
        let air_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render shell air"),
            entries: &[
                buffer_entry(0, compute, Uniform),
                buffer_entry(1, compute, Storage { read_only: true }),
                buffer_entry(2, compute, Storage { read_only: false }),
            ],
        });
        let air_module = module("render::volume_air")?;
        let lit = |luts: &atmos::gpu::AtmosphereLuts,
                   label: &str|
         -> Result<ShellLit, crate::RenderError> {
            Ok(ShellLit {
                march: cloudlight::gpu::MarchShellPass::new(device)?,
                air_pipeline: compute_pipeline(
                    device,
                    label,
                    &air_module,
                    "volume_air_main",
                    &[
                        Some(&luts.layouts().uniforms),
                        Some(&luts.layouts().tables),
                        Some(&air_layout),
                    ],
                ),
                air: None,
            })
        };
        let sun = lit(luts, "render shell air")?;
        let moon = match moon_luts {
            Some(moon_luts) => Some(lit(moon_luts, "render shell air (moonlit)")?),
            None => None,
        };
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let read = Storage { read_only: true };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render shell clouds"),
            entries: &[
                buffer_entry(0, fragment, Uniform),
                buffer_entry(1, fragment, read),
                depth_entry(2, fragment),
                buffer_entry(3, fragment, read),
                buffer_entry(4, fragment, read),
                buffer_entry(5, fragment, read),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render shell clouds"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let composite = module("render::volume_clouds")?;
        // dst · T_c + the deck's own light (premultiplied), as the volume cloud's.
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::SrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("render shell clouds"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &composite,
                entry_point: Some("volume_clouds_vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &composite,
                entry_point: Some("volume_clouds_fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: target,
                    blend: Some(blend),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        Ok(Self {
            sun,
            moon,
            distance_pipeline,
            distance_layout,
            distance_uniform: uniform_buffer(
                "render shell distance uniform",
                std::mem::size_of::<VolumeDistanceParams>(),
            ),
            distance: None,
            air_layout,
            air_uniform: uniform_buffer(
                "render shell air uniform",
                std::mem::size_of::<VolumeAirParams>(),
            ),
            pipeline,
            layout,
            uniform: uniform_buffer(
                "render shell clouds uniform",
                std::mem::size_of::<VolumeComposite>(),
            ),
            bind_group: None,
        })
    }

    /// The frame's marches (the scene camera in the shell's frame, one ray per pixel up
    /// to the terrain; the moon's at night), the distance, air and composite passes'
    /// uniforms and bind groups.
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        cloud: &PreparedShell,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), crate::RenderError> {
        use crate::volume_clouds::{VolumeAirParams, VolumeComposite, VolumeDistanceParams};
        let camera = &scene.camera;
        let pinhole = shell_camera(camera)?;
        let near = scene.near.max(0.01) as f32;
        let size = [camera.width, camera.height];
        let moon_lighting = match (&self.moon, &cloud.moon) {
            (Some(_), Some(lighting)) => Some(lighting),
            (None, None) => None,
            (built, _) => {
                return Err(crate::RenderError::InvalidParameter {
                    field: "clouds.shell",
                    value: if built.is_some() {
                        "not lit by the moon"
                    } else {
                        "lit by the moon"
                    }
                    .into(),
                    reason: "differs from the scene the renderer was built for",
                });
            }
        };
        queue.write_buffer(
            &self.distance_uniform,
            0,
            bytemuck::bytes_of(&VolumeDistanceParams {
                camera: *camera,
                near,
                width: camera.width,
                height: camera.height,
                padding0: 0,
            }),
        );
        queue.write_buffer(
            &self.air_uniform,
            0,
            bytemuck::bytes_of(&VolumeAirParams {
                width: camera.width,
                height: camera.height,
                padding: [0; 2],
            }),
        );
        queue.write_buffer(
            &self.uniform,
            0,
            bytemuck::bytes_of(&VolumeComposite {
                camera: *camera,
                near,
                radiance_scale: scene.present.exposure,
                width: camera.width,
                moonlit: u32::from(self.moon.is_some()),
            }),
        );
        // The distance and air buffers follow the image: kept across frames of one size.
        let pixels = u64::from(camera.width) * u64::from(camera.height);
        let storage = |label: &str, bytes: u64, kept: Option<wgpu::Buffer>| match kept {
            Some(buffer) if buffer.size() == bytes => buffer,
            _ => device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }),
        };
        let distances = storage(
            "render shell distances",
            pixels * 4,
            self.distance.take().map(|(buffer, _, _)| buffer),
        );
        let distance_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render shell distance"),
            layout: &self.distance_layout,
            entries: &[
                entry(0, self.distance_uniform.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(depth_view)),
                entry(2, distances.as_entire_binding()),
            ],
        });
        let mut lights = vec![(&mut self.sun, &cloud.lighting)];
        if let (Some(moon), Some(lighting)) = (self.moon.as_mut(), moon_lighting) {
            lights.push((moon, lighting));
        }
        for (lit, lighting) in lights {
            // The march stops at the terrain: a hill hides the deck behind it.
            lit.march.prepare_limited(
                device,
                queue,
                &cloud.shell,
                &pinhole,
                size,
                &cloud.settings,
                lighting,
                Some(&distances),
            )?;
            let image = lit
                .march
                .image_buffer()
                .ok_or(crate::RenderError::NotPrepared)?;
            let air = storage(
                "render shell air",
                pixels * 32,
                lit.air.take().map(|(buffer, _)| buffer),
            );
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("render shell air"),
                layout: &self.air_layout,
                entries: &[
                    entry(0, self.air_uniform.as_entire_binding()),
                    entry(1, image.as_entire_binding()),
                    entry(2, air.as_entire_binding()),
                ],
            });
            lit.air = Some((air, group));
        }
        fn buffers(lit: &ShellLit) -> Result<(&wgpu::Buffer, &wgpu::Buffer), crate::RenderError> {
            let image = lit
                .march
                .image_buffer()
                .ok_or(crate::RenderError::NotPrepared)?;
            let (air, _) = lit.air.as_ref().ok_or(crate::RenderError::NotPrepared)?;
            Ok((image, air))
        }
        let (image, air) = buffers(&self.sun)?;
        // Without the moon its bindings hold the sun's buffers (unread: moonlit = 0).
        let (moon_image, moon_air) = buffers(self.moon.as_ref().unwrap_or(&self.sun))?;
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render shell clouds"),
            layout: &self.layout,
            entries: &[
                entry(0, self.uniform.as_entire_binding()),
                entry(1, image.as_entire_binding()),
                entry(2, wgpu::BindingResource::TextureView(depth_view)),
                entry(3, air.as_entire_binding()),
                entry(4, moon_image.as_entire_binding()),
                entry(5, moon_air.as_entire_binding()),
            ],
        }));
        self.distance = Some((
            distances,
            distance_group,
            [camera.width.div_ceil(8), camera.height.div_ceil(8)],
        ));
        Ok(())
    }

    /// Records the distance pass (after the terrain has written the depth), the marches
    /// (the sun's timed with `march_times`, the moon's with `moon_times`) and the air
    /// passes with each light's tables (`moon_luts`: the moonlit ones, at night), each a
    /// compute pass of its own.
    pub(crate) fn encode_march(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        luts: &atmos::gpu::AtmosphereLuts,
        moon_luts: Option<&atmos::gpu::AtmosphereLuts>,
        march_times: Option<wgpu::ComputePassTimestampWrites<'_>>,
        moon_times: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), crate::RenderError> {
        let (_, distance_group, groups) = self
            .distance
            .as_ref()
            .ok_or(crate::RenderError::NotPrepared)?;
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render shell distance"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.distance_pipeline);
            pass.set_bind_group(0, distance_group, &[]);
            pass.dispatch_workgroups(groups[0], groups[1], 1);
        }
        self.sun.march.encode_timed(encoder, march_times)?;
        let moon = match (&self.moon, moon_luts) {
            (Some(moon), Some(moon_luts)) => {
                moon.march.encode_timed(encoder, moon_times)?;
                Some((moon, moon_luts))
            }
            (None, _) => None,
            (Some(_), None) => return Err(crate::RenderError::NotPrepared),
        };
        for (lit, tables) in std::iter::once((&self.sun, luts)).chain(moon) {
            let (_, air_group) = lit.air.as_ref().ok_or(crate::RenderError::NotPrepared)?;
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render shell air"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&lit.air_pipeline);
            pass.set_bind_group(0, tables.uniform_bind_group(), &[]);
            pass.set_bind_group(1, tables.table_bind_group(), &[]);
            pass.set_bind_group(2, air_group, &[]);
            pass.dispatch_workgroups(groups[0], groups[1], 1);
        }
        Ok(())
    }

    /// Draws the composite (one full-screen triangle) into `pass`.
    pub(crate) fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> Result<(), crate::RenderError> {
        let bind_group = self
            .bind_group
            .as_ref()
            .ok_or(crate::RenderError::NotPrepared)?;
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}

#[cfg(feature = "gpu")]
fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

/// What `skyscape explain` says of the shell's passes (the march, the moon's march at
/// night, the composite).
pub fn shell_pass_plans(
    scene: &crate::scene::PreparedScene,
) -> [(&'static str, Result<String, String>); 3] {
    let Some(cloud) = &scene.shell_cloud else {
        let none = || Err("no [clouds.shell]: no march".to_string());
        return [
            ("shell cloud march", none()),
            ("moonlit shell march", none()),
            (
                "shell clouds",
                Err("no [clouds.shell]: no shell, no march pass, nothing allocated".into()),
            ),
        ];
    };
    let s = cloud.shell.settings();
    let planet = cloud.shell.planet_radius();
    let c = cloud.settings.config();
    let light_steps = match c.light {
        LightMarch::Full { steps } => steps.get(),
        LightMarch::Cone { .. } => 7,
    };
    [
        (
            "shell cloud march",
            Ok(format!(
                "the terrain's depth as a distance per pixel, then cloudlight's march of the \
                 [clouds.shell] shell ({:.0}–{:.0} m, procedural noise per sample: no bake; \
                 {} view × {} light steps per pixel) up to it (a hill hides the deck behind it)",
                s.inner_radius - planet,
                s.outer_radius - planet,
                c.view_steps,
                light_steps,
            )),
        ),
        (
            "moonlit shell march",
            if cloud.moon.is_some() {
                Ok(
                    "the [clouds.shell] deck marched again lit by the moon (celestial's \
                     MoonLight through atmos: the terrain's moonlit draw's light), added \
                     through the moonlit air"
                        .into(),
                )
            } else {
                Err(
                    "the moon does not light the scene (no [time], or the sun up or the moon \
                     below −2°): the sun's march only"
                        .into(),
                )
            },
        ),
        (
            "shell clouds",
            Ok(
                "the air in front of the deck per pixel (atmos' aerial_perspective), then the \
                volume cloud's composite of the shell's march over the scene"
                    .into(),
            ),
        ),
    ]
}
