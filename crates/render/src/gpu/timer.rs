//! GPU timestamps per pass: a query set with two timestamps per span, resolved into a
//! buffer the caller reads after submitting. Only when the device has
//! `TIMESTAMP_QUERY`; timings on a CPU adapter are CPU timings and are reported so.

/// A span per pass of a frame.
#[derive(Debug)]
pub struct PassTimes {
    labels: Vec<&'static str>,
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f32,
    /// The spans whose timestamp writes were handed out since [`Self::begin_frame`], in
    /// order: what the frame recorded.
    recorded: std::sync::Mutex<Vec<&'static str>>,
}

impl PassTimes {
    /// Timestamps for the passes `labels`, or `None` when the device has no
    /// `TIMESTAMP_QUERY` feature.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        labels: Vec<&'static str>,
    ) -> Option<Self> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) || labels.is_empty() {
            return None;
        }
        let count = 2 * labels.len() as u32;
        let query_set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("render pass times"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let bytes = u64::from(count) * 8;
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render pass times (resolve)"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render pass times (readback)"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Some(Self {
            labels,
            query_set,
            resolve,
            readback,
            period_ns: queue.get_timestamp_period(),
            recorded: std::sync::Mutex::new(Vec::new()),
        })
    }

    /// The index of the span labelled `label`.
    pub fn span(&self, label: &str) -> Option<u32> {
        self.labels
            .iter()
            .position(|l| *l == label)
            .map(|i| i as u32)
    }

    /// Starts a frame: forgets the spans recorded so far.
    pub fn begin_frame(&self) {
        self.recorded_spans().clear();
    }

    /// The spans whose timestamp writes were handed out since [`Self::begin_frame`], in
    /// order.
    pub fn recorded(&self) -> Vec<&'static str> {
        self.recorded_spans().clone()
    }

    fn recorded_spans(&self) -> std::sync::MutexGuard<'_, Vec<&'static str>> {
        // A poisoned lock only means a panic elsewhere; the list is still a list.
        self.recorded
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The span of `label`, noted as recorded (a label without a span too: a step the
    /// plan does not time, which a check of the frame's list must see).
    fn record(&self, label: &'static str) -> Option<u32> {
        self.recorded_spans().push(label);
        self.span(label)
    }

    /// Timestamp writes of a compute pass for `label`'s span.
    pub fn compute_writes(
        &self,
        label: &'static str,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        self.record(label)
            .map(|span| wgpu::ComputePassTimestampWrites {
                query_set: &self.query_set,
                beginning_of_pass_write_index: Some(2 * span),
                end_of_pass_write_index: Some(2 * span + 1),
            })
    }

    /// Timestamp writes of a render pass for `label`'s span.
    pub fn render_writes(
        &self,
        label: &'static str,
    ) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        self.record(label)
            .map(|span| wgpu::RenderPassTimestampWrites {
                query_set: &self.query_set,
                beginning_of_pass_write_index: Some(2 * span),
                end_of_pass_write_index: Some(2 * span + 1),
            })
    }

    /// Records the resolve and the copy for reading; call after the frame's passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        let count = 2 * self.labels.len() as u32;
        encoder.resolve_query_set(&self.query_set, 0..count, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, self.resolve.size());
    }

    /// Seconds per span, once the frame is submitted (blocks on the device).
    pub fn read(&self, device: &wgpu::Device) -> Result<Vec<(&'static str, f64)>, String> {
        let (sender, receiver) = std::sync::mpsc::channel();
        self.readback
            .map_async(wgpu::MapMode::Read, .., move |result| {
                let _ = sender.send(result);
            });
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| e.to_string())?;
        receiver
            .recv()
            .map_err(|e| e.to_string())?
            .map_err(|e| e.to_string())?;
        let ticks: Vec<u64> = {
            let view = self
                .readback
                .get_mapped_range(..)
                .map_err(|e| e.to_string())?;
            bytemuck::cast_slice::<u8, u64>(&view).to_vec()
        };
        self.readback.unmap();
        Ok(self
            .labels
            .iter()
            .zip(ticks.chunks_exact(2))
            .map(|(label, pair)| {
                let ticks = pair[1].saturating_sub(pair[0]);
                (*label, ticks as f64 * f64::from(self.period_ns) * 1e-9)
            })
            .collect())
    }
}
