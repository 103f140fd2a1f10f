//! The viewer's overlay (egui): the adapter, frame and pass times, what is being
//! prepared, and the choices a user can switch live — each with what the trade-off
//! reports measured for it (`docs/tradeoffs/*.md`, read when the binary was built).

use render::aerial_vertex::AerialPerspective;
use render::billboard_clouds::VolumeDraw;
use render::scene::{HorizonVariant, Rung};

use super::camera::CameraMode;
use super::state::ViewState;

/// A trade-off report's first table: `(report, header, rows)`, each row its cells.
type Table = (
    &'static str,
    &'static [&'static str],
    &'static [&'static [&'static str]],
);

/// The trade-off reports' first tables.
const TRADEOFFS: &[Table] = include!(concat!(env!("OUT_DIR"), "/tradeoffs.rs"));

/// What the overlay shows besides the state it edits.
pub(crate) struct Readings<'a> {
    pub(crate) adapter: &'a str,
    pub(crate) frame_ms: f64,
    pub(crate) passes: &'a [(&'static str, f64)],
    pub(crate) render_size: (u32, u32),
    pub(crate) preparing: Option<&'a str>,
    pub(crate) last_prepare: &'a [(&'static str, f64)],
    pub(crate) renderers_built: u32,
}

/// The rungs the GPU renderer draws (the reference rungs are CPU only).
const GPU_RUNGS: [Rung; 5] = [
    Rung::Precomputed,
    Rung::Single,
    Rung::ClosedForm,
    Rung::ClosedFormVertex,
    Rung::Dome,
];

/// Draws the overlay; edits of the scene's values mark the state dirty.
pub(crate) fn show(ctx: &egui::Context, state: &mut ViewState, readings: &Readings<'_>) {
    egui::Window::new("skyscape")
        .default_pos([12.0, 12.0])
        .default_width(330.0)
        .resizable(true)
        .vscroll(true)
        .show(ctx, |ui| {
            ui.label(readings.adapter);
            ui.label(format!(
                "frame {:.1} ms · {}×{} pixels · {} renderer{} built",
                readings.frame_ms,
                readings.render_size.0,
                readings.render_size.1,
                readings.renderers_built,
                if readings.renderers_built == 1 {
                    ""
                } else {
                    "s"
                }
            ));
            match readings.preparing {
                Some(stage) => {
                    ui.colored_label(egui::Color32::YELLOW, format!("preparing: {stage}…"))
                }
                None => ui.label(prepare_summary(readings.last_prepare)),
            };
            if let Some(error) = &state.error {
                ui.colored_label(egui::Color32::LIGHT_RED, error);
            }
            egui::CollapsingHeader::new("GPU time per pass")
                .default_open(true)
                .show(ui, |ui| passes(ui, readings.passes));
            egui::CollapsingHeader::new("camera and time")
                .default_open(true)
                .show(ui, |ui| camera_and_time(ui, state));
            egui::CollapsingHeader::new("models")
                .default_open(true)
                .show(ui, |ui| models(ui, state));
        });
}

fn prepare_summary(stages: &[(&'static str, f64)]) -> String {
    let total: f64 = stages.iter().map(|(_, s)| s).sum();
    let slowest = stages
        .iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map_or_else(String::new, |(name, s)| {
            format!(" (most: {name} {:.0} ms)", s * 1e3)
        });
    format!("last preparation {:.0} ms{slowest}", total * 1e3)
}

fn passes(ui: &mut egui::Ui, passes: &[(&'static str, f64)]) {
    if passes.is_empty() {
        ui.label("no timestamps on this device");
        return;
    }
    egui::Grid::new("passes").striped(true).show(ui, |ui| {
        for (name, seconds) in passes {
            ui.label(*name);
            ui.label(format!("{:.3} ms", seconds * 1e3));
            ui.end_row();
        }
        ui.label("all passes");
        ui.label(format!(
            "{:.3} ms",
            passes.iter().map(|(_, s)| s).sum::<f64>() * 1e3
        ));
        ui.end_row();
    });
}

fn camera_and_time(ui: &mut egui::Ui, state: &mut ViewState) {
    ui.horizontal(|ui| {
        ui.radio_value(&mut state.camera.mode, CameraMode::Fly, "fly");
        ui.radio_value(&mut state.camera.mode, CameraMode::Orbit, "orbit");
        if ui.button("reset (R)").clicked() {
            state.reset_camera();
        }
    });
    let p = state.camera.position;
    ui.label(format!(
        "at ({:.0}, {:.0}, {:.0}) m · heading {:.1}° · pitch {:.1}°",
        p.x,
        p.y,
        p.z,
        state.camera.azimuth.to_degrees(),
        state.camera.elevation.to_degrees()
    ));
    ui.add(
        egui::Slider::new(&mut state.camera.speed, 0.5..=1.0e5)
            .logarithmic(true)
            .text("speed m/s"),
    );
    if let Some(time) = state.scene.file.time.clone() {
        ui.label(format!("{} + {:.0} s", time.utc, time.offset_s));
        ui.horizontal(|ui| {
            ui.checkbox(&mut state.playing, "play (Space)");
            ui.add(
                egui::Slider::new(&mut state.rate, 1.0..=86_400.0)
                    .logarithmic(true)
                    .text("× real time"),
            );
        });
        ui.horizontal(|ui| {
            for (label, seconds) in [
                ("−1 h", -3600.0),
                ("−10 min", -600.0),
                ("+10 min", 600.0),
                ("+1 h", 3600.0),
            ] {
                if ui.button(label).clicked() {
                    let _ = state.add_time(seconds);
                }
            }
        });
    } else if let Some(sun) = state.scene.file.sun {
        let (mut elevation, mut azimuth) = (sun.elevation_deg, sun.azimuth_deg);
        let a = ui.add(egui::Slider::new(&mut elevation, -10.0..=90.0).text("sun elevation °"));
        let b = ui.add(egui::Slider::new(&mut azimuth, 0.0..=360.0).text("sun azimuth °"));
        if a.changed() || b.changed() {
            let _ = state.set_sun(elevation, azimuth);
        }
    }
    let mut exposure = f64::from(state.scene.file.output.exposure);
    if ui
        .add(
            egui::Slider::new(&mut exposure, 0.01..=1000.0)
                .logarithmic(true)
                .text("exposure"),
        )
        .changed()
    {
        state.scene.file.output.exposure = exposure as f32;
        state.dirty = true;
    }
    if ui
        .add(egui::Slider::new(&mut state.scale, 0.125..=1.0).text("render scale"))
        .changed()
    {
        state.dirty = true;
    }
}

fn models(ui: &mut egui::Ui, state: &mut ViewState) {
    let mut dirty = false;
    let rung = &mut state.scene.file.atmosphere.rung;
    egui::ComboBox::from_label("sky rung")
        .selected_text(rung.name())
        .show_ui(ui, |ui| {
            for choice in GPU_RUNGS {
                dirty |= ui.selectable_value(rung, choice, choice.name()).changed();
            }
        });
    tradeoff(ui, "atmos", rung_row_prefix(*rung), &[0, 1, 2, 4, 10]);
    if let Some(terrain) = &mut state.scene.file.terrain {
        ui.horizontal(|ui| {
            ui.label("horizon maps");
            dirty |= ui
                .radio_value(&mut terrain.horizon, HorizonVariant::EastWest, "east/west")
                .changed();
            dirty |= ui
                .radio_value(&mut terrain.horizon, HorizonVariant::Azimuths, "azimuths")
                .changed();
        });
        if terrain.horizon == HorizonVariant::Azimuths {
            let mut count = terrain.horizon_azimuths.unwrap_or(8);
            if ui
                .add(egui::Slider::new(&mut count, 4..=64).text("azimuths"))
                .changed()
            {
                terrain.horizon_azimuths = Some(count);
                dirty = true;
            }
        }
        let variant = match terrain.horizon {
            HorizonVariant::EastWest => "E/W".to_owned(),
            HorizonVariant::Azimuths => format!("N={}", terrain.horizon_azimuths.unwrap_or(8)),
        };
        tradeoff(ui, "terrain", &variant, &[0, 1, 3, 5, 8]);
        ui.horizontal(|ui| {
            ui.label("aerial perspective");
            let ap = &mut terrain.aerial_perspective;
            dirty |= ui
                .radio_value(ap, AerialPerspective::PerPixel, "per pixel")
                .changed();
            dirty |= ui
                .radio_value(ap, AerialPerspective::PerVertex, "per vertex")
                .changed();
        });
    }
    if let Some(volume) = state
        .scene
        .file
        .clouds
        .as_mut()
        .and_then(|c| c.volume.as_mut())
    {
        ui.horizontal(|ui| {
            ui.label("volume cloud");
            dirty |= ui
                .radio_value(&mut volume.draw, VolumeDraw::March, "march")
                .changed();
            dirty |= ui
                .radio_value(&mut volume.draw, VolumeDraw::Billboards, "billboards")
                .changed();
        });
        dirty |= ui
            .add(egui::Slider::new(&mut volume.view_steps, 8..=512).text("view steps"))
            .changed();
        dirty |= ui
            .add(egui::Slider::new(&mut volume.light_steps, 1..=64).text("light steps"))
            .changed();
        dirty |= ui
            .add(egui::Slider::new(&mut volume.octaves, 1..=8).text("octaves"))
            .changed();
        ui.add(egui::Slider::new(&mut state.growth_rate, 0.0..=20.0).text("automaton steps/s"));
        ui.label(format!("automaton: {} steps", volume.steps));
    }
    if let Some(shell) = state
        .scene
        .file
        .clouds
        .as_mut()
        .and_then(|c| c.shell.as_mut())
    {
        ui.label("cloud shell");
        dirty |= ui
            .add(egui::Slider::new(&mut shell.view_steps, 8..=512).text("view steps"))
            .changed();
        dirty |= ui
            .add(egui::Slider::new(&mut shell.light_steps, 1..=64).text("light steps"))
            .changed();
        dirty |= ui
            .add(egui::Slider::new(&mut shell.octaves, 1..=8).text("octaves"))
            .changed();
    }
    if state
        .scene
        .file
        .clouds
        .as_ref()
        .is_some_and(|c| c.volume.is_some() || c.shell.is_some())
    {
        tradeoff(ui, "cloudlight", "60°", &[1, 3, 4]);
    }
    state.dirty |= dirty;
}

/// The atmos report's rows for a rung start with its number and family.
fn rung_row_prefix(rung: Rung) -> &'static str {
    match rung {
        Rung::Dome => "0 SGSky dome/",
        Rung::ClosedForm => "1 closed form/closed form, per pixel",
        Rung::ClosedFormVertex => "1 closed form/closed form per vertex (16×32",
        Rung::Single => "2 single scattering/",
        Rung::Precomputed => "3 precomputed/",
        Rung::Reference | Rung::ReferenceSpectral => "reference/",
    }
}

/// The rows of `report` whose first cells (joined by '/') start with `prefix`, the
/// columns `columns` of each, under the report's header.
fn tradeoff(ui: &mut egui::Ui, report: &str, prefix: &str, columns: &[usize]) {
    let Some((_, header, rows)) = TRADEOFFS.iter().find(|(name, _, _)| *name == report) else {
        return;
    };
    let matching: Vec<&&[&str]> = rows
        .iter()
        .filter(|row| row.join("/").starts_with(prefix))
        .collect();
    if matching.is_empty() {
        return;
    }
    ui.small(format!("measured (docs/tradeoffs/{report}.md):"));
    egui::Grid::new(("tradeoff", report))
        .striped(true)
        .show(ui, |ui| {
            for &column in columns {
                ui.small(header.get(column).copied().unwrap_or(""));
            }
            ui.end_row();
            for row in matching {
                for &column in columns {
                    ui.small(row.get(column).copied().unwrap_or(""));
                }
                ui.end_row();
            }
        });
}
