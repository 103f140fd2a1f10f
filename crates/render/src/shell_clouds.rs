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
//! air.
//!
//! # Shadow on the terrain
//!
//! Over a scene's terrain the deck shades it as the volume cloud does: cloudlight's
//! shadow map of the shell's density field toward each light that is up ([`shell_shadow`],
//! [`crate::volume_clouds::CloudShadow::over`]), baked once on the CPU at prepare (not by
//! [`Scene::prepare_for_gpu`](crate::scene::Scene::prepare_for_gpu)), on the
//! plane of the shell's base over the heightfield's extent swept along the light. The
//! GPU renderer bakes the same map again on the GPU (`crate::gpu::shell_shadow`:
//! cloudlight's `ShellShadowMapPass` over [`shell_shadow_map_plan`], whose f32 twin
//! `cloudlight::shell_shadow::shell_shadow_map` equals the CPU bake bit for bit) and
//! uses it instead of the CPU's values. Both renderers read the map with the same
//! bilinear lookup, faded inside the deck's altitudes (`CloudShadow::on_terrain`, the
//! terrain pass's `shadow_map_at`) and multiply
//! the terrain's direct light by it times the volume cloud's map (the terrain pass holds
//! one map per marched cloud: `crate::gpu::cloud_shadow`). At night the map is the
//! moon's.
//!
//! # What it costs
//!
//! Nothing without the section: no shell, no march pipeline, no buffer, no shadow map.
//! The GPU pass evaluates the noise procedurally per sample (cloudlight's
//! `MarchShellPass` has no baked-noise variant), so there is no noise bake either. The
//! shadow map is [`SHADOW_SIDE`]² texels × [`SHADOW_STEPS`] noise samples on the CPU
//! (its time is [`PreparedShell::shadow_seconds`], printed by `skyscape explain`).

use glam::DVec3;
use serde::Deserialize;

use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchError, MarchResult, MarchSettings, Octaves,
    PinholeCamera,
};
use cloudlight::shell::{ProceduralWeather, WeatherMap};
use cloudlight::{CloudShell, ShellError, ShellSettings};

use crate::scene::{Scene, SceneError};
use crate::volume_clouds::{CloudShadow, world_to_enu};

/// The most view-march steps per pixel.
pub const MAX_VIEW_STEPS: u32 = 1024;
/// The most light-march steps per sample.
pub const MAX_LIGHT_STEPS: u32 = 256;
/// The most ambient-visibility steps per sample.
pub const MAX_AMBIENT_STEPS: u32 = 64;
/// The most multiple-scattering octaves.
pub const MAX_OCTAVES: u32 = 8;
/// Texels along the longer side of the deck's shadow map ([`shell_shadow`]): 125 m
/// texels over the shipped scene's 16 km, 6 per period of its 800 m detail noise.
pub const SHADOW_SIDE: u32 = 128;
/// Midpoint steps of the deck's shadow map per span toward the light: 78 m steps
/// through the shipped 800 m deck under a 40° sun.
pub const SHADOW_STEPS: u32 = 16;

/// `[clouds.shell]`: seed 003's procedural cloud shell (`cloudlight::CloudShell`)
/// between two altitudes, its coverage and cloud type from cloudlight's procedural
/// weather or a weather grid from a PNG ([`crate::shell_weather`]), marched by `cloudlight` (seed 003's lighting). Defaults not given here are
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
    /// A weather grid from a PNG (relative to the scene file's folder; R coverage,
    /// G cloud type, B precipitation; [`crate::shell_weather`]) instead of the
    /// procedural weather (whose keys are then unused).
    #[serde(default)]
    pub weather_image: Option<std::path::PathBuf>,
    /// The weather image's pixel edge on the ground, metres (> 0; with `weather_image`).
    #[serde(default)]
    pub weather_cell_m: Option<f64>,
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
    /// The deck's shadow on the terrain toward the sun ([`shell_shadow`]): `None` in a
    /// scene without terrain or with the sun below 1°, and nothing is baked then.
    pub shadow: Option<CloudShadow>,
    /// Its shadow toward the moon, in scenes the moon lights (`None` otherwise, or with
    /// the moon below 1°).
    pub moon_shadow: Option<CloudShadow>,
    /// Seconds the shadow maps took to bake on this machine's CPU (0 without one).
    pub shadow_seconds: f64,
    /// The deck's shadow on the scene's volume cloud, `[sun, moon]`
    /// (`crate::mutual_shadow::deck_over_volume`, always baked on the CPU): `None`
    /// without a marched volume cloud or that light (or with it below 1°).
    pub over_volume: [Option<CloudShadow>; 2],
}

impl PreparedShell {
    /// Whether the shadow maps hold their values (a scene from `Scene::prepare`), or only
    /// their grids (from [`Scene::prepare_for_gpu`]: the GPU renderer bakes them; the CPU
    /// renderer needs [`crate::scene::PreparedScene::bake_shell_shadow_on_cpu`] first).
    pub fn shadows_baked_on_cpu(&self) -> bool {
        [&self.shadow, &self.moon_shadow]
            .into_iter()
            .flatten()
            .all(|map| !map.values.is_empty())
    }
}

impl crate::scene::PreparedScene {
    /// Bakes on the CPU the deck's shadow maps a [`Scene::prepare_for_gpu`] left as grids
    /// (the CPU renderer's, when the GPU renderer is not used after all); nothing for a
    /// scene whose maps are baked. Sets `shadow_seconds`.
    pub fn bake_shell_shadow_on_cpu(&mut self) {
        let (Some(cloud), Some(terrain)) = (&mut self.shell_cloud, &self.terrain) else {
            return;
        };
        if cloud.shadows_baked_on_cpu() {
            return;
        }
        let started = std::time::Instant::now();
        if cloud.shadow.is_some() {
            cloud.shadow = shell_shadow(&cloud.shell, terrain, self.sun);
        }
        if let (Some(_), Some(moon)) = (&cloud.moon_shadow, &self.moonlit) {
            cloud.moon_shadow = shell_shadow(&cloud.shell, terrain, moon.direction);
        }
        cloud.shadow_seconds = started.elapsed().as_secs_f64();
    }
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
            "weather_image" => format!("{:?}", self.weather_image),
            "weather_cell_m" => format!("{:?} m", self.weather_cell_m),
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
        let mut shell_settings = s.shell_settings(atmosphere.planet_radius);
        if let Some(grid) = self.shell_weather_grid(s)? {
            shell_settings.weather = WeatherMap::Grid(grid);
        }
        let shell = CloudShell::new(atmosphere, shell_settings)
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
    /// (`moonlit`) lit by the moon too. Over `terrain` it bakes the deck's shadow maps
    /// ([`shell_shadow`]) toward each light.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn shell_cloud(
        &self,
        section: &CloudShellSection,
        atmosphere: &atmos::Atmosphere,
        model: &(dyn atmos::SkyModel + Send + Sync),
        camera_position: DVec3,
        sun: DVec3,
        moonlit: Option<&crate::scene::prepare::MoonlitSky>,
        terrain: Option<&crate::scene::prepare::PreparedTerrain>,
        cpu_shadow: bool,
        volume: Option<&cloudlight::CloudVolume>,
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
                &model,
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
        // The shadow maps: only over terrain, only toward a light that is up.
        let started = std::time::Instant::now();
        // Without `cpu_shadow` (a scene prepared for the GPU renderer) only the maps'
        // grids: the GPU bakes them (procedural or grid weather).
        let on_gpu = !cpu_shadow;
        let shadow_toward = |toward: DVec3| {
            terrain.and_then(|t| {
                if on_gpu {
                    shell_shadow_unbaked(&shell, t, toward)
                } else {
                    shell_shadow(&shell, t, toward)
                }
            })
        };
        let shadow = shadow_toward(sun);
        let moon_shadow = moonlit.and_then(|moon| shadow_toward(moon.direction));
        let shadow_seconds = if !on_gpu && (shadow.is_some() || moon_shadow.is_some()) {
            started.elapsed().as_secs_f64()
        } else {
            0.0
        };
        // Its shadow on the volume cloud (crate::mutual_shadow), toward each light.
        let over_volume = [Some(sun), moonlit.map(|m| m.direction)].map(|toward| {
            crate::mutual_shadow::deck_over_volume(
                &shell,
                volume?,
                world_to_enu(toward?.to_array()),
            )
        });
        Ok(PreparedShell {
            shell,
            settings,
            lighting,
            moon,
            shadow,
            moon_shadow,
            shadow_seconds,
            over_volume,
        })
    }
}

/// The deck's shadow on `terrain` toward unit world direction `toward` (the sun, or the
/// moon at night), or `None` with the light below 1° (as the volume's,
/// [`CloudShadow::new`]): cloudlight's shadow map of the shell's density field
/// ([`CloudShadow::over`], `shadow_map::<f32, _>`, [`SHADOW_STEPS`] midpoint steps per
/// span) on the plane of the shell's base altitude, over the heightfield's extent swept
/// along the light to that plane from its lowest and highest points ([`SHADOW_SIDE`]
/// texels along its longer side, none finer than the heightfield's). Every terrain point below the base reads its exact
/// transmittance up to the map's sampling (clear air between it and the plane); a peak
/// standing in the deck is shaded by the faded column of [`CloudShadow::on_terrain`]
/// (none above the deck's top). The plane is flat and the
/// shell's base a sphere: at `d` metres from the camera's ground point the plane lies
/// `d²/2R` inside the deck (5 m at 8 km), where the march starts a few metres in.
pub fn shell_shadow(
    shell: &cloudlight::CloudShell,
    terrain: &crate::scene::prepare::PreparedTerrain,
    toward: DVec3,
) -> Option<CloudShadow> {
    shell_shadow_of(shell, shell, terrain, toward)
}

/// A [`shell_shadow`]'s grid, plane and light without its values (`values` empty): what
/// [`Scene::prepare_for_gpu`] keeps for the GPU renderer, which bakes the values itself
/// (`crate::gpu::shell_shadow`). Its texels cost nothing: the march runs over a field
/// without spans.
pub fn shell_shadow_unbaked(
    shell: &cloudlight::CloudShell,
    terrain: &crate::scene::prepare::PreparedTerrain,
    toward: DVec3,
) -> Option<CloudShadow> {
    struct NoCloud;
    impl cloudlight::DensityField<f32> for NoCloud {
        fn density(&self, _: [f32; 3]) -> f32 {
            0.0
        }
        fn extinction_per_density(&self) -> f32 {
            0.0
        }
        fn ray_spans(&self, _: [f32; 3], _: [f32; 3]) -> cloudlight::RaySpans<f32> {
            cloudlight::RaySpans::none()
        }
    }
    let mut map = shell_shadow_of(&NoCloud, shell, terrain, toward)?;
    map.values = Vec::new();
    Some(map)
}

/// [`shell_shadow`] marching `field` (the shell, or a field without spans for the grid
/// alone).
fn shell_shadow_of<D: cloudlight::DensityField<f32> + Sync + ?Sized>(
    field: &D,
    shell: &cloudlight::CloudShell,
    terrain: &crate::scene::prepare::PreparedTerrain,
    toward: DVec3,
) -> Option<CloudShadow> {
    let to_light = world_to_enu(toward.to_array());
    if to_light[2] < 1f64.to_radians().sin() {
        return None;
    }
    let planet = shell.planet_radius();
    let plane = shell.settings().inner_radius - planet;
    let hf = &terrain.heightfield;
    let [half_east, half_south] = terrain.map_offset();
    let (low, high) = hf
        .elevations()
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
            (lo.min(h), hi.max(h))
        });
    // A point at altitude h meets the plane (plane − h)/l_z along the light (capped at
    // 100 km as the volume's sweep).
    let sweep = |h: f64| ((plane - h) / to_light[2]).clamp(-1e5, 1e5);
    let (near, far) = (sweep(high), sweep(low));
    let lo =
        [0, 1].map(|a| -[half_east, half_south][a] + (near * to_light[a]).min(far * to_light[a]));
    let hi =
        [0, 1].map(|a| [half_east, half_south][a] + (near * to_light[a]).max(far * to_light[a]));
    let longer = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    CloudShadow::over(
        field,
        [lo, hi],
        hf.spacing().max(longer / f64::from(SHADOW_SIDE)),
        [plane, planet],
        shell.settings().outer_radius - planet,
        to_light,
        SHADOW_STEPS,
    )
}

/// The plan of `map` (a [`shell_shadow`] of `shell` toward unit world direction
/// `toward`) in the shell's planet-centred frame: its texels, the plane of the shell's
/// base, the light and [`SHADOW_STEPS`]; in f32 the same texel centres and direction as
/// the CPU bake's (the GPU bake, `crate::gpu::shell_shadow`, marches this plan with
/// `cloudlight::gpu::ShellShadowMapPass`).
pub fn shell_shadow_map_plan(
    shell: &cloudlight::CloudShell,
    map: &CloudShadow,
    toward: DVec3,
) -> Result<cloudlight::shadow_map::ShadowMapPlan, cloudlight::shadow_map::ShadowMapError> {
    let planet = shell.planet_radius();
    let plane = shell.settings().inner_radius - planet;
    let grid = cloudlight::shadow_map::ShadowGrid::new(
        map.origin.map(f64::from),
        f64::from(map.cell_size),
        map.resolution,
        plane + planet,
    )?;
    cloudlight::shadow_map::ShadowMapPlan::new(grid, world_to_enu(toward.to_array()), SHADOW_STEPS)
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
    let result = crate::volume_clouds::march_field_pixel(
        &cloud.shell,
        &cloud.settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
    );
    cloudlight::march::faded(result, cloud.shell.horizon_fade(result.depth))
}

/// The CPU twin of the GPU's shell march and composite: per pixel, the f32 march through
/// the shell up to the terrain's hit (`PixelRadiance::terrain_distance`; the sky: no
/// limit), faded toward the horizon, in the volume cloud's composite
/// (`crate::volume_clouds::composite_marched_cloud`: drawn where it has opacity in front
/// of the scene, seen through the air of [`crate::air::air_in_front`] with the sun's `tables`). At
/// night (`moon`: the moon's light and its tables) the deck's march lit by the moon,
/// seen through the moonlit air, is added.
pub fn composite_shell_cloud(
    scene: &crate::scene::PreparedScene,
    cloud: &PreparedShell,
    tables: crate::air::AirTables<'_>,
    moon: Option<(&crate::scene::Illuminant<'_>, crate::air::AirTables<'_>)>,
    out: &mut [crate::cpu_frame::PixelRadiance],
) -> Result<(), crate::RenderError> {
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let pinhole = shell_camera(camera)?;
    let moon = match (&cloud.moon, moon) {
        (Some(lighting), Some((light, moon_tables))) => Some((lighting, light, moon_tables)),
        _ => None,
    };
    crate::volume_clouds::composite_marched_cloud(
        scene,
        &cloud.lighting,
        tables,
        moon,
        |lighting, xy, behind| march_shell_pixel_lit(cloud, lighting, &pinhole, size, xy, behind),
        out,
    )
}

/// The GPU side: `cloudlight::gpu::MarchShellPass` over the scene's pixels (prepared per
/// frame with [`shell_camera`]; at night a second one lit by the moon) in the volume
/// cloud's passes ([`crate::gpu::cloud_composite::CloudComposite`]: the terrain's depth
/// as a distance per pixel the march stops at, the air in front of the deck per pixel
/// and light, the composite render pass `shaders/render/volume_clouds.wgsl`). Built only
/// for scenes with `[clouds.shell]`.
#[cfg(feature = "gpu")]
pub(crate) type ShellCloudPass =
    crate::gpu::cloud_composite::CloudComposite<cloudlight::gpu::MarchShellPass>;

#[cfg(feature = "gpu")]
impl ShellCloudPass {
    /// The march, distance, air and composite pipelines (`moon_luts`: the moonlit tables
    /// when the deck is lit by the moon too, [`PreparedShell::moon`]).
    pub(crate) fn new_shell(
        device: &wgpu::Device,
        luts: crate::gpu::cloud_air::CloudAir<'_>,
        moon_luts: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        Self::new(
            device,
            "shell",
            "clouds.shell",
            luts,
            moon_luts,
            target,
            || Ok(cloudlight::gpu::MarchShellPass::new(device)?),
        )
    }

    /// The frame's marches (the scene camera in the shell's frame, one ray per pixel up
    /// to `distance`'s buffer; the moon's at night), the air and composite passes'
    /// uniforms and bind groups.
    pub(crate) fn prepare_shell(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        cloud: &PreparedShell,
        distance: &crate::gpu::cloud_composite::CloudDistance,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), crate::RenderError> {
        let camera = &scene.camera;
        let pinhole = shell_camera(camera)?;
        let size = [camera.width, camera.height];
        self.prepare(
            device,
            queue,
            scene,
            distance,
            depth_view,
            &cloud.lighting,
            cloud.moon.as_ref(),
            |march, light, lighting, distances, kept| {
                // Lit through the volume cloud's shadow map for this light
                // (crate::mutual_shadow; uploaded once, kept while unchanged), read the
                // planet's radius below the march's frame.
                let volume = scene
                    .volume_cloud
                    .as_ref()
                    .and_then(|volume| crate::mutual_shadow::volume_on_deck(volume, light));
                let volume = kept.upload(device, queue, volume);
                let planet = cloud.shell.planet_radius() as f32;
                // The march stops at the terrain: a hill hides the deck behind it.
                Ok(march.prepare_lit_through(
                    device,
                    queue,
                    &cloud.shell,
                    &pinhole,
                    size,
                    &cloud.settings,
                    lighting,
                    Some(distances),
                    volume
                        .map(|v| crate::mutual_shadow::outside(v, planet))
                        .as_ref(),
                )?)
            },
        )
    }
}

/// What `skyscape explain` says of the shell's steps (the march, the moon's march at
/// night, the composite; the shadow maps' bake is the terrain pass's).
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

/// What `skyscape explain` says of the deck's shadow maps: baked at prepare (measured
/// here), or why none is.
pub(crate) fn shell_shadow_plan(cloud: &PreparedShell) -> Result<String, String> {
    let maps: Vec<String> = [("the sun", &cloud.shadow), ("the moon", &cloud.moon_shadow)]
        .into_iter()
        .filter_map(|(light, map)| {
            map.as_ref().map(|m| {
                format!(
                    "toward {light} {}×{} texels of {:.0} m",
                    m.resolution[0], m.resolution[1], m.cell_size
                )
            })
        })
        .collect();
    if maps.is_empty() {
        return Err(
            "no [terrain] under the deck, or no light above 1°: no shadow map baked".into(),
        );
    }
    let baked = if cloud.shadows_baked_on_cpu() {
        format!(
            "baked on the CPU at prepare in {:.2} s (measured; the CPU renderer's) and again \
             on the GPU by the GPU renderer",
            cloud.shadow_seconds
        )
    } else {
        "prepared for the GPU: baked by the GPU renderer only".to_owned()
    };
    Ok(format!(
        "cloudlight's shadow map of the deck over the terrain on the plane of its base \
         ({}; {} steps per texel), {baked} (cloudlight's ShellShadowMapPass, the same \
         formula; timed on the frame whose map changed, the first or a new light, and \
         as an empty pass on a frame that reuses it), read by the terrain pass times the \
         volume's",
        maps.join(", "),
        SHADOW_STEPS,
    ))
}
