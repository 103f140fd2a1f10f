// LUT lookups and the raymarch of the precomputed rung. Twin:
// atmos::lut::{transmittance_lut, multiple_scattering_lut, sky_view_lut,
// aerial_perspective, raymarch} (Rust f32): the same functions by name, arguments and
// units, except that the Rust twins take the bindings (`LutBindings`, a LUT) as
// explicit first arguments where WGSL reads them from module scope.
//
// The bindings are declared by `atmos::lut_bindings` (uniforms in group 0, tables in
// group 1 for skyscape's own passes; `atmos::gpu::composer_with_lut_groups` moves them
// to the groups a user's pipeline has free). The tables are textures of rgba32float
// texels read with textureLoad and filtered by hand: exact (the CPU twin's arithmetic),
// and portable to adapters without float32 filtering. Texel (x, y) of layer m is
// entry x + w·(y + h·m) of the CPU twin's table.
#import atmos::atmosphere
#import atmos::phase
#import atmos::lut_parameterization
#import atmos::lut_multiple_scattering_moments
#import atmos::lut_bindings

// Segment lengths at or above this mean "to the ground or space" (Rust:
// frame::UNLIMITED_DISTANCE).
const UNLIMITED_DISTANCE: f32 = 1e30;

struct MediumSample {
    rayleigh_scattering: vec3<f32>,
    mie_scattering: vec3<f32>,
    extinction: vec3<f32>,
}

// Scattering and extinction coefficients (1/m) at an altitude.
fn medium_at_altitude(atmosphere: AtmosphereParameters, altitude: f32) -> MediumSample {
    let rayleigh = exponential_density(altitude, atmosphere.rayleigh_scale_height);
    let mie = exponential_density(altitude, atmosphere.mie_scale_height);
    let ozone = tent_density(altitude, atmosphere.ozone_center_altitude, atmosphere.ozone_half_width);
    return MediumSample(
        atmosphere.rayleigh_scattering * rayleigh,
        atmosphere.mie_scattering * mie,
        atmosphere.rayleigh_scattering * rayleigh + atmosphere.mie_extinction * mie
            + atmosphere.ozone_absorption * ozone,
    );
}

// Transmittance to the top of the atmosphere from (r, mu), bilinear.
fn lookup_transmittance(r: f32, mu: f32) -> vec3<f32> {
    let w = lut_settings.transmittance_width;
    let h = lut_settings.transmittance_height;
    let uv = transmittance_lut_uv(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius, w, h);
    let f = bilinear_footprint(uv, w, h, 0u, h - 1u);
    return bilinear_blend(
        textureLoad(transmittance_lut, vec2<u32>(f.x0, f.y0), 0).xyz,
        textureLoad(transmittance_lut, vec2<u32>(f.x1, f.y0), 0).xyz,
        textureLoad(transmittance_lut, vec2<u32>(f.x0, f.y1), 0).xyz,
        textureLoad(transmittance_lut, vec2<u32>(f.x1, f.y1), 0).xyz,
        f.fx,
        f.fy,
    );
}

// Transmittance to where the ray leaves the atmosphere or meets the ground (ground
// rays: Bruneton's ratio of two upward lookups, capped at 1).
fn transmittance_to_boundary(r_in: f32, mu: f32) -> vec3<f32> {
    let r = max(r_in, lut_atmosphere.planet_radius);
    let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    if segment.z < 0.5 {
        return lookup_transmittance(r, mu);
    }
    let d = segment.y;
    let r_d = radius_along_ray(r, mu, d);
    let mu_d = clamp((r * mu + d) / r_d, -1.0, 1.0);
    let numerator = lookup_transmittance(r_d, -mu_d);
    let denominator = lookup_transmittance(r, -mu);
    return select(vec3<f32>(0.0), min(numerator / denominator, vec3<f32>(1.0)), denominator > vec3<f32>(0.0));
}

// Transmittance from a point to the sun, 0 in the planet's shadow.
fn sun_transmittance(r: f32, mu_s: f32) -> vec3<f32> {
    return lookup_transmittance(r, mu_s) * sun_visibility(r, mu_s, lut_atmosphere.planet_radius);
}

// One layer of the multiple-scattering LUT, bilinear over a footprint.
fn multiple_scattering_layer(f: BilinearFootprint, layer: u32) -> vec3<f32> {
    return bilinear_blend(
        textureLoad(multiple_scattering_lut, vec2<u32>(f.x0, f.y0), layer, 0).xyz,
        textureLoad(multiple_scattering_lut, vec2<u32>(f.x1, f.y0), layer, 0).xyz,
        textureLoad(multiple_scattering_lut, vec2<u32>(f.x0, f.y1), layer, 0).xyz,
        textureLoad(multiple_scattering_lut, vec2<u32>(f.x1, f.y1), layer, 0).xyz,
        f.fx,
        f.fy,
    );
}

// The field's moments at (r, mu_s), bilinear.
fn lookup_multiple_scattering(r: f32, mu_s: f32) -> MultipleScatteringMoments {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    let uv = multiple_scattering_lut_uv(r, mu_s, lut_atmosphere.planet_radius, lut_atmosphere.top_radius, w, h);
    let f = bilinear_footprint(uv, w, h, 0u, h - 1u);
    return MultipleScatteringMoments(
        multiple_scattering_layer(f, 0u),
        multiple_scattering_layer(f, 1u),
        multiple_scattering_layer(f, 2u),
        multiple_scattering_layer(f, 3u),
        multiple_scattering_layer(f, 4u),
        multiple_scattering_layer(f, 5u),
    );
}

// One layer of the sky-irradiance LUT, bilinear over a footprint.
fn sky_irradiance_layer(f: BilinearFootprint, layer: u32) -> vec3<f32> {
    return bilinear_blend(
        textureLoad(sky_irradiance_lut, vec2<u32>(f.x0, f.y0), layer, 0).xyz,
        textureLoad(sky_irradiance_lut, vec2<u32>(f.x1, f.y0), layer, 0).xyz,
        textureLoad(sky_irradiance_lut, vec2<u32>(f.x0, f.y1), layer, 0).xyz,
        textureLoad(sky_irradiance_lut, vec2<u32>(f.x1, f.y1), layer, 0).xyz,
        f.fx,
        f.fy,
    );
}

// Irradiance (the unit of sun_irradiance) at (r, μ_s) on a surface whose normal is
// `normal` in the point's sun frame: bilinear over (μ_s, r) in the four layers around
// the normal, blended bilinearly over (n_z, φ_n).
fn lookup_sky_irradiance(r: f32, mu_s: f32, normal: vec3<f32>) -> vec3<f32> {
    let uv = sky_irradiance_lut_uv(r, mu_s, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    let f = bilinear_footprint(uv, SKY_IRRADIANCE_WIDTH, SKY_IRRADIANCE_HEIGHT, 0u, SKY_IRRADIANCE_HEIGHT - 1u);
    let last_zenith = f32(SKY_IRRADIANCE_NORMAL_ZENITHS - 1u);
    let last_azimuth = f32(SKY_IRRADIANCE_NORMAL_AZIMUTHS - 1u);
    let z = clamp((clamp(normal.z, -1.0, 1.0) + 1.0) * 0.5 * last_zenith, 0.0, last_zenith);
    let a = clamp(atan2(abs(normal.y), normal.x) / PI * last_azimuth, 0.0, last_azimuth);
    let z0 = u32(z);
    let a0 = u32(a);
    let z1 = min(z0 + 1u, SKY_IRRADIANCE_NORMAL_ZENITHS - 1u);
    let a1 = min(a0 + 1u, SKY_IRRADIANCE_NORMAL_AZIMUTHS - 1u);
    let fz = z - f32(z0);
    let fa = a - f32(a0);
    let n = SKY_IRRADIANCE_NORMAL_AZIMUTHS;
    let low = sky_irradiance_layer(f, z0 * n + a0) * (1.0 - fa) + sky_irradiance_layer(f, z0 * n + a1) * fa;
    let high = sky_irradiance_layer(f, z1 * n + a0) * (1.0 - fa) + sky_irradiance_layer(f, z1 * n + a1) * fa;
    return low * (1.0 - fz) + high * fz;
}

// In-scatter source of orders ≥ 2 per metre per unit sun irradiance at radius r (sun
// zenith cosine mu_s) towards a viewer looking along (mu, nu): Rayleigh and Mie
// scattering of the table's field with each phase function's Legendre moments.
fn multiple_scattering_source(medium: MediumSample, r: f32, mu: f32, mu_s: f32, nu: f32) -> vec3<f32> {
    let moments = lookup_multiple_scattering(r, mu_s);
    let direction = sun_frame_direction(mu, mu_s, nu);
    let rayleigh = scattered_multiple_scattering(moments, direction, RAYLEIGH_LEGENDRE_MOMENTS);
    let mie = scattered_multiple_scattering(moments, direction, cornette_shanks_legendre_moments(lut_atmosphere.mie_g));
    return medium.rayleigh_scattering * rayleigh + medium.mie_scattering * mie;
}

// One layer of the sky-view LUT (0: radiance, 1: transmittance when stored), bilinear.
fn sky_view_layer(f: BilinearFootprint, layer: u32) -> vec3<f32> {
    return bilinear_blend(
        textureLoad(sky_view_lut, vec2<u32>(f.x0, f.y0), layer, 0).xyz,
        textureLoad(sky_view_lut, vec2<u32>(f.x1, f.y0), layer, 0).xyz,
        textureLoad(sky_view_lut, vec2<u32>(f.x0, f.y1), layer, 0).xyz,
        textureLoad(sky_view_lut, vec2<u32>(f.x1, f.y1), layer, 0).xyz,
        f.fx,
        f.fy,
    );
}

// Radiance and transmittance of the whole view ray towards (mu, cos_azimuth) from
// radius r: the radiance by a bilinear lookup (sky directions read sky rows only,
// ground directions ground rows only), the transmittance from the same footprint or,
// for a radiance-only table, from the transmittance LUT (a uniform branch).
fn lookup_sky_view(r: f32, mu: f32, cos_azimuth: f32) -> ScatteringSegment {
    let w = lut_settings.sky_view_width;
    let h = lut_settings.sky_view_height;
    let uv = sky_view_lut_uv(r, mu, cos_azimuth, lut_atmosphere.planet_radius, w, h);
    let half_height = h / 2u;
    var f: BilinearFootprint;
    // At the horizon both halves meet at v = 1/2; a viewer on the ground looking along
    // (or above) the tangent plane sees the sky (docs/architecture.md, "Rays at the
    // ground"), so it reads the sky rows.
    if uv.y < 0.5 || (mu >= 0.0 && r <= lut_atmosphere.planet_radius) {
        f = bilinear_footprint(uv, w, h, 0u, half_height - 1u);
    } else {
        f = bilinear_footprint(uv, w, h, half_height, h - 1u);
    }
    let radiance = sky_view_layer(f, 0u);
    if lut_settings.sky_view_transmittance == 0u {
        return ScatteringSegment(radiance, transmittance_to_boundary(r, mu));
    }
    return ScatteringSegment(radiance, sky_view_layer(f, 1u));
}

// One slice of the aerial-perspective volume (which 0: radiance, 1: transmittance),
// bilinear; the virtual slice z < 0 at the camera holds (0, 1).
fn aerial_perspective_slice(f: BilinearFootprint, z: f32, which: u32) -> vec3<f32> {
    if z < 0.0 {
        return select(vec3<f32>(1.0), vec3<f32>(0.0), which == 0u);
    }
    let zi = u32(z);
    if which == 0u {
        return bilinear_blend(
            textureLoad(aerial_perspective_radiance, vec3<u32>(f.x0, f.y0, zi), 0).xyz,
            textureLoad(aerial_perspective_radiance, vec3<u32>(f.x1, f.y0, zi), 0).xyz,
            textureLoad(aerial_perspective_radiance, vec3<u32>(f.x0, f.y1, zi), 0).xyz,
            textureLoad(aerial_perspective_radiance, vec3<u32>(f.x1, f.y1, zi), 0).xyz,
            f.fx,
            f.fy,
        );
    }
    return bilinear_blend(
        textureLoad(aerial_perspective_transmittance, vec3<u32>(f.x0, f.y0, zi), 0).xyz,
        textureLoad(aerial_perspective_transmittance, vec3<u32>(f.x1, f.y0, zi), 0).xyz,
        textureLoad(aerial_perspective_transmittance, vec3<u32>(f.x0, f.y1, zi), 0).xyz,
        textureLoad(aerial_perspective_transmittance, vec3<u32>(f.x1, f.y1, zi), 0).xyz,
        f.fx,
        f.fy,
    );
}

// Trilinear lookup of the aerial-perspective volume at screen uv and distance (m);
// slice k ends at (k + 1)·range/depth, a virtual slice at 0 holds (0, 1).
fn lookup_aerial_perspective(uv: vec2<f32>, distance: f32) -> ScatteringSegment {
    let w = lut_settings.aerial_perspective_width;
    let h = lut_settings.aerial_perspective_height;
    let d = lut_settings.aerial_perspective_depth;
    let f = bilinear_footprint(uv, w, h, 0u, h - 1u);
    let slice = clamp(distance / lut_settings.aerial_perspective_range * f32(d) - 1.0, -1.0, f32(d - 1u));
    let z0 = floor(slice);
    let fz = slice - z0;
    let z1 = min(z0 + 1.0, f32(d - 1u));
    let radiance = aerial_perspective_slice(f, z0, 0u) * (1.0 - fz) + aerial_perspective_slice(f, z1, 0u) * fz;
    let transmittance = aerial_perspective_slice(f, z0, 1u) * (1.0 - fz) + aerial_perspective_slice(f, z1, 1u) * fz;
    return ScatteringSegment(radiance, transmittance);
}

// In-scatter source per metre per unit sun irradiance at radius r towards a viewer
// looking along (mu, nu) (sun zenith cosine mu_s there): single scattering lit through
// the transmittance LUT plus all higher orders from the multiple-scattering LUT.
fn scattering_source(medium: MediumSample, r: f32, mu: f32, mu_s: f32, nu: f32, rayleigh_phase_value: f32, mie_phase_value: f32) -> vec3<f32> {
    let sun = sun_transmittance(r, mu_s);
    let multiple = multiple_scattering_source(medium, r, mu, mu_s, nu);
    return sun * (medium.rayleigh_scattering * rayleigh_phase_value + medium.mie_scattering * mie_phase_value)
        + multiple;
}

// Marches (r, mu) from t_start to t_end, steps spaced quadratically, each sampled at
// its midpoint, with Hillaire's energy-conserving step. Radiance includes the sun
// irradiance.
fn raymarch_scattering(r: f32, mu: f32, mu_s: f32, nu: f32, t_start: f32, t_end: f32, sample_count: u32) -> ScatteringSegment {
    let rayleigh_phase_value = rayleigh_phase(nu);
    let mie_phase_value = cornette_shanks_phase(nu, lut_atmosphere.mie_g);
    let ray_length = max(t_end - t_start, 0.0);
    let n = f32(sample_count);
    var march = ScatteringSegment(vec3<f32>(0.0), vec3<f32>(1.0));
    var t_previous = t_start;
    for (var i = 0u; i < sample_count; i++) {
        let s = (f32(i) + 1.0) / n;
        let t_next = t_start + ray_length * s * s;
        let dt = t_next - t_previous;
        let t = t_previous + 0.5 * dt;
        t_previous = t_next;
        let point = point_along_ray(r, mu, mu_s, nu, t);
        let medium = medium_at_altitude(lut_atmosphere, point.x - lut_atmosphere.planet_radius);
        let source = scattering_source(medium, point.x, point.y, point.z, nu, rayleigh_phase_value, mie_phase_value);
        march = integrate_scattering_step(march, source, medium.extinction, dt);
    }
    return ScatteringSegment(march.radiance * lut_atmosphere.sun_irradiance, march.transmittance);
}

// The per-pixel path without the sky-view and aerial-perspective tables: the segment
// inside the atmosphere up to max_distance, origin moved to where the ray enters the
// shell (space views); an unlimited segment takes its transmittance from the LUT.
fn march_view_segment(r_in: f32, mu: f32, mu_s: f32, nu: f32, max_distance: f32, sample_count: u32) -> ScatteringSegment {
    let r = max(r_in, lut_atmosphere.planet_radius);
    let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    let t_start = segment.x;
    let t_end = min(segment.y, max_distance);
    if t_end <= t_start {
        return ScatteringSegment(vec3<f32>(0.0), vec3<f32>(1.0));
    }
    let r_0 = radius_along_ray(r, mu, t_start);
    let mu_0 = clamp((r * mu + t_start) / r_0, -1.0, 1.0);
    let mu_s_0 = clamp((r * mu_s + t_start * nu) / r_0, -1.0, 1.0);
    var result = raymarch_scattering(r_0, mu_0, mu_s_0, nu, 0.0, t_end - t_start, sample_count);
    if max_distance >= UNLIMITED_DISTANCE {
        result.transmittance = transmittance_to_boundary(r_0, mu_0);
    }
    return result;
}
