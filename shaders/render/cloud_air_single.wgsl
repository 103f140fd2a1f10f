// The air in front of a marched cloud (the volume's, the shell's) with rung 2, single
// scattering: per pixel, atmos::single_scattering's in-scatter and transmittance of the
// segment camera → the cloud's transmittance-weighted depth, for the light whose
// direction is `cloud_air_camera.sun` and whose atmosphere is bound in group 1 (the
// sun's, or at night the moon's), with the CPU's SingleScatteringSky's sample counts
// (override constants). The twin of render::volume_air for a rung without tables, with
// its group 2 (render::cloud_air_io), by render::air_segment_single (which
// render::billboard_air_single calls per particle; the formulas are render::air_single's,
// the terrain's aerial perspective). CPU twin: render::volume_clouds::air_in_front without
// tables (the light's segment model, SkyQuery::with_max_distance).
#import atmos::frame
#import atmos::single_scattering
#import render::cloud_air_io
#import render::air_segment_single

@group(0) @binding(0) var<uniform> cloud_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> cloud_air_atmosphere: AtmosphereParameters;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

@compute @workgroup_size(8, 8)
fn cloud_air_single(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = cloud_air_segment(id.xy, cloud_air_camera);
    if !s.has_air {
        return;
    }
    let air = air_segment_single(s, cloud_air_camera.sun, cloud_air_atmosphere, view_samples, light_samples);
    cloud_air_store(s, air.radiance, air.transmittance);
}
