//! [`BakedShell`]: the shell with its noise baked into textures.

use atmos::real::Real;

use super::*;
use crate::density::{DensityField, RaySpans};
use crate::noise::NoiseTexture;

/// A [`CloudShell`] whose noise is looked up in baked textures ([`NoiseTexture`], the CPU
/// twins of [`crate::gpu::NoiseBake`]'s) instead of evaluated: the density a GPU march
/// over the baked textures sees, as a [`DensityField`] (the spans and σ_t are the
/// shell's).
#[derive(Debug, Clone, PartialEq)]
pub struct BakedShell {
    shell: CloudShell,
    shape: NoiseTexture,
    detail: NoiseTexture,
}

impl BakedShell {
    /// Bakes `shell`'s noise (its seed) into a `shape_size`³ shape and a `detail_size`³
    /// detail texture on the CPU (128³ is about 2 million noise evaluations: seconds in
    /// a release build). Sizes of 0 are an error naming the field.
    pub fn new(shell: CloudShell, shape_size: u32, detail_size: u32) -> Result<Self, ShellError> {
        if shape_size == 0 {
            return Err(ShellError::ZeroCount {
                field: "shape_size",
            });
        }
        if detail_size == 0 {
            return Err(ShellError::ZeroCount {
                field: "detail_size",
            });
        }
        let seed = shell.settings.seed;
        Ok(Self {
            shape: NoiseTexture::shape(seed, shape_size),
            detail: NoiseTexture::detail(seed, detail_size),
            shell,
        })
    }

    /// The shell.
    pub fn shell(&self) -> &CloudShell {
        &self.shell
    }

    /// The baked shape texture.
    pub fn shape(&self) -> &NoiseTexture {
        &self.shape
    }

    /// The baked detail texture.
    pub fn detail(&self) -> &NoiseTexture {
        &self.detail
    }
}

impl<F: Real> DensityField<F> for BakedShell {
    /// [`shell_density_textured`] with the shell's weather at `(x, y)`.
    fn density(&self, p: [F; 3]) -> F {
        let s = &self.shell.settings;
        let (inner, outer) = (F::of(s.inner_radius), F::of(s.outer_radius));
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if !(r > inner && r < outer) {
            return F::zero();
        }
        let weather = self.shell.weather_at([p[0], p[1]]);
        shell_density_textured(
            p,
            inner,
            outer,
            weather.coverage,
            weather.cloud_type,
            F::of(s.shape_period),
            F::of(s.detail_period),
            F::of(s.erosion),
            &self.shape,
            &self.detail,
        )
    }

    fn extinction_per_density(&self) -> F {
        DensityField::<F>::extinction_per_density(&self.shell)
    }

    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> RaySpans<F> {
        self.shell.ray_spans(origin, direction)
    }
}
