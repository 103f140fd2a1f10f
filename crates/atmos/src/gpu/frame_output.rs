//! Where every rung's GPU renderer writes a frame: two storage buffers of one
//! `vec4<f32>` per pixel (index `x + width · y`): in-scattered radiance (rgb, w = 1)
//! and transmittance (rgb, w = 1), in the units of [`crate::ladder`].

use crate::frame::FrameCamera;
use crate::{AtmosError, GpuError};

/// The two per-pixel output buffers of a frame.
#[derive(Debug)]
pub struct FrameOutput {
    width: u32,
    height: u32,
    radiance: wgpu::Buffer,
    transmittance: wgpu::Buffer,
}

impl FrameOutput {
    /// Bytes per pixel per buffer.
    pub const BYTES_PER_PIXEL: u64 = 16;

    /// Buffers for a `width × height` frame (usage `STORAGE | COPY_SRC`); errors when
    /// they would exceed the device's storage-buffer binding limit.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Result<Self, AtmosError> {
        if width == 0 || height == 0 {
            return Err(AtmosError::InvalidSetting {
                setting: "frame output",
                field: if width == 0 { "width" } else { "height" }.to_owned(),
                value: 0.0,
                reason: "must be ≥ 1 pixel",
            });
        }
        let size = u64::from(width) * u64::from(height) * Self::BYTES_PER_PIXEL;
        let limit = device.limits().max_storage_buffer_binding_size;
        if size > limit {
            return Err(GpuError::StorageBufferTooLarge {
                resource: format!("a {width}×{height} frame"),
                bytes: size,
                limit,
            }
            .into());
        }
        let buffer = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        Ok(Self {
            width,
            height,
            radiance: buffer("atmos frame radiance"),
            transmittance: buffer("atmos frame transmittance"),
        })
    }

    /// Errors unless `camera` describes a frame of this output's size.
    pub fn check_camera(&self, camera: &FrameCamera) -> Result<(), AtmosError> {
        if camera.width != self.width || camera.height != self.height {
            return Err(GpuError::OutputSizeMismatch {
                camera_width: camera.width,
                camera_height: camera.height,
                output_width: self.width,
                output_height: self.height,
            }
            .into());
        }
        Ok(())
    }

    /// Frame width (pixels).
    pub fn width(&self) -> u32 {
        self.width
    }
    /// Frame height (pixels).
    pub fn height(&self) -> u32 {
        self.height
    }
    /// Radiance per pixel (`vec4<f32>`, rgb used).
    pub fn radiance(&self) -> &wgpu::Buffer {
        &self.radiance
    }
    /// Transmittance per pixel (`vec4<f32>`, rgb used).
    pub fn transmittance(&self) -> &wgpu::Buffer {
        &self.transmittance
    }
    /// Bind-group entries for the two buffers at `first_binding` and `first_binding + 1`.
    pub fn bind_group_entries(&self, first_binding: u32) -> [wgpu::BindGroupEntry<'_>; 2] {
        [
            wgpu::BindGroupEntry {
                binding: first_binding,
                resource: self.radiance.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: first_binding + 1,
                resource: self.transmittance.as_entire_binding(),
            },
        ]
    }
}
