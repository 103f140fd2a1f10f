//! [`MarchStage`]: which of the device's stages runs the march's per-pixel work, and
//! what each stage needs of the pass: its pipeline, the attachment a fragment stage's
//! render pass draws into, the image sizes it allows and its recording.

use std::future::Future;
use std::pin::pin;
use std::task::{Context, Poll, Waker};

use super::*;

/// The stage that runs [`FieldMarchPass`]'s per-pixel march (the module documentation
/// says why a fragment stage); both write the same output buffer with the same WGSL
/// function.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MarchStage {
    /// One fragment per pixel of a full-screen triangle over an image-sized depth
    /// attachment (`march_raster.wgsl`): the choice wherever fragment shaders may write
    /// storage buffers.
    Fragment,
    /// One compute invocation per pixel, [`MARCH_WORKGROUP_SIZE`]² per workgroup: the
    /// fallback where they may not.
    Compute,
}

impl MarchStage {
    /// The stage [`FieldMarchPass::new`] chooses on an adapter with `downlevel`
    /// capabilities: [`MarchStage::Fragment`] where the adapter lets a fragment shader
    /// write storage buffers ([`wgpu::DownlevelFlags::FRAGMENT_WRITABLE_STORAGE`]),
    /// otherwise [`MarchStage::Compute`]. (The pass binds four storage buffers; wgpu has
    /// one `max_storage_buffers_per_shader_stage` for every stage, so that limit does not
    /// choose between them.)
    pub fn supported(downlevel: &wgpu::DownlevelCapabilities) -> Self {
        if downlevel
            .flags
            .contains(wgpu::DownlevelFlags::FRAGMENT_WRITABLE_STORAGE)
        {
            Self::Fragment
        } else {
            Self::Compute
        }
    }

    /// The visibility of the pass's bindings.
    pub(super) fn visibility(self) -> wgpu::ShaderStages {
        match self {
            Self::Fragment => wgpu::ShaderStages::FRAGMENT,
            Self::Compute => wgpu::ShaderStages::COMPUTE,
        }
    }
}

impl std::fmt::Display for MarchStage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Fragment => "fragment",
            Self::Compute => "compute",
        })
    }
}

/// The depth format of the fragment stage's attachment: the smallest depth format every
/// backend renders to.
const RASTER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth16Unorm;

/// A march's pipeline on its stage and, on the fragment stage, its attachment.
#[derive(Debug)]
pub(super) enum StagePass {
    /// The fragment stage's render pipeline (`march_raster.wgsl`'s vertex entry and the
    /// field's fragment entry).
    Fragment {
        pipeline: wgpu::RenderPipeline,
        /// The attachment and its size (after `prepare`; kept while the size is).
        /// A render pass must have an attachment, and only the fragment stage's storage
        /// writes matter, so it is depth-only (the smallest depth format), neither
        /// tested nor written: it fixes the pass's size, one fragment per pixel.
        target: Option<(wgpu::TextureView, [u32; 2])>,
    },
    /// The compute stage's pipeline (the field's compute entry).
    Compute { pipeline: wgpu::ComputePipeline },
}

/// `error` on one line: wgpu's description without its blank and heading lines.
fn one_line(error: &wgpu::Error) -> String {
    error
        .to_string()
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && *line != "Validation Error" && *line != "Caused by:")
        .collect::<Vec<_>>()
        .join(": ")
}

/// Runs `build` inside validation and internal error scopes on `device`; what they
/// caught (validation first) is [`MarchGpuError::Pipeline`] on `stage`. wgpu's native
/// and GL backends answer a scope at once; an answer still pending (the browser's
/// WebGPU, which skyscape does not enable) counts as none.
fn scoped<T>(
    device: &wgpu::Device,
    stage: MarchStage,
    build: impl FnOnce() -> T,
) -> Result<T, MarchGpuError> {
    let scopes = [wgpu::ErrorFilter::Internal, wgpu::ErrorFilter::Validation]
        .map(|f| device.push_error_scope(f));
    let built = build();
    // Popped innermost first (wgpu panics on any other order).
    let mut caught = None;
    for scope in scopes.into_iter().rev() {
        let answer = match pin!(scope.pop()).poll(&mut Context::from_waker(Waker::noop())) {
            Poll::Ready(answer) => answer,
            Poll::Pending => None,
        };
        caught = caught.or(answer);
    }
    match caught {
        Some(error) => Err(MarchGpuError::Pipeline {
            stage,
            message: one_line(&error),
        }),
        None => Ok(built),
    }
}

impl StagePass {
    /// The pipeline on `stage` of the composed `source` (`entry_point`: the field's
    /// entry for that stage) over one bind group of `entries` (their visibility
    /// `stage`'s), and the group's layout; a pipeline the device refuses (a fragment
    /// stage where fragment shaders cannot write storage buffers) is
    /// [`MarchGpuError::Pipeline`].
    pub(super) fn new(
        device: &wgpu::Device,
        stage: MarchStage,
        source: &str,
        label: &str,
        entry_point: &str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> Result<(Self, wgpu::BindGroupLayout), MarchGpuError> {
        scoped(device, stage, || {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            match stage {
                MarchStage::Compute => {
                    let (pipeline, layout) = crate::gpu::one_group_pipeline(
                        device,
                        label,
                        entries,
                        &module,
                        entry_point,
                    );
                    (Self::Compute { pipeline }, layout)
                }
                MarchStage::Fragment => {
                    let layout =
                        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                            label: Some(label),
                            entries,
                        });
                    let pipeline = raster_pipeline(device, label, &layout, &module, entry_point);
                    (
                        Self::Fragment {
                            pipeline,
                            target: None,
                        },
                        layout,
                    )
                }
            }
        })
    }

    /// The stage this pass runs on.
    pub(super) fn stage(&self) -> MarchStage {
        match self {
            Self::Fragment { .. } => MarchStage::Fragment,
            Self::Compute { .. } => MarchStage::Compute,
        }
    }

    /// Checks `size` against what the stage allows on `device` (at least one pixel along
    /// each axis; at most `max_texture_dimension_2d` for the fragment stage's attachment,
    /// [`MARCH_WORKGROUP_SIZE`] × `max_compute_workgroups_per_dimension` for a dispatch)
    /// and, on the fragment stage, creates the attachment when its size changes.
    pub(super) fn prepare(
        &mut self,
        device: &wgpu::Device,
        label: &str,
        size: [u32; 2],
    ) -> Result<(), MarchGpuError> {
        let limits = device.limits();
        let limit = match self {
            Self::Fragment { .. } => limits.max_texture_dimension_2d,
            Self::Compute { .. } => limits
                .max_compute_workgroups_per_dimension
                .saturating_mul(MARCH_WORKGROUP_SIZE),
        };
        for (field, value) in ["size.x", "size.y"].into_iter().zip(size) {
            if value == 0 || value > limit {
                return Err(MarchGpuError::ImageSize {
                    field,
                    value,
                    stage: self.stage(),
                    limit,
                });
            }
        }
        if let Self::Fragment { target, .. } = self
            && target.as_ref().is_none_or(|(_, kept)| *kept != size)
        {
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&format!("{label} raster")),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: RASTER_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                view_formats: &[],
            });
            *target = Some((texture.create_view(&Default::default()), size));
        }
        Ok(())
    }

    /// Records the march over a `size` image with `bind_group`: one render pass drawing
    /// the full-screen triangle, or one compute pass of one dispatch; `timestamp_writes`
    /// on that pass (a compute pass takes the same query set and indices).
    pub(super) fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        label: &str,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
        bind_group: &wgpu::BindGroup,
        size: [u32; 2],
    ) -> Result<(), MarchGpuError> {
        match self {
            Self::Fragment { pipeline, target } => {
                let (view, _) = target.as_ref().ok_or(MarchGpuError::EncodeBeforePrepare)?;
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(label),
                    color_attachments: &[],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view,
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Discard,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes,
                    ..Default::default()
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
            Self::Compute { pipeline } => crate::gpu::dispatch_2d(
                encoder,
                label,
                timestamp_writes.map(|w| wgpu::ComputePassTimestampWrites {
                    query_set: w.query_set,
                    beginning_of_pass_write_index: w.beginning_of_pass_write_index,
                    end_of_pass_write_index: w.end_of_pass_write_index,
                }),
                pipeline,
                bind_group,
                size.map(|s| s.div_ceil(MARCH_WORKGROUP_SIZE)),
            ),
        }
        Ok(())
    }
}

/// The fragment stage's pipeline: `march_raster_vertex`'s triangle, `fragment` writing
/// only storage buffers, the depth attachment neither tested nor written.
fn raster_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    fragment: &str,
) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("march_raster_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: RASTER_FORMAT,
            depth_write_enabled: Some(false),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &[],
        }),
        multiview_mask: None,
        cache: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fragment_stage_needs_fragment_writable_storage() {
        let mut downlevel = wgpu::DownlevelCapabilities::default();
        assert!(
            downlevel
                .flags
                .contains(wgpu::DownlevelFlags::FRAGMENT_WRITABLE_STORAGE)
        );
        assert_eq!(MarchStage::supported(&downlevel), MarchStage::Fragment);
        downlevel
            .flags
            .remove(wgpu::DownlevelFlags::FRAGMENT_WRITABLE_STORAGE);
        assert_eq!(MarchStage::supported(&downlevel), MarchStage::Compute);
    }
}
