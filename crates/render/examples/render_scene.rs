//! Renders a scene file on the CPU reference renderer and writes a PNG:
//!
//! ```sh
//! cargo run --release -p render --example render_scene -- scenes/default.toml out.png
//! ```
//!
//! Prints the time each stage took (preparation: atmosphere tables, terrain and
//! horizon maps; the frame).

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(scene_path), output) = (args.first(), args.get(1)) else {
        eprintln!("usage: render_scene SCENE.toml [OUT.png]");
        return ExitCode::from(2);
    };
    let scene = match render::scene::Scene::open(scene_path) {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("render_scene: {e}");
            return ExitCode::from(2);
        }
    };
    let start = std::time::Instant::now();
    let prepared = match scene.prepare() {
        Ok(prepared) => prepared,
        Err(e) => {
            eprintln!("render_scene: {e}");
            return ExitCode::from(2);
        }
    };
    let prepared_in = start.elapsed();
    let start = std::time::Instant::now();
    let frame = match render::cpu_renderer::render_cpu(&prepared) {
        Ok(frame) => frame,
        Err(e) => {
            eprintln!("render_scene: {e}");
            return ExitCode::FAILURE;
        }
    };
    let rendered_in = start.elapsed();
    let path = output
        .map(std::path::PathBuf::from)
        .or_else(|| scene.file.output.path.clone())
        .unwrap_or_else(|| "target/skyscape/scene.png".into());
    if let Err(e) = render::cpu_renderer::write_png(&path, &frame) {
        eprintln!("render_scene: {e}");
        return ExitCode::FAILURE;
    }
    println!(
        "prepared in {:.2} s ({}), rendered {}×{} on the CPU ({} threads) in {:.2} s\nwrote {}",
        prepared_in.as_secs_f64(),
        prepared.sky_model.label(),
        frame.width,
        frame.height,
        rayon::current_num_threads(),
        rendered_in.as_secs_f64(),
        path.display()
    );
    ExitCode::SUCCESS
}
