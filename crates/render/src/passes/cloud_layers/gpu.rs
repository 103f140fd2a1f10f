//! The cloud layers on the GPU: one full-screen pass, farthest layer first,
//! premultiplied over the scene, hidden where the terrain's depth is nearer.

use super::CloudComposite;
use crate::RenderError;
use crate::gpu::frame::{GpuPass, GpuShared, HDR};
use crate::gpu::layout::{storage_read, uniform_entry};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// Builds the layers' pass for the scene's layers.
pub(crate) fn build(
    shared: &GpuShared,
    scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    Ok(Box::new(CloudPass::new(
        &shared.device,
        scene.cloud_layers.len(),
        &shared.depth_view,
    )?))
}

/// The cloud layers' compositing pass (`render::clouds`).
#[derive(Debug)]
struct CloudPass {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    layers: wgpu::Buffer,
    capacity: usize,
    bind_group: wgpu::BindGroup,
}

impl CloudPass {
    fn new(
        device: &wgpu::Device,
        capacity: usize,
        depth_view: &wgpu::TextureView,
    ) -> Result<Self, RenderError> {
        let source = crate::composer().compose_module("render::clouds")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render clouds"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render clouds"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT),
                storage_read(1, wgpu::ShaderStages::FRAGMENT),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render clouds uniform"),
            size: std::mem::size_of::<CloudComposite>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layers = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render cloud layers"),
            size: (capacity.max(1) * std::mem::size_of::<celestial::clouds::CloudLayerUniforms>())
                as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render clouds"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: layers.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(depth_view),
                },
            ],
        });
        // Premultiplied: the fragment's colour is the layers' own light, its alpha the
        // fraction of the scene they hide.
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent::OVER,
        };
        let pipeline = crate::gpu::cloud_composite::fullscreen_pipeline(
            device,
            "render clouds",
            &layout,
            &module,
            ["clouds_vertex", "clouds_fragment"],
            HDR,
            blend,
        );
        Ok(Self {
            pipeline,
            uniform,
            layers,
            capacity,
            bind_group,
        })
    }

    fn write(&self, queue: &wgpu::Queue, scene: &PreparedScene) -> Result<(), RenderError> {
        if scene.cloud_layers.len() > self.capacity {
            return Err(RenderError::InvalidParameter {
                field: "clouds.layers",
                value: format!("{} layers", scene.cloud_layers.len()),
                reason: "more than the renderer was built for",
            });
        }
        let uniform = CloudComposite {
            camera: scene.camera,
            viewer_radius: scene.viewer_radius as f32,
            near: scene.near.max(0.01) as f32,
            layer_count: scene.cloud_layers.len() as u32,
            radiance_scale: scene.present.exposure,
            fog: crate::in_cloud_fog::InCloudFogUniforms::new(scene.in_cloud_fog.as_ref()),
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        if !scene.cloud_layers.is_empty() {
            queue.write_buffer(&self.layers, 0, bytemuck::cast_slice(&scene.cloud_layers));
        }
        Ok(())
    }
}

impl GpuPass for CloudPass {
    fn prepare(
        &mut self,
        _shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        self.write(queue, scene)
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        crate::gpu::cloud_composite::draw_fullscreen(
            encoder,
            "render clouds",
            &shared.hdr_view,
            times.and_then(|t| t.render_writes("clouds")),
            &self.pipeline,
            &self.bind_group,
        );
        Ok(())
    }
}
