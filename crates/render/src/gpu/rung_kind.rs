//! Which rungs have GPU passes of their own, and what their passes need.

use crate::RenderError;
use crate::scene::Rung;

/// Whether `rung` is drawn by these passes (the closed form and single scattering).
pub fn has_rung_passes(rung: Rung) -> bool {
    matches!(
        rung,
        Rung::ClosedForm | Rung::ClosedFormVertex | Rung::Single
    )
}

/// The error of a rung without GPU passes.
pub fn no_gpu_passes(rung: Rung) -> RenderError {
    RenderError::InvalidParameter {
        field: "atmosphere.rung",
        value: format!("\"{}\"", rung.name()),
        reason: "the reference rungs (f64) have no GPU passes; render them on the CPU (--cpu)",
    }
}

/// The error of a scene with GPU marched clouds (`[clouds.volume]`'s march,
/// `[clouds.shell]`) on a rung with neither tables nor passes of its own (the reference
/// rungs): their air is the precomputed rung's tables or the rung's functions
/// (`super::cloud_air`).
pub fn volume_needs_tables(rung: Rung) -> RenderError {
    RenderError::InvalidParameter {
        field: "atmosphere.rung",
        value: format!("\"{}\"", rung.name()),
        reason: "the GPU's volume and shell clouds see their air through the precomputed \
                 rung's tables or the closed form's or single scattering's passes; render \
                 this scene with one of those rungs, or on the CPU (--cpu)",
    }
}

/// The override constants of a rung's aerial-perspective shader (single scattering's
/// sample counts, those of the CPU's `SingleScatteringSky`).
pub(crate) fn air_constants(rung: Rung) -> Vec<(&'static str, f64)> {
    match rung {
        Rung::Single => {
            let settings = atmos::single_scattering::SingleScatteringSettings::default();
            vec![
                ("view_samples", f64::from(settings.view_samples)),
                ("light_samples", f64::from(settings.light_samples)),
            ]
        }
        _ => Vec::new(),
    }
}
