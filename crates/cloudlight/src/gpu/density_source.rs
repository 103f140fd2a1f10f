//! [`GpuDensitySource`]: the GPU's [`DensityField`](crate::DensityField), what the one
//! march and shadow-map march of `shaders/cloudlight/field_march.wgsl` read.
//!
//! That WGSL is written once against `cloudlight::density_source` (`field_density`,
//! `field_extinction_per_density`, `field_ray_spans`); a pass composes its entry with
//! that import bound to a source module
//! ([`skyscape_wgsl::Composer::compose_module_bound`]) and binds the source's parameters
//! at group 0, binding 4 (a uniform) and binding 5 (a read-only storage buffer). The
//! sources: a [`CloudVolume`]'s grid (`density_grid.wgsl`) and a procedural shell
//! (`density_shell.wgsl`, its [`ShellField`]; a [`CloudShell`] is the same source).

use std::borrow::Cow;

use crate::shell_shadow::ShellField;
use crate::{CloudShell, CloudVolume};

/// The import the march binds to a source module.
pub(crate) const DENSITY_SLOT: &str = "cloudlight::density_source";

/// The binding of a source's uniform.
const SOURCE_PARAMS_BINDING: u32 = 4;
/// The binding of a source's storage buffer.
const SOURCE_CELLS_BINDING: u32 = 5;

/// A density field a GPU march reads (module documentation).
pub trait GpuDensitySource {
    /// The WGSL module bound to `cloudlight::density_source`.
    const MODULE: &'static str;
    /// The storage buffer's name in errors (`density`, `weather grid`).
    const CELLS: &'static str;
    /// The storage binding's minimum size in bytes (`None`: any).
    const CELLS_MIN_BYTES: Option<u64>;

    /// The source module's uniform (binding 4), as words.
    fn params_words(&self) -> Vec<u32>;

    /// The source module's storage buffer (binding 5), as bytes.
    fn cells_bytes(&self) -> Cow<'_, [u8]>;
}

/// `density_grid.wgsl`'s `DensityGrid`: the box, σ_t and the cells along each axis;
/// the cells themselves, x fastest.
impl GpuDensitySource for CloudVolume {
    const MODULE: &'static str = "cloudlight::density_grid";
    const CELLS: &'static str = "density";
    const CELLS_MIN_BYTES: Option<u64> = None;

    fn params_words(&self) -> Vec<u32> {
        let f = |x: f64| (x as f32).to_bits();
        let (lo, dims, voxel) = (self.origin(), self.dims(), self.voxel_size());
        let hi: [f64; 3] = [0, 1, 2].map(|a| lo[a] + f64::from(dims[a]) * voxel);
        vec![
            f(lo[0]),
            f(lo[1]),
            f(lo[2]),
            f(voxel),
            f(hi[0]),
            f(hi[1]),
            f(hi[2]),
            f(self.extinction_per_density()),
            dims[0],
            dims[1],
            dims[2],
            0,
        ]
    }

    fn cells_bytes(&self) -> Cow<'_, [u8]> {
        Cow::Borrowed(bytemuck::cast_slice(self.density()))
    }
}

/// `density_shell.wgsl`'s `ShellField`, member for member; the weather grid's
/// `[coverage, cloud_type]` per cell, x fastest (one zero cell for procedural weather).
impl GpuDensitySource for ShellField<f32> {
    const MODULE: &'static str = "cloudlight::density_shell";
    const CELLS: &'static str = "weather grid";
    const CELLS_MIN_BYTES: Option<u64> = Some(8);

    fn params_words(&self) -> Vec<u32> {
        let b = f32::to_bits;
        vec![
            b(self.planet_radius),
            b(self.inner_radius),
            b(self.outer_radius),
            b(self.shape_period),
            b(self.detail_period),
            b(self.erosion),
            b(self.extinction_per_density),
            b(self.weather_period),
            b(self.coverage_mean),
            b(self.coverage_contrast),
            b(self.cloud_type_mean),
            b(self.cloud_type_contrast),
            self.seed,
            self.weather_seed,
            self.weather_cells,
            self.weather_kind,
            self.grid_size[0],
            self.grid_size[1],
            b(self.grid_cell_size),
            0,
        ]
    }

    fn cells_bytes(&self) -> Cow<'_, [u8]> {
        if self.grid_cells.is_empty() {
            Cow::Owned(vec![0; 8])
        } else {
            Cow::Borrowed(bytemuck::cast_slice(&self.grid_cells))
        }
    }
}

/// The shell's [`ShellField::of`] in f32.
impl GpuDensitySource for CloudShell {
    const MODULE: &'static str = <ShellField<f32> as GpuDensitySource>::MODULE;
    const CELLS: &'static str = <ShellField<f32> as GpuDensitySource>::CELLS;
    const CELLS_MIN_BYTES: Option<u64> = <ShellField<f32> as GpuDensitySource>::CELLS_MIN_BYTES;

    fn params_words(&self) -> Vec<u32> {
        ShellField::<f32>::of(self).params_words()
    }

    fn cells_bytes(&self) -> Cow<'_, [u8]> {
        Cow::Owned(ShellField::<f32>::of(self).cells_bytes().into_owned())
    }
}

/// The composed WGSL of the pass `entry` over the source `S`.
pub(crate) fn compose_over<S: GpuDensitySource + ?Sized>(
    entry: &str,
) -> Result<String, skyscape_wgsl::ComposeError> {
    crate::composer().compose_module_bound(entry, &[(DENSITY_SLOT, S::MODULE)])
}

/// The layout entries of a source's bindings 4 and 5, visible to `visibility`.
pub(crate) fn source_layout_entries<S: GpuDensitySource + ?Sized>(
    visibility: wgpu::ShaderStages,
) -> [wgpu::BindGroupLayoutEntry; 2] {
    let entry = |binding, ty, min: Option<u64>| wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: min.and_then(wgpu::BufferSize::new),
        },
        count: None,
    };
    [
        entry(
            SOURCE_PARAMS_BINDING,
            wgpu::BufferBindingType::Uniform,
            None,
        ),
        entry(
            SOURCE_CELLS_BINDING,
            wgpu::BufferBindingType::Storage { read_only: true },
            S::CELLS_MIN_BYTES,
        ),
    ]
}

/// A source's uploaded uniform and storage buffer, for bindings 4 and 5.
#[derive(Debug)]
pub(crate) struct SourceBuffers {
    params: wgpu::Buffer,
    cells: wgpu::Buffer,
}

impl SourceBuffers {
    /// Uploads `source`'s uniform and cells (labels after `label`); the cells' byte
    /// count when it exceeds the storage binding `limit`.
    pub(crate) fn upload<S: GpuDensitySource + ?Sized>(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        source: &S,
        label: &str,
        limit: u64,
    ) -> Result<Self, u64> {
        let cells_bytes = source.cells_bytes();
        let bytes = cells_bytes.len() as u64;
        if bytes > limit {
            return Err(bytes);
        }
        let words = source.params_words();
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{label} source params")),
            size: words.len() as u64 * 4,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
        let cells = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{label} {}", S::CELLS)),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&cells, 0, &cells_bytes);
        Ok(Self { params, cells })
    }

    /// The bind group entries of bindings 4 and 5.
    pub(crate) fn entries(&self) -> [wgpu::BindGroupEntry<'_>; 2] {
        [
            wgpu::BindGroupEntry {
                binding: SOURCE_PARAMS_BINDING,
                resource: self.params.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: SOURCE_CELLS_BINDING,
                resource: self.cells.as_entire_binding(),
            },
        ]
    }
}
