//! `[clouds.shell]` prepared: checked, the shell built about the scene's planet, lit
//! by each of the scene's lights, its shadow maps toward them planned or baked.

use glam::DVec3;

use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchError, MarchSettings, Octaves,
};
use cloudlight::shell::WeatherMap;
use cloudlight::{CloudShell, ShellError};

use crate::frames::world_to_enu;
use crate::scene::{Scene, SceneError};

use super::*;

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
        let directions =
            std::iter::once(self.sun).chain(self.other_lights.iter().map(|l| l.direction));
        for (light, toward) in cloud.lights.iter_mut().zip(directions) {
            if light.shadow.is_some() {
                light.shadow = shell_shadow(&cloud.shell, terrain, toward);
            }
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

    /// Builds `[clouds.shell]` for a camera at planet-centred `camera_position` (m) and
    /// lights it by each of the scene's `lights` (the sun first, whose atmosphere the
    /// shell is built about). Over `terrain` it bakes the deck's shadow maps
    /// ([`shell_shadow`]) toward each light, and over `volume` its map on that cloud.
    pub(crate) fn shell_cloud(
        &self,
        section: &CloudShellSection,
        lights: &[crate::light::LightSource<'_>],
        camera_position: DVec3,
        terrain: Option<&crate::scene::prepare::PreparedTerrain>,
        cpu_shadow: bool,
        volume: Option<&cloudlight::CloudVolume>,
    ) -> Result<PreparedShell, SceneError> {
        let atmosphere = lights[0].atmosphere;
        let (shell, settings) = self.check_shell_cloud(section, atmosphere)?;
        // The middle of the shell straight above the camera.
        let middle = atmosphere.planet_radius + 0.5 * (section.bottom_m + section.top_m);
        let point = camera_position.try_normalize().unwrap_or(DVec3::Y) * middle;
        // One light (the sun, or the moon through the moonlit atmosphere) there.
        let light_at = |light: &crate::light::LightSource<'_>| {
            let (model, atmosphere, toward) =
                (light.scattered(), light.atmosphere, light.direction);
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
        let sources = lights;
        let lights: Vec<crate::light::CloudLight> = sources
            .iter()
            .map(|light| {
                Ok(crate::light::CloudLight {
                    lighting: light_at(light)?,
                    shadow: shadow_toward(light.direction),
                })
            })
            .collect::<Result<_, SceneError>>()?;
        let shadow_seconds = if !on_gpu && lights.iter().any(|l| l.shadow.is_some()) {
            started.elapsed().as_secs_f64()
        } else {
            0.0
        };
        // Its shadow on the volume cloud (crate::mutual_shadow), toward each light.
        let over_volume = sources
            .iter()
            .map(|light| {
                crate::mutual_shadow::deck_over_volume(
                    &shell,
                    volume?,
                    world_to_enu(light.direction.to_array()),
                )
            })
            .collect();
        Ok(PreparedShell {
            shell,
            settings,
            lights,
            shadow_seconds,
            over_volume,
        })
    }
}
