// celestial::moon — the lit part of the moon's disc.
// Twin: crates/celestial/src/moon_phase.rs (Rust, generic over the float type; the f32
// instance mirrors this file): same name, argument order and units (disc radii,
// radians).

// Cosine of the sun's incidence on the moon's sphere at disc point (east, north) in
// disc radii (+north toward the celestial pole, +east toward celestial east), for
// phase angle i and bright-limb position angle chi; 0 on the dark side and outside.
// Normal n = (east, north, sqrt(1 - rho^2)), sun s = (sin i sin chi, sin i cos chi, cos i).
fn moon_disc_incidence_cosine(east: f32, north: f32, phase_angle: f32, bright_limb: f32) -> f32 {
    let rho2 = east * east + north * north;
    if rho2 > 1.0 {
        return 0.0;
    }
    let toward_observer = sqrt(1.0 - rho2);
    let sin_i = sin(phase_angle);
    let cos_i = cos(phase_angle);
    let sin_x = sin(bright_limb);
    let cos_x = cos(bright_limb);
    let incidence = east * sin_i * sin_x + north * sin_i * cos_x + toward_observer * cos_i;
    return max(incidence, 0.0);
}
