//! `skyscape`: renders a scene to a PNG, on the GPU when an adapter exists, else on
//! the CPU twin. Run `skyscape --help` for the options.

use render::SkyScene;
use std::path::PathBuf;
use std::process::ExitCode;

const HELP: &str = "\
skyscape — render an outdoor scene to a PNG

USAGE:
    skyscape [OPTIONS]

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
        --cpu                  render on the CPU even if a GPU adapter exists
        --compare              render on both and report how many pixels agree
    -h, --help                 print this help

ENVIRONMENT:
    WGPU_BACKEND               restrict the adapter search (vulkan, gl, …)
";

struct Options {
    scene: SkyScene,
    output: PathBuf,
    cpu_only: bool,
    compare: bool,
}

fn parse(args: &[String]) -> Result<Option<Options>, String> {
    let mut options = Options {
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
            "--cpu" => options.cpu_only = true,
            "--compare" => options.compare = true,
            other => return Err(format!("unknown option `{other}` (see --help)")),
        }
    }
    options.scene.validate().map_err(|e| e.to_string())?;
    Ok(Some(options))
}

/// Renders on the first adapter wgpu finds (honouring WGPU_BACKEND).
fn render_gpu(scene: &SkyScene) -> Result<(Vec<u32>, String), String> {
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
    let mut sky = render::gpu::SkyRenderer::new(&device).map_err(|e| e.to_string())?;
    sky.prepare(&device, &queue, scene)
        .map_err(|e| e.to_string())?;
    let size = u64::from(scene.width) * u64::from(scene.height) * 4;
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("skyscape"),
    });
    sky.encode(&mut encoder).map_err(|e| e.to_string())?;
    let pixels = sky.pixel_buffer().ok_or("sky pass has no pixel buffer")?;
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
    Ok((out, label))
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

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
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
    let cpu = || render::sky::render_sky_cpu(scene).map_err(|e| e.to_string());
    let result = if options.cpu_only {
        cpu().map(|p| (p, "the CPU twin (--cpu)".to_string()))
    } else {
        match render_gpu(scene) {
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
            (Ok(reference), false) if device.starts_with("the CPU twin") => {
                let _ = reference;
                println!("--compare: no GPU image to compare with");
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
