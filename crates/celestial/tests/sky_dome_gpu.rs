//! SGSky's dome drawn by `celestial::gpu::SkyDomeRenderer` against its CPU twin
//! `celestial::dome_sky::SgskyDomeSky`, pixel for pixel (harness GPU policy: an adapter
//! runs it, none skips it visibly, none with SKYSCAPE_REQUIRE_GPU=1 fails).

use atmos::Atmosphere;
use atmos::closed_form_sky::ClosedFormSky;
use atmos::frame::{FrameCamera, frame_view_direction};
use atmos::gpu::FrameOutput;
use atmos::ladder::{SkyModel, SkyQuery};
use celestial::dome::DomeColouring;
use celestial::dome_sky::SgskyDomeSky;
use celestial::gpu::SkyDomeRenderer;
use glam::DVec3;

fn elevation_azimuth(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.sin(), e.cos() * a.cos(), e.sin())
}

/// Three views of a dome painted from the closed form: toward a low sun (aureole,
/// bright horizon ring), straight up (the centre fan) and down past the skirt, in a
/// frame whose up is not +z (the dome's own frame is built from the viewer). Every
/// pixel's radiance agrees with the CPU within 5e-5 relative to the frame's brightest
/// pixel: the GPU blends in f32 (vertex positions to ~1e-7 relative, barycentric
/// weights to ~1e-5 near the tolerance at shared edges, which the continuous blend
/// turns into a colour error of that order times a vertex-to-vertex difference) and
/// the aureole's Cornette–Shanks phase in f32 (≤ 24 ULP, the parity case's bound); the
/// transmittance is the uniform's, exactly the CPU's rounded to f32.
#[test]
fn the_dome_pass_matches_its_cpu_twin() {
    let Some(ctx) = skyscape_harness::gpu_or_skip("the_dome_pass_matches_its_cpu_twin") else {
        return;
    };
    let atmosphere = Atmosphere::earth();
    let sky = SgskyDomeSky::new(
        ClosedFormSky::new(&atmosphere).unwrap(),
        &atmosphere,
        DomeColouring::SeedWeights,
    )
    .unwrap();
    let tilt = glam::DQuat::from_rotation_x(0.7);
    let up = tilt * DVec3::Z;
    let position = up * (atmosphere.planet_radius + 300.0);
    let sun = tilt * elevation_azimuth(4.0, 120.0);
    let mut renderer = SkyDomeRenderer::new(&ctx.device).unwrap();
    let (width, height) = (96, 64);
    let output = FrameOutput::new(&ctx.device, width, height).unwrap();
    for (name, forward) in [
        ("toward the sun", tilt * elevation_azimuth(6.0, 115.0)),
        ("up", tilt * elevation_azimuth(80.0, 300.0)),
        ("down", tilt * elevation_azimuth(-30.0, 200.0)),
    ] {
        let camera =
            FrameCamera::look_at(position, forward, up, 1.3, width, height, sun, None).unwrap();
        let uniforms = sky.uniforms(position, sun).unwrap();
        renderer
            .prepare(&ctx.queue, &camera, &uniforms, &output)
            .unwrap();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder, None).unwrap();
        ctx.queue.submit([encoder.finish()]);
        let read = |texture| {
            let bytes = skyscape_harness::read_texture(ctx, name, texture).unwrap();
            bytemuck::cast_slice::<u8, [f32; 4]>(&bytes).to_vec()
        };
        let radiance = read(output.radiance());
        let transmittance = read(output.transmittance());
        let mut cpu = Vec::with_capacity(radiance.len());
        for y in 0..height {
            for x in 0..width {
                let view = frame_view_direction([x, y], &camera).map(f64::from);
                let query = SkyQuery::new(
                    atmosphere.planet_radius,
                    position,
                    DVec3::from_array(view).normalize(),
                    sun,
                )
                .unwrap();
                cpu.push(sky.evaluate(&query));
            }
        }
        let peak = cpu.iter().flat_map(|s| s.radiance).fold(0.0f64, f64::max);
        let mut worst = 0.0f64;
        for (k, (gpu, cpu)) in radiance.iter().zip(&cpu).enumerate() {
            for c in 0..3 {
                let error = (f64::from(gpu[c]) - cpu.radiance[c]).abs() / peak;
                worst = worst.max(error);
                assert!(
                    error <= 5e-5,
                    "{name}, pixel {k} channel {c}: GPU {} CPU {} (peak {peak})",
                    gpu[c],
                    cpu.radiance[c]
                );
                assert_eq!(transmittance[k][c], cpu.transmittance[c] as f32);
            }
        }
        eprintln!("{name}: worst |GPU − CPU| / peak = {worst:.2e}");
    }
}

/// `encode` before `prepare`, a frame output of another size and a non-finite dome are
/// typed errors naming what is wrong.
#[test]
fn the_dome_pass_rejects_bad_input() {
    let Some(ctx) = skyscape_harness::gpu_or_skip("the_dome_pass_rejects_bad_input") else {
        return;
    };
    let atmosphere = Atmosphere::earth();
    let sky = SgskyDomeSky::new(
        ClosedFormSky::new(&atmosphere).unwrap(),
        &atmosphere,
        DomeColouring::Model,
    )
    .unwrap();
    let mut renderer = SkyDomeRenderer::new(&ctx.device).unwrap();
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    let error = renderer.encode(&mut encoder, None).unwrap_err().to_string();
    assert!(error.contains("SkyDomeRenderer"), "{error}");
    let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + 2.0);
    let sun = DVec3::new(0.0, 0.6, 0.8);
    let camera =
        FrameCamera::look_at(position, DVec3::X, DVec3::Z, 1.0, 32, 16, sun, None).unwrap();
    let mut uniforms = sky.uniforms(position, sun).unwrap();
    let wrong_size = FrameOutput::new(&ctx.device, 16, 16).unwrap();
    assert!(
        renderer
            .prepare(&ctx.queue, &camera, &uniforms, &wrong_size)
            .is_err()
    );
    let output = FrameOutput::new(&ctx.device, 32, 16).unwrap();
    uniforms.colours[7][1] = f32::NAN;
    let error = renderer
        .prepare(&ctx.queue, &camera, &uniforms, &output)
        .unwrap_err()
        .to_string();
    assert!(error.contains("dome.colours"), "{error}");
}
