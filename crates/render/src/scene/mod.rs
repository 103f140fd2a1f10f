//! The TOML scene file: what a scene contains, parsed with serde + `toml`, every
//! value checked by the crate that owns it (`atmos`, `terrain`), every error naming
//! the line, column, field and value as the user typed them (degrees stay degrees).
//!
//! World frame (`docs/architecture.md`): right-handed, metres, `x` east, `y` up,
//! `z` south; `y = 0` is the planet's surface under the camera (the atmosphere's
//! planet centre is at `(0, −planet_radius, 0)`). A heightfield is centred on the
//! origin: its columns run east along `x`, its rows south along `z`, its elevation
//! is `y`.
//!
//! ```toml
//! [camera]
//! position = [0.0, 1500.0, 9000.0]   # metres: x east, y up, z south
//! look_at = [0.0, 600.0, 0.0]        # or look_direction = [x, y, z]
//! vertical_fov_deg = 50.0
//!
//! [sun]
//! elevation_deg = 35.0
//! azimuth_deg = 220.0                # clockwise from north (east 90)
//!
//! [atmosphere]
//! rung = "precomputed"               # as `skyscape --rung` spells it
//!
//! [terrain.procedural]
//! seed = 7
//! size = 256
//! cell_size = 60.0
//!
//! [output]
//! width = 960
//! height = 540
//! ```
//!
//! ```
//! let scene = render::scene::Scene::parse(
//!     "[camera]\nposition = [0.0, 2.0, 0.0]\nlook_direction = [0.0, 0.3, -1.0]\n\
//!      [sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n",
//!     ".",
//! )
//! .unwrap();
//! assert!(scene.file.terrain.is_none());
//! ```

mod animation;
mod assemble;
pub mod cache;
mod error;
mod ground;
mod layer_frame;
mod locate;
pub mod prepare;
mod sgsky;
mod sgsky_prepare;
pub mod shipped;
mod terrain_colour_section;
mod terrain_prepare;
mod warnings;

pub use animation::{AnimationSection, LayerChange, MAX_FRAMES};
pub use cache::PrepareCache;
pub use error::{Location, Origin, SceneError};
pub use prepare::{CameraMove, Illuminant, PreparedScene, PreparedTerrain};
pub use sgsky::{CloudKindName, CloudLayerSection, Coverage, CoverageName, VisibilitySection};
pub use terrain_colour_section::{ColourSection, MaterialsModel, ProceduralMaterialsSection};

use std::path::{Path, PathBuf};

use serde::Deserialize;

/// A parsed scene: the file's contents, its source text (to locate fields in errors
/// found after parsing) and the folder relative paths are read from.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The values, as typed (defaults filled in).
    pub file: SceneFile,
    source: String,
    base_dir: PathBuf,
    /// Dotted keys whose value a command-line flag replaced, and the flag.
    flags: Vec<(String, &'static str)>,
}

impl Scene {
    /// Reads and parses a scene file; relative paths inside it are relative to its folder.
    pub fn open(path: impl AsRef<Path>) -> Result<Self, SceneError> {
        let path = path.as_ref();
        let source = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            path: path.to_owned(),
            source,
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        Self::parse(&source, base)
    }

    /// Parses scene text; relative paths inside it are relative to `base_dir`.
    pub fn parse(source: &str, base_dir: impl AsRef<Path>) -> Result<Self, SceneError> {
        let file: SceneFile =
            toml::from_str(source).map_err(|e| SceneError::from_toml(source, e))?;
        Ok(Self {
            file,
            source: source.to_owned(),
            base_dir: base_dir.as_ref().to_owned(),
            flags: Vec::new(),
        })
    }

    /// Where a field (`["camera", "vertical_fov_deg"]`) is written, if it is; the flag
    /// when one replaced it ([`Scene::set_by_flag`]).
    pub fn location(&self, path: &[&str]) -> Option<Location> {
        let dotted = path.join(".");
        match self.flags.iter().find(|(key, _)| *key == dotted) {
            Some(&(_, flag)) => {
                let at = locate::locate(&self.source, path)
                    .filter(|l| l.origin == Origin::Key)
                    .map_or((0, 0), |l| (l.line, l.column));
                Some(Location {
                    line: at.0,
                    column: at.1,
                    origin: Origin::Flag(flag),
                })
            }
            None => locate::locate(&self.source, path),
        }
    }

    /// Records that `flag` (`"--width"`) supplied the value of the key at `path`
    /// (`["output", "width"]`): errors about that key then name the flag, not the
    /// file's line.
    pub fn set_by_flag(&mut self, path: &[&str], flag: &'static str) {
        let dotted = path.join(".");
        self.flags.retain(|(key, _)| *key != dotted);
        self.flags.push((dotted, flag));
    }

    /// A path from the scene, resolved against the scene file's folder.
    pub fn resolve(&self, path: &Path) -> PathBuf {
        if path.is_absolute() {
            path.to_owned()
        } else {
            self.base_dir.join(path)
        }
    }

    /// An error about the field at `path` (dotted in the message) with its value as typed.
    pub(crate) fn invalid(&self, path: &[&str], value: String, reason: String) -> SceneError {
        SceneError::Invalid {
            location: self.location(path),
            field: path.join("."),
            value,
            reason,
        }
    }

    /// An error `atmos` raised about the field at `path`.
    pub(crate) fn atmos_error(
        &self,
        path: &[&str],
        value: String,
        source: atmos::AtmosError,
    ) -> SceneError {
        SceneError::Atmosphere {
            location: self.location(path),
            field: path.join("."),
            value,
            source: Box::new(source),
        }
    }

    /// An error `celestial` raised about the field at `path`.
    pub(crate) fn celestial_error(
        &self,
        path: &[&str],
        value: String,
        source: celestial::CelestialError,
    ) -> SceneError {
        SceneError::Celestial {
            location: self.location(path),
            field: path.join("."),
            value,
            source: Box::new(source),
        }
    }

    /// An error `terrain` raised about the field at `path`.
    pub(crate) fn terrain_error(
        &self,
        path: &[&str],
        value: String,
        source: terrain::TerrainError,
    ) -> SceneError {
        SceneError::Terrain {
            location: self.location(path),
            field: path.join("."),
            value,
            source: Box::new(source),
        }
    }
}

/// The whole file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// The viewer.
    pub camera: CameraSection,
    /// The sun's direction, given explicitly; exactly one of this and `[time]`.
    pub sun: Option<SunSection>,
    /// A date, time and place: the sun (and, with `[sky_objects]`, the moon, planets
    /// and stars) placed by `celestial`'s ephemeris; exactly one of this and `[sun]`.
    pub time: Option<TimeSection>,
    /// The sun's disc, the moon, planets and stars drawn over the sky (`celestial`).
    /// Needs `[time]`; on by default when `[time]` is given.
    pub sky_objects: Option<SkyObjectsSection>,
    /// Which model of the atmosphere, and its parameters.
    #[serde(default)]
    pub atmosphere: AtmosphereSection,
    /// The terrain; without it the view shows the sky over the atmosphere's ground.
    pub terrain: Option<TerrainSection>,
    /// Image size, exposure, where to write it.
    #[serde(default)]
    pub output: OutputSection,
    /// A sequence of frames (`skyscape render --frames`, numbered files).
    pub animation: Option<AnimationSection>,
    /// Cloud layers (SimGear's SGSky layers from `celestial`), lit by its `Sky`:
    /// needs `[time]`.
    pub clouds: Option<CloudsSection>,
    /// The meteorological visibility (SGSky's `set_visibility`): the aerosol of the
    /// atmosphere and the fog of the cloud layers.
    pub visibility: Option<VisibilitySection>,
}

/// `[clouds]`: `[[clouds.layers]]` tables, drawn after the opaque scene, farthest
/// first, each hidden where terrain is nearer than the layer; and `[clouds.volume]`, a
/// cumulus grown by `cloudsim` and ray-marched by `cloudlight`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudsSection {
    /// The layers.
    #[serde(default)]
    pub layers: Vec<CloudLayerSection>,
    /// A volumetric cloud (`crate::volume_clouds`).
    pub volume: Option<CloudVolumeSection>,
    /// Schneider's (GPU Pro 7, 2015) ray-marched cloud shell (`crate::shell_clouds`).
    pub shell: Option<crate::shell_clouds::CloudShellSection>,
}

/// `[clouds.volume]`: a cloud grown by `cloudsim`'s automaton (seed, steps, grid,
/// ellipsoids) and marched by `cloudlight` (Schneider's (GPU Pro 7) lighting). The grid's cells are
/// `cell_size_m` cubes; its axes are east, north, up (cloudsim's x, y, z up).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudVolumeSection {
    /// The automaton's seed.
    #[serde(default)]
    pub seed: u32,
    /// Automaton steps grown before the frame (≥ 1).
    pub steps: u32,
    /// Cells `[east, north, up]` (each ≥ 1; at most 256 × 256 × 128).
    #[serde(default = "default_volume_grid")]
    pub grid: [u32; 3],
    /// Cell edge, metres.
    pub cell_size_m: f64,
    /// Altitude of the grid's bottom above the camera's ground (world y), metres.
    pub base_m: f64,
    /// World `[x, z]` (east, south) of the grid's horizontal centre, metres.
    #[serde(default)]
    pub centre_m: [f64; 2],
    /// Extinction per unit density σ_t, 1/m (physical: 0.03 /m is a 33 m mean free
    /// path in the cloud's core).
    #[serde(default = "default_sigma_t")]
    pub sigma_t_per_density: f64,
    /// View-march steps per pixel (1..=1024).
    #[serde(default = "default_view_steps")]
    pub view_steps: u32,
    /// Light-march steps toward the sun per sample (1..=256).
    #[serde(default = "default_light_steps")]
    pub light_steps: u32,
    /// Multiple-scattering octaves of the march (1: single scattering; 1..=8).
    #[serde(default = "default_octaves_volume")]
    pub octaves: u32,
    /// The octaves' extinction factor `a` in [0, 1] (octave `n` sees `aⁿ·τ`).
    #[serde(default = "half")]
    pub octave_a: f64,
    /// The octaves' contribution factor `b` in [0, 1] (octave `n` weighs `bⁿ`;
    /// `a ≤ b` keeps the sum energy-conserving).
    #[serde(default = "half")]
    pub octave_b: f64,
    /// The octaves' phase eccentricity factor `c` in [0, 1] (octave `n` uses `cⁿ·g`).
    #[serde(default = "half")]
    pub octave_c: f64,
    /// Where clouds may grow, in cells of the grid (default: two overlapping
    /// ellipsoids filling the grid, a cumulus with a tower).
    #[serde(default)]
    pub ellipsoids: Vec<EllipsoidSection>,
    /// How the cloud is drawn: `"march"` (default, `crate::volume_clouds`) or
    /// `"billboards"` (Dobashi et al. 2000: lit by slices, `crate::billboard_clouds`).
    #[serde(default)]
    pub draw: crate::billboard_clouds::VolumeDraw,
    /// `[clouds.volume.billboards]`: the billboards' settings (`draw = "billboards"`).
    pub billboards: Option<crate::billboard_clouds::BillboardsSection>,
}

/// One `[[clouds.volume.ellipsoids]]`: cloudsim's growth region, in cells.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EllipsoidSection {
    /// Centre, cells `[east, north, up]` from the grid's corner.
    pub centre: [f64; 3],
    /// Semi-axes, cells.
    pub radii: [f64; 3],
}

fn default_volume_grid() -> [u32; 3] {
    [32, 32, 16]
}
fn default_sigma_t() -> f64 {
    0.03
}
fn default_view_steps() -> u32 {
    48
}
fn default_light_steps() -> u32 {
    8
}
fn default_octaves_volume() -> u32 {
    8
}
fn half() -> f64 {
    0.5
}

/// `[camera]`: a pinhole camera in the world frame.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    /// Position, metres: x east, y up (above the surface), z south.
    pub position: [f64; 3],
    /// A point to look at (metres, world frame); exactly one of this and `look_direction`.
    pub look_at: Option<[f64; 3]>,
    /// A direction to look along (world frame, any length > 0).
    pub look_direction: Option<[f64; 3]>,
    /// Vertical field of view, degrees.
    #[serde(default = "default_fov_deg")]
    pub vertical_fov_deg: f64,
    /// Terrain nearer than this (metres along the ray) is not drawn.
    #[serde(default = "default_near")]
    pub near: f64,
    /// Terrain farther than this (metres along the ray) is not drawn: the sky shows.
    #[serde(default = "default_far")]
    pub far: f64,
    /// The camera's travel from where the scene starts it (m, world frame): an
    /// animation's `camera_m_per_frame` sums. The cloud layers' texture offset is the
    /// travel from the start (SimGear's SGSky: "the viewer's travel plus wind drift"),
    /// so a layer keeps its place on the ground while the camera moves. Not a key.
    #[serde(skip)]
    pub travel_m: [f64; 3],
}

fn default_fov_deg() -> f64 {
    60.0
}
fn default_near() -> f64 {
    0.5
}
fn default_far() -> f64 {
    200_000.0
}

/// `[sun]`: an explicit direction.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SunSection {
    /// Elevation above the horizon, degrees (−90 to 90).
    pub elevation_deg: f64,
    /// Azimuth clockwise from north (east 90, south 180, west 270), degrees.
    pub azimuth_deg: f64,
}

/// `[time]`: when and where, for `celestial`'s ephemeris. The viewer's altitude is the
/// camera's height.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSection {
    /// The instant, ISO 8601 UTC (`2024-08-20T02:30:00Z`).
    pub utc: String,
    /// Geodetic latitude, degrees north (−90 to 90).
    pub latitude_deg: f64,
    /// Longitude, degrees east.
    pub longitude_deg: f64,
    /// Seconds added to `utc` (an animation's frames move it; 0 in a file).
    #[serde(default)]
    pub offset_s: f64,
}

/// `[sky_objects]`: what `celestial` draws over the sky.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkyObjectsSection {
    /// Draw the sun's limb-darkened disc, the moon, planets and stars (default true).
    #[serde(default = "default_true")]
    pub enabled: bool,
    /// The faintest star drawn, visual magnitude (default: the eye's limit against the
    /// sky behind each star).
    pub star_limit_magnitude: Option<f64>,
}

fn default_true() -> bool {
    true
}

/// Which rung of the `atmos` ladder renders the atmosphere (names as `skyscape --rung`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Rung {
    /// SimGear's SGSky dome: 12-sided, painted from the closed form with SGSky's weights
    /// (13 queries per frame), the sun's aureole per pixel; terrain and clouds see the
    /// closed form's air (the cheapest sky).
    Dome,
    /// Rung 1, Hoffman and Preetham's closed form, per pixel.
    ClosedForm,
    /// Rung 1 evaluated per vertex of a 16×32 dome for the sky (terrain segments per pixel).
    ClosedFormVertex,
    /// Rung 2, single scattering.
    Single,
    /// Rung 3, Hillaire-style precomputed LUTs (the default: accurate and real-time).
    #[default]
    Precomputed,
    /// Rung 4, the f64 multiple-scattering reference (slow: small images only).
    Reference,
    /// Rung 4 at 18 wavelengths through the CIE 1931 observer (slower still).
    ReferenceSpectral,
}

/// The dome of the per-vertex closed-form rung (the binary's `--rung closed-form-vertex`).
pub const DOME: atmos::dome::DomeResolution = atmos::dome::DomeResolution {
    rings: 16,
    segments: 32,
};

impl Rung {
    /// Every rung.
    pub const ALL: [Rung; 7] = [
        Self::Dome,
        Self::ClosedForm,
        Self::ClosedFormVertex,
        Self::Single,
        Self::Precomputed,
        Self::Reference,
        Self::ReferenceSpectral,
    ];

    /// The rung called `name` (as [`Rung::name`] spells it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|rung| rung.name() == name)
    }

    /// The name as written in a scene file and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dome => "dome",
            Self::ClosedForm => "closed-form",
            Self::ClosedFormVertex => "closed-form-vertex",
            Self::Single => "single",
            Self::Precomputed => "precomputed",
            Self::Reference => "reference",
            Self::ReferenceSpectral => "reference-spectral",
        }
    }

    /// The sky model's name in `skyscape explain`'s plan ("the closed form"), for a
    /// rung the GPU draws with passes of its own; `None` for a rung drawn through atmos'
    /// tables (or with no GPU passes). The dome's terrain and clouds see the closed
    /// form's air; its sky is [`Rung::gpu_sky_evaluation`]'s.
    pub fn gpu_model(self) -> Option<&'static str> {
        match self {
            Self::Dome | Self::ClosedForm | Self::ClosedFormVertex => Some("the closed form"),
            Self::Single => Some("single scattering"),
            _ => None,
        }
    }

    /// What the GPU's evaluation of the rung's sky does (a step of the frame's plan),
    /// for a rung with passes of its own.
    pub fn gpu_sky_evaluation(self) -> Option<String> {
        match self {
            Self::Dome => Some(
                "celestial's SkyDomeRenderer: SGSky's 12-sided dome painted from the closed \
                 form on the CPU (13 queries), blended per pixel with the sun's aureole \
                 (compute)"
                    .to_owned(),
            ),
            Self::ClosedForm => Some(
                "atmos' ClosedFormRenderer, Hoffman and Preetham's closed form per pixel \
                 (compute)"
                    .to_owned(),
            ),
            Self::ClosedFormVertex => Some(format!(
                "atmos' ClosedFormRenderer per vertex of a {}×{} dome, interpolated per pixel \
                 (compute, two dispatches)",
                DOME.rings, DOME.segments
            )),
            Self::Single => {
                let s = atmos::single_scattering::SingleScatteringSettings::default();
                Some(format!(
                    "atmos' SingleScatteringRenderer per pixel, {} view × {} light samples \
                     (compute)",
                    s.view_samples, s.light_samples
                ))
            }
            _ => None,
        }
    }
}

/// `[atmosphere]`: the rung and overrides of `atmos::Atmosphere::earth()`'s parameters
/// (each checked by `Atmosphere::validate`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct AtmosphereSection {
    /// The model.
    #[serde(default)]
    pub rung: Rung,
    /// Multiplies Mie scattering and extinction (haze); 1 is Earth's default.
    pub mie_scale: Option<f64>,
    /// Mie anisotropy, |g| < 1.
    pub mie_g: Option<f64>,
    /// Rayleigh scale height, metres.
    pub rayleigh_scale_height: Option<f64>,
    /// Mie scale height, metres.
    pub mie_scale_height: Option<f64>,
    /// Grey albedo of the atmosphere's ground (its bounce light in multiple scattering).
    pub ground_albedo: Option<f64>,
}

/// `[terrain]`: one heightfield source, its albedo and its horizon maps.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainSection {
    /// `[terrain.procedural]`: `terrain::generate`'s seeded fBm/ridged noise.
    pub procedural: Option<ProceduralTerrain>,
    /// `[terrain.png16]`: a 16-bit greyscale PNG.
    pub png16: Option<Png16Terrain>,
    /// `[terrain.raw_f32]`: raw little-endian `f32` metres.
    pub raw_f32: Option<RawF32Terrain>,
    /// `[terrain.albedo]`: colour by height and slope.
    #[serde(default)]
    pub albedo: AlbedoSection,
    /// `[terrain.colour]`: a colour image over the heightfield's ground, replacing the
    /// ramp's albedo (with procedural materials, the grass's).
    pub colour: Option<ColourSection>,
    /// Where the albedo comes from: `ramp` (`[terrain.albedo]`) or `procedural`.
    #[serde(default)]
    pub materials: MaterialsModel,
    /// `[terrain.procedural_materials]`: rock, grass and snow (with `materials = "procedural"`).
    pub procedural_materials: Option<ProceduralMaterialsSection>,
    /// Self-shadow maps: Hoffman and Preetham's east/west pair, or `azimuths` equally spaced ones.
    #[serde(default)]
    pub horizon: HorizonVariant,
    /// Number of azimuths when `horizon = "azimuths"` (terrain accepts 4..=64).
    pub horizon_azimuths: Option<usize>,
    /// Where the aerial perspective is evaluated: `per-pixel` or `per-vertex` (Hoffman and Preetham 2002).
    #[serde(default)]
    pub aerial_perspective: crate::aerial_vertex::AerialPerspective,
}

/// `[terrain.procedural]`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProceduralTerrain {
    /// Seed: different seeds give unrelated terrains.
    pub seed: u64,
    /// Texels per side.
    pub size: usize,
    /// Metres per texel.
    pub cell_size: f64,
    /// Peak-to-peak relief, metres.
    #[serde(default = "default_relief")]
    pub relief: f64,
    /// Wavelength of the largest features, metres (default: a quarter of the map).
    pub wavelength: Option<f64>,
    /// Octaves of noise.
    #[serde(default = "default_octaves")]
    pub octaves: u32,
    /// Ridged multifractal (sharp crests) instead of fBm.
    #[serde(default)]
    pub ridged: bool,
}

fn default_relief() -> f64 {
    1000.0
}
fn default_octaves() -> u32 {
    8
}

/// `[terrain.png16]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Png16Terrain {
    /// The PNG (relative to the scene file's folder).
    pub path: PathBuf,
    /// Metres per texel.
    pub cell_size: f64,
    /// Metres per 16-bit count.
    pub height_scale: f64,
    /// Elevation of count 0, metres.
    #[serde(default)]
    pub height_offset: f64,
}

/// `[terrain.raw_f32]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawF32Terrain {
    /// The file (relative to the scene file's folder): `width × height` LE `f32`.
    pub path: PathBuf,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Metres per texel.
    pub cell_size: f64,
    /// Multiplies every sample (vertical exaggeration).
    #[serde(default = "one")]
    pub height_scale: f64,
}

fn one() -> f64 {
    1.0
}

/// Which horizon maps shade the terrain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum HorizonVariant {
    /// Hoffman and Preetham 2002's pair: the east map while the sun is in the east, else the west.
    #[default]
    EastWest,
    /// `horizon_azimuths` maps, interpolated at the sun's azimuth.
    Azimuths,
}

/// `[terrain.albedo]`: a colour ramp by elevation, and a steep-slope colour.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AlbedoSection {
    /// Elevations of the ramp's stops, metres, increasing.
    pub heights: Vec<f64>,
    /// Linear RGB albedo at each stop, in [0, 1].
    pub colors: Vec<[f64; 3]>,
    /// Albedo where the slope is steeper than `steep_slope_deg` (rock).
    pub steep_color: [f64; 3],
    /// Slope (degrees from horizontal) above which `steep_color` takes over; the
    /// blend spans the 10° below it.
    pub steep_slope_deg: f64,
}

impl Default for AlbedoSection {
    /// Meadow in the valleys, dry grass and scree higher, snow on the tops; grey rock
    /// on slopes over 40°.
    fn default() -> Self {
        Self {
            heights: vec![0.0, 500.0, 1100.0, 1400.0],
            colors: vec![
                [0.06, 0.11, 0.035],
                [0.12, 0.13, 0.06],
                [0.20, 0.18, 0.15],
                [0.80, 0.80, 0.82],
            ],
            steep_color: [0.18, 0.16, 0.14],
            steep_slope_deg: 40.0,
        }
    }
}

/// `[output]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Pixels.
    #[serde(default = "default_width")]
    pub width: u32,
    /// Pixels.
    #[serde(default = "default_height")]
    pub height: u32,
    /// Exposure before the display transform (radiance per unit sun irradiance).
    #[serde(default = "default_exposure")]
    pub exposure: f32,
    /// `neutral` (hue-preserving, the default) or `per-channel` (1 − exp(−x)).
    #[serde(default)]
    pub display_transform: crate::tonemap::DisplayTransform,
    /// Dither seed.
    #[serde(default)]
    pub dither_seed: u32,
    /// Where the image goes (relative to the scene file's folder); `-o` overrides it.
    pub path: Option<PathBuf>,
    /// `rectilinear` (the camera), `cubemap` (a 6:1 strip: width = 6 × height),
    /// `equirectangular` or `fisheye` (environment maps, from 90° cube faces).
    #[serde(default)]
    pub projection: crate::projection::Projection,
    /// The fisheye's field across the image's height, degrees (0 to 360].
    #[serde(default = "default_fisheye_fov_deg")]
    pub fisheye_fov_deg: f64,
}

fn default_fisheye_fov_deg() -> f64 {
    180.0
}

fn default_width() -> u32 {
    960
}
fn default_height() -> u32 {
    540
}
fn default_exposure() -> f32 {
    20.0
}

impl Default for OutputSection {
    fn default() -> Self {
        Self {
            width: default_width(),
            height: default_height(),
            exposure: default_exposure(),
            display_transform: Default::default(),
            dither_seed: 0,
            path: None,
            projection: Default::default(),
            fisheye_fov_deg: default_fisheye_fov_deg(),
        }
    }
}
