//! Which rungs have GPU passes of their own, and what their passes need: the one place
//! that maps a [`Rung`] to its WGSL module, its parameters and its override constants.
//!
//! The passes of the rungs without tables (the terrain's air per pixel and per vertex,
//! the terrain's light, the air in front of marched clouds and of billboards) are each
//! one WGSL entry written against the slot `render::rung_sky`: what a rung provides (its
//! parameter type, a segment's in-scatter and transmittance for one light, the light's
//! irradiance at a terrain point). [`compose_rung_entry`] composes an entry with that
//! slot bound to the rung's own module ([`rung_module`]), so the entries and their entry
//! points are the same for every rung.

use crate::RenderError;
use crate::scene::Rung;

/// The slot the rung-agnostic entries import (`shaders/render/rung_sky.wgsl`).
pub(crate) const RUNG_SLOT: &str = "render::rung_sky";

/// The WGSL module that implements [`RUNG_SLOT`] for `rung`, `None` for a rung without
/// GPU passes of its own: SGSky's dome (its terrain and clouds see the closed form's
/// air), rung 1, the closed form (Hoffman & Preetham 2002), for both its
/// sky evaluations (per pixel, per dome vertex: their air and terrain light are per
/// pixel); rung 2, single scattering.
pub(crate) fn rung_module(rung: Rung) -> Option<&'static str> {
    match rung {
        Rung::Dome | Rung::ClosedForm | Rung::ClosedFormVertex => Some("render::rung_closed_form"),
        Rung::Single => Some("render::rung_single"),
        Rung::Precomputed | Rung::Reference | Rung::ReferenceSpectral => None,
    }
}

/// Whether `rung` is drawn by these passes (the closed form and single scattering).
pub fn has_rung_passes(rung: Rung) -> bool {
    rung_module(rung).is_some()
}

/// The composed WGSL of the rung-agnostic `entry` (a registered module importing
/// [`RUNG_SLOT`]) with the slot bound to `rung`'s module; an error for a rung without
/// GPU passes.
pub(crate) fn compose_rung_entry(rung: Rung, entry: &str) -> Result<String, RenderError> {
    let module = rung_module(rung).ok_or_else(|| no_gpu_passes(rung))?;
    Ok(crate::composer().compose_module_bound(entry, &[(RUNG_SLOT, module)])?)
}

/// The bytes of the uniform `RungParameters` of `rung`'s module for a light of
/// `atmosphere`: `ClosedFormSkyParameters` for the closed form, `AtmosphereParameters`
/// for single scattering.
pub(crate) fn rung_parameters(
    rung: Rung,
    atmosphere: &atmos::Atmosphere,
) -> Result<Vec<u8>, RenderError> {
    Ok(match rung {
        Rung::Dome | Rung::ClosedForm | Rung::ClosedFormVertex => bytemuck::bytes_of(
            &atmos::closed_form_sky::ClosedFormSkyParameters::from_atmosphere(atmosphere)?,
        )
        .to_vec(),
        Rung::Single => bytemuck::bytes_of(&atmosphere.to_uniforms()?).to_vec(),
        Rung::Precomputed | Rung::Reference | Rung::ReferenceSpectral => {
            return Err(no_gpu_passes(rung));
        }
    })
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

/// The override constants of `rung`'s module that its compute passes set (single
/// scattering's sample counts, those of the CPU's `SingleScatteringSky`).
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The rung-agnostic entries and their entry points, as the passes compose them.
    const ENTRIES: [(&str, &[&str]); 5] = [
        ("render::rung_air", &["rung_air"]),
        ("render::vertex_air_compute", &["vertex_air_compute"]),
        ("render::cloud_air_rung", &["cloud_air_rung"]),
        ("render::billboard_air_rung", &["billboard_air_rung"]),
        (
            "render::terrain_rung_aerial_vertex",
            &[
                "terrain_vertex",
                "terrain_rung_fragment",
                "terrain_rung_aerial_vertex",
                "terrain_rung_aerial_fragment",
            ],
        ),
    ];

    /// Every module that imports the slot (directly or not) composes and validates with
    /// every rung's module bound, keeps its entry points, and declares the override
    /// constants its rung's passes set; the entries listed above are such modules.
    #[test]
    fn every_entry_composes_and_validates_with_every_rung_module() {
        let composer = crate::composer();
        let slot_marker = format!("// ---- begin {RUNG_SLOT} ----");
        let importers: Vec<&str> = crate::wgsl::WGSL_MODULES
            .iter()
            .map(|m| m.name)
            .filter(|&name| name != RUNG_SLOT)
            .filter(|name| {
                composer
                    .compose_module(name)
                    .unwrap()
                    .contains(&slot_marker)
            })
            .collect();
        for (entry, _) in ENTRIES {
            assert!(
                importers.contains(&entry),
                "{entry} does not import {RUNG_SLOT}"
            );
        }
        let rungs: Vec<Rung> = Rung::ALL
            .into_iter()
            .filter(|&r| has_rung_passes(r))
            .collect();
        assert_eq!(rungs.len(), 4);
        for rung in rungs {
            let module = rung_module(rung).unwrap();
            for &name in &importers {
                let source = compose_rung_entry(rung, name).unwrap();
                assert!(source.contains(&format!("// ---- begin {module} ----")));
                assert!(!source.contains(&slot_marker), "{name} kept the slot");
                let parsed = skyscape_wgsl::validate(name, &source)
                    .unwrap_or_else(|e| panic!("{name} with {module}: {e}"));
                if let Some((_, points)) = ENTRIES.iter().find(|(e, _)| *e == name) {
                    for point in *points {
                        assert!(
                            parsed.entry_points.iter().any(|p| p.name == *point),
                            "{name} with {module} has no entry point {point}"
                        );
                    }
                }
                for (constant, _) in air_constants(rung) {
                    assert!(
                        parsed
                            .overrides
                            .iter()
                            .any(|(_, o)| o.name.as_deref() == Some(constant)),
                        "{name} with {module} has no override {constant}"
                    );
                }
            }
        }
    }

    /// The rungs without GPU passes have no module and no entry.
    #[test]
    fn rungs_without_passes_have_no_module() {
        for rung in [Rung::Precomputed, Rung::Reference, Rung::ReferenceSpectral] {
            assert_eq!(rung_module(rung), None);
            assert!(compose_rung_entry(rung, "render::rung_air").is_err());
        }
    }
}
