//! What [`Scene::prepare_cached`](super::Scene::prepare_cached) keeps between
//! preparations: products whose inputs did not change are taken, not built again. An
//! animation's frames, or a viewer's, prepare with one cache, so a frame whose sun moved
//! bakes only what depends on the sun.
//!
//! Kept now: the precomputed rung's static tables (transmittance and multiple
//! scattering, `atmos::lut::StaticLuts`, 1–2 s on two cores), keyed by the atmosphere's
//! air and the table settings: a light other than the sun (the moon) or a frame with
//! the same air takes them relit (`StaticLuts::relit`: the tables hold the air's
//! response per unit irradiance, equal bit for bit to a new bake); and the terrain
//! (heightfield, normals, horizon maps, albedo), keyed by the `[terrain]` section and,
//! for a heightfield file, the file's path, length and modification time.

use std::sync::{Arc, Mutex, PoisonError};

use atmos::lut::{LutSettings, StaticLuts};

use super::TerrainSection;
use super::prepare::PreparedTerrain;

/// What a prepared terrain is built from: the section, and the heightfield file's path,
/// length and modification time when it reads one (a file replaced between frames is
/// read again).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TerrainKey {
    pub(crate) section: TerrainSection,
    pub(crate) file: Option<(std::path::PathBuf, u64, Option<std::time::SystemTime>)>,
}

/// The most table sets kept (each ~0.3 MB): a scene's sun and moon, and a few
/// atmospheres a user switches between.
const KEPT_TABLES: usize = 4;

/// Preparation products kept across preparations (see the module documentation).
/// Shared by reference; safe to use from several threads.
#[derive(Debug, Default)]
pub struct PrepareCache {
    static_luts: Mutex<Vec<(LutSettings, Arc<StaticLuts>)>>,
    terrain: Mutex<Option<(TerrainKey, Arc<PreparedTerrain>)>>,
    /// Bakes done and products taken: `[baked, taken]`.
    counts: Mutex<[usize; 2]>,
}

impl PrepareCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// The static tables of `atmosphere` with `settings`: a kept set of the same air
    /// relit for this atmosphere's light, or a new bake (then kept).
    pub(crate) fn static_luts(
        &self,
        atmosphere: &atmos::Atmosphere,
        settings: &LutSettings,
    ) -> Result<StaticLuts, atmos::AtmosError> {
        let kept: Vec<Arc<StaticLuts>> = self
            .lock_tables()
            .iter()
            .filter(|(kept, _)| kept == settings)
            .map(|(_, luts)| luts.clone())
            .collect();
        for luts in kept {
            if let Some(relit) = luts.relit(atmosphere)? {
                self.count(1);
                return Ok(relit);
            }
        }
        let baked = StaticLuts::bake(atmosphere, settings)?;
        self.count(0);
        let mut tables = self.lock_tables();
        if tables.len() >= KEPT_TABLES {
            tables.remove(0);
        }
        tables.push((*settings, Arc::new(baked.clone())));
        Ok(baked)
    }

    /// The terrain for `key`: the kept one when the key is the same, else `build`'s
    /// (then kept in its place).
    pub(crate) fn terrain<E>(
        &self,
        key: TerrainKey,
        build: impl FnOnce() -> Result<PreparedTerrain, E>,
    ) -> Result<PreparedTerrain, E> {
        let mut kept = self.terrain.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((kept_key, terrain)) = kept.as_ref()
            && *kept_key == key
        {
            self.count(1);
            return Ok(PreparedTerrain::clone(terrain));
        }
        let terrain = build()?;
        self.count(0);
        *kept = Some((key, Arc::new(terrain.clone())));
        Ok(terrain)
    }

    /// How many products were built and how many taken from the cache since it was made:
    /// `[built, taken]`.
    pub fn counts(&self) -> [usize; 2] {
        *self.counts.lock().unwrap_or_else(PoisonError::into_inner)
    }

    fn count(&self, which: usize) {
        self.counts.lock().unwrap_or_else(PoisonError::into_inner)[which] += 1;
    }

    fn lock_tables(&self) -> std::sync::MutexGuard<'_, Vec<(LutSettings, Arc<StaticLuts>)>> {
        // A panic while holding the lock leaves a valid Vec: keep using it.
        self.static_luts
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }
}
