//! A horizon stack on the GPU: a `texture_2d_array<f32>` of the baked layers in their
//! encoding (u8 as `R8Unorm`, u16 as `Rg8Unorm`, f32 as `R32Float`: no optional wgpu
//! feature; see [`crate::horizon_stack`]) and its parameters uniform, with a public
//! bind-group layout. Read it in your own shader with `#import terrain::horizon_stack`
//! (`sample_horizon`, `self_shadow`), declaring the two bindings at the group your
//! pipeline has free ([`horizon_stack_bindings_wgsl`]).
//!
//! Bring your own device: [`GpuHorizonStack::upload`] creates the texture and writes it
//! through the caller's queue (one `write_texture`, executed at the caller's next
//! submit); nothing here submits.
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue, maps: &terrain::AzimuthHorizonMaps) -> Result<(), terrain::TerrainError> {
//! use terrain::horizon_stack::HorizonStack;
//! use terrain::horizon_texture::{GpuHorizonStack, horizon_stack_bindings_wgsl};
//! let stack = HorizonStack::new(maps, terrain::HorizonEncoding::Unorm16)?;
//! let gpu = GpuHorizonStack::upload(device, queue, &stack)?;
//! // Your pipeline layout holds `gpu.layout()` at group 1; your WGSL starts with
//! // `#import terrain::horizon_stack` and `horizon_stack_bindings_wgsl(1)`, then calls
//! // self_shadow(horizon_stack, horizon_stack_params, position, sun_enu, radius).
//! let _declarations = horizon_stack_bindings_wgsl(1);
//! # let _ = gpu.bind_group(); Ok(()) }
//! ```

use wgpu::util::DeviceExt as _;

use crate::horizon_stack::HorizonStack;
use crate::{HorizonEncoding, TerrainError};

/// The stages the stack may be read from.
pub const READ_STAGES: wgpu::ShaderStages = wgpu::ShaderStages::COMPUTE
    .union(wgpu::ShaderStages::VERTEX)
    .union(wgpu::ShaderStages::FRAGMENT);

/// The WGSL declarations of the stack's two bindings at `@group(group)`: the texture
/// `horizon_stack` (binding 0) and the uniform `horizon_stack_params` (binding 1).
pub fn horizon_stack_bindings_wgsl(group: u32) -> String {
    format!(
        "@group({group}) @binding(0) var horizon_stack: texture_2d_array<f32>;\n\
         @group({group}) @binding(1) var<uniform> horizon_stack_params: HorizonStackParams;\n"
    )
}

/// The texture format that holds `encoding`.
pub fn horizon_stack_format(encoding: HorizonEncoding) -> wgpu::TextureFormat {
    match encoding {
        HorizonEncoding::Unorm8 => wgpu::TextureFormat::R8Unorm,
        HorizonEncoding::Unorm16 => wgpu::TextureFormat::Rg8Unorm,
        HorizonEncoding::F32 => wgpu::TextureFormat::R32Float,
    }
}

/// The bind-group layout of a stack: the texture (unfilterable float, 2-D array) at
/// binding 0, the parameters uniform at binding 1, readable from [`READ_STAGES`].
pub fn horizon_stack_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("terrain horizon stack"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: READ_STAGES,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2Array,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: READ_STAGES,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    })
}

/// A horizon stack uploaded to the GPU.
#[derive(Debug)]
pub struct GpuHorizonStack {
    texture: wgpu::Texture,
    layout: wgpu::BindGroupLayout,
    bind_group: wgpu::BindGroup,
    encoding: HorizonEncoding,
}

impl GpuHorizonStack {
    /// Creates the texture and its bind group and writes `stack` into it through
    /// `queue`. Errors naming the side or the layer count the device cannot hold.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        stack: &HorizonStack,
    ) -> Result<Self, TerrainError> {
        let params = stack.params();
        let limits = device.limits();
        for (field, value, limit) in [
            ("width", params.width, limits.max_texture_dimension_2d),
            ("height", params.height, limits.max_texture_dimension_2d),
            ("count", params.count, limits.max_texture_array_layers),
        ] {
            if value > limit {
                return Err(TerrainError::param(
                    field,
                    f64::from(value),
                    "exceeds the device's texture limit for a horizon stack",
                ));
            }
        }
        let encoding = stack.encoding();
        let size = wgpu::Extent3d {
            width: params.width,
            height: params.height,
            depth_or_array_layers: params.count,
        };
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("terrain horizon stack"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: horizon_stack_format(encoding),
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let texel_bytes = encoding.bytes() as u32;
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            stack.bytes(),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(params.width * texel_bytes),
                rows_per_image: Some(params.height),
            },
            size,
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("terrain horizon stack"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("terrain horizon stack parameters"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let layout = horizon_stack_layout(device);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("terrain horizon stack"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: uniform.as_entire_binding(),
                },
            ],
        });
        Ok(Self {
            texture,
            layout,
            bind_group,
            encoding,
        })
    }

    /// The texture (layers = azimuths).
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// The bind-group layout ([`horizon_stack_layout`]) to put in a pipeline layout.
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// The bind group (texture at binding 0, parameters at binding 1).
    pub fn bind_group(&self) -> &wgpu::BindGroup {
        &self.bind_group
    }

    /// How the angles are stored.
    pub fn encoding(&self) -> HorizonEncoding {
        self.encoding
    }
}
