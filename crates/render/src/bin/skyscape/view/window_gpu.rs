//! The viewer's GPU: the window's surface, the device, the scene renderer (the same
//! `SceneRenderer` as `skyscape render`, kept while it accepts the prepared scene), the
//! pass that draws its display pixels over the surface, and screenshots read back from
//! the surface itself.

use std::sync::Arc;

use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::scene::PreparedScene;
use winit::window::Window;

use crate::adapter::{copy_texture, describe, read_buffer, read_radiance};

/// What the window shows, read back: RGBA8 (R in the low byte, as `Rendered::pixels`)
/// and the HDR radiance behind it.
pub(crate) struct Shot {
    pub(crate) size: (u32, u32),
    pub(crate) pixels: Vec<u32>,
    pub(crate) radiance: Vec<[f32; 3]>,
    /// The radiance's size: the render size (the window's × the render scale).
    pub(crate) radiance_size: (u32, u32),
}

/// The overlay's share of a frame: egui's triangles and texture changes.
pub(crate) struct OverlayFrame {
    pub(crate) primitives: Vec<egui::ClippedPrimitive>,
    pub(crate) textures: egui::TexturesDelta,
    pub(crate) screen: egui_wgpu::ScreenDescriptor,
}

/// The window's device and everything drawn with it.
pub(crate) struct WindowGpu {
    surface: wgpu::Surface<'static>,
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) info: wgpu::AdapterInfo,
    config: wgpu::SurfaceConfiguration,
    timestamps: bool,
    present: wgpu::RenderPipeline,
    present_uniforms: wgpu::Buffer,
    present_bind_group: Option<wgpu::BindGroup>,
    pub(crate) renderer: Option<SceneRenderer>,
    /// Whether the renderer amortises the marched clouds over frames.
    temporal_clouds: bool,
    /// Renderers built so far (the first, then one per change the last one refused).
    pub(crate) renderers_built: u32,
    pub(crate) overlay: egui_wgpu::Renderer,
}

impl WindowGpu {
    /// A device on an adapter that can present to `window`'s surface.
    pub(crate) fn new(
        window: Arc<Window>,
        display: winit::event_loop::OwnedDisplayHandle,
        backends: wgpu::Backends,
        vsync: bool,
    ) -> Result<Self, String> {
        let mut descriptor =
            wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(display));
        descriptor.backends = backends;
        let instance = wgpu::Instance::new(descriptor);
        let size = window.inner_size();
        let surface = instance
            .create_surface(window)
            .map_err(|e| format!("the window's surface: {e}"))?;
        let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
            &instance,
            Some(&surface),
        ))
        .map_err(|e| format!("no GPU adapter that can draw into the window: {e}"))?;
        let info = adapter.get_info();
        let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("skyscape view"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| format!("no device on {}: {e}", info.name))?;
        let capabilities = surface.get_capabilities(&adapter);
        let format = capabilities
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .or_else(|| capabilities.formats.first().copied())
            .ok_or_else(|| format!("the window's surface on {} has no format", info.name))?;
        // Screenshots are read from the surface when it allows copies.
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT
            | (capabilities.usages & wgpu::TextureUsages::COPY_SRC);
        let present_mode = if vsync {
            wgpu::PresentMode::AutoVsync
        } else {
            wgpu::PresentMode::AutoNoVsync
        };
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            color_space: Default::default(),
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode: capabilities
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: Vec::new(),
        };
        surface.configure(&device, &config);
        let (present, present_uniforms) = present_pipeline(&device, format)?;
        let overlay = egui_wgpu::Renderer::new(&device, format, Default::default());
        Ok(Self {
            surface,
            device,
            queue,
            timestamps: features.contains(wgpu::Features::TIMESTAMP_QUERY),
            info,
            config,
            present,
            present_uniforms,
            present_bind_group: None,
            renderer: None,
            temporal_clouds: false,
            renderers_built: 0,
            overlay,
        })
    }

    /// The adapter in plain words ("a CPU adapter (software rasteriser): …").
    pub(crate) fn adapter(&self) -> String {
        describe(&self.info)
    }

    /// The surface's size.
    pub(crate) fn surface_size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Resizes the surface (a 0×0 window, minimised, is left as it was).
    pub(crate) fn resize(&mut self, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(&self.device, &self.config);
    }

    /// Writes `scene`'s frame uniforms into the renderer, building a new renderer when
    /// there is none, the current one refuses the scene (other passes, size, tables or
    /// terrain) or `temporal_clouds` (the marched clouds amortised over frames)
    /// changed. Returns whether a renderer was built.
    pub(crate) fn prepare(
        &mut self,
        scene: &PreparedScene,
        temporal_clouds: bool,
    ) -> Result<bool, String> {
        if let Some(renderer) = &mut self.renderer
            && temporal_clouds == self.temporal_clouds
            && renderer.prepare(&self.queue, scene).is_ok()
        {
            return Ok(false);
        }
        self.temporal_clouds = temporal_clouds;
        self.renderer = None;
        self.present_bind_group = None;
        let settings = SceneRendererSettings {
            timestamps: self.timestamps,
            temporal_clouds,
            ..Default::default()
        };
        let mut renderer = SceneRenderer::new(&self.device, &self.queue, scene, settings)
            .map_err(|e| e.to_string())?;
        renderer
            .prepare(&self.queue, scene)
            .map_err(|e| e.to_string())?;
        self.present_bind_group = Some(self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("skyscape view present"),
            layout: &self.present.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.present_uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: renderer.pixel_buffer().as_entire_binding(),
                },
            ],
        }));
        self.renderer = Some(renderer);
        self.renderers_built += 1;
        Ok(true)
    }

    /// Draws a frame: the scene (when a renderer is prepared), then the overlay; with
    /// `shoot`, reads back what the surface shows under the overlay. `Ok(None)` when
    /// the surface gave no texture this time (occluded, timed out, reconfigured).
    pub(crate) fn draw(
        &mut self,
        scene: Option<&PreparedScene>,
        overlay: Option<OverlayFrame>,
        shoot: bool,
    ) -> Result<Option<Option<Shot>>, String> {
        let texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&self.device, &self.config);
                return Ok(None);
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(None);
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                return Err("the window's surface raised a validation error".into());
            }
        };
        let view = texture.texture.create_view(&Default::default());
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let drawn = match (&mut self.renderer, scene) {
            (Some(renderer), Some(scene)) => {
                renderer.encode(&mut encoder).map_err(|e| e.to_string())?;
                let (width, height) = (scene.camera.width, scene.camera.height);
                let srgb = u32::from(self.config.format.is_srgb());
                let uniforms = [
                    width,
                    height,
                    self.config.width,
                    self.config.height,
                    srgb,
                    0,
                    0,
                    0,
                ];
                self.queue
                    .write_buffer(&self.present_uniforms, 0, bytemuck::cast_slice(&uniforms));
                true
            }
            _ => false,
        };
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("skyscape view present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.02,
                            g: 0.02,
                            b: 0.03,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            if drawn && let Some(bind_group) = &self.present_bind_group {
                pass.set_pipeline(&self.present);
                pass.set_bind_group(0, bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        let shot_buffer = if shoot && drawn {
            Some(self.copy_surface(&mut encoder, &texture.texture))
        } else {
            None
        };
        if let Some(mut frame) = overlay {
            for (id, deltas) in &frame.textures.set {
                for delta in deltas {
                    self.overlay
                        .update_texture(&self.device, &self.queue, *id, delta);
                }
            }
            let commands = self.overlay.update_buffers(
                &self.device,
                &self.queue,
                &mut encoder,
                &frame.primitives,
                &frame.screen,
            );
            {
                let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("skyscape view overlay"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Load,
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    ..Default::default()
                });
                self.overlay.render(
                    &mut pass.forget_lifetime(),
                    &frame.primitives,
                    &frame.screen,
                );
            }
            for id in &frame.textures.free {
                self.overlay.free_texture(id);
            }
            frame.textures.clear();
            self.queue
                .submit(commands.into_iter().chain([encoder.finish()]));
        } else {
            self.queue.submit([encoder.finish()]);
        }
        let shot = match (shot_buffer, scene) {
            (Some(buffer), Some(scene)) => Some(self.read_shot(buffer, scene)?),
            _ => None,
        };
        self.queue.present(texture);
        Ok(Some(shot))
    }

    /// GPU seconds per pass of the last frame, when the device has timestamps.
    pub(crate) fn pass_seconds(&self) -> Vec<(&'static str, f64)> {
        self.renderer
            .as_ref()
            .and_then(SceneRenderer::pass_seconds)
            .and_then(Result::ok)
            .unwrap_or_default()
    }

    /// Records a copy of the surface (when it allows copies) into a buffer; else the
    /// scene's display pixels, which the surface shows one for one at scale 1.
    fn copy_surface(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
    ) -> (wgpu::Buffer, u32, bool) {
        if !self.config.usage.contains(wgpu::TextureUsages::COPY_SRC) {
            let renderer = self.renderer.as_ref().expect("drawn with a renderer");
            let pixels = renderer.pixel_buffer();
            let copy = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("skyscape view shot"),
                size: pixels.size(),
                usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            encoder.copy_buffer_to_buffer(pixels, 0, &copy, 0, pixels.size());
            return (copy, 0, false);
        }
        let (buffer, padded) = copy_texture(&self.device, encoder, texture, 4);
        (buffer, padded, true)
    }

    fn read_shot(
        &self,
        (buffer, padded, from_surface): (wgpu::Buffer, u32, bool),
        scene: &PreparedScene,
    ) -> Result<Shot, String> {
        let bytes = read_buffer(&self.device, &self.queue, &buffer)?;
        let (size, pixels) = if from_surface {
            let (width, height) = (self.config.width, self.config.height);
            let bgra = matches!(
                self.config.format,
                wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
            );
            let pixels = bytes
                .chunks(padded as usize)
                .flat_map(|line| line[..width as usize * 4].chunks(4))
                .map(|p| {
                    let [r, g, b] = if bgra {
                        [p[2], p[1], p[0]]
                    } else {
                        [p[0], p[1], p[2]]
                    };
                    u32::from_le_bytes([r, g, b, 255])
                })
                .collect();
            ((width, height), pixels)
        } else {
            (
                (scene.camera.width, scene.camera.height),
                bytemuck::cast_slice(&bytes).to_vec(),
            )
        };
        let renderer = self.renderer.as_ref().ok_or("no renderer")?;
        let exposure = scene.present.exposure;
        let radiance = read_radiance(&self.device, &self.queue, renderer.radiance_texture())?
            .iter()
            .map(|p| p.map(|v| v / exposure))
            .collect();
        Ok(Shot {
            size,
            pixels,
            radiance,
            radiance_size: (scene.camera.width, scene.camera.height),
        })
    }
}

/// The pipeline that draws the display pixels over the surface, and its uniforms.
fn present_pipeline(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
) -> Result<(wgpu::RenderPipeline, wgpu::Buffer), String> {
    let source = render::composer()
        .compose_module("render::window_present")
        .map_err(|e| e.to_string())?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("skyscape view present"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("skyscape view present"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape view present uniforms"),
        size: 32,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    Ok((pipeline, uniforms))
}
