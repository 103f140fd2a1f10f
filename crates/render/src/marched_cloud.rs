//! A marched cloud composited over the scene on the CPU (the volume's, the shell's): the
//! cloud seen at a pixel through the air in front of it, and two clouds in depth order.

use cloudlight::march::{Lighting, MarchResult};

use crate::cpu_frame::{LightFrame, PixelRadiance};
use crate::light::LightIndex;

/// Whether a march result is drawn over a scene whose opaque surface is
/// `scene_distance` metres along the ray (infinite for the sky): the cloud has opacity
/// and its depth is nearer. Twin of the test in `volume_clouds.wgsl`.
pub fn cloud_in_front(cloud: &MarchResult<f32>, scene_distance: f32) -> bool {
    cloud.transmittance < 1.0 && cloud.depth < scene_distance
}

/// The cloud seen through the air: `L_c · T_air + L_air · (1 − T_c)` (module docs); the
/// caller adds `T_c · L_behind`. WGSL twin of the same name in
/// `shaders/render/volume_composite.wgsl`.
pub fn cloud_through_air(
    cloud: &MarchResult<f32>,
    air_transmittance: [f32; 3],
    air_radiance: [f32; 3],
) -> [f32; 3] {
    std::array::from_fn(|k| {
        cloud.radiance[k] * air_transmittance[k] + air_radiance[k] * (1.0 - cloud.transmittance)
    })
}

/// The CPU twin of the GPU's composite of a marched cloud (the volume's, the shell's):
/// per pixel `march(lighting, pixel, behind)` up to the terrain's hit
/// (`PixelRadiance::terrain_distance`; the sky: no limit), drawn where it has opacity in
/// front of the scene ([`cloud_in_front`]) as `L_c·T_air + L_air·(1 − T_c) + T_c·L`
/// ([`cloud_through_air`], the air from [`crate::air::air_in_front`] with the light's
/// tables), once per light of `lights` (the cloud's lighting for each of the frame's
/// lights, in the scene's order), added.
pub(crate) fn composite_marched_cloud(
    scene: &crate::scene::PreparedScene,
    lights: &[(&Lighting<f32>, &LightFrame<'_>)],
    march: impl Fn(&Lighting<f32>, [u32; 2], f32) -> MarchResult<f32> + Sync,
    out: &mut [crate::cpu_frame::PixelRadiance],
) -> Result<(), crate::RenderError> {
    // One cloud alone: its march is the same function for every light.
    let march = |_: LightIndex, lighting: &Lighting<f32>, xy, behind| march(lighting, xy, behind);
    let cloud = MarchedCloud {
        lights,
        march: &march,
    };
    draw_seen_clouds(scene.camera.width, out, |xy, behind| {
        cloud.seen(scene, xy, behind)
    })
}

/// The frame's lights a cloud is lit by, each with the cloud's lighting for it: the
/// cloud's `CloudLight`s zipped with the frame's lights (the same order, the sun first).
pub(crate) fn lit_by<'a>(
    cloud: &'a [crate::light::CloudLight],
    frame: &'a [LightFrame<'a>],
) -> Vec<(&'a Lighting<f32>, &'a LightFrame<'a>)> {
    cloud.iter().map(|l| &l.lighting).zip(frame).collect()
}

/// A marched cloud as the CPU composites it (the volume's, the shell's): its lighting for
/// each light of the frame with that light and its tables (the scene's order, the sun
/// first), and its march per pixel (`march(light, lighting, pixel, behind)`, up to
/// `behind` metres: `light` is the index of the light `lighting` is for, so a march can
/// pick what else depends on it, the other cloud's shadow map for that light,
/// `crate::mutual_shadow`).
pub(crate) struct MarchedCloud<'a, M> {
    pub(crate) lights: &'a [(&'a Lighting<f32>, &'a LightFrame<'a>)],
    pub(crate) march: &'a M,
}

impl<M> MarchedCloud<'_, M>
where
    M: Fn(LightIndex, &Lighting<f32>, [u32; 2], f32) -> MarchResult<f32>,
{
    /// The cloud at pixel `xy` in front of a scene `behind` metres away: `None` where it
    /// has no opacity in front under the first light ([`cloud_in_front`]; the
    /// transmittance and depth do not depend on the light), else its light seen through
    /// the air ([`cloud_through_air`] with each light's air from
    /// [`crate::air::air_in_front`], summed over the lights), its transmittance and
    /// depth; the caller adds `T_c · L_behind`.
    pub(crate) fn seen(
        &self,
        scene: &crate::scene::PreparedScene,
        xy: [u32; 2],
        behind: f32,
    ) -> Result<Option<SeenCloud>, crate::RenderError> {
        let march = self.march;
        let Some(((lighting, light), others)) = self.lights.split_first() else {
            return Ok(None);
        };
        let result = march(0, lighting, xy, behind);
        if !cloud_in_front(&result, behind) {
            return Ok(None);
        }
        let view = atmos::frame::frame_view_direction(xy, &scene.camera);
        let (transmittance, radiance) =
            crate::air::air_in_front(scene, &light.illuminant, light.air(), view, result.depth)?;
        let mut seen = cloud_through_air(&result, transmittance, radiance);
        for (index, (lighting, light)) in others.iter().enumerate() {
            let lit = march(index + 1, lighting, xy, behind);
            let (transmittance, radiance) =
                crate::air::air_in_front(scene, &light.illuminant, light.air(), view, lit.depth)?;
            let added = cloud_through_air(&lit, transmittance, radiance);
            for (value, a) in seen.iter_mut().zip(added) {
                *value += a;
            }
        }
        Ok(Some(SeenCloud {
            radiance: seen,
            transmittance: result.transmittance,
            depth: result.depth,
        }))
    }
}

/// One marched cloud seen at a pixel as if alone: the radiance it adds in front of what
/// is behind it (its light through the air in front of it and the air's in-scatter it
/// hides, `L_c·T_air + L_air·(1 − T_c)`, summed over its lights), its transmittance
/// `T_c` and its opacity-weighted depth (m). Behind it, `T_c · L_behind` is added.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeenCloud {
    /// What the cloud adds in front of what is behind it.
    pub radiance: [f32; 3],
    /// The light from behind that arrives through it, in [0, 1].
    pub transmittance: f32,
    /// The opacity-weighted depth of its density along the ray (m).
    pub depth: f32,
}

impl SeenCloud {
    /// No cloud at the pixel: adds nothing and lets everything through.
    pub const NONE: Self = Self {
        radiance: [0.0; 3],
        transmittance: 1.0,
        depth: 0.0,
    };
}

/// Two clouds at one pixel in depth order (module docs): the one with the smaller
/// opacity-weighted depth over the other (`a` over `b` when the depths tie), as one
/// cloud `S_near + T_near·S_far` with transmittance `T_near·T_far` and the nearer one's
/// depth. With either [`SeenCloud::NONE`] it is the other exactly. WGSL twin
/// `clouds_in_depth_order` in `shaders/render/cloud_order.wgsl`.
pub fn in_depth_order(a: SeenCloud, b: SeenCloud) -> SeenCloud {
    let (near, far) = if b.depth < a.depth { (b, a) } else { (a, b) };
    SeenCloud {
        radiance: std::array::from_fn(|k| near.radiance[k] + near.transmittance * far.radiance[k]),
        transmittance: near.transmittance * far.transmittance,
        depth: near.depth,
    }
}

/// Draws clouds over an image of `width`-pixel rows (rows in parallel): per pixel,
/// `seen(xy, behind)` (`behind`: the terrain's hit, `PixelRadiance::terrain_distance`;
/// the sky: infinity) over what the pixel holds, `L = S + T_c · L`; a pixel where it is
/// `None` is kept. The loop of both CPU cloud composites, the one cloud's
/// (`crate::volume_clouds::composite_marched_cloud`) and the two by depth
/// (`composite_clouds_by_depth`); the first error stops it.
pub(crate) fn draw_seen_clouds(
    width: u32,
    out: &mut [PixelRadiance],
    seen: impl Fn([u32; 2], f32) -> Result<Option<SeenCloud>, crate::RenderError> + Sync,
) -> Result<(), crate::RenderError> {
    use rayon::prelude::*;
    out.par_chunks_mut(width as usize)
        .enumerate()
        .try_for_each(|(row, pixels)| {
            for (column, pixel) in pixels.iter_mut().enumerate() {
                let xy = [column as u32, row as u32];
                let behind = pixel.terrain_distance.unwrap_or(f32::INFINITY);
                let Some(seen) = seen(xy, behind)? else {
                    continue;
                };
                for (value, s) in pixel.radiance.iter_mut().zip(seen.radiance) {
                    *value = s + seen.transmittance * *value;
                }
            }
            Ok(())
        })
}
