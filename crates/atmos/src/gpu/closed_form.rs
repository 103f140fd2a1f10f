//! Rung 1's frame renderer: the closed-form sky per pixel, or per vertex of a dome
//! (`shaders/atmos/render_closed_form.wgsl`).
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<(), atmos::AtmosError> {
//! use atmos::gpu::{ClosedFormRenderer, EvaluationFrequency, FrameOutput};
//! let mut sky = ClosedFormRenderer::new(device, &atmos::Atmosphere::earth(), EvaluationFrequency::PerPixel)?;
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

use crate::closed_form_sky::ClosedFormSkyParameters;
use crate::dome::DomeResolution;
use crate::frame::FrameCamera;
use crate::gpu::FrameOutput;
use crate::gpu::resources::{FramePassLayout, PreparedFrame, uniform_buffer};
use crate::{AtmosError, Atmosphere};

/// Where the closed form is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EvaluationFrequency {
    /// Once per pixel.
    PerPixel,
    /// Once per vertex of a latitude–longitude dome, interpolated per pixel.
    PerVertex(DomeResolution),
}

/// The closed-form sky as a compute pass writing a [`FrameOutput`].
#[derive(Debug)]
pub struct ClosedFormRenderer {
    device: wgpu::Device,
    frequency: EvaluationFrequency,
    layout: FramePassLayout,
    pixels: wgpu::ComputePipeline,
    vertices: Option<(wgpu::ComputePipeline, wgpu::ComputePipeline)>,
    camera: wgpu::Buffer,
    params: wgpu::Buffer,
    dome: wgpu::Buffer,
    parameters: ClosedFormSkyParameters,
    prepared: Option<PreparedFrame>,
}

/// The composed WGSL of the renderer.
pub fn closed_form_renderer_source() -> Result<String, AtmosError> {
    Ok(crate::composer().compose_module("atmos::render_closed_form")?)
}

impl ClosedFormRenderer {
    /// Compiles the pass for `atmosphere` (validated) at the given evaluation frequency.
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        frequency: EvaluationFrequency,
    ) -> Result<Self, AtmosError> {
        let parameters = ClosedFormSkyParameters::from_atmosphere(atmosphere)?;
        let (rings, segments) = match frequency {
            EvaluationFrequency::PerPixel => (2, 3),
            EvaluationFrequency::PerVertex(resolution) => {
                resolution.validate()?;
                (resolution.rings, resolution.segments)
            }
        };
        let source = closed_form_renderer_source()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("atmos render_closed_form"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        // binding 4: the dome's vertices
        let layout = FramePassLayout::new(device, "atmos closed form", 1);
        let constants = [
            ("dome_rings", f64::from(rings)),
            ("dome_segments", f64::from(segments)),
            ("dome_planet_radius", atmosphere.planet_radius),
            ("dome_top_radius", atmosphere.top_radius),
        ];
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&layout.pipeline),
                module: &module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        let pixels = pipeline("render_closed_form_pixels");
        let vertices = match frequency {
            EvaluationFrequency::PerPixel => None,
            EvaluationFrequency::PerVertex(_) => Some((
                pipeline("evaluate_dome_vertices"),
                pipeline("interpolate_dome"),
            )),
        };
        let camera = uniform_buffer(
            device,
            "atmos closed form camera",
            std::mem::size_of::<FrameCamera>() as u64,
        );
        let params = uniform_buffer(
            device,
            "atmos closed form parameters",
            std::mem::size_of::<ClosedFormSkyParameters>() as u64,
        );
        // Rows: the rings plus the horizon seam's second row (see `atmos::dome`).
        let vertex_count = (u64::from(rings) + 2) * (u64::from(segments) + 1);
        let dome = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("atmos closed form dome vertices"),
            size: 32 * vertex_count,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        Ok(Self {
            device: device.clone(),
            frequency,
            layout,
            pixels,
            vertices,
            camera,
            params,
            dome,
            parameters,
            prepared: None,
        })
    }

    /// The evaluation frequency chosen at creation.
    pub fn frequency(&self) -> EvaluationFrequency {
        self.frequency
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
            &self.params,
            output,
            &[&self.dome],
        )?;
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&self.parameters));
        self.prepared = Some(prepared);
        Ok(())
    }

    /// Records the prepared frame into `encoder` (one compute pass; per vertex, two
    /// dispatches in it: the dome's vertices, then the per-pixel interpolation).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        let PreparedFrame { camera, bind_group } = self.layout.prepared(&self.prepared)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmos closed form"),
            timestamp_writes,
        });
        pass.set_bind_group(0, bind_group, &[]);
        let groups = [camera.width.div_ceil(8), camera.height.div_ceil(8)];
        match (&self.vertices, self.frequency) {
            (Some((evaluate, interpolate)), EvaluationFrequency::PerVertex(resolution)) => {
                let vertex_count = resolution.vertex_count() as u32;
                pass.set_pipeline(evaluate);
                pass.dispatch_workgroups(vertex_count.div_ceil(64), 1, 1);
                pass.set_pipeline(interpolate);
                pass.dispatch_workgroups(groups[0], groups[1], 1);
            }
            _ => {
                pass.set_pipeline(&self.pixels);
                pass.dispatch_workgroups(groups[0], groups[1], 1);
            }
        }
        Ok(())
    }
}
