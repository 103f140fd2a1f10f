//! [`TemporalMarch`]: a view march amortised over frames (after Schneider's Nubis
//! talks): each frame marches one pixel of every 2×2 block in turn and reprojects the
//! others from the last frame's image (`shaders/cloudlight/march_reproject_pass.wgsl`,
//! its functions in `march_temporal.wgsl`; CPU twins in
//! [`crate::march::temporal`]). A still camera's image is the full march's after four
//! frames; a moving one's lags by up to three frames where the reprojection guessed.
//!
//! Per frame, around a [`FieldMarchPass`]: [`TemporalMarch::phase`] →
//! [`FieldMarchPass::set_phase`] → the march's `prepare` → [`TemporalMarch::prepare`]
//! (binds this frame's image and parameters to the history) → [`TemporalMarch::encode`]
//! (the reprojection, the march, and the copy of the image into the history).

use super::pass::{FieldMarchPass, MarchedField};
use super::*;
use crate::CloudVolume;
use crate::gpu::density_source::compose_over;

/// The distance (m) at which a pixel that showed no cloud last frame is reprojected:
/// far enough that only the view's turn moves it.
pub const SKY_DISTANCE_M: f32 = 1.0e6;

/// The reprojection pass, the history and the last frame's camera (module docs).
#[derive(Debug)]
pub struct TemporalMarch {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    /// The last frame's image and its size.
    history: Option<(wgpu::Buffer, [u32; 2])>,
    /// The last frame's camera: `MarchParams`' first four rows.
    last_camera: Option<[u32; 16]>,
    /// The camera rows' uniform (the last frame's camera, the sky distance).
    before: wgpu::Buffer,
    /// This frame's reprojection (after `prepare`, when there is a history).
    bind_group: Option<(wgpu::BindGroup, [u32; 2])>,
    frame: u32,
}

impl TemporalMarch {
    /// Builds the reprojection pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, MarchGpuError> {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cloudlight march reproject"),
            source: wgpu::ShaderSource::Wgsl(
                compose_over::<CloudVolume>("cloudlight::march_reproject_pass")?.into(),
            ),
        });
        let buffer = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        use wgpu::BufferBindingType::{Storage, Uniform};
        let entries = [
            buffer(0, Uniform),
            buffer(1, Uniform),
            buffer(2, Storage { read_only: true }),
            buffer(3, Storage { read_only: false }),
        ];
        let (pipeline, layout) = crate::gpu::one_group_pipeline(
            device,
            "cloudlight march reproject",
            &entries,
            &module,
            "reproject_main",
        );
        let before = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march reproject camera"),
            size: 80,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Self {
            pipeline,
            layout,
            history: None,
            last_camera: None,
            before,
            bind_group: None,
            frame: 0,
        })
    }

    /// The phase for this frame's march of a `size` image: `None` (march every pixel)
    /// when there is no history of that size yet, else the frame's turn (0..3).
    pub fn phase(&self, size: [u32; 2]) -> Option<u32> {
        match &self.history {
            Some((_, history_size)) if *history_size == size && self.last_camera.is_some() => {
                Some(self.frame % 4)
            }
            _ => None,
        }
    }

    /// Forgets the history: the next frame marches every pixel (a scene whose light or
    /// clouds changed, so that the last image is not this one's).
    pub fn reset(&mut self) {
        self.last_camera = None;
    }

    /// After `march`'s `prepare` for this frame: binds its parameters and image to the
    /// history and writes the last frame's camera (a march prepared without a phase
    /// reprojects nothing).
    pub fn prepare<F: MarchedField>(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        march: &FieldMarchPass<F>,
    ) -> Result<(), MarchGpuError> {
        let (params, words, size) = march
            .prepared_params()
            .ok_or(MarchGpuError::EncodeBeforePrepare)?;
        let image = march
            .image_buffer()
            .ok_or(MarchGpuError::EncodeBeforePrepare)?;
        if self.history.as_ref().is_none_or(|(_, s)| *s != size) {
            self.history = Some((
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("cloudlight march history"),
                    size: image.size(),
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                size,
            ));
            self.last_camera = None;
        }
        let interleaved = words[50] == 1;
        self.bind_group = match (&self.history, self.last_camera, interleaved) {
            (Some((history, _)), Some(camera), true) => {
                let mut rows = [0u32; 20];
                rows[..16].copy_from_slice(&camera);
                rows[19] = SKY_DISTANCE_M.to_bits();
                queue.write_buffer(&self.before, 0, bytemuck::cast_slice(&rows));
                let entries = [(0, params), (1, &self.before), (2, history), (3, image)].map(
                    |(binding, buffer)| wgpu::BindGroupEntry {
                        binding,
                        resource: buffer.as_entire_binding(),
                    },
                );
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("cloudlight march reproject"),
                    layout: &self.layout,
                    entries: &entries,
                });
                let groups = size.map(|s| s.div_ceil(MARCH_WORKGROUP_SIZE));
                Some((bind_group, groups))
            }
            _ => None,
        };
        let mut camera = [0u32; 16];
        camera.copy_from_slice(&words[..16]);
        self.last_camera = Some(camera);
        self.frame = self.frame.wrapping_add(1);
        Ok(())
    }

    /// Records the frame: the reprojection (a compute pass, when there is a history),
    /// `march` (only the pixels left to it, on its stage; `timestamp_writes` on its
    /// pass, as [`FieldMarchPass::encode_timed`] takes them), and the copy of its image
    /// into the history.
    pub fn encode<F: MarchedField>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        march: &FieldMarchPass<F>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), MarchGpuError> {
        if let Some((bind_group, groups)) = &self.bind_group {
            crate::gpu::dispatch_2d(
                encoder,
                "cloudlight march reproject",
                None,
                &self.pipeline,
                bind_group,
                *groups,
            );
        }
        march.encode_timed(encoder, timestamp_writes)?;
        let image = march
            .image_buffer()
            .ok_or(MarchGpuError::EncodeBeforePrepare)?;
        if let Some((history, _)) = &self.history {
            encoder.copy_buffer_to_buffer(image, 0, history, 0, image.size());
        }
        Ok(())
    }
}
