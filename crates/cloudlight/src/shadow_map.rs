//! The ground's cloud shadow map (Hoffman and Preetham's `clouds_shadow` term): the transmittance of
//! the sunlight through a cloud, toward the sun, from every texel centre of a 2-D grid on
//! flat ground. `render` multiplies terrain shading by it.
//!
//! * [`ShadowGrid`] states the extent: the minimum corner `(x, y)` of the grid (metres, the
//!   terrain's frame), the texel edge, the resolution and the ground height. Texel
//!   `(i, j)` (`i` fastest in every output) is the ground point
//!   `(x₀ + (i + ½)·cell, y₀ + (j + ½)·cell, ground_height)`.
//! * [`ShadowMapPlan`] adds the direction toward the sun and the march's step count.
//! * [`shadow_map`] is the march, written once over the float type for any
//!   [`DensityField`]: for each span of the sun ray where the field may be non-zero,
//!   `steps` midpoint samples, `τ = Σ σ_t·h·Σρ`, light `exp(−τ)`. `shadow_map::<f32>` on a
//!   [`CloudVolume`] is the twin of the GPU pass (`gpu::ShadowMapPass`,
//!   `shaders/cloudlight/shadow_map_pass.wgsl`, `field_march.wgsl`'s `shadow_texel` over
//!   `density_grid.wgsl`); the per-texel pieces
//!   ([`shadow_texel_centre`], [`shadow_box_span`], [`shadow_march_point`],
//!   [`shadow_accumulate`], [`shadow_span_optical_depth`]) are WGSL twins in `shaders/cloudlight/shadow_map.wgsl`.
//! * [`shadow_map_reference`] is the exact f64 transmittance of a [`CloudVolume`]
//!   ([`crate::reference::transmittance`]: no discretisation error), which the march is
//!   measured against (`tests` here, `docs/cloudlight-methods.md`, `examples/shadow_map.rs`).
//!
//! Any sun elevation is accepted. A low sun gives long oblique paths (the span's `steps`
//! samples stretch over them). A sun at or below the horizon still gives the cloud's own
//! transmittance along the ray toward the sun: a cloud wholly above the ground then casts
//! nothing (1), one reaching below `ground_height` still does. The planet's shadow, and
//! the atmosphere's transmittance, are `atmos`' and `render`'s business, not this map's.
//! The ground is flat (no curvature): right for a terrain tile, not for a continent.

use std::num::NonZeroU32;

use atmos::real::Real;

use crate::density::DensityField;
use crate::reference::ReferenceError;
use crate::{CloudVolume, cone};

/// The shadow map's default march: midpoint steps per span. The f32 twin's error against
/// the exact reference at this setting is printed by
/// `examples/shadow_map.rs` (`docs/cloudlight-methods.md`).
pub const DEFAULT_STEPS: u32 = 64;

/// The largest step count a plan accepts (the GPU loops this many times per texel).
pub const MAX_STEPS: u32 = 4096;

/// Bad input to the shadow map, naming the field and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShadowMapError {
    /// A field is out of its domain.
    #[error("{field} = {value}: {requirement}")]
    BadParameter {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
    /// The exact reference refused a ray (cannot happen for a valid plan; kept typed).
    #[error(transparent)]
    Reference(#[from] ReferenceError),
}

fn bad(field: &'static str, value: f64, requirement: &'static str) -> ShadowMapError {
    ShadowMapError::BadParameter {
        field,
        value,
        requirement,
    }
}

/// The ground grid a shadow map covers (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowGrid {
    origin: [f64; 2],
    cell_size: f64,
    resolution: [u32; 2],
    ground_height: f64,
}

impl ShadowGrid {
    /// A grid of `resolution = [nx, ny]` texels of edge `cell_size` metres whose minimum
    /// corner is `origin = [x, y]` (metres), on flat ground at `ground_height` (metres, z).
    /// Coordinates within ±1e8 m and cells up to 1e6 m (f32 keeps every texel centre
    /// finite); errors name the field and value.
    pub fn new(
        origin: [f64; 2],
        cell_size: f64,
        resolution: [u32; 2],
        ground_height: f64,
    ) -> Result<Self, ShadowMapError> {
        for (field, value) in ["origin.x", "origin.y"].into_iter().zip(origin) {
            if value.is_nan() || value.abs() > 1e8 {
                return Err(bad(field, value, "must be in [-1e8, 1e8] (metres)"));
            }
        }
        if !(cell_size > 0.0 && cell_size <= 1e6) {
            return Err(bad("cell_size", cell_size, "must be in (0, 1e6] (metres)"));
        }
        for (field, n) in ["resolution.x", "resolution.y"].into_iter().zip(resolution) {
            if n == 0 {
                return Err(bad(field, 0.0, "must be ≥ 1 texel"));
            }
        }
        if ground_height.is_nan() || ground_height.abs() > 1e8 {
            return Err(bad(
                "ground_height",
                ground_height,
                "must be in [-1e8, 1e8] (metres)",
            ));
        }
        Ok(Self {
            origin,
            cell_size,
            resolution,
            ground_height,
        })
    }

    /// Minimum corner `[x, y]`, metres.
    pub fn origin(&self) -> [f64; 2] {
        self.origin
    }

    /// Texel edge, metres.
    pub fn cell_size(&self) -> f64 {
        self.cell_size
    }

    /// `[nx, ny]` texels.
    pub fn resolution(&self) -> [u32; 2] {
        self.resolution
    }

    /// The ground's height (z), metres.
    pub fn ground_height(&self) -> f64 {
        self.ground_height
    }

    /// Texels in the map.
    pub fn texels(&self) -> usize {
        self.resolution[0] as usize * self.resolution[1] as usize
    }

    /// Ground point of texel `(i, j)` in f64.
    pub fn texel_centre(&self, i: u32, j: u32) -> [f64; 3] {
        shadow_texel_centre([i, j], self.origin, self.cell_size, self.ground_height)
    }
}

/// A shadow map's settings: the grid, the unit direction toward the sun and the march's
/// midpoint steps per span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowMapPlan {
    /// The ground grid.
    pub grid: ShadowGrid,
    to_sun: [f64; 3],
    steps: NonZeroU32,
}

impl ShadowMapPlan {
    /// `to_sun`: toward the sun, any finite non-zero length (normalised here), any
    /// elevation; `steps` in `1..=MAX_STEPS` ([`DEFAULT_STEPS`] is the measured default).
    pub fn new(grid: ShadowGrid, to_sun: [f64; 3], steps: u32) -> Result<Self, ShadowMapError> {
        for (field, value) in ["to_sun.x", "to_sun.y", "to_sun.z"].into_iter().zip(to_sun) {
            if !value.is_finite() {
                return Err(bad(field, value, "must be finite"));
            }
        }
        let norm = to_sun.iter().map(|c| c * c).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(bad("|to_sun|", norm, "must be non-zero and finite"));
        }
        if !(1..=MAX_STEPS).contains(&steps) {
            return Err(bad(
                "steps",
                f64::from(steps),
                "must be in 1..=4096 (midpoint steps per span)",
            ));
        }
        Ok(Self {
            grid,
            to_sun: to_sun.map(|c| c / norm),
            steps: NonZeroU32::new(steps).expect("checked ≥ 1"),
        })
    }

    /// The unit direction toward the sun.
    pub fn to_sun(&self) -> [f64; 3] {
        self.to_sun
    }

    /// Midpoint steps per span.
    pub fn steps(&self) -> u32 {
        self.steps.get()
    }
}

/// Ground point of texel `texel = (i, j)`: `(x₀ + (i + ½)·cell, y₀ + (j + ½)·cell,
/// ground_height)`. WGSL twin `shadow_texel_centre`.
pub fn shadow_texel_centre<F: Real>(
    texel: [u32; 2],
    origin: [F; 2],
    cell_size: F,
    ground_height: F,
) -> [F; 3] {
    let half = F::of(0.5);
    [
        origin[0] + (atmos::real::count::<F>(texel[0]) + half) * cell_size,
        origin[1] + (atmos::real::count::<F>(texel[1]) + half) * cell_size,
        ground_height,
    ]
}

/// `[t_enter, t_exit]` of the ray `p + t·l` (`t ≥ 0`) through the box `[lo, hi]` (the
/// slab method, in the operation order of [`CloudVolume`]'s
/// [`DensityField::ray_spans`]); `t_enter > t_exit` when it misses. WGSL twin
/// `shadow_box_span` (its "no exit yet" is the largest finite float, as here).
pub fn shadow_box_span<F: Real>(p: [F; 3], l: [F; 3], lo: [F; 3], hi: [F; 3]) -> [F; 2] {
    let mut enter = F::zero();
    let mut exit = F::max_value();
    for a in 0..3 {
        if l[a] == F::zero() {
            if p[a] < lo[a] || p[a] > hi[a] {
                return [F::one(), F::zero()];
            }
        } else {
            let t0 = (lo[a] - p[a]) / l[a];
            let t1 = (hi[a] - p[a]) / l[a];
            enter = enter.max(t0.min(t1));
            exit = exit.min(t0.max(t1));
        }
    }
    [enter, exit]
}

/// Sample `k` of `n` midpoint steps over `span = [t_enter, t_exit]`:
/// `p + (t_enter + (k + ½)·h)·l` with `h = (t_exit − t_enter)/n`. WGSL twin
/// `shadow_march_point`.
pub fn shadow_march_point<F: Real>(p: [F; 3], l: [F; 3], span: [F; 2], k: u32, n: u32) -> [F; 3] {
    let h = (span[1] - span[0]) / atmos::real::count::<F>(n);
    let t = span[0] + (atmos::real::count::<F>(k) + F::of(0.5)) * h;
    [p[0] + t * l[0], p[1] + t * l[1], p[2] + t * l[2]]
}

/// Densities, their sums and optical depths saturate here (1e30): `exp(−τ)` is 0 long
/// before (τ > 104 in f32), and the saturation keeps every product finite, so a huge
/// density (up to `f32::MAX`, which the f32 lookup can round up to ∞) meets σ_t = 0 or a
/// zero-length span as 0, never as `0·∞` = NaN.
pub const SATURATION: f64 = 1e30;

/// The march's running sum plus one sample's density, the density saturated at
/// [`SATURATION`] (so `MAX_STEPS` samples stay below 5e33, finite in f32). WGSL twin
/// `shadow_accumulate`.
pub fn shadow_accumulate<F: Real>(density_sum: F, density: F) -> F {
    density_sum + density.min(F::of(SATURATION))
}

/// A span's optical depth from the sum of its `n` midpoint densities:
/// `min(σ_t, S)·min(Σρ·h, S)`, saturated at `S` = [`SATURATION`];
/// `h = (t_exit − t_enter)/n`. WGSL twin `shadow_span_optical_depth`.
pub fn shadow_span_optical_depth<F: Real>(density_sum: F, span: [F; 2], n: u32, sigma_t: F) -> F {
    let saturation = F::of(SATURATION);
    let h = (span[1] - span[0]) / atmos::real::count::<F>(n);
    let depth = (density_sum * h).min(saturation);
    (sigma_t.min(saturation) * depth).min(saturation)
}

/// Where `point` reads a shadow map whose plane lies at height `plane` (the point's
/// frame, z up): carried along unit `to_light` to the plane, in texel-centre coordinates
/// `(x − origin)/cell − ½` (texel `(i, j)`'s centre is `(i, j)`). The terrain's lookup
/// (`render::volume_clouds::volume_shadow_texel`) and another cloud's
/// (`shaders/cloudlight/outside_shadow.wgsl`). WGSL twin `shadow_map_texel`.
pub fn shadow_map_texel<F: Real>(
    point: [F; 3],
    to_light: [F; 3],
    plane: F,
    origin: [F; 2],
    cell_size: F,
) -> [F; 2] {
    let t = (plane - point[2]) / to_light[2];
    let x = point[0] + t * to_light[0];
    let y = point[1] + t * to_light[1];
    let half = F::of(0.5);
    [
        (x - origin[0]) / cell_size - half,
        (y - origin[1]) / cell_size - half,
    ]
}

/// The four texels a shadow map's bilinear lookup reads ([`shadow_map_taps`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowMapTaps<F> {
    /// Flat indices (east fastest) of texels `(i, j)`, `(i + 1, j)`, `(i, j + 1)`,
    /// `(i + 1, j + 1)`, `i = ⌊x⌋`, `j = ⌊y⌋`; −1 for a texel outside the map (its value
    /// 1: no cloud there).
    pub index: [i64; 4],
    /// `(x − i, y − j)`.
    pub fraction: [F; 2],
}

/// The texels and fractions of a bilinear lookup between texel centres at texel-centre
/// coordinates `texel` ([`shadow_map_texel`]) of a map of `resolution` texels. The
/// caller reads each index's value from its map (1 for −1) and blends them with
/// [`shadow_map_bilinear`]; [`shadow_map_lookup`] is the two over a slice. Used by the
/// terrain's lookup (`render::volume_clouds::CloudShadow::at`, `shaders/render/
/// terrain.wgsl`'s `shadow_map_at`) and another cloud's ([`OutsideShadowMap`]). WGSL
/// twin `shadow_map_taps` (indices in `i32` there: a texel coordinate beyond ±2³¹ is
/// outside the map on both).
pub fn shadow_map_taps<F: Real>(texel: [F; 2], resolution: [u32; 2]) -> ShadowMapTaps<F> {
    let (fx, fy) = (texel[0].floor(), texel[1].floor());
    let to_index = |f: F| f.to_f64().unwrap_or(f64::NAN) as i64;
    let (i, j) = (to_index(fx), to_index(fy));
    let [w, h] = resolution.map(i64::from);
    let at = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= w || y >= h {
            -1
        } else {
            x + w * y
        }
    };
    ShadowMapTaps {
        index: [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)],
        fraction: [texel[0] - fx, texel[1] - fy],
    }
}

/// The lookup's value from its four texels' `values` (in [`ShadowMapTaps::index`]'s
/// order, 1 for a texel outside the map) at `fraction`: cloudlight's bilinear
/// ([`crate::propagate::bilinear`]). WGSL twin `shadow_map_bilinear`.
pub fn shadow_map_bilinear<F: Real>(values: [F; 4], fraction: [F; 2]) -> F {
    crate::propagate::bilinear(
        values[0],
        values[1],
        values[2],
        values[3],
        fraction[0],
        fraction[1],
    )
}

/// A shadow map's value at texel-centre coordinates `texel`: [`shadow_map_taps`] read
/// from `values` (`resolution` texels, east fastest; 1 outside the map), then
/// [`shadow_map_bilinear`]. On the GPU each caller reads its own binding between the
/// two (WGSL passes no storage array to a function).
pub fn shadow_map_lookup<F: Real>(values: &[F], resolution: [u32; 2], texel: [F; 2]) -> F {
    let taps = shadow_map_taps(texel, resolution);
    let value = |index: i64| usize::try_from(index).map_or(F::one(), |k| values[k]);
    shadow_map_bilinear(taps.index.map(value), taps.fraction)
}

/// Another cloud's shadow map as a march reads it (`march::march_view_lit_through`'s
/// `outside_depth`): the CPU twin of `shaders/cloudlight/outside_shadow.wgsl`'s uniform
/// and values, its values a slice (`V = &[F]`); on the GPU `V` is the storage buffer
/// that holds them (`gpu::OutsideShadow`, the same fields bound as that uniform).
#[derive(Debug, Clone, Copy)]
pub struct OutsideShadowMap<V, F> {
    /// East, north of texel (0, 0)'s corner (m).
    pub origin: [F; 2],
    /// Texel edge (m).
    pub cell_size: F,
    /// Texels east × north.
    pub resolution: [u32; 2],
    /// The map plane's altitude (m).
    pub plane: F,
    /// Unit direction toward the map's light (east/north/up).
    pub to_light: [F; 3],
    /// The casting cloud's base and top altitude (m), `base < top`.
    pub extent: [F; 2],
    /// The march frame's height of altitude 0 (0 about the ground, the planet's radius
    /// in a planet-centred frame).
    pub frame_height: F,
    /// The map's transmittances, east fastest.
    pub values: V,
}

impl<V, F> OutsideShadowMap<V, F> {
    /// The same map with its values held in `values` (a slice on the CPU, the buffer
    /// the GPU march binds).
    pub fn with_values<W>(self, values: W) -> OutsideShadowMap<W, F> {
        OutsideShadowMap {
            origin: self.origin,
            cell_size: self.cell_size,
            resolution: self.resolution,
            plane: self.plane,
            to_light: self.to_light,
            extent: self.extent,
            frame_height: self.frame_height,
            values,
        }
    }
}

impl<F: Real> OutsideShadowMap<&[F], F> {
    /// The casting cloud's optical depth toward the light above the march's sample `p`
    /// (the march's frame): `p` lowered by `frame_height`, [`shadow_map_texel`],
    /// [`shadow_map_lookup`], then [`shadow_depth_above`]. WGSL twin `outside_depth`
    /// (`shaders/cloudlight/outside_shadow.wgsl`, its map the bound uniform).
    pub fn outside_depth(&self, p: [F; 3]) -> F {
        let point = [p[0], p[1], p[2] - self.frame_height];
        let texel = shadow_map_texel(
            point,
            self.to_light,
            self.plane,
            self.origin,
            self.cell_size,
        );
        let value = shadow_map_lookup(self.values, self.resolution, texel);
        shadow_depth_above(value, point[2], self.extent[0], self.extent[1])
    }
}

/// The smallest transmittance [`shadow_depth_above`] reads from a map: an opaque texel
/// (0, its τ saturated) counts as optical depth `−ln 1e-30 ≈ 69`, so the result stays
/// finite (the light through it is `e^{−69}`, 0 to every channel's precision).
pub const OPAQUE_TRANSMITTANCE: f64 = 1e-30;

/// The optical depth toward the light of a cloud spanning altitudes `[base, top]`
/// (`top > base`) above a point at altitude `height`, from the transmittance
/// `transmittance` its shadow map holds where the point's light ray meets the map's
/// plane at the cloud's base: `−ln max(T, 1e-30) · f²`, `f = clamp((top − h)/(top −
/// base), 0, 1)`. Below the base the whole of the map's column lies above the point
/// (exact up to the map's sampling); above the top none of it. Inside, an empirical
/// fade: `f²` of the column, continuous at both ends (the part of the column above the
/// point is not in the map; `render::mutual_shadow` measures this fade against `f`, 0
/// and 1). Another cloud's shadow on a march
/// (`crate::march::march_view_lit_through`'s `outside_depth`). WGSL twin
/// `shadow_depth_above`.
pub fn shadow_depth_above<F: Real>(transmittance: F, height: F, base: F, top: F) -> F {
    let above = ((top - height) / (top - base)).max(F::zero()).min(F::one());
    let depth = -(transmittance.max(F::of(OPAQUE_TRANSMITTANCE)).ln());
    depth * (above * above)
}

/// The marched transmittance toward the sun from `ground` (unit `to_sun`) through
/// `field`: `steps` midpoint samples on each of the field's spans, `exp(−Σ τ)`. Infallible
/// (per-texel math; [`ShadowMapPlan::new`] validates). The f32 instantiation on a
/// [`CloudVolume`] is the GPU pass's twin (the pass's trilinear lookup runs in f32, this
/// one in f64 rounded once: they differ by rounding only, bounded in
/// `tests/shadow_map_gpu.rs`).
pub fn shadow_texel<F: Real, D: DensityField<F> + ?Sized>(
    field: &D,
    ground: [F; 3],
    to_sun: [F; 3],
    steps: u32,
) -> F {
    let spans = field.ray_spans(ground, to_sun);
    let sigma_t = field.extinction_per_density();
    let mut tau = F::zero();
    for &(enter, exit) in spans.as_slice() {
        let span = [enter, exit];
        let mut sum = F::zero();
        for k in 0..steps {
            let rho = field.density(shadow_march_point(ground, to_sun, span, k, steps));
            sum = shadow_accumulate(sum, rho);
        }
        tau = (tau + shadow_span_optical_depth(sum, span, steps, sigma_t)).min(F::of(SATURATION));
    }
    cone::beer_lambert(tau)
}

/// The marched shadow map of `field` for `plan`: one transmittance per texel, `i`
/// fastest. The f32 instantiation is the twin of `gpu::ShadowMapPass`.
pub fn shadow_map<F: Real, D: DensityField<F> + ?Sized>(field: &D, plan: &ShadowMapPlan) -> Vec<F> {
    let grid = &plan.grid;
    let [nx, ny] = grid.resolution;
    let origin = grid.origin.map(F::of);
    let (cell, ground) = (F::of(grid.cell_size), F::of(grid.ground_height));
    let to_sun = plan.to_sun.map(F::of);
    let mut out = Vec::with_capacity(grid.texels());
    for j in 0..ny {
        for i in 0..nx {
            let p = shadow_texel_centre([i, j], origin, cell, ground);
            out.push(shadow_texel(field, p, to_sun, plan.steps()));
        }
    }
    out
}

/// The exact shadow map of a [`CloudVolume`] (f64, `i` fastest): at every texel
/// [`crate::reference::transmittance`] toward the sun, integrated to the volume's exit.
pub fn shadow_map_reference(
    volume: &CloudVolume,
    plan: &ShadowMapPlan,
) -> Result<Vec<f64>, ShadowMapError> {
    let [nx, ny] = plan.grid.resolution;
    let mut out = Vec::with_capacity(plan.grid.texels());
    for j in 0..ny {
        for i in 0..nx {
            let p = plan.grid.texel_centre(i, j);
            out.push(crate::reference::transmittance(
                volume,
                p,
                plan.to_sun,
                f64::INFINITY,
            )?);
        }
    }
    Ok(out)
}

/// Root-mean-square and largest absolute difference between a map and a reference of
/// the same length (`None` when the lengths differ or both are empty).
pub fn map_error<F: Real>(map: &[F], reference: &[f64]) -> Option<(f64, f64)> {
    if map.len() != reference.len() || map.is_empty() {
        return None;
    }
    let (mut sum, mut max) = (0.0, 0.0f64);
    for (m, r) in map.iter().zip(reference) {
        let e = m.to_f64().unwrap_or(f64::NAN) - r;
        sum += e * e;
        max = max.max(e.abs());
    }
    Some(((sum / map.len() as f64).sqrt(), max))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blob(n: u32) -> CloudVolume {
        let c = f64::from(n) / 2.0;
        let mut density = Vec::new();
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    let p = [x, y, z].map(|v| f64::from(v) + 0.5 - c);
                    let r2: f64 = p.iter().map(|v| v * v).sum();
                    let wobble = 1.0 + 0.3 * (((x * 5 + y * 3 + z) % 4) as f64 / 3.0);
                    density.push((wobble * (1.0 - r2 / (c * c))).max(0.0) as f32);
                }
            }
        }
        CloudVolume::new([n; 3], [0.0, 0.0, 1000.0], 40.0, 0.01, density).unwrap()
    }

    fn sun(elevation_deg: f64) -> [f64; 3] {
        let (e, a) = (elevation_deg.to_radians(), 30f64.to_radians());
        [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
    }

    #[test]
    fn the_depth_above_is_the_whole_column_below_the_base_and_none_above_the_top() {
        let t = 0.25f64;
        let column = -t.ln();
        // Below the base: the whole column; above the top: nothing; inside: f² of it.
        assert_eq!(shadow_depth_above(t, 500.0, 1000.0, 1800.0), column);
        assert_eq!(shadow_depth_above(t, 1000.0, 1000.0, 1800.0), column);
        assert_eq!(shadow_depth_above(t, 1800.0, 1000.0, 1800.0), 0.0);
        assert_eq!(shadow_depth_above(t, 2500.0, 1000.0, 1800.0), 0.0);
        let inside = shadow_depth_above(t, 1600.0, 1000.0, 1800.0);
        assert!((inside - column * 0.0625).abs() < 1e-15, "{inside}");
        // An opaque texel is a finite depth (T floored at 1e-30), a clear one 0.
        let opaque = shadow_depth_above(0.0f32, 0.0, 1000.0, 1800.0);
        assert!(
            opaque.is_finite() && (opaque - 69.077_55).abs() < 1e-3,
            "{opaque}"
        );
        assert_eq!(shadow_depth_above(1.0f32, 0.0, 1000.0, 1800.0), 0.0);
        // The map's lookup: carried along the light to the plane, texel-centre units.
        let texel: [f64; 2] = shadow_map_texel(
            [100.0, 50.0, 500.0],
            [0.6, 0.0, 0.8],
            1300.0,
            [0.0; 2],
            100.0,
        );
        assert!(
            (texel[0] - 6.5).abs() < 1e-12 && (texel[1] - 0.0).abs() < 1e-12,
            "{texel:?}"
        );
    }

    #[test]
    fn homogeneous_slab_is_beer_lambert_at_any_elevation() {
        // One cell 100 km wide, density 0.5 everywhere (one cell: the lookup clamps).
        let thin = CloudVolume::new([1, 1, 1], [-5e4, -5e4, 500.0], 1e5, 1e-5, vec![0.5]).unwrap();
        // z ∈ [500, 100500]: a zenith sun crosses 100 km, τ = 1e-5 · 0.5 · 1e5 = 0.5; lower
        // suns leave through a side.
        let grid = ShadowGrid::new([-100.0, -100.0], 50.0, [4, 4], 0.0).unwrap();
        for e in [90.0, 60.0, 20.0] {
            let plan = ShadowMapPlan::new(grid, sun(e), 8).unwrap();
            let exact = shadow_map_reference(&thin, &plan).unwrap();
            let marched = shadow_map::<f64, _>(&thin, &plan);
            let twin = shadow_map::<f32, _>(&thin, &plan);
            if e == 90.0 {
                assert!((exact[0] - (-0.5f64).exp()).abs() < 1e-12, "{}", exact[0]);
            }
            for ((x, m), t) in exact.iter().zip(&marched).zip(&twin) {
                // Constant density: the midpoint rule is exact; the f32 twin within rounding.
                assert!((x - m).abs() < 1e-12, "{e}: {x} vs {m}");
                assert!((x - f64::from(*t)).abs() < 1e-5, "{e}: {x} vs {t}");
            }
        }
    }

    #[test]
    fn below_the_horizon_a_cloud_above_casts_nothing() {
        let v = blob(8);
        let grid = ShadowGrid::new([0.0, 0.0], 40.0, [8, 8], 0.0).unwrap();
        for e in [0.0, -5.0, -90.0] {
            let plan = ShadowMapPlan::new(grid, sun(e), 16).unwrap();
            assert!(shadow_map::<f32, _>(&v, &plan).iter().all(|&t| t == 1.0));
            assert!(
                shadow_map_reference(&v, &plan)
                    .unwrap()
                    .iter()
                    .all(|&t| t == 1.0)
            );
        }
        // Ground inside the cloud (ground height 1100 m): a sun below the horizon still
        // crosses the cloud's lower part.
        let inside = ShadowGrid::new([0.0, 0.0], 40.0, [8, 8], 1100.0).unwrap();
        let plan = ShadowMapPlan::new(inside, sun(-20.0), 64).unwrap();
        let exact = shadow_map_reference(&v, &plan).unwrap();
        assert!(exact.iter().any(|&t| t < 0.9), "{exact:?}");
        let (rmse, max) = map_error(&shadow_map::<f32, _>(&v, &plan), &exact).unwrap();
        assert!(rmse < 0.01 && max < 0.05, "{rmse} {max}");
    }

    #[test]
    fn the_march_converges_to_the_exact_map() {
        let v = blob(12);
        for e in [60.0, 10.0] {
            // Centred on the shadow of the blob's centre (240, 240, 1240).
            let l = sun(e);
            let centre = [0, 1].map(|a| 240.0 - 1240.0 * l[a] / l[2] - 600.0);
            let grid = ShadowGrid::new(centre, 30.0, [40, 40], 0.0).unwrap();
            let plan = ShadowMapPlan::new(grid, sun(e), DEFAULT_STEPS).unwrap();
            let exact = shadow_map_reference(&v, &plan).unwrap();
            assert!(exact.iter().any(|&t| t < 0.5), "the blob shades the grid");
            let (rmse, max) = map_error(&shadow_map::<f32, _>(&v, &plan), &exact).unwrap();
            assert!(rmse < 2e-3 && max < 2e-2, "sun {e}: rmse {rmse}, max {max}");
        }
    }

    #[test]
    fn bad_settings_are_named() {
        let err = ShadowGrid::new([0.0, f64::NAN], 1.0, [1, 1], 0.0).unwrap_err();
        assert!(err.to_string().starts_with("origin.y = NaN"), "{err}");
        let err = ShadowGrid::new([0.0, 0.0], 0.0, [1, 1], 0.0).unwrap_err();
        assert!(err.to_string().starts_with("cell_size = 0"), "{err}");
        let err = ShadowGrid::new([0.0, 0.0], 1.0, [1, 0], 0.0).unwrap_err();
        assert!(err.to_string().starts_with("resolution.y = 0"), "{err}");
        let err = ShadowGrid::new([0.0, 0.0], 1.0, [1, 1], f64::INFINITY).unwrap_err();
        assert!(err.to_string().starts_with("ground_height = inf"), "{err}");
        let grid = ShadowGrid::new([0.0, 0.0], 1.0, [1, 1], 0.0).unwrap();
        let err = ShadowMapPlan::new(grid, [0.0; 3], 8).unwrap_err();
        assert!(err.to_string().starts_with("|to_sun| = 0"), "{err}");
        let err = ShadowMapPlan::new(grid, [f64::NAN, 0.0, 1.0], 8).unwrap_err();
        assert!(err.to_string().starts_with("to_sun.x = NaN"), "{err}");
        let err = ShadowMapPlan::new(grid, [0.0, 0.0, 1.0], 0).unwrap_err();
        assert!(err.to_string().starts_with("steps = 0"), "{err}");
        let err = ShadowMapPlan::new(grid, [0.0, 0.0, 1.0], 5000).unwrap_err();
        assert!(err.to_string().starts_with("steps = 5000"), "{err}");
    }
}
