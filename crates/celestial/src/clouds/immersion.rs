//! Inside and between the layers: immersion, in-cloud transmittance and radiance, draw
//! order.

use super::*;
use crate::error::CelestialError;

/// ∫ immersion(h) dh (m) over the altitudes a ray from `altitude_m` crosses going up
/// (`upward`) or down to sea level: the layer's bands of immersion (smoothstep across
/// each transition, 1 inside), by Simpson's rule on 64 intervals per band (exact to
/// 10⁻⁶ of the band for the smoothstep's cubic).
pub fn immersion_column(layer: &CloudLayer, altitude_m: f64, upward: bool) -> f64 {
    let (low, high) = if upward {
        (altitude_m, f64::INFINITY)
    } else {
        (0.0f64.min(altitude_m), altitude_m)
    };
    let bands = [
        (layer.base_m - layer.transition_m, layer.base_m),
        (layer.base_m, layer.top_m()),
        (layer.top_m(), layer.top_m() + layer.transition_m),
    ];
    let mut total = 0.0;
    for (a, b) in bands {
        let (a, b) = (a.max(low), b.min(high));
        if b <= a {
            continue;
        }
        let n = 64;
        let h = (b - a) / f64::from(n);
        let mut sum = layer.immersion(a) + layer.immersion(b);
        for k in 1..n {
            let w = if k % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * layer.immersion(a + h * f64::from(k));
        }
        total += sum * h / 3.0;
    }
    total
}

/// Transmittance along a view of zenith cosine `mu` from `altitude_m` through the
/// layers' in-cloud extinction (the same per-layer extinction `modify_vis` closes the
/// visibility in with: immersion × coverage × 3.912/in-cloud visibility), on flat
/// bands (|μ| ≥ 10⁻³: a horizontal view inside a band sees no way out).
pub fn in_cloud_transmittance(layers: &[CloudLayer], altitude_m: f64, mu: f64) -> f64 {
    let slant = mu.abs().max(1e-3);
    let k = -crate::visibility::KOSCHMIEDER_CONTRAST.ln();
    let optical_depth: f64 = layers
        .iter()
        .map(|l| {
            l.coverage * k / l.in_cloud_visibility_m * immersion_column(l, altitude_m, mu > 0.0)
        })
        .sum();
    (-optical_depth / slant).exp()
}

/// The radiance of a layer's inside (the fog a viewer in it sees): the mean of its top's
/// reflected and its base's transmitted light at the element optical thickness, lit as
/// [`cloud_layer_radiance`] lights it (CPU only: the in-cloud fog is a CPU stage-2 step).
pub fn cloud_interior_radiance(layer: &CloudLayerUniforms) -> [f32; 3] {
    let tau = layer.optical_thickness;
    let mu_sun = layer.sun_direction[2];
    let reflected = cloud_reflectance(tau, layer.asymmetry, mu_sun);
    let direct = if mu_sun > 0.0 {
        (-tau / mu_sun).exp()
    } else {
        1.0
    };
    let transmitted = (1.0 - reflected - direct).max(0.0);
    let sky_reflected = cloud_reflectance(tau, layer.asymmetry, 0.5);
    let sky_transmitted = (1.0 - sky_reflected - (-tau / 0.5).exp()).max(0.0);
    std::array::from_fn(|i| {
        0.5 * ((reflected + transmitted) * layer.sunlight[i] * mu_sun.max(0.0)
            + (sky_reflected + sky_transmitted) * layer.skylight[i])
            * skyscape_wgsl::common::INV_PI
    })
}

/// The order in which to draw `layers` for a viewer at `altitude_m` (SGSky's
/// `postDraw`): farthest first — layers above the viewer by decreasing base, then
/// layers below by increasing top, so the nearest comes last. A layer the viewer is
/// inside is left out (it is drawn as fog, not as a sheet).
pub fn draw_order(layers: &[CloudLayer], altitude_m: f64) -> Vec<usize> {
    let mut above: Vec<usize> = (0..layers.len())
        .filter(|&i| layers[i].base_m > altitude_m)
        .collect();
    let mut below: Vec<usize> = (0..layers.len())
        .filter(|&i| layers[i].top_m() < altitude_m)
        .collect();
    above.sort_by(|&a, &b| layers[b].base_m.total_cmp(&layers[a].base_m));
    below.sort_by(|&a, &b| layers[a].top_m().total_cmp(&layers[b].top_m()));
    // Farthest first: whichever group's farthest layer is farther starts; the groups
    // do not overlap on screen (above: upward views, below: downward), so each group
    // only needs its own order.
    above.into_iter().chain(below).collect()
}

/// A typed error for an index past the list of layers.
pub(crate) fn no_layer(index: usize, count: usize) -> CelestialError {
    CelestialError::NoSuchIndex {
        field: "cloud layer index",
        index,
        count,
    }
}
