//! What is valid but almost certainly not meant: one line each, naming where the value
//! came from (the file's line or the flag), for the caller to show.

use super::Scene;
use super::error::At;

/// Below this elevation the sun is past nautical twilight: the sky is close to black.
const DARK_SUN_DEG: f64 = -12.0;

impl Scene {
    /// Warnings about values that are valid but give an image that is almost certainly
    /// not the one meant: a `[sun]` past nautical twilight seen from inside the
    /// atmosphere (nearly black: a night sky needs `[time]` for the moon and stars), a
    /// camera so far out that the planet is smaller than a pixel.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        let file = &self.file;
        let earth = atmos::Atmosphere::earth();
        let altitude = file.camera.position[1];
        // Above the atmosphere the planet's lit side may be in view whatever the sun's
        // elevation at the point below.
        if let Some(sun) = file.sun
            && sun.elevation_deg < DARK_SUN_DEG
            && altitude < earth.top_radius - earth.planet_radius
        {
            warnings.push(format!(
                "{}`sun.elevation_deg` = {}°: the sun is past nautical twilight ({DARK_SUN_DEG}°), \
                 so the image will be nearly black; a night sky with the moon and stars needs \
                 [time] instead of [sun]",
                At(self.location(&["sun", "elevation_deg"])),
                sun.elevation_deg
            ));
        }
        let radius = earth.planet_radius;
        let height = f64::from(file.output.height.max(1));
        let pixel = file.camera.vertical_fov_deg.to_radians() / height;
        let planet = 2.0 * (radius / (radius + altitude)).clamp(-1.0, 1.0).asin();
        if altitude > 0.0 && planet < pixel {
            warnings.push(format!(
                "{}`camera.position` altitude {altitude} m: the planet spans {:.2e}°, less than \
                 a pixel ({:.2e}°), so the image will be black",
                At(self.location(&["camera", "position"])),
                planet.to_degrees(),
                pixel.to_degrees()
            ));
        }
        if let Some(section) = file.visibility
            && let Ok(aerosol) =
                celestial::visibility::aerosol_for_visibility(&earth, section.distance_m, altitude)
            && aerosol.rayleigh_limited
        {
            warnings.push(format!(
                "{}`visibility.distance_m` = {} m: the air alone (Rayleigh scattering and \
                 ozone) limits the visibility at the camera to {:.0} m, so the aerosol is \
                 zero and the image shows that visibility",
                At(self.location(&["visibility", "distance_m"])),
                section.distance_m,
                aerosol.effective_visibility_m
            ));
        }
        warnings
    }
}
