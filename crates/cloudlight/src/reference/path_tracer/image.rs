//! The path tracer over a whole image: one [`PathTracerResult`] per pixel of a
//! [`PinholeCamera`], rows across rayon's threads.

use rayon::prelude::*;

use super::{
    GOLDEN_GAMMA, PathTracerResult, PathTracerSettings, Problem, RaySample, ReferenceError,
    ReferenceField, mix,
};
use crate::march::{PinholeCamera, pixel_direction};
use crate::reference::{Phase, Sun};

/// The seed of pixel `index`'s samples: SplitMix64's mix of the image's `seed` and the
/// index, so that neighbouring pixels draw uncorrelated streams (one seed for every pixel
/// would give every pixel the same random numbers, and the noise would be structured
/// across the image instead of independent per pixel).
pub(super) fn pixel_seed(seed: u64, index: u64) -> u64 {
    mix(mix(seed).wrapping_add(mix(index ^ GOLDEN_GAMMA)))
}

/// The path tracer's estimate at every pixel of a `size[0] × size[1]` image of `camera`
/// (rows top to bottom, x fastest, as [`crate::march::render_image`]): pixel `(x, y)`
/// traces `settings.samples` paths along the ray from the camera's origin through the
/// pixel's centre ([`pixel_direction`]) through `field` lit by `sun`, scattered by
/// `phase`. Radiance is in the units of the sun's irradiance per steradian (W m⁻² sr⁻¹
/// for an irradiance in W m⁻²), like [`radiance`](super::radiance).
///
/// Pixel `i = x + size[0]·y` draws its own streams under a seed mixed (SplitMix64) from
/// `settings.seed` and `i`, so neighbouring pixels' noise is independent, and traces its
/// samples in order on one thread; rows run across rayon's threads. The image is
/// therefore the same bit for bit whatever the thread count, and each pixel equals
/// [`radiance`](super::radiance) with the pixel's seed up to the order of its sums.
/// `progress`, if given, is called with 1 as each row finishes (e.g. `&|rows|
/// bar.inc(rows)` on an indicatif bar of length `size[1]`), from rayon's
/// threads. A zero-sized image is empty.
///
/// Errors: bad `settings` or `phase` (named as by [`estimate`](super::estimate)), a field
/// whose density exceeds its bound ([`ReferenceError::MajorantExceeded`]).
pub fn radiance_image<F: ReferenceField + ?Sized>(
    field: &F,
    camera: &PinholeCamera,
    size: [u32; 2],
    sun: &Sun,
    phase: &Phase,
    settings: &PathTracerSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<PathTracerResult>, ReferenceError> {
    let problem = Problem::new(field, sun, phase, settings)?;
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half(size);
    let origin = camera.origin();
    let rows = (0..size[1])
        .into_par_iter()
        .map(|y| -> Result<Vec<PathTracerResult>, ReferenceError> {
            let row = (0..size[0])
                .map(|x| {
                    let direction = pixel_direction([x, y], size, forward, right, up, tan_half);
                    let sampler = |_: [f64; 2]| RaySample {
                        origin,
                        direction,
                        weight: 1.0,
                    };
                    let index = u64::from(x) + u64::from(size[0]) * u64::from(y);
                    let seed = pixel_seed(settings.seed, index);
                    let tally = problem.trace(seed, 0..settings.samples, &sampler)?;
                    problem.result(tally, sun)
                })
                .collect::<Result<Vec<_>, _>>()?;
            if let Some(tick) = progress {
                tick(1);
            }
            Ok(row)
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(rows.into_iter().flatten().collect())
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicU64, Ordering};

    use super::*;
    use crate::CloudVolume;
    use crate::reference::path_tracer::radiance;

    fn scene() -> (CloudVolume, PinholeCamera, Sun, Phase) {
        // A 4³ block of 25 m cells with a density ramp, seen from outside.
        let density = (0..64).map(|i| 0.25 + (i % 7) as f32 * 0.1).collect();
        let volume = CloudVolume::new([4, 4, 4], [0.0; 3], 25.0, 0.02, density).unwrap();
        let camera =
            PinholeCamera::look_at([-150.0, 50.0, 50.0], [50.0; 3], [0.0, 0.0, 1.0], 0.9).unwrap();
        let sun = Sun::new([0.3, 0.2, 0.9], [1.0, 0.9, 0.8]).unwrap();
        let phase = Phase::DualLobe {
            g_forward: 0.8,
            g_back: -0.3,
            back_weight: 0.2,
        };
        (volume, camera, sun, phase)
    }

    /// One thread or the default pool, the same image bit for bit; each pixel is the
    /// single-ray estimate with its own seed (to 1e-12 relative: only the order of the
    /// sums may differ), pixels draw different streams, and the progress sees every row.
    #[test]
    fn the_image_does_not_depend_on_the_thread_count() {
        let (volume, camera, sun, phase) = scene();
        let size = [5, 3];
        let settings = PathTracerSettings {
            samples: 64,
            ..Default::default()
        };
        let rows = AtomicU64::new(0);
        let tick = |n: u64| {
            rows.fetch_add(n, Ordering::Relaxed);
        };
        let image = |threads: Option<usize>| {
            let run = || {
                radiance_image(&volume, &camera, size, &sun, &phase, &settings, Some(&tick))
                    .unwrap()
            };
            match threads {
                Some(n) => rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .unwrap()
                    .install(run),
                None => run(),
            }
        };
        let one = image(Some(1));
        let default = image(None);
        let three = image(Some(3));
        assert_eq!(one.len(), 15);
        assert_eq!(one, default);
        assert_eq!(one, three);
        assert_eq!(rows.load(Ordering::Relaxed), 9);
        let lit = one.iter().filter(|p| p.total.mean[0] > 0.0).count();
        assert!(lit >= 5, "only {lit} pixels see the cloud");
        let [forward, right, up] = camera.basis();
        for (i, pixel) in one.iter().enumerate() {
            let (x, y) = (i as u32 % size[0], i as u32 / size[0]);
            let direction =
                pixel_direction([x, y], size, forward, right, up, camera.tan_half(size));
            let single = radiance(
                &volume,
                camera.origin(),
                direction,
                &sun,
                &phase,
                &PathTracerSettings {
                    seed: pixel_seed(settings.seed, i as u64),
                    ..settings
                },
            )
            .unwrap();
            for c in 0..3 {
                let (a, b) = (pixel.total.mean[c], single.total.mean[c]);
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
                    "{i}: {a} vs {b}"
                );
            }
        }
        let seeds: std::collections::HashSet<u64> =
            (0..15).map(|i| pixel_seed(settings.seed, i)).collect();
        assert_eq!(seeds.len(), 15);
    }

    #[test]
    fn bad_settings_are_named_and_an_empty_image_is_empty() {
        let (volume, camera, sun, phase) = scene();
        let bad = PathTracerSettings {
            samples: 1,
            ..Default::default()
        };
        let e = radiance_image(&volume, &camera, [2, 2], &sun, &phase, &bad, None).unwrap_err();
        assert!(e.to_string().starts_with("samples = 1"), "{e}");
        let good = PathTracerSettings {
            samples: 8,
            ..Default::default()
        };
        let empty = radiance_image(&volume, &camera, [0, 4], &sun, &phase, &good, None).unwrap();
        assert!(empty.is_empty());
    }
}
