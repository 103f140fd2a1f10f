//! The view march along one ray.

use atmos::real::{Real, count};

use super::*;
use crate::cone::powder;
use crate::density::{DensityField, RaySpans};

/// The view march with midpoint samples (start offset ½). `direction` is a unit vector
/// in the field's frame; `settings.config().jitter` is not used (see
/// [`march_view_at_pixel`]).
pub fn march_view<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
) -> MarchResult<F> {
    march_view_with_offset(field, origin, direction, settings, lighting, F::of(0.5))
}

/// The view march of pixel `pixel`, its start offset from the settings' [`Jitter`].
pub fn march_view_at_pixel<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    pixel: [u32; 2],
) -> MarchResult<F> {
    let offset = F::of(f64::from(settings.config.jitter.offset(pixel)));
    march_view_with_offset(field, origin, direction, settings, lighting, offset)
}

/// [`march_view_at_pixel`] stopped at `max_distance` metres along the ray
/// ([`march_view_limited`]).
pub fn march_view_at_pixel_limited<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    pixel: [u32; 2],
    max_distance: F,
) -> MarchResult<F> {
    let offset = F::of(f64::from(settings.config.jitter.offset(pixel)));
    march_view_limited(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        max_distance,
    )
}

/// The view march with step `k` sampled at `(k + offset)·Δ` (`offset` in [0, 1); other
/// values are wrapped into it). Unlimited: [`march_view_limited`] with `max_distance = ∞`.
pub fn march_view_with_offset<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    offset: F,
) -> MarchResult<F> {
    march_view_limited(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        F::infinity(),
    )
}

/// The field's spans along a ray clipped to `[0, max_distance]` (WGSL twin `clip_spans`
/// in `field_march.wgsl`). A span starting at or beyond the limit
/// is dropped, one crossing it ends there. `max_distance` of `+∞` (or at least the
/// largest finite `f32`, the WGSL's "infinite") or NaN means no limit; a negative one
/// clips everything, as 0 does.
pub fn clip_spans<F: Real>(spans: RaySpans<F>, max_distance: F) -> RaySpans<F> {
    // `!(limit < MAX)` as the WGSL writes it: NaN is no limit too.
    if max_distance.is_nan() || max_distance >= F::of(f64::from(f32::MAX)) {
        return spans;
    }
    let limit = max_distance.max(F::zero());
    let mut out = RaySpans::none();
    for &(enter, exit) in spans.as_slice() {
        if enter < limit {
            out.spans[out.count] = (enter, if exit > limit { limit } else { exit });
            out.count += 1;
        }
    }
    out
}

/// The view march stopped at `max_distance` metres along the ray (an opaque surface
/// there: terrain in front of or inside the cloud). The field's spans are clipped to
/// `[0, max_distance]` ([`clip_spans`]) and the `view_steps` steps spread over the
/// clipped length, so a limited march is the unlimited march of the field cut at that
/// distance; a limit of 0 (or below) gives radiance 0 and transmittance 1, and a limit of
/// `+∞` or NaN is no limit ([`march_view_with_offset`]). Step offsets as
/// [`march_view_with_offset`].
pub fn march_view_limited<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    offset: F,
    max_distance: F,
) -> MarchResult<F> {
    march_view_lit_through(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        max_distance,
        |_| F::zero(),
    )
}

/// [`march_view_limited`] with the light crossing something outside the field too:
/// `outside_depth(p)` (≥ 0, finite) is the optical depth toward the sun of what lies
/// outside the field at view sample `p` (another cloud's shadow, read from its map:
/// `render::mutual_shadow`), added to the light march's `τ_l` before the octaves and the
/// powder, as one march over both would add it (`crate::union::UnionField`). The sun
/// term only: the ambient visibility stays the field's own. With `|_| 0` it is
/// [`march_view_limited`] exactly. WGSL twin: `march_view_lit_through` in
/// `field_march.wgsl`, its `outside_depth` the `outside_shadow.wgsl` map.
#[allow(clippy::too_many_arguments)] // the limited march's seven inputs and the hook
pub fn march_view_lit_through<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    offset: F,
    max_distance: F,
    outside_depth: impl Fn([F; 3]) -> F,
) -> MarchResult<F> {
    let c = &settings.config;
    let zero = F::zero();
    let offset = if offset.is_finite() {
        offset - offset.floor()
    } else {
        F::of(0.5)
    };
    let mut result = MarchResult {
        radiance: [zero; 3],
        transmittance: F::one(),
        depth: zero,
    };
    let spans = clip_spans(field.ray_spans(origin, direction), max_distance);
    let total = spans.length();
    if total <= zero || !total.is_finite() {
        return result;
    }
    let dt = total / count::<F>(c.view_steps);
    let sigma_per_density = field.extinction_per_density();
    let albedo = F::of(c.albedo);
    let to_sun = lighting.sun_direction;
    let cos_theta = direction[0] * to_sun[0] + direction[1] * to_sun[1] + direction[2] * to_sun[2];
    let (g_forward, g_back, back_weight) =
        (F::of(c.g_forward), F::of(c.g_back), F::of(c.back_weight));
    let (a, b, cc) = (F::of(c.octaves.a), F::of(c.octaves.b), F::of(c.octaves.c));
    let epsilon = F::of(c.transmittance_epsilon);
    let sun_lit = lighting.sun_irradiance.iter().any(|&e| e > zero);
    let ambient_lit = lighting.ambient_radiance.iter().any(|&e| e > zero);
    let mut weight_sum = zero;
    let mut depth_sum = zero;
    let mut span = 0usize;
    let mut span_start = zero; // concatenated length before `span`
    for k in 0..c.view_steps {
        let u = (count::<F>(k) + offset) * dt;
        while span + 1 < spans.count
            && u >= span_start + (spans.spans[span].1 - spans.spans[span].0)
        {
            span_start = span_start + (spans.spans[span].1 - spans.spans[span].0);
            span += 1;
        }
        let t = spans.spans[span].0 + (u - span_start);
        let p = [
            origin[0] + t * direction[0],
            origin[1] + t * direction[1],
            origin[2] + t * direction[2],
        ];
        let density = field.density(p);
        if density <= zero || density.is_nan() {
            continue;
        }
        let sigma_t = sigma_per_density * density;
        let sigma_s = albedo * sigma_t;
        let mut sun_term = zero;
        if sun_lit {
            let tau = light_optical_depth(field, p, to_sun, &c.light) + outside_depth(p);
            sun_term = octave_scattering(
                tau,
                cos_theta,
                g_forward,
                g_back,
                back_weight,
                c.octaves.count,
                a,
                b,
                cc,
            );
            if c.powder {
                sun_term = sun_term * powder(tau);
            }
        }
        let visibility = if ambient_lit {
            ambient_visibility(field, p, lighting.up, c.ambient_steps)
        } else {
            zero
        };
        let mut next = result.transmittance;
        for ch in 0..3 {
            let source = sigma_s
                * (lighting.sun_irradiance[ch] * sun_term
                    + lighting.ambient_radiance[ch] * visibility);
            let [gain, after] = scatter_step(result.transmittance, source, sigma_t, dt);
            result.radiance[ch] = result.radiance[ch] + gain;
            next = after;
        }
        let opacity = result.transmittance - next;
        weight_sum = weight_sum + opacity;
        depth_sum = depth_sum + opacity * t;
        result.transmittance = next;
        if result.transmittance < epsilon {
            break;
        }
    }
    if weight_sum > zero {
        result.depth = depth_sum / weight_sum;
    }
    result
}
