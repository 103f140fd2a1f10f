// Where a per-vertex sky dome's rows sit: a seam at the geometric horizon (a row on
// each side, never interpolated across), rows crowding quadratically toward it, and,
// above the atmosphere, most sky rows in the band between the horizon and the limb.
// Placed in mu (cosine of the zenith angle) so that no transcendental function's
// driver error can move a view across the seam.
// CPU twins: atmos::dome::{dome_horizon_mu, dome_row_mu, dome_row_coordinate}.

// Distance in mu between the horizon and each of the seam's rows; twin of
// atmos::dome::DOME_SEAM_OFFSET.
const DOME_SEAM_OFFSET: f32 = 1e-4;

// Twin of atmos::dome::dome_horizon_mu: the zenith cosine of the horizon of a sphere of
// radius sphere_radius seen from radius r, with r² − R² formed as (r − R)(r + R).
fn dome_horizon_mu(r: f32, sphere_radius: f32) -> f32 {
    let tangent_squared = max((r - sphere_radius) * (r + sphere_radius), 0.0);
    return -(sqrt(tangent_squared) / r);
}

// Twin of atmos::dome::dome_row_mu: the zenith cosine of row `row` (0 = nadir …
// rings + 1 = zenith); rows crowd quadratically toward the horizon seam, and above the
// atmosphere all sky bands but one cover the band between horizon and limb. In mu, not
// elevation: no asin/sin whose driver error could move a view across the seam.
fn dome_row_mu(row: u32, rings: u32, r: f32, planet_radius: f32, top_radius: f32) -> f32 {
    let horizon = dome_horizon_mu(r, planet_radius);
    let ground_bands = rings / 2u;
    let sky_bands = rings - ground_bands;
    if row <= ground_bands {
        let t = f32(ground_bands - row) / f32(ground_bands);
        let ground_seam = horizon - DOME_SEAM_OFFSET;
        return ground_seam - (1.0 + ground_seam) * t * t;
    }
    let sky_row = row - ground_bands - 1u;
    let sky_seam = horizon + DOME_SEAM_OFFSET;
    if r > top_radius {
        if sky_row >= sky_bands {
            return 1.0;
        }
        let limb = dome_horizon_mu(r, top_radius);
        let t = f32(sky_row) / f32(sky_bands - 1u);
        return sky_seam + (limb - sky_seam) * t * t;
    }
    let t = f32(sky_row) / f32(sky_bands);
    return sky_seam + (1.0 - sky_seam) * t * t;
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
    if r > top_radius {
        let limb = dome_horizon_mu(r, top_radius);
        if mu > limb {
            let above = clamp((mu - limb) / (1.0 - limb), 0.0, 1.0);
            return first_sky_row + sky_bands - 1.0 + above;
        }
        let t = sqrt(clamp((mu - sky_seam) / (limb - sky_seam), 0.0, 1.0));
        return first_sky_row + (sky_bands - 1.0) * t;
    }
    let t = sqrt(clamp((mu - sky_seam) / (1.0 - sky_seam), 0.0, 1.0));
    return first_sky_row + sky_bands * t;
}
