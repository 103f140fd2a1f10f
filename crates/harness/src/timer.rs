//! GPU timing with timestamp queries: the only way skyscape reports GPU cost.
//!
//! A [`PassTimer`] owns a query set with two timestamps per *span* (one pass each).
//! Hand [`PassTimer::compute_writes`] / [`PassTimer::render_writes`] to the passes you
//! want timed, call [`PassTimer::resolve`] before finishing the encoder, submit, then
//! [`PassTimer::read_seconds`]. On a software adapter the figures are CPU time of the
//! rasteriser: label them with [`GpuContext::is_cpu_adapter`] /
//! [`describe_adapter`](crate::describe_adapter).

use crate::{GpuContext, HarnessError, read_buffer};

/// Timestamp queries for a fixed number of passes.
#[derive(Debug)]
pub struct PassTimer {
    query_set: wgpu::QuerySet,
    resolve_buffer: wgpu::Buffer,
    spans: u32,
    nanoseconds_per_tick: f64,
}

impl PassTimer {
    /// A timer for `spans` passes; errors when the device was created without
    /// `TIMESTAMP_QUERY` (the harness asks for it whenever the adapter offers it).
    pub fn new(ctx: &GpuContext, spans: u32) -> Result<Self, HarnessError> {
        ctx.require_features(wgpu::Features::TIMESTAMP_QUERY)?;
        let spans = spans.max(1);
        let query_set = ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("skyscape-harness pass timer"),
            ty: wgpu::QueryType::Timestamp,
            count: 2 * spans,
        });
        let resolve_buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("skyscape-harness pass timer resolve"),
            size: 16 * u64::from(spans),
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Ok(Self {
            query_set,
            resolve_buffer,
            spans,
            nanoseconds_per_tick: f64::from(ctx.queue.get_timestamp_period()),
        })
    }

    /// Number of spans.
    pub fn spans(&self) -> u32 {
        self.spans
    }

    /// Timestamp writes for a compute pass measured as span `span`.
    ///
    /// # Panics
    /// If `span >= self.spans()` (a programming error, like an out-of-range index).
    pub fn compute_writes(&self, span: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        assert!(span < self.spans, "span {span} of {}", self.spans);
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * span),
            end_of_pass_write_index: Some(2 * span + 1),
        }
    }

    /// Timestamp writes for a render pass measured as span `span`.
    ///
    /// # Panics
    /// If `span >= self.spans()`.
    pub fn render_writes(&self, span: u32) -> wgpu::RenderPassTimestampWrites<'_> {
        assert!(span < self.spans, "span {span} of {}", self.spans);
        wgpu::RenderPassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * span),
            end_of_pass_write_index: Some(2 * span + 1),
        }
    }

    /// Records the resolve of every span; call once, after the timed passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.query_set, 0..2 * self.spans, &self.resolve_buffer, 0);
    }

    /// Seconds each span took (end − begin), after the encoder holding
    /// [`PassTimer::resolve`] was submitted.
    pub fn read_seconds(&self, ctx: &GpuContext) -> Result<Vec<f64>, HarnessError> {
        let bytes = read_buffer(
            ctx,
            "pass timer",
            &self.resolve_buffer,
            0,
            16 * u64::from(self.spans),
        )?;
        let ticks: &[u64] = bytemuck::cast_slice(&bytes);
        Ok(ticks
            .chunks_exact(2)
            .map(|pair| pair[1].wrapping_sub(pair[0]) as f64 * self.nanoseconds_per_tick * 1e-9)
            .collect())
    }
}

/// Runs `encode` (which records the timed pass with the given span's timestamp writes)
/// `repeats` times, one submit each, and returns the median seconds per pass. The
/// first run is a warm-up (pipeline creation, first-touch of memory) and not counted.
pub fn median_pass_seconds(
    ctx: &GpuContext,
    repeats: u32,
    mut encode: impl FnMut(&mut wgpu::CommandEncoder, &PassTimer, u32),
) -> Result<f64, HarnessError> {
    let repeats = repeats.max(1);
    let timer = PassTimer::new(ctx, repeats + 1)?;
    for span in 0..=repeats {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("skyscape-harness timed pass"),
            });
        encode(&mut encoder, &timer, span);
        if span == repeats {
            timer.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
    }
    let mut seconds = timer.read_seconds(ctx)?.split_off(1);
    seconds.sort_by(f64::total_cmp);
    Ok(seconds[seconds.len() / 2])
}
