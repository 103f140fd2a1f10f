//! The moon through a month as a phase strip: every 2 days from the new moon of
//! 8 April 2024, each frame 0.8° wide centred on the moon for an observer who has it
//! 50° up on the meridian, one fixed exposure, so crescents are as
//! faint as the moon's magnitude makes them. Image up is the zenith: the bright limb
//! points at the sun with the tilt χ − q the observer sees.
//!
//! `cargo run -p celestial --example moon_phases` → `target/celestial-examples/moon_phases.png`

#[path = "common/mod.rs"]
mod common;

use atmos::Atmosphere;
use atmos::closed_form_sky::ClosedFormSky;
use celestial::objects::{
    BackgroundSampling, SkyObjectsBuilder, SkyObjectsFrame, render_sky_objects_cpu,
};
use celestial::{Angle, Instant, LuminanceScale, MoonLight, Observer, moon_position, sun_position};

fn main() -> celestial::Result<()> {
    let atmosphere = Atmosphere::earth();
    let model =
        ClosedFormSky::new(&atmosphere).map_err(|source| celestial::CelestialError::Atmos {
            field: "model",
            source,
        })?;
    let size = 128u32;
    let days = 15;
    let mut strip = vec![[0.0f32; 3]; (size * size * days) as usize];
    let mut full_radiance = 0.0f32;
    let mut frames = Vec::new();
    for k in 0..days {
        let instant = Instant::from_utc(
            Instant::parse("2024-04-08T18:21:00Z")?.utc()
                + chrono::Duration::hours(48 * i64::from(k)),
        )?;
        // 40° south of the sub-lunar point: the moon 50° up in the north (or the
        // reverse in the far south), on the observer's meridian.
        let centre = Observer::new(Angle::ZERO, Angle::ZERO, 0.0)?;
        let geocentric = moon_position(&instant, &centre)?.geocentric;
        let gast = celestial::sidereal::greenwich_apparent_sidereal_time(&instant);
        let observer = Observer::new(
            geocentric.declination - Angle::from_degrees(40.0),
            (geocentric.right_ascension - gast).wrapped_signed(),
            0.0,
        )?;
        let sun = sun_position(&instant, &observer)?;
        let moon = moon_position(&instant, &observer)?;
        let scale = LuminanceScale::new(&atmosphere, sun.distance_m)?;
        let light = MoonLight::new(&moon, &sun, &atmosphere, &scale)?;
        let builder = SkyObjectsBuilder::new(
            &atmosphere,
            &model,
            0.0,
            sun.airless.to_enu(),
            sun.distance_m,
            Some(light),
            BackgroundSampling::PerObject,
        )?;
        let disc = builder.moon_disc()?;
        let camera = atmos::frame::FrameCamera::look_at(
            glam::DVec3::new(0.0, 0.0, atmosphere.planet_radius),
            glam::DVec3::from_array(light.direction),
            glam::DVec3::Z,
            0.8f64.to_radians(),
            size,
            size,
            glam::DVec3::from_array(sun.airless.to_enu()),
            None,
        )
        .map_err(|source| celestial::CelestialError::Atmos {
            field: "camera",
            source,
        })?;
        let frame = SkyObjectsFrame::new(
            camera,
            atmosphere.planet_radius,
            &scale,
            1.0,
            [celestial::draw::DiscObject::NONE, disc],
            Vec::new(),
        )?;
        let mut radiance = vec![[0.0f32; 3]; (size * size) as usize];
        render_sky_objects_cpu(&frame, &mut radiance)?;
        full_radiance = full_radiance.max(disc.radiance[1]);
        println!(
            "{}  lit {:5.1} %  phase angle {:6.1}°  bright limb from the zenith {:6.1}°  {:.3} lx",
            instant.utc().format("%Y-%m-%d"),
            100.0 * moon.phase.illuminated_fraction,
            moon.phase.phase_angle.degrees(),
            moon.bright_limb_from_zenith().degrees(),
            light.illuminance_lx
        );
        frames.push(radiance);
    }
    for (k, frame) in frames.iter().enumerate() {
        for y in 0..size {
            for x in 0..size {
                strip[(y * size * days + k as u32 * size + x) as usize] =
                    frame[(y * size + x) as usize];
            }
        }
    }
    // One exposure for the whole month: the full moon's disc just below white.
    let exposure = 2.0 / (0.5 * full_radiance);
    common::write_png(
        &common::output("moon_phases.png"),
        size * days,
        size,
        &strip,
        exposure,
    );
    Ok(())
}
