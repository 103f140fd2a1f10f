//! A scene's two marched clouds — the `[clouds.shell]` deck and the `[clouds.volume]`
//! cloud — composited by depth per pixel, on the CPU (`composite_clouds_by_depth`)
//! and on the GPU (`render::gpu::cloud_order`, `shaders/render/cloud_order_composite.wgsl`).
//! A scene with only one of them composites it alone, as before
//! (`render::volume_clouds::composite_marched_cloud`, the GPU's `CloudComposite`).
//!
//! # Order along the ray
//!
//! Each cloud's march gives, per pixel, its radiance `L_c`, transmittance `T_c` and the
//! opacity-weighted depth `d` of its density along the ray (`cloudlight::march`'s
//! `MarchResult::depth`, `Σ tₖ·wₖ / Σ wₖ` with `wₖ` the opacity step `k` adds); each is
//! seen through the air in front of it as alone ([`SeenCloud`]: `S = L_c·T_air(d) +
//! L_air(d)·(1 − T_c)`, the moon's march added at night, `crate::volume_clouds`). Along
//! the ray the nearer cloud goes over the farther one, and both over what is behind:
//!
//! `L = S_near + T_near · (S_far + T_far · L_behind)`
//!
//! ([`in_depth_order`], WGSL twin `clouds_in_depth_order` in
//! `shaders/render/cloud_order.wgsl`), "nearer" being the smaller `d`. Where the two
//! clouds' segments along the ray are disjoint (a volume cloud above or below the deck,
//! beside it) this is the exact order: each `d` lies inside its own cloud's segment. The
//! air is exact too: `L_air(d_far) = L_air(d_near) + T_air(d_near)·L_air(d_near → d_far)`,
//! so the farther cloud's air, scaled by `T_near`, is the air behind the nearer cloud.
//!
//! **The approximation**, where the segments overlap along the ray (a volume cloud
//! reaching into the deck's altitudes, the ray crossing both in the same stretch): each
//! march is still its own cloud's alone, and the whole of the cloud with the smaller
//! opacity-weighted depth is put in front of the whole of the other. The true pixel then
//! lies between the two orders; the error is at most their difference,
//! `|S_a·(1 − T_b) − S_b·(1 − T_a)|`, and vanishes where either cloud is transparent
//! (and where both have the same source function `J`: then `S = J·(1 − T)` for each and
//! the two orders agree).
//! Each march is also limited only by the terrain, not by the other cloud: a cloud
//! behind an opaque one is marched in full and hidden by `T_near`, exact up to the
//! march's early exit.
//!
//! **Each cloud's shadow on the other** (`crate::mutual_shadow`): each march's light
//! crosses the other cloud through that cloud's shadow map for the same light, its
//! optical depth above the sample added to the light march's (exact below the other
//! cloud's base, an empirical fade inside its altitudes, nothing above it); the ambient
//! sky is each cloud's own. On the GPU the same maps and formula in cloudlight's march
//! passes.
//!
//! **Measured** (`cargo test -p render --test cloud_overlap -- --nocapture`, in the
//! debug test build): the deck (1,000–1,800 m) and a cumulus (a 2.4 ×
//! 2.4 × 0.6 km grid, its base at 1,400 m, reaching into the deck, or at 2,000 m), four
//! 64×36 views from below and above the deck, in f64 with one light and the same march
//! settings for both clouds, against one march over their union
//! (`cloudlight::union::UnionField`, interleaved, its light and ambient marches through
//! both), over the pixels crossing both (each ≥ 1 % opaque alone), the clouds' radiance
//! over black, LSB after the tone map at exposure 12. This composite, each cloud lit
//! through the other's map: 150 pixels whose segments overlap, mean 3.6 LSB, max 16.3
//! (relative mean 6.0 %); 529 disjoint, mean 0.51 LSB, max 20.5. Without the maps (each
//! lit through itself only, before `crate::mutual_shadow`): mean 5.2, max 29.5
//! overlapping; mean 3.0, max 97.0 disjoint (a deck pixel in the cumulus's shadow drawn
//! lit: 258 % too bright). What remains is the maps' fade inside the other cloud's
//! altitudes (the cumulus reaching into the deck: its view from above the deck holds the
//! disjoint maximum): each cloud's view march alone but lit through both, in depth
//! order, is within 0.02 LSB mean, 0.4 max of the union on the overlapping pixels (the
//! ordering alone; the march's own floor, on the disjoint pixels where the order is
//! exact, reaches 1.2 LSB), inside the bound above on 150 of 150 (mean 49 LSB, max 136:
//! loose, the two clouds' source functions being close where they overlap) and between
//! the two orders on 150 of 150 (within that floor).

use cloudlight::march::{Lighting, MarchResult};

use crate::cpu_frame::{LightFrame, PixelRadiance};
use crate::light::LightIndex;
use crate::marched_cloud::{MarchedCloud, draw_seen_clouds, lit_by};
pub use crate::marched_cloud::{SeenCloud, in_depth_order};
use crate::scene::PreparedScene;
use crate::shell_clouds::PreparedShell;
use crate::volume_clouds::PreparedVolume;

/// The CPU twin of the GPU's composite of both marched clouds by depth
/// (`shaders/render/cloud_order_composite.wgsl`): per pixel the volume's and the deck's
/// f32 marches up to the terrain's hit (`PixelRadiance::terrain_distance`; the sky: no
/// limit), each seen as alone (`crate::volume_clouds::composite_marched_cloud`'s pixel:
/// drawn where it has opacity in front of the scene, through the air of each of the
/// frame's `lights`, their marches added), then [`in_depth_order`] over what is behind.
pub(crate) fn composite_clouds_by_depth(
    scene: &PreparedScene,
    shell: &PreparedShell,
    volume: &PreparedVolume,
    lights: &[LightFrame<'_>],
    out: &mut [PixelRadiance],
) -> Result<(), crate::RenderError> {
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let volume_camera =
        crate::volume_clouds::pinhole_camera(camera, scene.atmosphere.planet_radius)?;
    let shell_camera = crate::shell_clouds::shell_camera(camera)?;
    // Each lit through the other's shadow map for the same light (crate::mutual_shadow):
    // `MarchedCloud::seen` names the light of each march.
    let march_volume = |light: LightIndex,
                        lighting: &Lighting<f32>,
                        xy: [u32; 2],
                        behind: f32|
     -> MarchResult<f32> {
        let deck = crate::mutual_shadow::deck_on_volume(shell, light);
        crate::mutual_shadow::march_volume_pixel(
            volume,
            lighting,
            &volume_camera,
            size,
            xy,
            behind,
            deck,
        )
    };
    let march_shell = |light: LightIndex,
                       lighting: &Lighting<f32>,
                       xy: [u32; 2],
                       behind: f32|
     -> MarchResult<f32> {
        let cumulus = crate::mutual_shadow::volume_on_deck(volume, light);
        crate::mutual_shadow::march_deck_pixel(
            shell,
            lighting,
            &shell_camera,
            size,
            xy,
            behind,
            cumulus,
        )
    };
    let (volume_lights, shell_lights) = (
        lit_by(&volume.lights, lights),
        lit_by(&shell.lights, lights),
    );
    let clouds = (
        MarchedCloud {
            lights: &volume_lights,
            march: &march_volume,
        },
        MarchedCloud {
            lights: &shell_lights,
            march: &march_shell,
        },
    );
    draw_seen_clouds(camera.width, out, |xy, behind| {
        let volume = clouds.0.seen(scene, xy, behind)?;
        let shell = clouds.1.seen(scene, xy, behind)?;
        if volume.is_none() && shell.is_none() {
            return Ok(None);
        }
        Ok(Some(in_depth_order(
            volume.unwrap_or(SeenCloud::NONE),
            shell.unwrap_or(SeenCloud::NONE),
        )))
    })
}
