//! What [`Scene::prepare_cached`](super::Scene::prepare_cached) keeps between
//! preparations: products whose inputs did not change are taken, not built again. An
//! animation's frames, or a viewer's, prepare with one cache, so a frame whose sun moved
//! bakes only what depends on the sun.
//!
//! Kept:
//! - the precomputed rung's static tables (transmittance and multiple scattering,
//!   `atmos::lut::StaticLuts`, the largest part of a preparation), keyed by the
//!   atmosphere's air and the table settings: a light other than the sun (the moon) or
//!   a frame with the same air takes them relit (`StaticLuts::relit`: the tables hold
//!   the air's response per unit irradiance, equal bit for bit to a new bake); also on
//!   disk when the cache has a folder ([`PrepareCache::in_folder`]: one file per air,
//!   settings and version of the code that bakes them, `StaticLuts::to_bytes`, so a
//!   second run of a scene starts without the bake);
//! - the terrain (heightfield, normals, horizon maps, albedo), keyed by the `[terrain]`
//!   section, the hemisphere and, for a heightfield file or a colour image, the file's
//!   path, length and modification time;
//! - celestial's sky as built (its star catalogue loaded), keyed by the atmosphere and
//!   the sky's options, placed anew for each frame's instant.

use std::sync::{Arc, Mutex, PoisonError};

use atmos::lut::{LutSettings, StaticLuts};

use super::TerrainSection;
use super::prepare::PreparedTerrain;

/// What celestial's sky is built from.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SkyKey {
    pub(crate) atmosphere: atmos::Atmosphere,
    pub(crate) options: celestial::sky::SkyOptions,
}

/// A file's path, length and modification time.
pub(crate) type FileStamp = (std::path::PathBuf, u64, Option<std::time::SystemTime>);

/// What a prepared terrain is built from: the section, the heightfield file's and the
/// colour image's path, length and modification time when it reads them (a file
/// replaced between frames is read again), and the hemisphere (the procedural
/// materials' shaded side).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TerrainKey {
    pub(crate) section: TerrainSection,
    pub(crate) file: Option<FileStamp>,
    pub(crate) colour_file: Option<FileStamp>,
    pub(crate) pole_north: i8,
}

/// The most table sets kept in memory: a scene's sun and moon, and a few atmospheres a
/// user switches between.
const KEPT_TABLES: usize = 4;

/// Preparation products kept across preparations (see the module documentation).
/// Shared by reference; safe to use from several threads.
#[derive(Debug, Default)]
pub struct PrepareCache {
    /// Where the static tables are kept between runs (`None`: in memory only).
    folder: Option<std::path::PathBuf>,
    static_luts: Mutex<Vec<(LutSettings, Arc<StaticLuts>)>>,
    terrain: Mutex<Option<(TerrainKey, Arc<PreparedTerrain>)>>,
    sky: Mutex<Option<(SkyKey, celestial::sky::Sky)>>,
    /// Bakes done and products taken: `[baked, taken]`.
    counts: Mutex<[usize; 2]>,
}

impl PrepareCache {
    /// An empty cache, in memory only.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty cache that also keeps the static tables in files in `folder` between
    /// runs (created when the first file is written). A file that cannot be read or
    /// does not hold tables for the same air, settings and format is baked again and
    /// replaced; a folder that cannot be written leaves the cache in memory only. The
    /// files are only ever written as a whole (a temporary file renamed over).
    pub fn in_folder(folder: impl Into<std::path::PathBuf>) -> Self {
        Self {
            folder: Some(folder.into()),
            ..Self::default()
        }
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
        let file = self.folder.as_ref().map(|folder| {
            folder.join(format!(
                "static-luts-{:016x}.bin",
                tables_key(atmosphere, settings)
            ))
        });
        let from_file = match &file {
            Some(path) => match std::fs::read(path) {
                Ok(bytes) => StaticLuts::from_bytes(&bytes, atmosphere, settings)?,
                Err(_) => None,
            },
            None => None,
        };
        let baked = match from_file {
            Some(read) => {
                self.count(1);
                read
            }
            None => {
                let baked = StaticLuts::bake(atmosphere, settings)?;
                self.count(0);
                if let Some(path) = &file {
                    write_whole(path, &baked.to_bytes());
                }
                baked
            }
        };
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

    /// celestial's sky for `key` as built (not yet placed): the kept one when the key is
    /// the same, else `build`'s (then kept in its place).
    pub(crate) fn sky<E>(
        &self,
        key: SkyKey,
        build: impl FnOnce() -> Result<celestial::sky::Sky, E>,
    ) -> Result<celestial::sky::Sky, E> {
        let mut kept = self.sky.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((kept_key, sky)) = kept.as_ref()
            && *kept_key == key
        {
            self.count(1);
            return Ok(sky.clone());
        }
        let sky = build()?;
        self.count(0);
        *kept = Some((key, sky.clone()));
        Ok(sky)
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

/// The name of a static-table file: FNV-1a (64-bit) over the atmosphere's air (its
/// light zeroed), the table settings, this crate's version and, in the workspace, a
/// fingerprint of `atmos`' sources (`build.rs`), so tables baked by other code are
/// never read back. A name, not a check: `StaticLuts::from_bytes` compares the whole
/// header.
fn tables_key(atmosphere: &atmos::Atmosphere, settings: &LutSettings) -> u64 {
    let air = atmos::Atmosphere {
        sun_irradiance: [0.0; 3],
        sun_angular_radius: 0.0,
        ..atmosphere.clone()
    };
    let text = format!(
        "{air:?} {settings:?} {} {}",
        env!("CARGO_PKG_VERSION"),
        option_env!("SKYSCAPE_ATMOS_SOURCE_HASH").unwrap_or("")
    );
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |hash, byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Writes `bytes` to `path` as a whole: a temporary file beside it, renamed over. A
/// failure leaves no file and is not an error (the cache stays in memory).
fn write_whole(path: &std::path::Path, bytes: &[u8]) {
    let Some(folder) = path.parent() else {
        return;
    };
    if std::fs::create_dir_all(folder).is_err() {
        return;
    }
    let temporary = path.with_extension(format!("tmp-{}", std::process::id()));
    if std::fs::write(&temporary, bytes).is_err() || std::fs::rename(&temporary, path).is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
}
