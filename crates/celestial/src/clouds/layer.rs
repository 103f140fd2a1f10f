//! The layers' types, shapes and settings.

use super::*;
use crate::error::{Result, check_range};

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

    /// The coverage a layer of this kind has unless told otherwise: the sheets
    /// (overcast, stratus) cover the sky, the others half of it.
    pub fn default_coverage(self) -> f64 {
        match self {
            CloudKind::Overcast | CloudKind::Stratus => 1.0,
            _ => 0.5,
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

/// One cloud layer, as SGSky's `add_cloud_layer` takes it (base above sea level,
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
            coverage: kind.default_coverage(),
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

    /// The layer's own noise over 64 × 64 samples 0.37 features apart, sorted.
    fn noise_samples(&self) -> Vec<f32> {
        let p = self.kind.parameters();
        let mut samples: Vec<f32> = (0..64 * 64)
            .map(|k| {
                let (i, j) = ((k % 64) as f32, (k / 64) as f32);
                cloud_fbm(0.37 * i + 0.11, 0.37 * j + 0.23, p.octaves, self.seed)
            })
            .collect();
        samples.sort_by(f32::total_cmp);
        samples
    }

    /// The noise threshold giving this layer's coverage: the (1 − c) quantile of the
    /// layer's own noise over 64 × 64 samples 0.37 features apart (the softness is
    /// centred on it). 2 above the noise's range at c = 0, below it at c = 1.
    pub fn coverage_threshold(&self) -> f32 {
        if self.coverage <= 0.0 {
            return 2.0;
        }
        if self.coverage >= 1.0 {
            return -2.0;
        }
        let samples = self.noise_samples();
        let index = ((1.0 - self.coverage) * (samples.len() - 1) as f64).round() as usize;
        samples[index]
    }

    /// The mean height of the noise above the foot of the cloud edge (threshold −
    /// softness/2) over the covered samples (noise above the threshold) of the same
    /// sample set as [`coverage_threshold`](Self::coverage_threshold): the divisor that
    /// makes the kind's optical thickness the mean over the covered area of
    /// [`cloud_optical_thickness`]. 1 for a layer without cloud.
    pub fn core_depth(&self) -> f32 {
        let threshold = self.coverage_threshold();
        let softness = self.kind.parameters().softness as f32;
        let covered: Vec<f32> = self
            .noise_samples()
            .into_iter()
            .filter(|&n| n > threshold)
            .map(|n| n - threshold + 0.5 * softness)
            .collect();
        if covered.is_empty() {
            return 1.0;
        }
        covered.iter().sum::<f32>() / covered.len() as f32
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
            core_depth: self.core_depth(),
            skylight: frame.skylight.map(|c| c as f32),
            padding1: 0.0,
            fog_colour: frame.fog_colour.map(|c| c as f32),
            padding2: 0.0,
        }
    }
}
