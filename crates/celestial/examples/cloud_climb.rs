//! A flight climbing through a cloud layer: from 300 m to 3,300 m at 5 m/s through a
//! stratus deck (base 1,500 m, 400 m thick, 300 m transitions, coverage 0.8, SimGear's
//! 25 m in-cloud visibility) under a cirrus layer at 8 km, 20 km visibility, a June
//! afternoon at 52° N. `modify_vis(altitude, dt)` every 0.5 s gives the visibility over
//! altitude (the deterministic "puffs" included), plotted as an SVG; eight frames of the
//! view ahead (north, 5° up) show the deck from below, the fog inside and the deck from
//! above: stage 1 the dome backdrop, stage 2 the cloud layers and the in-cloud fog.
//!
//! `cargo run -p celestial --example cloud_climb` → `target/celestial-examples/cloud_climb.png`,
//! `cloud_climb_visibility.svg` (and the same plot as `cloud_climb_visibility.png`)

#[path = "common/mod.rs"]
mod common;

use std::fmt::Write as _;

use atmos::Atmosphere;
use atmos::lut::{LutSettings, PrecomputedSky};
use celestial::clouds::{CloudKind, CloudLayer};
use celestial::{Angle, Instant, Observer, Sky, SkyOptions};

fn main() -> celestial::Result<()> {
    let atmosphere = Atmosphere::earth();
    let model = PrecomputedSky::new(&atmosphere, &LutSettings::default()).map_err(|source| {
        celestial::CelestialError::Atmos {
            field: "model",
            source,
        }
    })?;
    let mut sky = Sky::build(atmosphere.clone(), SkyOptions::default())?;
    sky.set_visibility(20_000.0)?;
    let deck = CloudLayer {
        coverage: 0.8,
        seed: 11,
        ..CloudLayer::new(1500.0, 400.0, 300.0, 40_000.0, CloudKind::Stratus)?
    };
    sky.add_cloud_layer(deck)?;
    sky.add_cloud_layer(CloudLayer {
        seed: 3,
        ..CloudLayer::new(8000.0, 300.0, 200.0, 80_000.0, CloudKind::Cirrus)?
    })?;
    let instant = Instant::parse("2024-06-21T14:00:00Z")?;

    // Visibility over altitude at 5 m/s, modify_vis every 0.5 s.
    let (climb_rate, dt) = (5.0, 0.5);
    let mut samples = Vec::new();
    let mut altitude = 300.0;
    while altitude <= 3300.0 {
        samples.push((altitude, sky.modify_vis(altitude, dt)?));
        altitude += climb_rate * dt;
    }
    let path = common::output("cloud_climb_visibility.svg");
    std::fs::write(&path, svg(&samples)).expect("write the SVG");
    println!("wrote {}", path.display());
    plot_png(&samples);

    let (width, height) = (240u32, 160u32);
    let frames = [
        300.0, 1100.0, 1300.0, 1550.0, 1700.0, 2000.0, 2300.0, 3300.0,
    ];
    let mut strip = vec![[0.0f32; 3]; (width * height * frames.len() as u32) as usize];
    let mut exposure = None;
    for (k, &altitude) in frames.iter().enumerate() {
        let observer = Observer::new(
            Angle::from_degrees(52.0),
            Angle::from_degrees(5.0),
            altitude,
        )?;
        sky.reposition(&observer, &instant)?;
        sky.repaint(&model)?;
        let visibility = sky.modify_vis(altitude, 0.0)?;
        let camera = sky.camera(
            [0.0, 5f64.to_radians().cos(), 5f64.to_radians().sin()],
            [0.0, 0.0, 1.0],
            Angle::from_degrees(60.0),
            width,
            height,
        )?;
        let mut radiance = sky.render_backdrop_cpu(&camera)?;
        sky.render_clouds_cpu(&camera, &mut radiance)?;
        println!("{altitude:6.0} m: visibility {visibility:8.1} m");
        let e = *exposure.get_or_insert_with(|| common::exposure_for(&radiance, 0.5) * 0.6);
        let _ = e;
        for y in 0..height {
            for x in 0..width {
                strip[(y * width * frames.len() as u32 + k as u32 * width + x) as usize] =
                    radiance[(y * width + x) as usize];
            }
        }
    }
    common::write_png(
        &common::output("cloud_climb.png"),
        width * frames.len() as u32,
        height,
        &strip,
        exposure.unwrap_or(1.0),
    );
    Ok(())
}

/// Visibility (log scale) against altitude, as an SVG line plot.
fn svg(samples: &[(f64, f64)]) -> String {
    let (w, h, margin) = (640.0, 400.0, 60.0);
    let (v_min, v_max) = (10f64.log10(), 1e5f64.log10());
    let x = |altitude: f64| margin + (altitude - 300.0) / 3000.0 * (w - 2.0 * margin);
    let y = |v: f64| h - margin - (v.log10() - v_min) / (v_max - v_min) * (h - 2.0 * margin);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    // The deck and its transitions.
    let _ = writeln!(
        out,
        r#"<rect x="{}" y="{margin}" width="{}" height="{}" fill="rgb(221,221,221)"/>"#,
        x(1200.0),
        x(2200.0) - x(1200.0),
        h - 2.0 * margin
    );
    let _ = writeln!(
        out,
        r#"<rect x="{}" y="{margin}" width="{}" height="{}" fill="rgb(187,187,187)"/>"#,
        x(1500.0),
        x(1900.0) - x(1500.0),
        h - 2.0 * margin
    );
    for decade in 1..=5 {
        let v = 10f64.powi(decade);
        let _ = writeln!(
            out,
            r#"<line x1="{margin}" x2="{}" y1="{}" y2="{}" stroke="rgb(238,238,238)"/><text x="{}" y="{}" text-anchor="end">{}</text>"#,
            w - margin,
            y(v),
            y(v),
            margin - 6.0,
            y(v) + 4.0,
            v
        );
    }
    for altitude in [300.0, 1300.0, 2300.0, 3300.0] {
        let _ = writeln!(
            out,
            r#"<text x="{}" y="{}" text-anchor="middle">{altitude}</text>"#,
            x(altitude),
            h - margin + 18.0
        );
    }
    let points: Vec<String> = samples
        .iter()
        .map(|&(a, v)| format!("{:.1},{:.1}", x(a), y(v)))
        .collect();
    let _ = writeln!(
        out,
        r#"<polyline fill="none" stroke="rgb(16,96,192)" stroke-width="1.5" points="{}"/>"#,
        points.join(" ")
    );
    let _ = writeln!(
        out,
        r#"<text x="{}" y="{}" text-anchor="middle">altitude (m); grey: the deck, light grey: its transitions</text>"#,
        w / 2.0,
        h - 15.0
    );
    let _ = writeln!(
        out,
        r#"<text x="15" y="{}" transform="rotate(-90 15 {})" text-anchor="middle">visibility (m)</text>"#,
        h / 2.0,
        h / 2.0
    );
    let _ = writeln!(
        out,
        r#"<text x="{}" y="30" text-anchor="middle">Sky::modify_vis climbing at 5 m/s (dt 0.5 s)</text>"#,
        w / 2.0
    );
    out.push_str("</svg>\n");
    out
}

/// The same plot as a PNG (axes, the deck's band, the curve).
fn plot_png(samples: &[(f64, f64)]) {
    let (w, h, margin) = (640u32, 400u32, 60.0);
    let mut image = image::RgbImage::from_pixel(w, h, image::Rgb([255, 255, 255]));
    let (v_min, v_max) = (1.0, 5.0);
    let x = |altitude: f64| margin + (altitude - 300.0) / 3000.0 * (f64::from(w) - 2.0 * margin);
    let y = |v: f64| {
        f64::from(h)
            - margin
            - (v.log10() - v_min) / (v_max - v_min) * (f64::from(h) - 2.0 * margin)
    };
    for (a, b, shade) in [(1200.0, 2200.0, 221u8), (1500.0, 1900.0, 187)] {
        for px in x(a) as u32..x(b) as u32 {
            for py in margin as u32..h - margin as u32 {
                image.put_pixel(px, py, image::Rgb([shade; 3]));
            }
        }
    }
    for decade in 1..=5 {
        let py = y(10f64.powi(decade)) as u32;
        for px in margin as u32..w - margin as u32 {
            image.put_pixel(px, py.min(h - 1), image::Rgb([150; 3]));
        }
    }
    for pair in samples.windows(2) {
        let (x0, y0, x1, y1) = (x(pair[0].0), y(pair[0].1), x(pair[1].0), y(pair[1].1));
        let steps = ((x1 - x0).abs().max((y1 - y0).abs()).ceil() as usize).max(1);
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            let (px, py) = ((x0 + t * (x1 - x0)) as u32, (y0 + t * (y1 - y0)) as u32);
            if px < w && py < h {
                image.put_pixel(px, py, image::Rgb([16, 96, 192]));
            }
        }
    }
    let path = common::output("cloud_climb_visibility.png");
    image.save(&path).expect("write the PNG");
    println!("wrote {}", path.display());
}
