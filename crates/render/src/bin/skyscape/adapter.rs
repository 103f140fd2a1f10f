//! The GPU adapter: which backends, the device, reading a frame back, and a frame drawn
//! on the GPU or the CPU.

use crate::*;

/// The backends named by `--backend` or `WGPU_BACKEND`; a name wgpu does not know is
/// an error, not a silent fallback to the CPU.
pub(crate) fn backends(flag: Option<&str>) -> Result<wgpu::Backends, Failure> {
    const KNOWN: &[&str] = &[
        "vulkan",
        "vk",
        "gl",
        "gles",
        "opengl",
        "metal",
        "mtl",
        "dx12",
        "d3d12",
        "webgpu",
        "primary",
        "secondary",
        "all",
    ];
    let (value, source) = match flag {
        Some(value) => (value.to_owned(), "--backend"),
        None => match std::env::var("WGPU_BACKEND") {
            Ok(value) => (value, "WGPU_BACKEND"),
            Err(_) => return Ok(wgpu::Backends::all()),
        },
    };
    for name in value.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        if !KNOWN.contains(&name.to_ascii_lowercase().as_str()) {
            return Err(Failure::Input(format!(
                "{source} = \"{value}\": `{name}` is not a backend (vulkan, gl, metal, dx12)"
            )));
        }
    }
    let backends = wgpu::Backends::from_comma_list(&value);
    if backends.is_empty() {
        return Err(Failure::Input(format!(
            "{source} = \"{value}\": names no backend"
        )));
    }
    Ok(backends)
}

pub(crate) fn instance(backends: wgpu::Backends) -> wgpu::Instance {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    descriptor.backends = backends;
    wgpu::Instance::new(descriptor)
}

pub(crate) fn describe(info: &wgpu::AdapterInfo) -> String {
    let kind = if info.device_type == wgpu::DeviceType::Cpu {
        "a CPU adapter (software rasteriser)"
    } else {
        "the GPU"
    };
    format!("{kind}: {} ({:?})", info.name, info.backend)
}

pub(crate) fn adapters_command(backend: Option<&str>) -> Result<(), Failure> {
    let instance = instance(backends(backend)?);
    let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()));
    if adapters.is_empty() {
        println!("no adapter: skyscape renders on the CPU reference renderer");
    }
    for adapter in &adapters {
        let info = adapter.get_info();
        println!(
            "{:?} {:?} {} ({})",
            info.backend, info.device_type, info.name, info.driver
        );
    }
    match pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
        &instance, None,
    )) {
        Ok(adapter) => println!("chosen: {}", describe(&adapter.get_info())),
        Err(_) if !adapters.is_empty() => println!("chosen: none usable"),
        Err(_) => {}
    }
    Ok(())
}

/// A device on the first adapter wgpu finds for `backends`, with timestamps when the
/// adapter has them, and what it is.
pub(crate) fn open_device(
    backends: wgpu::Backends,
) -> Result<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo), String> {
    let instance = instance(backends);
    let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
        &instance, None,
    ))
    .map_err(|e| format!("no GPU adapter: {e}"))?;
    let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("skyscape"),
        required_features: features,
        required_limits: adapter.limits(),
        ..Default::default()
    }))
    .map_err(|e| format!("no device on {}: {e}", adapter.get_info().name))?;
    Ok((device, queue, adapter.get_info()))
}

/// Reads a `COPY_SRC` buffer back (blocks on the device).
pub(crate) fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
) -> Result<Vec<u8>, String> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = sender.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("waiting for the GPU: {e}"))?;
    receiver
        .recv()
        .map_err(|e| e.to_string())?
        .map_err(|e| format!("reading back: {e}"))?;
    let bytes = staging
        .get_mapped_range(..)
        .map_err(|e| e.to_string())?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}

/// Records a copy of `texture` (`COPY_SRC`, `bytes_per_texel` a texel) into a new
/// buffer whose rows are padded to wgpu's copy alignment; returns it and its row pitch.
pub(crate) fn copy_texture(
    device: &wgpu::Device,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    bytes_per_texel: u32,
) -> (wgpu::Buffer, u32) {
    let size = texture.size();
    let row = size.width * bytes_per_texel;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape texture copy"),
        size: u64::from(padded) * u64::from(size.height),
        usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: None,
            },
        },
        size,
    );
    (buffer, padded)
}

/// The GPU frame's HDR radiance (rgba16float) as f32 RGB.
pub(crate) fn read_radiance(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 3]>, String> {
    let row = texture.size().width * 8;
    let mut encoder = device.create_command_encoder(&Default::default());
    let (buffer, padded) = copy_texture(device, &mut encoder, texture, 8);
    queue.submit([encoder.finish()]);
    let bytes = read_buffer(device, queue, &buffer)?;
    Ok(bytes
        .chunks(padded as usize)
        .flat_map(|line| {
            let f = |b: &[u8]| half::f16::from_bits(u16::from_le_bytes([b[0], b[1]])).to_f32();
            line[..row as usize]
                .chunks(8)
                .map(|t| [f(&t[0..2]), f(&t[2..4]), f(&t[4..6])])
                .collect::<Vec<_>>()
        })
        .collect())
}

/// One rendered frame.
pub(crate) struct Rendered {
    pub(crate) pixels: Vec<u32>,
    pub(crate) radiance: Option<Vec<[f32; 3]>>,
    pub(crate) device: String,
    pub(crate) pass_seconds: Vec<(&'static str, f64)>,
}

/// The GPU side of a run: the device, opened on the first frame, and the scene
/// renderer, kept for the next frame while it accepts that frame's scene (an
/// animation's frames whose sun moved; `SceneRenderer::prepare` refuses a scene that
/// needs other passes, tables or terrain, and then a new renderer is built).
pub(crate) struct GpuSession {
    backends: wgpu::Backends,
    timestamps: bool,
    device: Option<(wgpu::Device, wgpu::Queue, wgpu::AdapterInfo)>,
    renderer: Option<SceneRenderer>,
}

impl GpuSession {
    /// A session on `backends`; `timestamps`: time each pass.
    pub(crate) fn new(backends: wgpu::Backends, timestamps: bool) -> Self {
        Self {
            backends,
            timestamps,
            device: None,
            renderer: None,
        }
    }

    /// Draws `scene` (`want_radiance`: read back the HDR target too).
    pub(crate) fn render(
        &mut self,
        scene: &PreparedScene,
        want_radiance: bool,
    ) -> Result<Rendered, String> {
        if self.device.is_none() {
            self.device = Some(open_device(self.backends)?);
        }
        let Some((device, queue, info)) = &self.device else {
            return Err("no device".into());
        };
        let kept = match &mut self.renderer {
            Some(renderer) => renderer.prepare(queue, scene).is_ok(),
            None => false,
        };
        if !kept {
            self.renderer = None;
            let settings = SceneRendererSettings {
                timestamps: self.timestamps,
                ..Default::default()
            };
            let mut renderer =
                SceneRenderer::new(device, queue, scene, settings).map_err(|e| e.to_string())?;
            renderer.prepare(queue, scene).map_err(|e| e.to_string())?;
            self.renderer = Some(renderer);
        }
        let Some(renderer) = &mut self.renderer else {
            return Err("no renderer".into());
        };
        let mut encoder = device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder).map_err(|e| e.to_string())?;
        queue.submit([encoder.finish()]);
        let pixels =
            bytemuck::cast_slice(&read_buffer(device, queue, renderer.pixel_buffer())?).to_vec();
        let radiance = if want_radiance {
            // The target holds radiance × exposure.
            let exposure = scene.present.exposure;
            let exposed = read_radiance(device, queue, renderer.radiance_texture())?;
            Some(exposed.iter().map(|p| p.map(|v| v / exposure)).collect())
        } else {
            None
        };
        let pass_seconds = match renderer.pass_seconds() {
            Some(result) => result?,
            None => Vec::new(),
        };
        Ok(Rendered {
            pixels,
            radiance,
            device: describe(info),
            pass_seconds,
        })
    }
}

/// One frame on a new device and renderer ([`GpuSession`] for one frame).
pub(crate) fn render_gpu(
    scene: &PreparedScene,
    backends: wgpu::Backends,
    want_radiance: bool,
    timestamps: bool,
) -> Result<Rendered, String> {
    GpuSession::new(backends, timestamps).render(scene, want_radiance)
}

pub(crate) fn render_cpu(scene: &PreparedScene) -> Result<Rendered, String> {
    let (frame, radiance) =
        render::cpu_renderer::render_cpu_with_radiance(scene).map_err(|e| e.to_string())?;
    Ok(Rendered {
        pixels: frame.pixels,
        radiance: Some(radiance.iter().map(|p| p.radiance).collect()),
        device: "the CPU reference renderer".into(),
        pass_seconds: Vec::new(),
    })
}
