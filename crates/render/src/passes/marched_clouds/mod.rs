//! The ray-marched clouds: the `[clouds.shell]` deck (Schneider's procedural shell) and
//! the `[clouds.volume]` cumulus (grown by cloudsim), each marched by cloudlight up to
//! the terrain's depth and seen through the air to its depth; with both, one composite
//! orders the two by depth per pixel, and each casts its shadow on the other.

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use super::{PassEntry, PlanLine, rung_model};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::scene::prepare::PreparedScene;

/// The marched clouds' entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "marched clouds",
    runs: |scene| scene.volume_cloud.is_some() || scene.shell_cloud.is_some(),
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

/// Whether the scene has both marched clouds (composited together by depth).
fn both(scene: &PreparedScene) -> bool {
    scene.volume_cloud.is_some() && scene.shell_cloud.is_some()
}

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let by_depth = || Err("with both marched clouds, composited in \"clouds by depth\"".into());
    let [march, moon_march, shell] = crate::shell_clouds::shell_pass_plans(scene);
    let mut lines = vec![
        PlanLine::timed(march.0, march.1),
        PlanLine::timed(moon_march.0, moon_march.1),
        PlanLine::timed(shell.0, if both(scene) { by_depth() } else { shell.1 }),
        PlanLine::timed(
            "volume cloud march",
            match &scene.volume_cloud {
                Some(_) => Ok(
                    "the terrain's depth as a distance per pixel, then cloudlight's march of \
                     the [clouds.volume] cloud up to it (a ridge cuts the cloud where it stands)"
                        .into(),
                ),
                None => Err("no [clouds.volume] to march (none, or draw = \"billboards\")".into()),
            },
        ),
        PlanLine::timed("moonlit cloud march", moonlit_march_plan(scene)),
        PlanLine::timed(
            "volume clouds",
            match &scene.volume_cloud {
                Some(_) if both(scene) => by_depth(),
                Some(cloud) => Ok(volume_composite_plan(scene, cloud)),
                None => Err(
                    "no [clouds.volume] to march (none, or draw = \"billboards\"): no march \
                     pass, no composite, nothing allocated for it"
                        .into(),
                ),
            },
        ),
    ];
    lines.push(PlanLine::timed(
        "clouds by depth",
        if both(scene) {
            Ok(
                "the shell's and the volume cloud's marches and air composited by depth per \
                 pixel in one full-screen pass: the one with the smaller opacity-weighted \
                 depth over the other"
                    .into(),
            )
        } else {
            Err(
                "not both [clouds.shell] and a marched [clouds.volume]: each marched cloud \
                 composites alone"
                    .into(),
            )
        },
    ));
    let (label, status) = crate::mutual_shadow::plan(scene);
    lines.push(PlanLine::untimed(label, status));
    lines
}

/// What the volume cloud's composite does (its march's size and the air it is seen
/// through).
fn volume_composite_plan(
    scene: &PreparedScene,
    cloud: &crate::volume_clouds::PreparedVolume,
) -> String {
    let [nx, ny, nz] = cloud.volume.dims();
    let config = cloud.settings.config();
    let composite = format!(
        "the composite of cloudlight's march of the [clouds.volume] cumulus ({nx}×{ny}×{nz} \
         cells, {} of density > 0, grown by cloudsim in {} steps; {} view × {} light steps \
         per pixel) over the scene",
        cloud.cloudy_cells,
        cloud.steps,
        config.view_steps,
        match config.light {
            cloudlight::march::LightMarch::Full { steps } => steps.get(),
            _ => 0,
        },
    );
    match rung_model(scene) {
        None => format!(
            "{composite}, through atmos' aerial perspective to its depth per pixel and light \
             (a compute pass, untimed: the table within its range, a march of the tables \
             beyond)"
        ),
        Some(model) => format!(
            "{composite}, through {model}'s in-scatter and transmittance of the segment to \
             its depth per pixel and light (a compute pass, untimed: render::gpu::cloud_air)"
        ),
    }
}

/// The CPU twin: each marched cloud alone over the scene, or both by depth per pixel;
/// each marched once per light of the frame, seen through that light's air, added.
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let scene = frame.scene;
    let lights = &frame.lights;
    match (&scene.shell_cloud, &scene.volume_cloud) {
        (Some(shell), Some(volume)) => crate::cloud_order::composite_clouds_by_depth(
            scene,
            shell,
            volume,
            lights,
            &mut frame.pixels,
        ),
        (Some(shell), None) => {
            crate::shell_clouds::composite_shell_cloud(scene, shell, lights, &mut frame.pixels)
        }
        (None, Some(volume)) => composite_volume_cloud(scene, volume, lights, &mut frame.pixels),
        (None, None) => Ok(()),
    }
}

/// The twin of the GPU's march and volume-cloud composite (`crate::volume_clouds`):
/// each pixel's f32 march through the scene's cloud, drawn where its depth is nearer
/// than the terrain, seen through the air (the precomputed rung's aerial-perspective
/// table, else the segment model) over what is behind it; once per light of `lights`,
/// added.
fn composite_volume_cloud(
    scene: &PreparedScene,
    cloud: &crate::volume_clouds::PreparedVolume,
    lights: &[crate::cpu_frame::LightFrame<'_>],
    out: &mut [crate::cpu_frame::PixelRadiance],
) -> Result<(), RenderError> {
    use crate::marched_cloud::{composite_marched_cloud, lit_by};
    use crate::volume_clouds::{march_pixel_lit, pinhole_camera};
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let pinhole = pinhole_camera(camera, scene.atmosphere.planet_radius)?;
    composite_marched_cloud(
        scene,
        &lit_by(&cloud.lights, lights),
        |lighting, xy, behind| march_pixel_lit(cloud, lighting, &pinhole, size, xy, behind),
        out,
    )
}

/// What `skyscape explain` says of the moonlit march (a pass of the GPU renderer, and
/// the second march of the CPU's): run when the scene's cloud is lit by the moon.
fn moonlit_march_plan(scene: &PreparedScene) -> Result<String, String> {
    let Some(cloud) = &scene.volume_cloud else {
        return Err("no [clouds.volume] to march (none, or draw = \"billboards\")".into());
    };
    match (cloud.lights.get(1), scene.other_lights.first()) {
        (Some(moon), Some(sky)) => Ok(format!(
            "the [clouds.volume] cloud marched again lit by the moon ({:.1}° up; the terrain's \
             moonlit draw's light: celestial's MoonLight through atmos), added through the \
             moonlit air; {}",
            sky.direction.y.clamp(-1.0, 1.0).asin().to_degrees(),
            if moon.shadow.is_some() {
                "its shadow map along the moon shades the moonlit terrain"
            } else {
                "no shadow map (no terrain, or the moon below 1°)"
            }
        )),
        _ => Err(
            "the moon does not light the scene (no [time], or the sun up or the moon \
                  below −2°, as for the terrain's moonlit draw): the sun's march only"
                .into(),
        ),
    }
}
