// The ground's cloud shadow map of a procedural cloud shell as a compute pass: one
// invocation per texel runs field_march's shadow_texel, its density field the shell
// (cloudlight::gpu::ShellShadowMapPass binds cloudlight::density_source to
// cloudlight::density_shell: procedural or grid weather), and writes exp(−τ) into a
// storage buffer, i fastest. Twin: cloudlight::shell_shadow::shell_shadow_map::<f32>.
#import cloudlight::field_march

@group(0) @binding(0) var<uniform> params: ShadowMapParams;
// One transmittance per texel, i fastest.
@group(0) @binding(1) var<storage, read_write> shadow_out: array<f32>;

@compute @workgroup_size(8, 8)
fn shell_shadow_map_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = params.size.xy;
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let ground = shadow_texel_centre(gid.xy, params.grid.xy, params.grid.z, params.grid.w);
    shadow_out[gid.x + size.x * gid.y] = shadow_texel(ground, params.to_sun.xyz, params.size.z);
}
