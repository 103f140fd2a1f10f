//! Drawing: stage 1's backdrop and objects, stage 2's cloud layers.

use atmos::frame::FrameCamera;

use super::*;
use crate::clouds::{CloudLayerFrame, CloudLayerUniforms, draw_order, immersion_column};
use crate::dome::DOME_SIDES;
use crate::error::{CelestialError, Result};
use crate::objects::{SkyObjectsFrame, render_sky_objects_cpu};

/// The fog of the cloud layers a viewer is in or near (in a layer or its transition
/// zone): SGSky's closed-in visibility as a medium to see through ([`Sky::in_cloud_fog`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InCloudFog {
    /// The layers' in-cloud extinction at the viewer (1/m): per layer, its immersion ×
    /// coverage × 3.912 / in-cloud visibility — the terms [`Sky::modify_vis`] adds to
    /// the clear air's (without the puffs, which change the reported visibility only).
    pub extinction_per_m: f64,
    /// That extinction integrated from the viewer up through the layers (vertical
    /// optical depth).
    pub optical_depth_up: f64,
    /// That extinction integrated from the viewer down to sea level.
    pub optical_depth_down: f64,
    /// Height above the viewer (m) past which no layer's band reaches: a view that
    /// climbs this far has crossed the whole column above.
    pub band_above_m: f64,
    /// Depth below the viewer (m, to sea level at most) past which no layer's band
    /// reaches.
    pub band_below_m: f64,
    /// The fog's radiance: the most immersed layer's inside
    /// ([`crate::clouds::cloud_interior_radiance`]), in the atmosphere's unit.
    pub radiance: [f32; 3],
    /// The most immersed layer's index.
    pub layer: usize,
}

impl Sky {
    /// The in-cloud fog around a viewer at `altitude_m`, or `None` when the viewer is
    /// in no layer's band (the layer or its transition zones). A view of zenith cosine
    /// μ sees `exp(−optical_depth/|μ|)` of what lies beyond the layers (|μ| ≥ 10⁻³,
    /// flat bands: [`crate::clouds::in_cloud_transmittance`]).
    pub fn in_cloud_fog(&self, altitude_m: f64) -> Result<Option<InCloudFog>> {
        let paint = self.painted("in_cloud_fog")?;
        let Some(layer) = (0..self.layers.len())
            .filter(|&i| self.layers[i].immersion(altitude_m) > 0.0)
            .max_by(|&a, &b| {
                self.layers[a]
                    .immersion(altitude_m)
                    .total_cmp(&self.layers[b].immersion(altitude_m))
            })
        else {
            return Ok(None);
        };
        let k = -crate::visibility::KOSCHMIEDER_CONTRAST.ln();
        let (mut extinction_per_m, mut optical_depth_up, mut optical_depth_down) = (0.0, 0.0, 0.0);
        for l in &self.layers {
            let per_immersion = l.coverage * k / l.in_cloud_visibility_m;
            extinction_per_m += per_immersion * l.immersion(altitude_m);
            optical_depth_up += per_immersion * immersion_column(l, altitude_m, true);
            optical_depth_down += per_immersion * immersion_column(l, altitude_m, false);
        }
        let top = self
            .layers
            .iter()
            .map(|l| l.top_m() + l.transition_m)
            .fold(altitude_m, f64::max);
        let bottom = self
            .layers
            .iter()
            .map(|l| l.base_m - l.transition_m)
            .fold(altitude_m, f64::min)
            .max(0.0f64.min(altitude_m));
        let light = &paint.layer_light[layer];
        let frame = CloudLayerFrame {
            planet_radius_m: self.atmosphere.planet_radius,
            offset_m: [0.0, 0.0],
            fog_extinction_per_m: 0.0,
            exp2_fog: false,
            sun_direction: light.direction,
            sunlight: light.irradiance,
            skylight: light.skylight,
            fog_colour: [0.0; 3],
        };
        let radiance = crate::clouds::cloud_interior_radiance(&self.layers[layer].uniforms(&frame));
        Ok(Some(InCloudFog {
            extinction_per_m,
            optical_depth_up,
            optical_depth_down,
            band_above_m: top - altitude_m,
            band_below_m: altitude_m - bottom,
            radiance,
            layer,
        }))
    }

    /// Stage 1's objects for `camera` (made by [`Sky::camera`]): what
    /// [`render_sky_objects_cpu`] and `celestial::gpu::SkyObjectsPass` draw over a sky.
    pub fn sky_objects_frame(&self, camera: &FrameCamera) -> Result<SkyObjectsFrame> {
        let placement = self.placed("sky_objects_frame")?;
        let paint = self.painted("sky_objects_frame")?;
        SkyObjectsFrame::new(
            *camera,
            self.atmosphere.planet_radius,
            &placement.scale,
            self.options.sprite_sigma_px,
            paint.discs,
            paint.points.clone(),
        )
    }

    /// SGSky's stage 1 on the CPU with the cheap sky: per pixel the dome's colour and
    /// the sun's aureole (which the dome cannot resolve), then the sun, moon, planets
    /// and stars. Row-major radiance in the atmosphere's unit.
    pub fn render_backdrop_cpu(&self, camera: &FrameCamera) -> Result<Vec<[f32; 3]>> {
        let paint = self.painted("render_backdrop_cpu")?;
        let mut radiance = vec![[0.0f32; 3]; camera.pixel_count()];
        for y in 0..camera.height {
            for x in 0..camera.width {
                let view = atmos::frame::frame_view_direction([x, y], camera);
                let dome = paint.dome.radiance(view.map(f64::from));
                let aureole = paint.aureole.radiance(view);
                radiance[(y * camera.width + x) as usize] =
                    std::array::from_fn(|i| dome[i] as f32 + aureole[i]);
            }
        }
        render_sky_objects_cpu(&self.sky_objects_frame(camera)?, &mut radiance)?;
        Ok(radiance)
    }

    /// The uniform blocks of the cloud layers for a viewer at `altitude_m`, farthest
    /// first (SGSky's `postDraw` order); a layer the viewer is inside is left out
    /// (its effect is the closed-in visibility). Pairs of (layer index, uniforms).
    pub fn cloud_layers_in_draw_order(
        &self,
        altitude_m: f64,
    ) -> Result<Vec<(usize, CloudLayerUniforms)>> {
        let paint = self.painted("cloud_layers_in_draw_order")?;
        let fog_colour = {
            let mut sum = [0.0; 3];
            for f in &paint.fog_colours {
                for i in 0..3 {
                    sum[i] += f[i] / DOME_SIDES as f64;
                }
            }
            sum
        };
        Ok(draw_order(&self.layers, altitude_m)
            .into_iter()
            .map(|i| {
                let light = &paint.layer_light[i];
                let frame = CloudLayerFrame {
                    planet_radius_m: self.atmosphere.planet_radius,
                    offset_m: [0.0, 0.0],
                    fog_extinction_per_m: self.fog_extinction(),
                    exp2_fog: self.options.fog == FogModel::Exp2,
                    sun_direction: light.direction,
                    sunlight: light.irradiance,
                    skylight: light.skylight,
                    fog_colour,
                };
                (i, self.layers[i].uniforms(&frame))
            })
            .collect())
    }

    /// SGSky's stage 2 on the CPU: composites every cloud layer over `radiance` (the
    /// scene already drawn, row-major for `camera`), farthest first; then the in-cloud
    /// fog of the layers the viewer is in or near (those are not drawn as sheets when
    /// the viewer is inside; in their transition zones both) (the extinction `modify_vis` uses,
    /// integrated along each view: [`crate::clouds::in_cloud_transmittance`]) toward
    /// the nearest such layer's interior colour. Puffs change the reported visibility,
    /// not this image.
    pub fn render_clouds_cpu(&self, camera: &FrameCamera, radiance: &mut [[f32; 3]]) -> Result<()> {
        let p = camera.position;
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let altitude = f64::from(r) - self.atmosphere.planet_radius;
        let layers = self.cloud_layers_in_draw_order(altitude)?;
        if radiance.len() != camera.pixel_count() {
            return Err(CelestialError::OutOfRange {
                field: "radiance.len()",
                value: radiance.len() as f64,
                min: camera.pixel_count() as f64,
                max: camera.pixel_count() as f64,
                unit: "pixels",
            });
        }
        let fog = self.in_cloud_fog(altitude)?;
        for y in 0..camera.height {
            for x in 0..camera.width {
                let view = atmos::frame::frame_view_direction([x, y], camera);
                let out = &mut radiance[(y * camera.width + x) as usize];
                for (_, layer) in &layers {
                    *out = crate::clouds::cloud_layer_radiance(view, r, layer, *out);
                }
                if let Some(fog) = &fog {
                    let t = crate::clouds::in_cloud_transmittance(
                        &self.layers,
                        altitude,
                        f64::from(view[2]),
                    ) as f32;
                    for (channel, fog) in out.iter_mut().zip(fog.radiance) {
                        *channel = t * *channel + (1.0 - t) * fog;
                    }
                }
            }
        }
        Ok(())
    }
}
