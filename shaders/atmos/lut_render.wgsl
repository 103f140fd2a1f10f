// The per-pixel pass of the precomputed rung (atmos::lut_shading's shade_pixel for
// every pixel of the frame camera), writing the FrameOutput textures. Twin:
// atmos::lut::precomputed_sky::shade_pixel.
#import atmos::lut_shading

@group(2) @binding(0) var frame_radiance: texture_storage_2d<rgba32float, write>;
@group(2) @binding(1) var frame_transmittance: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn render_precomputed(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame_camera.width || id.y >= frame_camera.height {
        return;
    }
    let result = shade_pixel(id.xy);
    textureStore(frame_radiance, id.xy, vec4<f32>(result.radiance, 1.0));
    textureStore(frame_transmittance, id.xy, vec4<f32>(result.transmittance, 1.0));
}
