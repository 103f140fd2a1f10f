//! What the runner audits about a case beyond its verdict: whether its reference is
//! independent of the side it checks, and whether its tolerance is tight enough that
//! a real regression would fail it.
//!
//! A check that cannot fail is a defect: a row whose reference calls the same Rust
//! function as the CPU side compares that function with itself, so it is reported as
//! "reference = this side" and never counted as a pass; and a tolerance many times
//! larger than the error any side shows would let a much worse formula through, so
//! the ratio is reported per case and the self-test rejects it above
//! [`LOOSENESS_LIMIT`] unless the case says why.

/// Where a case's reference column comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceKind {
    /// An f64 reference, pinned published values or a second formulation: the CPU
    /// and GPU rows are both checks.
    Independent,
    /// The reference is the case's own CPU side (the same Rust function or bake): the
    /// CPU row compares it with itself and is labelled "reference = this side"; only
    /// the GPU row checks anything.
    CpuSide,
}

/// How the runner audits one case.
#[derive(Clone, Copy, Debug)]
pub struct Audit {
    /// Where the reference column comes from.
    pub reference: ReferenceKind,
    /// Why the tolerance may exceed the largest observed error by more than
    /// [`LOOSENESS_LIMIT`] (`None`: it may not, and the tightness audit fails it).
    pub loose_because: Option<&'static str>,
}

impl Audit {
    /// An independent reference and a tolerance within [`LOOSENESS_LIMIT`] of the
    /// observed error: the usual case.
    pub const INDEPENDENT: Audit = Audit {
        reference: ReferenceKind::Independent,
        loose_because: None,
    };

    /// The reference column is the CPU side itself.
    pub const CPU_IS_REFERENCE: Audit = Audit {
        reference: ReferenceKind::CpuSide,
        loose_because: None,
    };

    /// The same audit, with the reason this case's tolerance is allowed to be more than
    /// [`LOOSENESS_LIMIT`] times the error observed (e.g. a forward-error bound written
    /// for the worst input of a family, or an adapter-dependent built-in).
    pub const fn loose(self, because: &'static str) -> Audit {
        Audit {
            loose_because: Some(because),
            ..self
        }
    }
}

/// The largest allowed ratio of a case's tolerance to the error its checked sides show
/// (the reciprocal of the worst error/allowed ratio over the checked rows). A tolerance
/// looser than this would pass a formula that many times worse than the one under test.
pub const LOOSENESS_LIMIT: f64 = 1000.0;
