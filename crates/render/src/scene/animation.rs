//! `[animation]`: a numbered sequence of frames, each the scene with its sun (or its
//! `[time]`) moved, its volume cloud grown and its cloud layers changed, and the checks
//! that the whole sequence is valid before its first frame is drawn.

use serde::Deserialize;

use super::{CloudKindName, Coverage, Scene, SceneError, SceneFile};

/// The most frames an animation may have (an hour at 24 frames per second is 86,400).
pub const MAX_FRAMES: u32 = 100_000;

/// `[animation]`: frames of the scene with the sun moving (a time-lapse) and the volume
/// cloud growing. Frames are independent (frame `k` is the scene with the sun moved `k`
/// steps and the cloud grown `k` more steps from the same seed), so any range of them
/// can be rendered anywhere (`--frame-range a..b`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
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
    /// The camera's travel per frame, metres `[x east, y up, z south]` (its `look_at`
    /// point travels with it, so the view's direction is kept): a flight.
    #[serde(default)]
    pub camera_m_per_frame: [f64; 3],
    /// `[[animation.layers]]`: how the `[[clouds.layers]]` change, applied in order.
    #[serde(default)]
    pub layers: Vec<LayerChange>,
}

/// One `[[animation.layers]]` table: how layer `layer` of `[[clouds.layers]]` (its
/// index in the file, from 0) changes. The per-frame rates act from `from_frame` to
/// `to_frame` (the values hold after it); `kind` replaces the layer's from `from_frame`
/// on; the layer is in the sky from `appear_at_frame` until before `remove_at_frame`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayerChange {
    /// The layer's index in `[[clouds.layers]]`.
    pub layer: usize,
    /// The first frame the change acts on.
    #[serde(default)]
    pub from_frame: u32,
    /// The frame after which the rates stop (the values hold); none: the last frame.
    pub to_frame: Option<u32>,
    /// Coverage change per frame (fraction of the sky).
    #[serde(default)]
    pub coverage_per_frame: f64,
    /// Base altitude change per frame (m).
    #[serde(default)]
    pub base_m_per_frame: f64,
    /// Thickness change per frame (m).
    #[serde(default)]
    pub thickness_m_per_frame: f64,
    /// The layer's kind from `from_frame` on.
    pub kind: Option<CloudKindName>,
    /// The first frame the layer is in the sky (before it, the layer is not there).
    #[serde(default)]
    pub appear_at_frame: u32,
    /// The first frame the layer is no longer in the sky; none: it stays.
    pub remove_at_frame: Option<u32>,
}

impl LayerChange {
    /// Frames of change by `frame`: 0 before `from_frame`, counted up to `to_frame`.
    fn steps(&self, frame: u32) -> f64 {
        let last = self.to_frame.map_or(frame, |to| frame.min(to));
        f64::from(last.saturating_sub(self.from_frame))
    }

    /// Whether the layer is in the sky at `frame`.
    fn present(&self, frame: u32) -> bool {
        frame >= self.appear_at_frame && self.remove_at_frame.is_none_or(|end| frame < end)
    }

    /// The per-frame keys with their values, as the file names them.
    fn rates(&self) -> [(&'static str, f64); 3] {
        [
            ("coverage_per_frame", self.coverage_per_frame),
            ("base_m_per_frame", self.base_m_per_frame),
            ("thickness_m_per_frame", self.thickness_m_per_frame),
        ]
    }
}

impl AnimationSection {
    /// The scene's values at `frame` (its sun moved `frame` steps, its layers changed
    /// and those not in the sky at `frame` removed).
    pub fn apply(&self, file: &mut SceneFile, frame: u32) {
        self.apply_keeping_layers(file, frame);
        if let Some(clouds) = file.clouds.as_mut() {
            let present: Vec<bool> = (0..clouds.layers.len())
                .map(|index| {
                    self.layers
                        .iter()
                        .filter(|change| change.layer == index)
                        .all(|change| change.present(frame))
                })
                .collect();
            let mut index = 0;
            clouds.layers.retain(|_| {
                index += 1;
                present[index - 1]
            });
        }
    }

    /// [`AnimationSection::apply`] with every layer kept (each at its file index).
    fn apply_keeping_layers(&self, file: &mut SceneFile, frame: u32) {
        let k = f64::from(frame);
        let travel = self.camera_m_per_frame.map(|v| k * v);
        for (i, step) in travel.iter().enumerate() {
            file.camera.position[i] += step;
            file.camera.travel_m[i] += step;
            if let Some(target) = file.camera.look_at.as_mut() {
                target[i] += step;
            }
        }
        if let Some(layers) = file.clouds.as_mut().map(|c| &mut c.layers) {
            for change in &self.layers {
                let Some(layer) = layers.get_mut(change.layer) else {
                    continue;
                };
                let steps = change.steps(frame);
                // The coverage the layer starts from: its own, else its kind's.
                let start = layer.coverage.map_or_else(
                    || celestial::clouds::CloudKind::from(layer.kind).default_coverage(),
                    Coverage::fraction,
                );
                if let Some(kind) = change.kind
                    && frame >= change.from_frame
                {
                    layer.kind = kind;
                }
                if change.coverage_per_frame != 0.0 {
                    layer.coverage = Some(Coverage::Fraction(
                        start + steps * change.coverage_per_frame,
                    ));
                }
                layer.base_m += steps * change.base_m_per_frame;
                layer.thickness_m += steps * change.thickness_m_per_frame;
            }
        }
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
        let Some(animation) = &self.file.animation else {
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
        if let Some(v) = animation.camera_m_per_frame.iter().find(|v| !v.is_finite()) {
            return Err(self.invalid(
                &["animation", "camera_m_per_frame"],
                format!("{v} m"),
                "must be finite [x, y, z] metres".into(),
            ));
        }
        self.check_layer_changes(animation)?;
        self.check_frame(animation, range.start)?;
        let last = range.end.saturating_sub(1).max(range.start);
        if self.check_frame(animation, last).is_err() {
            // The valid frames are an interval holding `range.start`: name the first
            // frame past it.
            let (mut valid, mut invalid) = (range.start, last);
            while invalid - valid > 1 {
                let middle = valid + (invalid - valid) / 2;
                if self.check_frame(animation, middle).is_ok() {
                    valid = middle;
                } else {
                    invalid = middle;
                }
            }
            self.check_frame(animation, invalid)?;
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
        animation.apply_keeping_layers(&mut moved, frame);
        self.check_moved_layers(animation, &moved, &of)?;
        if animation.camera_m_per_frame != [0.0; 3] {
            let earth = atmos::Atmosphere::earth();
            let p = moved.camera.position;
            let planet_centred =
                glam::DVec3::from_array(p) + glam::DVec3::new(0.0, earth.planet_radius, 0.0);
            if let Err(e) = atmos::SkyQuery::new(
                earth.planet_radius,
                planet_centred,
                glam::DVec3::Y,
                glam::DVec3::Y,
            ) {
                let v = animation.camera_m_per_frame;
                return Err(self.invalid(
                    &["animation", "camera_m_per_frame"],
                    format!("[{}, {}, {}] m", v[0], v[1], v[2]),
                    format!(
                        "frame {of} puts the camera at [{}, {}, {}] m, where no viewer can be: {e}",
                        p[0], p[1], p[2]
                    ),
                ));
            }
        }
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

impl Scene {
    /// The `[[animation.layers]]` entries on their own: each names a layer the file
    /// has, its rates are finite, its frames in order.
    fn check_layer_changes(&self, animation: &AnimationSection) -> Result<(), SceneError> {
        let count = self.file.clouds.as_ref().map_or(0, |c| c.layers.len());
        for (entry, change) in animation.layers.iter().enumerate() {
            let key = |name: &'static str| {
                ["animation", "layers", &entry.to_string(), name].map(str::to_owned)
            };
            let invalid = |name: &'static str, value: String, reason: String| {
                let path = key(name);
                let path: Vec<&str> = path.iter().map(String::as_str).collect();
                self.invalid(&path, value, reason)
            };
            if change.layer >= count {
                return Err(invalid(
                    "layer",
                    change.layer.to_string(),
                    format!(
                        "the scene has {count} [[clouds.layers]] (indices from 0 in the \
                         file's order)"
                    ),
                ));
            }
            for (name, value) in change.rates() {
                if !value.is_finite() {
                    return Err(invalid(name, value.to_string(), "must be finite".into()));
                }
            }
            if let Some(to) = change.to_frame
                && to < change.from_frame
            {
                return Err(invalid(
                    "to_frame",
                    to.to_string(),
                    format!("must be ≥ from_frame ({})", change.from_frame),
                ));
            }
            if let Some(end) = change.remove_at_frame
                && end <= change.appear_at_frame
            {
                return Err(invalid(
                    "remove_at_frame",
                    end.to_string(),
                    format!(
                        "must be > appear_at_frame ({}): the layer would never be in the sky",
                        change.appear_at_frame
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The changed layers of `moved` (the scene at `frame`, every layer kept) are valid
    /// layers; a rejected one is named by the per-frame key that moved the value.
    fn check_moved_layers(
        &self,
        animation: &AnimationSection,
        moved: &SceneFile,
        of: &str,
    ) -> Result<(), SceneError> {
        let Some(clouds) = &moved.clouds else {
            return Ok(());
        };
        for (entry, change) in animation.layers.iter().enumerate() {
            let Some(layer) = clouds.layers.get(change.layer) else {
                continue;
            };
            // Only what the animation moved: the file's own values are checked by the
            // scene's preparation, naming their own keys.
            let base_file = self
                .file
                .clouds
                .as_ref()
                .and_then(|c| c.layers.get(change.layer));
            if base_file.is_some_and(|l| self.cloud_layer(change.layer, l).is_err()) {
                continue;
            }
            let Err(error) = self.cloud_layer(change.layer, layer) else {
                continue;
            };
            let (field, reason) = match &error {
                SceneError::Invalid { field, reason, .. } => (field.clone(), reason.clone()),
                SceneError::Celestial { field, source, .. } => (field.clone(), source.to_string()),
                other => (String::new(), other.to_string()),
            };
            let moved_key = field.rsplit('.').next().unwrap_or_default().to_owned();
            let (name, rate) = match moved_key.as_str() {
                "base_m" => ("base_m_per_frame", change.base_m_per_frame),
                "thickness_m" => ("thickness_m_per_frame", change.thickness_m_per_frame),
                _ => ("coverage_per_frame", change.coverage_per_frame),
            };
            let value = match moved_key.as_str() {
                "base_m" => format!("{} m", layer.base_m),
                "thickness_m" => format!("{} m", layer.thickness_m),
                _ => layer.coverage.map_or_else(String::new, Coverage::typed),
            };
            return Err(self.invalid(
                &["animation", "layers", &entry.to_string(), name],
                rate.to_string(),
                format!(
                    "frame {of} puts clouds.layers.{}.{moved_key} at {value}: {reason}",
                    change.layer
                ),
            ));
        }
        Ok(())
    }
}
