//! Rung 2's frame renderer: single scattering per pixel (`atmos::single_scattering`),
//! one compute pass writing a [`FrameOutput`]. The sample counts are WGSL `override`
//! constants, so the loops have fixed trip counts the compiler can see.
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<(), atmos::AtmosError> {
//! use atmos::gpu::{FrameOutput, SingleScatteringRenderer};
//! use atmos::single_scattering::SingleScatteringSettings;
//! let mut sky = SingleScatteringRenderer::new(
//!     device, &atmos::Atmosphere::earth(), SingleScatteringSettings::default())?;
//! let camera = atmos::frame::FrameCamera::look_at(
//!     glam::DVec3::new(0.0, 0.0, 6_360_002.0), glam::DVec3::X, glam::DVec3::Z,
//!     1.2, 1280, 720, glam::DVec3::new(0.5, 0.0, 0.866), None)?;
//! let output = FrameOutput::new(device, 1280, 720)?;
//! sky.prepare(queue, &camera, &output)?;
//! let mut encoder = device.create_command_encoder(&Default::default());
//! sky.encode(&mut encoder, None)?;
//! queue.submit([encoder.finish()]);
//! # Ok(()) }
//! ```

use crate::frame::FrameCamera;
use crate::gpu::FrameOutput;
use crate::gpu::resources::{FramePassLayout, PreparedFrame, uniform_buffer};
use crate::single_scattering::SingleScatteringSettings;
use crate::{AtmosError, Atmosphere, AtmosphereParameters};

/// The per-pixel kernel around `single_scattering` (bindings: camera, atmosphere,
/// radiance and transmittance outputs).
const KERNEL: &str = r"
#import atmos::frame
#import atmos::single_scattering

@group(0) @binding(0) var<uniform> camera: FrameCamera;
@group(0) @binding(1) var<uniform> atmosphere: AtmosphereParameters;
@group(0) @binding(2) var radiance_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(3) var transmittance_out: texture_storage_2d<rgba32float, write>;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

@compute @workgroup_size(8, 8)
fn render_single_scattering(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= camera.width || gid.y >= camera.height {
        return;
    }
    let view = frame_view_direction(gid.xy, camera);
    let r = length(camera.position);
    let up = camera.position / r;
    let sample = single_scattering(
        atmosphere,
        r,
        dot(view, up),
        dot(camera.sun, up),
        dot(view, camera.sun),
        camera.max_distance,
        view_samples,
        light_samples,
    );
    textureStore(radiance_out, gid.xy, vec4<f32>(sample.radiance, 1.0));
    textureStore(transmittance_out, gid.xy, vec4<f32>(sample.transmittance, 1.0));
}
";

/// The composed WGSL of the renderer.
pub fn single_scattering_renderer_source() -> Result<String, AtmosError> {
    Ok(crate::composer().compose("atmos::render_single_scattering", KERNEL)?)
}

/// The CPU twin of one pixel of the kernel (same f32 operations as the WGSL).
pub fn render_single_scattering_pixel(
    camera: &FrameCamera,
    atmosphere: &AtmosphereParameters,
    settings: SingleScatteringSettings,
    pixel: [u32; 2],
) -> crate::single_scattering::SingleScatteringSample {
    let view = crate::frame::frame_view_direction(pixel, camera);
    let p = camera.position;
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let up = p.map(|c| c / r);
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    crate::single_scattering::single_scattering(
        atmosphere,
        r,
        dot(view, up),
        dot(camera.sun, up),
        dot(view, camera.sun),
        camera.max_distance,
        settings.view_samples,
        settings.light_samples,
    )
}

/// Single scattering as a compute pass writing a [`FrameOutput`].
#[derive(Debug)]
pub struct SingleScatteringRenderer {
    device: wgpu::Device,
    settings: SingleScatteringSettings,
    layout: FramePassLayout,
    pipeline: wgpu::ComputePipeline,
    camera: wgpu::Buffer,
    atmosphere: wgpu::Buffer,
    parameters: AtmosphereParameters,
    prepared: Option<PreparedFrame>,
}

impl SingleScatteringRenderer {
    /// Compiles the pass for `atmosphere` and `settings` (both validated).
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        settings: SingleScatteringSettings,
    ) -> Result<Self, AtmosError> {
        settings.validate()?;
        let parameters = atmosphere.to_uniforms()?;
        let source = single_scattering_renderer_source()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("atmos render_single_scattering"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = FramePassLayout::new(device, "atmos single scattering", 0);
        let constants = [
            ("view_samples", f64::from(settings.view_samples)),
            ("light_samples", f64::from(settings.light_samples)),
        ];
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("render_single_scattering"),
            layout: Some(&layout.pipeline),
            module: &module,
            entry_point: Some("render_single_scattering"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            cache: None,
        });
        Ok(Self {
            device: device.clone(),
            settings,
            layout,
            pipeline,
            camera: uniform_buffer(
                device,
                "atmos single scattering camera",
                std::mem::size_of::<FrameCamera>() as u64,
            ),
            atmosphere: uniform_buffer(
                device,
                "atmos single scattering atmosphere",
                std::mem::size_of::<AtmosphereParameters>() as u64,
            ),
            parameters,
            prepared: None,
        })
    }

    /// The sample counts chosen at creation.
    pub fn settings(&self) -> SingleScatteringSettings {
        self.settings
    }

    /// Uploads the camera (and sun) of the next frame and the atmosphere, and binds
    /// `output` (checked against the camera's frame size) for [`Self::encode`].
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &FrameCamera,
        output: &FrameOutput,
    ) -> Result<(), AtmosError> {
        self.prepared = None;
        let prepared = self.layout.prepare(
            &self.device,
            camera,
            &self.camera,
            &self.atmosphere,
            output,
            &[],
        )?;
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
        queue.write_buffer(&self.atmosphere, 0, bytemuck::bytes_of(&self.parameters));
        self.prepared = Some(prepared);
        Ok(())
    }

    /// Records the prepared frame into `encoder` (one compute pass, 8×8 workgroups).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        let PreparedFrame { camera, bind_group } = self.layout.prepared(&self.prepared)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmos single scattering"),
            timestamp_writes,
        });
        pass.set_bind_group(0, bind_group, &[]);
        pass.set_pipeline(&self.pipeline);
        pass.dispatch_workgroups(camera.width.div_ceil(8), camera.height.div_ceil(8), 1);
        Ok(())
    }
}
