//! The air in front of a marched cloud (the volume's, the shell's) per pixel and light:
//! what groups 0 and 1 of a cloud's air pass bind ([`CloudAir`]). The precomputed rung
//! binds its tables there (`shaders/render/volume_air.wgsl`: atmos'
//! `aerial_perspective`, the twin of `atmos::lut::drop_in::aerial_perspective`); a rung
//! without tables binds a camera whose `sun` is the light's direction and the rung's
//! parameters of the light's atmosphere ([`RungCloudAir`]:
//! `shaders/render/cloud_air_rung.wgsl` composed with the rung's module
//! (`super::rung_kind`), whose `segment_air` the billboards' air pass and the terrain's
//! aerial-perspective pass of `super::rungs` call too), the twin of the CPU's
//! `air::air_in_front` without tables (the light's segment model over the segment
//! camera → the cloud's transmittance-weighted depth). Both write the
//! same buffer (group 2, `render::cloud_air_io`'s layout), which the composite reads.

use crate::RenderError;
use crate::scene::Rung;

/// What a cloud's air pass binds in groups 0 and 1 for one light.
#[derive(Debug, Clone, Copy)]
pub(crate) enum CloudAir<'a> {
    /// The precomputed rung's tables of the light.
    Tables(&'a atmos::gpu::AtmosphereLuts),
    /// A rung without tables: the rung's functions for the light.
    Rung(&'a RungCloudAir),
}

impl CloudAir<'_> {
    /// The air pass's pipeline with `air_layout` (group 2) and this light's groups.
    pub(crate) fn pipeline(
        &self,
        device: &wgpu::Device,
        label: &str,
        air_layout: &wgpu::BindGroupLayout,
    ) -> Result<wgpu::ComputePipeline, RenderError> {
        match self {
            Self::Tables(luts) => air_pipeline(
                device,
                label,
                (
                    crate::composer().compose_module("render::volume_air")?,
                    "volume_air_main",
                ),
                [&luts.layouts().uniforms, &luts.layouts().tables],
                air_layout,
                &[],
            ),
            Self::Rung(air) => air.pipeline(
                device,
                label,
                ("render::cloud_air_rung", "cloud_air_rung"),
                air_layout,
            ),
        }
    }

    /// Binds this light's groups 0 and 1 in `pass`.
    pub(crate) fn bind(&self, pass: &mut wgpu::ComputePass<'_>) {
        let [uniforms, tables] = match self {
            Self::Tables(luts) => [luts.uniform_bind_group(), luts.table_bind_group()],
            Self::Rung(air) => [&air.camera_group, &air.parameters_group],
        };
        pass.set_bind_group(0, uniforms, &[]);
        pass.set_bind_group(1, tables, &[]);
    }
}

/// A light's cloud air for a rung without tables: the scene camera with `sun` set to
/// the light's direction (group 0, written each frame by [`Self::prepare`]) and the
/// rung's parameters of the light's atmosphere (group 1: `ClosedFormSkyParameters`,
/// or `AtmosphereParameters` for single scattering).
#[derive(Debug)]
pub struct RungCloudAir {
    rung: Rung,
    camera: wgpu::Buffer,
    camera_layout: wgpu::BindGroupLayout,
    camera_group: wgpu::BindGroup,
    parameters_layout: wgpu::BindGroupLayout,
    parameters_group: wgpu::BindGroup,
}

impl RungCloudAir {
    /// The groups of `rung`'s air for a light of `atmosphere` (the closed forms and
    /// single scattering; `parameters`: the rung's uniform of that atmosphere).
    pub(crate) fn new(device: &wgpu::Device, rung: Rung, parameters: &wgpu::Buffer) -> Self {
        let layout = |label: &str| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                }],
            })
        };
        let group = |label: &str, layout: &wgpu::BindGroupLayout, buffer: &wgpu::Buffer| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: buffer.as_entire_binding(),
                }],
            })
        };
        let camera = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render cloud air camera (rung)"),
            size: std::mem::size_of::<atmos::frame::FrameCamera>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let camera_layout = layout("render cloud air camera (rung)");
        let camera_group = group("render cloud air camera (rung)", &camera_layout, &camera);
        let parameters_layout = layout("render cloud air parameters (rung)");
        let parameters_group = group(
            "render cloud air parameters (rung)",
            &parameters_layout,
            parameters,
        );
        Self {
            rung,
            camera,
            camera_layout,
            camera_group,
            parameters_layout,
            parameters_group,
        }
    }

    /// Writes the frame's camera (its `sun` the light's direction: the scene camera for
    /// the sun, `MoonlitSky::camera` for the moon).
    pub(crate) fn prepare(&self, queue: &wgpu::Queue, camera: &atmos::frame::FrameCamera) {
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
    }

    /// The pipeline of a pass of this rung's functions for one light with `air_layout`
    /// (group 2) and this light's groups 0 and 1: `entry`'s (rung-agnostic module, entry
    /// point), composed with the rung's module (`super::rung_kind::compose_rung_entry`)
    /// and its constants (`super::rung_kind::air_constants`). The clouds' air
    /// ([`CloudAir::pipeline`]) and the billboards' air (`crate::billboard_clouds`) are
    /// such passes.
    pub(crate) fn pipeline(
        &self,
        device: &wgpu::Device,
        label: &str,
        (module, entry): (&str, &str),
        air_layout: &wgpu::BindGroupLayout,
    ) -> Result<wgpu::ComputePipeline, RenderError> {
        air_pipeline(
            device,
            label,
            (
                super::rung_kind::compose_rung_entry(self.rung, module)?,
                entry,
            ),
            [&self.camera_layout, &self.parameters_layout],
            air_layout,
            &super::rung_kind::air_constants(self.rung),
        )
    }

    /// This light's bind groups 0 and 1, for a pass made by [`Self::pipeline`].
    pub(crate) fn groups(&self) -> [&wgpu::BindGroup; 2] {
        [&self.camera_group, &self.parameters_group]
    }
}

/// The compute pipeline of `module`'s (composed WGSL, entry point) with groups 0 and 1
/// `layouts` and group 2 `air_layout`, its overrides `constants`.
fn air_pipeline(
    device: &wgpu::Device,
    label: &str,
    (source, entry): (String, &str),
    layouts: [&wgpu::BindGroupLayout; 2],
    air_layout: &wgpu::BindGroupLayout,
    constants: &[(&str, f64)],
) -> Result<wgpu::ComputePipeline, RenderError> {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layouts[0]), Some(layouts[1]), Some(air_layout)],
        immediate_size: 0,
    });
    Ok(
        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&layout),
            module: &module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            cache: None,
        }),
    )
}
