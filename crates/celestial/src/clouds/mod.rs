//! SimGear SGSky's 2-D cloud layers: flat or curved (following the Earth) sheets at
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

mod immersion;
mod layer;
mod shading;
#[cfg(test)]
mod tests;

pub(crate) use immersion::no_layer;
pub use immersion::{
    cloud_interior_radiance, draw_order, immersion_column, in_cloud_transmittance,
};
pub use layer::{
    CloudKind, CloudKindParameters, CloudLayer, LayerShape, SGSKY_IN_CLOUD_VISIBILITY_M,
};
pub use shading::{
    CloudLayerFrame, CloudLayerUniforms, DIFFUSIVITY, cloud_density, cloud_fbm,
    cloud_layer_distance, cloud_layer_radiance, cloud_reflectance, cloud_shadow, cloud_value_noise,
};
