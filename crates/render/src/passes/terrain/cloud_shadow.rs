//! The marched clouds' shadow maps in the terrain pass: two slots, `[0]` the
//! `[clouds.volume]` cloud's (marched or drawn as billboards), `[1]` the `[clouds.shell]`
//! deck's, each a `crate::volume_clouds::CloudShadow` baked on the CPU at prepare (the
//! CPU renderer reads the same values), except the deck's, baked on the GPU
//! (`super::shell_shadow`, the same formula). One storage buffer holds both maps' values,
//! each from its slot's offset, and a uniform per terrain draw (the sun's, the moon's)
//! holds the two maps' parameters (WGSL `array<VolumeShadowUniform, 2>` in
//! `shaders/render/terrain.wgsl`, whose `volume_cloud_shadow` multiplies them, as
//! `render::cpu_renderer` does). A slot has room only when the scene has that cloud.

use super::uniforms::VolumeShadowUniform;
use crate::RenderError;
use crate::cloud_shadow::{CloudShadow, SHADOW_MAP_MAX_SIDE};
use crate::scene::PreparedScene;

/// The largest map's texels (a slot's room).
const SLOT_TEXELS: u32 = SHADOW_MAP_MAX_SIDE * SHADOW_MAP_MAX_SIDE;

/// Where each slot's values start in the buffer (elements), for a scene with the volume
/// cloud (`clouds[0]`) and the shell (`clouds[1]`).
pub(crate) fn offsets(clouds: [bool; 2]) -> [u32; 2] {
    [0, if clouds[0] { SLOT_TEXELS } else { 0 }]
}

/// The values buffer's elements: room for each cloud's map, one unused element when
/// there is none (a binding may not be empty).
pub(crate) fn capacity(clouds: [bool; 2]) -> usize {
    (clouds.iter().filter(|&&c| c).count() * SLOT_TEXELS as usize).max(1)
}

/// Both slots disabled: the contents of a light's draw's uniform without clouds.
pub(crate) const NONE: [VolumeShadowUniform; 2] = [VolumeShadowUniform::DISABLED; 2];

/// Writes the scene's maps into `values` (built for `clouds`) and returns each light's
/// draw's uniforms (the scene's lights' order). One light at most has a map per cloud (a
/// map needs its light above 1°, and a scene the moon lights has the sun below the
/// horizon), so that light's map takes the cloud's slot; a second map for one cloud is
/// an error naming the cloud, as is a map for a cloud the buffer has no room for. With
/// `shell_gpu` (a scene with the shell over terrain) the deck's map is baked on the GPU
/// into its slot (prepared here by [`super::shell_shadow::ShellShadowGpu::prepare`],
/// recorded by the renderer's `encode`) instead of uploaded from the CPU's bake.
pub(crate) fn write(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    values: &wgpu::Buffer,
    scene: &PreparedScene,
    clouds: [bool; 2],
    shell_gpu: Option<&mut super::shell_shadow::ShellShadowGpu>,
) -> Result<Vec<[VolumeShadowUniform; 2]>, RenderError> {
    let lights = scene.lights();
    let maps: Vec<[Option<&CloudShadow>; 2]> = lights
        .iter()
        .map(|l| [l.volume_shadow, l.shell_shadow])
        .collect();
    let offsets = offsets(clouds);
    let gpu_shell_light = match shell_gpu {
        Some(gpu) if clouds[1] => gpu.prepare(device, queue, scene, values, offsets[1])?,
        _ => None,
    };
    let mut uniforms = vec![NONE; lights.len()];
    for slot in 0..2 {
        let field = ["clouds.volume", "clouds.shell"][slot];
        let mut lit = maps
            .iter()
            .enumerate()
            .filter_map(|(light, maps)| Some((light, maps[slot]?)));
        let Some((light, map)) = lit.next() else {
            continue;
        };
        if lit.next().is_some() {
            return Err(RenderError::InvalidParameter {
                field,
                value: "shadow maps toward two lights".into(),
                reason: "the terrain pass holds one shadow map per cloud",
            });
        }
        if !clouds[slot] || map.values.len() > SLOT_TEXELS as usize {
            return Err(RenderError::InvalidParameter {
                field,
                value: format!("a {}×{} shadow map", map.resolution[0], map.resolution[1]),
                reason: "the renderer was built for a scene without this cloud",
            });
        }
        if !(slot == 1 && gpu_shell_light == Some(light)) {
            queue.write_buffer(
                values,
                u64::from(offsets[slot]) * 4,
                bytemuck::cast_slice(&map.values),
            );
        }
        uniforms[light][slot] = VolumeShadowUniform::of(map, offsets[slot]);
    }
    Ok(uniforms)
}
