// The cloud shell's noise baked into two tileable 3-D textures, one invocation per
// texel: the shape noise (cloud_shape_noise, four channels) into an rgba8unorm
// shape_size³ texture and the detail noise (cloud_detail_noise, three channels, alpha 1)
// into an rgba8unorm detail_size³ texture, each texel at its centre (i + ½)/size of one
// tile. Twin: cloudlight::noise::{bake_shape_noise, bake_detail_noise} (f32), quantised
// by cloudlight::noise::unorm8.

#import cloudlight::noise

struct BakeParams {
    seed: u32,
    shape_size: u32,
    detail_size: u32,
    unused: u32,
}

@group(0) @binding(0) var<uniform> params: BakeParams;
@group(0) @binding(1) var shape_out: texture_storage_3d<rgba8unorm, write>;
@group(0) @binding(2) var detail_out: texture_storage_3d<rgba8unorm, write>;

// The tile coordinate of a texel's centre, (i + ½)/size.
fn noise_texel_coordinate(texel: vec3<u32>, size: u32) -> vec3<f32> {
    return (vec3<f32>(texel) + vec3<f32>(0.5)) / f32(size);
}

@compute @workgroup_size(4, 4, 4)
fn bake_shape(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id >= vec3<u32>(params.shape_size)) {
        return;
    }
    let u = noise_texel_coordinate(id, params.shape_size);
    textureStore(shape_out, id, cloud_shape_noise(u, params.seed));
}

@compute @workgroup_size(4, 4, 4)
fn bake_detail(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id >= vec3<u32>(params.detail_size)) {
        return;
    }
    let u = noise_texel_coordinate(id, params.detail_size);
    textureStore(detail_out, id, vec4<f32>(cloud_detail_noise(u, params.seed), 1.0));
}
