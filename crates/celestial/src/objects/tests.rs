use super::*;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};

fn dir(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()]
}

/// The aureole is the Mie part of the per-pixel sky near the sun: against rung 2
/// (single scattering, 128/32 samples) of a Mie-only atmosphere, sun at 30°.
#[test]
fn aureole_matches_single_scattering_near_the_sun() {
    let atmosphere = Atmosphere {
        rayleigh_scattering: [0.0; 3],
        ozone_absorption: [0.0; 3],
        ..Atmosphere::earth()
    };
    let model = SingleScatteringSky::new(
        &atmosphere,
        SingleScatteringSettings {
            view_samples: 128,
            light_samples: 32,
        },
    )
    .unwrap();
    let sun = dir(30.0, 180.0);
    let builder = SkyObjectsBuilder::new(
        &atmosphere,
        &model,
        0.0,
        sun,
        crate::sun::ASTRONOMICAL_UNIT_M,
        None,
        BackgroundSampling::PerObject,
    )
    .unwrap();
    let aureole = builder.aureole().unwrap();
    let error = |view: [f64; 3]| {
        let exact = builder.sky(view).unwrap().radiance[1];
        let drawn = f64::from(aureole.radiance(view.map(|c| c as f32))[1]);
        (drawn - exact) / exact
    };
    let mut rows = Vec::new();
    for offset in [0.25, 0.5, 1.0, 2.0, 5.0] {
        // Above, below and beside the sun (the azimuth offset for a great-circle
        // offset θ at elevation 30°).
        let above = error(dir(30.0 + offset, 180.0));
        let below = error(dir(30.0 - offset, 180.0));
        let beside = error(dir(30.0, 180.0 + offset / 30f64.to_radians().cos()));
        rows.push((offset, above, below, beside));
    }
    println!("aureole vs single scattering (θ°, above, below, beside): {rows:?}");
    for (offset, above, below, beside) in rows {
        // First order in θ: the view path tilts against the sun's (its Mie optical
        // depth differs by ≈ θ·cot e), which cancels between opposite sides.
        for e in [above, below] {
            assert!(e.abs() < 0.035 * offset, "θ = {offset}°: {e}");
        }
        assert!(
            ((above + below) / 2.0).abs() < 0.01 * offset.max(1.0),
            "θ = {offset}°"
        );
        assert!(
            beside.abs() < 0.01 * offset.max(1.0),
            "θ = {offset}°: beside {beside}"
        );
    }
}

#[test]
fn sun_disc_is_red_at_the_horizon_and_fades_below() {
    let atmosphere = Atmosphere::earth();
    let model = atmos::closed_form_sky::ClosedFormSky::new(&atmosphere).unwrap();
    let make = |elevation: f64| {
        SkyObjectsBuilder::new(
            &atmosphere,
            &model,
            2.0,
            dir(elevation, 270.0),
            crate::sun::ASTRONOMICAL_UNIT_M,
            None,
            BackgroundSampling::PerObject,
        )
        .unwrap()
        .sun_disc()
        .unwrap()
    };
    let high = make(60.0);
    let low = make(0.5);
    let t = |d: &DiscObject| d.log_transmittance.map(f32::exp);
    assert!(t(&high)[2] > 0.6 && t(&high)[0] > 0.85, "{:?}", t(&high));
    // Near the horizon blue is all but gone and red dims.
    assert!(
        t(&low)[2] < 0.05 && t(&low)[0] > 5.0 * t(&low)[2],
        "{:?}",
        t(&low)
    );
    // Transmittance falls toward the lower limb (slope in μ is positive).
    assert!(low.log_transmittance_slope.iter().all(|&s| s > 0.0));
    // The disc's total irradiance is the atmosphere's (quadrature over the disc).
    let n = 400;
    let sin_r = high.sin_radius as f64;
    let mut sum = [0.0f64; 3];
    let centre = DVec3::from_array(high.direction.map(f64::from));
    let e = centre.cross(DVec3::Z).normalize();
    let nn = e.cross(centre);
    let step = 2.0 * sin_r / n as f64;
    let flat = DiscObject {
        log_transmittance: [0.0; 3],
        log_transmittance_slope: [0.0; 3],
        log_transmittance_curvature: [0.0; 3],
        ..high
    };
    for a in 0..n {
        for b in 0..n {
            let x = -sin_r + (a as f64 + 0.5) * step;
            let y = -sin_r + (b as f64 + 0.5) * step;
            let v = (centre + e * x + nn * y).normalize();
            let l = draw::disc_object_radiance(
                v.as_vec3().to_array(),
                &flat,
                [0.0, 0.0, 1.0],
                6_360_002.0,
                6_360_000.0,
            );
            for i in 0..3 {
                sum[i] += f64::from(l[i]) * step * step;
            }
        }
    }
    for s in sum {
        assert!((s - 1.0).abs() < 5e-3, "{sum:?}");
    }
}
