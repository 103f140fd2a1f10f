//! `skyscape`: renders an outdoor scene (a scene file, or a shipped scene by name) to
//! a PNG or an OpenEXR, on the GPU when an adapter exists, on the CPU reference
//! renderer otherwise or with `--cpu`. `skyscape --help` lists the commands.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};
use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::scene::shipped::{SHIPPED, shipped};
use render::scene::{PreparedScene, Scene};

#[derive(Debug, Parser)]
#[command(
    name = "skyscape",
    version,
    about = "Render an outdoor scene: sky, terrain and the atmosphere between",
    long_about = "Render an outdoor scene — sky and aerial perspective from atmospheric \
                  scattering, terrain with self-shadows — from a TOML scene file or a \
                  shipped scene. With no command, renders the default scene.\n\n\
                  Scene files: docs/scenes.md. Environment: WGPU_BACKEND restricts the \
                  adapter search (vulkan, gl, metal, dx12)."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Render a scene (a .toml file or a shipped scene's name; default: "default").
    Render(RenderArgs),
    /// Say which passes a scene runs on the GPU, which it skips and why, and what each
    /// costs (measured with GPU timestamps on the chosen adapter).
    Explain {
        /// The scene: a .toml file or a shipped scene's name.
        scene: String,
        /// Restrict the adapter search to these backends (vulkan, gl, metal, dx12).
        #[arg(long)]
        backend: Option<String>,
    },
    /// List the shipped scenes.
    Scenes,
    /// List the adapters wgpu finds and which one skyscape would use.
    Adapters {
        /// Restrict the search to these backends.
        #[arg(long)]
        backend: Option<String>,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Format {
    /// 8-bit sRGB, tone-mapped and dithered.
    Png,
    /// 32-bit float linear radiance (the unit of the sun's irradiance per sr).
    Exr,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum ProjectionArg {
    Rectilinear,
    Cubemap,
    Equirectangular,
    Fisheye,
}

#[derive(Debug, Args, Default)]
struct RenderArgs {
    /// The scene: a .toml file or a shipped scene's name (`skyscape scenes`).
    scene: Option<String>,
    /// Where to write the image [the scene's output.path, else target/skyscape/NAME.png].
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Image width, pixels (overrides the scene's).
    #[arg(long)]
    width: Option<u32>,
    /// Image height, pixels (overrides the scene's).
    #[arg(long)]
    height: Option<u32>,
    /// Output format [from the output's extension, else png].
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// The output's projection (overrides the scene's): rectilinear, cubemap (a 6:1
    /// strip; width = 6 × height), equirectangular, fisheye.
    #[arg(long, value_enum)]
    projection: Option<ProjectionArg>,
    /// Render on the CPU reference renderer even if a GPU adapter exists.
    #[arg(long)]
    cpu: bool,
    /// Render on the GPU and on the CPU and report how many pixels agree.
    #[arg(long, conflicts_with = "cpu")]
    compare: bool,
    /// Print the passes that run and their measured GPU cost.
    #[arg(long)]
    explain: bool,
    /// The atmosphere's rung (overrides the scene's): closed-form, closed-form-vertex,
    /// single, precomputed, reference, reference-spectral.
    #[arg(long)]
    rung: Option<String>,
    /// The sun's elevation, degrees (overrides the scene's).
    #[arg(long, allow_negative_numbers = true)]
    sun_elevation_deg: Option<f64>,
    /// The sun's azimuth clockwise from north, degrees (overrides the scene's).
    #[arg(long, allow_negative_numbers = true)]
    sun_azimuth_deg: Option<f64>,
    /// Exposure before the 1 − exp(−x) tone map (overrides the scene's).
    #[arg(long)]
    exposure: Option<f32>,
    /// Render this many frames of the scene's animation (numbered files).
    #[arg(long)]
    frames: Option<u32>,
    /// Only frames a..b (half-open) of the animation, to split it across machines.
    #[arg(long, value_parser = parse_range)]
    frame_range: Option<(u32, u32)>,
    /// Create the output's folder if it does not exist (otherwise a missing folder is
    /// an error).
    #[arg(long)]
    mkdir: bool,
    /// Restrict the adapter search to these backends (vulkan, gl, metal, dx12).
    #[arg(long)]
    backend: Option<String>,
}

fn parse_range(text: &str) -> Result<(u32, u32), String> {
    let (a, b) = text
        .split_once("..")
        .ok_or_else(|| format!("`{text}` is not a range a..b"))?;
    let parse = |s: &str| {
        s.parse::<u32>()
            .map_err(|_| format!("`{s}` in `{text}` is not a frame number"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    if a >= b {
        return Err(format!("`{text}`: the range must not be empty (a < b)"));
    }
    Ok((a, b))
}

/// A failure: bad input (exit 2, the message names the field and value) or a runtime
/// failure (exit 1).
enum Failure {
    Input(String),
    Runtime(String),
}

impl Failure {
    fn exit(self) -> ExitCode {
        match self {
            Failure::Input(message) => {
                eprintln!("skyscape: {message}");
                ExitCode::from(2)
            }
            Failure::Runtime(message) => {
                eprintln!("skyscape: {message}");
                ExitCode::FAILURE
            }
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => render_command(RenderArgs::default()),
        Some(Command::Render(args)) => render_command(args),
        Some(Command::Explain { scene, backend }) => explain_command(&scene, backend.as_deref()),
        Some(Command::Scenes) => {
            for scene in SHIPPED {
                println!("{:<10} {}", scene.name, scene.description);
            }
            Ok(())
        }
        Some(Command::Adapters { backend }) => adapters_command(backend.as_deref()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => failure.exit(),
    }
}

/// The backends named by `--backend` or `WGPU_BACKEND`; a name wgpu does not know is
/// an error, not a silent fallback to the CPU.
fn backends(flag: Option<&str>) -> Result<wgpu::Backends, Failure> {
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

fn instance(backends: wgpu::Backends) -> wgpu::Instance {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    descriptor.backends = backends;
    wgpu::Instance::new(descriptor)
}

fn describe(info: &wgpu::AdapterInfo) -> String {
    let kind = if info.device_type == wgpu::DeviceType::Cpu {
        "a CPU adapter (software rasteriser)"
    } else {
        "the GPU"
    };
    format!("{kind}: {} ({:?})", info.name, info.backend)
}

fn adapters_command(backend: Option<&str>) -> Result<(), Failure> {
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
fn open_device(
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

/// The scene named on the command line (a file, or a shipped scene) and its name.
fn load_scene(name: Option<&str>) -> Result<(Scene, String), Failure> {
    let name = name.unwrap_or("default");
    let path = Path::new(name);
    if path.extension().is_some() || path.exists() {
        let scene =
            Scene::open(path).map_err(|e| Failure::Input(format!("{}: {e}", path.display())))?;
        let stem = path
            .file_stem()
            .map_or_else(|| "scene".to_owned(), |s| s.to_string_lossy().into_owned());
        return Ok((scene, stem));
    }
    let shipped = shipped(name).ok_or_else(|| {
        let names: Vec<&str> = SHIPPED.iter().map(|s| s.name).collect();
        Failure::Input(format!(
            "scene `{name}`: no such file, and not a shipped scene ({})",
            names.join(", ")
        ))
    })?;
    let scene = Scene::parse(shipped.source, ".")
        .map_err(|e| Failure::Input(format!("shipped scene {name}: {e}")))?;
    Ok((scene, name.to_owned()))
}

/// Applies the command line's overrides to the scene's values.
fn apply_overrides(scene: &mut Scene, args: &RenderArgs) -> Result<(), Failure> {
    let file = &mut scene.file;
    if let Some(width) = args.width {
        file.output.width = width;
    }
    if let Some(height) = args.height {
        file.output.height = height;
    }
    if let Some(projection) = args.projection {
        use render::projection::Projection;
        file.output.projection = match projection {
            ProjectionArg::Rectilinear => Projection::Rectilinear,
            ProjectionArg::Cubemap => Projection::Cubemap,
            ProjectionArg::Equirectangular => Projection::Equirectangular,
            ProjectionArg::Fisheye => Projection::Fisheye,
        };
    }
    if let Some(exposure) = args.exposure {
        file.output.exposure = exposure;
    }
    // An explicit sun replaces the scene's [time] (then no sky objects are placed).
    let current = file.sun.map(|sun| (sun.elevation_deg, sun.azimuth_deg));
    let explicit = match (args.sun_elevation_deg, args.sun_azimuth_deg, current) {
        (None, None, _) => None,
        (Some(e), Some(a), _) => Some((e, a)),
        (Some(e), None, Some((_, a))) => Some((e, a)),
        (None, Some(a), Some((e, _))) => Some((e, a)),
        (Some(_), None, None) | (None, Some(_), None) => {
            return Err(Failure::Input(
                "--sun-elevation-deg/--sun-azimuth-deg: the scene places the sun by [time]; \
                 give both to replace it with an explicit sun"
                    .into(),
            ));
        }
    };
    if let Some((elevation, azimuth)) = explicit {
        file.sun = Some(render::scene::SunSection {
            elevation_deg: elevation,
            azimuth_deg: azimuth,
        });
        file.time = None;
        file.sky_objects = None;
    }
    if let Some(rung) = &args.rung {
        file.atmosphere.rung = render::scene::Rung::from_name(rung).ok_or_else(|| {
            Failure::Input(format!(
                "--rung `{rung}`: not one of closed-form, closed-form-vertex, single, \
                 precomputed, reference, reference-spectral"
            ))
        })?;
    }
    Ok(())
}

/// `for_gpu`: only the GPU renderer will draw it (`Scene::prepare_for_gpu`: the shell
/// deck's shadow maps are left to the GPU to bake).
fn prepare(scene: &Scene, label: &str, for_gpu: bool) -> Result<PreparedScene, Failure> {
    let spinner = indicatif::ProgressBar::new_spinner().with_message(format!(
        "preparing {label}: atmosphere tables, terrain, horizon maps"
    ));
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let prepared = if for_gpu {
        scene.prepare_for_gpu()
    } else {
        scene.prepare()
    }
    .map_err(|e| Failure::Input(format!("{label}: {e}")));
    spinner.finish_and_clear();
    prepared
}

/// Where a frame goes: the given path, else the scene's, else target/skyscape/NAME;
/// numbered when the animation has several frames.
fn output_path(
    args: &RenderArgs,
    scene: &Scene,
    name: &str,
    format: Format,
    frame: Option<u32>,
) -> Result<PathBuf, Failure> {
    let extension = match format {
        Format::Png => "png",
        Format::Exr => "exr",
    };
    let (path, default) = match args
        .output
        .clone()
        .or_else(|| scene.file.output.path.clone())
    {
        Some(path) => (path, false),
        None => (
            PathBuf::from(format!("target/skyscape/{name}.{extension}")),
            true,
        ),
    };
    let path = match frame {
        Some(frame) => {
            let stem = path
                .file_stem()
                .map_or_else(|| name.into(), |s| s.to_string_lossy().into_owned());
            path.with_file_name(format!("{stem}_{frame:04}.{extension}"))
        }
        None => path,
    };
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty())
        && !parent.is_dir()
    {
        if default || args.mkdir {
            std::fs::create_dir_all(parent)
                .map_err(|e| Failure::Runtime(format!("creating {}: {e}", parent.display())))?;
        } else {
            return Err(Failure::Input(format!(
                "output `{}`: the folder {} does not exist (create it, or pass --mkdir)",
                path.display(),
                parent.display()
            )));
        }
    }
    Ok(path)
}

/// Reads a `COPY_SRC` buffer back (blocks on the device).
fn read_buffer(
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

/// The GPU frame's HDR radiance (rgba16float) as f32 RGB.
fn read_radiance(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 3]>, String> {
    let size = texture.size();
    let row = size.width * 8;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape radiance"),
        size: u64::from(padded) * u64::from(size.height),
        usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
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
struct Rendered {
    pixels: Vec<u32>,
    radiance: Option<Vec<[f32; 3]>>,
    device: String,
    pass_seconds: Vec<(&'static str, f64)>,
}

fn render_gpu(
    scene: &PreparedScene,
    backends: wgpu::Backends,
    want_radiance: bool,
    timestamps: bool,
) -> Result<Rendered, String> {
    let (device, queue, info) = open_device(backends)?;
    let settings = SceneRendererSettings {
        timestamps,
        ..Default::default()
    };
    let mut renderer =
        SceneRenderer::new(&device, &queue, scene, settings).map_err(|e| e.to_string())?;
    renderer.prepare(&queue, scene).map_err(|e| e.to_string())?;
    let mut encoder = device.create_command_encoder(&Default::default());
    renderer.encode(&mut encoder).map_err(|e| e.to_string())?;
    queue.submit([encoder.finish()]);
    let pixels =
        bytemuck::cast_slice(&read_buffer(&device, &queue, renderer.pixel_buffer())?).to_vec();
    let radiance = if want_radiance {
        // The target holds radiance × exposure.
        let exposure = scene.present.exposure;
        let exposed = read_radiance(&device, &queue, renderer.radiance_texture())?;
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
        device: describe(&info),
        pass_seconds,
    })
}

fn render_cpu(scene: &PreparedScene) -> Result<Rendered, String> {
    let radiance = render::cpu_renderer::render_radiance(scene).map_err(|e| e.to_string())?;
    let frame = render::cpu_renderer::render_cpu(scene).map_err(|e| e.to_string())?;
    Ok(Rendered {
        pixels: frame.pixels,
        radiance: Some(radiance.iter().map(|p| p.radiance).collect()),
        device: "the CPU reference renderer".into(),
        pass_seconds: Vec::new(),
    })
}

fn write(
    path: &Path,
    (width, height): (u32, u32),
    format: Format,
    rendered: &Rendered,
) -> Result<(), Failure> {
    let result = match format {
        Format::Png => render::cpu_renderer::write_png(
            path,
            &render::cpu_renderer::Frame {
                width,
                height,
                pixels: rendered.pixels.clone(),
            },
        ),
        Format::Exr => {
            let radiance = rendered.radiance.as_deref().unwrap_or_default();
            render::cpu_renderer::write_exr(path, width, height, radiance)
        }
    };
    result.map_err(|e| Failure::Input(format!("writing {}: {e}", path.display())))
}

/// A cubemap, panorama or fisheye: the six 90° faces of the scene drawn (GPU or CPU)
/// from the one preparation (`PreparedScene::look_along` turns its camera), then placed
/// or resampled (`render::projection`).
fn render_projected(
    scene: &Scene,
    view: &mut PreparedScene,
    backends: wgpu::Backends,
    on: FacesOn,
) -> Result<Rendered, Failure> {
    use render::projection::{assemble, face_size};
    let output = &scene.file.output;
    let side = face_size(output.projection, output.width, output.height);
    let camera = view.camera;
    let objects = view.sky_objects.clone();
    let gpu = if on == FacesOn::Cpu {
        None
    } else {
        match gpu_faces(view, backends, side) {
            Ok(faces) => Some(faces),
            Err(reason) if on == FacesOn::Gpu => {
                view.camera = camera;
                view.sky_objects = objects;
                return Err(Failure::Runtime(format!(
                    "--compare needs a GPU image: {reason}"
                )));
            }
            Err(reason) => {
                eprintln!("skyscape: {reason}; rendering on the CPU reference renderer");
                None
            }
        }
    };
    let faces = match gpu {
        Some(faces) => Ok(faces),
        None => cpu_faces(view, side),
    };
    // The scene's own view again, for the caller.
    view.camera = camera;
    view.sky_objects = objects;
    let (faces, device) = faces.map_err(Failure::Runtime)?;
    let radiance = assemble(
        output.projection,
        &faces,
        output.width,
        output.height,
        &camera,
        output.fisheye_fov_deg.to_radians(),
    )
    .map_err(|e| Failure::Runtime(e.to_string()))?;
    Ok(Rendered {
        pixels: render::cpu_renderer::display_pixels(&radiance, output.width, &view.present),
        radiance: Some(radiance),
        device: format!("{device} (six {side}×{side} faces)"),
        pass_seconds: Vec::new(),
    })
}

/// Where a projection's six faces are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum FacesOn {
    /// The CPU reference renderer.
    Cpu,
    /// The GPU, or the CPU (with a line on stderr) when no GPU renders them.
    GpuOrCpu,
    /// The GPU only (`--compare`).
    Gpu,
}

/// Turns `view` along the cube face `forward`: a 90° square of `side` pixels.
fn look_along_face(view: &mut PreparedScene, forward: [f64; 3], side: u32) -> Result<(), String> {
    view.look_along(
        glam::DVec3::from_array(forward),
        std::f64::consts::FRAC_PI_2,
        side,
        side,
    )
    .map_err(|e| e.to_string())
}

/// The six faces on the GPU: one device and one `SceneRenderer` for all of them (its
/// pipelines, tables, horizon maps and terrain mesh built and baked once); between faces
/// only `prepare` runs again, with the face's camera. Each face's radiance is read back
/// before the next is prepared.
fn gpu_faces(
    view: &mut PreparedScene,
    backends: wgpu::Backends,
    side: u32,
) -> Result<(Vec<render::projection::Face>, String), String> {
    use render::projection::{CUBE_FACES, Face};
    let (device, queue, info) = open_device(backends)?;
    let mut renderer: Option<SceneRenderer> = None;
    let mut faces = Vec::with_capacity(CUBE_FACES.len());
    for forward in CUBE_FACES {
        look_along_face(view, forward, side)?;
        let renderer = match &mut renderer {
            Some(renderer) => renderer,
            None => renderer.insert(
                SceneRenderer::new(&device, &queue, view, SceneRendererSettings::default())
                    .map_err(|e| e.to_string())?,
            ),
        };
        renderer.prepare(&queue, view).map_err(|e| e.to_string())?;
        let mut encoder = device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder).map_err(|e| e.to_string())?;
        queue.submit([encoder.finish()]);
        // The target holds radiance × exposure.
        let exposure = view.present.exposure;
        let exposed = read_radiance(&device, &queue, renderer.radiance_texture())?;
        faces.push(Face {
            camera: view.camera,
            radiance: exposed.iter().map(|p| p.map(|v| v / exposure)).collect(),
        });
    }
    Ok((faces, describe(&info)))
}

/// The six faces on the CPU reference renderer: each face's radiance alone (the
/// projection is tone-mapped after it is assembled).
fn cpu_faces(
    view: &mut PreparedScene,
    side: u32,
) -> Result<(Vec<render::projection::Face>, String), String> {
    use render::projection::{CUBE_FACES, Face};
    let mut faces = Vec::with_capacity(CUBE_FACES.len());
    for forward in CUBE_FACES {
        look_along_face(view, forward, side)?;
        let radiance = render::cpu_renderer::render_radiance(view).map_err(|e| e.to_string())?;
        faces.push(Face {
            camera: view.camera,
            radiance: radiance.iter().map(|p| p.radiance).collect(),
        });
    }
    Ok((faces, "the CPU reference renderer".into()))
}

fn print_passes(scene: &PreparedScene, rendered: &Rendered) {
    println!("passes ({}):", rendered.device);
    for (pass, plan) in render::passes::planned_passes(scene) {
        let time = rendered
            .pass_seconds
            .iter()
            .find(|(label, _)| *label == pass)
            .map(|(_, s)| format!("{:.3} ms", s * 1e3));
        match plan {
            Ok(what) => println!(
                "  run   {pass:<22} {:<12} {what}",
                time.unwrap_or_else(|| "(no timestamps)".into())
            ),
            Err(why) => println!("  skip  {pass:<22} {:<12} {why}", "—"),
        }
    }
}

fn render_command(args: RenderArgs) -> Result<(), Failure> {
    let backends = backends(args.backend.as_deref())?;
    let (mut scene, name) = load_scene(args.scene.as_deref())?;
    apply_overrides(&mut scene, &args)?;
    let format = args.format.unwrap_or_else(|| {
        match args
            .output
            .as_ref()
            .and_then(|p| p.extension())
            .and_then(|e| e.to_str())
        {
            Some("exr") => Format::Exr,
            _ => Format::Png,
        }
    });
    if (args.compare || args.explain)
        && !matches!(
            scene.file.atmosphere.rung,
            render::scene::Rung::Precomputed
                | render::scene::Rung::ClosedForm
                | render::scene::Rung::ClosedFormVertex
                | render::scene::Rung::Single
        )
    {
        // The reference rungs have no GPU passes: comparing would set the CPU image
        // against itself.
        return Err(Failure::Input(format!(
            "{} needs a GPU image, and rung `{}` renders on the CPU reference renderer only \
             (the GPU scene renderer draws the closed-form, closed-form-vertex, single and \
             precomputed rungs)",
            if args.compare {
                "--compare"
            } else {
                "--explain"
            },
            scene.file.atmosphere.rung.name()
        )));
    }
    let animation = scene.file.animation;
    let frames = args.frames.or(animation.map(|a| a.frames)).unwrap_or(1);
    if frames == 0 {
        return Err(Failure::Input("--frames 0: must be ≥ 1".into()));
    }
    let range = args.frame_range.unwrap_or((0, frames));
    if range.1 > frames {
        return Err(Failure::Input(format!(
            "--frame-range {}..{}: the animation has {frames} frames",
            range.0, range.1
        )));
    }
    let bar = (range.1 - range.0 > 1)
        .then(|| indicatif::ProgressBar::new(u64::from(range.1 - range.0)).with_message("frames"));
    for frame in range.0..range.1 {
        let mut frame_scene = scene.clone();
        if let Some(animation) = animation {
            animation.apply(&mut frame_scene.file, frame);
        }
        let start = std::time::Instant::now();
        let projected =
            frame_scene.file.output.projection != render::projection::Projection::Rectilinear;
        let mut prepared = prepare(
            &frame_scene,
            &name,
            !(args.cpu || args.compare || projected),
        )?;
        let gpu = if args.cpu || projected {
            None
        } else {
            match render_gpu(&prepared, backends, format == Format::Exr, args.explain) {
                Ok(rendered) => Some(rendered),
                Err(reason) if args.compare || args.explain => {
                    return Err(Failure::Runtime(format!(
                        "{} needs a GPU image: {reason}",
                        if args.compare {
                            "--compare"
                        } else {
                            "--explain"
                        }
                    )));
                }
                Err(reason) => {
                    eprintln!("skyscape: {reason}; rendering on the CPU reference renderer");
                    None
                }
            }
        };
        let rendered = match gpu {
            Some(rendered) => rendered,
            None if projected => {
                let on = match (args.cpu, args.compare) {
                    (true, _) => FacesOn::Cpu,
                    (false, true) => FacesOn::Gpu,
                    (false, false) => FacesOn::GpuOrCpu,
                };
                render_projected(&frame_scene, &mut prepared, backends, on)?
            }
            None => {
                // A GPU failure falls back here: bake what was left to the GPU.
                prepared.bake_shell_shadow_on_cpu();
                render_cpu(&prepared).map_err(Failure::Runtime)?
            }
        };
        let numbered = (frames > 1).then_some(frame);
        let path = output_path(&args, &frame_scene, &name, format, numbered)?;
        let size = (
            frame_scene.file.output.width,
            frame_scene.file.output.height,
        );
        write(&path, size, format, &rendered)?;
        if let Some(bar) = &bar {
            bar.inc(1);
        }
        println!(
            "rendered {name}{} ({}×{} {:?}, {}) on {} in {:.2} s\nwrote {}",
            numbered.map_or_else(String::new, |f| format!(" frame {f}")),
            frame_scene.file.output.width,
            frame_scene.file.output.height,
            frame_scene.file.output.projection,
            prepared.sky_model.label(),
            rendered.device,
            start.elapsed().as_secs_f64(),
            path.display()
        );
        if args.explain {
            print_passes(&prepared, &rendered);
        }
        if args.compare {
            // A projection against the CPU's six faces resampled the same way, not
            // against the scene camera's rectilinear view.
            let cpu = if projected {
                render_projected(&frame_scene, &mut prepared, backends, FacesOn::Cpu)?
            } else {
                render_cpu(&prepared).map_err(Failure::Runtime)?
            };
            let within =
                |lsb| render::tonemap::fraction_within_lsb(&rendered.pixels, &cpu.pixels, lsb);
            match (within(2), within(0)) {
                (Ok(close), Ok(identical)) => println!(
                    "--compare: {:.4} % of pixels within 2 LSB of the CPU reference renderer, \
                     {:.4} % identical",
                    100.0 * close,
                    100.0 * identical
                ),
                (Err(e), _) | (_, Err(e)) => return Err(Failure::Runtime(e.to_string())),
            }
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(())
}

fn explain_command(name: &str, backend: Option<&str>) -> Result<(), Failure> {
    let backends = backends(backend)?;
    let (scene, label) = load_scene(Some(name))?;
    let prepared = prepare(&scene, &label, false)?;
    println!(
        "{label}: {}×{}, {}, terrain {}",
        prepared.camera.width,
        prepared.camera.height,
        prepared.sky_model.label(),
        prepared.terrain.as_ref().map_or_else(
            || "none".to_owned(),
            |t| format!(
                "{}×{} texels",
                t.heightfield.width(),
                t.heightfield.height()
            )
        )
    );
    match render_gpu(&prepared, backends, false, true) {
        Ok(rendered) => print_passes(&prepared, &rendered),
        Err(reason) => {
            println!("no GPU passes ({reason}): the CPU reference renderer would draw it");
            for (pass, plan) in render::passes::planned_passes(&prepared) {
                match plan {
                    Ok(what) => println!("  (run) {pass:<22} {what}"),
                    Err(why) => println!("  skip  {pass:<22} {why}"),
                }
            }
        }
    }
    Ok(())
}
