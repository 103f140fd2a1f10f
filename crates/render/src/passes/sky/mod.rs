//! The sky: each light's sky radiance where no terrain hides it, the sun's disc through
//! its transmittance (unless celestial draws the sun), drawn first with depth writes
//! off (the sky dome of Hoffman and Preetham 2002); on a moonlit night the moon's sky added.

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use glam::DVec3;
use rayon::prelude::*;

use super::{PassEntry, PlanLine, rung_model};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::scene::prepare::PreparedScene;

/// The sky's entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "sky",
    runs: |_| true,
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let what = match rung_model(scene) {
        None => "atmos' sky pass, drawn first with depth writes off".to_owned(),
        Some(_) if scene.rung == crate::scene::Rung::Dome => {
            "SGSky's dome (with the sun's aureole) per pixel with the sun's disc through \
             the transmittance toward the sun, drawn first with depth writes off"
                .to_owned()
        }
        Some(model) => format!(
            "{model}'s radiance per pixel with the sun's disc through its transmittance, \
             drawn first with depth writes off"
        ),
    };
    let visibility = match &scene.visibility {
        Some(v) => Ok(format!(
            "[visibility] {:.0} m: the aerosol at the camera gives 3.912/V (Koschmieder){}; \
             the sky and the terrain's air are fogged by the rung itself{}",
            v.distance_m,
            if v.rayleigh_limited {
                format!(
                    " — the air alone limits it to {:.0} m, so the aerosol is zero",
                    v.aerosol_visibility_m
                )
            } else {
                String::new()
            },
            v.effective_m
                .filter(|&e| e < v.distance_m)
                .map_or_else(String::new, |e| format!(
                    "; SGSky's modify_vis closes it in to {e:.0} m at the camera (the \
                     in-cloud fog)"
                ))
        )),
        None => Err("no [visibility]: the atmosphere's own aerosol".into()),
    };
    vec![
        PlanLine::timed("sky", Ok(what)),
        PlanLine::untimed("visibility", visibility),
    ]
}

/// The CPU twin: the sun's sky (with its disc) at every pixel whose ray misses the
/// terrain, each other light's sky (no disc: celestial draws the moon) added.
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let scene = frame.scene;
    let camera = &scene.camera;
    let planet = scene.atmosphere.planet_radius;
    let width = frame.width();
    let (sun, others) = frame.lights.split_first().ok_or(RenderError::NotPrepared)?;
    frame
        .pixels
        .par_chunks_mut(width)
        .zip(frame.hits.par_chunks(width))
        .enumerate()
        .try_for_each(|(row, (pixels, hits))| {
            for (column, (pixel, hit)) in pixels.iter_mut().zip(hits).enumerate() {
                if hit.is_some() {
                    continue;
                }
                let xy = [column as u32, row as u32];
                let view32 = atmos::frame::frame_view_direction(xy, camera);
                let view = DVec3::from_array(view32.map(f64::from)).normalize();
                pixel.radiance = match &sun.tables {
                    // The twin of the GPU's sky pass (the sun's disc included).
                    Some(p) => atmos::lut::drop_in::sky_pass_radiance(p.luts, &p.frame, xy, &p.sky),
                    None => {
                        let query =
                            atmos::SkyQuery::new(planet, scene.camera_position, view, scene.sun)
                                .map_err(RenderError::Atmosphere)?;
                        let sample = scene.sky_model.evaluate(&query);
                        crate::present::present_radiance(
                            view32,
                            sample.radiance.map(|v| v as f32),
                            sample.transmittance.map(|v| v as f32),
                            camera,
                            &scene.present,
                        )
                    }
                };
                for light in others {
                    let added = match &light.tables {
                        Some(p) => {
                            atmos::lut::drop_in::sky_pass_radiance(p.luts, &p.frame, xy, &p.sky)
                        }
                        None => {
                            let query = atmos::SkyQuery::new(
                                planet,
                                scene.camera_position,
                                view,
                                light.illuminant.direction,
                            )
                            .map_err(RenderError::Atmosphere)?;
                            light
                                .illuminant
                                .sky_model
                                .evaluate(&query)
                                .radiance
                                .map(|v| v as f32)
                        }
                    };
                    for (value, a) in pixel.radiance.iter_mut().zip(added) {
                        *value += a;
                    }
                }
            }
            Ok::<(), RenderError>(())
        })
}
