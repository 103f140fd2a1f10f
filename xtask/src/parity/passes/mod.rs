//! Parity cases for whole passes (a simulation step, a bake): the case supplies its
//! own CPU evaluation (reference and f32 twin) and GPU evaluation; comparison and
//! reporting are shared with the function cases.

pub use super::audit::Audit;
use super::compare::Tolerance;

mod atmos_drop_in_passes;
mod atmos_irradiance_passes;
mod atmos_passes;
mod cloudlight_march_passes;
mod cloudlight_march_shell_passes;
mod cloudlight_noise_passes;
mod cloudlight_passes;
mod cloudlight_shadow_passes;
mod cloudlight_shell_shadow_passes;
mod cloudsim_passes;
mod terrain_passes;
mod terrain_stack_passes;

/// The CPU side of a pass case.
#[derive(Debug, Default)]
pub struct PassCpu {
    /// Number of inputs (cells, texels, …) the pass covered.
    pub inputs: usize,
    /// The reference outputs (f64; exact integers for bit-exact passes).
    pub reference: Vec<f64>,
    /// Optional forward-error allowance per output.
    pub bounds: Option<Vec<f64>>,
    /// The fast CPU implementation's outputs.
    pub cpu: Vec<f32>,
}

/// A pass checked GPU vs CPU vs reference.
pub struct PassCase {
    /// `crate::pass`.
    pub name: &'static str,
    /// Runs the reference and the CPU implementation.
    pub cpu: fn() -> Result<PassCpu, String>,
    /// Runs the pass on the GPU; outputs in the same order as `PassCpu::reference`.
    pub gpu: fn(&skyscape_harness::GpuContext) -> Result<Vec<f32>, String>,
    /// Whether the reference is independent of the CPU side (LUT bakes without an
    /// f64 bake are `Audit::CPU_IS_REFERENCE`), and why the tolerance may be loose.
    pub audit: Audit,
    /// Tolerance with its justification.
    pub tolerance: Tolerance,
}

/// Splits 32-bit words into exact f32 halves (16 bits each), so bit-exact state
/// comparisons go through the same comparator (exact tolerance).
pub fn words_as_exact_floats(words: &[u32]) -> Vec<f32> {
    words
        .iter()
        .flat_map(|w| [(w & 0xffff) as f32, (w >> 16) as f32])
        .collect()
}

/// All pass cases, in report order.
pub fn all() -> Vec<PassCase> {
    [
        terrain_passes::cases(),
        terrain_stack_passes::cases(),
        cloudsim_passes::cases(),
        cloudlight_passes::cases(),
        cloudlight_march_passes::cases(),
        cloudlight_march_shell_passes::cases(),
        cloudlight_noise_passes::cases(),
        cloudlight_shadow_passes::cases(),
        cloudlight_shell_shadow_passes::cases(),
        atmos_passes::cases(),
        atmos_drop_in_passes::cases(),
        atmos_irradiance_passes::cases(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn word_split_is_exact_and_ordered() {
        assert_eq!(
            super::words_as_exact_floats(&[0xdead_beef]),
            vec![0xbeef as f32, 0xdead as f32]
        );
    }
}
