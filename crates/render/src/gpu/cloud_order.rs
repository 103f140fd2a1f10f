//! The shell and the volume cloud of one scene composited by depth per pixel on the GPU
//! (`crate::cloud_order` explains the order and its approximation): one full-screen
//! pass (`shaders/render/cloud_order_composite.wgsl`) reading both clouds' marches and
//! air, in place of their two composites. Built only for a scene with both; each
//! cloud's marches and air passes stay its `CloudComposite`'s
//! (`CloudComposite::encode_marches`).

use super::cloud_composite::{CloudComposite, CloudMarch, draw_fullscreen, fullscreen_pipeline};
use crate::gpu::layout::{buffer_entry, depth_entry};

/// The composite's uniform (layout identical to WGSL `CloudOrderComposite` in
/// `shaders/render/cloud_order_composite.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CloudOrderComposite {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Multiplies the clouds' own light (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
    /// The march images' width (pixels).
    pub width: u32,
    /// 1: the volume's moonlit march is added (night), 0: the sun's only.
    pub volume_moonlit: u32,
    /// 1: the shell's moonlit march is added (night), 0: the sun's only.
    pub shell_moonlit: u32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding: [u32; 3],
}

/// The storage buffers the composite's fragment stage reads: each cloud's march and
/// air, sun and moon.
const STORAGE_BUFFERS: u32 = 8;

/// The composite of both marched clouds by depth (module docs).
#[derive(Debug)]
pub(crate) struct CloudOrderPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    /// After `prepare`.
    bind_group: Option<wgpu::BindGroup>,
}

impl CloudOrderPass {
    /// The composite's pipeline into a `target` colour target (blended `src + dst ·
    /// src_alpha`, as each cloud's own composite). The device must allow
    /// [`STORAGE_BUFFERS`] storage buffers per shader stage (wgpu's default limits do).
    pub(crate) fn new(
        device: &wgpu::Device,
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        use wgpu::BufferBindingType::{Storage, Uniform};
        let limit = device.limits().max_storage_buffers_per_shader_stage;
        if limit < STORAGE_BUFFERS {
            return Err(crate::RenderError::InvalidParameter {
                field: "clouds",
                value: format!("a device with {limit} storage buffers per shader stage"),
                reason: "the shell and volume clouds' composite by depth reads 8",
            });
        }
        let label = "render clouds by depth";
        let source = crate::composer().compose_module("render::cloud_order_composite")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let read = Storage { read_only: true };
        let mut entries = vec![buffer_entry(0, fragment, Uniform), depth_entry(1, fragment)];
        entries
            .extend((2..2 + STORAGE_BUFFERS).map(|binding| buffer_entry(binding, fragment, read)));
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &entries,
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render clouds by depth uniform"),
            size: std::mem::size_of::<CloudOrderComposite>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let blend = super::cloud_composite::over_transmittance_blend();
        let pipeline = fullscreen_pipeline(
            device,
            label,
            &layout,
            &module,
            ["cloud_order_vertex", "cloud_order_fragment"],
            target,
            blend,
        );
        Ok(Self {
            pipeline,
            layout,
            uniform,
            bind_group: None,
        })
    }

    /// The frame's uniform and bind group over the terrain's `depth_view` and the
    /// buffers of `volume` and `shell`, both prepared this frame.
    pub(crate) fn prepare<V: CloudMarch, S: CloudMarch>(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        volume: &CloudComposite<V>,
        shell: &CloudComposite<S>,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), crate::RenderError> {
        let camera = &scene.camera;
        queue.write_buffer(
            &self.uniform,
            0,
            bytemuck::bytes_of(&CloudOrderComposite {
                camera: *camera,
                near: scene.near.max(0.01) as f32,
                radiance_scale: scene.present.exposure,
                width: camera.width,
                volume_moonlit: u32::from(volume.light_count() > 1),
                shell_moonlit: u32::from(shell.light_count() > 1),
                padding: [0; 3],
            }),
        );
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: self.uniform.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(depth_view),
            },
        ];
        let buffers = volume
            .seen_buffers()?
            .into_iter()
            .chain(shell.seen_buffers()?);
        entries.extend(
            (2..)
                .zip(buffers)
                .map(|(binding, buffer)| wgpu::BindGroupEntry {
                    binding,
                    resource: buffer.as_entire_binding(),
                }),
        );
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render clouds by depth"),
            layout: &self.layout,
            entries: &entries,
        }));
        Ok(())
    }

    /// Records the composite over `target` (after both clouds' `encode_marches`).
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), crate::RenderError> {
        let bind_group = self
            .bind_group
            .as_ref()
            .ok_or(crate::RenderError::NotPrepared)?;
        draw_fullscreen(
            encoder,
            "render clouds by depth",
            target,
            timestamp_writes,
            &self.pipeline,
            bind_group,
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    /// The uniform's twin has the size and field offsets of its WGSL struct.
    #[test]
    fn the_uniform_matches_its_wgsl_layout() {
        use super::CloudOrderComposite;
        let module = "render::cloud_order_composite";
        let source = crate::composer().compose_module(module).unwrap();
        let parsed = skyscape_wgsl::validate(module, &source).unwrap();
        let wgsl = skyscape_wgsl::struct_layout(&parsed, "CloudOrderComposite").unwrap();
        let rust = skyscape_wgsl::rust_layout!(CloudOrderComposite {
            camera,
            near,
            radiance_scale,
            width,
            volume_moonlit,
            shell_moonlit,
            padding,
        });
        rust.check_twin_of(&wgsl).unwrap();
    }
}
