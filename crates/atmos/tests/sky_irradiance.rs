//! The sky irradiance a caller's shader reads on the GPU (`sky_irradiance(position,
//! normal)` of `atmos::aerial_perspective`; the GPU against its CPU twin
//! `atmos::lut::drop_in::sky_irradiance` is a case of `cargo xtask parity`) against the
//! f64 Reference's irradiance over normals and altitudes 0–100 km, and on a horizontal
//! surface against `ground_irradiance` of the same rung.

use atmos::frame::FrameCamera;
use atmos::ground_irradiance::{HemisphereQuadrature, ground_irradiance};
use atmos::lut::drop_in::sky_irradiance;
use atmos::lut::sky_irradiance::bake_sky_irradiance_lut;
use atmos::lut::{Lut2d, LutSettings, PrecomputedSky};
use atmos::reference::{ReferenceSettings, ReferenceSky, ray_sphere_intersect};
use atmos::twins::direction_zenith_sample;
use atmos::{Atmosphere, SkyModel, SkyQuery};
use glam::DVec3;
use rayon::prelude::*;
use std::sync::OnceLock;

const ALTITUDES: [f64; 5] = [0.0, 1_000.0, 10_000.0, 30_000.0, 100_000.0];
const SUN_ELEVATIONS_DEG: [f64; 4] = [10.0, 30.0, 60.0, 90.0];

fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// Unit normals spread over the sphere (a Fibonacci lattice).
fn normals(count: usize) -> Vec<DVec3> {
    (0..count)
        .map(|k| {
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / count as f64;
            let radius = (1.0 - z * z).sqrt();
            let phi = k as f64 * 2.399_963_229_728_653;
            DVec3::new(radius * phi.cos(), radius * phi.sin(), z)
        })
        .collect()
}

/// The precomputed rung's tables (default settings) and the sky-irradiance LUT baked
/// from them on the CPU, once for both tests.
fn tables() -> &'static (PrecomputedSky, Lut2d) {
    static TABLES: OnceLock<(PrecomputedSky, Lut2d)> = OnceLock::new();
    TABLES.get_or_init(|| {
        let luts = PrecomputedSky::new(&Atmosphere::earth(), &LutSettings::default()).unwrap();
        let start = std::time::Instant::now();
        let table = bake_sky_irradiance_lut(&luts.static_luts().bindings());
        eprintln!(
            "CPU sky-irradiance bake: {:.1} s",
            start.elapsed().as_secs_f64()
        );
        (luts, table)
    })
}

/// A camera at `position` with the sun along `sun`: what the twin reads of it.
fn camera(position: DVec3, sun: DVec3) -> FrameCamera {
    FrameCamera::look_at(position, DVec3::X, DVec3::Z, 1.0, 4, 4, sun, None).unwrap()
}

/// Ground irradiance (direct sun + sky) of the Reference on a horizontal surface at
/// sea level, tabulated over the sun's zenith cosine μ_s ∈ [−1, 1]: what the ground
/// reflects (Lambert, albedo ρ) towards a point that sees it.
fn ground_table(reference: &ReferenceSky, atmosphere: &Atmosphere, size: usize) -> Vec<[f64; 3]> {
    let ground = DVec3::new(0.0, 0.0, atmosphere.planet_radius);
    (0..size)
        .into_par_iter()
        .map(|i| {
            let mu_s = -1.0 + 2.0 * i as f64 / (size - 1) as f64;
            let sun = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
            let quadrature = HemisphereQuadrature {
                zenith_cells: 8,
                azimuth_cells: 16,
            };
            ground_irradiance(reference, atmosphere, ground, sun, quadrature)
                .unwrap()
                .total()
        })
        .collect()
}

fn ground_irradiance_at(table: &[[f64; 3]], mu_s: f64) -> [f64; 3] {
    let x = (mu_s.clamp(-1.0, 1.0) + 1.0) * 0.5 * (table.len() - 1) as f64;
    let i = (x.floor() as usize).min(table.len() - 2);
    let f = x - i as f64;
    std::array::from_fn(|c| table[i][c] * (1.0 - f) + table[i + 1][c] * f)
}

/// The Reference's irradiance on each normal at `position`: its radiance (light
/// scattered in the air) plus, on rays that meet the ground, the ground's Lambertian
/// radiance ρ E_g/π through the ray's transmittance, integrated against the clamped
/// cosine over the sphere. Zenith samples split at the horizon and crowd towards it
/// (`direction_zenith_sample`), azimuths over the sun plane's half (the field is
/// mirror-symmetric in it) counted for both halves.
fn reference_irradiance(
    reference: &ReferenceSky,
    atmosphere: &Atmosphere,
    ground: &[[f64; 3]],
    position: DVec3,
    sun: DVec3,
    normals: &[DVec3],
) -> Vec<[f64; 3]> {
    let (zenith_count, azimuth_count) = (64u32, 48u32);
    let planet = atmosphere.planet_radius;
    let r = position.length();
    let z = position / r;
    let x = (sun - z * sun.dot(z))
        .try_normalize()
        .unwrap_or(z.any_orthonormal_vector());
    let y = z.cross(x);
    let rows: Vec<Vec<[f64; 3]>> = (0..zenith_count)
        .into_par_iter()
        .map(|i| {
            let [mu, share] = direction_zenith_sample::<f64>(r, planet, i, zenith_count);
            let sin = (1.0 - mu * mu).max(0.0).sqrt();
            let mut sums = vec![[0.0; 3]; normals.len()];
            for j in 0..azimuth_count {
                let phi = std::f64::consts::PI * (f64::from(j) + 0.5) / f64::from(azimuth_count);
                let weight = share * std::f64::consts::PI / f64::from(azimuth_count);
                let direction = z * mu + (x * phi.cos() + y * phi.sin()) * sin;
                let mirrored = z * mu + (x * phi.cos() - y * phi.sin()) * sin;
                let query = SkyQuery::new(planet, position, direction, sun).unwrap();
                let sample = reference.evaluate(&query);
                let mut radiance = sample.radiance;
                let hit = ray_sphere_intersect(r, mu, planet)[0];
                if mu < 0.0 && hit >= 0.0 {
                    let ground_point = position + direction * hit;
                    let mu_s = sun.dot(ground_point.normalize());
                    let e = ground_irradiance_at(ground, mu_s);
                    for c in 0..3 {
                        radiance[c] += sample.transmittance[c] * atmosphere.ground_albedo[c]
                            / std::f64::consts::PI
                            * e[c];
                    }
                }
                for (sum, normal) in sums.iter_mut().zip(normals) {
                    let cosines = normal.dot(direction).max(0.0) + normal.dot(mirrored).max(0.0);
                    for c in 0..3 {
                        sum[c] += weight * cosines * radiance[c];
                    }
                }
            }
            sums
        })
        .collect();
    (0..normals.len())
        .map(|n| std::array::from_fn(|c| rows.iter().map(|row| row[n][c]).sum()))
        .collect()
}

/// Mean and max relative luminance error of the sky irradiance over 32 normals, five
/// altitudes 0–100 km and four sun elevations, against the f64 Reference (default
/// settings): the relative error of each normal's irradiance, except that normals
/// receiving under 1 % of the brightest normal's light at that point (those facing
/// the black sky from the top of the atmosphere) are compared with that 1 %. About a
/// minute at the test profile's opt-level 2.
#[test]
fn sky_irradiance_follows_the_reference_over_normals_and_altitudes() {
    let earth = Atmosphere::earth();
    let reference = ReferenceSky::new(&earth, ReferenceSettings::default()).unwrap();
    let (luts, table) = tables();
    let ground = ground_table(&reference, &earth, 65);
    let normals = normals(32);
    let mut errors = Vec::new();
    let mut worst_relative: f64 = 0.0;
    for altitude in ALTITUDES {
        let mut at_altitude = Vec::new();
        for elevation in SUN_ELEVATIONS_DEG {
            let e = elevation.to_radians();
            let sun = DVec3::new(e.cos(), 0.0, e.sin());
            let position = DVec3::new(0.0, 0.0, earth.planet_radius + altitude);
            let expected =
                reference_irradiance(&reference, &earth, &ground, position, sun, &normals);
            let camera = camera(position, sun);
            // Normals that receive under 1 % of the brightest normal's light (those
            // facing the black sky from the top of the atmosphere) are compared with
            // that 1 %, not with their own near-zero irradiance.
            let floor = 0.01 * expected.iter().map(|e| luminance(*e)).fold(0.0, f64::max);
            for (normal, expected) in normals.iter().zip(&expected) {
                let got = sky_irradiance(
                    luts.static_luts(),
                    table,
                    &camera,
                    position.as_vec3().to_array(),
                    normal.as_vec3().to_array(),
                )
                .map(f64::from);
                let difference = (luminance(got) - luminance(*expected)).abs();
                worst_relative = worst_relative.max(difference / luminance(*expected));
                at_altitude.push(difference / luminance(*expected).max(floor));
            }
        }
        let mean = at_altitude.iter().sum::<f64>() / at_altitude.len() as f64;
        let max = at_altitude.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "altitude {:>6.0} m: mean {:.2} %, max {:.2} %",
            altitude,
            100.0 * mean,
            100.0 * max
        );
        errors.extend(at_altitude);
    }
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    let max = errors.iter().copied().fold(0.0, f64::max);
    eprintln!(
        "sky irradiance against the Reference, {} (normal, altitude, sun): mean {:.2} %, \
         max {:.2} % (max {:.1} % relative to the normal's own irradiance)",
        errors.len(),
        100.0 * mean,
        100.0 * max,
        100.0 * worst_relative
    );
    assert!(mean < 0.01, "mean {mean}");
}

/// On a horizontal surface at sea level the sky irradiance is `ground_irradiance`'s
/// sky part of the same rung (its radiance integrated over the upper hemisphere).
#[test]
fn sky_irradiance_on_the_ground_matches_ground_irradiance() {
    let earth = Atmosphere::earth();
    let (luts, table) = tables();
    let position = DVec3::new(0.0, 0.0, earth.planet_radius);
    let mut worst: f64 = 0.0;
    for elevation in [5.0f64, 10.0, 30.0, 60.0, 90.0] {
        let e = elevation.to_radians();
        let sun = DVec3::new(e.cos(), 0.0, e.sin());
        let expected = ground_irradiance(
            luts,
            &earth,
            position,
            sun,
            HemisphereQuadrature {
                zenith_cells: 32,
                azimuth_cells: 64,
            },
        )
        .unwrap()
        .sky;
        let got = sky_irradiance(
            luts.static_luts(),
            table,
            &camera(position, sun),
            position.as_vec3().to_array(),
            [0.0, 0.0, 1.0],
        )
        .map(f64::from);
        let error = (luminance(got) - luminance(expected)).abs() / luminance(expected);
        eprintln!(
            "sun {elevation:>4}°: sky_irradiance {:.5}, ground_irradiance {:.5} (luminance), {:.2} %",
            luminance(got),
            luminance(expected),
            100.0 * error
        );
        worst = worst.max(error);
    }
    // The same rung integrated by two quadratures (32 × 64 cells; the table's 32 × 32
    // directions) and the table's interpolation over μ_s.
    assert!(worst < 0.01, "{worst}");
}
