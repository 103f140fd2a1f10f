//! The `[clouds.shell]` deck's shadow map on the terrain baked on the GPU:
//! `cloudlight::gpu::ShellShadowMapPass` over the map's grid and light
//! ([`crate::shell_clouds::shell_shadow_map_plan`]: the plane, texels, steps and light
//! direction of the CPU's [`crate::shell_clouds::shell_shadow`]), its buffer copied into
//! the terrain pass's shadow values at the shell's slot (`super::cloud_shadow`). The CPU
//! renderer reads the CPU bake (cloudlight's generic march on the `CloudShell`, equal bit
//! for bit to the pass's f32 twin `cloudlight::shell_shadow::shell_shadow_map`).
//!
//! Baked when a prepared scene's map differs from the one in the buffer (the first
//! prepare; a new sun), not every frame: `prepare` fills the pass's inputs, the
//! renderer's `encode` records the dispatch and the copy (no submit of its own), timed
//! as "shell cloud shadow" when the renderer records timestamps (an empty pass on a
//! frame that reuses the map). Procedural weather and a weather grid alike (the pass uploads the
//! grid).

use cloudlight::gpu::ShellShadowMapPass;
use cloudlight::shadow_map::ShadowMapPlan;
use cloudlight::shell_shadow::ShellField;

use crate::RenderError;
use crate::scene::PreparedScene;

/// The shell's shadow-map bake and what the values buffer holds.
#[derive(Debug)]
pub(crate) struct ShellShadowGpu {
    pass: ShellShadowMapPass,
    /// The plan and the light (0 sun, 1 moon) of the map in the buffer (or recorded
    /// into it by the next `encode`).
    baked: Option<(ShadowMapPlan, usize)>,
    /// A bake `prepare` made ready and `encode` has not recorded yet: the values
    /// buffer's byte offset and the map's bytes.
    pending: Option<(u64, u64)>,
}

fn bake_error(e: impl std::fmt::Display) -> RenderError {
    RenderError::InvalidParameter {
        field: "clouds.shell",
        value: e.to_string(),
        reason: "the deck's shadow map could not be baked on the GPU",
    }
}

impl ShellShadowGpu {
    /// The bake's pipeline (built only for a scene with `[clouds.shell]` over terrain).
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        Ok(Self {
            pass: ShellShadowMapPass::new(device).map_err(bake_error)?,
            baked: None,
            pending: None,
        })
    }

    /// Prepares the bake of the deck's map toward the light that has one into `values`
    /// at element `offset`, unless the buffer already holds it: [`Self::encode`] records
    /// it (no submit here). Returns that light (its index in the scene's lights), or `None` when
    /// the scene has no deck map (then the caller uploads the CPU's values, if any).
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        values: &wgpu::Buffer,
        offset: u32,
    ) -> Result<Option<usize>, RenderError> {
        let Some(cloud) = &scene.shell_cloud else {
            return Ok(None);
        };
        let field = ShellField::<f32>::of(&cloud.shell);
        // The first light with a map (a map needs its light above 1°: at most one of
        // the sun and the moon is).
        let Some((light, map, toward)) = scene
            .lights()
            .iter()
            .zip(&cloud.lights)
            .find_map(|(light, lit)| Some((light.index, lit.shadow.as_ref()?, light.direction)))
        else {
            return Ok(None);
        };
        let plan = crate::shell_clouds::shell_shadow_map_plan(&cloud.shell, map, toward)
            .map_err(bake_error)?;
        if self.baked == Some((plan, light)) {
            return Ok(Some(light));
        }
        let bytes = plan.grid.texels() as u64 * 4;
        if u64::from(offset) * 4 + bytes > values.size() {
            return Err(bake_error(format!(
                "a {}×{} map beyond the shadow buffer",
                map.resolution[0], map.resolution[1]
            )));
        }
        self.pass
            .prepare(device, queue, &field, &plan)
            .map_err(bake_error)?;
        self.pending = Some((u64::from(offset) * 4, bytes));
        self.baked = Some((plan, light));
        Ok(Some(light))
    }

    /// Records the bake `prepare` made ready, and its copy into `values`, into
    /// `encoder`, with `timestamp_writes` on the bake's compute pass (an empty pass when
    /// the buffer already holds the map). Recorded before the terrain pass
    /// that reads `values`.
    pub(crate) fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        values: &wgpu::Buffer,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let Some((offset, bytes)) = self.pending.take() else {
            // An empty pass keeps the span this frame's (an unwritten query would
            // resolve to the last frame that baked).
            if timestamp_writes.is_some() {
                encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("shell cloud shadow (kept)"),
                    timestamp_writes,
                });
            }
            return Ok(());
        };
        self.pass
            .encode_timed(encoder, timestamp_writes)
            .map_err(bake_error)?;
        let baked = self
            .pass
            .buffer()
            .ok_or_else(|| bake_error("no map after prepare"))?;
        encoder.copy_buffer_to_buffer(baked, 0, values, offset, bytes);
        Ok(())
    }
}
