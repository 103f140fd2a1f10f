//! [`NoiseBake`]: the cloud shell's tileable noise baked into two 3-D textures on a GPU
//! (`shaders/cloudlight/noise_bake_pass.wgsl`), bring your own device.
//!
//! [`NoiseBake::new`] builds the two pipelines; [`NoiseBake::prepare`] creates the
//! textures, the parameters and the bind group; [`NoiseBake::encode`] only records one
//! compute pass (two dispatches of 4×4×4 texels per workgroup). Nothing here creates a
//! device or submits.
//!
//! The textures (both **Rgba8Unorm**, 3-D, one mip, `STORAGE_BINDING | TEXTURE_BINDING |
//! COPY_SRC`), each one tile of period 1 (sample it with `Repeat` addressing):
//!
//! * the **shape** texture, `shape_size³` (default 128³, 8 MiB):
//!   [`cloud_shape_noise`](crate::noise::cloud_shape_noise) at each texel centre
//!   `(i + ½)/size` — R the Perlin–Worley, G, B, A inverted Worley with 4, 8, 16 cells
//!   per tile;
//! * the **detail** texture, `detail_size³` (default 32³, 128 KiB):
//!   [`cloud_detail_noise`](crate::noise::cloud_detail_noise) — R, G, B inverted Worley
//!   with 2, 4, 8 cells per tile, A = 1.
//!
//! Why Rgba8Unorm: a core WebGPU storage format that is filterable (the march samples
//! the textures trilinearly), at a quarter of the memory of 32-bit floats, as Schneider's
//! textures are 8-bit; its quantisation step is 1/255 (≤ 0.0020 of a value in [0, 1]).
//! The f32 twins are [`bake_shape_noise`](crate::noise::bake_shape_noise) and
//! [`bake_detail_noise`](crate::noise::bake_detail_noise), quantised by
//! [`unorm8`](crate::noise::unorm8).

/// Texels per workgroup along each axis.
pub const NOISE_BAKE_WORKGROUP_SIZE: u32 = 4;

/// The format of both baked textures (see the module documentation).
pub const NOISE_TEXTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

const PARAMS_BYTES: u64 = 16;

/// What to bake: the seed and the edge of each cubic texture in texels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NoiseBakeSettings {
    /// Seed of the shape and detail noise (a [`ShellSettings::seed`](crate::ShellSettings)).
    pub seed: u32,
    /// Edge of the shape texture, texels (≥ 1; default 128).
    pub shape_size: u32,
    /// Edge of the detail texture, texels (≥ 1; default 32).
    pub detail_size: u32,
}

impl Default for NoiseBakeSettings {
    /// Seed 3 (the default shell's), 128³ shape and 32³ detail textures.
    fn default() -> Self {
        Self {
            seed: 3,
            shape_size: 128,
            detail_size: 32,
        }
    }
}

/// Errors of the noise bake, naming the field and value.
#[derive(Debug, thiserror::Error)]
pub enum NoiseBakeError {
    /// Composing the WGSL failed (a packaging bug).
    #[error(transparent)]
    Compose(#[from] skyscape_wgsl::ComposeError),
    /// A texture edge is zero.
    #[error("{field} = 0: a noise texture needs at least one texel")]
    ZeroSize {
        /// `shape_size` or `detail_size`.
        field: &'static str,
    },
    /// A texture is larger than the device's 3-D textures.
    #[error("{field} = {value} texels, the device's max_texture_dimension_3d is {limit}")]
    TextureTooLarge {
        /// `shape_size` or `detail_size`.
        field: &'static str,
        /// Its edge in texels.
        value: u32,
        /// The device limit.
        limit: u32,
    },
    /// `encode` was called before `prepare`.
    #[error("encode before prepare: no textures to bake")]
    EncodeBeforePrepare,
}

/// The composed WGSL of the bake (entry points `bake_shape` and `bake_detail`).
pub fn compose_noise_bake_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    crate::composer().compose_module("cloudlight::noise_bake_pass")
}

#[derive(Debug)]
struct Prepared {
    bind_group: wgpu::BindGroup,
    settings: NoiseBakeSettings,
    shape: wgpu::Texture,
    detail: wgpu::Texture,
    _params: wgpu::Buffer,
}

/// The noise bake on a GPU (see the module documentation).
#[derive(Debug)]
pub struct NoiseBake {
    shape_pipeline: wgpu::ComputePipeline,
    detail_pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

impl NoiseBake {
    /// Builds the pipelines on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, NoiseBakeError> {
        let source = compose_noise_bake_shader()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cloudlight::noise_bake_pass"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let entry = |binding: u32, ty: wgpu::BindingType| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        };
        let storage = wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: NOISE_TEXTURE_FORMAT,
            view_dimension: wgpu::TextureViewDimension::D3,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cloudlight noise bake"),
            entries: &[
                entry(
                    0,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(PARAMS_BYTES),
                    },
                ),
                entry(1, storage),
                entry(2, storage),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cloudlight noise bake"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry_point: &'static str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        };
        Ok(Self {
            shape_pipeline: pipeline("bake_shape"),
            detail_pipeline: pipeline("bake_detail"),
            layout,
            prepared: None,
        })
    }

    /// Creates the two textures (see the module documentation), the parameters and the
    /// bind group [`NoiseBake::encode`] records with. Takes effect at the next submit.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        settings: NoiseBakeSettings,
    ) -> Result<(), NoiseBakeError> {
        let limit = device.limits().max_texture_dimension_3d;
        for (field, value) in [
            ("shape_size", settings.shape_size),
            ("detail_size", settings.detail_size),
        ] {
            if value == 0 {
                return Err(NoiseBakeError::ZeroSize { field });
            }
            if value > limit {
                return Err(NoiseBakeError::TextureTooLarge {
                    field,
                    value,
                    limit,
                });
            }
        }
        let texture = |label: &'static str, size: u32| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: size,
                    height: size,
                    depth_or_array_layers: size,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D3,
                format: NOISE_TEXTURE_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let shape = texture("cloudlight shape noise", settings.shape_size);
        let detail = texture("cloudlight detail noise", settings.detail_size);
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight noise bake params"),
            size: PARAMS_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let words: [u32; 4] = [settings.seed, settings.shape_size, settings.detail_size, 0];
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
        let shape_view = shape.create_view(&Default::default());
        let detail_view = detail.create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cloudlight noise bake"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&shape_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&detail_view),
                },
            ],
        });
        self.prepared = Some(Prepared {
            bind_group,
            settings,
            shape,
            detail,
            _params: params,
        });
        Ok(())
    }

    /// Records the bake (one compute pass, both dispatches) into `encoder`.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), NoiseBakeError> {
        self.encode_timed(encoder, None)
    }

    /// [`NoiseBake::encode`] with timestamp writes around the pass (e.g. from
    /// `skyscape_harness::timer::PassTimer`).
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), NoiseBakeError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(NoiseBakeError::EncodeBeforePrepare)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("cloudlight noise bake"),
            timestamp_writes,
        });
        pass.set_bind_group(0, &prepared.bind_group, &[]);
        let s = &prepared.settings;
        for (pipeline, size) in [
            (&self.shape_pipeline, s.shape_size),
            (&self.detail_pipeline, s.detail_size),
        ] {
            let groups = size.div_ceil(NOISE_BAKE_WORKGROUP_SIZE);
            pass.set_pipeline(pipeline);
            pass.dispatch_workgroups(groups, groups, groups);
        }
        Ok(())
    }

    /// The shape texture (after [`NoiseBake::prepare`]).
    pub fn shape_texture(&self) -> Option<&wgpu::Texture> {
        self.prepared.as_ref().map(|p| &p.shape)
    }

    /// The detail texture (after [`NoiseBake::prepare`]).
    pub fn detail_texture(&self) -> Option<&wgpu::Texture> {
        self.prepared.as_ref().map(|p| &p.detail)
    }
}
