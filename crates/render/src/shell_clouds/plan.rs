//! What `skyscape explain` says of the deck's steps.

use cloudlight::march::LightMarch;

use super::{PreparedShell, SHADOW_STEPS};

/// What `skyscape explain` says of the shell's steps (the march, the moon's march at
/// night, the composite; the shadow maps' bake is the terrain pass's).
pub fn shell_pass_plans(
    scene: &crate::scene::PreparedScene,
) -> [(&'static str, Result<String, String>); 3] {
    let Some(cloud) = &scene.shell_cloud else {
        let none = || Err("no [clouds.shell]: no march".to_string());
        return [
            ("shell cloud march", none()),
            ("moonlit shell march", none()),
            (
                "shell clouds",
                Err("no [clouds.shell]: no shell, no march pass, nothing allocated".into()),
            ),
        ];
    };
    let s = cloud.shell.settings();
    let planet = cloud.shell.planet_radius();
    let c = cloud.settings.config();
    let light_steps = match c.light {
        LightMarch::Full { steps } => steps.get(),
        LightMarch::Cone { .. } => 7,
    };
    [
        (
            "shell cloud march",
            Ok(format!(
                "the terrain's depth as a distance per pixel, then cloudlight's march of the \
                 [clouds.shell] shell ({:.0}–{:.0} m, procedural noise per sample: no bake; \
                 {} view × {} light steps per pixel) up to it (a hill hides the deck behind it)",
                s.inner_radius - planet,
                s.outer_radius - planet,
                c.view_steps,
                light_steps,
            )),
        ),
        (
            "moonlit shell march",
            if cloud.lights.len() > 1 {
                Ok(
                    "the [clouds.shell] deck marched again lit by the moon (celestial's \
                     MoonLight through atmos: the terrain's moonlit draw's light), added \
                     through the moonlit air"
                        .into(),
                )
            } else {
                Err(
                    "the moon does not light the scene (no [time], or the sun up or the moon \
                     below −2°): the sun's march only"
                        .into(),
                )
            },
        ),
        (
            "shell clouds",
            Ok(
                "the air in front of the deck per pixel (atmos' aerial_perspective), then the \
                volume cloud's composite of the shell's march over the scene"
                    .into(),
            ),
        ),
    ]
}

/// What `skyscape explain` says of the deck's shadow maps: baked at prepare (measured
/// here), or why none is.
pub(crate) fn shell_shadow_plan(
    scene: &crate::scene::PreparedScene,
    cloud: &PreparedShell,
) -> Result<String, String> {
    let maps: Vec<String> = scene
        .lights()
        .iter()
        .zip(&cloud.lights)
        .filter_map(|(light, lit)| {
            let light = format!("the {}", light.name);
            lit.shadow.as_ref().map(|m| {
                format!(
                    "toward {light} {}×{} texels of {:.0} m",
                    m.resolution[0], m.resolution[1], m.cell_size
                )
            })
        })
        .collect();
    if maps.is_empty() {
        return Err(
            "no [terrain] under the deck, or no light above 1°: no shadow map baked".into(),
        );
    }
    let baked = if cloud.shadows_baked_on_cpu() {
        format!(
            "baked on the CPU at prepare in {:.2} s (measured; the CPU renderer's) and again \
             on the GPU by the GPU renderer",
            cloud.shadow_seconds
        )
    } else {
        "prepared for the GPU: baked by the GPU renderer only".to_owned()
    };
    Ok(format!(
        "cloudlight's shadow map of the deck over the terrain on the plane of its base \
         ({}; {} steps per texel), {baked} (cloudlight's ShellShadowMapPass, the same \
         formula; timed on the frame whose map changed, the first or a new light, and \
         as an empty pass on a frame that reuses it), read by the terrain pass times the \
         volume's",
        maps.join(", "),
        SHADOW_STEPS,
    ))
}
