//! Where every rung's frame renderer writes a frame: two `rgba32float` textures the
//! caller can sample, copy or read back: in-scattered radiance (rgb, a = 1) and
//! transmittance (rgb, a = 1) per pixel, in the units of [`crate::ladder`].
//!
//! `rgba32float` keeps the CPU twin's f32 values exactly (parity) and can be written
//! by compute passes on every adapter; it is not filterable everywhere, so sample it
//! with `textureLoad` (a frame is read one texel per pixel anyway).

use crate::frame::FrameCamera;
use crate::{AtmosError, GpuError};

/// The two per-pixel output textures of a frame.
#[derive(Debug)]
pub struct FrameOutput {
    width: u32,
    height: u32,
    radiance: wgpu::Texture,
    transmittance: wgpu::Texture,
    radiance_view: wgpu::TextureView,
    transmittance_view: wgpu::TextureView,
}

impl FrameOutput {
    /// The texel format of both textures.
    pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
    /// Bytes per texel.
    pub const BYTES_PER_PIXEL: u64 = 16;

    /// Textures for a `width × height` frame (usage `STORAGE_BINDING |
    /// TEXTURE_BINDING | COPY_SRC`); errors naming the field when a side is 0 or beyond
    /// the device's `max_texture_dimension_2d`.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Result<Self, AtmosError> {
        let limit = device.limits().max_texture_dimension_2d;
        for (field, value) in [("width", width), ("height", height)] {
            if value == 0 {
                return Err(AtmosError::InvalidSetting {
                    setting: "frame output",
                    field: field.to_owned(),
                    value: 0.0,
                    reason: "must be ≥ 1 pixel",
                });
            }
            if value > limit {
                return Err(GpuError::TextureTooLarge {
                    resource: format!("a {width}×{height} frame ({field})"),
                    size: value,
                    limit,
                }
                .into());
            }
        }
        let texture = |label| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: Self::FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let radiance = texture("atmos frame radiance");
        let transmittance = texture("atmos frame transmittance");
        Ok(Self {
            width,
            height,
            radiance_view: radiance.create_view(&Default::default()),
            transmittance_view: transmittance.create_view(&Default::default()),
            radiance,
            transmittance,
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
    /// Radiance per pixel (rgb used).
    pub fn radiance(&self) -> &wgpu::Texture {
        &self.radiance
    }
    /// Transmittance per pixel (rgb used).
    pub fn transmittance(&self) -> &wgpu::Texture {
        &self.transmittance
    }
    /// A view of the radiance texture.
    pub fn radiance_view(&self) -> &wgpu::TextureView {
        &self.radiance_view
    }
    /// A view of the transmittance texture.
    pub fn transmittance_view(&self) -> &wgpu::TextureView {
        &self.transmittance_view
    }
    /// Bind-group entries for the two textures at `first_binding` and
    /// `first_binding + 1` (as storage textures when a renderer writes them, as sampled
    /// textures when a later pass reads them: the layout decides).
    pub fn bind_group_entries(&self, first_binding: u32) -> [wgpu::BindGroupEntry<'_>; 2] {
        [
            wgpu::BindGroupEntry {
                binding: first_binding,
                resource: wgpu::BindingResource::TextureView(&self.radiance_view),
            },
            wgpu::BindGroupEntry {
                binding: first_binding + 1,
                resource: wgpu::BindingResource::TextureView(&self.transmittance_view),
            },
        ]
    }
}
