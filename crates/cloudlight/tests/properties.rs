//! Property tests over extreme inputs: densities 0 and huge
//! (up to f32::MAX), σ_t from 0 to 1 /m, the sun at the horizon and below, grids from
//! 1×1×1 to a few hundred cells along an axis, rays starting inside the cloud. Every
//! result is finite, transmittance and light lie in [0, 1], and bad input is a typed
//! error, never a panic or NaN. Covered: the slice propagation (physical with both
//! resamplings, faithful), the 6 + 1 cone and the full light march through
//! [`LightRay`], the exact reference's transmittance, the shadow map (f32 twin, f64
//! march and the exact map). Cases are capped so the file runs in seconds in debug:
//!
//! ```sh
//! cargo test -p cloudlight --test properties
//! ```

use cloudlight::CloudVolume;
use cloudlight::cone::{ConeSettings, ConeWeights, FullMarchSettings, LightRay, beer_lambert};
use cloudlight::propagate::{Resampling, SliceMode, SlicePlan, propagate};
use cloudlight::reference;
use cloudlight::shadow_map::{ShadowGrid, ShadowMapPlan, shadow_map, shadow_map_reference};
use proptest::prelude::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 200,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// One density: zero, ordinary, at most 1 (faithful mode's range), or huge.
fn density_value() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => Just(0.0f32),
        4 => 0.0f32..=1.0,
        1 => Just(1.0f32),
        1 => 1.0f32..1e6,
        1 => Just(f32::MAX),
        1 => 1e30f32..f32::MAX,
    ]
}

/// Grid sizes: small cubes or one long axis (up to 300 cells), the others 1–2.
fn dims() -> impl Strategy<Value = [u32; 3]> {
    prop_oneof![
        3 => [1u32..=6, 1u32..=6, 1u32..=6],
        1 => (1u32..=300, 1u32..=2, 1u32..=2, 0usize..3).prop_map(|(n, a, b, r)| {
            let mut d = [n, a, b];
            d.rotate_left(r);
            d
        }),
        1 => Just([1, 1, 1]),
    ]
}

/// A volume with σ_t in [0, 1] /m (0 and 1 included), cells of 0.5 m to 1 km.
fn volume() -> impl Strategy<Value = CloudVolume> {
    let sigma = prop_oneof![Just(0.0f64), Just(1.0f64), 0.0f64..=1.0, 1e-6f64..1e-2];
    (
        dims(),
        sigma,
        0.5f64..1000.0,
        [-5e3f64..5e3, -5e3f64..5e3, -1e3f64..5e3],
    )
        .prop_flat_map(|(d, sigma, voxel, origin)| {
            let n = (d[0] * d[1] * d[2]) as usize;
            proptest::collection::vec(density_value(), n).prop_map(move |density| {
                CloudVolume::new(d, origin, voxel, sigma, density).expect("valid by construction")
            })
        })
}

/// Directions toward the sun: anywhere, exactly on the horizon, below it, along axes.
fn to_sun() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        3 => (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
            .prop_filter("non-zero", |(x, y, z)| x * x + y * y + z * z > 1e-6)
            .prop_map(|(x, y, z)| [x, y, z]),
        1 => (0.0f64..std::f64::consts::TAU).prop_map(|a| [a.cos(), a.sin(), 0.0]),
        1 => (0.0f64..std::f64::consts::TAU, -1.0f64..-1e-4)
            .prop_map(|(a, z)| [a.cos(), a.sin(), z]),
        1 => prop_oneof![
            Just([0.0, 0.0, 1.0]),
            Just([0.0, 0.0, -1.0]),
            Just([1.0, 0.0, 0.0]),
            Just([0.0, -1.0, 0.0]),
        ],
    ]
}

/// A point inside the volume's box (fractions of its extent), or well outside it.
fn point_in(v: &CloudVolume, fraction: [f64; 3]) -> [f64; 3] {
    let (o, d, s) = (v.origin(), v.dims(), v.voxel_size());
    [0, 1, 2].map(|a| o[a] + fraction[a] * f64::from(d[a]) * s)
}

fn in_unit(x: f64) -> bool {
    x.is_finite() && (0.0..=1.0).contains(&x)
}

/// A value that is not a valid finite number for a direction or a length.
fn bad_number() -> impl Strategy<Value = f64> {
    prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY)]
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn propagation_light_is_finite_and_in_unit_range(
        v in volume(),
        l in to_sun(),
        ratio in 0.0f64..=1.0,
    ) {
        for resampling in [Resampling::CatmullRom, Resampling::Bilinear] {
            let plan = SlicePlan::new(&v, l, SliceMode::Physical).unwrap().with_resampling(resampling);
            for x in propagate::<f32>(&v, &plan).unwrap() {
                prop_assert!(in_unit(f64::from(x)), "physical f32 {resampling:?}: {x}");
            }
            for x in propagate::<f64>(&v, &plan).unwrap() {
                prop_assert!(in_unit(x), "physical f64 {resampling:?}: {x}");
            }
        }
        let faithful = SliceMode::Faithful { attenuation_ratio: ratio };
        let max = v.density().iter().copied().fold(0.0f32, f32::max);
        match SlicePlan::new(&v, l, faithful) {
            Ok(plan) => {
                prop_assert!(max <= 1.0);
                for x in propagate::<f32>(&v, &plan).unwrap() {
                    prop_assert!(in_unit(f64::from(x)), "faithful: {x}");
                }
            }
            Err(e) => {
                prop_assert!(max > 1.0, "refused a valid faithful plan: {e}");
                prop_assert!(e.to_string().starts_with("max density = "), "{e}");
            }
        }
    }

    #[test]
    fn bad_slice_settings_are_errors(
        v in volume(),
        bad in bad_number(),
        ratio in prop_oneof![-10.0f64..-1e-9, 1.0 + 1e-9..10.0],
    ) {
        let err = SlicePlan::new(&v, [0.0, bad, 1.0], SliceMode::Physical).unwrap_err();
        prop_assert!(err.to_string().starts_with("to_sun.y = "), "{err}");
        prop_assert!(SlicePlan::new(&v, [0.0; 3], SliceMode::Physical).is_err());
        let faithful = SliceMode::Faithful { attenuation_ratio: ratio };
        let err = SlicePlan::new(&v, [0.0, 0.0, 1.0], faithful).unwrap_err();
        prop_assert!(err.to_string().starts_with("attenuation_ratio = "), "{err}");
        // A plan for another volume: an error naming both sizes, not a panic.
        let d = v.dims();
        let other = CloudVolume::new([d[0] + 1, d[1], d[2]], [0.0; 3], 1.0, 0.1,
            vec![0.0; ((d[0] + 1) * d[1] * d[2]) as usize]).unwrap();
        let plan = SlicePlan::new(&other, [0.0, 0.0, 1.0], SliceMode::Physical).unwrap();
        let err = propagate::<f32>(&v, &plan).unwrap_err();
        prop_assert!(err.to_string().starts_with("plan is for a "), "{err}");
        prop_assert!(propagate::<f64>(&other, &plan).is_ok());
    }

    #[test]
    fn cone_and_march_light_is_finite_and_in_unit_range(
        v in volume(),
        l in to_sun(),
        fraction in [-0.5f64..1.5, -0.5f64..1.5, -0.5f64..1.5],
        step in prop_oneof![1e-3f64..1.0, 1.0f64..1e4],
        spread in 0.0f64..2.0,
        steps in 1u32..=128,
    ) {
        let p = point_in(&v, fraction);
        let ray = LightRay::through(&v, p, l).unwrap();
        prop_assert!(ray.exit_distance().is_finite() && ray.exit_distance() >= 0.0);
        let march = FullMarchSettings::new(steps).unwrap();
        for weights in [ConeWeights::Raw, ConeWeights::Partitioned] {
            let cone = ConeSettings::new(step, spread, weights).unwrap();
            let tau32: f32 = ray.cone_optical_depth(&v, &cone);
            let tau64: f64 = ray.cone_optical_depth(&v, &cone);
            prop_assert!(tau32 >= 0.0 && !tau32.is_nan(), "cone f32 τ {tau32}");
            prop_assert!(tau64 >= 0.0 && !tau64.is_nan(), "cone f64 τ {tau64}");
            prop_assert!(in_unit(f64::from(beer_lambert(tau32))));
            prop_assert!(in_unit(beer_lambert(tau64)));
        }
        let tau32: f32 = ray.march_optical_depth(&v, &march);
        let tau64: f64 = ray.march_optical_depth(&v, &march);
        prop_assert!(tau32 >= 0.0 && !tau32.is_nan(), "march f32 τ {tau32}");
        prop_assert!(tau64 >= 0.0 && !tau64.is_nan(), "march f64 τ {tau64}");
        prop_assert!(in_unit(f64::from(beer_lambert(tau32))));
        prop_assert!(in_unit(beer_lambert(tau64)));
    }

    #[test]
    fn bad_cone_and_march_input_is_an_error(
        bad in bad_number(),
        negative in -1e6f64..=0.0,
    ) {
        let err = LightRay::new([0.0; 3], [bad, 0.0, 1.0], 1.0).unwrap_err();
        prop_assert!(err.to_string().starts_with("to_sun.x = "), "{err}");
        let err = LightRay::new([0.0, 0.0, bad], [0.0, 0.0, 1.0], 1.0).unwrap_err();
        prop_assert!(err.to_string().starts_with("point.z = "), "{err}");
        prop_assert!(LightRay::new([0.0; 3], [0.0; 3], 1.0).is_err());
        let err = LightRay::new([0.0; 3], [0.0, 0.0, 1.0], bad).unwrap_err();
        prop_assert!(err.to_string().starts_with("exit_distance = "), "{err}");
        if negative < 0.0 {
            prop_assert!(LightRay::new([0.0; 3], [0.0, 0.0, 1.0], negative).is_err());
        }
        let err = ConeSettings::new(negative, 0.1, ConeWeights::Raw).unwrap_err();
        prop_assert!(err.to_string().starts_with("step = "), "{err}");
        let err = ConeSettings::new(bad, 0.1, ConeWeights::Partitioned).unwrap_err();
        prop_assert!(err.to_string().starts_with("step = "), "{err}");
        let err = ConeSettings::new(1.0, bad, ConeWeights::Raw).unwrap_err();
        prop_assert!(err.to_string().starts_with("spread = "), "{err}");
        prop_assert!(FullMarchSettings::new(0).is_err());
    }

    #[test]
    fn reference_transmittance_is_in_unit_range(
        v in volume(),
        l in to_sun(),
        fraction in [-0.5f64..1.5, -0.5f64..1.5, -0.5f64..1.5],
        length in prop_oneof![Just(f64::INFINITY), Just(0.0f64), 0.0f64..1e5],
        bad in bad_number(),
    ) {
        let p = point_in(&v, fraction);
        let t = reference::transmittance(&v, p, l, length).unwrap();
        prop_assert!(in_unit(t), "{t}");
        let tau = reference::optical_depth(&v, p, l, length).unwrap();
        prop_assert!(tau >= 0.0 && !tau.is_nan(), "{tau}");
        prop_assert!(reference::transmittance(&v, p, [bad, 0.0, 1.0], length).is_err());
        prop_assert!(reference::transmittance(&v, [bad, 0.0, 0.0], l, length).is_err());
        prop_assert!(reference::transmittance(&v, p, [0.0; 3], length).is_err());
        prop_assert!(reference::transmittance(&v, p, l, -1.0).is_err());
    }

    #[test]
    fn shadow_maps_are_in_unit_range(
        v in volume(),
        l in to_sun(),
        resolution in [1u32..=6, 1u32..=6],
        cell in prop_oneof![0.1f64..10.0, 10.0f64..2000.0],
        ground_fraction in prop_oneof![Just(-0.5f64), -0.2f64..1.2],
        steps in 1u32..=64,
    ) {
        let lo = point_in(&v, [-0.3, -0.3, ground_fraction]);
        let grid = ShadowGrid::new([lo[0], lo[1]], cell, resolution, lo[2]).unwrap();
        let plan = ShadowMapPlan::new(grid, l, steps).unwrap();
        for t in shadow_map::<f32, _>(&v, &plan) {
            prop_assert!(in_unit(f64::from(t)), "f32 twin {t}");
        }
        for t in shadow_map::<f64, _>(&v, &plan) {
            prop_assert!(in_unit(t), "f64 march {t}");
        }
        for t in shadow_map_reference(&v, &plan).unwrap() {
            prop_assert!(in_unit(t), "exact {t}");
        }
    }

    #[test]
    fn bad_shadow_map_input_is_an_error(
        bad in bad_number(),
        cell in -1e3f64..=0.0,
        steps in prop_oneof![Just(0u32), 4097u32..u32::MAX],
    ) {
        prop_assert!(ShadowGrid::new([bad, 0.0], 1.0, [4, 4], 0.0).is_err());
        prop_assert!(ShadowGrid::new([0.0, 0.0], cell, [4, 4], 0.0).is_err());
        prop_assert!(ShadowGrid::new([0.0, 0.0], bad, [4, 4], 0.0).is_err());
        prop_assert!(ShadowGrid::new([0.0, 0.0], 1.0, [0, 4], 0.0).is_err());
        prop_assert!(ShadowGrid::new([0.0, 0.0], 1.0, [4, 4], bad).is_err());
        let grid = ShadowGrid::new([0.0, 0.0], 1.0, [4, 4], 0.0).unwrap();
        let err = ShadowMapPlan::new(grid, [0.0, 0.0, 1.0], steps).unwrap_err();
        prop_assert!(err.to_string().starts_with("steps = "), "{err}");
        let err = ShadowMapPlan::new(grid, [0.0, bad, 1.0], 8).unwrap_err();
        prop_assert!(err.to_string().starts_with("to_sun.y = "), "{err}");
        prop_assert!(ShadowMapPlan::new(grid, [0.0; 3], 8).is_err());
    }
}
