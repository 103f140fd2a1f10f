//! What the renderers draw: a scene prepared ([`PreparedScene`]: the `atmos`
//! atmosphere, rung and camera, the display constants, the `terrain` heightfield with
//! its normal and horizon maps, the clouds and the lights), built by
//! `Scene::prepare` (`super::assemble`).

use glam::DVec3;
use terrain::{Heightfield, NormalMap};

use super::Rung;
pub use super::layer_frame::{PreparedVisibility, cloud_layers_at};
use crate::present::PresentParameters;
use crate::terrain_shading::AlbedoRamp;

/// The most pixels per side an output may have, checked before anything is allocated.
pub const MAX_OUTPUT_SIDE: u32 = 16_384;

/// The most pixels an output may have (the CPU renderer holds 20 bytes per pixel:
/// 1.3 GiB at this size), checked before anything is allocated.
pub const MAX_OUTPUT_PIXELS: u64 = 1 << 26;

pub use super::DOME;

/// A sky model the renderer can share across threads.
pub type SharedSkyModel = Box<dyn atmos::SkyModel + Send + Sync>;

/// The terrain of a prepared scene: heights, normals, horizon maps and albedo.
#[derive(Debug, Clone)]
pub struct PreparedTerrain {
    /// The heightfield, centred on the world origin (columns east, rows south).
    pub heightfield: Heightfield,
    /// Its normals (east, north, up).
    pub normals: NormalMap,
    /// Its self-shadow maps.
    pub horizon: HorizonMaps,
    /// Its colour by the ramp (`materials = "ramp"` without a colour texture).
    pub albedo: AlbedoRamp,
    /// The procedural materials (`materials = "procedural"`), `None` for the ramp.
    pub materials: Option<crate::terrain_materials::MaterialParams<f32>>,
    /// The colour texture (`[terrain.colour]`): the albedo with the ramp, the grass's
    /// with the procedural materials.
    pub colour: Option<std::sync::Arc<crate::terrain_colour::ColourTexture>>,
    /// Where its aerial perspective is evaluated (`[terrain] aerial_perspective`).
    pub aerial_perspective: crate::aerial_vertex::AerialPerspective,
}

/// The horizon maps of the scene's variant.
#[derive(Debug, Clone)]
pub enum HorizonMaps {
    /// Hoffman and Preetham 2002's pair.
    EastWest(terrain::EastWestHorizon),
    /// `N` azimuths.
    Azimuths(terrain::AzimuthHorizonMaps),
}

impl PreparedTerrain {
    /// Metres from the map's corner texel (0, 0) to its centre, along x (east) and z
    /// (south): world position + this offset = map position.
    pub fn map_offset(&self) -> [f64; 2] {
        let hf = &self.heightfield;
        [
            0.5 * (hf.width() - 1) as f64 * hf.spacing(),
            0.5 * (hf.height() - 1) as f64 * hf.spacing(),
        ]
    }
}

/// Everything a renderer needs, validated.
pub struct PreparedScene {
    /// The atmosphere (Earth with the scene's overrides).
    pub atmosphere: atmos::Atmosphere,
    /// The rung.
    pub rung: Rung,
    /// The model that renders the sky (view rays to the ground or space).
    pub sky_model: SharedSkyModel,
    /// The model for finite segments (aerial perspective, the sun's path from a
    /// terrain point): the sky model, except for the per-vertex dome, whose grid is
    /// built per viewpoint — Hoffman and Preetham 2002 evaluates terrain per vertex, i.e. at the point,
    /// which a ray caster does per pixel with the closed form itself.
    pub segment_model: SharedSkyModel,
    /// The camera (planet-centred position, frame size, sun).
    pub camera: atmos::frame::FrameCamera,
    /// The camera's planet-centred position, f64.
    pub camera_position: DVec3,
    /// Unit direction toward the sun (world frame = planet frame axes).
    pub sun: DVec3,
    /// Display constants (sun disc, exposure, dither).
    pub present: PresentParameters,
    /// Terrain range along a view ray, metres.
    pub near: f64,
    /// See `near`.
    pub far: f64,
    /// The terrain, if any.
    pub terrain: Option<PreparedTerrain>,
    /// The precomputed rung's CPU tables, when the scene uses it: the CPU renderer then
    /// draws with the twins of the GPU's passes (`atmos::lut::drop_in`), so the two
    /// images agree pixel for pixel.
    pub precomputed: Option<std::sync::Arc<atmos::lut::PrecomputedSky>>,
    /// The sun's disc, moon, planets and stars (`celestial`), when `[time]` places them
    /// and `[sky_objects]` does not turn them off: drawn over the sky where no terrain
    /// is in front (the sky pass then draws no disc of its own).
    pub sky_objects: Option<celestial::objects::SkyObjectsFrame>,
    /// The scene's cloud layers lit for this frame, farthest first (a layer the viewer
    /// is inside is left out: celestial models it as closed-in visibility).
    pub cloud_layers: Vec<celestial::clouds::CloudLayerUniforms>,
    /// Each `[[clouds.layers]]` layer's wind drift (m, east and north: −wind ×
    /// `[time] offset_s`), in the file's order: with the camera's east and north, the
    /// layers' texture offset ([`super::layer_frame::cloud_layers_at`]).
    pub cloud_layer_drift_m: Vec<[f64; 2]>,
    /// The fog of the cloud layers the camera is in or near (celestial's
    /// `Sky::in_cloud_fog`), drawn by the cloud layers' pass over terrain and sky.
    pub in_cloud_fog: Option<celestial::sky::InCloudFog>,
    /// What `[visibility]` made of the scene.
    pub visibility: Option<PreparedVisibility>,
    /// The viewer's distance from the planet's centre (m): celestial's frame puts the
    /// viewer on its +z axis.
    pub viewer_radius: f64,
    /// The scene's lights after the sun, each a sky of its own added to the sunlit one
    /// where the sky shows: the moon on a moonlit night (scenes with `[time]`, the sun
    /// down and the moon up), else none. [`PreparedScene::lights`] lists them all.
    pub other_lights: Vec<LightSky>,
    /// The `[clouds.volume]` cloud grown, placed and lit (`crate::volume_clouds`);
    /// `None` without the section (then no automaton runs and no march pass is built).
    pub volume_cloud: Option<crate::volume_clouds::PreparedVolume>,
    /// The `[clouds.volume]` cloud with `draw = "billboards"`, grown and lit by slices
    /// (`crate::billboard_clouds`); then `volume_cloud` is `None` (no march).
    pub billboard_cloud: Option<crate::billboard_clouds::PreparedBillboards>,
    /// The `[clouds.shell]` shell and its lighting (`crate::shell_clouds`); `None`
    /// without the section (then no march pass is built, nothing allocated).
    pub shell_cloud: Option<crate::shell_clouds::PreparedShell>,
    /// The placed `celestial` sky (scenes with `[time]` and sky objects): what
    /// [`PreparedScene::look_along`] redraws the sky objects' frame from.
    pub celestial_sky: Option<celestial::sky::Sky>,
}

/// The sky lit by a light other than the sun: the scene's atmosphere with that light's
/// irradiance (the moon's: `celestial::MoonLight::atmosphere`), seen from its direction.
pub struct LightSky {
    /// "moon": what `explain` and the passes' labels call the light.
    pub name: &'static str,
    /// The atmosphere lit by the light.
    pub atmosphere: atmos::Atmosphere,
    /// Unit world direction toward the light (the moon's: airless).
    pub direction: DVec3,
    /// The scene's rung built from that atmosphere.
    pub sky_model: SharedSkyModel,
    /// The model finite segments (terrain's aerial perspective) are evaluated with.
    pub segment_model: SharedSkyModel,
    /// Its tables, for the precomputed rung.
    pub precomputed: Option<std::sync::Arc<atmos::lut::PrecomputedSky>>,
    /// The scene's cloud layers with this light as theirs: the shadows they cast in it.
    pub cloud_layers: Vec<celestial::clouds::CloudLayerUniforms>,
}

/// One light of a scene — the sun, or the moon at night — and what the terrain's
/// shading, its aerial perspective and the clouds read for it. The moon's is the same
/// atmosphere lit by the moon (celestial's `MoonLight::atmosphere`), so every light goes
/// through the same functions.
#[derive(Clone, Copy)]
pub struct Illuminant<'a> {
    /// Its place in [`PreparedScene::lights`] (0: the sun).
    pub index: crate::light::LightIndex,
    /// "sun", "moon".
    pub name: &'static str,
    /// The atmosphere lit by this light (its `sun_irradiance` and `sun_angular_radius`
    /// are the light's).
    pub atmosphere: &'a atmos::Atmosphere,
    /// Unit world direction toward the light.
    pub direction: DVec3,
    /// The scene's rung lit by it.
    pub sky_model: &'a (dyn atmos::SkyModel + Send + Sync),
    /// Its model for finite segments.
    pub segment_model: &'a (dyn atmos::SkyModel + Send + Sync),
    /// Its tables (precomputed rung).
    pub precomputed: Option<&'a atmos::lut::PrecomputedSky>,
    /// The cloud layers with this light's direction (their shadows).
    pub cloud_layers: &'a [celestial::clouds::CloudLayerUniforms],
    /// The volumetric cloud's shadow map toward this light (its
    /// [`crate::light::CloudLight::shadow`], marched or drawn as billboards).
    pub volume_shadow: Option<&'a crate::volume_clouds::CloudShadow>,
    /// The `[clouds.shell]` deck's shadow map toward this light (its
    /// [`crate::light::CloudLight::shadow`]): multiplies the volume's.
    pub shell_shadow: Option<&'a crate::volume_clouds::CloudShadow>,
}

impl std::fmt::Debug for Illuminant<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Illuminant")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .field("sky_model", &self.sky_model.label())
            .field("cloud_layers", &self.cloud_layers.len())
            .finish_non_exhaustive()
    }
}

impl Illuminant<'_> {
    /// The light as a cloud's preparation sees it.
    pub fn source(&self) -> crate::light::LightSource<'_> {
        crate::light::LightSource {
            name: self.name,
            atmosphere: self.atmosphere,
            sky_model: self.sky_model,
            direction: self.direction,
            precomputed: self.precomputed,
        }
    }

    /// The scene camera with this light as its "sun" (what its tables are baked and
    /// looked up for).
    pub fn camera(&self, camera: &atmos::frame::FrameCamera) -> atmos::frame::FrameCamera {
        atmos::frame::FrameCamera {
            sun: self.direction.as_vec3().to_array(),
            ..*camera
        }
    }
}

impl std::fmt::Debug for LightSky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LightSky")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .field("sky_model", &self.sky_model.label())
            .finish_non_exhaustive()
    }
}

impl LightSky {
    /// The light as a cloud's preparation sees it.
    pub fn source(&self) -> crate::light::LightSource<'_> {
        crate::light::LightSource {
            name: self.name,
            atmosphere: &self.atmosphere,
            sky_model: self.sky_model.as_ref(),
            direction: self.direction,
            precomputed: self.precomputed.as_deref(),
        }
    }
}

impl PreparedScene {
    /// The same scene seen along world direction `forward` (any length > 0) with a
    /// vertical field of view `vertical_fov` (radians) into `width × height` pixels:
    /// the camera and the sky objects' frame change, nothing else is prepared again (a
    /// cubemap's, panorama's or fisheye's six faces share one preparation).
    pub fn look_along(
        &mut self,
        forward: DVec3,
        vertical_fov: f64,
        width: u32,
        height: u32,
    ) -> Result<(), crate::RenderError> {
        let forward = forward.normalize();
        self.camera = atmos::frame::FrameCamera::look_at(
            self.camera_position,
            forward,
            up_hint(forward),
            vertical_fov,
            width,
            height,
            self.sun,
            None,
        )
        .map_err(crate::RenderError::Atmosphere)?;
        if let (Some(sky), Some(frame)) = (&self.celestial_sky, &mut self.sky_objects) {
            let enu = |v: DVec3| [v.x, -v.z, v.y];
            let camera = sky.camera(
                enu(forward),
                enu(up_hint(forward)),
                celestial::Angle::from_radians(vertical_fov),
                width,
                height,
            )?;
            *frame = sky.sky_objects_frame(&camera)?;
            // Reverse z: the sky is at depth 0, terrain in front of it hides the objects.
            frame.uniforms.far_depth = 0.0;
        }
        Ok(())
    }

    /// The same scene seen from `position` (metres in the scene's frame: x east, y up
    /// above the surface, z south, as `[camera] position`) along `forward`, with a
    /// vertical field of view `vertical_fov` (radians), into the frame's size: the
    /// camera, its planet-centred position, the viewer's radius, the sky objects' frame
    /// and the cloud layers' draw order, texture offsets (anchored to the world) and
    /// in-cloud fog change, nothing else is prepared again.
    ///
    /// A move at the prepared altitude gives the scene a preparation there gives
    /// ([`CameraMove::Moved`]; `tests/move_camera.rs`). A move to another altitude keeps
    /// `celestial`'s paint of the prepared one — the fog's and cloud layers' colours and
    /// the stars' brightness, which `Sky::repaint` works out for the viewer's altitude
    /// — and says so ([`CameraMove::MovedKeepingPaint`]): prepare the scene again there
    /// for the exact picture. What a viewpoint's preparation holds and a move cannot
    /// carry is refused with [`CameraMove::NeedsPrepare`] and the reason (the scene
    /// then is unchanged): the per-vertex dome's grid (built per viewpoint), and the
    /// cloud layers when the camera crossed one while another light than the sun
    /// lights them. The shell deck's light is taken above the prepared viewpoint; it
    /// varies over tens of kilometres, so a caller prepares again a camera that moved
    /// far.
    pub fn move_camera(
        &mut self,
        position: DVec3,
        forward: DVec3,
        vertical_fov: f64,
    ) -> Result<CameraMove, crate::RenderError> {
        if !position.is_finite() {
            return Err(crate::RenderError::InvalidParameter {
                field: "camera.position",
                value: format!("{position:?}"),
                reason: "must be finite",
            });
        }
        let planet_centred = position + DVec3::new(0.0, self.atmosphere.planet_radius, 0.0);
        if planet_centred == self.camera_position {
            self.look_along(forward, vertical_fov, self.camera.width, self.camera.height)?;
            return Ok(CameraMove::Moved);
        }
        if self.rung == Rung::ClosedFormVertex {
            return Ok(CameraMove::NeedsPrepare(
                "the per-vertex dome's grid is built for one viewpoint",
            ));
        }
        // Where atmos accepts a viewer (not under the ground).
        atmos::SkyQuery::new(
            self.atmosphere.planet_radius,
            planet_centred,
            DVec3::Y,
            self.sun,
        )
        .map_err(crate::RenderError::Atmosphere)?;
        // The layers (their texture anchored to the world: the offsets follow the
        // camera's east and north) and the in-cloud fog at the new viewpoint.
        let layers = match &self.celestial_sky {
            Some(sky) if !self.cloud_layer_drift_m.is_empty() => Some((
                cloud_layers_at(sky, position, &self.cloud_layer_drift_m)?,
                sky.in_cloud_fog(position.y)?,
            )),
            _ => None,
        };
        if let Some((layers, in_cloud_fog)) = layers {
            let geometry = |l: &[celestial::clouds::CloudLayerUniforms]| -> Vec<_> {
                l.iter()
                    .map(|u| celestial::clouds::CloudLayerUniforms {
                        offset: [0.0; 2],
                        ..*u
                    })
                    .collect()
            };
            let crossed = geometry(&layers) != geometry(&self.cloud_layers);
            if crossed && !self.other_lights.is_empty() {
                return Ok(CameraMove::NeedsPrepare(
                    "the camera crossed a cloud layer lit by more than the sun",
                ));
            }
            // The other lights' layers are the same layers lit from elsewhere: the same
            // offsets.
            for light in &mut self.other_lights {
                for (theirs, ours) in light.cloud_layers.iter_mut().zip(&layers) {
                    theirs.offset = ours.offset;
                }
            }
            self.cloud_layers = layers;
            self.in_cloud_fog = in_cloud_fog;
        }
        let altitude_change_m = planet_centred.y - self.camera_position.y;
        self.camera_position = planet_centred;
        self.viewer_radius = planet_centred.y;
        self.look_along(forward, vertical_fov, self.camera.width, self.camera.height)?;
        Ok(
            if self.celestial_sky.is_some() && altitude_change_m != 0.0 {
                CameraMove::MovedKeepingPaint { altitude_change_m }
            } else {
                CameraMove::Moved
            },
        )
    }

    /// The scene's lights, the sun first, then [`PreparedScene::other_lights`] in order:
    /// what every pass runs once per light.
    pub fn lights(&self) -> Vec<Illuminant<'_>> {
        let sun = Illuminant {
            index: 0,
            name: "sun",
            atmosphere: &self.atmosphere,
            direction: self.sun,
            sky_model: self.sky_model.as_ref(),
            segment_model: self.segment_model.as_ref(),
            precomputed: self.precomputed.as_deref(),
            cloud_layers: &self.cloud_layers,
            volume_shadow: None,
            shell_shadow: None,
        };
        let others = self.other_lights.iter().map(|light| Illuminant {
            name: light.name,
            atmosphere: &light.atmosphere,
            direction: light.direction,
            sky_model: light.sky_model.as_ref(),
            segment_model: light.segment_model.as_ref(),
            precomputed: light.precomputed.as_deref(),
            cloud_layers: &light.cloud_layers,
            ..sun
        });
        std::iter::once(sun)
            .chain(others)
            .enumerate()
            .map(|(index, light)| Illuminant {
                index,
                volume_shadow: self.volume_shadow(index),
                shell_shadow: self
                    .shell_cloud
                    .as_ref()
                    .and_then(|s| s.lights.get(index)?.shadow.as_ref()),
                ..light
            })
            .collect()
    }

    /// The sun as the scene's light ([`PreparedScene::lights`]' first).
    pub fn sun_light(&self) -> Illuminant<'_> {
        self.lights().swap_remove(0)
    }

    /// The `[clouds.volume]` cloud's shadow map toward light `index`, marched or drawn
    /// as billboards.
    fn volume_shadow(
        &self,
        index: crate::light::LightIndex,
    ) -> Option<&crate::cloud_shadow::CloudShadow> {
        let marched = self.volume_cloud.as_ref().and_then(|v| v.lights.get(index));
        let billboards = self
            .billboard_cloud
            .as_ref()
            .and_then(|b| b.lights.get(index));
        marched
            .and_then(|l| l.shadow.as_ref())
            .or_else(|| billboards.and_then(|l| l.shadow.as_ref()))
    }

    /// The sun's elevation above the horizon plane, degrees.
    pub fn sun_elevation_deg(&self) -> f64 {
        self.sun.y.clamp(-1.0, 1.0).asin().to_degrees()
    }
}

impl std::fmt::Debug for PreparedScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PreparedScene")
            .field("rung", &self.rung)
            .field("sky_model", &self.sky_model.label())
            .field("camera", &self.camera)
            .field("terrain", &self.terrain.is_some())
            .finish_non_exhaustive()
    }
}

/// The image's up for a camera looking along `forward`: the zenith, except when
/// looking straight up or down (within 0.06°), where north is the top of the image.
pub fn up_hint(forward: DVec3) -> DVec3 {
    let length = forward.length();
    if length > 0.0 && (forward.y / length).abs() > 1.0 - 5e-7 {
        DVec3::NEG_Z
    } else {
        DVec3::Y
    }
}

/// The world direction of an elevation and an azimuth clockwise from north (radians):
/// x east, y up, z south.
pub fn world_direction(elevation: f64, azimuth: f64) -> DVec3 {
    let (sin_e, cos_e) = elevation.sin_cos();
    let (sin_a, cos_a) = azimuth.sin_cos();
    DVec3::new(cos_e * sin_a, sin_e, -cos_e * cos_a)
}

/// What [`PreparedScene::move_camera`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CameraMove {
    /// The camera moved; the scene is what a preparation at the new viewpoint gives.
    Moved,
    /// The camera moved to another altitude (by this many metres); `celestial`'s
    /// paint (fog and cloud-layer colours, star brightness) is still the prepared
    /// altitude's until the scene is prepared there.
    MovedKeepingPaint {
        /// New altitude − prepared altitude, metres.
        altitude_change_m: f64,
    },
    /// The scene holds something prepared for its viewpoint that a move cannot carry
    /// (the reason): prepare the scene again from the new position.
    NeedsPrepare(&'static str),
}
