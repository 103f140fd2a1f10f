//! Each light's atmosphere for the frame: atmos' tables (the precomputed rung: the
//! static tables once per atmosphere, the sky view and aerial perspective per frame),
//! or a rung's own per-pixel evaluation of the sky (the closed form, single
//! scattering). The sun's, and on a moonlit night the moon's (the same atmosphere lit
//! by celestial's `MoonLight`).

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use super::{PassEntry, PlanLine, moonlit, rung_model};
use crate::RenderError;
use crate::cpu_frame::{CpuFrame, precomputed_frame};
use crate::scene::prepare::PreparedScene;

/// The tables' entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "atmosphere tables",
    runs: |_| true,
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let no_moon = || "no [time], or the sun is up or the moon below −2°".to_owned();
    let Some(model) = rung_model(scene) else {
        return vec![
            PlanLine::timed(
                "atmosphere LUT bakes",
                Ok(
                    "sky view and aerial perspective per frame; transmittance and multiple \
                     scattering once, written from the preparation's CPU tables (no GPU bake)"
                        .into(),
                ),
            ),
            PlanLine::timed(
                "moonlit sky LUT bakes",
                if moonlit(scene) {
                    Ok(
                        "the tables lit by the moon (celestial's MoonLight) per frame; its sky \
                         pass adds to the sunlit sky's (timed with \"sky\")"
                            .into(),
                    )
                } else {
                    Err(format!("{}: no moonlit tables", no_moon()))
                },
            ),
        ];
    };
    let rung = scene.rung;
    let evaluation = rung
        .gpu_sky_evaluation()
        .unwrap_or_else(|| format!("{model} per pixel"));
    vec![
        PlanLine::timed(
            "atmosphere LUT bakes",
            Err(format!(
                "rung `{}` has no tables: nothing baked or allocated",
                rung.name()
            )),
        ),
        PlanLine::timed("sky evaluation", Ok(evaluation)),
        PlanLine::timed(
            "moonlit sky LUT bakes",
            Err(format!("rung `{}` has no tables", rung.name())),
        ),
        PlanLine::timed(
            "moonlit sky evaluation",
            if moonlit(scene) {
                Ok(format!(
                    "{model} lit by the moon (celestial's MoonLight), added to the sky"
                ))
            } else {
                Err(no_moon())
            },
        ),
    ]
}

/// The CPU twin: each light's tables for the frame (the precomputed rung; the other
/// rungs evaluate per query and have none).
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let camera = &frame.scene.camera;
    // The sun's sky pass draws its disc unless celestial draws it (sky objects).
    let sun_disc = frame.scene.sky_objects.is_none();
    // The other lights' skies add to the sun's without a disc (celestial draws the moon).
    for light in &mut frame.lights {
        let disc = sun_disc && light.illuminant.index == 0;
        light.tables = precomputed_frame(&light.illuminant, camera, disc)?;
    }
    Ok(())
}
