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
// Group 2 (the uniform, cloudlight's march output, the air per pixel) is
// render::cloud_air_io's, shared with the rungs' cloud air passes.
#import atmos::aerial_perspective
#import render::cloud_air_io

@compute @workgroup_size(8, 8)
fn volume_air_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = cloud_air_segment(id.xy, frame_camera);
    if !s.has_air {
        return;
    }
    let segment = aerial_perspective(s.view * s.distance);
    cloud_air_store(s, segment.radiance, segment.transmittance);
}
