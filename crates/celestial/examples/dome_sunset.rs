//! A sunset (sun 2° up, on the evening of 21 June 2024 at 52° N 5° E) three ways, side by
//! side: atmos' rung 3 per pixel with the sun's disc; SimGear SGSky's 12-sided dome with its 70/30 and
//! 10/90 sky/fog weights (sky = the zenith, fog = the horizon in each vertex's azimuth,
//! rotated so vertex 0 faces the sun) plus the sun's aureole and disc; the same dome
//! with every vertex from rung 3. One exposure for all three. The dome's error over the
//! whole sky is in `cargo xtask tradeoff sky-dome`.
//!
//! `cargo run -p celestial --example dome_sunset` → `target/celestial-examples/dome_sunset.png`

#[path = "common/mod.rs"]
mod common;

use atmos::Atmosphere;
use atmos::lut::{LutSettings, PrecomputedSky};
use celestial::dome::DomeColouring;
use celestial::objects::render_sky_objects_cpu;
use celestial::{Angle, Instant, Observer, Sky, SkyOptions, sun_position};

fn main() -> celestial::Result<()> {
    let atmosphere = Atmosphere::earth();
    let model = PrecomputedSky::new(&atmosphere, &LutSettings::default()).map_err(|source| {
        celestial::CelestialError::Atmos {
            field: "model",
            source,
        }
    })?;
    let observer = Observer::new(Angle::from_degrees(52.0), Angle::from_degrees(5.0), 10.0)?;
    // Bisect the evening for a sun 2° up.
    let at = |minutes: i64| {
        Instant::from_utc(
            Instant::parse("2024-06-21T16:00:00Z").expect("valid").utc()
                + chrono::Duration::minutes(minutes),
        )
    };
    let (mut lo, mut hi) = (0i64, 360i64);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let e = sun_position(&at(mid)?, &observer)?
            .airless
            .elevation
            .degrees();
        if e > 2.0 { lo = mid } else { hi = mid }
    }
    let instant = at(hi)?;
    let (width, height) = (480u32, 320u32);
    let mut panels = Vec::new();
    for colouring in [
        None,
        Some(DomeColouring::SeedWeights),
        Some(DomeColouring::Model),
    ] {
        let options = SkyOptions {
            dome: colouring.unwrap_or_default(),
            ..SkyOptions::default()
        };
        let mut sky = Sky::build(atmosphere.clone(), options)?;
        let placement = sky.reposition(&observer, &instant)?.clone();
        sky.repaint(&model)?;
        let mut aim = placement.sun.airless;
        aim.elevation = Angle::from_degrees(18.0);
        let camera = sky.camera(
            aim.to_enu(),
            [0.0, 0.0, 1.0],
            Angle::from_degrees(50.0),
            width,
            height,
        )?;
        let radiance = match colouring {
            None => {
                let mut r = common::per_pixel_sky(
                    &model,
                    &atmosphere,
                    &camera,
                    Some(&placement.moon_light),
                );
                render_sky_objects_cpu(&sky.sky_objects_frame(&camera)?, &mut r)?;
                r
            }
            Some(_) => sky.render_backdrop_cpu(&camera)?,
        };
        println!(
            "{}: sun {:.2}° at azimuth {:.1}°, dome spin {:.1}°",
            match colouring {
                None => "per pixel",
                Some(DomeColouring::SeedWeights) => "dome, seed weights",
                Some(DomeColouring::Model) => "dome, model per vertex",
            },
            placement.sun.airless.elevation.degrees(),
            placement.sun.airless.azimuth.degrees(),
            placement.spin.degrees()
        );
        panels.push(radiance);
    }
    // Exposure from the per-pixel panel's sky away from the sun.
    let exposure = common::exposure_for(&panels[0], 0.5) * 0.5;
    let mut image = vec![[0.0f32; 3]; (3 * width * height) as usize];
    for (k, panel) in panels.iter().enumerate() {
        for y in 0..height {
            for x in 0..width {
                image[(y * 3 * width + k as u32 * width + x) as usize] =
                    panel[(y * width + x) as usize];
            }
        }
    }
    common::write_png(
        &common::output("dome_sunset.png"),
        3 * width,
        height,
        &image,
        exposure,
    );
    Ok(())
}
