// The view ray-march of a procedural cloud shell as a compute pass: one invocation per
// pixel of a pinhole camera (planet-centred metres) runs field_march's march_pixel, its
// density field the shell (cloudlight::gpu::MarchShellPass binds
// cloudlight::density_source to cloudlight::density_shell), then fades the result toward
// the horizon at its transmittance-weighted depth. Twin:
// cloudlight::march::render_image::<f32> on a CloudShell, each pixel then march::faded by
// CloudShell::horizon_fade(depth).
#import cloudlight::field_march
#import cloudlight::shell

@group(0) @binding(0) var<uniform> params: MarchParams;
// Two texels per pixel (x fastest): (radiance rgb, transmittance), (depth, 0, 0, 0).
@group(0) @binding(1) var<storage, read_write> image_out: array<vec4<f32>>;
// The distance (m) along each pixel's ray (x fastest) where its march stops; read only
// when view.y is 1 (otherwise a placeholder is bound).
@group(0) @binding(2) var<storage, read> max_distance: array<f32>;

@compute @workgroup_size(8, 8)
fn march_shell_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = params.image.xy;
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    // Temporally amortised (view.z = 1): only the pixels the reprojection left to march.
    if params.view.z == 1u && image_out[2u * (gid.x + size.x * gid.y) + 1u].y == 0.0 {
        return;
    }
    var limit = INFINITE_DISTANCE;
    if params.view.y != 0u {
        limit = max_distance[gid.x + size.x * gid.y];
    }
    let result = march_pixel(params, gid.xy, limit);
    // The horizon fade at the cloud's depth (march::faded).
    let fade = horizon_fade(result.depth, params.horizon_fade.x, params.horizon_fade.y);
    let radiance = vec3<f32>(result.radiance.x * fade, result.radiance.y * fade, result.radiance.z * fade);
    let transmittance = 1.0 - fade * (1.0 - result.transmittance);
    let index = 2u * (gid.x + size.x * gid.y);
    image_out[index] = vec4<f32>(radiance, transmittance);
    image_out[index + 1u] = vec4<f32>(result.depth, 0.0, 0.0, 0.0);
}
