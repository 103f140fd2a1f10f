//! Preparing SGSky's keys (`super::sgsky`): the visibility as the atmosphere's aerosol
//! and the cloud layers' fog, each `[[clouds.layers]]` table as a `celestial` layer,
//! the layers' texture anchored to the world and drifting with the wind, and the
//! in-cloud fog around a camera inside or near a layer.

use super::assemble::metres;
use super::layer_frame::PreparedVisibility;
use super::{CloudLayerSection, Scene, SceneError};

/// The strongest wind a layer may be given (m/s): above the strongest jet-stream cores
/// measured (about 110 m/s).
pub const MAX_WIND_M_PER_S: f64 = 200.0;

impl Scene {
    /// The atmosphere with `[visibility]`'s aerosol (celestial's Koschmieder mapping at
    /// the camera's altitude), and what it made; `atmosphere` unchanged without it.
    pub(super) fn with_visibility(
        &self,
        atmosphere: atmos::Atmosphere,
    ) -> Result<(atmos::Atmosphere, Option<PreparedVisibility>), SceneError> {
        let Some(section) = self.file.visibility else {
            return Ok((atmosphere, None));
        };
        let key = ["visibility", "distance_m"];
        let value = metres(section.distance_m);
        celestial::visibility::check_visibility("visibility.distance_m", section.distance_m)
            .map_err(|e| self.celestial_error(&key, value.clone(), e))?;
        if let Some(scale) = self.file.atmosphere.mie_scale {
            return Err(self.invalid(
                &key,
                value,
                format!(
                    "the visibility sets the aerosol, and atmosphere.mie_scale ({scale}) sets \
                     it too: give one of them"
                ),
            ));
        }
        let altitude = self.file.camera.position[1];
        let aerosol = celestial::visibility::aerosol_for_visibility(
            &atmosphere,
            section.distance_m,
            altitude,
        )
        .map_err(|e| {
            self.invalid(
                &key,
                value.clone(),
                format!(
                    "the aerosol is set at the camera's altitude ({altitude} m), which \
                             must be in the atmosphere: {e}"
                ),
            )
        })?;
        let prepared = PreparedVisibility {
            distance_m: section.distance_m,
            aerosol_visibility_m: aerosol.effective_visibility_m,
            rayleigh_limited: aerosol.rayleigh_limited,
            effective_m: None,
        };
        Ok((aerosol.atmosphere, Some(prepared)))
    }

    /// Layer `index` of `[[clouds.layers]]` as a `celestial` layer, each rejected value
    /// named by its key.
    pub(super) fn cloud_layer(
        &self,
        index: usize,
        layer: &CloudLayerSection,
    ) -> Result<celestial::clouds::CloudLayer, SceneError> {
        let index = index.to_string();
        let value_of = |key: &str| match key {
            "base_m" => metres(layer.base_m),
            "thickness_m" => metres(layer.thickness_m),
            "transition_m" => metres(layer.transition_m),
            "span_m" => metres(layer.span_m),
            "coverage" => layer
                .coverage
                .map_or_else(|| "(the kind's)".to_owned(), |c| c.typed()),
            _ => layer.kind.name().to_owned(),
        };
        let field = |e: celestial::CelestialError| {
            let message = e.to_string();
            let key = [
                "base_m",
                "thickness_m",
                "transition_m",
                "span_m",
                "coverage",
            ]
            .into_iter()
            .find(|k| message.contains(k.trim_end_matches("_m")))
            .unwrap_or("kind");
            self.celestial_error(&["clouds", "layers", &index, key], value_of(key), e)
        };
        // celestial draws a layer of no thickness; nothing would be there.
        if !(layer.thickness_m > 0.0 && layer.thickness_m.is_finite()) {
            return Err(self.invalid(
                &["clouds", "layers", &index, "thickness_m"],
                value_of("thickness_m"),
                "must be finite and > 0 m".into(),
            ));
        }
        let [east, north] = layer.wind_m_per_s;
        if !(east.is_finite() && north.is_finite() && east.hypot(north) <= MAX_WIND_M_PER_S) {
            return Err(self.invalid(
                &["clouds", "layers", &index, "wind_m_per_s"],
                format!("[{east}, {north}] m/s"),
                format!(
                    "must be finite [east, north] with a speed ≤ {MAX_WIND_M_PER_S} m/s (the \
                     strongest jet streams reach about 110 m/s)"
                ),
            ));
        }
        let mut built = celestial::clouds::CloudLayer::new(
            layer.base_m,
            layer.thickness_m,
            layer.transition_m,
            layer.span_m,
            layer.kind.into(),
        )
        .map_err(field)?;
        if let Some(coverage) = layer.coverage {
            built.coverage = coverage.fraction();
        }
        built.seed = layer.seed;
        if layer.flat {
            built.shape = celestial::clouds::LayerShape::Flat;
        }
        built.validate().map_err(field)?;
        Ok(built)
    }

    /// Adds the scene's layers to `sky` and sets its visibility; returns each layer's
    /// wind drift (m, east and north: −wind × `[time] offset_s`, the texture moving
    /// downwind) less the east and north of where the scene starts its camera (the
    /// camera's position less its travel), in the file's order: with the camera's east
    /// and north, [`super::layer_frame::cloud_layers_at`]'s offset is the viewer's travel plus the drift.
    pub(super) fn add_cloud_layers(
        &self,
        sky: &mut celestial::sky::Sky,
    ) -> Result<Vec<[f64; 2]>, SceneError> {
        if let Some(section) = self.file.visibility {
            sky.set_visibility(section.distance_m).map_err(|e| {
                self.celestial_error(&["visibility", "distance_m"], metres(section.distance_m), e)
            })?;
        }
        let seconds = self.file.time.as_ref().map_or(0.0, |t| t.offset_s);
        let camera = &self.file.camera;
        let start = [0, 2].map(|a| camera.position[a] - camera.travel_m[a]);
        let mut drift = Vec::new();
        for (index, layer) in self
            .file
            .clouds
            .iter()
            .flat_map(|c| c.layers.iter())
            .enumerate()
        {
            let built = self.cloud_layer(index, layer)?;
            sky.add_cloud_layer(built).map_err(|e| {
                self.celestial_error(
                    &["clouds", "layers", &index.to_string(), "kind"],
                    layer.kind.name().to_owned(),
                    e,
                )
            })?;
            let [east, north] = layer.wind_m_per_s.map(|w| -w * seconds);
            drift.push([east - start[0], north + start[1]]);
        }
        Ok(drift)
    }
}
