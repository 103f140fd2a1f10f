//! The two marched clouds' shadows on each other: the `[clouds.shell]` deck darkens the
//! `[clouds.volume]` cloud's direct light and the volume cloud the deck's, on the CPU
//! (this module's marches, `crate::cloud_order::composite_clouds_by_depth`) and on the
//! GPU (the same maps and formula in cloudlight's march passes, `crate::gpu::scene`).
//!
//! # The formula
//!
//! Each cloud has a shadow map toward each of the scene's lights (the sun, and the moon
//! at night; one map per light that is above 1°): the transmittance of the light through the whole cloud
//! along the light ray, stored on a flat plane at the cloud's base
//! ([`crate::volume_clouds::CloudShadow`]). A view sample of cloud A at east/north/up
//! point `p` (altitude `h`) reads cloud B's map where its light ray meets B's plane (the
//! terrain's lookup, [`CloudShadow::at`]: cloudlight's `shadow_map_texel` and
//! `shadow_map_lookup`) and adds to its light march's optical depth
//! `τ_l` (before the octaves and the powder, as one march over both clouds does:
//! `cloudlight::union::UnionField`)
//!
//! `τ_B = −ln max(T_B, 1e-30) · f²`, `f = clamp((top_B − h)/(top_B − base_B), 0, 1)`
//!
//! (`cloudlight::shadow_map::shadow_depth_above`, WGSL twin of the same name; the
//! lookup and it together are `cloudlight::shadow_map::OutsideShadowMap::outside_depth`,
//! [`CloudShadow::outside`], whose WGSL twin `outside_depth` in
//! `shaders/cloudlight/outside_shadow.wgsl` both GPU march passes call;
//! `cloudlight::march::march_view_lit_through` adds it).
//! Below B's base it is B's whole column along the light, exact up to the map's
//! sampling (clear air between `p` and the plane); above B's top it is 0. **Approximate
//! inside B's altitudes** (a cumulus reaching into the deck): the map holds B's whole
//! column along the ray, of which only the part above `h` shades `p`, and that part is
//! not known from the map; `f²` of it is an empirical fade, continuous at both ends. On
//! `cargo test -p render --test cloud_overlap -- --nocapture`'s two views with the
//! cumulus reaching into the deck (against one march over both clouds; LSB, mean / max
//! over the pixels where the two overlap along the ray, then where they are disjoint):
//! `f²` 3.6 / 16.3 and 0.7 / 20.5; no shadowing 5.2 / 29.5 and 2.4 / 55.0; `f` (B's
//! optical depth spread evenly over its height) 8.2 / 38.8 where they overlap, worse
//! than none; 0 inside (the map below the base only) 3.4 / 20.4 and 1.1 / 26.5; the
//! whole column 24.5 / 87.8 and 4.8 / 59.1. The deck's base is a sphere and the map's plane flat: at `d`
//! metres from the camera's ground point the heights differ by `d²/2R` (0.7 m at 3 km).
//!
//! **Not shadowed: the ambient sky.** Each cloud's ambient visibility is its own field's
//! (the sky above A through B is not taken away), and nothing is shadowed when a light
//! is below 1° (no map then: a sunset's grazing light).
//!
//! # The maps
//!
//! The volume cloud's is its terrain map toward each light
//! ([`crate::light::CloudLight::shadow`] of [`PreparedVolume::lights`]), baked whenever the scene has the
//! deck or terrain. The deck's terrain map covers the terrain only, so the deck gets a
//! second, small map over the volume cloud ([`PreparedShell::over_volume`],
//! [`deck_over_volume`]): the grid's footprint swept along the light to the deck's base
//! from the grid's altitudes below the deck's top, baked on the CPU at prepare, also
//! for the GPU renderer, which uploads it and the volume's map into a buffer each and
//! keeps them across prepares while their values are unchanged (`ShadowValues`, one per light in each march's pass state; the
//! `tests/cloud_order.rs` scene with the cumulus reaching into the deck:
//! the deck's 56×55 map on the volume, the volume's 30×29 on the deck, `skyscape
//! explain`'s "mutual cloud shadows" line). A scene with one cloud kind bakes neither
//! extra map and marches as before: `outside_depth` 0 is the plain march on the CPU, and
//! the GPU passes bind a disabled 64-byte uniform and a 4-byte placeholder, one
//! branch per view sample.

use cloudlight::march::{Lighting, MarchResult, PinholeCamera};
use cloudlight::{CloudShell, CloudVolume};

use crate::cloud_shadow::CloudShadow;
use crate::shell_clouds::PreparedShell;
use crate::volume_clouds::PreparedVolume;

/// Texel edge of the deck's map over the volume cloud (m): a sixteenth of the shipped
/// deck's 800 m detail period, finer than its terrain map's 125 m.
pub const DECK_OVER_VOLUME_CELL_M: f64 = 50.0;

/// The volume cloud's altitudes `[base, top]` (m): its grid's.
pub fn volume_extent(volume: &CloudVolume) -> [f32; 2] {
    let base = volume.origin()[2];
    let top = base + f64::from(volume.dims()[2]) * volume.voxel_size();
    [base as f32, top as f32]
}

/// The deck's altitudes `[base, top]` (m): its inner and outer radius above the planet.
pub fn deck_extent(shell: &CloudShell) -> [f32; 2] {
    let s = shell.settings();
    let planet = shell.planet_radius();
    [
        (s.inner_radius - planet) as f32,
        (s.outer_radius - planet) as f32,
    ]
}

use crate::light::LightIndex;

/// The volume cloud's shadow on the deck toward light `light` (its index in the scene's
/// lights): its map for that light, `None` without one.
pub fn volume_on_deck(volume: &PreparedVolume, light: LightIndex) -> Option<&CloudShadow> {
    volume.lights.get(light)?.shadow.as_ref()
}

/// The deck's shadow on the volume cloud toward light `light`: its map over the volume
/// for that light ([`PreparedShell::over_volume`]).
pub fn deck_on_volume(shell: &PreparedShell, light: LightIndex) -> Option<&CloudShadow> {
    shell.over_volume.get(light)?.as_ref()
}

/// The deck's shadow map over `volume` toward unit `to_light` (east/north/up), or `None`
/// with the light below 1° or the grid wholly above the deck's top: cloudlight's shadow
/// map of the shell ([`CloudShadow::over`], the terrain map's
/// [`crate::shell_clouds::SHADOW_STEPS`] steps per span) on the plane of the deck's base,
/// over the grid's footprint swept along the light to that plane from the grid's lowest
/// altitude and its highest below the deck's top, texels [`DECK_OVER_VOLUME_CELL_M`]
/// (coarser if the footprint needs more than 256 a side).
pub fn deck_over_volume(
    shell: &CloudShell,
    volume: &CloudVolume,
    to_light: [f64; 3],
) -> Option<CloudShadow> {
    if to_light[2] < 1f64.to_radians().sin() {
        return None;
    }
    let [base, top] = deck_extent(shell).map(f64::from);
    let [low, high] = volume_extent(volume).map(f64::from);
    if low >= top {
        return None;
    }
    let high = high.min(top);
    let sweep = |h: f64| ((base - h) / to_light[2]).clamp(-1e5, 1e5);
    let (a, b) = (sweep(low), sweep(high));
    let o = volume.origin();
    let dims = volume.dims();
    let size = volume.voxel_size();
    let lo = [0, 1].map(|k| o[k] + (a * to_light[k]).min(b * to_light[k]));
    let hi =
        [0, 1].map(|k| o[k] + f64::from(dims[k]) * size + (a * to_light[k]).max(b * to_light[k]));
    CloudShadow::over(
        shell,
        [lo, hi],
        DECK_OVER_VOLUME_CELL_M,
        [base, shell.planet_radius()],
        top,
        to_light,
        crate::shell_clouds::SHADOW_STEPS,
    )
}

/// The volume cloud's march at `pixel` lit by `lighting` (its sun's or moon's), the
/// deck's shadow `deck` on it (module docs; `None`: the plain march,
/// [`crate::volume_clouds::march_pixel_lit`]).
pub fn march_volume_pixel(
    volume: &PreparedVolume,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
    deck: Option<&CloudShadow>,
) -> MarchResult<f32> {
    let deck = deck.map(|d| d.outside(0.0));
    crate::volume_clouds::march_field_pixel_through(
        &volume.volume,
        &volume.settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
        |p| deck.map_or(0.0, |d| d.outside_depth(p)),
    )
}

/// The deck's march at `pixel` lit by `lighting`, faded toward the horizon
/// ([`crate::shell_clouds::march_shell_pixel_lit`]), the volume cloud's shadow `volume`
/// on it: its samples (planet-centred) read the map at their east/north/up point, the
/// planet's radius below.
pub fn march_deck_pixel(
    shell: &PreparedShell,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
    volume: Option<&CloudShadow>,
) -> MarchResult<f32> {
    let volume = volume.map(|v| v.outside(shell.shell.planet_radius() as f32));
    let result = crate::volume_clouds::march_field_pixel_through(
        &shell.shell,
        &shell.settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
        |p| volume.map_or(0.0, |v| v.outside_depth(p)),
    );
    cloudlight::march::faded(result, shell.shell.horizon_fade(result.depth))
}

/// One light's march's copy of the other cloud's shadow map values on the GPU (the
/// storage buffer `cloudlight::gpu::OutsideShadow` binds), kept in the march's pass
/// state across prepares: the map depends on the prepared scene only, so a prepare
/// whose map holds the same values (compared bit for bit, a few thousand texels)
/// reuses the buffer, and any other map gets a new one. A new buffer rather than a
/// rewrite: a frame recorded before this prepare still reads the values it was
/// prepared with.
#[cfg(feature = "gpu")]
#[derive(Debug, Default)]
pub(crate) struct ShadowValues {
    /// The values uploaded last (their bits) and the buffer holding them.
    kept: Option<(Vec<u32>, wgpu::Buffer)>,
}

#[cfg(feature = "gpu")]
impl ShadowValues {
    /// `shadow` with its values on the GPU: the kept buffer when it holds them, else a
    /// new one written with them (then kept). `None` without a map (the kept buffer
    /// stays for a later prepare).
    pub(crate) fn upload<'s>(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        shadow: Option<&'s CloudShadow>,
    ) -> Option<(&'s CloudShadow, &wgpu::Buffer)> {
        let shadow = shadow?;
        let values = &shadow.values;
        let bits: &[u32] = bytemuck::cast_slice(values);
        let kept = match self.kept.take() {
            Some((kept, buffer)) if kept == bits => (kept, buffer),
            _ => {
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("render mutual shadow values"),
                    size: (values.len().max(1) * 4) as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                queue.write_buffer(&buffer, 0, bytemuck::cast_slice(values));
                (bits.to_vec(), buffer)
            }
        };
        let (_, buffer) = self.kept.insert(kept);
        Some((shadow, buffer))
    }
}

/// [`ShadowValues::upload`]'s map as the march pass binds it, in a march frame whose
/// altitude 0 lies at height `frame_height` (0 for the volume's frame, the planet's
/// radius for the deck's): `cloudlight::gpu::OutsideShadow`, the same map and lookup as
/// [`CloudShadow::outside`]'s `outside_depth`.
#[cfg(feature = "gpu")]
pub(crate) fn outside<'a>(
    (shadow, values): (&CloudShadow, &'a wgpu::Buffer),
    frame_height: f32,
) -> cloudlight::gpu::OutsideShadow<'a> {
    shadow.outside(frame_height).with_values(values)
}

/// What `skyscape explain` says of the clouds' shadows on each other
/// (the marched clouds' pass lists it after "clouds by depth"): which maps each
/// march reads, or why none.
pub fn plan(scene: &crate::scene::PreparedScene) -> (&'static str, Result<String, String>) {
    let name = "mutual cloud shadows";
    let (Some(volume), Some(shell)) = (&scene.volume_cloud, &scene.shell_cloud) else {
        return (
            name,
            Err("not both [clouds.shell] and a marched [clouds.volume]".into()),
        );
    };
    let read: Vec<String> = scene
        .lights()
        .into_iter()
        .flat_map(|light| {
            let (lit_by, light) = (light.name, light.index);
            let on_volume = deck_on_volume(shell, light).map(|s| {
                let [w, h] = s.resolution;
                format!("the deck's {w}×{h} map on the volume ({lit_by})")
            });
            let on_deck = volume_on_deck(volume, light).map(|s| {
                let [w, h] = s.resolution;
                format!("the volume's {w}×{h} map on the deck ({lit_by})")
            });
            [on_volume, on_deck].into_iter().flatten()
        })
        .collect();
    if read.is_empty() {
        return (name, Err("no shadow map: no light above 1°".into()));
    }
    (
        name,
        Ok(format!(
            "each march's light through the other cloud's shadow map (in its march pass): {}",
            read.join(", ")
        )),
    )
}
