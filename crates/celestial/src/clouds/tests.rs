#[test]
fn a_cloud_shadow_is_the_direct_term_where_the_sun_crosses_the_base() {
    let layer = CloudLayer {
        coverage: 0.5,
        seed: 3,
        ..CloudLayer::new(2000.0, 400.0, 100.0, 40_000.0, CloudKind::Cumulus).unwrap()
    };
    let frame = |sun: [f64; 3]| CloudLayerFrame {
        planet_radius_m: 6_360_000.0,
        offset_m: [0.0, 0.0],
        fog_extinction_per_m: 0.0,
        exp2_fog: false,
        sun_direction: sun,
        sunlight: [1.0; 3],
        skylight: [0.1; 3],
        fog_colour: [0.0; 3],
    };
    let (s, c) = (0.6f64, 0.8f64);
    let u = layer.uniforms(&frame([0.0, s, c]));
    let r = 6_360_000.0 + 500.0;
    let (mut shaded, mut clear) = (0, 0);
    for k in 0..400 {
        let point = [
            (k % 20) as f32 * 700.0 - 7000.0,
            (k / 20) as f32 * 700.0 - 7000.0,
            -200.0,
        ];
        let shadow = cloud_shadow(point, r, &u);
        // The sun's ray from 300 m up climbs 1,700 m to the base: 1,275 m north.
        let crossing = [point[0], point[1] + 1700.0 * 0.75];
        let density = cloud_density(crossing[0], crossing[1], &u);
        let expected = (-u.optical_thickness * density / 0.8).exp();
        assert!((shadow - expected).abs() < 1e-4, "{shadow} {expected}");
        shaded += usize::from(shadow < 0.5);
        clear += usize::from(shadow == 1.0);
        // Above the top, or with the sun down: no shadow.
        assert_eq!(cloud_shadow([point[0], point[1], 2000.0], r, &u), 1.0);
        let night = layer.uniforms(&frame([0.0, 0.6, -0.8]));
        assert_eq!(cloud_shadow(point, r, &night), 1.0);
    }
    // Half coverage: both shadowed and sunlit ground.
    assert!(shaded > 50 && clear > 50, "{shaded} {clear}");
}

use super::*;
use crate::error::Result;

fn frame() -> CloudLayerFrame {
    CloudLayerFrame {
        planet_radius_m: 6_360_000.0,
        offset_m: [0.0, 0.0],
        fog_extinction_per_m: 3.912 / 30_000.0,
        exp2_fog: false,
        sun_direction: [0.0, 0.6, 0.8],
        sunlight: [1.0, 0.95, 0.9],
        skylight: [0.3, 0.4, 0.6],
        fog_colour: [0.2, 0.25, 0.3],
    }
}

#[test]
fn coverage_is_the_covered_fraction() {
    for kind in CloudKind::ALL {
        for coverage in [0.1, 0.3, 0.5, 0.8] {
            let layer = CloudLayer {
                coverage,
                seed: 7,
                ..CloudLayer::new(2000.0, 300.0, 200.0, 40_000.0, kind).unwrap()
            };
            let u = layer.uniforms(&frame());
            // A different sample set than the threshold's: 200 × 200 points half a
            // feature apart (10⁴ features of the first octave).
            let step = 0.5 * kind.parameters().feature_size_m as f32;
            let mut cloudy = 0usize;
            for i in 0..200 {
                for j in 0..200 {
                    let d = cloud_density(
                        i as f32 * step * u.stretch + 13.0,
                        j as f32 * step + 71.0,
                        &u,
                    );
                    cloudy += usize::from(d > 0.5);
                }
            }
            let fraction = cloudy as f64 / 40_000.0;
            assert!(
                (fraction - coverage).abs() < 0.05,
                "{kind:?} coverage {coverage}: measured {fraction}"
            );
        }
    }
}

#[test]
fn reflectance_limits() {
    // Thin: ~τ/μ-ish small; thick: → 1; conservative: R + T ≤ 1.
    assert!(cloud_reflectance(0.01, 0.85, 1.0) < 0.01);
    assert!(cloud_reflectance(1000.0, 0.85, 0.7) > 0.98);
    for tau in [0.5, 3.0, 9.0, 30.0] {
        let r = cloud_reflectance(tau, 0.85, 0.6);
        assert!((0.0..=1.0).contains(&r));
    }
    // Thick stratus (τ 30) reflects 70–85 % of overhead sun (Lacis & Hansen's
    // formula gives 0.818; satellite albedos of such decks are 0.6–0.8).
    let r = cloud_reflectance(30.0, 0.85, 1.0);
    assert!((0.6..0.85).contains(&r), "{r}");
    assert_eq!(cloud_reflectance(10.0, 0.85, -0.1), 0.0);
}

#[test]
fn layer_distance_flat_and_curved() {
    let r = 6_361_000.0f32;
    // Straight up to a layer 1 km above: 1 km either way.
    assert!((cloud_layer_distance(r, 1.0, r + 1000.0, 0) - 1000.0).abs() < 0.1);
    assert!((cloud_layer_distance(r, 1.0, r + 1000.0, 1) - 1000.0).abs() < 0.2);
    // Horizontal view: a flat layer is never reached, a curved one is (the Earth
    // falls away beneath the view), √(2Rh) ≈ 113 km.
    assert_eq!(cloud_layer_distance(r, 0.0, r + 1000.0, 0), -1.0);
    let d = cloud_layer_distance(r, 0.0, r + 1000.0, 1);
    assert!((d - 112_800.0).abs() < 500.0, "{d}");
    // Looking up at a layer below: missed.
    assert_eq!(cloud_layer_distance(r, 0.5, r - 500.0, 0), -1.0);
    assert_eq!(cloud_layer_distance(r, 0.5, r - 500.0, 1), -1.0);
}

#[test]
fn immersion_and_draw_order() {
    let layer = CloudLayer::new(1000.0, 500.0, 200.0, 40_000.0, CloudKind::Stratus).unwrap();
    assert_eq!(layer.immersion(0.0), 0.0);
    assert_eq!(layer.immersion(799.0), 0.0);
    assert!((layer.immersion(900.0) - 0.5).abs() < 1e-12);
    assert_eq!(layer.immersion(1200.0), 1.0);
    assert!((layer.immersion(1600.0) - 0.5).abs() < 1e-12);
    assert_eq!(layer.immersion(1800.0), 0.0);
    let layers: Vec<CloudLayer> = [500.0, 3000.0, 8000.0, 1500.0]
        .iter()
        .map(|&b| CloudLayer::new(b, 100.0, 50.0, 40_000.0, CloudKind::Cumulus).unwrap())
        .collect();
    // Viewer at 2 km: above it 8000 then 3000; below it 500 then 1500 (nearest last).
    assert_eq!(draw_order(&layers, 2000.0), vec![2, 1, 0, 3]);
    assert!(draw_order(&[], 2000.0).is_empty());
    // Inside the 1500 m layer: it is left out.
    assert_eq!(draw_order(&layers, 1550.0), vec![2, 1, 0]);
}

#[test]
fn in_cloud_fog_column() {
    let layer = CloudLayer::new(1000.0, 500.0, 200.0, 40_000.0, CloudKind::Stratus).unwrap();
    // From the ground looking up: both ramps (half each) and the core: 200 + 500.
    assert!((immersion_column(&layer, 0.0, true) - 700.0).abs() < 1e-6);
    assert!(immersion_column(&layer, 0.0, false).abs() < 1e-12);
    // From the middle: half the core and one ramp each way.
    assert!((immersion_column(&layer, 1250.0, true) - 350.0).abs() < 1e-6);
    assert!((immersion_column(&layer, 1250.0, false) - 350.0).abs() < 1e-6);
    let t = in_cloud_transmittance(std::slice::from_ref(&layer), 1250.0, 1.0);
    assert!((t - (-3.912_023_005 / 25.0 * 350.0_f64).exp()).abs() < 1e-12);
    assert_eq!(in_cloud_transmittance(&[], 1250.0, 0.3), 1.0);
}

#[test]
fn bad_layers_name_the_field() {
    let e = |r: Result<CloudLayer>| r.unwrap_err().to_string();
    assert!(e(CloudLayer::new(f64::NAN, 1.0, 1.0, 1.0, CloudKind::Cirrus)).contains("base_m"));
    assert!(e(CloudLayer::new(1.0, -1.0, 1.0, 1.0, CloudKind::Cirrus)).contains("thickness_m"));
    assert!(e(CloudLayer::new(1.0, 1.0, 1.0, 0.0, CloudKind::Cirrus)).contains("span_m"));
    let bad = CloudLayer {
        coverage: 1.5,
        ..CloudLayer::new(1.0, 1.0, 1.0, 1000.0, CloudKind::Cirrus).unwrap()
    };
    assert!(bad.validate().unwrap_err().to_string().contains("coverage"));
}

#[test]
fn layers_fade_into_fog_and_hide_from_inside() {
    let layer = CloudLayer::new(2000.0, 400.0, 200.0, 200_000.0, CloudKind::Overcast).unwrap();
    let u = layer.uniforms(&frame());
    let r = 6_360_000.0 + 500.0;
    let background = [0.1, 0.2, 0.5];
    // Overhead: the overcast deck, grey-white, opaque.
    let up = cloud_layer_radiance([0.0, 0.0, 1.0], r, &u, background);
    assert!(up != background);
    // Toward the horizon through 30 km visibility: the layer is nearly the fog.
    let view = [0.0, 0.999_f32.sqrt(), 0.031_6];
    let far = cloud_layer_radiance(view, r, &u, background);
    for i in 0..3 {
        assert!(
            (far[i] - frame().fog_colour[i] as f32).abs() < 0.05,
            "{far:?}"
        );
    }
    // Inside the layer nothing is drawn.
    let inside = cloud_layer_radiance([0.0, 0.0, 1.0], 6_360_000.0 + 2100.0, &u, background);
    assert_eq!(inside, background);
}
