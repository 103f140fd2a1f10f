//! `[clouds.volume]` drawn as billboards, prepared: grown, lit by slice propagation
//! toward the sun (and the moon on a moonlit night), its particles' lighting baked.

use cloudlight::CloudVolume;
use cloudlight::billboard::{
    BillboardSettings, LATTICE_DIAMETER_CELLS, Opacity, ParticleScattering, SizeRule,
};
use cloudlight::march::Lighting;
use cloudlight::propagate::{SliceMode, SlicePlan};

use crate::scene::{CloudVolumeSection, Scene, SceneError};

use super::*;

impl Scene {
    fn billboards_invalid(&self, key: &str, value: String, reason: &str) -> SceneError {
        self.invalid(
            &["clouds", "volume", "billboards", key],
            value,
            reason.into(),
        )
    }

    /// Checks `[clouds.volume]`'s drawing keys (cheap: before anything is built).
    pub(crate) fn check_billboard_cloud(
        &self,
        section: &CloudVolumeSection,
    ) -> Result<(), SceneError> {
        let b = match (section.draw, &section.billboards) {
            (VolumeDraw::March, None) => return Ok(()),
            (VolumeDraw::March, Some(_)) => {
                return Err(self.invalid(
                    &["clouds", "volume", "billboards"],
                    "a table".into(),
                    "billboard settings need draw = \"billboards\" in [clouds.volume] \
                     (draw is \"march\")"
                        .into(),
                ));
            }
            (VolumeDraw::Billboards, b) => b.unwrap_or_default(),
        };
        if !(0.0..=1.0).contains(&b.density_threshold) {
            return Err(self.billboards_invalid(
                "density_threshold",
                b.density_threshold.to_string(),
                "must be in [0, 1]",
            ));
        }
        if let Some(m) = b.size_m_per_density
            && !(m.is_finite() && m > 0.0 && m <= 1e5)
        {
            return Err(self.billboards_invalid(
                "size_m_per_density",
                format!("{m} m"),
                "must be finite, > 0 m and ≤ 100,000 m",
            ));
        }
        if let Some(c) = b.splat_cells
            && !(c.is_finite() && c > 0.0 && c <= 100.0)
        {
            return Err(self.billboards_invalid(
                "splat_cells",
                format!("{c} cells"),
                "must be finite, > 0 and ≤ 100 cells",
            ));
        }
        if let (Some(c), Some(_)) = (b.splat_cells, b.size_m_per_density) {
            return Err(self.billboards_invalid(
                "splat_cells",
                format!("{c} cells"),
                "give one size rule: splat_cells, size_m_per_density or seed_k, not two",
            ));
        }
        if let Some(k) = b.seed_k {
            if b.size_m_per_density.is_some() || b.splat_cells.is_some() {
                return Err(self.billboards_invalid(
                    "seed_k",
                    k.to_string(),
                    "give one size rule: splat_cells, size_m_per_density or seed_k (Dobashi et al. 2000's), not two",
                ));
            }
            if !(k.is_finite() && k > 0.0) {
                return Err(self.billboards_invalid(
                    "seed_k",
                    k.to_string(),
                    "must be finite and > 0 (pixel·metres)",
                ));
            }
        }
        if !(b.opacity_cells.is_finite() && b.opacity_cells > 0.0 && b.opacity_cells <= 1e3) {
            return Err(self.billboards_invalid(
                "opacity_cells",
                b.opacity_cells.to_string(),
                "must be finite, > 0 and ≤ 1000 cells",
            ));
        }
        if !(0.0..=1.0).contains(&b.attenuation_ratio) {
            return Err(self.billboards_invalid(
                "attenuation_ratio",
                b.attenuation_ratio.to_string(),
                "must be in [0, 1]",
            ));
        }
        Ok(())
    }

    /// Grows `[clouds.volume]`'s cloud (`Scene::volume_cloud`: the same automaton,
    /// placement, lights and shadows) and lights it with the slices toward each of the
    /// scene's `lights`, for drawing as billboards.
    pub(crate) fn billboard_cloud(
        &self,
        section: &CloudVolumeSection,
        lights: &[crate::light::LightSource<'_>],
        near: f64,
        shadows_on_terrain: bool,
    ) -> Result<PreparedBillboards, SceneError> {
        self.check_billboard_cloud(section)?;
        let b = section.billboards.unwrap_or_default();
        // The marched cloud's growth, placement, lights and shadows.
        let grown = self.volume_cloud(section, lights, shadows_on_terrain)?;
        let slices = match b.slices {
            SlicesName::Physical => SliceMode::Physical,
            SlicesName::Faithful => SliceMode::Faithful {
                attenuation_ratio: b.attenuation_ratio,
            },
        };
        let propagate = |toward: [f32; 3]| {
            let plan =
                SlicePlan::new(&grown.volume, toward.map(f64::from), slices).map_err(|e| {
                    self.billboards_invalid("slices", format!("{:?}", b.slices), &e.to_string())
                })?;
            cloudlight::propagate::propagate::<f32>(&grown.volume, &plan).map_err(|e| {
                self.billboards_invalid("slices", format!("{:?}", b.slices), &e.to_string())
            })
        };
        let lights = grown
            .lights
            .iter()
            .map(|lit| {
                Ok(BillboardLight {
                    light: propagate(lit.lighting.sun_direction())?,
                    lighting: lit.lighting,
                    shadow: lit.shadow.clone(),
                })
            })
            .collect::<Result<Vec<_>, SceneError>>()?;
        let size = match (b.seed_k, b.size_m_per_density) {
            (Some(k), _) => SizeRule::Seed { k },
            (None, Some(metres_per_density)) => SizeRule::World { metres_per_density },
            (None, None) => SizeRule::Fixed {
                diameter: b.splat_cells.unwrap_or(LATTICE_DIAMETER_CELLS) * section.cell_size_m,
            },
        };
        let cells = b.opacity_cells;
        let opacity = match b.opacity {
            OpacityName::OpticalDepth => Opacity::OpticalDepth { cells },
            OpacityName::Slab => Opacity::Slab { cells },
        };
        let settings = BillboardSettings {
            density_threshold: b.density_threshold,
            size,
            opacity,
            // Dobashi et al. 2000's colour (the light alone): `particles` replaces it with
            // `particle_radiance`.
            sun_colour: [1.0; 3],
            near: billboard_near(near),
        };
        settings.validate().map_err(|e| {
            self.billboards_invalid("density_threshold", b.density_threshold.to_string(), &{
                e.to_string()
            })
        })?;
        let dense_cells = grown
            .volume
            .density()
            .iter()
            .filter(|&&d| f64::from(d) > b.density_threshold)
            .count();
        let ambient_visibility = sky_visibility(
            &grown.volume,
            &grown.lights[0].lighting,
            &grown.settings,
            b.density_threshold,
        );
        Ok(PreparedBillboards {
            ambient_visibility,
            scattering: ParticleScattering::of_march(&grown.settings),
            lights,
            volume: grown.volume,
            settings,
            slices,
            steps: grown.steps,
            dense_cells,
        })
    }
}

/// The ambient sky's visibility at the centre of every cell of `volume` denser than
/// `threshold` (0 at the others): the march's (`cloudlight::march::ambient_visibility`
/// along `lighting`'s up with `settings`' ambient steps), x fastest.
fn sky_visibility(
    volume: &CloudVolume,
    lighting: &Lighting<f32>,
    settings: &cloudlight::march::MarchSettings,
    threshold: f64,
) -> Vec<f32> {
    let [nx, ny, _] = volume.dims().map(|n| n as usize);
    let origin = volume.origin();
    let voxel = volume.voxel_size();
    let steps = settings.config().ambient_steps;
    volume
        .density()
        .iter()
        .enumerate()
        .map(|(cell, &rho)| {
            if f64::from(rho) <= threshold {
                return 0.0;
            }
            let index = [cell % nx, (cell / nx) % ny, cell / (nx * ny)];
            let centre: [f32; 3] =
                std::array::from_fn(|a| (origin[a] + (index[a] as f64 + 0.5) * voxel) as f32);
            cloudlight::march::ambient_visibility::<f32>(volume, centre, lighting.up(), steps)
        })
        .collect()
}
