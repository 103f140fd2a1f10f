//! SGSky's 2-D cloud layers (seed 004): flat or curved (following the Earth) sheets at
//! their altitude, with a procedural texture per type, a coverage, lit by the sun's
//! light as the atmosphere delivers it at the layer, fading with distance into the fog,
//! and hidden while the viewer is inside them (the visibility closes in instead:
//! [`CloudLayer::immersion`], used by the `Sky` facade's `modify_vis`). Twin of
//! `shaders/celestial/clouds.wgsl`.
//!
//! **Texture.** Value noise on an integer lattice hashed with `common::hash` (bit-equal
//! in Rust and WGSL), summed over octaves (fBm), stretched along x for cirrus; a layer
//! of `coverage` c is cloudy where the noise exceeds its own (1 − c) quantile (measured
//! from the layer's noise when the layer is made, so the covered fraction is c by
//! construction), with a soft edge of the type's width.
//!
//! **Optical thickness and lighting.** Each type has the vertical optical thickness τ
//! of a cloud element from its ISCCP class (Rossow & Schiffer 1999, BAMS 80, 2261:
//! high, middle and low clouds split at τ = 3.6 and 23); a view crossing it sees
//! τ/|μ| and lets `exp(−τ/|μ|)` of the background through. The cloud's own radiance is
//! the Eddington two-stream reflectance of a conservative layer (Lacis & Hansen 1974,
//! J. Atmos. Sci. 31, 118): `R = ((1 − g)τ + (2/3 − μ₀)(1 − e^{−τ/μ₀})) / (4/3 + (1 −
//! g)τ)` seen from above, the diffusely transmitted `1 − R − e^{−τ/μ₀}` from below,
//! both Lambertian, lit by the sun's irradiance at the layer (the atmosphere's
//! transmittance from the layer toward the sun) and the sky's.
//!
//! The texture's feature sizes are appearance choices anchored where a definition
//! exists (WMO International Cloud Atlas: cirrocumulus elements are narrower than 1°
//! as seen from the ground, ≈ 120 m at 7 km); they are not measurements.

use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};

use crate::error::{CelestialError, Result, check_range};

/// SGSky's cloud types, each with its texture and optical thickness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CloudKind {
    /// Fibrous ice streaks, high (ISCCP high, thin).
    Cirrus,
    /// Small high cells (< 1° across seen from the ground; ISCCP high, thin).
    Cirrocumulus,
    /// A grey middle sheet (ISCCP middle, 3.6 < τ < 23).
    Altostratus,
    /// Heaped low cells with sharp edges (ISCCP low, τ < 3.6 class).
    Cumulus,
    /// A thick low sheet (ISCCP low, τ > 23).
    Stratus,
    /// A thick sheet covering the sky (nimbostratus: ISCCP middle, τ > 23).
    Overcast,
}

/// How a kind looks: the texture and optical constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudKindParameters {
    /// Lattice spacing of the noise's first octave (m).
    pub feature_size_m: f64,
    /// Stretch along x (cirrus streaks); 1 = isotropic.
    pub stretch: f64,
    /// Octaves of noise.
    pub octaves: u32,
    /// Width of the cloud edge in noise units (0.02 sharp … 0.5 diffuse).
    pub softness: f64,
    /// Vertical optical thickness of a cloud element.
    pub optical_thickness: f64,
    /// Asymmetry of the scattering (water droplets ≈ 0.85, ice ≈ 0.75).
    pub asymmetry: f64,
}

impl CloudKind {
    /// Every kind.
    pub const ALL: [CloudKind; 6] = [
        CloudKind::Cirrus,
        CloudKind::Cirrocumulus,
        CloudKind::Altostratus,
        CloudKind::Cumulus,
        CloudKind::Stratus,
        CloudKind::Overcast,
    ];

    /// The kind's texture and optics (τ inside its ISCCP class; g 0.85 for water,
    /// 0.75 for ice crystals).
    pub fn parameters(self) -> CloudKindParameters {
        let p = |feature_size_m, stretch, octaves, softness, optical_thickness, asymmetry| {
            CloudKindParameters {
                feature_size_m,
                stretch,
                octaves,
                softness,
                optical_thickness,
                asymmetry,
            }
        };
        match self {
            CloudKind::Cirrus => p(3000.0, 8.0, 5, 0.25, 1.0, 0.75),
            CloudKind::Cirrocumulus => p(150.0, 1.0, 3, 0.05, 2.0, 0.75),
            CloudKind::Altostratus => p(8000.0, 1.0, 3, 0.4, 9.0, 0.85),
            CloudKind::Cumulus => p(1000.0, 1.0, 5, 0.03, 3.0, 0.85),
            CloudKind::Stratus => p(5000.0, 1.0, 4, 0.3, 30.0, 0.85),
            CloudKind::Overcast => p(10_000.0, 1.0, 3, 0.5, 40.0, 0.85),
        }
    }

    /// Index used by the GPU uniform.
    pub fn index(self) -> u32 {
        Self::ALL.iter().position(|&k| k == self).expect("listed") as u32
    }
}

/// Whether a layer is a plane or a shell following the planet's curvature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LayerShape {
    /// A horizontal plane (SGSky's flat polygon).
    Flat,
    /// A sphere concentric with the planet (SGSky's round-earth "bowl").
    Curved,
}

/// SimGear's default in-cloud visibility (m): `SGCloudLayer`'s `visibility_m`.
pub const SGSKY_IN_CLOUD_VISIBILITY_M: f64 = 25.0;

/// One cloud layer, as `add_cloud_layer` takes it (seed 004: base above sea level,
/// thickness, transition, span, type), plus coverage, shape, in-cloud visibility and the
/// texture's seed.
#[derive(Debug, Clone, PartialEq)]
pub struct CloudLayer {
    /// Base above sea level (m).
    pub base_m: f64,
    /// Thickness (m).
    pub thickness_m: f64,
    /// Transition zone above and below the layer where the visibility closes in (m).
    pub transition_m: f64,
    /// Size of the layer's patch around the viewer (m); SGSky uses 40 km.
    pub span_m: f64,
    /// The type.
    pub kind: CloudKind,
    /// Fraction of the sky covered, in [0, 1].
    pub coverage: f64,
    /// Flat or curved.
    pub shape: LayerShape,
    /// Visibility inside a cloud element (m); the mean extinction inside the layer is
    /// `coverage · 3.912 / in_cloud_visibility_m`.
    pub in_cloud_visibility_m: f64,
    /// Seed of the texture and of the "puffy" variation.
    pub seed: u32,
}

impl CloudLayer {
    /// A layer of `kind` with the given geometry, full coverage for overcast and
    /// stratus, half otherwise, curved, SimGear's 25 m in-cloud visibility, seed 0.
    pub fn new(
        base_m: f64,
        thickness_m: f64,
        transition_m: f64,
        span_m: f64,
        kind: CloudKind,
    ) -> Result<Self> {
        let layer = Self {
            base_m,
            thickness_m,
            transition_m,
            span_m,
            kind,
            coverage: match kind {
                CloudKind::Overcast | CloudKind::Stratus => 1.0,
                _ => 0.5,
            },
            shape: LayerShape::Curved,
            in_cloud_visibility_m: SGSKY_IN_CLOUD_VISIBILITY_M,
            seed: 0,
        };
        layer.validate()?;
        Ok(layer)
    }

    /// Checks every field; the error names the first bad one and its value.
    pub fn validate(&self) -> Result<()> {
        check_range("base_m", self.base_m, -500.0, 100_000.0, "m")?;
        check_range("thickness_m", self.thickness_m, 0.0, 20_000.0, "m")?;
        check_range("transition_m", self.transition_m, 0.0, 20_000.0, "m")?;
        check_range("span_m", self.span_m, 1.0, 2.0e6, "m")?;
        check_range("coverage", self.coverage, 0.0, 1.0, "")?;
        crate::visibility::check_visibility("in_cloud_visibility_m", self.in_cloud_visibility_m)?;
        Ok(())
    }

    /// Top above sea level (m).
    pub fn top_m(&self) -> f64 {
        self.base_m + self.thickness_m
    }

    /// How deep a viewer at `altitude_m` is in the layer, in [0, 1]: 0 outside the
    /// transition zones, 1 between base and top, a smoothstep across each transition
    /// (SGSky ramps linearly; smoothstep makes the visibility's change smooth too).
    pub fn immersion(&self, altitude_m: f64) -> f64 {
        let depth = if altitude_m < self.base_m {
            self.base_m - altitude_m
        } else if altitude_m > self.top_m() {
            altitude_m - self.top_m()
        } else {
            return 1.0;
        };
        if self.transition_m <= 0.0 || depth >= self.transition_m {
            return 0.0;
        }
        let x = 1.0 - depth / self.transition_m;
        x * x * (3.0 - 2.0 * x)
    }

    /// The noise threshold giving this layer's coverage: the (1 − c) quantile of the
    /// layer's own noise over 64 × 64 samples 0.37 features apart (the softness is
    /// centred on it). 2 above the noise's range at c = 0, below it at c = 1.
    pub fn coverage_threshold(&self) -> f32 {
        let p = self.kind.parameters();
        if self.coverage <= 0.0 {
            return 2.0;
        }
        if self.coverage >= 1.0 {
            return -2.0;
        }
        let mut samples: Vec<f32> = (0..64 * 64)
            .map(|k| {
                let (i, j) = ((k % 64) as f32, (k / 64) as f32);
                cloud_fbm(0.37 * i + 0.11, 0.37 * j + 0.23, p.octaves, self.seed)
            })
            .collect();
        samples.sort_by(f32::total_cmp);
        let index = ((1.0 - self.coverage) * (samples.len() - 1) as f64).round() as usize;
        samples[index]
    }

    /// The layer's uniform block for the WGSL functions and the CPU twin.
    pub fn uniforms(&self, frame: &CloudLayerFrame) -> CloudLayerUniforms {
        let p = self.kind.parameters();
        CloudLayerUniforms {
            base_radius: (frame.planet_radius_m + self.base_m) as f32,
            top_radius: (frame.planet_radius_m + self.top_m()) as f32,
            planet_radius: frame.planet_radius_m as f32,
            curved: u32::from(self.shape == LayerShape::Curved),
            feature_size: p.feature_size_m as f32,
            stretch: p.stretch as f32,
            octaves: p.octaves,
            seed: self.seed,
            threshold: self.coverage_threshold(),
            softness: p.softness as f32,
            optical_thickness: p.optical_thickness as f32,
            asymmetry: p.asymmetry as f32,
            offset: frame.offset_m.map(|o| o as f32),
            half_span: (0.5 * self.span_m) as f32,
            fog_extinction: frame.fog_extinction_per_m as f32,
            sun_direction: frame.sun_direction.map(|c| c as f32),
            exp2_fog: u32::from(frame.exp2_fog),
            sunlight: frame.sunlight.map(|c| c as f32),
            padding0: 0.0,
            skylight: frame.skylight.map(|c| c as f32),
            padding1: 0.0,
            fog_colour: frame.fog_colour.map(|c| c as f32),
            padding2: 0.0,
        }
    }
}

/// What a layer needs from the frame: the planet, the fog, the light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudLayerFrame {
    /// Ground radius (m).
    pub planet_radius_m: f64,
    /// Texture offset (m, east and north): the viewer's travel plus wind drift.
    pub offset_m: [f64; 2],
    /// Fog extinction (1/m) between the viewer and the layer: 3.912 / visibility.
    pub fog_extinction_per_m: f64,
    /// SGSky's exp² fog instead of the exponential one.
    pub exp2_fog: bool,
    /// Unit direction toward the sun (east/north/up).
    pub sun_direction: [f64; 3],
    /// The sun's irradiance at the layer (after the atmosphere), per channel.
    pub sunlight: [f64; 3],
    /// The sky's irradiance on a horizontal surface at the layer, per channel.
    pub skylight: [f64; 3],
    /// Radiance of the fog the layer fades into (the horizon sky), per channel.
    pub fog_colour: [f64; 3],
}

/// A layer's uniform block; layout identical to WGSL `CloudLayerUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs)]
pub struct CloudLayerUniforms {
    pub base_radius: f32,
    pub top_radius: f32,
    pub planet_radius: f32,
    pub curved: u32,
    pub feature_size: f32,
    pub stretch: f32,
    pub octaves: u32,
    pub seed: u32,
    pub threshold: f32,
    pub softness: f32,
    pub optical_thickness: f32,
    pub asymmetry: f32,
    pub offset: [f32; 2],
    pub half_span: f32,
    pub fog_extinction: f32,
    pub sun_direction: [f32; 3],
    pub exp2_fog: u32,
    pub sunlight: [f32; 3],
    pub padding0: f32,
    pub skylight: [f32; 3],
    pub padding1: f32,
    pub fog_colour: [f32; 3],
    pub padding2: f32,
}

/// −ln 0.02: the optical depth at which Koschmieder's contrast threshold is reached.
const KOSCHMIEDER_OPTICAL_DEPTH: f32 = 3.912_023;

/// Value noise in [0, 1) at (x, y) (lattice units): the four corners' hashes (seed,
/// cell x, cell y) blended with the smoothstep of the fractional position.
#[doc(hidden)]
pub fn cloud_value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i32, fy as i32);
    let (tx, ty) = (x - fx, y - fy);
    let corner = |dx: i32, dy: i32| {
        unit_float_from_bits(hash_combine(
            hash_combine(seed, ix.wrapping_add(dx) as u32),
            iy.wrapping_add(dy) as u32,
        ))
    };
    let sx = tx * tx * (3.0 - 2.0 * tx);
    let sy = ty * ty * (3.0 - 2.0 * ty);
    let bottom = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    let top = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

/// fBm: `octaves` octaves of [`cloud_value_noise`], each twice the frequency and half
/// the amplitude of the previous (with its own seed), normalised to [0, 1).
#[doc(hidden)]
pub fn cloud_fbm(x: f32, y: f32, octaves: u32, seed: u32) -> f32 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0f32, 1.0f32, 0.0f32, 1.0f32);
    for octave in 0..octaves {
        sum +=
            amplitude * cloud_value_noise(x * frequency, y * frequency, hash_combine(seed, octave));
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total
}

/// Cloud density in [0, 1] at horizontal position (`u`, `v`) metres on the layer:
/// fBm at the layer's scale, stretched along u, through the coverage threshold with
/// the kind's soft edge (a smoothstep of width `softness` centred on `threshold`).
#[doc(hidden)]
pub fn cloud_density(u: f32, v: f32, layer: &CloudLayerUniforms) -> f32 {
    let x = u / (layer.feature_size * layer.stretch);
    let y = v / layer.feature_size;
    let n = cloud_fbm(x, y, layer.octaves, layer.seed);
    let t = ((n - layer.threshold) / layer.softness + 0.5).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Fraction of the direct sun that reaches a point under the layer: the sun's ray from
/// the point crosses the layer's base where the texture has density ρ, and the
/// element's vertical optical thickness τ along the slant leaves exp(−τρ/μ☉) — the
/// `direct` term `cloud_layer_radiance` lights the layer with. `point` is east/north/up
/// metres from the viewer (on the +z axis at radius `r`), the sun the layer's
/// `sun_direction`. 1 for a point at or above the layer's top, outside its patch, or
/// with the sun at or below the horizon (no direct sun for the layer to block). The
/// base is taken flat over the point (the layer's curvature over a shadow's reach is
/// left out: 0.2 m at 1.6 km).
pub fn cloud_shadow(point: [f32; 3], r: f32, layer: &CloudLayerUniforms) -> f32 {
    let sun = layer.sun_direction;
    let mu_sun = sun[2];
    let point_radius = r + point[2];
    if mu_sun <= 0.0 || point_radius >= layer.top_radius {
        return 1.0;
    }
    let distance = (layer.base_radius - point_radius).max(0.0) / mu_sun;
    let x = point[0] + sun[0] * distance;
    let y = point[1] + sun[1] * distance;
    if (x * x + y * y).sqrt() >= layer.half_span {
        return 1.0;
    }
    let density = cloud_density(x + layer.offset[0], y + layer.offset[1], layer);
    (-layer.optical_thickness * density / mu_sun).exp()
}

/// Eddington two-stream reflectance of a conservative layer of optical thickness
/// `optical_thickness` and asymmetry `asymmetry`, lit at cosine `mu_sun` (Lacis &
/// Hansen 1974); the sun below the layer's horizon (μ₀ ≤ 0) reflects nothing.
#[doc(hidden)]
pub fn cloud_reflectance(optical_thickness: f32, asymmetry: f32, mu_sun: f32) -> f32 {
    if mu_sun <= 0.0 {
        return 0.0;
    }
    let scaled = (1.0 - asymmetry) * optical_thickness;
    let direct = 1.0 - (-optical_thickness / mu_sun).exp();
    ((scaled + (2.0 / 3.0 - mu_sun) * direct) / (4.0 / 3.0 + scaled)).clamp(0.0, 1.0)
}

/// Distance (m) along a view from radius `r` with zenith cosine `mu` to the layer
/// surface of radius `layer_radius`: the sphere (curved) or the plane at that altitude
/// (flat); −1 when the view does not reach it (or the viewer is on it).
#[doc(hidden)]
pub fn cloud_layer_distance(r: f32, mu: f32, layer_radius: f32, curved: u32) -> f32 {
    if curved != 0 {
        let hit = atmos::geometry::ray_sphere_intersect(r, mu, layer_radius);
        if r < layer_radius {
            return hit[1];
        }
        if hit[0] >= 0.0 && mu < 0.0 {
            return hit[0];
        }
        return -1.0;
    }
    let height = layer_radius - r;
    if (height > 0.0 && mu > 0.0) || (height < 0.0 && mu < 0.0) {
        return height / mu;
    }
    -1.0
}

/// The layer seen along `view` (unit, east/north/up) from a viewer at radius `r` on
/// the +z axis, composited over `background` (the radiance behind it, per channel):
/// the layer's surface facing the viewer (its base from below, its top from above;
/// nothing from inside), the texture's density there, the cloud's opacity
/// `1 − exp(−τ·density/|μ_layer|)` and radiance (reflected or diffusely transmitted
/// sun and sky light), faded into the fog colour by the fog over the distance and
/// toward the patch's rim (linearly over its outer half). Returns the composited
/// radiance.
pub fn cloud_layer_radiance(
    view: [f32; 3],
    r: f32,
    layer: &CloudLayerUniforms,
    background: [f32; 3],
) -> [f32; 3] {
    let mu = view[2];
    let inside = r >= layer.base_radius && r <= layer.top_radius;
    if inside {
        return background;
    }
    let below = r < layer.base_radius;
    let surface = if below {
        layer.base_radius
    } else {
        layer.top_radius
    };
    let distance = cloud_layer_distance(r, mu, surface, layer.curved);
    if distance < 0.0 {
        return background;
    }
    let horizontal = [view[0] * distance, view[1] * distance];
    let reach = (horizontal[0] * horizontal[0] + horizontal[1] * horizontal[1]).sqrt();
    if reach >= layer.half_span {
        return background;
    }
    let rim = (2.0 * (1.0 - reach / layer.half_span)).min(1.0);
    let density = cloud_density(
        horizontal[0] + layer.offset[0],
        horizontal[1] + layer.offset[1],
        layer,
    );
    if density <= 0.0 {
        return background;
    }
    // Zenith cosine of the view at the hit point (the local vertical there for a
    // curved layer) and of the sun.
    let hit_z = r + mu * distance;
    let hit_radius = if layer.curved != 0 { surface } else { hit_z };
    let mu_hit = if layer.curved != 0 {
        (view[0] * horizontal[0] + view[1] * horizontal[1] + view[2] * hit_z) / hit_radius
    } else {
        mu
    };
    let slant = mu_hit.abs().max(0.01);
    let tau = layer.optical_thickness * density;
    let opacity = (1.0 - (-tau / slant).exp()) * rim;
    let sun = layer.sun_direction;
    let mu_sun = sun[2];
    let reflectance = cloud_reflectance(tau, layer.asymmetry, mu_sun);
    let direct = if mu_sun > 0.0 {
        (-tau / mu_sun).exp()
    } else {
        1.0
    };
    let diffuse_factor = if below {
        (1.0 - reflectance - direct).max(0.0)
    } else {
        reflectance
    };
    let sky_factor = if below {
        (1.0 - cloud_reflectance(tau, layer.asymmetry, 0.5) - (-tau / 0.5).exp()).max(0.0)
    } else {
        cloud_reflectance(tau, layer.asymmetry, 0.5)
    };
    let fog = if layer.exp2_fog != 0 {
        // SGSky's exp² fog with the same 2 % at the visibility: exp(−(βd)²/3.912).
        let x = layer.fog_extinction * distance;
        (-(x * x) / KOSCHMIEDER_OPTICAL_DEPTH).exp()
    } else {
        (-layer.fog_extinction * distance).exp()
    };
    std::array::from_fn(|i| {
        let lit = (diffuse_factor * layer.sunlight[i] * mu_sun.max(0.0)
            + sky_factor * layer.skylight[i])
            * skyscape_wgsl::common::INV_PI;
        let seen = fog * lit + (1.0 - fog) * layer.fog_colour[i];
        background[i] + opacity * (seen - background[i])
    })
}

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

#[cfg(test)]
mod tests {

    #[test]
    fn a_cloud_shadow_is_the_direct_term_where_the_sun_crosses_the_base() {
        let layer = CloudLayer {
            coverage: 0.5,
            seed: 3,
            ..CloudLayer::new(2000.0, 400.0, 100.0, 40_000.0, CloudKind::Cumulus).unwrap()
        };
        let frame = |sun: [f64; 3]| CloudLayerFrame {
            planet_radius_m: 6_360_000.0,
            offset_m: [0.0, 0.0],
            fog_extinction_per_m: 0.0,
            exp2_fog: false,
            sun_direction: sun,
            sunlight: [1.0; 3],
            skylight: [0.1; 3],
            fog_colour: [0.0; 3],
        };
        let (s, c) = (0.6f64, 0.8f64);
        let u = layer.uniforms(&frame([0.0, s, c]));
        let r = 6_360_000.0 + 500.0;
        let (mut shaded, mut clear) = (0, 0);
        for k in 0..400 {
            let point = [
                (k % 20) as f32 * 700.0 - 7000.0,
                (k / 20) as f32 * 700.0 - 7000.0,
                -200.0,
            ];
            let shadow = cloud_shadow(point, r, &u);
            // The sun's ray from 300 m up climbs 1,700 m to the base: 1,275 m north.
            let crossing = [point[0], point[1] + 1700.0 * 0.75];
            let density = cloud_density(crossing[0], crossing[1], &u);
            let expected = (-u.optical_thickness * density / 0.8).exp();
            assert!((shadow - expected).abs() < 1e-4, "{shadow} {expected}");
            shaded += usize::from(shadow < 0.5);
            clear += usize::from(shadow == 1.0);
            // Above the top, or with the sun down: no shadow.
            assert_eq!(cloud_shadow([point[0], point[1], 2000.0], r, &u), 1.0);
            let night = layer.uniforms(&frame([0.0, 0.6, -0.8]));
            assert_eq!(cloud_shadow(point, r, &night), 1.0);
        }
        // Half coverage: both shadowed and sunlit ground.
        assert!(shaded > 50 && clear > 50, "{shaded} {clear}");
    }

    use super::*;

    fn frame() -> CloudLayerFrame {
        CloudLayerFrame {
            planet_radius_m: 6_360_000.0,
            offset_m: [0.0, 0.0],
            fog_extinction_per_m: 3.912 / 30_000.0,
            exp2_fog: false,
            sun_direction: [0.0, 0.6, 0.8],
            sunlight: [1.0, 0.95, 0.9],
            skylight: [0.3, 0.4, 0.6],
            fog_colour: [0.2, 0.25, 0.3],
        }
    }

    #[test]
    fn coverage_is_the_covered_fraction() {
        for kind in CloudKind::ALL {
            for coverage in [0.1, 0.3, 0.5, 0.8] {
                let layer = CloudLayer {
                    coverage,
                    seed: 7,
                    ..CloudLayer::new(2000.0, 300.0, 200.0, 40_000.0, kind).unwrap()
                };
                let u = layer.uniforms(&frame());
                // A different sample set than the threshold's: 200 × 200 points half a
                // feature apart (10⁴ features of the first octave).
                let step = 0.5 * kind.parameters().feature_size_m as f32;
                let mut cloudy = 0usize;
                for i in 0..200 {
                    for j in 0..200 {
                        let d = cloud_density(
                            i as f32 * step * u.stretch + 13.0,
                            j as f32 * step + 71.0,
                            &u,
                        );
                        cloudy += usize::from(d > 0.5);
                    }
                }
                let fraction = cloudy as f64 / 40_000.0;
                assert!(
                    (fraction - coverage).abs() < 0.05,
                    "{kind:?} coverage {coverage}: measured {fraction}"
                );
            }
        }
    }

    #[test]
    fn reflectance_limits() {
        // Thin: ~τ/μ-ish small; thick: → 1; conservative: R + T ≤ 1.
        assert!(cloud_reflectance(0.01, 0.85, 1.0) < 0.01);
        assert!(cloud_reflectance(1000.0, 0.85, 0.7) > 0.98);
        for tau in [0.5, 3.0, 9.0, 30.0] {
            let r = cloud_reflectance(tau, 0.85, 0.6);
            assert!((0.0..=1.0).contains(&r));
        }
        // Thick stratus (τ 30) reflects 70–85 % of overhead sun (Lacis & Hansen's
        // formula gives 0.818; satellite albedos of such decks are 0.6–0.8).
        let r = cloud_reflectance(30.0, 0.85, 1.0);
        assert!((0.6..0.85).contains(&r), "{r}");
        assert_eq!(cloud_reflectance(10.0, 0.85, -0.1), 0.0);
    }

    #[test]
    fn layer_distance_flat_and_curved() {
        let r = 6_361_000.0f32;
        // Straight up to a layer 1 km above: 1 km either way.
        assert!((cloud_layer_distance(r, 1.0, r + 1000.0, 0) - 1000.0).abs() < 0.1);
        assert!((cloud_layer_distance(r, 1.0, r + 1000.0, 1) - 1000.0).abs() < 0.2);
        // Horizontal view: a flat layer is never reached, a curved one is (the Earth
        // falls away beneath the view), √(2Rh) ≈ 113 km.
        assert_eq!(cloud_layer_distance(r, 0.0, r + 1000.0, 0), -1.0);
        let d = cloud_layer_distance(r, 0.0, r + 1000.0, 1);
        assert!((d - 112_800.0).abs() < 500.0, "{d}");
        // Looking up at a layer below: missed.
        assert_eq!(cloud_layer_distance(r, 0.5, r - 500.0, 0), -1.0);
        assert_eq!(cloud_layer_distance(r, 0.5, r - 500.0, 1), -1.0);
    }

    #[test]
    fn immersion_and_draw_order() {
        let layer = CloudLayer::new(1000.0, 500.0, 200.0, 40_000.0, CloudKind::Stratus).unwrap();
        assert_eq!(layer.immersion(0.0), 0.0);
        assert_eq!(layer.immersion(799.0), 0.0);
        assert!((layer.immersion(900.0) - 0.5).abs() < 1e-12);
        assert_eq!(layer.immersion(1200.0), 1.0);
        assert!((layer.immersion(1600.0) - 0.5).abs() < 1e-12);
        assert_eq!(layer.immersion(1800.0), 0.0);
        let layers: Vec<CloudLayer> = [500.0, 3000.0, 8000.0, 1500.0]
            .iter()
            .map(|&b| CloudLayer::new(b, 100.0, 50.0, 40_000.0, CloudKind::Cumulus).unwrap())
            .collect();
        // Viewer at 2 km: above it 8000 then 3000; below it 500 then 1500 (nearest last).
        assert_eq!(draw_order(&layers, 2000.0), vec![2, 1, 0, 3]);
        assert!(draw_order(&[], 2000.0).is_empty());
        // Inside the 1500 m layer: it is left out.
        assert_eq!(draw_order(&layers, 1550.0), vec![2, 1, 0]);
    }

    #[test]
    fn in_cloud_fog_column() {
        let layer = CloudLayer::new(1000.0, 500.0, 200.0, 40_000.0, CloudKind::Stratus).unwrap();
        // From the ground looking up: both ramps (half each) and the core: 200 + 500.
        assert!((immersion_column(&layer, 0.0, true) - 700.0).abs() < 1e-6);
        assert!(immersion_column(&layer, 0.0, false).abs() < 1e-12);
        // From the middle: half the core and one ramp each way.
        assert!((immersion_column(&layer, 1250.0, true) - 350.0).abs() < 1e-6);
        assert!((immersion_column(&layer, 1250.0, false) - 350.0).abs() < 1e-6);
        let t = in_cloud_transmittance(std::slice::from_ref(&layer), 1250.0, 1.0);
        assert!((t - (-3.912_023_005 / 25.0 * 350.0_f64).exp()).abs() < 1e-12);
        assert_eq!(in_cloud_transmittance(&[], 1250.0, 0.3), 1.0);
    }

    #[test]
    fn bad_layers_name_the_field() {
        let e = |r: Result<CloudLayer>| r.unwrap_err().to_string();
        assert!(e(CloudLayer::new(f64::NAN, 1.0, 1.0, 1.0, CloudKind::Cirrus)).contains("base_m"));
        assert!(e(CloudLayer::new(1.0, -1.0, 1.0, 1.0, CloudKind::Cirrus)).contains("thickness_m"));
        assert!(e(CloudLayer::new(1.0, 1.0, 1.0, 0.0, CloudKind::Cirrus)).contains("span_m"));
        let bad = CloudLayer {
            coverage: 1.5,
            ..CloudLayer::new(1.0, 1.0, 1.0, 1000.0, CloudKind::Cirrus).unwrap()
        };
        assert!(bad.validate().unwrap_err().to_string().contains("coverage"));
    }

    #[test]
    fn layers_fade_into_fog_and_hide_from_inside() {
        let layer = CloudLayer::new(2000.0, 400.0, 200.0, 200_000.0, CloudKind::Overcast).unwrap();
        let u = layer.uniforms(&frame());
        let r = 6_360_000.0 + 500.0;
        let background = [0.1, 0.2, 0.5];
        // Overhead: the overcast deck, grey-white, opaque.
        let up = cloud_layer_radiance([0.0, 0.0, 1.0], r, &u, background);
        assert!(up != background);
        // Toward the horizon through 30 km visibility: the layer is nearly the fog.
        let view = [0.0, 0.999_f32.sqrt(), 0.031_6];
        let far = cloud_layer_radiance(view, r, &u, background);
        for i in 0..3 {
            assert!(
                (far[i] - frame().fog_colour[i] as f32).abs() < 0.05,
                "{far:?}"
            );
        }
        // Inside the layer nothing is drawn.
        let inside = cloud_layer_radiance([0.0, 0.0, 1.0], 6_360_000.0 + 2100.0, &u, background);
        assert_eq!(inside, background);
    }
}
