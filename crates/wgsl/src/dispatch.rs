//! Workgroup counts for one-dimensional compute kernels, within the device's limit.
//!
//! A dispatch may have at most `max_compute_workgroups_per_dimension` workgroups along
//! each axis (65,535 on many devices, WebGPU's guaranteed minimum). A kernel over `n`
//! invocations that needs more groups than that folds the surplus into `y`, and
//! recovers its linear index as
//!
//! ```wgsl
//! let index = gid.x + gid.y * num_workgroups.x * WORKGROUP_SIZE;
//! if index >= n { return; }
//! ```
//!
//! This is the one place skyscape computes such counts. It takes the limit as an
//! argument, so it needs no wgpu: callers pass
//! `device.limits().max_compute_workgroups_per_dimension`.

/// Errors from [`workgroups_1d`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum DispatchError {
    /// A zero workgroup size.
    #[error("workgroup_size must be at least 1, got 0")]
    ZeroWorkgroupSize,
    /// A zero limit (no device reports one; WebGPU guarantees at least 65,535).
    #[error("max_compute_workgroups_per_dimension must be at least 1, got 0")]
    ZeroLimit,
    /// The invocations need more than `limit × limit` workgroups.
    #[error(
        "{invocations} invocations in workgroups of {workgroup_size} need {groups} workgroups, \
         more than max_compute_workgroups_per_dimension² = {limit}²"
    )]
    TooManyInvocations {
        /// Invocations asked for.
        invocations: u32,
        /// Invocations per workgroup.
        workgroup_size: u32,
        /// Workgroups needed.
        groups: u32,
        /// The device's `max_compute_workgroups_per_dimension`.
        limit: u32,
    },
}

/// Workgroup counts `[x, y, 1]` covering `invocations` invocations of a 1-D kernel
/// with `workgroup_size` invocations per group, each count at most
/// `max_per_dimension` (the device's `max_compute_workgroups_per_dimension`).
///
/// `x·y·workgroup_size ≥ invocations` always; `y = 1` while the groups fit in one
/// row, and otherwise `x` is as even as possible so the surplus invocations (which
/// the kernel skips) stay below one row of `x` groups. At least one group is returned
/// for zero invocations, so a dispatch is never empty.
///
/// ```
/// use skyscape_wgsl::dispatch::workgroups_1d;
/// assert_eq!(workgroups_1d(100, 64, 65_535), Ok([2, 1, 1]));
/// // 10 million invocations need 156,250 groups: folded into 3 rows of 52,084.
/// assert_eq!(workgroups_1d(10_000_000, 64, 65_535), Ok([52_084, 3, 1]));
/// ```
pub fn workgroups_1d(
    invocations: u32,
    workgroup_size: u32,
    max_per_dimension: u32,
) -> Result<[u32; 3], DispatchError> {
    if workgroup_size == 0 {
        return Err(DispatchError::ZeroWorkgroupSize);
    }
    if max_per_dimension == 0 {
        return Err(DispatchError::ZeroLimit);
    }
    let groups = invocations.div_ceil(workgroup_size).max(1);
    if groups <= max_per_dimension {
        return Ok([groups, 1, 1]);
    }
    let rows = groups.div_ceil(max_per_dimension);
    if rows > max_per_dimension {
        return Err(DispatchError::TooManyInvocations {
            invocations,
            workgroup_size,
            groups,
            limit: max_per_dimension,
        });
    }
    Ok([groups.div_ceil(rows), rows, 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every index below `invocations` is reached by some (gid.x, gid.y), and the
    /// counts respect the limit.
    fn check_cover(invocations: u32, workgroup_size: u32, limit: u32) {
        let [x, y, z] = workgroups_1d(invocations, workgroup_size, limit).unwrap();
        assert!(x >= 1 && y >= 1 && z == 1);
        assert!(
            x <= limit && y <= limit,
            "{invocations}: {x} x {y} over {limit}"
        );
        let covered = u64::from(x) * u64::from(y) * u64::from(workgroup_size);
        assert!(covered >= u64::from(invocations), "{invocations}");
        // The surplus (skipped by the kernel's bounds check) is less than one row
        // (zero invocations still get one group).
        assert!(
            invocations == 0
                || covered - u64::from(invocations) < u64::from(x) * u64::from(workgroup_size),
            "{invocations}: {x} x {y}"
        );
    }

    #[test]
    fn folding_covers_every_index_within_the_limit() {
        for limit in [65_535, 65_536, 1 << 20, 7] {
            for n in [
                0u32,
                1,
                63,
                64,
                65,
                64 * 7,
                64 * 7 + 1,
                64 * 49,
                65_535 * 64,
                65_535 * 64 + 1,
                10_000_000,
                u32::MAX / 64 * 63,
            ] {
                if workgroups_1d(n, 64, limit).is_ok() {
                    check_cover(n, 64, limit);
                }
            }
        }
        // Without folding below the limit; folded just above it.
        assert_eq!(workgroups_1d(65_535 * 64, 64, 65_535), Ok([65_535, 1, 1]));
        assert_eq!(
            workgroups_1d(65_535 * 64 + 1, 64, 65_535),
            Ok([32_768, 2, 1])
        );
        // A larger device limit is used, not 65,535.
        assert_eq!(workgroups_1d(65_536 * 64, 64, 1 << 20), Ok([65_536, 1, 1]));
        // Every u32 count fits with a workgroup of 64 under WebGPU's minimum limit.
        check_cover(u32::MAX, 64, 65_535);
        check_cover(u32::MAX, 1, 65_536);
    }

    #[test]
    fn impossible_requests_are_typed_errors() {
        assert_eq!(
            workgroups_1d(10, 0, 65_535),
            Err(DispatchError::ZeroWorkgroupSize)
        );
        assert_eq!(workgroups_1d(10, 64, 0), Err(DispatchError::ZeroLimit));
        let error = workgroups_1d(50, 1, 7).unwrap_err();
        assert_eq!(
            error,
            DispatchError::TooManyInvocations {
                invocations: 50,
                workgroup_size: 1,
                groups: 50,
                limit: 7
            }
        );
        assert!(
            error
                .to_string()
                .contains("max_compute_workgroups_per_dimension")
        );
        // 49 groups fit in 7 x 7.
        check_cover(49, 1, 7);
    }
}
