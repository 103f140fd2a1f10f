//! The viewer's camera: fly (move along the view, turn with the mouse) and orbit (turn
//! about a point in front), in the scene's frame (x east, y up above the surface, z
//! south; metres), starting from the scene's `[camera]`.

use glam::DVec3;

/// How the mouse and the movement keys move the camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CameraMode {
    /// W/S along the view, A/D sideways, E/Q up and down; the mouse turns the view.
    Fly,
    /// The mouse turns the camera about the point `distance` in front; W/S and the
    /// wheel move toward or away from it.
    Orbit,
}

/// A camera pose and how it moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Camera {
    /// Position, metres (scene frame).
    pub(crate) position: DVec3,
    /// Azimuth of the view, radians clockwise from north.
    pub(crate) azimuth: f64,
    /// Elevation of the view above the horizon plane, radians.
    pub(crate) elevation: f64,
    /// Vertical field of view, radians.
    pub(crate) vertical_fov: f64,
    /// Flying speed, m/s.
    pub(crate) speed: f64,
    /// The orbit's distance to its centre, m.
    pub(crate) orbit_distance: f64,
    pub(crate) mode: CameraMode,
}

/// The steepest view: straight up or down would leave the camera's "up" undefined.
const MAX_ELEVATION: f64 = 89.5 * std::f64::consts::PI / 180.0;

impl Camera {
    /// The scene's camera: its position, its view (toward `look_at`, or along
    /// `look_direction`) and field of view; the speed scales with the height above the
    /// surface (a walker's near the ground, an aircraft's high up).
    pub(crate) fn from_scene(section: &render::scene::CameraSection) -> Self {
        let position = DVec3::from_array(section.position);
        let (forward, distance) = match (section.look_at, section.look_direction) {
            (Some(target), _) => {
                let to = DVec3::from_array(target) - position;
                (to, to.length())
            }
            (None, Some(direction)) => (DVec3::from_array(direction), 0.0),
            (None, None) => (DVec3::NEG_Z, 0.0),
        };
        let forward = forward.try_normalize().unwrap_or(DVec3::NEG_Z);
        let height = position.y.abs().max(2.0);
        Self {
            position,
            azimuth: forward.x.atan2(-forward.z),
            elevation: forward.y.clamp(-1.0, 1.0).asin(),
            vertical_fov: section.vertical_fov_deg.to_radians(),
            speed: (height * 0.5).clamp(5.0, 2.0e4),
            orbit_distance: if distance > 1.0 {
                distance
            } else {
                (height * 4.0).max(100.0)
            },
            mode: CameraMode::Fly,
        }
    }

    /// The unit view direction.
    pub(crate) fn forward(&self) -> DVec3 {
        let (sin_a, cos_a) = self.azimuth.sin_cos();
        let (sin_e, cos_e) = self.elevation.sin_cos();
        DVec3::new(sin_a * cos_e, sin_e, -cos_a * cos_e)
    }

    /// The unit horizontal direction to the view's right.
    pub(crate) fn right(&self) -> DVec3 {
        let (sin_a, cos_a) = self.azimuth.sin_cos();
        DVec3::new(cos_a, 0.0, sin_a)
    }

    /// The point an orbit turns about.
    pub(crate) fn orbit_centre(&self) -> DVec3 {
        self.position + self.forward() * self.orbit_distance
    }

    /// Turns the view by `azimuth` and `elevation` (radians); in orbit mode the camera
    /// moves about the orbit's centre so that it keeps looking at it.
    pub(crate) fn turn(&mut self, azimuth: f64, elevation: f64) {
        let centre = self.orbit_centre();
        self.azimuth = (self.azimuth + azimuth).rem_euclid(std::f64::consts::TAU);
        self.elevation = (self.elevation + elevation).clamp(-MAX_ELEVATION, MAX_ELEVATION);
        if self.mode == CameraMode::Orbit {
            self.position = centre - self.forward() * self.orbit_distance;
        }
    }

    /// Moves by `forward`, `right` and `up` metres: fly mode along the view, sideways and
    /// along the world's up; orbit mode toward the centre (never through it), around
    /// it, and up.
    pub(crate) fn translate(&mut self, forward: f64, right: f64, up: f64) {
        match self.mode {
            CameraMode::Fly => {
                self.position += self.forward() * forward + self.right() * right + DVec3::Y * up;
            }
            CameraMode::Orbit => {
                let centre = self.orbit_centre();
                self.orbit_distance = (self.orbit_distance - forward).max(1.0);
                if self.orbit_distance > 0.0 {
                    let turn = right / self.orbit_distance;
                    self.azimuth = (self.azimuth - turn).rem_euclid(std::f64::consts::TAU);
                }
                self.position = centre - self.forward() * self.orbit_distance + DVec3::Y * up;
            }
        }
    }

    /// The wheel: in fly mode the speed (×1.25 a notch), in orbit mode the distance.
    pub(crate) fn wheel(&mut self, notches: f64) {
        let factor = 1.25f64.powf(notches);
        match self.mode {
            CameraMode::Fly => self.speed = (self.speed * factor).clamp(0.5, 1.0e6),
            CameraMode::Orbit => {
                let centre = self.orbit_centre();
                self.orbit_distance = (self.orbit_distance / factor).clamp(1.0, 1.0e7);
                self.position = centre - self.forward() * self.orbit_distance;
            }
        }
    }

    /// Keeps the camera at least `clearance` metres above `ground` (the surface height
    /// under it, when the scene has terrain there).
    pub(crate) fn keep_above(&mut self, ground: Option<f64>, clearance: f64) {
        let floor = ground.unwrap_or(0.0) + clearance;
        if self.position.y < floor {
            self.position.y = floor;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(look_at: [f64; 3]) -> render::scene::CameraSection {
        render::scene::CameraSection {
            position: [0.0, 100.0, 0.0],
            look_at: Some(look_at),
            look_direction: None,
            vertical_fov_deg: 50.0,
            near: 0.5,
            far: 1.0e5,
            travel_m: [0.0; 3],
        }
    }

    #[test]
    fn the_scene_camera_looks_where_the_scene_says() {
        // Due east and 45° down.
        let camera = Camera::from_scene(&section([100.0, 0.0, 0.0]));
        let f = camera.forward();
        let expected = DVec3::new(1.0, -1.0, 0.0).normalize();
        assert!((f - expected).length() < 1e-12, "{f:?}");
        assert!((camera.azimuth.to_degrees() - 90.0).abs() < 1e-9);
        assert!((camera.orbit_distance - 100.0 * 2f64.sqrt()).abs() < 1e-9);
    }

    #[test]
    fn north_is_minus_z_and_right_is_east() {
        let mut camera = Camera::from_scene(&section([0.0, 100.0, -100.0]));
        assert!((camera.forward() - DVec3::NEG_Z).length() < 1e-12);
        assert!((camera.right() - DVec3::X).length() < 1e-12);
        camera.translate(10.0, 5.0, 1.0);
        assert!((camera.position - DVec3::new(5.0, 101.0, -10.0)).length() < 1e-9);
    }

    #[test]
    fn an_orbit_keeps_its_centre_in_view() {
        let mut camera = Camera::from_scene(&section([100.0, 0.0, 0.0]));
        camera.mode = CameraMode::Orbit;
        let centre = camera.orbit_centre();
        camera.turn(0.7, 0.2);
        camera.translate(0.0, 30.0, 0.0);
        camera.wheel(2.0);
        assert!((camera.orbit_centre() - centre).length() < 1e-6);
    }

    #[test]
    fn the_view_never_turns_straight_up() {
        let mut camera = Camera::from_scene(&section([100.0, 0.0, 0.0]));
        camera.turn(0.0, 10.0);
        assert!(camera.elevation <= MAX_ELEVATION);
        assert!(camera.forward().is_finite());
    }
}
