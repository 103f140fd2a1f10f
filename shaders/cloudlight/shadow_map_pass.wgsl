// The ground's cloud shadow map of a CloudVolume as a compute pass: one invocation per
// texel runs field_march's shadow_texel, its density field the volume's grid
// (cloudlight::gpu::ShadowMapPass binds cloudlight::density_source to
// cloudlight::density_grid), and writes exp(−τ) into an R32Float storage texture.
// Twin: cloudlight::shadow_map::shadow_map::<f32> on a CloudVolume (whose density
// lookup is f64 rounded once; this one is f32).
#import cloudlight::field_march

@group(0) @binding(0) var<uniform> params: ShadowMapParams;
@group(0) @binding(1) var shadow_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn shadow_map_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.size.x || gid.y >= params.size.y {
        return;
    }
    let ground = shadow_texel_centre(gid.xy, params.grid.xy, params.grid.z, params.grid.w);
    let transmittance = shadow_texel(ground, params.to_sun.xyz, params.size.z);
    textureStore(shadow_out, vec2<i32>(gid.xy), vec4<f32>(transmittance, 0.0, 0.0, 1.0));
}
