// The air in front of the volume cloud, per pixel: atmos' aerial_perspective (the
// aerial-perspective volume within its range, a march of the tables beyond it: the
// function the CPU renderer calls, atmos::lut::drop_in::aerial_perspective) between the
// camera and the cloud's transmittance-weighted depth, for the light whose tables are
// bound in groups 0 and 1 (the sun's, or at night the moon's). A compute pass: the
// composite fragment reads its result. Calling aerial_perspective in that fragment
// shader instead crashes lavapipe (Mesa 22.3.6, LLVM 15: SIGSEGV in a libvulkan_lvp
// worker thread during the draw, not at pipeline creation). Reduced there to a copy of
// atmos::geometry's ray_sphere_intersect(R + 1000 m, view.y, top radius), its result
// scaled by 1e-30 into the output: it crashes as written (two data-dependent early
// returns, then min/max of q and c/q) and runs with the `q == 0` return removed, with
// min/max replaced by (q, c/q), or with a branch-free intersection; the terrain
// fragment, which imports the same function, runs. The compute pass runs it on lavapipe.
#import atmos::aerial_perspective

struct VolumeAirParams {
    width: u32,
    height: u32,
    padding0: u32,
    padding1: u32,
}

@group(2) @binding(0) var<uniform> air_params: VolumeAirParams;
// cloudlight's march output: two vec4 per pixel, x fastest (radiance rgb + T_c, then the
// transmittance-weighted depth d in x).
@group(2) @binding(1) var<storage, read> march: array<vec4<f32>>;
// Two vec4 per pixel: the air's in-scattered radiance, then its transmittance (written
// where the cloud has opacity, T_c < 1).
@group(2) @binding(2) var<storage, read_write> air: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn volume_air_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= air_params.width || id.y >= air_params.height {
        return;
    }
    let i = 2u * (id.y * air_params.width + id.x);
    if !(march[i].w < 1.0) {
        return;
    }
    let view = frame_view_direction(id.xy, frame_camera);
    let segment = aerial_perspective(view * march[i + 1u].x);
    air[i] = vec4<f32>(segment.radiance, 0.0);
    air[i + 1u] = vec4<f32>(segment.transmittance, 0.0);
}
