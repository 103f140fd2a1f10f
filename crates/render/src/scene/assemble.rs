//! From a parsed [`Scene`] to a [`PreparedScene`]: the `atmos` atmosphere, rung,
//! camera and display constants, the `terrain` heightfield with its normal and horizon
//! maps, and each cloud kind's preparation. Every value is checked by the crate that
//! owns it; this module only says which scene key a rejected value came from.

use glam::DVec3;

use super::layer_frame::cloud_layers_at;
use super::prepare::*;
use super::{PrepareCache, Rung, Scene, SceneError};

/// What the celestial sky made of the scene's cloud layers and visibility.
#[derive(Default)]
struct SkyClouds {
    /// The layers drawn, farthest first, anchored to the world.
    cloud_layers: Vec<celestial::clouds::CloudLayerUniforms>,
    /// Each layer's wind drift (m, east and north), in the file's order.
    drift: Vec<[f64; 2]>,
    /// The fog of the layers the camera is in or near.
    in_cloud_fog: Option<celestial::sky::InCloudFog>,
    /// SGSky's effective visibility at the camera (with `[visibility]`).
    effective_m: Option<f64>,
}
use crate::present::PresentParameters;

fn deg(value: f64) -> String {
    format!("{value}°")
}
pub(super) fn metres(value: f64) -> String {
    format!("{value} m")
}
fn triple(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

impl Scene {
    /// Validates the scene and builds its atmosphere, rung, camera and terrain.
    pub fn prepare(&self) -> Result<PreparedScene, SceneError> {
        self.prepare_with(true, &PrepareCache::new(), &mut |_| {})
    }

    /// [`Scene::prepare`] taking what `cache` kept from earlier preparations (an
    /// animation's frames, a viewer's) where its inputs did not change, and keeping what
    /// it builds.
    pub fn prepare_cached(&self, cache: &PrepareCache) -> Result<PreparedScene, SceneError> {
        self.prepare_with(true, cache, &mut |_| {})
    }

    /// [`Scene::prepare_cached`] (`for_gpu`: [`Scene::prepare_for_gpu`]) calling `stage`
    /// with each step's name as the step begins (the checks, the atmosphere's tables, the
    /// terrain and its horizon maps, the sky objects and cloud layers, the moonlit sky,
    /// each cloud), for a caller to show progress and time the steps.
    pub fn prepare_in_stages(
        &self,
        for_gpu: bool,
        cache: &PrepareCache,
        stage: &mut dyn FnMut(&'static str),
    ) -> Result<PreparedScene, SceneError> {
        self.prepare_with(!for_gpu, cache, stage)
    }

    /// [`Scene::prepare`] for the GPU renderer: the `[clouds.shell]` deck's shadow maps
    /// are left as grids for the GPU to bake (`crate::shell_clouds::shell_shadow_unbaked`);
    /// the CPU renderer refuses such a scene until
    /// [`PreparedScene::bake_shell_shadow_on_cpu`].
    pub fn prepare_for_gpu(&self) -> Result<PreparedScene, SceneError> {
        self.prepare_with(false, &PrepareCache::new(), &mut |_| {})
    }

    /// [`Scene::prepare_for_gpu`] with [`Scene::prepare_cached`]'s `cache`.
    pub fn prepare_for_gpu_cached(
        &self,
        cache: &PrepareCache,
    ) -> Result<PreparedScene, SceneError> {
        self.prepare_with(false, cache, &mut |_| {})
    }

    fn prepare_with(
        &self,
        cpu_shell_shadow: bool,
        cache: &PrepareCache,
        stage: &mut dyn FnMut(&'static str),
    ) -> Result<PreparedScene, SceneError> {
        stage("checking the scene");
        let (atmosphere, mut visibility) = self.atmosphere_and_visibility()?;
        let file = &self.file;

        let (sun, mut sky) = self.sun(cache)?;

        let out = &file.output;
        for (key, value) in [("width", out.width), ("height", out.height)] {
            if value == 0 || value > MAX_OUTPUT_SIDE {
                return Err(self.invalid(
                    &["output", key],
                    format!("{value} pixels"),
                    format!("must be in 1..={MAX_OUTPUT_SIDE}"),
                ));
            }
        }
        match out.projection {
            crate::projection::Projection::Cubemap if out.width != 6 * out.height => {
                return Err(self.invalid(
                    &["output", "width"],
                    format!("{} pixels", out.width),
                    format!(
                        "a cubemap strip is six square faces: width must be 6 × height = {}",
                        6 * u64::from(out.height)
                    ),
                ));
            }
            crate::projection::Projection::Fisheye
                if !(out.fisheye_fov_deg > 0.0 && out.fisheye_fov_deg <= 360.0) =>
            {
                return Err(self.invalid(
                    &["output", "fisheye_fov_deg"],
                    deg(out.fisheye_fov_deg),
                    "must be in (0°, 360°]".into(),
                ));
            }
            _ => {}
        }
        let pixels = u64::from(out.width) * u64::from(out.height);
        if pixels > MAX_OUTPUT_PIXELS {
            return Err(self.invalid(
                &["output", "height"],
                format!("{} pixels ({}×{})", pixels, out.width, out.height),
                format!("width × height must be ≤ {MAX_OUTPUT_PIXELS}"),
            ));
        }
        let mut present = PresentParameters::new(&atmosphere, out.exposure, out.dither_seed)
            .map(|p| p.with_display_transform(out.display_transform))
            .map_err(|e| {
                self.invalid(
                    &["output", "exposure"],
                    out.exposure.to_string(),
                    e.to_string(),
                )
            })?;

        let cam = &file.camera;
        let (forward, look_key) = match (cam.look_at, cam.look_direction) {
            (Some(target), None) => (
                DVec3::from_array(target) - DVec3::from_array(cam.position),
                "look_at",
            ),
            (None, Some(direction)) => (DVec3::from_array(direction), "look_direction"),
            (Some(target), Some(_)) => {
                return Err(self.invalid(
                    &["camera", "look_at"],
                    triple(target),
                    "give either look_at or look_direction, not both".into(),
                ));
            }
            (None, None) => {
                return Err(self.invalid(
                    &["camera", "position"],
                    triple(cam.position),
                    "the camera needs look_at or look_direction".into(),
                ));
            }
        };
        let look_value = triple(cam.look_at.or(cam.look_direction).unwrap_or_default());
        let planet = atmosphere.planet_radius;
        let camera_position = DVec3::from_array(cam.position) + DVec3::new(0.0, planet, 0.0);
        let camera = atmos::frame::FrameCamera::look_at(
            camera_position,
            forward,
            up_hint(forward),
            cam.vertical_fov_deg.to_radians(),
            out.width,
            out.height,
            sun,
            None,
        )
        .map_err(|e| {
            let field = atmos_field(&e);
            if field.starts_with("fov_y") {
                self.atmos_error(
                    &["camera", "vertical_fov_deg"],
                    deg(cam.vertical_fov_deg),
                    e,
                )
            } else if field.starts_with("position") {
                self.atmos_error(&["camera", "position"], triple(cam.position), e)
            } else {
                self.atmos_error(&["camera", look_key], look_value.clone(), e)
            }
        })?;
        // The viewer must be where atmos accepts one (not deep under the ground).
        atmos::SkyQuery::new(planet, camera_position, DVec3::Y, sun)
            .map_err(|e| self.atmos_error(&["camera", "position"], triple(cam.position), e))?;
        if !(cam.near.is_finite() && cam.near >= 0.0) {
            return Err(self.invalid(
                &["camera", "near"],
                metres(cam.near),
                "must be finite and ≥ 0 m".into(),
            ));
        }
        if cam.far.is_nan() || cam.far <= cam.near {
            return Err(self.invalid(
                &["camera", "far"],
                metres(cam.far),
                format!("must be > near ({} m)", cam.near),
            ));
        }

        if let Some(section) = file.clouds.as_ref().and_then(|c| c.volume.as_ref()) {
            self.check_volume_cloud(section)?;
            self.check_billboard_cloud(section)?;
        }
        if let Some(section) = file.clouds.as_ref().and_then(|c| c.shell.as_ref()) {
            self.check_shell_cloud(section, &atmosphere)?;
        }
        // The expensive parts last, once every cheap check has passed.
        stage("atmosphere tables");
        let (sky_model, segment_model, precomputed) = self.models(&atmosphere, cache)?;
        stage("terrain and horizon maps");
        let terrain = self.cached_terrain(cache)?;
        stage("sky objects and cloud layers");
        let (sky_objects, clouds) = match sky.as_mut() {
            Some(sky) => {
                // celestial's repaint queries the sky at scattered directions.
                let model = crate::light::scattered_queries(&*sky_model, precomputed.as_deref());
                self.sky_objects_and_clouds(sky, &*model, forward, cam, out)?
            }
            None => {
                if let Some(clouds) = file.clouds.as_ref().filter(|c| !c.layers.is_empty()) {
                    return Err(self.invalid(
                        &["clouds", "layers"],
                        format!("{} layers", clouds.layers.len()),
                        "cloud layers are lit by celestial's sky, placed by [time] (a date, \
                         time and place): give [time] instead of [sun]"
                            .into(),
                    ));
                }
                (None, SkyClouds::default())
            }
        };
        let SkyClouds {
            cloud_layers,
            drift: cloud_layer_drift_m,
            in_cloud_fog,
            effective_m,
        } = clouds;
        if let Some(visibility) = visibility.as_mut() {
            visibility.effective_m = effective_m;
        }
        stage("moonlit sky");
        let other_lights: Vec<LightSky> = match &sky {
            Some(sky) => self.moonlit_sky(sky, &atmosphere, sun, &cloud_layers, cache)?,
            None => None,
        }
        .into_iter()
        .collect();
        // Every light the clouds are lit by, the sun first (PreparedScene::lights' order).
        let lights: Vec<crate::light::LightSource<'_>> =
            std::iter::once(crate::light::LightSource {
                name: "sun",
                atmosphere: &atmosphere,
                sky_model: &*sky_model,
                direction: sun,
                precomputed: precomputed.as_deref(),
            })
            .chain(other_lights.iter().map(LightSky::source))
            .collect();
        stage("clouds");
        let billboard_cloud = match file.clouds.as_ref().and_then(|c| c.volume.as_ref()) {
            Some(section) if section.draw == crate::billboard_clouds::VolumeDraw::Billboards => {
                Some(self.billboard_cloud(section, &lights, cam.near, terrain.is_some())?)
            }
            _ => None,
        };
        let volume_cloud = match file
            .clouds
            .as_ref()
            .and_then(|c| c.volume.as_ref())
            .filter(|v| v.draw == crate::billboard_clouds::VolumeDraw::March)
        {
            Some(section) => Some(self.volume_cloud(
                section,
                &lights,
                // Its shadow map shades the terrain and the deck (crate::mutual_shadow).
                terrain.is_some() || file.clouds.as_ref().is_some_and(|c| c.shell.is_some()),
            )?),
            None => None,
        };
        let shell_cloud = match file.clouds.as_ref().and_then(|c| c.shell.as_ref()) {
            Some(section) => Some(self.shell_cloud(
                section,
                &lights,
                camera_position,
                terrain.as_ref(),
                cpu_shell_shadow,
                volume_cloud.as_ref().map(|v| &v.volume),
            )?),
            None => None,
        };
        if sky_objects.is_some() {
            // celestial draws the sun's limb-darkened disc: atmos' uniform one is off.
            present.sun_disc_radiance = [0.0; 3];
        }
        Ok(PreparedScene {
            atmosphere,
            rung: file.atmosphere.rung,
            sky_model,
            segment_model,
            camera,
            camera_position,
            sun,
            present,
            near: cam.near,
            far: cam.far,
            terrain,
            precomputed,
            sky_objects,
            cloud_layers,
            cloud_layer_drift_m,
            in_cloud_fog,
            visibility,
            viewer_radius: planet + cam.position[1],
            billboard_cloud,
            other_lights,
            volume_cloud,
            shell_cloud,
            celestial_sky: sky,
        })
    }

    /// The moonlit sky (celestial's `MoonLight`: the same atmosphere lit by the moon's
    /// irradiance from the moon's direction, any rung), when it can matter: the sun
    /// below the horizon and the moon above −2° (in daylight it is ~10⁻⁶ of the sky).
    fn moonlit_sky(
        &self,
        sky: &celestial::sky::Sky,
        atmosphere: &atmos::Atmosphere,
        sun: DVec3,
        cloud_layers: &[celestial::clouds::CloudLayerUniforms],
        cache: &PrepareCache,
    ) -> Result<Option<LightSky>, SceneError> {
        let Some(placement) = sky.placement() else {
            return Ok(None);
        };
        let light = &placement.moon_light;
        let [east, north, up] = light.direction;
        if sun.y >= 0.0 || up < (-2f64).to_radians().sin() {
            return Ok(None);
        }
        let moon_atmosphere = light.atmosphere(atmosphere);
        let (sky_model, segment_model, precomputed) = self.models(&moon_atmosphere, cache)?;
        // The layers' light is in their east–north–up frame, as the moon's direction.
        let toward_moon = light.direction.map(|c| c as f32);
        let cloud_layers = cloud_layers
            .iter()
            .map(|layer| celestial::clouds::CloudLayerUniforms {
                sun_direction: toward_moon,
                ..*layer
            })
            .collect();
        Ok(Some(LightSky {
            name: "moon",
            atmosphere: moon_atmosphere,
            direction: DVec3::new(east, up, -north),
            sky_model,
            segment_model,
            precomputed,
            cloud_layers,
        }))
    }

    /// The sun's world direction from `[sun]` or from `[time]` (then also the placed
    /// `celestial` sky, when `[sky_objects]` draws it).
    fn sun(
        &self,
        cache: &PrepareCache,
    ) -> Result<(DVec3, Option<celestial::sky::Sky>), SceneError> {
        let file = &self.file;
        match (&file.sun, &file.time) {
            (Some(section), None) => {
                if section.elevation_deg.is_nan() || section.elevation_deg.abs() > 90.0 {
                    return Err(self.invalid(
                        &["sun", "elevation_deg"],
                        deg(section.elevation_deg),
                        "must be in [−90°, 90°]".into(),
                    ));
                }
                if !section.azimuth_deg.is_finite() {
                    return Err(self.invalid(
                        &["sun", "azimuth_deg"],
                        deg(section.azimuth_deg),
                        "must be finite (degrees clockwise from north)".into(),
                    ));
                }
                if file.sky_objects.is_some_and(|o| o.enabled) {
                    return Err(self.invalid(
                        &["sky_objects", "enabled"],
                        "true".into(),
                        "the sky objects are placed by [time] (a date, time and place), \
                         not by an explicit [sun]"
                            .into(),
                    ));
                }
                let sun = world_direction(
                    section.elevation_deg.to_radians(),
                    section.azimuth_deg.to_radians(),
                );
                Ok((sun, None))
            }
            (None, Some(time)) => {
                let celestial = |key: &'static str, value: String| {
                    move |e| self.celestial_error(&["time", key], value, e)
                };
                let mut instant = celestial::Instant::parse(&time.utc)
                    .map_err(celestial("utc", format!("\"{}\"", time.utc)))?;
                if time.offset_s != 0.0 {
                    let offset =
                        chrono::Duration::try_milliseconds((time.offset_s * 1e3).round() as i64)
                            .filter(|_| time.offset_s.is_finite())
                            .ok_or_else(|| {
                                self.invalid(
                                    &["time", "offset_s"],
                                    format!("{} s", time.offset_s),
                                    "must be a finite number of seconds".into(),
                                )
                            })?;
                    instant = celestial::Instant::from_utc(instant.utc() + offset)
                        .map_err(celestial("offset_s", format!("{} s", time.offset_s)))?;
                }
                let observer = celestial::Observer::new(
                    celestial::Angle::from_degrees(time.latitude_deg),
                    celestial::Angle::from_degrees(time.longitude_deg),
                    file.camera.position[1],
                )
                .map_err(|e| {
                    let (key, value) = match e.to_string() {
                        m if m.contains("latitude") => ("latitude_deg", deg(time.latitude_deg)),
                        m if m.contains("longitude") => ("longitude_deg", deg(time.longitude_deg)),
                        _ => ("utc", time.utc.clone()),
                    };
                    self.celestial_error(&["time", key], value, e)
                })?;
                let options = celestial::sky::SkyOptions {
                    star_limit_magnitude: file.sky_objects.and_then(|o| o.star_limit_magnitude),
                    ..Default::default()
                };
                let atmosphere = self.atmosphere()?;
                let key = super::cache::SkyKey {
                    atmosphere: atmosphere.clone(),
                    options: options.clone(),
                };
                let mut sky = cache.sky(key, || {
                    celestial::sky::Sky::build(atmosphere, options).map_err(|e| {
                        let value = file
                            .sky_objects
                            .and_then(|o| o.star_limit_magnitude)
                            .map_or_else(|| "(default)".to_owned(), |m| m.to_string());
                        self.celestial_error(&["sky_objects", "star_limit_magnitude"], value, e)
                    })
                })?;
                let placement = sky
                    .reposition(&observer, &instant)
                    .map_err(celestial("utc", format!("\"{}\"", time.utc)))?;
                let sun = world_direction(
                    placement.sun.airless.elevation.radians(),
                    placement.sun.airless.azimuth.radians(),
                );
                Ok((sun, Some(sky)))
            }
            (Some(section), Some(time)) => Err(self.invalid(
                &["time", "utc"],
                format!("\"{}\"", time.utc),
                format!(
                    "give either [time] or [sun] (elevation {}°), not both",
                    section.elevation_deg
                ),
            )),
            (None, None) => Err(self.invalid(
                &["sun"],
                "(missing)".into(),
                "the scene needs a sun: a [sun] section (elevation_deg, azimuth_deg) or a \
                 [time] section (utc, latitude_deg, longitude_deg)"
                    .into(),
            )),
        }
    }

    /// The sky objects of the placed `sky` (when drawn) and its cloud layers, painted
    /// from `model`, seen by the scene's camera (the same pixel rays in celestial's
    /// east/north/up frame), the objects depth-tested against reverse-z terrain.
    fn sky_objects_and_clouds(
        &self,
        sky: &mut celestial::sky::Sky,
        model: &(dyn atmos::SkyModel + Send + Sync),
        forward: DVec3,
        cam: &super::CameraSection,
        out: &super::OutputSection,
    ) -> Result<(Option<celestial::objects::SkyObjectsFrame>, SkyClouds), SceneError> {
        let at_time = |e| {
            self.celestial_error(
                &["time", "utc"],
                self.file
                    .time
                    .as_ref()
                    .map_or_else(String::new, |t| format!("\"{}\"", t.utc)),
                e,
            )
        };
        let drift = self.add_cloud_layers(sky)?;
        sky.repaint(model).map_err(at_time)?;
        let position = DVec3::from_array(cam.position);
        let cloud_layers = cloud_layers_at(sky, position, &drift).map_err(at_time)?;
        let in_cloud_fog = sky.in_cloud_fog(position.y).map_err(at_time)?;
        // SGSky's effective visibility at the camera, for `explain`; the sky keeps the
        // clear air's, which the layers' own fog uses (the in-cloud fog is drawn per view).
        let effective_m = match self.file.visibility {
            Some(section) => {
                let closed_in = sky.modify_vis(position.y, 0.0).map_err(at_time)?;
                sky.set_visibility(section.distance_m).map_err(at_time)?;
                Some(closed_in)
            }
            None => None,
        };
        let clouds = SkyClouds {
            cloud_layers,
            drift,
            in_cloud_fog,
            effective_m,
        };
        if !self.file.sky_objects.is_none_or(|o| o.enabled) {
            return Ok((None, clouds));
        }
        // World x east, y up, z south → east, north, up: a rotation, so the pixel rays
        // are the scene camera's.
        let enu = |v: DVec3| [v.x, -v.z, v.y];
        let camera = sky
            .camera(
                enu(forward),
                enu(up_hint(forward)),
                celestial::Angle::from_degrees(cam.vertical_fov_deg),
                out.width,
                out.height,
            )
            .map_err(at_time)?;
        let mut frame = sky.sky_objects_frame(&camera).map_err(at_time)?;
        // Reverse z: the sky is at depth 0, terrain in front of it hides the objects.
        frame.uniforms.far_depth = 0.0;
        Ok((Some(frame), clouds))
    }

    /// Earth's atmosphere with the scene's overrides and `[visibility]`'s aerosol.
    fn atmosphere(&self) -> Result<atmos::Atmosphere, SceneError> {
        Ok(self.atmosphere_and_visibility()?.0)
    }

    /// Earth's atmosphere with the scene's overrides, validated by atmos, then with
    /// `[visibility]`'s aerosol (and what it made of the scene).
    fn atmosphere_and_visibility(
        &self,
    ) -> Result<
        (
            atmos::Atmosphere,
            Option<super::layer_frame::PreparedVisibility>,
        ),
        SceneError,
    > {
        let section = &self.file.atmosphere;
        let mut atmosphere = atmos::Atmosphere::earth();
        if let Some(scale) = section.mie_scale {
            atmosphere.mie_scattering = atmosphere.mie_scattering.map(|b| b * scale);
            atmosphere.mie_extinction = atmosphere.mie_extinction.map(|b| b * scale);
        }
        if let Some(g) = section.mie_g {
            atmosphere.mie_g = g;
        }
        if let Some(h) = section.rayleigh_scale_height {
            atmosphere.rayleigh_scale_height = h;
        }
        if let Some(h) = section.mie_scale_height {
            atmosphere.mie_scale_height = h;
        }
        if let Some(albedo) = section.ground_albedo {
            atmosphere.ground_albedo = [albedo; 3];
        }
        atmosphere.validate().map_err(|e| {
            let field = atmos_field(&e);
            let (key, value) =
                if field.starts_with("mie_scattering") || field.starts_with("mie_extinction") {
                    ("mie_scale", section.mie_scale)
                } else if field.starts_with("mie_g") {
                    ("mie_g", section.mie_g)
                } else if field.starts_with("rayleigh_scale_height") {
                    ("rayleigh_scale_height", section.rayleigh_scale_height)
                } else if field.starts_with("mie_scale_height") {
                    ("mie_scale_height", section.mie_scale_height)
                } else {
                    ("ground_albedo", section.ground_albedo)
                };
            let value = value.map_or_else(|| "(default)".to_owned(), |v| v.to_string());
            self.atmos_error(&["atmosphere", key], value, e)
        })?;
        self.with_visibility(atmosphere)
    }

    /// The rung's models (sky, finite segments); the precomputed rung's static tables
    /// from `cache` when it holds them for this air.
    #[allow(clippy::type_complexity)]
    fn models(
        &self,
        atmosphere: &atmos::Atmosphere,
        cache: &PrepareCache,
    ) -> Result<
        (
            SharedSkyModel,
            SharedSkyModel,
            Option<std::sync::Arc<atmos::lut::PrecomputedSky>>,
        ),
        SceneError,
    > {
        use atmos::closed_form_sky::ClosedFormSky;
        let rung = self.file.atmosphere.rung;
        let e = |e| self.atmos_error(&["atmosphere", "rung"], format!("\"{}\"", rung.name()), e);
        let model: SharedSkyModel = match rung {
            Rung::Dome => {
                let dome = celestial::dome_sky::SgskyDomeSky::new(
                    ClosedFormSky::new(atmosphere).map_err(e)?,
                    atmosphere,
                    celestial::dome::DomeColouring::SeedWeights,
                )
                .map_err(|error| {
                    self.invalid(
                        &["atmosphere", "rung"],
                        "\"dome\"".to_owned(),
                        error.to_string(),
                    )
                })?;
                let per_pixel = Box::new(ClosedFormSky::new(atmosphere).map_err(e)?);
                return Ok((Box::new(dome), per_pixel, None));
            }
            Rung::ClosedForm => Box::new(ClosedFormSky::new(atmosphere).map_err(e)?),
            Rung::ClosedFormVertex => {
                let dome = atmos::dome::DomeInterpolated::new(
                    ClosedFormSky::new(atmosphere).map_err(e)?,
                    DOME,
                    atmosphere,
                )
                .map_err(e)?;
                let per_pixel = Box::new(ClosedFormSky::new(atmosphere).map_err(e)?);
                return Ok((Box::new(dome), per_pixel, None));
            }
            Rung::Single => Box::new(
                atmos::single_scattering::SingleScatteringSky::new(atmosphere, Default::default())
                    .map_err(e)?,
            ),
            Rung::Precomputed => {
                let luts = cache
                    .static_luts(atmosphere, &Default::default())
                    .map_err(e)?;
                let sky = std::sync::Arc::new(atmos::lut::PrecomputedSky::from_static_luts(luts));
                let model: SharedSkyModel = Box::new(sky.clone());
                let shared = std::sync::Arc::new(model);
                return Ok((Box::new(shared.clone()), Box::new(shared), Some(sky)));
            }
            Rung::Reference => Box::new(
                atmos::reference::ReferenceSky::new(atmosphere, Default::default()).map_err(e)?,
            ),
            Rung::ReferenceSpectral => Box::new(
                atmos::reference::SpectralReferenceSky::new(atmosphere, Default::default())
                    .map_err(e)?,
            ),
        };
        // One model for both roles: share it through a reference-counted wrapper.
        let shared = std::sync::Arc::new(model);
        Ok((Box::new(shared.clone()), Box::new(shared), None))
    }
}

/// The field an atmos error names: its message's first `quoted` name (every
/// parameter variant of `AtmosError` starts with it), or "".
fn atmos_field(error: &atmos::AtmosError) -> String {
    error
        .to_string()
        .split('`')
        .nth(1)
        .unwrap_or_default()
        .to_owned()
}
