//! The device's errors as [`RenderError`]s.
//!
//! wgpu reports a rejected pipeline, bind group or shader (e.g. a WGSL feature the GL
//! backend cannot translate to GLSL, which wgpu classes as an internal error) to the
//! device's uncaptured-error handler, whose default panics. The device is the caller's,
//! so `render` installs no handler on it: each GPU entry point that creates pipelines
//! or bind groups runs inside error scopes ([`wgpu::Device::push_error_scope`]:
//! validation, internal, out of memory) and returns what they caught as
//! [`RenderError::Device`], naming the entry point and the adapter.

use std::future::Future;
use std::pin::pin;
use std::task::{Context, Poll, Waker};

use crate::RenderError;

/// The filters `scoped` catches, outermost first.
const FILTERS: [wgpu::ErrorFilter; 3] = [
    wgpu::ErrorFilter::OutOfMemory,
    wgpu::ErrorFilter::Internal,
    wgpu::ErrorFilter::Validation,
];

/// Runs `build` inside validation, internal and out-of-memory error scopes on
/// `device`; an error they caught becomes [`RenderError::Device`] naming `what` (the
/// entry point) and the adapter (a validation error first, then internal, then out of
/// memory). An error `build` returns itself is returned as it is when the device caught
/// nothing.
///
/// wgpu's native and GL backends answer a scope at once. The browser's WebGPU (not a
/// backend skyscape enables) answers asynchronously; there the answer is not awaited
/// and what the scope caught is dropped with it.
pub(crate) fn scoped<T>(
    device: &wgpu::Device,
    what: &'static str,
    build: impl FnOnce() -> Result<T, RenderError>,
) -> Result<T, RenderError> {
    let scopes = FILTERS.map(|filter| device.push_error_scope(filter));
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
        // The device's error came first: whatever `build` did after it is a consequence.
        Some(source) => {
            let info = device.adapter_info();
            Err(RenderError::Device {
                what,
                adapter: format!("{} ({})", info.name, info.backend),
                source,
            })
        }
        None => built,
    }
}

#[cfg(test)]
mod tests {
    use crate::error::one_line;

    #[test]
    fn one_line_joins_wgpu_descriptions() {
        let error = wgpu::Error::Internal {
            source: "inner".into(),
            description: "Validation Error\n\nCaused by:\n  In Device::create_render_pipeline, \
                          label = 'x'\n    Internal error in ShaderStages(FRAGMENT) shader: no\n"
                .into(),
        };
        assert_eq!(
            one_line(&error),
            "internal error: In Device::create_render_pipeline, label = 'x': \
             Internal error in ShaderStages(FRAGMENT) shader: no"
        );
        let oom = wgpu::Error::OutOfMemory {
            source: "inner".into(),
        };
        assert_eq!(one_line(&oom), "out of memory: inner");
    }
}
