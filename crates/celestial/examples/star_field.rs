//! A star field with planets for a date and place: 2024-08-20 02:30 UTC from 52° N
//! 5° E (moonlight included: the moon was nearly full), looking at the brightest
//! planet above the horizon, 90° wide; the sky per pixel from atmos' rung 3 and the
//! stars, planets and moon from the `Sky` facade.
//!
//! `cargo run -p celestial --example star_field` → `target/celestial-examples/star_field.png`

#[path = "common/mod.rs"]
mod common;

use atmos::Atmosphere;
use atmos::lut::{LutSettings, PrecomputedSky};
use celestial::objects::render_sky_objects_cpu;
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
    let observer = Observer::new(Angle::from_degrees(52.0), Angle::from_degrees(5.0), 10.0)?;
    let instant = Instant::parse("2024-08-20T02:30:00Z")?;
    let placement = sky.reposition(&observer, &instant)?.clone();
    let brightest = placement
        .planets
        .iter()
        .filter(|p| p.airless.elevation.degrees() > 5.0)
        .min_by(|a, b| a.magnitude.total_cmp(&b.magnitude))
        .expect("a planet is up");
    println!(
        "sun {:.1}°, moon {:.1}° (lit {:.0} %), aiming at {:?} (mag {:.1}) az {:.1}° el {:.1}°",
        placement.sun.airless.elevation.degrees(),
        placement.moon.airless.elevation.degrees(),
        100.0 * placement.moon.phase.illuminated_fraction,
        brightest.planet,
        brightest.magnitude,
        brightest.airless.azimuth.degrees(),
        brightest.airless.elevation.degrees()
    );
    let mut aim = brightest.airless;
    aim.elevation = Angle::from_degrees(aim.elevation.degrees().max(30.0));
    sky.repaint(&model)?;
    let (width, height) = (960, 540);
    let camera = sky.camera(
        aim.to_enu(),
        [0.0, 0.0, 1.0],
        Angle::from_degrees(60.0),
        width,
        height,
    )?;
    let start = std::time::Instant::now();
    let mut radiance =
        common::per_pixel_sky(&model, &atmosphere, &camera, Some(&placement.moon_light));
    let frame = sky.sky_objects_frame(&camera)?;
    render_sky_objects_cpu(&frame, &mut radiance)?;
    let visible = frame
        .points
        .iter()
        .filter(|p| {
            celestial::draw::point_source_irradiance(
                p.illuminance_lux,
                p.colour,
                p.transmittance,
                p.background_luminance,
                p.scintillation,
                frame.uniforms.lux_per_unit,
            )[1] > 0.0
        })
        .count();
    println!(
        "{} point sources above the horizon, {visible} brighter than the eye's threshold; frame {:.2} s",
        frame.points.len(),
        start.elapsed().as_secs_f64()
    );
    let exposure = common::exposure_for(&radiance, 0.999);
    common::write_png(
        &common::output("star_field.png"),
        width,
        height,
        &radiance,
        exposure,
    );
    Ok(())
}
