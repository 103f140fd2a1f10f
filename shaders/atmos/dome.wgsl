// Where a per-vertex sky dome's rows sit: a seam at the geometric horizon (a row on
// each side, never interpolated across), rows crowding quadratically toward it, and a
// share of the sky rows growing with altitude in the limb band below the horizontal
// (all but one above the atmosphere, between the horizon and the limb).
// Placed in mu (cosine of the zenith angle) so that no transcendental function's
// driver error can move a view across the seam.
// CPU twins: atmos::dome::{dome_horizon_mu, dome_limb_band, dome_row_mu, dome_row_coordinate}.

// Distance in mu between the horizon and each of the seam's rows; twin of
// atmos::dome::DOME_SEAM_OFFSET.
const DOME_SEAM_OFFSET: f32 = 1e-4;

// Twin of atmos::dome::dome_horizon_mu: the zenith cosine of the horizon of a sphere of
// radius sphere_radius seen from radius r, with r² − R² formed as (r − R)(r + R).
fn dome_horizon_mu(r: f32, sphere_radius: f32) -> f32 {
    let tangent_squared = max((r - sphere_radius) * (r + sphere_radius), 0.0);
    return -(sqrt(tangent_squared) / r);
}

// Twin of atmos::dome::dome_limb_band: the sky side's split — the zenith cosine that
// closes the limb band (the horizontal, or the atmosphere's limb seen from above it)
// and how many of the sky bands cover that band, growing linearly with altitude from
// none on the ground to all but one at the atmosphere's top.
fn dome_limb_band(sky_bands: f32, r: f32, planet_radius: f32, top_radius: f32, sky_seam: f32) -> vec2<f32> {
    var band_top = 0.0;
    var depth = 1.0;
    if r > top_radius {
        band_top = dome_horizon_mu(r, top_radius);
    } else {
        let altitude = max(r - planet_radius, 0.0);
        depth = min(altitude / (top_radius - planet_radius), 1.0);
    }
    let limb_bands = (sky_bands - 1.0) * depth;
    return vec2<f32>(max(band_top, sky_seam), limb_bands);
}

// Twin of atmos::dome::dome_row_mu: the zenith cosine of row `row` (0 = nadir …
// rings + 1 = zenith); rows crowd quadratically toward the horizon seam, and the sky's
// rows toward the seam within the limb band and toward the band's top above it. In mu,
// not elevation: no asin/sin whose driver error could move a view across the seam.
fn dome_row_mu(row: u32, rings: u32, r: f32, planet_radius: f32, top_radius: f32) -> f32 {
    let horizon = dome_horizon_mu(r, planet_radius);
    let ground_bands = rings / 2u;
    let sky_band_count = rings - ground_bands;
    if row <= ground_bands {
        let t = f32(ground_bands - row) / f32(ground_bands);
        let ground_seam = horizon - DOME_SEAM_OFFSET;
        return ground_seam - (1.0 + ground_seam) * t * t;
    }
    let sky_row = f32(row - ground_bands - 1u);
    let sky_bands = f32(sky_band_count);
    let sky_seam = horizon + DOME_SEAM_OFFSET;
    let band = dome_limb_band(sky_bands, r, planet_radius, top_radius, sky_seam);
    let band_top = band.x;
    let limb_bands = band.y;
    if sky_row <= limb_bands {
        var t = 0.0;
        if limb_bands > 0.0 {
            t = sky_row / limb_bands;
        }
        return sky_seam + (band_top - sky_seam) * t * t;
    }
    let t = (sky_row - limb_bands) / (sky_bands - limb_bands);
    return band_top + (1.0 - band_top) * t * t;
}

// Twin of atmos::dome::dome_row_coordinate: the fractional row of a view whose zenith
// cosine is mu, on the view's own side of the horizon seam.
fn dome_row_coordinate(mu: f32, rings: u32, r: f32, planet_radius: f32, top_radius: f32) -> f32 {
    let horizon = dome_horizon_mu(r, planet_radius);
    let ground_bands = f32(rings / 2u);
    let sky_bands = f32(rings - rings / 2u);
    if mu < horizon {
        let ground_seam = horizon - DOME_SEAM_OFFSET;
        let t = sqrt(clamp((ground_seam - mu) / (1.0 + ground_seam), 0.0, 1.0));
        return ground_bands * (1.0 - t);
    }
    let sky_seam = horizon + DOME_SEAM_OFFSET;
    let first_sky_row = ground_bands + 1.0;
    let band = dome_limb_band(sky_bands, r, planet_radius, top_radius, sky_seam);
    let band_top = band.x;
    let limb_bands = band.y;
    if mu <= band_top {
        let width = band_top - sky_seam;
        var t = 0.0;
        if width > 0.0 {
            t = sqrt(clamp((mu - sky_seam) / width, 0.0, 1.0));
        }
        return first_sky_row + limb_bands * t;
    }
    let t = sqrt(clamp((mu - band_top) / (1.0 - band_top), 0.0, 1.0));
    return first_sky_row + limb_bands + (sky_bands - limb_bands) * t;
}

