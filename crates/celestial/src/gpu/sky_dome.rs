//! SGSky's dome on the GPU, bring-your-own-device: [`SkyDomeRenderer`] writes each
//! pixel's sky from a painted dome ([`crate::dome_sky::SkyDomeUniforms`]) into an
//! atmos [`FrameOutput`], as atmos' own frame renderers do, so a caller composes it
//! like any rung's sky. Painting stays on the CPU (SGSky's `repaint`: a few model
//! queries); the pass only draws. Twin: [`crate::dome_sky::SgskyDomeSky`].
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue) -> celestial::Result<()> {
//! use atmos::closed_form_sky::ClosedFormSky;
//! use atmos::gpu::FrameOutput;
//! use celestial::dome::DomeColouring;
//! use celestial::dome_sky::SgskyDomeSky;
//! use celestial::gpu::SkyDomeRenderer;
//! use glam::DVec3;
//! let atmosphere = atmos::Atmosphere::earth();
//! let model = ClosedFormSky::new(&atmosphere).expect("Earth's air");
//! let sky = SgskyDomeSky::new(model, &atmosphere, DomeColouring::SeedWeights)?;
//! let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + 2.0);
//! let sun = DVec3::new(0.5, 0.0, 0.866);
//! let camera = atmos::frame::FrameCamera::look_at(
//!     position, DVec3::X, DVec3::Z, 1.2, 1280, 720, sun, None).expect("a camera");
//! let output = FrameOutput::new(device, 1280, 720).expect("textures");
//! let mut pass = SkyDomeRenderer::new(device)?;
//! pass.prepare(queue, &camera, &sky.uniforms(position, sun)?, &output)?;
//! let mut encoder = device.create_command_encoder(&Default::default());
//! pass.encode(&mut encoder, None)?;
//! queue.submit([encoder.finish()]);
//! # Ok(()) }
//! ```

use atmos::frame::FrameCamera;
use atmos::gpu::FrameOutput;
use atmos::gpu::resources::{storage_texture_entry, uniform_buffer, uniform_entry};

use super::GpuError;
use crate::dome_sky::SkyDomeUniforms;
use crate::error::{CelestialError, Result};

/// The composed WGSL of the pass (`shaders/celestial/sky_dome_pass.wgsl`).
pub fn sky_dome_shader_source() -> Result<String> {
    Ok(crate::composer().compose_module("celestial::sky_dome_pass")?)
}

/// SGSky's dome as a compute pass writing a [`FrameOutput`].
#[derive(Debug)]
pub struct SkyDomeRenderer {
    device: wgpu::Device,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    camera: wgpu::Buffer,
    dome: wgpu::Buffer,
    prepared: Option<(FrameCamera, wgpu::BindGroup)>,
}

impl SkyDomeRenderer {
    /// Compiles the pass.
    pub fn new(device: &wgpu::Device) -> Result<Self> {
        let source = sky_dome_shader_source()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("celestial sky dome"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("celestial sky dome"),
            entries: &[
                uniform_entry(0),
                uniform_entry(1),
                storage_texture_entry(2, wgpu::TextureViewDimension::D2),
                storage_texture_entry(3, wgpu::TextureViewDimension::D2),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("celestial sky dome"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("render_sky_dome"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("render_sky_dome"),
            compilation_options: Default::default(),
            cache: None,
        });
        let camera = uniform_buffer(
            device,
            "celestial sky dome camera",
            std::mem::size_of::<FrameCamera>() as u64,
        );
        let dome = uniform_buffer(
            device,
            "celestial sky dome",
            std::mem::size_of::<SkyDomeUniforms>() as u64,
        );
        Ok(Self {
            device: device.clone(),
            layout,
            pipeline,
            camera,
            dome,
            prepared: None,
        })
    }

    /// Uploads the camera and the painted dome of the next frame and binds `output`
    /// (checked against the camera's frame size) for [`Self::encode`]. `dome` must be
    /// painted for the camera's position and sun
    /// ([`crate::dome_sky::SgskyDomeSky::uniforms`]).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &FrameCamera,
        dome: &SkyDomeUniforms,
        output: &FrameOutput,
    ) -> Result<()> {
        self.prepared = None;
        output
            .check_camera(camera)
            .map_err(|source| CelestialError::Atmos {
                field: "camera (against the frame output)",
                source,
            })?;
        for (k, value) in bytemuck::cast_slice::<SkyDomeUniforms, f32>(std::slice::from_ref(dome))
            .iter()
            .enumerate()
        {
            if !value.is_finite() {
                return Err(CelestialError::NotFinite {
                    field: sky_dome_field(k),
                    value: f64::from(*value),
                });
            }
        }
        let [radiance, transmittance] = output.bind_group_entries(2);
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("celestial sky dome"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.camera.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.dome.as_entire_binding(),
                },
                radiance,
                transmittance,
            ],
        });
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
        queue.write_buffer(&self.dome, 0, bytemuck::bytes_of(dome));
        self.prepared = Some((*camera, bind_group));
        Ok(())
    }

    /// Records the prepared frame into `encoder` (one compute pass, one dispatch).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<()> {
        let (camera, bind_group) = self.prepared.as_ref().ok_or(GpuError::NotPrepared {
            pass: "SkyDomeRenderer",
        })?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("celestial sky dome"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(camera.width.div_ceil(8), camera.height.div_ceil(8), 1);
        Ok(())
    }
}

/// The uniform field holding the `k`-th f32 of [`SkyDomeUniforms`].
fn sky_dome_field(k: usize) -> &'static str {
    match k {
        0..196 => "dome.colours",
        196..199 => "dome.sun_irradiance",
        199 => "dome.spin",
        200..203 => "dome.sun_transmittance",
        203 => "dome.mie_g",
        _ => "dome.mie_optical_depth",
    }
}
