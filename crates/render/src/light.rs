//! The lights of a scene's frame, as a list.
//!
//! A scene is lit by the sun and, on a moonlit night, by the moon
//! ([`crate::scene::PreparedScene::lights`], the sun first). Nothing downstream names a
//! light: each cloud kind keeps one [`CloudLight`] per scene light in the same order,
//! the terrain is drawn once per light, and a march, an air pass or a shadow map is
//! identified by its light's index in that list ([`LightIndex`]). A night is the same
//! passes run for a second entry.

use cloudlight::march::Lighting;
use glam::DVec3;

use crate::cloud_shadow::CloudShadow;

/// A light's place in [`crate::scene::PreparedScene::lights`] (0: the sun).
pub type LightIndex = usize;

/// A light as a cloud's preparation sees it: the atmosphere it lights (its
/// `sun_irradiance` and `sun_angular_radius` are this light's), the scene's rung built
/// from that atmosphere, and the direction toward it.
#[derive(Clone, Copy)]
pub struct LightSource<'a> {
    /// "sun", "moon": what `explain` and the passes' labels call it.
    pub name: &'static str,
    /// The atmosphere lit by this light.
    pub atmosphere: &'a atmos::Atmosphere,
    /// The scene's rung lit by it.
    pub sky_model: &'a (dyn atmos::SkyModel + Send + Sync),
    /// Unit world direction toward the light (x east, y up, z south).
    pub direction: DVec3,
    /// The precomputed rung's tables lit by it, when the scene uses that rung.
    pub precomputed: Option<&'a atmos::lut::PrecomputedSky>,
}

impl<'a> LightSource<'a> {
    /// The model this light's scattered queries read ([`scattered_queries`]).
    pub fn scattered(&self) -> Box<dyn atmos::SkyModel + Send + Sync + 'a> {
        scattered_queries(self.sky_model, self.precomputed)
    }
}

/// The model a handful of scattered sky queries read — a hemisphere quadrature for an
/// irradiance, celestial's dome, stars and cloud-layer light — for the rung `sky_model`
/// with its precomputed tables `precomputed` (when the rung is the precomputed one):
/// those tables marched per ray ([`atmos::lut::MarchedPrecomputedSky`]) rather than a
/// sky-view table baked for each viewpoint and sun the queries come from; any other rung
/// is itself. A frame's pixels still read the sky-view table, as the GPU does.
pub fn scattered_queries<'a>(
    sky_model: &'a (dyn atmos::SkyModel + Send + Sync),
    precomputed: Option<&'a atmos::lut::PrecomputedSky>,
) -> Box<dyn atmos::SkyModel + Send + Sync + 'a> {
    match precomputed {
        Some(sky) => Box::new(atmos::lut::MarchedPrecomputedSky::new(sky)),
        None => Box::new(sky_model),
    }
}

impl std::fmt::Debug for LightSource<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LightSource")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .finish_non_exhaustive()
    }
}

/// A cloud lit by one light: the light and the ambient sky at the cloud (the march's
/// `Lighting`, in the cloud's frame) and the cloud's shadow on the terrain toward it.
#[derive(Debug, Clone)]
pub struct CloudLight {
    /// The light and the ambient sky it scatters, at the cloud.
    pub lighting: Lighting<f32>,
    /// The cloud's shadow map toward this light (`None` with the light below 1° or no
    /// terrain or other cloud to shade: nothing is computed then).
    pub shadow: Option<CloudShadow>,
}
