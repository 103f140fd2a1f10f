//! Cubemaps, panoramas and fisheyes: six faces of one preparation.

use crate::*;

/// A cubemap, panorama or fisheye: the six 90° faces of the scene drawn (GPU or CPU)
/// from the one preparation (`PreparedScene::look_along` turns its camera), then placed
/// or resampled (`render::projection`).
pub(crate) fn render_projected(
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
pub(crate) enum FacesOn {
    /// The CPU reference renderer.
    Cpu,
    /// The GPU, or the CPU (with a line on stderr) when no GPU renders them.
    GpuOrCpu,
    /// The GPU only (`--compare`).
    Gpu,
}

/// Turns `view` along the cube face `forward`: a 90° square of `side` pixels.
pub(crate) fn look_along_face(
    view: &mut PreparedScene,
    forward: [f64; 3],
    side: u32,
) -> Result<(), String> {
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
pub(crate) fn gpu_faces(
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
pub(crate) fn cpu_faces(
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
