// Rung 2 of the scattering ladder: single scattering in a spherical atmosphere
// (Nishita et al. 1993, O'Neil 2005).
// Twin: atmos::single_scattering (f32) and atmos::reference (f64), same names,
// arguments and units (metres, 1/m, cosines in the r/mu/mu_s/nu convention).
//
// Radiance is in the unit of sun_irradiance per steradian; transmittance is that of
// the view segment. The camera may be anywhere from below the ground (treated as on
// it) to deep space: outside the shell the segment starts where the ray enters it.
#import atmos::atmosphere
#import atmos::phase
#import atmos::geometry
#import atmos::transmittance

// Radiance scattered toward the viewer and transmittance of the segment.
struct SingleScatteringSample {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

// Relative densities at an altitude: (Rayleigh, Mie, ozone), each 1 at its reference.
fn density_profile(atmosphere: AtmosphereParameters, altitude: f32) -> vec3<f32> {
    return vec3<f32>(
        exponential_density(altitude, atmosphere.rayleigh_scale_height),
        exponential_density(altitude, atmosphere.mie_scale_height),
        tent_density(altitude, atmosphere.ozone_center_altitude, atmosphere.ozone_half_width),
    );
}

// Extinction (1/m) per channel from relative densities (Rayleigh, Mie, ozone); also
// turns optical lengths (m) into optical depths, the map being linear.
fn extinction_from_densities(atmosphere: AtmosphereParameters, densities: vec3<f32>) -> vec3<f32> {
    return atmosphere.rayleigh_scattering * densities.x
        + atmosphere.mie_extinction * densities.y
        + atmosphere.ozone_absorption * densities.z;
}

// Distance along a ray of length ray_length (m) at parameter s ∈ [0, 1]: quadratic on
// each side of t_split, so samples crowd where the ray passes lowest (the densest air:
// the camera for rays looking up, the ground for rays that meet it, the tangent point
// for rays that graze the planet) and t(0) = 0, t(t_split/ray_length) = t_split,
// t(1) = ray_length. The segments depend only on the whole ray, never on where a caller
// cuts it, so cutting later only adds light (aerial perspective is monotone).
fn ray_sample_distance(s: f32, t_split: f32, ray_length: f32) -> f32 {
    let s_split = t_split / ray_length;
    if s <= s_split && s_split > 0.0 {
        let x = (s_split - s) / s_split;
        return t_split - t_split * x * x;
    }
    let x = (s - s_split) / (1.0 - s_split);
    return t_split + (ray_length - t_split) * x * x;
}

// Where a ray from (r, mu) of length ray_length passes closest to the planet centre.
fn lowest_point_distance(r: f32, mu: f32, ray_length: f32) -> f32 {
    return clamp(-r * mu, 0.0, ray_length);
}

// ∫₀^ray_length density(altitude(t)) dt (m) for (Rayleigh, Mie, ozone): sample_count
// segments (at least one) laid out by ray_sample_distance, each sampled at its
// parameter midpoint.
fn optical_lengths(
    atmosphere: AtmosphereParameters,
    r: f32,
    mu: f32,
    ray_length: f32,
    sample_count: u32,
) -> vec3<f32> {
    if ray_length <= 0.0 {
        return vec3<f32>(0.0);
    }
    let n = max(sample_count, 1u);
    let t_split = lowest_point_distance(r, mu, ray_length);
    var sum = vec3<f32>(0.0);
    var t_start = 0.0;
    for (var i = 0u; i < n; i++) {
        let t_end = ray_sample_distance(f32(i + 1u) / f32(n), t_split, ray_length);
        let t = ray_sample_distance((f32(i) + 0.5) / f32(n), t_split, ray_length);
        sum += density_profile(atmosphere, altitude_along_ray(r, mu, t, atmosphere.planet_radius)) * (t_end - t_start);
        t_start = t_end;
    }
    return sum;
}

// Transmittance from a point at `altitude` (m) with sun zenith cosine mu_s to the sun
// through the shell, with light_samples samples. Zero where the planet hides the sun
// (the shadow of the earth: mu_s below the horizon's −√(1 − R²/r²)). The test is done on
// the altitude, mu_s²·r² > altitude·(r + R), because r = R + altitude rounds away
// sub-metre altitudes in f32 and would shadow samples just above the ground.
fn light_path_transmittance(atmosphere: AtmosphereParameters, altitude: f32, mu_s: f32, light_samples: u32) -> vec3<f32> {
    let planet_radius = atmosphere.planet_radius;
    let r = planet_radius + altitude;
    if mu_s < 0.0 && mu_s * mu_s * (r * r) > altitude * (r + planet_radius) {
        return vec3<f32>(0.0);
    }
    // Far root of the top sphere; a point rounded just above the top gets length 0.
    let top = ray_sphere_intersect(r, mu_s, atmosphere.top_radius);
    let length = max(top.y, 0.0);
    let lengths = optical_lengths(atmosphere, r, mu_s, length, light_samples);
    return transmittance_from_optical_depth(extinction_from_densities(atmosphere, lengths));
}

// (1 − e^{−x})/x per channel (1 at x = 0): the mean transmittance across a segment of
// optical depth x with constant extinction.
fn mean_transmittance_over_segment(optical_depth: vec3<f32>) -> vec3<f32> {
    let x = optical_depth;
    let safe = select(x, vec3<f32>(1.0), x == vec3<f32>(0.0));
    let mean = vec3<f32>(one_minus_exp_neg(safe.x), one_minus_exp_neg(safe.y), one_minus_exp_neg(safe.z)) / safe;
    return select(mean, vec3<f32>(1.0), x == vec3<f32>(0.0));
}

// Single scattering for a viewer inside the shell (r ≤ top_radius; r below the ground
// counts as on it). The segment ends at the ground, the top or max_distance. Midpoint
// samples, each standing for a segment of constant extinction integrated exactly
// (energy conserving: radiance stays bounded however thick a segment is).
fn single_scattering_inside(
    atmosphere: AtmosphereParameters,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    max_distance: f32,
    view_samples: u32,
    light_samples: u32,
) -> SingleScatteringSample {
    let planet_radius = atmosphere.planet_radius;
    let r0 = max(r, planet_radius);
    let ground = ray_sphere_intersect(r0, mu, planet_radius);
    let top = ray_sphere_intersect(r0, mu, atmosphere.top_radius);
    var end = max(top.y, 0.0);
    if mu < 0.0 && ground.x >= 0.0 {
        end = ground.x;
    }
    let limit = min(end, max(max_distance, 0.0));
    let n = max(view_samples, 1u);
    let t_split = lowest_point_distance(r0, mu, end);
    let rayleigh = rayleigh_phase(nu);
    let mie = cornette_shanks_phase(nu, atmosphere.mie_g);
    var optical_depth = vec3<f32>(0.0);
    var radiance = vec3<f32>(0.0);
    var t_start = 0.0;
    for (var i = 0u; i < n; i++) {
        if t_start >= limit {
            break;
        }
        // The segment's sample stays where the whole ray puts it; only its length is cut.
        let t_end = ray_sample_distance(f32(i + 1u) / f32(n), t_split, end);
        let dt = min(t_end, limit) - t_start;
        let t = ray_sample_distance((f32(i) + 0.5) / f32(n), t_split, end);
        t_start = t_end;
        let altitude = altitude_along_ray(r0, mu, t, planet_radius);
        let r_t = planet_radius + altitude;
        let mu_s_t = clamp((r0 * mu_s + t * nu) / r_t, -1.0, 1.0);
        let densities = density_profile(atmosphere, altitude);
        let segment_depth = extinction_from_densities(atmosphere, densities) * dt;
        let scattering = atmosphere.rayleigh_scattering * (densities.x * rayleigh)
            + atmosphere.mie_scattering * (densities.y * mie);
        let sun = light_path_transmittance(atmosphere, altitude, mu_s_t, light_samples);
        let weight = mean_transmittance_over_segment(segment_depth) * dt;
        radiance += transmittance_from_optical_depth(optical_depth) * sun * scattering * weight;
        optical_depth += segment_depth;
    }
    return SingleScatteringSample(
        radiance * atmosphere.sun_irradiance,
        transmittance_from_optical_depth(optical_depth),
    );
}

// Single scattering for a viewer anywhere. Outside the shell the ray is re-based at its
// near intersection with the top sphere (radius top_radius, zenith cosine
// −√D/top_radius exactly, sun cosine from the same point), so the two branches agree
// at the boundary; rays that miss the shell see nothing (radiance 0, transmittance 1).
fn single_scattering(
    atmosphere: AtmosphereParameters,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    max_distance: f32,
    view_samples: u32,
    light_samples: u32,
) -> SingleScatteringSample {
    let top_radius = atmosphere.top_radius;
    if r <= top_radius {
        return single_scattering_inside(atmosphere, r, mu, mu_s, nu, max_distance, view_samples, light_samples);
    }
    let hit = ray_sphere_intersect(r, mu, top_radius);
    if mu >= 0.0 || hit.x < 0.0 {
        return SingleScatteringSample(vec3<f32>(0.0), vec3<f32>(1.0));
    }
    let entry = hit.x;
    let b = r * mu;
    let c = (r - top_radius) * (r + top_radius);
    let mu_entry = -sqrt(max(b * b - c, 0.0)) / top_radius;
    let mu_s_entry = clamp((r * mu_s + entry * nu) / top_radius, -1.0, 1.0);
    return single_scattering_inside(
        atmosphere,
        top_radius,
        mu_entry,
        mu_s_entry,
        nu,
        max_distance - entry,
        view_samples,
        light_samples,
    );
}
