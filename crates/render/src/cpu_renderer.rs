//! The CPU reference renderer of a scene: the frame's passes ([`crate::passes::FRAME`])
//! run in order, each pass's CPU twin compositing into one image of linear radiance
//! (rayon across rows), then the display pass's twin: exposure, `1 − exp(−x)`, sRGB,
//! triangular dither, RGBA8 ([`crate::tonemap`]).
//!
//! Where the GPU rasterises, the CPU ray casts: before the passes, each pixel's ray
//! finds its first terrain hit (`terrain::intersect::HeightfieldTracer`, exact per cell
//! of the bilinear heightfield within `[near, far]`). That is the CPU's depth buffer:
//! the sky pass shades the pixels without a hit, the terrain pass those with one, and
//! every later pass reads the hit's distance as the GPU's passes read the depth.
//!
//! Frames: the world is `x` east, `y` up, `z` south; the planet-centred frame of
//! `atmos` is the same axes shifted by the planet radius along `y` (the camera's
//! ground is the planet's surface at the origin). The terrain is flat in the world:
//! at 30 km the sphere falls 70 m below it, which the atmosphere (and the flat-baked
//! horizon maps) ignore.

use crate::RenderError;
use crate::scene::prepare::PreparedScene;

pub use crate::cpu_frame::PixelRadiance;
pub use crate::passes::display::display_pixels;

pub use crate::passes::terrain::lighting::{
    SUN_TABLE_SIZE, TerrainLighting, light_irradiance_at, sun_irradiance_at, terrain_lighting,
    terrain_lighting_for,
};

/// A rendered frame: packed RGBA8 (R in the low byte), row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// `width × height` packed pixels.
    pub pixels: Vec<u32>,
}

/// Linear radiance of every pixel, row-major (the HDR image before display).
pub fn render_radiance(scene: &PreparedScene) -> Result<Vec<PixelRadiance>, RenderError> {
    Ok(run_frame(scene)?.pixels)
}

/// The frame's display pixels and its linear radiance from one run of the passes
/// ([`render_cpu`] and [`render_radiance`] each run them all).
pub fn render_cpu_with_radiance(
    scene: &PreparedScene,
) -> Result<(Frame, Vec<PixelRadiance>), RenderError> {
    let frame = run_frame(scene)?;
    let camera = &scene.camera;
    let pixels = frame.display.ok_or(RenderError::NotPrepared)?;
    Ok((
        Frame {
            width: camera.width,
            height: camera.height,
            pixels,
        },
        frame.pixels,
    ))
}

/// Runs the scene's passes on the CPU.
fn run_frame(scene: &PreparedScene) -> Result<crate::cpu_frame::CpuFrame<'_>, RenderError> {
    if let Some(cloud) = scene
        .shell_cloud
        .as_ref()
        .filter(|c| !c.shadows_baked_on_cpu())
    {
        let maps = cloud.lights.iter().filter(|l| l.shadow.is_some()).count();
        return Err(RenderError::InvalidParameter {
            field: "clouds.shell",
            value: format!("{maps} shadow map(s) without values"),
            reason: "prepared for the GPU (Scene::prepare_for_gpu): call \
                     PreparedScene::bake_shell_shadow_on_cpu first",
        });
    }
    let mut frame = crate::cpu_frame::CpuFrame::new(scene);
    for entry in crate::passes::frame_passes(scene) {
        (entry.cpu)(&mut frame)?;
    }
    Ok(frame)
}

/// The scene on the CPU, tone-mapped and dithered to RGBA8.
pub fn render_cpu(scene: &PreparedScene) -> Result<Frame, RenderError> {
    let frame = run_frame(scene)?;
    let camera = &scene.camera;
    Ok(Frame {
        width: camera.width,
        height: camera.height,
        pixels: frame.display.ok_or(RenderError::NotPrepared)?,
    })
}

/// An error unless `path` is a regular file or does not exist: the atomic writes below
/// rename over it, which would replace a device, a FIFO or a symbolic link itself.
#[cfg(any(feature = "png", feature = "exr"))]
fn check_replaceable(path: &std::path::Path) -> Result<(), image::ImageError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if !meta.is_file() => Err(image::ImageError::IoError(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "{} is not a regular file (a folder, link, device or FIFO): only a regular \
                 file is replaced",
                path.display()
            ),
        ))),
        _ => Ok(()),
    }
}

/// Writes `frame` as an 8-bit RGBA PNG, atomically: to a temporary file beside
/// `path`, renamed over it only when complete (an existing file is replaced only on
/// success; anything but a regular file is an error). A missing folder is an error (it
/// is not created). Behind the `png` feature (on with the default `cli`), so the
/// library needs no PNG encoder otherwise.
#[cfg(feature = "png")]
pub fn write_png(path: &std::path::Path, frame: &Frame) -> Result<(), image::ImageError> {
    check_replaceable(path)?;
    let bytes: Vec<u8> = frame.pixels.iter().flat_map(|p| p.to_le_bytes()).collect();
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(".partial");
    let temporary = std::path::PathBuf::from(temporary);
    image::save_buffer_with_format(
        &temporary,
        &bytes,
        frame.width,
        frame.height,
        image::ExtendedColorType::Rgba8,
        image::ImageFormat::Png,
    )?;
    std::fs::rename(&temporary, path).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        image::ImageError::IoError(e)
    })
}

/// Writes linear HDR radiance (`width × height` RGB, row-major, the unit of the sun's
/// irradiance per sr, before exposure) as a 32-bit float OpenEXR, atomically like
/// [`write_png`]. Behind the `exr` feature (on with the default `cli`).
#[cfg(feature = "exr")]
pub fn write_exr(
    path: &std::path::Path,
    width: u32,
    height: u32,
    radiance: &[[f32; 3]],
) -> Result<(), image::ImageError> {
    check_replaceable(path)?;
    let floats: Vec<f32> = radiance.iter().flatten().copied().collect();
    let image = image::Rgb32FImage::from_raw(width, height, floats).ok_or_else(|| {
        image::ImageError::Parameter(image::error::ParameterError::from_kind(
            image::error::ParameterErrorKind::DimensionMismatch,
        ))
    })?;
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(".partial");
    let temporary = std::path::PathBuf::from(temporary);
    image.save_with_format(&temporary, image::ImageFormat::OpenExr)?;
    std::fs::rename(&temporary, path).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        image::ImageError::IoError(e)
    })
}
