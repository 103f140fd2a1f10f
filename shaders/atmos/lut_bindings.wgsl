// The bindings of the precomputed rung's passes: the uniforms (group 0) and the LUTs
// (group 1) every lookup in atmos::lut_sampling reads. A user's pipeline that has
// other groups at 0 and 1 composes its shader with
// `atmos::gpu::composer_with_lut_groups(uniform_group, table_group)`, which moves these
// declarations (and only these) to the groups it names; the bind-group layouts are
// `atmos::gpu::LutLayouts`.
#import atmos::atmosphere
#import atmos::frame

// Sizes and sample counts (Rust: LutSettingsUniform).
struct LutSettings {
    transmittance_width: u32,
    transmittance_height: u32,
    transmittance_samples: u32,
    multiple_scattering_width: u32,
    multiple_scattering_height: u32,
    multiple_scattering_samples: u32,
    multiple_scattering_direction_sqrt: u32,
    sky_view_width: u32,
    sky_view_height: u32,
    sky_view_samples: u32,
    // 1: the sky-view LUT stores each texel's transmittance (layer 1); 0: radiance only.
    sky_view_transmittance: u32,
    aerial_perspective_width: u32,
    aerial_perspective_height: u32,
    aerial_perspective_depth: u32,
    aerial_perspective_steps_per_slice: u32,
    aerial_perspective_range: f32,
    pixel_samples: u32,
}

@group(0) @binding(0) var<uniform> lut_atmosphere: AtmosphereParameters;
@group(0) @binding(1) var<uniform> lut_settings: LutSettings;
@group(0) @binding(2) var<uniform> frame_camera: FrameCamera;
// The same view's exact per-pixel mapping (the sky pass, the depth-buffer aerial
// perspective); frame_camera is the symmetric camera covering it.
@group(0) @binding(3) var<uniform> frame_view: FrameView;
// Transmittance to the top of the atmosphere (transmittance_width × _height).
@group(1) @binding(0) var transmittance_lut: texture_2d<f32>;
// The multiple-scattering field's six moment layers (MULTIPLE_SCATTERING_LAYERS).
@group(1) @binding(1) var multiple_scattering_lut: texture_2d_array<f32>;
// The sky view for the frame camera: layer 0 radiance, layer 1 transmittance (if stored).
@group(1) @binding(2) var sky_view_lut: texture_2d_array<f32>;
// The aerial-perspective volume for the frame camera (froxels: x, y, depth slice).
@group(1) @binding(3) var aerial_perspective_radiance: texture_3d<f32>;
@group(1) @binding(4) var aerial_perspective_transmittance: texture_3d<f32>;
// Irradiance on every normal (atmos::lut::sky_irradiance): μ_s × r, one layer per normal.
@group(1) @binding(5) var sky_irradiance_lut: texture_2d_array<f32>;
