// The sky of a scene whose rung has no tables (the closed form per pixel or per dome
// vertex, single scattering), drawn first with depth writes off as Hoffman & Preetham
// 2002 draw their sky hemisphere: atmos' frame renderer of the rung (atmos::gpu::ClosedFormRenderer,
// SingleScatteringRenderer) has written each pixel's view-ray radiance and
// transmittance into an atmos::gpu::FrameOutput; this full-screen triangle adds the
// sun's disc through the transmittance (render::present's present_radiance: zero disc
// radiance draws none) and writes radiance × `present.exposure`, the scene's exposure
// (the HDR target holds radiance × exposure). Bindings: render::present's camera,
// parameters and input textures (its pixel buffer unused).
// Twin: render::cpu_renderer's sky for these rungs (SkyModel::evaluate, then
// render::present::present_radiance).
#import render::present

@vertex
fn rung_sky_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    // Reverse z: depth 0 is infinitely far.
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn rung_sky_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    let view = frame_view_direction(pixel, camera);
    let radiance = present_radiance(view, textureLoad(radiance_in, pixel, 0).xyz, textureLoad(transmittance_in, pixel, 0).xyz, camera, present);
    // Scaled as a whole to fit the f16 target (the sun's disc), keeping its hue.
    let exposed = radiance * present.exposure;
    let peak = max(max(exposed.x, exposed.y), exposed.z);
    return vec4<f32>(exposed * select(1.0, HDR_LARGEST / peak, peak > HDR_LARGEST), 1.0);
}
