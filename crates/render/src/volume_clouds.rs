//! A volumetric cloud in a scene (`[clouds.volume]`): `cloudsim` grows a cumulus,
//! `cloudlight` ray-marches it with seed 003's lighting, and this module composites it
//! over the opaque scene (sky and terrain), depth-aware. It owns only the placement,
//! the frames and the compositing; the march is `cloudlight::march` (CPU, the f32 twin)
//! and `cloudlight::gpu::MarchPass` (GPU, `shaders/render/volume_clouds.wgsl` composites).
//!
//! # Frames
//!
//! The render world is `x` east, `y` up, `z` south (metres, the camera's ground at the
//! origin); the cloud's volume frame is east, north, up (cloudsim's `x`, `y`, `z` up):
//! `world_to_enu(x, y, z) = (x, −z, y)`, a rotation, so the march's pixel rays are the
//! scene camera's rays rotated ([`pinhole_camera`]; `tests/volume_clouds.rs` checks them
//! against `atmos::frame::frame_view_direction` within f32 rounding).
//!
//! # Lighting
//!
//! Once per scene, at the grid's centre: the sun's irradiance through the scene's rung
//! (`cloudlight::march::atmos_light`: the atmosphere's sun irradiance × the rung's
//! transmittance toward the sun, zero behind the planet) and the ambient sky (atmos'
//! sky irradiance on a horizontal surface / π). At night — when the scene has a moonlit
//! sky (`PreparedScene::moonlit`: the sun below the horizon, the moon above −2°, the
//! decision that gives the terrain its second, moonlit draw) — the cloud is marched a
//! second time with the moon as its light, passed exactly as the sun's is
//! (`atmos_light` of the moonlit atmosphere, `celestial::MoonLight::atmosphere`, along
//! the moon's direction: [`MoonlitVolume`]), and the two are added, each seen through
//! the air its own light scatters; its shadow map along the moon shades the moonlit
//! terrain. The march is linear in the light, and its transmittance and depth do not
//! depend on it, so the sum is the cloud lit by both.
//!
//! # Compositing
//!
//! Per pixel the march gives the cloud's radiance `L_c`, its transmittance `T_c` and the
//! transmittance-weighted depth `d` of its opacity along the ray. The pixel becomes
//!
//! `L = L_c · T_air(d) + L_air(d) · (1 − T_c) + T_c · L_behind`
//!
//! where `(L_air, T_air)` are the rung's in-scattering and transmittance of the air
//! between the camera and `d` (the same aerial perspective the terrain gets: for the
//! precomputed rung the aerial-perspective LUT, `atmos::lut::drop_in`; otherwise a
//! `SkyQuery::with_max_distance`, `cloudlight::march::apply_aerial_perspective`) and
//! `L_behind` is the sky or terrain already drawn. Both renderers evaluate the air with
//! the same function: atmos' `aerial_perspective` (the aerial-perspective volume within
//! its range, 32 km by default, a march of the tables beyond it), on the CPU
//! `atmos::lut::drop_in::aerial_perspective`, on the GPU its WGSL twin in a compute pass
//! per pixel (`shaders/render/volume_air.wgsl`) whose result the composite reads. The march stops at the
//! terrain: the CPU's at the ray's terrain hit, the GPU's at the distance its terrain
//! depth gives (`shaders/render/volume_distance.wgsl`, then
//! `cloudlight::gpu::MarchPass::prepare_limited`), so a ridge standing in the cloud
//! hides the part behind it and the part in front is drawn. The aerial perspective is
//! the air's up to the cloud's opacity-weighted depth `d`.

use glam::DVec3;

use cloudlight::CloudVolume;
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchResult, MarchSettings, Octaves, PinholeCamera,
};
use cloudlight::shadow_map::OutsideShadowMap;

use crate::air::AirTables;
use crate::scene::{CloudVolumeSection, Scene, SceneError};

/// The largest grid side along east and north (cells).
pub const MAX_HORIZONTAL_CELLS: u32 = 256;
/// The largest grid side along up (cells).
pub const MAX_VERTICAL_CELLS: u32 = 128;
/// The most automaton steps a scene may ask for.
pub const MAX_STEPS: u32 = 100_000;

/// A world direction or offset (x east, y up, z south) in the volume's east/north/up
/// frame.
pub fn world_to_enu(v: [f64; 3]) -> [f64; 3] {
    [v[0], -v[2], v[1]]
}

/// The scene's volumetric cloud, built once per scene.
#[derive(Debug, Clone)]
pub struct PreparedVolume {
    /// The grown density in the east/north/up frame, metres from the camera's ground
    /// point (its minimum corner at `origin`).
    pub volume: CloudVolume,
    /// The march's settings (the scene's view and light steps; midpoint samples).
    pub settings: MarchSettings,
    /// The sun and ambient sky at the grid's centre, east/north/up.
    pub lighting: Lighting<f32>,
    /// The automaton steps grown.
    pub steps: u32,
    /// Cells holding density > 0.
    pub cloudy_cells: usize,
    /// Its shadow on the terrain under the sun (`None` with the sun below 1° or no
    /// terrain in the scene: nothing is computed then).
    pub shadow: Option<CloudShadow>,
    /// The cloud lit by the moon: only in scenes with a moonlit sky (the sun down, the
    /// moon up: `PreparedScene::moonlit`), else `None` and no second march runs.
    pub moon: Option<MoonlitVolume>,
}

/// The volume's second light at night: the moon, as [`PreparedVolume::lighting`] is the
/// sun's (`cloudlight::march::atmos_light` of the moonlit atmosphere along the moon's
/// direction), and the shadow map along it.
#[derive(Debug, Clone)]
pub struct MoonlitVolume {
    /// The moon and the moonlit ambient sky at the grid's centre, east/north/up.
    pub lighting: Lighting<f32>,
    /// Its shadow on the terrain under the moon (`None` with the moon below 1° or no
    /// terrain in the scene).
    pub shadow: Option<CloudShadow>,
}

/// The volume's shadow on the terrain: `cloudlight`'s ground shadow map (seed 000's
/// `cloud_shadow` term; `shadow_map::<f32>`, the twin of `cloudlight::gpu::ShadowMapPass`)
/// on the plane of the grid's base, over the part of it whose sun rays can cross the
/// grid (the footprint swept away from the sun by the grid's height). A terrain point is
/// carried along the sun ray to that plane and the map read there, bilinearly between
/// texel centres (1 outside the map): exact, up to the map's sampling, for terrain
/// below the cloud's base (the ray between the point and the plane is clear air). A
/// peak reaching into the cloud's altitudes ([`CloudShadow::on_terrain`]) is shaded by
/// the part of the column above it only, which the map does not hold: cloudlight's
/// `shadow_depth_above` fade of the column, the clouds' mutual shadows' (`f²`,
/// `render::mutual_shadow`), none above the cloud's top. Both renderers read the same
/// map (the GPU's terrain pass uploads it).
#[derive(Debug, Clone)]
pub struct CloudShadow {
    /// East/north of texel (0, 0)'s corner, metres (the volume's frame).
    pub origin: [f32; 2],
    /// Texel edge, metres.
    pub cell_size: f32,
    /// Texels east × north.
    pub resolution: [u32; 2],
    /// The plane's altitude (the grid's base), metres.
    pub plane: f32,
    /// The casting cloud's top altitude, metres (above `plane`).
    pub top: f32,
    /// Unit direction toward the sun, east/north/up.
    pub to_sun: [f32; 3],
    /// Transmittance toward the sun per texel, east fastest.
    pub values: Vec<f32>,
}

/// The most texels along one side of the cloud's shadow map.
pub const SHADOW_MAP_MAX_SIDE: u32 = 256;
/// Midpoint steps of the shadow map's march per span.
pub const SHADOW_MAP_STEPS: u32 = 32;

impl CloudShadow {
    /// The shadow map of `volume` for the sun along unit `to_sun` (east/north/up), or
    /// `None` when the sun is below 1° (it lights no terrain through a cloud layer then).
    pub fn new(volume: &CloudVolume, to_sun: [f64; 3]) -> Option<Self> {
        if to_sun[2] < 1f64.to_radians().sin() {
            return None;
        }
        let o = volume.origin();
        let size = volume.voxel_size();
        let [nx, ny, nz] = volume.dims();
        let height = f64::from(nz) * size;
        // The footprint, swept by −(horizontal sun) × height / sun_z (capped at 100 km).
        let reach = (height / to_sun[2]).min(1e5);
        let (sx, sy) = (-to_sun[0] * reach, -to_sun[1] * reach);
        let lo = [o[0] + sx.min(0.0), o[1] + sy.min(0.0)];
        let hi = [
            o[0] + f64::from(nx) * size + sx.max(0.0),
            o[1] + f64::from(ny) * size + sy.max(0.0),
        ];
        Self::over(
            volume,
            [lo, hi],
            size,
            [o[2], 0.0],
            o[2] + height,
            to_sun,
            SHADOW_MAP_STEPS,
        )
    }

    /// The shadow map of any density field (the volume's, the shell's: cloudlight's
    /// `shadow_map::<f32, _>`, rows in parallel) on the plane at altitude `plane[0]` (metres) covering the
    /// east/north rectangle `footprint = [lo, hi]` (metres), in square texels no smaller
    /// than `finest` metres and at most [`SHADOW_MAP_MAX_SIDE`] a side, `steps` midpoint
    /// samples per span toward unit `to_sun` (east/north/up). `plane[1]` is the field's
    /// frame's height of altitude 0 (0 for the volume's frame, the planet's radius for
    /// the shell's planet-centred one): the map's texels are at `plane[0] + plane[1]` in
    /// the field's frame and at altitude `plane[0]` in [`CloudShadow::at`]'s. `top` is the
    /// field's highest altitude (metres, above `plane[0]`; [`CloudShadow::on_terrain`]).
    pub fn over<D: cloudlight::DensityField<f32> + Sync + ?Sized>(
        field: &D,
        footprint: [[f64; 2]; 2],
        finest: f64,
        plane: [f64; 2],
        top: f64,
        to_sun: [f64; 3],
        steps: u32,
    ) -> Option<Self> {
        let [lo, hi] = footprint;
        let cell = finest
            .max((hi[0] - lo[0]) / f64::from(SHADOW_MAP_MAX_SIDE))
            .max((hi[1] - lo[1]) / f64::from(SHADOW_MAP_MAX_SIDE));
        let resolution = [
            (((hi[0] - lo[0]) / cell).ceil() as u32).clamp(1, SHADOW_MAP_MAX_SIDE),
            (((hi[1] - lo[1]) / cell).ceil() as u32).clamp(1, SHADOW_MAP_MAX_SIDE),
        ];
        let grid =
            cloudlight::shadow_map::ShadowGrid::new(lo, cell, resolution, plane[0] + plane[1])
                .ok()?;
        let plan = cloudlight::shadow_map::ShadowMapPlan::new(grid, to_sun, steps).ok()?;
        // cloudlight's `shadow_map::<f32, _>`, its rows across threads: the same texels,
        // the same values.
        let values = {
            use cloudlight::shadow_map::{shadow_texel, shadow_texel_centre};
            use rayon::prelude::*;
            let (origin, cell, ground) = (
                grid.origin().map(|c| c as f32),
                grid.cell_size() as f32,
                grid.ground_height() as f32,
            );
            let to_sun = plan.to_sun().map(|c| c as f32);
            let [nx, ny] = resolution;
            (0..ny)
                .into_par_iter()
                .flat_map_iter(|j| {
                    (0..nx).map(move |i| {
                        let p = shadow_texel_centre([i, j], origin, cell, ground);
                        shadow_texel(field, p, to_sun, plan.steps())
                    })
                })
                .collect::<Vec<f32>>()
        };
        Some(Self {
            origin: [lo[0] as f32, lo[1] as f32],
            cell_size: cell as f32,
            resolution,
            plane: plane[0] as f32,
            top: top as f32,
            to_sun: to_sun.map(|c| c as f32),
            values,
        })
    }

    /// The transmittance toward the sun at `point` (east/north/up, metres):
    /// cloudlight's lookup ([`cloudlight::shadow_map::shadow_map_lookup`]: bilinear
    /// between texel centres, 1 outside the map): the whole column above the plane,
    /// wherever `point` lies (the terrain reads [`CloudShadow::on_terrain`]).
    pub fn at(&self, point: [f32; 3]) -> f32 {
        let texel =
            volume_shadow_texel(point, self.to_sun, self.plane, self.origin, self.cell_size);
        cloudlight::shadow_map::shadow_map_lookup(&self.values, self.resolution, texel)
    }

    /// The transmittance toward the light at terrain point `point` (east/north/up,
    /// metres): [`CloudShadow::at`] at or below the plane; above it, `exp(−τ)` of the
    /// part of the column above the point by cloudlight's
    /// [`shadow_depth_above`](cloudlight::shadow_map::shadow_depth_above) (the clouds'
    /// mutual shadows' fade; 1 at and above the cloud's top). The WGSL twin is
    /// `shadow_map_at` in `shaders/render/terrain.wgsl`.
    pub fn on_terrain(&self, point: [f32; 3]) -> f32 {
        if point[2] <= self.plane {
            return self.at(point);
        }
        (-self.depth_at(point)).exp()
    }

    /// The map as a march in a frame whose altitude 0 lies at height `frame_height`
    /// reads it (0 for the volume's frame, the planet's radius for the deck's), the
    /// casting cloud spanning `[plane, top]`: cloudlight's CPU twin of the GPU march's
    /// uniform and values (the GPU renderer fills those from it;
    /// `crate::mutual_shadow`).
    pub fn outside(&self, frame_height: f32) -> OutsideShadowMap<&[f32], f32> {
        OutsideShadowMap {
            origin: self.origin,
            cell_size: self.cell_size,
            resolution: self.resolution,
            plane: self.plane,
            to_light: self.to_sun,
            extent: [self.plane, self.top],
            frame_height,
            values: &self.values,
        }
    }

    /// The casting cloud's optical depth toward the map's light above `point`
    /// (east/north/up about the camera's ground point, `point[2]` the altitude):
    /// cloudlight's `outside_depth` in the volume's frame ([`CloudShadow::at`]'s lookup,
    /// then `shadow_depth_above`).
    pub fn depth_at(&self, point: [f32; 3]) -> f32 {
        self.outside(0.0).outside_depth(point)
    }
}

/// Where `point` (east/north/up, metres) reads the cloud's shadow map: carried along
/// unit `to_sun` to the plane at altitude `plane`, in texel-centre coordinates
/// (`(x − origin)/cell − ½`: texel `(i, j)`'s centre is `(i, j)`). WGSL twin of the same
/// name in `shaders/render/terrain.wgsl`.
pub fn volume_shadow_texel(
    point: [f32; 3],
    to_sun: [f32; 3],
    plane: f32,
    origin: [f32; 2],
    cell_size: f32,
) -> [f32; 2] {
    // cloudlight's lookup, which another cloud's march shares (crate::mutual_shadow).
    cloudlight::shadow_map::shadow_map_texel(point, to_sun, plane, origin, cell_size)
}

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

    /// Grows and lights `[clouds.volume]` (checked by [`Scene::check_volume_cloud`]): by
    /// the sun, and by the moon too when `moonlit` (the scene's moonlit sky) is given.
    pub(crate) fn volume_cloud(
        &self,
        section: &CloudVolumeSection,
        atmosphere: &atmos::Atmosphere,
        model: &(dyn atmos::SkyModel + Send + Sync),
        sun: DVec3,
        shadows_on_terrain: bool,
        moonlit: Option<&crate::scene::prepare::MoonlitSky>,
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
        let lighting = self.volume_light(section, model, atmosphere, sun)?;
        // Only a scene with terrain needs the shadow map.
        let shadow = shadows_on_terrain
            .then(|| CloudShadow::new(&volume, world_to_enu(sun.to_array())))
            .flatten();
        let mut cloud = PreparedVolume {
            volume,
            settings,
            lighting,
            steps: s.steps,
            cloudy_cells,
            shadow,
            moon: None,
        };
        // At night the moon, the terrain's second light, lights the cloud too.
        if let Some(moon) = moonlit {
            cloud.moon = Some(self.moonlit_volume(section, &cloud, moon, shadows_on_terrain)?);
        }
        Ok(cloud)
    }

    /// One light of `[clouds.volume]` at the grid's centre: `cloudlight::march::atmos_light`
    /// of `model` (the sun's rung, or the moon's through the moonlit atmosphere) toward
    /// unit world direction `toward`, east/north/up.
    fn volume_light(
        &self,
        section: &CloudVolumeSection,
        model: &(dyn atmos::SkyModel + Send + Sync),
        atmosphere: &atmos::Atmosphere,
        toward: DVec3,
    ) -> Result<Lighting<f32>, SceneError> {
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

    /// At night the moon, the terrain's second light, lights `cloud` too: its light at the
    /// grid's centre passed as the sun's is (the moonlit atmosphere and rung along the
    /// moon's direction) and, with terrain, its shadow map along the moon.
    fn moonlit_volume(
        &self,
        section: &CloudVolumeSection,
        cloud: &PreparedVolume,
        moon: &crate::scene::prepare::MoonlitSky,
        shadows_on_terrain: bool,
    ) -> Result<MoonlitVolume, SceneError> {
        let toward = moon.direction;
        Ok(MoonlitVolume {
            lighting: self.volume_light(
                section,
                moon.sky_model.as_ref(),
                &moon.atmosphere,
                toward,
            )?,
            shadow: shadows_on_terrain
                .then(|| CloudShadow::new(&cloud.volume, world_to_enu(toward.to_array())))
                .flatten(),
        })
    }
}

/// The scene camera as the march's pinhole camera in the volume's frame: the camera's
/// position (its planet-centred position less the planet radius up) and basis rotated
/// to east/north/up, the horizontal field of view from the vertical one and the aspect,
/// so [`cloudlight::march::pixel_direction`] gives the scene's pixel rays.
pub fn pinhole_camera(
    camera: &atmos::frame::FrameCamera,
    planet_radius: f64,
) -> Result<PinholeCamera, cloudlight::march::MarchError> {
    let p = camera.position.map(f64::from);
    let origin = world_to_enu([p[0], p[1] - planet_radius, p[2]]);
    let forward = world_to_enu(camera.forward.map(f64::from));
    let up = world_to_enu(camera.up.map(f64::from));
    let target = std::array::from_fn(|a| origin[a] + forward[a]);
    let aspect = f64::from(camera.width) / f64::from(camera.height);
    let horizontal_fov = 2.0 * (f64::from(camera.tan_half_fov_y) * aspect).atan();
    PinholeCamera::look_at(origin, target, up, horizontal_fov)
}

/// The march of pixel `pixel` (f32, the twin of `MarchPass`'s pixel): along
/// [`cloudlight::march::pixel_direction`] of `camera` from its origin, up to
/// `max_distance` metres (the terrain's hit; infinite for the sky).
pub fn march_pixel(
    cloud: &PreparedVolume,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    march_pixel_lit(cloud, &cloud.lighting, camera, size, pixel, max_distance)
}

/// [`march_pixel`] lit by `lighting` (the sun's, [`PreparedVolume::lighting`], or the
/// moon's, [`MoonlitVolume::lighting`]): the twin of the GPU's march with that light.
pub fn march_pixel_lit(
    cloud: &PreparedVolume,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    march_field_pixel(
        &cloud.volume,
        &cloud.settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
    )
}

/// The f32 march of pixel `pixel` through any density field (the volume's, the
/// shell's): along [`cloudlight::march::pixel_direction`] of `camera` from its origin,
/// up to `max_distance` metres.
pub(crate) fn march_field_pixel(
    field: &impl cloudlight::DensityField<f32>,
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    march_field_pixel_through(
        field,
        settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
        |_| 0.0,
    )
}

/// [`march_field_pixel`] with the light crossing another cloud too: `outside_depth(p)`
/// its optical depth toward the light above view sample `p` (the field's frame;
/// `cloudlight::march::march_view_lit_through`, `crate::mutual_shadow`).
#[allow(clippy::too_many_arguments)] // march_field_pixel's seven inputs and the hook
pub(crate) fn march_field_pixel_through(
    field: &impl cloudlight::DensityField<f32>,
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
    outside_depth: impl Fn([f32; 3]) -> f32,
) -> MarchResult<f32> {
    let [forward, right, up] = camera.basis().map(|v| v.map(|c| c as f32));
    let tan_half = camera.tan_half(size).map(|t| t as f32);
    let origin = camera.origin().map(|c| c as f32);
    let direction = cloudlight::march::pixel_direction(pixel, size, forward, right, up, tan_half);
    let offset = settings.config().jitter.offset(pixel);
    cloudlight::march::march_view_lit_through(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        max_distance,
        outside_depth,
    )
}

/// Whether a march result is drawn over a scene whose opaque surface is
/// `scene_distance` metres along the ray (infinite for the sky): the cloud has opacity
/// and its depth is nearer. Twin of the test in `volume_clouds.wgsl`.
pub fn cloud_in_front(cloud: &MarchResult<f32>, scene_distance: f32) -> bool {
    cloud.transmittance < 1.0 && cloud.depth < scene_distance
}

/// The cloud seen through the air: `L_c · T_air + L_air · (1 − T_c)` (module docs); the
/// caller adds `T_c · L_behind`. WGSL twin of the same name in
/// `shaders/render/volume_composite.wgsl`.
pub fn cloud_through_air(
    cloud: &MarchResult<f32>,
    air_transmittance: [f32; 3],
    air_radiance: [f32; 3],
) -> [f32; 3] {
    std::array::from_fn(|k| {
        cloud.radiance[k] * air_transmittance[k] + air_radiance[k] * (1.0 - cloud.transmittance)
    })
}

/// The CPU twin of the GPU's composite of a marched cloud (the volume's, the shell's):
/// per pixel `march(lighting, pixel, behind)` up to the terrain's hit
/// (`PixelRadiance::terrain_distance`; the sky: no limit), drawn where it has opacity in
/// front of the scene ([`cloud_in_front`]) as `L_c·T_air + L_air·(1 − T_c) + T_c·L`
/// ([`cloud_through_air`], the air from [`crate::air::air_in_front`] with the sun's `tables`). At
/// night (`moon`: the moon's lighting, light and tables) the march lit by the moon,
/// seen through the moonlit air, is added.
pub(crate) fn composite_marched_cloud(
    scene: &crate::scene::PreparedScene,
    lighting: &Lighting<f32>,
    tables: AirTables<'_>,
    moon: Option<(&Lighting<f32>, &crate::scene::Illuminant<'_>, AirTables<'_>)>,
    march: impl Fn(&Lighting<f32>, [u32; 2], f32) -> MarchResult<f32> + Sync,
    out: &mut [crate::cpu_frame::PixelRadiance],
) -> Result<(), crate::RenderError> {
    let sun = scene.sun_light();
    // One cloud alone: its march is the same function for either light.
    let march = |_: crate::mutual_shadow::Light, lighting: &Lighting<f32>, xy, behind| {
        march(lighting, xy, behind)
    };
    let cloud = MarchedCloud {
        lighting,
        tables,
        moon,
        march: &march,
    };
    crate::cloud_order::draw_seen_clouds(scene.camera.width, out, |xy, behind| {
        cloud.seen(scene, &sun, xy, behind)
    })
}

/// A marched cloud as the CPU composites it (the volume's, the shell's): the sun's
/// lighting and tables, at night the moon's lighting, light and tables, and its march
/// per pixel (`march(light, lighting, pixel, behind)`, up to `behind` metres: `light`
/// says which of the two `lighting` is, so a march can pick what else depends on it,
/// the other cloud's shadow map for that light, `crate::mutual_shadow`).
pub(crate) struct MarchedCloud<'a, M> {
    pub(crate) lighting: &'a Lighting<f32>,
    pub(crate) tables: AirTables<'a>,
    pub(crate) moon: Option<(
        &'a Lighting<f32>,
        &'a crate::scene::Illuminant<'a>,
        AirTables<'a>,
    )>,
    pub(crate) march: &'a M,
}

impl<M> MarchedCloud<'_, M>
where
    M: Fn(crate::mutual_shadow::Light, &Lighting<f32>, [u32; 2], f32) -> MarchResult<f32>,
{
    /// The cloud at pixel `xy` in front of a scene `behind` metres away (`sun`: the
    /// scene's sun light): `None` where it has no opacity in front ([`cloud_in_front`]),
    /// else its light seen through the air ([`cloud_through_air`] with the sun's air
    /// from [`crate::air::air_in_front`], plus the moon's at night), its transmittance and depth;
    /// the caller adds `T_c · L_behind`.
    pub(crate) fn seen(
        &self,
        scene: &crate::scene::PreparedScene,
        sun: &crate::scene::Illuminant<'_>,
        xy: [u32; 2],
        behind: f32,
    ) -> Result<Option<crate::cloud_order::SeenCloud>, crate::RenderError> {
        let march = self.march;
        let result = march(crate::mutual_shadow::Light::Sun, self.lighting, xy, behind);
        if !cloud_in_front(&result, behind) {
            return Ok(None);
        }
        let view = atmos::frame::frame_view_direction(xy, &scene.camera);
        let (transmittance, radiance) =
            crate::air::air_in_front(scene, sun, self.tables, view, result.depth)?;
        let mut seen = cloud_through_air(&result, transmittance, radiance);
        if let Some((moon_lighting, light, moon_tables)) = self.moon {
            let lit = march(crate::mutual_shadow::Light::Moon, moon_lighting, xy, behind);
            let (transmittance, radiance) =
                crate::air::air_in_front(scene, light, moon_tables, view, lit.depth)?;
            let added = cloud_through_air(&lit, transmittance, radiance);
            for (value, a) in seen.iter_mut().zip(added) {
                *value += a;
            }
        }
        Ok(Some(crate::cloud_order::SeenCloud {
            radiance: seen,
            transmittance: result.transmittance,
            depth: result.depth,
        }))
    }
}

/// The composite pass's uniform (layout identical to WGSL `VolumeComposite`).
#[cfg(feature = "gpu")]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeComposite {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Multiplies the cloud's own light (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
    /// The march image's width (pixels).
    pub width: u32,
    /// 1: the moonlit march is added (night), 0: the sun's only.
    pub moonlit: u32,
}

/// The uniform of the distance pass (layout identical to WGSL `VolumeDistanceParams` in
/// `shaders/render/volume_distance.wgsl`).
#[cfg(feature = "gpu")]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeDistanceParams {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding0: u32,
}

/// The uniform of the cloud air passes (layout identical to WGSL `CloudAirParams` in
/// `shaders/render/cloud_air_io.wgsl`, group 2 of every cloud air pass).
#[cfg(feature = "gpu")]
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeAirParams {
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Keeps the struct 16 bytes.
    pub padding: [u32; 2],
}

/// The GPU side: `cloudlight::gpu::MarchPass` over the scene's pixels (prepared per
/// frame with [`pinhole_camera`]; at night a second one lit by the moon) in
/// [`crate::gpu::cloud_composite::CloudComposite`]'s passes: the terrain's depth as a
/// distance per pixel the march stops at, the air in front of the cloud per pixel and
/// light (atmos' `aerial_perspective`, the CPU's function) and the composite render pass
/// (`shaders/render/volume_clouds.wgsl`).
#[cfg(feature = "gpu")]
pub(crate) type VolumeCloudPass =
    crate::gpu::cloud_composite::CloudComposite<cloudlight::gpu::MarchPass>;

#[cfg(feature = "gpu")]
pub(crate) fn buffer_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::BufferBindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

#[cfg(feature = "gpu")]
pub(crate) fn depth_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Depth,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

#[cfg(feature = "gpu")]
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    entry_point: &str,
    layouts: &[Option<&wgpu::BindGroupLayout>],
) -> wgpu::ComputePipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: layouts,
        immediate_size: 0,
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        module,
        entry_point: Some(entry_point),
        compilation_options: Default::default(),
        cache: None,
    })
}

#[cfg(feature = "gpu")]
impl VolumeCloudPass {
    /// The march, air and composite pipelines; `moon_luts`: the moonlit tables when the
    /// scene's cloud is lit by the moon too ([`PreparedVolume::moon`]).
    pub(crate) fn new_volume(
        device: &wgpu::Device,
        luts: crate::gpu::cloud_air::CloudAir<'_>,
        moon_luts: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        Self::new(
            device,
            "volume",
            "clouds.volume",
            luts,
            moon_luts,
            target,
            || Ok(cloudlight::gpu::MarchPass::new(device)?),
        )
    }

    /// The frame's marches (the scene camera as a pinhole camera in the volume's frame,
    /// one ray per pixel up to `distance`'s buffer; the moon's at night), the air passes'
    /// and the composite's uniforms and bind groups.
    pub(crate) fn prepare_volume(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        cloud: &PreparedVolume,
        distance: &crate::gpu::cloud_composite::CloudDistance,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), crate::RenderError> {
        let camera = &scene.camera;
        let pinhole = pinhole_camera(camera, scene.atmosphere.planet_radius)?;
        let size = [camera.width, camera.height];
        let moon = cloud.moon.as_ref().map(|moon| &moon.lighting);
        self.prepare(
            device,
            queue,
            scene,
            distance,
            depth_view,
            &cloud.lighting,
            moon,
            |march, light, lighting, distances, kept| {
                // Lit through the deck's shadow map for this light (crate::mutual_shadow),
                // its values uploaded once and kept while unchanged.
                let deck = scene
                    .shell_cloud
                    .as_ref()
                    .and_then(|shell| crate::mutual_shadow::deck_on_volume(shell, light));
                let deck = kept.upload(device, queue, deck);
                // The march stops at the terrain: a ridge cuts the cloud where it stands.
                Ok(march.prepare_lit_through(
                    device,
                    queue,
                    &cloud.volume,
                    &pinhole,
                    size,
                    &cloud.settings,
                    lighting,
                    Some(distances),
                    deck.map(|d| crate::mutual_shadow::outside(d, 0.0)).as_ref(),
                )?)
            },
        )
    }
}

/// What `skyscape explain` says of the moonlit march (a pass of the GPU renderer, and
/// the second march of the CPU's): run when the scene's cloud is lit by the moon.
pub fn moonlit_march_plan(scene: &crate::scene::PreparedScene) -> Result<String, String> {
    let Some(cloud) = &scene.volume_cloud else {
        return Err("no [clouds.volume] to march (none, or draw = \"billboards\")".into());
    };
    match (&cloud.moon, &scene.moonlit) {
        (Some(moon), Some(sky)) => Ok(format!(
            "the [clouds.volume] cloud marched again lit by the moon ({:.1}° up; the terrain's \
             moonlit draw's light: celestial's MoonLight through atmos), added through the \
             moonlit air; {}",
            sky.direction.y.clamp(-1.0, 1.0).asin().to_degrees(),
            if moon.shadow.is_some() {
                "its shadow map along the moon shades the moonlit terrain"
            } else {
                "no shadow map (no terrain, or the moon below 1°)"
            }
        )),
        _ => Err(
            "the moon does not light the scene (no [time], or the sun up or the moon \
                  below −2°, as for the terrain's moonlit draw): the sun's march only"
                .into(),
        ),
    }
}
