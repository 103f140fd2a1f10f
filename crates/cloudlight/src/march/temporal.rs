//! Temporal amortisation of a view march (after Schneider's Nubis talks, which march a
//! fraction of the cloud pixels each frame and reproject the rest): each frame marches
//! one pixel of every 2×2 block in turn ([`interleave_marches`]) and takes the others
//! from the last frame's image where the cloud seen through them was then
//! ([`reprojected_position`]). A still camera's image is the full march's after four
//! frames. Twins of `shaders/cloudlight/march_temporal.wgsl`; the GPU pass is
//! `gpu::TemporalMarch`.

use atmos::real::Real;

use super::image::pixel_direction;

/// Whether `pixel` is marched in the frame of `phase` (0..3, taken mod 4): the 2×2
/// block's pixel `x mod 2 + 2·(y mod 2) = phase`.
pub fn interleave_marches(pixel: [u32; 2], phase: u32) -> bool {
    (pixel[0] & 1) + 2 * (pixel[1] & 1) == phase % 4
}

/// A pinhole camera as a march's parameters hold it: origin (m); unit forward, right
/// and up; the tangents of the horizontal and vertical half fields of view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchCamera<F> {
    /// Origin, metres (the march's frame).
    pub origin: [F; 3],
    /// Unit forward.
    pub forward: [F; 3],
    /// Unit right.
    pub right: [F; 3],
    /// Unit up.
    pub up: [F; 3],
    /// `[tan(horizontal fov / 2), tan(vertical fov / 2)]`.
    pub tan_half: [F; 2],
}

impl MarchCamera<f64> {
    /// `camera` drawing a `size` image.
    pub fn of(camera: &super::PinholeCamera, size: [u32; 2]) -> Self {
        let [forward, right, up] = camera.basis();
        Self {
            origin: camera.origin(),
            forward,
            right,
            up,
            tan_half: camera.tan_half(size),
        }
    }
}

/// Where the point `distance` metres along `now`'s ray through `pixel` was in
/// `before`'s image of the same `size`: its image position in pixels (pixel `(i, j)`
/// spans `[i, i + 1) × [j, j + 1)`), or `None` when it was behind that camera or outside
/// its image. A pixel through which the last frame saw no cloud
/// (`distance` ≤ 0 or NaN) is taken at `fallback_distance` (the sky far away: only the
/// view's turn moves it).
pub fn reprojected_position<F: Real>(
    now: &MarchCamera<F>,
    before: &MarchCamera<F>,
    size: [u32; 2],
    pixel: [u32; 2],
    distance: F,
    fallback_distance: F,
) -> Option<[F; 2]> {
    let direction = pixel_direction(pixel, size, now.forward, now.right, now.up, now.tan_half);
    let along = if distance > F::zero() {
        distance
    } else {
        fallback_distance
    };
    let v: [F; 3] =
        std::array::from_fn(|a| now.origin[a] + direction[a] * along - before.origin[a]);
    let dot = |b: [F; 3]| v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
    let depth = dot(before.forward);
    // Behind the last camera, or NaN.
    if depth.partial_cmp(&F::zero()) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let (one, half) = (F::one(), F::of(0.5));
    let sx = dot(before.right) / (depth * before.tan_half[0]);
    let sy = dot(before.up) / (depth * before.tan_half[1]);
    let x = (sx + one) * half * F::of(f64::from(size[0]));
    let y = (one - sy) * half * F::of(f64::from(size[1]));
    let inside = x >= F::zero()
        && y >= F::zero()
        && x < F::of(f64::from(size[0]))
        && y < F::of(f64::from(size[1]));
    inside.then_some([x, y])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::march::PinholeCamera;

    fn camera(origin: [f64; 3], target: [f64; 3]) -> MarchCamera<f64> {
        let camera = PinholeCamera::look_at(origin, target, [0.0, 0.0, 1.0], 1.0).unwrap();
        MarchCamera::of(&camera, [64, 36])
    }

    #[test]
    fn four_phases_cover_every_pixel_once() {
        for y in 0..4 {
            for x in 0..4 {
                let phases = (0..4).filter(|&p| interleave_marches([x, y], p)).count();
                assert_eq!(phases, 1, "({x}, {y})");
            }
        }
    }

    #[test]
    fn a_still_camera_finds_every_pixel_where_it_was() {
        let c = camera([0.0, -500.0, 100.0], [0.0, 0.0, 300.0]);
        for y in 0..36 {
            for x in 0..64 {
                for distance in [0.0, 50.0, 800.0] {
                    let [px, py] =
                        reprojected_position(&c, &c, [64, 36], [x, y], distance, 1e5).unwrap();
                    let centre = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                    assert!(
                        (px - centre[0]).abs() < 1e-9 && (py - centre[1]).abs() < 1e-9,
                        "({x}, {y}) at {distance} m: {px} {py}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_camera_moved_sideways_finds_near_points_further_over() {
        let before = camera([0.0, -500.0, 100.0], [0.0, 0.0, 100.0]);
        // 10 m to the right (+x): a point 500 m ahead moves left in the image.
        let now = camera([10.0, -500.0, 100.0], [10.0, 0.0, 100.0]);
        let near = reprojected_position(&now, &before, [64, 36], [32, 18], 500.0, 1e5).unwrap();
        let far = reprojected_position(&now, &before, [64, 36], [32, 18], 0.0, 1e7).unwrap();
        assert!(near[0] > 33.0, "{near:?}");
        assert!(
            (far[0] - 32.5).abs() < 0.01 && (far[1] - 18.5).abs() < 1e-9,
            "{far:?}"
        );
        // Behind the last camera: none.
        let behind = camera([0.0, -1000.0, 100.0], [0.0, -2000.0, 100.0]);
        assert_eq!(
            reprojected_position(&behind, &before, [64, 36], [32, 18], 10.0, 1e5),
            None
        );
    }
}
