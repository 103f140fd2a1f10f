// Light sampling toward the sun (Schneider 2015's 6 cone samples + 1 far sample),
// Beer–Lambert, the powder term and dual-lobe Henyey–Greenstein (atmos' lobe, imported).
// Twin: cloudlight::cone (Rust, generic over the float type: the f32 instantiation mirrors
// these operations).
#import atmos::phase

// Sample i (0–5 cone, 6 far) of a light estimate: (offset from the shaded point in metres,
// weight in metres). Raw (partitioned = false): Schneider's layout, samples at (i + 1)·step,
// the far one at 9·step, every weight step. Partitioned: a quadrature of the path to the
// volume's exit: Δ = min(step, exit/7), midpoints (i + ½)Δ, the far sample at the midpoint
// of [6Δ, exit] with weight exit − 6Δ. The cone samples spread sideways by
// spread · distance along fixed unit kernel directions.
fn cone_sample(i: u32, to_sun: vec3<f32>, step: f32, exit_distance: f32, spread: f32, partitioned: bool) -> vec4<f32> {
    var distance: f32;
    var weight: f32;
    var lateral: f32;
    if !partitioned {
        if i < 6u {
            distance = f32(i + 1u) * step;
            weight = step;
            lateral = spread;
        } else {
            distance = 9.0 * step;
            weight = step;
            lateral = 0.0;
        }
    } else {
        let delta = min(step, exit_distance / 7.0);
        if i < 6u {
            distance = (f32(i) + 0.5) * delta;
            weight = delta;
            lateral = spread;
        } else {
            let near = 6.0 * delta;
            distance = 0.5 * (near + exit_distance);
            weight = max(exit_distance - near, 0.0);
            lateral = 0.0;
        }
    }
    let kernel = array<vec3<f32>, 6>(
        vec3<f32>(0.38051305, 0.92453450, -0.02111345),
        vec3<f32>(-0.50625799, -0.03590792, -0.86163418),
        vec3<f32>(-0.32509218, -0.94557439, 0.01428793),
        vec3<f32>(0.09026238, -0.27376545, 0.95755166),
        vec3<f32>(0.28128598, 0.42443639, -0.86065786),
        vec3<f32>(-0.16852403, 0.14748697, 0.97460107),
    );
    let k = kernel[min(i, 5u)];
    let side = lateral * distance;
    return vec4<f32>(
        to_sun.x * distance + side * k.x,
        to_sun.y * distance + side * k.y,
        to_sun.z * distance + side * k.z,
        weight,
    );
}

// Beer–Lambert: transmittance exp(−τ).
fn beer_lambert(optical_depth: f32) -> f32 {
    return exp(-optical_depth);
}

// Schneider's powder darkening 1 − exp(−2τ): not physical, an art-directed option.
fn powder(optical_depth: f32) -> f32 {
    return 1.0 - exp(-2.0 * optical_depth);
}

// (1 − w)·HG(g_forward) + w·HG(g_back), 1/sr, with atmos' Henyey–Greenstein.
fn dual_lobe_henyey_greenstein(cos_theta: f32, g_forward: f32, g_back: f32, back_weight: f32) -> f32 {
    let forward = henyey_greenstein_phase(cos_theta, g_forward);
    let back = henyey_greenstein_phase(cos_theta, g_back);
    return (1.0 - back_weight) * forward + back_weight * back;
}

// Distance from p along unit dir to where the ray leaves the box [lo, hi] (0 when p is
// outside and moving away; the largest finite f32 for a zero direction).
fn box_exit_distance(p: vec3<f32>, dir: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> f32 {
    var exit = 3.40282347e+38;
    for (var a = 0; a < 3; a++) {
        if dir[a] > 0.0 {
            exit = min(exit, (hi[a] - p[a]) / dir[a]);
        } else if dir[a] < 0.0 {
            exit = min(exit, (lo[a] - p[a]) / dir[a]);
        }
    }
    return max(exit, 0.0);
}
