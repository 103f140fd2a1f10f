//! The lights of a scene's frame.

/// Which light a cloud's march is lit by: the sun's march always, the moon's at night
/// (the clouds' `moon` lighting). The code that runs a cloud's marches names the light
/// of each (`crate::volume_clouds`' CPU composite, the GPU's per-light march hook), so a
/// march reads the other cloud's map for its own light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Light {
    /// The sun (the clouds' `lighting`).
    Sun,
    /// The moon (the clouds' `moon` lighting, at night).
    Moon,
}

impl Light {
    /// Both lights, the sun's first (the order the marches run in).
    pub const ALL: [Light; 2] = [Light::Sun, Light::Moon];

    /// "sun" or "moon".
    pub fn name(self) -> &'static str {
        match self {
            Light::Sun => "sun",
            Light::Moon => "moon",
        }
    }
}
