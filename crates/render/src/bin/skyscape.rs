//! `skyscape`: renders a scene to a PNG, on the GPU when an adapter exists, else on
//! the CPU twin. Run `skyscape --help` for the options.

use render::SkyScene;
use std::path::PathBuf;
use std::process::ExitCode;

const HELP: &str = "\
skyscape — render an outdoor scene to a PNG

USAGE:
    skyscape [OPTIONS]
    skyscape render SCENE.toml [-o OUT.png] [--width N] [--height N]
                               a scene file (sky + terrain) on the CPU reference
                               renderer; see docs/scenes.md and scenes/default.toml

With no options, renders the default scene (a clear afternoon seen from 2 m above
the ground: sky with seed 000's closed-form Rayleigh + Mie scattering, the sun and
its glow, the ground through aerial perspective) to target/skyscape/default.png.

OPTIONS:
    -o, --output PATH          where to write the PNG [target/skyscape/default.png]
        --width N              image width in pixels [960]
        --height N             image height in pixels [540]
        --sun-elevation DEG    sun elevation above the horizon, degrees [20.05]
        --sun-azimuth DEG      sun azimuth from north towards east, degrees [34.4]
        --view-elevation DEG   camera pitch, degrees [20.05]
        --view-azimuth DEG     camera heading from north towards east, degrees [0]
        --fov DEG              vertical field of view, degrees [80.2]
        --altitude M           camera altitude above the ground, metres [2]
        --exposure X           exposure before the 1 − exp(−x) tone map [20]
        --mie-scale X          multiply Mie scattering (haze) by X [1]
        --mie-g G              Mie anisotropy, |G| < 1 [0.8]
        --seed N               dither seed [0]
        --rung NAME            which model of the atmosphere renders the sky [sky]:
                                 sky                 seed 000's closed form with the lit
                                                     ground and the sun (the default image)
                                 closed-form         ladder rung 1, per pixel
                                 closed-form-vertex  ladder rung 1, per vertex of a 16×32 dome
                                 single              ladder rung 2, single scattering (32/8)
                                 precomputed         ladder rung 3, Hillaire-style LUTs
                                 reference           ladder rung 4, the f64 reference (CPU
                                                     only, slow: use a small --width/--height)
                                 reference-spectral  rung 4 at 18 wavelengths through the
                                                     CIE 1931 observer (CPU only, 6× slower)
                               Ladder rungs show the atmosphere alone: in-scatter, the sun
                               disc through it, the ground dark behind aerial perspective.
        --cpu                  render on the CPU even if a GPU adapter exists
        --compare              render on both and report how many pixels agree
    -h, --help                 print this help

ENVIRONMENT:
    WGPU_BACKEND               restrict the adapter search (vulkan, gl, …)
";

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rung {
    Sky,
    ClosedForm,
    ClosedFormVertex,
    Single,
    Precomputed,
    Reference,
    ReferenceSpectral,
}

impl Rung {
    fn parse(name: &str) -> Result<Self, String> {
        Ok(match name {
            "sky" => Self::Sky,
            "closed-form" => Self::ClosedForm,
            "closed-form-vertex" => Self::ClosedFormVertex,
            "single" => Self::Single,
            "precomputed" => Self::Precomputed,
            "reference" => Self::Reference,
            "reference-spectral" => Self::ReferenceSpectral,
            other => {
                return Err(format!(
                    "--rung: `{other}` is not one of sky, closed-form, closed-form-vertex, single, precomputed, reference, reference-spectral"
                ));
            }
        })
    }
}

struct Options {
    rung: Rung,
    scene: SkyScene,
    output: PathBuf,
    cpu_only: bool,
    compare: bool,
}

fn parse(args: &[String]) -> Result<Option<Options>, String> {
    let mut options = Options {
        rung: Rung::Sky,
        scene: SkyScene::default(),
        output: PathBuf::from("target/skyscape/default.png"),
        cpu_only: false,
        compare: false,
    };
    let mut iter = args.iter();
    while let Some(flag) = iter.next() {
        let mut value = || iter.next().ok_or_else(|| format!("{flag} needs a value"));
        let number = |text: &String| -> Result<f32, String> {
            text.parse::<f32>()
                .map_err(|_| format!("{flag}: `{text}` is not a number"))
        };
        let integer = |text: &String| -> Result<u32, String> {
            text.parse::<u32>()
                .map_err(|_| format!("{flag}: `{text}` is not a non-negative integer"))
        };
        let s = &mut options.scene;
        match flag.as_str() {
            "-h" | "--help" => return Ok(None),
            "-o" | "--output" => options.output = PathBuf::from(value()?),
            "--width" => s.width = integer(value()?)?,
            "--height" => s.height = integer(value()?)?,
            "--sun-elevation" => s.sun_elevation = number(value()?)?.to_radians(),
            "--sun-azimuth" => s.sun_azimuth = number(value()?)?.to_radians(),
            "--view-elevation" => s.camera_elevation = number(value()?)?.to_radians(),
            "--view-azimuth" => s.camera_azimuth = number(value()?)?.to_radians(),
            "--fov" => s.vertical_fov = number(value()?)?.to_radians(),
            "--altitude" => s.camera_altitude = number(value()?)?,
            "--exposure" => s.exposure = number(value()?)?,
            "--mie-scale" => {
                let scale = number(value()?)?;
                if !(scale.is_finite() && scale >= 0.0) {
                    return Err(format!("--mie-scale: {scale} must be a finite number ≥ 0"));
                }
                s.atmosphere.mie_scattering *= scale;
            }
            "--mie-g" => s.atmosphere.mie_g = number(value()?)?,
            "--seed" => s.dither_seed = integer(value()?)?,
            "--rung" => options.rung = Rung::parse(value()?)?,
            "--cpu" => options.cpu_only = true,
            "--compare" => options.compare = true,
            other => return Err(format!("unknown option `{other}` (see --help)")),
        }
    }
    options.scene.validate().map_err(|e| e.to_string())?;
    Ok(Some(options))
}

/// The first adapter wgpu finds (honouring WGPU_BACKEND), its device and a label
/// saying what kind of adapter it is.
fn open_device() -> Result<(wgpu::Device, wgpu::Queue, String), String> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
        &instance, None,
    ))
    .map_err(|e| format!("no GPU adapter: {e}"))?;
    let info = adapter.get_info();
    let kind = if info.device_type == wgpu::DeviceType::Cpu {
        "a CPU adapter (software rasteriser)"
    } else {
        "the GPU"
    };
    let label = format!("{kind}: {} ({:?})", info.name, info.backend);
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("skyscape"),
        ..Default::default()
    }))
    .map_err(|e| format!("adapter {} refused a device: {e}", info.name))?;
    Ok((device, queue, label))
}

/// Copies a pixel buffer back (the binary owns its device, so it may submit and wait).
fn read_pixels(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mut encoder: wgpu::CommandEncoder,
    pixels: &wgpu::Buffer,
    count: usize,
) -> Result<Vec<u32>, String> {
    let size = 4 * count as u64;
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_buffer_to_buffer(pixels, 0, &readback, 0, size);
    queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    readback.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = sender.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("waiting for the GPU: {e}"))?;
    receiver
        .recv()
        .map_err(|e| e.to_string())?
        .map_err(|e| format!("mapping the pixels: {e}"))?;
    let view = readback.get_mapped_range(..).map_err(|e| e.to_string())?;
    let out = bytemuck::cast_slice::<u8, u32>(&view).to_vec();
    drop(view);
    readback.unmap();
    Ok(out)
}

/// Renders the default sky pass on the GPU.
fn render_gpu(scene: &SkyScene) -> Result<(Vec<u32>, String), String> {
    let (device, queue, label) = open_device()?;
    let mut sky = render::gpu::SkyRenderer::new(&device).map_err(|e| e.to_string())?;
    sky.prepare(&device, &queue, scene)
        .map_err(|e| e.to_string())?;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("skyscape"),
    });
    sky.encode(&mut encoder).map_err(|e| e.to_string())?;
    let pixels = sky.pixel_buffer().ok_or("sky pass has no pixel buffer")?;
    let count = scene.width as usize * scene.height as usize;
    Ok((read_pixels(&device, &queue, encoder, pixels, count)?, label))
}

/// The scene's atmosphere as an `atmos::Atmosphere` (Earth, with the scene's haze,
/// anisotropy, albedo and sun).
fn ladder_atmosphere(scene: &SkyScene) -> atmos::Atmosphere {
    let a = &scene.atmosphere;
    let mut atmosphere = atmos::Atmosphere::earth();
    let earth_mie = atmosphere.mie_scattering[0];
    let haze = f64::from(a.mie_scattering) / earth_mie;
    atmosphere.planet_radius = f64::from(a.planet_radius);
    atmosphere.top_radius = atmosphere.planet_radius + 100_000.0;
    atmosphere.rayleigh_scattering = a.rayleigh_scattering.map(f64::from);
    atmosphere.rayleigh_scale_height = f64::from(a.rayleigh_scale_height);
    atmosphere.mie_scattering = atmosphere.mie_scattering.map(|b| b * haze);
    atmosphere.mie_extinction = atmosphere.mie_extinction.map(|b| b * haze);
    atmosphere.mie_scale_height = f64::from(a.mie_scale_height);
    atmosphere.mie_g = f64::from(a.mie_g);
    atmosphere.ground_albedo = [f64::from(a.ground_albedo); 3];
    atmosphere.sun_irradiance = a.sun_irradiance.map(f64::from);
    atmosphere.sun_angular_radius = f64::from(a.sun_angular_radius);
    atmosphere
}

/// The scene's camera as an `atmos` frame camera (the scene's frame is y-up).
fn ladder_camera(scene: &SkyScene) -> Result<atmos::frame::FrameCamera, String> {
    let d = |v: glam::Vec3| v.as_dvec3();
    let position = glam::DVec3::new(
        0.0,
        f64::from(scene.atmosphere.planet_radius) + f64::from(scene.camera_altitude),
        0.0,
    );
    atmos::frame::FrameCamera::look_at(
        position,
        d(render::sky::direction_from_angles(
            scene.camera_elevation,
            scene.camera_azimuth,
        )),
        glam::DVec3::Y,
        f64::from(scene.vertical_fov),
        scene.width,
        scene.height,
        d(render::sky::direction_from_angles(
            scene.sun_elevation,
            scene.sun_azimuth,
        )),
        None,
    )
    .map_err(|e| e.to_string())
}

const DOME: atmos::dome::DomeResolution = atmos::dome::DomeResolution {
    rings: 16,
    segments: 32,
};

fn ladder_model(
    rung: Rung,
    atmosphere: &atmos::Atmosphere,
) -> Result<Box<dyn atmos::SkyModel + Sync>, String> {
    let e = |e: atmos::AtmosError| e.to_string();
    Ok(match rung {
        Rung::Sky | Rung::ClosedForm => {
            Box::new(atmos::closed_form_sky::ClosedFormSky::new(atmosphere).map_err(e)?)
        }
        Rung::ClosedFormVertex => Box::new(
            atmos::dome::DomeInterpolated::new(
                atmos::closed_form_sky::ClosedFormSky::new(atmosphere).map_err(e)?,
                DOME,
                atmosphere,
            )
            .map_err(e)?,
        ),
        Rung::Single => Box::new(
            atmos::single_scattering::SingleScatteringSky::new(atmosphere, Default::default())
                .map_err(e)?,
        ),
        Rung::Precomputed => {
            Box::new(atmos::lut::PrecomputedSky::new(atmosphere, &Default::default()).map_err(e)?)
        }
        Rung::Reference => Box::new(
            atmos::reference::ReferenceSky::new(atmosphere, Default::default()).map_err(e)?,
        ),
        Rung::ReferenceSpectral => Box::new(
            atmos::reference::SpectralReferenceSky::new(atmosphere, Default::default())
                .map_err(e)?,
        ),
    })
}

fn render_ladder_cpu(rung: Rung, scene: &SkyScene) -> Result<Vec<u32>, String> {
    let atmosphere = ladder_atmosphere(scene);
    let camera = ladder_camera(scene)?;
    let present =
        render::present::PresentParameters::new(&atmosphere, scene.exposure, scene.dither_seed)
            .map_err(|e| e.to_string())?;
    let model = ladder_model(rung, &atmosphere)?;
    render::present::render_model_cpu(model.as_ref(), atmosphere.planet_radius, &camera, &present)
        .map_err(|e| e.to_string())
}

fn render_ladder_gpu(rung: Rung, scene: &SkyScene) -> Result<(Vec<u32>, String), String> {
    let e = |e: atmos::AtmosError| e.to_string();
    let atmosphere = ladder_atmosphere(scene);
    let camera = ladder_camera(scene)?;
    let present =
        render::present::PresentParameters::new(&atmosphere, scene.exposure, scene.dither_seed)
            .map_err(|e| e.to_string())?;
    let (device, queue, label) = open_device()?;
    let frame = atmos::gpu::FrameOutput::new(&device, scene.width, scene.height).map_err(e)?;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("skyscape ladder"),
    });
    match rung {
        Rung::Sky | Rung::ClosedForm | Rung::ClosedFormVertex => {
            let frequency = if rung == Rung::ClosedFormVertex {
                atmos::gpu::EvaluationFrequency::PerVertex(DOME)
            } else {
                atmos::gpu::EvaluationFrequency::PerPixel
            };
            let mut sky =
                atmos::gpu::ClosedFormRenderer::new(&device, &atmosphere, frequency).map_err(e)?;
            sky.prepare(&queue, &camera, &frame).map_err(e)?;
            sky.encode(&mut encoder, None).map_err(e)?;
        }
        Rung::Precomputed => {
            let mut sky = atmos::gpu::precomputed::PrecomputedRenderer::new(
                &device,
                &atmosphere,
                Default::default(),
            )
            .map_err(e)?;
            sky.prepare(&queue, &camera, &frame).map_err(e)?;
            sky.encode(&mut encoder, None).map_err(e)?;
        }
        Rung::Single => {
            let mut sky = atmos::gpu::single_scattering::SingleScatteringRenderer::new(
                &device,
                &atmosphere,
                Default::default(),
            )
            .map_err(e)?;
            sky.prepare(&queue, &camera, &frame).map_err(e)?;
            sky.encode(&mut encoder, None).map_err(e)?;
        }
        Rung::Reference | Rung::ReferenceSpectral => {
            return Err("the reference rung runs on the CPU only".into());
        }
    }
    let mut presenter = render::gpu::Presenter::new(&device).map_err(|e| e.to_string())?;
    presenter
        .prepare(&queue, &camera, &present, &frame)
        .map_err(|e| e.to_string())?;
    presenter.encode(&mut encoder).map_err(|e| e.to_string())?;
    let pixels = presenter
        .pixel_buffer()
        .ok_or("present pass has no pixel buffer")?;
    Ok((
        read_pixels(&device, &queue, encoder, pixels, camera.pixel_count())?,
        label,
    ))
}

fn write_png(path: &PathBuf, scene: &SkyScene, pixels: &[u32]) -> Result<(), String> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| format!("creating {}: {e}", parent.display()))?;
    }
    let bytes: Vec<u8> = pixels.iter().flat_map(|p| p.to_le_bytes()).collect();
    image::save_buffer(
        path,
        &bytes,
        scene.width,
        scene.height,
        image::ExtendedColorType::Rgba8,
    )
    .map_err(|e| format!("writing {}: {e}", path.display()))
}

/// `skyscape render SCENE [-o OUT] [--width N] [--height N]`: a scene file drawn by
/// the CPU reference renderer (`render::cpu_renderer`; the GPU scene passes are to
/// come). Bad input exits with code 2, naming the line, column, field and value.
fn render_scene_command(args: &[String]) -> ExitCode {
    const USAGE: &str = "usage: skyscape render SCENE.toml [-o OUT.png] [--width N] [--height N]";
    let mut scene_path = None;
    let mut output = None;
    let mut size = [None, None];
    let mut iter = args.iter();
    while let Some(arg) = iter.next() {
        let mut value = || {
            iter.next()
                .ok_or_else(|| format!("{arg} needs a value ({USAGE})"))
        };
        let parsed = match arg.as_str() {
            "-h" | "--help" => {
                println!(
                    "{USAGE}\nScene files: docs/scenes.md; the shipped one: scenes/default.toml"
                );
                return ExitCode::SUCCESS;
            }
            "-o" | "--output" => value().map(|v| output = Some(PathBuf::from(v))),
            "--width" | "--height" => value().and_then(|v| {
                let n = v
                    .parse::<u32>()
                    .map_err(|_| format!("{arg}: `{v}` is not a non-negative integer"))?;
                size[usize::from(arg == "--height")] = Some(n);
                Ok(())
            }),
            other if other.starts_with('-') => Err(format!("unknown option `{other}` ({USAGE})")),
            other if scene_path.is_none() => {
                scene_path = Some(PathBuf::from(other));
                Ok(())
            }
            other => Err(format!("unexpected argument `{other}` ({USAGE})")),
        };
        if let Err(message) = parsed {
            eprintln!("skyscape render: {message}");
            return ExitCode::from(2);
        }
    }
    let Some(scene_path) = scene_path else {
        eprintln!("skyscape render: no scene file ({USAGE})");
        return ExitCode::from(2);
    };
    let mut scene = match render::scene::Scene::open(&scene_path) {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("skyscape render: {}: {e}", scene_path.display());
            return ExitCode::from(2);
        }
    };
    let out = &mut scene.file.output;
    out.width = size[0].unwrap_or(out.width);
    out.height = size[1].unwrap_or(out.height);
    // A folder the user names must exist; the default one is created.
    let output = match output.or_else(|| out.path.clone()) {
        Some(path) => path,
        None => {
            let default = PathBuf::from("target/skyscape/scene.png");
            if let Err(e) = std::fs::create_dir_all("target/skyscape") {
                eprintln!("skyscape render: creating target/skyscape: {e}");
                return ExitCode::FAILURE;
            }
            default
        }
    };
    let start = std::time::Instant::now();
    let prepared = match scene.prepare() {
        Ok(prepared) => prepared,
        Err(e) => {
            eprintln!("skyscape render: {}: {e}", scene_path.display());
            return ExitCode::from(2);
        }
    };
    let frame = match render::cpu_renderer::render_cpu(&prepared) {
        Ok(frame) => frame,
        Err(e) => {
            eprintln!("skyscape render: {e}");
            return ExitCode::FAILURE;
        }
    };
    if let Err(e) = render::cpu_renderer::write_png(&output, &frame) {
        eprintln!("skyscape render: writing {}: {e}", output.display());
        return ExitCode::from(2);
    }
    println!(
        "rendered {} ({}×{}, {}) on the CPU reference renderer in {:.2} s\nwrote {}",
        scene_path.display(),
        frame.width,
        frame.height,
        prepared.sky_model.label(),
        start.elapsed().as_secs_f64(),
        output.display()
    );
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("render") {
        return render_scene_command(&args[1..]);
    }
    let options = match parse(&args) {
        Ok(Some(options)) => options,
        Ok(None) => {
            print!("{HELP}");
            return ExitCode::SUCCESS;
        }
        Err(message) => {
            eprintln!("skyscape: {message}");
            return ExitCode::FAILURE;
        }
    };
    let scene = &options.scene;
    let rung = options.rung;
    // --compare checks the GPU image against the CPU twin: without a GPU image it would
    // compare the CPU image with itself and report 100 %.
    if options.compare {
        let conflict = if options.cpu_only {
            Some("--cpu renders no GPU image".to_string())
        } else if matches!(rung, Rung::Reference | Rung::ReferenceSpectral) {
            Some("the reference rungs have no GPU version".to_string())
        } else {
            None
        };
        if let Some(conflict) = conflict {
            eprintln!(
                "skyscape: --compare compares the GPU image with the CPU twin, but {conflict}"
            );
            return ExitCode::from(2);
        }
    }
    let cpu = || match rung {
        Rung::Sky => render::sky::render_sky_cpu(scene).map_err(|e| e.to_string()),
        _ => render_ladder_cpu(rung, scene),
    };
    let result = if matches!(rung, Rung::Reference | Rung::ReferenceSpectral) {
        cpu().map(|p| {
            (
                p,
                "the CPU (the reference rung has no GPU version)".to_string(),
            )
        })
    } else if options.cpu_only {
        cpu().map(|p| (p, "the CPU twin (--cpu)".to_string()))
    } else {
        let gpu = match rung {
            Rung::Sky => render_gpu(scene),
            _ => render_ladder_gpu(rung, scene),
        };
        match gpu {
            Ok(done) => Ok(done),
            Err(reason) => {
                eprintln!("skyscape: {reason}; rendering on the CPU twin instead");
                cpu().map(|p| (p, "the CPU twin (no GPU adapter)".to_string()))
            }
        }
    };
    let (pixels, device) = match result {
        Ok(done) => done,
        Err(message) => {
            eprintln!("skyscape: {message}");
            return ExitCode::FAILURE;
        }
    };
    if let Err(message) = write_png(&options.output, scene, &pixels) {
        eprintln!("skyscape: {message}");
        return ExitCode::FAILURE;
    }
    println!(
        "rendered {}×{} on {device}\nwrote {}",
        scene.width,
        scene.height,
        options.output.display()
    );
    if options.compare {
        match (cpu(), options.cpu_only) {
            (Ok(_), _) if device.starts_with("the CPU twin") => {
                eprintln!(
                    "skyscape: --compare: no GPU adapter, so there is no GPU image to compare \
                     with the CPU twin"
                );
                return ExitCode::FAILURE;
            }
            (Ok(reference), _) => {
                let agreement = |lsb| {
                    render::tonemap::fraction_within_lsb(&pixels, &reference, lsb)
                        .map(|fraction| 100.0 * fraction)
                };
                match (agreement(2), agreement(0)) {
                    (Ok(close), Ok(identical)) => println!(
                        "--compare: {close:.4} % of pixels within 2 LSB of the CPU twin, \
                         {identical:.4} % identical"
                    ),
                    (Err(e), _) | (_, Err(e)) => {
                        eprintln!("skyscape: {e}");
                        return ExitCode::FAILURE;
                    }
                }
            }
            (Err(message), _) => {
                eprintln!("skyscape: {message}");
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}
