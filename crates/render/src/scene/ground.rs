//! The camera against the ground: a camera under the terrain's surface sees only rock
//! (every ray starts inside it), so it is an error, not a uniform image.

use terrain::Heightfield;

use super::{Scene, SceneError};

impl Scene {
    /// An error naming `camera.position` when the camera is under `heightfield`'s
    /// surface (off the map it may be anywhere).
    pub(crate) fn check_camera_above(&self, heightfield: &Heightfield) -> Result<(), SceneError> {
        let position = self.file.camera.position;
        match surface_under(heightfield, position[0], position[2]) {
            Some(ground) if position[1] < ground => Err(self.invalid(
                &["camera", "position"],
                format!("[{}, {}, {}]", position[0], position[1], position[2]),
                format!(
                    "the camera is {:.1} m under the terrain's surface ({ground:.1} m at x = {}, \
                     z = {})",
                    ground - position[1],
                    position[0],
                    position[2]
                ),
            )),
            _ => Ok(()),
        }
    }
}

/// The heightfield's surface (bilinear, metres) under world `x`, `z` (the map is
/// centred on the origin), or `None` off the map.
fn surface_under(heightfield: &Heightfield, x: f64, z: f64) -> Option<f64> {
    let (width, height) = (heightfield.width(), heightfield.height());
    let spacing = heightfield.spacing();
    let column = x / spacing + 0.5 * (width - 1) as f64;
    let row = z / spacing + 0.5 * (height - 1) as f64;
    if !(column >= 0.0 && row >= 0.0 && column <= (width - 1) as f64 && row <= (height - 1) as f64)
    {
        return None;
    }
    let (c0, r0) = (
        (column.floor() as usize).min(width - 2),
        (row.floor() as usize).min(height - 2),
    );
    let (fc, fr) = (column - c0 as f64, row - r0 as f64);
    let at = |c, r| heightfield.elevation(c, r).ok();
    let top = at(c0, r0)? * (1.0 - fc) + at(c0 + 1, r0)? * fc;
    let bottom = at(c0, r0 + 1)? * (1.0 - fc) + at(c0 + 1, r0 + 1)? * fc;
    Some(top * (1.0 - fr) + bottom * fr)
}
