//! Drawing: stage 1's backdrop and objects, stage 2's cloud layers.

use atmos::frame::FrameCamera;

use super::*;
use crate::clouds::{CloudLayerFrame, CloudLayerUniforms, draw_order};
use crate::dome::DOME_SIDES;
use crate::error::{CelestialError, Result};
use crate::objects::{SkyObjectsFrame, render_sky_objects_cpu};

impl Sky {
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
        // The layer whose fog the viewer is in (the most immersed), with its colour.
        let paint = self.painted("render_clouds_cpu")?;
        let fog_layer = (0..self.layers.len())
            .filter(|&i| self.layers[i].immersion(altitude) > 0.0)
            .max_by(|&a, &b| {
                self.layers[a]
                    .immersion(altitude)
                    .total_cmp(&self.layers[b].immersion(altitude))
            });
        let interior = fog_layer.map(|i| {
            let light = &paint.layer_light[i];
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
            crate::clouds::cloud_interior_radiance(&self.layers[i].uniforms(&frame))
        });
        for y in 0..camera.height {
            for x in 0..camera.width {
                let view = atmos::frame::frame_view_direction([x, y], camera);
                let out = &mut radiance[(y * camera.width + x) as usize];
                for (_, layer) in &layers {
                    *out = crate::clouds::cloud_layer_radiance(view, r, layer, *out);
                }
                if let Some(colour) = interior {
                    let t = crate::clouds::in_cloud_transmittance(
                        &self.layers,
                        altitude,
                        f64::from(view[2]),
                    ) as f32;
                    for i in 0..3 {
                        out[i] = t * out[i] + (1.0 - t) * colour[i];
                    }
                }
            }
        }
        Ok(())
    }
}
