//! `[clouds.volume]` drawn as seed 002's billboards (`draw = "billboards"`): `cloudsim`
//! grows the cumulus (the same growth, grid and placement as the marched cloud,
//! `crate::volume_clouds`), `cloudlight`'s slice propagation lights every cell toward the
//! scene's sun, and each cell denser than the threshold becomes a soft splat
//! (`cloudlight::billboard`), sorted back to front, depth-tested against the terrain and
//! seen through the aerial perspective. This module owns only the composition: which
//! camera and sun the particles see, the air in front of each, and where the image meets
//! the scene.
//!
//! # Lighting
//!
//! Once per scene: `cloudlight::propagate::propagate::<f32>` (the slices' f32 twin,
//! physical Beer–Lambert mode with Catmull–Rom resampling by default, or seed 002's
//! faithful mode) through the grown volume toward the sun gives every cell its
//! transmittance `T` toward the sun. The light is the marched cloud's
//! (`crate::volume_clouds`, `PreparedVolume::lighting`), at the grid's centre: the
//! sun's irradiance `E` through the scene's rung (`cloudlight::march::atmos_light`: the
//! atmosphere's sun irradiance × the rung's transmittance toward the sun) and the
//! ambient sky radiance `L_amb` (atmos' sky irradiance on a horizontal surface / π).
//! Each drawn cell's sky visibility `V_amb` is the march's
//! (`cloudlight::march::ambient_visibility`: `e^{−τ}` straight up, the march's
//! `ambient_steps` midpoint steps). Per frame a particle's colour is
//! `cloudlight::billboard::particle_radiance`: `albedo · (E · P(τ, cos θ) + L_amb ·
//! V_amb)` with `P` the march's `octave_scattering` of `τ = −ln T` (its dual-lobe
//! Henyey–Greenstein phase and `[clouds.volume]`'s octaves, 8 by default; one octave is
//! `T · p(cos θ)`, Dobashi 2000's single scattering; seed 002 itself had `E · T` alone)
//! and the march's albedo, `θ` between the view ray to the particle and the sun. At night — when the scene has a
//! moonlit sky (`PreparedScene::moonlit`, as the marched cloud) — the slices run a
//! second time toward the moon and the moon's term and its moonlit ambient sky are
//! added ([`MoonlitBillboards`]); its shadow map along the moon shades the moonlit
//! terrain. The particle's colour is computed on the CPU for both renderers (the
//! particles are selected and sorted there per frame): the GPU's instances carry it.
//!
//! # Drawing
//!
//! Per frame the particles are selected and sorted for the scene's camera
//! (`cloudlight::billboard::billboards`, the camera rotated into the volume's
//! east/north/up frame, [`billboard_camera`]). Each particle is seen through the air
//! between the camera and its centre (`atmos::lut::drop_in::aerial_perspective` on the
//! precomputed rung, WGSL `aerial_perspective`, else the rung's
//! `SkyQuery::with_max_distance`; on the GPU a compute pass of the rung's own functions
//! per particle before the draw, `shaders/render/billboard_air_closed_form.wgsl`,
//! `billboard_air_single.wgsl`, read per instance by `billboard_clouds_rung.wgsl`):
//! `colour' = colour · T_air + L_air`
//! ([`billboard_seen_through_air`]), so the premultiplied splat adds
//! `α · (colour · T_air + L_air)` over `(1 − α)` of what is behind, the marched cloud's
//! `L_c · T_air + L_air · (1 − T_c)`. At night the moonlit air in front of each particle
//! is added to `L_air` ([`moonlit_air`]: the moon's segment model, computed on the CPU
//! and, on the precomputed rung, read by the GPU's vertex stage per instance; under the
//! closed form and single scattering the GPU runs the rung's pass for the moon instead;
//! the sun's air comes from the tables or the rung's pass). A particle covers a pixel
//! only where its view depth is less than the terrain's: on the CPU `cloudlight::billboard::rasterise_limited`
//! with the ray-cast terrain's view depth per pixel, on the GPU a depth test `Greater`
//! of `near / z` against the terrain's reverse-z depth (`shaders/render/billboard_clouds.wgsl`,
//! which draws cloudlight's instanced quads with `cloudlight::billboard`'s
//! `billboard_screen` and `splat_alpha`).

use glam::DVec3;
use serde::Deserialize;

use cloudlight::CloudVolume;
use cloudlight::billboard::{
    Billboard, BillboardSettings, Camera, FieldOfView, Opacity, ParticleLight, ParticleScattering,
    SizeRule,
};
use cloudlight::march::Lighting;
use cloudlight::propagate::{SliceMode, SlicePlan};

use crate::RenderError;
use crate::cpu_frame::PixelRadiance;
use crate::scene::{CloudVolumeSection, PreparedScene, Scene, SceneError};
use crate::volume_clouds::{CloudShadow, world_to_enu};

/// `[clouds.volume] draw`: how the automaton's cloud is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VolumeDraw {
    /// Ray-marched by `cloudlight` (seed 003's lighting), `crate::volume_clouds`.
    #[default]
    March,
    /// Seed 002's billboards lit by slices (this module).
    Billboards,
}

/// `[clouds.volume.billboards]`: the billboards' settings (with `draw = "billboards"`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BillboardsSection {
    /// A cell becomes a billboard when its density is strictly above this (seed 002:
    /// 0.3), in [0, 1].
    #[serde(default = "default_threshold")]
    pub density_threshold: f64,
    /// The billboard's world diameter per unit density, metres (default 2.5 cells).
    /// Exclusive with `seed_k`.
    pub size_m_per_density: Option<f64>,
    /// Seed 002's size rule instead: `(k·ρ/d)·ρ` pixels, `k` in pixel·metres (the seed
    /// used 9500, tuned to its own units: small in metres).
    pub seed_k: Option<f64>,
    /// Opacity of a billboard: a slab this many cells thick at the cell's density
    /// (`1 − exp(−σ_t·ρ·cell·cells)`), > 0.
    #[serde(default = "default_opacity_cells")]
    pub opacity_cells: f64,
    /// The slice propagation's mode: `"physical"` (Beer–Lambert over the true spacing)
    /// or `"faithful"` (seed 002's attenuation ratio per slice).
    #[serde(default)]
    pub slices: SlicesName,
    /// Faithful mode's light passed by a slice of density 1, in [0, 1].
    #[serde(default = "default_attenuation_ratio")]
    pub attenuation_ratio: f64,
}

impl Default for BillboardsSection {
    fn default() -> Self {
        Self {
            density_threshold: default_threshold(),
            size_m_per_density: None,
            seed_k: None,
            opacity_cells: default_opacity_cells(),
            slices: SlicesName::default(),
            attenuation_ratio: default_attenuation_ratio(),
        }
    }
}

/// `[clouds.volume.billboards] slices`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SlicesName {
    /// `cloudlight::propagate::SliceMode::Physical`.
    #[default]
    Physical,
    /// `cloudlight::propagate::SliceMode::Faithful`.
    Faithful,
}

fn default_threshold() -> f64 {
    0.3
}
fn default_opacity_cells() -> f64 {
    1.0
}
fn default_attenuation_ratio() -> f64 {
    0.9
}

/// The default billboard diameter per unit density, in cells.
pub const DEFAULT_CELLS_PER_DENSITY: f64 = 2.5;

/// The scene's billboard cloud, built once per scene.
#[derive(Debug, Clone)]
pub struct PreparedBillboards {
    /// The grown density in the east/north/up frame (as `PreparedVolume::volume`).
    pub volume: CloudVolume,
    /// The slices' light at every cell centre, x fastest (`propagate::<f32>`).
    pub light: Vec<f32>,
    /// The particles' settings: threshold, size, opacity, the sun's colour (its
    /// irradiance at the cloud / π), the near plane.
    pub settings: BillboardSettings,
    /// The slices' mode.
    pub slices: SliceMode,
    /// The automaton steps grown.
    pub steps: u32,
    /// Cells denser than the threshold (billboards before the camera's culling).
    pub dense_cells: usize,
    /// Its shadow on the terrain (as the marched cloud's, `CloudShadow`).
    pub shadow: Option<CloudShadow>,
    /// The sun and the ambient sky at the grid's centre, east/north/up (the marched
    /// cloud's `PreparedVolume::lighting`).
    pub lighting: Lighting<f32>,
    /// The ambient sky's visibility at every cell centre denser than the threshold
    /// (`cloudlight::march::ambient_visibility`), x fastest; 0 at the cells not drawn.
    pub ambient_visibility: Vec<f32>,
    /// The particles' albedo and phase: the march's (`ParticleScattering::of_march`).
    pub scattering: ParticleScattering,
    /// The cloud lit by the moon too: only in scenes with a moonlit sky
    /// (`PreparedScene::moonlit`), else `None` and no second propagation runs.
    pub moon: Option<MoonlitBillboards>,
}

/// The billboards' second light at night: the moon, as the sun is
/// ([`PreparedBillboards::lighting`] and `light`), from the marched cloud's
/// `MoonlitVolume`.
#[derive(Debug, Clone)]
pub struct MoonlitBillboards {
    /// The moon and the moonlit ambient sky at the grid's centre, east/north/up.
    pub lighting: Lighting<f32>,
    /// The slices' light toward the moon at every cell centre, x fastest.
    pub light: Vec<f32>,
    /// Its shadow on the terrain under the moon (`None` with the moon below 1° or no
    /// terrain in the scene).
    pub shadow: Option<CloudShadow>,
}

/// The air in front of a particle: `colour · T_air + L_air` per channel (the colour the
/// premultiplied splat carries, module docs). WGSL twin of the same name in
/// `shaders/render/billboard_air.wgsl` (parity case `render::billboard_seen_through_air`).
pub fn billboard_seen_through_air(
    colour: [f32; 3],
    air_transmittance: [f32; 3],
    air_radiance: [f32; 3],
) -> [f32; 3] {
    std::array::from_fn(|k| colour[k] * air_transmittance[k] + air_radiance[k])
}

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
        if let Some(k) = b.seed_k {
            if b.size_m_per_density.is_some() {
                return Err(self.billboards_invalid(
                    "seed_k",
                    k.to_string(),
                    "give either seed_k (seed 002's size rule) or size_m_per_density, not both",
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
    /// placement, sun and shadow) and lights it with the slices, for drawing as
    /// billboards.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn billboard_cloud(
        &self,
        section: &CloudVolumeSection,
        atmosphere: &atmos::Atmosphere,
        model: &(dyn atmos::SkyModel + Send + Sync),
        sun: DVec3,
        near: f64,
        shadows_on_terrain: bool,
        moonlit: Option<&crate::scene::prepare::MoonlitSky>,
    ) -> Result<PreparedBillboards, SceneError> {
        self.check_billboard_cloud(section)?;
        let b = section.billboards.unwrap_or_default();
        // The marched cloud's growth, placement, lights (the moon's at night) and shadows.
        let grown =
            self.volume_cloud(section, atmosphere, model, sun, shadows_on_terrain, moonlit)?;
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
        let light = propagate(grown.lighting.sun_direction())?;
        let moon = match grown.moon {
            Some(moon) => Some(MoonlitBillboards {
                light: propagate(moon.lighting.sun_direction())?,
                lighting: moon.lighting,
                shadow: moon.shadow,
            }),
            None => None,
        };
        let size = match b.seed_k {
            Some(k) => SizeRule::Seed { k },
            None => SizeRule::World {
                metres_per_density: b
                    .size_m_per_density
                    .unwrap_or(DEFAULT_CELLS_PER_DENSITY * section.cell_size_m),
            },
        };
        let settings = BillboardSettings {
            density_threshold: b.density_threshold,
            size,
            opacity: Opacity::Slab {
                cells: b.opacity_cells,
            },
            // Seed 002's colour (the light alone): `particles` replaces it with
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
            &grown.lighting,
            &grown.settings,
            b.density_threshold,
        );
        Ok(PreparedBillboards {
            ambient_visibility,
            scattering: ParticleScattering::of_march(&grown.settings),
            lighting: grown.lighting,
            moon,
            volume: grown.volume,
            light,
            settings,
            slices,
            steps: grown.steps,
            dense_cells,
            shadow: grown.shadow,
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

/// The near plane of the billboards and of the GPU's depth (`near / z`): the scene's,
/// at least 1 cm (as the volume cloud's composite).
pub fn billboard_near(near: f64) -> f64 {
    near.max(0.01)
}

/// The scene camera as `cloudlight::billboard`'s camera in the volume's frame: its
/// position less the planet radius up and its basis rotated to east/north/up, the
/// vertical field of view `2·atan(tan_half_fov_y)`, the image size.
pub fn billboard_camera(
    camera: &atmos::frame::FrameCamera,
    planet_radius: f64,
) -> Result<Camera, cloudlight::billboard::BillboardError> {
    let p = camera.position.map(f64::from);
    let origin = world_to_enu([p[0], p[1] - planet_radius, p[2]]);
    let forward = world_to_enu(camera.forward.map(f64::from));
    let up = world_to_enu(camera.up.map(f64::from));
    Camera::new(
        DVec3::from(origin),
        DVec3::from(forward),
        DVec3::from(up),
        FieldOfView::from_radians(2.0 * f64::from(camera.tan_half_fov_y).atan()),
        camera.width,
        camera.height,
    )
}

fn billboard_error(e: cloudlight::billboard::BillboardError) -> RenderError {
    RenderError::Billboards(e)
}

/// The particles of `cloud` the scene's camera sees, sorted back to front, their colours
/// the light they scatter toward the eye before the air
/// (`cloudlight::billboard::particle_radiance`: the sun's, the moon's at night, and the
/// ambient sky's).
pub fn particles(
    scene: &PreparedScene,
    cloud: &PreparedBillboards,
) -> Result<(Camera, Vec<Billboard>), RenderError> {
    let camera =
        billboard_camera(&scene.camera, scene.atmosphere.planet_radius).map_err(billboard_error)?;
    let mut particles =
        cloudlight::billboard::billboards(&cloud.volume, &cloud.light, &cloud.settings, &camera)
            .map_err(billboard_error)?;
    let light = |lighting: &Lighting<f32>, transmittance: f32| ParticleLight {
        direction: lighting.sun_direction().map(f64::from),
        irradiance: lighting.sun_irradiance().map(f64::from),
        transmittance: f64::from(transmittance),
    };
    let mut ambient = cloud.lighting.ambient_radiance().map(f64::from);
    if let Some(moon) = &cloud.moon {
        let add = moon.lighting.ambient_radiance();
        for (a, m) in ambient.iter_mut().zip(add) {
            *a += f64::from(m);
        }
    }
    for p in &mut particles {
        let r = DVec3::from_array(p.relative);
        let view = (r / r.length()).to_array();
        let sun = light(&cloud.lighting, cloud.light[p.cell]);
        let (lights, count) = match &cloud.moon {
            Some(moon) => ([sun, light(&moon.lighting, moon.light[p.cell])], 2),
            None => ([sun; 2], 1),
        };
        p.colour = cloudlight::billboard::particle_radiance(
            view,
            &lights[..count],
            ambient,
            f64::from(cloud.ambient_visibility[p.cell]),
            &cloud.scattering,
        );
    }
    Ok((camera, particles))
}

/// The world offset (x east, y up, z south) of a particle's position relative to the
/// eye (east/north/up), in f32 as the GPU's instance holds it.
pub fn world_offset(relative: [f64; 3]) -> [f32; 3] {
    let r = relative.map(|c| c as f32);
    [r[0], r[2], -r[1]]
}

/// At night (the cloud lit by the moon and the scene's moonlit sky), the moonlit air in
/// front of each particle: its in-scattered radiance between the camera and the
/// particle's centre from the moon's segment model ([`crate::air::segment_to`],
/// f32), the same values for both renderers (the GPU's vertex stage adds them to the
/// sun's air, the CPU twin likewise). `None` otherwise.
pub fn moonlit_air(
    scene: &PreparedScene,
    cloud: &PreparedBillboards,
    particles: &[Billboard],
) -> Result<Option<Vec<[f32; 3]>>, RenderError> {
    let (Some(_), Some(moon)) = (&cloud.moon, scene.moon_light()) else {
        return Ok(None);
    };
    particles
        .iter()
        .map(|p| {
            let offset = world_offset(p.relative);
            Ok(crate::air::segment_to(scene, &moon, None, offset)?.radiance)
        })
        .collect::<Result<Vec<_>, RenderError>>()
        .map(Some)
}

/// The twin of the GPU's billboard pass: `cloud`'s particles seen through the air
/// (the precomputed rung's `tables`, else the segment model), rasterised by
/// `cloudlight::billboard::rasterise_limited::<f32>` in front of the terrain and
/// composited over `out`.
pub fn composite_billboards_cpu(
    scene: &PreparedScene,
    cloud: &PreparedBillboards,
    tables: crate::air::AirTables<'_>,
    out: &mut [PixelRadiance],
) -> Result<(), RenderError> {
    let (camera, mut particles) = particles(scene, cloud)?;
    let moon_air = moonlit_air(scene, cloud, &particles)?;
    let sun = scene.sun_light();
    for (i, p) in particles.iter_mut().enumerate() {
        let offset = world_offset(p.relative);
        let air = crate::air::segment_to(scene, &sun, tables, offset)?;
        let (transmittance, radiance) = (air.transmittance, air.radiance);
        // At night the moonlit air is added to the sun's, as the GPU's vertex stage does.
        let radiance = match &moon_air {
            Some(air) => std::array::from_fn(|k| radiance[k] + air[i][k]),
            None => radiance,
        };
        // The f32 colour the GPU reads, seen through the air in f32.
        let colour = p.colour.map(|c| c as f32);
        p.colour = billboard_seen_through_air(colour, transmittance, radiance).map(f64::from);
    }
    let frame = &scene.camera;
    let width = frame.width as usize;
    let forward = frame.forward;
    let max_depth: Vec<f32> = out
        .iter()
        .enumerate()
        .map(|(i, pixel)| match pixel.terrain_distance {
            Some(distance) => {
                let view = atmos::frame::frame_view_direction(
                    [(i % width) as u32, (i / width) as u32],
                    frame,
                );
                distance * (view[0] * forward[0] + view[1] * forward[1] + view[2] * forward[2])
            }
            None => f32::INFINITY,
        })
        .collect();
    let image = cloudlight::billboard::rasterise_limited::<f32>(
        &particles,
        &camera,
        cloud.settings.size,
        &max_depth,
    )
    .map_err(billboard_error)?;
    for (pixel, over) in out.iter_mut().zip(&image.rgba) {
        for (value, c) in pixel.radiance.iter_mut().zip(over) {
            *value = c + (1.0 - over[3]) * *value;
        }
    }
    Ok(())
}

/// `skyscape explain`'s line for the billboard pass.
pub fn explain(scene: &PreparedScene) -> Result<String, String> {
    match &scene.billboard_cloud {
        Some(cloud) => {
            let [nx, ny, nz] = cloud.volume.dims();
            let drawn = particles(scene, cloud).map_or(0, |(_, p)| p.len());
            Ok(format!(
                "seed 002's billboards of the [clouds.volume] cumulus ({nx}×{ny}×{nz} cells grown \
                 by cloudsim in {} steps, lit on the CPU by cloudlight's {} slice propagation \
                 toward the sun{}, the march's phase and octaves and the ambient sky): \
                 {drawn} of {} cells denser than {} drawn back to front, depth-tested against \
                 the terrain, through the aerial perspective",
                cloud.steps,
                match cloud.slices {
                    SliceMode::Physical => "physical",
                    SliceMode::Faithful { .. } => "faithful",
                },
                if cloud.moon.is_some() {
                    " and again toward the moon (a moonlit sky)"
                } else {
                    ""
                },
                cloud.dense_cells,
                cloud.settings.density_threshold,
            ))
        }
        None => Err(
            "no [clouds.volume] with draw = \"billboards\": no slice propagation, no billboard \
             pipeline"
                .into(),
        ),
    }
}

/// The billboard pass's uniform bytes: `cloudlight::billboard`'s frame (64 bytes), the
/// near plane, the radiance scale, which moonlit air is added (WGSL
/// `BillboardCloudParams`: 0 none, 1 the CPU's per instance, 2 a rung's pass's).
#[cfg(feature = "gpu")]
pub fn params_bytes(
    frame: &cloudlight::billboard::ScreenFrame<f32>,
    near: f32,
    radiance_scale: f32,
    moonlit: u32,
) -> [u8; PARAMS_BYTES as usize] {
    let mut bytes = [0u8; PARAMS_BYTES as usize];
    bytes[..64].copy_from_slice(&cloudlight::gpu::billboard::frame_bytes(frame));
    bytes[64..68].copy_from_slice(&near.to_ne_bytes());
    bytes[68..72].copy_from_slice(&radiance_scale.to_ne_bytes());
    bytes[72..76].copy_from_slice(&moonlit.to_ne_bytes());
    bytes
}

/// The billboard pass's group 2: the uniform (vertex stage) and the moonlit air per
/// instance (a read-only storage buffer of `vec4<f32>`); with `rung_air` (a rung without
/// tables) the sun's and the moon's air per instance too
/// (`shaders/render/billboard_clouds_rung.wgsl`).
#[cfg(feature = "gpu")]
fn params_layout(device: &wgpu::Device, rung_air: bool) -> wgpu::BindGroupLayout {
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX,
        ty,
        count: None,
    };
    let storage = |binding| {
        entry(
            binding,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(16),
            },
        )
    };
    let entries = [
        entry(
            0,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(PARAMS_BYTES),
            },
        ),
        storage(1),
        storage(2),
        storage(3),
    ];
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("render billboard clouds"),
        entries: &entries[..if rung_air { 4 } else { 2 }],
    })
}

#[cfg(feature = "gpu")]
fn needs_tables() -> RenderError {
    RenderError::InvalidParameter {
        field: "clouds.volume.draw",
        value: "\"billboards\"".into(),
        reason: "the GPU billboards see their air through the precomputed rung's tables or \
                 the closed form's or single scattering's passes; render this scene with one \
                 of those rungs, or on the CPU (--cpu)",
    }
}

#[cfg(feature = "gpu")]
fn moon_air_buffer(device: &wgpu::Device, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("render billboard moonlit air"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

#[cfg(feature = "gpu")]
fn params_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    uniform: &wgpu::Buffer,
    moon_air: &wgpu::Buffer,
    rung_air: Option<[&wgpu::Buffer; 2]>,
) -> wgpu::BindGroup {
    let [sun, moon] = rung_air.map_or([None; 2], |airs| airs.map(Some));
    let entries: Vec<wgpu::BindGroupEntry<'_>> = [Some(uniform), Some(moon_air), sun, moon]
        .into_iter()
        .enumerate()
        .filter_map(|(binding, buffer)| {
            Some(wgpu::BindGroupEntry {
                binding: binding as u32,
                resource: buffer?.as_entire_binding(),
            })
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("render billboard clouds"),
        layout,
        entries: &entries,
    })
}

/// Bytes of WGSL `BillboardCloudParams`.
#[cfg(feature = "gpu")]
pub const PARAMS_BYTES: u64 = 80;

/// The particles per workgroup of the rungs' billboard air passes
/// (`shaders/render/billboard_air_*.wgsl`).
#[cfg(feature = "gpu")]
const AIR_WORKGROUP: u32 = 64;

/// The air in front of every particle under a rung without tables, per light (the sun,
/// and the moon on a moonlit night): a compute pass of the rung's functions
/// (`shaders/render/billboard_air_closed_form.wgsl`, `billboard_air_single.wgsl`) per
/// particle, with the light's camera and the rung's parameters of its atmosphere
/// (`crate::gpu::cloud_air::RungCloudAir`, written each frame by the rung's passes) in
/// groups 0 and 1, the particles' world offsets in and their air out in group 2
/// (`shaders/render/billboard_air_io.wgsl`). The twin of the CPU's segment models in
/// [`composite_billboards_cpu`] (the sun's) and [`moonlit_air`] (the moon's).
#[cfg(feature = "gpu")]
#[derive(Debug)]
struct RungBillboardAir {
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    /// The particles' world offsets (one `vec4<f32>` each).
    offsets: wgpu::Buffer,
    sun: LightAir,
    moon: Option<LightAir>,
}

/// One light's billboard air pass and its output.
#[cfg(feature = "gpu")]
#[derive(Debug)]
struct LightAir {
    pipeline: wgpu::ComputePipeline,
    /// The light's camera and the rung's parameters (groups 0 and 1).
    light: [wgpu::BindGroup; 2],
    /// The particles' air (two `vec4<f32>` each: radiance, transmittance), read by the
    /// draw's vertex stage.
    air: wgpu::Buffer,
    group: wgpu::BindGroup,
}

#[cfg(feature = "gpu")]
impl RungBillboardAir {
    fn new(
        device: &wgpu::Device,
        sun: &crate::gpu::cloud_air::RungCloudAir,
        moon: Option<&crate::gpu::cloud_air::RungCloudAir>,
    ) -> Result<Self, RenderError> {
        let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(16),
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render billboard air"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(16),
                    },
                    count: None,
                },
                storage(1, true),
                storage(2, false),
            ],
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render billboard air uniform"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let offsets = Self::buffer(device, "render billboard offsets", 16);
        let light = |air: &crate::gpu::cloud_air::RungCloudAir, label: &str| {
            let pipeline = air.pipeline(
                device,
                label,
                ("render::billboard_air_single", "billboard_air_single"),
                (
                    "render::billboard_air_closed_form",
                    "billboard_air_closed_form",
                ),
                &layout,
            )?;
            let light = air.groups().map(Clone::clone);
            let air = Self::buffer(device, label, 32);
            let group = Self::group(device, &layout, &uniform, &offsets, &air);
            Ok::<_, RenderError>(LightAir {
                pipeline,
                light,
                air,
                group,
            })
        };
        let sun = light(sun, "render billboard sun air")?;
        let moon = match moon {
            Some(moon) => Some(light(moon, "render billboard moon air")?),
            None => None,
        };
        Ok(Self {
            layout,
            uniform,
            offsets,
            sun,
            moon,
        })
    }

    fn buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    fn group(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        uniform: &wgpu::Buffer,
        offsets: &wgpu::Buffer,
        air: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = [uniform, offsets, air]
            .into_iter()
            .enumerate()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: binding as u32,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render billboard air"),
            layout,
            entries: &entries,
        })
    }

    /// The sun's air and the moon's (the sun's again without a moon pass: unread).
    fn airs(&self) -> [&wgpu::Buffer; 2] {
        [&self.sun.air, &self.moon.as_ref().unwrap_or(&self.sun).air]
    }

    /// Uploads the particles' world offsets (the draw's order) and their count; `true`
    /// when the air buffers were replaced (the draw's group 2 must be made again).
    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        particles: &[Billboard],
    ) -> Result<bool, RenderError> {
        let count = particles.len() as u64;
        let groups = count.div_ceil(u64::from(AIR_WORKGROUP));
        let limits = device.limits();
        if groups > u64::from(limits.max_compute_workgroups_per_dimension)
            || 32 * count > limits.max_storage_buffer_binding_size
        {
            return Err(RenderError::InvalidParameter {
                field: "clouds.volume.billboards",
                value: format!("{count} billboards"),
                reason: "more particles than the device's compute dispatch or storage \
                         binding limits allow for their air",
            });
        }
        let replaced = self.offsets.size() < 16 * count;
        if replaced {
            self.offsets = Self::buffer(device, "render billboard offsets", 16 * count);
            for (light, label) in [
                (Some(&mut self.sun), "render billboard sun air"),
                (self.moon.as_mut(), "render billboard moon air"),
            ] {
                if let Some(light) = light {
                    light.air = Self::buffer(device, label, 32 * count);
                    light.group = Self::group(
                        device,
                        &self.layout,
                        &self.uniform,
                        &self.offsets,
                        &light.air,
                    );
                }
            }
        }
        let offsets: Vec<f32> = particles
            .iter()
            .flat_map(|p| {
                let [x, y, z] = world_offset(p.relative);
                [x, y, z, 0.0]
            })
            .collect();
        if !offsets.is_empty() {
            queue.write_buffer(&self.offsets, 0, bytemuck::cast_slice(&offsets));
        }
        let params = [count as u32, 0, 0, 0];
        queue.write_buffer(&self.uniform, 0, bytemuck::cast_slice(&params));
        Ok(replaced)
    }

    /// Records the compute passes of `count` particles' air: the sun's, and the moon's
    /// when `moon`.
    fn encode(&self, encoder: &mut wgpu::CommandEncoder, count: u32, moon: bool) {
        let lights = [Some(&self.sun), self.moon.as_ref().filter(|_| moon)];
        for light in lights.into_iter().flatten() {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render billboard air"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&light.pipeline);
            pass.set_bind_group(0, &light.light[0], &[]);
            pass.set_bind_group(1, &light.light[1], &[]);
            pass.set_bind_group(2, &light.group, &[]);
            pass.dispatch_workgroups(count.div_ceil(AIR_WORKGROUP), 1, 1);
        }
    }
}

/// The GPU side: cloudlight's instanced quads (`cloudlight::gpu::billboard`'s instance
/// layout, pipeline and pass) drawn by `shaders/render/billboard_clouds.wgsl` into the HDR target with the
/// terrain's depth as a read-only depth attachment (test `Greater`), the LUTs in groups
/// 0 and 1 for the aerial perspective (the precomputed rung), or each particle's air
/// from [`RungBillboardAir`]'s pass in group 2 (the closed form, single scattering).
#[cfg(feature = "gpu")]
use cloudlight::gpu::billboard::{
    BillboardPipelineDescriptor, begin_billboard_pass, billboard_pipeline, draw_billboards,
};

#[cfg(feature = "gpu")]
#[derive(Debug)]
pub(crate) struct BillboardCloudPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    bind_group: wgpu::BindGroup,
    uniform: wgpu::Buffer,
    /// The moonlit air per instance (16 bytes, unread, without a moonlit sky).
    moon_air: wgpu::Buffer,
    /// The air per particle under a rung without tables (`None`: the precomputed rung's
    /// tables in groups 0 and 1).
    rung_air: Option<RungBillboardAir>,
    /// This frame's moonlit air: 0 none, 1 the CPU's per instance, 2 the rung's pass.
    moonlit: u32,
    instances: Option<wgpu::Buffer>,
    count: u32,
}

#[cfg(feature = "gpu")]
impl BillboardCloudPass {
    /// The pipeline for an HDR target of `target` and a depth attachment of `depth`;
    /// the particles' air is the sun's `air` (`crate::gpu::cloud_air::cloud_airs`): the
    /// precomputed rung's tables, read in the vertex stage, or a rung's functions, a
    /// compute pass per particle before the draw (an error without either). A rung's
    /// `moon` (a moonlit sky) gets its pass too; on the precomputed rung the moonlit air
    /// is the CPU's ([`moonlit_air`]).
    pub(crate) fn new(
        device: &wgpu::Device,
        air: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        moon: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        target: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
    ) -> Result<Self, RenderError> {
        use crate::gpu::cloud_air::CloudAir;
        let (module_name, vertex_entry, fragment_entry) = match air {
            Some(CloudAir::Tables(_)) => (
                "render::billboard_clouds",
                "billboard_clouds_vertex",
                "billboard_clouds_fragment",
            ),
            Some(CloudAir::Rung(_)) => (
                "render::billboard_clouds_rung",
                "billboard_clouds_rung_vertex",
                "billboard_clouds_rung_fragment",
            ),
            None => return Err(needs_tables()),
        };
        let rung_air = match air {
            Some(CloudAir::Rung(rung)) => {
                let moon = match moon {
                    Some(CloudAir::Rung(moon)) => Some(moon),
                    _ => None,
                };
                Some(RungBillboardAir::new(device, rung, moon)?)
            }
            _ => None,
        };
        let source = crate::composer().compose_module(module_name)?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render billboard clouds"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = params_layout(device, rung_air.is_some());
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render billboard clouds uniform"),
            size: PARAMS_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let moon_air = moon_air_buffer(device, 16);
        let bind_group = params_bind_group(
            device,
            &layout,
            &uniform,
            &moon_air,
            rung_air.as_ref().map(RungBillboardAir::airs),
        );
        // The rungs' pipeline binds group 2 alone (its air is in group 2).
        let tables = match air {
            Some(CloudAir::Tables(luts)) => {
                [Some(&luts.layouts().uniforms), Some(&luts.layouts().tables)]
            }
            _ => [None, None],
        };
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render billboard clouds"),
            bind_group_layouts: &[tables[0], tables[1], Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = billboard_pipeline(
            device,
            &BillboardPipelineDescriptor {
                label: "render billboard clouds",
                layout: &pipeline_layout,
                module: &module,
                vertex_entry,
                fragment_entry,
                target,
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: depth,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
            },
        );
        Ok(Self {
            pipeline,
            layout,
            bind_group,
            uniform,
            moon_air,
            rung_air,
            moonlit: 0,
            instances: None,
            count: 0,
        })
    }

    /// Selects and sorts the particles for the scene's camera (on the CPU, as the twin
    /// does) and uploads them and the frame's uniform; the instance buffer is kept while
    /// it is large enough.
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        cloud: &PreparedBillboards,
    ) -> Result<(), RenderError> {
        let (camera, particles) = particles(scene, cloud)?;
        let bytes = cloudlight::gpu::billboard::instance_bytes(&particles);
        let limit = device.limits().max_buffer_size;
        let count = u32::try_from(particles.len())
            .ok()
            .filter(|_| bytes.len() as u64 <= limit)
            .ok_or_else(|| RenderError::InvalidParameter {
                field: "clouds.volume.billboards",
                value: format!("{} billboards ({} bytes)", particles.len(), bytes.len()),
                reason: "more instance bytes than the device's max_buffer_size",
            })?;
        if count > 0 {
            let fits = self
                .instances
                .as_ref()
                .is_some_and(|b| b.size() >= bytes.len() as u64);
            if !fits {
                self.instances = Some(device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("render billboard instances"),
                    size: bytes.len() as u64,
                    usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
            }
            if let Some(buffer) = &self.instances {
                queue.write_buffer(buffer, 0, &bytes);
            }
        }
        self.count = count;
        // The moon's air from the rung's pass (a moonlit night under a rung without
        // tables), else the CPU's.
        let rung_moon = self.rung_air.as_ref().is_some_and(|r| r.moon.is_some())
            && cloud.moon.is_some()
            && scene.moon_light().is_some();
        let moon_air = if rung_moon {
            None
        } else {
            moonlit_air(scene, cloud, &particles)?
        };
        self.moonlit = match (rung_moon, &moon_air) {
            (true, _) => 2,
            (false, Some(_)) => 1,
            (false, None) => 0,
        };
        if let Some(air) = &moon_air
            && !air.is_empty()
        {
            let bytes: Vec<u8> = air
                .iter()
                .flat_map(|l| [l[0], l[1], l[2], 0.0])
                .flat_map(f32::to_ne_bytes)
                .collect();
            if self.moon_air.size() < bytes.len() as u64 {
                self.moon_air = moon_air_buffer(device, bytes.len() as u64);
                self.bind_group = self.params_group(device);
            }
            queue.write_buffer(&self.moon_air, 0, &bytes);
        }
        // A rung without tables: the particles' offsets for the air passes.
        if let Some(rung_air) = &mut self.rung_air
            && rung_air.prepare(device, queue, &particles)?
        {
            self.bind_group = self.params_group(device);
        }
        let frame = cloudlight::billboard::ScreenFrame::<f32>::new(&camera, cloud.settings.size);
        queue.write_buffer(
            &self.uniform,
            0,
            &params_bytes(
                &frame,
                cloud.settings.near as f32,
                scene.present.exposure,
                self.moonlit,
            ),
        );
        Ok(())
    }

    /// The draw's group 2 over the current buffers.
    fn params_group(&self, device: &wgpu::Device) -> wgpu::BindGroup {
        params_bind_group(
            device,
            &self.layout,
            &self.uniform,
            &self.moon_air,
            self.rung_air.as_ref().map(RungBillboardAir::airs),
        )
    }

    /// Records one render pass drawing the particles over `target`, depth-tested against
    /// `depth` (read only); under a rung without tables, the particles' air pass first
    /// (compute, untimed), else the precomputed rung's `luts` bound in groups 0 and 1.
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        luts: Option<&atmos::gpu::AtmosphereLuts>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let luts = match &self.rung_air {
            Some(air) => {
                if self.count > 0 {
                    air.encode(encoder, self.count, self.moonlit == 2);
                }
                None
            }
            None => Some(luts.ok_or_else(needs_tables)?),
        };
        let mut pass = begin_billboard_pass(
            encoder,
            "render billboard clouds",
            target,
            Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: None,
                stencil_ops: None,
            }),
            timestamp_writes,
        );
        if let (Some(instances), true) = (&self.instances, self.count > 0) {
            if let Some(luts) = luts {
                pass.set_bind_group(0, luts.uniform_bind_group(), &[]);
                pass.set_bind_group(1, luts.table_bind_group(), &[]);
            }
            pass.set_bind_group(2, &self.bind_group, &[]);
            draw_billboards(&mut pass, &self.pipeline, instances, self.count);
        }
        Ok(())
    }
}
