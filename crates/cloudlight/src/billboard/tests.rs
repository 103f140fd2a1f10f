use super::*;
use crate::CloudVolume;
use glam::DVec3;

fn camera() -> Camera {
    Camera::looking_at(
        DVec3::new(0.0, -1000.0, 0.0),
        DVec3::ZERO,
        DVec3::Z,
        FieldOfView::from_degrees(40.0),
        64,
        48,
    )
    .unwrap()
}

fn cube() -> CloudVolume {
    let mut density = vec![0.0f32; 27];
    density[13] = 0.9; // centre
    density[0] = 0.5;
    density[26] = 0.2; // below the threshold
    CloudVolume::new([3, 3, 3], [-75.0, -75.0, -75.0], 50.0, 0.01, density).unwrap()
}

#[test]
fn bad_input_names_field_and_value() {
    let v = cube();
    let light = vec![1.0f32; 27];
    let cam = camera();
    let mut s = BillboardSettings {
        density_threshold: f64::NAN,
        ..Default::default()
    };
    let e = billboards(&v, &light, &s, &cam).unwrap_err();
    assert!(e.to_string().contains("density_threshold = NaN"), "{e}");
    s.density_threshold = 1.5;
    let e = billboards(&v, &light, &s, &cam).unwrap_err();
    assert!(e.to_string().contains("density_threshold = 1.5"), "{e}");
    s.density_threshold = 0.3;
    assert_eq!(
        billboards(&v, &light[..5], &s, &cam),
        Err(BillboardError::LightLength { len: 5, cells: 27 })
    );
    let mut bad_light = light.clone();
    bad_light[4] = -1.0;
    assert_eq!(
        billboards(&v, &bad_light, &s, &cam),
        Err(BillboardError::BadLight {
            index: 4,
            value: -1.0
        })
    );
    s.sun_colour[1] = f64::INFINITY;
    let e = billboards(&v, &light, &s, &cam).unwrap_err();
    assert!(e.to_string().contains("sun_colour.g = inf"), "{e}");
    let e = Camera::new(
        DVec3::ZERO,
        DVec3::Z,
        DVec3::Z * 2.0,
        FieldOfView::from_degrees(40.0),
        8,
        8,
    )
    .unwrap_err();
    assert!(e.to_string().contains("camera.up = 0"), "{e}");
    let e = Camera::new(
        DVec3::ZERO,
        DVec3::X,
        DVec3::Z,
        FieldOfView::from_degrees(180.0),
        8,
        8,
    )
    .unwrap_err();
    assert!(e.to_string().contains("camera.vertical_fov"), "{e}");
    let e = Camera::new(
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::X,
        DVec3::Z,
        FieldOfView::from_degrees(40.0),
        8,
        8,
    )
    .unwrap_err();
    assert!(e.to_string().contains("camera.position.x = NaN"), "{e}");
    let e = Camera::new(
        DVec3::ZERO,
        DVec3::ZERO,
        DVec3::Z,
        FieldOfView::from_degrees(40.0),
        8,
        8,
    )
    .unwrap_err();
    assert!(e.to_string().contains("camera.look = 0"), "{e}");
    let e = Camera::new(
        DVec3::ZERO,
        DVec3::X,
        DVec3::Z,
        FieldOfView::from_degrees(40.0),
        0,
        8,
    )
    .unwrap_err();
    assert!(e.to_string().contains("camera.width = 0"), "{e}");
    let dense = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, 0.1, vec![1.5]).unwrap();
    let s = BillboardSettings {
        opacity: Opacity::Density,
        ..Default::default()
    };
    assert_eq!(
        billboards(&dense, &[1.0f64], &s, &cam),
        Err(BillboardError::DensityAboveOne {
            index: 0,
            value: 1.5
        })
    );
    assert!(splat_texture(0).is_err());
}

#[test]
fn particles_above_threshold_coloured_and_sorted_back_to_front() {
    let v = cube();
    let light: Vec<f64> = (0..27).map(|i| f64::from(i) / 26.0).collect();
    let s = BillboardSettings {
        sun_colour: [1.0, 0.5, 0.25],
        ..Default::default()
    };
    let b = billboards(&v, &light, &s, &camera()).unwrap();
    // Cells 0 (y = 0, nearer the camera at y = −1000) and 13; 26 is below 0.3.
    assert_eq!(b.iter().map(|b| b.cell).collect::<Vec<_>>(), vec![13, 0]);
    assert_eq!(b[0].centre, [0.0, 0.0, 0.0]);
    assert_eq!(b[1].centre, [-50.0, -50.0, -50.0]);
    assert!(b[0].depth > b[1].depth);
    let l = 13.0 / 26.0;
    assert_eq!(b[0].colour, [l, 0.5 * l, 0.25 * l]);
    let alpha = 1.0 - (-0.01f64 * 0.9f32 as f64 * 50.0).exp();
    assert!((b[0].alpha - alpha).abs() < 1e-15);
    // Equal depths keep cell order: a row of cells across the view.
    let row = CloudVolume::new([4, 1, 1], [-100.0, 0.0, 0.0], 50.0, 0.01, vec![0.5; 4]).unwrap();
    let b = billboards(&row, &[1.0f32; 4], &s, &camera()).unwrap();
    assert_eq!(b.iter().map(|b| b.cell).collect::<Vec<_>>(), [0, 1, 2, 3]);
    // Behind the camera or nearer than `near`: dropped.
    let behind = Camera::looking_at(
        DVec3::new(0.0, 1000.0, 0.0),
        DVec3::new(0.0, 2000.0, 0.0),
        DVec3::Z,
        FieldOfView::from_degrees(40.0),
        8,
        8,
    )
    .unwrap();
    assert!(billboards(&v, &light, &s, &behind).unwrap().is_empty());
}

#[test]
fn camera_inside_the_cloud_and_extreme_inputs_give_finite_images() {
    // A 6³ block of density 0…1e6 around the eye; huge σ_t; both size rules.
    let n = 6u32;
    let density: Vec<f32> = (0..n * n * n)
        .map(|i| [0.0, 0.31, 1.0, 1e6][i as usize % 4])
        .collect();
    let v = CloudVolume::new([n; 3], [-150.0; 3], 50.0, 1.0, density).unwrap();
    let light: Vec<f32> = (0..n * n * n).map(|i| [0.0, 1.0][i as usize % 2]).collect();
    for (eye, near) in [(DVec3::ZERO, 1.0), (DVec3::new(10.0, 3.0, -7.0), 1e-3)] {
        let cam = Camera::new(
            eye,
            DVec3::new(0.3, 1.0, 0.2),
            DVec3::Z,
            FieldOfView::from_degrees(90.0),
            32,
            24,
        )
        .unwrap();
        for (size, opacity) in [
            (SizeRule::default(), Opacity::default()),
            (
                SizeRule::World {
                    metres_per_density: 100.0,
                },
                Opacity::default(),
            ),
            (
                SizeRule::lattice(v.voxel_size()),
                Opacity::OpticalDepth { cells: 1.0 },
            ),
        ] {
            let s = BillboardSettings {
                size,
                opacity,
                near,
                ..Default::default()
            };
            let b = billboards(&v, &light, &s, &cam).unwrap();
            assert!(!b.is_empty());
            assert!(
                b.iter()
                    .all(|b| b.depth > near && (0.0..=1.0).contains(&b.alpha))
            );
            assert!(b.windows(2).all(|w| w[0].depth >= w[1].depth));
            let image = rasterise::<f64>(&b, &cam, size, opacity);
            assert!(image.rgba.iter().flatten().all(|c| c.is_finite()));
            // Premultiplied: 0 ≤ colour ≤ alpha ≤ 1 (sun colour 1, light ≤ 1).
            assert!(image.rgba.iter().all(|p| (0.0..=1.0).contains(&p[3])
                && p[..3].iter().all(|c| (0.0..=p[3] + 1e-12).contains(c))));
            let image = rasterise::<f32>(&b, &cam, size, opacity);
            assert!(
                image
                    .rgba
                    .iter()
                    .flatten()
                    .all(|c| c.is_finite() && *c >= 0.0)
            );
        }
    }
}

#[test]
fn limited_rasteriser_hides_billboards_behind_the_surface() {
    // Two billboards straight ahead at 1000 m and 1050 m (World size 100 m).
    let cam = camera();
    let two = CloudVolume::new([1, 2, 1], [-25.0, -25.0, -25.0], 50.0, 0.01, vec![1.0; 2]).unwrap();
    let s = BillboardSettings {
        size: SizeRule::World {
            metres_per_density: 100.0,
        },
        ..Default::default()
    };
    let b = billboards(&two, &[0.5f32, 1.0], &s, &cam).unwrap();
    let pixels = 64 * 48;
    let open = rasterise::<f64>(&b, &cam, s.size, s.opacity);
    let unlimited =
        rasterise_limited::<f64>(&b, &cam, s.size, s.opacity, &vec![f64::INFINITY; pixels])
            .unwrap();
    assert_eq!(open, unlimited);
    // A wall at 1025 m: only the nearer billboard (light 0.5) shows.
    let wall =
        rasterise_limited::<f64>(&b, &cam, s.size, s.opacity, &vec![1025.0; pixels]).unwrap();
    let near_only = rasterise::<f64>(&b[1..], &cam, s.size, s.opacity);
    assert_eq!(b[1].depth, 1000.0);
    assert_eq!(wall, near_only);
    // A wall at exactly a billboard's depth hides it (strictly less is drawn).
    let flush =
        rasterise_limited::<f32>(&b, &cam, s.size, s.opacity, &vec![1000.0; pixels]).unwrap();
    assert!(flush.rgba.iter().all(|p| *p == [0.0; 4]));
    assert_eq!(
        rasterise_limited::<f32>(&b, &cam, s.size, s.opacity, &[1.0; 3]),
        Err(BillboardError::DepthLength { len: 3, pixels })
    );
}

#[test]
fn splat_is_smooth_one_at_the_centre_zero_at_the_rim() {
    assert_eq!(splat_alpha(0.0f64), 1.0);
    assert_eq!(splat_alpha(1.0f64), 0.0);
    assert_eq!(splat_alpha(3.0f32), 0.0);
    assert!((splat_alpha(0.5f64) - 0.5625).abs() < 1e-15);
    // C¹ at the rim: the slope −4r(1 − r²) → 0.
    let e = 1e-6;
    assert!(splat_alpha(1.0 - e) / e < 1e-5);
    let t = splat_texture(4).unwrap();
    assert_eq!(t.len(), 16);
    let inner = splat_alpha((2.0f64 * 0.25 * 0.25).sqrt()) as f32;
    assert_eq!(t[5], inner);
    assert_eq!(t[0], 0.0); // corner texel: r = √(0.75² · 2) > 1
}

#[test]
fn rasteriser_composites_over_in_order_at_pixel_centres() {
    // One billboard straight ahead at 1000 m, World size 100 m: radius = 50·f/1000.
    let cam = camera();
    let one = CloudVolume::new([1, 1, 1], [-25.0, -25.0, -25.0], 50.0, 0.01, vec![1.0]).unwrap();
    let s = BillboardSettings {
        size: SizeRule::World {
            metres_per_density: 100.0,
        },
        ..Default::default()
    };
    let b = billboards(&one, &[0.5f32], &s, &cam).unwrap();
    let image = rasterise::<f64>(&b, &cam, s.size, s.opacity);
    let f = cam.focal_pixels();
    let radius = 50.0 * f / 1000.0;
    // Centre of the image (32, 24) is a pixel corner: the 4 nearest pixels are at
    // r = √0.5 / radius.
    let a = b[0].alpha * splat_alpha(0.5f64.sqrt() / radius);
    let p = image.rgba[31 + 64 * 23];
    assert!((p[3] - a).abs() < 1e-12, "{p:?} vs {a}");
    assert!((p[0] - 0.5 * a).abs() < 1e-12);
    // Outside the disc: untouched.
    assert_eq!(image.rgba[0], [0.0; 4]);
    let covered = image.rgba.iter().filter(|p| p[3] > 0.0).count() as f64;
    let disc = std::f64::consts::PI * radius * radius;
    assert!(
        (covered - disc).abs() < 2.0 * std::f64::consts::PI * radius,
        "{covered} vs {disc}"
    );
    // Two billboards at one pixel: over in order.
    let twice = [b[0], b[0]];
    let two = rasterise::<f64>(&twice, &cam, s.size, s.opacity);
    let q = two.rgba[31 + 64 * 23];
    assert!((q[3] - (a + (1.0 - a) * a)).abs() < 1e-12);
    // The f32 twin agrees with the reference to rounding.
    let image32 = rasterise::<f32>(&b, &cam, s.size, s.opacity);
    let worst = image
        .rgba
        .iter()
        .zip(&image32.rgba)
        .flat_map(|(p, q)| (0..4).map(move |c| (p[c] - f64::from(q[c])).abs()))
        .fold(0.0, f64::max);
    assert!(worst < 1e-5, "{worst}");
}

#[test]
fn particle_radiance_scatters_forward_and_adds_the_sky() {
    let scattering = ParticleScattering::default();
    let sun = |transmittance: f64| ParticleLight {
        direction: [1.0, 0.0, 0.0],
        irradiance: [2.0, 1.0, 0.5],
        transmittance,
    };
    let toward = particle_radiance([1.0, 0.0, 0.0], &[sun(0.5)], [0.0; 3], 1.0, &scattering);
    let away = particle_radiance([-1.0, 0.0, 0.0], &[sun(0.5)], [0.0; 3], 1.0, &scattering);
    // E · T · p(±1) with the march's phase.
    let p = |c: f64| crate::cone::dual_lobe_henyey_greenstein(c, 0.8, -0.3, 0.2);
    assert!((toward[0] - 2.0 * 0.5 * p(1.0)).abs() < 1e-12, "{toward:?}");
    assert!((away[2] - 0.5 * 0.5 * p(-1.0)).abs() < 1e-12, "{away:?}");
    assert!(toward[1] > 10.0 * away[1], "{toward:?} {away:?}");
    // In full shadow only the sky, times its visibility; two lights add.
    let shadowed = particle_radiance(
        [0.0, 1.0, 0.0],
        &[sun(0.0)],
        [0.1, 0.2, 0.3],
        0.5,
        &scattering,
    );
    assert_eq!(shadowed, [0.05, 0.1, 0.15]);
    let both = particle_radiance(
        [0.0, 1.0, 0.0],
        &[sun(0.5), sun(0.25)],
        [0.0; 3],
        1.0,
        &scattering,
    );
    let one = particle_radiance([0.0, 1.0, 0.0], &[sun(0.75)], [0.0; 3], 1.0, &scattering);
    assert!((both[0] - one[0]).abs() < 1e-12);
}
