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
//! **Optical thickness and lighting.** Each type has the mean vertical optical thickness
//! τ of its cloud elements from its ISCCP class (Rossow & Schiffer 1999, BAMS 80, 2261:
//! high, middle and low clouds split at τ = 3.6 and 23). An element covers part of the
//! area across its soft edge and its column thickens toward its core: the local τ grows
//! with the noise's height above the coverage threshold (floored at the threshold: a
//! cloud's edge is sharp at a pixel's scale), scaled so that the covered area's mean is
//! the kind's τ ([`cloud_column`]). A view crossing it sees τ/|μ| and lets
//! `exp(−τ/|μ|)` of the background through on the covered part. The column's own
//! radiance ([`cloud_sun_scattering`]) is its exact single scattering with a
//! Henyey–Greenstein phase function (the forward glow around the sun, brightest through
//! the thinner columns) plus the rest of the Eddington
//! two-stream flux (Lacis & Hansen 1974, J. Atmos. Sci. 31, 118; Meador & Weaver 1980)
//! as a uniform source (a thick core's base darker than its thin edges), lit by the
//! sun's irradiance at the layer (the atmosphere's transmittance from the layer toward
//! the sun) and the sky's. `crates/celestial/tests/layer_vs_path_tracer.rs` measures it
//! against cloudlight's path tracer of the same layer as a volume.
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
    CloudLayerFrame, CloudLayerUniforms, DIFFUSIVITY, cloud_column, cloud_density, cloud_fbm,
    cloud_layer_distance, cloud_layer_radiance, cloud_optical_thickness, cloud_reflectance,
    cloud_shadow, cloud_sun_scattering, cloud_value_noise,
};
