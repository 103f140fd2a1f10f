//! What the viewer shows: the scene as loaded, the choices made since (time, rung,
//! quality, exposure: each an edit of the scene's values, prepared again on the
//! preparation thread), the camera, and the last prepared scene, moved with the camera
//! every frame without preparing it again (`PreparedScene::move_camera`).

use glam::DVec3;
use render::scene::{CameraMove, PreparedScene, Scene};

use super::camera::Camera;

/// The distance a camera may move from where its scene was prepared before the scene
/// is prepared again there (the shell deck's and the layers' light were taken at the
/// prepared viewpoint; they change over tens of kilometres).
const REPREPARE_DISTANCE_M: f64 = 5_000.0;

/// The altitude change after which the sky's paint (fog and layer colours, star
/// brightness, worked out for the viewer's altitude) is prepared again.
const REPAINT_ALTITUDE_M: f64 = 50.0;

/// The viewer's state.
pub(crate) struct ViewState {
    /// The scene with the viewer's edits (the camera is the prepared one's).
    pub(crate) scene: Scene,
    /// The scene as loaded (what `R` and a reload start from).
    pub(crate) loaded: Scene,
    pub(crate) camera: Camera,
    /// Seconds of `[time]` added since loading.
    pub(crate) time_offset_s: f64,
    /// Whether time runs, and how many scene seconds a real second is.
    pub(crate) playing: bool,
    pub(crate) rate: f64,
    /// Automaton steps a real second grows the volume cloud by (0: still).
    pub(crate) growth_rate: f64,
    growth_accumulated: f64,
    /// Render size = window size × this (a CPU adapter draws fewer pixels).
    pub(crate) scale: f64,
    /// Amortise the marched clouds over frames (`SceneRendererSettings::temporal_clouds`).
    pub(crate) temporal_clouds: bool,
    /// The last prepared scene, moved to the current camera.
    pub(crate) prepared: Option<PreparedScene>,
    /// Where the prepared scene was prepared (scene frame).
    prepared_at: Option<DVec3>,
    /// The scene's values changed since the last request to prepare them.
    pub(crate) dirty: bool,
    /// The last error (a scene that failed to prepare, a camera move refused); the last
    /// good scene stays on screen.
    pub(crate) error: Option<String>,
}

impl ViewState {
    pub(crate) fn new(scene: Scene, scale: f64) -> Self {
        let camera = Camera::from_scene(&scene.file.camera);
        Self {
            loaded: scene.clone(),
            scene,
            camera,
            time_offset_s: 0.0,
            playing: false,
            rate: 600.0,
            growth_rate: 0.0,
            growth_accumulated: 0.0,
            scale,
            temporal_clouds: true,
            prepared: None,
            prepared_at: None,
            dirty: true,
            error: None,
        }
    }

    /// The scene to prepare: the current values with the camera's pose and `size`.
    pub(crate) fn request(&mut self, size: (u32, u32)) -> Scene {
        self.dirty = false;
        let mut scene = self.scene.clone();
        let loaded = &self.loaded.file.camera;
        let camera = &mut scene.file.camera;
        camera.position = self.camera.position.to_array();
        // The travel from the scene's camera: the cloud layers keep their place on the
        // ground (their texture offset is the viewer's travel plus the wind's drift).
        camera.travel_m = std::array::from_fn(|a| {
            self.camera.position[a] - loaded.position[a] + loaded.travel_m[a]
        });
        camera.look_at = None;
        camera.look_direction = Some(self.camera.forward().to_array());
        camera.vertical_fov_deg = self.camera.vertical_fov.to_degrees();
        scene.file.output.width = size.0.max(1);
        scene.file.output.height = size.1.max(1);
        // The viewer draws frames, not a sequence.
        scene.file.animation = None;
        scene
    }

    /// The render size for a window of `size` pixels.
    pub(crate) fn render_size(&self, (width, height): (u32, u32)) -> (u32, u32) {
        let side = |s: u32| ((f64::from(s) * self.scale).round() as u32).max(1);
        (side(width), side(height))
    }

    /// A prepared scene arrived: it is shown from the current camera.
    pub(crate) fn prepared(&mut self, scene: PreparedScene, at: DVec3) {
        self.prepared = Some(scene);
        self.prepared_at = Some(at);
        self.error = None;
        self.follow_camera();
    }

    /// Moves the prepared scene to the camera; asks for a new preparation when the
    /// scene cannot move there or has moved far from where it was prepared.
    pub(crate) fn follow_camera(&mut self) {
        let ground = self.ground_height();
        self.camera.keep_above(ground, 1.5);
        let Some(prepared) = &mut self.prepared else {
            return;
        };
        let moved = prepared.move_camera(
            self.camera.position,
            self.camera.forward(),
            self.camera.vertical_fov,
        );
        match moved {
            Ok(CameraMove::Moved) => {}
            // The sky's paint follows the altitude a preparation later.
            Ok(CameraMove::MovedKeepingPaint { .. }) => {
                if self
                    .prepared_at
                    .is_some_and(|at| (at.y - self.camera.position.y).abs() > REPAINT_ALTITUDE_M)
                {
                    self.dirty = true;
                }
            }
            Ok(CameraMove::NeedsPrepare(_)) => self.dirty = true,
            Err(e) => self.error = Some(format!("camera: {e}")),
        }
        if self
            .prepared_at
            .is_some_and(|at| at.distance(self.camera.position) > REPREPARE_DISTANCE_M)
        {
            self.dirty = true;
        }
    }

    /// The terrain's height under the camera, if the scene has terrain there.
    fn ground_height(&self) -> Option<f64> {
        let terrain = self.prepared.as_ref()?.terrain.as_ref()?;
        let [offset_x, offset_z] = terrain.map_offset();
        let spacing = terrain.heightfield.spacing();
        let x = (self.camera.position.x + offset_x) / spacing;
        let z = (self.camera.position.z + offset_z) / spacing;
        let (width, height) = (terrain.heightfield.width(), terrain.heightfield.height());
        if x < 0.0 || z < 0.0 || x > (width - 1) as f64 || z > (height - 1) as f64 {
            return None;
        }
        Some(terrain.heightfield.bilinear_elevation(x, z))
    }

    /// Adds `seconds` to `[time]` (a scene with `[sun]` has no time to move).
    pub(crate) fn add_time(&mut self, seconds: f64) -> Result<(), String> {
        let Some(time) = &mut self.scene.file.time else {
            return Err("the scene gives [sun], not [time]: move the sun instead".into());
        };
        time.offset_s += seconds;
        self.time_offset_s += seconds;
        self.dirty = true;
        Ok(())
    }

    /// Sets `[sun]`'s elevation and azimuth, degrees.
    pub(crate) fn set_sun(&mut self, elevation_deg: f64, azimuth_deg: f64) -> Result<(), String> {
        let Some(sun) = &mut self.scene.file.sun else {
            return Err("the scene gives [time]: move the time instead".into());
        };
        sun.elevation_deg = elevation_deg.clamp(-90.0, 90.0);
        sun.azimuth_deg = azimuth_deg.rem_euclid(360.0);
        self.dirty = true;
        Ok(())
    }

    /// Advances what runs by itself by `seconds` of real time: the clock while
    /// playing, the automaton at its growth rate.
    pub(crate) fn advance(&mut self, seconds: f64) {
        if self.playing && self.scene.file.time.is_some() {
            let _ = self.add_time(seconds * self.rate);
        }
        if self.growth_rate > 0.0
            && let Some(volume) = self
                .scene
                .file
                .clouds
                .as_mut()
                .and_then(|c| c.volume.as_mut())
        {
            self.growth_accumulated += seconds * self.growth_rate;
            let steps = self.growth_accumulated.floor();
            if steps >= 1.0 {
                self.growth_accumulated -= steps;
                volume.steps = volume.steps.saturating_add(steps as u32);
                self.dirty = true;
            }
        }
    }

    /// Back to the scene's camera (`R`).
    pub(crate) fn reset_camera(&mut self) {
        let mode = self.camera.mode;
        self.camera = Camera::from_scene(&self.loaded.file.camera);
        self.camera.mode = mode;
        self.follow_camera();
    }

    /// A scene read again from its file (`F5`): its values replace the loaded ones, the
    /// camera and the clock stay where the viewer has them.
    pub(crate) fn reload(&mut self, scene: Scene) {
        let offset = self.time_offset_s;
        self.loaded = scene.clone();
        self.scene = scene;
        if let Some(time) = &mut self.scene.file.time {
            time.offset_s += offset;
        }
        self.dirty = true;
    }
}
