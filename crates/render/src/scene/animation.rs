//! `[animation]`: a numbered sequence of frames, each the scene with its sun (or its
//! `[time]`) moved and its volume cloud grown, and the checks that the whole sequence
//! is valid before its first frame is drawn.

use serde::Deserialize;

use super::{Scene, SceneError, SceneFile};

/// The most frames an animation may have (an hour at 24 frames per second is 86,400).
pub const MAX_FRAMES: u32 = 100_000;

/// `[animation]`: frames of the scene with the sun moving (a time-lapse) and the volume
/// cloud growing. Frames are independent (frame `k` is the scene with the sun moved `k`
/// steps and the cloud grown `k` more steps from the same seed), so any range of them
/// can be rendered anywhere (`--frame-range a..b`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnimationSection {
    /// Frames in the sequence.
    pub frames: u32,
    /// The sun's elevation change per frame, degrees.
    #[serde(default)]
    pub sun_elevation_deg_per_frame: f64,
    /// The sun's azimuth change per frame, degrees.
    #[serde(default)]
    pub sun_azimuth_deg_per_frame: f64,
    /// Seconds of `[time]` per frame (a time-lapse: sun, moon and stars move).
    #[serde(default)]
    pub seconds_per_frame: f64,
    /// Automaton steps `[clouds.volume]`'s cloud grows per frame: frame `k` shows it
    /// after `steps + k × this` steps (the same seed, so the frames are one growth).
    #[serde(default)]
    pub automaton_steps_per_frame: u32,
}

impl AnimationSection {
    /// The scene's values at `frame` (its sun moved `frame` steps).
    pub fn apply(&self, file: &mut SceneFile, frame: u32) {
        let k = f64::from(frame);
        if let Some(sun) = &mut file.sun {
            sun.elevation_deg += k * self.sun_elevation_deg_per_frame;
            sun.azimuth_deg += k * self.sun_azimuth_deg_per_frame;
        }
        if let Some(time) = &mut file.time {
            time.offset_s += k * self.seconds_per_frame;
        }
        if let Some(volume) = file.clouds.as_mut().and_then(|c| c.volume.as_mut()) {
            // Saturating: a count past u32 is then refused by the steps check, naming it.
            volume.steps = volume
                .steps
                .saturating_add(frame.saturating_mul(self.automaton_steps_per_frame));
        }
    }
}

impl Scene {
    /// Checks the scene's `[animation]` (nothing without one) before any frame is
    /// drawn: its length is in 1..=[`MAX_FRAMES`]; each per-frame key is finite and
    /// moves something the scene has (`sun_*_per_frame` a `[sun]`, `seconds_per_frame`
    /// a `[time]`, `automaton_steps_per_frame` a `[clouds.volume]`); and at frames
    /// `range` the moved values stay valid. Every moved value is linear in the frame,
    /// so the range's first and last frames are its extremes. An error names the
    /// per-frame key and the first frame that breaks the rule.
    pub fn check_animation(&self, range: std::ops::Range<u32>) -> Result<(), SceneError> {
        let Some(animation) = self.file.animation else {
            return Ok(());
        };
        if animation.frames == 0 || animation.frames > MAX_FRAMES {
            return Err(self.invalid(
                &["animation", "frames"],
                animation.frames.to_string(),
                format!("must be in 1..={MAX_FRAMES}"),
            ));
        }
        let per_frame = [
            (
                "sun_elevation_deg_per_frame",
                animation.sun_elevation_deg_per_frame,
                "°",
            ),
            (
                "sun_azimuth_deg_per_frame",
                animation.sun_azimuth_deg_per_frame,
                "°",
            ),
            ("seconds_per_frame", animation.seconds_per_frame, " s"),
        ];
        for (name, value, unit) in per_frame {
            if !value.is_finite() {
                return Err(self.invalid(
                    &["animation", name],
                    format!("{value}{unit}"),
                    "must be finite".into(),
                ));
            }
        }
        let file = &self.file;
        let moves = |name: &str, value: String, needs: &str| {
            self.invalid(
                &["animation", name],
                value,
                format!("it moves {needs}, which this scene does not have"),
            )
        };
        if file.sun.is_none() {
            for (name, value, _) in &per_frame[..2] {
                if *value != 0.0 {
                    return Err(moves(
                        name,
                        format!("{value}°"),
                        "an explicit [sun] (a scene with [time] moves by seconds_per_frame)",
                    ));
                }
            }
        }
        if file.time.is_none() && animation.seconds_per_frame != 0.0 {
            return Err(moves(
                "seconds_per_frame",
                format!("{} s", animation.seconds_per_frame),
                "[time] (a scene with [sun] moves by sun_elevation_deg_per_frame and \
                 sun_azimuth_deg_per_frame)",
            ));
        }
        let volume = file.clouds.as_ref().and_then(|c| c.volume.as_ref());
        if volume.is_none() && animation.automaton_steps_per_frame != 0 {
            return Err(moves(
                "automaton_steps_per_frame",
                animation.automaton_steps_per_frame.to_string(),
                "[clouds.volume]'s cloud",
            ));
        }
        self.check_frame(&animation, range.start)?;
        let last = range.end.saturating_sub(1).max(range.start);
        if self.check_frame(&animation, last).is_err() {
            // The valid frames are an interval holding `range.start`: name the first
            // frame past it.
            let (mut valid, mut invalid) = (range.start, last);
            while invalid - valid > 1 {
                let middle = valid + (invalid - valid) / 2;
                if self.check_frame(&animation, middle).is_ok() {
                    valid = middle;
                } else {
                    invalid = middle;
                }
            }
            self.check_frame(&animation, invalid)?;
        }
        Ok(())
    }

    /// The values `animation` moves, at `frame`.
    fn check_frame(&self, animation: &AnimationSection, frame: u32) -> Result<(), SceneError> {
        // "frame 4 of 12", and the flag when one set the length.
        let of = match self.location(&["animation", "frames"]) {
            Some(super::Location {
                origin: super::Origin::Flag(flag),
                ..
            }) => format!("{frame} of {} ({flag})", animation.frames),
            _ => format!("{frame} of {}", animation.frames),
        };
        let mut moved = self.file.clone();
        animation.apply(&mut moved, frame);
        if let (Some(base), Some(sun)) = (self.file.sun, moved.sun) {
            if sun.elevation_deg.is_nan() || sun.elevation_deg.abs() > 90.0 {
                return Err(self.invalid(
                    &["animation", "sun_elevation_deg_per_frame"],
                    format!("{}°", animation.sun_elevation_deg_per_frame),
                    format!(
                        "frame {of} puts the sun at {}° (sun.elevation_deg {}° + {frame} × \
                         {}°): it must stay in [−90°, 90°]",
                        sun.elevation_deg,
                        base.elevation_deg,
                        animation.sun_elevation_deg_per_frame
                    ),
                ));
            }
            if !sun.azimuth_deg.is_finite() {
                return Err(self.invalid(
                    &["animation", "sun_azimuth_deg_per_frame"],
                    format!("{}°", animation.sun_azimuth_deg_per_frame),
                    format!(
                        "frame {frame} puts the sun's azimuth at {}°",
                        sun.azimuth_deg
                    ),
                ));
            }
        }
        if let Some(time) = &moved.time
            && animation.seconds_per_frame != 0.0
        {
            let seconds = time.offset_s;
            let instant = celestial::Instant::parse(&time.utc).ok().and_then(|start| {
                let offset = chrono::Duration::try_milliseconds((seconds * 1e3).round() as i64)?;
                celestial::Instant::from_utc(start.utc().checked_add_signed(offset)?).ok()
            });
            // An unparsable `utc` is the base key's error, reported by the scene's checks.
            if celestial::Instant::parse(&time.utc).is_ok() && instant.is_none() {
                return Err(self.invalid(
                    &["animation", "seconds_per_frame"],
                    format!("{} s", animation.seconds_per_frame),
                    format!(
                        "frame {of} is {seconds} s after time.utc \"{}\", outside the \
                         ephemeris' years",
                        time.utc
                    ),
                ));
            }
        }
        let volume = |file: &SceneFile| file.clouds.as_ref().and_then(|c| c.volume.clone());
        if let (Some(base), Some(grown)) = (volume(&self.file), volume(&moved))
            && animation.automaton_steps_per_frame != 0
            && self.check_volume_cloud(&base).is_ok()
            && let Err(e) = self.check_volume_cloud(&grown)
        {
            let reason = match &e {
                SceneError::Invalid { reason, .. } => reason.clone(),
                other => other.to_string(),
            };
            return Err(self.invalid(
                &["animation", "automaton_steps_per_frame"],
                animation.automaton_steps_per_frame.to_string(),
                format!(
                    "frame {of} grows the cloud to {} steps (clouds.volume.steps {} + {frame} × \
                     {}), and clouds.volume.steps {reason}",
                    grown.steps, base.steps, animation.automaton_steps_per_frame
                ),
            ));
        }
        Ok(())
    }
}
