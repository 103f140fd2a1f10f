//! A panorama's faces: each a rectilinear view of the scene, sampled into the
//! projection's image.

use glam::DVec3;

use super::{Face, Projection};
use crate::RenderError;
use crate::scene::prepare::world_direction;

/// The scene of the cube face looking along `forward` ([`CUBE_FACES`](super::CUBE_FACES)): the scene's
/// camera position, a 90° square rectilinear view of `side` pixels.
pub fn face_scene(
    scene: &crate::scene::Scene,
    forward: [f64; 3],
    side: u32,
) -> crate::scene::Scene {
    let mut face = scene.clone();
    let file = &mut face.file;
    file.output.projection = Projection::Rectilinear;
    file.output.width = side;
    file.output.height = side;
    file.camera.look_at = None;
    file.camera.look_direction = Some(forward);
    file.camera.vertical_fov_deg = 90.0;
    face
}

/// The radiance along world direction `direction` (unit) from the six `faces`: the face
/// that sees it most head-on, bilinear between its pixel centres (clamped at its edge).
pub fn sample_faces(faces: &[Face], direction: DVec3) -> [f32; 3] {
    let mut best = (f64::NEG_INFINITY, 0usize);
    for (i, face) in faces.iter().enumerate() {
        let forward = DVec3::from_array(face.camera.forward.map(f64::from));
        let along = direction.dot(forward);
        if along > best.0 {
            best = (along, i);
        }
    }
    let face = &faces[best.1];
    let camera = &face.camera;
    let along = best.0;
    let right = DVec3::from_array(camera.right.map(f64::from));
    let up = DVec3::from_array(camera.up.map(f64::from));
    let tan = f64::from(camera.tan_half_fov_y);
    let aspect = f64::from(camera.width) / f64::from(camera.height);
    // Invert atmos::frame::frame_view_direction: ndc = (2 (p + 0.5)/n − 1)·tan·(aspect).
    let a = direction.dot(right) / along / (tan * aspect);
    let b = direction.dot(up) / along / tan;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let px = ((a + 1.0) * 0.5 * w as f64 - 0.5).clamp(0.0, (w - 1) as f64);
    let py = ((1.0 - b) * 0.5 * h as f64 - 0.5).clamp(0.0, (h - 1) as f64);
    let (x0, y0) = (px.floor() as usize, py.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (fx, fy) = ((px - x0 as f64) as f32, (py - y0 as f64) as f32);
    let at = |x: usize, y: usize| face.radiance[y * w + x];
    let (p00, p10, p01, p11) = (at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1));
    std::array::from_fn(|k| {
        let top = p00[k] + (p10[k] - p00[k]) * fx;
        let bottom = p01[k] + (p11[k] - p01[k]) * fx;
        top + (bottom - top) * fy
    })
}

/// The output image (row-major radiance, `width` × `height`) of `projection` from the
/// six faces drawn along [`CUBE_FACES`](super::CUBE_FACES); `view` is the scene camera (the fisheye's
/// axis and roll), `fisheye_fov` its field across the image's height (rad).
pub fn assemble(
    projection: Projection,
    faces: &[Face],
    width: u32,
    height: u32,
    view: &atmos::frame::FrameCamera,
    fisheye_fov: f64,
) -> Result<Vec<[f32; 3]>, RenderError> {
    if faces.len() != 6 {
        return Err(RenderError::InvalidParameter {
            field: "faces",
            value: faces.len().to_string(),
            reason: "a cubemap has six faces",
        });
    }
    let (w, h) = (width as usize, height as usize);
    let mut out = vec![[0.0f32; 3]; w * h];
    match projection {
        Projection::Rectilinear => {
            return Err(RenderError::InvalidParameter {
                field: "output.projection",
                value: "\"rectilinear\"".into(),
                reason: "drawn directly by the scene camera, not from cube faces",
            });
        }
        Projection::Cubemap => {
            let side = h;
            if w != 6 * side {
                return Err(RenderError::InvalidParameter {
                    field: "output.width",
                    value: format!("{width}"),
                    reason: "a cubemap strip is six faces of `height` pixels: width = 6 × height",
                });
            }
            for (i, face) in faces.iter().enumerate() {
                if face.radiance.len() != side * side {
                    return Err(RenderError::InvalidParameter {
                        field: "faces",
                        value: format!("{} pixels", face.radiance.len()),
                        reason: "each face must be height × height",
                    });
                }
                for y in 0..side {
                    out[y * w + i * side..y * w + (i + 1) * side]
                        .copy_from_slice(&face.radiance[y * side..(y + 1) * side]);
                }
            }
        }
        Projection::Equirectangular => {
            for y in 0..h {
                let elevation = std::f64::consts::FRAC_PI_2
                    - (y as f64 + 0.5) / h as f64 * std::f64::consts::PI;
                for x in 0..w {
                    let azimuth = (x as f64 + 0.5) / w as f64 * std::f64::consts::TAU;
                    out[y * w + x] = sample_faces(faces, world_direction(elevation, azimuth));
                }
            }
        }
        Projection::Fisheye => {
            let forward = DVec3::from_array(view.forward.map(f64::from));
            let right = DVec3::from_array(view.right.map(f64::from));
            let up = DVec3::from_array(view.up.map(f64::from));
            // Radians per pixel: the field across the height.
            let scale = fisheye_fov / h as f64;
            for y in 0..h {
                for x in 0..w {
                    let dx = (x as f64 + 0.5 - 0.5 * w as f64) * scale;
                    let dy = (0.5 * h as f64 - (y as f64 + 0.5)) * scale;
                    let theta = dx.hypot(dy);
                    if theta > std::f64::consts::PI {
                        continue;
                    }
                    let (sin_t, cos_t) = theta.sin_cos();
                    let (cx, cy) = if theta > 0.0 {
                        (dx / theta, dy / theta)
                    } else {
                        (0.0, 0.0)
                    };
                    let direction = forward * cos_t + (right * cx + up * cy) * sin_t;
                    if theta <= 0.5 * fisheye_fov {
                        out[y * w + x] = sample_faces(faces, direction);
                    }
                }
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::projection::CUBE_FACES;

    /// Faces whose radiance is the view direction's components (+1, halved): a
    /// lookup must return (close to) the direction it was asked for.
    fn direction_faces(side: u32) -> Vec<Face> {
        CUBE_FACES
            .iter()
            .map(|&forward| {
                let forward = DVec3::from_array(forward);
                let camera = atmos::frame::FrameCamera::look_at(
                    DVec3::new(0.0, 6.371e6, 0.0),
                    forward,
                    crate::scene::prepare::up_hint(forward),
                    std::f64::consts::FRAC_PI_2,
                    side,
                    side,
                    DVec3::Y,
                    None,
                )
                .unwrap();
                let radiance = (0..side * side)
                    .map(|i| {
                        let d = atmos::frame::frame_view_direction([i % side, i / side], &camera);
                        d.map(|c| 0.5 * (c + 1.0))
                    })
                    .collect();
                Face { camera, radiance }
            })
            .collect()
    }

    #[test]
    fn a_lookup_returns_the_direction_it_was_asked_for() {
        let faces = direction_faces(64);
        let mut worst = 0.0f64;
        for k in 0..2000 {
            // Directions spread over the sphere (a Fibonacci lattice).
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / 2000.0;
            let phi = k as f64 * 2.399_963_229_728_653;
            let d = DVec3::new(
                (1.0 - z * z).sqrt() * phi.cos(),
                z,
                (1.0 - z * z).sqrt() * phi.sin(),
            );
            let got = sample_faces(&faces, d);
            let got = DVec3::new(
                f64::from(got[0]) * 2.0 - 1.0,
                f64::from(got[1]) * 2.0 - 1.0,
                f64::from(got[2]) * 2.0 - 1.0,
            );
            worst = worst.max(got.angle_between(d));
        }
        // Bilinear between pixel centres of a 64-pixel face (1.4° apart at the centre).
        assert!(worst < 0.01, "worst direction error {worst} rad");
    }

    #[test]
    fn equirectangular_rows_run_from_zenith_to_nadir_and_columns_around_from_north() {
        let faces = direction_faces(32);
        let view = faces[4].camera;
        let out = assemble(Projection::Equirectangular, &faces, 64, 32, &view, 0.0).unwrap();
        let direction = |x: usize, y: usize| out[y * 64 + x].map(|c| 2.0 * c - 1.0);
        assert!(direction(10, 0)[1] > 0.99, "top row looks up");
        assert!(direction(10, 31)[1] < -0.99, "bottom row looks down");
        let south = direction(32, 16);
        assert!(south[2] > 0.98, "centre column looks south: {south:?}");
        let east = direction(16, 16);
        assert!(east[0] > 0.98, "a quarter across looks east: {east:?}");
        assert!(assemble(Projection::Cubemap, &faces, 100, 32, &view, 0.0).is_err());
        assert!(assemble(Projection::Rectilinear, &faces, 64, 32, &view, 0.0).is_err());
    }
}
