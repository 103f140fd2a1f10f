//! What the march pass holds whatever its field and stage: the outside-shadow bindings,
//! the bind group's layout, the output image and its decoding.

use super::*;
use crate::gpu::density_source::{GpuDensitySource, SourceBuffers, source_layout_entries};
use crate::march::{Jitter, LightMarch, MarchResult, MarchSettings};

/// Bytes of `outside_shadow.wgsl`'s `OutsideShadowParams`.
pub(super) const OUTSIDE_PARAMS_BYTES: u64 = 64;

/// The uniform and values bound as bindings 8 and 9: `outside`'s, or a disabled uniform
/// and a 4-byte placeholder.
pub(super) fn outside_bindings(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    outside: Option<&OutsideShadow<'_>>,
) -> Result<(wgpu::Buffer, wgpu::Buffer), MarchGpuError> {
    let f = |x: f32| x.to_bits();
    let words: [u32; 16] = match outside {
        None => [0; 16],
        Some(o) => {
            let needed = u64::from(o.resolution[0]) * u64::from(o.resolution[1]) * 4;
            let (bytes, usage) = (o.values.size(), o.values.usage());
            if needed == 0 || bytes < needed || !usage.contains(wgpu::BufferUsages::STORAGE) {
                return Err(MarchGpuError::OutsideShadowBuffer {
                    bytes,
                    usage,
                    needed,
                });
            }
            [
                f(o.origin[0]),
                f(o.origin[1]),
                f(o.cell_size),
                f(o.plane),
                f(o.to_light[0]),
                f(o.to_light[1]),
                f(o.to_light[2]),
                f(1.0),
                f(o.extent[0]),
                f(o.extent[1]),
                f(o.frame_height),
                0,
                o.resolution[0],
                o.resolution[1],
                0,
                0,
            ]
        }
    };
    let params = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("cloudlight march outside shadow"),
        size: OUTSIDE_PARAMS_BYTES,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
    let values = match outside {
        Some(o) => o.values.clone(),
        None => device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march no outside shadow"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        }),
    };
    Ok((params, values))
}

/// What the march pass keeps from `prepare`: the bind group, the image's size and the
/// output image; `_inputs` and `_source` keep the bound buffers alive.
#[derive(Debug)]
pub(super) struct Prepared {
    pub(super) bind_group: wgpu::BindGroup,
    pub(super) size: [u32; 2],
    pub(super) image: wgpu::Buffer,
    /// The parameters' words (`MarchParams`), as uploaded.
    pub(super) params: [u32; 52],
    pub(super) _inputs: Vec<wgpu::Buffer>,
    pub(super) _source: SourceBuffers,
}

/// A march pass's bind group layout entries, each visible to `visibility`: `bindings[i]`
/// is binding `i`'s buffer type and minimum size (buffers only), then the density
/// source's bindings 4 and 5 and bindings 8 and 9, another cloud's shadow
/// ([`OutsideShadow`]).
pub(super) fn march_layout_entries<S: GpuDensitySource + ?Sized>(
    visibility: wgpu::ShaderStages,
    bindings: &[(wgpu::BufferBindingType, Option<u64>)],
) -> Vec<wgpu::BindGroupLayoutEntry> {
    let buffer = |binding, ty, min: Option<u64>| wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: min.and_then(wgpu::BufferSize::new),
        },
        count: None,
    };
    bindings
        .iter()
        .enumerate()
        .map(|(binding, &(ty, min))| buffer(binding as u32, ty, min))
        .chain(source_layout_entries::<S>(visibility))
        // outside_shadow.wgsl's uniform and values (field_march imports it).
        .chain([
            buffer(
                8,
                wgpu::BufferBindingType::Uniform,
                Some(OUTSIDE_PARAMS_BYTES),
            ),
            buffer(
                9,
                wgpu::BufferBindingType::Storage { read_only: true },
                None,
            ),
        ])
        .collect()
}

/// The light march's mode word, cone step and spread, light steps; the jitter's word.
pub(super) fn light_words(settings: &MarchSettings) -> (u32, f64, f64, u32, u32) {
    let c = settings.config();
    let (mode, light_steps, cone_step, spread) = match c.light {
        LightMarch::Full { steps } => (0u32, steps.get(), 0.0, 0.0),
        LightMarch::Cone {
            step,
            spread,
            weights,
        } => (
            match weights {
                crate::cone::ConeWeights::Raw => 1,
                crate::cone::ConeWeights::Partitioned => 2,
            },
            0,
            step,
            spread,
        ),
    };
    let jitter = match c.jitter {
        Jitter::None => 0u32,
        Jitter::Bayer4x4 => 1,
        Jitter::InterleavedGradient => 2,
    };
    (mode, cone_step, spread, light_steps, jitter)
}

/// The buffer bound as `max_distance`: the caller's (checked) or a 4-byte placeholder the
/// shader does not read (its flag word is 0).
pub(super) fn distance_binding(
    device: &wgpu::Device,
    max_distance: Option<&wgpu::Buffer>,
    size: [u32; 2],
) -> Result<wgpu::Buffer, MarchGpuError> {
    let Some(buffer) = max_distance else {
        return Ok(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march no max_distance"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        }));
    };
    let needed = u64::from(size[0]) * u64::from(size[1]) * 4;
    let (bytes, usage) = (buffer.size(), buffer.usage());
    if bytes < needed || !usage.contains(wgpu::BufferUsages::STORAGE) {
        return Err(MarchGpuError::DistanceBuffer {
            bytes,
            usage,
            needed,
        });
    }
    Ok(buffer.clone())
}

/// The output buffer of a `size` image (two `vec4<f32>` per pixel), within the storage
/// binding `limit`.
pub(super) fn march_image(
    device: &wgpu::Device,
    label: &str,
    size: [u32; 2],
    limit: u64,
) -> Result<wgpu::Buffer, MarchGpuError> {
    let bytes = u64::from(size[0]) * u64::from(size[1]) * 32;
    if bytes > limit {
        return Err(MarchGpuError::BufferTooLarge {
            what: "image",
            bytes,
            limit,
        });
    }
    Ok(device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    }))
}

/// A march pass's bind group: each buffer whole at its binding, and the density
/// source's.
pub(super) fn march_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    buffers: &[(u32, &wgpu::Buffer)],
    source: &SourceBuffers,
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
        .iter()
        .map(|&(binding, buffer)| wgpu::BindGroupEntry {
            binding,
            resource: buffer.as_entire_binding(),
        })
        .chain(source.entries())
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// The output buffer's bytes as one [`MarchResult`] per pixel of `prepared`'s image
/// (none before `prepare`: a size error).
pub(super) fn decode_pixels(
    bytes: &[u8],
    prepared: Option<&Prepared>,
) -> Result<Vec<MarchResult<f32>>, MarchGpuError> {
    let expected = prepared.map_or(0, |p| p.size[0] as usize * p.size[1] as usize * 32);
    if bytes.len() != expected || expected == 0 {
        return Err(MarchGpuError::ReadbackSize {
            got: bytes.len(),
            expected,
        });
    }
    Ok(bytes
        .chunks_exact(32)
        .map(|b| {
            let w: [f32; 8] = std::array::from_fn(|k| {
                f32::from_ne_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]])
            });
            MarchResult {
                radiance: [w[0], w[1], w[2]],
                transmittance: w[3],
                depth: w[4],
            }
        })
        .collect())
}
