//! `skyscape`: renders an outdoor scene (a scene file, or a shipped scene by name) to
//! a PNG, a JPEG or an OpenEXR, on the GPU when an adapter exists, on the CPU reference
//! renderer otherwise or with `--cpu`. `skyscape --help` lists the commands.

mod adapter;
mod args;
mod commands;
mod input;
mod output;
mod progress;
mod projected;
mod runtime_dir;
#[cfg(feature = "view")]
mod view;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};
use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::scene::shipped::{SHIPPED, shipped};
use render::scene::{PreparedScene, Scene};

use adapter::*;
use args::*;
use commands::*;
use input::*;
use output::*;
use progress::*;
use projected::*;

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
    /// Show a scene in a window and fly through it while the sun moves (a shipped
    /// scene's name or a .toml; default: "default"). Controls: docs/viewer.md.
    #[cfg(feature = "view")]
    View(view::ViewArgs),
    /// List the shipped scenes.
    Scenes,
    /// List the adapters wgpu finds and which one skyscape would use.
    Adapters {
        /// Restrict the search to these backends.
        #[arg(long)]
        backend: Option<String>,
    },
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
    runtime_dir::ensure_runtime_dir();
    let cli = Cli::parse();
    handle_interrupts();
    let result = match cli.command {
        None => render_command(RenderArgs::default()),
        Some(Command::Render(args)) => render_command(args),
        Some(Command::Explain { scene, backend }) => explain_command(&scene, backend.as_deref()),
        #[cfg(feature = "view")]
        Some(Command::View(args)) => view::view_command(args),
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
