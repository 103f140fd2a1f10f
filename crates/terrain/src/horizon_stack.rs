//! A horizon stack as a texture holds it: `N` azimuth layers of horizon angles in the
//! encoding they were stored in, and the lookups a shader makes in it — the horizon
//! angle at any point of the map for any azimuth, and the self-shadow of the sun's disc
//! there. Twin of `shaders/terrain/horizon_stack.wgsl` (same names, argument order and
//! units; the WGSL takes the texture and its [`HorizonStackParams`] where these take the
//! [`HorizonStack`]); the GPU resource is `terrain::horizon_texture` (feature `gpu`).
//!
//! Texel layouts, one `texture_2d_array<f32>` read with `textureLoad` for all three
//! (no sampler, and no optional wgpu feature):
//!
//! | encoding | format | texel | angle |
//! |---|---|---|---|
//! | [`HorizonEncoding::Unorm8`] | `R8Unorm` | `q/255` | `decode_horizon_angle(q/255)` |
//! | [`HorizonEncoding::Unorm16`] | `Rg8Unorm` | `(hi/255, lo/255)`, `q = 256·hi + lo` | `decode_horizon_angle(q/65535)` |
//! | [`HorizonEncoding::F32`] | `R32Float` | the angle (rad) | the texel |
//!
//! `R16Unorm` would need wgpu's optional `TEXTURE_FORMAT_16BIT_NORM`; two 8-bit
//! channels hold the same 16 bits on every adapter and decode exactly (both bytes are
//! recovered by rounding `255·channel`).
//!
//! Positions are in texels: texel (x, y) of the map (x east, rows south) is at
//! `(x, y)`; between texels the angle is bilinear, outside the map it is the edge's.

use glam::Vec3;

use crate::encoding::{encode_horizon_unorm8, encode_horizon_unorm16};
use crate::shadow::{
    azimuth_layers, decode_horizon_angle, soft_shadow, sun_azimuth, sun_elevation,
};
use crate::{AzimuthHorizonMaps, HorizonEncoding, TerrainError};

/// The stack's uniform (WGSL `HorizonStackParams`, 16 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct HorizonStackParams {
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Azimuth layers `N` (layer k at k · 2π / N).
    pub count: u32,
    /// 0: u8, 1: u16 (two bytes), 2: f32 ([`HorizonStack::encoding_code`]).
    pub encoding: u32,
}

/// The encoded texels of a horizon stack, layer-major then row-major, as uploaded.
#[derive(Debug, Clone, PartialEq)]
pub struct HorizonStack {
    params: HorizonStackParams,
    encoding: HorizonEncoding,
    bytes: Vec<u8>,
}

impl HorizonStack {
    /// Encodes `maps` (every layer) in `encoding`. Errors for an angle no bake produces
    /// (NaN, beyond ±π/2), naming the layer and texel.
    pub fn new(maps: &AzimuthHorizonMaps, encoding: HorizonEncoding) -> Result<Self, TerrainError> {
        let layers = maps.layers();
        let (width, height) = (layers[0].width(), layers[0].height());
        let mut bytes = Vec::with_capacity(layers.len() * width * height * encoding.bytes());
        for (k, layer) in layers.iter().enumerate() {
            for (i, &angle) in layer.angles().iter().enumerate() {
                let named = |e: TerrainError| match e {
                    TerrainError::HorizonAngle { value, .. } => TerrainError::HorizonAngle {
                        field: format!("layer {k}, texel ({}, {})", i % width, i / width),
                        value,
                    },
                    other => other,
                };
                match encoding {
                    HorizonEncoding::Unorm8 => {
                        bytes.push(encode_horizon_unorm8(angle).map_err(named)?)
                    }
                    HorizonEncoding::Unorm16 => {
                        let q = encode_horizon_unorm16(angle).map_err(named)?;
                        bytes.extend([(q >> 8) as u8, (q & 0xff) as u8]);
                    }
                    HorizonEncoding::F32 => {
                        HorizonEncoding::F32.round_trip(angle).map_err(named)?;
                        bytes.extend(angle.to_le_bytes());
                    }
                }
            }
        }
        Ok(Self {
            params: HorizonStackParams {
                width: width as u32,
                height: height as u32,
                count: layers.len() as u32,
                encoding: Self::encoding_code(encoding),
            },
            encoding,
            bytes,
        })
    }

    /// The code of `encoding` in [`HorizonStackParams::encoding`].
    pub fn encoding_code(encoding: HorizonEncoding) -> u32 {
        match encoding {
            HorizonEncoding::Unorm8 => 0,
            HorizonEncoding::Unorm16 => 1,
            HorizonEncoding::F32 => 2,
        }
    }

    /// The uniform a shader reads beside the texture.
    pub fn params(&self) -> HorizonStackParams {
        self.params
    }

    /// How the angles are stored.
    pub fn encoding(&self) -> HorizonEncoding {
        self.encoding
    }

    /// The texels, layer-major then row-major (`encoding.bytes()` per texel): the
    /// texture's contents.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// What `textureLoad` returns for texel (x, y) of `layer` (red, green).
    fn texel(&self, x: u32, y: u32, layer: u32) -> [f32; 2] {
        let p = self.params;
        let index = ((layer * p.height + y) * p.width + x) as usize;
        match self.encoding {
            HorizonEncoding::Unorm8 => [f32::from(self.bytes[index]) / 255.0, 0.0],
            HorizonEncoding::Unorm16 => [
                f32::from(self.bytes[2 * index]) / 255.0,
                f32::from(self.bytes[2 * index + 1]) / 255.0,
            ],
            HorizonEncoding::F32 => {
                let b = &self.bytes[4 * index..4 * index + 4];
                [f32::from_le_bytes([b[0], b[1], b[2], b[3]]), 0.0]
            }
        }
    }
}

/// The horizon angle (rad) of texel `texel` of layer `layer`, decoded from its
/// encoding. `texel` must lie in the map (the WGSL twin's `textureLoad` returns 0
/// outside it).
pub fn horizon_stack_angle(stack: &HorizonStack, texel: [u32; 2], layer: u32) -> f32 {
    let [r, g] = stack.texel(texel[0], texel[1], layer);
    match stack.params.encoding {
        0 => decode_horizon_angle(r),
        1 => decode_horizon_angle(((r * 255.0).round() * 256.0 + (g * 255.0).round()) / 65535.0),
        _ => r,
    }
}

/// The horizon angle (rad) at `position` (texels; texel (x, y) at (x, y), clamped to
/// the map) for the azimuth `sun_azimuth` (rad clockwise from north): bilinear between
/// the four texels around the position in each of the two layers around the azimuth,
/// then linear between the layers ([`azimuth_layers`]). `sun_azimuth` must be finite
/// and the stack non-empty (checked by [`HorizonStack::new`] and [`sun_azimuth`]).
pub fn sample_horizon(stack: &HorizonStack, position: [f32; 2], sun_azimuth: f32) -> f32 {
    let p = stack.params;
    let x = position[0].clamp(0.0, (p.width - 1) as f32);
    let y = position[1].clamp(0.0, (p.height - 1) as f32);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as u32, y0 as u32);
    let (x1, y1) = ((x0 + 1).min(p.width - 1), (y0 + 1).min(p.height - 1));
    let bilinear = |layer: u32| {
        let a = horizon_stack_angle(stack, [x0, y0], layer);
        let b = horizon_stack_angle(stack, [x1, y0], layer);
        let c = horizon_stack_angle(stack, [x0, y1], layer);
        let d = horizon_stack_angle(stack, [x1, y1], layer);
        let top = a + (b - a) * fx;
        let bottom = c + (d - c) * fx;
        top + (bottom - top) * fy
    };
    let layers = azimuth_layers(sun_azimuth, p.count).unwrap_or(crate::shadow::AzimuthLayers {
        lower: 0,
        upper: 0,
        weight: 0.0,
    });
    let lower = bilinear(layers.lower);
    let upper = bilinear(layers.upper);
    lower + (upper - lower) * layers.weight
}

/// The visible fraction of the sun's disc (angular radius `sun_angular_radius`, rad;
/// ≤ 0: a point sun, the hard shadow) above the horizon at `position` (texels), the
/// sun along `sun_direction` (unit, east–north–up, towards the sun): 1 lit, 0 in the
/// terrain's shadow, the disc's segment in between ([`soft_shadow`]).
pub fn self_shadow(
    stack: &HorizonStack,
    position: [f32; 2],
    sun_direction: Vec3,
    sun_angular_radius: f32,
) -> f32 {
    let horizon = sample_horizon(stack, position, sun_azimuth(sun_direction));
    soft_shadow(sun_elevation(sun_direction), horizon, sun_angular_radius)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Algorithm, Heightfield, HorizonOptions, bake_azimuths};

    fn maps() -> AzimuthHorizonMaps {
        let hf = Heightfield::from_fn(24, 16, 10.0, |x, y| {
            let (dx, dy) = (x as f32 - 12.0, y as f32 - 8.0);
            60.0 * (-(dx * dx + dy * dy) / 20.0).exp()
        })
        .unwrap();
        bake_azimuths(&hf, 8, &HorizonOptions::flat(), Algorithm::HullSweep).unwrap()
    }

    #[test]
    fn every_encoding_gives_back_its_round_trip_at_the_texels() {
        let maps = maps();
        for encoding in HorizonEncoding::ALL {
            let stack = HorizonStack::new(&maps, encoding).unwrap();
            assert_eq!(stack.bytes().len(), 8 * 24 * 16 * encoding.bytes());
            for (k, layer) in maps.layers().iter().enumerate() {
                for (x, y) in [(0, 0), (5, 7), (12, 8), (23, 15)] {
                    let angle = layer.angle(x, y).unwrap();
                    let stored = horizon_stack_angle(&stack, [x as u32, y as u32], k as u32);
                    assert_eq!(stored, encoding.round_trip(angle).unwrap(), "{encoding:?}");
                }
            }
        }
    }

    #[test]
    fn sampling_at_a_texel_and_a_layer_azimuth_is_the_maps_angle() {
        let maps = maps();
        let stack = HorizonStack::new(&maps, HorizonEncoding::F32).unwrap();
        for (k, layer) in maps.layers().iter().enumerate() {
            let azimuth = k as f32 * std::f32::consts::TAU / 8.0;
            let got = sample_horizon(&stack, [5.0, 7.0], azimuth);
            assert!((got - layer.angle(5, 7).unwrap()).abs() < 1e-6);
        }
        // Half way between two texels of one layer: their mean.
        let a = maps.layers()[2].angle(5, 7).unwrap();
        let b = maps.layers()[2].angle(6, 7).unwrap();
        let half = sample_horizon(&stack, [5.5, 7.0], std::f32::consts::FRAC_PI_2);
        assert!((half - 0.5 * (a + b)).abs() < 1e-6);
    }

    #[test]
    fn the_hill_shadows_its_west_side_at_a_low_eastern_sun() {
        let stack = HorizonStack::new(&maps(), HorizonEncoding::Unorm16).unwrap();
        let sun = Vec3::new(1.0, 0.0, 0.05).normalize();
        // West of the hill's top (x < 12) the hill hides a 3° sun; east of it, lit.
        assert_eq!(self_shadow(&stack, [8.0, 8.0], sun, 0.0), 0.0);
        assert_eq!(self_shadow(&stack, [16.0, 8.0], sun, 0.0), 1.0);
    }

    #[test]
    fn a_bad_angle_names_its_layer_and_texel() {
        let good = maps();
        let mut layers = good.layers().to_vec();
        let mut angles = layers[3].angles().to_vec();
        angles[5 * 24 + 2] = f32::NAN;
        layers[3] = crate::HorizonMap::from_angles(24, 16, layers[3].azimuth(), angles);
        let bad = AzimuthHorizonMaps { layers };
        for encoding in HorizonEncoding::ALL {
            let error = HorizonStack::new(&bad, encoding).unwrap_err();
            assert!(
                error.to_string().contains("layer 3, texel (2, 5)"),
                "{error}"
            );
        }
    }
}
