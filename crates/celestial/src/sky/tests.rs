use super::*;
use crate::clouds::CloudKind;

#[test]
fn puffs_are_deterministic_and_frame_rate_independent() {
    let mut active = 0;
    for k in 0..20_000 {
        let t = f64::from(k) * 0.05;
        let e = puff_envelope(3, t);
        assert!((0.0..=1.0).contains(&e));
        active += usize::from(e > 0.0);
        assert_eq!(e, puff_envelope(3, t));
    }
    // Puffs happen, but not all the time.
    assert!(active > 100 && active < 19_000, "{active}");
    assert_ne!(
        (0..2000)
            .map(|k| puff_envelope(3, f64::from(k) * 0.05))
            .sum::<f64>(),
        (0..2000)
            .map(|k| puff_envelope(4, f64::from(k) * 0.05))
            .sum::<f64>()
    );
}

#[test]
fn visibility_closes_in_and_reopens_whatever_the_step() {
    let mut coarse = Sky::build(Atmosphere::earth(), SkyOptions::default()).unwrap();
    coarse.set_visibility(20_000.0).unwrap();
    let layer = CloudLayer::new(1000.0, 500.0, 200.0, 40_000.0, CloudKind::Stratus).unwrap();
    coarse.add_cloud_layer(layer).unwrap();
    let mut fine = Sky::build(Atmosphere::earth(), SkyOptions::default()).unwrap();
    fine.set_visibility(20_000.0).unwrap();
    fine.add_cloud_layer(coarse.cloud_layer(0).unwrap().clone())
        .unwrap();
    // Far below: the clear visibility; inside: the cloud's 25 m (coverage 1).
    assert!((coarse.modify_vis(0.0, 0.0).unwrap() - 20_000.0).abs() < 1e-6);
    let inside = coarse.modify_vis(1200.0, 0.0).unwrap();
    assert!(
        (inside - 1.0 / (1.0 / 20_000.0 + 1.0 / 25.0)).abs() < 1e-9,
        "{inside}"
    );
    // The same accumulated time in 1 step or 100 gives the same visibility.
    let a = coarse.modify_vis(900.0, 10.0).unwrap();
    for _ in 0..100 {
        fine.modify_vis(900.0, 0.1).unwrap();
    }
    assert!((fine.visibility() - a).abs() < 1e-9 * a);
    // Bad input names the field.
    assert!(
        coarse
            .modify_vis(f64::NAN, 0.1)
            .unwrap_err()
            .to_string()
            .contains("altitude_m")
    );
    assert!(
        coarse
            .modify_vis(0.0, -1.0)
            .unwrap_err()
            .to_string()
            .contains("dt_s")
    );
    assert!(
        coarse
            .set_visibility(0.0)
            .unwrap_err()
            .to_string()
            .contains("visibility_m")
    );
    assert!(
        coarse
            .remove_cloud_layer(3)
            .unwrap_err()
            .to_string()
            .contains("cloud layer index")
    );
}
