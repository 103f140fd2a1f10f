//! Projections beyond the rectilinear camera: a cubemap's six faces and, resampled
//! from them, an equirectangular panorama or an equidistant fisheye — HDR environment
//! maps for other engines' image-based lighting. Each face is an ordinary 90° square
//! frame of the scene (the GPU or the CPU renderer draws it); this module only places
//! the faces and maps directions to face pixels, with the faces' own cameras so the
//! lookup inverts exactly the rays they were drawn with.

/// What an output image shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Projection {
    /// The scene's camera (any pitch).
    #[default]
    Rectilinear,
    /// The six faces in one 6:1 strip, `+x −x +y −y +z −z` (east, west, up, down,
    /// south, north), each `height` pixels square; the side faces' top is up, the up
    /// and down faces' top is north.
    Cubemap,
    /// Longitude along x (the centre column looks south, the left edge north, azimuth
    /// clockwise from north), elevation +90° at the top row to −90° at the bottom.
    Equirectangular,
    /// Equidistant fisheye around the camera's view: the angle from the view axis is
    /// proportional to the distance from the image centre, `fisheye_fov_deg` across
    /// the image's height; outside the circle is black.
    Fisheye,
}

/// The cube faces' view directions (world axes: x east, y up, z south), in the strip's
/// order.
pub const CUBE_FACES: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, -1.0],
];

/// One face's radiance and the camera it was drawn with.
#[derive(Debug, Clone)]
pub struct Face {
    /// The camera (its basis and size place the pixels).
    pub camera: atmos::frame::FrameCamera,
    /// Row-major radiance.
    pub radiance: Vec<[f32; 3]>,
}

/// The faces' side in pixels for an output of `width` × `height` in `projection`:
/// matched to the output's angular resolution at the face centres.
pub fn face_size(projection: Projection, width: u32, height: u32) -> u32 {
    match projection {
        Projection::Rectilinear | Projection::Cubemap | Projection::Fisheye => height,
        Projection::Equirectangular => width.div_ceil(4),
    }
    .max(1)
}

mod faces;

pub use faces::{assemble, face_scene, sample_faces};
