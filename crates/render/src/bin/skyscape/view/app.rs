//! The viewer's window and frame loop (winit): input moves the camera and the clock,
//! every frame moves the prepared scene to the camera and draws it with the scene
//! renderer; changed choices are prepared on the preparation thread meanwhile.

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::ViewOptions;
use super::camera::CameraMode;
use super::overlay::{self, Readings};
use super::script::{Action, Script};
use super::shots;
use super::state::ViewState;
use super::window_gpu::{OverlayFrame, WindowGpu};
use super::worker::Preparer;

/// The window, its GPU and what it shows.
pub(crate) struct App {
    options: ViewOptions,
    window: Option<Arc<Window>>,
    gpu: Option<WindowGpu>,
    egui: Option<(egui::Context, egui_winit::State)>,
    pub(crate) state: ViewState,
    preparer: Preparer,
    /// The camera position the newest request was prepared at.
    requested_at: DVec3,
    keys: HashSet<KeyCode>,
    looking: bool,
    cursor: Option<(f64, f64)>,
    last_frame: Instant,
    frame_ms: f64,
    passes: Vec<(&'static str, f64)>,
    last_prepare: Vec<(&'static str, f64)>,
    overlay_visible: bool,
    script: Option<Script>,
    /// Frames drawn with everything asked before them prepared (what a script counts).
    ready_frames: u32,
    /// The script's actions for the next ready frame have been applied.
    actions_applied: bool,
    /// Screenshots to take on the next ready frame (`None`: numbered, F12).
    shots_wanted: Vec<Option<PathBuf>>,
    quit_after_frame: bool,
    /// Each ready frame's GPU time per pass and wall time (s), for `--timings`.
    timings: Vec<(Vec<(&'static str, f64)>, f64)>,
    /// A failure that ends the viewer: a scene whose first preparation fails (exit
    /// status 2), a window or device that cannot be had (1).
    pub(crate) failure: Option<crate::Failure>,
}

impl App {
    pub(crate) fn new(options: ViewOptions, state: ViewState, preparer: Preparer) -> Self {
        let script = options.script.clone();
        let overlay_visible = !options.no_overlay;
        Self {
            options,
            window: None,
            gpu: None,
            egui: None,
            requested_at: state.camera.position,
            state,
            preparer,
            keys: HashSet::new(),
            looking: false,
            cursor: None,
            last_frame: Instant::now(),
            frame_ms: 0.0,
            passes: Vec::new(),
            last_prepare: Vec::new(),
            overlay_visible,
            script,
            ready_frames: 0,
            actions_applied: false,
            shots_wanted: Vec::new(),
            quit_after_frame: false,
            timings: Vec::new(),
            failure: None,
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, message: String) {
        self.failure = Some(crate::Failure::Runtime(message));
        event_loop.exit();
    }

    /// Says `message` in the window (the overlay) and on stderr.
    fn say(&mut self, message: String) {
        eprintln!("skyscape view: {message}");
        self.state.error = Some(message);
    }

    fn render_size(&self) -> (u32, u32) {
        let surface = self
            .gpu
            .as_ref()
            .map_or(self.options.size, WindowGpu::surface_size);
        self.state.render_size(surface)
    }

    /// Applies the keys held down for `seconds`.
    fn held_keys(&mut self, seconds: f64) {
        let held = |code| self.keys.contains(&code);
        let boost = if held(KeyCode::ShiftLeft) || held(KeyCode::ShiftRight) {
            4.0
        } else {
            1.0
        };
        let step = self.state.camera.speed * boost * seconds;
        let axis = |plus, minus| f64::from(u8::from(held(plus))) - f64::from(u8::from(held(minus)));
        let forward = axis(KeyCode::KeyW, KeyCode::KeyS) * step;
        let right = axis(KeyCode::KeyD, KeyCode::KeyA) * step;
        let up = axis(KeyCode::KeyE, KeyCode::KeyQ) * step;
        let turn_rate = 60f64.to_radians() * seconds;
        let azimuth = axis(KeyCode::ArrowRight, KeyCode::ArrowLeft) * turn_rate;
        let elevation = axis(KeyCode::ArrowUp, KeyCode::ArrowDown) * turn_rate;
        if forward != 0.0 || right != 0.0 || up != 0.0 {
            self.state.camera.translate(forward, right, up);
        }
        if azimuth != 0.0 || elevation != 0.0 {
            self.state.camera.turn(azimuth, elevation);
        }
    }

    fn key_pressed(&mut self, event_loop: &ActiveEventLoop, code: KeyCode) {
        let shift =
            self.keys.contains(&KeyCode::ShiftLeft) || self.keys.contains(&KeyCode::ShiftRight);
        match code {
            KeyCode::Escape => event_loop.exit(),
            KeyCode::KeyR => self.state.reset_camera(),
            KeyCode::Tab => {
                self.state.camera.mode = match self.state.camera.mode {
                    CameraMode::Fly => CameraMode::Orbit,
                    CameraMode::Orbit => CameraMode::Fly,
                };
            }
            KeyCode::Space => self.state.playing = !self.state.playing,
            KeyCode::BracketLeft | KeyCode::BracketRight => {
                let sign = if code == KeyCode::BracketLeft {
                    -1.0
                } else {
                    1.0
                };
                let result = if let Some(sun) = self.state.scene.file.sun {
                    let degrees = if shift { 10.0 } else { 1.0 };
                    self.state
                        .set_sun(sun.elevation_deg + sign * degrees, sun.azimuth_deg)
                } else {
                    self.state
                        .add_time(sign * if shift { 3600.0 } else { 600.0 })
                };
                if let Err(message) = result {
                    self.say(message);
                }
            }
            KeyCode::Comma => self.state.rate = (self.state.rate / 2.0).max(1.0),
            KeyCode::Period => self.state.rate = (self.state.rate * 2.0).min(86_400.0),
            KeyCode::Minus | KeyCode::Equal => {
                let factor = if code == KeyCode::Minus { 0.8 } else { 1.25 };
                let exposure = &mut self.state.scene.file.output.exposure;
                *exposure = (*exposure * factor).clamp(1e-3, 1e6);
                self.state.dirty = true;
            }
            KeyCode::F1 => self.overlay_visible = !self.overlay_visible,
            KeyCode::F5 => self.reload(),
            KeyCode::F12 => self.shots_wanted.push(None),
            _ => {}
        }
    }

    /// `F5`: the scene file read again; one that fails to parse leaves the last good
    /// scene on screen and says why.
    fn reload(&mut self) {
        match super::load(&self.options.scene) {
            Ok(scene) => {
                self.state.reload(scene);
                self.state.error = None;
            }
            Err(message) => self.say(format!("reload: {message} (the last good scene stays)")),
        }
    }

    fn apply_action(&mut self, action: Action) {
        let result = match action {
            Action::Turn(azimuth, elevation) => {
                self.state
                    .camera
                    .turn(azimuth.to_radians(), elevation.to_radians());
                Ok(())
            }
            Action::Move(forward, right, up) => {
                self.state.camera.translate(forward, right, up);
                Ok(())
            }
            Action::Time(seconds) => self.state.add_time(seconds),
            Action::Sun(elevation, azimuth) => self.state.set_sun(elevation, azimuth),
            Action::Rung(name) => match render::scene::Rung::from_name(&name) {
                Some(rung) => {
                    self.state.scene.file.atmosphere.rung = rung;
                    self.state.dirty = true;
                    Ok(())
                }
                None => Err(format!("script: rung `{name}`: no such rung")),
            },
            Action::Exposure(exposure) => {
                self.state.scene.file.output.exposure = exposure as f32;
                self.state.dirty = true;
                Ok(())
            }
            Action::Overlay(on) => {
                self.overlay_visible = on;
                Ok(())
            }
            Action::Temporal(on) => {
                self.state.temporal_clouds = on;
                Ok(())
            }
            Action::Screenshot(stem) => {
                self.shots_wanted.push(Some(stem));
                Ok(())
            }
            Action::Quit => {
                self.quit_after_frame = true;
                Ok(())
            }
        };
        if let Err(message) = result {
            self.say(message);
        }
    }

    /// One frame: input, preparation, the scene and the overlay drawn.
    fn frame(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let wall = now.duration_since(self.last_frame).as_secs_f64();
        // A slow frame moves the camera and the clock no further than half a second's.
        let seconds = wall.min(0.5);
        self.last_frame = now;
        self.frame_ms = if self.frame_ms == 0.0 {
            wall * 1e3
        } else {
            0.9 * self.frame_ms + 0.1 * wall * 1e3
        };
        if self.script.is_none() {
            self.state.advance(seconds);
            self.held_keys(seconds);
        }
        if let Some((result, stages)) = self.preparer.poll() {
            self.last_prepare = stages;
            match result {
                Ok(prepared) => self.state.prepared(prepared, self.requested_at),
                Err(message) if self.state.prepared.is_none() => {
                    let label = &self.options.scene_label;
                    self.failure = Some(crate::Failure::Input(format!("{label}: {message}")));
                    return event_loop.exit();
                }
                Err(message) => self.say(format!("{message} (the last good scene stays)")),
            }
        }
        // A script's actions apply once everything before them is prepared.
        let settled =
            |app: &Self| app.state.prepared.is_some() && !app.preparer.busy() && !app.state.dirty;
        if settled(self) && !self.actions_applied {
            if let Some(script) = &mut self.script {
                let actions = script.take(self.ready_frames);
                for action in actions {
                    self.apply_action(action);
                }
            }
            self.actions_applied = true;
        }
        self.state.follow_camera();
        if self.state.dirty {
            let size = self.render_size();
            self.requested_at = self.state.camera.position;
            let scene = self.state.request(size);
            self.preparer.request(scene);
        }
        let Some(gpu) = &mut self.gpu else {
            return;
        };
        if let Some(prepared) = &self.state.prepared
            && let Err(message) = gpu.prepare(prepared, self.state.temporal_clouds)
        {
            let message = format!("drawing: {message}");
            if self.script.is_some() {
                return self.fail(event_loop, message);
            }
            self.say(message);
        }
        let ready = settled(self);
        let shoot = ready && (!self.shots_wanted.is_empty() || self.options.record.is_some());
        let overlay = if self.overlay_visible {
            self.overlay_frame()
        } else {
            None
        };
        let Some(gpu) = &mut self.gpu else {
            return;
        };
        let drawn = match gpu.draw(self.state.prepared.as_ref(), overlay, shoot) {
            Ok(drawn) => drawn,
            Err(message) => {
                self.fail(event_loop, message);
                return;
            }
        };
        if self.overlay_visible || self.options.timings.is_some() {
            self.passes = gpu.pass_seconds();
        }
        // A frame the surface did not show does not count.
        let Some(shot) = drawn else {
            return;
        };
        if !ready {
            return;
        }
        if let Some(shot) = &shot {
            for wanted in std::mem::take(&mut self.shots_wanted) {
                let written = match wanted {
                    Some(stem) => shots::write_pair(&stem, shot),
                    None => shots::write_numbered(&self.options.screenshot_folder, shot),
                };
                match written {
                    Ok(path) => eprintln!("skyscape view: wrote {}", path.display()),
                    Err(message) => {
                        if self.script.is_some() {
                            self.fail(event_loop, message);
                            return;
                        }
                        self.say(message);
                    }
                }
            }
            if let (Some(count), Some(folder)) = (self.options.record, &self.options.out)
                && self.ready_frames < count
                && let Err(message) = shots::write_frame(folder, self.ready_frames, shot)
            {
                self.fail(event_loop, message);
                return;
            }
        }
        if self.options.timings.is_some() {
            self.timings.push((self.passes.clone(), wall));
        }
        self.ready_frames += 1;
        self.actions_applied = false;
        let recorded = self
            .options
            .record
            .is_some_and(|count| self.ready_frames >= count);
        let script_done = self.script.as_ref().is_some_and(Script::is_done);
        if self.quit_after_frame || (recorded && (self.script.is_none() || script_done)) {
            event_loop.exit();
        }
    }

    pub(crate) fn options_timings(&self) -> Option<PathBuf> {
        self.options.timings.clone()
    }

    /// `--timings`: the median GPU time per pass and the median wall time between
    /// frames over the ready frames after the first (which builds the renderer), as
    /// Markdown with the command that measured them.
    pub(crate) fn write_timings(&self, path: &std::path::Path) -> Result<(), String> {
        let median = |mut values: Vec<f64>| -> f64 {
            values.sort_by(f64::total_cmp);
            values.get(values.len() / 2).copied().unwrap_or(f64::NAN)
        };
        let frames = self.timings.get(1..).unwrap_or_default();
        let adapter = self
            .gpu
            .as_ref()
            .map_or_else(String::new, WindowGpu::adapter);
        let (width, height) = self.render_size();
        let command: Vec<String> = std::env::args()
            .skip(1)
            .map(|a| if a.contains(' ') { format!("'{a}'") } else { a })
            .collect();
        let mut text = format!(
            "# skyscape view: frame time per pass\n\nGenerated by `skyscape {}`; do not \
             edit by hand.\n\nScene `{}` at {width}×{height} pixels, {} frames after the first. \
             Adapter: {adapter}.{}\n\n| pass (GPU timestamps) | median ms |\n|---|---:|\n",
            command.join(" "),
            self.options.scene_label,
            frames.len(),
            if adapter.starts_with("a CPU adapter") {
                " **A CPU adapter: every time below is CPU time on the machine that \
                 measured it, not a GPU's.**"
            } else {
                ""
            },
        );
        let names: Vec<&'static str> = frames
            .first()
            .map(|(passes, _)| passes.iter().map(|(name, _)| *name).collect())
            .unwrap_or_default();
        for name in &names {
            let values = frames
                .iter()
                .filter_map(|(passes, _)| passes.iter().find(|(n, _)| n == name).map(|p| p.1))
                .collect();
            text.push_str(&format!("| {name} | {:.3} |\n", median(values) * 1e3));
        }
        let all = frames
            .iter()
            .map(|(passes, _)| passes.iter().map(|p| p.1).sum())
            .collect();
        text.push_str(&format!(
            "| **all passes** | **{:.3}** |\n",
            median(all) * 1e3
        ));
        let wall = frames.iter().map(|(_, seconds)| *seconds).collect();
        text.push_str(&format!(
            "| frame wall time (window to window, with preparation and presentation) | {:.3} |\n",
            median(wall) * 1e3
        ));
        let partial = path.with_extension("md.partial");
        std::fs::write(&partial, text)
            .and_then(|()| std::fs::rename(&partial, path))
            .map_err(|e| format!("--timings `{}`: {e}", path.display()))
    }

    fn overlay_frame(&mut self) -> Option<OverlayFrame> {
        let window = self.window.clone()?;
        let render_size = self.render_size();
        let (context, egui_state) = self.egui.as_mut()?;
        let input = egui_state.take_egui_input(&window);
        let adapter = self
            .gpu
            .as_ref()
            .map_or_else(String::new, WindowGpu::adapter);
        let readings = Readings {
            adapter: &adapter,
            frame_ms: self.frame_ms,
            passes: &self.passes,
            render_size,
            preparing: self.preparer.stage.filter(|_| self.preparer.busy()),
            last_prepare: &self.last_prepare,
            renderers_built: self.gpu.as_ref().map_or(0, |g| g.renderers_built),
        };
        let state = &mut self.state;
        let output = context.run_pass(input, |ctx| overlay::show(ctx, state, &readings));
        egui_state.handle_platform_output(&window, output.platform_output);
        let primitives = context.tessellate(output.shapes, output.pixels_per_point);
        let size = window.inner_size();
        Some(OverlayFrame {
            primitives,
            textures: output.textures_delta,
            screen: egui_wgpu::ScreenDescriptor {
                size_in_pixels: [size.width, size.height],
                pixels_per_point: output.pixels_per_point,
            },
        })
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let (width, height) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(format!("skyscape view — {}", self.options.scene_label))
            .with_inner_size(winit::dpi::PhysicalSize::new(width, height));
        let window = match event_loop.create_window(attributes) {
            Ok(window) => Arc::new(window),
            Err(e) => return self.fail(event_loop, format!("opening a window: {e}")),
        };
        let gpu = match WindowGpu::new(
            window.clone(),
            event_loop.owned_display_handle(),
            self.options.backends,
            !self.options.no_vsync,
        ) {
            Ok(gpu) => gpu,
            Err(message) => return self.fail(event_loop, message),
        };
        if self.options.scale.is_none() {
            // A CPU adapter draws a quarter of the pixels unless told otherwise.
            self.state.scale = if gpu.info.device_type == wgpu::DeviceType::Cpu {
                0.5
            } else {
                1.0
            };
        }
        eprintln!("skyscape view: drawing on {}", gpu.adapter());
        let context = egui::Context::default();
        let egui_state = egui_winit::State::new(
            context.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        self.egui = Some((context, egui_state));
        self.gpu = Some(gpu);
        self.state.dirty = true;
        self.window = Some(window);
        self.last_frame = Instant::now();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(window) = self.window.clone() else {
            return;
        };
        let consumed = match (&mut self.egui, self.overlay_visible) {
            (Some((_, egui_state)), true) => egui_state.on_window_event(&window, &event).consumed,
            _ => false,
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(gpu) = &mut self.gpu {
                    gpu.resize(size.width, size.height);
                }
                if size.width > 0 && size.height > 0 {
                    self.state.dirty = true;
                }
            }
            WindowEvent::RedrawRequested => self.frame(event_loop),
            WindowEvent::KeyboardInput { event, .. } if !consumed => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    match event.state {
                        ElementState::Pressed => {
                            if !event.repeat {
                                self.key_pressed(event_loop, code);
                            }
                            self.keys.insert(code);
                        }
                        ElementState::Released => {
                            self.keys.remove(&code);
                        }
                    }
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let pressed = state == ElementState::Pressed;
                if button == MouseButton::Right || (button == MouseButton::Left && !consumed) {
                    self.looking = pressed;
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                if self.looking
                    && !consumed
                    && let Some((x, y)) = self.cursor
                {
                    let per_pixel = self.state.camera.vertical_fov
                        / f64::from(window.inner_size().height.max(1));
                    self.state
                        .camera
                        .turn((position.x - x) * per_pixel, -(position.y - y) * per_pixel);
                }
                self.cursor = Some((position.x, position.y));
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.state.camera.wheel(notches);
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(window) = &self.window {
            window.request_redraw();
        }
    }
}
