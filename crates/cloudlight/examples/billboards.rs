//! The automaton's cumulus lit by slices and drawn as billboards (Dobashi et al. 2000).
//!
//! `cargo run -p cloudlight --example billboards` grows a cumulus with `cloudsim` (seed
//! 2026, 64×64×24 cells, 600 steps, two ellipsoids, 50 m cells), lights it with the slice
//! propagation (physical mode, sun at 60° elevation), turns every cell denser than 0.3 into
//! a billboard and draws them back to front with the CPU rasteriser, over a plain sky:
//!
//! * `target/cloudlight/billboards.png`: billboards set by the lattice
//!   (`BillboardSettings::lattice`: 3.1 cells across whatever the density, carrying the
//!   cell's optical depth through the kernel), 512×384;
//! * `target/cloudlight/billboards_density_size.png`: billboards sized 2.5 cells across at
//!   unit density (`SizeRule::World`), each a one-cell slab's opacity at its centre;
//! * `target/cloudlight/billboards_seed_size.png`: the same with Dobashi et al. 2000's size formula
//!   (`(9500·ρ/d)·ρ` pixels), whose `k` was tuned for another scene scale: in metres
//!   the particles are a pixel or two across, so the cloud looks sparse;
//! * `target/cloudlight/splat.png`: the procedural splat texture, 64×64;
//! * with a GPU adapter (lavapipe counts: `WGPU_BACKEND=vulkan`), also
//!   `target/cloudlight/billboards_gpu.png` from `gpu::billboard::BillboardPass`, its
//!   agreement with the CPU image, and the pass's time (timestamp queries; labelled a CPU
//!   adapter's time on lavapipe).

use std::path::{Path, PathBuf};
use std::time::Instant;

use cloudlight::CloudVolume;
use cloudlight::billboard::{
    Billboard, BillboardSettings, Camera, FieldOfView, Image, SizeRule, billboards, rasterise,
    splat_texture,
};
use cloudlight::gpu::billboard::BillboardPass;
use cloudlight::propagate::{SliceMode, propagate_f64};
use glam::DVec3;

const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Linear RGB of the plain sky behind the cloud.
const SKY: [f32; 3] = [0.18, 0.32, 0.62];

fn cumulus() -> CloudVolume {
    let size = cloudsim::GridSize::new(64, 64, 24);
    let mut config = cloudsim::Config::new(size);
    config.seed = 2026;
    config.ellipsoids = vec![
        cloudsim::Ellipsoid {
            center: [28.0, 32.0, 9.0],
            radii: [20.0, 18.0, 8.0],
        },
        cloudsim::Ellipsoid {
            center: [40.0, 30.0, 13.0],
            radii: [16.0, 20.0, 9.0],
        },
    ];
    let model = cloudsim::Model::new(config).expect("valid cloudsim config");
    let mut sim = cloudsim::Simulation::new(model).expect("valid cloudsim model");
    sim.advance(600).expect("cloudsim steps");
    let density = sim.density().expect("cloudsim density");
    CloudVolume::new([64, 64, 24], [0.0, 0.0, 1500.0], 50.0, 0.01, density)
        .expect("valid cloud volume")
}

fn srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// The premultiplied image over the sky, sRGB-encoded.
fn write_png(image: &Image<f32>, path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let mut bytes = Vec::with_capacity(image.rgba.len() * 3);
    for p in &image.rgba {
        for c in 0..3 {
            let linear = p[c] + (1.0 - p[3]) * SKY[c];
            bytes.push((255.0 * srgb(linear)).round() as u8);
        }
    }
    image::save_buffer(
        path,
        &bytes,
        image.width,
        image.height,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(())
}

/// Draws `particles` with the GPU pass; returns the image and the pass's median time over
/// 5 runs (timestamp queries), if the adapter has them.
fn render_gpu(
    gpu: &skyscape_harness::GpuContext,
    particles: &[Billboard],
    camera: &Camera,
    settings: &BillboardSettings,
) -> Result<(Image<f32>, Option<f64>), Box<dyn std::error::Error>> {
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("billboards"),
        size: wgpu::Extent3d {
            width: camera.width(),
            height: camera.height(),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let mut pass = BillboardPass::new(&gpu.device, FORMAT)?;
    pass.prepare(
        &gpu.device,
        &gpu.queue,
        particles,
        camera,
        settings.size,
        settings.opacity,
    )?;
    let clear = |encoder: &mut wgpu::CommandEncoder| {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("clear"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
    };
    let seconds = if gpu
        .device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY)
    {
        Some(skyscape_harness::median_pass_seconds(
            gpu,
            5,
            |encoder, timer, span| {
                clear(encoder);
                pass.encode_timed(encoder, &view, Some(timer.render_writes(span)))
                    .expect("prepared, matching target");
            },
        )?)
    } else {
        None
    };
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    clear(&mut encoder);
    pass.encode(&mut encoder, &view)?;
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_texture(gpu, "billboards", &texture)?;
    let values: Vec<f32> = bytes
        .chunks_exact(2)
        .map(|b| half::f16::from_bits(u16::from_ne_bytes([b[0], b[1]])).to_f32())
        .collect();
    let image = Image {
        width: camera.width(),
        height: camera.height(),
        rgba: values
            .chunks_exact(4)
            .map(|p| [p[0], p[1], p[2], p[3]])
            .collect(),
    };
    Ok((image, seconds))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/cloudlight");
    std::fs::create_dir_all(&out)?;
    let out = out.canonicalize()?;

    let start = Instant::now();
    let volume = cumulus();
    println!(
        "cumulus grown (cloudsim seed 2026, 64×64×24, 600 steps) in {:.2} s",
        start.elapsed().as_secs_f64()
    );
    let (e, a) = (60f64.to_radians(), 30f64.to_radians());
    let to_sun = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
    let start = Instant::now();
    let light = propagate_f64(&volume, to_sun, SliceMode::Physical)?;
    println!(
        "lit by slices (physical, Catmull–Rom, sun 60°) in {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    // 4.5 km from the cloud's centre, a little below it.
    let centre = DVec3::new(1600.0, 1600.0, 2100.0);
    let camera = Camera::looking_at(
        centre + DVec3::new(-2600.0, -3600.0, -500.0),
        centre,
        DVec3::Z,
        FieldOfView::from_degrees(40.0),
        512,
        384,
    )?;
    let world = SizeRule::World {
        metres_per_density: 2.5 * volume.voxel_size(),
    };
    let mut written = Vec::new();
    let sun_colour = [1.0, 0.97, 0.92];
    for (settings, name) in [
        (
            BillboardSettings {
                sun_colour,
                ..BillboardSettings::lattice(volume.voxel_size())
            },
            "billboards.png",
        ),
        (
            BillboardSettings {
                size: world,
                sun_colour,
                ..Default::default()
            },
            "billboards_density_size.png",
        ),
        (
            BillboardSettings {
                sun_colour,
                ..Default::default()
            },
            "billboards_seed_size.png",
        ),
    ] {
        let size = settings.size;
        let start = Instant::now();
        let particles = billboards(&volume, &light, &settings, &camera)?;
        let sorted = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let image = rasterise::<f32>(&particles, &camera, size, settings.opacity);
        let drawn = start.elapsed().as_secs_f64();
        println!(
            "{size:?}: {} particles selected and sorted in {:.1} ms, rasterised (CPU, f32) in {:.1} ms",
            particles.len(),
            sorted * 1e3,
            drawn * 1e3
        );
        let path = out.join(name);
        write_png(&image, &path)?;
        written.push(path);
        if name != "billboards.png" {
            continue;
        }
        match skyscape_harness::context() {
            Ok(gpu) => {
                let (gpu_image, seconds) = render_gpu(gpu, &particles, &camera, &settings)?;
                let code = |v: f32| (255.0 * srgb(v)).round() as i32;
                let within = image
                    .rgba
                    .iter()
                    .zip(&gpu_image.rgba)
                    .filter(|(c, g)| {
                        (0..3).all(|k| (code(c[k]) - code(g[k])).abs() <= 2)
                            && ((255.0 * c[3]).round() - (255.0 * g[3]).round()).abs() <= 2.0
                    })
                    .count();
                println!(
                    "GPU ({}): {:.3} % of pixels within 2 LSB of the CPU image (sRGB 8-bit)",
                    skyscape_harness::describe_adapter(&gpu.info),
                    100.0 * within as f64 / image.rgba.len() as f64
                );
                if let Some(s) = seconds {
                    let label = if gpu.is_cpu_adapter() {
                        "CPU adapter time (software rasteriser), not a GPU's"
                    } else {
                        "GPU time"
                    };
                    println!("billboard pass: {:.3} ms median of 5, {label}", s * 1e3);
                }
                let path = out.join("billboards_gpu.png");
                write_png(&gpu_image, &path)?;
                written.push(path);
            }
            Err(e) => println!("no GPU adapter ({e}): CPU image only"),
        }
    }
    let splat = splat_texture(64)?;
    let bytes: Vec<u8> = splat.iter().map(|a| (255.0 * a).round() as u8).collect();
    let path = out.join("splat.png");
    image::save_buffer(&path, &bytes, 64, 64, image::ExtendedColorType::L8)?;
    written.push(path);
    for path in written {
        println!("wrote {}", path.display());
    }
    Ok(())
}
