use std::num::NonZeroUsize;

use super::EFFECTIVE_EARTH_RADIUS;
use crate::TerrainError;

/// Which algorithm computes the horizon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// Evaluate every sample: the reference, O(n²) per line.
    BruteForce,
    /// Timonen & Westerholm's convex-hull sweep: same angles, O(n) per line.
    HullSweep,
}

/// Options of a horizon bake.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HorizonOptions {
    /// Radius of the sphere whose curvature drops distant terrain by `d²/(2R)`,
    /// metres; `None` for a flat Earth. Default [`EFFECTIVE_EARTH_RADIUS`]
    /// = 4/3 × 6,371 km = 8,494,667 m: the Earth's curvature *with* standard
    /// atmospheric refraction (sight lines bend down with about a quarter of the
    /// Earth's curvature, so distant terrain drops less than on the bare sphere). Use
    /// [`EARTH_RADIUS`](super::EARTH_RADIUS) for the geometric horizon without refraction.
    pub effective_radius: Option<f64>,
    /// Only samples at most this far (metres) count; `None`: up to the map edge.
    pub max_distance: Option<f64>,
    /// Worker threads; `None` uses `std::thread::available_parallelism`.
    pub threads: Option<NonZeroUsize>,
}

impl Default for HorizonOptions {
    fn default() -> Self {
        Self {
            effective_radius: Some(EFFECTIVE_EARTH_RADIUS),
            max_distance: None,
            threads: None,
        }
    }
}

impl HorizonOptions {
    /// No curvature, no maximum distance.
    pub fn flat() -> Self {
        Self {
            effective_radius: None,
            ..Self::default()
        }
    }

    pub(crate) fn validate(&self) -> Result<(), TerrainError> {
        if let Some(r) = self.effective_radius
            && !(r.is_finite() && r > 0.0)
        {
            return Err(TerrainError::param(
                "effective_radius",
                r,
                "must be finite and > 0 metres",
            ));
        }
        if let Some(d) = self.max_distance
            && (d.is_nan() || d < 0.0)
        {
            return Err(TerrainError::param(
                "max_distance",
                d,
                "must be >= 0 metres (or +inf)",
            ));
        }
        Ok(())
    }

    pub(crate) fn inv_two_r(&self) -> f64 {
        self.effective_radius.map_or(0.0, |r| 0.5 / r)
    }

    pub(super) fn thread_count(&self) -> usize {
        self.threads.map_or_else(
            || std::thread::available_parallelism().map_or(1, NonZeroUsize::get),
            NonZeroUsize::get,
        )
    }
}
