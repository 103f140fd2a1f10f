//! The `[clouds.volume.billboards]` section of a scene file and its defaults.

use serde::Deserialize;

/// `[clouds.volume] draw`: how the automaton's cloud is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VolumeDraw {
    /// Ray-marched by `cloudlight` (Schneider's (GPU Pro 7) lighting), `crate::volume_clouds`.
    #[default]
    March,
    /// Dobashi et al. 2000's billboards lit by slices (this module).
    Billboards,
}

/// `[clouds.volume.billboards]`: the billboards' settings (with `draw = "billboards"`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BillboardsSection {
    /// A cell becomes a billboard when its density is strictly above this (Dobashi et al. 2000:
    /// 0.3), in [0, 1].
    #[serde(default = "default_threshold")]
    pub density_threshold: f64,
    /// The billboard's world diameter in cells whatever its density (the default size
    /// rule, `cloudlight::billboard::SizeRule::Fixed`; default
    /// `cloudlight::billboard::LATTICE_DIAMETER_CELLS`, where the splats' lattice sum is
    /// flattest). Exclusive with `size_m_per_density` and `seed_k`.
    pub splat_cells: Option<f64>,
    /// The billboard's world diameter per unit density, metres, instead.
    /// Exclusive with `splat_cells` and `seed_k`.
    pub size_m_per_density: Option<f64>,
    /// The size rule of a GPU implementation of Dobashi et al. 2000 instead:
    /// `(k·ρ/d)·ρ` pixels, `k` in pixel·metres (that implementation used 9500, tuned to
    /// its own units: small in metres).
    pub seed_k: Option<f64>,
    /// How a billboard's kernel becomes opacity: `"optical_depth"` (the cell's optical
    /// depth spread over the kernel) or `"slab"` (a slab's opacity at the centre times
    /// the kernel, Dobashi et al. 2000's).
    #[serde(default)]
    pub opacity: OpacityName,
    /// The cells of optical depth a billboard carries (`σ_t·ρ·cell·cells`; 1: the
    /// volume's own), > 0.
    #[serde(default = "default_opacity_cells")]
    pub opacity_cells: f64,
    /// The slice propagation's mode: `"physical"` (Beer–Lambert over the true spacing)
    /// or `"faithful"` (Dobashi et al. 2000's attenuation ratio per slice).
    #[serde(default)]
    pub slices: SlicesName,
    /// Faithful mode's light passed by a slice of density 1, in [0, 1].
    #[serde(default = "default_attenuation_ratio")]
    pub attenuation_ratio: f64,
}

impl Default for BillboardsSection {
    fn default() -> Self {
        Self {
            density_threshold: default_threshold(),
            splat_cells: None,
            size_m_per_density: None,
            seed_k: None,
            opacity: OpacityName::default(),
            opacity_cells: default_opacity_cells(),
            slices: SlicesName::default(),
            attenuation_ratio: default_attenuation_ratio(),
        }
    }
}

/// `[clouds.volume.billboards] slices`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SlicesName {
    /// `cloudlight::propagate::SliceMode::Physical`.
    #[default]
    Physical,
    /// `cloudlight::propagate::SliceMode::Faithful`.
    Faithful,
}

/// `[clouds.volume.billboards] opacity`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OpacityName {
    /// `cloudlight::billboard::Opacity::OpticalDepth`.
    #[default]
    OpticalDepth,
    /// `cloudlight::billboard::Opacity::Slab`.
    Slab,
}

fn default_threshold() -> f64 {
    0.3
}
fn default_opacity_cells() -> f64 {
    1.0
}
fn default_attenuation_ratio() -> f64 {
    0.9
}
