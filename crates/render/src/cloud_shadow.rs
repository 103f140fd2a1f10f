//! A marched cloud's shadow map on the terrain (and on the other cloud), read alike by
//! both renderers.

use cloudlight::CloudVolume;
use cloudlight::shadow_map::OutsideShadowMap;

/// The volume's shadow on the terrain: `cloudlight`'s ground shadow map (Hoffman and Preetham's
/// `cloud_shadow` term; `shadow_map::<f32>`, the twin of `cloudlight::gpu::ShadowMapPass`)
/// on the plane of the grid's base, over the part of it whose sun rays can cross the
/// grid (the footprint swept away from the sun by the grid's height). A terrain point is
/// carried along the sun ray to that plane and the map read there, bilinearly between
/// texel centres (1 outside the map): exact, up to the map's sampling, for terrain
/// below the cloud's base (the ray between the point and the plane is clear air). A
/// peak reaching into the cloud's altitudes ([`CloudShadow::on_terrain`]) is shaded by
/// the part of the column above it only, which the map does not hold: cloudlight's
/// `shadow_depth_above` fade of the column, the clouds' mutual shadows' (`f²`,
/// `render::mutual_shadow`), none above the cloud's top. Both renderers read the same
/// map (the GPU's terrain pass uploads it).
#[derive(Debug, Clone)]
pub struct CloudShadow {
    /// East/north of texel (0, 0)'s corner, metres (the volume's frame).
    pub origin: [f32; 2],
    /// Texel edge, metres.
    pub cell_size: f32,
    /// Texels east × north.
    pub resolution: [u32; 2],
    /// The plane's altitude (the grid's base), metres.
    pub plane: f32,
    /// The casting cloud's top altitude, metres (above `plane`).
    pub top: f32,
    /// Unit direction toward the sun, east/north/up.
    pub to_sun: [f32; 3],
    /// Transmittance toward the sun per texel, east fastest.
    pub values: Vec<f32>,
}

/// The most texels along one side of the cloud's shadow map.
pub const SHADOW_MAP_MAX_SIDE: u32 = 256;
/// Midpoint steps of the shadow map's march per span.
pub const SHADOW_MAP_STEPS: u32 = 32;

impl CloudShadow {
    /// The shadow map of `volume` for the sun along unit `to_sun` (east/north/up), or
    /// `None` when the sun is below 1° (it lights no terrain through a cloud layer then).
    pub fn new(volume: &CloudVolume, to_sun: [f64; 3]) -> Option<Self> {
        if to_sun[2] < 1f64.to_radians().sin() {
            return None;
        }
        let o = volume.origin();
        let size = volume.voxel_size();
        let [nx, ny, nz] = volume.dims();
        let height = f64::from(nz) * size;
        // The footprint, swept by −(horizontal sun) × height / sun_z (capped at 100 km).
        let reach = (height / to_sun[2]).min(1e5);
        let (sx, sy) = (-to_sun[0] * reach, -to_sun[1] * reach);
        let lo = [o[0] + sx.min(0.0), o[1] + sy.min(0.0)];
        let hi = [
            o[0] + f64::from(nx) * size + sx.max(0.0),
            o[1] + f64::from(ny) * size + sy.max(0.0),
        ];
        Self::over(
            volume,
            [lo, hi],
            size,
            [o[2], 0.0],
            o[2] + height,
            to_sun,
            SHADOW_MAP_STEPS,
        )
    }

    /// The shadow map of any density field (the volume's, the shell's: cloudlight's
    /// `shadow_map::<f32, _>`, rows in parallel) on the plane at altitude `plane[0]` (metres) covering the
    /// east/north rectangle `footprint = [lo, hi]` (metres), in square texels no smaller
    /// than `finest` metres and at most [`SHADOW_MAP_MAX_SIDE`] a side, `steps` midpoint
    /// samples per span toward unit `to_sun` (east/north/up). `plane[1]` is the field's
    /// frame's height of altitude 0 (0 for the volume's frame, the planet's radius for
    /// the shell's planet-centred one): the map's texels are at `plane[0] + plane[1]` in
    /// the field's frame and at altitude `plane[0]` in [`CloudShadow::at`]'s. `top` is the
    /// field's highest altitude (metres, above `plane[0]`; [`CloudShadow::on_terrain`]).
    pub fn over<D: cloudlight::DensityField<f32> + Sync + ?Sized>(
        field: &D,
        footprint: [[f64; 2]; 2],
        finest: f64,
        plane: [f64; 2],
        top: f64,
        to_sun: [f64; 3],
        steps: u32,
    ) -> Option<Self> {
        let [lo, hi] = footprint;
        let cell = finest
            .max((hi[0] - lo[0]) / f64::from(SHADOW_MAP_MAX_SIDE))
            .max((hi[1] - lo[1]) / f64::from(SHADOW_MAP_MAX_SIDE));
        let resolution = [
            (((hi[0] - lo[0]) / cell).ceil() as u32).clamp(1, SHADOW_MAP_MAX_SIDE),
            (((hi[1] - lo[1]) / cell).ceil() as u32).clamp(1, SHADOW_MAP_MAX_SIDE),
        ];
        let grid =
            cloudlight::shadow_map::ShadowGrid::new(lo, cell, resolution, plane[0] + plane[1])
                .ok()?;
        let plan = cloudlight::shadow_map::ShadowMapPlan::new(grid, to_sun, steps).ok()?;
        // cloudlight's `shadow_map::<f32, _>`, its rows across threads: the same texels,
        // the same values.
        let values = {
            use cloudlight::shadow_map::{shadow_texel, shadow_texel_centre};
            use rayon::prelude::*;
            let (origin, cell, ground) = (
                grid.origin().map(|c| c as f32),
                grid.cell_size() as f32,
                grid.ground_height() as f32,
            );
            let to_sun = plan.to_sun().map(|c| c as f32);
            let [nx, ny] = resolution;
            (0..ny)
                .into_par_iter()
                .flat_map_iter(|j| {
                    (0..nx).map(move |i| {
                        let p = shadow_texel_centre([i, j], origin, cell, ground);
                        shadow_texel(field, p, to_sun, plan.steps())
                    })
                })
                .collect::<Vec<f32>>()
        };
        Some(Self {
            origin: [lo[0] as f32, lo[1] as f32],
            cell_size: cell as f32,
            resolution,
            plane: plane[0] as f32,
            top: top as f32,
            to_sun: to_sun.map(|c| c as f32),
            values,
        })
    }

    /// The transmittance toward the sun at `point` (east/north/up, metres):
    /// cloudlight's lookup ([`cloudlight::shadow_map::shadow_map_lookup`]: bilinear
    /// between texel centres, 1 outside the map): the whole column above the plane,
    /// wherever `point` lies (the terrain reads [`CloudShadow::on_terrain`]).
    pub fn at(&self, point: [f32; 3]) -> f32 {
        let texel =
            volume_shadow_texel(point, self.to_sun, self.plane, self.origin, self.cell_size);
        cloudlight::shadow_map::shadow_map_lookup(&self.values, self.resolution, texel)
    }

    /// The transmittance toward the light at terrain point `point` (east/north/up,
    /// metres): [`CloudShadow::at`] at or below the plane; above it, `exp(−τ)` of the
    /// part of the column above the point by cloudlight's
    /// [`shadow_depth_above`](cloudlight::shadow_map::shadow_depth_above) (the clouds'
    /// mutual shadows' fade; 1 at and above the cloud's top). The WGSL twin is
    /// `shadow_map_at` in `shaders/render/terrain.wgsl`.
    pub fn on_terrain(&self, point: [f32; 3]) -> f32 {
        if point[2] <= self.plane {
            return self.at(point);
        }
        (-self.depth_at(point)).exp()
    }

    /// The map as a march in a frame whose altitude 0 lies at height `frame_height`
    /// reads it (0 for the volume's frame, the planet's radius for the deck's), the
    /// casting cloud spanning `[plane, top]`: cloudlight's CPU twin of the GPU march's
    /// uniform and values (the GPU renderer fills those from it;
    /// `crate::mutual_shadow`).
    pub fn outside(&self, frame_height: f32) -> OutsideShadowMap<&[f32], f32> {
        OutsideShadowMap {
            origin: self.origin,
            cell_size: self.cell_size,
            resolution: self.resolution,
            plane: self.plane,
            to_light: self.to_sun,
            extent: [self.plane, self.top],
            frame_height,
            values: &self.values,
        }
    }

    /// The casting cloud's optical depth toward the map's light above `point`
    /// (east/north/up about the camera's ground point, `point[2]` the altitude):
    /// cloudlight's `outside_depth` in the volume's frame ([`CloudShadow::at`]'s lookup,
    /// then `shadow_depth_above`).
    pub fn depth_at(&self, point: [f32; 3]) -> f32 {
        self.outside(0.0).outside_depth(point)
    }
}

/// Where `point` (east/north/up, metres) reads the cloud's shadow map: carried along
/// unit `to_sun` to the plane at altitude `plane`, in texel-centre coordinates
/// (`(x − origin)/cell − ½`: texel `(i, j)`'s centre is `(i, j)`). WGSL twin of the same
/// name in `shaders/render/terrain.wgsl`.
pub fn volume_shadow_texel(
    point: [f32; 3],
    to_sun: [f32; 3],
    plane: f32,
    origin: [f32; 2],
    cell_size: f32,
) -> [f32; 2] {
    // cloudlight's lookup, which another cloud's march shares (crate::mutual_shadow).
    cloudlight::shadow_map::shadow_map_texel(point, to_sun, plane, origin, cell_size)
}
