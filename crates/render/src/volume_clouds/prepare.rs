//! `[clouds.volume]` prepared: checked, grown by cloudsim's automaton, lit by each of
//! the scene's lights, its shadow maps toward them baked.

use glam::DVec3;

use cloudlight::CloudVolume;
use cloudlight::march::{Jitter, LightMarch, Lighting, MarchConfig, MarchSettings, Octaves};

use super::*;
use crate::light::{CloudLight, LightSource};
use crate::scene::{CloudVolumeSection, Scene, SceneError};

fn deg_free(value: f64, unit: &str) -> String {
    format!("{value}{unit}")
}

impl Scene {
    /// An error about `[clouds.volume]`'s key `key`.
    fn volume_invalid(&self, key: &str, value: String, reason: String) -> SceneError {
        self.invalid(&["clouds", "volume", key], value, reason)
    }

    /// Checks `[clouds.volume]`'s values (cheap: before any table or automaton is
    /// built), every error naming its key.
    pub(crate) fn check_volume_cloud(
        &self,
        section: &CloudVolumeSection,
    ) -> Result<(), SceneError> {
        let invalid =
            |k: &str, value: String, reason: String| self.volume_invalid(k, value, reason);
        let s = section;
        if s.steps == 0 || s.steps > MAX_STEPS {
            return Err(invalid(
                "steps",
                s.steps.to_string(),
                format!("must be in 1..={MAX_STEPS}"),
            ));
        }
        let limits = [
            MAX_HORIZONTAL_CELLS,
            MAX_HORIZONTAL_CELLS,
            MAX_VERTICAL_CELLS,
        ];
        if s.grid.iter().zip(limits).any(|(&n, max)| n == 0 || n > max) {
            return Err(invalid(
                "grid",
                format!("[{}, {}, {}]", s.grid[0], s.grid[1], s.grid[2]),
                format!(
                    "cells [east, north, up] must each be ≥ 1 and at most \
                     [{MAX_HORIZONTAL_CELLS}, {MAX_HORIZONTAL_CELLS}, {MAX_VERTICAL_CELLS}]"
                ),
            ));
        }
        if !(s.cell_size_m.is_finite() && s.cell_size_m > 0.0 && s.cell_size_m <= 10_000.0) {
            return Err(invalid(
                "cell_size_m",
                deg_free(s.cell_size_m, " m"),
                "must be finite, > 0 m and ≤ 10,000 m".into(),
            ));
        }
        if !(s.base_m.is_finite() && s.base_m >= 0.0 && s.base_m <= 20_000.0) {
            return Err(invalid(
                "base_m",
                deg_free(s.base_m, " m"),
                "must be in [0 m, 20,000 m] above the camera's ground".into(),
            ));
        }
        if s.centre_m.iter().any(|c| !c.is_finite() || c.abs() > 1e6) {
            return Err(invalid(
                "centre_m",
                format!("[{}, {}]", s.centre_m[0], s.centre_m[1]),
                "must be finite world [x, z] metres within 1,000 km of the origin".into(),
            ));
        }
        if !(s.sigma_t_per_density.is_finite()
            && s.sigma_t_per_density > 0.0
            && s.sigma_t_per_density <= 10.0)
        {
            return Err(invalid(
                "sigma_t_per_density",
                deg_free(s.sigma_t_per_density, " /m"),
                "must be finite, > 0 /m and ≤ 10 /m".into(),
            ));
        }
        if s.view_steps == 0 || s.view_steps > 1024 {
            return Err(invalid(
                "view_steps",
                s.view_steps.to_string(),
                "must be in 1..=1024".into(),
            ));
        }
        if s.light_steps == 0 || s.light_steps > 256 {
            return Err(invalid(
                "light_steps",
                s.light_steps.to_string(),
                "must be in 1..=256".into(),
            ));
        }
        if s.octaves == 0 || s.octaves > 8 {
            return Err(invalid(
                "octaves",
                s.octaves.to_string(),
                "must be in 1..=8".into(),
            ));
        }
        for (k, v) in [
            ("octave_a", s.octave_a),
            ("octave_b", s.octave_b),
            ("octave_c", s.octave_c),
        ] {
            if !(0.0..=1.0).contains(&v) {
                return Err(invalid(k, v.to_string(), "must be in [0, 1]".into()));
            }
        }
        for (index, e) in s.ellipsoids.iter().enumerate() {
            if e.centre.iter().chain(&e.radii).any(|v| !v.is_finite())
                || e.radii.iter().any(|&r| r <= 0.0)
            {
                return Err(self.invalid(
                    &[
                        "clouds",
                        "volume",
                        "ellipsoids",
                        &index.to_string(),
                        "radii",
                    ],
                    format!("centre {:?}, radii {:?}", e.centre, e.radii),
                    "centre and radii (cells) must be finite, radii > 0".into(),
                ));
            }
        }
        Ok(())
    }

    /// Grows `[clouds.volume]` (checked by [`Scene::check_volume_cloud`]) and lights it
    /// by each of the scene's `lights` (the sun first); with `shadows_on_terrain` it
    /// bakes its shadow map toward each.
    pub(crate) fn volume_cloud(
        &self,
        section: &CloudVolumeSection,
        lights: &[LightSource<'_>],
        shadows_on_terrain: bool,
    ) -> Result<PreparedVolume, SceneError> {
        self.check_volume_cloud(section)?;
        let invalid =
            |k: &str, value: String, reason: String| self.volume_invalid(k, value, reason);
        let s = section;
        let [nx, ny, nz] = s.grid;
        let ellipsoids = if s.ellipsoids.is_empty() {
            // The cumulus of cloudlight's examples (64×64×24 cells) scaled to the grid.
            let scale = [
                f64::from(nx) / 64.0,
                f64::from(ny) / 64.0,
                f64::from(nz) / 24.0,
            ];
            [
                ([28.0, 32.0, 9.0], [20.0, 18.0, 8.0]),
                ([40.0, 30.0, 13.0], [16.0, 20.0, 9.0]),
            ]
            .map(|(c, r): ([f64; 3], [f64; 3])| cloudsim::Ellipsoid {
                center: std::array::from_fn(|a| (c[a] * scale[a]) as f32),
                radii: std::array::from_fn(|a| (r[a] * scale[a]) as f32),
            })
            .to_vec()
        } else {
            s.ellipsoids
                .iter()
                .map(|e| cloudsim::Ellipsoid {
                    center: e.centre.map(|c| c as f32),
                    radii: e.radii.map(|r| r as f32),
                })
                .collect()
        };
        let mut config = cloudsim::Config::new(cloudsim::GridSize::new(nx, ny, nz));
        config.seed = s.seed;
        config.ellipsoids = ellipsoids;
        let model_error = |e: cloudsim::Error| {
            let message = e.to_string();
            let k = if message.contains("ellipsoid") || message.contains("radii") {
                "ellipsoids"
            } else if message.contains("size") || message.contains("cells") {
                "grid"
            } else {
                "seed"
            };
            invalid(k, format!("{section:?}"), message)
        };
        let automaton = cloudsim::Model::new(config).map_err(model_error)?;
        let mut simulation = cloudsim::Simulation::new(automaton).map_err(model_error)?;
        simulation
            .advance(s.steps)
            .map_err(|e| invalid("steps", s.steps.to_string(), e.to_string()))?;
        let density = simulation
            .density()
            .map_err(|e| invalid("steps", s.steps.to_string(), e.to_string()))?;
        let cloudy_cells = density.iter().filter(|&&d| d > 0.0).count();
        let cell = s.cell_size_m;
        // World [x, z] centre → east/north corner: north is −z.
        let origin = [
            s.centre_m[0] - 0.5 * f64::from(nx) * cell,
            -s.centre_m[1] - 0.5 * f64::from(ny) * cell,
            s.base_m,
        ];
        let volume = CloudVolume::new(s.grid, origin, cell, s.sigma_t_per_density, density)
            .map_err(|e| invalid("cell_size_m", deg_free(cell, " m"), e.to_string()))?;
        let settings = MarchSettings::new(MarchConfig {
            view_steps: s.view_steps,
            jitter: Jitter::None,
            light: LightMarch::Full {
                steps: std::num::NonZeroU32::new(s.light_steps).expect("checked ≥ 1 above"),
            },
            // Wrenninge's octaves (docs/tradeoffs/cloudlight.md measures them against the
            // path tracer).
            octaves: Octaves {
                count: s.octaves,
                a: s.octave_a,
                b: s.octave_b,
                c: s.octave_c,
            },
            ..MarchConfig::default()
        })
        .map_err(|e| invalid("view_steps", s.view_steps.to_string(), e.to_string()))?;
        let lights = lights
            .iter()
            .map(|light| {
                Ok(CloudLight {
                    lighting: self.volume_light(section, light)?,
                    // Only a scene with terrain (or the deck) reads the shadow map.
                    shadow: shadows_on_terrain
                        .then(|| {
                            CloudShadow::new(&volume, world_to_enu(light.direction.to_array()))
                        })
                        .flatten(),
                })
            })
            .collect::<Result<_, SceneError>>()?;
        Ok(PreparedVolume {
            volume,
            settings,
            steps: s.steps,
            cloudy_cells,
            lights,
        })
    }

    /// One light of `[clouds.volume]` at the grid's centre: `cloudlight::march::atmos_light`
    /// of the light's rung and atmosphere (the sun's, or the moon's moonlit one) toward
    /// it, east/north/up.
    pub(crate) fn volume_light(
        &self,
        section: &CloudVolumeSection,
        light: &LightSource<'_>,
    ) -> Result<Lighting<f32>, SceneError> {
        let (model, atmosphere, toward) = (light.scattered(), light.atmosphere, light.direction);
        let s = section;
        let invalid = |e: String| self.volume_invalid("base_m", deg_free(s.base_m, " m"), e);
        // Planet-centred: world + planet radius up.
        let centre = DVec3::new(
            s.centre_m[0],
            atmosphere.planet_radius + s.base_m + 0.5 * f64::from(s.grid[2]) * s.cell_size_m,
            s.centre_m[1],
        );
        let light = cloudlight::march::atmos_light(
            &model,
            atmosphere,
            centre,
            toward,
            atmos::ground_irradiance::HemisphereQuadrature::default(),
        )
        .map_err(|e| invalid(e.to_string()))?;
        Lighting::new(
            world_to_enu(toward.to_array()),
            light.sun_irradiance,
            light.ambient_radiance,
            [0.0, 0.0, 1.0],
        )
        .map_err(|e| invalid(e.to_string()))
    }
}
