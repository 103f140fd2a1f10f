//! Errors of the `render` crate.

/// What went wrong, naming the field and the value.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A scene parameter is outside its valid range (or not finite).
    #[error("invalid scene: `{field}` = {value}: {reason}")]
    InvalidParameter {
        /// The field, as spelled in the API (e.g. `atmosphere.mie_g`).
        field: &'static str,
        /// Its value, formatted.
        value: String,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// `encode` was called before `prepare`.
    #[error("the pass was encoded before `prepare` gave it a scene")]
    NotPrepared,
    /// The atmosphere, a camera or query, a setting or an atmos GPU pass was rejected
    /// by `atmos`; the typed error is kept as the source (its message says which input).
    #[error("atmos: {0}")]
    Atmosphere(#[from] atmos::AtmosError),
    /// WGSL composition failed (a bug in skyscape's shaders).
    /// `celestial` failed to draw the sky objects.
    #[error("celestial: {0}")]
    Celestial(#[from] celestial::CelestialError),
    #[error("WGSL composition: {0}")]
    Shader(#[from] skyscape_wgsl::ComposeError),
    /// `cloudlight` rejected the volume cloud's camera or lighting (its message names
    /// the field and value).
    #[error("cloudlight: {0}")]
    VolumeCloud(#[from] cloudlight::march::MarchError),
    /// `cloudlight` rejected the billboard cloud's camera or particles (its message
    /// names the field and value).
    #[error("cloudlight billboards: {0}")]
    Billboards(#[from] cloudlight::billboard::BillboardError),
    /// `cloudlight`'s GPU march pass failed (a size beyond the device's limits).
    #[cfg(feature = "gpu")]
    #[error("cloudlight march pass: {0}")]
    MarchPass(#[from] cloudlight::gpu::MarchGpuError),
    /// The device rejected a pipeline, shader or bind group that `what` created (caught
    /// by error scopes: validation, internal, out of memory): e.g. a WGSL feature the
    /// GL backend cannot translate to GLSL. `adapter` is the adapter's name and backend.
    #[cfg(feature = "gpu")]
    #[error(
        "{what} on {adapter}: the device rejected it: {}",
        one_line(.source)
    )]
    Device {
        /// The entry point that failed (e.g. `SceneRenderer::new`).
        what: &'static str,
        /// The adapter's name and backend (e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (gl)`).
        adapter: String,
        /// wgpu's error; its message names the call and the object's label.
        #[source]
        source: wgpu::Error,
    },
}

pub(crate) fn check(
    field: &'static str,
    value: f32,
    ok: bool,
    reason: &'static str,
) -> Result<(), RenderError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(RenderError::InvalidParameter {
            field,
            value: value.to_string(),
            reason,
        })
    }
}

#[cfg(feature = "gpu")]
/// `error`'s message on one line: wgpu's descriptions span several, indented, under a
/// "Validation Error / Caused by:" header (whatever the error's kind), which is dropped.
pub(crate) fn one_line(error: &wgpu::Error) -> String {
    let (kind, text) = match error {
        // Its message is only "Out of Memory": the source names the call and label.
        wgpu::Error::OutOfMemory { source } => ("out of memory", source.to_string()),
        wgpu::Error::Validation { .. } => ("validation error", error.to_string()),
        wgpu::Error::Internal { .. } => ("internal error", error.to_string()),
    };
    let causes: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && *line != "Validation Error" && *line != "Caused by:")
        .collect();
    if causes.is_empty() {
        kind.to_owned()
    } else {
        format!("{kind}: {}", causes.join(": "))
    }
}

#[cfg(test)]
mod tests {
    use super::RenderError;

    #[test]
    fn atmosphere_errors_keep_their_source() {
        let atmos_error = atmos::Atmosphere {
            mie_g: 2.0,
            ..atmos::Atmosphere::earth()
        }
        .validate()
        .unwrap_err();
        let error = RenderError::from(atmos_error.clone());
        let source = std::error::Error::source(&error).expect("the atmos error is the source");
        assert_eq!(
            source.downcast_ref::<atmos::AtmosError>(),
            Some(&atmos_error)
        );
    }
}
