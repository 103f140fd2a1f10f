//! Cloud layers over the opaque scene: `celestial`'s SGSky layers composited farthest
//! first, each hidden where the terrain is nearer than the layer (depth-aware
//! compositing). The layer's look is `celestial::clouds::cloud_layer_radiance`; this
//! module only decides, per pixel, which layers are in front of the scene. Twin:
//! `shaders/render/clouds.wgsl` (same names, argument order and units).

use celestial::clouds::CloudLayerUniforms;

pub use crate::frames::world_to_enu;

/// Distance (m) along `view` (east/north/up) from radius `r` to the layer's near
/// surface — its base seen from below, its top from above — or −1 when the view does
/// not reach it. Which surface `cloud_layer_radiance` draws.
pub fn cloud_hit_distance(view: [f32; 3], r: f32, layer: &CloudLayerUniforms) -> f32 {
    let surface = if r < layer.base_radius {
        layer.base_radius
    } else {
        layer.top_radius
    };
    celestial::twins::cloud_layer_distance(r, view[2], surface, layer.curved)
}

/// `background` seen through the layers (farthest first) along the world direction
/// `view` from radius `r`, each layer drawn only where it is nearer than the scene
/// (`scene_distance`, m along the view; infinite for the sky), then through the in-cloud
/// fog around the camera (`crate::in_cloud_fog`).
pub fn composite_cloud_layers(
    view: [f32; 3],
    r: f32,
    scene_distance: f32,
    layers: &[CloudLayerUniforms],
    fog: &crate::in_cloud_fog::InCloudFogUniforms,
    background: [f32; 3],
) -> [f32; 3] {
    let view = world_to_enu(view);
    let mut out = background;
    for layer in layers {
        let distance = cloud_hit_distance(view, r, layer);
        if distance >= 0.0 && distance < scene_distance {
            out = celestial::clouds::cloud_layer_radiance(view, r, layer, out);
        }
    }
    crate::in_cloud_fog::in_cloud_fog(view[2], scene_distance, fog, out)
}

/// The direct sun's fraction through every layer at `offset` (world axes, metres from
/// the camera at radius `r`): the product of `celestial::clouds::cloud_shadow`. Twin:
/// `cloud_shadow_at` in `shaders/render/terrain.wgsl`.
pub fn cloud_shadow_at(offset: [f32; 3], r: f32, layers: &[CloudLayerUniforms]) -> f32 {
    let point = world_to_enu(offset);
    layers
        .iter()
        .map(|layer| celestial::clouds::cloud_shadow(point, r, layer))
        .product()
}

#[cfg(test)]
mod tests {
    use super::*;

    const NO_FOG: crate::in_cloud_fog::InCloudFogUniforms =
        crate::in_cloud_fog::InCloudFogUniforms {
            radiance: [0.0; 3],
            extinction: 0.0,
            optical_depth_up: 0.0,
            optical_depth_down: 0.0,
            band_above: 0.0,
            band_below: 0.0,
            enabled: 0,
            padding0: 0,
            padding1: 0,
            padding2: 0,
        };

    fn layer(base: f32, top: f32) -> CloudLayerUniforms {
        let mut layer = celestial::clouds::CloudLayer::new(
            f64::from(base),
            f64::from(top - base),
            100.0,
            80_000.0,
            celestial::clouds::CloudKind::Overcast,
        )
        .unwrap();
        layer.shape = celestial::clouds::LayerShape::Flat;
        let frame = celestial::clouds::CloudLayerFrame {
            planet_radius_m: 0.0,
            offset_m: [0.0, 0.0],
            fog_extinction_per_m: 0.0,
            exp2_fog: false,
            sun_direction: [0.0, 0.0, 1.0],
            sunlight: [1.0; 3],
            skylight: [0.1; 3],
            fog_colour: [0.0; 3],
        };
        layer.uniforms(&frame)
    }

    #[test]
    fn a_layer_behind_the_terrain_is_hidden_and_one_in_front_is_drawn() {
        // Overcast at 2,000–2,300 m, viewer at 1,000 m looking 30° up: the base is
        // 2,000 m away along the view.
        let overcast = layer(2000.0, 2300.0);
        let view = [0.0, 0.5, -(0.75f32).sqrt()]; // world: up 30°, north
        let background = [0.2, 0.3, 0.4];
        let hit = cloud_hit_distance(world_to_enu(view), 1000.0, &overcast);
        assert!((hit - 2000.0).abs() < 1e-2, "{hit}");
        let sky = composite_cloud_layers(
            view,
            1000.0,
            f32::INFINITY,
            &[overcast],
            &NO_FOG,
            background,
        );
        assert_ne!(sky, background);
        let behind = composite_cloud_layers(view, 1000.0, 1500.0, &[overcast], &NO_FOG, background);
        assert_eq!(behind, background);
        let in_front =
            composite_cloud_layers(view, 1000.0, 2500.0, &[overcast], &NO_FOG, background);
        assert_eq!(in_front, sky);
        // Looking down from below: the layer is not reached.
        let down = [0.0, -0.5, -(0.75f32).sqrt()];
        assert_eq!(
            composite_cloud_layers(
                down,
                1000.0,
                f32::INFINITY,
                &[overcast],
                &NO_FOG,
                background
            ),
            background
        );
    }

    #[test]
    fn compositing_is_affine_in_the_background() {
        // The GPU pass blends c + a·background with c = F(0) and a = F(1) − F(0).
        let layers = [layer(2000.0, 2300.0), layer(1500.0, 1600.0)];
        let view = [0.3, 0.6, -0.74];
        let f =
            |b: [f32; 3]| composite_cloud_layers(view, 1000.0, f32::INFINITY, &layers, &NO_FOG, b);
        let (c, one) = (f([0.0; 3]), f([1.0; 3]));
        let background = [0.25, 0.5, 0.75];
        let direct = f(background);
        for i in 0..3 {
            let blended = c[i] + (one[i] - c[i]) * background[i];
            assert!(
                (blended - direct[i]).abs() < 1e-6,
                "{blended} {}",
                direct[i]
            );
        }
    }
}
